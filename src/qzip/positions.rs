//! Positions on a [`Mesh`]: where the vertices a Q-zip (or the preprocessing) creates are
//! placed, and the undo that restores the positions it overwrote. Kept apart so that the
//! position keeping can be swapped for an attribute layer.

use alloc::vec::Vec;
use glam::DVec3;

use super::execute::ZipReport;
use crate::ops::quad::QuadRecord;
use crate::ops::Refusal;
use crate::{Mesh, Vert};

/// A Q-zip on a [`Mesh`] ([`super::Qzip::zip_mesh`]): the report, and the positions it
/// overwrote (for the undo). Each vertex a split creates is placed at the mean of its
/// neighbours (in the order created, so a copy next to an earlier copy uses its new place);
/// merged vertices keep the position of the vertex that keeps the handle.
///
/// See [`super::Qzip::zip_mesh`] for an example.
#[derive(Clone, Debug)]
pub struct MeshZip {
    report: ZipReport,
    overwritten: Vec<(Vert, DVec3)>,
    old_len: usize,
}

impl MeshZip {
    /// The connectivity report.
    ///
    /// See [`super::Qzip::zip_mesh`] for an example.
    pub fn report(&self) -> &ZipReport {
        &self.report
    }

    /// Undoes the edit: connectivity `==` and positions exactly as before.
    ///
    /// See [`super::Qzip::zip_mesh`] for an example.
    pub fn undo(&self, mesh: &mut Mesh) -> Result<(), Refusal> {
        self.report.undo(&mut mesh.map)?;
        for &(v, p) in self.overwritten.iter().rev() {
            if let Some(x) = mesh.positions.get_mut(v.index()) {
                *x = p;
            }
        }
        mesh.positions.truncate(self.old_len);
        Ok(())
    }
}

/// Places each vertex created by a split in `records` at the mean of its neighbours, in
/// order; returns the positions overwritten (of reused handles below `old_len`).
pub(super) fn place_created(
    mesh: &mut Mesh,
    records: &[QuadRecord],
    old_len: usize,
) -> Vec<(Vert, DVec3)> {
    let mut overwritten = Vec::new();
    if mesh.positions.len() < mesh.map.vertex_slots() {
        mesh.positions.resize(mesh.map.vertex_slots(), DVec3::ZERO);
    }
    for r in records {
        if let QuadRecord::Split(s) = r {
            let v = s.created();
            let (mut sum, mut n) = (DVec3::ZERO, 0.0);
            for d in mesh.map.vertex_darts(v) {
                let p = mesh.positions.get(mesh.map.dest(d).index());
                sum += p.copied().unwrap_or_default();
                n += 1.0;
            }
            if let Some(x) = mesh.positions.get_mut(v.index()) {
                if v.index() < old_len {
                    overwritten.push((v, *x));
                }
                if n > 0.0 {
                    *x = sum / n;
                }
            }
        }
    }
    overwritten
}

/// The positions after a Q-zip on `mesh.map` (`report`) that found `old_len` positions: the
/// created vertices placed, the overwritten positions kept for the undo.
pub(super) fn keep_positions(mesh: &mut Mesh, report: ZipReport, old_len: usize) -> MeshZip {
    let overwritten = place_created(mesh, report.records(), old_len);
    MeshZip {
        report,
        overwritten,
        old_len,
    }
}
