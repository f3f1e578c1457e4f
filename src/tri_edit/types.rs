//! Type splitting and aggregation (Sec. 6.3): a vk (k > 7) into k - 6 v7, a v4 into two
//! v5, a v3 into three v5, and back: two or three v5 into a v4 or a v3, m v7 into a
//! v(6 + m).
//!
//! The sequences (valences by Sec. 6.1's rules, the neighbours regular):
//! * vk, k > 7: split it along two darts to regular neighbours with `s` darts inside the
//!   kept arc: it gets `s + 3`, the new vertex `k + 1 - s`, both separators become v7. With
//!   `s = 3` for k = 8 (6 and 6) and `s = 4` otherwise (a v7 and a v(k-3)), repeated on the
//!   new vertex while it has more than 7: k - 6 v7 in all, every other vertex as it was.
//! * v4: collapse it into a regular neighbour (4 + 6 - 4 = 6); the two apexes become v5.
//! * v3: collapse it into a neighbour (3 + 6 - 4 = 5); the other two become v5 as well.
//! * Aggregation, two v5 `b`, `c` with a regular common neighbour `a` where one dart lies
//!   between them: split `a`, the new vertex taking that dart (valence 1 + 3 = 4), `a` keeps
//!   3 + 3 = 6, `b`, `c` gain one. Three v5 around a triangle: split one of them with an
//!   empty moved arc between the other two (a new v3 inside the triangle).
//! * Aggregation of m v7: collapses whose apexes are two of the v7 gather them into one
//!   vertex (`gather`).

use super::record::turn;
use super::{interior_of_valence, regular, TriEditError};
use crate::map::{Map, Vert};
use crate::mesh::{EditTarget, Edited, Journal, VertexAttributes};
use crate::ops::tri::{can_split_vertex, TriOp, TriRecord};
use crate::ops::{Refusal, Undo};
use alloc::vec::Vec;

/// The vertices other than a new one whose valence `op` changes, read before it applies.
fn involved(map: &Map, op: TriOp) -> [Option<Vert>; 4] {
    match op {
        TriOp::SplitVertex(d1, d2) => [
            Some(map.origin(d1)),
            Some(map.dest(d1)),
            Some(map.dest(d2)),
            None,
        ],
        TriOp::Collapse(d) | TriOp::Flip(d) => [
            Some(map.origin(d)),
            Some(map.dest(d)),
            super::apex(map, d),
            super::apex(map, d.twin()),
        ],
        TriOp::SplitEdge(_) => [None; 4],
    }
}

/// The steps applied and every vertex they touched (old ones read before each step, new
/// ones from the records).
type Done = (Vec<TriRecord>, Vec<Vert>);

/// Applies operations one at a time, each computed from the map so far, on a map and a
/// per-vertex layer: each step places its vertex by its operator's rule
/// ([`TriOp::apply_with`]) and one journal keeps every value overwritten. On a refusal the
/// steps done are undone in reverse and the layer rewound: map and layer as they were.
pub(super) fn run_with<A: VertexAttributes>(
    map: &mut Map,
    attrs: &mut A,
    mut next: impl FnMut(&Map, &[TriRecord]) -> Result<Option<TriOp>, TriEditError>,
) -> Result<(Done, Journal<A>), TriEditError> {
    let (mut done, mut seen): Done = (Vec::new(), Vec::new());
    let mut journal = Journal::start(attrs);
    loop {
        let step = next(map, &done).and_then(|op| match op {
            Some(op) => {
                let vs = involved(map, op);
                let (r, j) = op.apply(&mut (&mut *map, &mut *attrs))?.into_parts();
                journal.absorb(j);
                seen.extend(vs.into_iter().flatten());
                if let TriRecord::SplitVertex(s) = r {
                    seen.push(s.created());
                }
                done.push(r);
                Ok(true)
            }
            None => Ok(false),
        });
        match step {
            Ok(true) => {}
            Ok(false) => return Ok(((done, seen), journal)),
            Err(e) => {
                // Fresh records of this map: their undo does not refuse.
                for r in done.iter().rev() {
                    let _ = r.undo(map);
                }
                journal.rewind(attrs);
                return Err(e);
            }
        }
    }
}

