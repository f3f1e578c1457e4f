//! The `zipmesh` command-line tool: argument parsing and printing only; every number comes
//! from the library.
//!
//! Exit codes: 0 success (for `iso`: isomorphic), 1 not isomorphic (for `check`: a property
//! failed), 2 any error (bad file, bad usage, a full disk), 141 standard output closed by its
//! reader (quietly, as a Unix tool stopped by `SIGPIPE`), 130 and 143 interrupted by
//! `SIGINT` and `SIGTERM` (temporary files removed). `check` adds its own (see `check.rs`).

mod check;
mod optimize;
mod out;
mod quad_dominant;
mod quality;
mod qzip;
mod render;
mod signals;
mod singular;
mod tri;
mod view;

use out::outln;

use clap::{Parser, Subcommand};
use serde_json::{json, Map as JsonMap, Value};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use zipmesh::invariants::canonical::canonical_hash;
use zipmesh::invariants::{gauss_bonnet, irregular_vertices, Counts, Histograms, MeshKind};
use zipmesh::io::{self, MeshFileError};
use zipmesh::quality::{Reference, Summary};
use zipmesh::{BuildReport, Mesh};

/// The mesh `zipmesh stats` reads when no file is given (Spot's control mesh, CC0).
const DEFAULT_MESH: &str = include_str!("../data/spot_control_mesh.obj");
const DEFAULT_NAME: &str = "spot_control_mesh.obj (built in)";

#[derive(Parser)]
#[command(
    name = "zipmesh",
    version,
    about = "Edit the singularities of quad, triangle and quad-dominant meshes (move, cancel, optimize), measure and draw them, and check the edits' properties (OBJ, OFF, PLY)",
    after_help = "Vertices and faces are numbered from 0 in file order, in arguments and in every \
message (an OBJ file's vertex `1` is vertex 0; a message about an OBJ file quotes the file's \
number beside); lines are counted from 1.\n\nExit status: 0 success; 1 `iso`: not isomorphic, `check`: a property failed; \
2 an error (bad file, bad usage, output that cannot be written); 3 `check`: every property held \
on what ran but --time-limit cut the run; 141 standard output closed by its reader (quietly); \
130/143 ended by SIGINT/SIGTERM (temporary files removed). A command that writes a file leaves \
it in place only with status 0."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Counts, Euler characteristic, genus, histograms, Gauss-Bonnet, the canonical hash and
    /// the quality of the geometry (folded quads, scaled Jacobians, angles, edge ratios).
    Stats {
        /// An .obj, .off or .ply file; without it, the built-in Spot control mesh.
        file: Option<PathBuf>,
        /// Print one JSON object instead of a table.
        #[arg(long)]
        json: bool,
        /// Also measure each vertex's distance to this mesh's surface (the input of an
        /// edit), as a fraction of its bounding-box diagonal.
        #[arg(long, value_name = "FILE")]
        reference: Option<PathBuf>,
    },
    /// Every singularity (irregular vertex): its number, valence, place (interior or
    /// boundary), defect (valence minus the regular or ideal valence) and position.
    Singularities(singular::SingularitiesArgs),
    /// The 128-bit canonical hash of the mesh's connectivity, in 32 hex digits.
    Hash {
        /// An .obj, .off or .ply file.
        file: PathBuf,
    },
    /// Whether two meshes have isomorphic connectivity: exit 0 if so, 1 if not.
    Iso {
        /// The first mesh.
        a: PathBuf,
        /// The second mesh.
        b: PathBuf,
        /// Also accept a mirror image (an orientation-reversing isomorphism).
        #[arg(long)]
        mirror: bool,
    },
    /// Property campaigns: check the kernel's and the operators' properties on generated
    /// meshes (no arguments: the default campaign) or on the given files. Exit 1 on a failure.
    Check(check::CheckArgs),
    /// The four movements of a pair of singularities of a quad mesh (Q-zip) and whether each
    /// is realizable.
    Moves(qzip::MovesArgs),
    /// Move a pair of singularities of a quad mesh (Q-zip) and write the result; prints the
    /// report and the command that undoes it.
    ///
    /// The undo is a Q-zip back along the moved pair, derived from the edit (the path read
    /// backwards, the compass turned by pi) and checked, else searched for; when none
    /// restores the input (a third singularity on or next to the path can prevent it) the
    /// text says so and `--json` gives `"undo": null`, with exit 0: the edit was done, and
    /// only the input file undoes it. With `--preprocess` the undo restores the
    /// preprocessed mesh.
    Zip(qzip::ZipArgs),
    /// Move an adjacent 5-7 pair of a triangle mesh K steps in one of six directions
    /// (docs/tri-edit.md) and write the result; prints the command that undoes it.
    TriMove(tri::MoveArgs),
    /// Generate a 5-5-7-7 quadruple at a regular vertex of a triangle mesh.
    TriGenerate(tri::GenerateArgs),
    /// Split the type of an irregular vertex of a triangle mesh (v3, v4, vk with k > 7) or
    /// aggregate two or three v5 into a v4 or a v3.
    TriType(tri::TypeArgs),
    /// Cancel a 5-5-7-7 quadruple inside two triangles (`--quadruple`), or reduce a 5-5-7 or
    /// 5-7-7 triple to its one left-over singularity (`--triple`), in a triangle mesh.
    TriCancel(tri::CancelArgs),
    /// Move a triangle of a quad-dominant (qd) mesh by one edge per move (VE, EV, LE, RE), or
    /// walk it to a vertex, and write the result; prints the triangle and the moves that undo
    /// it.
    #[command(alias = "tri-walk")]
    QdWalk(quad_dominant::QdWalkArgs),
    /// Reduce the singularities of a quad, quad-dominant or triangle mesh by batches of
    /// Q-zips (Q-zip paper, Sec. 4.1; triangle meshes by the triangle paper's moves)
    /// and write the result; `--json` prints the counts before, after each batch and at the end.
    Optimize(optimize::OptimizeArgs),
    /// Draw the mesh (SVG or PNG): shaded faces and edges, hidden surfaces removed, the seen
    /// interior singularities as balls, optionally surgery paths from a JSON report.
    Render(render::RenderArgs),
    /// One self-contained HTML page (WebGL, no network access) to look around the mesh:
    /// orbit, zoom, the interior singularities coloured as `render` draws them with a legend,
    /// and picking: click two singularities and the page shows the `moves`/`zip` command for
    /// them (`tri-move` on triangle meshes). The URL's hash sets the view:
    /// `view.html#view=AZ,EL&zoom=Z&pick=A,B`.
    View(view::ViewArgs),
}

