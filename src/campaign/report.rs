//! The campaign's report: one row per property, the failures, as a table or as JSON.

use super::shrink::Shrunk;
use super::Shard;
use core::time::Duration;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::format;
use std::path::{Path, PathBuf};
use std::string::{String, ToString};
use std::vec::Vec;

/// What a campaign's results depend on besides its seed and its properties: two shard
/// reports merge only when these are equal.
///
/// ```
/// use zipmesh::campaign::{self, Config};
/// let r = campaign::run(&Config { cases: 3, max_faces: 100, ..Config::default() }, &campaign::kernel());
/// assert_eq!((r.campaign.cases, r.campaign.max_faces), (3, 100));
/// assert!(r.campaign.inputs.is_empty()); // generated cases
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Campaign {
    /// The positions before sharding: generated cases, or given cases.
    pub cases: u64,
    /// The face budget of generated cases.
    pub max_faces: usize,
    /// The given cases, one label each (a file name; `generated case I` for a generated case
    /// given by index), with ` --focus V` when the case has a focus; empty when the campaign
    /// generates its cases.
    pub inputs: Vec<String>,
    /// Other settings the properties depend on ([`Config::settings`](super::Config::settings);
    /// `zipmesh check` records `max-distance` when it is not the default).
    pub settings: BTreeMap<String, String>,
}

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
    /// ([`Case::note_unchecked`](super::Case::note_unchecked)); for the reversal
    /// properties, the movements with no reverse run found; for the homotopy ones, the swept
    /// paths next to a triangle, not compared. Not in `checks`, and not failures.
    pub unchecked: u64,
    /// Checks that needed a fallback search, among `checks`
    /// ([`Case::note_searched`](super::Case::note_searched)): for the reversal properties,
    /// the reverse runs found by the search, not derived.
    pub searched: u64,
    /// Time spent in the property, summed over the cases and workers (so it can exceed the
    /// wall time with several jobs). Not deterministic, unlike every other field.
    pub time: Duration,
}

impl Row {
    /// A row of `property` with every count 0.
    pub(crate) fn zero(property: &str) -> Row {
        Row {
            property: property.to_string(),
            cases: 0,
            passed: 0,
            failed: 0,
            skipped: 0,
            checks: 0,
            cut: 0,
            unchecked: 0,
            searched: 0,
            time: Duration::ZERO,
        }
    }

    /// Adds `other`'s counts and time to this row (the rows of two disjoint sets of cases).
    pub(crate) fn add(&mut self, other: &Row) {
        self.cases += other.cases;
        self.passed += other.passed;
        self.failed += other.failed;
        self.skipped += other.skipped;
        self.checks += other.checks;
        self.cut += other.cut;
        self.unchecked = self.unchecked.saturating_add(other.unchecked);
        self.searched = self.searched.saturating_add(other.searched);
        self.time += other.time;
    }
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
    /// The failing case's position in the campaign (the index for generated cases, the place
    /// in the list for given ones): the failure reported is the one of smallest position.
    pub position: u64,
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
    /// counterexample when there is one, else [`case_replay`](Failure::case_replay).
    pub replay: String,
    /// The command line that replays the failure on the original case: for a generated case
    /// it needs no file, so it works on any machine; for a given case it names the file.
    pub case_replay: String,
}

impl Failure {
    /// The counterexample's file name: `<property>-seed<S>-case<I>.obj`, with characters
    /// other than ASCII letters, digits, `-` and `_` in the property name replaced by `_`.
    ///
    /// ```
    /// use zipmesh::campaign::{self, Config, Outcome, Property};
    /// let p = Property::new("a/b", "", |_| Outcome::fail("no", None));
    /// let r = campaign::run(&Config { seed: 2, cases: 1, max_faces: 50, ..Config::default() }, &[p]);
    /// assert_eq!(r.failures[0].file_name(2), "a_b-seed2-case0.obj");
    /// ```
    pub fn file_name(&self, seed: u64) -> String {
        let safe: String = self
            .property
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        format!("{safe}-seed{seed}-case{}.obj", self.case)
    }

    /// Writes the shrunk counterexample (if any) atomically into `dir` as
    /// [`file_name`](Failure::file_name), and points `path` and `replay` at it; if there is
    /// none or it cannot be written, `path` is `None` and `replay` is
    /// [`case_replay`](Failure::case_replay).
    fn write_counterexample(&mut self, dir: &Path, seed: u64, flags: &str) {
        self.path = None;
        self.replay = self.case_replay.clone();
        let Some(s) = &self.shrunk else { return };
        let path = dir.join(self.file_name(seed));
        if std::fs::create_dir_all(dir).is_err() || crate::io::write_mesh(&path, &s.mesh).is_err() {
            return;
        }
        let focus = s
            .focus
            .map(|v| format!(" --focus {}", v.index()))
            .unwrap_or_default();
        self.replay = format!(
            "zipmesh check {} --seed {seed} --property {}{focus}{flags}",
            path.display(),
            self.property
        );
        self.path = Some(path);
    }
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
    /// What identifies the campaign, so that only shards of one campaign are merged.
    pub campaign: Campaign,
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

