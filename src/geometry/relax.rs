//! Relaxing an edit's footprint on the input surface: the vertices a Q-zip (or the
//! preprocessing) created or moved, and a ring or two around them, each moved towards the
//! mean of its neighbours and put back on the surface, never into an inverted element.
//!
//! Placement ([`crate::qzip::Qzip::zip_along`]) puts a created vertex at the mean of its
//! neighbours: near them, but off a curved surface and, where the chain turned, often
//! inside a neighbouring quad. Relaxation is tangential smoothing with projection (as in
//! pmp-library's remeshing, QuadWild's and Instant Meshes' final smoothing): each sweep
//! moves each vertex of the region to the closest point of the input surface to its
//! neighbours' mean, and keeps the move only where its faces get no worse ("smart"
//! Laplacian: the fan's worst corner, read in the plane of the fan's normal before the
//! move, does not fall below its value before or below 0, its triangles' worst corner not
//! below its value before or below 20 degrees, no corner or diagonal fold appears, and no
//! more triangles round it or across their edges point against their edge-neighbours).
//! Boundary vertices keep their place after the projection; the projection itself is not
//! judged (a vertex off the surface is what the bounds forbid). The triangle optimizer relaxes
//! each batch the same way.

use alloc::vec;
use alloc::vec::Vec;

use glam::DVec3;

use super::element::{angles, corner_fold, corners, diagonal_fold, normal};
use super::region::{relax_region, touched_vertices};
use crate::geometry::Surface;
use crate::{Face, Map, Mesh, Vert};

/// How far and how long [`relax_footprint`] works.
///
/// ```
/// use zipmesh::geometry::RelaxOptions;
/// let o = RelaxOptions::default();
/// assert_eq!((o.rings, o.sweeps), (2, 10));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RelaxOptions {
    /// Rings of vertices around the seeds that move too (0: the seeds alone).
    pub rings: usize,
    /// Sweeps over the region (0: projection only).
    pub sweeps: usize,
}

impl Default for RelaxOptions {
    /// Two rings and ten sweeps: on the shipped meshes more of either changes the worst
    /// quads of a zip by little (docs/quality.md, "Q-zip placement").
    fn default() -> Self {
        RelaxOptions {
            rings: 2,
            sweeps: 10,
        }
    }
}

/// What [`relax_footprint`] did.
///
/// See [`relax_footprint`] for an example.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Relaxation {
    /// The vertices put on the surface: the live seeds and the region.
    pub projected: usize,
    /// The interior vertices within the rings of a seed, which the sweeps move.
    pub region: usize,
    /// Moves kept, over all sweeps.
    pub moves: usize,
    /// Moves refused (each vertex tries a full, a half and a quarter step per sweep).
    pub refused: usize,
}

/// The worst of a vertex's faces: how many are inverted, and the smallest corner term
/// `(c_i . n) / (|e1| |e2|)` with `n` fixed (the fan's normal before the move).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Fan {
    bad: usize,
    worst: f64,
    /// The worst corner term of its triangles alone.
    worst_triangle: f64,
    /// Its triangles with a true (3D) corner under [`THIN_DEGREES`]: the corner term, read
    /// in one plane, misses a triangle that turns thin out of that plane (a fan across a
    /// crease of the surface).
    thin: usize,
}

/// A triangle with a corner under this many degrees is thin to the relaxation: a move may
/// not add one to a vertex's fan.
const THIN_DEGREES: f64 = 20.0;

/// The corner term of a 20-degree corner: a triangle's worst corner may fall below it only
/// by rising (thin triangles are what a relaxed triangle mesh must not gain).
const TRIANGLE_FLOOR: f64 = 0.342_020_143_325_668_7;

impl Fan {
    /// Whether `self` (after a move) is no worse than `before`: no new inverted face, the
    /// worst corner above 0 or no lower than before, the worst triangle corner above
    /// 20 degrees or no lower than before, and no more thin triangles.
    fn accepts(&self, before: &Fan) -> bool {
        let triangles =
            self.worst_triangle >= TRIANGLE_FLOOR || self.worst_triangle >= before.worst_triangle;
        self.bad <= before.bad
            && (self.worst > 0.0 || self.worst >= before.worst)
            && triangles
            && self.thin <= before.thin
    }
}

