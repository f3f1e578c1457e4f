//! The triangle operators on a [`Mesh`] (the `mesh_*` wrappers): the topology changes as in
//! [`super`], and the positions follow (the rules are on [`Placed`]).
//!
//! ```
//! use zipmesh::{gen, ops::tri};
//! let mut mesh = gen::random_triangle(300, 0, 1, 2);
//! let before = mesh.clone();
//! let h = mesh.map.darts().find(|&d| tri::can_collapse_edge(&mesh.map, d).is_ok()).unwrap();
//! let placed = tri::mesh_collapse_edge(&mut mesh, h).unwrap();
//! assert_eq!(mesh.map.num_vertices(), before.map.num_vertices() - 1);
//! placed.undo(&mut mesh).unwrap();
//! assert_eq!(mesh, before);
//! ```

use super::{EdgeCollapse, EdgeFlip, EdgeSplit, Undo, VertexSplit};
use crate::map::{Dart, NONE};
use crate::mesh::Mesh;
use crate::ops::Refusal;
use glam::DVec3;

/// A topological record plus the one position the wrapper wrote.
///
/// The `mesh_*` wrappers place positions by these rules:
/// * [`mesh_flip_edge`]: no position changes.
/// * [`mesh_collapse_edge`]: the kept vertex moves to the midpoint of the collapsed edge.
/// * [`mesh_split_vertex`]: `w` stays; the new vertex goes halfway between `w` and the
///   average of its other neighbours (`a`, `b` and the ends of the moved darts), inside its
///   own fan.
/// * [`mesh_split_edge`]: the new vertex goes to the midpoint of the edge.
///
/// A position slot that did not exist is created (positions follow vertex slots); the
/// record's `undo` restores the topology and then the one position it overwrote, so the
/// whole [`Mesh`] is equal (`==`) to the one before.
///
/// ```
/// use zipmesh::{gen, ops::tri};
/// let mut mesh = gen::random_triangle(100, 0, 0, 3);
/// let before = mesh.clone();
/// let placed = tri::mesh_split_edge(&mut mesh, zipmesh::Dart::new(0)).unwrap();
/// placed.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed<R> {
    /// The record of the topological operation.
    pub record: R,
    /// The vertex slot whose position was written (`u32::MAX` if none).
    slot: u32,
    /// Its position before, if the slot existed.
    old: Option<DVec3>,
    /// Length of the position array before.
    old_len: usize,
}

impl<R: Undo> Placed<R> {
    /// Undoes the operation and restores the position it overwrote; on
    /// [`Refusal::StaleRecord`] nothing changes.
    ///
    /// ```
    /// use zipmesh::{gen, ops::tri};
    /// let mut mesh = gen::random_triangle(100, 0, 1, 8);
    /// let before = mesh.clone();
    /// let h = mesh.map.darts().find(|&d| tri::can_collapse_edge(&mesh.map, d).is_ok()).unwrap();
    /// let placed = tri::mesh_collapse_edge(&mut mesh, h).unwrap();
    /// placed.undo(&mut mesh).unwrap();
    /// assert_eq!(mesh, before);
    /// ```
    pub fn undo(&self, mesh: &mut Mesh) -> Result<(), Refusal> {
        self.record.undo(&mut mesh.map)?;
        if let (Some(old), Some(p)) = (self.old, mesh.positions.get_mut(self.slot as usize)) {
            *p = old;
        }
        mesh.positions.truncate(self.old_len);
        Ok(())
    }
}

fn pos(mesh: &Mesh, v: u32) -> DVec3 {
    mesh.positions
        .get(v as usize)
        .copied()
        .unwrap_or(DVec3::ZERO)
}

/// Writes `p` at slot `v`, growing the array if needed, and returns the record of it.
fn place<R>(mesh: &mut Mesh, record: R, v: u32, p: DVec3) -> Placed<R> {
    let old_len = mesh.positions.len();
    let old = mesh.positions.get(v as usize).copied();
    if old.is_none() {
        mesh.positions.resize(v as usize + 1, DVec3::ZERO);
    }
    mesh.positions[v as usize] = p;
    Placed {
        record,
        slot: v,
        old,
        old_len,
    }
}

