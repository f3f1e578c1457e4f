//! The quad operators on a [`Mesh`]: the same topology, with positions for new or merged
//! vertices placed by a stated rule, and undo restoring the old positions exactly.

use super::{
    collapse_quad, insert_doublet, remove_valence2, rotate_edge, split_high_valence, split_vertex,
    QuadOp, QuadRecord, Rotation, VertexSplit,
};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{Edited, Journal, Mesh, Rule, VertexAttributes};
use crate::ops::Refusal;

/// A quad operator applied to a [`Mesh`]: the record and the positions it overwrote; its
/// `undo` restores the mesh `==` (see [`Edited`]).
pub type MeshEdit = Edited<QuadRecord>;

impl QuadOp {
    /// Applies the operator to a map and its per-vertex data: each operator's placement
    /// rule is stated here once (the `mesh_*` wrappers below apply it to positions).
    ///
    /// ```
    /// use zipmesh::{gen, ops::quad::QuadOp, Dart};
    /// let mut mesh = gen::torus_grid(5, 5);
    /// let mut layers = (mesh.positions.clone(), vec![true; mesh.map.vertex_slots()]);
    /// let before = (mesh.map.clone(), layers.clone());
    /// let e = QuadOp::InsertDoublet(Dart::new(0)).apply_with(&mut mesh.map, &mut layers).unwrap();
    /// assert_eq!(layers.1.len(), mesh.map.vertex_slots()); // the new vertex is marked too
    /// e.undo_with(&mut mesh.map, &mut layers).unwrap();
    /// assert_eq!((mesh.map, layers), before);
    /// ```
    pub fn apply_with<A: VertexAttributes>(
        self,
        map: &mut Map,
        attrs: &mut A,
    ) -> Result<Edited<QuadRecord, A>, Refusal> {
        match self {
            QuadOp::Collapse(d) => edit(
                map,
                attrs,
                |m| collapse_quad(m, d),
                |r| Some((r.kept(), Rule::Midpoint(r.kept(), r.removed()))),
            ),
            QuadOp::Split(s1, s2) => edit(map, attrs, |m| split_vertex(m, s1, s2), split_rule),
            QuadOp::HighValence(d) => {
                let v = map.origin(d);
                edit(map, attrs, |m| split_high_valence(m, v, d), split_rule)
            }
            QuadOp::RemoveValence2(x) => edit(map, attrs, |m| remove_valence2(m, x), |_| None),
            QuadOp::InsertDoublet(d) => {
                // The diagonal the new vertex sits on, read before the edit.
                let (p, q) = (map.origin(d), map.origin(map.next(map.next(d))));
                edit(
                    map,
                    attrs,
                    |m| insert_doublet(m, d),
                    |r| Some((r.vertex(), Rule::Midpoint(p, q))),
                )
            }
            QuadOp::Rotate(h, dir) => edit(map, attrs, |m| rotate_edge(m, h, dir), |_| None),
        }
    }
}

/// Applies `op` to the map, then places the vertex `place` names for the record (if any).
fn edit<R: Into<QuadRecord>, A: VertexAttributes>(
    map: &mut Map,
    attrs: &mut A,
    op: impl FnOnce(&mut Map) -> Result<R, Refusal>,
    place: impl FnOnce(&R) -> Option<(Vert, Rule)>,
) -> Result<Edited<QuadRecord, A>, Refusal> {
    let mut journal = Journal::start(attrs);
    let record = op(map)?;
    if let Some((v, rule)) = place(&record) {
        journal.place(map, attrs, v, rule);
    }
    Ok(Edited::new(record.into(), journal))
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
    QuadOp::Collapse(d).apply_mesh(mesh)
}

/// A split's new vertex goes halfway between the kept vertex and the centroid of the new
/// vertex's neighbours; the kept vertex does not move.
fn split_rule(r: &VertexSplit) -> Option<(Vert, Rule)> {
    let rule = Rule::TowardNeighbours {
        from: r.kept(),
        of: r.created(),
        skip_from: false,
    };
    Some((r.created(), rule))
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
    QuadOp::Split(s1, s2).apply_mesh(mesh)
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
    let op = |m: &mut Map| split_high_valence(m, v, first);
    edit(&mut mesh.map, &mut mesh.positions, op, split_rule)
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
    QuadOp::RemoveValence2(x).apply_mesh(mesh)
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
    QuadOp::InsertDoublet(d).apply_mesh(mesh)
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
    QuadOp::Rotate(h, dir).apply_mesh(mesh)
}