/// Relaxes the footprint of an edit of `mesh` on `surface` (the input surface, say
/// `Surface::new(&input)`): the live `seeds` (the vertices the edit created or moved:
/// [`edited_vertices`] of the meshes before and after) are projected onto
/// the surface, then the interior vertices within `options.rings` of them are smoothed
/// tangentially for `options.sweeps` sweeps, never into a worse fan: a move is kept only if
/// the worst corner of the vertex's fan (read in the plane of the fan's normal before the
/// move) does not fall below its value before or below 0, the worst corner of its
/// triangles not below its value before or below 20 degrees, no corner or diagonal fold
/// appears, and where there are triangles no more of the faces round it and across their
/// edges point against their edge-neighbours ([`crate::quality::against_neighbours`]).
/// Deterministic: vertices go in slot order, and only their positions change.
///
/// ```
/// use zipmesh::optimize::Surface;
/// use zipmesh::geometry::{edited_vertices, relax_footprint, RelaxOptions};
/// use zipmesh::qzip::{Qzip, Tag};
/// use zipmesh::quality::{Reference, Summary};
/// use zipmesh::{gen, Vert};
/// let input = gen::subdivided_icosahedron(2);
/// let mut mesh = input.clone();
/// Qzip::new().zip(&mut mesh, Vert::new(42), Vert::new(0), Tag::LS).unwrap();
/// let seeds = edited_vertices(&input, &mesh);
/// let r = relax_footprint(&mut mesh, &Surface::new(&input), &seeds, RelaxOptions::default());
/// assert!(r.projected >= seeds.len() && r.region > 0);
/// let s = Summary::against(&mesh, &Reference::new(&input));
/// assert!(s.distance.unwrap().max < 1e-9);
/// assert_eq!(s.folded_quads, Summary::of(&input).folded_quads);
/// ```
pub fn relax_footprint(
    mesh: &mut Mesh,
    surface: &Surface,
    seeds: &[Vert],
    options: RelaxOptions,
) -> Relaxation {
    relax_footprint_fixed(mesh, surface, seeds, options, &[], &mut Vec::new())
}

/// [`relax_footprint`] with the vertices marked in `fixed` left where they are (neither
/// projected nor swept), the previous position of every vertex it may move pushed onto
/// `saved` (each once, in slot order) so that the caller can put them back.
pub(crate) fn relax_footprint_fixed(
    mesh: &mut Mesh,
    surface: &Surface,
    seeds: &[Vert],
    options: RelaxOptions,
    fixed: &[bool],
    saved: &mut Vec<(Vert, DVec3)>,
) -> Relaxation {
    let n = mesh.map.vertex_slots();
    if mesh.positions.len() < n {
        mesh.positions.resize(n, DVec3::ZERO);
    }
    let is_fixed = |v: Vert| fixed.get(v.index()).copied().unwrap_or(false);
    let mut region = relax_region(&mesh.map, seeds, options.rings);
    region.retain(|&v| !is_fixed(v));
    let mut r = Relaxation {
        region: region.len(),
        ..Relaxation::default()
    };
    let mut on: Vec<Vert> = seeds
        .iter()
        .copied()
        .filter(|&v| mesh.map.is_live_vertex(v) && !is_fixed(v))
        .chain(region.iter().copied())
        .collect();
    on.sort_unstable();
    on.dedup();
    saved.extend(on.iter().map(|&v| (v, mesh.positions[v.index()])));
    // Placement is near the surface, not on it: every vertex of the footprint goes onto it.
    for &v in &on {
        let p = mesh.positions[v.index()];
        mesh.positions[v.index()] = surface.closest(p);
    }
    r.projected = on.len();
    for _ in 0..options.sweeps {
        let moved = r.moves;
        for &v in &region {
            relax_vertex(mesh, surface, v, &mut r);
        }
        if r.moves == moved {
            break;
        }
    }
    r
}

