//! Relaxation of the geometry after a connectivity edit (triangle paper, Sec. 8):
//! the edits leave triangles with poor aspect ratios, and relaxation moves the vertices of
//! the edit's neighbourhood along the input surface to even them out. Connectivity never
//! changes; only the positions of the region's interior vertices do.
//!
//! **The energy (Eq. 5).** With `p_i` the position of `v_i`, `N_i` its neighbours, `d` the
//! average edge length of the whole mesh and `u_ij` unit target tangent vectors,
//!
//! ```text
//! E(p) = sum_i sum_{j in N_i} | p_j - (p_i + d u_ij) |^2
//! ```
//!
//! The targets `u_ij` divide the tangent plane at `p_i` into `l(v_i)` equal angles: with
//! `alpha0_ij` the angle of `p_j - p_i` projected onto the plane, measured from a local `x`
//! direction, and `k_j` the rank of `v_j` sorted counter-clockwise (about the normal), the
//! targets sit at `alpha0 + k_j 2 pi / l(v_i)`, where `alpha0` is the best fit of the
//! offsets `alpha0_ij - k_j 2 pi / l(v_i)`. The paper takes their arithmetic mean; we take
//! their circular mean (the angle of the sum of unit vectors), which is the same when the
//! offsets do not straddle the branch cut of the angle and does not jump when they do.
//! [`relax_energy`] sums the terms with `v_i` or `v_j` in the region: the others do not
//! depend on what moves. A vertex without a tangent plane (degenerate or non-finite
//! triangles around it) has no targets, adds no terms and does not move.
//!
//! **Global relaxation** ([`relax_global`], behind the `sparse` feature, which brings the
//! sparse Cholesky of `nalgebra-sparse`): each region vertex is kept on its tangent plane,
//! `p_i = c_i + a_i t1_i + b_i t2_i` with `c_i` its current position, which makes `E`
//! quadratic in the `2 n` unknowns `(a_i, b_i)` with the targets held fixed. The normal
//! equations (plus `1e-9` times the identity, so that a region that could slide as a whole
//! on a flat surface still has one minimiser) are solved by sparse Cholesky, each moved
//! vertex is projected back onto the input surface, and the targets are recomputed: one
//! iteration. The paper uses UMFPACK for the same system. An iteration whose projected
//! result would raise `E` is retried at half and a quarter of the step, and relaxation stops
//! when none of those lowers it, so `E` never increases.
//!
//! **Local relaxation** ([`relax_local`], Turk 1992, one vertex at a time): sweeps over the
//! region in order, each vertex moved to the centroid of its neighbours within its tangent
//! plane (the tangential part of the uniform Laplacian, with the neighbours' positions as
//! they are at that moment, Gauss-Seidel style), then projected onto the input surface. The
//! paper found it the faster of the two, and so do we (docs/benchmarks.md).
//!
//! **The region.** [`touched_vertices`](crate::geometry::touched_vertices) finds the vertices whose neighbours an edit changed
//! (or which it created); [`relax_region`](crate::geometry::relax_region) adds rings around them. Boundary vertices keep
//! their place (the boundary's shape is the input's), as do all vertices outside the region,
//! bit for bit. The input surface is a [`Surface`] of the mesh before the edit; projection is
//! onto its nearest triangle ([`Surface::closest`], shared with the quad optimizer's
//! smoothing).
//!
//! ```
//! use zipmesh::optimize::Surface;
//! use zipmesh::tri_edit::{relax_energy, relax_local, relax_region};
//! use zipmesh::{Mesh, Vert};
//! use glam::DVec3;
//! // A flat hexagon of six triangles around vertex 0, which sits off centre.
//! let mut p = vec![DVec3::new(0.3, 0.2, 0.0)];
//! p.extend((0..6).map(|k| {
//!     let a = k as f64 * core::f64::consts::TAU / 6.0;
//!     DVec3::new(a.cos(), a.sin(), 0.0)
//! }));
//! let tris: Vec<[u32; 3]> = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
//! let (mut mesh, _) = Mesh::from_polygons(p, &tris).unwrap();
//! let surface = Surface::new(&mesh);
//! let region = relax_region(&mesh.map, &[Vert::new(0)], 1);
//! assert_eq!(region, vec![Vert::new(0)]); // the ring is boundary: it stays
//! let r = relax_local(&mut mesh, &surface, &region, 5).unwrap();
//! assert!(mesh.positions[0].length() < 1e-12); // back at the centre
//! assert!(r.energy_after < r.energy_before);
//! assert_eq!(r.energy_after, relax_energy(&mesh, &region, r.edge_length));
//! ```

