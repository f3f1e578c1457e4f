//! Atomic v7 movement with 5-7 generation and its inverse with 5-7 removal (the mirror of
//! Fig. 7, Sec. 6.2 "similar"), and the 5-5-7 / 5-7-7 triples of Sec. 7.2-7.3 built on
//! them and on the v5 counterparts ([`super::generate_pair`], [`super::remove_pair`]).
//!
//! Generation at a lone v7 `v`, along the dart `d = v -> a` (`b`, `e` the apexes left and
//! right of `d`, `c` the neighbour four darts clockwise from `a`):
//!
//! ```text
//!   Flip (flip v-a)               Split (v along v->a, v->c, 3 darts kept between)
//!       b                b(7)          a                a(7)
//!      /|\              /   \          |                |   \
//!     v | a    =>    v(6)---a(5)   ... v(7) ...  =>  v(6)---v'(5)
//!      \|/              \   /          |                |   /
//!       e                e(7)          c                c(7)
//! ```
//!
//! | [`Via7`] | operation | the two new v7 (`Moved::First`, `Moved::Second`) | new v5 | `v` |
//! |---|---|---|---|---|
//! | `Flip` | flip `v-a` | `b`, `e` | `a` | 6 |
//! | `Split` | split `v` along `v->a`, `v->c` (3 darts in the kept arc) | `a`, `c` | the new `v'` | 6 |
//!
//! A collapse cannot take a v7 down by one with every other vertex regular (a collapse
//! lowers only the two apexes, and the kept vertex gets `6 + 6 - 4 = 8` or more), so the
//! v7 has two configurations where the v5 has three.
//!
//! **Removal** (`remove_pair_v7(map, m, p, q)`: the v7 `m` moves, the pair of the v5 `p`
//! and the v7 `q` goes; `m` and `q` both neighbours of `p`) is read off the gap between
//! `m` and `q` around `p`: 1 (`m-q` an edge), flip `m-q`, the v7 ends at the far apex;
//! 2 (one vertex `x` between), collapse `p` into `x`, which becomes the v7 (5 + 6 - 4).

use super::generate::{remove_pair, Moved};
use super::record::{apply_one, created, tri_apex, turn, VertexMove};
use super::{interior_of_valence, regular, TriEditError};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited, VertexAttributes};
use crate::ops::tri::{TriOp, TriRecord};
use crate::ops::{Refusal, Undo};
use alloc::vec::Vec;

/// The graph operation of a v7 movement with 5-7 generation (see the module table).
///
/// ```
/// use zipmesh::tri_edit::Via7;
/// assert_ne!(Via7::Flip, Via7::Split);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Via7 {
    /// Flip the spoke `v-a`.
    Flip,
    /// Split `v` along `v -> a` and `v -> c`, three darts in the kept arc.
    Split,
}

impl Via7 {
    /// Both configurations.
    ///
    /// See [`Via7`] for an example.
    pub const ALL: [Via7; 2] = [Via7::Flip, Via7::Split];
}

/// The operation, the two new v7 (first, second) and the new v5 (`None`: created).
type Plan7 = (TriOp, [Vert; 2], Option<Vert>);

fn plan_generation(map: &Map, d: Dart, via: Via7) -> Result<Plan7, TriEditError> {
    if !map.is_live_dart(d) {
        return Err(TriEditError::DeadHandle);
    }
    let (v, a) = (map.origin(d), map.dest(d));
    if !interior_of_valence(map, v, 7) {
        return Err(TriEditError::NotAPair);
    }
    let plan = match via {
        Via7::Flip => {
            let (b, e) = (tri_apex(map, d)?, tri_apex(map, d.twin())?);
            (TriOp::Flip(d), [b, e], Some(a))
        }
        Via7::Split => {
            let vc = turn(map, d, 4);
            (TriOp::SplitVertex(d, vc), [a, map.dest(vc)], None)
        }
    };
    for w in plan.1.into_iter().chain(plan.2) {
        regular(map, w)?;
    }
    Ok(plan)
}

