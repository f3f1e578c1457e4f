//! `zipmesh tri-move`, `tri-generate`, `tri-type` and `tri-cancel`: the triangle paper's
//! semantic edits (`zipmesh::tri_edit`) from the command line.
//!
//! Same conventions as `zip`: 0-based vertex numbers of the file, OUT written compacted and
//! atomically after the report, exit 2 and no OUT on bad input. Vertices the edit does not
//! touch keep their positions bit for bit; a vertex an operator creates or moves is placed
//! by its rule (`TriOp::apply_with`).

use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::process::ExitCode;
use zipmesh::io;
use zipmesh::ops::tri::TriRecord;
use zipmesh::tri_edit::{
    aggregate_type_with, can_generate_quadruple, generate_quadruple_with, move_pair_with,
    remove_quadruple_with, split_type_with, Direction, Quadruple, TriEditError,
};
use zipmesh::{Compaction, Dart, Map, Mesh, Vert};

use crate::out::{self, outln};
use crate::qzip::InputError;

/// Input and output shared by every triangle edit.
#[derive(Args)]
pub struct Files {
    /// A triangle mesh (.obj or .off).
    file: PathBuf,
    /// Where to write the edited mesh (compacted: vertices renumbered 0..V).
    #[arg(short, long)]
    output: PathBuf,
    /// Print one JSON value instead of text.
    #[arg(long)]
    json: bool,
}

/// `zipmesh tri-move`.
#[derive(Args)]
pub struct MoveArgs {
    #[command(flatten)]
    files: Files,
    /// The adjacent 5-7 pair: two 0-based vertex numbers, a v5 and a v7 (either order).
    #[arg(long, value_delimiter = ',', num_args = 1, required = true)]
    pair: Vec<u32>,
    /// The direction, 0 to 5, counter-clockwise; 0 is just left of the edge v5 -> v7
    /// (docs/tri-edit.md).
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..6))]
    direction: u8,
    /// How many steps to move (each a flip, a collapse or a split).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    steps: u32,
}

/// A configuration of 5-5-7-7 generation.
#[derive(Clone, Copy, ValueEnum)]
pub enum Config {
    /// Flip the edge V-W: v5 at V and W.
    Flip,
    /// Split V along V->W and the opposite dart: v7 at W and the opposite neighbour.
    Split,
    /// Collapse V into W, then flip a spoke of W: a 5-7-7-5 chain, not a quadruple in two
    /// triangles (tri-cancel does not remove it).
    CollapseFlip,
}

/// `zipmesh tri-generate`.
#[derive(Args)]
pub struct GenerateArgs {
    #[command(flatten)]
    files: Files,
    /// A regular interior vertex (valence 6).
    #[arg(long)]
    at: u32,
    /// A neighbour of V that fixes the dart V->W (default: the first neighbour that works).
    #[arg(long)]
    toward: Option<u32>,
    /// The configuration.
    #[arg(long, value_enum, default_value = "flip")]
    config: Config,
}

/// `zipmesh tri-type`.
#[derive(Args)]
#[group(id = "which", required = true, multiple = false, args = ["split", "aggregate"])]
pub struct TypeArgs {
    #[command(flatten)]
    files: Files,
    /// Split an interior v3 (three v5), v4 (two v5) or vk, k > 7 (k - 6 v7).
    #[arg(long)]
    split: Option<u32>,
    /// Aggregate two v5 into a v4 or three v5 into a v3.
    #[arg(long, value_delimiter = ',', num_args = 1)]
    aggregate: Option<Vec<u32>>,
}

/// `zipmesh tri-cancel`.
#[derive(Args)]
pub struct CancelArgs {
    #[command(flatten)]
    files: Files,
    /// A 5-5-7-7 quadruple inside two triangles: four vertex numbers.
    #[arg(long, value_delimiter = ',', num_args = 1, required = true)]
    quadruple: Vec<u32>,
}

fn err(msg: impl std::fmt::Display) -> InputError {
    InputError(msg.to_string())
}

/// Reads a triangle mesh.
fn load(f: &Files) -> Result<Mesh, InputError> {
    let (mesh, _) = io::read_mesh(&f.file)?;
    let map = &mesh.map;
    if let Some(face) = map.faces().find(|&x| map.degree(x) != 3) {
        return Err(err(format_args!(
            "{}: not a triangle mesh (face {} has {} corners)",
            f.file.display(),
            face.index(),
            map.degree(face)
        )));
    }
    Ok(mesh)
}

