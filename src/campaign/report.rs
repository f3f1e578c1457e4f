//! The campaign's report: one row per property, the failures, as a table or as JSON.

use super::shrink::Shrunk;
use super::Shard;
use core::time::Duration;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::string::String;
use std::vec::Vec;

/// One property's totals.
///
/// ```
/// use zipmesh::campaign::{self, Config};
/// let r = campaign::run(&Config { cases: 4, max_faces: 150, ..Config::default() }, &campaign::kernel());
/// let row = &r.rows[0];
/// assert_eq!(row.cases, row.passed + row.failed);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    /// The property's name.
    pub property: String,
    /// Cases the property applied to (not skipped).
    pub cases: u64,
    /// Cases that passed.
    pub passed: u64,
    /// Cases that failed.
    pub failed: u64,
    /// Cases the property did not apply to.
    pub skipped: u64,
    /// Assertions made (summed [`Outcome::Pass`](super::Outcome::Pass) `checks`).
    pub checks: u64,
    /// Cases the time limit cut the property short on (it polled
    /// [`Case::out_of_time`](super::Case::out_of_time) after the deadline): their outcome
    /// covers only the checks that ran, which `checks` counts.
    pub cut: u64,
    /// What the property found but could not check, summed over the cases
    /// ([`Case::note_unchecked`](super::Case::note_unchecked)); for `qzip-reversal`, the
    /// movements with no reverse run found. Not in `checks`, and not failures.
    pub unchecked: u64,
    /// Time spent in the property, summed over the cases and workers (so it can exceed the
    /// wall time with several jobs). Not deterministic, unlike every other field.
    pub time: Duration,
}

/// A property's first failing case (the one with the smallest index), shrunk.
///
/// ```
/// use zipmesh::campaign::{self, Config, Outcome, Property};
/// let p = Property::new("no-boundary", "", |c| {
///     let m = &c.mesh.map;
///     match m.vertices().find(|&v| m.is_boundary_vertex(v)) {
///         Some(v) => Outcome::fail("a boundary vertex", Some(v)),
///         None => Outcome::Pass { checks: 1 },
///     }
/// });
/// let r = campaign::run(&Config { cases: 20, max_faces: 200, ..Config::default() }, &[p]);
/// let f = &r.failures[0];
/// assert!(f.shrunk.as_ref().unwrap().mesh.map.num_faces() < f.original_faces);
/// ```
#[derive(Clone, Debug)]
pub struct Failure {
    /// The property.
    pub property: String,
    /// The failing case's index.
    pub case: u64,
    /// The failing case, described ([`Case::describe`](super::Case::describe)).
    pub description: String,
    /// The failure message on the original case.
    pub message: String,
    /// The original case's face count.
    pub original_faces: usize,
    /// The shrunk counterexample, when shrinking ran and found a failing mesh.
    pub shrunk: Option<Shrunk>,
    /// Where the shrunk counterexample was written as OBJ (when an output directory was set).
    pub path: Option<PathBuf>,
    /// One `zipmesh check` command line that replays the failure: on the written
    /// counterexample when there is one, else on the original case.
    pub replay: String,
}

/// Everything a campaign found.
///
/// ```
/// use zipmesh::campaign::{self, Config};
/// let r = campaign::run(&Config { cases: 3, max_faces: 150, ..Config::default() }, &campaign::kernel());
/// assert!(r.passed());
/// assert!(r.table(false).starts_with("property"));
/// assert!(r.to_json(false).starts_with('{'));
/// ```
#[derive(Clone, Debug)]
pub struct Report {
    /// The campaign seed.
    pub seed: u64,
    /// The shard that was run.
    pub shard: Shard,
    /// Cases in the shard.
    pub planned: u64,
    /// Cases run (fewer than `planned` only when the time limit was reached).
    pub run: u64,
    /// Whether the time limit stopped the campaign early: cases not run, or a property cut
    /// short inside a case ([`Row::cut`]).
    pub timed_out: bool,
    /// Wall time of the whole campaign, shrinking included (not deterministic).
    pub elapsed: Duration,
    /// One row per property, in the order given.
    pub rows: Vec<Row>,
    /// One entry per property that failed, in the order of `rows`.
    pub failures: Vec<Failure>,
}

impl Report {
    /// Whether no property failed.
    ///
    /// ```
    /// use zipmesh::campaign::{self, Config};
    /// let r = campaign::run(&Config { cases: 2, max_faces: 100, ..Config::default() }, &campaign::kernel());
    /// assert!(r.passed());
    /// ```
    pub fn passed(&self) -> bool {
        self.failures.is_empty() && self.rows.iter().all(|r| r.failed == 0)
    }

