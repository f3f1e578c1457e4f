//! Merging the reports of a campaign's shards into the report of one run.
//!
//! Each shard `i/n` ([`Shard`]) runs on its own machine and writes its report (as JSON with
//! `zipmesh check --shard i/n --json`); [`merge`] sums the rows and keeps, for each
//! property, the failure of the smallest position, which is the failure one unsharded run
//! reports and shrinks (shrinking depends on the case and the property only). Reports of
//! different campaigns ([`Campaign`](super::Campaign), the seed, the property list, the shard count) or an
//! incomplete set of shards are refused with a [`MergeError`].

use super::report::{Failure, Report, Row};
use super::Shard;
use core::fmt;
use core::time::Duration;
use std::collections::BTreeMap;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

/// Why shard reports could not be merged. Reports are numbered from 0 in the order given.
///
/// ```
/// use zipmesh::campaign::{self, Config, MergeError, Shard};
/// let shard = |seed, index| {
///     let c = Config { seed, cases: 4, max_faces: 100, shard: Shard { index, count: 2 }, ..Config::default() };
///     campaign::run(&c, &campaign::kernel())
/// };
/// let e = campaign::merge(&[shard(0, 0), shard(1, 1)]).unwrap_err();
/// assert!(matches!(e, MergeError::Differs { what: "seed", .. }));
/// assert!(e.to_string().contains("seed"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MergeError {
    /// No report was given.
    Empty,
    /// Report `report` is of another campaign than report 0: `what` differs.
    Differs {
        /// The report that differs from report 0.
        report: usize,
        /// What differs: `seed`, `cases`, `max-faces`, `inputs`, `settings`, `properties`
        /// or `shard count`.
        what: &'static str,
        /// Its value in report 0.
        first: String,
        /// Its value in `report`.
        other: String,
    },
    /// Two reports are of the same shard.
    Duplicate {
        /// The shard.
        shard: Shard,
        /// The earlier report of it.
        first: usize,
        /// The later report of it.
        second: usize,
    },
    /// Shards of the campaign are missing (at most the first 10 are listed).
    Missing {
        /// The number of shards of the campaign.
        count: u64,
        /// The indices of missing shards (the first 10).
        missing: Vec<u64>,
        /// How many are missing in all.
        total: u64,
    },
    /// A report contradicts itself (edited by hand, or from another version).
    Inconsistent {
        /// The report.
        report: usize,
        /// What is wrong.
        why: String,
    },
}

impl MergeError {
    /// The message, naming the reports by `names` (for example their file names) instead of
    /// their numbers.
    ///
    /// ```
    /// use zipmesh::campaign::{MergeError, Shard};
    /// let e = MergeError::Duplicate { shard: Shard { index: 1, count: 4 }, first: 0, second: 2 };
    /// let names = ["a.json".to_string(), "b.json".into(), "c.json".into()];
    /// assert_eq!(e.describe(&names), "a.json and c.json are both shard 1/4");
    /// ```
    pub fn describe(&self, names: &[String]) -> String {
        let name = |k: usize| {
            names
                .get(k)
                .cloned()
                .unwrap_or_else(|| format!("report {k}"))
        };
        match self {
            MergeError::Empty => "no shard report to merge".to_string(),
            MergeError::Differs {
                report,
                what,
                first,
                other,
            } => format!(
                "{} is not a shard of the campaign of {}: {what} {other}, not {first}",
                name(*report),
                name(0)
            ),
            MergeError::Duplicate {
                shard,
                first,
                second,
            } => format!(
                "{} and {} are both shard {shard}",
                name(*first),
                name(*second)
            ),
            MergeError::Missing {
                count,
                missing,
                total,
            } => {
                let list: Vec<String> = missing.iter().map(|i| format!("{i}/{count}")).collect();
                let more = if *total > missing.len() as u64 {
                    format!(" and {} more", total - missing.len() as u64)
                } else {
                    String::new()
                };
                format!(
                    "{total} of {count} shards missing: {}{more}",
                    list.join(", ")
                )
            }
            MergeError::Inconsistent { report, why } => {
                format!("{} is not a consistent report: {why}", name(*report))
            }
        }
    }
}

impl fmt::Display for MergeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe(&[]))
    }
}

impl std::error::Error for MergeError {}