/// The vertices `vs` given with `flag`, each live, and `n` of them when `n` is given.
fn verts(
    f: &Files,
    map: &Map,
    flag: &str,
    vs: &[u32],
    n: Option<usize>,
) -> Result<Vec<Vert>, InputError> {
    if let Some(n) = n.filter(|&n| n != vs.len()) {
        return Err(err(format_args!(
            "{}: {flag} takes {n} vertex numbers, got {}",
            f.file.display(),
            vs.len()
        )));
    }
    vs.iter()
        .map(|&v| {
            let x = Vert::new(v);
            if map.is_live_vertex(x) {
                Ok(x)
            } else {
                Err(err(format_args!(
                    "{}: {flag} {v}: no such vertex (the file has {} vertex numbers, and \
                     unreferenced ones do not count)",
                    f.file.display(),
                    map.vertex_slots()
                )))
            }
        })
        .collect()
}

/// A vertex of the edited map in the compacted numbering.
fn renumber(c: &Compaction, v: Vert) -> Option<u32> {
    c.vertices
        .get(v.index())
        .copied()
        .flatten()
        .map(|x| x.index() as u32)
}

fn renumber_all(c: &Compaction, vs: &[Vert]) -> Vec<Option<u32>> {
    vs.iter().map(|&v| renumber(c, v)).collect()
}

/// Flips, collapses and splits among the graph operations applied.
#[derive(Default)]
struct Ops {
    flips: usize,
    collapses: usize,
    splits: usize,
}

impl Ops {
    fn add(&mut self, r: &TriRecord) {
        match r {
            TriRecord::Flip(_) => self.flips += 1,
            TriRecord::Collapse(_) => self.collapses += 1,
            _ => self.splits += 1,
        }
    }

    fn of(steps: &[TriRecord]) -> Ops {
        let mut ops = Ops::default();
        steps.iter().for_each(|r| ops.add(r));
        ops
    }

    fn text(&self) -> String {
        format!(
            "{} flips, {} collapses, {} splits",
            self.flips, self.collapses, self.splits
        )
    }
}

/// Compacts, prepares OUT, prints the report (`json` built from the compaction), then puts
/// OUT in place: no OUT with a failing status.
fn finish(
    f: &Files,
    mut mesh: Mesh,
    ops: &Ops,
    report: impl FnOnce(&Compaction) -> (Value, String),
) -> Result<ExitCode, InputError> {
    let c = mesh.compact();
    let pending = io::prepare_mesh(&f.output, &mesh)?;
    let (mut value, text) = report(&c);
    value["file"] = json!(f.file.display().to_string());
    value["output"] = json!(f.output.display().to_string());
    value["flips"] = json!(ops.flips);
    value["collapses"] = json!(ops.collapses);
    value["splits"] = json!(ops.splits);
    if f.json {
        outln!("{value}");
    } else {
        outln!(
            "{} -> {}: {}; {text}",
            f.file.display(),
            f.output.display(),
            ops.text()
        );
    }
    out::flush()?;
    pending.commit()?;
    Ok(ExitCode::SUCCESS)
}

fn list(v: &[Option<u32>]) -> String {
    v.iter()
        .map(|x| x.map_or("?".to_string(), |x| x.to_string()))
        .collect::<Vec<_>>()
        .join(",")
}

/// Runs `zipmesh tri-move`: an adjacent 5-7 pair moved `--steps` times in `--direction`.
pub fn run_move(args: MoveArgs) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let mut mesh = load(f)?;
    let given = verts(f, &mesh.map, "--pair", &args.pair, Some(2))?;
    let swapped = mesh.map.valence(given[0]) == 7 && mesh.map.valence(given[1]) == 5;
    let (mut p, mut q) = if swapped {
        (given[1], given[0])
    } else {
        (given[0], given[1])
    };
    let dir = Direction::from_index(args.direction.into()).unwrap_or(Direction::SplitLeft);
    let mut ops = Ops::default();
    for step in 1..=args.steps {
        let e = move_pair_with(&mut mesh.map, &mut mesh.positions, p, q, dir).map_err(|e| {
            err(format_args!(
                "{}: --pair {},{} --direction {}: step {step} of {} refused: {}",
                f.file.display(),
                args.pair[0],
                args.pair[1],
                args.direction,
                args.steps,
                why(e)
            ))
        })?;
        ops.add(e.record().record());
        (p, q) = (e.record().p(), e.record().q());
    }
    let back = dir.opposite().index();
    let steps = args.steps;
    finish(f, mesh, &ops, |c| {
        let (np, nq) = (renumber(c, p), renumber(c, q));
        let pair = if swapped { [nq, np] } else { [np, nq] };
        let value = json!({
            "pair": pair,
            "direction": args.direction,
            "steps": steps,
            "undo": {"pair": pair, "direction": back, "steps": steps},
        });
        let text = format!(
            "the pair is at {}\nundo: zipmesh tri-move {} --pair {} --direction {back} --steps {steps} -o UNDONE",
            list(&pair),
            f.output.display(),
            list(&pair)
        );
        (value, text)
    })
}

