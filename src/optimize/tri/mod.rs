//! Automatic singularity reduction of pure triangle meshes (beyond the paper):
//! batches of valence-improving edge flips, triple cancellations (Sec. 7.2), 5-7 pair
//! moves (Sec. 6.2) that bring isolated pairs towards the nearest other irregular vertex,
//! a two-edit look-ahead ([`lookahead`]) and far pair moves (Sec. 7.1.1) of 5-7
//! pairs 2 or 3 edges apart, each batch followed by relaxation of what it touched on the
//! input surface ([`crate::geometry::relax_footprint`]).
//! `docs/optimize.md` gives the reading.
//!
//! A flip, collapse or cancellation is kept only when it lowers the sum of
//! `(valence - 6)^2` over the interior vertices ([`tri_score`]) and makes no new irregular
//! vertex; a look-ahead edit only when it lowers the number of irregular vertices (it may
//! raise the score); a pair move, adjacent or far, changes neither. So the count never rises, nor the score
//! while the count stays. Boundary vertices
//! keep their valences (no edit changes one), and an edit that would turn a triangle over
//! (its normal against the old one's) is undone.
//!
//! ```
//! use zipmesh::{gen, optimize::{optimize_triangles, TriOptimizeOptions}};
//! let mut mesh = gen::random_triangle(400, 1, 0, 3);
//! let out = optimize_triangles(&mut mesh, &TriOptimizeOptions::default(), |_| {}).unwrap();
//! assert!(out.final_counts.irregular() < out.input.irregular());
//! assert_eq!(mesh.map.check(), Ok(()));
//! ```

use alloc::collections::BTreeMap;
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

use glam::DVec3;

mod guard;
mod lookahead;

use crate::geometry::Surface;
use crate::ops::tri::{can_collapse_edge, can_flip_edge, TriOp};
use crate::quality::{Bound, Bounds, Summary};
use crate::tri_edit::{
    can_cancel_triple, cancel_triple, move_far_pair, move_pair, Direction, FarStart, Moved, Start,
};
use crate::{Dart, Map, Mesh, Vert};
use guard::{face_normal, facing, fan, folds, Budget};
use lookahead::Lookahead;

/// How a run goes. Start from [`TriOptimizeOptions::default`].
///
/// ```
/// use zipmesh::optimize::TriOptimizeOptions;
/// let o = TriOptimizeOptions { max_batches: 5, ..TriOptimizeOptions::default() };
/// assert!(o.relax);
/// ```
#[derive(Clone, Debug)]
pub struct TriOptimizeOptions {
    /// The most batches to run (a batch that changes nothing ends the run earlier).
    pub max_batches: usize,
    /// How far (edges) an isolated 5-7 pair looks for another irregular vertex to move to.
    pub search_radius: usize,
    /// Relax the vertices each batch touched on the input surface, two rings round them
    /// ([`crate::geometry::relax_footprint`]): no face inverts, no triangle's smallest angle
    /// falls below 20 degrees unless it rises.
    pub relax: bool,
    /// How far the face count may drift from the input's, as a fraction: an edit that
    /// would leave `[F - s, F + s]`, `s = floor(f F)`, is undone. `f` is clamped to
    /// `[0, 1]`; NaN reads as 0 (no drift).
    pub face_drift: f64,
    /// When the greedy passes find nothing, try every edit and pair of edits round each
    /// irregular vertex and make the best that leaves fewer irregular vertices (the
    /// look-ahead, `docs/optimize.md`).
    pub lookahead: bool,
}

impl Default for TriOptimizeOptions {
    fn default() -> Self {
        TriOptimizeOptions {
            max_batches: 50,
            search_radius: 8,
            relax: true,
            face_drift: 0.05,
            lookahead: true,
        }
    }
}

/// Interior valence counts of a triangle mesh (boundary vertices are not counted).
///
/// ```
/// use zipmesh::{gen, optimize::TriCounts};
/// let c = TriCounts::of(&gen::geodesic_sphere(2));
/// assert_eq!((c.v5, c.irregular()), (12, 12));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TriCounts {
    /// Live faces.
    pub faces: usize,
    /// Live vertices.
    pub vertices: usize,
    /// Interior vertices of valence 3 or less.
    pub v3: usize,
    /// Interior vertices of valence 4.
    pub v4: usize,
    /// Interior vertices of valence 5.
    pub v5: usize,
    /// Interior vertices of valence 7.
    pub v7: usize,
    /// Interior vertices of valence 8 or more.
    pub v8plus: usize,
}

impl TriCounts {
    /// The counts of `map`.
    ///
    /// See [`TriCounts`] for an example.
    pub fn of(map: &Map) -> TriCounts {
        let mut c = TriCounts {
            faces: map.num_faces(),
            vertices: map.num_vertices(),
            ..TriCounts::default()
        };
        for v in map.vertices().filter(|&v| !map.is_boundary_vertex(v)) {
            match map.valence(v) {
                0..=3 => c.v3 += 1,
                4 => c.v4 += 1,
                5 => c.v5 += 1,
                6 => {}
                7 => c.v7 += 1,
                _ => c.v8plus += 1,
            }
        }
        c
    }

