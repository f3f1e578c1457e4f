//! `zipmesh moves` and `zipmesh zip`: Q-zip from the command line.

use clap::Args;
use serde_json::{json, Value};
use std::path::PathBuf;
use std::process::ExitCode;
use zipmesh::geometry::{edited_vertices, relax_footprint, RelaxOptions, Relaxation};
use zipmesh::io::{self, MeshFileError};
use zipmesh::optimize::Surface;
use zipmesh::quality::{Reference, Summary};
use zipmesh::qzip::{
    find_reverse, moves, sketch, validate_path, Path, Qzip, SketchOptions, Tag, ZipReport,
};
use zipmesh::{Compaction, Map, Mesh, Vert};

use crate::out::{self, outln};
use crate::quality;

/// Arguments shared by `moves` and `zip`.
#[derive(Args)]
pub struct PairArgs {
    /// A quad mesh (.obj, .off or .ply).
    file: PathBuf,
    /// The initial singularity: a 0-based vertex number of the file.
    #[arg(long)]
    from: u32,
    /// The terminal singularity: a 0-based vertex number of the file.
    #[arg(long)]
    to: u32,
    /// The surgery path as comma-separated vertex numbers (default: a shortest path).
    #[arg(long, value_delimiter = ',')]
    path: Option<Vec<u32>>,
    /// Print one JSON value instead of text.
    #[arg(long)]
    json: bool,
    /// First split every interior vertex of valence 6 or more and remove every interior
    /// valence-2 vertex (Sec. 2.6 covers v3 and v5 only); new vertices get new numbers.
    #[arg(long)]
    preprocess: bool,
}

/// `zipmesh moves`.
#[derive(Args)]
pub struct MovesArgs {
    /// A quad mesh (.obj, .off or .ply).
    file: PathBuf,
    /// The initial singularity: a 0-based vertex number of the file.
    #[arg(long)]
    from: u32,
    /// The terminal singularity: a 0-based vertex number of the file.
    #[arg(long, required_unless_present = "partners")]
    to: Option<u32>,
    /// The surgery path as comma-separated vertex numbers (default: a shortest path).
    #[arg(long, value_delimiter = ',')]
    path: Option<Vec<u32>>,
    /// Print one JSON value instead of text.
    #[arg(long)]
    json: bool,
    /// First split every interior vertex of valence 6 or more and remove every interior
    /// valence-2 vertex (Sec. 2.6 covers v3 and v5 only); new vertices get new numbers.
    #[arg(long)]
    preprocess: bool,
    /// Instead of one pair: the N interior singularities nearest to --from (fewest edges
    /// first; default 5), each with its distance and the movements realizable towards it.
    #[arg(long, value_name = "N", num_args = 0..=1, default_missing_value = "5",
          conflicts_with_all = ["to", "path"])]
    partners: Option<usize>,
}

/// `zipmesh zip`.
#[derive(Args)]
pub struct ZipArgs {
    #[command(flatten)]
    pair: PairArgs,
    /// The initial operation at the initial singularity, read along the path's first edge
    /// (the paper's compass, docs/qzip.md): LS or RS split it, the left (LS) or right (RS)
    /// copy going on along the path; LC or RC collapse the quad along the first edge on its
    /// right (LC) or left (RC). `moves` shows what each of the four does.
    #[arg(long = "move")]
    tag: Tag,
    /// Where to write the edited mesh (compacted: vertices renumbered 0..V).
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// Keep the raw placement (each created vertex at the mean of its neighbours) instead of
    /// relaxing the edit's footprint on the input surface.
    #[arg(long)]
    no_relax: bool,
}

/// An input problem: printed as `zipmesh: <message>`, exit 2.
pub struct InputError(pub String);

impl std::fmt::Display for InputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<out::OutputError> for InputError {
    fn from(e: out::OutputError) -> Self {
        InputError(e.to_string())
    }
}

impl From<MeshFileError> for InputError {
    fn from(e: MeshFileError) -> Self {
        InputError(e.to_string())
    }
}

