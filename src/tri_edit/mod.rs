//! Semantic editing of irregular vertices in triangle meshes (triangle paper,
//! Sec. 6.2-6.3): operations that move, create and remove v5 and v7 vertices, each built from
//! the graph operators of [`crate::ops::tri`].
//!
//! Every operation follows the operators' contract: a pure check `can_*`, the operation
//! itself (all or nothing: on a refusal the map is exactly as before, `==`), a record that
//! says where the irregular vertices are now and whose `undo` restores the map exactly.
//! Every operation takes any [`crate::mesh::EditTarget`]: a bare map, a [`crate::Mesh`] or a
//! map with any per-vertex values. New and moved vertices are placed by their operators'
//! rules ([`crate::ops::tri::TriOp::apply`]), and the result's `undo` gives back map and
//! values `==` (see [`crate::mesh::Edited`]).
//!
//! ```
//! use zipmesh::tri_edit::{move_pair, Direction};
//! use zipmesh::{ops::tri, Map, Vert};
//! // A triangulated torus (every vertex of valence 6); one flip makes two 5-7 pairs.
//! let (nx, ny) = (8u32, 8u32);
//! let mut tris = Vec::new();
//! for j in 0..ny {
//!     for i in 0..nx {
//!         let v = |a: u32, b: u32| ((b % ny) * nx + a % nx);
//!         let q = [v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)];
//!         tris.push([q[0], q[1], q[2]]);
//!         tris.push([q[0], q[2], q[3]]);
//!     }
//! }
//! let mut map = Map::from_polygons((nx * ny) as usize, &tris).unwrap();
//! let d = map.dart_between(Vert::new(0), Vert::new(9)).unwrap();
//! let flip = tri::flip_edge(&mut map, d).unwrap();
//! let (p, q) = (Vert::new(0), Vert::new(1)); // a v5 and an adjacent v7
//! assert_eq!((map.valence(p), map.valence(q)), (5, 7));
//! let before = map.clone();
//! let step = move_pair(&mut map, p, q, Direction::SplitRight).unwrap();
//! assert_eq!((map.valence(step.p()), map.valence(step.q())), (5, 7));
//! step.undo(&mut map).unwrap();
//! assert_eq!(map, before);
//! # let _ = flip;
//! ```
//!
//! The operations:
//! * atomic 5-7 movement in six [`Direction`]s: [`move_pair`] (Fig. 6);
//! * v5 movement with 5-7 generation, read two ways ([`Moved`]): [`generate_pair`], and its
//!   inverse with 5-7 removal, [`remove_pair`] (Fig. 7);
//! * 5-5-7-7 generation from a regular vertex in three configurations ([`Quadruple`]):
//!   [`generate_quadruple`], and removal of a quadruple inside two triangles,
//!   [`remove_quadruple`] (Fig. 8);
//! * type splitting and aggregation: [`split_type`], [`aggregate_type`] (Sec. 6.3);
//! * v7 movement with 5-7 generation, [`generate_pair_v7`], and with 5-7 removal,
//!   [`remove_pair_v7`] (the mirror of Fig. 7), and the cancellation of an adjacent 5-5-7
//!   or 5-7-7 triple into one v5 or one v7, [`cancel_triple`] (Sec. 7.2; generation,
//!   Sec. 7.3, is [`generate_pair`] or [`generate_pair_v7`]);
//! * relaxation of the geometry after an edit (Sec. 8): [`relax_local`] (Turk-style, one
//!   vertex at a time) and `relax_global` (Eq. 5 on tangent planes, sparse Cholesky; `sparse`
//!   feature), on the region [`relax_region`] grows around [`touched_vertices`]; the
//!   equations and our reading of them in [`relax`];
//! * composite movement of a 5-7, 5-5 or 7-7 pair that need not be adjacent (Sec. 7.1):
//!   [`move_far_pair`], the three-step pipeline of 7.1.1 (generation at one vertex, a walk
//!   of the generated pair, removal at the other);
//! * the generations by name ([`Generation::of`] a valence and a [`GenerationConfig`]), and
//!   the inverses no record holds, each checked by isomorphism:
//!   [`TripleCancel::inverse_generation`], [`TypeEdit::inverse_restores`] and
//!   [`far_pair_inverse`].
//!
//! [`crate::gen::geodesic_sphere`], [`crate::gen::subdivided_tetrahedron`],
//! [`crate::gen::subdivided_bipyramid`] and [`crate::gen::cone_disk`] make meshes with lone
//! v5, v3, v4, vk and v7 in regular neighbourhoods to try them on. The readings chosen
//! where the paper's figures are missing, with diagrams: `docs/tri-edit.md`.

