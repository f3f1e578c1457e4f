//! The quad operators on per-vertex data: the same topology, with the vertex an operator
//! creates or merges placed by the operator's rule, stated once each in
//! [`QuadOp::apply_with`], and undo restoring the old values exactly (see
//! [`crate::mesh::Edited`]).

use super::{
    collapse_quad, insert_doublet, remove_valence2, rotate_edge, split_high_valence, split_vertex,
    DoubletInsertion, EdgeRotation, QuadCollapse, QuadOp, QuadRecord, Rotation, Valence2Removal,
    VertexSplit,
};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{Edited, Mesh, Rule, VertexAttributes};
use crate::ops::Refusal;

/// The merged vertex goes to the midpoint of the two merged corners.
fn collapse_rule(_: &Map, r: &QuadCollapse) -> Option<(Vert, Rule)> {
    Some((r.kept(), Rule::Midpoint(r.kept(), r.removed())))
}

/// The kept vertex stays; the new one goes halfway between it and the centroid of the new
/// vertex's neighbours.
fn split_rule(_: &Map, r: &VertexSplit) -> Option<(Vert, Rule)> {
    let rule = Rule::TowardNeighbours {
        from: r.kept(),
        of: r.created(),
        skip_from: false,
    };
    Some((r.created(), rule))
}

/// The new vertex goes to the midpoint of the diagonal it joins (its two neighbours).
fn doublet_rule(_: &Map, r: &DoubletInsertion) -> Option<(Vert, Rule)> {
    Some((r.vertex(), Rule::NeighbourMean(r.vertex())))
}

/// No vertex moves (a removed vertex's slot keeps its value, as dead slots do).
fn no_rule<R>(_: &Map, _: &R) -> Option<(Vert, Rule)> {
    None
}

impl QuadOp {
    /// Applies the operator to a map and its per-vertex data (positions, marks, or a pair
    /// of layers), placing the vertex it creates or merges by its rule.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::QuadOp, Dart};
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
        let (m, a) = (map, attrs);
        Ok(match self {
            QuadOp::Collapse(d) => {
                Edited::run(m, a, |m| collapse_quad(m, d), collapse_rule)?.map_record(Into::into)
            }
            QuadOp::Split(s1, s2) => {
                Edited::run(m, a, |m| split_vertex(m, s1, s2), split_rule)?.map_record(Into::into)
            }
            QuadOp::HighValence(d) => {
                let v = m.origin(d);
                let op = |m: &mut Map| split_high_valence(m, v, d);
                Edited::run(m, a, op, split_rule)?.map_record(Into::into)
            }
            QuadOp::RemoveValence2(x) => {
                let op = |m: &mut Map| remove_valence2(m, x);
                Edited::run(m, a, op, no_rule)?.map_record(Into::into)
            }
            QuadOp::InsertDoublet(d) => {
                let op = |m: &mut Map| insert_doublet(m, d);
                Edited::run(m, a, op, doublet_rule)?.map_record(Into::into)
            }
            QuadOp::Rotate(h, dir) => {
                let op = |m: &mut Map| rotate_edge(m, h, dir);
                Edited::run(m, a, op, no_rule)?.map_record(Into::into)
            }
        })
    }
}

/// [`collapse_quad`] on a mesh; the merged vertex is placed at the midpoint of the two merged
/// corners.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart};
/// let mut mesh = gen::grid(3, 3);
/// let before = mesh.clone();
/// let d = mesh.map.vertex_dart(zipmesh_kernel::Vert::new(5)); // an interior vertex
/// let (a, c) = (mesh.map.origin(d), mesh.map.origin(mesh.map.next(mesh.map.next(d))));
/// let mid = (mesh.positions[a.index()] + mesh.positions[c.index()]) / 2.0;
/// let e = quad::mesh_collapse_quad(&mut mesh, d).unwrap();
/// assert_eq!(mesh.positions[a.index()], mid);
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_collapse_quad(mesh: &mut Mesh, d: Dart) -> Result<Edited<QuadCollapse>, Refusal> {
    let op = |m: &mut Map| collapse_quad(m, d);
    Edited::run(&mut mesh.map, &mut mesh.positions, op, collapse_rule)
}

