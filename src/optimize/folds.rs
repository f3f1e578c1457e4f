//! Folded quads: where the geometry of a quad mesh turns over. The optimizer's Q-zips make
//! new vertices and move old ones; where the surface curves strongly, a new quad can come
//! out folded (docs/results.md, "Pictures"). No score term sees it, so the batches guard
//! against it ([`super::OptimizeOptions::fold_guard`]).

use glam::DVec3;

use super::marks::Marks;
use crate::map::Face;
use crate::{Mesh, Vert};

/// Whether face `f` is folded: a quad whose two triangles, for either diagonal, have
/// normals pointing apart (a negative dot product); a face of another degree is never
/// folded. Corners without a position read as the origin.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::{optimize::is_folded, Map, Mesh};
/// let map = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
/// let flat = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// let f = map.faces().next().unwrap();
/// assert!(!is_folded(&Mesh { map: map.clone(), positions: flat }, f));
/// // The third corner pulled across the first diagonal: a bow tie.
/// let bow = vec![DVec3::ZERO, DVec3::X, DVec3::new(-1.0, -1.0, 0.0), DVec3::Y];
/// assert!(is_folded(&Mesh { map, positions: bow }, f));
/// ```
pub fn is_folded(mesh: &Mesh, f: Face) -> bool {
    let map = &mesh.map;
    if !map.is_live_face(f) || map.degree(f) != 4 {
        return false;
    }
    let p = |v: Vert| {
        mesh.positions
            .get(v.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    };
    // A quad (checked above): four corners, in an array rather than a list per face.
    let mut c = [DVec3::ZERO; 4];
    for (x, d) in c.iter_mut().zip(map.face_darts(f)) {
        *x = p(map.origin(d));
    }
    crate::quality::diagonal_fold(&c)
}

/// The folded quads of `mesh` ([`is_folded`]).
///
/// ```
/// use zipmesh::{gen, optimize::folded_quads};
/// assert_eq!(folded_quads(&gen::torus_grid(6, 6)), 0);
/// ```
pub fn folded_quads(mesh: &Mesh) -> usize {
    mesh.map.faces().filter(|&f| is_folded(mesh, f)).count()
}

/// Quads flagged by the fold tests of [`crate::quality`]: by the diagonal test of
/// [`is_folded`], and by any of the three (a corner normal against the quad's, i.e. a
/// negative scaled Jacobian, or the quad's normal against its neighbours'): what `zipmesh
/// stats` counts as folded. The fold guard keeps neither count from rising.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct FoldCount {
    diagonal: usize,
    any: usize,
}

impl FoldCount {
    /// Counts face `f` if it is a quad the tests flag.
    fn add(&mut self, mesh: &Mesh, f: Face) {
        if !mesh.map.is_live_face(f) || mesh.map.degree(f) != 4 {
            return;
        }
        if let Some(q) = crate::quality::FaceQuality::of(mesh, f) {
            self.diagonal += usize::from(q.folds.diagonal);
            self.any += usize::from(q.folds.any());
        }
    }

    /// Whether either count is above `before`'s.
    pub(super) fn rises_from(self, before: FoldCount) -> bool {
        self.diagonal > before.diagonal || self.any > before.any
    }
}

/// The [`FoldCount`] of the faces round `v`.
pub(super) fn folds_round(mesh: &Mesh, v: Vert) -> FoldCount {
    let mut n = FoldCount::default();
    for f in mesh.map.vertex_darts(v).filter_map(|d| mesh.map.face(d)) {
        n.add(mesh, f);
    }
    n
}

/// The [`FoldCount`] of `mesh`.
pub(super) fn unsound_quads(mesh: &Mesh) -> FoldCount {
    let mut n = FoldCount::default();
    for f in mesh.map.faces() {
        n.add(mesh, f);
    }
    n
}

/// The [`FoldCount`] of the quads with a corner among `verts` (each counted once, by
/// `marks`: the guard counts round every candidate, so without listing and sorting the
/// faces).
pub(super) fn folded_near(mesh: &Mesh, verts: &[Vert], marks: &mut Marks) -> FoldCount {
    let map = &mesh.map;
    marks.begin(map.face_slots());
    let mut n = FoldCount::default();
    for &v in verts.iter().filter(|&&v| map.is_live_vertex(v)) {
        for f in map.vertex_darts(v).filter_map(|d| map.face(d)) {
            if marks.first(f.index()) {
                n.add(mesh, f);
            }
        }
    }
    n
}