    /// Interior irregular vertices.
    ///
    /// See [`TriCounts`] for an example.
    pub fn irregular(&self) -> usize {
        self.v3 + self.v4 + self.v5 + self.v7 + self.v8plus
    }
}

/// What one batch did.
#[derive(Clone, Debug)]
pub struct TriBatch {
    /// 1-based.
    pub batch: usize,
    /// Edge flips kept.
    pub flips: usize,
    /// Triple cancellations kept.
    pub cancellations: usize,
    /// Look-ahead edits (one or two atomic edits each) kept.
    pub lookaheads: usize,
    /// 5-7 pair moves made (adjacent pairs, Sec. 6.2).
    pub pair_moves: usize,
    /// Far 5-7 pair moves made (pairs 2 or 3 edges apart, Sec. 7.1.1).
    pub far_pair_moves: usize,
    /// The score after the batch ([`tri_score`]).
    pub score: u64,
    /// The counts after the batch.
    pub counts: TriCounts,
}

/// The result of [`optimize_triangles`].
#[derive(Clone, Debug)]
pub struct TriOutcome {
    /// The counts of the input.
    pub input: TriCounts,
    /// One row per batch run.
    pub batches: Vec<TriBatch>,
    /// The counts of the result.
    pub final_counts: TriCounts,
    /// With the relaxation on, the batch whose output the result is when a later batch's
    /// broke a geometry bound (a new flipped triangle, or thin triangles past the slack of
    /// [`crate::quality::Bounds`]) and the run went back to it; 0 is the input. `None`
    /// when the result is the last batch's output.
    pub restored: Option<usize>,
}

/// Why [`optimize_triangles`] refused (the mesh is then unchanged).
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum TriOptimizeError {
    /// A face is not a triangle (or the mesh has no face).
    NotTriangles,
    /// A vertex has no position or a non-finite one.
    Positions(Vert),
}

impl fmt::Display for TriOptimizeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotTriangles => f.write_str("not a triangle mesh (a face is not a triangle)"),
            Self::Positions(v) => write!(f, "vertex {} has no finite position", v.index()),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for TriOptimizeError {}

/// What interior vertices cost: how many are irregular, and the sum of `(valence - 6)^2`.
#[derive(Clone, Copy, Default, PartialEq, Eq, Debug)]
struct Cost {
    irregular: u64,
    spread: u64,
}

impl Cost {
    fn of(k: usize) -> Cost {
        let d = k.abs_diff(6) as u64;
        Cost {
            irregular: u64::from(d > 0),
            spread: d * d,
        }
    }

    /// An edit from `self` to `after` is kept when it spreads the valences less and makes
    /// no new irregular vertex (so two v7s never merge into a v8 to save one).
    fn improved_by(self, after: Cost) -> bool {
        after.irregular <= self.irregular && after.spread < self.spread
    }
}

impl core::iter::Sum for Cost {
    fn sum<I: Iterator<Item = Cost>>(iter: I) -> Cost {
        iter.fold(Cost::default(), |a, b| Cost {
            irregular: a.irregular + b.irregular,
            spread: a.spread + b.spread,
        })
    }
}

/// The score: the sum of `(valence - 6)^2` over the interior vertices. Every edit the
/// optimizer keeps lowers the number of irregular vertices, or lowers the score and keeps
/// that number.
///
/// ```
/// use zipmesh::{gen, optimize::tri_score};
/// assert_eq!(tri_score(&gen::geodesic_sphere(1)), 12);
/// ```
pub fn tri_score(map: &Map) -> u64 {
    map.vertices().map(|v| vertex_cost(map, v).spread).sum()
}

fn vertex_cost(map: &Map, v: Vert) -> Cost {
    if map.is_boundary_vertex(v) {
        Cost::default()
    } else {
        Cost::of(map.valence(v))
    }
}

/// Triangles with a corner under this many degrees get their vertices moved towards shape
/// after the batches (`geometry::widen_thin_triangles`).
const WIDEN_BELOW_DEGREES: f64 = 15.0;

