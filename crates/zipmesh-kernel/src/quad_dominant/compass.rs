//! Walking a triangle to a vertex (Q-zip paper, Fig. 14): the quad-dominant compass.
//!
//! The compass is the triangle's tip dart: every move hands on the new one, so where the
//! base is (the EV direction) is carried along without being guessed. At the tip `T`, with
//! tip dart `t`, each move sends the tip one edge along a fixed dart of `T`'s rotation:
//! LE along `rotate_cw(t)`, VE along `rotate_cw²(t)`, RE along `rotate_ccw²(t)`, EV onto
//! the base corners `dest(t)` and `dest(rotate_ccw(t))` (merged). With the paper's
//! valence-5 tip these are the five neighbours, so every direction of a shortest path is one
//! move; the "small rotation" of Fig. 14 is this choice of move by where the next path edge
//! sits relative to `t`. Each step takes the applicable move whose new tip is nearest the
//! target (breadth-first distances on the current map, ties in the order VE, EV, LE, RE)
//! and must bring it strictly nearer; where none does, a move aside followed by one that
//! brings the tip nearer than it was is taken (the first such pair). The walk is all or
//! nothing.

use super::walk::{can_move_triangle, Move, TriangleMove};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited, Positions, VertexAttributes};
use crate::ops::{Refusal, VertexChanges};
use alloc::collections::VecDeque;
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

/// Why a walk did not reach its target (the map is as it was).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WalkError {
    /// The tip dart is not a triangle's, or the target is not a live vertex.
    BadArguments(Refusal),
    /// No path joins the tip to the target.
    Unreachable,
    /// At this tip no applicable move brings the tip nearer the target, nor a move aside
    /// followed by one.
    Stuck {
        /// The tip vertex where the walk stopped (in the map as it was then).
        tip: Vert,
        /// Its distance to the target.
        distance: usize,
        /// Each move there ([`Move::ALL`] order): why it is refused, or how far from the
        /// target it lands the tip (`usize::MAX`: where no path leads).
        moves: [(Move, Result<usize, Refusal>); 4],
    },
}

impl fmt::Display for WalkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WalkError::BadArguments(r) => write!(f, "bad arguments: {r}"),
            WalkError::Unreachable => f.write_str("no path joins the tip to the target"),
            WalkError::Stuck {
                tip,
                distance,
                moves,
            } => {
                write!(
                    f,
                    "no move, nor a move aside and then one, brings the triangle nearer the \
                     target from vertex {} ({distance} edges away):",
                    tip.index()
                )?;
                for (i, (mv, r)) in moves.iter().enumerate() {
                    let sep = if i == 0 { " " } else { "; " };
                    match r {
                        Err(why) => write!(f, "{sep}{} refused ({why})", mv.name())?,
                        Ok(usize::MAX) => write!(f, "{sep}{} leads nowhere", mv.name())?,
                        Ok(d) => write!(f, "{sep}{} lands {d} away", mv.name())?,
                    }
                }
                Ok(())
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for WalkError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            WalkError::BadArguments(r) => Some(r),
            _ => None,
        }
    }
}

/// A walk's moves, in order, and the triangle's tip dart at the end.
#[derive(Clone, Debug)]
pub struct Walk<A: VertexAttributes = Positions> {
    steps: Vec<Edited<TriangleMove, A>>,
    tip: Dart,
}

impl<A: VertexAttributes> Walk<A> {
    /// The moves made, in order.
    ///
    /// See [`walk_to`] for an example.
    pub fn moves(&self) -> Vec<Move> {
        self.steps.iter().map(|e| e.record().kind()).collect()
    }

    /// The triangle's tip dart at the end.
    ///
    /// See [`walk_to`] for an example.
    pub fn tip(&self) -> Dart {
        self.tip
    }

    /// Undoes every move, last first, on the target walked on: map and values `==` as
    /// before the walk; on a stale record the moves undone so far stay undone and the
    /// error is returned.
    ///
    /// See [`walk_to`] for an example.
    pub fn undo<T: EditTarget<Values = A>>(&self, target: &mut T) -> Result<(), Refusal> {
        self.steps.iter().rev().try_for_each(|e| e.undo(target))
    }
}