/// Checks whether [`generate_pair_v7`] applies, without changing anything: `origin(d)` an
/// interior v7 ([`TriEditError::NotAPair`] otherwise), the vertices that change valence
/// regular ([`TriEditError::Irregular`]), then the graph operator's rules.
///
/// See [`generate_pair_v7`] for an example.
pub fn can_generate_pair_v7(map: &Map, d: Dart, via: Via7) -> Result<(), TriEditError> {
    let (op, _, _) = plan_generation(map, d, via)?;
    Ok(op.can(map)?)
}

/// Moves the v7 `origin(d)` one step by `via`, generating an adjacent 5-7 pair, or refuses
/// (see [`can_generate_pair_v7`]) with the map unchanged. [`V7Move::moved`] is the v7 that
/// `moved` names; [`V7Move::pair`] the new v5 and the other new v7. The irregular multiset
/// gains one v5 and one v7.
///
/// ```
/// use zipmesh::gen::cone_disk;
/// use zipmesh::tri_edit::{generate_pair_v7, Moved, Via7};
/// use zipmesh::Vert;
/// let mut map = cone_disk(7, 4); // a lone v7 at vertex 0
/// let before = map.clone();
/// let d = map.vertex_dart(Vert::new(0));
/// let g = generate_pair_v7(&mut map, d, Via7::Split, Moved::First).unwrap();
/// let (p, q) = g.pair().unwrap();
/// assert_eq!((map.valence(g.moved()), map.valence(p), map.valence(q)), (7, 5, 7));
/// assert_eq!(map.valence(Vert::new(0)), 6);
/// g.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
pub fn generate_pair_v7<T: EditTarget>(
    target: &mut T,
    d: Dart,
    via: Via7,
    moved: Moved,
) -> Result<Edited<V7Move, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let (op, sevens, five) = plan_generation(map, d, via)?;
    apply_one(map, attrs, op, |op, r| {
        generation_record(op, r, sevens, five, moved)
    })
}

fn generation_record(
    op: TriOp,
    record: TriRecord,
    [x, y]: [Vert; 2],
    five: Option<Vert>,
    moved: Moved,
) -> V7Move {
    let p = five.or(created(&record)).unwrap_or(x);
    let (m, q) = if moved == Moved::First {
        (x, y)
    } else {
        (y, x)
    };
    V7Move {
        moved: m,
        pair: Some((p, q)),
        op,
        record,
    }
}

/// The removal's operation and where the v7 ends.
fn plan_removal(map: &Map, m: Vert, p: Vert, q: Vert) -> Result<(TriOp, Vert), TriEditError> {
    if ![m, p, q].iter().all(|&v| map.is_live_vertex(v)) {
        return Err(TriEditError::DeadHandle);
    }
    let seven = |v| interior_of_valence(map, v, 7);
    if m == q || !seven(m) || !seven(q) || !interior_of_valence(map, p, 5) {
        return Err(TriEditError::NotAPair);
    }
    let pm = map.dart_between(p, m).ok_or(TriEditError::NotAPair)?;
    let gap = (1..5).find(|&k| map.dest(turn(map, pm, k)) == q);
    let gap = gap.ok_or(TriEditError::NotAPair)?;
    let plan = match gap.min(5 - gap) {
        1 => {
            let mq = map.dart_between(m, q).ok_or(TriEditError::NotAPair)?;
            // The apex of m-q other than p.
            let x = if tri_apex(map, mq)? == p {
                tri_apex(map, mq.twin())?
            } else {
                tri_apex(map, mq)?
            };
            (TriOp::Flip(mq), x)
        }
        _ => {
            let px = turn(map, pm, if gap == 2 { 1 } else { 4 });
            (TriOp::Collapse(px), map.dest(px))
        }
    };
    regular(map, plan.1)?;
    Ok(plan)
}

/// Checks whether [`remove_pair_v7`] applies, without changing anything.
///
/// See [`remove_pair_v7`] for an example.
pub fn can_remove_pair_v7(map: &Map, m: Vert, p: Vert, q: Vert) -> Result<(), TriEditError> {
    let (op, _) = plan_removal(map, m, p, q)?;
    Ok(op.can(map)?)
}