use alloc::vec;
use alloc::vec::Vec;
use core::f64::consts::TAU;
use core::fmt;

use glam::DVec3;

use crate::geometry::Surface;
use crate::{Map, Mesh, Vert};

/// Why a relaxation refuses (the positions are then unchanged).
///
/// ```
/// use zipmesh::optimize::Surface;
/// use zipmesh::tri_edit::{relax_local, RelaxError};
/// use zipmesh::{gen, Vert};
/// let mut mesh = gen::random_triangle(50, 0, 0, 1);
/// let s = Surface::new(&mesh);
/// mesh.positions[0].x = f64::NAN;
/// let before = mesh.clone();
/// let r = relax_local(&mut mesh, &s, &[Vert::new(0)], 3);
/// assert_eq!(r, Err(RelaxError::NonFinite(Vert::new(0))));
/// assert!(mesh.positions[0].x.is_nan() && mesh.map == before.map);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RelaxError {
    /// A region vertex is not live.
    DeadHandle(Vert),
    /// A region vertex or one of its neighbours has no position, or one that is not finite.
    NonFinite(Vert),
    /// The sparse solver failed (the system was not positive definite, or gave a
    /// non-finite solution).
    Solver,
}

impl fmt::Display for RelaxError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RelaxError::DeadHandle(v) => write!(f, "vertex {} is not live", v.index()),
            RelaxError::NonFinite(v) => {
                write!(f, "vertex {} has no finite position", v.index())
            }
            RelaxError::Solver => f.write_str("the sparse solver failed"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for RelaxError {}

/// What a relaxation did.
///
/// See [`relax_local`] and [`relax_global`] for examples.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Relaxed {
    /// How many region vertices could move (live and interior, each counted once).
    pub movable: usize,
    /// How many vertices changed position.
    pub moved: usize,
    /// Iterations done: sweeps (local) or accepted solves (global).
    pub iterations: usize,
    /// `d` of Eq. 5: the average edge length of the mesh before relaxation.
    pub edge_length: f64,
    /// [`relax_energy`] of the region before.
    pub energy_before: f64,
    /// [`relax_energy`] of the region after.
    pub energy_after: f64,
}

/// The average length of the mesh's edges whose ends have finite positions (0 when there
/// is none): `d` of Eq. 5.
///
/// ```
/// use zipmesh::{gen, tri_edit::mean_edge_length};
/// assert!((mean_edge_length(&gen::grid(3, 2)) - 1.0).abs() < 1e-12);
/// ```
pub fn mean_edge_length(mesh: &Mesh) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for e in mesh.map.edges() {
        let d = e.dart(0);
        let (a, b) = (mesh.map.origin(d), mesh.map.dest(d));
        if let (Some(p), Some(q)) = (finite(&mesh.positions, a), finite(&mesh.positions, b)) {
            sum += p.distance(q);
            n += 1;
        }
    }
    if n == 0 {
        0.0
    } else {
        sum / n as f64
    }
}

/// Eq. 5 over the terms `(i, j)` with `v_i` or `v_j` in `region`, with edge length `d` and
/// the targets of the current positions (see [the module](self)).
///
/// ```
/// use zipmesh::{gen, tri_edit::relax_energy, Vert};
/// let mesh = gen::random_triangle(80, 0, 0, 4);
/// assert_eq!(relax_energy(&mesh, &[], 1.0), 0.0);
/// assert!(relax_energy(&mesh, &[Vert::new(3)], 1.0) > 0.0);
/// ```
pub fn relax_energy(mesh: &Mesh, region: &[Vert], d: f64) -> f64 {
    let mut mask = vec![false; mesh.map.vertex_slots()];
    for &v in region {
        if let Some(m) = mask.get_mut(v.index()) {
            *m = true;
        }
    }
    energy(&mesh.map, &mesh.positions, region, &mask, d)
}

/// The position of `v` when it is there and finite.
fn finite(pos: &[DVec3], v: Vert) -> Option<DVec3> {
    pos.get(v.index()).copied().filter(|p| p.is_finite())
}

