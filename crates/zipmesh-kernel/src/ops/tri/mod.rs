//! Triangle operators (triangle paper, Sec. 6.1): edge flip, edge collapse with the
//! link condition, vertex split (the collapse's inverse) and edge split.
//!
//! Every operator comes as a pure check `can_*` and the operation itself, which refuses with
//! the same [`Refusal`] and leaves the map untouched, or applies and returns a record whose
//! `undo` restores the map exactly (`==`, free lists included). [`TriOp::apply`] applies
//! any of them to a map with per-vertex values ([`crate::mesh::EditTarget`]: a
//! [`crate::Mesh`], say) and places new vertices.
//!
//! ```
//! use zipmesh_kernel::{gen, ops::tri};
//! let mut map = gen::random_triangle(500, 1, 0, 7).map;
//! let before = map.clone();
//! let h = map.darts().find(|&d| tri::can_flip_edge(&map, d).is_ok()).unwrap();
//! let flip = tri::flip_edge(&mut map, h).unwrap();
//! let split = tri::split_edge(&mut map, h).unwrap();
//! assert!(map.check().is_ok());
//! split.undo(&mut map).unwrap(); // records are undone in reverse order
//! flip.undo(&mut map).unwrap();
//! assert_eq!(map, before);
//! ```
//!
//! # Conventions
//! Faces run counter-clockwise seen from the front; `rotate_cw(d) = next(twin(d))`. Valence is
//! the number of darts leaving a vertex. A *proper triangle* is a face of degree 3 with three
//! distinct corners. Every triangle an operator touches must be proper
//! ([`Refusal::DegenerateTriangle`] otherwise); faces elsewhere may have any degree.
//!
//! **Valence minimum.** No operator leaves an interior vertex of valence below 3 or a boundary
//! vertex of valence below 2 where there was none ([`Refusal::ValenceTooLow`]). An interior
//! vertex of valence 2 means two triangles folded onto each other along two edges: zero area
//! and an undefined normal, the defect pmp-library's issue 245 reports after a collapse.
//!
//! # Changes in counts (V, E, F) and valences, as tested
//! | operator | V | E | F | valences |
//! |---|---|---|---|---|
//! | [`flip_edge`] of a-b (apexes c, d) | 0 | 0 | 0 | a, b: -1; c, d: +1 |
//! | [`collapse_edge`] of v→u, interior edge | -1 | -3 | -2 | u: d(u) + d(v) - 4; apexes -1 |
//! | [`collapse_edge`] of v→u, boundary edge | -1 | -2 | -1 | u: d(u) + d(v) - 3; apex -1 |
//! | [`split_vertex`] of w at w→a, w→b | +1 | +3 | +2 | w: k_w + 3, new v: k_v + 3; a, b: +1 |
//! | [`split_edge`] of a-b, interior edge | +1 | +3 | +2 | new m: 4; apexes +1 |
//! | [`split_edge`] of a-b, boundary edge | +1 | +2 | +1 | new m: 3; apex +1 |
//!
//! Every other vertex keeps its valence. This table is the rule for people; [`TriOp::effect`]
//! is the same rule as code (an [`Effect`](crate::ops::Effect), one copy), against which the
//! proofs, the tests and the campaign check every application. `k_w` and `k_v` count the darts of `w` strictly
//! inside the kept and the moved arc (see [`split_vertex`]); the paper's `d1 + 3`, `d2 + 3`.
//! Diagrams and the reasons for each rule: `docs/operators-tri.md`.
//!
//! # Cost
//! Flip: O(valence of c) for the multi-edge test. Collapse: O(d(v) + sum of the valences of
//! v's other neighbours) for the link test, plus O(d(u)) when the edge is on the boundary.
//! Vertex split: O(size of the moved arc + valences of its ends). Edge split: O(1), plus
//! O(d(b)) on a boundary edge whose face is on the side of `twin(h)`. No operator allocates
//! unless a free list is empty (then the arrays grow) or a free list grows.

use super::Refusal;
use crate::map::{Dart, Map, Vert, NONE};

