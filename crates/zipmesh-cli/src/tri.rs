//! `zipmesh tri-move`, `tri-generate`, `tri-type` and `tri-cancel`: the triangle paper's
//! semantic edits (`zipmesh::tri_edit`) from the command line.
//!
//! Same conventions as `zip`: 0-based vertex numbers of the file, OUT written compacted and
//! atomically after the report, exit 2 and no OUT on bad input. Vertices the edit does not
//! touch keep their positions bit for bit; a vertex an operator creates or moves is placed
//! by its rule (`TriOp::apply`). Then the edit's neighbourhood is relaxed on the input
//! surface: by default without inverting a face or thinning a triangle
//! (`geometry::relax_footprint`), with `--relax local|global` as Sec. 8 does
//! (`tri_edit::relax_local` / `relax_global`); `--no-relax` keeps the placement.

use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::process::ExitCode;
use zipmesh::geometry::{relax_footprint, RelaxOptions};
use zipmesh::io;
use zipmesh::ops::tri::TriRecord;
use zipmesh::optimize::Surface;
use zipmesh::quality::{Reference, Summary};
use zipmesh::tri_edit::{
    aggregate_type, cancel_triple_along, far_pair_inverse, far_pair_start, generate_pair,
    generate_pair_v7, generate_quadruple, generate_quadruple_apart, move_far_pair, move_pair,
    quadruple_sides, relax_global, relax_local, relax_region, remove_quadruple, split_type,
    touched_vertices, Direction, FarStart, Generation, GenerationConfig, Moved, Relaxed,
    TriEditError, TripleEdit,
};
use zipmesh::{Compaction, Dart, Map, Mesh, Vert};

use crate::out::{self, outln};
use crate::quality;
use crate::qzip::InputError;

/// The most atomic 5-7 moves `tri-cancel --triple` makes to bring a pair next to the
/// third vertex (Sec. 7.2).
const MAX_WALK: usize = 64;

/// Sweeps of `--relax local`.
const LOCAL_SWEEPS: usize = 10;

/// Solves of `--relax global` (it stops earlier when Eq. 5 no longer decreases).
const GLOBAL_SOLVES: usize = 5;

/// How `--relax` moves the vertices near the edit.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Relax {
    /// Onto the input surface and towards the neighbours' mean, a move kept only when no
    /// face inverts and no triangle's smallest angle falls below 20 degrees unless it rises
    /// (`geometry::relax_footprint`, 10 sweeps).
    Surface,
    /// One vertex at a time toward its neighbours' centroid in its tangent plane (Turk).
    Local,
    /// The quadratic energy of Eq. 5 on tangent planes, solved for all at once.
    Global,
}

impl Relax {
    fn name(self) -> &'static str {
        match self {
            Relax::Surface => "surface",
            Relax::Local => "local",
            Relax::Global => "global",
        }
    }
}

/// Input and output shared by every triangle edit.
#[derive(Args)]
pub struct Files {
    /// A triangle mesh (.obj, .off or .ply).
    file: PathBuf,
    /// Where to write the edited mesh (compacted: vertices renumbered 0..V).
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// Print one JSON value instead of text.
    #[arg(long)]
    json: bool,
    /// How the edit's neighbourhood is relaxed on the input surface afterwards: `surface`
    /// (the default) never inverts a face or thins a triangle; `local` and `global` are
    /// Sec. 8's relaxations, which may.
    #[arg(long, value_enum, default_value = "surface")]
    relax: Relax,
    /// Keep the placement: every vertex the edit does not touch keeps its position bit
    /// for bit, and a vertex an operator creates or moves stays where its rule put it.
    #[arg(long, conflicts_with_all = ["relax", "rings"])]
    no_relax: bool,
    /// How many rings around the vertices the edit touched relax too.
    #[arg(long, default_value_t = 2)]
    rings: usize,
}

/// `zipmesh tri-move`.
#[derive(Args)]
pub struct MoveArgs {
    #[command(flatten)]
    pub(crate) files: Files,
    /// The pair: two 0-based vertex numbers, interior v5 or v7. An adjacent 5-7 pair (either
    /// order) moves by atomic moves; a 5-7 pair that is not adjacent, a 5-5 or a 7-7 pair by
    /// the composite moves of Sec. 7.1 (docs/tri-edit.md).
    #[arg(long, value_delimiter = ',', num_args = 1, required = true)]
    pair: Vec<u32>,
    /// The direction, 0 to 5, counter-clockwise; for an adjacent 5-7 pair 0 is just left of
    /// the edge v5 -> v7; for a composite move the numbering of docs/tri-edit.md.
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..6))]
    direction: u8,
    /// How many steps to move (each a flip, a collapse or a split).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    steps: u32,
}

