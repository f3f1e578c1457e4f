//! Property campaigns: run named properties over many deterministic cases (generated or
//! given meshes), in parallel, and report a table; failures are shrunk to small
//! counterexamples. This is the engine behind `zipmesh check`, and a library API for checking
//! your own editing code against the kernel.
//!
//! * [`Case`]: one mesh, made from `(seed, index)` only ([`Case::generate`]) or given.
//! * [`Property`]: a name and a check `Fn(&Case) -> Outcome`; [`builtin`] lists the kernel's
//!   and the operators' properties, and your own are just more values; [`undo_property`]
//!   makes one for an editing operator with an undo record.
//! * [`run`] / [`run_cases`]: the campaign; [`Report`]: rows and [`Failure`]s.
//! * [`shrink()`]: deletes faces far from the failure while it still fails.
//!
//! **Determinism.** Case `i` depends only on the seed, `i` and `max_faces`; properties take
//! their random choices from the case; results are gathered in case order and the first
//! failure per property is the one with the smallest index. So the same configuration gives
//! the same report (every field but the times) for any number of jobs, unless a time limit
//! stops it early. `docs/campaign.md` describes every property.
//!
//! ```
//! use zipmesh::campaign::{self, Config, Outcome, Property};
//! // A property of your own: a quad collapse followed by its undo restores the map.
//! let mine = Property::new("collapse-undo", "collapse then undo is the identity", |case| {
//!     let mut map = case.mesh.map.clone();
//!     let mut checks = 0;
//!     for d in case.sites(4) {
//!         if let Ok(rec) = zipmesh::ops::quad::collapse_quad(&mut map, d) {
//!             if rec.undo(&mut map).is_err() || map != case.mesh.map {
//!                 return Outcome::fail("undo differs", Some(case.mesh.map.origin(d)));
//!             }
//!             checks += 1;
//!         }
//!     }
//!     Outcome::Pass { checks }
//! });
//! let mut properties = campaign::kernel();
//! properties.push(mine);
//! let config = Config { cases: 6, max_faces: 300, ..Config::default() };
//! let report = campaign::run(&config, &properties);
//! assert!(report.passed(), "{}", report.table(true));
//! assert_eq!(report.rows.len(), 5);
//! ```

use core::time::Duration;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::string::{String, ToString};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Instant;
use std::vec::Vec;
use std::{format, vec};

mod budget;
mod case;
mod merge;
mod optimize;
mod property;
mod qzip;
mod qzip_quad_dominant;
mod report;
mod shard;
mod shrink;
mod tri_edit;

pub use budget::CheckCounter;
pub use case::{Case, Kind, Origin};
pub use merge::{merge, MergeError};
pub use optimize::{
    check_optimize_triangles, optimize_property, optimize_triangles_property, OPTIMIZE_MAX_FACES,
    TRI_OPTIMIZE_MAX_FACES,
};
pub use property::{
    builtin, builtin_with, kernel, operators, quad_dominant, undo_property, CheckFn, Outcome,
    Property,
};
pub use qzip::PairChoice;
pub use qzip_quad_dominant::qzip_properties;
pub use report::{Campaign, Failure, Report, Row};
pub use shard::{Shard, ShardError};
pub use shrink::{shrink, Shrunk, SHRINK_BUDGET};
pub use tri_edit::tri_edit_properties;

/// A campaign's settings. `Config::default()` is the default campaign of `zipmesh check`.
///
/// ```
/// let c = zipmesh::campaign::Config::default();
/// assert_eq!((c.seed, c.cases, c.max_faces), (0, 2000, 1000));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// The campaign seed.
    pub seed: u64,
    /// How many cases (before sharding) [`run`] generates; [`run_cases`] ignores it.
    pub cases: u64,
    /// The face budget of generated cases ([`Case::generate`]).
    pub max_faces: usize,
    /// Which slice of the cases to run.
    pub shard: Shard,
    /// Worker threads; `None` uses rayon's global pool (all cores).
    pub jobs: Option<usize>,
    /// Stop after this long: no new case starts, and properties stop between their checks
    /// ([`Case::out_of_time`]). The report then says `timed_out`, counts the cases each
    /// property was cut short on ([`Row::cut`]), and which cases ran depends on timing.
    pub time_limit: Option<Duration>,
    /// Counts the checks polled while the campaign runs, for a progress display.
    pub checks: CheckCounter,
    /// Shrink the first failure of each property.
    pub shrink: bool,
    /// Where to write shrunk counterexamples as OBJ files (`None`: not written).
    pub out_dir: Option<PathBuf>,
    /// Settings your properties depend on beyond the seed and the cases (for example a
    /// search radius), named by the `zipmesh check` flag that sets them (without `--`):
    /// recorded in the report ([`Campaign::settings`]) so that shards run with different
    /// settings are never merged, and passed on in every replay line as `--name value`.
    pub settings: BTreeMap<String, String>,
}

