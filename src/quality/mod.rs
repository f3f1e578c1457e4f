//! Quality as a measurement: whether the geometry of a mesh is sound after an edit.
//!
//! The connectivity of an edit is checked by the kernel; its geometry is measured here, per
//! element and in a [`Summary`] of percentiles and counts below thresholds. For a quad
//! `p0 p1 p2 p3` with corner normals `c_i = (p_{i+1} - p_i) x (p_{i-1} - p_i)` and normal
//! `n = unit((p2 - p0) x (p3 - p1))`:
//!
//! * [`scaled_jacobian`]: `min_i (c_i . n) / (|p_{i+1} - p_i| |p_{i-1} - p_i|)` (Knupp,
//!   "Algebraic mesh quality metrics", SIAM J. Sci. Comput. 2001; Verdict's quad metric):
//!   1 for a rectangle, 0 degenerate, below 0 where a corner is inverted.
//! * Folded ([`Folds`]) by any of three tests: (a) [`diagonal_fold`], the two triangles of
//!   either diagonal split point apart; (b) [`corner_fold`], a corner normal points against
//!   `n`; (c) `n` points against the sum of the unit normals of the faces across its edges.
//!
//! Every face has its corner [`angles`] and [`edge_ratio`]; a triangle is flipped when its
//! normal points against the sum of its edge-neighbours' unit normals. Against a
//! [`Reference`] (the input surface), [`Distances`] measure how far the vertices moved off
//! it, as fractions of the input's bounding-box diagonal. `zipmesh stats` prints the
//! summary; docs/quality.md has the numbers of the shipped meshes.
//!
//! Degenerate geometry (zero-length sides, corners that are not finite) never panics: each
//! measure says what it reads as, and [`FaceQuality::degenerate`] flags the face.
//!
//! ```
//! use glam::DVec3;
//! use zipmesh::{gen, quality::{Reference, Summary}};
//! let input = gen::grid(4, 4);
//! let mut edited = input.clone();
//! edited.positions[6] = DVec3::new(1.9, 1.9, 0.0); // a vertex pushed into the next quad
//! let s = Summary::against(&edited, &Reference::new(&input));
//! assert_eq!((s.quads, s.folded_quads, s.negative_jacobian), (16, 1, 1));
//! assert_eq!(s.distance.unwrap().max, 0.0); // still on the plane
//! ```

mod bounds;
mod face;
mod reference;
mod summary;

pub use crate::geometry::element::{
    against_neighbours, angles, corner_fold, corner_normal, corners, diagonal_fold, edge_ratio,
    neighbour_normals, normal, quad_normal, scaled_jacobian, Angles,
};
pub use bounds::{Bound, Bounds};
pub use face::{measure_faces, FaceQuality, Folds};
pub use reference::{Distances, Reference};
pub use summary::{FoldCounts, Percentiles, Summary, THIN_TRIANGLE_DEGREES};

/// The `q`-th percentile of `sorted` (ascending) by nearest rank: the `ceil(q / 100 * n)`-th
/// smallest of `n` (the smallest for `q = 0`); `None` if empty.
fn nearest_rank(sorted: &[f64], q: f64) -> Option<f64> {
    let n = sorted.len();
    let rank = libm::ceil(q / 100.0 * n as f64) as usize;
    sorted.get(rank.clamp(1, n.max(1)) - 1).copied()
}

#[cfg(test)]
mod tests;
