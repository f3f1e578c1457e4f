//! A map with vertex positions (what mesh files hold and generators make), and the one
//! attribute layer that keeps per-vertex data in step with every edit and its undo:
//! [`VertexAttributes`] (the data), [`Rule`] (where a new vertex takes it from), [`Journal`]
//! (what an edit overwrote) and [`Edited`] (an edit's record with its journal).

mod attributes;
mod edited;
mod target;

pub use attributes::{Blend, Positions, VertexAttributes};
pub use edited::{Edited, Journal, Rule};
pub use target::EditTarget;

use crate::map::{BuildError, BuildReport, Map};
use alloc::vec::Vec;
use glam::DVec3;

/// A [`Map`] together with one position per vertex slot.
///
/// Positions follow vertex slots (`positions[v.index()]`); a dead slot keeps whatever
/// position it had. The topology never reads positions.
///
/// ```
/// let mesh = zipmesh_kernel::gen::cube(1);
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// ```
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Mesh {
    /// The connectivity.
    pub map: Map,
    /// Per vertex slot, its position.
    pub positions: Vec<DVec3>,
}

impl Mesh {
    /// Builds a mesh from positions and polygons (see [`Map::from_polygons_with_report`]).
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh_kernel::Mesh;
    /// let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    /// let (mesh, report) = Mesh::from_polygons(p, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(mesh.map.num_faces(), 1);
    /// assert!(report.unreferenced.is_empty());
    /// ```
    pub fn from_polygons<F: AsRef<[u32]>>(
        positions: Vec<DVec3>,
        faces: &[F],
    ) -> Result<(Mesh, BuildReport), BuildError> {
        let (map, report) = Map::from_polygons_with_report(positions.len(), faces)?;
        Ok((Mesh { map, positions }, report))
    }

    /// The polygons of the live faces as vertex slot lists, each starting at the face's
    /// recorded dart, in face slot order.
    ///
    /// ```
    /// use zipmesh_kernel::gen;
    /// let polys = gen::grid(2, 1).polygons();
    /// assert_eq!(polys.len(), 2);
    /// assert!(polys.iter().all(|p| p.len() == 4));
    /// ```
    pub fn polygons(&self) -> Vec<Vec<u32>> {
        self.map
            .faces()
            .map(|f| {
                self.map
                    .face_darts(f)
                    .map(|d| self.map.origin(d).index() as u32)
                    .collect()
            })
            .collect()
    }

    /// Removes dead slots from the map and the positions alike (see [`Map::compact`]).
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh_kernel::Mesh;
    /// let p = vec![DVec3::ZERO, DVec3::ONE, DVec3::X, DVec3::Y];
    /// let (mut mesh, _) = Mesh::from_polygons(p, &[[0u32, 2, 3]]).unwrap();
    /// mesh.compact();
    /// assert_eq!(mesh.positions, vec![DVec3::ZERO, DVec3::X, DVec3::Y]);
    /// ```
    pub fn compact(&mut self) -> crate::map::Compaction {
        let c = self.map.compact();
        let mut kept = Vec::with_capacity(self.map.vertex_slots());
        for (old, new) in c.vertices.iter().enumerate() {
            if new.is_some() {
                kept.push(self.positions.get(old).copied().unwrap_or(DVec3::ZERO));
            }
        }
        self.positions = kept;
        c
    }
}
