//! Epoch-stamped marks over slots (vertices or faces), reused between calls: forgetting
//! every mark is one increment, not a pass over the slots. The searches, the face lists
//! and the fold guard run round every candidate, so they share this one mechanism.

use alloc::vec::Vec;

/// A set of slots, emptied in O(1) by [`Marks::begin`].
#[derive(Clone, Debug, Default)]
pub(crate) struct Marks {
    stamp: Vec<u32>,
    epoch: u32,
}

impl Marks {
    /// Forgets every mark, with room for `slots` slots (a slot past them is never marked).
    pub(crate) fn begin(&mut self, slots: usize) {
        if self.stamp.len() < slots {
            self.stamp.resize(slots, 0);
        }
        self.epoch = self.epoch.wrapping_add(1);
        // After 2^32 begins a stale stamp could equal the epoch: clear them all once.
        if self.epoch == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.epoch = 1;
        }
    }

    /// Marks slot `i`: whether it was unmarked since [`Marks::begin`] (false for a slot
    /// past the room given to it).
    pub(crate) fn first(&mut self, i: usize) -> bool {
        match self.stamp.get_mut(i) {
            Some(s) if *s != self.epoch => {
                *s = self.epoch;
                true
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slot_is_first_once_per_begin() {
        let mut m = Marks::default();
        for round in 0..3 {
            m.begin(4 + round);
            assert!(m.first(2) && !m.first(2), "round {round}");
            assert!(m.first(0) && m.first(3 + round));
            assert!(!m.first(4 + round), "past the room");
        }
        // The epoch wraps: every stamp is cleared, no slot reads as marked.
        m.epoch = u32::MAX;
        m.stamp.iter_mut().for_each(|s| *s = 1);
        m.begin(4);
        assert_eq!(m.epoch, 1);
        assert!(m.first(1));
    }
}
