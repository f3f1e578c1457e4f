//! Atomic 5-7 movement (Sec. 6.2, Fig. 6): an adjacent v5 `p` and v7 `q` move one step in
//! one of six directions by one flip, one collapse or one vertex split.
//!
//! With `xL` the apex left of `p -> q` and `xR` the one right of it, the six directions,
//! counter-clockwise from `p -> q` (direction 0 is just left of it):
//!
//! ```text
//!              1 flip q-xL
//!      2 collapse  xL   n4    0 split q at (p, n4)
//!       p into xL   \   /
//!                p ---- q      (q has 7 neighbours, counter-clockwise from p:
//!       p into xR   /   \       p, xR, n2, n3, n4, n5, xL)
//!      3 collapse  xR   n3    5 split q at (p, n3)
//!              4 flip q-xR
//! ```
//! Opposite directions (`d` and `d + 3 mod 6`) undo each other up to isomorphism.

use super::record::{apply_one, one_operation, turn};
use super::{apex, interior_of_valence, regular, TriEditError};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited};
use crate::ops::tri::{TriOp, TriRecord};
use crate::ops::Refusal;

/// One of the six directions of an atomic 5-7 movement, counter-clockwise from `p -> q`
/// (see the module diagram and `docs/tri-edit.md`).
///
/// ```
/// use zipmesh::tri_edit::Direction;
/// assert_eq!(Direction::from_index(1), Some(Direction::FlipLeft));
/// assert_eq!(Direction::FlipLeft.opposite(), Direction::FlipRight);
/// assert_eq!(Direction::ALL.map(Direction::index), [0, 1, 2, 3, 4, 5]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    /// 0: split `q` along `q -> p` and `q -> n4`; `q` becomes the v5, `n4` the v7.
    SplitLeft,
    /// 1: flip `q-xL`; `xL` becomes the v5, the far apex of `q-xL` the v7.
    FlipLeft,
    /// 2: collapse `p` into `xL`; `xL` becomes the v7, the far apex of `p-xL` the v5.
    CollapseLeft,
    /// 3: collapse `p` into `xR`; `xR` becomes the v7, the far apex of `p-xR` the v5.
    CollapseRight,
    /// 4: flip `q-xR`; `xR` becomes the v5, the far apex of `q-xR` the v7.
    FlipRight,
    /// 5: split `q` along `q -> n3` and `q -> p`; `q` becomes the v5, `n3` the v7.
    SplitRight,
}

impl Direction {
    /// The six directions in counter-clockwise order.
    ///
    /// See [`Direction`] for an example.
    pub const ALL: [Direction; 6] = [
        Direction::SplitLeft,
        Direction::FlipLeft,
        Direction::CollapseLeft,
        Direction::CollapseRight,
        Direction::FlipRight,
        Direction::SplitRight,
    ];

    /// The direction's number, 0 to 5.
    ///
    /// See [`Direction`] for an example.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The direction numbered `i` (0 to 5), `None` otherwise.
    ///
    /// See [`Direction`] for an example.
    pub fn from_index(i: usize) -> Option<Direction> {
        Direction::ALL.get(i).copied()
    }

    /// The direction half a turn away (`d + 3 mod 6`).
    ///
    /// See [`Direction`] for an example.
    pub fn opposite(self) -> Direction {
        Direction::ALL[(self.index() + 3) % 6]
    }
}

/// The dart `p -> q` of an adjacent 5-7 pair, or why `p`, `q` are not one.
fn pair_dart(map: &Map, p: Vert, q: Vert) -> Result<Dart, TriEditError> {
    if !map.is_live_vertex(p) || !map.is_live_vertex(q) {
        return Err(TriEditError::DeadHandle);
    }
    if !interior_of_valence(map, p, 5) || !interior_of_valence(map, q, 7) {
        return Err(TriEditError::NotAPair);
    }
    map.dart_between(p, q).ok_or(TriEditError::NotAPair)
}

/// The far apex across the edge of `d` (the apex of `twin(d)`'s triangle).
fn far(map: &Map, d: Dart) -> Result<Vert, TriEditError> {
    apex(map, d.twin()).ok_or(TriEditError::Refused(Refusal::WrongDegree))
}

/// The graph operation of the move and the pair it leaves `(p', q')`, checking that the
/// vertices that become the new pair are regular now.
pub(super) fn plan(
    map: &Map,
    p: Vert,
    q: Vert,
    dir: Direction,
) -> Result<(TriOp, Vert, Vert), TriEditError> {
    let d = pair_dart(map, p, q)?;
    let t = d.twin();
    let bad = TriEditError::Refused(Refusal::WrongDegree);
    let (op, np, nq) = match dir {
        Direction::FlipLeft | Direction::FlipRight => {
            // The dart q -> x along the flipped edge.
            let qx = if dir == Direction::FlipLeft {
                map.next(d)
            } else {
                map.next(map.next(t)).twin()
            };
            // The far apex of q-x is on the side away from p.
            let y = if dir == Direction::FlipLeft {
                far(map, qx)?
            } else {
                apex(map, qx).ok_or(bad)?
            };
            (TriOp::Flip(qx), map.dest(qx), y)
        }
        Direction::CollapseLeft | Direction::CollapseRight => {
            let px = if dir == Direction::CollapseLeft {
                map.next(map.next(d)).twin()
            } else {
                map.next(t)
            };
            // The far apex of p-x is on the side away from q.
            let z = if dir == Direction::CollapseLeft {
                apex(map, px).ok_or(bad)?
            } else {
                far(map, px)?
            };
            (TriOp::Collapse(px), z, map.dest(px))
        }
        Direction::SplitLeft | Direction::SplitRight => {
            // Clockwise around q from q -> p: xL, n5, n4, n3, n2, xR.
            let (d1, d2, b) = if dir == Direction::SplitLeft {
                (t, turn(map, t, 3), map.dest(turn(map, t, 3)))
            } else {
                (turn(map, t, 4), t, map.dest(turn(map, t, 4)))
            };
            (TriOp::SplitVertex(d1, d2), q, b)
        }
    };
    // A split leaves q as the v5 and needs only the new v7 regular.
    if np != q {
        regular(map, np)?;
    }
    regular(map, nq)?;
    Ok((op, np, nq))
}

