//! The quality of a whole mesh in a few numbers: counts below thresholds and percentiles,
//! since a cleaned mesh is as good as its worst elements.

use alloc::vec::Vec;

use super::face::{measure_faces, FaceQuality};
use super::reference::{Distances, Reference};
use crate::Mesh;

/// Triangles with a corner angle below this many degrees count as thin
/// ([`Summary::thin_triangles`]).
///
/// ```
/// assert_eq!(zipmesh::quality::THIN_TRIANGLE_DEGREES, 10.0);
/// ```
pub const THIN_TRIANGLE_DEGREES: f64 = 10.0;

/// How many quads each fold test flags (a quad may be flagged by several).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FoldCounts {
    /// (a) Quads whose diagonal splits point apart ([`super::diagonal_fold`]).
    pub diagonal: usize,
    /// (b) Quads with a corner normal against the quad's normal ([`super::corner_fold`]).
    pub corner: usize,
    /// (c) Quads whose normal points against their neighbours' ([`super::Folds`]).
    pub neighbours: usize,
}

/// Order statistics of the quads' scaled Jacobians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Percentiles {
    /// The smallest.
    pub min: f64,
    /// The 1st percentile (nearest rank: the `ceil(n / 100)`-th smallest of `n`).
    pub p1: f64,
    /// The 5th percentile (nearest rank).
    pub p5: f64,
    /// The median (nearest rank: the `ceil(n / 2)`-th smallest).
    pub median: f64,
}

/// The quality of a mesh: folds, scaled Jacobians, angles, edge ratios and, against a
/// [`Reference`], the distance to the input surface. Each count is of live faces; what each
/// measure reads on degenerate geometry is in [`FaceQuality`] and its measures.
///
/// ```
/// use zipmesh::{gen, quality::Summary};
/// let s = Summary::of(&gen::grid(4, 3));
/// assert_eq!((s.quads, s.folded_quads, s.negative_jacobian), (12, 0, 0));
/// assert_eq!(s.jacobian.unwrap().p1, 1.0);
/// assert_eq!((s.min_angle, s.max_edge_ratio), (Some(90.0), Some(1.0)));
/// assert!(s.distance.is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// Live faces.
    pub faces: usize,
    /// Faces of degree 4.
    pub quads: usize,
    /// Faces of degree 3.
    pub triangles: usize,
    /// Quads flagged by any fold test.
    pub folded_quads: usize,
    /// Quads flagged by each fold test.
    pub folded_by: FoldCounts,
    /// Quads whose scaled Jacobian is below 0 (the same quads as [`FoldCounts::corner`]).
    pub negative_jacobian: usize,
    /// The quads' scaled Jacobians (degenerate quads count 0); `None` without quads.
    pub jacobian: Option<Percentiles>,
    /// The smallest corner angle of any face, degrees; `None` without faces.
    pub min_angle: Option<f64>,
    /// Triangles with a corner angle below [`THIN_TRIANGLE_DEGREES`].
    pub thin_triangles: usize,
    /// Triangles whose normal points against their neighbours' ([`FaceQuality::flipped`]).
    pub flipped_triangles: usize,
    /// The largest edge ratio of a face that is not degenerate; `None` without one.
    pub max_edge_ratio: Option<f64>,
    /// Faces with degenerate geometry ([`FaceQuality::degenerate`]).
    pub degenerate_faces: usize,
    /// The vertices' distances to the reference surface; `None` from [`Summary::of`].
    pub distance: Option<Distances>,
}

impl Summary {
    /// The quality of `mesh` on its own (no distance).
    ///
    /// See [`Summary`] for an example.
    pub fn of(mesh: &Mesh) -> Self {
        let faces = measure_faces(mesh);
        let mut s = Summary {
            faces: faces.len(),
            quads: 0,
            triangles: 0,
            folded_quads: 0,
            folded_by: FoldCounts::default(),
            negative_jacobian: 0,
            jacobian: None,
            min_angle: None,
            thin_triangles: 0,
            flipped_triangles: 0,
            max_edge_ratio: None,
            degenerate_faces: 0,
            distance: None,
        };
        let mut jacobians = Vec::with_capacity(faces.len());
        for (_, q) in &faces {
            s.count(q);
            jacobians.extend(q.scaled_jacobian);
        }
        jacobians.sort_by(f64::total_cmp);
        s.jacobian = percentiles(&jacobians);
        s
    }

    /// The quality of `mesh` with its vertices' distances to `reference` (the input surface
    /// of an edit, say).
    ///
    /// ```
    /// use zipmesh::{gen, quality::{Reference, Summary}};
    /// let input = gen::grid(3, 4);
    /// let mut edited = input.clone();
    /// edited.positions[7].z = 0.05; // 1% of the diagonal
    /// let s = Summary::against(&edited, &Reference::new(&input));
    /// assert!((s.distance.unwrap().max - 0.01).abs() < 1e-15);
    /// ```
    pub fn against(mesh: &Mesh, reference: &Reference) -> Self {
        Summary {
            distance: Distances::of(mesh, reference),
            ..Summary::of(mesh)
        }
    }

    /// Adds one face's measures to the counts.
    fn count(&mut self, q: &FaceQuality) {
        self.quads += usize::from(q.degree == 4);
        self.triangles += usize::from(q.degree == 3);
        self.folded_quads += usize::from(q.folds.any());
        self.folded_by.diagonal += usize::from(q.folds.diagonal);
        self.folded_by.corner += usize::from(q.folds.corner);
        self.folded_by.neighbours += usize::from(q.folds.neighbours);
        self.negative_jacobian += usize::from(q.scaled_jacobian.is_some_and(|j| j < 0.0));
        let thin = q.degree == 3 && q.angles.min < THIN_TRIANGLE_DEGREES;
        self.thin_triangles += usize::from(thin);
        self.flipped_triangles += usize::from(q.flipped);
        self.degenerate_faces += usize::from(q.degenerate);
        self.min_angle = Some(self.min_angle.map_or(q.angles.min, |m| m.min(q.angles.min)));
        if !q.degenerate {
            let r = q.edge_ratio;
            self.max_edge_ratio = Some(self.max_edge_ratio.map_or(r, |m| m.max(r)));
        }
    }
}

/// The order statistics of `sorted` (ascending); `None` if empty.
fn percentiles(sorted: &[f64]) -> Option<Percentiles> {
    Some(Percentiles {
        min: *sorted.first()?,
        p1: super::nearest_rank(sorted, 1.0)?,
        p5: super::nearest_rank(sorted, 5.0)?,
        median: super::nearest_rank(sorted, 50.0)?,
    })
}