/// The unit normal at `v`: the sum of the cross products of its triangles' edges (area
/// weighted), `None` when it vanishes or is not finite.
fn normal(map: &Map, pos: &[DVec3], v: Vert) -> Option<DVec3> {
    let a = finite(pos, v)?;
    let mut n = DVec3::ZERO;
    for d in map.vertex_darts(v) {
        if map.face(d).is_none() {
            continue;
        }
        let (b, c) = (map.dest(d), map.dest(map.next(d)));
        if let (Some(b), Some(c)) = (finite(pos, b), finite(pos, c)) {
            n += (b - a).cross(c - a);
        }
    }
    let len = n.length();
    (len.is_finite() && len > 1e-300).then(|| n / len)
}

/// The tangent frame at `v`: the normal, then the local `x` direction (toward the first
/// neighbour, in the plane) and `y = normal x x`.
fn frame(map: &Map, pos: &[DVec3], v: Vert) -> Option<[DVec3; 3]> {
    let n = normal(map, pos, v)?;
    let p = finite(pos, v)?;
    let x = map.vertex_darts(v).find_map(|d| {
        let w = finite(pos, map.dest(d))? - p;
        let t = w - n * n.dot(w);
        let len = t.length();
        (len > 1e-300 && len.is_finite()).then(|| t / len)
    })?;
    Some([n, x, n.cross(x)])
}

/// The reused lists of [`targets`]: a relaxation's energy reads the targets of every
/// vertex round its region, and four lists per vertex were most of its allocations.
#[derive(Default)]
struct Targets {
    angle: Vec<(Vert, f64)>,
    order: Vec<usize>,
    rank: Vec<usize>,
    out: Vec<(Vert, DVec3)>,
}

/// The targets `u_ij` at `v_i` (see the module documentation), one per neighbour in the
/// order of `vertex_darts`, in `b`; `None` when `v_i` has no tangent frame or a neighbour
/// has no finite position.
fn targets<'b>(
    map: &Map,
    pos: &[DVec3],
    i: Vert,
    b: &'b mut Targets,
) -> Option<&'b [(Vert, DVec3)]> {
    let [n, x, y] = frame(map, pos, i)?;
    let p = finite(pos, i)?;
    let angle = &mut b.angle;
    angle.clear();
    for d in map.vertex_darts(i) {
        let j = map.dest(d);
        let w = finite(pos, j)? - p;
        let t = w - n * n.dot(w);
        let a = libm::atan2(t.dot(y), t.dot(x));
        angle.push((j, if a < 0.0 { a + TAU } else { a }));
    }
    let order = &mut b.order;
    order.clear();
    order.extend(0..angle.len());
    order.sort_by(|&a, &b| angle[a].1.total_cmp(&angle[b].1));
    let step = TAU / angle.len().max(1) as f64;
    let rank = &mut b.rank;
    rank.clear();
    rank.resize(angle.len(), 0);
    for (k, &o) in order.iter().enumerate() {
        rank[o] = k;
    }
    let (mut s, mut c) = (0.0, 0.0);
    for (o, &(_, a)) in angle.iter().enumerate() {
        let off = a - rank[o] as f64 * step;
        s += libm::sin(off);
        c += libm::cos(off);
    }
    let alpha0 = libm::atan2(s, c);
    let u = |o: usize| {
        let a = alpha0 + rank[o] as f64 * step;
        x * libm::cos(a) + y * libm::sin(a)
    };
    b.out.clear();
    b.out
        .extend(angle.iter().enumerate().map(|(o, &(j, _))| (j, u(o))));
    Some(&b.out)
}

/// The region's vertices and their neighbours, each once: the `v_i` whose terms may depend
/// on the region.
fn centres(map: &Map, region: &[Vert]) -> Vec<Vert> {
    let mut seen = vec![false; map.vertex_slots()];
    let mut out = Vec::new();
    for &v in region {
        let ring = core::iter::once(v).chain(map.vertex_darts(v).map(|d| map.dest(d)));
        for w in ring {
            if let Some(s) = seen.get_mut(w.index()).filter(|s| !**s) {
                *s = true;
                out.push(w);
            }
        }
    }
    out
}

fn energy(map: &Map, pos: &[DVec3], region: &[Vert], mask: &[bool], d: f64) -> f64 {
    let inside = |v: Vert| mask.get(v.index()).copied().unwrap_or(false);
    let mut e = 0.0;
    let mut buf = Targets::default();
    for i in centres(map, region) {
        let (Some(p), Some(t)) = (finite(pos, i), targets(map, pos, i, &mut buf)) else {
            continue;
        };
        for &(j, u) in t {
            if let (true, Some(q)) = (inside(i) || inside(j), finite(pos, j)) {
                e += (q - p - u * d).length_squared();
            }
        }
    }
    e
}

