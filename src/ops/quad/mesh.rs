//! The quad operators on a [`Mesh`]: the same topology, with positions for new or merged
//! vertices placed by a stated rule, and undo restoring the old positions exactly.

use super::{
    collapse_quad, insert_doublet, remove_valence2, rotate_edge, split_high_valence, split_vertex,
    QuadRecord, Rotation, VertexSplit,
};
use crate::map::{Dart, Vert};
use crate::mesh::Mesh;
use crate::ops::Refusal;
use glam::DVec3;

/// A quad operator applied to a [`Mesh`]: the topological record and the positions it
/// overwrote.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshEdit {
    record: QuadRecord,
    /// Old positions of overwritten slots (at most two), restored in reverse order.
    saved: [(Vert, DVec3); 2],
    n_saved: usize,
    /// `positions.len()` before; undo cuts the vector back to it.
    old_len: usize,
}

impl MeshEdit {
    fn new(record: QuadRecord, old_len: usize) -> MeshEdit {
        MeshEdit {
            record,
            saved: [(Vert(0), DVec3::ZERO); 2],
            n_saved: 0,
            old_len,
        }
    }

    /// Writes `p` at slot `v`, growing the vector if needed and remembering the old value.
    fn place(&mut self, mesh: &mut Mesh, v: Vert, p: DVec3) {
        let i = v.index();
        if i < self.old_len && self.n_saved < 2 {
            self.saved[self.n_saved] = (v, mesh.positions[i]);
            self.n_saved += 1;
        }
        if mesh.positions.len() <= i {
            mesh.positions.resize(i + 1, DVec3::ZERO);
        }
        mesh.positions[i] = p;
    }

    /// The topological record.
    ///
    /// ```
    /// use zipmesh::{gen, ops::quad::{self, QuadRecord}, Dart};
    /// let mut mesh = gen::torus_grid(4, 4);
    /// let e = quad::mesh_collapse_quad(&mut mesh, Dart::new(0)).unwrap();
    /// assert!(matches!(e.record(), QuadRecord::Collapse(_)));
    /// ```
    pub fn record(&self) -> &QuadRecord {
        &self.record
    }

    /// Undoes the topology (see [`QuadRecord::undo`]) and then the positions: the result is
    /// `==` the mesh before the edit, with the mesh as the edit left it.
    ///
    /// ```
    /// use zipmesh::{gen, ops::quad, Dart};
    /// let mut mesh = gen::cube(3);
    /// let before = mesh.clone();
    /// let e = quad::mesh_insert_doublet(&mut mesh, Dart::new(0)).unwrap();
    /// e.undo(&mut mesh).unwrap();
    /// assert_eq!(mesh, before);
    /// ```
    pub fn undo(self, mesh: &mut Mesh) -> Result<(), Refusal> {
        self.record.undo(&mut mesh.map)?;
        for &(v, p) in self.saved[..self.n_saved].iter().rev() {
            if let Some(x) = mesh.positions.get_mut(v.index()) {
                *x = p;
            }
        }
        mesh.positions.truncate(self.old_len);
        Ok(())
    }
}

fn pos(mesh: &Mesh, v: Vert) -> DVec3 {
    mesh.positions
        .get(v.index())
        .copied()
        .unwrap_or(DVec3::ZERO)
}

/// [`collapse_quad`] on a mesh; the merged vertex is placed at the midpoint of the two merged
/// corners.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::{gen, ops::quad, Dart};
/// let mut mesh = gen::grid(3, 3);
/// let before = mesh.clone();
/// let d = mesh.map.vertex_dart(zipmesh::Vert::new(5)); // an interior vertex
/// let (a, c) = (mesh.map.origin(d), mesh.map.origin(mesh.map.next(mesh.map.next(d))));
/// let mid = (mesh.positions[a.index()] + mesh.positions[c.index()]) / 2.0;
/// let e = quad::mesh_collapse_quad(&mut mesh, d).unwrap();
/// assert_eq!(mesh.positions[a.index()], mid);
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_collapse_quad(mesh: &mut Mesh, d: Dart) -> Result<MeshEdit, Refusal> {
    let old_len = mesh.positions.len();
    let r = collapse_quad(&mut mesh.map, d)?;
    let mid = (pos(mesh, r.kept()) + pos(mesh, r.removed())) * 0.5;
    let kept = r.kept();
    let mut e = MeshEdit::new(r.into(), old_len);
    e.place(mesh, kept, mid);
    Ok(e)
}