/// Reads the mesh and checks the pair and the path: the mesh as read, the mesh to edit (the
/// same, or preprocessed) and the path.
fn load(a: &PairArgs) -> Result<(Mesh, Mesh, Path), InputError> {
    let vertices = [("--from", a.from), ("--to", a.to)];
    let (input, mesh) = load_mesh(&a.file, a.preprocess, &vertices)?;
    let map = &mesh.map;
    let name = a.file.display();
    let (from, to) = (Vert::new(a.from), Vert::new(a.to));
    let opts = zipmesh::qzip::avoid_triangles(map, SketchOptions::default());
    let path = match &a.path {
        Some(vs) => {
            let vs: Vec<Vert> = vs.iter().map(|&v| Vert::new(v)).collect();
            validate_path(map, from, to, &vs, &opts)
        }
        None => sketch(map, from, to, &opts),
    }
    .map_err(|e| InputError(format!("{name}: no surgery path: {e}")))?;
    Ok((input, mesh, path))
}

/// Reads `file` (preprocessed if asked), checks it is a quad or quad-dominant mesh and each
/// of `vertices` (a flag and a number) an irregular vertex; the input and the mesh to edit.
fn load_mesh(
    file: &std::path::Path,
    preprocess: bool,
    vertices: &[(&str, u32)],
) -> Result<(Mesh, Mesh), InputError> {
    let (input, _) = io::read_mesh(file)?;
    let mut mesh = input.clone();
    let name = file.display();
    if preprocess {
        zipmesh::qzip::preprocess(&mut mesh)
            .map_err(|e| InputError(format!("{name}: the preprocessing was refused: {e}")))?;
    }
    let map = &mesh.map;
    // Quad and quad-dominant meshes: the paths wind around the triangles (Sec. 3.2).
    if let Some(f) = map.faces().find(|&f| !(3..=4).contains(&map.degree(f))) {
        return Err(InputError(format!(
            "{name}: not a quad or quad-dominant mesh (face {} has {} corners); Q-zip edits \
             quads, with triangles among them",
            f.index(),
            map.degree(f)
        )));
    }
    if !map.faces().any(|f| map.degree(f) == 4) {
        return Err(InputError(format!(
            "{name}: not a quad or quad-dominant mesh (no quad); Q-zip edits quads"
        )));
    }
    for &(flag, v) in vertices {
        let vert = Vert::new(v);
        if !map.is_live_vertex(vert) {
            return Err(InputError(format!(
                "{name}: {flag} {v}: no such vertex (the file has {} vertex numbers, and \
                 unreferenced ones do not count)",
                map.vertex_slots()
            )));
        }
        let regular = if map.is_boundary_vertex(vert) { 3 } else { 4 };
        if map.valence(vert) == regular {
            return Err(InputError(format!(
                "{name}: {flag} {v} is not irregular (valence {}{}); Q-zip moves singularities",
                map.valence(vert),
                if map.is_boundary_vertex(vert) {
                    " on the boundary"
                } else {
                    ""
                }
            )));
        }
    }
    Ok((input, mesh))
}

fn numbers(vs: &[Vert]) -> Vec<u32> {
    vs.iter().map(|v| v.index() as u32).collect()
}

/// A vertex of the edited map in the compacted numbering.
fn renumber(c: &Compaction, v: Vert) -> Option<u32> {
    c.vertices
        .get(v.index())
        .copied()
        .flatten()
        .map(|x| x.index() as u32)
}

fn surgery_path(r: &ZipReport) -> Vec<u32> {
    r.surgery()
        .steps()
        .iter()
        .map(|s| s.vertex.index() as u32)
        .collect()
}

/// Runs `zipmesh moves`: the four movements of the pair and their outcome.
pub fn run_moves(args: MovesArgs) -> Result<ExitCode, InputError> {
    let Some(to) = args.to else {
        return run_partners(&args, args.partners.unwrap_or(5));
    };
    let pair = PairArgs {
        file: args.file,
        from: args.from,
        to,
        path: args.path,
        json: args.json,
        preprocess: args.preprocess,
    };
    run_pair(pair)
}

