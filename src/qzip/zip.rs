//! The four stages in one call, and the four movements of a pair.

use core::fmt;

use super::compass::{plan, PlanError, Tag};
use super::execute::{execute_owned, ZipError, ZipReport};
use super::prepare::{prepare, PrepareError};
use super::sketch::{sketch, Path, SketchError, SketchOptions, SketchWorkspace};
use alloc::vec::Vec;
use glam::DVec3;

use crate::invariants::canonical::CanonicalCode;
use crate::invariants::{is_irregular, MeshKind};
use crate::ops::quad::{remove_valence2, split_high_valence, QuadRecord};
use crate::ops::Refusal;
use crate::{Dart, Map, Mesh, Vert};

/// Why a Q-zip was refused, by stage; the map is unchanged in every case.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{zip, QzipError, SketchOptions, Tag};
/// let mut map = gen::torus_grid(6, 6).map;
/// // A regular torus has no singularity to move.
/// let e = zip(&mut map, Vert::new(0), Vert::new(2), Tag::LC, &SketchOptions::default());
/// assert!(matches!(e, Err(QzipError::Prepare(_))));
/// assert!(e.unwrap_err().to_string().contains("valence 4"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum QzipError {
    /// Stage 1: no path.
    Sketch(SketchError),
    /// Stage 2: the compass cannot be carried along the path.
    Plan(PlanError),
    /// Stage 3: the ends cannot be adjusted.
    Prepare(PrepareError),
    /// Stage 4: an operation is not realizable.
    Execute(ZipError),
}

impl fmt::Display for QzipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Sketch(e) => write!(f, "sketching: {e}"),
            Self::Plan(e) => write!(f, "planning: {e}"),
            Self::Prepare(e) => write!(f, "preparation: {e}"),
            Self::Execute(e) => write!(f, "execution: {e}"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for QzipError {}

/// Runs stages 2 to 4 along a given path with the initial operation `initial`.
///
/// All or nothing: on an error the map is unchanged.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, zip_along, SketchOptions, Tag};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let path = sketch(&map, v3, v5, &SketchOptions::default()).unwrap();
/// let r = zip_along(&mut map, &path, Tag::RS).unwrap();
/// assert_eq!(map.valence(r.moved_to()), 5);
/// ```
pub fn zip_along(map: &mut Map, path: &Path, initial: Tag) -> Result<ZipReport, QzipError> {
    let p = plan(map, path, initial).map_err(QzipError::Plan)?;
    let s = prepare(map, &p).map_err(QzipError::Prepare)?;
    execute_owned(map, s).map_err(QzipError::Execute)
}

/// Runs the four stages: the path from `from` to `to` sketched with `opts`, then
/// [`zip_along`] it with the initial operation `initial`.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{zip, SketchOptions, Tag};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let r = zip(&mut map, v3, v5, Tag::LC, &SketchOptions::default()).unwrap();
/// assert_eq!(map.valence(r.moved_from()), 3);
/// ```
pub fn zip(
    map: &mut Map,
    from: Vert,
    to: Vert,
    initial: Tag,
    opts: &SketchOptions,
) -> Result<ZipReport, QzipError> {
    let path = sketch(map, from, to, opts).map_err(QzipError::Sketch)?;
    zip_along(map, &path, initial)
}

/// [`zip`] with the sketch done in a reusable [`SketchWorkspace`] (the same path, without
/// per-call allocation proportional to the explored region): for many Q-zips on one large
/// map. With a [`super::Guide`] in `opts` the sketch explores about O(path length) vertices.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{zip, zip_with, SketchOptions, SketchWorkspace, Tag};
/// let mut ws = SketchWorkspace::new();
/// let mut a = gen::subdivided_icosahedron(2).map;
/// let mut b = a.clone();
/// let (v5, v3) = (Vert::new(0), Vert::new(42));
/// let o = SketchOptions::default();
/// let ra = zip_with(&mut ws, &mut a, v3, v5, Tag::LC, &o).unwrap();
/// let rb = zip(&mut b, v3, v5, Tag::LC, &o).unwrap();
/// assert_eq!((a, ra), (b, rb));
/// ```
pub fn zip_with(
    ws: &mut SketchWorkspace,
    map: &mut Map,
    from: Vert,
    to: Vert,
    initial: Tag,
    opts: &SketchOptions<'_>,
) -> Result<ZipReport, QzipError> {
    let path = ws.sketch(map, from, to, opts).map_err(QzipError::Sketch)?;
    zip_along(map, &path, initial)
}

/// One of the four movements of a pair: the initial operation and its outcome (the edited
/// copy of the map and the report, or the refusal).
///
/// See [`moves`] for an example.
#[derive(Clone, Debug)]
pub struct Move {
    /// The initial operation.
    pub tag: Tag,
    /// The edited copy and the report, or why this movement is not realizable.
    pub outcome: Result<(Map, ZipReport), QzipError>,
}

/// The four movements of the pair at the ends of `path`: each initial operation in compass
/// order (LS, RC, LC, RS), run on a copy of the map.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{moves, sketch, SketchOptions};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let path = sketch(&map, v3, v5, &SketchOptions::default()).unwrap();
/// let all = moves(&map, &path);
/// assert_eq!(all.len(), 4);
/// assert!(all.iter().any(|m| m.outcome.is_ok()));
/// ```
pub fn moves(map: &Map, path: &Path) -> [Move; 4] {
    Tag::CCW.map(|tag| {
        let mut copy = map.clone();
        let outcome = zip_along(&mut copy, path, tag).map(|r| (copy, r));
        Move { tag, outcome }
    })
}

/// A Q-zip run that undoes another: a path from the moved terminal singularity to the moved
/// initial one, and the initial operation to run along it.
///
/// See [`find_reverse`] for an example.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReverseRun {
    /// The reverse path, in the edited map.
    pub path: Path,
    /// The initial operation of the reverse run.
    pub tag: Tag,
}

