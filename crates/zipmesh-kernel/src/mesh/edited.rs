//! One wrapper for every edit on a map with per-vertex data: the edit's own record (an
//! operator's, a Q-zip's, a preprocessing's) and the values it overwrote.
//!
//! The edit runs on the map first; then each vertex it created or moved is placed by a
//! [`Rule`] through a [`Journal`], which saves the value it overwrites the first time. Undo
//! runs the record's undo on the map, puts the saved values back in reverse order and cuts
//! the layer back to its old extent, so map and data both come back `==`.

use super::attributes::{Blend, Positions, VertexAttributes};
use super::EditTarget;
use crate::edit::{Refusal, Undo};
use crate::map::{Map, Vert};
use alloc::vec::Vec;
use hashbrown::HashSet;

/// Where a created or moved vertex takes its data from, read on the map after the edit.
/// Each editing wrapper states its rule once, as one of these.
///
/// ```
/// use glam::DVec3;
/// use zipmesh_kernel::{gen, mesh::Rule, Vert};
/// let mesh = gen::grid(2, 2);
/// let at = |v: Vert| mesh.positions[v.index()];
/// let mid = Rule::Midpoint(Vert::new(0), Vert::new(1)).evaluate(&mesh.map, at);
/// assert_eq!(mid, Some(DVec3::new(0.5, 0.0, 0.0)));
/// // The centre of a 2 x 2 grid is the mean of its four neighbours.
/// let centre = Rule::NeighbourMean(Vert::new(4)).evaluate(&mesh.map, at);
/// assert_eq!(centre, Some(at(Vert::new(4))));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Rule {
    /// The mean of two vertices.
    Midpoint(Vert, Vert),
    /// The mean of the vertex's neighbours; none leaves the value as it is.
    NeighbourMean(Vert),
    /// The mean of `from` and the mean of the neighbours of `of` (leaving `from` out of
    /// those when `skip_from`); `from` itself when there are none.
    TowardNeighbours {
        /// The vertex the new one came from.
        from: Vert,
        /// The vertex whose neighbours pull it.
        of: Vert,
        /// Leave `from` out of the neighbours' mean.
        skip_from: bool,
    },
}

impl Rule {
    /// The rule's value, with `value` the data of each vertex (read on `map`).
    ///
    /// See [`Rule`] for an example.
    pub fn evaluate<T: Blend>(&self, map: &Map, value: impl Fn(Vert) -> T) -> Option<T> {
        match *self {
            Rule::Midpoint(a, b) => T::mean(&[value(a), value(b)]),
            Rule::NeighbourMean(v) => T::mean(&neighbours(map, v, None, &value)),
            Rule::TowardNeighbours {
                from,
                of,
                skip_from,
            } => {
                let own = value(from);
                let pull = T::mean(&neighbours(map, of, skip_from.then_some(from), &value));
                T::mean(&[own.clone(), pull.unwrap_or(own)])
            }
        }
    }
}

/// The values of the neighbours of `v` other than `skip`, in rotation order.
fn neighbours<T>(map: &Map, v: Vert, skip: Option<Vert>, value: impl Fn(Vert) -> T) -> Vec<T> {
    map.vertex_darts(v)
        .map(|d| map.dest(d))
        .filter(|&n| Some(n) != skip)
        .map(value)
        .collect()
}

/// The values an edit overwrote, collected while it places vertices.
///
/// ```
/// use glam::DVec3;
/// use zipmesh_kernel::{gen, mesh::{Journal, Rule}, Vert};
/// let mut mesh = gen::grid(1, 1);
/// let before = mesh.positions.clone();
/// let mut journal = Journal::start(&mesh.positions);
/// journal.place(&mesh.map, &mut mesh.positions, Vert::new(0), Rule::Midpoint(Vert::new(1), Vert::new(2)));
/// assert_eq!(mesh.positions[0], (before[1] + before[2]) / 2.0);
/// journal.rewind(&mut mesh.positions);
/// assert_eq!(mesh.positions, before);
/// ```
#[derive(Clone, Debug)]
pub struct Journal<A: VertexAttributes> {
    /// Old values, in the order first overwritten.
    saved: Vec<(Vert, A::Value)>,
    /// The vertices of `saved`, filled once `saved` outgrows a short scan, so that an edit
    /// overwriting many reused slots stays linear.
    seen: HashSet<Vert>,
    /// The layer's extent before the edit.
    extent: A::Extent,
}

/// Journals are equal when they saved the same values and extent (`seen` is an index).
impl<A: VertexAttributes> PartialEq for Journal<A>
where
    A::Value: PartialEq,
    A::Extent: PartialEq,
{
    fn eq(&self, other: &Self) -> bool {
        self.saved == other.saved && self.extent == other.extent
    }
}

/// Up to this many saved values a linear scan finds repeats; beyond it, the `seen` index.
const SCAN: usize = 16;

