//! What every edit of the triangle optimizer must keep, shared by its passes and its
//! look-ahead: the face budget, and no triangle folded round the edited vertices.

use glam::DVec3;

use crate::{Dart, Map, Mesh, Vert};

/// The face counts an edit may leave.
pub(super) struct Budget {
    pub(super) min: usize,
    pub(super) max: usize,
}

impl Budget {
    pub(super) fn holds(&self, map: &Map) -> bool {
        (self.min..=self.max).contains(&map.num_faces())
    }
}

/// The unit normal of the triangle of `d`, `None` if degenerate.
pub(super) fn face_normal(mesh: &Mesh, d: Dart) -> Option<DVec3> {
    let m = &mesh.map;
    let p = |v: Vert| mesh.positions[v.index()];
    let (a, b, c) = (p(m.origin(d)), p(m.dest(d)), p(m.dest(m.next(d))));
    (b - a).cross(c - a).try_normalize()
}

/// The summed unit normals of the triangles round `verts` (a reference direction for
/// [`folds`]).
pub(super) fn region_normal(mesh: &Mesh, verts: &[Vert]) -> DVec3 {
    verts
        .iter()
        .filter(|&&v| mesh.map.is_live_vertex(v))
        .flat_map(|&v| fan(&mesh.map, v))
        .filter_map(|x| face_normal(mesh, x))
        .sum::<DVec3>()
        .normalize_or_zero()
}

/// Whether a triangle round `verts` is degenerate or faces away from `reference` (more
/// than about 70 degrees off): the edit folded the surface there.
pub(super) fn folds(mesh: &Mesh, verts: &[Vert], reference: DVec3) -> bool {
    verts
        .iter()
        .filter(|&&v| mesh.map.is_live_vertex(v))
        .flat_map(|&v| fan(&mesh.map, v))
        .any(|x| face_normal(mesh, x).is_none_or(|n| n.dot(reference) < 0.3))
}

/// The darts leaving `v` that have a face (one per triangle round `v`).
pub(super) fn fan(map: &Map, v: Vert) -> impl Iterator<Item = Dart> + '_ {
    map.vertex_darts(v).filter(move |&x| map.face(x).is_some())
}
