//! `zipmesh check`: property campaigns on generated cases or on given mesh files, and
//! `--merge` of the JSON reports of a campaign's shards (run on other machines).
//!
//! Exit codes: 0 every property held on every planned case, 1 a property failed, 2 a usage
//! or input error (with `--merge`: reports that are not the shards of one campaign), 3 every
//! property held on what ran but the time limit cut the campaign (cases not run, or
//! properties cut short inside a case).

mod report_json;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;
use zipmesh::campaign::{self, Case, Config, Property, Report, Shard};
use zipmesh::{io, Vert};

use crate::out::{self, outln};

/// Arguments of `zipmesh check`.
#[derive(Args)]
pub struct CheckArgs {
    /// Mesh files (.obj, .off) to check; without them, generated cases. With `--merge`: the
    /// shard reports (JSON) to merge.
    files: Vec<PathBuf>,
    /// The campaign seed: the same seed and arguments give the same cases and table.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// How many generated cases (before sharding).
    #[arg(long, default_value_t = Config::default().cases)]
    cases: u64,
    /// The face budget of a generated case.
    #[arg(long, default_value_t = Config::default().max_faces)]
    max_faces: usize,
    /// Check only this property (repeatable); `--list` prints the names.
    #[arg(long = "property", value_name = "NAME")]
    properties: Vec<String>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=4096))]
    jobs: Option<u64>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    json: bool,
    /// Run only the cases whose position p has p % n == i (0-based: shards 0/n to n-1/n).
    #[arg(long, value_name = "i/n")]
    shard: Option<Shard>,
    /// Merge the FILEs, the `--json` reports of every shard of one campaign, into the table
    /// (or with --json the JSON) and exit status of one unsharded run; counterexamples are
    /// written again into --out.
    #[arg(long, conflicts_with_all = [
        "seed", "cases", "max_faces", "properties", "jobs", "shard", "time_limit",
        "max_distance", "pairs", "case", "focus", "list",
    ])]
    merge: bool,
    /// Stop after this many seconds: no new case starts and properties stop between their
    /// checks; exit 3 if everything that ran held.
    #[arg(long, value_name = "SECONDS")]
    time_limit: Option<f64>,
    /// Q-zip pairs: the largest distance (in edges) between two irregular vertices to pair;
    /// on given files every such ordered pair is tried with every movement.
    #[arg(long, default_value_t = DEFAULT_MAX_DISTANCE)]
    max_distance: usize,
    /// Q-zip pairs on given files: draw N ordered pairs within --max-distance from the
    /// seed's random stream, instead of every pair; the report names the sample (seed and N).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    pairs: Option<u64>,
    /// Run only generated case number INDEX (what a replay line uses).
    #[arg(long, value_name = "INDEX")]
    case: Option<u64>,
    /// Try edits at this vertex first (what a replay line on a counterexample uses).
    #[arg(long, value_name = "VERTEX")]
    focus: Option<u32>,
    /// Directory for shrunk counterexamples (OBJ).
    #[arg(long, default_value = ".")]
    out: PathBuf,
    /// Print the property names and what each asserts, then exit.
    #[arg(long)]
    list: bool,
}

/// Runs `zipmesh check`.
pub fn run(args: CheckArgs) -> ExitCode {
    match run_inner(args) {
        Ok(code) => code,
        Err(message) => {
            out::error_line(format_args!("zipmesh check: {message}"));
            ExitCode::from(2)
        }
    }
}

/// Refuses, before the campaign runs, a `--out` that cannot be a directory: a file, or a
/// path under one. A missing directory is no error: it is made when a shrunk counterexample
/// is written (as for the shards of a campaign, each with its own new folder).
fn check_out_dir(dir: &Path) -> Result<(), String> {
    let is_file = |a: &&Path| std::fs::metadata(a).is_ok_and(|m| !m.is_dir());
    match dir.ancestors().find(is_file) {
        None => Ok(()),
        Some(file) => Err(format!(
            "--out {}: {} is not a directory (shrunk counterexamples are written there)",
            dir.display(),
            file.display()
        )),
    }
}

/// `--max-distance` when not given; other values are recorded in the report's settings and
/// passed on in replay lines.
const DEFAULT_MAX_DISTANCE: usize = 12;

