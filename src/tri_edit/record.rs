//! What the one-operation semantic edits share: the dart and apex helpers, the map-only
//! data layer, the run of a planned graph operation (written once, with or without
//! per-vertex data) and the record of a lone vertex's movement.

use super::{apex, TriEditError};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{Edited, Rule, VertexAttributes};
use crate::ops::tri::{TriOp, TriRecord};
use crate::ops::Refusal;

/// `d` turned clockwise `k` times around its origin.
pub(super) fn turn(map: &Map, d: Dart, k: usize) -> Dart {
    (0..k).fold(d, |x, _| map.rotate_cw(x))
}

/// The apex of `d`'s triangle, or a refusal when the face is not a triangle.
pub(super) fn tri_apex(map: &Map, d: Dart) -> Result<Vert, TriEditError> {
    apex(map, d).ok_or(TriEditError::Refused(Refusal::WrongDegree))
}

/// The vertex a split created (`None` for the other operators).
pub(super) fn created(record: &TriRecord) -> Option<Vert> {
    match record {
        TriRecord::SplitVertex(s) => Some(s.created()),
        _ => None,
    }
}

/// No per-vertex data: the map-only edits run through their `*_with` variant with it, so
/// each edit's effect is written once.
pub(super) struct NoData;

impl VertexAttributes for NoData {
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

/// Applies a planned graph operation on the map and its data and builds the edit's record
/// from the operator's (the one place a one-operation edit is applied).
pub(super) fn apply_one<A: VertexAttributes, R>(
    map: &mut Map,
    attrs: &mut A,
    op: TriOp,
    build: impl FnOnce(TriOp, TriRecord) -> R,
) -> Result<Edited<R, A>, TriEditError> {
    let edit = op.apply_with(map, attrs)?;
    Ok(edit.map_record(|r| build(op, r)))
}

/// The map-only edit of a `*_with` variant: the record without the (empty) journal.
pub(super) fn map_only<R>(
    edit: impl FnOnce(&mut NoData) -> Result<Edited<R, NoData>, TriEditError>,
) -> Result<R, TriEditError> {
    edit(&mut NoData).map(|e| e.into_parts().0)
}

/// The accessors and the undo of a record made of one graph operation (fields `op` and
/// `record`), written once for every such record; `$example` names where the example is.
macro_rules! one_operation {
    ($record:ty, $example:literal) => {
        impl $record {
            /// The graph operation applied.
            ///
            #[doc = concat!("See ", $example, " for an example.")]
            pub fn op(&self) -> crate::ops::tri::TriOp {
                self.op
            }

            /// The graph operator's record.
            ///
            #[doc = concat!("See ", $example, " for an example.")]
            pub fn record(&self) -> &crate::ops::tri::TriRecord {
                &self.record
            }

            /// Restores the map as it was before the edit (`==`), or refuses with
            /// [`crate::ops::Refusal::StaleRecord`] and the map unchanged.
            ///
            #[doc = concat!("See ", $example, " for an example.")]
            pub fn undo(&self, map: &mut crate::Map) -> Result<(), crate::ops::Refusal> {
                self.record.undo(map)
            }
        }

        impl crate::ops::Undo for $record {
            fn undo(&self, map: &mut crate::Map) -> Result<(), crate::ops::Refusal> {
                <$record>::undo(self, map)
            }
        }
    };
}
pub(super) use one_operation;

/// Record of a lone irregular vertex's movement with 5-7 generation or removal: the v5 of
/// [`super::generate_pair`] / [`super::remove_pair`] ([`super::V5Move`]) or the v7 of
/// [`super::generate_pair_v7`] / [`super::remove_pair_v7`] ([`super::V7Move`]).
///
/// See [`super::generate_pair`] for an example.
#[derive(Clone, Copy, Debug)]
pub struct VertexMove {
    pub(super) moved: Vert,
    pub(super) pair: Option<(Vert, Vert)>,
    pub(super) op: TriOp,
    pub(super) record: TriRecord,
}

impl VertexMove {
    /// Where the moved vertex is now.
    ///
    /// See [`super::generate_pair`] for an example.
    pub fn moved(&self) -> Vert {
        self.moved
    }

    /// The generated pair (v5, v7); `None` after a removal.
    ///
    /// See [`super::generate_pair`] for an example.
    pub fn pair(&self) -> Option<(Vert, Vert)> {
        self.pair
    }
}

one_operation!(VertexMove, "[`super::generate_pair`]");