/// Finds the Q-zip that reverses an edit (Sec. 2.8): along a path from the moved terminal
/// singularity back to the moved initial one, the initial operation whose result is
/// isomorphic to `original`; `None` if no candidate restores it.
///
/// The candidate paths are images of the surgery path, in order: the shortest path keeping
/// to the edit's scar and surviving path vertices; the same with the other singularities
/// blocked; the surviving path vertices read backwards; shortest paths with and without the
/// blocking; then those with the singularities they run through passed on either side; last
/// a bounded search near the scar. Along each, the compass rotated by pi (the surgery's last
/// hand, rotated) is tried first, then the other three. `docs/qzip.md` gives the details and
/// what was measured (every movement on the real meshes as given is reversed).
///
/// `edited` is the map after the edit that `report` describes, `original` the map before.
///
/// ```
/// use zipmesh::{gen, is_isomorphic};
/// use zipmesh::qzip::{find_reverse, zip_along, sketch, SketchOptions, Tag};
/// let original = gen::cube(4).map;
/// let (a, b) = (zipmesh::Vert::new(0), zipmesh::Vert::new(4));
/// let path = sketch(&original, a, b, &SketchOptions::default()).unwrap();
/// let mut edited = original.clone();
/// let r = zip_along(&mut edited, &path, Tag::LS).unwrap();
/// let back = find_reverse(&edited, &r, &original).unwrap();
/// let mut m = edited.clone();
/// zip_along(&mut m, &back.path, back.tag).unwrap();
/// assert!(is_isomorphic(&m, &original));
/// ```
pub fn find_reverse(edited: &Map, report: &ZipReport, original: &Map) -> Option<ReverseRun> {
    let target = CanonicalCode::of(original);
    let first = report
        .surgery()
        .steps()
        .last()
        .map(|s| s.hand.rotate_pi())
        .unwrap_or(Tag::LS);
    let order = [first, first.ccw(), first.ccw().ccw(), first.cw()];
    let mut tried: Vec<Path> = Vec::new();
    let mut try_path = |path: Path| {
        if tried.contains(&path) {
            return None;
        }
        let found = order.into_iter().find_map(|tag| {
            let mut m = edited.clone();
            zip_along(&mut m, &path, tag).ok()?;
            (CanonicalCode::of(&m) == target).then(|| ReverseRun {
                path: path.clone(),
                tag,
            })
        });
        tried.push(path);
        found
    };
    let (from, to) = (report.moved_to(), report.moved_from());
    let image = image_options(edited, report, from, to);
    // The first image restores in most cases: the others are built only when it does not.
    let first = sketch(edited, from, to, &image).ok();
    if let Some(r) = first.clone().and_then(&mut try_path) {
        return Some(r);
    }
    // Singularities other than the pair: the forward path passed them on one side; a
    // reverse path through one (where the forward path did not run) reads the compass
    // there by the counting rule and may take the other side.
    let blocked: Vec<u32> = edited
        .vertices()
        .filter(|&v| v != from && v != to && is_irregular(edited, MeshKind::Quad, v))
        .flat_map(|v| edited.vertex_darts(v).map(|d| (d.index() / 2) as u32))
        .collect();
    let block = |o: &SketchOptions<'static>| SketchOptions {
        forbidden_edges: blocked.clone(),
        ..o.clone()
    };
    let plain = SketchOptions::default();
    let others: [&dyn Fn() -> Option<Path>; 5] = [
        &|| sketch(edited, from, to, &block(&image)).ok(),
        &|| literal_image(edited, report, &plain),
        &|| sketch(edited, from, to, &block(&plain)).ok(),
        &|| literal_image(edited, report, &block(&image)),
        &|| sketch(edited, from, to, &plain).ok(),
    ];
    let mut candidates: Vec<Path> = first.into_iter().collect();
    for make in others {
        if let Some(c) = make() {
            if let Some(r) = try_path(c.clone()) {
                return Some(r);
            }
            candidates.push(c);
        }
    }
    // Then each candidate with the singularities it runs through passed on either side.
    for c in &candidates {
        for p in pushed_off(edited, c) {
            if let Some(r) = try_path(p) {
                return Some(r);
            }
        }
    }
    // Last, a bounded search near the image: simple paths inside the scar, the surviving
    // path vertices and their one-rings, at most two edges longer than the shortest
    // candidate (or as long as the surgery), those keeping most to the surviving path first.
    let shortest = candidates.iter().map(Path::len).min()?;
    let forward = report.surgery().steps().len().saturating_sub(1);
    near_paths(edited, report, (shortest + 2).max(forward), 256)
        .into_iter()
        .find_map(&mut try_path)
}

