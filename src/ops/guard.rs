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
