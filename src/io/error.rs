//! The error type of mesh files: where (path, line) and what ([`ErrorKind`]).

use super::Format;
use crate::map::BuildError;
use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt;
use std::io;
use std::path::{Path, PathBuf};

/// What is wrong with a mesh file.
///
/// Defects the readers find while parsing have their own variants. Defects of the surface
/// that the faces describe are the kernel's [`BuildError`], wrapped in
/// [`ErrorKind::Topology`] with the file's format.
///
/// Messages number vertices from 0 in file order, as the command line and the kernel do,
/// whatever the format. Where the file writes another number (OBJ counts from 1), the
/// file's own text follows in one note: ``vertex 5 (0-based; `6` in the file)``,
/// ``edge 7-8 (0-based; `8`-`9` in the file)``. Lines are counted from 1, as editors count
/// them. A token that names no vertex (OBJ's `0`, a negative index counting back too far,
/// a number too long to hold) is quoted as written.
///
/// ```
/// use zipmesh::io::{obj, off, ErrorKind, Format};
/// use zipmesh::BuildError;
/// let e = obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n").unwrap_err();
/// let ErrorKind::Topology { error: BuildError::RepeatedCorner { vertex, .. }, format, .. } =
///     e.kind()
/// else {
///     panic!("{e}");
/// };
/// assert_eq!((*vertex, format.vertex_number(*vertex)), (0, 1)); // slot 0 is OBJ's `1`
/// assert_eq!(
///     e.to_string(),
///     "line 4: face uses vertex 0 (0-based; `1` in the file) twice: repeated corner"
/// );
/// let e = off::parse("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 0\n").unwrap_err();
/// assert!(matches!(
///     e.kind(),
///     ErrorKind::Topology { error: BuildError::RepeatedCorner { vertex: 0, .. }, format: Format::Off, .. }
/// ));
/// assert_eq!(e.to_string(), "line 6: face uses vertex 0 twice: repeated corner");
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub enum ErrorKind {
    /// Reading or writing the file failed.
    Io(io::Error),
    /// The path names a directory, where a file to read or to write was expected.
    IsDirectory,
    /// The directory a file is to be written in does not exist (checked before any work,
    /// see [`check_target`](super::check_target)).
    MissingDirectory {
        /// The directory.
        dir: PathBuf,
    },
    /// What should be the directory of a file to be written is something else, such as a
    /// file.
    NotADirectory {
        /// The path that is not a directory.
        dir: PathBuf,
    },
    /// The file name's extension is neither `.obj` nor `.off`.
    UnknownFormat,
    /// An OFF file does not start with an `OFF` header.
    MissingHeader,
    /// The file is not text: it starts with a UTF-16 or UTF-32 byte-order mark (`byte` is
    /// `None`), or holds the control byte `byte` (such as NUL), as binary files and UTF-16
    /// without a mark do. A UTF-8 byte-order mark is skipped, not refused.
    NotText {
        /// The first control byte found, if that is what gave it away.
        byte: Option<u8>,
    },
    /// An OBJ file has content but not one `v` or `f` statement (random text, say); an
    /// empty or comment-only file is an empty mesh. (OFF's header says what a file holds:
    /// an OFF file without one is [`ErrorKind::MissingHeader`].)
    NoMeshData {
        /// The format that was expected.
        format: Format,
    },
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
    ///
    /// A file-level variant rather than the kernel's `IndexOutOfRange`: the index is the
    /// text of the file (OBJ's may be zero or negative, and any may exceed `u32`), which the
    /// kernel's numbering cannot hold. OBJ's positive indices may refer forward, so their
    /// range is checked by the kernel once every vertex is read; the readers report that
    /// as this variant too, so one defect has one variant.
    ///
    /// The message gives the 0-based vertex the index names, with the file's text beside
    /// it when that differs (OBJ):
    ///
    /// ```
    /// let e = zipmesh::io::obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap_err();
    /// assert_eq!(
    ///     e.to_string(),
    ///     "line 4: vertex 8 (0-based; `9` in the file) is out of range for 3 vertices \
    ///      (0 to 2): index out of range"
    /// );
    /// ```
    IndexOutOfRange {
        /// The index's value as the file writes it (beyond ±10^18 it saturates; `written`
        /// has the digits).
        index: i64,
        /// The index as the file writes it (cut to 40 bytes, then `...`), for messages.
        written: String,
        /// The number of vertices it was checked against (for OBJ's negative indices, the
        /// vertices defined before the face).
        vertices: usize,
        /// The file's format, which says how `index` numbers vertices.
        format: Format,
    },
    /// The faces do not describe an oriented surface, as
    /// [`Map::from_flat_polygons`](crate::Map::from_flat_polygons) found: a face with fewer
    /// than three corners or a repeated one, a non-manifold edge or vertex, or two faces
    /// whose orientations disagree.
    Topology {
        /// The kernel's error, in its numbering: vertex slots from 0, faces counted from 0
        /// in the order of the file.
        error: BuildError,
        /// The file's format, which says how it numbers vertices ([`Format::vertex_number`]).
        format: Format,
        /// The lines of the faces `error` names, in its order.
        lines: Vec<usize>,
    },
    /// More vertices or corners than 32-bit handles can address (whether the reader or the
    /// kernel found it).
    TooLarge,
    /// A PLY header that does not describe a mesh the reader can read: no `ply` start, an
    /// unknown format, type or keyword, no `vertex` element with `x`, `y`, `z`, a `face`
    /// element without its corner list, no `end_header`.
    BadHeader {
        /// What is wrong.
        problem: String,
    },
    /// A PLY file ends inside the instance `index` (0-based) of the element `element`,
    /// which the header declares `count` of.
    Truncated {
        /// The element's name.
        element: String,
        /// The instance the data ends in.
        index: usize,
        /// The instances the header declares.
        count: usize,
    },
    /// A PLY file has more than white space after the last element the header declares.
    TrailingData,
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorKind::Io(e) => write!(f, "I/O error: {e}"),
            ErrorKind::IsDirectory => f.write_str("is a directory"),
            ErrorKind::MissingDirectory { dir } => {
                write!(f, "the directory {} does not exist", Escaped(dir))
            }
            ErrorKind::NotADirectory { dir } => {
                write!(f, "{} is not a directory", Escaped(dir))
            }
            ErrorKind::UnknownFormat => f.write_str(
                "unknown mesh format: the file name must end in .obj, .off or .ply",
            ),
            ErrorKind::MissingHeader => f.write_str("missing `OFF` header"),
            ErrorKind::NotText { byte: None } => f.write_str(
                "the file is UTF-16 or UTF-32 (it starts with a byte-order mark); \
                 save it as UTF-8 or ASCII: not text",
            ),
            ErrorKind::NotText { byte: Some(b) } => write!(
                f,
                "byte 0x{b:02X} is a control character (a binary or UTF-16 file?): not text"
            ),
            ErrorKind::NoMeshData { format } => {
                let name = match format {
                    Format::Obj => "OBJ",
                    Format::Off => "OFF",
                    Format::Ply => "PLY",
                };
                write!(f, "no {name} vertex or face found: not a mesh file")
            }
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
            ErrorKind::IndexOutOfRange {
                index,
                written,
                vertices,
                format,
            } => fmt_out_of_range(f, *index, written, *vertices, *format),
            ErrorKind::Topology {
                error,
                format,
                lines,
            } => fmt_topology(f, error, *format, lines),
            ErrorKind::TooLarge => f.write_str("the mesh is too large for 32-bit handles"),
            ErrorKind::BadHeader { problem } => write!(f, "{problem}: bad PLY header"),
            ErrorKind::Truncated {
                element,
                index,
                count,
            } => write!(
                f,
                "the data ends inside {element} {index} of {count}: truncated"
            ),
            ErrorKind::TrailingData => {
                f.write_str("data after the last element the header declares: trailing data")
            }
        }
    }
}