/// A split of `x` along two darts to distinct regular vertices with `s` darts strictly
/// inside the kept arc, that the split operator accepts.
fn find_split(map: &Map, x: Vert, s: usize) -> Option<TriOp> {
    map.vertex_darts(x).find_map(|d1| {
        let d2 = turn(map, d1, s + 1);
        let (a, b) = (map.dest(d1), map.dest(d2));
        let ok = a != b
            && regular(map, a).is_ok()
            && regular(map, b).is_ok()
            && can_split_vertex(map, d1, d2).is_ok();
        ok.then_some(TriOp::SplitVertex(d1, d2))
    })
}

/// The next step of a vk split: `None` once the vertex being split has at most 7.
fn next_high_split(map: &Map, v: Vert, done: &[TriRecord]) -> Result<Option<TriOp>, TriEditError> {
    // The vertex still to split: v, then the new vertex of the last split.
    let x = match done.last() {
        Some(TriRecord::SplitVertex(s)) => s.created(),
        _ => v,
    };
    let k = map.valence(x);
    let finished = done.last().is_some() && k <= 7;
    if finished {
        return Ok(None);
    }
    let s = if k == 8 { 3 } else { 4 };
    find_split(map, x, s)
        .map(Some)
        .ok_or(TriEditError::Irregular)
}

/// A collapse of the v3 or v4 `v` into a neighbour, every vertex that changes valence
/// regular before.
fn low_collapse(map: &Map, v: Vert) -> Result<TriOp, TriEditError> {
    let op = map.vertex_darts(v).find_map(|d| {
        let apexes = [super::apex(map, d)?, super::apex(map, d.twin())?];
        let ok = regular(map, map.dest(d)).is_ok()
            && apexes.iter().all(|&c| regular(map, c).is_ok())
            && TriOp::Collapse(d).can(map).is_ok();
        ok.then_some(TriOp::Collapse(d))
    });
    op.ok_or(TriEditError::Irregular)
}

/// Checks whether [`split_type`] applies. A vk split runs on a copy of the map (O(map) time
/// and memory); a v3 or v4 split is a pure check.
///
/// See [`split_type`] for an example.
pub fn can_split_type(map: &Map, v: Vert) -> Result<(), TriEditError> {
    if !map.is_live_vertex(v) {
        return Err(TriEditError::DeadHandle);
    }
    match map.valence(v) {
        3 | 4 if interior_of_valence(map, v, map.valence(v)) => low_collapse(map, v).map(|_| ()),
        k if k > 7 && interior_of_valence(map, v, k) => split_type(&mut map.clone(), v).map(|_| ()),
        _ => Err(TriEditError::WrongValence),
    }
}

/// Splits the type of the interior vertex `v`: a vk (k > 7) into k - 6 v7, a v4 into two
/// v5, a v3 into three v5 (the sequences in the module documentation), or refuses with the
/// map unchanged: [`TriEditError::WrongValence`] for another valence or a boundary vertex,
/// [`TriEditError::Irregular`] when no step with regular neighbours applies.
/// [`TypeEdit::vertices`] lists the irregular vertices left; every other vertex keeps its
/// valence.
///
/// ```
/// use zipmesh::gen::subdivided_bipyramid;
/// use zipmesh::tri_edit::split_type;
/// use zipmesh::Vert;
/// let mut map = subdivided_bipyramid(10, 2);
/// let before = map.clone();
/// let s = split_type(&mut map, Vert::new(0)).unwrap(); // a v10 into four v7
/// assert_eq!(s.vertices().iter().map(|&v| map.valence(v)).collect::<Vec<_>>(), [7; 4]);
/// s.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// assert!(split_type(&mut map, Vert::new(20)).is_err()); // a regular vertex
/// assert_eq!(map, before);
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
///
/// ```
/// use zipmesh::gen::subdivided_bipyramid;
/// use zipmesh::tri_edit::split_type;
/// use zipmesh::Vert;
/// let mut map = subdivided_bipyramid(9, 2);
/// let mut marks = vec![0.5f64; map.vertex_slots()];
/// let before = (map.clone(), marks.clone());
/// let e = split_type(&mut (&mut map, &mut marks), Vert::new(0)).unwrap(); // a v9 into three v7
/// assert_eq!(e.record().vertices().len(), 3);
/// assert_eq!(marks.len(), map.vertex_slots());
/// e.undo(&mut (&mut map, &mut marks)).unwrap();
/// assert_eq!((map, marks), before);
/// ```
pub fn split_type<T: EditTarget>(
    target: &mut T,
    v: Vert,
) -> Result<Edited<TypeEdit, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    if !map.is_live_vertex(v) {
        return Err(TriEditError::DeadHandle);
    }
    let k = map.valence(v);
    if !interior_of_valence(map, v, k) || !(k == 3 || k == 4 || k > 7) {
        return Err(TriEditError::WrongValence);
    }
    let ((steps, seen), journal) = if k <= 4 {
        let op = low_collapse(map, v)?;
        let mut once = Some(op);
        run_with(map, attrs, |_, _| Ok(once.take()))?
    } else {
        run_with(map, attrs, |m, done| next_high_split(m, v, done))?
    };
    let vertices = irregular_among(map, seen);
    let edit = TypeEdit {
        vertices,
        steps,
        split: true,
    };
    Ok(Edited::new(edit, journal))
}

