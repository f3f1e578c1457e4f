//! Quad operators (the Q-zip paper, Sec. 2.2): quad collapse and its inverse the vertex split,
//! the high-valence split, valence-2 removal and its inverse the doublet insertion, and the
//! edge rotation in both directions.
//!
//! Every operator follows the contract of [`crate::ops`]: a pure `can_*` check, an operation
//! that refuses with the same [`Refusal`] and an untouched map or returns a record, and an
//! exact inverse `record.undo(&mut map)`. The full rules, with before/after diagrams, are in
//! `docs/operators-quad.md`; each function's documentation states its own.
//!
//! | operator | V | E | F | valences |
//! |---|---|---|---|---|
//! | [`collapse_quad`] | −1 | −2 | −1 | merged `val(a) + val(c) − 2`; `b`, `d` −1 |
//! | [`split_vertex`] | +1 | +2 | +1 | copies `arc₁ + 2`, `arc₂ + 2`; both ends +1 |
//! | [`split_high_valence`] | +1 | +2 | +1 | `k` → `⌊k/2⌋ + 1` and `⌈k/2⌉ + 1`; ends +1 |
//! | [`remove_valence2`] | −1 | −2 | −1 | the two neighbours −1 |
//! | [`insert_doublet`] | +1 | +2 | +1 | new vertex 2; the diagonal's ends +1 |
//! | [`rotate_edge`] | 0 | 0 | 0 | old ends −1, new ends +1 |
//!
//! Every other vertex keeps its valence. This table is the rule for people;
//! [`QuadOp::effect`] is the same rule as code (an [`Effect`](crate::ops::Effect), one copy),
//! against which the proofs, the tests and the campaign check every application.
//!
//! **Policies shared by all of them.** Loops and multi-edges are never created, and none
//! exists at a vertex whose edges an operator redistributes (so every operator and its inverse
//! refuse exactly the same configurations: the inverse of an applied operator is always
//! allowed). No face of degree below 3 results (every face keeps its degree or is a new quad).
//! A vertex may be left with valence 2 (Q-zip removes those afterwards with
//! [`remove_valence2`]) but never with valence 1. The boundary is never pinched.
//!
//! **Handles.** Operators keep the handles of every element they do not delete; new elements
//! take free slots last-in first-out, so undoing in reverse order gives back the same slots.
//!
//! ```
//! use zipmesh_kernel::{gen, ops::quad, Dart};
//! let mut map = gen::torus_grid(4, 4).map;
//! let before = map.clone();
//! let d = Dart::new(0);
//! let rec = quad::collapse_quad(&mut map, d).unwrap();
//! assert_eq!(map.num_faces(), before.num_faces() - 1);
//! assert_eq!(map.check(), Ok(()));
//! rec.undo(&mut map).unwrap();
//! assert_eq!(map, before);
//! ```

use super::slots::Slots;
use super::Refusal;
use crate::map::{Dart, Face, Map, Vert, NONE};
use alloc::vec::Vec;

mod collapse;
mod doublet;
mod effect;
mod mesh;
mod rotate;
#[cfg(test)]
mod tests;

pub use collapse::{
    can_collapse_quad, can_split_high_valence, can_split_vertex, collapse_quad, split_high_valence,
    split_vertex, QuadCollapse, VertexSplit, MIN_HIGH_VALENCE,
};
pub use doublet::{
    can_insert_doublet, can_remove_valence2, insert_doublet, remove_valence2, DoubletInsertion,
    Valence2Removal,
};
pub use rotate::{can_rotate_edge, rotate_edge, EdgeRotation, Rotation};

/// Any quad operator with its arguments, as a value: for drivers that pick operators at
/// run time (fuzzers, exhaustive proofs, property tests).
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad::QuadOp, Dart};
/// let mut map = gen::torus_grid(5, 5).map;
/// let before = map.clone();
/// let op = QuadOp::Collapse(Dart::new(0));
/// assert_eq!(op.can(&map), Ok(()));
/// let record = op.apply(&mut map).unwrap();
/// record.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// assert_eq!(op.name(), "collapse");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QuadOp {
    /// [`collapse_quad`] at the dart.
    Collapse(Dart),
    /// [`split_vertex`] along the two separators.
    Split(Dart, Dart),
    /// [`split_high_valence`] of the dart's origin, from the dart.
    HighValence(Dart),
    /// [`remove_valence2`] of the dart's origin.
    RemoveValence2(Dart),
    /// [`insert_doublet`] at the dart.
    InsertDoublet(Dart),
    /// [`rotate_edge`] of the dart's edge.
    Rotate(Dart, Rotation),
}

