//! The per-vertex records of a search: one [`Slot`] per vertex, kept in a hash map
//! ([`HashStore`], one-off sketches) or in epoch-stamped arrays ([`ArrayStore`], a
//! [`super::SketchWorkspace`]), and the reused buffers of one search.

use alloc::collections::BinaryHeap;
use alloc::vec::Vec;

use hashbrown::HashMap;

use super::heap::{AEntry, Entry};
use crate::{Dart, Vert};

/// What a search knows of one vertex, in 16 bytes (the searches are bound by memory traffic
/// on large maps). Every field is valid only with its flag set.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Slot {
    /// The search epoch that wrote this slot (workspace arrays only) above 8 flag bits.
    pub(super) tag: u32,
    /// Distance from `from` (BFS layer, A* g; `FWD`).
    pub(super) fwd: u32,
    /// Distance from `to` (backward BFS layer, `BWD`); in A*, the dart that last improved
    /// `fwd` (with `FWD`).
    pub(super) bwd: u32,
    /// The dart that reached this vertex in the final pass (`PRED`).
    pub(super) pred: u32,
}

pub(super) const FWD: u8 = 1;
pub(super) const BWD: u8 = 2;
pub(super) const DAG: u8 = 4;
pub(super) const PRED: u8 = 8;
pub(super) const DONE: u8 = 16;
/// Epochs live in the tag's upper 24 bits.
pub(super) const EPOCHS: u32 = 1 << 24;

impl Slot {
    pub(super) fn has(&self, flag: u8) -> bool {
        self.tag & u32::from(flag) != 0
    }

    pub(super) fn set(&mut self, flag: u8) {
        self.tag |= u32::from(flag);
    }

    /// Dijkstra's distance, kept in `fwd` and `bwd` (with `FWD`).
    pub(super) fn dist(&self) -> f64 {
        f64::from_bits((u64::from(self.fwd) << 32) | u64::from(self.bwd))
    }

    pub(super) fn set_dist(&mut self, d: f64) {
        let bits = d.to_bits();
        self.fwd = (bits >> 32) as u32;
        self.bwd = bits as u32;
    }
}

/// Per-vertex records of one search pass: a hash map ([`sketch`]) or epoch-stamped arrays
/// ([`SketchWorkspace`]).
pub(super) trait Store {
    /// The record of `v` (all flags clear when the pass has not touched it).
    fn get(&self, v: Vert) -> Slot;
    /// The record of `v`, created empty on first touch.
    fn get_mut(&mut self, v: Vert) -> &mut Slot;
    /// Forgets every record: the start of a new search pass.
    fn next_pass(&mut self);
}

/// One-off records: the search costs what it explores, with no O(V) set-up.
pub(super) struct HashStore(pub(super) HashMap<u32, Slot>);

impl Store for HashStore {
    fn get(&self, v: Vert) -> Slot {
        self.0.get(&(v.index() as u32)).copied().unwrap_or_default()
    }
    fn get_mut(&mut self, v: Vert) -> &mut Slot {
        self.0.entry(v.index() as u32).or_default()
    }
    fn next_pass(&mut self) {
        self.0.clear();
    }
}

/// Records in a reused array: a slot is valid when its stamp is the current epoch, so a new
/// pass costs one increment, not an O(V) clear. The epoch and the count of touched slots are
/// held by value (through references, each slot access reloaded them) and handed back to
/// the workspace after the search.
pub(super) struct ArrayStore<'w> {
    pub(super) slots: &'w mut Vec<Slot>,
    pub(super) epoch: u32,
    pub(super) touched: usize,
}

/// Grows `slots` to hold index `i`: only for handles past the map's slots, which live darts
/// never reach, so kept out of line (inlined, it kept `get_mut` from being inlined, and the
/// searches call `get_mut` a few hundred times per sketch).
#[cold]
#[inline(never)]
fn grow(slots: &mut Vec<Slot>, i: usize) -> &mut Slot {
    slots.resize(i + 1, Slot::default());
    &mut slots[i]
}

impl Store for ArrayStore<'_> {
    #[inline]
    fn get(&self, v: Vert) -> Slot {
        match self.slots.get(v.index()) {
            Some(s) if s.tag >> 8 == self.epoch => *s,
            _ => Slot::default(),
        }
    }
    #[inline]
    fn get_mut(&mut self, v: Vert) -> &mut Slot {
        let i = v.index();
        let s = if i < self.slots.len() {
            &mut self.slots[i]
        } else {
            grow(self.slots, i)
        };
        if s.tag >> 8 != self.epoch {
            *s = Slot {
                tag: self.epoch << 8,
                ..Slot::default()
            };
            self.touched += 1;
        }
        s
    }
    fn next_pass(&mut self) {
        // A fresh epoch; on wrap-around, clear once so no old stamp matches.
        self.epoch += 1;
        if self.epoch >= EPOCHS {
            self.slots.fill(Slot::default());
            self.epoch = 1;
        }
    }
}

/// Reused buffers of one search.
#[derive(Default)]
pub(super) struct Buffers {
    pub(super) a: Vec<Vert>,
    pub(super) b: Vec<Vert>,
    pub(super) c: Vec<Vert>,
    pub(super) darts: Vec<Dart>,
    pub(super) astar: BinaryHeap<AEntry>,
    pub(super) dijkstra: BinaryHeap<Entry>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A handle past the arrays grows them and starts empty; a new pass forgets every
    /// record without clearing the array, and stamps never leak from one pass into the next.
    #[test]
    fn array_store_grows_and_forgets() {
        let mut slots = Vec::new();
        let mut st = ArrayStore {
            slots: &mut slots,
            epoch: 1,
            touched: 0,
        };
        let v = Vert::new(9);
        assert!(!st.get(v).has(FWD));
        st.get_mut(v).set(FWD);
        st.get_mut(v).fwd = 3;
        assert!(st.get(v).has(FWD) && st.get(v).fwd == 3);
        assert!(!st.get(Vert::new(8)).has(FWD));
        st.next_pass();
        // The pass is one increment: the old record is still in the array, stale.
        assert!(st.slots[9].has(FWD) && st.slots[9].fwd == 3);
        assert!(!st.get(v).has(FWD));
        assert!(!st.get_mut(v).has(FWD));
        // The first handle past the end grows the arrays by one.
        assert!(!st.get_mut(Vert::new(10)).has(FWD));
        let touched = st.touched;
        assert_eq!((slots.len(), touched), (11, 3));
    }
}
