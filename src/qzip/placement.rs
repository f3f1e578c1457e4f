//! Per-vertex data through a Q-zip or the preprocessing, on the crate's one attribute layer
//! ([`crate::mesh`]).
//!
//! The rule, in two passes over the splits in the order applied:
//!
//! 1. each created vertex first takes the value of the vertex it was split from (the split's
//!    kept vertex), read when the split is reached. Splits are read in order and only
//!    splits write values, so that read gives the kept vertex's value at the time of the
//!    split, even when its slot is reused later;
//! 2. each created vertex that is still live is then placed at the mean of its neighbours
//!    on the edited map, in the order created (a copy next to an earlier copy uses its new
//!    place).
//!
//! Why the first pass: the edited map's neighbours of a created vertex include vertices
//! created later in the chain, whose slots held the default value (the origin) or the
//! value of a vertex a collapse removed (anywhere on the mesh). Their mean pulled the
//! vertex off the surface (measured on the shipped meshes: up to 56 % of the diagonal on
//! fandisk; docs/quality.md, "Q-zip placement"). After it, every neighbour holds a value
//! from the edit's own neighbourhood. Merged vertices keep the value of the vertex that
//! keeps the handle; every other vertex keeps its value.

use super::execute::ZipReport;
use crate::map::Map;
use crate::mesh::{Journal, Rule, VertexAttributes};
use crate::ops::quad::QuadRecord;
use crate::ops::{Refusal, Undo};

/// Places the vertices the splits among `records` created (see the module's rule), then
/// covers every vertex slot of `map`. Values of no size (a bare map's `()`) carry nothing
/// to place, so the passes are skipped for them.
pub(super) fn place_created<A: VertexAttributes>(
    map: &Map,
    attrs: &mut A,
    journal: &mut Journal<A>,
    records: &[QuadRecord],
) {
    if core::mem::size_of::<A::Value>() != 0 {
        place_splits(map, attrs, journal, records);
    }
    attrs.cover(map.vertex_slots());
}

/// The two passes of [`place_created`].
fn place_splits<A: VertexAttributes>(
    map: &Map,
    attrs: &mut A,
    journal: &mut Journal<A>,
    records: &[QuadRecord],
) {
    let splits = || {
        records.iter().filter_map(|r| match r {
            QuadRecord::Split(s) => Some(s),
            _ => None,
        })
    };
    // Pass 1 reads no neighbour, so the map's later state plays no part in it.
    for s in splits() {
        let from = Rule::Midpoint(s.kept(), s.kept());
        journal.place(map, attrs, s.created(), from);
    }
    for s in splits() {
        if map.is_live_vertex(s.created()) {
            journal.place(map, attrs, s.created(), Rule::NeighbourMean(s.created()));
        }
    }
}

impl Undo for ZipReport {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        ZipReport::undo(self, map)
    }
}

#[cfg(test)]
mod tests {
    use crate::qzip::{Qzip, Tag};
    use crate::{gen, Vert};
    use glam::DVec3;

    /// Every vertex a zip creates lands inside the input's bounding box (the mesh is moved
    /// away from the origin, where an unplaced vertex would sit), and the last one created
    /// at the mean of its neighbours.
    #[test]
    fn created_vertices_land_among_their_neighbours() {
        let mut mesh = gen::subdivided_icosahedron(2);
        for p in &mut mesh.positions {
            *p += DVec3::splat(100.0);
        }
        let (lo, hi) = mesh
            .positions
            .iter()
            .fold((DVec3::MAX, DVec3::MIN), |(a, b), &p| (a.min(p), b.max(p)));
        let z = Qzip::new()
            .zip(&mut mesh, Vert::new(42), Vert::new(0), Tag::LS)
            .unwrap();
        let created: alloc::vec::Vec<Vert> = z
            .record()
            .records()
            .iter()
            .filter_map(|r| match r {
                crate::ops::quad::QuadRecord::Split(s) => Some(s.created()),
                _ => None,
            })
            .filter(|&v| mesh.map.is_live_vertex(v))
            .collect();
        assert!(!created.is_empty());
        for &v in &created {
            let p = mesh.positions[v.index()];
            assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "{v:?} at {p}");
        }
        let last = *created.last().unwrap();
        let ring: alloc::vec::Vec<DVec3> = mesh
            .map
            .vertex_darts(last)
            .map(|d| mesh.positions[mesh.map.dest(d).index()])
            .collect();
        let mean = ring.iter().copied().sum::<DVec3>() / ring.len() as f64;
        assert!(mesh.positions[last.index()].distance(mean) < 1e-9);
    }
}
