//! Atomic v5 movement with 5-7 generation, and its inverse, v5 movement with 5-7 removal
//! (Sec. 6.2, Fig. 7). One graph operation, read two ways: of the two v5 it leaves, the
//! caller names the one that is "the moved v5" ([`Moved`]); the other forms the new pair.
//!
//! Generation at a v5 `v`, along the dart `d = v -> a` (`b` the apex left of `d`, `e` the
//! apex right of it, `c` the far apex of the edge `a-b`, `f` the neighbour of `a` opposite
//! `v`):
//!
//! ```text
//!   Flip: flip a-b        v5 at a, b   v7 at c    v regular
//!   Collapse: v into a    v5 at b, e   v7 at a    v removed
//!   Split: a at (v, f)    v5 at a, a'  v7 at f    v regular (a' the new vertex)
//! ```
//! Removal is the inverse, told apart by where the two v5 `m`, `p` sit around the v7 `q`:
//! adjacent (gap 1), collapse `m-p` keeping `m`; one vertex `x` between them (gap 2), flip
//! `q-x`; gap 3, split `q` with the new vertex on the side with two darts between them.

use super::record::{apply_one, created, tri_apex, turn, VertexMove};
use super::{interior_of_valence, regular, TriEditError};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited};
use crate::ops::tri::{TriOp, TriRecord};

/// The graph operation of a v5 movement with 5-7 generation (see the module table).
///
/// ```
/// use zipmesh::tri_edit::Via;
/// assert_ne!(Via::Flip, Via::Split);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Via {
    /// Flip the link edge `a-b`.
    Flip,
    /// Collapse `v` into `a`.
    Collapse,
    /// Split `a` along `a -> v` and the opposite dart `a -> f`.
    Split,
}

/// Which of the two new v5 is read as the moved one: `First` is `a` (flip, split) or `b`
/// (collapse), `Second` is `b` (flip), `e` (collapse) or the new vertex (split).
///
/// ```
/// use zipmesh::tri_edit::Moved;
/// assert_ne!(Moved::First, Moved::Second);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Moved {
    /// The first reading.
    First,
    /// The second reading.
    Second,
}

/// The operation of a generation, the two new v5 (first, second; `None` for a vertex the
/// operation creates) and the new v7; the vertices that change valence are checked regular.
type Plan = (TriOp, [Option<Vert>; 2], Vert);

fn plan_generation(map: &Map, d: Dart, via: Via) -> Result<Plan, TriEditError> {
    if !map.is_live_dart(d) {
        return Err(TriEditError::DeadHandle);
    }
    let (v, a) = (map.origin(d), map.dest(d));
    if !interior_of_valence(map, v, 5) {
        return Err(TriEditError::NotAPair);
    }
    let b = tri_apex(map, d)?;
    // The plan, and the vertices other than v that change valence.
    let (plan, touched) = match via {
        Via::Flip => {
            let ab = map.next(d);
            let c = tri_apex(map, ab.twin())?;
            ((TriOp::Flip(ab), [Some(a), Some(b)], c), [a, b, c])
        }
        Via::Collapse => {
            let e = tri_apex(map, d.twin())?;
            ((TriOp::Collapse(d), [Some(b), Some(e)], a), [a, b, e])
        }
        Via::Split => {
            let av = d.twin();
            let af = turn(map, av, 3);
            let f = map.dest(af);
            ((TriOp::SplitVertex(av, af), [Some(a), None], f), [a, f, f])
        }
    };
    for w in touched {
        regular(map, w)?;
    }
    Ok(plan)
}

/// Checks whether [`generate_pair`] applies, without changing anything: `origin(d)` must be
/// an interior v5 ([`TriEditError::NotAPair`] otherwise), every other vertex that changes
/// valence regular ([`TriEditError::Irregular`]), then the graph operator's rules.
///
/// See [`generate_pair`] for an example.
pub fn can_generate_pair(map: &Map, d: Dart, via: Via) -> Result<(), TriEditError> {
    let (op, _, _) = plan_generation(map, d, via)?;
    Ok(op.can(map)?)
}

/// Moves the v5 `origin(d)` one step by `via`, generating an adjacent 5-7 pair, or refuses
/// (see [`can_generate_pair`]) with the map unchanged. [`V5Move::moved`] is the v5 that
/// `moved` names; [`V5Move::pair`] the other new v5 and the new v7. The irregular multiset
/// gains one v5 and one v7; only the vertices of the module table change valence.
///
/// ```
/// use zipmesh::tri_edit::{can_generate_pair, generate_pair, Moved, Via};
/// let mut map = zipmesh::gen::geodesic_sphere(2); // twelve lone v5
/// let before = map.clone();
/// let v = map.vertices().find(|&v| map.valence(v) == 5).unwrap();
/// let d = map.vertex_dart(v);
/// assert_eq!(can_generate_pair(&map, d, Via::Flip), Ok(()));
/// let g = generate_pair(&mut map, d, Via::Flip, Moved::First).unwrap();
/// let (p, q) = g.pair().unwrap();
/// assert_eq!((map.valence(g.moved()), map.valence(p), map.valence(q)), (5, 5, 7));
/// g.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
///
/// ```
/// use zipmesh::gen::geodesic_sphere;
/// use zipmesh::tri_edit::{generate_pair, Moved, Via};
/// use zipmesh::Vert;
/// let mut map = geodesic_sphere(2);
/// let mut marks = vec![1.0f64; map.vertex_slots()];
/// let before = (map.clone(), marks.clone());
/// let d = map.vertex_dart(Vert::new(0));
/// let e = generate_pair(&mut (&mut map, &mut marks), d, Via::Split, Moved::Second).unwrap();
/// assert_eq!(marks.len(), map.vertex_slots());
/// e.undo(&mut (&mut map, &mut marks)).unwrap();
/// assert_eq!((map, marks), before);
/// ```
pub fn generate_pair<T: EditTarget>(
    target: &mut T,
    d: Dart,
    via: Via,
    moved: Moved,
) -> Result<Edited<V5Move, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let (op, fives, q) = plan_generation(map, d, via)?;
    apply_one(map, attrs, op, |op, r| {
        generation_record(op, r, fives, q, moved)
    })
}