    /// The table: property, cases, passed, failed, skipped, checks, cut, unchecked and, if
    /// `times`, the time in seconds. Without times the text is the same for the same campaign on any
    /// machine and with any number of jobs.
    ///
    /// ```
    /// use zipmesh::campaign::{self, Config};
    /// let c = Config { cases: 3, max_faces: 100, ..Config::default() };
    /// let a = campaign::run(&c, &campaign::kernel()).table(false);
    /// let b = campaign::run(&Config { jobs: Some(1), ..c }, &campaign::kernel()).table(false);
    /// assert_eq!(a, b);
    /// ```
    pub fn table(&self, times: bool) -> String {
        let width = self
            .rows
            .iter()
            .map(|r| r.property.len())
            .max()
            .unwrap_or(0)
            .max(8);
        let mut s = String::new();
        let _ = write!(
            s,
            "{:<width$} {:>7} {:>7} {:>7} {:>7} {:>9} {:>5} {:>9}",
            "property", "cases", "passed", "failed", "skipped", "checks", "cut", "unchecked"
        );
        if times {
            let _ = write!(s, " {:>9}", "time (s)");
        }
        s.push('\n');
        for r in &self.rows {
            let _ = write!(
                s,
                "{:<width$} {:>7} {:>7} {:>7} {:>7} {:>9} {:>5} {:>9}",
                r.property, r.cases, r.passed, r.failed, r.skipped, r.checks, r.cut, r.unchecked
            );
            if times {
                let _ = write!(s, " {:>9.3}", r.time.as_secs_f64());
            }
            s.push('\n');
        }
        s
    }

    /// The report as one JSON object: `seed`, `shard` (`"i/n"`), `planned`, `run`,
    /// `timed_out`, `passed`, `properties` (a list of objects with `name`, `cases`, `passed`,
    /// `failed`, `skipped`, `checks`, `cut`, `unchecked` and, if `times`, `seconds`), if `times` the campaign's
    /// wall time `seconds`, and `failures` (a list of
    /// objects with `property`, `case`, `description`, `message`, `original_faces`,
    /// `shrunk_faces`, `counterexample` (a path or null) and `replay`).
    ///
    /// ```
    /// use zipmesh::campaign::{self, Config};
    /// let r = campaign::run(&Config { cases: 2, max_faces: 100, ..Config::default() }, &campaign::kernel());
    /// let json = r.to_json(true);
    /// assert!(json.contains("\"name\":\"validity\"") && json.contains("\"seconds\":"));
    /// ```
    pub fn to_json(&self, times: bool) -> String {
        let mut s = String::new();
        let _ = write!(
            s,
            "{{\"seed\":{},\"shard\":\"{}\",\"planned\":{},\"run\":{},\"timed_out\":{},\"passed\":{},\"properties\":[",
            self.seed,
            self.shard,
            self.planned,
            self.run,
            self.timed_out,
            self.passed()
        );
        for (i, r) in self.rows.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            let _ = write!(
                s,
                "{{\"name\":{},\"cases\":{},\"passed\":{},\"failed\":{},\"skipped\":{},\"checks\":{},\"cut\":{},\"unchecked\":{}",
                quote(&r.property),
                r.cases,
                r.passed,
                r.failed,
                r.skipped,
                r.checks,
                r.cut,
                r.unchecked
            );
            if times {
                let _ = write!(s, ",\"seconds\":{}", r.time.as_secs_f64());
            }
            s.push('}');
        }
        if times {
            let _ = write!(s, "],\"seconds\":{}", self.elapsed.as_secs_f64());
            s.push_str(",\"failures\":[");
        } else {
            s.push_str("],\"failures\":[");
        }
        for (i, f) in self.failures.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            let shrunk = f
                .shrunk
                .as_ref()
                .map_or("null".into(), |x| x.mesh.map.num_faces().to_string());
            let path = f
                .path
                .as_ref()
                .map_or("null".into(), |p| quote(&p.display().to_string()));
            let _ = write!(
                s,
                "{{\"property\":{},\"case\":{},\"description\":{},\"message\":{},\"original_faces\":{},\"shrunk_faces\":{},\"counterexample\":{},\"replay\":{}}}",
                quote(&f.property),
                f.case,
                quote(&f.description),
                quote(&f.message),
                f.original_faces,
                shrunk,
                path,
                quote(&f.replay)
            );
        }
        s.push_str("]}");
        s
    }
}

use std::string::ToString;

/// A JSON string literal.
fn quote(text: &str) -> String {
    let mut s = String::with_capacity(text.len() + 2);
    s.push('"');
    for c in text.chars() {
        match c {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            '\r' => s.push_str("\\r"),
            '\t' => s.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(s, "\\u{:04x}", c as u32);
            }
            c => s.push(c),
        }
    }
    s.push('"');
    s
}

#[cfg(test)]
mod tests {
    use super::quote;

    #[test]
    fn quote_escapes_control_and_quote_characters() {
        assert_eq!(quote("a\"b\\c\nd\u{1}"), "\"a\\\"b\\\\c\\nd\\u0001\"");
    }
}