/// What follows 0-based vertex numbers in a message when the file writes other numbers:
/// `` (0-based; `1`-`2` in the file)``, the file's numbers joined by `sep`; nothing for a
/// format that numbers vertices from 0.
fn file_note(format: Format, written: &[&str], sep: &str) -> String {
    if format.vertex_number(0) == 0 {
        return String::new();
    }
    let quoted: Vec<String> = written.iter().map(|w| format!("`{w}`")).collect();
    format!(" (0-based; {} in the file)", quoted.join(sep))
}

/// An index that names no vertex: the 0-based vertex it would be (with the file's text
/// when that differs), or the file's text alone when it names none (OBJ's `0`, a negative
/// index, a number too long to hold).
fn fmt_out_of_range(
    f: &mut fmt::Formatter<'_>,
    index: i64,
    written: &str,
    vertices: usize,
    format: Format,
) -> fmt::Result {
    let exact = written.parse::<i64>() == Ok(index);
    let first = format.vertex_number(0) as i64;
    match format {
        _ if exact && index >= first => {
            let range = match vertices {
                0 => String::new(),
                n => format!(" (0 to {})", n - 1),
            };
            write!(
                f,
                "vertex {}{} is out of range for {vertices} vertices{range}",
                index - first,
                file_note(format, &[written], "")
            )
        }
        Format::Obj if exact && index == 0 => {
            f.write_str("vertex index `0` is not valid in OBJ, which counts vertices from 1")
        }
        Format::Obj if index < 0 => write!(
            f,
            "vertex index `{written}` counts back past the first vertex \
             ({vertices} are defined before the face)"
        ),
        _ => write!(
            f,
            "vertex index `{written}` is out of range for {vertices} vertices"
        ),
    }?;
    f.write_str(": index out of range")
}