    /// Writes every shrunk counterexample into `dir` (see [`Failure::file_name`]) and points
    /// each failure's `path` and `replay` at its file. [`run`](super::run) does this when
    /// [`Config::out_dir`](super::Config::out_dir) is set; after [`merge`](super::merge) it
    /// writes the shards' counterexamples on this machine.
    ///
    /// ```
    /// use zipmesh::campaign::{self, Config, Outcome, Property};
    /// let p = Property::new("never", "", |_| Outcome::fail("no", None));
    /// let mut r = campaign::run(&Config { cases: 1, max_faces: 50, ..Config::default() }, &[p]);
    /// assert!(r.failures[0].path.is_none());
    /// let dir = std::env::temp_dir().join(format!("zipmesh-doc-cx-{}", std::process::id()));
    /// r.write_counterexamples(&dir);
    /// let path = r.failures[0].path.clone().unwrap();
    /// assert!(path.is_file() && r.failures[0].replay.contains("never-seed0-case0.obj"));
    /// std::fs::remove_dir_all(&dir).unwrap();
    /// ```
    pub fn write_counterexamples(&mut self, dir: &Path) {
        let flags = setting_flags(&self.campaign.settings);
        for f in &mut self.failures {
            f.write_counterexample(dir, self.seed, &flags);
        }
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

    /// The report as one JSON object: `seed`, `shard` (`"i/n"`), the campaign (`cases`,
    /// `max_faces`, `inputs`, a list of labels, and `settings`, an object of strings),
    /// `planned`, `run`, `timed_out`, `passed`, `properties` (a list of objects with `name`,
    /// `cases`, `passed`, `failed`, `skipped`, `checks`, `cut`, `unchecked` and, if `times`,
    /// `seconds`), if `times` the campaign's wall time `seconds`, and `failures` (a list of
    /// objects with `property`, `case`, `position`, `description`, `message`,
    /// `original_faces`, `shrunk_faces`, `shrunk_message`, `shrunk_focus`, `counterexample`
    /// (a path), `counterexample_obj` (the shrunk mesh as OBJ text, so that another machine
    /// can write it again), `replay` and `case_replay`; absent values are `null`).
    ///
    /// ```
    /// use zipmesh::campaign::{self, Config};
    /// let r = campaign::run(&Config { cases: 2, max_faces: 100, ..Config::default() }, &campaign::kernel());
    /// let json = r.to_json(true);
    /// assert!(json.contains("\"name\":\"validity\"") && json.contains("\"seconds\":"));
    /// assert!(json.contains("\"cases\":2,\"max_faces\":100,\"inputs\":[],\"settings\":{}"));
    /// ```
    pub fn to_json(&self, times: bool) -> String {
        let c = &self.campaign;
        let inputs: Vec<String> = c.inputs.iter().map(|i| quote(i)).collect();
        let settings: Vec<String> = c
            .settings
            .iter()
            .map(|(k, v)| format!("{}:{}", quote(k), quote(v)))
            .collect();
        let mut s = String::new();
        let _ = write!(
            s,
            "{{\"seed\":{},\"shard\":\"{}\",\"cases\":{},\"max_faces\":{},\"inputs\":[{}],\"settings\":{{{}}},\"planned\":{},\"run\":{},\"timed_out\":{},\"passed\":{},\"properties\":[",
            self.seed,
            self.shard,
            c.cases,
            c.max_faces,
            inputs.join(","),
            settings.join(","),
            self.planned,
            self.run,
            self.timed_out,
            self.passed()
        );
        for (i, r) in self.rows.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            row_json(&mut s, r, times);
        }
        s.push(']');
        if times {
            let _ = write!(s, ",\"seconds\":{}", self.elapsed.as_secs_f64());
        }
        s.push_str(",\"failures\":[");
        for (i, f) in self.failures.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            failure_json(&mut s, f);
        }
        s.push_str("]}");
        s
    }
}

fn row_json(s: &mut String, r: &Row, times: bool) {
    let _ = write!(
        s,
        "{{\"name\":{},\"cases\":{},\"passed\":{},\"failed\":{},\"skipped\":{},\"checks\":{},\"cut\":{},\"unchecked\":{},\"searched\":{}",
        quote(&r.property),
        r.cases,
        r.passed,
        r.failed,
        r.skipped,
        r.checks,
        r.cut,
        r.unchecked,
        r.searched
    );
    if times {
        let _ = write!(s, ",\"seconds\":{}", r.time.as_secs_f64());
    }
    s.push('}');
}

fn failure_json(s: &mut String, f: &Failure) {
    let null = || "null".to_string();
    let shrunk = f.shrunk.as_ref();
    let faces = shrunk.map_or_else(null, |x| x.mesh.map.num_faces().to_string());
    let message = shrunk.map_or_else(null, |x| quote(&x.message));
    let focus = shrunk
        .and_then(|x| x.focus)
        .map_or_else(null, |v| v.index().to_string());
    let obj = shrunk.map_or_else(null, |x| {
        let mut text = Vec::new();
        match crate::io::obj::write(&x.mesh, &mut text) {
            Ok(()) => quote(&String::from_utf8_lossy(&text)),
            Err(_) => null(),
        }
    });
    let path = f
        .path
        .as_ref()
        .map_or_else(null, |p| quote(&p.display().to_string()));
    let _ = write!(
        s,
        "{{\"property\":{},\"case\":{},\"position\":{},\"description\":{},\"message\":{},\"original_faces\":{},\"shrunk_faces\":{faces},\"shrunk_message\":{message},\"shrunk_focus\":{focus},\"counterexample\":{path},\"counterexample_obj\":{obj},\"replay\":{},\"case_replay\":{}}}",
        quote(&f.property),
        f.case,
        f.position,
        quote(&f.description),
        quote(&f.message),
        f.original_faces,
        quote(&f.replay),
        quote(&f.case_replay)
    );
}

/// The settings as command-line flags: ` --name value` each, in name order.
pub(crate) fn setting_flags(settings: &std::collections::BTreeMap<String, String>) -> String {
    settings
        .iter()
        .map(|(k, v)| format!(" --{k} {v}"))
        .collect()
}

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