impl<A: VertexAttributes> Journal<A> {
    /// Starts a journal on the layer as it is before the edit.
    ///
    /// See [`Journal`] for an example.
    pub fn start(attrs: &A) -> Self {
        Journal {
            saved: Vec::new(),
            seen: HashSet::new(),
            extent: attrs.extent(),
        }
    }

    /// Places `v` by `rule` (read on `map` after the edit), saving its old value the first
    /// time the journal writes it.
    ///
    /// See [`Journal`] for an example.
    pub fn place(&mut self, map: &Map, attrs: &mut A, v: Vert, rule: Rule) {
        if let Some(value) = attrs.place(map, rule) {
            self.set(attrs, v, value);
        }
    }

    /// Sets `v` to `value`, saving its old value the first time.
    ///
    /// ```
    /// use zipmesh_kernel::{mesh::Journal, Vert};
    /// let mut marks = vec![false, false];
    /// let mut j = Journal::start(&marks);
    /// j.set(&mut marks, Vert::new(1), true);
    /// j.set(&mut marks, Vert::new(3), true);
    /// j.rewind(&mut marks);
    /// assert_eq!(marks, vec![false, false]);
    /// ```
    pub fn set(&mut self, attrs: &mut A, v: Vert, value: A::Value) {
        // Only slots the layer already reached are saved, so the scan runs over the (few)
        // overwritten vertices, never over the new ones an edit appends.
        if let Some(old) = attrs.value(v) {
            if !self.saved_before(v) {
                self.saved.push((v, old));
            }
        }
        attrs.set_value(v, value);
    }

    /// Whether `v`'s old value is saved already; past [`SCAN`] values, records `v` as saved.
    fn saved_before(&mut self, v: Vert) -> bool {
        if self.saved.len() < SCAN {
            return self.saved.iter().any(|&(s, _)| s == v);
        }
        if self.seen.is_empty() {
            self.seen.extend(self.saved.iter().map(|&(s, _)| s));
        }
        !self.seen.insert(v)
    }

    /// Puts the saved values back, newest first, and cuts the layer back to its extent
    /// before the edit.
    ///
    /// See [`Journal`] for an example.
    pub fn rewind(&self, attrs: &mut A) {
        for (v, old) in self.saved.iter().rev() {
            attrs.set_value(*v, old.clone());
        }
        attrs.shrink_to(self.extent);
    }

    /// Takes over the saves of a later journal on the same layer, so that an edit of
    /// several steps keeps one journal: a vertex saved already keeps its older value, and
    /// the extent stays this journal's (the layer's before the first step).
    ///
    /// ```
    /// use zipmesh_kernel::{mesh::Journal, Vert};
    /// let mut marks = vec![false, false];
    /// let mut first = Journal::start(&marks);
    /// first.set(&mut marks, Vert::new(0), true);
    /// let mut second = Journal::start(&marks);
    /// second.set(&mut marks, Vert::new(0), false);
    /// second.set(&mut marks, Vert::new(1), true);
    /// first.absorb(second);
    /// first.rewind(&mut marks);
    /// assert_eq!(marks, vec![false, false]);
    /// ```
    pub fn absorb(&mut self, later: Journal<A>) {
        for (v, old) in later.saved {
            if !self.saved.iter().any(|&(s, _)| s == v) {
                self.saved.push((v, old));
            }
        }
    }

    /// The number of values saved (vertices that existed and were overwritten).
    ///
    /// See [`Journal`] for an example.
    pub fn overwritten(&self) -> usize {
        self.saved.len()
    }
}

/// An edit applied to a map with per-vertex data `A` (by default a [`crate::Mesh`]'s positions):
/// the edit's record `R` and the journal of values it overwrote. The one wrapper of every
/// position-keeping edit: quad and triangle operators, Q-zip, preprocessing.
///
/// ```
/// use zipmesh_kernel::{gen, mesh::{Edited, Journal, Rule}, ops::quad, Dart};
/// let mut mesh = gen::torus_grid(4, 4);
/// let before = mesh.clone();
/// let mut journal = Journal::start(&mesh.positions);
/// let record = quad::collapse_quad(&mut mesh.map, Dart::new(0)).unwrap();
/// let rule = Rule::Midpoint(record.kept(), record.removed());
/// journal.place(&mesh.map, &mut mesh.positions, record.kept(), rule);
/// let edit = Edited::new(record, journal);
/// edit.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Edited<R, A: VertexAttributes = Positions> {
    record: R,
    journal: Journal<A>,
}