/// The `zipmesh` binary: parses the process's arguments, runs the command, prints its
/// output and returns the exit status (see the crate's documentation).
pub fn main() -> ExitCode {
    signals::install();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage(&e),
    };
    let result = check_outputs(&cli.command)
        .map_err(|e| format!("cannot write {e}"))
        .and_then(|()| dispatch(cli.command));
    match result {
        Ok(code) => out::finish(code),
        // `zip` flushes before it commits its file; a closed pipe there ends quietly too.
        Err(_) if out::closed() => ExitCode::from(out::CLOSED_PIPE),
        Err(e) => {
            let code = out::finish(ExitCode::from(2));
            out::error(e);
            code
        }
    }
}

/// Why [`run_captured`] ran no command to its end.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CapturedError {
    /// The arguments do not parse (clap's message, help and version included).
    Usage(String),
    /// The command failed: the message the binary prints after `zipmesh: `.
    Failed(String),
}

/// Runs one command (`args` without the program's name) in this process, as the binary
/// would but without signal handlers or progress bars, and returns what it printed on
/// standard output. Files are read and written as the binary does. Commands run one at a
/// time: a second caller waits for the first.
pub fn run_captured<I, T>(args: I) -> Result<String, CapturedError>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
    let argv = std::iter::once(std::ffi::OsString::from("zipmesh"))
        .chain(args.into_iter().map(Into::into));
    let cli = Cli::try_parse_from(argv).map_err(|e| CapturedError::Usage(e.to_string()))?;
    let (result, text) = out::capture(|| {
        check_outputs(&cli.command)
            .map_err(|e| format!("cannot write {e}"))
            .and_then(|()| dispatch(cli.command))
    });
    result.map(|_| text).map_err(CapturedError::Failed)
}