fn run_inner(args: CheckArgs) -> Result<ExitCode, String> {
    if !args.list {
        check_out_dir(&args.out)?;
    }
    if args.merge {
        return merge_reports(&args);
    }
    let all = properties(&args);
    if args.list {
        for p in &all {
            outln!("{:<24} {}", p.name(), p.about());
        }
        return Ok(ExitCode::SUCCESS);
    }
    let properties = campaign::select(&all, &args.properties).map_err(|unknown| {
        let names: Vec<&str> = all.iter().map(|p| p.name()).collect();
        format!(
            "unknown property {unknown:?}; valid names: {}",
            names.join(", ")
        )
    })?;
    let time_limit = match args.time_limit {
        Some(t) if t.is_finite() && t >= 0.0 => Some(Duration::from_secs_f64(t.min(1e9))),
        Some(t) => {
            return Err(format!(
                "--time-limit must be a number of seconds >= 0, got {t}"
            ))
        }
        None => None,
    };
    if args.case.is_some() && !args.files.is_empty() {
        return Err("--case selects a generated case; it cannot be used with files".into());
    }
    if args.pairs.is_some() && args.files.is_empty() {
        return Err("--pairs samples the pairs of given files; generated cases draw 4 each".into());
    }
    let config = Config {
        seed: args.seed,
        cases: args.cases,
        max_faces: args.max_faces,
        shard: args.shard.unwrap_or(Shard::ALL),
        jobs: args.jobs.map(|j| j as usize),
        time_limit,
        checks: campaign::CheckCounter::default(),
        shrink: true,
        out_dir: Some(args.out.clone()),
        settings: settings(&args),
    };
    let focus = args.focus.map(Vert::new);
    let given: Option<Vec<Case>> = if !args.files.is_empty() {
        let mut cases = Vec::with_capacity(args.files.len());
        for path in &args.files {
            let (mesh, _) = io::read_mesh(path).map_err(|e| e.to_string())?;
            let mut case = Case::from_mesh(mesh, args.seed, 0, path.display().to_string());
            case.focus = focus;
            cases.push(case);
        }
        Some(cases)
    } else {
        args.case.map(|i| {
            let mut case = Case::generate(args.seed, i, args.max_faces);
            case.focus = focus;
            vec![case]
        })
    };
    let planned = config.shard.size_of(match &given {
        Some(cases) => cases.len() as u64,
        None => config.cases,
    });
    let report = run_campaign(&config, given.as_deref(), &properties, planned, !args.json);
    Ok(print_report(&report, args.json))
}

/// The settings the properties depend on besides the cases: `--max-distance` when it is not
/// the default (so default campaigns keep short replay lines), and `--pairs`.
fn settings(args: &CheckArgs) -> BTreeMap<String, String> {
    let mut settings = BTreeMap::new();
    if args.max_distance != DEFAULT_MAX_DISTANCE {
        settings.insert("max-distance".into(), args.max_distance.to_string());
    }
    if let Some(n) = args.pairs {
        settings.insert("pairs".into(), n.to_string());
    }
    settings
}

/// Prints the report as the table or as JSON; the exit status of the campaign.
fn print_report(report: &Report, json: bool) -> ExitCode {
    if json {
        outln!("{}", report.to_json(true));
    } else {
        print_text(report);
    }
    ExitCode::from(match (report.passed(), report.timed_out) {
        (false, _) => 1,
        (true, true) => CUT_BY_TIME_LIMIT,
        (true, false) => 0,
    })
}

/// `--merge`: reads the shard reports, merges them (refusing reports of different campaigns
/// and missing or duplicate shards), writes the counterexamples into `--out` and prints what
/// one unsharded run would.
fn merge_reports(args: &CheckArgs) -> Result<ExitCode, String> {
    if args.files.is_empty() {
        return Err(
            "--merge needs the shard reports (the JSON of check --shard i/n --json)".into(),
        );
    }
    let names: Vec<String> = args
        .files
        .iter()
        .map(|p| out::escape(&p.display().to_string()))
        .collect();
    let mut parts = Vec::with_capacity(args.files.len());
    for (path, name) in args.files.iter().zip(&names) {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: {e}"))?;
        let report = report_json::parse(&text)
            .map_err(|e| format!("{name}: not a report of check --json: {e}"))?;
        parts.push(report);
    }
    let mut report = campaign::merge(&parts).map_err(|e| e.describe(&names))?;
    report.write_counterexamples(&args.out);
    Ok(print_report(&report, args.json))
}

/// Runs the campaign, with a progress bar on a terminal (when `bar` is wanted) that moves
/// with the cases and, during a long case, with the checks.
fn run_campaign(
    config: &Config,
    given: Option<&[Case]>,
    properties: &[Property],
    planned: u64,
    bar: bool,
) -> Report {
    let bar = (bar && std::io::stderr().is_terminal() && !out::capturing())
        .then(|| progress_bar(planned));
    let tick = || {
        if let Some(b) = &bar {
            b.inc(1);
        }
    };
    let done = std::sync::atomic::AtomicBool::new(false);
    let report = std::thread::scope(|s| {
        if let Some(b) = &bar {
            s.spawn(|| show_checks(b, &config.checks, &done));
        }
        let report = match given {
            Some(cases) => campaign::run_cases(config, cases, properties, &tick),
            None => campaign::run_with_progress(config, properties, &tick),
        };
        done.store(true, std::sync::atomic::Ordering::Relaxed);
        report
    });
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    report
}