impl QuadOp {
    /// A short name for reports.
    ///
    /// See [`QuadOp`] for an example.
    pub fn name(self) -> &'static str {
        match self {
            QuadOp::Collapse(_) => "collapse",
            QuadOp::Split(..) => "split",
            QuadOp::HighValence(_) => "high-valence split",
            QuadOp::RemoveValence2(_) => "valence-2 removal",
            QuadOp::InsertDoublet(_) => "doublet insertion",
            QuadOp::Rotate(_, Rotation::Clockwise) => "rotation cw",
            QuadOp::Rotate(_, Rotation::CounterClockwise) => "rotation ccw",
        }
    }

    /// The operator's `can_*` check.
    ///
    /// See [`QuadOp`] for an example.
    pub fn can(self, m: &Map) -> Result<(), Refusal> {
        match self {
            QuadOp::Collapse(d) => can_collapse_quad(m, d),
            QuadOp::Split(a, b) => can_split_vertex(m, a, b),
            QuadOp::HighValence(d) => can_split_high_valence(m, m.origin(d), d),
            QuadOp::RemoveValence2(d) => can_remove_valence2(m, d),
            QuadOp::InsertDoublet(d) => can_insert_doublet(m, d),
            QuadOp::Rotate(d, r) => can_rotate_edge(m, d, r),
        }
    }
}

/// Any quad operator's record, for undo stacks that mix operators.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad::{self, QuadRecord}, Dart};
/// let mut map = gen::torus_grid(5, 5).map;
/// let before = map.clone();
/// let mut stack: Vec<QuadRecord> = Vec::new();
/// stack.push(quad::collapse_quad(&mut map, Dart::new(0)).unwrap().into());
/// stack.push(quad::rotate_edge(&mut map, Dart::new(20), quad::Rotation::Clockwise).unwrap().into());
/// while let Some(r) = stack.pop() {
///     r.undo(&mut map).unwrap();
/// }
/// assert_eq!(map, before);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum QuadRecord {
    /// A [`collapse_quad`].
    Collapse(QuadCollapse),
    /// A [`split_vertex`] or [`split_high_valence`].
    Split(VertexSplit),
    /// A [`remove_valence2`].
    RemoveValence2(Valence2Removal),
    /// An [`insert_doublet`].
    InsertDoublet(DoubletInsertion),
    /// A [`rotate_edge`].
    Rotate(EdgeRotation),
}

impl QuadRecord {
    /// Undoes the recorded operation; see each record's `undo`.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::{self, QuadRecord}, Dart};
    /// let mut map = gen::grid(3, 3).map;
    /// let before = map.clone();
    /// let r: QuadRecord = quad::insert_doublet(&mut map, Dart::new(0)).unwrap().into();
    /// r.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        match self {
            QuadRecord::Collapse(r) => r.undo(map),
            QuadRecord::Split(r) => r.undo(map),
            QuadRecord::RemoveValence2(r) => r.undo(map),
            QuadRecord::InsertDoublet(r) => r.undo(map),
            QuadRecord::Rotate(r) => r.undo(map),
        }
    }
}

macro_rules! into_record {
    ($t:ty, $v:ident) => {
        impl From<$t> for QuadRecord {
            fn from(r: $t) -> QuadRecord {
                QuadRecord::$v(r)
            }
        }
    };
}
into_record!(QuadCollapse, Collapse);
into_record!(VertexSplit, Split);
into_record!(Valence2Removal, RemoveValence2);
into_record!(DoubletInsertion, InsertDoublet);
into_record!(EdgeRotation, Rotate);

// ---------------------------------------------------------------------------------------
// Shared helpers. They read the map through its total accessors and write only to slots the
// caller has shown to be live, so no operator can index out of range.

/// The four darts of the quad face of `d`, starting at `d`; refused for a dead dart, a
/// boundary dart or a face of another degree.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad::quad_of, Dart};
/// let map = gen::grid(2, 2).map;
/// let d = map.darts().find(|&d| map.face(d).is_some()).unwrap();
/// let q = quad_of(&map, d).unwrap();
/// assert_eq!((q[0], map.next(q[3])), (d, d));
/// assert!(quad_of(&map, Dart::new(10_000)).is_err());
/// ```
pub fn quad_of(map: &Map, d: Dart) -> Result<[Dart; 4], Refusal> {
    if !map.is_live_dart(d) {
        return Err(Refusal::DeadHandle);
    }
    if map.face(d).is_none() {
        return Err(Refusal::Boundary);
    }
    let d1 = map.next(d);
    let d2 = map.next(d1);
    let d3 = map.next(d2);
    if d1 == d || d2 == d || d3 == d || map.next(d3) != d {
        return Err(Refusal::WrongDegree);
    }
    Ok([d, d1, d2, d3])
}