/// A kernel error in the file's terms: vertices numbered from 0 (with the file's own
/// numbers beside them, see [`file_note`]), faces named by their lines (what someone
/// editing the file looks for).
fn fmt_topology(
    f: &mut fmt::Formatter<'_>,
    error: &BuildError,
    format: Format,
    lines: &[usize],
) -> fmt::Result {
    let file = |x: u32| format.vertex_number(x).to_string();
    let note = |xs: &[u32], sep: &str| {
        let written: Vec<String> = xs.iter().map(|&x| file(x)).collect();
        let written: Vec<&str> = written.iter().map(String::as_str).collect();
        file_note(format, &written, sep)
    };
    // `lines` is public, so it may be shorter than the error needs; never panic in Display.
    // Without lines (a binary file) the faces are named by their 0-based numbers.
    let faces = named_faces(error);
    let named = |n: usize| {
        let (word, xs): (&str, Vec<usize>) = if lines.is_empty() {
            (
                "faces",
                (0..n).map(|i| faces.get(i).copied().unwrap_or(0)).collect(),
            )
        } else {
            (
                "lines",
                (0..n).map(|i| lines.get(i).copied().unwrap_or(0)).collect(),
            )
        };
        let xs: Vec<String> = xs.iter().map(ToString::to_string).collect();
        match xs.split_last() {
            Some((last, rest)) if !rest.is_empty() => {
                alloc::format!("{word} {} and {last}", rest.join(", "))
            }
            _ => alloc::format!("{word} {}", xs.join("")),
        }
    };
    match *error {
        BuildError::FaceTooSmall { corners, .. } => write!(
            f,
            "face has {corners} corners, at least 3 are needed: face too small"
        ),
        BuildError::RepeatedCorner { vertex, .. } => write!(
            f,
            "face uses vertex {vertex}{} twice: repeated corner",
            note(&[vertex], "")
        ),
        // The readers report these two as the file-level variants; same messages here.
        BuildError::IndexOutOfRange {
            vertex, n_vertices, ..
        } => fmt_out_of_range(
            f,
            format.vertex_number(vertex) as i64,
            &file(vertex),
            n_vertices,
            format,
        ),
        BuildError::TooLarge { .. } => fmt::Display::fmt(&ErrorKind::TooLarge, f),
        BuildError::NonManifoldEdge { a, b, .. } => write!(
            f,
            "edge {a}-{b}{} is used by three or more faces ({}): non-manifold edge",
            note(&[a, b], "-"),
            named(3)
        ),
        BuildError::InconsistentOrientation { a, b, .. } => write!(
            f,
            "the faces on {} both run from vertex {a} to vertex {b}{}: \
             inconsistent orientation",
            named(2),
            note(&[a, b], " to ")
        ),
        BuildError::NonManifoldVertex { vertex, .. } => write!(
            f,
            "the faces around vertex {vertex}{} form more than one fan: non-manifold vertex",
            note(&[vertex], "")
        ),
    }
}

