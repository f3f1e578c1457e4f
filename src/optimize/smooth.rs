//! Smoothing after each batch near the scars (Q-zip paper, Sec. 4.1, "Smoothing"): a
//! valence-weighted Laplacian, each vertex then put back on the input surface.
//!
//! The paper smooths "in the polar geodesic parameterization of the one-ring of each vertex".
//! Our reading (docs/optimize.md): lay the one-ring flat by its polar map (each neighbour at
//! its edge length, at its cumulative tip angle scaled to sum to 2 pi), take the weighted
//! mean there, and map it back. To first order that mean is the weighted mean of the
//! neighbours in space followed by a projection onto the surface, which is what is done:
//! the weighted mean, then the closest point of the input surface.

use alloc::vec;
use alloc::vec::Vec;

use glam::DVec3;

use crate::geometry::Surface;
use crate::{Mesh, Vert};

/// The spring stiffness of an edge whose ends have valences summing to `sum`: 1 for 8 (two
/// regular vertices), 0.5 below, 2 above.
///
/// ```
/// use zipmesh::optimize::spring_stiffness;
/// assert_eq!((spring_stiffness(8), spring_stiffness(7), spring_stiffness(9)), (1.0, 0.5, 2.0));
/// ```
pub fn spring_stiffness(sum: usize) -> f64 {
    match sum {
        8 => 1.0,
        s if s < 8 => 0.5,
        _ => 2.0,
    }
}

/// `iterations` Jacobi steps of the valence-weighted Laplacian on `vertices` (interior ones
/// whose `fixed` mark is off), each step's new position projected onto `surface`.
///
/// ```
/// use zipmesh::{gen, optimize::{smooth, Surface}, Vert};
/// use glam::DVec3;
/// let mut m = gen::grid(2, 2);
/// let s = Surface::new(&m);
/// m.positions[4] = DVec3::new(1.3, 0.8, 0.0); // the centre, off its place
/// smooth(&mut m, &s, &[Vert::new(4)], &[], 1);
/// assert!((m.positions[4] - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-12);
/// ```
pub fn smooth(
    mesh: &mut Mesh,
    surface: &Surface,
    vertices: &[Vert],
    fixed: &[bool],
    iterations: usize,
) {
    laplacian(mesh, Some(surface), vertices, fixed, iterations);
}

/// The valence-weighted Laplacian of [`smooth`] on `vertices`, projected onto `surface` if
/// given; returns the moved vertices' previous positions (each vertex once, in order).
pub(crate) fn laplacian(
    mesh: &mut Mesh,
    surface: Option<&Surface>,
    vertices: &[Vert],
    fixed: &[bool],
    iterations: usize,
) -> Vec<(Vert, DVec3)> {
    let map = &mesh.map;
    let movable: Vec<Vert> = vertices
        .iter()
        .copied()
        .filter(|&v| {
            v.index() < mesh.positions.len()
                && map.is_live_vertex(v)
                && !map.is_boundary_vertex(v)
                && !fixed.get(v.index()).copied().unwrap_or(false)
        })
        .collect();
    let saved: Vec<(Vert, DVec3)> = movable
        .iter()
        .map(|&v| (v, mesh.positions[v.index()]))
        .collect();
    let mut next = vec![DVec3::ZERO; movable.len()];
    for _ in 0..iterations {
        for (i, &v) in movable.iter().enumerate() {
            let kv = map.valence(v);
            let (mut sum, mut w) = (DVec3::ZERO, 0.0);
            for d in map.vertex_darts(v) {
                let u = map.dest(d);
                let k = spring_stiffness(kv + map.valence(u));
                sum += mesh
                    .positions
                    .get(u.index())
                    .copied()
                    .unwrap_or(DVec3::ZERO)
                    * k;
                w += k;
            }
            next[i] = match (w > 0.0, surface) {
                (false, _) => mesh.positions[v.index()],
                (true, Some(s)) => s.closest(sum / w),
                (true, None) => sum / w,
            };
        }
        for (i, &v) in movable.iter().enumerate() {
            if next[i].is_finite() {
                mesh.positions[v.index()] = next[i];
            }
        }
    }
    saved
}
