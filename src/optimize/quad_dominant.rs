//! Quad-dominant input (Tarini et al. 2010, Sec. 6.1; Q-zip paper, Sec. 3.2): before the
//! batches, pairs of triangles crawl towards each other by triangle moves
//! ([`crate::quad_dominant::move_triangle`]) until they share an edge, and merge
//! ([`crate::quad_dominant::merge_collision`]), so that a mesh with an even number of triangles can
//! come out pure quad.
//!
//! A crawl is greedy: at each step it tries the four moves of both triangles and takes one
//! that makes them collide, or else the one that brings the tips nearest (then the corners),
//! never returning to a pair of tip darts it had; up to six moves may go uphill, to leave a
//! local minimum; it is all or nothing. A merge is kept only
//! if the constraints still hold and the interior singularities plus boundary defects
//! ([`SingularityCounts`]) did not grow; otherwise every move of the crawl is undone and the
//! pair is not tried again.

use alloc::collections::VecDeque;
use alloc::vec::Vec;

use hashbrown::HashMap;

use super::{Constraints, SingularityCounts};
use crate::geometry::Surface;
use crate::map::{Dart, Face, Map, Vert};
use crate::mesh::Edited;
use crate::quad_dominant::{self, Move, TriangleMove};
use crate::Mesh;

/// How far (edges) two triangles may be apart to be paired.
const RADIUS: usize = 64;

/// How many moves of a crawl may raise the potential.
const ESCAPES: usize = 6;

/// What the triangle stage did.
///
/// ```
/// use zipmesh::{gen, optimize::{optimize, Constraints, OptimizeOptions}};
/// let (mut mesh, _) = gen::quad_dominant(12, 12, 1, 4);
/// let out = optimize(&mut mesh, Constraints::default(), OptimizeOptions::default().batches(1), |_| {}).unwrap();
/// let t = out.triangles;
/// assert_eq!(t.input, 2);
/// assert_eq!(t.input - 2 * t.merged, out.final_counts.triangles);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct TriangleStage {
    /// Triangles of the input.
    pub input: usize,
    /// Pairs merged.
    pub merged: usize,
    /// Triangle moves kept (the crawls of the merged pairs).
    pub moves: usize,
    /// Pairs whose crawl or merge failed or was not kept (each tried once).
    pub refused: usize,
    /// Whether the run was made again from the input with each merge guarded: the first
    /// run's output had more folded quads than the input ([`super::optimize`]).
    pub guarded: bool,
}

/// Breadth-first search from the vertices of `from`, up to [`RADIUS`] edges: the first
/// vertex (nearest first) for which `hit` gives a value, with its distance.
fn search<T>(map: &Map, from: &[Vert], hit: impl Fn(Vert) -> Option<T>) -> Option<(usize, T)> {
    let mut seen: HashMap<Vert, usize> = from.iter().map(|&v| (v, 0)).collect();
    let mut queue: VecDeque<Vert> = from.iter().copied().collect();
    while let Some(v) = queue.pop_front() {
        let d = seen[&v];
        if let Some(x) = hit(v) {
            return Some((d, x));
        }
        if d >= RADIUS {
            continue;
        }
        for e in map.vertex_darts(v) {
            let w = map.dest(e);
            if !seen.contains_key(&w) {
                seen.insert(w, d + 1);
                queue.push_back(w);
            }
        }
    }
    None
}

/// Breadth-first distance from any vertex of `from` to any of `to`, up to [`RADIUS`]
/// (`usize::MAX` past it).
fn gap(map: &Map, from: &[Vert], to: &[Vert]) -> usize {
    search(map, from, |v| to.contains(&v).then_some(())).map_or(usize::MAX, |(d, ())| d)
}

fn corners(map: &Map, t: Dart) -> [Vert; 3] {
    [map.origin(t), map.dest(t), map.dest(map.next(t))]
}

/// How far apart two triangles are: their tips, then their nearest corners.
fn potential(map: &Map, a: Dart, b: Dart) -> (usize, usize) {
    let tips = gap(map, &[map.origin(a)], &[map.origin(b)]);
    (tips, gap(map, &corners(map, a), &corners(map, b)))
}

/// The best next move of the pair `(i, j)` to a state not visited: `(which, move, uphill)`,
/// `uphill` when it raises the potential; `None` when no move applies.
fn best_step(
    mesh: &mut Mesh,
    tips: &[Dart],
    i: usize,
    j: usize,
    visited: &[(Dart, Dart)],
) -> Option<(usize, Move, bool)> {
    let here = potential(&mesh.map, tips[i], tips[j]);
    let mut best: Option<((usize, usize), usize, Move)> = None;
    for (k, other) in [(i, j), (j, i)] {
        for mv in Move::ALL {
            // A probe on the map alone (positions play no part in the potential).
            let probe = quad_dominant::probe_move(&mut mesh.map, tips[k], mv, |map, e| {
                let (t, o) = (e.tip(), e.follow(tips[other]));
                let state = if k == i { (t, o) } else { (o, t) };
                let collides = quad_dominant::collision(map, t, o).is_some();
                (
                    state,
                    if collides {
                        (0, 0)
                    } else {
                        potential(map, t, o)
                    },
                )
            });
            let Ok((state, p)) = probe else {
                continue;
            };
            let fresh = !visited.contains(&state);
            if fresh && best.is_none_or(|b| p < b.0) {
                best = Some((p, k, mv));
            }
        }
    }
    best.map(|(p, k, mv)| (k, mv, p > here))
}