fn generation_record(
    op: TriOp,
    record: TriRecord,
    fives: [Option<Vert>; 2],
    q: Vert,
    moved: Moved,
) -> V5Move {
    let new = created(&record);
    let [x, y] = fives.map(|f| f.or(new).unwrap_or(q));
    let (m, p) = if moved == Moved::First {
        (x, y)
    } else {
        (y, x)
    };
    V5Move {
        moved: m,
        pair: Some((p, q)),
        op,
        record,
    }
}

/// The removal's operation and where the v5 ends (`None`: the vertex a split creates).
fn plan_removal(
    map: &Map,
    m: Vert,
    p: Vert,
    q: Vert,
) -> Result<(TriOp, Option<Vert>), TriEditError> {
    if ![m, p, q].iter().all(|&v| map.is_live_vertex(v)) {
        return Err(TriEditError::DeadHandle);
    }
    let five = |v| interior_of_valence(map, v, 5);
    if m == p || !five(m) || !five(p) || !interior_of_valence(map, q, 7) {
        return Err(TriEditError::NotAPair);
    }
    let qm = map.dart_between(q, m).ok_or(TriEditError::NotAPair)?;
    // Clockwise gap from m to p around q, and back.
    let gap = (1..7).find(|&k| map.dest(turn(map, qm, k)) == p);
    let gap = gap.ok_or(TriEditError::NotAPair)?;
    let plan = match gap.min(7 - gap) {
        1 => {
            let mp = map.dart_between(m, p).ok_or(TriEditError::NotAPair)?;
            let x = if map.dest(map.next(mp)) == q {
                tri_apex(map, mp.twin())?
            } else {
                tri_apex(map, mp)?
            };
            // Collapse p into m: the pair's v5 disappears, m stays.
            (TriOp::Collapse(mp.twin()), Some(x))
        }
        2 => {
            let qx = turn(map, qm, if gap == 2 { 1 } else { 6 });
            (TriOp::Flip(qx), Some(map.dest(qx)))
        }
        3 => {
            // The new vertex takes the side with two darts between m and p.
            let qp = turn(map, qm, gap);
            let (d1, d2) = if gap == 3 { (qp, qm) } else { (qm, qp) };
            (TriOp::SplitVertex(d1, d2), None)
        }
        _ => return Err(TriEditError::NotAPair),
    };
    if let Some(x) = plan.1 {
        regular(map, x)?;
    }
    Ok(plan)
}

/// Checks whether [`remove_pair`] applies, without changing anything.
///
/// See [`remove_pair`] for an example.
pub fn can_remove_pair(map: &Map, m: Vert, p: Vert, q: Vert) -> Result<(), TriEditError> {
    let (op, _) = plan_removal(map, m, p, q)?;
    Ok(op.can(map)?)
}

/// The inverse of [`generate_pair`]: the v5 `m` moves one step and the adjacent pair of the
/// v5 `p` and the v7 `q` disappears (all three interior, `m` and `p` both neighbours of
/// `q`). The graph operation is read off where `m` and `p` sit around `q` (module table);
/// afterwards [`V5Move::moved`] is the one v5 left and [`V5Move::pair`] is `None`.
/// Refusals: [`TriEditError::NotAPair`] when the three do not form one of the three
/// configurations, [`TriEditError::Irregular`], then the graph operator's own.
///
/// ```
/// use zipmesh::tri_edit::{generate_pair, remove_pair, Moved, Via};
/// use zipmesh::is_isomorphic;
/// let mut map = zipmesh::gen::geodesic_sphere(2);
/// let before = map.clone();
/// let v = map.vertices().find(|&v| map.valence(v) == 5).unwrap();
/// let d = map.vertex_dart(v);
/// let g = generate_pair(&mut map, d, Via::Collapse, Moved::First).unwrap();
/// let (p, q) = g.pair().unwrap();
/// let r = remove_pair(&mut map, g.moved(), p, q).unwrap();
/// assert_eq!(map.valence(r.moved()), 5);
/// assert!(is_isomorphic(&map, &before));
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
pub fn remove_pair<T: EditTarget>(
    target: &mut T,
    m: Vert,
    p: Vert,
    q: Vert,
) -> Result<Edited<V5Move, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let (op, to) = plan_removal(map, m, p, q)?;
    apply_one(map, attrs, op, |op, r| removal_record(op, r, to))
}

fn removal_record(op: TriOp, record: TriRecord, to: Option<Vert>) -> V5Move {
    V5Move {
        moved: to.or(created(&record)).unwrap_or(Vert::new(0)),
        pair: None,
        op,
        record,
    }
}

/// Record of a [`generate_pair`] or a [`remove_pair`] (the record of every lone vertex's
/// movement, [`VertexMove`]).
///
/// See [`generate_pair`] for an example.
pub type V5Move = VertexMove;