/// Simple paths from the moved terminal to the moved initial singularity through the
/// vertices near the edit (scar, surviving path, and their neighbours) of at most `max_len`
/// edges: at most `cap` of them, fewest vertices off the surviving path first, then shortest.
fn near_paths(edited: &Map, report: &ZipReport, max_len: usize, cap: usize) -> Vec<Path> {
    let (from, to) = (report.moved_to(), report.moved_from());
    let slots = edited.vertex_slots();
    let mut on_path = alloc::vec![false; slots];
    for s in report.surgery().steps() {
        if let Some(x) = on_path.get_mut(s.vertex.index()) {
            *x = edited.is_live_vertex(s.vertex);
        }
    }
    let mut core_set: Vec<Vert> = report
        .surgery()
        .steps()
        .iter()
        .map(|s| s.vertex)
        .filter(|&v| edited.is_live_vertex(v))
        .chain([from, to])
        .collect();
    for &f in report.scar_faces() {
        core_set.extend(edited.face_darts(f).map(|d| edited.origin(d)));
    }
    for &e in report.scar_edges() {
        let d = Dart::new(2 * e as u32);
        core_set.extend([edited.origin(d), edited.dest(d)]);
    }
    let mut allowed = alloc::vec![false; slots];
    for &v in &core_set {
        for d in edited.vertex_darts(v) {
            allowed[edited.dest(d).index()] = true;
        }
        allowed[v.index()] = true;
    }
    // Distances to `to` inside the allowed set prune the enumeration.
    let mut dist = alloc::vec![usize::MAX; slots];
    let mut queue = alloc::collections::VecDeque::from([to]);
    dist[to.index()] = 0;
    while let Some(v) = queue.pop_front() {
        for d in edited.vertex_darts(v) {
            let w = edited.dest(d);
            if allowed[w.index()] && dist[w.index()] == usize::MAX {
                dist[w.index()] = dist[v.index()] + 1;
                queue.push_back(w);
            }
        }
    }
    let mut found: Vec<(usize, Vec<Vert>)> = Vec::new();
    let mut stack: Vec<Vert> = alloc::vec![from];
    let mut visiting = alloc::vec![false; slots];
    visiting[from.index()] = true;
    // Iterative depth-first enumeration: (vertex's remaining darts) per level.
    let mut iters: Vec<Vec<Vert>> =
        alloc::vec![edited.vertex_darts(from).map(|d| edited.dest(d)).collect()];
    let limit = 16 * cap;
    while let Some(top) = iters.last_mut() {
        let Some(w) = top.pop() else {
            iters.pop();
            if let Some(v) = stack.pop() {
                visiting[v.index()] = false;
            }
            continue;
        };
        let depth = stack.len();
        if !allowed[w.index()] || visiting[w.index()] || dist[w.index()] == usize::MAX {
            continue;
        }
        if depth + dist[w.index()] > max_len {
            continue;
        }
        if w == to {
            let mut p = stack.clone();
            p.push(w);
            let off = p.iter().filter(|v| !on_path[v.index()]).count();
            found.push((off, p));
            if found.len() >= limit {
                break;
            }
            continue;
        }
        stack.push(w);
        visiting[w.index()] = true;
        iters.push(edited.vertex_darts(w).map(|d| edited.dest(d)).collect());
    }
    found.sort_by_key(|(off, p)| (*off, p.len()));
    let opts = SketchOptions::default();
    found
        .into_iter()
        .take(cap)
        .filter_map(|(_, p)| super::sketch::validate_path(edited, from, to, &p, &opts).ok())
        .collect()
}