mod collapse;
mod edge_split;
mod effect;
mod flip;
mod mesh;
#[cfg(test)]
mod tests;

pub use collapse::{can_collapse_edge, can_split_vertex, collapse_edge, split_vertex};
pub use collapse::{EdgeCollapse, VertexSplit};
pub use edge_split::{can_split_edge, split_edge, EdgeSplit};
pub use flip::{can_flip_edge, flip_edge, EdgeFlip};

pub use super::Undo;

/// One triangle operator with its arguments, as a value: for sequences, fuzzing and
/// replays (the triangle counterpart of [`crate::ops::quad::QuadOp`]).
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri::TriOp};
/// let mut map = gen::random_triangle(200, 0, 0, 3).map;
/// let before = map.clone();
/// let d = map.darts().find(|&d| TriOp::Flip(d).can(&map).is_ok()).unwrap();
/// let record = TriOp::Flip(d).apply(&mut map).unwrap();
/// record.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// assert_eq!(TriOp::Flip(d).name(), "flip");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TriOp {
    /// [`flip_edge`] of the dart's edge.
    Flip(Dart),
    /// [`collapse_edge`] of the dart's origin into its destination.
    Collapse(Dart),
    /// [`split_vertex`] along the two darts.
    SplitVertex(Dart, Dart),
    /// [`split_edge`] of the dart's edge.
    SplitEdge(Dart),
}

impl TriOp {
    /// A short name for reports.
    ///
    /// See [`TriOp`] for an example.
    pub fn name(self) -> &'static str {
        match self {
            TriOp::Flip(_) => "flip",
            TriOp::Collapse(_) => "collapse",
            TriOp::SplitVertex(..) => "vertex split",
            TriOp::SplitEdge(_) => "edge split",
        }
    }

    /// The operator's `can_*` check.
    ///
    /// See [`TriOp`] for an example.
    pub fn can(self, m: &Map) -> Result<(), Refusal> {
        match self {
            TriOp::Flip(d) => can_flip_edge(m, d),
            TriOp::Collapse(d) => can_collapse_edge(m, d),
            TriOp::SplitVertex(a, b) => can_split_vertex(m, a, b),
            TriOp::SplitEdge(d) => can_split_edge(m, d),
        }
    }
}

/// The record of any triangle operator (see [`TriOp::apply`]).
///
/// See [`TriOp`] for an example.
#[derive(Clone, Copy, Debug)]
pub enum TriRecord {
    /// A [`flip_edge`].
    Flip(EdgeFlip),
    /// A [`collapse_edge`].
    Collapse(EdgeCollapse),
    /// A [`split_vertex`].
    SplitVertex(VertexSplit),
    /// A [`split_edge`].
    SplitEdge(EdgeSplit),
}

impl TriRecord {
    /// Undoes the recorded operation; see each record's `undo`.
    ///
    /// See [`TriOp`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        match self {
            TriRecord::Flip(r) => r.undo(map),
            TriRecord::Collapse(r) => r.undo(map),
            TriRecord::SplitVertex(r) => r.undo(map),
            TriRecord::SplitEdge(r) => r.undo(map),
        }
    }
}

macro_rules! into_record {
    ($t:ty, $v:ident) => {
        impl From<$t> for TriRecord {
            fn from(r: $t) -> TriRecord {
                TriRecord::$v(r)
            }
        }
    };
}
into_record!(EdgeFlip, Flip);
into_record!(EdgeCollapse, Collapse);
into_record!(VertexSplit, SplitVertex);
into_record!(EdgeSplit, SplitEdge);

impl Undo for TriRecord {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        TriRecord::undo(self, map)
    }
}

/// Minimum valence of a vertex after an operation: 3 inside, 2 on the boundary.
#[inline]
pub(crate) fn min_valence(boundary: bool) -> usize {
    if boundary {
        2
    } else {
        3
    }
}

/// The darts `[d, next d, next next d]` of the face of the live face dart `d`, if that face
/// is a triangle ([`Refusal::WrongDegree`] otherwise).
#[inline]
pub(crate) fn triangle(map: &Map, d: Dart) -> Result<[Dart; 3], Refusal> {
    let n1 = map.next(d);
    let n2 = map.next(n1);
    if n1 == d || n2 == d || map.next(n2) != d {
        return Err(Refusal::WrongDegree);
    }
    Ok([d, n1, n2])
}