/// Runs the command; its error as the message to print.
fn dispatch(command: Command) -> Result<ExitCode, String> {
    match command {
        Command::Moves(args) => qzip::run_moves(args).map_err(|e| e.to_string()),
        Command::Zip(args) => qzip::run_zip(args).map_err(|e| e.to_string()),
        Command::TriMove(args) => tri::run_move(args).map_err(|e| e.to_string()),
        Command::TriGenerate(args) => tri::run_generate(args).map_err(|e| e.to_string()),
        Command::TriType(args) => tri::run_type(args).map_err(|e| e.to_string()),
        Command::TriCancel(args) => tri::run_cancel(args).map_err(|e| e.to_string()),
        Command::QdWalk(args) => quad_dominant::run_qd_walk(args).map_err(|e| e.to_string()),
        Command::Optimize(args) => optimize::run(args).map_err(|e| e.to_string()),
        Command::Render(args) => render::run(args),
        Command::View(args) => view::run(args),
        command => run(command).map_err(|e| e.to_string()),
    }
}

/// Refuses, before any file is read, an output that cannot be written (a missing
/// directory, a directory as the output: [`io::check_target`]) and a mesh output that
/// names no mesh format, so that a mistyped `-o` costs no run. `check` checks its `--out`
/// folder itself.
fn check_outputs(command: &Command) -> Result<(), MeshFileError> {
    let mesh = |path: &Path| {
        io::check_target(path)?;
        match io::Format::from_path(path) {
            Some(_) => Ok(()),
            None => Err(MeshFileError::new(None, io::ErrorKind::UnknownFormat).with_path(path)),
        }
    };
    match command {
        Command::Zip(a) => mesh(&a.output),
        Command::TriMove(a) => mesh(&a.files.output),
        Command::TriGenerate(a) => mesh(&a.files.output),
        Command::TriType(a) => mesh(&a.files.output),
        Command::TriCancel(a) => mesh(&a.files.output),
        Command::QdWalk(a) => mesh(&a.output),
        Command::Optimize(a) => mesh(&a.output),
        Command::Render(a) => io::check_target(&a.output),
        Command::View(a) => io::check_target(&a.output),
        Command::Stats { .. }
        | Command::Hash { .. }
        | Command::Iso { .. }
        | Command::Check(_)
        | Command::Moves(_)
        | Command::Singularities(_) => Ok(()),
    }
}

/// Help and version are successes (unless they cannot be written); usage errors exit 2.
fn usage(e: &clap::Error) -> ExitCode {
    if e.use_stderr() {
        let _ = e.print();
        return ExitCode::from(2);
    }
    out::push(format_args!("{}", e.render()));
    out::finish(ExitCode::SUCCESS)
}