/// Places a split's new vertex halfway between the old vertex and the centroid of the new
/// vertex's neighbours; the kept vertex does not move.
fn place_split(mesh: &mut Mesh, r: VertexSplit, old_len: usize) -> MeshEdit {
    let (w, w2) = (r.kept(), r.created());
    let mut sum = DVec3::ZERO;
    let mut n = 0.0;
    for d in mesh.map.vertex_darts(w2) {
        sum += pos(mesh, mesh.map.dest(d));
        n += 1.0;
    }
    let centroid = if n > 0.0 { sum / n } else { pos(mesh, w) };
    let p = (pos(mesh, w) + centroid) * 0.5;
    let mut e = MeshEdit::new(r.into(), old_len);
    e.place(mesh, w2, p);
    e
}

/// [`split_vertex`] on a mesh; the kept vertex stays where it was and the new vertex is placed
/// halfway between it and the centroid of the new vertex's neighbours.
///
/// ```
/// use zipmesh::{gen, ops::quad, Vert};
/// let mut mesh = gen::torus_grid(4, 4);
/// let before = mesh.clone();
/// let s1 = mesh.map.vertex_dart(Vert::new(5));
/// let s2 = mesh.map.rotate_cw(mesh.map.rotate_cw(s1));
/// let e = quad::mesh_split_vertex(&mut mesh, s1, s2).unwrap();
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_split_vertex(mesh: &mut Mesh, s1: Dart, s2: Dart) -> Result<MeshEdit, Refusal> {
    let old_len = mesh.positions.len();
    let r = split_vertex(&mut mesh.map, s1, s2)?;
    Ok(place_split(mesh, r, old_len))
}

/// [`split_high_valence`] on a mesh, placing the new vertex as [`mesh_split_vertex`] does.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// let mut mesh = gen::torus_grid(5, 5);
/// quad::mesh_collapse_quad(&mut mesh, Dart::new(0)).unwrap();
/// let v = mesh.map.origin(Dart::new(0));
/// let before = mesh.clone();
/// let x = mesh.map.vertex_dart(v);
/// let e = quad::mesh_split_high_valence(&mut mesh, v, x).unwrap();
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_split_high_valence(mesh: &mut Mesh, v: Vert, first: Dart) -> Result<MeshEdit, Refusal> {
    let old_len = mesh.positions.len();
    let r = split_high_valence(&mut mesh.map, v, first)?;
    Ok(place_split(mesh, r, old_len))
}

/// [`remove_valence2`] on a mesh; no position changes (the deleted vertex's slot keeps its
/// position, as dead slots do).
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// let mut mesh = gen::torus_grid(4, 4);
/// let ins = quad::mesh_insert_doublet(&mut mesh, Dart::new(0)).unwrap();
/// let before = mesh.clone();
/// let v = mesh.map.origin(mesh.map.next(mesh.map.next(mesh.map.next(Dart::new(0)))));
/// let x = mesh.map.vertex_dart(v);
/// let e = quad::mesh_remove_valence2(&mut mesh, x).unwrap();
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_remove_valence2(mesh: &mut Mesh, x: Dart) -> Result<MeshEdit, Refusal> {
    let old_len = mesh.positions.len();
    let r = remove_valence2(&mut mesh.map, x)?;
    Ok(MeshEdit::new(r.into(), old_len))
}

/// [`insert_doublet`] on a mesh; the new vertex is placed at the midpoint of the diagonal it
/// joins.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// let mut mesh = gen::grid(1, 1);
/// let d = mesh.map.face_dart(zipmesh::Face::new(0));
/// let e = quad::mesh_insert_doublet(&mut mesh, d).unwrap();
/// let v = mesh.map.vertex_slots() - 1;
/// assert_eq!(mesh.positions[v], glam::DVec3::new(0.5, 0.5, 0.0));
/// ```
pub fn mesh_insert_doublet(mesh: &mut Mesh, d: Dart) -> Result<MeshEdit, Refusal> {
    let old_len = mesh.positions.len();
    let p = mesh.map.origin(d);
    let q = mesh.map.origin(mesh.map.next(mesh.map.next(d)));
    let r = insert_doublet(&mut mesh.map, d)?;
    let v = r.vertex();
    let mid = (pos(mesh, p) + pos(mesh, q)) * 0.5;
    let mut e = MeshEdit::new(r.into(), old_len);
    e.place(mesh, v, mid);
    Ok(e)
}

/// [`rotate_edge`] on a mesh; no position changes.
///
/// ```
/// use zipmesh::{gen, ops::quad::{self, Rotation}, Dart};
/// let mut mesh = gen::torus_grid(4, 4);
/// let before = mesh.clone();
/// let e = quad::mesh_rotate_edge(&mut mesh, Dart::new(0), Rotation::Clockwise).unwrap();
/// assert_eq!(mesh.positions, before.positions);
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_rotate_edge(mesh: &mut Mesh, h: Dart, dir: Rotation) -> Result<MeshEdit, Refusal> {
    let old_len = mesh.positions.len();
    let r = rotate_edge(&mut mesh.map, h, dir)?;
    Ok(MeshEdit::new(r.into(), old_len))
}
