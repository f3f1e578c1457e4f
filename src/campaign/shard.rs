//! Shards: deterministic slices of a campaign's cases, to run one campaign on many machines.
//!
//! Shard `i/n` is 0-based, as Slurm's `SLURM_ARRAY_TASK_ID` with `--array=0-(n-1)` and a
//! CI matrix index: it runs the cases at the positions `p` with `p % n == i`. The shards
//! `0/n` … `(n-1)/n` partition the positions `0..cases`, whatever the number of jobs or
//! machines, so their reports merge ([`merge`](super::merge)) into the report of one run.

use core::fmt;
use core::str::FromStr;
use std::format;
use std::string::String;

/// A deterministic slice of the cases: those whose position `p` has `p % count == index`.
/// Written `index/count`; `0/1` is every case.
///
/// ```
/// use zipmesh::campaign::Shard;
/// let s: Shard = "1/3".parse().unwrap();
/// assert!(s.contains(4) && !s.contains(5));
/// assert_eq!(s.to_string(), "1/3");
/// assert!("3/3".parse::<Shard>().is_err() && "x".parse::<Shard>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shard {
    /// Which slice, `0..count`.
    pub index: u64,
    /// How many slices.
    pub count: u64,
}

impl Shard {
    /// Every case: `0/1`.
    ///
    /// ```
    /// assert!(zipmesh::campaign::Shard::ALL.contains(17));
    /// ```
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Whether the case at `position` is in this shard.
    ///
    /// ```
    /// let s = zipmesh::campaign::Shard { index: 0, count: 2 };
    /// assert!(s.contains(0) && !s.contains(1));
    /// ```
    pub fn contains(&self, position: u64) -> bool {
        self.count > 0 && position % self.count == self.index
    }

    /// How many of the positions `0..n` are in this shard (computed, not counted, so a
    /// campaign of 10^18 cases plans in no time).
    ///
    /// ```
    /// let s = zipmesh::campaign::Shard { index: 1, count: 3 };
    /// assert_eq!((s.size_of(0), s.size_of(1), s.size_of(2), s.size_of(7)), (0, 0, 1, 2));
    /// assert_eq!(zipmesh::campaign::Shard::ALL.size_of(u64::MAX), u64::MAX);
    /// ```
    pub fn size_of(&self, n: u64) -> u64 {
        if self.count == 0 || self.index >= n {
            0
        } else {
            (n - 1 - self.index) / self.count + 1
        }
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Why a shard could not be parsed.
///
/// ```
/// let e = "2/2".parse::<zipmesh::campaign::Shard>().unwrap_err();
/// assert!(e.to_string().contains("below"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShardError(String);

impl fmt::Display for ShardError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ShardError {}

impl FromStr for Shard {
    type Err = ShardError;

    fn from_str(s: &str) -> Result<Shard, ShardError> {
        let bad = || ShardError(format!("expected i/n with i below n, got {s:?}"));
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: u64 = i.trim().parse().map_err(|_| bad())?;
        let count: u64 = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}
