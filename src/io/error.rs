//! The error type of mesh files: where (path, line) and what ([`ErrorKind`]).

use alloc::string::String;
use core::fmt;
use std::io;
use std::path::{Path, PathBuf};

/// What is wrong with a mesh file.
///
/// Vertex numbers are given as the file writes them: 1-based for OBJ, 0-based for OFF.
///
/// ```
/// use zipmesh::io::{obj, off, ErrorKind};
/// let e = obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n").unwrap_err();
/// assert!(matches!(e.kind(), ErrorKind::RepeatedCorner { vertex: 1 }));
/// let e = off::parse("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 0\n").unwrap_err();
/// assert!(matches!(e.kind(), ErrorKind::RepeatedCorner { vertex: 0 }));
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub enum ErrorKind {
    /// Reading or writing the file failed.
    Io(io::Error),
    /// The file name's extension is neither `.obj` nor `.off`.
    UnknownFormat,
    /// An OFF file does not start with an `OFF` header.
    MissingHeader,
    /// A token is not the number that was expected there.
    BadNumber {
        /// What was expected, e.g. "a vertex coordinate".
        expected: &'static str,
        /// The token found (cut to 40 bytes).
        found: String,
    },
    /// A line ends where a number was expected.
    MissingNumber {
        /// What was expected.
        expected: &'static str,
    },
    /// An OFF file ends before the vertices or faces its header declares.
    CountsMismatch {
        /// "vertices" or "faces".
        what: &'static str,
        /// The number the header declares.
        declared: usize,
        /// The number the file holds.
        found: usize,
    },
    /// An OFF file has more lines after the faces its header declares.
    ExtraData {
        /// The number of faces the header declares.
        declared_faces: usize,
    },
    /// A face refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The index as written in the file.
        index: i64,
        /// The number of vertices it was checked against (for OBJ's negative indices, the
        /// vertices defined before the face).
        vertices: usize,
    },
    /// A face has fewer than three corners.
    FaceTooSmall {
        /// Its number of corners.
        corners: usize,
    },
    /// A face uses the same vertex twice.
    RepeatedCorner {
        /// The vertex.
        vertex: u64,
    },
    /// An edge is used by three or more faces.
    NonManifoldEdge {
        /// One end.
        a: u64,
        /// The other end.
        b: u64,
        /// The lines of three faces using it.
        lines: [usize; 3],
    },
    /// Two faces run along an edge in the same direction: their orientations disagree.
    InconsistentOrientation {
        /// Origin of both half-edges.
        a: u64,
        /// Destination of both half-edges.
        b: u64,
        /// The lines of the two faces.
        lines: [usize; 2],
    },
    /// The faces around a vertex form more than one fan (a pinched vertex).
    NonManifoldVertex {
        /// The vertex.
        vertex: u64,
    },
    /// More vertices or corners than 32-bit handles can address.
    TooLarge,
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorKind::Io(e) => write!(f, "I/O error: {e}"),
            ErrorKind::UnknownFormat => {
                f.write_str("unknown mesh format: the file name must end in .obj or .off")
            }
            ErrorKind::MissingHeader => f.write_str("missing `OFF` header"),
            ErrorKind::BadNumber { expected, found } => {
                write!(f, "expected {expected}, found `{found}`: bad number")
            }
            ErrorKind::MissingNumber { expected } => {
                write!(f, "expected {expected}, found the end of the line")
            }
            ErrorKind::CountsMismatch { what, declared, found } => write!(
                f,
                "the header declares {declared} {what} but the file has {found}: counts mismatch"
            ),
            ErrorKind::ExtraData { declared_faces } => write!(
                f,
                "unexpected data after the {declared_faces} faces the header declares: counts mismatch"
            ),
            ErrorKind::IndexOutOfRange { index, vertices } => write!(
                f,
                "vertex index {index} is out of range for {vertices} vertices: index out of range"
            ),
            ErrorKind::FaceTooSmall { corners } => write!(
                f,
                "face has {corners} corners, at least 3 are needed: face too small"
            ),
            ErrorKind::RepeatedCorner { vertex } => {
                write!(f, "face uses vertex {vertex} twice: repeated corner")
            }
            ErrorKind::NonManifoldEdge { a, b, lines } => write!(
                f,
                "edge {a}-{b} is used by three or more faces (lines {}, {} and {}): non-manifold edge",
                lines[0], lines[1], lines[2]
            ),
            ErrorKind::InconsistentOrientation { a, b, lines } => write!(
                f,
                "the faces on lines {} and {} both run from vertex {a} to vertex {b}: inconsistent orientation",
                lines[0], lines[1]
            ),
            ErrorKind::NonManifoldVertex { vertex } => write!(
                f,
                "the faces around vertex {vertex} form more than one fan: non-manifold vertex"
            ),
            ErrorKind::TooLarge => f.write_str("the mesh is too large for 32-bit handles"),
        }
    }
}