/// Reduces the interior irregular vertices of a triangle mesh by batches; `progress` sees
/// each batch. A batch keeps the flips, collapses and triple cancellations (Sec. 7.2) that
/// lower [`tri_score`] without adding an irregular vertex; when none is left it moves each
/// adjacent 5-7 pair (Sec. 6.2) towards its nearest other irregular vertex; when none moves
/// either, it makes the look-ahead's edits ([`TriOptimizeOptions::lookahead`]) that leave
/// fewer irregular vertices; when there are none, it moves each 5-7 pair 2 or 3 edges apart
/// (Sec. 7.1.1) towards its nearest other irregular vertex; then it relaxes what it touched.
/// After the batches it widens the triangles with a corner under 15 degrees on the input
/// surface (`geometry::widen_thin_triangles`). An edit that turns a triangle over
/// or lets the face count drift past
/// [`TriOptimizeOptions::face_drift`] is undone. Every edit keeps the map valid; the mesh's
/// topology (genus, boundary) and its boundary valences are kept. `docs/optimize.md` gives
/// the reading and measurements.
///
/// # Errors
/// [`TriOptimizeError`] before anything is changed.
///
/// ```
/// use zipmesh::{gen, optimize::{optimize_triangles, TriOptimizeOptions}};
/// let mut mesh = gen::random_triangle(400, 1, 0, 3);
/// let out = optimize_triangles(&mut mesh, &TriOptimizeOptions::default(), |_| {}).unwrap();
/// assert!(out.final_counts.irregular() < out.input.irregular());
/// assert_eq!(mesh.map.check(), Ok(()));
/// ```
pub fn optimize_triangles(
    mesh: &mut Mesh,
    options: &TriOptimizeOptions,
    mut progress: impl FnMut(&TriBatch),
) -> Result<TriOutcome, TriOptimizeError> {
    let map = &mesh.map;
    if map.num_faces() == 0 || map.faces().any(|f| map.degree(f) != 3) {
        return Err(TriOptimizeError::NotTriangles);
    }
    if let Some(v) = map
        .vertices()
        .find(|&v| mesh.positions.get(v.index()).is_none_or(|p| !p.is_finite()))
    {
        return Err(TriOptimizeError::Positions(v));
    }
    // The input surface the relaxation projects onto, built only when it will run.
    let surface = options.relax.then(|| Surface::new(mesh));
    let input = TriCounts::of(&mesh.map);
    let drift = options.face_drift.clamp(0.0, 1.0);
    // `as` truncates, and reads NaN as 0: the slack is the whole faces within the drift
    // (no `floor` in no_std).
    let slack = (drift * input.faces as f64) as usize;
    let budget = Budget {
        min: input.faces - slack.min(input.faces),
        max: input.faces + slack,
    };
    let mut batches = Vec::new();
    let mut lookahead = Lookahead::default();
    let mut keeper = surface.as_ref().map(|s| Keeper::new(mesh, s));
    for batch in 1..=options.max_batches {
        let mut touched = Vec::new();
        let flips = flip_pass(mesh, &mut touched) + collapse_pass(mesh, &budget, &mut touched);
        let cancellations = cancel_pass(mesh, &budget, &mut touched);
        let pair_moves = if flips + cancellations == 0 {
            move_pass(mesh, options.search_radius, &budget, &mut touched)
        } else {
            0
        };
        lookahead.forget_near(&mesh.map, &touched);
        let lookaheads = if flips + cancellations + pair_moves == 0 && options.lookahead {
            lookahead.pass(mesh, &budget, &mut touched)
        } else {
            0
        };
        let far_pair_moves = if flips + cancellations + pair_moves + lookaheads == 0 {
            far_move_pass(mesh, options.search_radius, &budget, &mut touched)
        } else {
            0
        };
        if let Some(surface) = surface.as_ref().filter(|_| !touched.is_empty()) {
            touched.retain(|&v| mesh.map.is_live_vertex(v));
            touched.sort_unstable();
            touched.dedup();
            // Positions were checked finite and edits keep them so: a refusal cannot happen.
            let o = crate::geometry::RelaxOptions {
                rings: 2,
                sweeps: 10,
            };
            crate::geometry::relax_footprint(mesh, surface, &touched, o);
        }
        let row = TriBatch {
            batch,
            flips,
            cancellations,
            lookaheads,
            pair_moves,
            far_pair_moves,
            score: tri_score(&mesh.map),
            counts: TriCounts::of(&mesh.map),
        };
        if let Some(k) = keeper.as_mut() {
            k.offer(mesh, batch);
        }
        progress(&row);
        batches.push(row);
        if flips + cancellations + lookaheads + pair_moves + far_pair_moves == 0 {
            break;
        }
    }
    let restored = keeper.as_mut().and_then(|k| k.finish(mesh));
    Ok(TriOutcome {
        input,
        batches,
        final_counts: TriCounts::of(&mesh.map),
        restored,
    })
}

/// The last output of the run that holds the geometry bounds: the result, widened, when the
/// last batch's breaks one. The passes' guards keep each edit from flipping a triangle, and
/// the relaxation and widening after them keep most triangles wide, but an edit's thin
/// triangle can be one no vertex move widens (the campaign found such cases on generated
/// meshes); going back to an earlier batch keeps the bounds whatever the mesh.
struct Keeper<'s> {
    surface: &'s Surface,
    input: Summary,
    /// The last batch that held, its output, and whether that copy is widened already.
    good: (usize, Mesh, bool),
    /// Whether the last batch offered held (then `good` is its output).
    last_held: bool,
}

impl<'s> Keeper<'s> {
    fn new(mesh: &Mesh, surface: &'s Surface) -> Self {
        Keeper {
            surface,
            input: Summary::of(mesh),
            good: (0, mesh.clone(), false),
            last_held: true,
        }
    }

    /// Whether `mesh` holds the bounds a run can break: flips and thin triangles (every
    /// vertex was put on the surface, so the distance is not measured here).
    fn holds(&self, mesh: &Mesh) -> bool {
        let failed = Bounds::default().failures(&self.input, &Summary::of(mesh));
        failed.iter().all(|&b| b == Bound::Distance)
    }

    fn widen(&self, mesh: &mut Mesh) {
        crate::geometry::widen_thin_triangles(mesh, self.surface, WIDEN_BELOW_DEGREES, 20);
    }