/// The exit status when every property held on what ran but the time limit cut the run.
pub const CUT_BY_TIME_LIMIT: u8 = 3;

fn progress_bar(planned: u64) -> ProgressBar {
    let bar = ProgressBar::new(planned);
    let template = "{bar:40} {pos}/{len} cases, {msg} checks, {elapsed} (eta {eta})";
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style);
    }
    bar
}

/// Moves the bar during a long case: the checks polled so far, five times a second.
fn show_checks(
    bar: &ProgressBar,
    checks: &campaign::CheckCounter,
    done: &std::sync::atomic::AtomicBool,
) {
    while !done.load(std::sync::atomic::Ordering::Relaxed) {
        bar.set_message(checks.get().to_string());
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// Every property `check` knows. On given meshes the Q-zip properties try every ordered
/// pair of singularities within `--max-distance` (generated cases draw a few pairs each).
fn properties(args: &CheckArgs) -> Vec<Property> {
    let per_case = if args.files.is_empty() {
        Some(4)
    } else {
        args.pairs.map(|n| n as usize)
    };
    campaign::builtin_with(campaign::PairChoice {
        max_distance: args.max_distance,
        per_case,
    })
}

fn print_text(report: &Report) {
    out::push(format_args!("{}", report.table(true)));
    let scope = if report.shard == Shard::ALL {
        String::new()
    } else {
        format!(" (shard {})", report.shard)
    };
    outln!(
        "{} of {} cases run{scope}, seed {}, {:.2} s",
        report.run,
        report.planned,
        report.seed,
        report.elapsed.as_secs_f64()
    );
    if let Some(n) = report.campaign.settings.get("pairs") {
        outln!(
            "Q-zip pairs: a sample of {n} per file, drawn by seed {} (the same seed, the same sample)",
            report.seed
        );
    }
    if report.timed_out {
        outln!(
            "time limit reached: {} cases not run",
            report.planned - report.run
        );
        for r in report.rows.iter().filter(|r| r.cut > 0) {
            outln!(
                "  {} cut short on {} cases ({} checks ran in all)",
                r.property,
                r.cut,
                r.checks
            );
        }
    }
    for r in report.rows.iter().filter(|r| r.unchecked > 0) {
        outln!(
            "{} left {} unchecked (not failures: {})",
            r.property,
            r.unchecked,
            unchecked_meaning(&r.property)
        );
    }
    for r in report.rows.iter().filter(|r| r.searched > 0) {
        outln!(
            "{}: {} of its {} checks found by the fallback search ({})",
            r.property,
            r.searched,
            r.checks,
            searched_meaning(&r.property)
        );
    }
    for f in &report.failures {
        outln!();
        outln!(
            "FAILED {} on case {}: {}",
            f.property,
            f.case,
            f.description
        );
        outln!("  {}", f.message);
        match (&f.shrunk, &f.path) {
            (Some(s), Some(path)) => outln!(
                "  counterexample: {} ({} faces, shrunk from {}): {}",
                path.display(),
                s.mesh.map.num_faces(),
                f.original_faces,
                s.message
            ),
            (Some(_), None) => outln!("  (the shrunk counterexample could not be written)"),
            _ => outln!("  (no smaller failing mesh found)"),
        }
        outln!("  replay: {}", f.replay);
    }
    match (report.passed(), report.timed_out) {
        (true, false) => outln!("all properties hold"),
        (true, true) => outln!("all properties hold on what ran (cut by the time limit)"),
        (false, _) => {}
    }
}

/// What a property's `searched` count means (docs/qzip.md).
fn searched_meaning(property: &str) -> &'static str {
    if property.ends_with("reversal") {
        "reverse runs not derived from the report"
    } else {
        "checks that needed a search"
    }
}

/// What a property's `unchecked` column counts (docs/campaign.md, docs/qzip.md).
fn unchecked_meaning(property: &str) -> &'static str {
    if property.ends_with("reversal") {
        "movements with no reverse run found"
    } else if property.ends_with("homotopy") {
        "swept paths next to a triangle, not compared"
    } else {
        "checks the property could not make"
    }
}

#[cfg(test)]
mod tests {
    use super::unchecked_meaning;

    /// Each kind of unchecked count is named for what it is, not for the reversal's.
    #[test]
    fn unchecked_counts_say_what_they_count() {
        let rev = unchecked_meaning("qzip-quad-dominant-reversal");
        assert_eq!(rev, unchecked_meaning("qzip-reversal"));
        assert!(rev.contains("reverse"));
        let hom = unchecked_meaning("qzip-quad-dominant-homotopy");
        assert!(hom.contains("triangle") && hom != rev);
        assert_ne!(unchecked_meaning("validity"), rev);
    }
}
