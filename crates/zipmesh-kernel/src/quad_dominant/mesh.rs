//! The triangle moves on per-vertex data: VE places the new vertex halfway between the
//! split tip and its new neighbours' centroid, EV puts the merged corner at the midpoint of
//! the two base corners; LE and RE move no vertex.

use super::walk::{move_triangle, Move, TriangleMove};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited, Rule};
use crate::ops::{Refusal, VertexChanges};

impl Move {
    /// Makes this move of the triangle of tip dart `t` on a map and the values kept in
    /// step with it (a bare map, a [`crate::Mesh`]'s positions, or a map with any layer:
    /// see [`EditTarget`]), placing the vertex VE creates (halfway between the split tip
    /// and its new neighbours' centroid) or EV merges (the midpoint of the two base
    /// corners); undo gives back map and values `==`.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, quad_dominant::Move};
    /// let (mut mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
    /// let before = mesh.clone();
    /// let e = Move::VE.apply(&mut mesh, tips[0]).unwrap();
    /// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
    /// e.undo(&mut mesh).unwrap();
    /// assert_eq!(mesh, before);
    /// ```
    pub fn apply<T: EditTarget>(
        self,
        target: &mut T,
        t: Dart,
    ) -> Result<Edited<TriangleMove, T::Values>, Refusal> {
        let (map, values) = target.parts();
        // Read before the move: the tip (VE's kept half) and EV's two base corners.
        let (tip, base) = (map.origin(t), [map.dest(t), map.dest(map.next(t))]);
        let rule = move |_: &Map, r: &TriangleMove| -> Option<(Vert, Rule)> {
            match self {
                Move::VE => r.created_vertex().map(|v| {
                    let rule = Rule::TowardNeighbours {
                        from: tip,
                        of: v,
                        skip_from: true,
                    };
                    (v, rule)
                }),
                Move::EV => Some((base[0], Rule::Midpoint(base[0], base[1]))),
                Move::LE | Move::RE => None,
            }
        };
        Edited::run(map, values, |m| move_triangle(m, t, self), rule)
    }
}