/// The inverse of [`generate_pair_v7`]: the v7 `m` moves one step and the adjacent pair of
/// the v5 `p` and the v7 `q` disappears (all three interior, `m` and `q` both neighbours of
/// `p`, one or two darts apart around it). Afterwards [`V7Move::moved`] is the one v7 left.
/// Refusals: [`TriEditError::NotAPair`], [`TriEditError::Irregular`] (the vertex that
/// becomes the v7 is not regular), then the graph operator's own; the map is then unchanged.
///
/// ```
/// use zipmesh::gen::cone_disk;
/// use zipmesh::tri_edit::{generate_pair_v7, remove_pair_v7, Moved, Via7};
/// use zipmesh::{is_isomorphic, Vert};
/// let mut map = cone_disk(7, 4);
/// let before = map.clone();
/// let d = map.vertex_dart(Vert::new(0));
/// let g = generate_pair_v7(&mut map, d, Via7::Flip, Moved::Second).unwrap();
/// let (p, q) = g.pair().unwrap();
/// let r = remove_pair_v7(&mut map, g.moved(), p, q).unwrap();
/// assert_eq!(map.valence(r.moved()), 7);
/// assert!(is_isomorphic(&map, &before));
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
pub fn remove_pair_v7<T: EditTarget>(
    target: &mut T,
    m: Vert,
    p: Vert,
    q: Vert,
) -> Result<Edited<V7Move, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let (op, to) = plan_removal(map, m, p, q)?;
    apply_one(map, attrs, op, |op, record| V7Move {
        moved: to,
        pair: None,
        op,
        record,
    })
}

/// Record of a [`generate_pair_v7`] or a [`remove_pair_v7`] (the record of every lone
/// vertex's movement, [`VertexMove`]).
///
/// See [`generate_pair_v7`] for an example.
pub type V7Move = VertexMove;

/// Up to three vertices, in order: [`kinds`] runs for every triple a pass tries, so it
/// allocates nothing.
struct Few {
    v: [Vert; 3],
    n: usize,
}

impl Few {
    fn new() -> Self {
        Few {
            v: [Vert::new(0); 3],
            n: 0,
        }
    }

    fn push(&mut self, v: Vert) {
        if let Some(x) = self.v.get_mut(self.n) {
            *x = v;
            self.n += 1;
        }
    }

    fn as_slice(&self) -> &[Vert] {
        &self.v[..self.n]
    }
}

/// The interior v5 and the interior v7 among three live vertices, each in the order given
/// (one walk round each vertex).
fn kinds(map: &Map, three: &[Vert]) -> Result<(Few, Few), TriEditError> {
    let &[a, b, c] = three else {
        return Err(TriEditError::NotAPair);
    };
    if ![a, b, c].iter().all(|&v| map.is_live_vertex(v)) {
        return Err(TriEditError::DeadHandle);
    }
    let (mut fives, mut sevens) = (Few::new(), Few::new());
    for v in [a, b, c]
        .into_iter()
        .filter(|&v| !map.is_boundary_vertex(v))
    {
        match map.valence(v) {
            5 => fives.push(v),
            7 => sevens.push(v),
            _ => {}
        }
    }
    Ok((fives, sevens))
}

/// The roles of a 5-5-7 or 5-7-7 triple: the vertex that moves (the first of its type in
/// the order given, or the second when the first cannot), and the pair that goes.
fn triple_plan(map: &Map, three: &[Vert]) -> Result<Triple, TriEditError> {
    let (fives, sevens) = kinds(map, three)?;
    let (options, kind) = match (fives.as_slice(), sevens.as_slice()) {
        (&[x, y], &[q]) => ([(x, y, q), (y, x, q)], 5),
        (&[p], &[x, y]) => ([(x, p, y), (y, p, x)], 7),
        _ => return Err(TriEditError::NotAPair),
    };
    let mut last = TriEditError::NotAPair;
    for (m, p, q) in options {
        let ok = if kind == 5 {
            super::can_remove_pair(map, m, p, q)
        } else {
            can_remove_pair_v7(map, m, p, q)
        };
        match ok {
            Ok(()) => return Ok(Triple { kind, m, p, q }),
            // Keep the most telling refusal.
            Err(e) if last == TriEditError::NotAPair => last = e,
            Err(_) => {}
        }
    }
    Err(last)
}