impl Default for Config {
    fn default() -> Config {
        Config {
            seed: 0,
            cases: 2000,
            max_faces: 1000,
            shard: Shard::ALL,
            jobs: None,
            time_limit: None,
            checks: CheckCounter::default(),
            shrink: true,
            out_dir: None,
            settings: BTreeMap::new(),
        }
    }
}

/// The properties of `all` named in `names`, in the order of `names` (every property when
/// `names` is empty); an unknown name is returned as the error.
///
/// ```
/// use zipmesh::campaign::{builtin, select};
/// let all = builtin();
/// assert_eq!(select(&all, &["euler".into()]).unwrap()[0].name(), "euler");
/// assert_eq!(select(&all, &["nope".into()]).unwrap_err(), "nope");
/// assert_eq!(select(&all, &[]).unwrap().len(), all.len());
/// // The quad-dominant properties' earlier names still select them.
/// let old = select(&all, &["qzip-hybrid-grid".into(), "tri-walk".into()]).unwrap();
/// assert_eq!((old[0].name(), old[1].name()), ("qzip-quad-dominant-grid", "qd-walk"));
/// ```
pub fn select(all: &[Property], names: &[String]) -> Result<Vec<Property>, String> {
    if names.is_empty() {
        return Ok(all.to_vec());
    }
    names
        .iter()
        .map(|n| {
            // Counterexamples found outside carry the earlier names in their file names.
            let current = match n.strip_prefix("qzip-hybrid-") {
                Some(rest) => Some(alloc::format!("qzip-quad-dominant-{rest}")),
                None => (n == "tri-walk").then(|| "qd-walk".into()),
            };
            let wanted = current.as_deref().unwrap_or(n);
            all.iter()
                .find(|p| p.name() == wanted)
                .cloned()
                .ok_or_else(|| n.clone())
        })
        .collect()
}

/// Runs `properties` over `config.cases` generated cases ([`Case::generate`]) of the
/// configured shard.
///
/// ```
/// use zipmesh::campaign::{self, Config, Shard};
/// let c = Config { cases: 6, max_faces: 120, shard: Shard { index: 1, count: 3 }, ..Config::default() };
/// let r = campaign::run(&c, &campaign::kernel());
/// assert_eq!(r.planned, 2); // cases 1 and 4
/// assert!(r.passed());
/// ```
pub fn run(config: &Config, properties: &[Property]) -> Report {
    run_with_progress(config, properties, &|| {})
}

/// [`run`], calling `progress` after each case (from any worker thread).
///
/// ```
/// use std::sync::atomic::{AtomicU64, Ordering};
/// use zipmesh::campaign::{self, Config};
/// let done = AtomicU64::new(0);
/// let c = Config { cases: 5, max_faces: 100, ..Config::default() };
/// campaign::run_with_progress(&c, &campaign::kernel(), &|| { done.fetch_add(1, Ordering::Relaxed); });
/// assert_eq!(done.load(Ordering::Relaxed), 5);
/// ```
pub fn run_with_progress(
    config: &Config,
    properties: &[Property],
    progress: &(dyn Fn() + Sync),
) -> Report {
    let (seed, max) = (config.seed, config.max_faces);
    execute(
        config,
        campaign_of(config, config.cases, Vec::new()),
        &|i| Some(Cow::Owned(Case::generate(seed, i, max))),
        properties,
        progress,
        &|case, property| {
            format!(
                "zipmesh check --seed {seed} --max-faces {max} --case {} --property {property}{}",
                case.index,
                focus_flag(case)
            )
        },
    )
}

