//! Mesh files (OBJ, OFF and PLY): reading with errors that name the line (or, in binary
//! PLY data, the byte), atomic writing.
//!
//! * [`read_mesh`] and [`write_mesh`] choose the format by the file name's extension
//!   (`.obj`, `.off` or `.ply`, any case).
//! * [`obj::parse`], [`off::parse`] (and their `parse_bytes` forms) read from memory and never
//!   panic, whatever the input; [`obj::write`] and [`off::write`] write to any `std::io::Write`.
//! * Every error is a [`MeshFileError`]: the file's path when known, the 1-based line, and a
//!   typed [`ErrorKind`]. Its `Display` reads `path:LINE: problem`. Topology defects found
//!   by [`Map::from_polygons_with_report`](crate::Map::from_polygons_with_report) are the
//!   kernel's error in [`ErrorKind::Topology`], traced back to the line of the offending
//!   face. Messages number vertices from 0 in file order, as the kernel and the command
//!   line do, with OBJ's own 1-based number quoted beside (see [`ErrorKind`]).
//! * Reading returns the [`Mesh`] and the [`BuildReport`]. Vertices that no face uses are
//!   kept as dead vertex slots (their positions stay in `mesh.positions`), so every other
//!   vertex keeps its number from the file; the report lists them.
//! * Writing drops dead slots (vertices are renumbered in slot order, faces written in slot
//!   order) and goes through a temporary file in the target's directory that is renamed into
//!   place, so a failed write leaves no partial file and does not touch an existing target.
//!
//! The readers are written by hand rather than taken from a crate such as `tobj` because
//! their errors must carry the exact line of the defect, including topology defects found
//! after parsing; `tobj` reports neither line numbers nor which face was at fault. Parsing
//! works on bytes (no regular expressions, no allocation per line), so files that are not
//! UTF-8 in their comments still load.
//!
//! ```
//! use zipmesh::io::{obj, off};
//! let (mesh, _) = obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
//! let mut text = Vec::new();
//! off::write(&mesh, &mut text).unwrap();
//! let (again, _) = off::parse_bytes(&text).unwrap();
//! assert_eq!(again.positions, mesh.positions);
//! ```

mod atomic;
mod error;
mod lex;
pub mod obj;
pub mod off;
pub mod ply;
mod soup;
mod write;

pub use atomic::{
    check_target, prepare_atomic, remove_temporaries, temporary_path, write_atomic, PendingFile,
};
pub use error::{ErrorKind, MeshFileError};

use crate::map::BuildReport;
use crate::mesh::Mesh;
use std::fs;
use std::io::{self, Write};
use std::path::Path;

/// A mesh file format.
///
/// ```
/// use zipmesh::{gen, io::Format};
/// let mut text = Vec::new();
/// Format::Off.write(&gen::cube(1), &mut text).unwrap();
/// let (cube, _) = Format::Off.parse_bytes(&text).unwrap();
/// assert_eq!(cube.map.num_faces(), 6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (see [`obj`]).
    Obj,
    /// Object File Format (see [`off`]).
    Off,
    /// Stanford PLY, ASCII or binary (see [`ply`]); written binary little-endian.
    Ply,
}

impl Format {
    /// The format named by the extension of `path` (`.obj`, `.off` or `.ply`, any case).
    ///
    /// ```
    /// use zipmesh::io::Format;
    /// assert_eq!(Format::from_path("bunny.OBJ"), Some(Format::Obj));
    /// assert_eq!(Format::from_path("cube.off"), Some(Format::Off));
    /// assert_eq!(Format::from_path("scan.ply"), Some(Format::Ply));
    /// assert_eq!(Format::from_path("notes.txt"), None);
    /// ```
    pub fn from_path(path: impl AsRef<Path>) -> Option<Format> {
        let ext = path.as_ref().extension()?.to_str()?;
        if ext.eq_ignore_ascii_case("obj") {
            Some(Format::Obj)
        } else if ext.eq_ignore_ascii_case("off") {
            Some(Format::Off)
        } else if ext.eq_ignore_ascii_case("ply") {
            Some(Format::Ply)
        } else {
            None
        }
    }

    /// The number a file of this format writes for vertex slot `slot`: OBJ counts from 1,
    /// OFF from 0. Error messages number vertices from 0 and quote this number beside
    /// when it differs (see [`ErrorKind`]).
    ///
    /// ```
    /// use zipmesh::io::Format;
    /// assert_eq!(Format::Obj.vertex_number(0), 1);
    /// assert_eq!(Format::Off.vertex_number(0), 0);
    /// ```
    pub fn vertex_number(self, slot: u32) -> u64 {
        let first = match self {
            Format::Obj => 1,
            Format::Off | Format::Ply => 0,
        };
        u64::from(slot) + first
    }