/// The live irregular vertices among `seen`, sorted, once each.
pub(super) fn irregular_among(map: &Map, mut seen: Vec<Vert>) -> Vec<Vert> {
    seen.retain(|&v| map.is_live_vertex(v) && map.valence(v) != 6);
    seen.sort();
    seen.dedup();
    seen
}

/// Aggregates two v5 into a v4, three v5 into a v3, or m v7 (2 to 64) into one v(6 + m)
/// (see the module documentation), or refuses with the map unchanged
/// ([`TriEditError::NotAPair`] when the vertices are not two v5 with a regular common
/// neighbour one dart apart, three v5 around a triangle, or v7 that collapses can gather,
/// each with two of the v7 as apexes, found within 4,096 collapses tried).
/// [`TypeEdit::vertices`] is the new vertex.
///
/// ```
/// use zipmesh::gen::subdivided_bipyramid;
/// use zipmesh::tri_edit::{aggregate_type, split_type};
/// use zipmesh::{is_isomorphic, Vert};
/// let mut map = subdivided_bipyramid(8, 2);
/// let before = map.clone();
/// let s = split_type(&mut map, Vert::new(2)).unwrap(); // a v4 into two v5
/// let a = aggregate_type(&mut map, s.vertices()).unwrap(); // and back
/// assert_eq!(map.valence(a.vertices()[0]), 4);
/// assert!(is_isomorphic(&map, &before));
/// // A v11 into five v7 and back: the five gathered by collapses.
/// let mut map = subdivided_bipyramid(11, 2);
/// let before = map.clone();
/// let s = split_type(&mut map, Vert::new(0)).unwrap();
/// let a = aggregate_type(&mut map, s.vertices()).unwrap();
/// assert_eq!(map.valence(a.vertices()[0]), 11);
/// assert!(is_isomorphic(&map, &before));
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
///
/// ```
/// use zipmesh::gen::subdivided_bipyramid;
/// use zipmesh::tri_edit::{aggregate_type, split_type};
/// use zipmesh::Vert;
/// let mut map = subdivided_bipyramid(8, 2);
/// let s = split_type(&mut map, Vert::new(2)).unwrap(); // a v4 into two v5
/// let mut marks = vec![1.0f64; map.vertex_slots()];
/// let before = (map.clone(), marks.clone());
/// let a = aggregate_type(&mut (&mut map, &mut marks), s.vertices()).unwrap();
/// assert_eq!(map.valence(a.record().vertices()[0]), 4);
/// a.undo(&mut (&mut map, &mut marks)).unwrap();
/// assert_eq!((map, marks), before);
/// ```
pub fn aggregate_type<T: EditTarget>(
    target: &mut T,
    vs: &[Vert],
) -> Result<Edited<TypeEdit, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    let (ops, gathered) = aggregation_plan(map, vs)?;
    let mut ops = ops.into_iter();
    let ((steps, _), journal) = run_with(map, attrs, |_, _| Ok(ops.next()))?;
    let vertices = match (gathered, steps.first()) {
        (Some(g), _) => alloc::vec![g],
        (None, Some(TriRecord::SplitVertex(s))) => alloc::vec![s.created()],
        _ => Vec::new(),
    };
    let edit = TypeEdit {
        vertices,
        steps,
        split: false,
    };
    Ok(Edited::new(edit, journal))
}

