//! Per-vertex data that follows vertex slots through edits: positions, and whatever else a
//! caller keeps per vertex (feature marks, protection marks, relaxation targets).
//!
//! An edit never reads these values to decide anything; it only tells the layer which
//! vertices were created or moved and from which old vertices their values come, as weights
//! (a [`Rule`]). The layer takes their mean ([`Blend`]), and the edit's journal
//! keeps every value it overwrote so that undo restores the data exactly
//! ([`Edited`](super::Edited)).

use super::Rule;
use crate::map::{Map, Vert};
use alloc::vec::Vec;
use glam::DVec3;

/// A per-vertex value that a new or moved vertex can take from old vertices: the mean of
/// some values. Every placement [`Rule`] is built from means, so a layer only says what
/// a mean of its values is.
///
/// ```
/// use glam::DVec3;
/// use zipmesh_kernel::mesh::Blend;
/// assert_eq!(DVec3::mean(&[DVec3::ZERO, DVec3::X]), Some(DVec3::new(0.5, 0.0, 0.0)));
/// assert_eq!(bool::mean(&[false, true]), Some(true));
/// assert_eq!(f64::mean(&[]), None);
/// ```
pub trait Blend: Clone + core::fmt::Debug + PartialEq {
    /// The mean of `values`, or `None` when there are none (the vertex keeps its value).
    fn mean(values: &[Self]) -> Option<Self>;
}

impl Blend for DVec3 {
    /// The centroid, summed in the order given.
    fn mean(values: &[Self]) -> Option<Self> {
        let (first, rest) = values.split_first()?;
        Some(rest.iter().fold(*first, |s, &p| s + p) / values.len() as f64)
    }
}

impl Blend for f64 {
    /// The arithmetic mean, summed in the order given.
    fn mean(values: &[Self]) -> Option<Self> {
        let (first, rest) = values.split_first()?;
        Some(rest.iter().fold(*first, |s, &x| s + x) / values.len() as f64)
    }
}

impl Blend for bool {
    /// A mark is kept when any value has it: a vertex made from a marked vertex stays
    /// marked.
    fn mean(values: &[Self]) -> Option<Self> {
        (!values.is_empty()).then(|| values.contains(&true))
    }
}

/// Per-vertex data indexed by vertex slot, kept in step with the map by edits.
///
/// Implemented for `Vec<T>` (one value per slot, the slot's index; a [`crate::Mesh`]'s
/// positions are one) and for pairs of layers, so several layers travel together through
/// one edit: `(positions, marks)`.
///
/// ```
/// use zipmesh_kernel::{mesh::{Rule, VertexAttributes}, Vert};
/// let mut marks = vec![false, true];
/// assert_eq!(marks.value(Vert::new(1)), Some(true));
/// marks.set_value(Vert::new(3), true); // grows with the default value
/// assert_eq!(marks, vec![false, true, false, true]);
/// let map = zipmesh_kernel::gen::grid(1, 1).map;
/// let placed = marks.place(&map, Rule::Midpoint(Vert::new(0), Vert::new(1)));
/// assert_eq!(placed, Some(true));
/// ```
pub trait VertexAttributes {
    /// What one vertex holds.
    type Value: Clone + core::fmt::Debug + PartialEq;
    /// How far the layer reaches (for a `Vec`, its length): an edit records it before and
    /// its undo cuts the layer back to it.
    type Extent: Copy + core::fmt::Debug + PartialEq;

    /// The layer's extent now.
    fn extent(&self) -> Self::Extent;
    /// Cuts the layer back to `extent` (never grows it).
    fn shrink_to(&mut self, extent: Self::Extent);
    /// Grows the layer with default values so that it covers `slots` vertex slots.
    fn cover(&mut self, slots: usize);
    /// The value of `v`, or `None` when the layer does not reach `v`.
    fn value(&self, v: Vert) -> Option<Self::Value>;
    /// Sets the value of `v`, growing the layer with default values to reach it.
    fn set_value(&mut self, v: Vert, value: Self::Value);
    /// The value `rule` gives, read on `map` after the edit, or `None` to leave the vertex
    /// as it is. Vertices the layer does not reach count as the default value.
    fn place(&self, map: &Map, rule: Rule) -> Option<Self::Value>;
}

