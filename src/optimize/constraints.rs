//! Sharp features and protected regions (Q-zip paper, Sec. 4.1): what a surgery must leave
//! exactly as it was, and the checks that hold it to that.
//!
//! The guarantee is checked, not assumed: the sketch avoids the constrained edges (so paths
//! do not cross them), and every Q-zip and every smoothing step is then checked against the
//! recorded corners and end positions, and undone if it touched them.

use alloc::vec::Vec;

use glam::DVec3;

use crate::{Edge, Face, Mesh, Vert};

/// A protected face (its corners in cyclic order and their positions) or a feature edge (its
/// two ends and their positions), as recorded on the input.
#[derive(Clone, Debug, PartialEq)]
struct Kept {
    corners: Vec<Vert>,
    positions: Vec<DVec3>,
}

/// The protected faces and the feature edges of a run.
///
/// ```
/// use zipmesh::{gen, optimize::Constraints, Face};
/// let mesh = gen::grid(3, 3);
/// let mut c = Constraints::default();
/// c.protect_face(&mesh, Face::new(0)).unwrap();
/// assert!(c.holds(&mesh));
/// assert_eq!(c.protected_faces(), 1);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Constraints {
    faces: Vec<Kept>,
    features: Vec<Kept>,
}

/// A constraint named a face or an edge the mesh does not have.
///
/// ```
/// use zipmesh::{gen, optimize::{Constraints, ConstraintError}, Face};
/// let mut c = Constraints::default();
/// let e = c.protect_face(&gen::grid(1, 1), Face::new(5)).unwrap_err();
/// assert_eq!(e, ConstraintError::NoFace(5));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ConstraintError {
    /// No live face with this index.
    NoFace(usize),
    /// No edge joins these two vertices.
    NoEdge(usize, usize),
}

impl core::fmt::Display for ConstraintError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NoFace(i) => write!(f, "face {i} does not exist"),
            Self::NoEdge(a, b) => write!(f, "no edge joins vertices {a} and {b}"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ConstraintError {}

fn position(mesh: &Mesh, v: Vert) -> DVec3 {
    mesh.positions.get(v.index()).copied().unwrap_or(DVec3::NAN)
}

fn same_bits(a: DVec3, b: DVec3) -> bool {
    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)
}

impl Constraints {
    /// Protects face `f`: its corners, their positions and their cyclic order must stay.
    ///
    /// See [`Constraints`] for an example.
    pub fn protect_face(&mut self, mesh: &Mesh, f: Face) -> Result<(), ConstraintError> {
        if !mesh.map.is_live_face(f) {
            return Err(ConstraintError::NoFace(f.index()));
        }
        let corners: Vec<Vert> = mesh.map.face_darts(f).map(|d| mesh.map.origin(d)).collect();
        let positions = corners.iter().map(|&v| position(mesh, v)).collect();
        self.faces.push(Kept { corners, positions });
        Ok(())
    }

    /// Makes the edge `a b` a feature: it must stay an edge, both ends where they are.
    ///
    /// ```
    /// use zipmesh::{gen, optimize::Constraints, Vert};
    /// let mesh = gen::grid(2, 2);
    /// let mut c = Constraints::default();
    /// c.add_feature(&mesh, Vert::new(0), Vert::new(1)).unwrap();
    /// assert!(c.add_feature(&mesh, Vert::new(0), Vert::new(4)).is_err());
    /// assert_eq!(c.feature_edges(), 1);
    /// ```
    pub fn add_feature(&mut self, mesh: &Mesh, a: Vert, b: Vert) -> Result<(), ConstraintError> {
        let live = mesh.map.is_live_vertex(a) && mesh.map.is_live_vertex(b);
        if !live || mesh.map.dart_between(a, b).is_none() {
            return Err(ConstraintError::NoEdge(a.index(), b.index()));
        }
        let positions = [a, b].iter().map(|&v| position(mesh, v)).collect();
        self.features.push(Kept {
            corners: [a, b].into(),
            positions,
        });
        Ok(())
    }

    /// Adds as features every interior edge whose faces meet at a dihedral angle of at least
    /// `degrees` (the angle between their normals); returns how many were added.
    ///
    /// ```
    /// use zipmesh::{gen, optimize::Constraints};
    /// let cube = gen::cube(2);
    /// let mut c = Constraints::default();
    /// assert_eq!(c.add_sharp_edges(&cube, 60.0), 12 * 2);
    /// ```
    pub fn add_sharp_edges(&mut self, mesh: &Mesh, degrees: f64) -> usize {
        let cos_limit = libm::cos(degrees.to_radians());
        let sharp: Vec<Edge> = mesh
            .map
            .edges()
            .filter(|&e| {
                let d = e.dart(0);
                let (Some(f), Some(g)) = (mesh.map.face(d), mesh.map.face(d.twin())) else {
                    return false;
                };
                let (n, m) = (face_normal(mesh, f), face_normal(mesh, g));
                n != DVec3::ZERO && m != DVec3::ZERO && n.dot(m) <= cos_limit
            })
            .collect();
        for e in &sharp {
            let d = e.dart(0);
            let (a, b) = (mesh.map.origin(d), mesh.map.dest(d));
            // Always an edge: it came from the map.
            let _ = self.add_feature(mesh, a, b);
        }
        sharp.len()
    }