/// A configuration of generation (docs/tri-edit.md).
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Config {
    /// Regular V: flip V-W (v5 at V and W). v5 V: flip the link edge W-B. v7 V: flip V-W.
    Flip,
    /// Regular V: split V along V->W and the opposite dart. v5 V: split W along W->V and
    /// the opposite dart. v7 V: split V along V->W and four darts clockwise.
    Split,
    /// v5 V only: collapse V into W.
    Collapse,
    /// Regular V only: collapse V into W, then flip a spoke of W: a 5-7-7-5 chain, not a
    /// quadruple in two triangles (tri-cancel does not remove it).
    CollapseFlip,
}

impl From<Config> for GenerationConfig {
    fn from(c: Config) -> GenerationConfig {
        match c {
            Config::Flip => GenerationConfig::Flip,
            Config::Split => GenerationConfig::Split,
            Config::Collapse => GenerationConfig::Collapse,
            Config::CollapseFlip => GenerationConfig::CollapseFlip,
        }
    }
}

impl Config {
    fn name(self) -> &'static str {
        GenerationConfig::from(self).name()
    }
}

/// `zipmesh tri-generate`.
#[derive(Args)]
pub struct GenerateArgs {
    #[command(flatten)]
    pub(crate) files: Files,
    /// An interior vertex: regular (a 5-5-7-7 quadruple), a v5 (a 5-5-7 triple: the v5
    /// moves and generates a 5-7 pair) or a v7 (a 5-7-7 triple).
    #[arg(long)]
    at: u32,
    /// A neighbour of V that fixes the dart V->W (default: the first neighbour that works).
    #[arg(long)]
    toward: Option<u32>,
    /// The configuration.
    #[arg(long, value_enum, default_value = "flip")]
    config: Config,
    /// A regular V with --config flip or split: then walk one of the two 5-7 pairs K atomic
    /// moves away in --direction (Sec. 7.3; the four form a parallelogram, reported as
    /// `sides`).
    #[arg(long, requires = "direction")]
    apart: Option<u32>,
    /// The direction of --apart's walk, 0 to 5, numbered as tri-move's from the moving v5
    /// to its v7.
    #[arg(long, requires = "apart", value_parser = clap::value_parser!(u8).range(0..6))]
    direction: Option<u8>,
}

impl GenerateArgs {
    /// `--apart K --direction D`, when both are given (clap requires them together).
    fn walk_apart(&self) -> Option<(usize, Direction)> {
        let dir = Direction::from_index(self.direction?.into())?;
        Some((self.apart? as usize, dir))
    }
}

/// `zipmesh tri-type`.
#[derive(Args)]
#[group(id = "which", required = true, multiple = false, args = ["split", "aggregate"])]
pub struct TypeArgs {
    #[command(flatten)]
    pub(crate) files: Files,
    /// Split an interior v3 (three v5), v4 (two v5) or vk, k > 7 (k - 6 v7).
    #[arg(long)]
    split: Option<u32>,
    /// Aggregate two v5 into a v4, three v5 into a v3, or m >= 2 v7 into a v(6 + m).
    #[arg(long, value_delimiter = ',', num_args = 1)]
    aggregate: Option<Vec<u32>>,
}