#[derive(Clone, Copy)]
struct Triple {
    kind: usize,
    m: Vert,
    p: Vert,
    q: Vert,
}

/// Checks whether [`cancel_triple`] applies, without changing anything.
///
/// See [`cancel_triple`] for an example.
pub fn can_cancel_triple(map: &Map, three: &[Vert]) -> Result<(), TriEditError> {
    triple_plan(map, three).map(|_| ())
}

/// Cancels an adjacent 5-5-7 triple into one v5, or a 5-7-7 triple into one v7 (Sec. 7.2's
/// last step: the atomic v5 or v7 movement with 5-7 removal). For 5-5-7 the v7 must be a
/// neighbour of both v5, for 5-7-7 the v5 of both v7; the vertex of the doubled type that
/// comes first in `three` is the one that moves (the other when the first cannot).
/// Refuses with the map unchanged: [`TriEditError::NotAPair`] when the three are not such
/// a triple, then the removal's refusals.
///
/// ```
/// use zipmesh::gen::geodesic_sphere;
/// use zipmesh::tri_edit::{cancel_triple, generate_pair, Moved, Via};
/// use zipmesh::{is_isomorphic, Vert};
/// let mut map = geodesic_sphere(2);
/// let before = map.clone();
/// // 7.3: a v5 moves and generates a pair: a 5-5-7 triple ...
/// let d = map.vertex_dart(Vert::new(0));
/// let g = generate_pair(&mut map, d, Via::Flip, Moved::First).unwrap();
/// let (p, q) = g.pair().unwrap();
/// // ... and 7.2 cancels it into one v5.
/// let c = cancel_triple(&mut map, &[g.moved(), p, q]).unwrap();
/// assert_eq!(map.valence(c.remaining()), 5);
/// assert!(is_isomorphic(&map, &before));
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
pub fn cancel_triple<T: EditTarget>(
    target: &mut T,
    three: &[Vert],
) -> Result<Edited<TripleEdit, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let t = triple_plan(map, three)?;
    Ok(if t.kind == 5 {
        remove_pair(&mut (&mut *map, &mut *attrs), t.m, t.p, t.q)?.map_record(TripleEdit::Five)
    } else {
        remove_pair_v7(&mut (&mut *map, &mut *attrs), t.m, t.p, t.q)?.map_record(TripleEdit::Seven)
    })
}

/// Record of a [`cancel_triple`]: the removal applied.
///
/// See [`cancel_triple`] for an example.
#[derive(Clone, Copy, Debug)]
pub enum TripleEdit {
    /// A 5-5-7 triple cancelled by a v5 movement with 5-7 removal.
    Five(VertexMove),
    /// A 5-7-7 triple cancelled by a v7 movement with 5-7 removal.
    Seven(VertexMove),
}

impl TripleEdit {
    /// The removal applied, whichever the triple's kind.
    ///
    /// See [`cancel_triple`] for an example.
    pub fn removal(&self) -> &VertexMove {
        match self {
            TripleEdit::Five(m) | TripleEdit::Seven(m) => m,
        }
    }

    /// The one irregular vertex left (the v5 or the v7 that moved).
    ///
    /// See [`cancel_triple`] for an example.
    pub fn remaining(&self) -> Vert {
        self.removal().moved()
    }

    /// The graph operation applied.
    ///
    /// See [`cancel_triple`] for an example.
    pub fn op(&self) -> TriOp {
        self.removal().op()
    }

    /// Restores the map exactly, or refuses with [`Refusal::StaleRecord`].
    ///
    /// See [`cancel_triple`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.removal().undo(map)
    }
}

impl Undo for TripleEdit {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        TripleEdit::undo(self, map)
    }
}