/// Sketch options for the image of the surgery path: unit weight on edges between vertices
/// of the edit's scar and surviving path, a high weight elsewhere.
fn image_options(edited: &Map, report: &ZipReport, from: Vert, to: Vert) -> SketchOptions<'static> {
    let mut near = alloc::vec![false; edited.vertex_slots()];
    let mut mark = |v: Vert| {
        if let Some(x) = near.get_mut(v.index()) {
            *x = true;
        }
    };
    for s in report.surgery().steps() {
        if edited.is_live_vertex(s.vertex) {
            mark(s.vertex);
        }
    }
    for &f in report.scar_faces() {
        for d in edited.face_darts(f) {
            mark(edited.origin(d));
        }
    }
    for &e in report.scar_edges() {
        let d = Dart::new(2 * e as u32);
        mark(edited.origin(d));
        mark(edited.dest(d));
    }
    mark(from);
    mark(to);
    let weights: Vec<f64> = (0..edited.dart_slots() / 2)
        .map(|e| {
            let d = Dart::new(2 * e as u32);
            let inside = |v: Vert| near.get(v.index()).copied().unwrap_or(false);
            if edited.is_live_dart(d) && inside(edited.origin(d)) && inside(edited.dest(d)) {
                1.0
            } else {
                1000.0
            }
        })
        .collect();
    SketchOptions {
        weights: Some(weights),
        ..SketchOptions::default()
    }
}