/// `moves --partners N`: the N interior singularities nearest to `--from`, in breadth-first
/// order (fewest edges first, then vertex number), each with the movements realizable along
/// a shortest path to it.
fn run_partners(args: &MovesArgs, n: usize) -> Result<ExitCode, InputError> {
    let (_, mesh) = load_mesh(&args.file, args.preprocess, &[("--from", args.from)])?;
    let map = &mesh.map;
    let from = Vert::new(args.from);
    let opts = zipmesh::qzip::avoid_triangles(map, SketchOptions::default());
    let mut rows = Vec::new();
    for (v, distance) in nearest_singularities(map, from, n) {
        let Ok(path) = sketch(map, from, v, &opts) else {
            continue;
        };
        let realizable: Vec<String> = moves(map, &path)
            .iter()
            .filter(|m| m.outcome.is_ok())
            .map(|m| m.tag.to_string())
            .collect();
        rows.push(json!({
            "to": v.index(),
            "valence": map.valence(v),
            "distance": distance,
            "realizable": realizable,
        }));
    }
    if args.json {
        outln!("{}", Value::Array(rows));
    } else {
        let name = args.file.display();
        outln!(
            "{name}: the {} singularities nearest to {}",
            rows.len(),
            args.from
        );
        for r in &rows {
            let tags: Vec<&str> = r["realizable"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(Value::as_str)
                .collect();
            outln!(
                "  {} (valence {}, {} edges): {} realizable; zipmesh moves {name} --from {} --to {}",
                r["to"],
                r["valence"],
                r["distance"],
                if tags.is_empty() { "none".to_string() } else { tags.join(" ") },
                args.from,
                r["to"]
            );
        }
    }
    out::flush()?;
    Ok(ExitCode::SUCCESS)
}

/// The first `n` interior irregular vertices other than `from` that it reaches, nearest
/// first (ties by vertex number), with their distances in edges.
fn nearest_singularities(map: &Map, from: Vert, n: usize) -> Vec<(Vert, usize)> {
    let dist = map.distances(from);
    let mut found: Vec<(Vert, usize)> = map
        .vertices()
        .filter(|&v| v != from && dist[v.index()] != usize::MAX)
        .filter(|&v| !map.is_boundary_vertex(v) && map.valence(v) != 4)
        .map(|v| (v, dist[v.index()]))
        .collect();
    found.sort_unstable_by_key(|&(v, d)| (d, v));
    found.truncate(n);
    found
}

/// `moves` for one pair: the four movements along the pair's path.
fn run_pair(pair: PairArgs) -> Result<ExitCode, InputError> {
    let (_, mesh, path) = load(&pair)?;
    let mut rows = Vec::new();
    for m in moves(&mesh.map, &path) {
        let row = match &m.outcome {
            Ok((edited, r)) => {
                let mut e: Map = edited.clone();
                let c = e.compact();
                json!({
                    "move": m.tag.to_string(),
                    "realizable": true,
                    "splits": r.splits(),
                    "collapses": r.collapses(),
                    "moved": {
                        "from": renumber(&c, r.moved_from()),
                        "to": renumber(&c, r.moved_to()),
                    },
                    "path": surgery_path(r),
                })
            }
            Err(e) => json!({
                "move": m.tag.to_string(),
                "realizable": false,
                "reason": e.to_string(),
            }),
        };
        rows.push(row);
    }
    if pair.json {
        outln!("{}", Value::Array(rows));
    } else {
        outln!(
            "{}: moving {} -> {} along {}",
            pair.file.display(),
            pair.from,
            pair.to,
            join(&numbers(path.vertices()))
        );
        for r in &rows {
            if r["realizable"] == json!(true) {
                outln!(
                    "{}  realizable: {} splits, {} collapses; the pair moves to {} and {} \
                     (vertex numbers after compaction)",
                    r["move"].as_str().unwrap_or("?"),
                    r["splits"],
                    r["collapses"],
                    r["moved"]["from"],
                    r["moved"]["to"]
                );
            } else {
                outln!(
                    "{}  not realizable: {}",
                    r["move"].as_str().unwrap_or("?"),
                    r["reason"].as_str().unwrap_or("?")
                );
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn join(v: &[u32]) -> String {
    v.iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// Runs `zipmesh zip`: one movement, the edited mesh written compacted to OUT.
pub fn run_zip(args: ZipArgs) -> Result<ExitCode, InputError> {
    let (input, original, path) = load(&args.pair)?;
    let mut mesh = original.clone();
    let z = Qzip::new()
        .zip_along(&mut mesh, &path, args.tag)
        .map_err(|e| {
            InputError(format!(
                "{}: the {} movement is not realizable: {e}",
                args.pair.file.display(),
                args.tag
            ))
        })?;
    let r = z.record();
    // The reverse run is found on the edited map before compaction renumbers it.
    let reverse = find_reverse(&mesh.map, r, &original.map);
    let (relaxed, quality) = relax(&input, &mut mesh, !args.no_relax);
    let c = mesh.compact();
    // Written now, in place only after the report is printed: no OUT with a failing status.
    let pending = io::prepare_mesh(&args.output, &mesh)?;
    let moved_from = renumber(&c, r.moved_from());
    let moved_to = renumber(&c, r.moved_to());
    let undo = reverse.as_ref().map(|rev| {
        let p: Vec<Option<u32>> = rev
            .path
            .vertices()
            .iter()
            .map(|&v| renumber(&c, v))
            .collect();
        json!({
            "from": moved_to,
            "to": moved_from,
            "move": rev.tag.to_string(),
            "path": p,
            "found": rev.way.to_string(),
        })
    });
    let report = json!({
        "file": args.pair.file.display().to_string(),
        "output": args.output.display().to_string(),
        "move": args.tag.to_string(),
        "splits": r.splits(),
        "collapses": r.collapses(),
        "cleanup": {"valence2_removals": r.cleanup_counts().0, "valence6_splits": r.cleanup_counts().1},
        "moved": {"from": moved_from, "to": moved_to},
        "path": surgery_path(r),
        "footprint": {"faces": r.footprint_faces().len(), "edges": r.footprint_edges().len()},
        "scar": {"faces": r.scar_faces().len(), "edges": r.scar_edges().len()},
        "undo": undo,
        "relax": relaxed.map(|x| json!({
            "projected": x.projected, "region": x.region, "moves": x.moves, "refused": x.refused,
        })),
        "quality": quality::both_json(&quality),
    });
    if args.pair.json {
        outln!("{report}");
    } else {
        outln!(
            "{} -> {}: {} movement, {} splits, {} collapses; the pair moved to {} and {}",
            args.pair.file.display(),
            args.output.display(),
            args.tag,
            r.splits(),
            r.collapses(),
            report["moved"]["from"],
            report["moved"]["to"]
        );
        let how = if relaxed.is_some() {
            "relaxed"
        } else {
            "raw placement"
        };
        outln!("quality ({how}): {}", quality::line(&quality));
        match &reverse {
            Some(rev) => outln!(
                "undo: zipmesh zip {} --from {} --to {} --move {} --path {} -o UNDONE",
                args.output.display(),
                report["moved"]["to"],
                report["moved"]["from"],
                rev.tag,
                report["undo"]["path"]
                    .as_array()
                    .map(|a| a
                        .iter()
                        .map(|x| x.to_string())
                        .collect::<Vec<_>>()
                        .join(","))
                    .unwrap_or_default()
            ),
            None => outln!("undo: no reverse Q-zip restores the input here"),
        }
    }
    out::flush()?;
    pending.commit()?;
    Ok(ExitCode::SUCCESS)
}

/// Relaxes the edit's footprint (unless `!relax`) and measures the input and the output,
/// both against the file as read: the preprocessing's vertices are the edit's too.
fn relax(input: &Mesh, mesh: &mut Mesh, relax: bool) -> (Option<Relaxation>, [Summary; 2]) {
    let relaxed = relax.then(|| {
        let seeds = edited_vertices(input, mesh);
        relax_footprint(mesh, &Surface::new(input), &seeds, RelaxOptions::default())
    });
    let reference = Reference::new(input);
    (
        relaxed,
        [input, &*mesh].map(|m| Summary::against(m, &reference)),
    )
}
