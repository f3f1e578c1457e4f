//! Measures of one polygon from its corners in order: normals, the scaled Jacobian and the
//! fold tests of a quad, corner angles and the edge ratio of any polygon.
//!
//! Corner `i` of a polygon `p_0 .. p_{k-1}` has the sides `e1 = p_{i+1} - p_i` and
//! `e2 = p_{i-1} - p_i` (indices mod `k`) and the corner normal `c_i = e1 x e2`; a
//! counter-clockwise polygon seen from above has every `c_i` pointing up.

use core::f64::consts::PI;

use alloc::vec::Vec;

use glam::DVec3;

use crate::map::Face;
use crate::{Mesh, Vert};

/// The corner normal `c_i = (p_{i+1} - p_i) x (p_{i-1} - p_i)` of corner `i` (mod the
/// number of corners); zero for fewer than three corners.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::corner_normal;
/// let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// assert_eq!(corner_normal(&square, 0), DVec3::Z);
/// assert_eq!(corner_normal(&square, 6), DVec3::Z); // corner 2
/// ```
pub fn corner_normal(p: &[DVec3], i: usize) -> DVec3 {
    let k = p.len();
    if k < 3 {
        return DVec3::ZERO;
    }
    let i = i % k;
    let here = p[i];
    (p[(i + 1) % k] - here).cross(p[(i + k - 1) % k] - here)
}

/// A quad's normal `n = unit((p2 - p0) x (p3 - p1))`, the cross product of its diagonals;
/// `None` when the diagonals are parallel, a diagonal has length zero, or a corner is not
/// finite.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::quad_normal;
/// let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// assert_eq!(quad_normal(&square), Some(DVec3::Z));
/// assert_eq!(quad_normal(&[DVec3::ZERO; 4]), None);
/// ```
pub fn quad_normal(p: &[DVec3; 4]) -> Option<DVec3> {
    (p[2] - p[0]).cross(p[3] - p[1]).try_normalize()
}

/// A polygon's unit normal: for a triangle `unit((p1 - p0) x (p2 - p0))`, for a quad
/// [`quad_normal`], for other polygons Newell's (the sum of the corner-to-corner cross
/// products about the centroid). `None` for fewer than three corners or where that vector is
/// zero or not finite.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::normal;
/// let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert_eq!(normal(&tri), Some(DVec3::Z));
/// let pentagon: Vec<DVec3> = (0..5)
///     .map(|i| {
///         let a = i as f64 * core::f64::consts::TAU / 5.0;
///         DVec3::new(a.cos(), -a.sin(), 0.0) // clockwise
///     })
///     .collect();
/// assert!((normal(&pentagon).unwrap() + DVec3::Z).length() < 1e-12);
/// assert_eq!(normal(&tri[..2]), None);
/// ```
pub fn normal(p: &[DVec3]) -> Option<DVec3> {
    match p {
        [a, b, c] => (*b - *a).cross(*c - *a).try_normalize(),
        [a, b, c, d] => quad_normal(&[*a, *b, *c, *d]),
        _ if p.len() < 3 => None,
        _ => {
            // About the centroid: the same vector, with less cancellation far from the origin.
            let centre = p.iter().copied().sum::<DVec3>() / p.len() as f64;
            let mut n = DVec3::ZERO;
            for (i, &a) in p.iter().enumerate() {
                n += (a - centre).cross(p[(i + 1) % p.len()] - centre);
            }
            n.try_normalize()
        }
    }
}

