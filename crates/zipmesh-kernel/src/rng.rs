//! A tiny deterministic random number generator (SplitMix64).
//!
//! Written by hand rather than taken from `rand` so that a seed gives the same meshes on every
//! platform and every future version of the crate: campaigns and their replay commands rely
//! on that, and `rand` does not promise value stability across releases.

/// SplitMix64 (Steele, Lea and Flood, 2014): 64 bits of state, passes BigCrush.
///
/// ```
/// let mut rng = zipmesh_kernel::rng::Rng::new(42);
/// assert!(rng.below(6) < 6);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    ///
    /// ```
    /// let mut a = zipmesh_kernel::rng::Rng::new(7);
    /// let mut b = zipmesh_kernel::rng::Rng::new(7);
    /// assert_eq!(a.next_u64(), b.next_u64());
    /// ```
    pub const fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// The next 64 random bits.
    ///
    /// ```
    /// let mut r = zipmesh_kernel::rng::Rng::new(1);
    /// assert_ne!(r.next_u64(), r.next_u64());
    /// ```
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in `0..n` (0 when `n` is 0), by Lemire's multiply-shift.
    ///
    /// ```
    /// let mut r = zipmesh_kernel::rng::Rng::new(3);
    /// assert!((0..100).all(|_| r.below(10) < 10));
    /// assert_eq!(r.below(0), 0);
    /// ```
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next_u64() as u128 * n as u128) >> 64) as usize
    }

    /// A uniform number in `lo..=hi` (`lo` when `hi < lo`).
    ///
    /// ```
    /// let mut r = zipmesh_kernel::rng::Rng::new(3);
    /// assert!((0..100).all(|_| (2..=5).contains(&r.range(2, 5))));
    /// ```
    pub fn range(&mut self, lo: usize, hi: usize) -> usize {
        if hi < lo {
            lo
        } else {
            lo + self.below(hi - lo + 1)
        }
    }

    /// `true` with probability `num / den`.
    ///
    /// ```
    /// let mut r = zipmesh_kernel::rng::Rng::new(3);
    /// assert!(!r.chance(0, 5));
    /// assert!(r.chance(5, 5));
    /// ```
    pub fn chance(&mut self, num: usize, den: usize) -> bool {
        self.below(den) < num
    }
}