fn run(command: Command) -> Result<ExitCode, MeshFileError> {
    match command {
        Command::Check(args) => return Ok(check::run(args)),
        // Dispatched in `main`: their errors are not file errors.
        Command::Moves(_)
        | Command::Zip(_)
        | Command::TriMove(_)
        | Command::TriGenerate(_)
        | Command::TriType(_)
        | Command::TriCancel(_)
        | Command::QdWalk(_)
        | Command::Optimize(_)
        | Command::Render(_)
        | Command::View(_) => {}
        Command::Singularities(args) => singular::run(args)?,
        Command::Stats {
            file,
            json,
            reference,
        } => run_stats(file, json, reference)?,
        Command::Hash { file } => {
            let (mesh, _) = io::read_mesh(&file)?;
            outln!("{:032x}", canonical_hash(&mesh.map));
        }
        Command::Iso { a, b, mirror } => {
            let (ma, _) = io::read_mesh(&a)?;
            let (mb, _) = io::read_mesh(&b)?;
            let same = if mirror {
                zipmesh::is_isomorphic_mirror(&ma.map, &mb.map)
            } else {
                zipmesh::is_isomorphic(&ma.map, &mb.map)
            };
            let how = if mirror {
                " (mirror images allowed)"
            } else {
                ""
            };
            let verdict = if same { "isomorphic" } else { "not isomorphic" };
            outln!("{verdict}: {} and {}{how}", a.display(), b.display());
            return Ok(if same {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            });
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// `zipmesh stats`: the table or the JSON object of [`stats`].
fn run_stats(
    file: Option<PathBuf>,
    json: bool,
    reference: Option<PathBuf>,
) -> Result<(), MeshFileError> {
    let (name, (mesh, report)) = match &file {
        Some(path) => (path.display().to_string(), io::read_mesh(path)?),
        None => (
            DEFAULT_NAME.to_string(),
            io::obj::parse(DEFAULT_MESH).map_err(|e| e.with_path(DEFAULT_NAME))?,
        ),
    };
    let reference = match &reference {
        Some(path) => Some(Reference::new(&io::read_mesh(path)?.0)),
        None => None,
    };
    let stats = stats(&mesh, &report, reference.as_ref());
    if json {
        let object: JsonMap<String, Value> =
            stats.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
        outln!("{}", Value::Object(object));
    } else {
        print_table(&name, &stats);
    }
    Ok(())
}

/// The name of a mesh kind in every report: `triangle`, `quad` or `mixed`.
pub(crate) fn kind_name(kind: MeshKind) -> &'static str {
    match kind {
        MeshKind::Triangle => "triangle",
        MeshKind::Quad => "quad",
        MeshKind::Mixed => "mixed",
    }
}

/// Everything `stats` reports, as JSON values in the order of the table; the quality
/// against `reference` if given.
fn stats(
    mesh: &Mesh,
    report: &BuildReport,
    reference: Option<&Reference>,
) -> Vec<(&'static str, Value)> {
    let map = &mesh.map;
    let c = Counts::of(map);
    let h = Histograms::of(map);
    let kind = MeshKind::of(map);
    let gb = gauss_bonnet(map, kind);
    let hist = |m: &BTreeMap<usize, usize>| -> Value {
        Value::Object(m.iter().map(|(k, v)| (k.to_string(), json!(v))).collect())
    };
    let summary = match reference {
        Some(r) => Summary::against(mesh, r),
        None => Summary::of(mesh),
    };
    vec![
        ("kind", json!(kind_name(kind))),
        ("vertices", json!(c.vertices)),
        ("edges", json!(c.edges)),
        ("faces", json!(c.faces)),
        ("boundary_loops", json!(c.boundary_loops)),
        ("components", json!(c.components)),
        ("euler_characteristic", json!(c.euler_characteristic)),
        ("genus", json!(c.genus)),
        ("unreferenced_vertices", json!(report.unreferenced.len())),
        (
            "irregular_vertices",
            json!(irregular_vertices(map, kind).len()),
        ),
        ("face_degrees", hist(&h.face_degrees)),
        ("interior_valences", hist(&h.interior_valences)),
        ("boundary_valences", hist(&h.boundary_valences)),
        (
            "gauss_bonnet",
            json!({
                "vertex_sum": gb.vertex_sum,
                "face_sum": gb.face_sum,
                "rhs": gb.rhs,
                "holds": gb.holds(),
            }),
        ),
        (
            "canonical_hash",
            json!(format!("{:032x}", canonical_hash(map))),
        ),
        ("quality", quality::to_json(&summary)),
    ]
}

/// One `key  value` row per entry; histograms as `value:count` pairs in numeric order.
fn print_table(name: &str, stats: &[(&str, Value)]) {
    outln!("{:<22} {name}", "file");
    for (key, value) in stats {
        if *key == "quality" {
            for (label, text) in quality::rows(value) {
                outln!("{label:<22} {text}");
            }
            continue;
        }
        let text = match value {
            Value::Object(o) if *key == "gauss_bonnet" => format!(
                "{} + {} = {} ({})",
                o["vertex_sum"],
                o["face_sum"],
                o["rhs"],
                if o["holds"] == Value::Bool(true) {
                    "holds"
                } else {
                    "FAILS"
                }
            ),
            Value::Object(o) if o.is_empty() => "-".to_string(),
            Value::Object(o) => {
                let mut pairs: Vec<(u64, &Value)> = o
                    .iter()
                    .map(|(k, v)| (k.parse().unwrap_or(u64::MAX), v))
                    .collect();
                pairs.sort_by_key(|&(k, _)| k);
                pairs
                    .iter()
                    .map(|(k, v)| format!("{k}:{v}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            }
            Value::String(s) => s.clone(),
            other => other.to_string(),
        };
        outln!("{:<22} {text}", key.replace('_', " "));
    }
}
