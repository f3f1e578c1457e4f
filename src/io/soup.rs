//! The polygons a reader collects, and building the map from them with errors traced back
//! to the lines of the faces.

use super::{ErrorKind, Format, MeshFileError};
use crate::map::{BuildError, BuildReport};
use crate::mesh::Mesh;
use alloc::string::ToString;
use alloc::vec::Vec;
use glam::DVec3;

/// Polygons as parsed, with the line of every face, before the topology is built.
#[derive(Default)]
pub(super) struct Soup {
    pub(super) positions: Vec<DVec3>,
    pub(super) corners: Vec<u32>,
    pub(super) offsets: Vec<u32>,
    pub(super) face_lines: Vec<u32>,
}

/// The builder needs fewer than 2^31 corners; checked while parsing so offsets fit in u32.
const MAX_CORNERS: usize = (u32::MAX / 2 - 1) as usize;

impl Soup {
    pub(super) fn new() -> Self {
        Soup {
            offsets: alloc::vec![0],
            ..Soup::default()
        }
    }

    /// Closes the face whose corners were pushed since the last call.
    pub(super) fn end_face(&mut self, line: usize) -> Result<(), MeshFileError> {
        if self.corners.len() > MAX_CORNERS {
            return Err(MeshFileError::new(Some(line), ErrorKind::TooLarge));
        }
        self.offsets.push(self.corners.len() as u32);
        self.face_lines
            .push(u32::try_from(line).unwrap_or(u32::MAX));
        Ok(())
    }

    /// Builds the map; errors name the lines of their faces and `format` numbers vertices.
    pub(super) fn finish(self, format: Format) -> Result<(Mesh, BuildReport), MeshFileError> {
        let built =
            crate::map::Map::from_flat_polygons(self.positions.len(), &self.corners, &self.offsets);
        match built {
            Ok((map, report)) => Ok((
                Mesh {
                    map,
                    positions: self.positions,
                },
                report,
            )),
            Err(e) => Err(self.locate(e, format)),
        }
    }

    fn line_of(&self, face: usize) -> usize {
        self.face_lines.get(face).map_or(0, |&l| l as usize)
    }

    /// Turns a build error into a file error at the line of its face.
    fn locate(&self, e: BuildError, format: Format) -> MeshFileError {
        let line = e.face().map(|f| self.line_of(f));
        let kind = match e {
            // Defects the parsers also find get the parsers' variants (see
            // `ErrorKind::IndexOutOfRange`): one defect, one variant, whoever finds it.
            BuildError::IndexOutOfRange {
                vertex, n_vertices, ..
            } => ErrorKind::IndexOutOfRange {
                index: format.vertex_number(vertex) as i64,
                written: format.vertex_number(vertex).to_string(),
                vertices: n_vertices,
                format,
            },
            BuildError::TooLarge { .. } => ErrorKind::TooLarge,
            error => ErrorKind::Topology {
                lines: named_faces(&error)
                    .iter()
                    .map(|&f| self.line_of(f))
                    .collect(),
                error,
                format,
            },
        };
        MeshFileError::new(line, kind)
    }
}

/// The faces `e` names, in its order.
fn named_faces(e: &BuildError) -> &[usize] {
    match e {
        BuildError::FaceTooSmall { face, .. }
        | BuildError::RepeatedCorner { face, .. }
        | BuildError::IndexOutOfRange { face, .. }
        | BuildError::NonManifoldVertex { face, .. } => core::slice::from_ref(face),
        BuildError::NonManifoldEdge { faces, .. } => faces,
        BuildError::InconsistentOrientation { faces, .. } => faces,
        BuildError::TooLarge { .. } => &[],
    }
}