/// The scaled Jacobian of a quad (Knupp 2001; the Verdict library's quad metric):
/// `min_i (c_i . n) / (|p_{i+1} - p_i| |p_{i-1} - p_i|)` with `n` the [`quad_normal`].
/// 1 for a rectangle, `sin` of the smallest angle for a planar parallelogram, 0 degenerate,
/// below 0 where a corner is inverted; in `[-1, 1]`.
///
/// Degenerate geometry reads as 0: a corner with a zero-length side (or a term that is not
/// finite) counts 0, and a quad without a normal ([`quad_normal`] `None`, which covers any
/// corner that is not finite) is 0.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::scaled_jacobian;
/// let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// assert_eq!(scaled_jacobian(&square), 1.0);
/// // Corner 2 pulled inside past the diagonal p1 p3: a dart, corner 2 inverted.
/// let dart = [DVec3::ZERO, DVec3::X, DVec3::new(0.25, 0.25, 0.0), DVec3::Y];
/// assert!(scaled_jacobian(&dart) < 0.0);
/// assert_eq!(scaled_jacobian(&[DVec3::ZERO, DVec3::X, DVec3::X, DVec3::Y]), 0.0);
/// ```
pub fn scaled_jacobian(p: &[DVec3; 4]) -> f64 {
    let Some(n) = quad_normal(p) else {
        return 0.0;
    };
    let mut sj = f64::INFINITY;
    for i in 0..4 {
        let (e1, e2) = (p[(i + 1) % 4] - p[i], p[(i + 3) % 4] - p[i]);
        let s = e1.cross(e2).dot(n) / (e1.length() * e2.length());
        sj = sj.min(if s.is_finite() { s } else { 0.0 });
    }
    // Rounding can put a right angle a hair past 1.
    sj.clamp(-1.0, 1.0)
}

/// Fold test (a): the two triangles of either diagonal split point apart, `c0 . c2 < 0`
/// (the split along `p1 p3`) or `c1 . c3 < 0` (along `p0 p2`). The same test as
/// [`crate::optimize::is_folded`].
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::diagonal_fold;
/// let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// assert!(!diagonal_fold(&square));
/// let bow_tie = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
/// assert!(diagonal_fold(&bow_tie));
/// ```
pub fn diagonal_fold(p: &[DVec3; 4]) -> bool {
    let c = |i| corner_normal(p, i);
    c(0).dot(c(2)) < 0.0 || c(1).dot(c(3)) < 0.0
}

/// Fold test (b): a corner normal points against the quad's normal, `c_i . n < 0` for some
/// `i`; never for a quad without a [`quad_normal`]. It fires exactly where a corner term
/// of the [`scaled_jacobian`] is negative.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::corner_fold;
/// let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// assert!(!corner_fold(&square));
/// let dart = [DVec3::ZERO, DVec3::X, DVec3::new(0.25, 0.25, 0.0), DVec3::Y];
/// assert!(corner_fold(&dart));
/// ```
pub fn corner_fold(p: &[DVec3; 4]) -> bool {
    quad_normal(p).is_some_and(|n| (0..4).any(|i| corner_normal(p, i).dot(n) < 0.0))
}

/// The smallest and largest corner angle of a polygon, in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Angles {
    /// The smallest corner angle (degrees, in `[0, 180]`).
    pub min: f64,
    /// The largest corner angle (degrees, in `[0, 180]`).
    pub max: f64,
}

/// The corner angles' range: at each corner the unsigned angle between its two sides, in
/// degrees (`atan2(|e1 x e2|, e1 . e2)`, exact near 0 and 180 where `acos` is not). In space
/// an angle has no sign, so an inverted corner reads as its mirror image: see the fold tests.
///
/// A corner with a zero-length side, or a corner that is not finite, reads as 0 degrees;
/// fewer than three corners read as `{ min: 0, max: 0 }`.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::angles;
/// let right = angles(&[DVec3::ZERO, DVec3::X, DVec3::Y]);
/// assert!((right.min - 45.0).abs() < 1e-12 && (right.max - 90.0).abs() < 1e-12);
/// let flat = angles(&[DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)]);
/// assert_eq!((flat.min, flat.max), (0.0, 180.0));
/// ```
pub fn angles(p: &[DVec3]) -> Angles {
    let k = p.len();
    if k < 3 {
        return Angles { min: 0.0, max: 0.0 };
    }
    let (mut min, mut max) = (f64::INFINITY, 0.0f64);
    for i in 0..k {
        let (e1, e2) = (p[(i + 1) % k] - p[i], p[(i + k - 1) % k] - p[i]);
        let a = libm::atan2(e1.cross(e2).length(), e1.dot(e2)) * (180.0 / PI);
        let usable = e1 != DVec3::ZERO && e2 != DVec3::ZERO && a.is_finite();
        let a = if usable { a } else { 0.0 };
        (min, max) = (min.min(a), max.max(a));
    }
    Angles { min, max }
}