/// Variants of `path` passing each irregular interior vertex on its left or on its right
/// instead (round its one-ring), at most the first three such vertices (8 variants).
fn pushed_off(map: &Map, path: &Path) -> Vec<Path> {
    let v = path.vertices();
    let sing: Vec<usize> = (1..v.len().saturating_sub(1))
        .filter(|&i| is_irregular(map, MeshKind::Quad, v[i]))
        .take(3)
        .collect();
    let mut out = Vec::new();
    for mask in 0u32..(1 << sing.len()) {
        let mut walk: Vec<Vert> = Vec::with_capacity(v.len() + 8);
        let mut ok = true;
        for (i, &x) in v.iter().enumerate() {
            let Some(k) = sing.iter().position(|&s| s == i) else {
                walk.push(x);
                continue;
            };
            // Round the one-ring from the incoming to the outgoing neighbour: through the
            // faces on the path's left (counter-clockwise from the outgoing edge) or right.
            let (din, dout) = (path.darts()[i - 1].twin(), path.darts()[i]);
            let left = mask & (1 << k) != 0;
            let (a, b) = if left { (dout, din) } else { (din, dout) };
            let mut d = a;
            let mut ring: Vec<Vert> = Vec::new();
            for _ in 0..map.valence(x) {
                if d == b {
                    break;
                }
                let Some(_) = map.face(d) else {
                    ok = false;
                    break;
                };
                // The face of `d` is on d's left: walk its boundary from dest(d) round to
                // the next spoke's end.
                let mut e = map.next(d);
                while map.dest(e) != x {
                    ring.push(map.dest(e));
                    e = map.next(e);
                }
                d = map.rotate_ccw(d);
            }
            if !ok || d != b {
                ok = false;
                break;
            }
            // `ring` runs from a's end to b's end (exclusive of a's end, inclusive of b's).
            if left {
                ring.pop();
                ring.reverse();
            } else {
                ring.pop();
            }
            walk.extend(ring);
        }
        if !ok {
            continue;
        }
        let simple = cut_loops(walk, path.end());
        let opts = SketchOptions::default();
        if let Ok(p) = super::sketch::validate_path(map, path.start(), path.end(), &simple, &opts) {
            out.push(p);
        }
    }
    out
}

/// The walk with its loops cut (a vertex met again goes back to its first visit), up to the
/// first visit of `end`: a simple walk.
fn cut_loops(walk: Vec<Vert>, end: Vert) -> Vec<Vert> {
    let mut simple: Vec<Vert> = Vec::with_capacity(walk.len());
    for v in walk {
        if let Some(k) = simple.iter().position(|&x| x == v) {
            simple.truncate(k + 1);
        } else {
            simple.push(v);
        }
        if v == end {
            break;
        }
    }
    simple
}

/// The surgery path's surviving vertices in reverse order, from the moved terminal to the
/// moved initial singularity, gaps bridged by shortest paths and loops cut: the image of the
/// surgery path read literally.
fn literal_image(edited: &Map, report: &ZipReport, bridge: &SketchOptions) -> Option<Path> {
    let (from, to) = (report.moved_to(), report.moved_from());
    let mut walk: Vec<Vert> = alloc::vec![from];
    let steps = report.surgery().steps().iter().rev().map(|s| s.vertex);
    for v in steps.filter(|&v| edited.is_live_vertex(v)).chain([to]) {
        let last = *walk.last()?;
        if last == v {
            continue;
        }
        if edited.vertex_darts(last).any(|d| edited.dest(d) == v) {
            walk.push(v);
        } else {
            let b = sketch(edited, last, v, bridge)
                .or_else(|_| sketch(edited, last, v, &SketchOptions::default()))
                .ok()?;
            walk.extend_from_slice(&b.vertices()[1..]);
        }
    }
    let simple = cut_loops(walk, to);
    super::sketch::validate_path(edited, from, to, &simple, &SketchOptions::default()).ok()
}