/// Checks whether [`aggregate_type`] applies, without changing anything. Gathering v7
/// searches on a copy of the map (O(map) time and memory); the v5 cases are a pure check.
///
/// See [`aggregate_type`] for an example.
pub fn can_aggregate_type(map: &Map, vs: &[Vert]) -> Result<(), TriEditError> {
    aggregation_plan(map, vs).map(|_| ())
}

/// The operations of an aggregation, and the vertex that gathers the v7 (`None` for v5,
/// where the new vertex is the split's).
fn aggregation_plan(map: &Map, vs: &[Vert]) -> Result<(Vec<TriOp>, Option<Vert>), TriEditError> {
    if !vs.iter().all(|&v| map.is_live_vertex(v)) {
        return Err(TriEditError::DeadHandle);
    }
    if vs.len() >= 2 && vs.iter().all(|&v| interior_of_valence(map, v, 7)) {
        return super::gather::gather_v7(map, vs).map(|(ops, g)| (ops, Some(g)));
    }
    aggregation_op(map, vs).map(|op| (alloc::vec![op], None))
}

fn aggregation_op(map: &Map, v5s: &[Vert]) -> Result<TriOp, TriEditError> {
    if !v5s.iter().all(|&v| interior_of_valence(map, v, 5)) {
        return Err(TriEditError::NotAPair);
    }
    let found = match *v5s {
        // A regular a with b, c four darts apart clockwise (one dart on the other side).
        [b, c] if b != c => map.vertex_darts(b).find_map(|ba| {
            let a = map.dest(ba);
            regular(map, a).ok()?;
            let d1 = map.vertex_darts(a).find(|&d| map.dest(d) == b)?;
            [(d1, turn(map, d1, 4)), (turn(map, d1, 2), d1)]
                .into_iter()
                .find(|&(x, y)| {
                    [map.dest(x), map.dest(y)] == [b, c] || [map.dest(x), map.dest(y)] == [c, b]
                })
                .filter(|&(x, y)| can_split_vertex(map, x, y).is_ok())
                .map(|(x, y)| TriOp::SplitVertex(x, y))
        }),
        // Split one of them with the other two consecutive: the moved arc is empty.
        [a, b, c] if a != b && b != c && a != c => [(a, b, c), (b, c, a), (c, a, b)]
            .into_iter()
            .find_map(|(x, y, z)| {
                map.vertex_darts(x).find_map(|d2| {
                    let d1 = map.rotate_cw(d2);
                    let ends = [map.dest(d2), map.dest(d1)];
                    let ok =
                        (ends == [y, z] || ends == [z, y]) && can_split_vertex(map, d1, d2).is_ok();
                    ok.then_some(TriOp::SplitVertex(d1, d2))
                })
            }),
        _ => None,
    };
    found.ok_or(TriEditError::NotAPair)
}

/// Record of a [`split_type`] or an [`aggregate_type`]: the irregular vertices left and the
/// graph operators' records, undone in reverse.
///
/// See [`split_type`] for an example.
#[derive(Clone, Debug)]
pub struct TypeEdit {
    vertices: Vec<Vert>,
    steps: Vec<TriRecord>,
    split: bool,
}

impl TypeEdit {
    /// The irregular vertices the edit leaves among those it touched: the k - 6 v7 or the
    /// v5 of a split, the new v4 or v3 of an aggregation.
    ///
    /// See [`split_type`] for an example.
    pub fn vertices(&self) -> &[Vert] {
        &self.vertices
    }

    /// The graph operators' records, in the order applied.
    ///
    /// See [`split_type`] for an example.
    pub fn steps(&self) -> &[TriRecord] {
        &self.steps
    }

    /// Whether the edit was a [`split_type`] (else an [`aggregate_type`]).
    ///
    /// See [`split_type`] for an example.
    pub fn is_split(&self) -> bool {
        self.split
    }

    /// Undoes every step in reverse (`==`). If a step's undo refuses (a stale record), the
    /// steps already undone are not redone: the map is then the one before that step.
    ///
    /// See [`split_type`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        for r in self.steps.iter().rev() {
            r.undo(map)?;
        }
        Ok(())
    }
}

impl Undo for TypeEdit {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        TypeEdit::undo(self, map)
    }
}
