//! The polygons a reader collects, and building the map from them with errors traced back
//! to the lines of the faces.

use super::error::named_faces;
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
    /// Where each face is: its line, or in a binary file its byte offset.
    pub(super) face_lines: Vec<u64>,
    /// Whether `face_lines` holds byte offsets (a binary file) rather than lines.
    pub(super) binary: bool,
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
        self.end_face_at(line as u64)
    }

    /// Closes the face whose corners were pushed since the last call, at `at`: its line,
    /// or in a binary file its byte offset.
    pub(super) fn end_face_at(&mut self, at: u64) -> Result<(), MeshFileError> {
        if self.corners.len() > MAX_CORNERS {
            return Err(self.error_at(at, ErrorKind::TooLarge));
        }
        self.offsets.push(self.corners.len() as u32);
        self.face_lines.push(at);
        Ok(())
    }

    /// An error of `kind` at `at`: a line, or in a binary file a byte offset.
    pub(super) fn error_at(&self, at: u64, kind: ErrorKind) -> MeshFileError {
        if self.binary {
            MeshFileError::new(None, kind).with_byte(at)
        } else {
            MeshFileError::new(Some(at as usize), kind)
        }
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

    /// Turns a build error into a file error at the line of its face (in a binary file, at
    /// the byte where the face starts, its message naming the faces).
    fn locate(&self, e: BuildError, format: Format) -> MeshFileError {
        match e.face().and_then(|f| self.face_lines.get(f).copied()) {
            Some(at) => self.error_at(at, self.kind_of(e, format)),
            None => MeshFileError::new(None, self.kind_of(e, format)),
        }
    }

    /// The file error a build error is, in `format`'s terms.
    fn kind_of(&self, e: BuildError, format: Format) -> ErrorKind {
        match e {
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
                lines: if self.binary {
                    Vec::new()
                } else {
                    named_faces(&error)
                        .iter()
                        .map(|&f| self.line_of(f))
                        .collect()
                },
                error,
                format,
            },
        }
    }
}
