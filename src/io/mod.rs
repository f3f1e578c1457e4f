//! Mesh files (OBJ and OFF): reading with errors that name the line, atomic writing.
//!
//! * [`read_mesh`] and [`write_mesh`] choose the format by the file name's extension
//!   (`.obj` or `.off`, any case).
//! * [`obj::parse`], [`off::parse`] (and their `parse_bytes` forms) read from memory and never
//!   panic, whatever the input; [`obj::write`] and [`off::write`] write to any `std::io::Write`.
//! * Every error is a [`MeshFileError`]: the file's path when known, the 1-based line, and a
//!   typed [`ErrorKind`]. Its `Display` reads `path:LINE: problem`. Topology defects found
//!   by [`Map::from_polygons_with_report`](crate::Map::from_polygons_with_report) are traced
//!   back to the line of the offending face.
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

pub mod obj;
pub mod off;

use crate::map::{BuildError, BuildReport};
use crate::mesh::Mesh;
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt;
use glam::DVec3;
use std::fs;
use std::io::{self, BufWriter, Write};
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

    fn io(path: &Path, e: io::Error) -> Self {
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
}

impl Format {
    /// The format named by the extension of `path` (`.obj` or `.off`, any case).
    ///
    /// ```
    /// use zipmesh::io::Format;
    /// assert_eq!(Format::from_path("bunny.OBJ"), Some(Format::Obj));
    /// assert_eq!(Format::from_path("cube.off"), Some(Format::Off));
    /// assert_eq!(Format::from_path("notes.txt"), None);
    /// ```
    pub fn from_path(path: impl AsRef<Path>) -> Option<Format> {
        let ext = path.as_ref().extension()?.to_str()?;
        if ext.eq_ignore_ascii_case("obj") {
            Some(Format::Obj)
        } else if ext.eq_ignore_ascii_case("off") {
            Some(Format::Off)
        } else {
            None
        }
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
        }
    }
}

/// Reads a mesh file, choosing the format by the extension (see [`Format::from_path`]).
///
/// Returns the mesh and the build report (unreferenced vertices are kept as dead slots).
/// Errors carry `path` and, for defects in the file, the line.
///
/// ```
/// use zipmesh::{gen, io};
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-read-{}.off", std::process::id()));
/// io::write_mesh(&path, &gen::cube(2)).unwrap();
/// let (mesh, report) = io::read_mesh(&path).unwrap();
/// assert_eq!(mesh.map.num_faces(), 24);
/// assert!(report.unreferenced.is_empty());
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn read_mesh(path: impl AsRef<Path>) -> Result<(Mesh, BuildReport), MeshFileError> {
    let path = path.as_ref();
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

/// Writes a file atomically: `fill` writes into a new temporary file in the directory of
/// `path`, which is flushed, synced and then renamed onto `path`.
///
/// If creating, filling, syncing or renaming fails, the temporary file is removed and the
/// error returned; an existing file at `path` is left as it was, and nothing is created.
///
/// ```
/// use std::io::Write;
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-atomic-{}.txt", std::process::id()));
/// zipmesh::io::write_atomic(&path, |w| w.write_all(b"hello")).unwrap();
/// let failed = zipmesh::io::write_atomic(&path, |w| {
///     w.write_all(b"partial")?;
///     Err(std::io::Error::other("stop"))
/// });
/// assert!(failed.is_err());
/// assert_eq!(std::fs::read(&path).unwrap(), b"hello");
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn write_atomic<F>(path: impl AsRef<Path>, fill: F) -> Result<(), MeshFileError>
where
    F: FnOnce(&mut BufWriter<fs::File>) -> io::Result<()>,
{
    let path = path.as_ref();
    let err = |e| MeshFileError::io(path, e);
    let name = path
        .file_name()
        .ok_or_else(|| err(io::Error::new(io::ErrorKind::InvalidInput, "no file name")))?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let (file, tmp) = create_temp(dir, name).map_err(err)?;
    let guard = TempGuard(Some(tmp));
    let mut w = BufWriter::with_capacity(1 << 16, file);
    fill(&mut w).map_err(err)?;
    let file = w.into_inner().map_err(|e| err(e.into_error()))?;
    file.sync_all().map_err(err)?;
    drop(file);
    let tmp = guard.path();
    fs::rename(tmp, path).map_err(err)?;
    guard.disarm();
    Ok(())
}

/// Creates a fresh temporary file next to the target: `.NAME.PID.N.tmp`.
fn create_temp(dir: &Path, name: &std::ffi::OsStr) -> io::Result<(fs::File, PathBuf)> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut last = None;
    for _ in 0..16 {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".{}.{n}.tmp", std::process::id()));
        let tmp = dir.join(tmp_name);
        match fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(f) => return Ok((f, tmp)),
            // A stale file of a crashed run with the same pid: try the next number.
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| io::Error::other("no temporary file name available")))
}