    /// Parses a file's bytes in this format (see [`obj::parse_bytes`], [`off::parse_bytes`]).
    ///
    /// ```
    /// use zipmesh::io::Format;
    /// let (mesh, _) = Format::Off.parse_bytes(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
    /// assert_eq!(mesh.map.num_faces(), 1);
    /// ```
    pub fn parse_bytes(self, src: &[u8]) -> Result<(Mesh, BuildReport), MeshFileError> {
        match self {
            Format::Obj => obj::parse_bytes(src),
            Format::Off => off::parse_bytes(src),
            Format::Ply => ply::parse_bytes(src),
        }
    }

    /// Writes `mesh` in this format (see [`obj::write`], [`off::write`]).
    ///
    /// ```
    /// use zipmesh::{gen, io::Format};
    /// let mut out = Vec::new();
    /// Format::Obj.write(&gen::grid(1, 1), &mut out).unwrap();
    /// assert_eq!(String::from_utf8(out).unwrap().matches("\nf ").count(), 1);
    /// ```
    pub fn write<W: Write>(self, mesh: &Mesh, w: W) -> io::Result<()> {
        match self {
            Format::Obj => obj::write(mesh, w),
            Format::Off => off::write(mesh, w),
            Format::Ply => ply::write(mesh, w),
        }
    }
}

/// Reads a mesh file, choosing the format by the extension (see [`Format::from_path`]).
///
/// Returns the mesh and the build report (unreferenced vertices are kept as dead slots).
/// Errors carry `path` and, for defects in the file, the line; a directory is
/// [`ErrorKind::IsDirectory`], whatever its name.
///
/// ```
/// use zipmesh::{gen, io};
/// let e = io::read_mesh(std::env::temp_dir()).unwrap_err();
/// assert!(matches!(e.kind(), io::ErrorKind::IsDirectory));
/// assert!(e.to_string().ends_with(": is a directory"));
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-read-{}.off", std::process::id()));
/// io::write_mesh(&path, &gen::cube(2)).unwrap();
/// let (mesh, report) = io::read_mesh(&path).unwrap();
/// assert_eq!(mesh.map.num_faces(), 24);
/// assert!(report.unreferenced.is_empty());
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn read_mesh(path: impl AsRef<Path>) -> Result<(Mesh, BuildReport), MeshFileError> {
    let path = path.as_ref();
    if fs::metadata(path).is_ok_and(|m| m.is_dir()) {
        return Err(MeshFileError::new(None, ErrorKind::IsDirectory).with_path(path));
    }
    let format = Format::from_path(path)
        .ok_or_else(|| MeshFileError::new(None, ErrorKind::UnknownFormat).with_path(path))?;
    let bytes = fs::read(path).map_err(|e| MeshFileError::io(path, e))?;
    format.parse_bytes(&bytes).map_err(|e| e.with_path(path))
}

/// Writes `mesh` to `path` atomically, choosing the format by the extension.
///
/// Dead slots are dropped (live vertices are renumbered in slot order). See
/// [`write_atomic`] for what happens on failure.
///
/// ```
/// use zipmesh::{gen, io};
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-write-{}.obj", std::process::id()));
/// io::write_mesh(&path, &gen::torus_grid(3, 3)).unwrap();
/// assert!(std::fs::read_to_string(&path).unwrap().starts_with("# "));
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn write_mesh(path: impl AsRef<Path>, mesh: &Mesh) -> Result<(), MeshFileError> {
    let path = path.as_ref();
    let format = Format::from_path(path)
        .ok_or_else(|| MeshFileError::new(None, ErrorKind::UnknownFormat).with_path(path))?;
    write_atomic(path, |w| format.write(mesh, w))
}

/// Writes `mesh` for `path` as [`write_mesh`] does, but leaves it pending: nothing is in
/// place until [`PendingFile::commit`], and dropping the result leaves `path` as it was.
///
/// ```
/// use zipmesh::{gen, io};
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-prepare-{}.off", std::process::id()));
/// let pending = io::prepare_mesh(&path, &gen::cube(1)).unwrap();
/// assert!(!path.exists());
/// pending.commit().unwrap();
/// assert_eq!(io::read_mesh(&path).unwrap().0.map.num_faces(), 6);
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn prepare_mesh(path: impl AsRef<Path>, mesh: &Mesh) -> Result<PendingFile, MeshFileError> {
    let path = path.as_ref();
    let format = Format::from_path(path)
        .ok_or_else(|| MeshFileError::new(None, ErrorKind::UnknownFormat).with_path(path))?;
    prepare_atomic(path, |w| format.write(mesh, w))
}