/// A refusal in words, with what `NotAPair` means for a pair move.
fn why(e: TriEditError) -> String {
    match e {
        TriEditError::NotAPair => {
            "not an adjacent 5-7 pair (an interior v5 and an interior v7 joined by one edge)"
                .to_string()
        }
        TriEditError::Irregular => "a vertex whose valence the edit changes is not regular \
             (interior, valence 6): the paper's edits need a regular neighbourhood"
            .to_string(),
        e => e.to_string(),
    }
}

fn quadruple(c: Config) -> Quadruple {
    match c {
        Config::Flip => Quadruple::Flip,
        Config::Split => Quadruple::Split,
        Config::CollapseFlip => Quadruple::CollapseFlip,
    }
}

/// The dart `at -> toward`, or the first dart of `at` whose generation applies.
fn generation_dart(args: &GenerateArgs, map: &Map, how: Quadruple) -> Result<Dart, InputError> {
    let f = &args.files;
    let at = verts(f, map, "--at", &[args.at], None)?[0];
    let darts: Vec<Dart> = match args.toward {
        Some(w) => {
            let w = verts(f, map, "--toward", &[w], None)?[0];
            let d = map.dart_between(at, w).ok_or_else(|| {
                err(format_args!(
                    "{}: --toward {}: not a neighbour of {}",
                    f.file.display(),
                    args.toward.unwrap_or(0),
                    args.at
                ))
            })?;
            vec![d]
        }
        None => map.vertex_darts(at).collect(),
    };
    let mut last = TriEditError::WrongValence;
    for &d in &darts {
        match can_generate_quadruple(map, d, how) {
            Ok(()) => return Ok(d),
            Err(e) => last = e,
        }
    }
    Err(err(format_args!(
        "{}: --at {}: no 5-5-7-7 generation there: {}",
        f.file.display(),
        args.at,
        match last {
            TriEditError::WrongValence => "not a regular interior vertex (valence 6)".to_string(),
            e => why(e),
        }
    )))
}

/// Runs `zipmesh tri-generate`: a 5-5-7-7 quadruple from a regular vertex.
pub fn run_generate(args: GenerateArgs) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let mut mesh = load(f)?;
    let how = quadruple(args.config);
    let d = generation_dart(&args, &mesh.map, how)?;
    let e = generate_quadruple_with(&mut mesh.map, &mut mesh.positions, d, how).map_err(|e| {
        err(format_args!(
            "{}: --at {}: {}",
            f.file.display(),
            args.at,
            why(e)
        ))
    })?;
    let g = e.into_parts().0;
    let in_two = g.in_two_triangles(&mesh.map);
    let by = |k: usize| -> Vec<Vert> {
        let vs = g.vertices().iter().copied();
        vs.filter(|&v| mesh.map.valence(v) == k).collect()
    };
    let (fives, sevens) = (by(5), by(7));
    let ops = Ops::of(g.steps());
    finish(f, mesh, &ops, |c| {
        let four = renumber_all(c, g.vertices());
        let undo = in_two.then(|| json!({"quadruple": four}));
        let value = json!({
            "four": four,
            "v5": renumber_all(c, &fives),
            "v7": renumber_all(c, &sevens),
            "in_two_triangles": in_two,
            "undo": undo,
        });
        let undo_text = if in_two {
            format!(
                "undo: zipmesh tri-cancel {} --quadruple {} -o UNDONE",
                f.output.display(),
                list(&four)
            )
        } else {
            "undo: none (a 5-7-7-5 chain, not a quadruple in two triangles)".to_string()
        };
        let text = format!(
            "v5 at {}, v7 at {}\n{undo_text}",
            list(&renumber_all(c, &fives)),
            list(&renumber_all(c, &sevens))
        );
        (value, text)
    })
}