/// `zipmesh tri-cancel`.
#[derive(Args)]
#[group(id = "what", required = true, multiple = false, args = ["quadruple", "triple"])]
pub struct CancelArgs {
    #[command(flatten)]
    pub(crate) files: Files,
    /// A 5-5-7-7 quadruple inside two triangles: four vertex numbers.
    #[arg(long, value_delimiter = ',', num_args = 1)]
    quadruple: Option<Vec<u32>>,
    /// A 5-5-7 triple (one v5 is left) or 5-7-7 triple (one v7 is left): three vertex
    /// numbers, an adjacent 5-7 pair among them. When the third is not next to the pair's
    /// v7 (5-5-7) or v5 (5-7-7) the pair first moves toward it (Sec. 7.2). The first v5 (v7)
    /// given is the one that moves in the cancellation.
    #[arg(long, value_delimiter = ',', num_args = 1)]
    triple: Option<Vec<u32>>,
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
    let input = load(f)?;
    let relaxed = (!f.no_relax)
        .then(|| relax(f, &input, &mut mesh))
        .transpose()?;
    let reference = Reference::new(&input);
    let quality = [&input, &mesh].map(|m| Summary::against(m, &reference));
    let c = mesh.compact();
    let pending = io::prepare_mesh(&f.output, &mesh)?;
    let (mut value, text) = report(&c);
    value["file"] = json!(f.file.display().to_string());
    value["output"] = json!(f.output.display().to_string());
    value["flips"] = json!(ops.flips);
    value["collapses"] = json!(ops.collapses);
    value["splits"] = json!(ops.splits);
    value["relax"] = relaxed.as_ref().map_or(Value::Null, |r| r.0.clone());
    value["quality"] = quality::both_json(&quality);
    if f.json {
        outln!("{value}");
    } else {
        outln!(
            "{} -> {}: {}; {text}",
            f.file.display(),
            f.output.display(),
            ops.text()
        );
        if let Some((_, line)) = &relaxed {
            outln!("{line}");
        }
        outln!("quality: {}", quality::line(&quality));
    }
    out::flush()?;
    pending.commit()?;
    Ok(ExitCode::SUCCESS)
}

/// The relaxation: the vertices the edit touched (compared with the input file) and
/// `--rings` rings around them, relaxed on the input's surface; the report's `relax` and
/// its text line.
fn relax(f: &Files, input: &Mesh, mesh: &mut Mesh) -> Result<(Value, String), InputError> {
    let touched = touched_vertices(&input.map, &mesh.map);
    let surface = Surface::new(input);
    let mode = f.relax;
    if mode == Relax::Surface {
        let before = mesh.positions.clone();
        let o = RelaxOptions {
            rings: f.rings,
            sweeps: 10,
        };
        let r = relax_footprint(mesh, &surface, &touched, o);
        let moved = (0..mesh.positions.len())
            .filter(|&i| before.get(i) != mesh.positions.get(i))
            .count();
        let value = json!({
            "mode": mode.name(), "rings": f.rings, "vertices": r.projected, "moved": moved,
            "moves": r.moves, "refused": r.refused,
        });
        let line = format!(
            "relaxed (surface, {} rings): {moved} of {} vertices moved, {} moves refused",
            f.rings, r.projected, r.refused
        );
        return Ok((value, line));
    }
    let region = relax_region(&mesh.map, &touched, f.rings);
    let r = match mode {
        Relax::Global => relax_global(mesh, &surface, &region, GLOBAL_SOLVES),
        _ => relax_local(mesh, &surface, &region, LOCAL_SWEEPS),
    };
    let r: Relaxed = r.map_err(|e| {
        err(format_args!(
            "{}: --relax {}: {e}",
            f.file.display(),
            mode.name()
        ))
    })?;
    let value = json!({
        "mode": mode.name(),
        "rings": f.rings,
        "vertices": r.movable,
        "moved": r.moved,
        "iterations": r.iterations,
        "edge_length": r.edge_length,
        "energy_before": r.energy_before,
        "energy_after": r.energy_after,
    });
    let line = format!(
        "relaxed ({}, {} rings): {} of {} vertices moved, Eq. 5 energy {:.6} -> {:.6}",
        mode.name(),
        f.rings,
        r.moved,
        r.movable,
        r.energy_before,
        r.energy_after
    );
    Ok((value, line))
}

fn list(v: &[Option<u32>]) -> String {
    v.iter()
        .map(|x| x.map_or("?".to_string(), |x| x.to_string()))
        .collect::<Vec<_>>()
        .join(",")
}

/// Runs `zipmesh tri-move`: an adjacent 5-7 pair moved `--steps` times in `--direction`
/// by atomic moves; any other pair of interior v5 / v7 (a 5-7 pair that is not adjacent,
/// a 5-5 or a 7-7 pair) by the composite moves of Sec. 7.1.
pub fn run_move(args: MoveArgs) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let mesh = load(f)?;
    let given = verts(f, &mesh.map, "--pair", &args.pair, Some(2))?;
    let (a, b) = (given[0], given[1]);
    let map = &mesh.map;
    let adjacent_57 = map.dart_between(a, b).is_some() && {
        let mut v = [map.valence(a), map.valence(b)];
        v.sort_unstable();
        v == [5, 7]
    };
    if adjacent_57 {
        move_adjacent(&args, mesh, a, b)
    } else {
        move_far(&args, mesh, a, b)
    }
}