/// Undoes the crawl's moves, last first.
fn undo_all(mesh: &mut Mesh, edits: &[Edited<TriangleMove>]) {
    for e in edits.iter().rev() {
        let _ = e.undo(mesh);
    }
}

/// The combinatorial singularity measure a merge may not raise.
fn irregularity(mesh: &Mesh) -> usize {
    let c = SingularityCounts::of(mesh);
    c.singularities() + c.boundary_defects
}

/// Crawls triangles `i` and `j` together and merges them; on success `tips` holds the
/// other triangles' tip darts and the number of moves is returned; on failure mesh and
/// `tips` are as they were.
fn crawl_and_merge(
    mesh: &mut Mesh,
    tips: &mut Vec<Dart>,
    i: usize,
    j: usize,
    constraints: &Constraints,
    guard: Option<&Surface>,
) -> Option<usize> {
    let saved = tips.clone();
    let before = irregularity(mesh);
    let guarded = guard.map(|s| (s, mesh.clone(), super::folds::unsound_quads(mesh)));
    let start = potential(&mesh.map, tips[i], tips[j]).0;
    let limit = 4 * start.min(RADIUS) + 16;
    let mut edits = Vec::new();
    let mut visited = alloc::vec![(tips[i], tips[j])];
    // A few moves uphill get a pair out of a local minimum of the potential.
    let mut uphill = ESCAPES;
    while quad_dominant::collision(&mesh.map, tips[i], tips[j]).is_none() && edits.len() < limit {
        let Some((k, mv, up)) = best_step(mesh, tips, i, j, &visited) else {
            break;
        };
        if up {
            if uphill == 0 {
                break;
            }
            uphill -= 1;
        }
        let Ok(e) = mv.apply(mesh, tips[k]) else {
            break;
        };
        for t in tips.iter_mut() {
            *t = e.record().follow(*t);
        }
        tips[k] = e.record().tip();
        visited.push((tips[i], tips[j]));
        edits.push(e);
    }
    if quad_dominant::collision(&mesh.map, tips[i], tips[j]).is_some() {
        if let Ok(rec) = quad_dominant::merge_collision(&mut mesh.map, tips[i], tips[j]) {
            if constraints.holds(mesh) && irregularity(mesh) <= before {
                if let Some((surface, before_mesh, folds)) = guarded {
                    super::relax_edited(mesh, &before_mesh, surface, constraints);
                    if super::folds::unsound_quads(mesh).rises_from(folds) {
                        *mesh = before_mesh;
                        *tips = saved;
                        return None;
                    }
                }
                let rest = tips.iter().enumerate().filter(|&(k, _)| k != i && k != j);
                *tips = rest.map(|(_, &t)| rec.follow(t)).collect();
                return Some(edits.len());
            }
            let _ = rec.undo(&mut mesh.map);
        }
    }
    undo_all(mesh, &edits);
    *tips = saved;
    None
}

/// The nearest triangle to triangle `i` by tip distance (up to [`RADIUS`]) whose pair with
/// `i` was not tried yet: `(distance, j)`. One breadth-first search from `i`'s tip.
fn nearest(
    map: &Map,
    tips: &[Dart],
    i: usize,
    untried: impl Fn(usize) -> bool,
) -> Option<(usize, usize)> {
    let start = map.origin(tips[i]);
    search(map, &[start], |v| {
        (0..tips.len()).find(|&j| j != i && map.origin(tips[j]) == v && untried(j))
    })
}

/// The closest pair of triangles not tried yet, by tip distance (ties: the lowest index).
fn closest_pair(map: &Map, tips: &[Dart], tried: &[(Face, Face)]) -> Option<(usize, usize)> {
    let pair = |i: usize, j: usize| (map.face(tips[i.min(j)]), map.face(tips[i.max(j)]));
    let untried = |i: usize, j: usize| match pair(i, j) {
        (Some(a), Some(b)) => !tried.contains(&(a, b)),
        _ => false,
    };
    let mut best: Option<(usize, usize, usize)> = None;
    for i in 0..tips.len() {
        if let Some((d, j)) = nearest(map, tips, i, |j| untried(i, j)) {
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, i.min(j), i.max(j)));
            }
        }
    }
    best.map(|(_, i, j)| (i, j))
}

/// Merges pairs of triangles of `mesh`, closest first, each pair tried once. With a `guard`
/// (the input surface), each merged crawl is relaxed on it at once and undone if more quads
/// of the mesh are folded than before it ([`super::folds::FoldCount`]).
pub(crate) fn pair_triangles(
    mesh: &mut Mesh,
    constraints: &Constraints,
    guard: Option<&Surface>,
) -> TriangleStage {
    let map = &mesh.map;
    let mut tips: Vec<Dart> = quad_dominant::triangles(map)
        .into_iter()
        .map(|f| quad_dominant::default_tip(map, f).unwrap_or(map.face_dart(f)))
        .collect();
    let mut stage = TriangleStage {
        input: tips.len(),
        ..TriangleStage::default()
    };
    let mut tried = Vec::new();
    while let Some((i, j)) = closest_pair(&mesh.map, &tips, &tried) {
        let faces = (mesh.map.face(tips[i]), mesh.map.face(tips[j]));
        match crawl_and_merge(mesh, &mut tips, i, j, constraints, guard) {
            Some(moves) => {
                stage.merged += 1;
                stage.moves += moves;
            }
            None => {
                if let (Some(a), Some(b)) = faces {
                    tried.push((a, b));
                }
                stage.refused += 1;
            }
        }
    }
    stage
}