/// The turn, in quarter turns counter-clockwise, from the first edge of `a` to the first
/// edge of `b` around their common start: the number of quads between them on the side with
/// fewer quads (positive counter-clockwise, negative clockwise).
///
/// Homotopy invariance (Sec. 3.1) compares movements, not labels: when two homotopic paths
/// leave the start along different edges, the movement with initial operation `t` along `a`
/// is the one with `t.turned(k)` along `b`, where `k` counts the quads the homotopy sweeps
/// at the start (a quad corner is a quarter turn whatever the valence). `None` if the starts
/// differ or a face between the two edges is missing (boundary) or not a quad.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{start_turn, validate_path, SketchOptions};
/// let map = gen::torus_grid(6, 6).map;
/// let v = |i: u32, j: u32| Vert::new(6 * j + i);
/// let o = SketchOptions::default();
/// let east = validate_path(&map, v(0, 0), v(1, 1), &[v(0, 0), v(1, 0), v(1, 1)], &o).unwrap();
/// let north = validate_path(&map, v(0, 0), v(1, 1), &[v(0, 0), v(0, 1), v(1, 1)], &o).unwrap();
/// assert_eq!(start_turn(&map, &east, &north), Some(1));
/// assert_eq!(start_turn(&map, &north, &east), Some(-1));
/// ```
pub fn start_turn(map: &Map, a: &Path, b: &Path) -> Option<i32> {
    let (&da, &db) = (a.darts().first()?, b.darts().first()?);
    if a.start() != b.start() || !map.is_live_dart(da) || !map.is_live_dart(db) {
        return None;
    }
    let quad = |d: Dart| map.face(d).is_some_and(|f| map.degree(f) == 4);
    let mut ccw = 0;
    let mut x = da;
    while x != db {
        if !quad(x) || ccw > map.valence(a.start()) {
            ccw = usize::MAX;
            break;
        }
        x = map.rotate_ccw(x);
        ccw += 1;
    }
    let mut cw = 0;
    let mut x = da;
    while x != db {
        let y = map.rotate_cw(x);
        if !quad(y) || cw > map.valence(a.start()) {
            cw = usize::MAX;
            break;
        }
        x = y;
        cw += 1;
    }
    match (ccw, cw) {
        (usize::MAX, usize::MAX) => None,
        (c, w) if c <= w => Some(c as i32),
        (_, w) => Some(-(w as i32)),
    }
}

/// A Q-zip on a [`Mesh`]: the report, and the positions it overwrote (for the undo).
///
/// See [`mesh_zip_along`] for an example.
#[derive(Clone, Debug)]
pub struct MeshZip {
    report: ZipReport,
    overwritten: Vec<(Vert, DVec3)>,
    old_len: usize,
}

impl MeshZip {
    /// The connectivity report.
    ///
    /// See [`mesh_zip_along`] for an example.
    pub fn report(&self) -> &ZipReport {
        &self.report
    }

    /// Undoes the edit: connectivity `==` and positions exactly as before.
    ///
    /// See [`mesh_zip_along`] for an example.
    pub fn undo(&self, mesh: &mut Mesh) -> Result<(), Refusal> {
        self.report.undo(&mut mesh.map)?;
        for &(v, p) in self.overwritten.iter().rev() {
            if let Some(x) = mesh.positions.get_mut(v.index()) {
                *x = p;
            }
        }
        mesh.positions.truncate(self.old_len);
        Ok(())
    }
}

/// Places each vertex created by a split in `records` at the mean of its neighbours, in
/// order; returns the positions overwritten (of reused handles below `old_len`).
fn place_created(mesh: &mut Mesh, records: &[QuadRecord], old_len: usize) -> Vec<(Vert, DVec3)> {
    let mut overwritten = Vec::new();
    if mesh.positions.len() < mesh.map.vertex_slots() {
        mesh.positions.resize(mesh.map.vertex_slots(), DVec3::ZERO);
    }
    for r in records {
        if let QuadRecord::Split(s) = r {
            let v = s.created();
            let (mut sum, mut n) = (DVec3::ZERO, 0.0);
            for d in mesh.map.vertex_darts(v) {
                let p = mesh.positions.get(mesh.map.dest(d).index());
                sum += p.copied().unwrap_or_default();
                n += 1.0;
            }
            if let Some(x) = mesh.positions.get_mut(v.index()) {
                if v.index() < old_len {
                    overwritten.push((v, *x));
                }
                if n > 0.0 {
                    *x = sum / n;
                }
            }
        }
    }
    overwritten
}

