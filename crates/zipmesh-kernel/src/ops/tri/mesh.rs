//! The triangle operators on per-vertex data: the same topology, with the vertex an
//! operator creates or moves placed by the operator's rule, stated once each in
//! [`TriOp::apply`], and undo restoring the old values exactly (see
//! [`crate::mesh::Edited`]).
//!
//! ```
//! use zipmesh_kernel::{gen, ops::tri};
//! let mut mesh = gen::random_triangle(300, 0, 1, 2);
//! let before = mesh.clone();
//! let h = mesh.map.darts().find(|&d| tri::can_collapse_edge(&mesh.map, d).is_ok()).unwrap();
//! let edit = tri::TriOp::Collapse(h).apply(&mut mesh).unwrap();
//! assert_eq!(mesh.map.num_vertices(), before.map.num_vertices() - 1);
//! edit.undo(&mut mesh).unwrap();
//! assert_eq!(mesh, before);
//! ```

use super::{
    collapse_edge, flip_edge, split_edge, split_vertex, EdgeCollapse, EdgeFlip, EdgeSplit, TriOp,
    TriRecord, VertexSplit,
};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited, Rule, VertexAttributes};
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
    /// Applies the operator to a map and the values kept in step with it (a bare map, a
    /// [`crate::Mesh`]'s positions, or a map with any layer: see [`EditTarget`]), placing
    /// the vertex it creates or moves by its rule: a collapse's kept vertex at the midpoint
    /// of the edge, an edge split's new vertex at the midpoint, a vertex split's new vertex
    /// inside its own fan; a flip moves none.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri::TriOp};
    /// let mut mesh = gen::random_triangle(200, 0, 0, 3);
    /// let mut marks = vec![false; mesh.map.vertex_slots()];
    /// let before = (mesh.map.clone(), marks.clone());
    /// let d = mesh.map.darts().find(|&d| TriOp::SplitEdge(d).can(&mesh.map).is_ok()).unwrap();
    /// let e = TriOp::SplitEdge(d).apply(&mut (&mut mesh.map, &mut marks)).unwrap();
    /// assert_eq!(marks.len(), mesh.map.vertex_slots());
    /// e.undo(&mut (&mut mesh.map, &mut marks)).unwrap();
    /// assert_eq!((mesh.map, marks), before);
    /// ```
    pub fn apply<T: EditTarget>(
        self,
        target: &mut T,
    ) -> Result<Edited<TriRecord, T::Values>, Refusal> {
        let (m, a) = target.parts();
        Ok(match self {
            TriOp::Flip(h) => {
                Edited::run(m, a, |m| flip_edge(m, h), flip_rule)?.map_record(Into::into)
            }
            TriOp::Collapse(h) => {
                let op = |m: &mut Map| collapse_edge(m, h);
                Edited::run(m, a, op, collapse_rule)?.map_record(Into::into)
            }
            TriOp::SplitVertex(d1, d2) => {
                let op = |m: &mut Map| split_vertex(m, d1, d2);
                Edited::run(m, a, op, split_vertex_rule)?.map_record(Into::into)
            }
            TriOp::SplitEdge(h) => split_edge_with(m, a, h)?.map_record(Into::into),
        })
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