/// `rotate_cw(rotate_cw(d)) == d`: the origin of `d` has valence at most 2.
#[inline]
fn valence_at_most_2(map: &Map, d: Dart) -> bool {
    map.rotate_cw(map.rotate_cw(d)) == d
}

/// Neighbour lists for the "simple vertex" checks: inline for the common case, on the heap
/// only past 32 entries (a merged or split vertex of valence over 32).
struct Neighbours {
    inline: [u32; 32],
    len: usize,
    heap: Vec<u32>,
}

impl Neighbours {
    fn new() -> Self {
        Neighbours {
            inline: [0; 32],
            len: 0,
            heap: Vec::new(),
        }
    }

    #[inline]
    fn push(&mut self, v: Vert) {
        if self.len < self.inline.len() {
            self.inline[self.len] = v.0;
        } else {
            if self.heap.is_empty() {
                self.heap.extend_from_slice(&self.inline);
            }
            self.heap.push(v.0);
        }
        self.len += 1;
    }

    /// `Loop` if a neighbour is one of `forbidden` (the vertex itself, or the two vertices
    /// being merged), `MultiEdge` if a neighbour repeats.
    fn check(&mut self, forbidden: [Vert; 2]) -> Result<(), Refusal> {
        let list: &mut [u32] = if self.heap.is_empty() {
            &mut self.inline[..self.len]
        } else {
            &mut self.heap
        };
        if list
            .iter()
            .any(|&x| x == forbidden[0].0 || x == forbidden[1].0)
        {
            return Err(Refusal::Loop);
        }
        if list.len() <= 32 {
            // A 64-bit filter of hashed handles: only a handle whose bit is already set is
            // looked for among the earlier ones (rarely), not every pair.
            let mut seen = 0u64;
            for (i, &x) in list.iter().enumerate() {
                let bit = 1u64 << (x.wrapping_mul(0x9e37_79b1) >> 26);
                if seen & bit != 0 && list[..i].contains(&x) {
                    return Err(Refusal::MultiEdge);
                }
                seen |= bit;
            }
        } else {
            list.sort_unstable();
            if list.windows(2).any(|w| w[0] == w[1]) {
                return Err(Refusal::MultiEdge);
            }
        }
        Ok(())
    }
}

/// The old value of `vdart[v]` put back if it is still a correct record for `v` (a live dart
/// leaving `v`, the boundary one if `v` has one); otherwise the operator's own choice stays.
/// With the record's own map the old value is always correct, which gives exact undo; with a
/// foreign record the map stays valid.
fn restore_vdart(map: &mut Map, v: Vert, old: Dart) {
    let cur = map.vertex_dart(v);
    if !map.is_live_vertex(v) || !map.is_live_dart(old) || map.origin(old) != v {
        return;
    }
    if old == cur || (!map.is_boundary_dart(cur) && !map.is_boundary_dart(old)) {
        map.set_vertex_dart(v, old);
    }
}

/// The old value of `fdart[f]` put back if it is still a dart of `f`.
fn restore_fdart(map: &mut Map, f: Option<Face>, old: Dart) {
    if let Some(f) = f {
        if map.is_live_face(f) && map.is_live_dart(old) && map.face(old) == Some(f) {
            map.set_face_dart(f, old);
        }
    }
}

/// The recorded value of `fdart[f]` (or `NONE` for a boundary loop).
fn fdart_of(map: &Map, f: Option<Face>) -> Dart {
    f.map_or(Dart(NONE), |f| map.face_dart(f))
}

/// Sets `fdart[f] = to` if it was `from` (`f` may be a boundary loop: nothing to do).
#[inline]
fn replace_fdart(map: &mut Map, f: Option<Face>, from: Dart, to: Dart) {
    if fdart_of(map, f) == from {
        map.set_face_dart(f, to);
    }
}

/// Sets `vdart[v] = to` if it was `from`.
#[inline]
fn replace_vdart(map: &mut Map, v: Vert, from: Dart, to: Dart) {
    if map.vertex_dart(v) == from {
        map.set_vertex_dart(v, to);
    }
}

macro_rules! impl_undo {
    ($($t:ty),*) => {
        $(impl super::Undo for $t {
            fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
                <$t>::undo(self, map)
            }
        })*
    };
}
impl_undo!(
    QuadCollapse,
    VertexSplit,
    Valence2Removal,
    DoubletInsertion,
    EdgeRotation,
    QuadRecord
);