/// Runs `properties` over the given cases (for example meshes read from files); the shard
/// selects by position in `cases`. `config.cases` is not used; `config.max_faces` only
/// appears in the replay command of a generated case.
///
/// ```
/// use zipmesh::campaign::{self, Case, Config};
/// use zipmesh::gen;
/// let cases = vec![Case::from_mesh(gen::cube(2), 0, 0, "cube"), Case::from_mesh(gen::grid(3, 3), 0, 0, "grid")];
/// let r = campaign::run_cases(&Config::default(), &cases, &campaign::builtin(), &|| {});
/// assert!(r.passed());
/// assert_eq!(r.planned, 2);
/// ```
pub fn run_cases(
    config: &Config,
    cases: &[Case],
    properties: &[Property],
    progress: &(dyn Fn() + Sync),
) -> Report {
    let inputs = cases
        .iter()
        .map(|c| match &c.origin {
            Origin::Given(label) => format!("{label}{}", focus_flag(c)),
            Origin::Generated { .. } => format!("generated case {}{}", c.index, focus_flag(c)),
        })
        .collect();
    execute(
        config,
        campaign_of(config, cases.len() as u64, inputs),
        &|i| cases.get(i as usize).map(Cow::Borrowed),
        properties,
        progress,
        &|case, property| {
            let (seed, max) = (case.seed, config.max_faces);
            let focus = focus_flag(case);
            match &case.origin {
                Origin::Given(label) => {
                    format!("zipmesh check {label} --seed {seed} --property {property}{focus}")
                }
                Origin::Generated { .. } => format!(
                    "zipmesh check --seed {seed} --max-faces {max} --case {} --property {property}{focus}",
                    case.index
                ),
            }
        },
    )
}

/// ` --focus V` when the case has a focus, else nothing.
fn focus_flag(case: &Case) -> String {
    case.focus
        .map(|v| format!(" --focus {}", v.index()))
        .unwrap_or_default()
}

/// Checks a property, turning a panic in it into a failure (user properties may panic).
pub(crate) fn guarded(property: &Property, case: &Case) -> Outcome {
    match catch_unwind(AssertUnwindSafe(|| property.check(case))) {
        Ok(o) => o,
        Err(e) => {
            let text = e
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| e.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic".to_string());
            Outcome::fail(format!("panicked: {text}"), None)
        }
    }
}

type MakeCase<'a> = dyn Fn(u64) -> Option<Cow<'a, Case>> + Sync + 'a;
type Replay<'r> = dyn Fn(&Case, &str) -> String + Sync + 'r;

/// Per property: the outcome, the time it took, whether the time limit cut it short and
/// what it left unchecked.
type CaseResult = Vec<(Outcome, Duration, budget::Notes)>;

/// The rows and first failures, merged case by case as workers finish them, so memory
/// does not grow with the number of cases.
struct Tally {
    rows: Vec<Row>,
    first_failure: Vec<Option<(u64, Outcome)>>,
    ran: u64,
}

impl Tally {
    fn new(properties: &[Property]) -> Tally {
        Tally {
            rows: properties.iter().map(|p| Row::zero(p.name())).collect(),
            first_failure: vec![None; properties.len()],
            ran: 0,
        }
    }

    /// Adds case `p`'s results; the first failure is the one of the smallest position,
    /// whatever order the workers finish in.
    fn add(&mut self, p: u64, result: CaseResult) {
        self.ran += 1;
        for (k, (outcome, time, notes)) in result.into_iter().enumerate() {
            let row = &mut self.rows[k];
            row.time += time;
            row.cut += u64::from(notes.cut);
            row.unchecked = row.unchecked.saturating_add(notes.unchecked);
            row.searched = row.searched.saturating_add(notes.searched);
            match outcome {
                Outcome::Pass { checks } => {
                    row.cases += 1;
                    row.passed += 1;
                    row.checks += checks;
                }
                Outcome::Skip => row.skipped += 1,
                Outcome::Fail { .. } => {
                    row.cases += 1;
                    row.failed += 1;
                    if self.first_failure[k].as_ref().is_none_or(|(q, _)| p < *q) {
                        self.first_failure[k] = Some((p, outcome));
                    }
                }
            }
        }
    }
}

/// Checks every property on one case, each under the deadline; a property the deadline
/// finds not yet started does not start (it counts as cut short with no check): on a
/// large case one property's set-up alone can take seconds.
fn check_case(
    case: &Case,
    properties: &[Property],
    config: &Config,
    deadline: Option<Instant>,
) -> CaseResult {
    properties
        .iter()
        .map(|prop| {
            let start = Instant::now();
            if deadline.is_some_and(|d| start >= d) {
                let cut = budget::Notes {
                    cut: true,
                    ..budget::Notes::default()
                };
                return (Outcome::Pass { checks: 0 }, start.elapsed(), cut);
            }
            let (outcome, notes) = budget::within(deadline, &config.checks, || guarded(prop, case));
            (outcome, start.elapsed(), notes)
        })
        .collect()
}