/// The triangle of `d`, `None` when `d` is a boundary dart, or why the face is not a
/// proper triangle ([`Refusal::WrongDegree`], [`Refusal::DegenerateTriangle`]).
#[inline]
pub(crate) fn side(map: &Map, d: Dart) -> Result<Option<[Dart; 3]>, Refusal> {
    if map.face(d).is_none() {
        return Ok(None);
    }
    triangle(map, d).map(Some)
}

/// The two sides of the live dart `h` (see [`side`]), both checked for their degree first
/// and then for distinct corners.
#[inline]
pub(crate) fn sides(map: &Map, h: Dart) -> Result<[Option<[Dart; 3]>; 2], Refusal> {
    let l = side(map, h)?;
    let r = side(map, h.twin())?;
    if l.is_some_and(|x| !distinct_corners(map, x)) || r.is_some_and(|x| !distinct_corners(map, x))
    {
        return Err(Refusal::DegenerateTriangle);
    }
    Ok([l, r])
}

/// Whether the triangle's three corners are distinct.
#[inline]
pub(crate) fn distinct_corners(map: &Map, t: [Dart; 3]) -> bool {
    let [a, b, c] = t.map(|d| map.origin(d));
    a != b && b != c && a != c
}

/// Whether the vertex with outgoing dart `d` has at least `k` darts (walks at most `k`).
#[inline]
pub(crate) fn valence_at_least(map: &Map, d: Dart, k: usize) -> bool {
    let mut x = d;
    for i in 1..k {
        x = map.rotate_cw(x);
        if x == d {
            return i >= k;
        }
    }
    true
}

/// Whether some dart leaving the vertex of `d` ends at `target` (walks that rotation).
#[inline]
pub(crate) fn joined(map: &Map, d: Dart, target: Vert) -> bool {
    let mut x = d;
    for _ in 0..map.dart_slots() {
        if map.dest(x) == target {
            return true;
        }
        x = map.rotate_cw(x);
        if x == d {
            break;
        }
    }
    false
}

/// How many neighbours [`gather`] keeps on the stack; longer walks fall back to walking the
/// neighbours' own rotations. (Unit tests pass a smaller limit to test the fallback.)
pub(crate) const SMALL: usize = 16;

/// The ends of a run of darts around one vertex, kept on the stack for membership tests.
pub(crate) struct Ends {
    ids: [Vert; SMALL],
    len: usize,
}

impl Ends {
    #[inline]
    pub(crate) fn contains(&self, v: Vert) -> bool {
        self.ids[..self.len].contains(&v)
    }

    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.len
    }
}

/// The destinations of the darts clockwise from `start` through `end` (the whole rotation if
/// `end` is not met), or `None` if there are more than `limit` (at most [`SMALL`]). One walk
/// of the rotation and no other memory: cheaper than walking each candidate's rotation.
#[inline]
pub(crate) fn gather(map: &Map, start: Dart, end: Option<Dart>, limit: usize) -> Option<Ends> {
    let mut e = Ends {
        ids: [Vert(NONE); SMALL],
        len: 0,
    };
    let mut x = start;
    loop {
        if e.len >= limit.min(SMALL) {
            return None;
        }
        e.ids[e.len] = map.dest(x);
        e.len += 1;
        if Some(x) == end {
            return Some(e);
        }
        x = map.rotate_cw(x);
        if x == start {
            return Some(e);
        }
    }
}

/// The dart before `d` around its face or boundary loop (see [`Map::prev`]).
#[inline]
pub(crate) fn prev_of(map: &Map, d: Dart) -> Dart {
    if map.face(d).is_some() {
        // Faces here are mostly triangles: walk the face, cheaper than the rotation.
        let mut x = d;
        for _ in 0..map.dart_slots() {
            let y = map.next(x);
            if y == d {
                return x;
            }
            x = y;
        }
    }
    map.prev(d)
}