impl<T: Blend + Default> VertexAttributes for Vec<T> {
    type Value = T;
    type Extent = usize;

    fn extent(&self) -> usize {
        self.len()
    }

    fn shrink_to(&mut self, extent: usize) {
        self.truncate(extent);
    }

    fn cover(&mut self, slots: usize) {
        if self.len() < slots {
            self.resize(slots, T::default());
        }
    }

    fn value(&self, v: Vert) -> Option<T> {
        self.get(v.index()).cloned()
    }

    fn set_value(&mut self, v: Vert, value: T) {
        self.cover(v.index() + 1);
        if let Some(x) = self.get_mut(v.index()) {
            *x = value;
        }
    }

    fn place(&self, map: &Map, rule: Rule) -> Option<T> {
        rule.evaluate(map, |v| self.value(v).unwrap_or_default())
    }
}

/// Two layers edited together. A side that does not reach a vertex reads as `None` there,
/// and setting `None` leaves that side alone, so each side is restored exactly.
///
/// ```
/// use glam::DVec3;
/// use zipmesh_kernel::{mesh::VertexAttributes, Vert};
/// let mut both = (vec![DVec3::ZERO, DVec3::X], vec![true]);
/// assert_eq!(both.value(Vert::new(1)), Some((Some(DVec3::X), None)));
/// both.shrink_to((1, 0));
/// assert_eq!(both, (vec![DVec3::ZERO], vec![]));
/// ```
impl<A: VertexAttributes, B: VertexAttributes> VertexAttributes for (A, B) {
    type Value = (Option<A::Value>, Option<B::Value>);
    type Extent = (A::Extent, B::Extent);

    fn extent(&self) -> Self::Extent {
        (self.0.extent(), self.1.extent())
    }

    fn shrink_to(&mut self, extent: Self::Extent) {
        self.0.shrink_to(extent.0);
        self.1.shrink_to(extent.1);
    }

    fn cover(&mut self, slots: usize) {
        self.0.cover(slots);
        self.1.cover(slots);
    }

    fn value(&self, v: Vert) -> Option<Self::Value> {
        let pair = (self.0.value(v), self.1.value(v));
        (pair.0.is_some() || pair.1.is_some()).then_some(pair)
    }

    fn set_value(&mut self, v: Vert, value: Self::Value) {
        if let Some(a) = value.0 {
            self.0.set_value(v, a);
        }
        if let Some(b) = value.1 {
            self.1.set_value(v, b);
        }
    }

    fn place(&self, map: &Map, rule: Rule) -> Option<Self::Value> {
        let pair = (self.0.place(map, rule), self.1.place(map, rule));
        (pair.0.is_some() || pair.1.is_some()).then_some(pair)
    }
}

/// No per-vertex values: the policy of an edit on a bare [`Map`] (see
/// [`super::EditTarget`]). Nothing is saved or placed.
///
/// ```
/// use zipmesh_kernel::{mesh::VertexAttributes, Vert};
/// let mut none = ();
/// none.set_value(Vert::new(3), ());
/// assert_eq!(none.value(Vert::new(3)), None);
/// ```
impl VertexAttributes for () {
    type Value = ();
    type Extent = ();
    fn extent(&self) {}
    fn shrink_to(&mut self, _: ()) {}
    fn cover(&mut self, _: usize) {}
    fn value(&self, _: Vert) -> Option<()> {
        None
    }
    fn set_value(&mut self, _: Vert, _: ()) {}
    fn place(&self, _: &Map, _: Rule) -> Option<()> {
        None
    }
}

/// Positions are the layer every [`crate::Mesh`] has.
pub type Positions = Vec<DVec3>;