    /// The number of protected faces.
    ///
    /// See [`Constraints`] for an example.
    pub fn protected_faces(&self) -> usize {
        self.faces.len()
    }

    /// The number of feature edges.
    ///
    /// See [`Constraints::add_feature`] for an example.
    pub fn feature_edges(&self) -> usize {
        self.features.len()
    }

    /// Whether there is nothing to keep.
    ///
    /// ```
    /// assert!(zipmesh::optimize::Constraints::default().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty() && self.features.is_empty()
    }

    /// Whether every protected face is still a face with the same corners in the same cyclic
    /// order at the same positions (bit for bit), and every feature edge still an edge with
    /// both ends where they were.
    ///
    /// See [`Constraints`] for an example.
    pub fn holds(&self, mesh: &Mesh) -> bool {
        let map = &mesh.map;
        let positions_kept = |k: &Kept| {
            k.corners
                .iter()
                .zip(&k.positions)
                .all(|(&v, &p)| map.is_live_vertex(v) && same_bits(position(mesh, v), p))
        };
        let face_kept = |k: &Kept| {
            if !positions_kept(k) {
                return false;
            }
            let Some(d) = map.dart_between(k.corners[0], k.corners[1]) else {
                return false;
            };
            map.face(d).is_some_and(|f| {
                map.degree(f) == k.corners.len()
                    && map
                        .face_cycle(d)
                        .map(|x| map.origin(x))
                        .eq(k.corners.iter().copied())
            })
        };
        let edge_kept =
            |k: &Kept| positions_kept(k) && map.dart_between(k.corners[0], k.corners[1]).is_some();
        self.faces.iter().all(face_kept) && self.features.iter().all(edge_kept)
    }

    /// The vertices that must not move: every corner of a protected face and every end of a
    /// feature edge (with repeats).
    ///
    /// ```
    /// use zipmesh::{gen, optimize::Constraints, Face};
    /// let mesh = gen::grid(2, 2);
    /// let mut c = Constraints::default();
    /// c.protect_face(&mesh, Face::new(0)).unwrap();
    /// assert_eq!(c.locked_vertices().count(), 4);
    /// ```
    pub fn locked_vertices(&self) -> impl Iterator<Item = Vert> + '_ {
        self.faces
            .iter()
            .chain(&self.features)
            .flat_map(|k| k.corners.iter().copied())
    }

    /// The ends of the feature edges (with repeats).
    ///
    /// ```
    /// use zipmesh::{gen, optimize::Constraints, Vert};
    /// let mesh = gen::grid(2, 2);
    /// let mut c = Constraints::default();
    /// c.add_feature(&mesh, Vert::new(0), Vert::new(1)).unwrap();
    /// assert_eq!(c.feature_vertices().collect::<Vec<_>>(), [Vert::new(0), Vert::new(1)]);
    /// ```
    pub fn feature_vertices(&self) -> impl Iterator<Item = Vert> + '_ {
        self.features.iter().flat_map(|k| k.corners.iter().copied())
    }

    /// The edges no surgery path may use in the current mesh: every edge at a locked vertex
    /// (so that a path neither crosses a feature nor enters a protected face).
    ///
    /// ```
    /// use zipmesh::{gen, optimize::Constraints, Vert};
    /// let mesh = gen::grid(2, 2);
    /// let mut c = Constraints::default();
    /// c.add_feature(&mesh, Vert::new(0), Vert::new(1)).unwrap();
    /// assert_eq!(c.forbidden_edges(&mesh).len(), 4); // 2 at vertex 0, 3 at vertex 1, one shared
    /// ```
    pub fn forbidden_edges(&self, mesh: &Mesh) -> Vec<Edge> {
        let mut edges: Vec<Edge> = self
            .locked_vertices()
            .filter(|&v| mesh.map.is_live_vertex(v))
            .flat_map(|v| mesh.map.vertex_darts(v).map(|d| d.edge()))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        edges
    }
}

/// The unit normal of face `f` (Newell's method), or zero for a degenerate face.
pub(crate) fn face_normal(mesh: &Mesh, f: Face) -> DVec3 {
    let pts: Vec<DVec3> = mesh
        .map
        .face_darts(f)
        .map(|d| position(mesh, mesh.map.origin(d)))
        .collect();
    let mut n = DVec3::ZERO;
    for (i, p) in pts.iter().enumerate() {
        let q = pts[(i + 1) % pts.len()];
        n += p.cross(q);
    }
    n.try_normalize().unwrap_or(DVec3::ZERO)
}