/// [`split_vertex`] on a mesh; the kept vertex stays where it was and the new vertex is placed
/// halfway between it and the centroid of the new vertex's neighbours.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Vert};
/// let mut mesh = gen::torus_grid(4, 4);
/// let before = mesh.clone();
/// let s1 = mesh.map.vertex_dart(Vert::new(5));
/// let s2 = mesh.map.rotate_cw(mesh.map.rotate_cw(s1));
/// let e = quad::mesh_split_vertex(&mut mesh, s1, s2).unwrap();
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_split_vertex(
    mesh: &mut Mesh,
    s1: Dart,
    s2: Dart,
) -> Result<Edited<VertexSplit>, Refusal> {
    let op = |m: &mut Map| split_vertex(m, s1, s2);
    Edited::run(&mut mesh.map, &mut mesh.positions, op, split_rule)
}

/// [`split_high_valence`] on a mesh, placing the new vertex as [`mesh_split_vertex`] does.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart};
/// let mut mesh = gen::torus_grid(5, 5);
/// quad::mesh_collapse_quad(&mut mesh, Dart::new(0)).unwrap();
/// let v = mesh.map.origin(Dart::new(0));
/// let before = mesh.clone();
/// let x = mesh.map.vertex_dart(v);
/// let e = quad::mesh_split_high_valence(&mut mesh, v, x).unwrap();
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_split_high_valence(
    mesh: &mut Mesh,
    v: Vert,
    first: Dart,
) -> Result<Edited<VertexSplit>, Refusal> {
    let op = |m: &mut Map| split_high_valence(m, v, first);
    Edited::run(&mut mesh.map, &mut mesh.positions, op, split_rule)
}

/// [`remove_valence2`] on a mesh; no position changes (the deleted vertex's slot keeps its
/// position, as dead slots do).
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart};
/// let mut mesh = gen::torus_grid(4, 4);
/// let ins = quad::mesh_insert_doublet(&mut mesh, Dart::new(0)).unwrap();
/// let before = mesh.clone();
/// let x = mesh.map.vertex_dart(ins.record().vertex());
/// let e = quad::mesh_remove_valence2(&mut mesh, x).unwrap();
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_remove_valence2(mesh: &mut Mesh, x: Dart) -> Result<Edited<Valence2Removal>, Refusal> {
    let op = |m: &mut Map| remove_valence2(m, x);
    Edited::run(&mut mesh.map, &mut mesh.positions, op, no_rule)
}

/// [`insert_doublet`] on a mesh; the new vertex is placed at the midpoint of the diagonal it
/// joins.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart};
/// let mut mesh = gen::grid(1, 1);
/// let d = mesh.map.face_dart(zipmesh_kernel::Face::new(0));
/// let e = quad::mesh_insert_doublet(&mut mesh, d).unwrap();
/// let v = e.record().vertex().index();
/// assert_eq!(mesh.positions[v], glam::DVec3::new(0.5, 0.5, 0.0));
/// ```
pub fn mesh_insert_doublet(mesh: &mut Mesh, d: Dart) -> Result<Edited<DoubletInsertion>, Refusal> {
    let op = |m: &mut Map| insert_doublet(m, d);
    Edited::run(&mut mesh.map, &mut mesh.positions, op, doublet_rule)
}

/// [`rotate_edge`] on a mesh; no position changes.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad::{self, Rotation}, Dart};
/// let mut mesh = gen::torus_grid(4, 4);
/// let before = mesh.clone();
/// let e = quad::mesh_rotate_edge(&mut mesh, Dart::new(0), Rotation::Clockwise).unwrap();
/// assert_eq!(mesh.positions, before.positions);
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_rotate_edge(
    mesh: &mut Mesh,
    h: Dart,
    dir: Rotation,
) -> Result<Edited<EdgeRotation>, Refusal> {
    let op = |m: &mut Map| rotate_edge(m, h, dir);
    Edited::run(&mut mesh.map, &mut mesh.positions, op, no_rule)
}