/// [`super::flip_edge`] on a mesh; no position changes.
///
/// ```
/// use zipmesh::{gen, ops::tri, Dart};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let before = mesh.positions.clone();
/// let h = mesh.map.darts().find(|&d| tri::can_flip_edge(&mesh.map, d).is_ok()).unwrap();
/// tri::mesh_flip_edge(&mut mesh, h).unwrap();
/// assert_eq!(mesh.positions, before);
/// ```
pub fn mesh_flip_edge(mesh: &mut Mesh, h: Dart) -> Result<Placed<EdgeFlip>, Refusal> {
    let record = super::flip_edge(&mut mesh.map, h)?;
    Ok(Placed {
        record,
        slot: NONE,
        old: None,
        old_len: mesh.positions.len(),
    })
}

/// [`super::collapse_edge`] on a mesh; the kept vertex moves to the edge's midpoint.
///
/// ```
/// use zipmesh::{gen, ops::tri};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let h = mesh.map.darts().find(|&d| tri::can_collapse_edge(&mesh.map, d).is_ok()).unwrap();
/// let (v, u) = (mesh.map.origin(h).index(), mesh.map.dest(h).index());
/// let mid = (mesh.positions[u] + mesh.positions[v]) / 2.0;
/// let placed = tri::mesh_collapse_edge(&mut mesh, h).unwrap();
/// assert_eq!(mesh.positions[placed.record.kept().index()], mid);
/// ```
pub fn mesh_collapse_edge(mesh: &mut Mesh, h: Dart) -> Result<Placed<EdgeCollapse>, Refusal> {
    let (v, u) = (mesh.map.origin(h).0, mesh.map.dest(h).0);
    let mid = (pos(mesh, u) + pos(mesh, v)) * 0.5;
    let record = super::collapse_edge(&mut mesh.map, h)?;
    Ok(place(mesh, record, u, mid))
}

/// [`super::split_vertex`] on a mesh; `w` stays and the new vertex goes halfway between `w`
/// and the average of its other neighbours.
///
/// ```
/// use zipmesh::{gen, ops::tri, Vert};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let w = Vert::new(5);
/// let d1 = mesh.map.vertex_dart(w);
/// let d2 = mesh.map.rotate_cw(mesh.map.rotate_cw(d1));
/// let placed = tri::mesh_split_vertex(&mut mesh, d1, d2).unwrap();
/// let v = placed.record.created().index();
/// assert!(mesh.positions[v] != mesh.positions[w.index()]);
/// ```
pub fn mesh_split_vertex(
    mesh: &mut Mesh,
    d1: Dart,
    d2: Dart,
) -> Result<Placed<VertexSplit>, Refusal> {
    let record = super::split_vertex(&mut mesh.map, d1, d2)?;
    let w = mesh.map.dest(record.edge()).0;
    let mut sum = DVec3::ZERO;
    let mut n = 0.0;
    for d in mesh.map.vertex_darts(record.created()) {
        let x = mesh.map.dest(d).0;
        if x != w {
            sum += pos(mesh, x);
            n += 1.0;
        }
    }
    let p = (pos(mesh, w) + sum / n) * 0.5;
    Ok(place(mesh, record, record.created().0, p))
}

/// [`super::split_edge`] on a mesh; the new vertex goes to the edge's midpoint.
///
/// ```
/// use zipmesh::{gen, ops::tri, Dart};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let (a, b) = (mesh.map.origin(Dart::new(0)).index(), mesh.map.dest(Dart::new(0)).index());
/// let mid = (mesh.positions[a] + mesh.positions[b]) / 2.0;
/// let placed = tri::mesh_split_edge(&mut mesh, Dart::new(0)).unwrap();
/// assert_eq!(mesh.positions[placed.record.created().index()], mid);
/// ```
pub fn mesh_split_edge(mesh: &mut Mesh, h: Dart) -> Result<Placed<EdgeSplit>, Refusal> {
    let (a, b) = (mesh.map.origin(h).0, mesh.map.dest(h).0);
    let mid = (pos(mesh, a) + pos(mesh, b)) * 0.5;
    let record = super::split_edge(&mut mesh.map, h)?;
    Ok(place(mesh, record, record.created().0, mid))
}
