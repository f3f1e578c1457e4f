//! What every edit of the triangle optimizer must keep, shared by its passes and its
//! look-ahead: the face budget, and no triangle folded round the edited vertices.

use glam::DVec3;

use crate::quality::FaceQuality;
use crate::{Dart, Face, Map, Mesh, Vert};
use alloc::vec::Vec;

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

/// What an edit round some vertices is held to, read before it: the summed unit normals of
/// the triangles round them (the direction no triangle may turn away from) and how many
/// triangles near them are flipped.
pub(super) struct Facing {
    reference: DVec3,
    flipped: usize,
}

/// [`Facing`] round `verts`, before an edit.
pub(super) fn facing(mesh: &Mesh, verts: &[Vert]) -> Facing {
    let reference = verts
        .iter()
        .filter(|&&v| mesh.map.is_live_vertex(v))
        .flat_map(|&v| fan(&mesh.map, v))
        .filter_map(|x| face_normal(mesh, x))
        .sum::<DVec3>()
        .normalize_or_zero();
    Facing {
        reference,
        flipped: flipped_near(mesh, verts),
    }
}

/// Whether the edit folded the surface round `verts`: a triangle there is degenerate or
/// faces away from the reference (more than about 70 degrees off), or more triangles near
/// them are flipped than before (each against its edge-neighbours, as
/// [`crate::quality::FaceQuality::flipped`] reads it).
pub(super) fn folds(mesh: &Mesh, verts: &[Vert], before: &Facing) -> bool {
    let turned = verts
        .iter()
        .filter(|&&v| mesh.map.is_live_vertex(v))
        .flat_map(|&v| fan(&mesh.map, v))
        .any(|x| face_normal(mesh, x).is_none_or(|n| n.dot(before.reference) < 0.3));
    turned || before.more_flipped(mesh, verts)
}

impl Facing {
    /// Whether more triangles near `verts` are flipped than were near the vertices this was
    /// read round (the same vertices, or what an edit made of them).
    pub(super) fn more_flipped(&self, mesh: &Mesh, verts: &[Vert]) -> bool {
        flipped_near(mesh, verts) > self.flipped
    }
}

/// The flipped triangles among those round `verts` and their edge-neighbours (whose
/// neighbours changed with them).
fn flipped_near(mesh: &Mesh, verts: &[Vert]) -> usize {
    let m = &mesh.map;
    let mut faces: Vec<Face> = verts
        .iter()
        .filter(|&&v| m.is_live_vertex(v))
        .flat_map(|&v| fan(m, v))
        .flat_map(|d| {
            let tri = [d, m.next(d), m.next(m.next(d))];
            core::iter::once(m.face(d)).chain(tri.map(|x| m.face(x.twin())))
        })
        .flatten()
        .collect();
    faces.sort_unstable();
    faces.dedup();
    faces
        .into_iter()
        .filter(|&f| FaceQuality::of(mesh, f).is_some_and(|q| q.flipped))
        .count()
}

/// The darts leaving `v` that have a face (one per triangle round `v`).
pub(super) fn fan(map: &Map, v: Vert) -> impl Iterator<Item = Dart> + '_ {
    map.vertex_darts(v).filter(move |&x| map.face(x).is_some())
}