/// Runs the `planned` cases of the shard on `config.jobs` threads (default: rayon's
/// number), each taking the next position when it is free: nothing is sized by the number
/// of cases, and no case starts after the deadline.
fn run_positions(
    config: &Config,
    planned: u64,
    make: &MakeCase<'_>,
    properties: &[Property],
    progress: &(dyn Fn() + Sync),
    deadline: Option<Instant>,
) -> Tally {
    let next = AtomicU64::new(0);
    let tally = Mutex::new(Tally::new(properties));
    let worker = || loop {
        if deadline.is_some_and(|d| Instant::now() >= d) {
            break;
        }
        let k = next.fetch_add(1, Ordering::Relaxed);
        if k >= planned {
            break;
        }
        let p = config.shard.index + k * config.shard.count;
        let Some(case) = make(p) else { continue };
        let result = check_case(&case, properties, config, deadline);
        tally
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .add(p, result);
        progress();
    };
    let jobs = config
        .jobs
        .unwrap_or_else(rayon::current_num_threads)
        .clamp(1, 4096);
    let jobs = jobs
        .min(usize::try_from(planned).unwrap_or(usize::MAX))
        .max(1);
    std::thread::scope(|s| {
        for _ in 1..jobs {
            s.spawn(worker);
        }
        worker();
    });
    tally.into_inner().unwrap_or_else(|e| e.into_inner())
}

/// What a run identifies its campaign by: the shard's settings and, for given cases, their
/// labels.
fn campaign_of(config: &Config, count: u64, inputs: Vec<String>) -> Campaign {
    Campaign {
        cases: count,
        max_faces: config.max_faces,
        inputs,
        settings: config.settings.clone(),
    }
}

fn execute<'a>(
    config: &Config,
    campaign: Campaign,
    make: &MakeCase<'a>,
    properties: &[Property],
    progress: &(dyn Fn() + Sync),
    replay: &Replay<'_>,
) -> Report {
    let started = Instant::now();
    let planned = config.shard.size_of(campaign.cases);
    let deadline = config.time_limit.map(|t| started + t);
    let tally = run_positions(config, planned, make, properties, progress, deadline);
    let mut failures = Vec::new();
    for (k, first) in tally.first_failure.into_iter().enumerate() {
        let Some((p, outcome)) = first else { continue };
        let Some(case) = make(p) else { continue };
        failures.push(failure(config, &properties[k], &case, p, outcome, replay));
    }
    let cut = tally.rows.iter().any(|r| r.cut > 0);
    let mut report = Report {
        seed: config.seed,
        shard: config.shard,
        planned,
        run: tally.ran,
        timed_out: tally.ran < planned || cut,
        elapsed: Duration::ZERO,
        rows: tally.rows,
        failures,
        campaign,
    };
    if let Some(dir) = &config.out_dir {
        report.write_counterexamples(dir);
    }
    report.elapsed = started.elapsed();
    report
}

/// A property's first failure (at `position`): shrunk, with its replay command on the
/// original case (the counterexample is written by [`Report::write_counterexamples`]).
fn failure(
    config: &Config,
    property: &Property,
    case: &Case,
    position: u64,
    outcome: Outcome,
    replay: &Replay<'_>,
) -> Failure {
    let message = match &outcome {
        Outcome::Fail { message, .. } => message.clone(),
        _ => String::new(),
    };
    let shrunk = if config.shrink {
        shrink(property, case, outcome)
    } else {
        None
    };
    let case_replay = replay(case, property.name()) + &report::setting_flags(&config.settings);
    Failure {
        property: property.name().to_string(),
        case: case.index,
        position,
        description: case.describe(),
        message,
        original_faces: case.mesh.map.num_faces(),
        shrunk,
        path: None,
        replay: case_replay.clone(),
        case_replay,
    }
}

/// The examples of `docs/campaign.md`, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../docs/campaign.md")]
struct CampaignDocDoctests;

/// The vertices within `radius` edges of `s` (breadth-first, `s` left out) that `keep`
/// accepts, nearest first: where the campaigns draw a partner for `s`.
fn near(
    map: &crate::Map,
    s: crate::Vert,
    radius: usize,
    keep: impl Fn(crate::Vert) -> bool,
) -> Vec<crate::Vert> {
    let mut seen = std::collections::BTreeSet::from([s]);
    let (mut ring, mut found) = (std::vec![s], Vec::new());
    for _ in 0..radius {
        let mut next = Vec::new();
        for &v in &ring {
            for d in map.vertex_darts(v) {
                let w = map.dest(d);
                if seen.insert(w) {
                    next.push(w);
                    if keep(w) {
                        found.push(w);
                    }
                }
            }
        }
        if next.is_empty() {
            break;
        }
        ring = next;
    }
    found
}