/// One vertex's move of a sweep: the full step to its neighbours' mean (on the surface),
/// else a half or a quarter step, whichever the fan accepts first.
fn relax_vertex(mesh: &mut Mesh, surface: &Surface, v: Vert, r: &mut Relaxation) {
    let map = &mesh.map;
    let here = mesh.positions[v.index()];
    let (mut sum, mut len, mut k) = (DVec3::ZERO, 0.0, 0usize);
    for d in map.vertex_darts(v) {
        let p = mesh.positions[map.dest(d).index()];
        sum += p;
        len += p.distance(here);
        k += 1;
    }
    if k == 0 || !sum.is_finite() || !here.is_finite() {
        return;
    }
    let Some(n) = fan_normal(mesh, v) else {
        return;
    };
    let before = fan(mesh, v, n);
    // Triangles turned against their neighbours are what the fan's tests miss (quads have
    // the fold tests, and Q-zips' fold guard); read before the first move the fan accepts.
    let triangles = triangles_near(&mesh.map, v);
    let mut against = None;
    let target = sum / k as f64;
    for step in [1.0, 0.5, 0.25] {
        let p = surface.closest(here + (target - here) * step);
        // A move of less than a part in 1e6 of an edge is no move: it ends the sweeps.
        if p.distance(here) <= 1e-6 * len / k as f64 {
            return;
        }
        if fan_at(mesh, v, p, n).accepts(&before) {
            if !triangles {
                mesh.positions[v.index()] = p;
                r.moves += 1;
                return;
            }
            let was = *against.get_or_insert_with(|| against_near(mesh, v));
            mesh.positions[v.index()] = p;
            if against_near(mesh, v) <= was {
                r.moves += 1;
                return;
            }
            mesh.positions[v.index()] = here;
        }
        r.refused += 1;
    }
    mesh.positions[v.index()] = here;
}

/// Whether a face round `v` or across the edges of one is a triangle.
fn triangles_near(m: &Map, v: Vert) -> bool {
    m.vertex_darts(v).filter_map(|d| m.face(d)).any(|f| {
        m.degree(f) == 3
            || m.face_darts(f)
                .filter_map(|x| m.face(x.twin()))
                .any(|g| m.degree(g) == 3)
    })
}

/// The [`Fan`] of `v` with `v` moved to `p` (and back to where it was).
fn fan_at(mesh: &mut Mesh, v: Vert, p: DVec3, n: DVec3) -> Fan {
    let here = core::mem::replace(&mut mesh.positions[v.index()], p);
    let f = fan(mesh, v, n);
    mesh.positions[v.index()] = here;
    f
}

/// How many of the faces round `v` and across their edges (the faces whose normal, or whose
/// neighbours' normals, a move of `v` changes) point against their edge-neighbours, as
/// [`against_neighbours`] reads it. Each face's normal is computed once, without
/// allocating: this runs for every move the relaxation keeps.
fn against_near(mesh: &Mesh, v: Vert) -> usize {
    let m = &mesh.map;
    let mut near: Vec<Face> = m
        .vertex_darts(v)
        .filter_map(|d| m.face(d))
        .flat_map(|f| m.face_darts(f).filter_map(|x| m.face(x.twin())).chain([f]))
        .collect();
    near.sort_unstable();
    near.dedup();
    let mut normals: Vec<(Face, Option<DVec3>)> = Vec::with_capacity(4 * near.len());
    let mut count = 0;
    for &f in &near {
        let Some(n) = cached_normal(mesh, f, &mut normals) else {
            continue;
        };
        let mut sum = DVec3::ZERO;
        for g in m.face_darts(f).filter_map(|d| m.face(d.twin())) {
            if g != f {
                sum += cached_normal(mesh, g, &mut normals).unwrap_or(DVec3::ZERO);
            }
        }
        count += usize::from(n.dot(sum) < 0.0);
    }
    count
}

/// The unit normal of face `f` ([`normal`] of its corners), looked up in or added to `cache`.
fn cached_normal(mesh: &Mesh, f: Face, cache: &mut Vec<(Face, Option<DVec3>)>) -> Option<DVec3> {
    if let Some(&(_, n)) = cache.iter().find(|(g, _)| *g == f) {
        return n;
    }
    let mut p = [DVec3::ZERO; 8];
    let mut k = 0;
    for d in mesh.map.face_darts(f) {
        if k == p.len() {
            k = usize::MAX; // a long polygon: read it the allocating way
            break;
        }
        p[k] = mesh
            .positions
            .get(mesh.map.origin(d).index())
            .copied()
            .unwrap_or(DVec3::ZERO);
        k += 1;
    }
    let n = if k == usize::MAX {
        normal(&corners(mesh, f))
    } else {
        normal(&p[..k])
    };
    cache.push((f, n));
    n
}

