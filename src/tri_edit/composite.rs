//! Composite movement of a pair of irregular vertices that need not be adjacent (Sec. 7.1):
//! a 5-7 pair (7.1.1) and the 5-5 and 7-7 pairs (7.1.2), all by the same three-step
//! pipeline.
//!
//! With `s` the vertex the pipeline starts at and `o` the pair's other vertex:
//! 1. `s` moves one step by the atomic movement with 5-7 generation
//!    ([`super::generate_pair`] at a v5, [`super::generate_pair_v7`] at a v7): `s` is now at
//!    `s'`, and a new adjacent 5-7 pair `(p, q)` sits next to it;
//! 2. the pair `(p, q)` walks by atomic 5-7 movements towards `o` until it touches it;
//! 3. the triple `(o, p, q)` cancels by the atomic movement with 5-7 removal, `o` being the
//!    vertex that moves: `o` is now at `o'` and the pair `(p, q)` is gone.
//!
//! Steps 2 and 3 are [`super::cancel_triple_along`] on `[o, p, q]` (a 5-5-7 triple when `o`
//! is a v5, a 5-7-7 triple when it is a v7). The pair `(s, o)` has become `(s', o')` with
//! the same valences; the rest of the mesh keeps its valences.
//!
//! ```text
//!   s(5) . . . . . o(7)        s'(5) p(5)-q(7) . o(7)      s'(5) . . . . . o'(7)
//!   |                    1.     \    /             2., 3.   (s', o') = (s, o) shifted
//!   s -> s' generates (p, q)     (p, q) walks to o, then o moves and (p, q) goes
//! ```

use super::generate::{generate_pair, Moved, Via};
use super::record::VertexMove;
use super::triple::{cancel_triple_along, distance, generate_pair_v7, TripleCancel, Via7};
use super::{interior_of_valence, TriEditError};
use crate::invariants::canonical::{is_isomorphic, CanonicalWorkspace};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited};
use crate::ops::{Refusal, Undo};
use alloc::vec::Vec;

/// The first step of the pipeline: the atomic generation at the starting vertex, a v5
/// ([`Via`]) or a v7 ([`Via7`]).
///
/// ```
/// use zipmesh::tri_edit::{Start, Via, Via7};
/// assert_ne!(Start::Five(Via::Flip), Start::Seven(Via7::Flip));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Start {
    /// The starting vertex is a v5 and moves by [`super::generate_pair`] with this operation.
    Five(Via),
    /// The starting vertex is a v7 and moves by [`super::generate_pair_v7`].
    Seven(Via7),
}

impl Start {
    /// Every configuration for a starting vertex of valence `k` (5 or 7; none otherwise).
    ///
    /// ```
    /// use zipmesh::tri_edit::Start;
    /// assert_eq!((Start::all(5).len(), Start::all(7).len(), Start::all(6).len()), (3, 2, 0));
    /// ```
    pub fn all(k: usize) -> &'static [Start] {
        match k {
            5 => &[
                Start::Five(Via::Flip),
                Start::Five(Via::Collapse),
                Start::Five(Via::Split),
            ],
            7 => &[Start::Seven(Via7::Flip), Start::Seven(Via7::Split)],
            _ => &[],
        }
    }

    fn valence(self) -> usize {
        match self {
            Start::Five(_) => 5,
            Start::Seven(_) => 7,
        }
    }
}

/// The kinds of the two vertices: `s` (the start) and `o`, each an interior v5 or v7, and
/// distinct.
fn check_pair(map: &Map, s: Vert, o: Vert, start: Start) -> Result<(), TriEditError> {
    if !map.is_live_vertex(s) || !map.is_live_vertex(o) {
        return Err(TriEditError::DeadHandle);
    }
    let kind = |v| interior_of_valence(map, v, 5) || interior_of_valence(map, v, 7);
    if s == o || !kind(o) || !interior_of_valence(map, s, start.valence()) {
        return Err(TriEditError::NotAPair);
    }
    Ok(())
}

/// Checks whether [`move_far_pair`] applies, without changing anything. The walk's
/// directions depend on where each step leaves the pair, so this runs the pipeline on a
/// copy of the map (one O(map) copy; the walk itself does not depend on the map's size).
///
/// See [`move_far_pair`] for an example.
pub fn can_move_far_pair(
    map: &Map,
    d: Dart,
    start: Start,
    moved: Moved,
    other: Vert,
    max_steps: usize,
) -> Result<(), TriEditError> {
    let mut probe = map.clone();
    move_far_pair(&mut probe, d, start, moved, other, max_steps).map(|_| ())
}

