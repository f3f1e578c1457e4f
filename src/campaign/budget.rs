//! The time limit inside a case: the runner sets a budget for the thread that checks a
//! property, and the property polls it between its checks with [`Case::out_of_time`]. The
//! same budget takes the count of what the property found but could not check
//! ([`Case::note_unchecked`]).
//!
//! A thread-local rather than a field of [`Case`], so that given cases are checked by
//! reference (no copy of a large mesh per property) and property signatures stay as they are.

use super::Case;
use alloc::sync::Arc;
use core::cell::RefCell;
use core::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// A count of the checks polled so far, shared between the runner and an observer (a
/// progress bar) that reads it while a long case runs.
///
/// ```
/// use zipmesh::campaign::{self, CheckCounter, Config};
/// let counter = CheckCounter::default();
/// let c = Config { cases: 2, max_faces: 200, checks: counter.clone(), ..Config::default() };
/// campaign::run(&c, &campaign::operators());
/// assert!(counter.get() > 0);
/// ```
#[derive(Clone, Debug, Default)]
pub struct CheckCounter(Arc<AtomicU64>);

impl CheckCounter {
    /// The checks polled so far.
    ///
    /// ```
    /// assert_eq!(zipmesh::campaign::CheckCounter::default().get(), 0);
    /// ```
    pub fn get(&self) -> u64 {
        self.0.load(Ordering::Relaxed)
    }
}

impl PartialEq for CheckCounter {
    /// Two counters are equal when they are the same counter.
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

struct Budget {
    deadline: Option<Instant>,
    counter: CheckCounter,
    cut: bool,
    unchecked: u64,
    searched: u64,
}

/// What the runner learns of one property on one case besides its outcome.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Notes {
    /// It polled after the deadline.
    pub cut: bool,
    /// The sum of its [`Case::note_unchecked`] calls.
    pub unchecked: u64,
    /// The sum of its [`Case::note_searched`] calls.
    pub searched: u64,
}

std::thread_local! {
    static CURRENT: RefCell<Option<Budget>> = const { RefCell::new(None) };
}

/// Runs `f` (one property on one case) under the deadline; returns its result, whether it
/// was cut short and what it left unchecked.
pub(crate) fn within<R>(
    deadline: Option<Instant>,
    counter: &CheckCounter,
    f: impl FnOnce() -> R,
) -> (R, Notes) {
    let budget = Budget {
        deadline,
        counter: counter.clone(),
        cut: false,
        unchecked: 0,
        searched: 0,
    };
    let previous = CURRENT.with(|c| c.replace(Some(budget)));
    let result = f();
    let notes = CURRENT
        .with(|c| c.replace(previous))
        .map_or(Notes::default(), |b| Notes {
            cut: b.cut,
            unchecked: b.unchecked,
            searched: b.searched,
        });
    (result, notes)
}

impl Case {
    /// Whether the campaign's time limit has passed: a property calls this between its
    /// checks and stops when it is `true` (it then returns what it checked so far, and the
    /// report counts the case as cut short). Each call also counts one check for the
    /// progress display. Outside a campaign with a time limit it is always `false`.
    ///
    /// ```
    /// use std::time::Duration;
    /// use zipmesh::campaign::{self, Case, Config, Outcome, Property};
    /// let p = Property::new("slow", "", |case: &Case| {
    ///     let mut checks = 0;
    ///     while !case.out_of_time() {
    ///         checks += 1; // one check
    ///     }
    ///     Outcome::Pass { checks }
    /// });
    /// let c = Config { cases: 1, time_limit: Some(Duration::from_millis(20)), ..Config::default() };
    /// let r = campaign::run(&c, &[p]);
    /// assert!(r.timed_out && r.rows[0].cut == 1 && r.rows[0].passed == 1);
    /// assert!(!Case::generate(0, 0, 100).out_of_time());
    /// ```
    pub fn out_of_time(&self) -> bool {
        CURRENT.with(|c| match c.borrow_mut().as_mut() {
            None => false,
            Some(b) => {
                b.counter.0.fetch_add(1, Ordering::Relaxed);
                if b.deadline.is_some_and(|d| Instant::now() >= d) {
                    b.cut = true;
                }
                b.cut
            }
        })
    }

    /// Records that the property found `n` things it could not check: for `qzip-reversal`,
    /// movements for which no reverse run was found. The report sums them per property
    /// ([`Row::unchecked`](super::Row::unchecked)) beside its checks; they neither fail nor
    /// skip the case. Outside a campaign it does nothing.
    ///
    /// ```
    /// use zipmesh::campaign::{self, Case, Config, Outcome, Property};
    /// let p = Property::new("odd-faces", "", |case: &Case| {
    ///     let n = case.mesh.map.num_faces() as u64;
    ///     case.note_unchecked(n % 2); // an odd face out, say, that it cannot check
    ///     Outcome::Pass { checks: n / 2 }
    /// });
    /// let c = Config { cases: 4, max_faces: 100, ..Config::default() };
    /// let r = campaign::run(&c, &[p]);
    /// assert!(r.passed() && r.rows[0].unchecked <= 4);
    /// assert!(r.to_json(false).contains("\"unchecked\":"));
    /// ```
    pub fn note_unchecked(&self, n: u64) {
        CURRENT.with(|c| {
            if let Some(b) = c.borrow_mut().as_mut() {
                b.unchecked = b.unchecked.saturating_add(n);
            }
        });
    }

    /// Records that `n` of the property's checks needed a fallback search: for the reversal
    /// properties, reverse runs that [`qzip::derive_reverse`](crate::qzip::derive_reverse)
    /// did not give and [`qzip::find_reverse`](crate::qzip::find_reverse)'s search found.
    /// They are checks like the others; the report sums them per property
    /// ([`Row::searched`](super::Row::searched)). Outside a campaign it does nothing.
    ///
    /// ```
    /// use zipmesh::campaign::{self, Case, Config, Outcome, Property};
    /// let p = Property::new("found-late", "", |case: &Case| {
    ///     case.note_searched(1);
    ///     Outcome::Pass { checks: 2 }
    /// });
    /// let c = Config { cases: 3, max_faces: 100, ..Config::default() };
    /// let r = campaign::run(&c, &[p]);
    /// assert_eq!((r.rows[0].checks, r.rows[0].searched), (6, 3));
    /// assert!(r.to_json(false).contains("\"searched\":3"));
    /// ```
    pub fn note_searched(&self, n: u64) {
        CURRENT.with(|c| {
            if let Some(b) = c.borrow_mut().as_mut() {
                b.searched = b.searched.saturating_add(n);
            }
        });
    }
}