/// The adjacent 5-7 pair of a triple that is not adjacent yet, and the vertex that its
/// moves must bring next to the third: for 5-5-7 the v7 (to touch the other v5), for 5-7-7
/// the v5 (to touch the other v7). `(p, q, third, v7_leads)`.
fn far_plan(map: &Map, three: &[Vert]) -> Result<(Vert, Vert, Vert, bool), TriEditError> {
    let (fives, sevens) = kinds(map, three)?;
    let adjacent = |x: Vert, y: Vert| map.dart_between(x, y).is_some();
    match (fives.as_slice(), sevens.as_slice()) {
        (&[x, y], &[q]) => {
            // The v5 given first that forms the pair stays with the v7; the other waits.
            let (p, w) = if adjacent(x, q) { (x, y) } else { (y, x) };
            adjacent(p, q)
                .then_some((p, q, w, true))
                .ok_or(TriEditError::NotAPair)
        }
        (&[p], &[x, y]) => {
            let (q, w) = if adjacent(p, x) { (x, y) } else { (y, x) };
            adjacent(p, q)
                .then_some((p, q, w, false))
                .ok_or(TriEditError::NotAPair)
        }
        _ => Err(TriEditError::NotAPair),
    }
}

/// Graph distance from `from` to `to` (`usize::MAX` when apart), by breadth-first search
/// (see [`distance_within`]).
pub(super) fn distance(map: &Map, from: Vert, to: Vert) -> usize {
    distance_within(map, from, to, usize::MAX).unwrap_or(usize::MAX)
}

/// Graph distance from `from` to `to` when it is at most `limit`, `None` when it is more or
/// they are apart. A breadth-first search from both ends, one whole layer of the smaller
/// frontier at a time: it visits two balls of about half the distance's radius (on a
/// triangle lattice half the vertices of one ball of the whole radius), and stops once the
/// two radii add to `limit`; its cost does not depend on the map's size.
pub(super) fn distance_within(map: &Map, from: Vert, to: Vert, limit: usize) -> Option<usize> {
    if from == to {
        return Some(0);
    }
    let mut a = Search::new(from);
    let mut b = Search::new(to);
    loop {
        // No vertex is in both balls: every path is longer than the two radii together.
        if a.depth + b.depth >= limit {
            return None;
        }
        let (grow, other) = if a.frontier.len() <= b.frontier.len() {
            (&mut a, &b)
        } else {
            (&mut b, &a)
        };
        if grow.frontier.is_empty() {
            return None; // its component is exhausted
        }
        if let Some(d) = grow.expand(map, other) {
            return (d <= limit).then_some(d);
        }
    }
}

/// One end of [`distance_within`]'s search: the depth of every vertex seen, the last layer.
struct Search {
    seen: hashbrown::HashMap<Vert, usize>,
    frontier: Vec<Vert>,
    depth: usize,
}

impl Search {
    fn new(v: Vert) -> Search {
        let mut seen = hashbrown::HashMap::new();
        seen.insert(v, 0);
        Search {
            seen,
            frontier: alloc::vec![v],
            depth: 0,
        }
    }

    /// Adds the next layer; returns the shortest path through a vertex the other end has
    /// seen, if any. When the layers first touch, every such path is a shortest one: a
    /// vertex seen by both is found as the second end reaches it, and before this layer the
    /// distance was more than the two radii.
    fn expand(&mut self, map: &Map, other: &Search) -> Option<usize> {
        let mut next = Vec::new();
        let mut best: Option<usize> = None;
        for &v in &self.frontier {
            for d in map.vertex_darts(v) {
                let w = map.dest(d);
                if let hashbrown::hash_map::Entry::Vacant(e) = self.seen.entry(w) {
                    e.insert(self.depth + 1);
                    next.push(w);
                    if let Some(&dw) = other.seen.get(&w) {
                        let via = self.depth + 1 + dw;
                        best = Some(best.map_or(via, |x| x.min(via)));
                    }
                }
            }
        }
        self.depth += 1;
        self.frontier = next;
        best
    }
}