    /// Keeps `mesh`, the output of `batch`, if it holds the bounds as it is or once widened
    /// (widened only then: widening every batch's copy cost more than the batches on Spot).
    fn offer(&mut self, mesh: &Mesh, batch: usize) {
        self.last_held = true;
        if self.holds(mesh) {
            self.good = (batch, mesh.clone(), false);
            return;
        }
        let mut widened = mesh.clone();
        self.widen(&mut widened);
        self.last_held = self.holds(&widened);
        if self.last_held {
            self.good = (batch, widened, true);
        }
    }

    /// Puts the result into `mesh`, widened: the last batch's output if it held, else the
    /// last that held, whose batch is returned. Widening never adds a thin triangle or a
    /// flip, but a result that would break a bound after it is left unwidened.
    fn finish(&mut self, mesh: &mut Mesh) -> Option<usize> {
        let (batch, good, widened) = core::mem::take(&mut self.good);
        *mesh = good;
        if !widened {
            let mut w = mesh.clone();
            self.widen(&mut w);
            if self.holds(&w) {
                *mesh = w;
            }
        }
        (!self.last_held).then_some(batch)
    }
}

/// The valences of a pass's map by vertex slot, kept up to date across its edits: the
/// passes test every edge with the valences of four vertices, and walking four rings per
/// edge was most of a pass on the fuzz target's meshes.
struct Valences(Vec<usize>);

impl Valences {
    fn of(map: &Map) -> Self {
        Valences(
            (0..map.vertex_slots() as u32)
                .map(|i| map.valence(Vert::new(i)))
                .collect(),
        )
    }

    fn get(&self, v: Vert) -> usize {
        self.0.get(v.index()).copied().unwrap_or(0)
    }

    /// Whether every live vertex's kept valence is its valence in `map`: checked (in debug
    /// builds, the fuzz targets' too) once per pass rather than per read, which would cost
    /// what the cache saves.
    fn is_current(&self, map: &Map) -> bool {
        map.vertices().all(|v| self.get(v) == map.valence(v))
    }

    /// Reads the valences of `verts` again after an edit there.
    fn update(&mut self, map: &Map, verts: &[Vert]) {
        for &v in verts {
            if let Some(k) = self.0.get_mut(v.index()) {
                *k = map.valence(v);
            }
        }
    }
}

/// The valences of `d`'s ends and of the two opposite corners, `None` when one of the four
/// is on the boundary (no edit changes a boundary valence).
fn edge_valences(map: &Map, vals: &Valences, d: Dart) -> Option<[usize; 4]> {
    let (a, b) = (map.origin(d), map.dest(d));
    let (c, e) = (map.dest(map.next(d)), map.dest(map.next(d.twin())));
    let four = [a, b, c, e];
    (!four.iter().any(|&v| map.is_boundary_vertex(v))).then(|| four.map(|v| vals.get(v)))
}

/// Whether an edit that turns the valences `before` into `after` is kept.
fn improves<const N: usize>(before: [usize; 4], after: [usize; N]) -> bool {
    let cost = |k: &[usize]| k.iter().map(|&x| Cost::of(x)).sum::<Cost>();
    cost(&before).improved_by(cost(&after))
}

/// Whether flipping `d` is kept: its ends lose one, the opposite corners gain one.
fn flip_gain(map: &Map, vals: &Valences, d: Dart) -> Option<bool> {
    let [a, b, c, e] = edge_valences(map, vals, d)?;
    let after = [a.saturating_sub(1), b.saturating_sub(1), c + 1, e + 1];
    Some(improves([a, b, c, e], after))
}

/// Whether the two triangles of `d` turned over (or became degenerate) compared with `old`.
fn turned_over(mesh: &Mesh, d: Dart, old: DVec3) -> bool {
    [d, d.twin()]
        .iter()
        .any(|&x| face_normal(mesh, x).is_none_or(|n| n.dot(old) < 0.5))
}

fn flip_pass(mesh: &mut Mesh, touched: &mut Vec<Vert>) -> usize {
    let mut kept = 0;
    let edges: Vec<Dart> = mesh.map.edges().map(|e| e.dart(0)).collect();
    let mut vals = Valences::of(&mesh.map);
    for d in edges {
        let map = &mesh.map;
        // The gain first: both tests are pure, and the gain is the cheaper with `vals`.
        if !map.is_live_dart(d) || flip_gain(map, &vals, d) != Some(true) {
            continue;
        }
        if can_flip_edge(map, d).is_err() {
            continue;
        }
        let old = match (face_normal(mesh, d), face_normal(mesh, d.twin())) {
            (Some(x), Some(y)) => (x + y).normalize_or_zero(),
            _ => continue,
        };
        let corners = |m: &Map| {
            [
                m.origin(d),
                m.dest(d),
                m.dest(m.next(d)),
                m.dest(m.next(d.twin())),
            ]
        };
        let before = facing(mesh, &corners(map));
        let Ok(edit) = TriOp::Flip(d).apply(mesh) else {
            continue;
        };
        if turned_over(mesh, d, old) || before.more_flipped(mesh, &corners(&mesh.map)) {
            // The record was made on this mesh just now: the undo cannot be stale.
            let _ = edit.undo(mesh);
            continue;
        }
        let four = corners(&mesh.map);
        vals.update(&mesh.map, &four);
        touched.extend(four);
        kept += 1;
    }
    debug_assert!(vals.is_current(&mesh.map), "a stale valence");
    kept
}

