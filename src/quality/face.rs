//! The measures of one face of a mesh, its neighbours included: which fold tests fire for a
//! quad, whether a triangle is flipped.

use alloc::vec::Vec;

use glam::DVec3;

use crate::geometry::element::{self, corners, neighbour_normals, Angles};
use crate::map::Face;
use crate::Mesh;

/// Which of the three fold tests fire for a quad (all `false` for other faces).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Folds {
    /// (a) The two triangles of either diagonal split point apart
    /// ([`element::diagonal_fold`]).
    pub diagonal: bool,
    /// (b) A corner normal points against the quad's normal ([`element::corner_fold`]).
    pub corner: bool,
    /// (c) The quad's normal points against the sum of the unit normals of the faces across
    /// its edges (see [`FaceQuality::of_corners`]).
    pub neighbours: bool,
}

impl Folds {
    /// Whether any test fires: the quad is folded.
    ///
    /// ```
    /// use zipmesh::quality::Folds;
    /// assert!(!Folds::default().any());
    /// assert!(Folds { neighbours: true, ..Folds::default() }.any());
    /// ```
    pub fn any(&self) -> bool {
        self.diagonal || self.corner || self.neighbours
    }
}

/// Every measure of one face.
///
/// What is measured depends on the degree: every face has [`angles`](Self::angles) and an
/// [`edge_ratio`](Self::edge_ratio); a quad also a [`scaled_jacobian`](Self::scaled_jacobian)
/// and its [`folds`](Self::folds); a triangle also [`flipped`](Self::flipped). Polygons of
/// other degrees have angles and the edge ratio only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceQuality {
    /// The number of corners.
    pub degree: usize,
    /// The smallest and largest corner angle, degrees ([`element::angles`]).
    pub angles: Angles,
    /// The longest side over the shortest ([`element::edge_ratio`]); infinity for a face
    /// with a zero-length side.
    pub edge_ratio: f64,
    /// A quad's scaled Jacobian ([`element::scaled_jacobian`]); `None` for other degrees.
    pub scaled_jacobian: Option<f64>,
    /// A quad's fold tests; all `false` for other degrees.
    pub folds: Folds,
    /// A triangle whose normal points against the sum of its edge-neighbours' unit normals;
    /// `false` for other degrees.
    pub flipped: bool,
    /// Geometry that the measures cannot read: fewer than three corners, a corner that is
    /// not finite, a zero-length side, or no normal ([`element::normal`] `None`). Such a
    /// face still gets every measure, read as each measure's documentation says.
    pub degenerate: bool,
}

impl FaceQuality {
    /// The measures of face `f` of `mesh`; `None` if `f` is not a live face. Corners
    /// without a position read as the origin.
    ///
    /// ```
    /// use zipmesh::{gen, quality::FaceQuality, Face};
    /// let q = FaceQuality::of(&gen::grid(2, 2), Face::new(0)).unwrap();
    /// assert_eq!((q.degree, q.scaled_jacobian, q.edge_ratio), (4, Some(1.0), 1.0));
    /// assert!(!q.folds.any() && !q.degenerate);
    /// ```
    pub fn of(mesh: &Mesh, f: Face) -> Option<Self> {
        if !mesh.map.is_live_face(f) {
            return None;
        }
        let around = neighbour_normals(mesh, f, |g| element::normal(&corners(mesh, g)));
        Some(Self::of_corners(&corners(mesh, f), around))
    }

    /// The measures of a face with corners `p`, in order, whose edge-neighbours' unit
    /// normals sum to `neighbours` (one term per edge with a face across it; zero for
    /// none, and then neither the neighbour fold test nor `flipped` fires).
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::quality::FaceQuality;
    /// let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
    /// assert!(!FaceQuality::of_corners(&tri, DVec3::Z * 3.0).flipped);
    /// assert!(FaceQuality::of_corners(&tri, -DVec3::Z).flipped);
    /// let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    /// assert!(FaceQuality::of_corners(&square, -DVec3::Z).folds.neighbours);
    /// ```
    pub fn of_corners(p: &[DVec3], neighbours: DVec3) -> Self {
        let n = element::normal(p);
        let against = n.is_some_and(|n| n.dot(neighbours) < 0.0);
        let mut q = FaceQuality {
            degree: p.len(),
            angles: element::angles(p),
            edge_ratio: element::edge_ratio(p),
            scaled_jacobian: None,
            folds: Folds::default(),
            flipped: false,
            degenerate: n.is_none() || !p.iter().all(|c| c.is_finite()),
        };
        // A zero-length side (any degree) shows as an infinite edge ratio.
        q.degenerate |= q.edge_ratio == f64::INFINITY;
        match p {
            [a, b, c, d] => {
                let quad = [*a, *b, *c, *d];
                q.scaled_jacobian = Some(element::scaled_jacobian(&quad));
                q.folds = Folds {
                    diagonal: element::diagonal_fold(&quad),
                    corner: element::corner_fold(&quad),
                    neighbours: against,
                };
            }
            [_, _, _] => q.flipped = against,
            _ => {}
        }
        q
    }
}

/// Every live face of `mesh` with its measures, in the order of [`crate::Map::faces`]. Each
/// face's normal is computed once (rather than once per neighbour, as repeated
/// [`FaceQuality::of`] would).
///
/// ```
/// use zipmesh::{gen, quality::measure_faces};
/// let all = measure_faces(&gen::torus_grid(6, 4));
/// assert_eq!(all.len(), 24);
/// assert!(all.iter().all(|(_, q)| !q.folds.any()));
/// ```
pub fn measure_faces(mesh: &Mesh) -> Vec<(Face, FaceQuality)> {
    let map = &mesh.map;
    let mut normals = alloc::vec![None; map.face_slots()];
    for f in map.faces() {
        normals[f.index()] = element::normal(&corners(mesh, f));
    }
    let normal = |g: Face| normals.get(g.index()).copied().flatten();
    map.faces()
        .map(|f| {
            let around = neighbour_normals(mesh, f, normal);
            (f, FaceQuality::of_corners(&corners(mesh, f), around))
        })
        .collect()
}