/// Moves the pair of the irregular vertices `origin(d)` and `other` (a 5-7, 5-5 or 7-7
/// pair, adjacent or not) by the pipeline of Sec. 7.1 (module docs): `origin(d)` moves one
/// step along `d` by `start` (`moved` says which new vertex is read as the moved one, see
/// [`Moved`]), the 5-7 pair generated walks to `other` in at most `max_steps` atomic 5-7
/// movements, and `other` moves by the 5-7 removal. Afterwards [`FarPairMove::pair`] is
/// `(origin(d)'s vertex, other's vertex)` with the valences they had.
///
/// All or nothing: on any refusal every step is undone and the map is `==` to before.
/// Refusals: [`TriEditError::DeadHandle`]; [`TriEditError::NotAPair`] when `origin(d)` is
/// not an interior vertex of `start`'s valence, or `other` not an interior v5 or v7; the
/// generation's and the walk's refusals ([`TriEditError::Irregular`] when the walk finds no
/// step closer or runs out of steps).
///
/// ```
/// use zipmesh::tri_edit::{move_far_pair, Moved, Start, Via};
/// use zipmesh::{gen, Vert};
/// // A level-3 geodesic sphere: twelve lone v5, far apart; two of them are a 5-5 pair.
/// let mut map = gen::geodesic_sphere(3);
/// let fives: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 5).collect();
/// let (s, o) = (fives[0], fives[1]);
/// let before = map.clone();
/// let found = map.vertex_darts(s).collect::<Vec<_>>().into_iter().find_map(|d| {
///     move_far_pair(&mut map, d, Start::Five(Via::Flip), Moved::First, o, 64).ok()
/// });
/// let m = found.expect("some direction moves the pair");
/// let (a, b) = m.pair();
/// assert_eq!((map.valence(a), map.valence(b)), (5, 5));
/// m.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
pub fn move_far_pair<T: EditTarget>(
    target: &mut T,
    d: Dart,
    start: Start,
    moved: Moved,
    other: Vert,
    max_steps: usize,
) -> Result<Edited<FarPairMove, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    if !map.is_live_dart(d) {
        return Err(TriEditError::DeadHandle);
    }
    check_pair(map, map.origin(d), other, start)?;
    let first = match start {
        Start::Five(via) => generate_pair(&mut (&mut *map, &mut *attrs), d, via, moved)?,
        Start::Seven(via) => generate_pair_v7(&mut (&mut *map, &mut *attrs), d, via, moved)?,
    };
    let (generation, mut journal) = first.into_parts();
    let (p, q) = generation.pair().ok_or(TriEditError::NotAPair)?;
    match cancel_triple_along(&mut (&mut *map, &mut *attrs), &[other, p, q], max_steps) {
        Ok(e) => {
            let (walk, j) = e.into_parts();
            journal.absorb(j);
            Ok(Edited::new(FarPairMove { generation, walk }, journal))
        }
        Err(e) => {
            // A fresh record of this map: its undo does not refuse.
            let _ = generation.undo(map);
            journal.rewind(attrs);
            Err(e)
        }
    }
}

/// How a composite move in one direction starts: the dart at the starting vertex, the
/// generation and its reading (the arguments of [`move_far_pair`]).
pub type FarStart = (Dart, Start, Moved);

/// The reference dart at `s`: towards the neighbour nearest `o` (graph distance); of two
/// such neighbours next to each other, the later counter-clockwise, so that the choice
/// does not depend on the numbering.
fn reference(map: &Map, s: Vert, o: Vert) -> Dart {
    let darts: Vec<Dart> = map.vertex_darts(s).collect();
    let dist: Vec<usize> = darts
        .iter()
        .map(|&d| distance(map, map.dest(d), o))
        .collect();
    let best = dist.iter().copied().min().unwrap_or(0);
    let k = darts.len();
    // A nearest neighbour whose clockwise predecessor (counter-clockwise successor) is not.
    let ccw_next = |i: usize| {
        let c = map.rotate_ccw(darts[i]);
        darts.iter().position(|&x| x == c).unwrap_or(i)
    };
    (0..k)
        .find(|&i| dist[i] == best && dist[ccw_next(i)] != best)
        .or_else(|| (0..k).find(|&i| dist[i] == best))
        .map_or(map.vertex_dart(s), |i| darts[i])
}

/// The six directions of Sec. 7.1 for the pair `(s, o)`, each as the first pipeline start
/// that realises it: every start at `s` ([`Start::all`], both readings) is tried on a copy,
/// in the order: darts counter-clockwise from the reference dart (towards the neighbour of
/// `s` nearest `o`), then [`Start::all`]'s order, then `First` before `Second`; starts
/// whose results are isomorphic are one direction, numbered by its first start. The paper
/// says there are six; fewer are returned when starts refuse (an irregular vertex or a
/// boundary nearby). Costs one pipeline and one canonical code per start.
///
/// ```
/// use zipmesh::tri_edit::far_pair_directions;
/// use zipmesh::{gen, Vert};
/// let map = gen::geodesic_sphere(2);
/// let fives: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 5).collect();
/// let dirs = far_pair_directions(&map, fives[0], fives[1], 64).unwrap();
/// assert!(dirs.len() <= 6);
/// ```
pub fn far_pair_directions(
    map: &Map,
    s: Vert,
    o: Vert,
    max_steps: usize,
) -> Result<Vec<FarStart>, TriEditError> {
    if !map.is_live_vertex(s) || !map.is_live_vertex(o) {
        return Err(TriEditError::DeadHandle);
    }
    let kind = if interior_of_valence(map, s, 5) { 5 } else { 7 };
    check_pair(
        map,
        s,
        o,
        Start::all(kind)
            .first()
            .copied()
            .ok_or(TriEditError::NotAPair)?,
    )?;
    let r = reference(map, s, o);
    // One workspace for the probes' codes (one per dart of `s`, start and mover).
    let mut codes = CanonicalWorkspace::new();
    let mut seen = Vec::new();
    let mut found = Vec::new();
    let mut d = r;
    for _ in 0..map.valence(s) {
        for &start in Start::all(kind) {
            for moved in [Moved::First, Moved::Second] {
                let mut probe = map.clone();
                if move_far_pair(&mut probe, d, start, moved, o, max_steps).is_ok() {
                    let h = codes.hash(&probe);
                    if !seen.contains(&h) {
                        seen.push(h);
                        found.push((d, start, moved));
                    }
                }
            }
        }
        d = map.rotate_ccw(d);
    }
    Ok(found)
}