impl<R, A: VertexAttributes> Edited<R, A> {
    /// Runs an edit on `map` and places the one vertex `place` names for its record (read
    /// on the map after the edit), if any: the path every operator wrapper takes. On a
    /// refusal nothing changes.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, mesh::{Edited, Rule}, ops::quad, Dart};
    /// let mut mesh = gen::torus_grid(4, 4);
    /// let before = mesh.clone();
    /// let edit = Edited::run(&mut mesh.map, &mut mesh.positions,
    ///     |m| quad::collapse_quad(m, Dart::new(0)),
    ///     |_, r| Some((r.kept(), Rule::Midpoint(r.kept(), r.removed())))).unwrap();
    /// edit.undo(&mut mesh).unwrap();
    /// assert_eq!(mesh, before);
    /// ```
    pub fn run<E>(
        map: &mut Map,
        attrs: &mut A,
        edit: impl FnOnce(&mut Map) -> Result<R, E>,
        place: impl FnOnce(&Map, &R) -> Option<(Vert, Rule)>,
    ) -> Result<Self, E> {
        let mut journal = Journal::start(attrs);
        let record = edit(map)?;
        if let Some((v, rule)) = place(map, &record) {
            journal.place(map, attrs, v, rule);
        }
        Ok(Edited::new(record, journal))
    }

    /// The same edit with its record converted (an operator's record into its family's).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, mesh::{Edited, Rule}, ops::quad::{self, QuadRecord}, Dart};
    /// let mut mesh = gen::torus_grid(4, 4);
    /// let e = Edited::run(&mut mesh.map, &mut mesh.positions,
    ///     |m| quad::collapse_quad(m, Dart::new(0)),
    ///     |_, r| Some((r.kept(), Rule::Midpoint(r.kept(), r.removed())))).unwrap();
    /// let e = e.map_record(QuadRecord::from);
    /// assert!(matches!(e.record(), QuadRecord::Collapse(_)));
    /// ```
    pub fn map_record<S>(self, f: impl FnOnce(R) -> S) -> Edited<S, A> {
        Edited {
            record: f(self.record),
            journal: self.journal,
        }
    }

    /// Pairs a record with the journal of the placements made after it.
    ///
    /// See [`Edited`] for an example.
    pub fn new(record: R, journal: Journal<A>) -> Self {
        Edited { record, journal }
    }

    /// The edit's own record (for a Q-zip, its report).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::{QuadOp, QuadRecord}, Dart};
    /// let mut mesh = gen::torus_grid(4, 4);
    /// let e = QuadOp::Collapse(Dart::new(0)).apply(&mut mesh).unwrap();
    /// assert!(matches!(e.record(), QuadRecord::Collapse(_)));
    /// ```
    pub fn record(&self) -> &R {
        &self.record
    }

    /// The journal of overwritten values.
    ///
    /// See [`Journal`] for an example.
    pub fn journal(&self) -> &Journal<A> {
        &self.journal
    }

    /// The edit's record, its journal dropped (an edit on a bare map keeps no values).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::{QuadOp, QuadRecord}, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let r: QuadRecord = QuadOp::Collapse(Dart::new(0)).apply(&mut map).unwrap().into_record();
    /// r.undo(&mut map).unwrap();
    /// assert_eq!(map, gen::torus_grid(4, 4).map);
    /// ```
    pub fn into_record(self) -> R {
        self.record
    }

    /// Splits the edit into its record and journal.
    ///
    /// See [`Edited`] for an example.
    pub fn into_parts(self) -> (R, Journal<A>) {
        (self.record, self.journal)
    }
}

impl<R: Undo, A: VertexAttributes> Edited<R, A> {
    /// Undoes the edit on the target it was made on (a map, a [`crate::Mesh`], or a map with its
    /// values, see [`EditTarget`]): the record's undo, then the journal, so map and values
    /// come back `==`. On a refusal (a stale record) neither changes.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, mesh::{Edited, Journal, Rule}, ops::quad, Dart};
    /// let mut mesh = gen::torus_grid(4, 4);
    /// let mut marks = vec![false; mesh.map.vertex_slots()];
    /// let before = (mesh.map.clone(), marks.clone());
    /// let mut journal = Journal::start(&marks);
    /// let record = quad::insert_doublet(&mut mesh.map, Dart::new(0)).unwrap();
    /// journal.set(&mut marks, record.vertex(), true);
    /// Edited::new(record, journal).undo(&mut (&mut mesh.map, &mut marks)).unwrap();
    /// assert_eq!((mesh.map, marks), before);
    /// ```
    pub fn undo<T: EditTarget<Values = A>>(&self, target: &mut T) -> Result<(), Refusal> {
        let (map, values) = target.parts();
        self.record.undo(map)?;
        self.journal.rewind(values);
        Ok(())
    }
}

/// An edit on a bare map undoes as its record does (undo stacks of [`Undo`] records).
impl<R: Undo> Undo for Edited<R, ()> {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.record.undo(map)
    }
}

/// An edit reads as its record (`e.removed()` for `e.record().removed()`).
impl<R, A: VertexAttributes> core::ops::Deref for Edited<R, A> {
    type Target = R;
    fn deref(&self) -> &R {
        &self.record
    }
}