/// The graph operation that moves the adjacent 5-7 pair `(p, q)` one step in `dir`
/// (see [`move_pair`]), without applying it.
///
/// ```
/// use zipmesh::tri_edit::{pair_op, Direction, TriEditError};
/// use zipmesh::{gen, Vert};
/// let map = gen::random_triangle(100, 0, 0, 1).map;
/// assert!(pair_op(&map, Vert::new(0), Vert::new(1), Direction::FlipLeft).is_err());
/// ```
pub fn pair_op(map: &Map, p: Vert, q: Vert, dir: Direction) -> Result<TriOp, TriEditError> {
    plan(map, p, q, dir).map(|x| x.0)
}

/// Checks whether [`move_pair`] applies, without changing anything.
///
/// Refusals, in the order checked: [`TriEditError::DeadHandle`]; [`TriEditError::NotAPair`]
/// (`p` not an interior v5, `q` not an interior v7, or not joined by one edge);
/// [`TriEditError::Refused`] with [`Refusal::WrongDegree`] when a face around the pair is
/// not a triangle; [`TriEditError::Irregular`] when a vertex that becomes part of the new
/// pair is not a regular interior vertex; then the graph operator's own refusal.
///
/// ```
/// use zipmesh::tri_edit::{can_move_pair, Direction, TriEditError};
/// use zipmesh::{gen, Vert};
/// let map = gen::torus_grid(4, 4).map; // quads: no v5 at all
/// let r = can_move_pair(&map, Vert::new(0), Vert::new(1), Direction::SplitLeft);
/// assert_eq!(r, Err(TriEditError::NotAPair));
/// ```
pub fn can_move_pair(map: &Map, p: Vert, q: Vert, dir: Direction) -> Result<(), TriEditError> {
    let (op, _, _) = plan(map, p, q, dir)?;
    Ok(op.can(map)?)
}

/// Moves the adjacent 5-7 pair `(p, q)` (`p` an interior v5, `q` an interior v7) one step
/// in `dir` by one graph operation, or refuses (see [`can_move_pair`]) with the map
/// unchanged.
///
/// Afterwards [`PairMove::p`] is a v5 and [`PairMove::q`] a v7, adjacent; the four vertices
/// the operation touches are the old and the new pair, every other vertex keeps its
/// valence, so the multiset of irregular valences is unchanged. Flips keep the face count,
/// a collapse removes two triangles (and the vertex `p`), a split adds two.
///
/// See the module example in [`crate::tri_edit`].
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
///
/// ```
/// use zipmesh::tri_edit::{move_pair, Direction};
/// use zipmesh::gen;
/// let mut mesh = gen::random_triangle(400, 1, 0, 3);
/// let before = mesh.clone();
/// let v5 = mesh.map.vertices().filter(|&v| mesh.map.valence(v) == 5);
/// let found = v5.flat_map(|p| mesh.map.vertex_darts(p).map(move |d| (p, d))).find_map(|(p, d)| {
///     let q = mesh.map.dest(d);
///     Direction::ALL.into_iter().find(|&dir| {
///         zipmesh::tri_edit::can_move_pair(&mesh.map, p, q, dir).is_ok()
///     }).map(|dir| (p, q, dir))
/// });
/// if let Some((p, q, dir)) = found {
///     let e = move_pair(&mut mesh, p, q, dir).unwrap();
///     e.undo(&mut mesh).unwrap();
///     assert_eq!(mesh, before);
/// }
/// ```
pub fn move_pair<T: EditTarget>(
    target: &mut T,
    p: Vert,
    q: Vert,
    dir: Direction,
) -> Result<Edited<PairMove, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let (op, np, nq) = plan(map, p, q, dir)?;
    apply_one(map, attrs, op, |op, record| PairMove {
        from: (p, q),
        to: (np, nq),
        direction: dir,
        op,
        record,
    })
}

/// Record of a [`move_pair`]: where the pair was and is, the graph operation, and what the
/// exact undo needs.
///
/// See the module example in [`crate::tri_edit`].
#[derive(Clone, Copy, Debug)]
pub struct PairMove {
    from: (Vert, Vert),
    to: (Vert, Vert),
    direction: Direction,
    op: TriOp,
    record: TriRecord,
}

impl PairMove {
    /// The v5 of the pair after the move.
    ///
    /// See the module example in [`crate::tri_edit`].
    pub fn p(&self) -> Vert {
        self.to.0
    }

    /// The v7 of the pair after the move.
    ///
    /// See the module example in [`crate::tri_edit`].
    pub fn q(&self) -> Vert {
        self.to.1
    }

    /// The pair `(v5, v7)` before the move.
    ///
    /// See the module example in [`crate::tri_edit`].
    pub fn before(&self) -> (Vert, Vert) {
        self.from
    }

    /// The direction moved.
    ///
    /// See the module example in [`crate::tri_edit`].
    pub fn direction(&self) -> Direction {
        self.direction
    }
}

one_operation!(PairMove, "the module example in [`crate::tri_edit`]");
