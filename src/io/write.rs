//! Helpers shared by the OBJ and OFF writers.

use crate::map::Face;
use crate::mesh::Mesh;
use alloc::format;
use alloc::vec::Vec;
use core::fmt;
use glam::DVec3;
use std::io::{self, Write};

/// Shortest round-trip text of a coordinate; exponent form for very small or large values
/// so that no coordinate needs hundreds of digits.
pub(super) struct Coord(pub(super) f64);

impl fmt::Display for Coord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || (1e-5..1e16).contains(&a) {
            fmt::Display::fmt(&self.0, f)
        } else {
            fmt::LowerExp::fmt(&self.0, f)
        }
    }
}

/// Live vertices renumbered `0..` in slot order, and their positions; `None` if a position
/// is not finite (the readers would refuse the file).
pub(super) fn live_vertices(mesh: &Mesh) -> io::Result<(Vec<u32>, Vec<DVec3>)> {
    let map = &mesh.map;
    let mut new_index = alloc::vec![u32::MAX; map.vertex_slots()];
    let mut positions = Vec::with_capacity(map.num_vertices());
    for v in map.vertices() {
        let p = mesh
            .positions
            .get(v.index())
            .copied()
            .unwrap_or(DVec3::ZERO);
        if !p.is_finite() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("vertex {v} has a position that is not finite: {p}"),
            ));
        }
        new_index[v.index()] = positions.len() as u32;
        positions.push(p);
    }
    Ok((new_index, positions))
}

/// Writes the corners of face `f` as ` i j k ...` (new numbers plus `base`).
#[inline]
pub(super) fn write_face<W: Write>(
    w: &mut W,
    mesh: &Mesh,
    f: Face,
    new_index: &[u32],
    base: u32,
) -> io::Result<()> {
    for d in mesh.map.face_darts(f) {
        let v = mesh.map.origin(d).index();
        let i = new_index.get(v).copied().unwrap_or(0);
        write!(w, " {}", u64::from(i) + u64::from(base))?;
    }
    w.write_all(b"\n")
}