/// Whether collapsing `d` is kept: its ends merge (valence `a + b - 4`), the opposite
/// corners lose one each.
fn collapse_gain(map: &Map, vals: &Valences, d: Dart) -> Option<bool> {
    let [a, b, c, e] = edge_valences(map, vals, d)?;
    let after = [
        (a + b).saturating_sub(4),
        c.saturating_sub(1),
        e.saturating_sub(1),
    ];
    Some(improves([a, b, c, e], after))
}

/// Edge collapses that lower the score (a 5-5 edge between two v7s is the quadruple removal
/// of Sec. 6.2 read backwards), undone when a triangle turns over.
fn collapse_pass(mesh: &mut Mesh, budget: &Budget, touched: &mut Vec<Vert>) -> usize {
    let mut kept = 0;
    let darts: Vec<Dart> = mesh.map.edges().map(|e| e.dart(0)).collect();
    let mut vals = Valences::of(&mesh.map);
    // The normals round a collapse, in one list for the pass (not one grown per edge).
    let mut normals: Vec<(Dart, DVec3)> = Vec::new();
    for d in darts {
        let map = &mesh.map;
        if !map.is_live_dart(d) || collapse_gain(map, &vals, d) != Some(true) {
            continue;
        }
        if can_collapse_edge(map, d).is_err() {
            continue;
        }
        let kept_vertex = map.dest(d);
        normals.clear();
        normals.extend(
            fan(map, kept_vertex)
                .chain(fan(map, map.origin(d)))
                .filter_map(|x| face_normal(mesh, x).map(|n| (x, n))),
        );
        let k = mesh.map.dest(d); // the collapse keeps the edge's end
        let before = facing(mesh, &[map.origin(d), k]);
        let Ok(edit) = TriOp::Collapse(d).apply(mesh) else {
            continue;
        };
        let turned = normals.iter().any(|&(x, n)| {
            mesh.map.is_live_dart(x)
                && mesh.map.face(x).is_some()
                && face_normal(mesh, x).is_none_or(|m| m.dot(n) < 0.5)
        });
        if turned || before.more_flipped(mesh, &[k]) || !budget.holds(&mesh.map) {
            let _ = edit.undo(mesh);
            continue;
        }
        let m = &mesh.map;
        let start = touched.len();
        touched.push(k);
        touched.extend(m.vertex_darts(k).map(|x| m.dest(x)));
        // The merged vertex and its ring: the opposite corners lost an edge each.
        vals.update(m, &touched[start..]);
        kept += 1;
    }
    debug_assert!(vals.is_current(&mesh.map), "a stale valence");
    kept
}

/// Triples `v, a, b` of interior v5/v7s, `a` a neighbour of `v` and `b` a neighbour of `v`
/// or `a`: the cancellations of Sec. 7.2, kept when they lower the score.
fn cancel_pass(mesh: &mut Mesh, budget: &Budget, touched: &mut Vec<Vert>) -> usize {
    let mut kept = 0;
    let verts: Vec<Vert> = mesh.map.vertices().collect();
    for v in verts {
        let map = &mesh.map;
        if !map.is_live_vertex(v) || !matches!(vertex_cost_kind(map, v), Some(5 | 7)) {
            continue;
        }
        let Some(three) = triple_at(map, v) else {
            continue;
        };
        let before: Cost = three.iter().map(|&x| vertex_cost(map, x)).sum();
        let reference = facing(mesh, &three);
        let Ok(edit) = cancel_triple(mesh, &three) else {
            continue;
        };
        let map = &mesh.map;
        let after: Cost = three
            .iter()
            .filter(|&&x| map.is_live_vertex(x))
            .map(|&x| vertex_cost(map, x))
            .sum();
        if !before.improved_by(after) || folds(mesh, &three, &reference) || !budget.holds(&mesh.map)
        {
            let _ = edit.undo(mesh);
            continue;
        }
        touched.extend(three.iter().copied().filter(|&x| map.is_live_vertex(x)));
        kept += 1;
    }
    kept
}

fn vertex_cost_kind(map: &Map, v: Vert) -> Option<usize> {
    (!map.is_boundary_vertex(v)).then(|| map.valence(v))
}

/// A cancellable 5-5-7 or 5-7-7 triple containing `v`, if any.
fn triple_at(map: &Map, v: Vert) -> Option<[Vert; 3]> {
    let odd = |x: Vert| matches!(vertex_cost_kind(map, x), Some(5 | 7));
    for a in map.vertex_darts(v).map(|d| map.dest(d)).filter(|&a| odd(a)) {
        let around = map
            .vertex_darts(v)
            .chain(map.vertex_darts(a))
            .map(|d| map.dest(d));
        for b in around.filter(|&b| b != v && b != a && odd(b)) {
            let three = [v, a, b];
            if can_cancel_triple(map, &three).is_ok() {
                return Some(three);
            }
        }
    }
    None
}