/// An error reading or writing a mesh file: where (path, line) and what ([`ErrorKind`]).
///
/// ```
/// use zipmesh::io::{obj, ErrorKind};
/// let err = obj::parse("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err();
/// assert_eq!(err.line(), Some(3));
/// assert!(matches!(err.kind(), ErrorKind::FaceTooSmall { corners: 2 }));
/// assert!(err.to_string().starts_with("line 3: "));
/// ```
#[derive(Debug)]
pub struct MeshFileError {
    path: Option<PathBuf>,
    line: Option<usize>,
    kind: ErrorKind,
}

impl MeshFileError {
    /// An error of `kind` at 1-based `line` (if known), without a path.
    ///
    /// ```
    /// use zipmesh::io::{ErrorKind, MeshFileError};
    /// let e = MeshFileError::new(Some(4), ErrorKind::MissingHeader);
    /// assert_eq!(e.to_string(), "line 4: missing `OFF` header");
    /// ```
    pub fn new(line: Option<usize>, kind: ErrorKind) -> Self {
        MeshFileError {
            path: None,
            line,
            kind,
        }
    }

    /// The same error, naming `path` as the file.
    ///
    /// ```
    /// use zipmesh::io::{ErrorKind, MeshFileError};
    /// let e = MeshFileError::new(Some(4), ErrorKind::MissingHeader).with_path("a.off");
    /// assert_eq!(e.to_string(), "a.off:4: missing `OFF` header");
    /// ```
    pub fn with_path(mut self, path: impl Into<PathBuf>) -> Self {
        self.path = Some(path.into());
        self
    }

    /// The file the error is about, when known.
    ///
    /// ```
    /// let e = zipmesh::io::read_mesh("/no/such/file.obj").unwrap_err();
    /// assert_eq!(e.path(), Some(std::path::Path::new("/no/such/file.obj")));
    /// ```
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The 1-based line of the defect, when the error is about one line.
    ///
    /// ```
    /// let e = zipmesh::io::off::parse("OFF\n1 0 0\n0 0 x\n").unwrap_err();
    /// assert_eq!(e.line(), Some(3));
    /// ```
    pub fn line(&self) -> Option<usize> {
        self.line
    }

    /// What is wrong.
    ///
    /// ```
    /// use zipmesh::io::{off, ErrorKind};
    /// let e = off::parse("3 1 0\n").unwrap_err();
    /// assert!(matches!(e.kind(), ErrorKind::MissingHeader));
    /// ```
    pub fn kind(&self) -> &ErrorKind {
        &self.kind
    }

    pub(super) fn io(path: &Path, e: io::Error) -> Self {
        MeshFileError::new(None, ErrorKind::Io(e)).with_path(path)
    }
}

impl fmt::Display for MeshFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.path, self.line) {
            (Some(p), Some(l)) => write!(f, "{}:{l}: {}", p.display(), self.kind),
            (Some(p), None) => write!(f, "{}: {}", p.display(), self.kind),
            (None, Some(l)) => write!(f, "line {l}: {}", self.kind),
            (None, None) => write!(f, "{}", self.kind),
        }
    }
}

impl std::error::Error for MeshFileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            ErrorKind::Io(e) => Some(e),
            _ => None,
        }
    }
}
