//! Defects: how far a vertex is from regular, with the boundary's ideal valence read from
//! its angle (Q-zip paper, Sec. 4.1, "Boundary defects").

use alloc::vec::Vec;
use core::f64::consts::FRAC_PI_2;

use glam::DVec3;

use crate::{Mesh, Vert};

/// The ideal valence of a boundary vertex whose faces subtend the angle `theta` (radians):
/// `max(2, ceil(theta / (pi/2) + 1/2))`, the valence of a regular grid vertex with the
/// closest multiple of `pi/2` as its angle (a straight boundary, `theta = pi`, gives 3; a
/// convex corner, `pi/2`, gives 2; a concave corner, `3 pi/2`, gives 4).
///
/// ```
/// use zipmesh::optimize::ideal_boundary_valence;
/// use core::f64::consts::PI;
/// assert_eq!(ideal_boundary_valence(PI), 3);
/// assert_eq!(ideal_boundary_valence(PI / 2.0), 2);
/// assert_eq!(ideal_boundary_valence(1.5 * PI), 4);
/// assert_eq!(ideal_boundary_valence(0.1), 2);
/// ```
pub fn ideal_boundary_valence(theta: f64) -> usize {
    let k = libm::ceil(theta / FRAC_PI_2 + 0.5);
    // A NaN or negative angle (degenerate faces) reads as the smallest ideal valence.
    if k.is_finite() && k > 2.0 {
        k.min(1e6) as usize
    } else {
        2
    }
}

/// The sum of the tip angles at `v` of the faces around it (radians); 0 for an isolated or
/// dead vertex. Degenerate corners (a zero-length side) count 0.
///
/// ```
/// use zipmesh::{gen, optimize::vertex_angle, Vert};
/// let m = gen::grid(2, 2); // unit squares, vertex 0 a corner, vertex 1 on a side
/// assert!((vertex_angle(&m, Vert::new(0)) - core::f64::consts::FRAC_PI_2).abs() < 1e-12);
/// assert!((vertex_angle(&m, Vert::new(1)) - core::f64::consts::PI).abs() < 1e-12);
/// ```
pub fn vertex_angle(mesh: &Mesh, v: Vert) -> f64 {
    let map = &mesh.map;
    if !map.is_live_vertex(v) {
        return 0.0;
    }
    let at = |u: Vert| {
        mesh.positions
            .get(u.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    };
    let p = at(v);
    let mut sum = 0.0;
    for d in map.vertex_darts(v) {
        if map.face(d).is_none() {
            continue;
        }
        let a = at(map.dest(d)) - p;
        let b = at(map.origin(map.prev(d))) - p;
        let (la, lb) = (a.length(), b.length());
        if la > 0.0 && lb > 0.0 {
            sum += libm::acos((a.dot(b) / (la * lb)).clamp(-1.0, 1.0));
        }
    }
    sum
}

/// The defect of `v`: its valence minus its ideal valence (4 inside, the
/// [`ideal_boundary_valence`] of its angle on the boundary). Negative is v3-like (a v3, or a
/// boundary vertex with one edge too few), positive v5-like.
///
/// ```
/// use zipmesh::{gen, optimize::defect, Vert};
/// let m = gen::subdivided_icosahedron(1);
/// assert_eq!(defect(&m, Vert::new(0)), 1); // a v5
/// let g = gen::grid(3, 3);
/// assert_eq!(defect(&g, Vert::new(0)), 0); // a corner with two edges
/// ```
pub fn defect(mesh: &Mesh, v: Vert) -> i64 {
    let map = &mesh.map;
    if !map.is_live_vertex(v) {
        return 0;
    }
    let k = map.valence(v) as i64;
    if map.is_boundary_vertex(v) {
        k - ideal_boundary_valence(vertex_angle(mesh, v)) as i64
    } else {
        k - 4
    }
}

/// Whether the mesh already carries the least total |[`defect`]| that Gauss-Bonnet allows:
/// every defect has the same sign (or there is none). The signed sum of the defects is fixed
/// by the topology and the boundary's angles, and the total |defect| is at least its absolute
/// value, so no edit can lower it; the optimizer leaves such a mesh as it is (its v6+
/// would otherwise be split into v5 pairs, more singularities and more faces).
///
/// ```
/// use zipmesh::{gen, optimize::at_defect_minimum};
/// assert!(at_defect_minimum(&gen::cube(2))); // eight v3, all of one sign
/// assert!(at_defect_minimum(&gen::torus_grid(4, 4))); // nothing to cancel
/// assert!(!at_defect_minimum(&gen::subdivided_icosahedron(1))); // v3s and v5s
/// ```
pub fn at_defect_minimum(mesh: &Mesh) -> bool {
    let (mut negative, mut positive) = (false, false);
    for v in mesh.map.vertices() {
        let d = defect(mesh, v);
        negative |= d < 0;
        positive |= d > 0;
    }
    !(negative && positive)
}

/// A vertex with a non-zero [`defect`].
///
/// See [`singularities`] for an example.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Singularity {
    /// The vertex.
    pub vertex: Vert,
    /// Its defect (never 0).
    pub defect: i64,
    /// Whether it is on the boundary.
    pub boundary: bool,
}

impl Singularity {
    /// The charge of the electric score: `-defect` (a v3 is +1, a v5 -1).
    ///
    /// ```
    /// use zipmesh::{optimize::Singularity, Vert};
    /// let s = Singularity { vertex: Vert::new(0), defect: -1, boundary: false };
    /// assert_eq!(s.charge(), 1.0);
    /// ```
    pub fn charge(&self) -> f64 {
        -(self.defect as f64)
    }
}

/// Every vertex with a non-zero [`defect`], in vertex order.
///
/// ```
/// use zipmesh::{gen, optimize::singularities};
/// let s = singularities(&gen::subdivided_icosahedron(1));
/// assert_eq!(s.len(), 12 + 20); // 12 v5, 20 v3
/// ```
pub fn singularities(mesh: &Mesh) -> Vec<Singularity> {
    mesh.map
        .vertices()
        .filter_map(|v| {
            let d = defect(mesh, v);
            (d != 0).then(|| Singularity {
                vertex: v,
                defect: d,
                boundary: mesh.map.is_boundary_vertex(v),
            })
        })
        .collect()
}