/// The corners of each face round `v` (boundary darts have none).
fn faces_of(mesh: &Mesh, v: Vert) -> impl Iterator<Item = Vec<DVec3>> + '_ {
    mesh.map
        .vertex_darts(v)
        .filter_map(|d| mesh.map.face(d))
        .map(|f| corners(mesh, f))
}

/// The unit sum of the normals of `v`'s faces: the plane its moves are judged in.
fn fan_normal(mesh: &Mesh, v: Vert) -> Option<DVec3> {
    faces_of(mesh, v)
        .filter_map(|c| normal(&c))
        .sum::<DVec3>()
        .try_normalize()
}

/// The [`Fan`] of `v` read against the fixed normal `n`: a face is inverted when a corner
/// term is at most 0 or, for a quad, a fold test flags it.
fn fan(mesh: &Mesh, v: Vert, n: DVec3) -> Fan {
    let mut f = Fan {
        bad: 0,
        worst: f64::INFINITY,
        worst_triangle: f64::INFINITY,
        thin: 0,
    };
    for c in faces_of(mesh, v) {
        let k = c.len();
        let mut worst = f64::INFINITY;
        for i in 0..k {
            let (e1, e2) = (c[(i + 1) % k] - c[i], c[(i + k - 1) % k] - c[i]);
            let s = e1.cross(e2).dot(n) / (e1.length() * e2.length());
            worst = worst.min(if s.is_finite() { s } else { 0.0 });
        }
        let folded = match <[DVec3; 4]>::try_from(c.as_slice()) {
            Ok(q) => diagonal_fold(&q) || corner_fold(&q),
            Err(_) => false,
        };
        f.bad += usize::from(worst <= 0.0 || folded);
        f.worst = f.worst.min(worst);
        if k == 3 {
            f.worst_triangle = f.worst_triangle.min(worst);
            f.thin += usize::from(angles(&c).min < THIN_DEGREES);
        }
    }
    f
}

/// The vertices of `after` an edit of `before` created or moved: live in `after` and dead
/// in `before`, or with other neighbours ([`touched_vertices`]), or at
/// another position. The last catches a vertex a collapse removed and a later split made
/// again in the same slot, with the same neighbours but a new place. The seeds of
/// [`relax_footprint`].
///
/// ```
/// use zipmesh::geometry::edited_vertices;
/// use zipmesh::qzip::{Qzip, Tag};
/// use zipmesh::{gen, Vert};
/// let input = gen::subdivided_icosahedron(2);
/// let mut mesh = input.clone();
/// assert!(edited_vertices(&input, &mesh).is_empty());
/// Qzip::new().zip(&mut mesh, Vert::new(42), Vert::new(0), Tag::LS).unwrap();
/// assert!(!edited_vertices(&input, &mesh).is_empty());
/// ```
pub fn edited_vertices(before: &Mesh, after: &Mesh) -> Vec<Vert> {
    let mut out = touched_vertices(&before.map, &after.map);
    let moved = |v: Vert| before.positions.get(v.index()) != after.positions.get(v.index());
    out.extend(after.map.vertices().filter(|&v| moved(v)));
    out.sort_unstable();
    out.dedup();
    out
}

