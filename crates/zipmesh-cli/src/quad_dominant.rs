//! `zipmesh qd-walk`: moving a triangle through a quad-dominant mesh (Q-zip paper, Sec. 3.2).

use clap::{ArgGroup, Args};
use serde_json::json;
use std::path::PathBuf;
use std::process::ExitCode;
use zipmesh::io;
use zipmesh::quad_dominant::{self, compass, Move};
use zipmesh::{Dart, Face, Map, Mesh, Vert};

use crate::out::{self, outln};
use crate::qzip::InputError;

/// `zipmesh qd-walk`.
#[derive(Args)]
#[command(group(ArgGroup::new("how").required(true).args(["moves", "to"])))]
pub struct QdWalkArgs {
    /// A quad-dominant mesh (.obj, .off or .ply).
    file: PathBuf,
    /// The triangle: a 0-based face number of the file.
    #[arg(long)]
    triangle: u32,
    /// Its tip: a 0-based vertex number, a corner of the triangle (default: the corner of
    /// highest valence; when no corner has it alone, the first corner from which the walk
    /// works).
    #[arg(long)]
    tip: Option<u32>,
    /// The moves, comma-separated, in order: VE (towards the tip), EV (towards the base),
    /// LE, RE (onto the quad across the left, right side).
    #[arg(long = "move", value_delimiter = ',')]
    moves: Option<Vec<Move>>,
    /// Make the moves this many times.
    #[arg(long, default_value_t = 1, conflicts_with = "to")]
    steps: usize,
    /// Walk the triangle's tip to this vertex along shortest paths (the quad-dominant compass).
    #[arg(long)]
    to: Option<u32>,
    /// Where to write the edited mesh (compacted: vertices and faces renumbered).
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// The tip darts to try for face `f`: the one leaving `tip`; else the default tip (the
/// corner of highest valence); else, when no corner has it alone, all three corners.
fn tip_darts(map: &Map, f: Face, tip: Option<u32>, name: &str) -> Result<Vec<Dart>, InputError> {
    let bad = |m: String| InputError(format!("{name}: {m}"));
    if !map.is_live_face(f) {
        return Err(bad(format!(
            "--triangle {}: no such face (the file has {} faces)",
            f.index(),
            map.face_slots()
        )));
    }
    if map.degree(f) != 3 {
        return Err(bad(format!(
            "--triangle {}: not a triangle ({} corners)",
            f.index(),
            map.degree(f)
        )));
    }
    match tip {
        Some(v) => map
            .face_darts(f)
            .find(|&d| map.origin(d) == Vert::new(v))
            .map(|d| vec![d])
            .ok_or_else(|| {
                bad(format!(
                    "--tip {v} is not a corner of triangle {}",
                    f.index()
                ))
            }),
        None => Ok(quad_dominant::default_tip(map, f)
            .map_or_else(|| map.face_darts(f).collect(), |d| vec![d])),
    }
}

/// Runs the walk from each of `tips` on a copy of `original` until one works: the mesh it
/// left, the tip it started from, its end tip and moves. With one tip its error is the
/// error; with several (no corner of highest valence alone) the error names each tip's.
fn walk_from_some(
    original: &Mesh,
    tips: &[Dart],
    args: &QdWalkArgs,
    name: &str,
) -> Result<(Mesh, Dart, Dart, Vec<Move>), InputError> {
    let mut why = Vec::new();
    for &t in tips {
        let mut mesh = original.clone();
        match walk(&mut mesh, t, args) {
            Ok((tip, done)) => return Ok((mesh, t, tip, done)),
            Err(e) => why.push(format!("tip {}: {e}", original.map.origin(t).index())),
        }
    }
    Err(InputError(match why.as_slice() {
        [one] => format!(
            "{name}: {}",
            one.split_once(": ").map_or(one.as_str(), |x| x.1)
        ),
        _ => format!(
            "{name}: triangle {}: no corner has the highest valence alone, and the walk fails \
             from each as the tip: {}",
            args.triangle,
            why.join("; ")
        ),
    }))
}

/// Makes the moves (`--move`, `--steps`) or the compass walk (`--to`); the moves made, or
/// why not (without the file's name).
fn walk(mesh: &mut Mesh, t: Dart, a: &QdWalkArgs) -> Result<(Dart, Vec<Move>), String> {
    if let Some(v) = a.to {
        let target = Vert::new(v);
        if !mesh.map.is_live_vertex(target) {
            return Err(format!("--to {v}: no such vertex"));
        }
        let w = compass::walk_to(mesh, t, target)
            .map_err(|e| format!("the walk to {v} failed: {e}"))?;
        return Ok((w.tip(), w.moves()));
    }
    let seq = a.moves.as_deref().unwrap_or_default();
    let mut done = Vec::new();
    let mut tip = t;
    for _ in 0..a.steps {
        for &mv in seq {
            let e = mv
                .apply(mesh, tip)
                .map_err(|r| format!("move {} ({mv}) was refused: {r}", done.len() + 1))?;
            tip = e.record().tip();
            done.push(mv);
        }
    }
    Ok((tip, done))
}

/// The face, tip vertex and undo sequence after compaction, and whether the undo restores
/// `original` (simulated on the compacted map).
fn undo_of(
    mesh: &Mesh,
    tip: Dart,
    done: &[Move],
    original: &Map,
) -> (Option<u32>, Option<u32>, Option<Vec<Move>>) {
    let face = mesh.map.face(tip).map(|f| f.index() as u32);
    let tip_v = Some(mesh.map.origin(tip).index() as u32);
    let back = compass::reverse_restores(&mesh.map, tip, done, original);
    (face, tip_v, back)
}

fn names(moves: &[Move]) -> String {
    moves.iter().map(|m| m.name()).collect::<Vec<_>>().join(",")
}

/// Runs `zipmesh qd-walk`.
pub fn run_qd_walk(args: QdWalkArgs) -> Result<ExitCode, InputError> {
    let name = args.file.display().to_string();
    let (original, _) = io::read_mesh(&args.file)?;
    let tips = tip_darts(&original.map, Face::new(args.triangle), args.tip, &name)?;
    let (mut mesh, start, tip, done) = walk_from_some(&original, &tips, &args, &name)?;
    let start = original.map.origin(start).index();
    // The tip the walk started from, when no corner had the highest valence alone.
    let chosen = (tips.len() > 1).then_some(start);
    let c = mesh.compact();
    let tip = c.darts.get(tip.index()).copied().flatten().unwrap_or(tip);
    let (face, tip_v, undo) = undo_of(&mesh, tip, &done, &original.map);
    let pending = io::prepare_mesh(&args.output, &mesh)?;
    let undo_json = undo
        .as_ref()
        .map(|u| json!({"triangle": face, "tip": tip_v, "move": names(u)}));
    if args.json {
        outln!(
            "{}",
            json!({
                "file": name,
                "output": args.output.display().to_string(),
                "moves": done.iter().map(|m| m.name()).collect::<Vec<_>>(),
                "start_tip": start,
                "triangle": face,
                "tip": tip_v,
                "undo": undo_json,
            })
        );
    } else {
        if let Some(v) = chosen {
            outln!(
                "tip {v}: no corner of triangle {} has the highest valence alone, and the \
                 walk works from this one (name another with --tip)",
                args.triangle
            );
        }
        outln!(
            "{name} -> {}: {} move(s) {}; the triangle is face {} with tip {}",
            args.output.display(),
            done.len(),
            names(&done),
            face.map_or("?".into(), |f| f.to_string()),
            tip_v.map_or("?".into(), |v| v.to_string())
        );
        match &undo {
            Some(u) if !u.is_empty() => outln!(
                "undo: zipmesh qd-walk {} --triangle {} --tip {} --move {} -o UNDONE",
                args.output.display(),
                face.unwrap_or(0),
                tip_v.unwrap_or(0),
                names(u)
            ),
            Some(_) => outln!("undo: nothing to undo"),
            None => outln!("undo: the reverse moves do not restore the input here"),
        }
    }
    out::flush()?;
    pending.commit()?;
    Ok(ExitCode::SUCCESS)
}
