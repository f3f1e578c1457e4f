//! `zipmesh optimize`: batches of Q-zips that reduce the singularities of a quad mesh (on
//! quad-dominant input after merging pairs of triangles).

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::{json, Value};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};
use zipmesh::io;
use zipmesh::optimize::{
    optimize, optimize_triangles, BatchReport, Constraints, OptimizeOptions, SingularityCounts,
    TriCounts, TriOptimizeOptions,
};
use zipmesh::quality::{Bound, Bounds, Reference, Summary};
use zipmesh::{Face, Mesh, Vert};

use crate::out::{self, outln};
use crate::quality;
use crate::qzip::InputError;

#[derive(Args)]
pub struct OptimizeArgs {
    /// The input mesh (.obj, .off or .ply): quad, quad-dominant (triangles and quads) or all triangles.
    file: PathBuf,
    /// Where to write the result.
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// The most batches to run. Quad meshes: no limit by default, the run goes on while
    /// batches execute Q-zips; triangle meshes: 50 by default.
    #[arg(long)]
    batches: Option<usize>,
    /// Stop after this many seconds (quad meshes), checked between the candidates of a
    /// batch: OUT is the mesh as the last executed Q-zip left it, settled on the surface.
    #[arg(long, value_parser = seconds)]
    time_limit: Option<Duration>,
    /// The seed of the sampling (the same seed gives the same OUT).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
    /// As each batch ends, print its row (the object the report's `batches` holds, with
    /// its `batch` number) as one JSON line on standard output, before the report: for
    /// tools that follow a long run.
    #[arg(long)]
    progress_json: bool,
    /// A file of 0-based face indices, one per line: faces kept bit for bit.
    #[arg(long)]
    protect: Option<PathBuf>,
    /// A file of `a b` 0-based vertex-index lines: feature edges kept.
    #[arg(long)]
    features: Option<PathBuf>,
    /// Edges whose faces meet at this dihedral angle (degrees) or more are features.
    #[arg(long)]
    sharp_angle: Option<f64>,
    /// No smoothing after the batches.
    #[arg(long)]
    no_smooth: bool,
    /// No chains of Q-zips walking v3/v5 pairs together, or singularities onto opposite
    /// ones, after an idle batch (quad meshes).
    #[arg(long)]
    no_chains: bool,
    /// Keep no Q-zip, chain or smoothing that adds a folded quad (quad meshes; the
    /// default, kept for compatibility).
    #[arg(long, conflicts_with = "no_fold_guard")]
    fold_guard: bool,
    /// Let Q-zips, chains and smoothing fold quads (quad meshes; more singularities go,
    /// the geometry suffers).
    #[arg(long)]
    no_fold_guard: bool,
    /// No look-ahead (pairs of edits round each irregular vertex) when the greedy passes stall
    /// (triangle meshes).
    #[arg(long)]
    no_lookahead: bool,
    /// With --json: each batch's executed surgery paths (vertex positions).
    #[arg(long)]
    paths: bool,
    /// A score term's weight, `NAME=W` (count, electric, isotropy, sizing, separatrix, faces); 0
    /// switches it off. Repeatable.
    #[arg(long = "weight", value_parser = parse_weight)]
    weights: Vec<(String, f64)>,
}

fn parse_weight(s: &str) -> Result<(String, f64), String> {
    // The names come from the library's default terms, so a new term needs no edit here.
    let defaults = zipmesh::optimize::OptimizeOptions::default();
    let names: Vec<&str> = defaults.terms().iter().map(|(_, t)| t.name()).collect();
    let (name, w) = s.split_once('=').ok_or("expected NAME=W")?;
    if !names.contains(&name) {
        return Err(format!(
            "unknown term {name} (expected one of {})",
            names.join(", ")
        ));
    }
    match w.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok((name.to_string(), x)),
        _ => Err(format!("{w}: expected a finite non-negative weight")),
    }
}