/// The faces a kernel error names, in its order.
pub(super) fn named_faces(e: &BuildError) -> &[usize] {
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

/// An error reading or writing a mesh file: where (path, line) and what ([`ErrorKind`]).
///
/// ```
/// use zipmesh::{io::{obj, ErrorKind}, BuildError};
/// let err = obj::parse("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err();
/// assert_eq!(err.line(), Some(3));
/// assert!(matches!(
///     err.kind(),
///     ErrorKind::Topology { error: BuildError::FaceTooSmall { corners: 2, .. }, .. }
/// ));
/// assert!(err.to_string().starts_with("line 3: "));
/// ```
#[derive(Debug)]
pub struct MeshFileError {
    path: Option<PathBuf>,
    place: Place,
    kind: ErrorKind,
}

/// Where in the file an error is: one of a line or a byte (binary data), so the error
/// stays small.
#[derive(Clone, Copy, Debug)]
enum Place {
    Nowhere,
    Line(usize),
    Byte(u64),
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
            place: line.map_or(Place::Nowhere, Place::Line),
            kind,
        }
    }

    /// The same error, at byte `offset` of the file (in binary data, where no line is).
    ///
    /// ```
    /// use zipmesh::io::{ErrorKind, MeshFileError};
    /// let e = MeshFileError::new(None, ErrorKind::TrailingData).with_byte(212).with_path("a.ply");
    /// assert_eq!(e.to_string(), "a.ply: byte 212: data after the last element the header declares: trailing data");
    /// assert_eq!(e.byte(), Some(212));
    /// ```
    pub fn with_byte(mut self, offset: u64) -> Self {
        self.place = Place::Byte(offset);
        self
    }

    /// The byte offset of the defect in binary data (PLY), when the error is about one
    /// element instance there.
    ///
    /// ```
    /// let e = zipmesh::io::off::parse("OFF\n1 0 0\n0 0 x\n").unwrap_err();
    /// assert_eq!(e.byte(), None);
    /// ```
    pub fn byte(&self) -> Option<u64> {
        match self.place {
            Place::Byte(b) => Some(b),
            _ => None,
        }
    }

    /// The same error, naming `path` as the file (its control characters escaped in the
    /// message).
    ///
    /// ```
    /// use zipmesh::io::{ErrorKind, MeshFileError};
    /// let e = MeshFileError::new(Some(4), ErrorKind::MissingHeader).with_path("a.off");
    /// assert_eq!(e.to_string(), "a.off:4: missing `OFF` header");
    /// let e = MeshFileError::new(None, ErrorKind::MissingHeader).with_path("a\x1b[2J.off");
    /// assert_eq!(e.to_string(), "a\\u{1b}[2J.off: missing `OFF` header");
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
        match self.place {
            Place::Line(l) => Some(l),
            _ => None,
        }
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
        match (&self.path, self.place) {
            (Some(p), Place::Line(l)) => write!(f, "{}:{l}: {}", Escaped(p), self.kind),
            (Some(p), Place::Byte(b)) => write!(f, "{}: byte {b}: {}", Escaped(p), self.kind),
            (Some(p), Place::Nowhere) => write!(f, "{}: {}", Escaped(p), self.kind),
            (None, Place::Line(l)) => write!(f, "line {l}: {}", self.kind),
            (None, Place::Byte(b)) => write!(f, "byte {b}: {}", self.kind),
            (None, Place::Nowhere) => write!(f, "{}", self.kind),
        }
    }
}

/// A path with its control characters escaped (`\u{1b}`), so that a file's name cannot
/// move the cursor or clear the terminal that shows the message.
struct Escaped<'a>(&'a Path);

impl fmt::Display for Escaped<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in self.0.display().to_string().chars() {
            if c.is_control() {
                write!(f, "{}", c.escape_default())?;
            } else {
                fmt::Write::write_char(f, c)?;
            }
        }
        Ok(())
    }
}

impl std::error::Error for MeshFileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            ErrorKind::Io(e) => Some(e),
            ErrorKind::Topology { error, .. } => Some(error),
            _ => None,
        }
    }
}
