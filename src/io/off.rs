//! Object File Format (OFF), ASCII.
//!
//! Layout: a header line `OFF` (the variants `COFF`, `NOFF`, `CNOFF`, `STOFF` ... are
//! accepted, their extra per-vertex values ignored), then `nv nf [ne]` (on the header line
//! or the next one; `ne` is ignored), then `nv` vertex lines `x y z ...` and `nf` face lines
//! `k i0 ... ik-1 ...` with 0-based indices; values after the `k` indices (face colours) are
//! ignored. Comments run from `#` to the end of the line; blank lines are skipped. Each
//! vertex and face is on its own line, as every common writer does, so that errors can
//! name the line. The binary variant and `4OFF`/`nOFF` are not read.
//!
//! Writing emits `OFF`, the counts (with the true edge count), one line per live vertex and
//! one per live face.
//!
//! ```
//! use zipmesh::io::off;
//! let src = "OFF\n# a triangle\n3 1 3\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n";
//! let (mesh, _) = off::parse(src).unwrap();
//! assert_eq!(mesh.polygons().len(), 1);
//! ```

use super::lex::{
    bad_number, for_each_line, missing_number, out_of_range, parse_int, parse_position, text,
    Tokens,
};
use super::soup::Soup;
use super::write::{live_vertices, write_face, Coord};
use super::{ErrorKind, Format, MeshFileError};
use crate::map::BuildReport;
use crate::mesh::Mesh;
use std::io::{self, Write};

enum Stage {
    Header,
    Counts,
    Body,
}

/// Parses OFF text. Never panics; see the [module documentation](self) for the layout.
///
/// ```
/// use zipmesh::io::{off, ErrorKind};
/// let err = off::parse("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n").unwrap_err();
/// assert!(matches!(err.kind(), ErrorKind::CountsMismatch { what: "faces", declared: 1, found: 0 }));
/// assert_eq!(err.line(), Some(2)); // the line that declares the counts
/// ```
pub fn parse(src: &str) -> Result<(Mesh, BuildReport), MeshFileError> {
    parse_bytes(src.as_bytes())
}

/// Parses OFF from bytes (comments need not be UTF-8). Never panics.
///
/// As for OBJ, a UTF-8 byte-order mark is skipped, lines may end in `\n`, `\r\n` or a
/// bare `\r`, and bytes that are not text are [`ErrorKind::NotText`]. A header declaring
/// more vertices than the body has (so that face lines would be read as vertices) is a
/// vertex [`ErrorKind::CountsMismatch`].
///
/// ```
/// use zipmesh::io::{off::parse_bytes, ErrorKind};
/// let src = b"OFF 4 2 5\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
/// let (mesh, _) = parse_bytes(src).unwrap();
/// assert_eq!(mesh.map.num_edges(), 5);
/// let e = parse_bytes(b"OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n").unwrap_err();
/// assert!(matches!(e.kind(), ErrorKind::CountsMismatch { what: "vertices", declared: 5, found: 4 }));
/// ```
pub fn parse_bytes(src: &[u8]) -> Result<(Mesh, BuildReport), MeshFileError> {
    let src = text(src)?;
    let mut soup = Soup::new();
    let mut stage = Stage::Header;
    let mut shape = VertexShape::default();
    let (mut nv, mut nf, mut counts_line) = (0usize, 0usize, 0usize);
    let mut faces_read = 0usize;
    for_each_line(src, false, |no, line| {
        let mut toks = Tokens(line);
        let Some(first) = toks.next() else {
            return Ok(());
        };
        match stage {
            Stage::Header => {
                if !is_header(first) {
                    return Err(MeshFileError::new(Some(no), ErrorKind::MissingHeader));
                }
                stage = Stage::Counts;
                // The counts may follow the keyword on the same line.
                match toks.next() {
                    None => Ok(()),
                    Some(tok) => {
                        read_counts(tok, toks, no, &mut nv, &mut nf, &mut soup, src.len())?;
                        counts_line = no;
                        stage = Stage::Body;
                        Ok(())
                    }
                }
            }
            Stage::Counts => {
                read_counts(first, toks, no, &mut nv, &mut nf, &mut soup, src.len())?;
                counts_line = no;
                stage = Stage::Body;
                Ok(())
            }
            Stage::Body if soup.positions.len() < nv => {
                shape.see(line, soup.positions.len());
                let mut toks = Tokens(line);
                soup.positions.push(parse_position(&mut toks, no)?);
                Ok(())
            }
            Stage::Body if faces_read < nf => {
                read_face(first, toks, no, nv, &mut soup)?;
                faces_read += 1;
                Ok(())
            }
            Stage::Body => Err(MeshFileError::new(
                Some(no),
                ErrorKind::ExtraData { declared_faces: nf },
            )),
        }
    })?;
    let missing = |what, declared, found| {
        MeshFileError::new(
            Some(counts_line),
            ErrorKind::CountsMismatch {
                what,
                declared,
                found,
            },
        )
    };
    match stage {
        Stage::Header => Err(MeshFileError::new(None, ErrorKind::MissingHeader)),
        Stage::Counts => Err(MeshFileError::new(
            None,
            ErrorKind::MissingNumber {
                expected: "the vertex and face counts",
            },
        )),
        Stage::Body if soup.positions.len() < nv => {
            Err(missing("vertices", nv, soup.positions.len()))
        }
        // Faces read as vertices: the header promises more vertices than the body has.
        Stage::Body if faces_read < nf => match shape.first_face {
            Some(found) => Err(missing("vertices", nv, found)),
            None => Err(missing("faces", nf, faces_read)),
        },
        Stage::Body => soup.finish(Format::Off),
    }
}