/// Cancels a 5-5-7 or 5-7-7 triple whose third vertex is not next to the pair yet (Sec.
/// 7.2): the adjacent 5-7 pair among the three moves by atomic 5-7 movements
/// ([`super::move_pair`]) until its v7 (5-5-7) or its v5 (5-7-7) touches the third vertex,
/// each step in the direction that brings it one edge closer, at most `max_steps` steps;
/// then [`cancel_triple`] removes the triple. All or nothing: when no direction brings it
/// closer, a move or the cancellation refuses, or the steps run out, every step is undone
/// and the error returned (the map `==` to before). An adjacent triple takes no step.
///
/// ```
/// use zipmesh::gen::geodesic_sphere;
/// use zipmesh::tri_edit::{cancel_triple_along, generate_pair, move_pair, Direction, Moved, Via};
/// use zipmesh::{is_isomorphic, Vert};
/// let mut map = geodesic_sphere(3);
/// let d = map.vertex_dart(Vert::new(0));
/// let g = generate_pair(&mut map, d, Via::Flip, Moved::First).unwrap();
/// let (p, q) = g.pair().unwrap();
/// // Walk the pair two steps away from the moved v5: a triple that is not adjacent.
/// let m1 = move_pair(&mut map, p, q, Direction::CollapseLeft).unwrap();
/// let m2 = move_pair(&mut map, m1.p(), m1.q(), Direction::CollapseLeft).unwrap();
/// let before = map.clone();
/// let c = cancel_triple_along(&mut map, &[g.moved(), m2.p(), m2.q()], 10).unwrap();
/// assert!(!c.moves().is_empty());
/// assert_eq!(map.valence(c.remaining()), 5);
/// c.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
pub fn cancel_triple_along<T: EditTarget>(
    target: &mut T,
    three: &[Vert],
    max_steps: usize,
) -> Result<Edited<TripleCancel, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let mut journal = crate::mesh::Journal::start(attrs);
    let mut moves: alloc::vec::Vec<super::PairMove> = alloc::vec::Vec::new();
    let result = walk_and_cancel(map, attrs, &mut journal, &mut moves, three, max_steps);
    match result {
        Ok(last) => Ok(Edited::new(TripleCancel { moves, last }, journal)),
        Err(e) => {
            // Fresh records of this map: their undo does not refuse.
            for m in moves.iter().rev() {
                let _ = m.undo(map);
            }
            journal.rewind(attrs);
            Err(e)
        }
    }
}

fn walk_and_cancel<A: VertexAttributes>(
    map: &mut Map,
    attrs: &mut A,
    journal: &mut crate::mesh::Journal<A>,
    moves: &mut alloc::vec::Vec<super::PairMove>,
    three: &[Vert],
    max_steps: usize,
) -> Result<TripleEdit, TriEditError> {
    if triple_plan(map, three).is_err() {
        let (mut p, mut q, w, v7_leads) = far_plan(map, three)?;
        let lead = |p: Vert, q: Vert| if v7_leads { q } else { p };
        let mut left = distance(map, lead(p, q), w);
        while left > 1 {
            if moves.len() >= max_steps {
                return Err(TriEditError::Irregular);
            }
            // The direction whose lead vertex ends one edge closer to w.
            let mut step = None;
            for dir in super::Direction::ALL {
                if let Some((np, nq)) = next_pair(map, p, q, dir) {
                    if distance_within(map, lead(np, nq), w, left - 1).is_some() {
                        step = Some(dir);
                        break;
                    }
                }
            }
            let dir = step.ok_or(TriEditError::Irregular)?;
            let e = super::pair::move_pair(&mut (&mut *map, &mut *attrs), p, q, dir)?;
            let (m, j) = e.into_parts();
            journal.absorb(j);
            (p, q) = (m.p(), m.q());
            moves.push(m);
            left = distance(map, lead(p, q), w);
        }
        let mut three = [p, q, w];
        // The vertex of the doubled type that waited moves in the cancellation.
        three.rotate_right(1);
        return cancel_step(map, attrs, journal, &three);
    }
    cancel_step(map, attrs, journal, three)
}

