//! The time limit inside a case: the runner sets a budget for the thread that checks a
//! property, and the property polls it between its checks with [`Case::out_of_time`].
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
}

std::thread_local! {
    static CURRENT: RefCell<Option<Budget>> = const { RefCell::new(None) };
}

/// Runs `f` (one property on one case) under the deadline; returns its result and whether
/// it was cut short (it polled after the deadline).
pub(crate) fn within<R>(
    deadline: Option<Instant>,
    counter: &CheckCounter,
    f: impl FnOnce() -> R,
) -> (R, bool) {
    let budget = Budget {
        deadline,
        counter: counter.clone(),
        cut: false,
    };
    let previous = CURRENT.with(|c| c.replace(Some(budget)));
    let result = f();
    let cut = CURRENT.with(|c| c.replace(previous)).is_some_and(|b| b.cut);
    (result, cut)
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
}
