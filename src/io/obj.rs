//! Wavefront OBJ: `v` and `f` statements.
//!
//! Reading keeps `v x y z` (further values, such as `w` or vertex colours, are ignored) and
//! `f` with corners written `i`, `i/t`, `i//n` or `i/t/n`; texture and normal indices are
//! ignored. Indices are 1-based; a negative index counts back from the last vertex defined
//! before the face (`-1` is that vertex), as the OBJ specification says. A positive index
//! may refer to a vertex defined later in the file. Every other statement (`vt`, `vn`, `g`,
//! `o`, `s`, `usemtl`, `mtllib`, `l`, ...), comments (`#` to the end of the line) and blank
//! lines are ignored; a line ending in `\` continues on the next one.
//!
//! Writing emits a comment line, one `v` line per live vertex (coordinates in their shortest
//! form that reads back to the same `f64`) and one `f` line per live face, 1-based.
//!
//! ```
//! use zipmesh::io::obj;
//! let src = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2/2/2 3/3/3 -1//4\n";
//! let (mesh, _) = obj::parse(src).unwrap();
//! let mut corners = mesh.polygons().remove(0);
//! corners.sort();
//! assert_eq!(corners, vec![0, 1, 2, 3]);
//! ```

use super::lex::{
    bad_number, for_each_line, out_of_range, parse_int, parse_position, text, Tokens,
};
use super::soup::Soup;
use super::write::{live_vertices, write_face, Coord};
use super::{ErrorKind, Format, MeshFileError};
use crate::map::BuildReport;
use crate::mesh::Mesh;
use std::io::{self, Write};

/// Parses OBJ text. Never panics; see the [module documentation](self) for what is read.
///
/// ```
/// use zipmesh::io::{obj, ErrorKind};
/// let (mesh, report) = obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n").unwrap();
/// assert_eq!(mesh.map.num_vertices(), 3);
/// assert_eq!(report.unreferenced.len(), 1); // vertex 4, kept as a dead slot
/// let err = obj::parse("v 0 0 0\nf 1 2 3\n").unwrap_err();
/// assert!(matches!(err.kind(), ErrorKind::IndexOutOfRange { index: 2, vertices: 1, .. }));
/// ```
pub fn parse(src: &str) -> Result<(Mesh, BuildReport), MeshFileError> {
    parse_bytes(src.as_bytes())
}

/// Parses OBJ from bytes (comments need not be UTF-8). Never panics.
///
/// A UTF-8 byte-order mark is skipped; lines may end in `\n`, `\r\n` or a bare `\r`.
/// Bytes that are not text (a UTF-16 byte-order mark, NUL or other control bytes) are
/// [`ErrorKind::NotText`]; content without one `v` or `f`
/// statement is [`ErrorKind::NoMeshData`]; an empty or
/// comment-only file is an empty mesh.
///
/// ```
/// use zipmesh::io::{obj::parse_bytes, ErrorKind};
/// let (mesh, _) = parse_bytes(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n").unwrap();
/// assert_eq!(mesh.map.num_faces(), 1);
/// let (mesh, _) = parse_bytes(b"\xEF\xBB\xBFv 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r").unwrap();
/// assert_eq!(mesh.polygons(), vec![vec![0, 1, 2]]);
/// let e = parse_bytes(b"\xFF\xFEv\x00 \x000\x00").unwrap_err();
/// assert!(matches!(e.kind(), ErrorKind::NotText { byte: None }));
/// let e = parse_bytes(b"hello world\n").unwrap_err();
/// assert!(matches!(e.kind(), ErrorKind::NoMeshData { .. }));
/// assert_eq!(parse_bytes(b"# nothing yet\n").unwrap().0.map.num_faces(), 0);
/// ```
pub fn parse_bytes(src: &[u8]) -> Result<(Mesh, BuildReport), MeshFileError> {
    let src = text(src)?;
    let mut soup = Soup::new();
    let mut content = None;
    for_each_line(src, true, |no, line| {
        let mut toks = Tokens(line);
        let first = toks.next();
        content = content.or(first.map(|_| no));
        match first {
            Some(b"v") => {
                let p = parse_position(&mut toks, no)?;
                soup.positions.push(p);
            }
            Some(b"f") => {
                let defined = soup.positions.len();
                for tok in toks {
                    let idx = tok.split(|&b| b == b'/').next().unwrap_or(tok);
                    let i = parse_int(idx).ok_or_else(|| bad_number(no, "a vertex index", tok))?;
                    // Positive: 1-based (range checked once all vertices are known);
                    // negative: relative to the vertices defined so far.
                    let zero_based = if i > 0 { i - 1 } else { defined as i64 + i };
                    if i == 0 || zero_based < 0 || zero_based >= i64::from(u32::MAX) - 1 {
                        return Err(out_of_range(no, i, idx, defined, Format::Obj));
                    }
                    soup.corners.push(zero_based as u32);
                }
                soup.end_face(no)?;
            }
            _ => {}
        }
        Ok(())
    })?;
    if let (Some(line), true) = (
        content,
        soup.positions.is_empty() && soup.face_lines.is_empty(),
    ) {
        let kind = ErrorKind::NoMeshData {
            format: Format::Obj,
        };
        return Err(MeshFileError::new(Some(line), kind));
    }
    soup.finish(Format::Obj)
}

/// Writes `mesh` as OBJ: dead slots are dropped and live vertices renumbered in slot order.
/// Each face is written from its recorded dart, as in [`Mesh::polygons`] (a cyclic
/// rotation of the corners a file gave).
///
/// Fails with `InvalidData`, before writing anything, if a position is not finite (the
/// reader would refuse it).
///
/// ```
/// use zipmesh::{gen, io::obj};
/// let mut out = Vec::new();
/// obj::write(&gen::grid(1, 1), &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains("v 1 1 0\n"));
/// assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 1);
/// ```
pub fn write<W: Write>(mesh: &Mesh, mut w: W) -> io::Result<()> {
    let (new_index, positions) = live_vertices(mesh)?;
    writeln!(
        w,
        "# zipmesh: {} vertices, {} faces",
        positions.len(),
        mesh.map.num_faces()
    )?;
    for p in &positions {
        writeln!(w, "v {} {} {}", Coord(p.x), Coord(p.y), Coord(p.z))?;
    }
    for f in mesh.map.faces() {
        w.write_all(b"f")?;
        write_face(&mut w, mesh, f, &new_index, 1)?;
    }
    w.flush()
}
