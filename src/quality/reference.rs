//! The distance of a mesh's vertices to a reference surface (the input before an edit).
//!
//! Closest points come from parry3d-f64's `TriMesh` with the `parry` feature and from
//! [`crate::geometry::Surface`] without it: the same distances (to 1e-16 of the diagonal);
//! parry's 2 to 5 times faster for vertices moved off the surface, the grid as fast or
//! faster for vertices on it (docs/quality.md, "Closest points").

use alloc::vec::Vec;

use glam::DVec3;

use crate::Mesh;

/// A reference surface: the faces of a mesh, each fanned from its first corner into
/// triangles, with its bounding box's diagonal as the unit of distance.
///
/// Triangles with a corner that is not finite are left out (they have no place to be
/// near); corners without a position read as the origin.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::{gen, quality::Reference};
/// let r = Reference::new(&gen::grid(3, 4)); // the rectangle [0, 3] x [0, 4]
/// assert_eq!(r.diagonal(), 5.0);
/// assert!((r.distance(DVec3::new(1.0, 1.0, 2.0)) - 2.0).abs() < 1e-12);
/// ```
pub struct Reference {
    diagonal: f64,
    triangles: usize,
    #[cfg(feature = "parry")]
    closest: Option<parry3d_f64::shape::TriMesh>,
    #[cfg(not(feature = "parry"))]
    closest: crate::geometry::Surface,
}

impl core::fmt::Debug for Reference {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Reference")
            .field("diagonal", &self.diagonal)
            .field("triangles", &self.triangles)
            .finish()
    }
}

impl Reference {
    /// The reference surface of `mesh`'s faces.
    ///
    /// See [`Reference`] for an example.
    pub fn new(mesh: &Mesh) -> Self {
        let triangles = finite_triangles(mesh);
        let (lo, hi) = triangles.iter().flatten().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let diagonal = if triangles.is_empty() {
            0.0
        } else {
            (hi - lo).length()
        };
        Reference {
            diagonal,
            triangles: triangles.len(),
            closest: build(triangles),
        }
    }

    /// The diagonal of the bounding box of the surface's triangles; 0 for a surface without
    /// triangles.
    ///
    /// See [`Reference`] for an example.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The distance from `p` to the closest point of the surface, in the mesh's units;
    /// infinity for a surface without triangles, NaN for a point that is not finite.
    ///
    /// See [`Reference`] for an example.
    pub fn distance(&self, p: DVec3) -> f64 {
        if !p.is_finite() {
            return f64::NAN;
        }
        if self.triangles == 0 {
            return f64::INFINITY;
        }
        self.search(p)
    }

    #[cfg(feature = "parry")]
    fn search(&self, p: DVec3) -> f64 {
        use parry3d_f64::query::PointQuery as _;
        let Some(t) = &self.closest else {
            return f64::INFINITY;
        };
        // Not `distance_to_local_point`: that one is negative for a point it reads as inside.
        let q = t.project_local_point(&parry3d_f64::math::Point::new(p.x, p.y, p.z), false);
        DVec3::new(q.point.x, q.point.y, q.point.z).distance(p)
    }

    #[cfg(not(feature = "parry"))]
    fn search(&self, p: DVec3) -> f64 {
        self.closest.closest(p).distance(p)
    }
}

#[cfg(feature = "parry")]
fn build(triangles: Vec<[DVec3; 3]>) -> Option<parry3d_f64::shape::TriMesh> {
    use parry3d_f64::math::Point;
    // Three corners per triangle, unshared: no topology is asked of the surface.
    let points = triangles
        .iter()
        .flatten()
        .map(|p| Point::new(p.x, p.y, p.z))
        .collect();
    let n = u32::try_from(triangles.len()).ok()?;
    let indices = (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    // The only refusal is an empty index list, which `distance` answers before asking.
    parry3d_f64::shape::TriMesh::new(points, indices).ok()
}

#[cfg(not(feature = "parry"))]
fn build(triangles: Vec<[DVec3; 3]>) -> crate::geometry::Surface {
    crate::geometry::Surface::from_triangles(triangles)
}

/// The faces of `mesh` fanned from their first corners, without the triangles that have a
/// corner that is not finite.
fn finite_triangles(mesh: &Mesh) -> Vec<[DVec3; 3]> {
    let mut out = Vec::with_capacity(2 * mesh.map.num_faces());
    for f in mesh.map.faces() {
        let c = super::corners(mesh, f);
        for k in 1..c.len().saturating_sub(1) {
            let t = [c[0], c[k], c[k + 1]];
            if t.iter().all(|p| p.is_finite()) {
                out.push(t);
            }
        }
    }
    out
}

/// How far the vertices of a mesh are from a [`Reference`], as fractions of the reference's
/// bounding-box [`diagonal`](Reference::diagonal) (of the distances themselves where the
/// diagonal is 0). The box is axis-aligned: a translation or a uniform scaling of mesh and
/// reference together changes none of these numbers, a rotation changes the diagonal (the
/// unit) and not the distances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Distances {
    /// The number of vertices measured: the live vertices with a finite position.
    pub vertices: usize,
    /// The mean distance.
    pub mean: f64,
    /// The 99th percentile (nearest rank).
    pub p99: f64,
    /// The largest distance.
    pub max: f64,
}

impl Distances {
    /// The distances of `mesh`'s live vertices with a finite position to `reference`;
    /// `None` if there is no such vertex or the reference has no triangle.
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::{gen, quality::{Distances, Reference}};
    /// let input = gen::grid(3, 4);
    /// let mut edited = input.clone();
    /// edited.positions[0].z = 0.5; // 0.1 of the diagonal, 5
    /// let d = Distances::of(&edited, &Reference::new(&input)).unwrap();
    /// assert_eq!((d.vertices, d.max), (20, 0.1));
    /// assert!((d.mean - 0.1 / 20.0).abs() < 1e-15);
    /// ```
    pub fn of(mesh: &Mesh, reference: &Reference) -> Option<Self> {
        if reference.triangles == 0 {
            return None;
        }
        let unit = if reference.diagonal > 0.0 {
            reference.diagonal
        } else {
            1.0
        };
        let mut d: Vec<f64> = mesh
            .map
            .vertices()
            .filter_map(|v| mesh.positions.get(v.index()))
            .filter(|p| p.is_finite())
            .map(|&p| reference.distance(p) / unit)
            .collect();
        d.sort_by(f64::total_cmp);
        let max = *d.last()?;
        Some(Distances {
            vertices: d.len(),
            mean: d.iter().sum::<f64>() / d.len() as f64,
            p99: super::nearest_rank(&d, 99.0).unwrap_or(max),
            max,
        })
    }
}