/// Removes the temporary file when dropped, unless it was renamed into place.
struct TempGuard(Option<PathBuf>);

impl TempGuard {
    fn path(&self) -> &Path {
        self.0.as_deref().unwrap_or(Path::new(""))
    }

    fn disarm(mut self) {
        self.0 = None;
    }
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            let _ = fs::remove_file(p);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Shared by the readers and writers.

/// Polygons as parsed, with the line of every face, before the topology is built.
#[derive(Default)]
struct Soup {
    positions: Vec<DVec3>,
    corners: Vec<u32>,
    offsets: Vec<u32>,
    face_lines: Vec<u32>,
}

/// The builder needs fewer than 2^31 corners; checked while parsing so offsets fit in u32.
const MAX_CORNERS: usize = (u32::MAX / 2 - 1) as usize;

impl Soup {
    fn new() -> Self {
        Soup {
            offsets: alloc::vec![0],
            ..Soup::default()
        }
    }

    /// Closes the face whose corners were pushed since the last call.
    fn end_face(&mut self, line: usize) -> Result<(), MeshFileError> {
        if self.corners.len() > MAX_CORNERS {
            return Err(MeshFileError::new(Some(line), ErrorKind::TooLarge));
        }
        self.offsets.push(self.corners.len() as u32);
        self.face_lines
            .push(u32::try_from(line).unwrap_or(u32::MAX));
        Ok(())
    }

    /// Builds the map; `base` is the file's number of the first vertex (1 for OBJ).
    fn finish(self, base: u64) -> Result<(Mesh, BuildReport), MeshFileError> {
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
            Err(e) => Err(self.locate(&e, base)),
        }
    }

    fn line_of(&self, face: usize) -> usize {
        self.face_lines.get(face).map_or(0, |&l| l as usize)
    }

    /// Turns a build error into a file error at the line of its face.
    fn locate(&self, e: &BuildError, base: u64) -> MeshFileError {
        let v = |x: u32| u64::from(x) + base;
        let kind = match *e {
            BuildError::FaceTooSmall { corners, .. } => ErrorKind::FaceTooSmall { corners },
            BuildError::RepeatedCorner { vertex, .. } => {
                ErrorKind::RepeatedCorner { vertex: v(vertex) }
            }
            BuildError::IndexOutOfRange {
                vertex, n_vertices, ..
            } => ErrorKind::IndexOutOfRange {
                index: v(vertex) as i64,
                vertices: n_vertices,
            },
            BuildError::NonManifoldEdge { a, b, faces } => ErrorKind::NonManifoldEdge {
                a: v(a),
                b: v(b),
                lines: faces.map(|f| self.line_of(f)),
            },
            BuildError::InconsistentOrientation { a, b, faces } => {
                ErrorKind::InconsistentOrientation {
                    a: v(a),
                    b: v(b),
                    lines: faces.map(|f| self.line_of(f)),
                }
            }
            BuildError::NonManifoldVertex { vertex, .. } => {
                ErrorKind::NonManifoldVertex { vertex: v(vertex) }
            }
            BuildError::TooLarge { .. } => ErrorKind::TooLarge,
        };
        MeshFileError::new(e.face().map(|f| self.line_of(f)), kind)
    }
}