/// Merges the reports of every shard `0/n` … `(n-1)/n` of one campaign, in any order, into
/// the report of one unsharded run: the same rows, failures, `planned`, `run` and
/// `timed_out`, with shard `0/1`. Only the times differ: row times are summed (time spent in
/// the property on all machines), and `elapsed` is the longest shard's (the wall time when
/// the shards run at once). Counterexample files keep the shards' paths; see
/// [`Report::write_counterexamples`] to write them again here.
///
/// ```
/// use zipmesh::campaign::{self, Config, Shard};
/// let config = |shard| Config { cases: 8, max_faces: 150, shard, ..Config::default() };
/// let one = campaign::run(&config(Shard::ALL), &campaign::kernel());
/// let parts: Vec<_> = (0..3)
///     .map(|index| campaign::run(&config(Shard { index, count: 3 }), &campaign::kernel()))
///     .collect();
/// let merged = campaign::merge(&parts).unwrap();
/// assert_eq!(merged.to_json(false), one.to_json(false));
/// assert!(campaign::merge(&parts[..2]).is_err()); // shard 2/3 missing
/// ```
pub fn merge(parts: &[Report]) -> Result<Report, MergeError> {
    let first = parts.first().ok_or(MergeError::Empty)?;
    for (k, part) in parts.iter().enumerate() {
        same_campaign(first, part, k)?;
        consistent(part, k)?;
    }
    complete(parts)?;
    let mut rows: Vec<Row> = first
        .rows
        .iter()
        .map(|r| Row {
            time: Duration::ZERO,
            ..Row::zero(&r.property)
        })
        .collect();
    let mut best: Vec<Option<&Failure>> = Vec::new();
    best.resize(rows.len(), None);
    for part in parts {
        let mut failures = part.failures.iter();
        for (k, r) in part.rows.iter().enumerate() {
            rows[k].add(r);
            if r.failed > 0 {
                // `consistent` checked that there is one failure per failing row, in order.
                if let Some(f) = failures.next() {
                    if best[k].is_none_or(|b| f.position < b.position) {
                        best[k] = Some(f);
                    }
                }
            }
        }
    }
    let planned = parts.iter().map(|p| p.planned).sum();
    let run = parts.iter().map(|p| p.run).sum();
    let cut = rows.iter().any(|r| r.cut > 0);
    Ok(Report {
        seed: first.seed,
        shard: Shard::ALL,
        planned,
        run,
        timed_out: run < planned || cut,
        elapsed: parts.iter().map(|p| p.elapsed).max().unwrap_or_default(),
        rows,
        failures: best.into_iter().flatten().cloned().collect(),
        campaign: first.campaign.clone(),
    })
}

/// Refuses `part` (number `k`) unless it is a shard of `first`'s campaign.
fn same_campaign(first: &Report, part: &Report, k: usize) -> Result<(), MergeError> {
    let differs = |what, a: String, b: String| {
        Err(MergeError::Differs {
            report: k,
            what,
            first: a,
            other: b,
        })
    };
    let (a, b) = (&first.campaign, &part.campaign);
    let names = |r: &Report| {
        let v: Vec<&str> = r.rows.iter().map(|r| r.property.as_str()).collect();
        v.join(",")
    };
    if first.seed != part.seed {
        return differs("seed", first.seed.to_string(), part.seed.to_string());
    }
    if a.cases != b.cases {
        return differs("cases", a.cases.to_string(), b.cases.to_string());
    }
    if a.max_faces != b.max_faces {
        return differs(
            "max-faces",
            a.max_faces.to_string(),
            b.max_faces.to_string(),
        );
    }
    if a.inputs != b.inputs {
        return differs("inputs", a.inputs.join(" "), b.inputs.join(" "));
    }
    if a.settings != b.settings {
        let show = |s: &BTreeMap<String, String>| {
            let v: Vec<String> = s.iter().map(|(k, v)| format!("{k}={v}")).collect();
            format!("[{}]", v.join(" "))
        };
        return differs("settings", show(&a.settings), show(&b.settings));
    }
    if names(first) != names(part) {
        return differs("properties", names(first), names(part));
    }
    if first.shard.count != part.shard.count {
        return differs(
            "shard count",
            first.shard.count.to_string(),
            part.shard.count.to_string(),
        );
    }
    Ok(())
}

/// Refuses a report whose numbers contradict each other.
fn consistent(part: &Report, k: usize) -> Result<(), MergeError> {
    let bad = |why: String| Err(MergeError::Inconsistent { report: k, why });
    let shard = part.shard;
    if shard.count == 0 || shard.index >= shard.count {
        return bad(format!("shard {shard}"));
    }
    if part.planned != shard.size_of(part.campaign.cases) || part.run > part.planned {
        return bad(format!(
            "shard {shard} of {} cases plans {} and ran {}",
            part.campaign.cases, part.planned, part.run
        ));
    }
    for r in &part.rows {
        if r.passed + r.failed != r.cases || r.cases + r.skipped > part.run {
            return bad(format!("row {} does not add up", r.property));
        }
    }
    let failing: Vec<&str> = part
        .rows
        .iter()
        .filter(|r| r.failed > 0)
        .map(|r| r.property.as_str())
        .collect();
    let failures: Vec<&str> = part.failures.iter().map(|f| f.property.as_str()).collect();
    if failing != failures {
        return bad("one failure per failing property expected".to_string());
    }
    for f in &part.failures {
        if !shard.contains(f.position) {
            return bad(format!("failure at position {} not in it", f.position));
        }
    }
    Ok(())
}

/// Refuses duplicate shards and missing ones.
fn complete(parts: &[Report]) -> Result<(), MergeError> {
    let count = parts[0].shard.count;
    let mut seen: BTreeMap<u64, usize> = BTreeMap::new();
    for (k, part) in parts.iter().enumerate() {
        if let Some(&first) = seen.get(&part.shard.index) {
            return Err(MergeError::Duplicate {
                shard: part.shard,
                first,
                second: k,
            });
        }
        seen.insert(part.shard.index, k);
    }
    let total = count - seen.len() as u64;
    if total > 0 {
        let missing = (0..count)
            .filter(|i| !seen.contains_key(i))
            .take(10)
            .collect();
        return Err(MergeError::Missing {
            count,
            missing,
            total,
        });
    }
    Ok(())
}