/// The region's movable vertices (live, interior, each once, in the order given), after
/// checking that each live region vertex and its neighbours have finite positions.
fn movable(mesh: &Mesh, region: &[Vert]) -> Result<Vec<Vert>, RelaxError> {
    let map = &mesh.map;
    let mut seen = vec![false; map.vertex_slots()];
    let mut out = Vec::new();
    for &v in region {
        if !map.is_live_vertex(v) {
            return Err(RelaxError::DeadHandle(v));
        }
        let ring = core::iter::once(v).chain(map.vertex_darts(v).map(|d| map.dest(d)));
        for w in ring {
            finite(&mesh.positions, w).ok_or(RelaxError::NonFinite(w))?;
        }
        if !seen[v.index()] && !map.is_boundary_vertex(v) {
            seen[v.index()] = true;
            out.push(v);
        }
    }
    Ok(out)
}

/// What both relaxations start from: the vertices that move, the mean edge length `d`, a
/// copy of the positions to work on, the region's mask and Eq. 5 before.
struct Start {
    moving: Vec<Vert>,
    d: f64,
    pos: Vec<DVec3>,
    mask: Vec<bool>,
    before: f64,
}

impl Start {
    fn new(mesh: &Mesh, region: &[Vert]) -> Result<Start, RelaxError> {
        let moving = movable(mesh, region)?;
        let d = mean_edge_length(mesh);
        let pos = mesh.positions.clone();
        let mut mask = vec![false; mesh.map.vertex_slots()];
        region.iter().for_each(|v| mask[v.index()] = true);
        let before = energy(&mesh.map, &pos, region, &mask, d);
        Ok(Start {
            moving,
            d,
            pos,
            mask,
            before,
        })
    }
}

/// Writes the moving vertices' new finite positions into `mesh` and reports the run;
/// `(d, before, after)` are the edge length and Eq. 5 before and after.
fn finish(
    mesh: &mut Mesh,
    moving: &[Vert],
    pos: &[DVec3],
    (d, before, after): (f64, f64, f64),
    iterations: usize,
) -> Relaxed {
    let mut moved = 0;
    for &v in moving {
        let (old, new) = (&mut mesh.positions[v.index()], pos[v.index()]);
        if new.is_finite() && *old != new {
            *old = new;
            moved += 1;
        }
    }
    Relaxed {
        movable: moving.len(),
        moved,
        iterations,
        edge_length: d,
        energy_before: before,
        energy_after: after,
    }
}

/// Local relaxation (Turk-style, one vertex at a time; see [the module](self)): `iterations`
/// sweeps over the interior vertices of `region`, each moved to the centroid of its
/// neighbours within its tangent plane and projected onto `surface`. Vertices outside the
/// region keep their positions bit for bit; the map is not touched.
///
/// # Errors
/// [`RelaxError::DeadHandle`] or [`RelaxError::NonFinite`] for a region vertex (or a
/// neighbour's position); the mesh is then unchanged.
///
/// See [the module](self) for an example.
pub fn relax_local(
    mesh: &mut Mesh,
    surface: &Surface,
    region: &[Vert],
    iterations: usize,
) -> Result<Relaxed, RelaxError> {
    let Start {
        moving,
        d,
        mut pos,
        mask,
        before,
    } = Start::new(mesh, region)?;
    let map = &mesh.map;
    let mut count = 0;
    for _ in 0..iterations {
        for &v in &moving {
            let Some(n) = normal(map, &pos, v) else {
                continue;
            };
            let p = pos[v.index()];
            let (mut sum, mut k) = (DVec3::ZERO, 0.0);
            for w in map.vertex_darts(v).map(|e| map.dest(e)) {
                if let Some(q) = finite(&pos, w) {
                    sum += q;
                    k += 1.0;
                }
            }
            let t = sum / k - p;
            let q = surface.closest(p + t - n * n.dot(t));
            if k > 0.0 && q.is_finite() {
                pos[v.index()] = q;
            }
        }
        count += 1;
    }
    let after = energy(map, &pos, region, &mask, d);
    Ok(finish(mesh, &moving, &pos, (d, before, after), count))
}

#[cfg(feature = "sparse")]
mod global;
#[cfg(feature = "sparse")]
pub use global::relax_global;
