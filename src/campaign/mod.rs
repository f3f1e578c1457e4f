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

use core::fmt;
use core::str::FromStr;
use core::time::Duration;
use rayon::prelude::*;
use std::borrow::Cow;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::string::{String, ToString};
use std::time::Instant;
use std::vec::Vec;
use std::{format, vec};

mod case;
mod property;
mod qzip;
mod report;
mod shrink;

pub use case::{Case, Kind, Origin};
pub use property::{builtin, kernel, operators, undo_property, CheckFn, Outcome, Property};
pub use qzip::{qzip_properties, PairChoice};
pub use report::{Failure, Report, Row};
pub use shrink::{shrink, Shrunk, SHRINK_BUDGET};

/// A deterministic slice of the cases: those whose position `p` has `p % count == index`.
/// Written `index/count`; `0/1` is every case.
///
/// ```
/// use zipmesh::campaign::Shard;
/// let s: Shard = "1/3".parse().unwrap();
/// assert!(s.contains(4) && !s.contains(5));
/// assert_eq!(s.to_string(), "1/3");
/// assert!("3/3".parse::<Shard>().is_err() && "x".parse::<Shard>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shard {
    /// Which slice, `0..count`.
    pub index: u64,
    /// How many slices.
    pub count: u64,
}

impl Shard {
    /// Every case: `0/1`.
    ///
    /// ```
    /// assert!(zipmesh::campaign::Shard::ALL.contains(17));
    /// ```
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Whether the case at `position` is in this shard.
    ///
    /// ```
    /// let s = zipmesh::campaign::Shard { index: 0, count: 2 };
    /// assert!(s.contains(0) && !s.contains(1));
    /// ```
    pub fn contains(&self, position: u64) -> bool {
        self.count > 0 && position % self.count == self.index
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Why a shard could not be parsed.
///
/// ```
/// let e = "2/2".parse::<zipmesh::campaign::Shard>().unwrap_err();
/// assert!(e.to_string().contains("below"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShardError(String);

impl fmt::Display for ShardError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ShardError {}

impl FromStr for Shard {
    type Err = ShardError;

    fn from_str(s: &str) -> Result<Shard, ShardError> {
        let bad = || ShardError(format!("expected i/n with i below n, got {s:?}"));
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: u64 = i.trim().parse().map_err(|_| bad())?;
        let count: u64 = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

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
    /// Stop starting new cases after this long (the report then says `timed_out`, and which
    /// cases ran depends on timing).
    pub time_limit: Option<Duration>,
    /// Shrink the first failure of each property.
    pub shrink: bool,
    /// Where to write shrunk counterexamples as OBJ files (`None`: not written).
    pub out_dir: Option<PathBuf>,
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
            shrink: true,
            out_dir: None,
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
/// ```
pub fn select(all: &[Property], names: &[String]) -> Result<Vec<Property>, String> {
    if names.is_empty() {
        return Ok(all.to_vec());
    }
    names
        .iter()
        .map(|n| {
            all.iter()
                .find(|p| p.name() == n)
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
        config.cases,
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
    execute(
        config,
        cases.len() as u64,
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

/// Per case: per property, the outcome and the time it took.
type CaseResult = Vec<(Outcome, Duration)>;

fn execute<'a>(
    config: &Config,
    count: u64,
    make: &MakeCase<'a>,
    properties: &[Property],
    progress: &(dyn Fn() + Sync),
    replay: &Replay<'_>,
) -> Report {
    let started = Instant::now();
    let positions: Vec<u64> = (0..count).filter(|&p| config.shard.contains(p)).collect();
    let deadline = config.time_limit.map(|t| Instant::now() + t);
    let one = |p: u64| -> Option<CaseResult> {
        if deadline.is_some_and(|d| Instant::now() >= d) {
            return None;
        }
        let case = make(p)?;
        let results = properties
            .iter()
            .map(|prop| {
                let start = Instant::now();
                let outcome = guarded(prop, &case);
                (outcome, start.elapsed())
            })
            .collect();
        progress();
        Some(results)
    };
    let run_all = || -> Vec<Option<CaseResult>> { positions.par_iter().map(|&p| one(p)).collect() };
    let results = match config.jobs {
        Some(j) => match rayon::ThreadPoolBuilder::new()
            .num_threads(j.max(1))
            .build()
        {
            Ok(pool) => pool.install(run_all),
            Err(_) => positions.iter().map(|&p| one(p)).collect(),
        },
        None => run_all(),
    };

    let mut rows: Vec<Row> = properties
        .iter()
        .map(|p| Row {
            property: p.name().to_string(),
            cases: 0,
            passed: 0,
            failed: 0,
            skipped: 0,
            checks: 0,
            time: Duration::ZERO,
        })
        .collect();
    let mut first_failure: Vec<Option<(u64, Outcome)>> = vec![None; properties.len()];
    let mut ran = 0;
    for (&p, result) in positions.iter().zip(&results) {
        let Some(result) = result else { continue };
        ran += 1;
        for (k, (outcome, time)) in result.iter().enumerate() {
            let row = &mut rows[k];
            row.time += *time;
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
                    if first_failure[k].is_none() {
                        first_failure[k] = Some((p, outcome.clone()));
                    }
                }
            }
        }
    }

    let mut failures = Vec::new();
    for (k, first) in first_failure.into_iter().enumerate() {
        let Some((p, outcome)) = first else { continue };
        let Some(case) = make(p) else { continue };
        let property = &properties[k];
        let message = match &outcome {
            Outcome::Fail { message, .. } => message.clone(),
            _ => String::new(),
        };
        let shrunk = if config.shrink {
            shrink(property, &case, outcome)
        } else {
            None
        };
        let path = match (&shrunk, &config.out_dir) {
            (Some(s), Some(dir)) => write_counterexample(dir, property.name(), &case, s),
            _ => None,
        };
        let replay = match (&shrunk, &path) {
            (Some(s), Some(path)) => {
                let focus = s
                    .focus
                    .map(|v| format!(" --focus {}", v.index()))
                    .unwrap_or_default();
                format!(
                    "zipmesh check {} --seed {} --property {}{focus}",
                    path.display(),
                    case.seed,
                    property.name()
                )
            }
            _ => replay(&case, property.name()),
        };
        failures.push(Failure {
            property: property.name().to_string(),
            case: case.index,
            description: case.describe(),
            message,
            original_faces: case.mesh.map.num_faces(),
            shrunk,
            path,
            replay,
        });
    }

    Report {
        seed: config.seed,
        shard: config.shard,
        planned: positions.len() as u64,
        run: ran,
        timed_out: ran < positions.len() as u64,
        elapsed: started.elapsed(),
        rows,
        failures,
    }
}

/// Writes the counterexample as `<dir>/<property>-seed<S>-case<I>.obj` (atomically);
/// `None` if that fails.
fn write_counterexample(dir: &PathBuf, property: &str, case: &Case, s: &Shrunk) -> Option<PathBuf> {
    std::fs::create_dir_all(dir).ok()?;
    let safe: String = property
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let path = dir.join(format!("{safe}-seed{}-case{}.obj", case.seed, case.index));
    crate::io::write_mesh(&path, &s.mesh).ok()?;
    Some(path)
}

/// The examples of `docs/campaign.md`, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../docs/campaign.md")]
struct CampaignDocDoctests;