fn tri_counts(c: &TriCounts) -> Value {
    json!({
        "faces": c.faces, "vertices": c.vertices, "v3": c.v3, "v4": c.v4, "v5": c.v5,
        "v7": c.v7, "v8plus": c.v8plus, "irregular": c.irregular(),
    })
}

fn tri_summary(c: &TriCounts) -> String {
    format!(
        "v3 {} v4 {} v5 {} v7 {} v8+ {} ({} irregular, {} faces)",
        c.v3,
        c.v4,
        c.v5,
        c.v7,
        c.v8plus,
        c.irregular(),
        c.faces
    )
}

/// A pure triangle mesh: flips, triple cancellations, pair moves and the look-ahead
/// (`optimize_triangles`).
/// The quad-only options (constraints, weights, paths) are refused rather than ignored.
fn run_triangles(args: &OptimizeArgs, mut mesh: Mesh, name: &str) -> Result<ExitCode, InputError> {
    let input = mesh.clone();
    let quad_only = [
        ("--protect", args.protect.is_some()),
        ("--features", args.features.is_some()),
        ("--sharp-angle", args.sharp_angle.is_some()),
        ("--paths", args.paths),
        ("--weight", !args.weights.is_empty()),
        ("--no-chains", args.no_chains),
        ("--fold-guard", args.fold_guard),
        ("--no-fold-guard", args.no_fold_guard),
        ("--time-limit", args.time_limit.is_some()),
    ];
    if let Some((flag, _)) = quad_only.iter().find(|(_, set)| *set) {
        return Err(InputError(format!(
            "{name}: {flag} applies to quad meshes only (this one is all triangles)"
        )));
    }
    let defaults = TriOptimizeOptions::default();
    let options = TriOptimizeOptions {
        max_batches: args.batches.unwrap_or(defaults.max_batches),
        relax: !args.no_smooth,
        lookahead: !args.no_lookahead,
        ..defaults
    };
    let bar = progress(Some(options.max_batches));
    let start = Instant::now();
    let mut rows = Vec::new();
    let mut stream = Stream::new(args.progress_json);
    let outcome = optimize_triangles(&mut mesh, &options, |b| {
        let mut row = tri_counts(&b.counts);
        if let Value::Object(m) = &mut row {
            m.insert("batch".into(), json!(b.batch));
            m.insert("flips".into(), json!(b.flips));
            m.insert("cancellations".into(), json!(b.cancellations));
            m.insert("lookaheads".into(), json!(b.lookaheads));
            m.insert("pair_moves".into(), json!(b.pair_moves));
            m.insert("far_pair_moves".into(), json!(b.far_pair_moves));
            m.insert("score".into(), json!(b.score));
        }
        rows.push(row);
        stream.send(rows.last());
        if let Some(bar) = &bar {
            bar.set_position(b.batch as u64);
            bar.set_message(tri_summary(&b.counts));
        }
    })
    .map_err(|e| InputError(format!("{name}: {e}")))?;
    stream.result()?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let seconds = start.elapsed().as_secs_f64();
    let mut report = json!({
        "kind": "triangle",
        "input": tri_counts(&outcome.input),
        "batches": rows,
        "final": tri_counts(&outcome.final_counts),
        "restored_batch": outcome.restored,
        "seconds": seconds,
    });
    // A run that went back to an earlier batch says so: its last rows are not the result.
    let restored = outcome.restored.map_or(String::new(), |b| {
        format!(" (batch {b}'s output: a later one broke a geometry bound)")
    });
    let lines = [
        format!("{name}: {}", tri_summary(&outcome.input)),
        format!(
            "{}: {} after {} batches{restored}, {seconds:.2} s",
            out::escape(&args.output.display().to_string()),
            tri_summary(&outcome.final_counts),
            outcome.batches.len()
        ),
    ];
    finish(args, (&input, &mut mesh), &mut report, &lines)
}

