//! The triangle operators on per-vertex data: the same topology, with the vertex an
//! operator creates or moves placed by the operator's rule, stated once each in
//! [`TriOp::apply_with`], and undo restoring the old values exactly (see
//! [`crate::mesh::Edited`]).
//!
//! ```
//! use zipmesh_kernel::{gen, ops::tri};
//! let mut mesh = gen::random_triangle(300, 0, 1, 2);
//! let before = mesh.clone();
//! let h = mesh.map.darts().find(|&d| tri::can_collapse_edge(&mesh.map, d).is_ok()).unwrap();
//! let edit = tri::mesh_collapse_edge(&mut mesh, h).unwrap();
//! assert_eq!(mesh.map.num_vertices(), before.map.num_vertices() - 1);
//! edit.undo(&mut mesh).unwrap();
//! assert_eq!(mesh, before);
//! ```

use super::{
    collapse_edge, flip_edge, split_edge, split_vertex, EdgeCollapse, EdgeFlip, EdgeSplit, TriOp,
    TriRecord, VertexSplit,
};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{Edited, Mesh, Rule, VertexAttributes};
use crate::ops::Refusal;

/// A flip moves no vertex.
fn flip_rule(_: &Map, _: &EdgeFlip) -> Option<(Vert, Rule)> {
    None
}

/// The kept vertex moves to the midpoint of the collapsed edge.
fn collapse_rule(_: &Map, r: &EdgeCollapse) -> Option<(Vert, Rule)> {
    Some((r.kept(), Rule::Midpoint(r.kept(), r.removed())))
}

/// `w` stays; the new vertex goes halfway between `w` and the mean of its other neighbours
/// (`a`, `b` and the ends of the moved darts), inside its own fan.
fn split_vertex_rule(map: &Map, r: &VertexSplit) -> Option<(Vert, Rule)> {
    let rule = Rule::TowardNeighbours {
        from: map.dest(r.edge()),
        of: r.created(),
        skip_from: true,
    };
    Some((r.created(), rule))
}

impl TriOp {
    /// Applies the operator to a map and its per-vertex data (positions, marks, or a pair
    /// of layers), placing the vertex it creates or moves by its rule.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri::TriOp};
    /// let mut mesh = gen::random_triangle(200, 0, 0, 3);
    /// let mut marks = vec![false; mesh.map.vertex_slots()];
    /// let before = (mesh.map.clone(), marks.clone());
    /// let d = mesh.map.darts().find(|&d| TriOp::SplitEdge(d).can(&mesh.map).is_ok()).unwrap();
    /// let e = TriOp::SplitEdge(d).apply_with(&mut mesh.map, &mut marks).unwrap();
    /// assert_eq!(marks.len(), mesh.map.vertex_slots());
    /// e.undo_with(&mut mesh.map, &mut marks).unwrap();
    /// assert_eq!((mesh.map, marks), before);
    /// ```
    pub fn apply_with<A: VertexAttributes>(
        self,
        map: &mut Map,
        attrs: &mut A,
    ) -> Result<Edited<TriRecord, A>, Refusal> {
        let (m, a) = (map, attrs);
        Ok(match self {
            TriOp::Flip(h) => {
                Edited::run(m, a, |m| flip_edge(m, h), flip_rule)?.map_record(Into::into)
            }
            TriOp::Collapse(h) => {
                Edited::run(m, a, |m| collapse_edge(m, h), collapse_rule)?.map_record(Into::into)
            }
            TriOp::SplitVertex(d1, d2) => {
                let op = |m: &mut Map| split_vertex(m, d1, d2);
                Edited::run(m, a, op, split_vertex_rule)?.map_record(Into::into)
            }
            TriOp::SplitEdge(h) => split_edge_with(m, a, h)?.map_record(Into::into),
        })
    }