use crate::map::{Dart, Map, Vert};
use crate::ops::Refusal;
use core::fmt;

mod apart;
mod composite;
mod gather;
mod generate;
mod generation;
mod pair;
mod quadruple;
mod record;
pub mod relax;
mod triple;
mod types;

pub use crate::geometry::{relax_region, touched_vertices};
pub use apart::{can_generate_quadruple_apart, generate_quadruple_apart, quadruple_sides};
pub use composite::{
    can_move_far_pair, far_pair_directions, far_pair_inverse, far_pair_start, move_far_pair,
    FarPairMove, FarStart, Start,
};
pub use generate::{
    can_generate_pair, can_remove_pair, generate_pair, remove_pair, Moved, V5Move, Via,
};
pub use generation::{Generation, GenerationConfig};
pub use pair::{can_move_pair, move_pair, pair_op, Direction, PairMove};
pub use quadruple::{
    can_generate_quadruple, can_remove_quadruple, generate_quadruple, remove_quadruple, Quadruple,
    QuadrupleEdit,
};
pub use record::VertexMove;
#[cfg(feature = "sparse")]
pub use relax::relax_global;
pub use relax::{mean_edge_length, relax_energy, relax_local, RelaxError, Relaxed};
pub use triple::{
    can_cancel_triple, can_generate_pair_v7, can_remove_pair_v7, cancel_triple,
    cancel_triple_along, generate_pair_v7, remove_pair_v7, TripleCancel, TripleEdit, V7Move, Via7,
};
pub use types::{aggregate_type, can_aggregate_type, can_split_type, split_type, TypeEdit};

/// Why a semantic edit refuses (the map is then unchanged).
///
/// ```
/// use zipmesh::tri_edit::{can_move_pair, Direction, TriEditError};
/// use zipmesh::{gen, Vert};
/// let map = gen::random_triangle(100, 0, 0, 1).map;
/// let r = can_move_pair(&map, Vert::new(0), Vert::new(0), Direction::FlipLeft);
/// assert!(matches!(r, Err(TriEditError::NotAPair)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TriEditError {
    /// A vertex argument is not live.
    DeadHandle,
    /// The vertices are not what the operation works on: for a 5-7 movement, `p` is not an
    /// interior v5, `q` not an interior v7, or they are not joined by exactly one edge.
    NotAPair,
    /// A vertex the operation needs regular (interior, valence 6) is not, so the
    /// operation would not have its semantic effect (the paper assumes a regular
    /// neighbourhood).
    Irregular,
    /// The vertex does not have a valence the operation works on (a type split needs an
    /// interior v3, v4 or vk with k > 7).
    WrongValence,
    /// The graph operator refused, for this reason.
    Refused(Refusal),
    /// A composite direction past those that apply to the pair (see
    /// [`far_pair_start`]).
    NoDirection {
        /// How many of the six directions apply.
        available: usize,
    },
}

impl From<Refusal> for TriEditError {
    fn from(r: Refusal) -> Self {
        TriEditError::Refused(r)
    }
}

impl fmt::Display for TriEditError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TriEditError::DeadHandle => f.write_str("a vertex is not live in this map"),
            TriEditError::NotAPair => f.write_str("the vertices are not an adjacent 5-7 pair"),
            TriEditError::WrongValence => f.write_str("the vertex has the wrong valence"),
            TriEditError::Irregular => f.write_str("a vertex that must be regular is not"),
            TriEditError::Refused(r) => write!(f, "the graph operator refused: {r}"),
            TriEditError::NoDirection { available } => write!(
                f,
                "only {available} of the six composite directions apply here (an irregular \
                 vertex or the boundary in the way)"
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for TriEditError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TriEditError::Refused(r) => Some(r),
            _ => None,
        }
    }
}

/// Whether `v` is live, interior and of valence `k`.
pub(crate) fn interior_of_valence(map: &Map, v: Vert, k: usize) -> bool {
    map.is_live_vertex(v) && !map.is_boundary_vertex(v) && map.valence(v) == k
}

/// `Ok` when `v` is a regular interior vertex, [`TriEditError::Irregular`] otherwise.
pub(crate) fn regular(map: &Map, v: Vert) -> Result<(), TriEditError> {
    if interior_of_valence(map, v, 6) {
        Ok(())
    } else {
        Err(TriEditError::Irregular)
    }
}

/// The third corner of the face of `d` when it is a triangle (`None` on a boundary dart or
/// a face of another degree).
pub(crate) fn apex(map: &Map, d: Dart) -> Option<Vert> {
    map.face(d)?;
    let n = map.next(d);
    (map.next(map.next(n)) == d).then(|| map.dest(n))
}