/// The refusal of step `step` in words.
fn step_refused(args: &MoveArgs, step: u32, why: String) -> InputError {
    err(format_args!(
        "{}: --pair {},{} --direction {}: step {step} of {} refused: {why}",
        args.files.file.display(),
        args.pair[0],
        args.pair[1],
        args.direction,
        args.steps,
    ))
}

fn move_adjacent(
    args: &MoveArgs,
    mut mesh: Mesh,
    a: Vert,
    b: Vert,
) -> Result<ExitCode, InputError> {
    let swapped = mesh.map.valence(a) == 7;
    let (mut p, mut q) = if swapped { (b, a) } else { (a, b) };
    let dir = Direction::from_index(args.direction.into()).unwrap_or(Direction::SplitLeft);
    let mut ops = Ops::default();
    for step in 1..=args.steps {
        let e = move_pair(&mut mesh, p, q, dir).map_err(|e| step_refused(args, step, why(e)))?;
        ops.add(e.record().record());
        (p, q) = (e.record().p(), e.record().q());
    }
    let back = Some(dir.opposite().index());
    let (first, second) = if swapped { (q, p) } else { (p, q) };
    finish_move(args, mesh, &ops, (first, second), back)
}

/// The composite move of Sec. 7.1: direction `D` is the `D`-th of
/// `far_pair_directions` at the pipeline's start (the v5 of a 5-7 pair, the first vertex
/// of a 5-5 or 7-7 pair).
fn move_far(args: &MoveArgs, mut mesh: Mesh, a: Vert, b: Vert) -> Result<ExitCode, InputError> {
    let original = mesh.map.clone();
    let swapped = mesh.map.valence(a) == 7 && mesh.map.valence(b) == 5;
    let (mut s, mut o) = if swapped { (b, a) } else { (a, b) };
    let mut ops = Ops::default();
    for step in 1..=args.steps {
        let start = far_start(&mesh.map, s, o, args.direction.into())
            .map_err(|e| step_refused(args, step, e))?;
        let (d, how, moved) = start;
        let e = move_far_pair(&mut mesh, d, how, moved, o, MAX_WALK)
            .map_err(|e| step_refused(args, step, why(e)))?;
        let r = e.record();
        ops.add(r.generation().record());
        r.walk().moves().iter().for_each(|m| ops.add(m.record()));
        ops.add(r.walk().cancellation().removal().record());
        (s, o) = r.pair();
    }
    let back = far_pair_inverse(&mesh.map, &original, (s, o), args.steps, MAX_WALK);
    let pair = if swapped { (o, s) } else { (s, o) };
    finish_move(args, mesh, &ops, pair, back)
}

/// The start of the composite move in direction `dir` at `s`, or why there is none.
fn far_start(map: &Map, s: Vert, o: Vert, dir: usize) -> Result<FarStart, String> {
    far_pair_start(map, s, o, dir, MAX_WALK).map_err(|e| match e {
        TriEditError::NotAPair => "not a pair of interior v5 / v7 vertices (a 5-7, 5-5 or \
                                   7-7 pair)"
            .to_string(),
        e => why(e),
    })
}