    /// [`TriOp::apply_with`] on a mesh's positions (the `mesh_*` wrappers).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri::TriOp};
    /// let mut mesh = gen::random_triangle(200, 0, 0, 3);
    /// let before = mesh.clone();
    /// let d = mesh.map.darts().find(|&d| TriOp::Collapse(d).can(&mesh.map).is_ok()).unwrap();
    /// let e = TriOp::Collapse(d).apply_mesh(&mut mesh).unwrap();
    /// e.undo(&mut mesh).unwrap();
    /// assert_eq!(mesh, before);
    /// ```
    pub fn apply_mesh(self, mesh: &mut Mesh) -> Result<Edited<TriRecord>, Refusal> {
        self.apply_with(&mut mesh.map, &mut mesh.positions)
    }
}

fn split_edge_with<A: VertexAttributes>(
    map: &mut Map,
    attrs: &mut A,
    h: Dart,
) -> Result<Edited<EdgeSplit, A>, Refusal> {
    // The edge's ends, read before the split.
    let (a, b) = (map.origin(h), map.dest(h));
    let rule = |_: &Map, r: &EdgeSplit| Some((r.created(), Rule::Midpoint(a, b)));
    Edited::run(map, attrs, |m| split_edge(m, h), rule)
}

/// [`flip_edge`] on a mesh; no position changes.
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let before = mesh.positions.clone();
/// let h = mesh.map.darts().find(|&d| tri::can_flip_edge(&mesh.map, d).is_ok()).unwrap();
/// tri::mesh_flip_edge(&mut mesh, h).unwrap();
/// assert_eq!(mesh.positions, before);
/// ```
pub fn mesh_flip_edge(mesh: &mut Mesh, h: Dart) -> Result<Edited<EdgeFlip>, Refusal> {
    Edited::run(
        &mut mesh.map,
        &mut mesh.positions,
        |m| flip_edge(m, h),
        flip_rule,
    )
}

/// [`collapse_edge`] on a mesh; the kept vertex moves to the edge's midpoint.
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let h = mesh.map.darts().find(|&d| tri::can_collapse_edge(&mesh.map, d).is_ok()).unwrap();
/// let (v, u) = (mesh.map.origin(h).index(), mesh.map.dest(h).index());
/// let mid = (mesh.positions[u] + mesh.positions[v]) / 2.0;
/// let edit = tri::mesh_collapse_edge(&mut mesh, h).unwrap();
/// assert_eq!(mesh.positions[edit.record().kept().index()], mid);
/// ```
pub fn mesh_collapse_edge(mesh: &mut Mesh, h: Dart) -> Result<Edited<EdgeCollapse>, Refusal> {
    Edited::run(
        &mut mesh.map,
        &mut mesh.positions,
        |m| collapse_edge(m, h),
        collapse_rule,
    )
}

/// [`split_vertex`] on a mesh; `w` stays and the new vertex goes halfway between `w` and
/// the mean of its other neighbours.
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri, Vert};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let w = Vert::new(5);
/// let d1 = mesh.map.vertex_dart(w);
/// let d2 = mesh.map.rotate_cw(mesh.map.rotate_cw(d1));
/// let edit = tri::mesh_split_vertex(&mut mesh, d1, d2).unwrap();
/// let v = edit.record().created().index();
/// assert!(mesh.positions[v] != mesh.positions[w.index()]);
/// ```
pub fn mesh_split_vertex(
    mesh: &mut Mesh,
    d1: Dart,
    d2: Dart,
) -> Result<Edited<VertexSplit>, Refusal> {
    let op = |m: &mut Map| split_vertex(m, d1, d2);
    Edited::run(&mut mesh.map, &mut mesh.positions, op, split_vertex_rule)
}

/// [`split_edge`] on a mesh; the new vertex goes to the edge's midpoint.
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri, Dart};
/// let mut mesh = gen::random_triangle(100, 0, 0, 1);
/// let (a, b) = (mesh.map.origin(Dart::new(0)).index(), mesh.map.dest(Dart::new(0)).index());
/// let mid = (mesh.positions[a] + mesh.positions[b]) / 2.0;
/// let edit = tri::mesh_split_edge(&mut mesh, Dart::new(0)).unwrap();
/// assert_eq!(mesh.positions[edit.record().created().index()], mid);
/// ```
pub fn mesh_split_edge(mesh: &mut Mesh, h: Dart) -> Result<Edited<EdgeSplit>, Refusal> {
    split_edge_with(&mut mesh.map, &mut mesh.positions, h)
}