/// The edge ratio: the longest side over the shortest; 1 for a square or an equilateral
/// triangle. A zero-length side, a corner that is not finite, or no corner reads as
/// infinity.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::quality::edge_ratio;
/// let rect = [DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0), DVec3::new(3.0, 1.0, 0.0), DVec3::Y];
/// assert_eq!(edge_ratio(&rect), 3.0);
/// assert_eq!(edge_ratio(&[DVec3::ZERO, DVec3::ZERO, DVec3::X]), f64::INFINITY);
/// ```
pub fn edge_ratio(p: &[DVec3]) -> f64 {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for (i, a) in p.iter().enumerate() {
        let l = (p[(i + 1) % p.len()] - *a).length();
        if !l.is_finite() {
            return f64::INFINITY;
        }
        (lo, hi) = (lo.min(l), hi.max(l));
    }
    let r = hi / lo;
    // 0/0 (every side zero-length) and x/0 alike: no shortest side to divide by.
    if lo > 0.0 && r.is_finite() {
        r
    } else {
        f64::INFINITY
    }
}

/// The corners of face `f` of `mesh`, in order; those without a position read as the
/// origin. Empty for a face that is not live.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::{gen, quality::corners, Face};
/// let c = corners(&gen::grid(1, 1), Face::new(0));
/// assert_eq!(c.len(), 4);
/// assert!(c.contains(&DVec3::ZERO));
/// ```
pub fn corners(mesh: &Mesh, f: Face) -> Vec<DVec3> {
    if !mesh.map.is_live_face(f) {
        return Vec::new();
    }
    let at = |v: Vert| {
        mesh.positions
            .get(v.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    };
    mesh.map
        .face_darts(f)
        .map(|d| at(mesh.map.origin(d)))
        .collect()
}

/// The sum of the unit normals (given by `normal`) of the faces across the edges of face
/// `f`, one term per edge; edges on the boundary and faces without a normal add nothing.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::{gen, quality::{corners, neighbour_normals, normal}, Face};
/// let m = gen::grid(3, 3); // the middle square has four neighbours, all facing up
/// let middle = Face::new(4);
/// let sum = neighbour_normals(&m, middle, |g| normal(&corners(&m, g)));
/// assert!((sum - DVec3::Z * 4.0).length() < 1e-12);
/// ```
pub fn neighbour_normals(mesh: &Mesh, f: Face, normal: impl Fn(Face) -> Option<DVec3>) -> DVec3 {
    let map = &mesh.map;
    if !map.is_live_face(f) {
        return DVec3::ZERO;
    }
    map.face_darts(f)
        .filter_map(|d| map.face(d.twin()))
        .filter(|&g| g != f)
        .filter_map(normal)
        .sum()
}

/// Whether face `f` points against its edge-neighbours: its unit normal's dot with the sum
/// of theirs is negative (a triangle's `flipped`, a quad's neighbour fold, in
/// [`crate::quality::FaceQuality`]); false for a face without a normal or neighbours.
///
/// ```
/// use zipmesh::{gen, quality::against_neighbours, Face};
/// let mut m = gen::grid(2, 1); // two unit squares side by side, vertices row by row
/// assert!(!against_neighbours(&m, Face::new(0)));
/// m.positions[2].x = 0.5; // fold the second square back over the first
/// m.positions[5].x = 0.5;
/// assert!(against_neighbours(&m, Face::new(0)) && against_neighbours(&m, Face::new(1)));
/// ```
pub fn against_neighbours(mesh: &Mesh, f: Face) -> bool {
    let n = |g: Face| normal(&corners(mesh, g));
    n(f).is_some_and(|x| x.dot(neighbour_normals(mesh, f, n)) < 0.0)
}