/// Widens the thin triangles of `mesh` on `surface`: each interior vertex of a triangle
/// with a corner under `degrees`, and each of its neighbours, moves where its fan's worst
/// triangle corner is widest, among the points of the surface closest to its neighbours'
/// mean and to the apex of an equilateral triangle on the far side of each of its
/// triangles (full, half and quarter steps), for up to `sweeps` sweeps. A move is kept only
/// if the fan's worst triangle corner rises, no more of its triangles are under `degrees`,
/// no face of the fan inverts, and no more faces near it point against their
/// edge-neighbours: the smallest angle of the mesh never falls, and no triangle turns.
/// The relaxation's Laplacian step ([`relax_footprint`]) leaves thin triangles where a
/// smoother fan needs a vertex off its neighbours' mean; this moves towards shape instead.
pub(crate) fn widen_thin_triangles(
    mesh: &mut Mesh,
    surface: &Surface,
    degrees: f64,
    sweeps: usize,
) -> Relaxation {
    let mut seeds = Vec::new();
    for f in mesh.map.faces() {
        if mesh.map.degree(f) == 3 && angles(&corners(mesh, f)).min < degrees {
            seeds.extend(mesh.map.face_darts(f).map(|d| mesh.map.origin(d)));
        }
    }
    let region = relax_region(&mesh.map, &seeds, 1);
    let mut r = Relaxation {
        region: region.len(),
        ..Relaxation::default()
    };
    for _ in 0..sweeps {
        let moved = r.moves;
        for &v in &region {
            widen_vertex(mesh, surface, v, degrees, &mut r);
        }
        if r.moves == moved {
            break;
        }
    }
    r
}

/// One vertex's move of [`widen_thin_triangles`]: the candidate point whose fan has the
/// widest worst triangle corner, if it beats the fan as it is.
fn widen_vertex(mesh: &mut Mesh, surface: &Surface, v: Vert, degrees: f64, r: &mut Relaxation) {
    let here = mesh.positions[v.index()];
    let Some(n) = fan_normal(mesh, v).filter(|_| here.is_finite()) else {
        return;
    };
    let before = fan(mesh, v, n);
    let (narrowest, thin) = triangle_angles_round(mesh, v, degrees);
    let mut best: Option<(DVec3, f64)> = None;
    for target in widening_targets(mesh, v, n) {
        for step in [1.0, 0.5, 0.25] {
            let p = surface.closest(here + (target - here) * step);
            let after = fan_at(mesh, v, p, n);
            let sound = p.is_finite()
                && after.bad <= before.bad
                && (after.worst > 0.0 || after.worst >= before.worst);
            if !sound {
                continue;
            }
            mesh.positions[v.index()] = p;
            let (min, count) = triangle_angles_round(mesh, v, degrees);
            mesh.positions[v.index()] = here;
            if count <= thin && min > best.map_or(narrowest, |(_, w)| w) {
                best = Some((p, min));
            }
        }
    }
    let Some((p, _)) = best else {
        return;
    };
    let was = against_near(mesh, v);
    mesh.positions[v.index()] = p;
    if against_near(mesh, v) <= was {
        r.moves += 1;
    } else {
        mesh.positions[v.index()] = here;
        r.refused += 1;
    }
}

/// Where [`widen_vertex`] looks: `v`'s neighbours' mean, and for each triangle round `v`
/// the apex of the equilateral triangle on its side opposite `v`, on `v`'s side of it, in
/// the plane of normal `n`.
fn widening_targets(mesh: &Mesh, v: Vert, n: DVec3) -> Vec<DVec3> {
    let m = &mesh.map;
    let at = |w: Vert| {
        mesh.positions
            .get(w.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    };
    let here = at(v);
    let ring: Vec<DVec3> = m.vertex_darts(v).map(|d| at(m.dest(d))).collect();
    let mut out = vec![ring.iter().sum::<DVec3>() / ring.len().max(1) as f64];
    for d in m.vertex_darts(v) {
        if m.face(d).is_none_or(|f| m.degree(f) != 3) {
            continue;
        }
        let (a, b) = (at(m.dest(d)), at(m.dest(m.next(d))));
        let mid = (a + b) / 2.0;
        let Some(mut up) = n.cross(b - a).try_normalize() else {
            continue;
        };
        if up.dot(here - mid) < 0.0 {
            up = -up;
        }
        // The height of an equilateral triangle of side 1, sqrt(3) / 2 (no sqrt in no_std).
        out.push(mid + up * (b - a).length() * 0.866_025_403_784_438_6);
    }
    out
}

/// The smallest corner angle of the triangles round `v` (degrees; 180 without one), and how
/// many of them have a corner under `degrees`.
fn triangle_angles_round(mesh: &Mesh, v: Vert, degrees: f64) -> (f64, usize) {
    let mut out = (180.0f64, 0);
    for c in faces_of(mesh, v).filter(|c| c.len() == 3) {
        let min = angles(&c).min;
        out = (out.0.min(min), out.1 + usize::from(min < degrees));
    }
    out
}