/// Runs `zipmesh tri-type`: type splitting or aggregation.
pub fn run_type(args: TypeArgs) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let mut mesh = load(f)?;
    let name = f.file.display();
    let (edit, what) = match (&args.split, &args.aggregate) {
        (Some(v), _) => {
            let x = verts(f, &mesh.map, "--split", &[*v], None)?[0];
            let e = split_type_with(&mut mesh.map, &mut mesh.positions, x).map_err(|e| {
                err(format_args!(
                    "{name}: --split {v}: {}",
                    type_why(e, &mesh.map, x)
                ))
            })?;
            (e.into_parts().0, "split")
        }
        (None, Some(vs)) => {
            let xs = verts(f, &mesh.map, "--aggregate", vs, None)?;
            let e = aggregate_type_with(&mut mesh.map, &mut mesh.positions, &xs).map_err(|e| {
                err(format_args!(
                    "{name}: --aggregate {}: {}",
                    list(&vs.iter().map(|&v| Some(v)).collect::<Vec<_>>()),
                    match e {
                        TriEditError::NotAPair => "not two interior v5 with a regular common \
                             neighbour one dart apart, nor three interior v5 around a triangle"
                            .to_string(),
                        e => e.to_string(),
                    }
                ))
            })?;
            (e.into_parts().0, "aggregate")
        }
        (None, None) => return Err(err("tri-type needs --split V or --aggregate A,B[,C]")),
    };
    let valences: Vec<usize> = edit
        .vertices()
        .iter()
        .map(|&v| mesh.map.valence(v))
        .collect();
    let ops = Ops::of(edit.steps());
    finish(f, mesh, &ops, |c| {
        let vs = renumber_all(c, edit.vertices());
        // A v3 or v4 split is undone by aggregation, an aggregation by a split; the v7 of a
        // vk split have no aggregation (only the input file undoes it).
        let undo = match what {
            "split" if valences.iter().all(|&k| k == 5) => Some(json!({"aggregate": vs})),
            "aggregate" => Some(json!({"split": vs.first()})),
            _ => None,
        };
        let undo_text = match &undo {
            Some(u) if what == "split" => format!(
                "undo: zipmesh tri-type {} --aggregate {} -o UNDONE",
                f.output.display(),
                list(&vs)
            ),
            Some(_) => format!(
                "undo: zipmesh tri-type {} --split {} -o UNDONE",
                f.output.display(),
                list(&vs)
            ),
            None => "undo: none (the v7 of a split have no aggregation)".to_string(),
        };
        let value = json!({
            "edit": what,
            "vertices": vs,
            "valences": valences,
            "undo": undo,
        });
        (
            value,
            format!("irregular vertices left: {}\n{undo_text}", list(&vs)),
        )
    })
}

fn type_why(e: TriEditError, map: &Map, v: Vert) -> String {
    match e {
        TriEditError::WrongValence => format!(
            "valence {}{}: a type split takes an interior v3, v4 or vk with k > 7",
            map.valence(v),
            if map.is_boundary_vertex(v) {
                " on the boundary"
            } else {
                ""
            }
        ),
        TriEditError::Irregular => {
            "no split or collapse with regular neighbours applies here".to_string()
        }
        e => e.to_string(),
    }
}

/// Runs `zipmesh tri-cancel`: a 5-5-7-7 quadruple inside two triangles removed.
pub fn run_cancel(args: CancelArgs) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let mut mesh = load(f)?;
    let four = verts(f, &mesh.map, "--quadruple", &args.quadruple, Some(4))?;
    let fives: Vec<Vert> = four
        .iter()
        .copied()
        .filter(|&v| mesh.map.valence(v) == 5)
        .collect();
    let e = remove_quadruple_with(&mut mesh.map, &mut mesh.positions, &four).map_err(|e| {
        err(format_args!(
            "{}: --quadruple {}: {}",
            f.file.display(),
            list(&args.quadruple.iter().map(|&v| Some(v)).collect::<Vec<_>>()),
            match e {
                TriEditError::NotAPair => "not two v5 and two v7 forming two triangles that \
                     share the edge of the two v7 or of the two v5"
                    .to_string(),
                e => e.to_string(),
            }
        ))
    })?;
    let r = e.into_parts().0;
    // The inverse generation: a flip between the two old v5 (now joined), or a split of the
    // kept vertex toward an old v7.
    let (at, toward, config) = match r.steps().first() {
        Some(TriRecord::Collapse(c)) => {
            let v7 = four.iter().copied().find(|v| !fives.contains(v));
            (c.kept(), v7, "split")
        }
        _ => (fives[0], fives.get(1).copied(), "flip"),
    };
    let ops = Ops::of(r.steps());
    finish(f, mesh, &ops, |c| {
        let (at, toward) = (renumber(c, at), toward.and_then(|t| renumber(c, t)));
        let value = json!({
            "quadruple": args.quadruple,
            "undo": {"at": at, "toward": toward, "config": config},
        });
        let text = format!(
            "undo: zipmesh tri-generate {} --at {} --toward {} --config {config} -o UNDONE",
            f.output.display(),
            list(&[at]),
            list(&[toward])
        );
        (value, text)
    })
}