/// Breadth-first edge distances to `target` (`usize::MAX` where unreachable or not
/// reached): the search stops once every vertex at most one edge farther than `tip` is
/// labelled, since every move lands the tip on a neighbour. O(ball around the target)
/// instead of O(map) per step.
fn distances(map: &Map, target: Vert, tip: Vert) -> Vec<usize> {
    let mut dist = vec![usize::MAX; map.vertex_slots()];
    let mut queue = VecDeque::from([target]);
    dist[target.index()] = 0;
    while let Some(v) = queue.pop_front() {
        let reached = dist.get(tip.index()).copied().unwrap_or(usize::MAX);
        if reached != usize::MAX && dist[v.index()] > reached {
            break;
        }
        for d in map.vertex_darts(v) {
            let w = map.dest(d);
            if dist[w.index()] == usize::MAX {
                dist[w.index()] = dist[v.index()] + 1;
                queue.push_back(w);
            }
        }
    }
    dist
}

/// Where the tip goes by each move: the new tip vertex (EV: the nearer base corner).
fn landing(map: &Map, t: Dart, mv: Move, dist: &[usize]) -> usize {
    let d = |v: Vert| dist.get(v.index()).copied().unwrap_or(usize::MAX);
    match mv {
        Move::VE => d(map.dest(map.rotate_cw(map.rotate_cw(t)))),
        Move::LE => d(map.dest(map.rotate_cw(t))),
        Move::RE => d(map.dest(map.rotate_ccw(map.rotate_ccw(t)))),
        Move::EV => d(map.dest(t)).min(d(map.dest(map.rotate_ccw(t)))),
    }
}

/// The compass's choice at tip dart `t` towards `target`: the applicable move that lands
/// the tip nearest the target, if one lands it nearer than it is; `None` at the target.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{compass, Move}};
/// let (mesh, tips) = gen::quad_dominant(8, 8, 1, 3);
/// let m = &mesh.map;
/// // The vertex two darts clockwise from the tip dart is reached by VE.
/// let u = m.dest(m.rotate_cw(m.rotate_cw(tips[0])));
/// assert_eq!(compass::next_move(m, tips[0], u), Some(Move::VE));
/// ```
pub fn next_move(map: &Map, t: Dart, target: Vert) -> Option<Move> {
    if !map.is_live_vertex(target) || map.origin(t) == target {
        return None;
    }
    next_move_by(map, t, &distances(map, target, map.origin(t)))
}

fn next_move_by(map: &Map, t: Dart, dist: &[usize]) -> Option<Move> {
    let here = dist.get(map.origin(t).index()).copied()?;
    Move::ALL
        .into_iter()
        .filter(|&mv| can_move_triangle(map, t, mv).is_ok())
        .map(|mv| (landing(map, t, mv, dist), mv))
        .filter(|&(d, _)| d < here)
        .min()
        .map(|(_, mv)| mv)
}

/// Walks the triangle of tip dart `t` until its tip is `target` (or `target` was merged
/// into the tip by an EV), one compass move at a time (see the [module docs](self)), on a
/// map and the values kept in step with it (see [`EditTarget`]). All or nothing: on an
/// error every move made is undone.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{self, compass}};
/// let (mut mesh, tips) = gen::quad_dominant(10, 10, 1, 3);
/// let before = mesh.clone();
/// let tip = mesh.map.origin(tips[0]);
/// // A vertex three edges away: straight on (two darts round each valence-4 vertex).
/// let m = &mesh.map;
/// let straight = |d: zipmesh_kernel::Dart| m.rotate_cw(m.rotate_cw(d.twin()));
/// let target = m.dest(straight(straight(m.rotate_cw(m.rotate_cw(tips[0])))));
/// let walk = compass::walk_to(&mut mesh, tips[0], target).unwrap();
/// assert!(mesh.map.origin(walk.tip()) == target || !mesh.map.is_live_vertex(target));
/// assert_ne!(mesh.map.origin(walk.tip()), tip);
/// walk.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn walk_to<T: EditTarget>(
    on: &mut T,
    t: Dart,
    target: Vert,
) -> Result<Walk<T::Values>, WalkError> {
    let (map, values) = on.parts();
    super::walk::triangle(map, t).map_err(WalkError::BadArguments)?;
    if !map.is_live_vertex(target) {
        return Err(WalkError::BadArguments(Refusal::DeadHandle));
    }
    let mut walk = Walk {
        steps: Vec::new(),
        tip: t,
    };
    while map.is_live_vertex(target) && map.origin(walk.tip) != target {
        let dist = distances(map, target, map.origin(walk.tip));
        let here = dist[map.origin(walk.tip).index()];
        let stop = if here == usize::MAX {
            Some(WalkError::Unreachable)
        } else if let Some(mv) = next_move_by(map, walk.tip, &dist) {
            step(map, values, &mut walk, mv)
                .err()
                .map(WalkError::BadArguments)
        } else if sidestep(map, values, &mut walk, target, here) {
            None
        } else {
            Some(WalkError::Stuck {
                tip: map.origin(walk.tip),
                distance: here,
                moves: Move::ALL.map(|mv| {
                    let r = can_move_triangle(map, walk.tip, mv);
                    (mv, r.map(|()| landing(map, walk.tip, mv, &dist)))
                }),
            })
        };
        if let Some(e) = stop {
            // The moves were just made, so their undo fits.
            let _ = walk.undo(&mut (&mut *map, &mut *values));
            return Err(e);
        }
    }
    Ok(walk)
}

