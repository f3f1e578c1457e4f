//! The searches' heap entries: Dijkstra's (distance, vertex) and A*'s packed (f, g, vertex),
//! each ordered so that `BinaryHeap` (a max-heap) pops the one to expand next.

use core::cmp::Ordering;

use crate::Vert;

/// Dijkstra heap entry: smallest (distance, vertex) first.
#[derive(PartialEq)]
pub(super) struct Entry(pub(super) f64, pub(super) u32);

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed so that BinaryHeap (a max-heap) pops the smallest; weights are finite.
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| other.1.cmp(&self.1))
    }
}

/// A* heap entry `(f, g, vertex)` packed in one integer: smallest f first, then the deepest
/// (largest g), which walks straight down a run of ties, then the smallest vertex. The order
/// only changes the work, not the path. `f >= 0`, so its bits order as the numbers do.
#[derive(PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct AEntry(core::cmp::Reverse<u128>);

impl AEntry {
    pub(super) fn new(f: f64, g: u32, v: Vert) -> Self {
        let key =
            (u128::from(f.to_bits()) << 64) | (u128::from(u32::MAX - g) << 32) | v.index() as u128;
        AEntry(core::cmp::Reverse(key))
    }

    pub(super) fn f(&self) -> f64 {
        f64::from_bits((self.0 .0 >> 64) as u64)
    }

    pub(super) fn g(&self) -> u32 {
        u32::MAX - (self.0 .0 >> 32) as u32
    }

    pub(super) fn vertex(&self) -> Vert {
        Vert::new(self.0 .0 as u32)
    }
}