/// The ending both paths share: the quality of input and output measured against the
/// input's surface, OUT prepared beside its place, the report printed (`--json`: the object
/// with `quality`, else the two lines and a quality line), and only then OUT moved in, so a
/// failed print leaves no OUT.
fn finish(
    args: &OptimizeArgs,
    (input, mesh): (&Mesh, &mut Mesh),
    report: &mut Value,
    lines: &[String; 2],
) -> Result<ExitCode, InputError> {
    mesh.compact();
    let reference = Reference::new(input);
    let q = [input, &*mesh].map(|m| Summary::against(m, &reference));
    report["quality"] = quality::both_json(&q);
    let failed: Vec<&str> = Bounds::default()
        .failures(&q[0], &q[1])
        .into_iter()
        .map(Bound::name)
        .collect();
    report["bounds"] = json!({"hold": failed.is_empty(), "failed": failed});
    let pending = io::prepare_mesh(&args.output, mesh)?;
    if args.json {
        outln!("{report}");
    } else {
        for line in lines {
            outln!("{line}");
        }
        outln!("quality: {}", quality::line(&q));
        match failed.as_slice() {
            [] => outln!("geometry bounds (docs/results.md): hold"),
            f => outln!(
                "geometry bounds (docs/results.md): broken: {}",
                f.join(", ")
            ),
        }
    }
    out::flush()?;
    pending.commit()?;
    Ok(ExitCode::SUCCESS)
}

fn counts(c: &SingularityCounts) -> serde_json::Map<String, Value> {
    let v = json!({
        "faces": c.faces, "triangles": c.triangles, "vertices": c.vertices, "v2": c.v2, "v3": c.v3, "v5": c.v5,
        "v6plus": c.v6plus, "boundary_defects": c.boundary_defects,
    });
    match v {
        Value::Object(m) => m,
        _ => serde_json::Map::new(),
    }
}

fn bad(file: &Path, line: usize, what: &str) -> InputError {
    InputError(format!(
        "{}: line {line}: {what}",
        out::escape(&file.display().to_string())
    ))
}

fn read_lines(file: &Path) -> Result<Vec<(usize, Vec<u32>)>, InputError> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| InputError(format!("{}: {e}", out::escape(&file.display().to_string()))))?;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let nums: Result<Vec<u32>, _> = line.split_whitespace().map(str::parse).collect();
        rows.push((
            i + 1,
            nums.map_err(|_| bad(file, i + 1, "not a 0-based index"))?,
        ));
    }
    Ok(rows)
}

fn constraints(args: &OptimizeArgs, mesh: &Mesh) -> Result<Constraints, InputError> {
    let mut c = Constraints::default();
    if let Some(file) = &args.protect {
        for (line, nums) in read_lines(file)? {
            let [f] = nums[..] else {
                return Err(bad(file, line, "expected one face index"));
            };
            c.protect_face(mesh, Face::new(f))
                .map_err(|e| bad(file, line, &e.to_string()))?;
        }
    }
    if let Some(file) = &args.features {
        for (line, nums) in read_lines(file)? {
            let [a, b] = nums[..] else {
                return Err(bad(file, line, "expected two vertex indices `a b`"));
            };
            c.add_feature(mesh, Vert::new(a), Vert::new(b))
                .map_err(|e| bad(file, line, &e.to_string()))?;
        }
    }
    if let Some(deg) = args.sharp_angle {
        if !(0.0..=180.0).contains(&deg) {
            return Err(InputError(format!(
                "--sharp-angle {deg}: expected 0 to 180 degrees"
            )));
        }
        c.add_sharp_edges(mesh, deg);
    }
    Ok(c)
}

fn progress(planned: Option<usize>) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() || out::capturing() {
        return None;
    }
    let (bar, template) = match planned {
        Some(n) => (
            ProgressBar::new(n as u64),
            "{elapsed_precise} [{bar:30}] batch {pos}/{len} {msg}",
        ),
        None => (
            ProgressBar::no_length(),
            "{elapsed_precise} batch {pos} {msg}",
        ),
    };
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style);
    }
    Some(bar)
}

/// `--progress-json`: each batch's row printed as one JSON line as the batch ends. A failed
/// write (a closed pipe, a full disk) stops the printing and is the run's error once the
/// batches are done, so that no OUT is written.
struct Stream {
    on: bool,
    failed: Option<out::OutputError>,
}