/// `OFF` with optional prefixes for per-vertex extras (texture, colour, normal).
/// Where the vertex lines stop looking like the first one and start looking like faces
/// (`k i0 .. ik-1`, integers only, k >= 3), which is what a header declaring too many
/// vertices makes the reader take as vertices.
#[derive(Default)]
struct VertexShape {
    tokens: usize,
    first_face: Option<usize>,
}

impl VertexShape {
    fn see(&mut self, line: &[u8], index: usize) {
        let count = Tokens(line).count();
        if index == 0 {
            self.tokens = count;
        } else if count != self.tokens && self.first_face.is_none() && looks_like_face(line) {
            self.first_face = Some(index);
        }
    }
}

fn looks_like_face(line: &[u8]) -> bool {
    let mut toks = Tokens(line);
    let k = toks.next().and_then(parse_int).unwrap_or(0);
    let rest: Option<usize> = toks.map(|t| parse_int(t).map(|_| 1)).sum();
    k >= 3 && rest.is_some_and(|n| n as i64 >= k)
}

fn is_header(tok: &[u8]) -> bool {
    tok.strip_suffix(b"OFF")
        .is_some_and(|p| p.iter().all(|b| b"STCN".contains(b)))
}

/// Reads a face line `k i0 ... ik-1 ...` whose first token is `first`; indices are checked
/// here because OFF's are 0-based and the vertex count is known from the header.
fn read_face(
    first: &[u8],
    mut toks: Tokens<'_>,
    no: usize,
    nv: usize,
    soup: &mut Soup,
) -> Result<(), MeshFileError> {
    const K: &str = "a corner count";
    const I: &str = "a vertex index";
    let k = parse_int(first)
        .filter(|&k| k >= 0)
        .ok_or_else(|| bad_number(no, K, first))? as usize;
    for _ in 0..k {
        let tok = toks.next().ok_or_else(|| missing_number(no, I))?;
        let i = parse_int(tok).ok_or_else(|| bad_number(no, I, tok))?;
        if i < 0 || i as usize >= nv {
            return Err(out_of_range(no, i, tok, nv, Format::Off));
        }
        soup.corners.push(i as u32);
    }
    soup.end_face(no)
}

/// Reads `nv nf [ne]` starting at token `first`; reserves memory no larger than the
/// file could fill, so a lying header cannot exhaust memory.
fn read_counts(
    first: &[u8],
    mut toks: Tokens<'_>,
    no: usize,
    nv: &mut usize,
    nf: &mut usize,
    soup: &mut Soup,
    src_len: usize,
) -> Result<(), MeshFileError> {
    const V: &str = "the number of vertices";
    const F: &str = "the number of faces";
    let count = |tok: &[u8], what| {
        parse_int(tok)
            .filter(|&n| n >= 0)
            .map(|n| n as usize)
            .ok_or_else(|| bad_number(no, what, tok))
    };
    *nv = count(first, V)?;
    let tok = toks.next().ok_or_else(|| missing_number(no, F))?;
    *nf = count(tok, F)?;
    if let Some(tok) = toks.next() {
        count(tok, "the number of edges")?;
    }
    if *nv >= u32::MAX as usize - 1 {
        return Err(MeshFileError::new(Some(no), ErrorKind::TooLarge));
    }
    soup.positions.reserve((*nv).min(src_len / 6));
    soup.offsets.reserve((*nf).min(src_len / 8));
    soup.face_lines.reserve((*nf).min(src_len / 8));
    Ok(())
}

/// Writes `mesh` as OFF: dead slots are dropped and live vertices renumbered in slot order.
/// Each face is written from its recorded dart, as in [`Mesh::polygons`].
///
/// Fails with `InvalidData`, before writing anything, if a position is not finite.
///
/// ```
/// use zipmesh::{gen, io::off};
/// let mut out = Vec::new();
/// off::write(&gen::grid(2, 1), &mut out).unwrap();
/// assert!(String::from_utf8(out).unwrap().starts_with("OFF\n6 2 7\n"));
/// ```
pub fn write<W: Write>(mesh: &Mesh, mut w: W) -> io::Result<()> {
    let (new_index, positions) = live_vertices(mesh)?;
    writeln!(
        w,
        "OFF\n{} {} {}",
        positions.len(),
        mesh.map.num_faces(),
        mesh.map.num_edges()
    )?;
    for p in &positions {
        writeln!(w, "{} {} {}", Coord(p.x), Coord(p.y), Coord(p.z))?;
    }
    for f in mesh.map.faces() {
        write!(w, "{}", mesh.map.degree(f))?;
        write_face(&mut w, mesh, f, &new_index, 0)?;
    }
    w.flush()
}