/// Breadth-first distances from `from`, up to `radius` edges; a hash map, not a per-slot
/// array, because the searches are small and many (one per pair and direction).
struct Near(hashbrown::HashMap<u32, usize>);

impl Near {
    fn from(map: &Map, from: &[Vert], radius: usize) -> Near {
        let mut dist = hashbrown::HashMap::new();
        // First in, first out: `queue[head..]` is still to expand, with its distance.
        let mut queue: Vec<(Vert, usize)> = Vec::new();
        for &v in from {
            dist.insert(v.index() as u32, 0);
            queue.push((v, 0));
        }
        let mut head = 0;
        while let Some(&(v, dv)) = queue.get(head) {
            head += 1;
            if dv == radius {
                continue;
            }
            for w in map.vertex_darts(v).map(|d| map.dest(d)) {
                if let hashbrown::hash_map::Entry::Vacant(e) = dist.entry(w.index() as u32) {
                    e.insert(dv + 1);
                    queue.push((w, dv + 1));
                }
            }
        }
        Near(dist)
    }

    /// The distance of `v`, `usize::MAX` beyond the radius.
    fn at(&self, v: Vert) -> usize {
        self.0
            .get(&(v.index() as u32))
            .copied()
            .unwrap_or(usize::MAX)
    }
}

/// Each adjacent 5-7 pair makes the one atomic move (Sec. 6.2) that brings it nearest to
/// the closest other irregular vertex within `radius`, if any move brings it strictly
/// nearer. "Nearer" is measured from the pair's vertex that can cancel with the target: a
/// target v5 cancels with the v7 (5-5-7), a target v7 with the v5 (5-7-7).
fn move_pass(mesh: &mut Mesh, radius: usize, budget: &Budget, touched: &mut Vec<Vert>) -> usize {
    let mut moved = 0;
    let pairs = five_seven_pairs(&mesh.map);
    for (p, q) in pairs {
        let map = &mesh.map;
        if !map.is_live_vertex(p) || !map.is_live_vertex(q) {
            continue;
        }
        let Some(target) = nearest_other(map, p, q, radius) else {
            continue;
        };
        let kind = vertex_cost_kind(map, target);
        let dist = Near::from(map, &[target], radius + 2);
        let now = lead(kind, dist.at(p), dist.at(q));
        let mut best: Option<(usize, Direction)> = None;
        for dir in Direction::ALL {
            let Ok(e) = move_pair(mesh, p, q, dir) else {
                continue;
            };
            // Distances from the target as they were: a move changes the graph next to the
            // pair only, and a vertex it made is one edge from one that was there.
            let m = &mesh.map;
            let seen = |v: Vert| {
                let old = dist.at(v);
                let via = m
                    .vertex_darts(v)
                    .map(|d| dist.at(m.dest(d)).saturating_add(1));
                via.fold(old, usize::min)
            };
            let (np, nq) = (e.record().p(), e.record().q());
            let at = lead(kind, seen(np), seen(nq));
            let _ = e.undo(mesh);
            if at < now && best.is_none_or(|(b, _)| at < b) {
                best = Some((at, dir));
            }
        }
        let reference = facing(mesh, &[p, q]);
        if let Some((_, dir)) = best {
            if let Ok(e) = move_pair(mesh, p, q, dir) {
                let four = [p, q, e.record().p(), e.record().q()];
                if folds(mesh, &four, &reference) || !budget.holds(&mesh.map) {
                    let _ = e.undo(mesh);
                    continue;
                }
                touched.extend(four);
                moved += 1;
            }
        }
    }
    touched.retain(|&v| mesh.map.is_live_vertex(v));
    moved
}

/// The distance that counts for a 5-7 pair whose v5 and v7 are `at_p` and `at_q` from a
/// target of valence `kind`: a target v5 cancels with the v7 (5-5-7), a target v7 with the
/// v5 (5-7-7), any other with the nearer of the two.
fn lead(kind: Option<usize>, at_p: usize, at_q: usize) -> usize {
    match kind {
        Some(5) => at_q,
        Some(7) => at_p,
        _ => at_p.min(at_q),
    }
}

/// Adjacent interior (v5, v7) pairs, each v5 with its first v7 neighbour.
fn five_seven_pairs(map: &Map) -> Vec<(Vert, Vert)> {
    map.vertices()
        .filter(|&p| vertex_cost_kind(map, p) == Some(5))
        .filter_map(|p| {
            map.vertex_darts(p)
                .map(|d| map.dest(d))
                .find(|&q| vertex_cost_kind(map, q) == Some(7))
                .map(|q| (p, q))
        })
        .collect()
}