impl Stream {
    fn new(on: bool) -> Self {
        Stream { on, failed: None }
    }

    fn send(&mut self, row: Option<&Value>) {
        if let (true, None, Some(row)) = (self.on, &self.failed, row) {
            outln!("{row}");
            self.failed = out::flush().err();
        }
    }

    fn result(self) -> Result<(), out::OutputError> {
        self.failed.map_or(Ok(()), Err)
    }
}

/// The progress bar's message on a quad mesh: singularities left (and from how many),
/// Q-zips so far, and on a closed mesh the time left at the pace so far to the least count
/// Gauss-Bonnet allows, `4 |chi|` (a rough estimate: the last singularities go slowest).
struct Pace {
    from: usize,
    floor: Option<usize>,
}

impl Pace {
    fn new(input: &Mesh) -> Self {
        let c = zipmesh::invariants::Counts::of(&input.map);
        Pace {
            from: SingularityCounts::of(input).singularities(),
            floor: (c.boundary_loops == 0)
                .then(|| 4 * c.euler_characteristic.unsigned_abs() as usize),
        }
    }

    fn message(&self, now: &SingularityCounts, qzips: usize, elapsed: Duration) -> String {
        let left = now.singularities();
        let mut m = format!("singularities {left}/{}, {qzips} Q-zips", self.from);
        if let Some(floor) = self.floor.filter(|&f| left > f && left < self.from) {
            let pace = (self.from - left) as f64 / elapsed.as_secs_f64().max(1e-3);
            let eta = (left - floor) as f64 / pace;
            m.push_str(&format!(", ~{eta:.0} s to {floor} at this pace"));
        }
        m
    }
}

/// `--time-limit`: a positive number of seconds that a `Duration` holds.
fn seconds(s: &str) -> Result<Duration, String> {
    let x: f64 = s.parse().map_err(|_| format!("`{s}` is not a number"))?;
    if x.is_nan() || x <= 0.0 {
        return Err(format!("`{s}`: the limit must be above 0 seconds"));
    }
    Duration::try_from_secs_f64(x).map_err(|_| format!("`{s}`: too many seconds"))
}

fn summary(c: &SingularityCounts) -> String {
    format!(
        "v2 {} v3 {} v5 {} v6+ {} boundary defects {} ({} faces, {} triangles)",
        c.v2, c.v3, c.v5, c.v6plus, c.boundary_defects, c.faces, c.triangles
    )
}

/// The quad optimizer's options from the command line.
fn quad_options(args: &OptimizeArgs) -> OptimizeOptions {
    let mut options = OptimizeOptions::default()
        .seed(args.seed)
        .smoothing(!args.no_smooth)
        .chains(!args.no_chains)
        .fold_guard(!args.no_fold_guard);
    for (name, w) in &args.weights {
        options = options.weight(name, *w);
    }
    if let Some(n) = args.batches {
        options = options.batches(n);
    }
    if let Some(limit) = args.time_limit {
        let start = Instant::now();
        options = options.until(move || start.elapsed() >= limit);
    }
    options
}

/// One batch's JSON row; `seconds` is the batch's time.
fn batch_row(b: &BatchReport, seconds: f64, with_paths: bool) -> Value {
    let mut row = counts(&b.counts);
    row.insert("batch".into(), json!(b.batch));
    // The batch's Q-zips and face change include the kept chains' (broken down under
    // "chains"), so they add up to the counts from row to row.
    row.insert("qzips".into(), json!(b.qzips + b.chains.qzips));
    row.insert("candidates".into(), json!(b.candidates));
    row.insert(
        "chains".into(),
        json!({"tried": b.chains.tried, "cancelled": b.chains.cancelled, "kept": b.chains.kept, "qzips": b.chains.qzips, "face_change": b.chains.face_change}),
    );
    let faces = b.stats.face_change + b.chains.face_change;
    row.insert("face_change".into(), json!(faces));
    row.insert("score".into(), json!(b.score));
    row.insert("smoothed".into(), json!(b.smoothed));
    row.insert("seconds".into(), json!(seconds));
    if with_paths {
        let paths: Vec<Vec<[f64; 3]>> = b
            .paths
            .iter()
            .map(|p| p.iter().map(|x| x.to_array()).collect())
            .collect();
        row.insert("paths".into(), json!(paths));
    }
    Value::Object(row)
}