/// The start of direction `dir` for the pair `(s, o)`: the `dir`-th of
/// [`far_pair_directions`], or [`TriEditError::NoDirection`] with how many apply.
///
/// ```
/// use zipmesh::tri_edit::{far_pair_start, move_far_pair, TriEditError};
/// use zipmesh::{gen, Vert};
/// let mut map = gen::geodesic_sphere(3);
/// let fives: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 5).collect();
/// let (s, o) = (fives[0], fives[1]);
/// let past = far_pair_start(&map, s, o, 6, 64); // there are six at most
/// assert!(matches!(past, Err(TriEditError::NoDirection { available }) if available <= 6));
/// let (d, start, moved) = far_pair_start(&map, s, o, 0, 64).unwrap();
/// move_far_pair(&mut map, d, start, moved, o, 64).unwrap();
/// ```
pub fn far_pair_start(
    map: &Map,
    s: Vert,
    o: Vert,
    dir: usize,
    max_steps: usize,
) -> Result<FarStart, TriEditError> {
    let dirs = far_pair_directions(map, s, o, max_steps)?;
    dirs.get(dir).copied().ok_or(TriEditError::NoDirection {
        available: dirs.len(),
    })
}

/// The direction whose `steps` composite moves from the pair `(s, o)` of `edited`, each
/// started by [`far_pair_start`], give a map isomorphic to `original`: the undo of `steps`
/// moves in one direction. `None` when none of the six does. The paper names no opposite
/// direction, so each is tried on a copy: up to six times `steps` moves, each with its
/// [`far_pair_directions`].
///
/// ```
/// use zipmesh::tri_edit::{far_pair_inverse, far_pair_start, move_far_pair};
/// use zipmesh::{gen, Vert};
/// let original = gen::geodesic_sphere(3);
/// let mut map = original.clone();
/// let fives: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 5).collect();
/// let (d, start, moved) = far_pair_start(&map, fives[0], fives[1], 0, 64).unwrap();
/// let m = move_far_pair(&mut map, d, start, moved, fives[1], 64).unwrap();
/// assert!(far_pair_inverse(&map, &original, m.pair(), 1, 64).is_some());
/// ```
pub fn far_pair_inverse(
    edited: &Map,
    original: &Map,
    (s, o): (Vert, Vert),
    steps: u32,
    max_steps: usize,
) -> Option<usize> {
    (0..6).find(|&dir| {
        let mut m = edited.clone();
        let (mut s, mut o) = (s, o);
        for _ in 0..steps {
            let Ok((d, start, moved)) = far_pair_start(&m, s, o, dir, max_steps) else {
                return false;
            };
            let Ok(e) = move_far_pair(&mut m, d, start, moved, o, max_steps) else {
                return false;
            };
            (s, o) = e.pair();
        }
        is_isomorphic(&m, original)
    })
}

/// Record of a [`move_far_pair`]: the generation at the starting vertex, then the walk and
/// the cancellation at the other.
///
/// See [`move_far_pair`] for an example.
#[derive(Clone, Debug)]
pub struct FarPairMove {
    generation: VertexMove,
    walk: TripleCancel,
}

impl FarPairMove {
    /// The pair after the move: where the starting vertex and the other vertex are now.
    ///
    /// See [`move_far_pair`] for an example.
    pub fn pair(&self) -> (Vert, Vert) {
        (self.generation.moved(), self.walk.remaining())
    }

    /// Step 1: the starting vertex's movement with 5-7 generation.
    ///
    /// See [`move_far_pair`] for an example.
    pub fn generation(&self) -> &VertexMove {
        &self.generation
    }

    /// Steps 2 and 3: the generated pair's walk and the cancellation at the other vertex.
    ///
    /// See [`move_far_pair`] for an example.
    pub fn walk(&self) -> &TripleCancel {
        &self.walk
    }

    /// Undoes the three steps in reverse (`==`), or refuses with [`Refusal::StaleRecord`].
    ///
    /// See [`move_far_pair`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.walk.undo(map)?;
        self.generation.undo(map)
    }
}

impl Undo for FarPairMove {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        FarPairMove::undo(self, map)
    }
}