/// The closest interior irregular vertex other than `p` and `q`, within `radius` (the
/// lowest handle among the closest): a breadth-first search that stops at the first ring
/// holding one.
fn nearest_other(map: &Map, p: Vert, q: Vert, radius: usize) -> Option<Vert> {
    let mut seen = BTreeMap::new();
    let mut ring: Vec<Vert> = vec![p, q];
    for &v in &ring {
        seen.insert(v.index(), ());
    }
    for _ in 0..radius {
        let mut next = Vec::new();
        for &v in &ring {
            for w in map.vertex_darts(v).map(|d| map.dest(d)) {
                if seen.insert(w.index(), ()).is_none() {
                    next.push(w);
                }
            }
        }
        let found = next
            .iter()
            .copied()
            .filter(|&w| vertex_cost(map, w).irregular > 0)
            .min();
        if found.is_some() || next.is_empty() {
            return found;
        }
        ring = next;
    }
    None
}

/// How far apart (edges) the v5 and v7 of a far pair may be: 3 leaves 43 irregular vertices
/// on the disk and 164 on Spot, where 2 left 49 and 183 (docs/optimize.md).
const FAR_PAIR: usize = 3;

/// Interior (v5, v7) pairs 2 to [`FAR_PAIR`] edges apart: each v5 that has no v7
/// neighbour, with its nearest v7 (the lowest handle among the nearest).
fn far_five_seven_pairs(map: &Map) -> Vec<(Vert, Vert)> {
    let seven = |q: Vert| vertex_cost_kind(map, q) == Some(7);
    map.vertices()
        .filter(|&p| vertex_cost_kind(map, p) == Some(5))
        .filter(|&p| !map.vertex_darts(p).any(|d| seven(map.dest(d))))
        .filter_map(|p| {
            let mut ring = vec![p];
            let mut seen = BTreeMap::from([(p.index(), ())]);
            for _ in 0..FAR_PAIR {
                let next: Vec<Vert> = ring
                    .iter()
                    .flat_map(|&v| map.vertex_darts(v).map(|d| map.dest(d)))
                    .filter(|w| seen.insert(w.index(), ()).is_none())
                    .collect();
                if let Some(q) = next.iter().copied().filter(|&q| seven(q)).min() {
                    return Some((p, q));
                }
                ring = next;
            }
            None
        })
        .collect()
}

/// How many atomic 5-7 movements a far pair move's walk may take.
const FAR_STEPS: usize = 8;

/// The start of the far pair move (Sec. 7.1.1) of `(p, q)` that brings it nearest to
/// `target` ([`lead`]), if one brings it strictly nearer: every start at the v5 `p` (its
/// darts, the three generations, both readings), each applied and undone.
fn best_far_move(
    mesh: &mut Mesh,
    p: Vert,
    q: Vert,
    target: Vert,
    radius: usize,
) -> Option<FarStart> {
    let kind = vertex_cost_kind(&mesh.map, target);
    let now = {
        let dist = Near::from(&mesh.map, &[target], radius + 4);
        lead(kind, dist.at(p), dist.at(q))
    };
    let darts: Vec<Dart> = mesh.map.vertex_darts(p).collect();
    let mut best: Option<(usize, FarStart)> = None;
    for d in darts {
        for &start in Start::all(5) {
            for moved in [Moved::First, Moved::Second] {
                let map = &mut mesh.map;
                let Ok(e) = move_far_pair(
                    &mut (map, &mut mesh.positions),
                    d,
                    start,
                    moved,
                    q,
                    FAR_STEPS,
                ) else {
                    continue;
                };
                let (np, nq) = e.record().pair();
                // The walk can pass far from the pair: the distances are measured again, as
                // far as matters (nearer than now).
                let reach = now.saturating_sub(1).min(radius + 4);
                let dist = Near::from(&mesh.map, &[target], reach);
                let at = lead(kind, dist.at(np), dist.at(nq));
                let _ = e.undo(mesh);
                if at < now && best.is_none_or(|b| at < b.0) {
                    best = Some((at, (d, start, moved)));
                }
            }
        }
    }
    best.map(|b| b.1)
}