/// Writes OUT and reports a pair move: the pair's new numbers in the order given and the
/// `tri-move` that undoes it (`null` when none was found).
fn finish_move(
    args: &MoveArgs,
    mesh: Mesh,
    ops: &Ops,
    pair: (Vert, Vert),
    back: Option<usize>,
) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let steps = args.steps;
    finish(f, mesh, ops, |c| {
        let pair = [renumber(c, pair.0), renumber(c, pair.1)];
        let undo = back.map(|d| json!({"pair": pair, "direction": d, "steps": steps}));
        let value = json!({
            "pair": pair,
            "direction": args.direction,
            "steps": steps,
            "undo": undo,
        });
        let undo_text = back.map_or("undo: none found (keep the input)".to_string(), |d| {
            format!(
                "undo: zipmesh tri-move {} --pair {} --direction {d} --steps {steps} -o UNDONE",
                f.output.display(),
                list(&pair)
            )
        });
        (
            value,
            format!("the pair is at {}\n{undo_text}", list(&pair)),
        )
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

/// The generation at `--at` and its dart: `at -> toward`, or the first dart of `at` whose
/// generation applies.
fn generation_dart(args: &GenerateArgs, map: &Map) -> Result<(Generation, Dart), InputError> {
    let f = &args.files;
    let at = verts(f, map, "--at", &[args.at], None)?[0];
    let k = if map.is_boundary_vertex(at) {
        0
    } else {
        map.valence(at)
    };
    let pairs_apart = matches!(args.config, Config::Flip | Config::Split) && k == 6;
    if args.apart.is_some() && !pairs_apart {
        return Err(err(format_args!(
            "{}: --at {} --apart: the pairs walk apart only from a regular interior vertex \
             with --config flip or split",
            f.file.display(),
            args.at
        )));
    }
    let how = Generation::of(k, args.config.into()).ok_or_else(|| {
        err(format_args!(
            "{}: --at {} --config {}: no such generation at {}; a regular vertex takes flip, \
             split or collapse-flip, a v5 flip, collapse or split, a v7 flip or split",
            f.file.display(),
            args.at,
            args.config.name(),
            if k == 0 {
                "a boundary vertex".to_string()
            } else {
                format!("an interior v{k}")
            }
        ))
    })?;
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
    let d = how.first_dart(map, darts, args.walk_apart()).map_err(|e| {
        err(format_args!(
            "{}: --at {}: no {} generation there: {}",
            f.file.display(),
            args.at,
            args.config.name(),
            why(e)
        ))
    })?;
    Ok((how, d))
}

/// Runs `zipmesh tri-generate`: a 5-5-7-7 quadruple from a regular vertex, or a 5-5-7 /
/// 5-7-7 triple from a v5 / v7.
pub fn run_generate(args: GenerateArgs) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let mut mesh = load(f)?;
    let (how, d) = generation_dart(&args, &mesh.map)?;
    let refused = |e: TriEditError| {
        err(format_args!(
            "{}: --at {}: {}",
            f.file.display(),
            args.at,
            why(e)
        ))
    };
    let (m, pos) = (&mut mesh.map, &mut mesh.positions);
    let triple = |moved: Vert, pair: Option<(Vert, Vert)>| {
        let (p, q) = pair.unwrap_or((moved, moved));
        [moved, p, q]
    };
    let (made, steps): (Made, Vec<TriRecord>) = match (how, args.walk_apart()) {
        (Generation::Quadruple(q), Some((k, dir))) => {
            let g = generate_quadruple_apart(&mut (&mut *m, &mut *pos), d, q, dir, k)
                .map_err(refused)?
                .into_parts()
                .0;
            let four: [Vert; 4] = g
                .vertices()
                .try_into()
                .map_err(|_| refused(TriEditError::NotAPair))?;
            let sides = quadruple_sides(m, four, 4 * k + 8);
            let back = (four[2], four[3], dir.opposite().index(), k);
            (Made::Apart(four, sides, back), g.steps().to_vec())
        }
        (_, Some(_)) => return Err(refused(TriEditError::WrongValence)),
        (Generation::Quadruple(q), None) => {
            let g = generate_quadruple(&mut (&mut *m, &mut *pos), d, q)
                .map_err(refused)?
                .into_parts()
                .0;
            let in_two = g.in_two_triangles(m);
            (
                Made::Four(g.vertices().to_vec(), in_two),
                g.steps().to_vec(),
            )
        }
        (Generation::Five(via), None) => {
            let g =
                generate_pair(&mut (&mut *m, &mut *pos), d, via, Moved::First).map_err(refused)?;
            let r = g.record();
            (Made::Three(triple(r.moved(), r.pair())), vec![*r.record()])
        }
        (Generation::Seven(via), None) => {
            let g = generate_pair_v7(&mut (&mut *m, &mut *pos), d, via, Moved::First)
                .map_err(refused)?;
            let r = g.record();
            (Made::Three(triple(r.moved(), r.pair())), vec![*r.record()])
        }
    };
    let ops = Ops::of(&steps);
    match made {
        Made::Four(four, in_two) => report_quadruple(f, mesh, &ops, four, in_two),
        Made::Three(three) => report_triple(f, mesh, &ops, three),
        Made::Apart(four, sides, back) => report_apart(f, mesh, &ops, four, sides, back),
    }
}

enum Made {
    Four(Vec<Vert>, bool),
    Three([Vert; 3]),
    /// The four in polygon order, their sides, and the walk back (pair, direction, steps).
    Apart(
        [Vert; 4],
        Option<[(usize, usize); 4]>,
        (Vert, Vert, usize, usize),
    ),
}

/// The report of `tri-generate --apart`: the four in polygon order (staying v5, v7, moving
/// v5, v7), the sides, and the way back (a walk, then a removal).
fn report_apart(
    f: &Files,
    mesh: Mesh,
    ops: &Ops,
    four: [Vert; 4],
    sides: Option<[(usize, usize); 4]>,
    back: (Vert, Vert, usize, usize),
) -> Result<ExitCode, InputError> {
    finish(f, mesh, ops, |c| {
        let four = renumber_all(c, &four);
        let pair = renumber_all(c, &[back.0, back.1]);
        let value = json!({
            "four": four,
            "v5": [four[0], four[2]],
            "v7": [four[1], four[3]],
            "in_two_triangles": false,
            "sides": sides.map(|s| s.map(|(x, y)| [x, y])),
            "undo": null,
            "walk_back": {"pair": pair, "direction": back.2, "steps": back.3},
        });
        let text = format!(
            "v5 at {}, v7 at {} (polygon {})\nundo: zipmesh tri-move {} --pair {} --direction {} \
             --steps {}, then tri-cancel --quadruple on the four",
            list(&[four[0], four[2]]),
            list(&[four[1], four[3]]),
            list(&four),
            f.output.display(),
            list(&pair),
            back.2,
            back.3
        );
        (value, text)
    })
}

fn report_quadruple(
    f: &Files,
    mesh: Mesh,
    ops: &Ops,
    four: Vec<Vert>,
    in_two: bool,
) -> Result<ExitCode, InputError> {
    let by = |k: usize| -> Vec<Vert> {
        four.iter()
            .copied()
            .filter(|&v| mesh.map.valence(v) == k)
            .collect()
    };
    let (fives, sevens) = (by(5), by(7));
    finish(f, mesh, ops, |c| {
        let four = renumber_all(c, &four);
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

fn report_triple(
    f: &Files,
    mesh: Mesh,
    ops: &Ops,
    three: [Vert; 3],
) -> Result<ExitCode, InputError> {
    finish(f, mesh, ops, |c| {
        let t = renumber_all(c, &three);
        let value = json!({
            "three": t,
            "moved": t[0],
            "pair": [t[1], t[2]],
            "undo": {"triple": t},
        });
        let text = format!(
            "the moved vertex is at {}, the new 5-7 pair at {},{}\nundo: zipmesh tri-cancel {} --triple {} -o UNDONE",
            list(&t[..1]),
            list(&t[1..2]),
            list(&t[2..]),
            f.output.display(),
            list(&t)
        );
        (value, text)
    })
}

/// Runs `zipmesh tri-type`: type splitting or aggregation.
pub fn run_type(args: TypeArgs) -> Result<ExitCode, InputError> {
    let f = &args.files;
    let mut mesh = load(f)?;
    let original = mesh.map.clone();
    let name = f.file.display();
    let edit = match (&args.split, &args.aggregate) {
        (Some(v), _) => {
            let x = verts(f, &mesh.map, "--split", &[*v], None)?[0];
            let e = split_type(&mut mesh, x).map_err(|e| {
                err(format_args!(
                    "{name}: --split {v}: {}",
                    type_why(e, &mesh.map, x)
                ))
            })?;
            e.into_parts().0
        }
        (None, Some(vs)) => {
            let xs = verts(f, &mesh.map, "--aggregate", vs, None)?;
            let e = aggregate_type(&mut mesh, &xs).map_err(|e| {
                err(format_args!(
                    "{name}: --aggregate {}: {}",
                    list(&vs.iter().map(|&v| Some(v)).collect::<Vec<_>>()),
                    match e {
                        TriEditError::NotAPair => "not two interior v5 with a regular common \
                             neighbour one dart apart, nor three interior v5 around a triangle, \
                             nor interior v7 that collapses gather (each with two of them as \
                             apexes)"
                            .to_string(),
                        e => e.to_string(),
                    }
                ))
            })?;
            e.into_parts().0
        }
        (None, None) => return Err(err("tri-type needs --split V or --aggregate A,B[,C]")),
    };
    let undoable = edit.inverse_restores(&mesh.map, &original);
    let what = if edit.is_split() {
        "split"
    } else {
        "aggregate"
    };
    let valences: Vec<usize> = edit
        .vertices()
        .iter()
        .map(|&v| mesh.map.valence(v))
        .collect();
    let ops = Ops::of(edit.steps());
    finish(f, mesh, &ops, |c| {
        let vs = renumber_all(c, edit.vertices());
        // A split is undone by aggregation, an aggregation by a split, when that gives back
        // the input up to isomorphism (gathering v7 may put the vk elsewhere).
        let undo = match what {
            "split" if undoable => Some(json!({"aggregate": vs})),
            "aggregate" if undoable => Some(json!({"split": vs.first()})),
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
            None => "undo: none (the inverse edit does not give back the input)".to_string(),
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

/// Runs `zipmesh tri-cancel`: a 5-5-7-7 quadruple inside two triangles, or an adjacent
/// 5-5-7 or 5-7-7 triple, removed.
pub fn run_cancel(args: CancelArgs) -> Result<ExitCode, InputError> {
    match (&args.quadruple, &args.triple) {
        (Some(q), _) => cancel_quadruple(&args.files, q),
        (None, Some(t)) => cancel_triple_cli(&args.files, t),
        (None, None) => Err(err(
            "tri-cancel needs --quadruple A,B,C,D or --triple A,B,C",
        )),
    }
}

fn cancel_triple_cli(f: &Files, given: &[u32]) -> Result<ExitCode, InputError> {
    let mut mesh = load(f)?;
    let original = mesh.map.clone();
    let three = verts(f, &mesh.map, "--triple", given, Some(3))?;
    let t = cancel_triple_along(&mut mesh, &three, MAX_WALK).map_err(|e| {
        err(format_args!(
            "{}: --triple {}: {}",
            f.file.display(),
            list(&given.iter().map(|&v| Some(v)).collect::<Vec<_>>()),
            match e {
                TriEditError::NotAPair => "not a 5-5-7 triple (two v5 and a v7, the v7 next to \
                     one of them) nor a 5-7-7 triple (a v5, two v7, the v5 next to one of them)"
                    .to_string(),
                TriEditError::Irregular => format!(
                    "the pair cannot be brought next to the third vertex through a regular \
                     neighbourhood within {MAX_WALK} steps (or the cancellation needs a \
                     vertex regular that is not)"
                ),
                e => why(e),
            }
        ))
    })?;
    let t = t.into_parts().0;
    let left = t.remaining();
    let walked = t.moves().len();
    let undo = t
        .inverse_generation(&mesh.map, &original)
        .map(|(d, config)| (mesh.map.dest(d), config));
    let mut steps: Vec<TriRecord> = t.moves().iter().map(|m| *m.record()).collect();
    steps.push(match t.cancellation() {
        TripleEdit::Five(m) => *m.record(),
        TripleEdit::Seven(m) => *m.record(),
    });
    let ops = Ops::of(&steps);
    let k = mesh.map.valence(left);
    finish(f, mesh, &ops, |c| {
        let at = renumber(c, left);
        let undo = undo.map(
            |(w, config)| json!({"at": at, "toward": renumber(c, w), "config": config.name()}),
        );
        let text = match &undo {
            Some(u) => format!(
                "one v{k} left at {}\nundo: zipmesh tri-generate {} --at {} --toward {} --config {} -o UNDONE",
                list(&[at]),
                f.output.display(),
                u["at"],
                u["toward"],
                u["config"].as_str().unwrap_or("?")
            ),
            None => format!(
                "one v{k} left at {} after {walked} pair moves\nundo: no single generation \
                 restores the input here (only the input file does)",
                list(&[at])
            ),
        };
        let value = json!({
            "triple": given,
            "remaining": at,
            "valence": k,
            "pair_moves": walked,
            "undo": undo,
        });
        (value, text)
    })
}

/// `tri-cancel --quadruple`.
fn cancel_quadruple(f: &Files, given: &[u32]) -> Result<ExitCode, InputError> {
    let mut mesh = load(f)?;
    let four = verts(f, &mesh.map, "--quadruple", given, Some(4))?;
    let fives: Vec<Vert> = four
        .iter()
        .copied()
        .filter(|&v| mesh.map.valence(v) == 5)
        .collect();
    let e = remove_quadruple(&mut mesh, &four).map_err(|e| {
        err(format_args!(
            "{}: --quadruple {}: {}",
            f.file.display(),
            list(&given.iter().map(|&v| Some(v)).collect::<Vec<_>>()),
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
            "quadruple": given,
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