/// Calls `f(line_number, line)` for every line of `src`, without the line break, the
/// comment (from `#`) and with OBJ-style continuations (a trailing `\`) joined; the number
/// is that of the first physical line. Allocates only for continued lines.
fn for_each_line<F>(src: &[u8], continuation: bool, mut f: F) -> Result<(), MeshFileError>
where
    F: FnMut(usize, &[u8]) -> Result<(), MeshFileError>,
{
    let mut joined: Vec<u8> = Vec::new();
    let mut joined_start = 0;
    for (i, raw) in src.split(|&b| b == b'\n').enumerate() {
        let mut line = raw.strip_suffix(b"\r").unwrap_or(raw);
        if let Some(h) = line.iter().position(|&b| b == b'#') {
            line = &line[..h];
        }
        let trimmed = trim_end(line);
        if continuation && trimmed.last() == Some(&b'\\') {
            if joined.is_empty() {
                joined_start = i + 1;
            }
            joined.extend_from_slice(&trimmed[..trimmed.len() - 1]);
            joined.push(b' ');
            continue;
        }
        if joined.is_empty() {
            f(i + 1, line)?;
        } else {
            joined.extend_from_slice(line);
            f(joined_start, &joined)?;
            joined.clear();
        }
    }
    if !joined.is_empty() {
        f(joined_start, &joined)?;
    }
    Ok(())
}

fn trim_end(mut s: &[u8]) -> &[u8] {
    while let [rest @ .., last] = s {
        if last.is_ascii_whitespace() {
            s = rest;
        } else {
            break;
        }
    }
    s
}

/// Whitespace-separated tokens of a line.
struct Tokens<'a>(&'a [u8]);

impl<'a> Iterator for Tokens<'a> {
    type Item = &'a [u8];

    #[inline]
    fn next(&mut self) -> Option<&'a [u8]> {
        let s = self.0;
        let start = s.iter().position(|b| !b.is_ascii_whitespace())?;
        let len = s[start..]
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(s.len() - start);
        self.0 = &s[start + len..];
        Some(&s[start..start + len])
    }
}

fn bad_number(line: usize, expected: &'static str, tok: &[u8]) -> MeshFileError {
    let cut = &tok[..tok.len().min(40)];
    MeshFileError::new(
        Some(line),
        ErrorKind::BadNumber {
            expected,
            found: String::from_utf8_lossy(cut).into_owned(),
        },
    )
}

fn missing_number(line: usize, expected: &'static str) -> MeshFileError {
    MeshFileError::new(Some(line), ErrorKind::MissingNumber { expected })
}

/// A finite coordinate.
#[inline]
fn parse_coord(tok: Option<&[u8]>, line: usize) -> Result<f64, MeshFileError> {
    const WHAT: &str = "a vertex coordinate (a finite number)";
    let tok = tok.ok_or_else(|| missing_number(line, WHAT))?;
    core::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .filter(|x| x.is_finite())
        .ok_or_else(|| bad_number(line, WHAT, tok))
}

/// Three coordinates from the next tokens (anything after them is left unread).
#[inline]
fn parse_position(toks: &mut Tokens<'_>, line: usize) -> Result<DVec3, MeshFileError> {
    let x = parse_coord(toks.next(), line)?;
    let y = parse_coord(toks.next(), line)?;
    let z = parse_coord(toks.next(), line)?;
    Ok(DVec3::new(x, y, z))
}

/// A decimal integer with optional sign; values beyond 10^18 saturate (they are out of
/// range for any index anyway). `None` if `tok` is not an integer.
#[inline]
fn parse_int(tok: &[u8]) -> Option<i64> {
    let (neg, digits) = match tok.first() {
        Some(b'-') => (true, &tok[1..]),
        Some(b'+') => (false, &tok[1..]),
        _ => (false, tok),
    };
    if digits.is_empty() {
        return None;
    }
    let mut n: i64 = 0;
    for &b in digits {
        if !b.is_ascii_digit() {
            return None;
        }
        n = n.saturating_mul(10).saturating_add(i64::from(b - b'0'));
    }
    n = n.min(1_000_000_000_000_000_000);
    Some(if neg { -n } else { n })
}

/// Shortest round-trip text of a coordinate; exponent form for very small or large values
/// so that no coordinate needs hundreds of digits.
struct Coord(f64);

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
fn live_vertices(mesh: &Mesh) -> io::Result<(Vec<u32>, Vec<DVec3>)> {
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
fn write_face<W: Write>(
    w: &mut W,
    mesh: &Mesh,
    f: crate::map::Face,
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
