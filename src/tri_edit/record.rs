//! What the one-operation semantic edits share: the dart and apex helpers, the run of a
//! planned graph operation (written once for every kind of per-vertex data) and the record
//! of a lone vertex's movement.

use super::{apex, TriEditError};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{Edited, VertexAttributes};
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

/// Applies a planned graph operation on the map and its data and builds the edit's record
/// from the operator's (the one place a one-operation edit is applied).
pub(super) fn apply_one<A: VertexAttributes, R>(
    map: &mut Map,
    attrs: &mut A,
    op: TriOp,
    build: impl FnOnce(TriOp, TriRecord) -> R,
) -> Result<Edited<R, A>, TriEditError> {
    let edit = op.apply(&mut (&mut *map, &mut *attrs))?;
    Ok(edit.map_record(|r| build(op, r)))
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
