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

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::collections::BinaryHeap;
    use alloc::vec::Vec;

    /// Dijkstra's heap pops by smallest distance, then smallest vertex; `partial_cmp` agrees
    /// with `cmp`.
    #[test]
    fn dijkstra_entries_pop_smallest_first() {
        let entries = [Entry(2.5, 1), Entry(0.5, 9), Entry(2.5, 0), Entry(1.0, 3)];
        for a in &entries {
            for b in &entries {
                assert_eq!(a.partial_cmp(b), Some(a.cmp(b)));
            }
        }
        let mut heap: BinaryHeap<Entry> = entries.into_iter().collect();
        let order: Vec<(f64, u32)> =
            core::iter::from_fn(|| heap.pop().map(|e| (e.0, e.1))).collect();
        assert_eq!(order, [(0.5, 9), (1.0, 3), (2.5, 0), (2.5, 1)]);
    }

    /// An A* entry gives back what it packs, and pops by smallest f, then largest g, then
    /// smallest vertex.
    #[test]
    fn a_star_entries_unpack_and_pop_in_order() {
        let e = AEntry::new(3.75, 12, Vert::new(40));
        assert_eq!((e.f(), e.g(), e.vertex()), (3.75, 12, Vert::new(40)));
        let mut heap: BinaryHeap<AEntry> = [
            AEntry::new(2.0, 1, Vert::new(5)),
            AEntry::new(1.0, 0, Vert::new(7)),
            AEntry::new(2.0, 4, Vert::new(6)),
            AEntry::new(2.0, 4, Vert::new(2)),
        ]
        .into_iter()
        .collect();
        let order: Vec<(f64, u32, u32)> = core::iter::from_fn(|| heap.pop())
            .map(|e| (e.f(), e.g(), e.vertex().index() as u32))
            .collect();
        assert_eq!(order, [(1.0, 0, 7), (2.0, 4, 2), (2.0, 4, 6), (2.0, 1, 5)]);
    }
}