pub fn run(args: OptimizeArgs) -> Result<ExitCode, InputError> {
    let (mut mesh, _) = io::read_mesh(&args.file)?;
    let name = out::escape(&args.file.display().to_string());
    let map = &mesh.map;
    if let Some(f) = map.faces().find(|&f| !matches!(map.degree(f), 3 | 4)) {
        return Err(InputError(format!(
            "{name}: not a quad-dominant mesh (face {} has {} corners); optimize edits quad meshes and quad-dominant ones (triangles and quads)",
            f.index(),
            map.degree(f)
        )));
    }
    if map.num_faces() > 0 && map.faces().all(|f| map.degree(f) == 3) {
        return run_triangles(&args, mesh, &name);
    }
    if args.no_lookahead {
        return Err(InputError(format!(
            "{name}: --no-lookahead applies to triangle meshes only (this one has quads)"
        )));
    }
    let c = constraints(&args, &mesh)?;
    let input = mesh.clone();
    let bar = progress(args.batches);
    let start = Instant::now();
    let mut last = Instant::now();
    let mut rows = Vec::new();
    let mut stream = Stream::new(args.progress_json);
    let pace = Pace::new(&input);
    let mut qzips = 0;
    let outcome = optimize(&mut mesh, c, quad_options(&args), |b| {
        rows.push(batch_row(b, last.elapsed().as_secs_f64(), args.paths));
        last = Instant::now();
        stream.send(rows.last());
        qzips += b.qzips + b.chains.qzips;
        if let Some(bar) = &bar {
            bar.set_position(b.batch as u64);
            bar.set_message(pace.message(&b.counts, qzips, start.elapsed()));
        }
    })
    .map_err(|e| InputError(format!("{name}: {e}")))?;
    stream.result()?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    // A guarded second run reported its batches after the first run's: keep its own.
    rows.drain(..rows.len().saturating_sub(outcome.batches.len()));
    let seconds = start.elapsed().as_secs_f64();
    let mut report = json!({
        "input": counts(&outcome.input),
        "triangle_stage": {
            "input": outcome.triangles.input,
            "merged_pairs": outcome.triangles.merged,
            "moves": outcome.triangles.moves,
            "refused_pairs": outcome.triangles.refused,
            "guarded": outcome.triangles.guarded,
        },
        "preprocessed": outcome.preprocessed,
        "minimal": outcome.minimal,
        "initial_score": outcome.initial_score,
        "batches": rows,
        "final": counts(&outcome.final_counts),
        "time_limit_reached": outcome.stopped,
        "seconds": seconds,
    });
    let qzips: usize = outcome
        .batches
        .iter()
        .map(|b| b.qzips + b.chains.qzips)
        .sum();
    let minimal = if outcome.minimal {
        " (already at the Gauss-Bonnet minimum: every defect of one sign, nothing to cancel)"
    } else {
        ""
    };
    let limit = if outcome.stopped {
        " (the time limit stopped it)"
    } else {
        ""
    };
    let guarded = if outcome.triangles.guarded {
        " (made again with each triangle merge guarded: the first run folded quads)"
    } else {
        ""
    };
    let lines = [
        format!("{name}: {}{minimal}", summary(&outcome.input)),
        format!(
            "{}: {} after {} batches, {qzips} Q-zips, {seconds:.2} s{limit}{guarded}",
            out::escape(&args.output.display().to_string()),
            summary(&outcome.final_counts),
            outcome.batches.len()
        ),
    ];
    finish(&args, (&input, &mut mesh), &mut report, &lines)
}