/// Each far 5-7 pair ([`far_five_seven_pairs`]) makes the far pair move (Sec. 7.1.1, the
/// generation, the walk and the removal of [`move_far_pair`]) that brings it nearest to the closest
/// other irregular vertex within `radius`, as [`move_pass`] does for adjacent pairs; undone
/// when it folds a triangle or leaves `budget`.
fn far_move_pass(
    mesh: &mut Mesh,
    radius: usize,
    budget: &Budget,
    touched: &mut Vec<Vert>,
) -> usize {
    let mut moved = 0;
    for (p, q) in far_five_seven_pairs(&mesh.map) {
        let map = &mesh.map;
        let pair = vertex_cost_kind(map, p) == Some(5) && vertex_cost_kind(map, q) == Some(7);
        if !map.is_live_vertex(p) || !map.is_live_vertex(q) || !pair {
            continue;
        }
        let Some(target) = nearest_other(map, p, q, radius) else {
            continue;
        };
        let Some((d, start, m)) = best_far_move(mesh, p, q, target, radius) else {
            continue;
        };
        let reference = facing(mesh, &[p, q]);
        let Ok(e) = move_far_pair(mesh, d, start, m, q, FAR_STEPS) else {
            continue;
        };
        let (np, nq) = e.record().pair();
        let four = [p, q, np, nq];
        if folds(mesh, &four, &reference) || !budget.holds(&mesh.map) {
            let _ = e.undo(mesh);
            continue;
        }
        touched.extend(four);
        moved += 1;
    }
    touched.retain(|&v| mesh.map.is_live_vertex(v));
    moved
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;

    /// A 6 x 6 torus of quads, each cut along the same diagonal: every valence 6.
    fn regular_torus() -> Mesh {
        let grid = gen::torus_grid(6, 6);
        let triangles: Vec<[u32; 3]> = gen::torus_quads(6, 6)
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        let mesh = Mesh::from_polygons(grid.positions, &triangles).unwrap().0;
        assert!(irregular_valences(&mesh.map).is_empty());
        mesh
    }

    fn irregular_valences(map: &Map) -> Vec<usize> {
        let mut v: Vec<usize> = map
            .vertices()
            .filter_map(|v| vertex_cost_kind(map, v))
            .filter(|&k| k != 6)
            .collect();
        v.sort_unstable();
        v
    }

    /// The flip pass flips back an edge whose flip made two v5 and two v7 on a regular
    /// triangulated torus (its ends lose an edge, its apexes gain one), and keeps the
    /// valence cache current through it.
    #[test]
    fn the_flip_pass_undoes_a_harmful_flip() {
        let mut mesh = regular_torus();
        let d = mesh.map.face_dart(crate::Face::new(7));
        crate::ops::tri::flip_edge(&mut mesh.map, d).unwrap();
        assert_eq!(irregular_valences(&mesh.map), [5, 5, 7, 7]);
        let mut touched = Vec::new();
        assert_eq!(flip_pass(&mut mesh, &mut touched), 1);
        assert!(irregular_valences(&mesh.map).is_empty());
        assert_eq!(touched.len(), 4);
    }

    /// The collapse pass collapses back the edge of a vertex split that made two v5 (the
    /// split halves) and two v7 (the ends) on a regular triangulated torus, and keeps the
    /// valence cache current through it.
    #[test]
    fn the_collapse_pass_undoes_a_harmful_split() {
        let mut mesh = regular_torus();
        let w = crate::Vert::new(14);
        let d1 = mesh.map.vertex_dart(w);
        let d2 = (0..3).fold(d1, |d, _| mesh.map.rotate_cw(d));
        crate::ops::tri::TriOp::SplitVertex(d1, d2)
            .apply(&mut mesh)
            .unwrap();
        assert_eq!(irregular_valences(&mesh.map), [5, 5, 7, 7]);
        let budget = Budget { min: 0, max: 1000 };
        let mut touched = Vec::new();
        assert_eq!(collapse_pass(&mut mesh, &budget, &mut touched), 1);
        assert!(irregular_valences(&mesh.map).is_empty());
        // Within the budget only: one face fewer than now is refused.
        let faces = mesh.map.num_faces();
        crate::ops::tri::TriOp::SplitVertex(d1, d2)
            .apply(&mut mesh)
            .unwrap();
        let tight = Budget {
            min: faces + 1,
            max: 1000,
        };
        assert_eq!(collapse_pass(&mut mesh, &tight, &mut touched), 0);
    }

    /// A far pair move keeps the pair's valences and every irregular valence, brings the
    /// pair strictly nearer its target, keeps the map valid and undoes to `==`.
    #[test]
    fn a_far_pair_move_brings_the_pair_nearer_and_changes_nothing_else() {
        let mut moved = 0;
        for seed in 0..6 {
            let mut mesh = gen::random_triangle(600, (seed % 3) as usize, 0, seed);
            // A few batches, so that pairs are left with a move to make.
            let few = TriOptimizeOptions {
                max_batches: 3,
                ..TriOptimizeOptions::default()
            };
            optimize_triangles(&mut mesh, &few, |_| {}).unwrap();
            for (p, q) in far_five_seven_pairs(&mesh.map) {
                let map = &mesh.map;
                assert_eq!((map.valence(p), map.valence(q)), (5, 7));
                let Some(target) = nearest_other(map, p, q, 8) else {
                    continue;
                };
                let Some((d, start, m)) = best_far_move(&mut mesh, p, q, target, 8) else {
                    continue;
                };
                let (before, valences) = (mesh.clone(), irregular_valences(&mesh.map));
                let kind = vertex_cost_kind(&mesh.map, target);
                let near = Near::from(&mesh.map, &[target], 12);
                let was = lead(kind, near.at(p), near.at(q));
                let (map, pos) = (&mut mesh.map, &mut mesh.positions);
                let e =
                    move_far_pair(&mut (&mut *map, &mut *pos), d, start, m, q, FAR_STEPS).unwrap();
                let (np, nq) = e.record().pair();
                let map = &mesh.map;
                assert_eq!(map.check(), Ok(()));
                assert_eq!((map.valence(np), map.valence(nq)), (5, 7));
                assert_eq!(irregular_valences(map), valences);
                let near = Near::from(map, &[target], 12);
                assert!(lead(kind, near.at(np), near.at(nq)) < was);
                e.undo(&mut mesh).unwrap();
                assert_eq!(mesh, before);
                moved += 1;
            }
        }
        std::eprintln!("{moved} far pair moves checked");
        assert!(moved > 10, "{moved}");
    }
}
