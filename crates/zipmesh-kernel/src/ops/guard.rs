//! Stale-record detection, one mechanism for every undo: a record's undo runs its checks in
//! order through a [`Guard`], each check named; the first that fails names the reason the
//! record does not fit, and the undo refuses with [`Refusal::StaleRecord`] and changes
//! nothing. The names let the unit tests pin every check down (each has a map on which it
//! alone fails).
//!
//! Checks are closures, run only while every earlier check has passed, so a check may rely
//! on the earlier ones (for example read a slot an earlier check showed to be in range).

use super::Refusal;

/// The checks of one undo, run in order; see the module documentation.
#[must_use]
pub(crate) struct Guard {
    failed: Option<&'static str>,
}

impl Guard {
    #[inline]
    pub(crate) fn new() -> Guard {
        Guard { failed: None }
    }

    /// Runs `ok` unless an earlier check failed; records `name` if it fails.
    #[inline]
    pub(crate) fn check(mut self, name: &'static str, ok: impl FnOnce() -> bool) -> Guard {
        if self.failed.is_none() && !ok() {
            self.failed = Some(name);
        }
        self
    }

    /// The name of the first failed check, if any.
    #[inline]
    pub(crate) fn failed(&self) -> Option<&'static str> {
        self.failed
    }

    /// `Err(StaleRecord)` if a check failed.
    #[inline]
    pub(crate) fn result(&self) -> Result<(), Refusal> {
        match self.failed {
            None => Ok(()),
            Some(_) => Err(Refusal::StaleRecord),
        }
    }
}

/// Test support: which check of a record's guard catches each of a set of edits.
#[cfg(test)]
pub(crate) mod pin {
    use crate::map::Map;
    use crate::ops::Refusal;
    use alloc::boxed::Box;
    use alloc::collections::BTreeSet;
    use alloc::vec::Vec;

    /// A change of a map.
    pub(crate) type Edit = Box<dyn Fn(&mut Map)>;

    /// Each operator as an edit applying it (a refusal leaves the map as it is).
    pub(crate) fn edits<T: Copy + 'static, R: 'static>(
        ops: Vec<T>,
        apply: fn(T, &mut Map) -> R,
    ) -> Vec<Edit> {
        ops.into_iter()
            .map(|op| {
                Box::new(move |m: &mut Map| {
                    let _ = apply(op, m);
                }) as Edit
            })
            .collect()
    }

    /// Applies each edit to a copy of `after` (the map as the record's operation left it)
    /// and returns the names of the checks that caught them. Checks the contract on the way:
    /// the untouched map passes every check; when a check fails the undo refuses with
    /// [`Refusal::StaleRecord`] and changes nothing; when none fails the undo succeeds, and
    /// after a `legit` edit (an operator: the map stays valid) leaves a valid map. `raw`
    /// edits change array entries directly.
    pub(crate) fn caught(
        after: &Map,
        legit: &[Edit],
        raw: &[Edit],
        reason: &dyn Fn(&Map) -> Option<&'static str>,
        undo: &dyn Fn(&mut Map) -> Result<(), Refusal>,
    ) -> BTreeSet<&'static str> {
        assert_eq!(
            reason(after),
            None,
            "the record's own map must pass every check"
        );
        let mut names = BTreeSet::new();
        let all = legit.iter().map(|e| (true, e));
        for (legit, edit) in all.chain(raw.iter().map(|e| (false, e))) {
            let mut m = after.clone();
            edit(&mut m);
            let r = reason(&m);
            let snapshot = m.clone();
            let res = undo(&mut m);
            match r {
                Some(name) => {
                    assert_eq!(res, Err(Refusal::StaleRecord), "{name}");
                    assert_eq!(m, snapshot, "{name}: a refused undo changed the map");
                    names.insert(name);
                }
                None => {
                    assert_eq!(res, Ok(()));
                    if legit {
                        assert_eq!(m.check(), Ok(()), "an undo that fits left an invalid map");
                    }
                }
            }
        }
        names
    }
}
