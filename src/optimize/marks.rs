//! Epoch-stamped marks over slots (vertices or faces), reused between calls: forgetting
//! every mark is one increment, not a pass over the slots. The searches, the face lists,
//! the fold guard, a candidate's window and the per-vertex memos of the score terms run
//! round every candidate, so they share this one mechanism.

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

    /// [`Marks::first`], making room for slot `i` first (for sets whose slots are not known
    /// when they begin).
    pub(crate) fn first_growing(&mut self, i: usize) -> bool {
        if self.stamp.len() <= i {
            self.stamp.resize(i + 1, 0);
        }
        self.first(i)
    }

    /// Whether slot `i` is marked since [`Marks::begin`].
    pub(crate) fn has(&self, i: usize) -> bool {
        self.stamp.get(i) == Some(&self.epoch)
    }
}

/// Per-slot values valid since the last [`Memo::begin`]: the marks say which are set.
#[derive(Clone, Debug, Default)]
pub(crate) struct Memo<T> {
    marks: Marks,
    value: Vec<T>,
}

impl<T: Copy + Default> Memo<T> {
    /// Forgets every value, with room for `slots` slots.
    pub(crate) fn begin(&mut self, slots: usize) {
        self.marks.begin(slots);
        if self.value.len() < slots {
            self.value.resize(slots, T::default());
        }
    }

    /// The value of slot `i`, computed by `f` the first time since [`Memo::begin`] (every
    /// time for a slot past the room given to it).
    pub(crate) fn get(&mut self, i: usize, f: impl FnOnce() -> T) -> T {
        match self.value.get_mut(i) {
            Some(x) => {
                if self.marks.first(i) {
                    *x = f();
                }
                *x
            }
            None => f(),
        }
    }

    /// The value of slot `i` if set since [`Memo::begin`].
    pub(crate) fn peek(&self, i: usize) -> Option<T> {
        if self.marks.has(i) {
            self.value.get(i).copied()
        } else {
            None
        }
    }

    /// Sets the value of slot `i` (nothing for a slot past the room given to it).
    pub(crate) fn set(&mut self, i: usize, x: T) {
        if let Some(y) = self.value.get_mut(i) {
            self.marks.first(i);
            *y = x;
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

    #[test]
    fn growing_marks_and_has() {
        let mut m = Marks::default();
        m.begin(0);
        assert!(!m.first(5) && !m.has(5), "no room yet");
        assert!(m.first_growing(5) && m.has(5) && !m.first_growing(5));
        assert!(!m.has(4));
        m.begin(0);
        assert!(!m.has(5) && m.first(5));
    }

    #[test]
    fn memo_computes_once_per_begin() {
        let mut memo = Memo::<i64>::default();
        memo.begin(3);
        let mut calls = 0;
        for _ in 0..2 {
            assert_eq!(
                memo.get(1, || {
                    calls += 1;
                    7
                }),
                7
            );
        }
        assert_eq!(calls, 1);
        assert_eq!((memo.peek(1), memo.peek(0)), (Some(7), None));
        memo.set(0, -2);
        assert_eq!(memo.peek(0), Some(-2));
        // Past the room: computed every time, never stored.
        assert_eq!(memo.get(9, || 4), 4);
        memo.set(9, 5);
        assert_eq!(memo.peek(9), None);
        memo.begin(3);
        assert_eq!((memo.peek(0), memo.peek(1)), (None, None));
        assert_eq!(memo.get(1, || 8), 8);
    }
}