/// Makes move `mv` at the walk's tip and records it.
fn step<A: VertexAttributes>(
    map: &mut Map,
    values: &mut A,
    walk: &mut Walk<A>,
    mv: Move,
) -> Result<(), Refusal> {
    let e = mv.apply(&mut (&mut *map, &mut *values), walk.tip)?;
    walk.tip = e.record().tip();
    walk.steps.push(e);
    Ok(())
}

/// Where no move brings the tip nearer than `here` edges from `target`: a move that does
/// not, then one that does (a tip of valence 3 or 4 reaches only some of its neighbours,
/// and a step aside turns the compass). Both are made, and `true` returned, for the first
/// such pair in [`Move::ALL`] order; otherwise the map is as it was.
fn sidestep<A: VertexAttributes>(
    map: &mut Map,
    values: &mut A,
    walk: &mut Walk<A>,
    target: Vert,
    here: usize,
) -> bool {
    for aside in Move::ALL {
        let before = walk.tip;
        if step(map, values, walk, aside).is_err() {
            continue;
        }
        if !map.is_live_vertex(target) || map.origin(walk.tip) == target {
            return true;
        }
        let dist = distances(map, target, map.origin(walk.tip));
        let on = Move::ALL
            .into_iter()
            .filter(|&mv| can_move_triangle(map, walk.tip, mv).is_ok())
            .map(|mv| (landing(map, walk.tip, mv, &dist), mv))
            .filter(|&(d, _)| d < here)
            .min();
        if let Some((_, mv)) = on {
            if step(map, values, walk, mv).is_ok() {
                return true;
            }
        }
        // The step aside was just made, so its undo fits.
        if let Some(e) = walk.steps.pop() {
            let _ = e.undo(&mut (&mut *map, &mut *values));
        }
        walk.tip = before;
    }
    false
}

/// Whether the walk's last move merged `target` away (EV onto it).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::compass};
/// let (mut mesh, tips) = gen::quad_dominant(8, 8, 1, 3);
/// let target = mesh.map.dest(tips[0]);
/// let walk = compass::walk_to(&mut mesh, tips[0], target).unwrap();
/// assert!(mesh.map.origin(walk.tip()) == target || compass::merged(&walk, target));
/// ```
pub fn merged<A: VertexAttributes>(walk: &Walk<A>, target: Vert) -> bool {
    walk.steps
        .last()
        .is_some_and(|e| e.record().removed_vertex() == Some(target))
}

/// The moves that take a triangle back along `done` (each [`Move::reverse`]d, the last
/// first) from tip dart `tip` of `map`, when they all apply and leave a map isomorphic to
/// `original`; `None` otherwise. This undoes moves where no record survives (a mesh written
/// to a file and read back), so it is checked on a copy, not assumed: O(moves + map).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{compass, Move}};
/// let (mut mesh, tips) = gen::quad_dominant(10, 10, 1, 3);
/// let original = mesh.map.clone();
/// let e = Move::VE.apply(&mut mesh, tips[0]).unwrap();
/// let back = compass::reverse_restores(&mesh.map, e.record().tip(), &[Move::VE], &original);
/// assert_eq!(back, Some(vec![Move::VE.reverse()]));
/// ```
pub fn reverse_restores(map: &Map, tip: Dart, done: &[Move], original: &Map) -> Option<Vec<Move>> {
    let back: Vec<Move> = done.iter().rev().map(|m| m.reverse()).collect();
    let mut m = map.clone();
    let mut t = tip;
    for &mv in &back {
        t = super::walk::move_triangle(&mut m, t, mv).ok()?.tip();
    }
    crate::is_isomorphic(&m, original).then_some(back)
}