/// [`preprocess`] on a mesh: the vertices its splits create are placed at the mean of their
/// neighbours.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// use zipmesh::qzip::mesh_preprocess;
/// let mut mesh = gen::torus_grid(8, 8);
/// quad::collapse_quad(&mut mesh.map, Dart::new(0)).unwrap();
/// mesh_preprocess(&mut mesh).unwrap();
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// ```
pub fn mesh_preprocess(mesh: &mut Mesh) -> Result<Preprocessed, Refusal> {
    let old_len = mesh.positions.len();
    let p = preprocess(&mut mesh.map)?;
    place_created(mesh, p.records(), old_len);
    Ok(p)
}

/// [`zip_along`] on a mesh: each vertex a split creates is placed at the mean of its
/// neighbours (in the order created, so a copy next to an earlier copy uses its new place);
/// merged vertices keep the position of the vertex that keeps the handle.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{mesh_zip_along, sketch, SketchOptions, Tag};
/// let mut mesh = gen::subdivided_icosahedron(2);
/// let before = mesh.clone();
/// let path = sketch(&mesh.map, Vert::new(42), Vert::new(0), &SketchOptions::default()).unwrap();
/// let z = mesh_zip_along(&mut mesh, &path, Tag::LS).unwrap();
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// assert!(z.report().splits() > 0);
/// z.undo(&mut mesh).unwrap();
/// assert_eq!(mesh.map, before.map);
/// assert_eq!(mesh.positions, before.positions);
/// ```
pub fn mesh_zip_along(mesh: &mut Mesh, path: &Path, initial: Tag) -> Result<MeshZip, QzipError> {
    let report = zip_along(&mut mesh.map, path, initial)?;
    let old_len = mesh.positions.len();
    let overwritten = place_created(mesh, report.records(), old_len);
    Ok(MeshZip {
        report,
        overwritten,
        old_len,
    })
}

/// What [`preprocess`] did, with the records for an exact undo.
///
/// See [`preprocess`] for an example.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Preprocessed {
    records: Vec<QuadRecord>,
}

impl Preprocessed {
    /// The operations applied, in order (valence-6+ splits and valence-2 removals).
    ///
    /// See [`preprocess`] for an example.
    pub fn records(&self) -> &[QuadRecord] {
        &self.records
    }

    /// Undoes the preprocessing (the map comes back `==`).
    ///
    /// See [`preprocess`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        super::execute::undo_records(&self.records, map)
    }
}

