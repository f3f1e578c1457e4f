//! Per-vertex data through a Q-zip or the preprocessing, on the crate's one attribute layer
//! ([`crate::mesh`]): each vertex a split creates is placed at the mean of its neighbours,
//! in the order created (so a copy next to an earlier copy uses its new place); merged
//! vertices keep the value of the vertex that keeps the handle.

use super::execute::ZipReport;
use super::preprocess::Preprocessed;
use crate::map::Map;
use crate::mesh::{Journal, Rule, VertexAttributes};
use crate::ops::quad::QuadRecord;
use crate::ops::{Refusal, Undo};

/// Places the vertices the splits among `records` created, then covers every vertex slot
/// of `map` (new slots nobody placed take the default value).
pub(super) fn place_created<A: VertexAttributes>(
    map: &Map,
    attrs: &mut A,
    journal: &mut Journal<A>,
    records: &[QuadRecord],
) {
    for r in records {
        if let QuadRecord::Split(s) = r {
            journal.place(map, attrs, s.created(), Rule::NeighbourMean(s.created()));
        }
    }
    attrs.cover(map.vertex_slots());
}

impl Undo for ZipReport {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        ZipReport::undo(self, map)
    }
}

impl Undo for Preprocessed {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        Preprocessed::undo(self, map)
    }
}
