//! The triangle moves on per-vertex data: VE places the new vertex halfway between the
//! split tip and its new neighbours' centroid, EV puts the merged corner at the midpoint of
//! the two base corners; LE and RE move no vertex.

use super::walk::{move_triangle, Move, TriangleMove};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{Edited, Mesh, Rule, VertexAttributes};
use crate::ops::{Refusal, VertexChanges};

/// [`move_triangle`] on a map and a per-vertex layer (positions, marks, or a pair of
/// layers), placing the vertex VE creates or EV merges; undo gives back map and layer `==`.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
/// let (mut mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
/// let before = mesh.clone();
/// let e = quad_dominant::move_triangle_with(&mut mesh.map, &mut mesh.positions, tips[0], Move::VE).unwrap();
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn move_triangle_with<A: VertexAttributes>(
    map: &mut Map,
    attrs: &mut A,
    t: Dart,
    mv: Move,
) -> Result<Edited<TriangleMove, A>, Refusal> {
    // Read before the move: the tip (VE's kept half) and EV's two base corners.
    let (tip, base) = (map.origin(t), [map.dest(t), map.dest(map.next(t))]);
    let rule = move |_: &Map, r: &TriangleMove| -> Option<(Vert, Rule)> {
        match mv {
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
    Edited::run(map, attrs, |m| move_triangle(m, t, mv), rule)
}

/// [`move_triangle_with`] on a [`Mesh`]'s positions.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
/// let (mut mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
/// let before = mesh.clone();
/// let e = quad_dominant::mesh_move_triangle(&mut mesh, tips[0], Move::EV).unwrap();
/// e.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_move_triangle(
    mesh: &mut Mesh,
    t: Dart,
    mv: Move,
) -> Result<Edited<TriangleMove>, Refusal> {
    move_triangle_with(&mut mesh.map, &mut mesh.positions, t, mv)
}