/// The preprocessing Sec. 2.6 assumes: every interior vertex of valence 6 or more is split
/// along a pair of opposite edges (a 6 becomes two regular vertices and two v5s at the far
/// ends; a 7 a 4 and a 5), and every interior valence-2 vertex is removed (its two quads
/// merge), until none is left. Pairs whose far ends have valence 4 or less are preferred so
/// no new valence-6 vertex appears. All or nothing: on a refusal everything is undone.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// use zipmesh::qzip::preprocess;
/// let mut map = gen::torus_grid(8, 8).map;
/// quad::collapse_quad(&mut map, Dart::new(0)).unwrap(); // makes a valence 6
/// let before = map.clone();
/// let p = preprocess(&mut map).unwrap();
/// assert!(map.vertices().all(|v| (3..=5).contains(&map.valence(v))));
/// assert_eq!(p.records().len(), 1);
/// p.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn preprocess(map: &mut Map) -> Result<Preprocessed, Refusal> {
    let mut out = Preprocessed::default();
    // Each step lowers the sum of (valence - 5) over high vertices or removes a vertex, so
    // this bound is never reached on a valid map; it keeps a corrupt one from looping.
    let bound = 4 * map.dart_slots() + 16;
    for _ in 0..bound {
        let next = map
            .vertices()
            .find(|&v| !map.is_boundary_vertex(v) && (map.valence(v) >= 6 || map.valence(v) == 2));
        let Some(v) = next else {
            return Ok(out);
        };
        let step = if map.valence(v) == 2 {
            remove_valence2(map, map.vertex_dart(v)).map(QuadRecord::from)
        } else {
            let k = map.valence(v);
            let far = |d: Dart| {
                let mut o = d;
                for _ in 0..k / 2 {
                    o = map.rotate_cw(o);
                }
                [map.dest(d), map.dest(o)]
            };
            let low = |x: Vert| map.valence(x) <= 4;
            let first = map
                .vertex_darts(v)
                .find(|&d| far(d).iter().all(|&x| low(x)))
                .unwrap_or_else(|| map.vertex_dart(v));
            split_high_valence(map, v, first).map(QuadRecord::from)
        };
        match step {
            Ok(r) => out.records.push(r),
            Err(e) => {
                let _ = out.undo(map);
                return Err(e);
            }
        }
    }
    let _ = out.undo(map);
    Err(Refusal::BadArguments)
}

/// The paths homotopic to `path` by sweeping one quad across one of its edges: the edge
/// `v[i] -> v[i+1]` is replaced by the quad's three other sides. Only sweeps that pass no
/// third singularity are listed: the quad's two new corners are regular, interior and off
/// the path, the edge's ends are regular unless they are the path's ends, and every
/// neighbour of the quad's corners is regular or one of the path's ends. Each comes with the
/// index `i` of the swept edge. Homotopy invariance (Sec. 3.1) says Q-zip gives the same maps
/// along them, labels matched by [`start_turn`].
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{one_quad_sweeps, sketch, start_turn, SketchOptions};
/// let map = gen::subdivided_icosahedron(2).map;
/// let p = sketch(&map, Vert::new(0), Vert::new(42), &SketchOptions::default()).unwrap();
/// let sweeps = one_quad_sweeps(&map, &p);
/// assert!(!sweeps.is_empty());
/// for (i, q) in &sweeps {
///     assert_eq!(q.len(), p.len() + 2);
///     assert_eq!(start_turn(&map, &p, q) == Some(0), *i > 0);
/// }
/// ```
pub fn one_quad_sweeps(map: &Map, path: &Path) -> Vec<(usize, Path)> {
    let regular = |v: Vert| map.valence(v) == 4 && !map.is_boundary_vertex(v);
    let v = path.vertices();
    let ends = [path.start(), path.end()];
    let mut out = Vec::new();
    for (i, &d) in path.darts().iter().enumerate() {
        for left in [true, false] {
            let e = if left { d } else { d.twin() };
            let Some(f) = map.face(e) else { continue };
            if map.degree(f) != 4 {
                continue;
            }
            let (x, y) = (map.origin(map.prev(e)), map.dest(map.next(e)));
            let (ni, nj) = if left { (x, y) } else { (y, x) };
            if v.contains(&ni) || v.contains(&nj) || !regular(ni) || !regular(nj) {
                continue;
            }
            if (i > 0 && !regular(v[i])) || (i + 2 < v.len() && !regular(v[i + 1])) {
                continue;
            }
            let clear = [v[i], v[i + 1], ni, nj].iter().all(|&c| {
                map.vertex_darts(c)
                    .all(|d| ends.contains(&map.dest(d)) || regular(map.dest(d)))
            });
            if !clear {
                continue;
            }
            let mut q = v[..=i].to_vec();
            q.extend([ni, nj]);
            q.extend_from_slice(&v[i + 1..]);
            let opts = SketchOptions::default();
            if let Ok(p) = super::sketch::validate_path(map, path.start(), path.end(), &q, &opts) {
                out.push((i, p));
            }
        }
    }
    out
}
