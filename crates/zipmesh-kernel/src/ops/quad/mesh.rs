//! The quad operators on per-vertex data: the same topology, with the vertex an operator
//! creates or merges placed by the operator's rule, stated once each in
//! [`QuadOp::apply`], and undo restoring the old values exactly (see
//! [`crate::mesh::Edited`]).

use super::{
    collapse_quad, insert_doublet, remove_valence2, rotate_edge, split_high_valence, split_vertex,
    DoubletInsertion, QuadCollapse, QuadOp, QuadRecord, VertexSplit,
};
use crate::map::{Map, Vert};
use crate::mesh::{EditTarget, Edited, Rule};
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
    /// Applies the operator to a map and the values kept in step with it (a bare map, a
    /// [`crate::Mesh`]'s positions, or a map with any layer: see [`EditTarget`]), placing
    /// the vertex it creates or merges by its rule: a collapse's merged vertex at the
    /// midpoint of the merged corners, a split's new vertex halfway between the kept one
    /// and its new neighbours' centroid, a doublet's at the midpoint of its diagonal.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::QuadOp, Dart};
    /// let mut mesh = gen::torus_grid(5, 5);
    /// let before = mesh.clone();
    /// let e = QuadOp::Collapse(Dart::new(0)).apply(&mut mesh).unwrap();
    /// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
    /// e.undo(&mut mesh).unwrap();
    /// assert_eq!(mesh, before);
    /// // A layer of marks beside the positions: the new vertex is marked too.
    /// let mut layers = (mesh.positions.clone(), vec![true; mesh.map.vertex_slots()]);
    /// let e = QuadOp::InsertDoublet(Dart::new(0)).apply(&mut (&mut mesh.map, &mut layers)).unwrap();
    /// assert_eq!(layers.1.len(), mesh.map.vertex_slots());
    /// e.undo(&mut (&mut mesh.map, &mut layers)).unwrap();
    /// assert_eq!(mesh.map, before.map);
    /// ```
    pub fn apply<T: EditTarget>(
        self,
        target: &mut T,
    ) -> Result<Edited<QuadRecord, T::Values>, Refusal> {
        let (m, a) = target.parts();
        Ok(match self {
            QuadOp::Collapse(d) => {
                let op = |m: &mut Map| collapse_quad(m, d);
                Edited::run(m, a, op, collapse_rule)?.map_record(Into::into)
            }
            QuadOp::Split(s1, s2) => {
                let op = |m: &mut Map| split_vertex(m, s1, s2);
                Edited::run(m, a, op, split_rule)?.map_record(Into::into)
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