fn cancel_step<A: VertexAttributes>(
    map: &mut Map,
    attrs: &mut A,
    journal: &mut crate::mesh::Journal<A>,
    three: &[Vert],
) -> Result<TripleEdit, TriEditError> {
    let (t, j) = cancel_triple(&mut (&mut *map, &mut *attrs), three)?.into_parts();
    journal.absorb(j);
    Ok(t)
}

/// Where a 5-7 move in `dir` would leave the pair, if it applies: the move is made and
/// undone (a copy of the map per probe made long walks quadratic in the map's size).
fn next_pair(map: &mut Map, p: Vert, q: Vert, dir: super::Direction) -> Option<(Vert, Vert)> {
    let m = super::move_pair(map, p, q, dir).ok()?;
    // A split creates no vertex of the pair (q stays), so the handles are the map's before.
    let pair = (m.p(), m.q());
    // The exact undo of a move just made is not refused.
    let _ = m.undo(map);
    Some(pair)
}

/// Record of a [`cancel_triple_along`]: the pair's moves, then the cancellation.
///
/// See [`cancel_triple_along`] for an example.
#[derive(Clone, Debug)]
pub struct TripleCancel {
    moves: alloc::vec::Vec<super::PairMove>,
    last: TripleEdit,
}

impl TripleCancel {
    /// The atomic 5-7 movements done before the cancellation, in order.
    ///
    /// See [`cancel_triple_along`] for an example.
    pub fn moves(&self) -> &[super::PairMove] {
        &self.moves
    }

    /// The cancellation of the (then adjacent) triple.
    ///
    /// See [`cancel_triple_along`] for an example.
    pub fn cancellation(&self) -> &TripleEdit {
        &self.last
    }

    /// The one irregular vertex left.
    ///
    /// See [`cancel_triple_along`] for an example.
    pub fn remaining(&self) -> Vert {
        self.last.remaining()
    }

    /// Undoes the cancellation and the moves in reverse (`==`), or refuses with
    /// [`Refusal::StaleRecord`] (the steps already undone are not redone).
    ///
    /// See [`cancel_triple_along`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.last.undo(map)?;
        self.moves.iter().rev().try_for_each(|m| m.undo(map))
    }
}

impl Undo for TripleCancel {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        TripleCancel::undo(self, map)
    }
}

#[cfg(test)]
mod tests {
    use super::{distance, distance_within};
    use crate::map::{Map, Vert};
    use alloc::vec::Vec;

    /// The two-ended bounded search gives the plain breadth-first distances
    /// ([`Map::distances`]) wherever they are within its bound.
    #[test]
    fn both_ends_search_agrees_with_a_plain_one() {
        // Two components (a random mesh of genus 1 with holes next to a sphere), so that
        // some pairs are apart.
        let mut polys = Vec::new();
        let a = crate::gen::random_triangle(300, 1, 2, 7);
        let b = crate::gen::geodesic_sphere(1);
        let na = a.map.vertex_slots() as u32;
        polys.extend(a.polygons());
        for f in b.faces() {
            polys.push(
                b.face_darts(f)
                    .map(|d| b.origin(d).index() as u32 + na)
                    .collect(),
            );
        }
        let n = na as usize + b.vertex_slots();
        let map = Map::from_polygons(n, &polys).unwrap();
        let vs: Vec<Vert> = map.vertices().step_by(7).collect();
        let mut checked = 0;
        for &s in &vs {
            let truth = map.distances(s);
            for &t in &vs {
                let want = truth[t.index()];
                assert_eq!(distance(&map, s, t), want, "{s:?} {t:?}");
                for limit in [0, 1, 2, 3, 5, 8, 13] {
                    let got = distance_within(&map, s, t, limit);
                    assert_eq!(got, (want <= limit).then_some(want), "{s:?} {t:?} {limit}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 4_000, "{checked}"); // measured: 5,488
        assert!(vs
            .iter()
            .any(|&t| map.distances(vs[0])[t.index()] == usize::MAX));
    }
}
