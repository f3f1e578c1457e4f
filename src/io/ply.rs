//! Stanford PLY: ASCII and binary (little- and big-endian) reading; binary little-endian and
//! ASCII writing.
//!
//! Layout: the header lines `ply`, `format ascii|binary_little_endian|binary_big_endian 1.0`,
//! any `comment` and `obj_info` lines, then for each element `element NAME COUNT` and its
//! properties, `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`, and
//! `end_header`; then each element's instances, in the header's order. The types are
//! `char uchar short ushort int uint float double` and their sized names (`int8` ... `float64`).
//!
//! Read: the `vertex` element's `x`, `y`, `z` (any scalar type) and the `face` element's
//! `vertex_indices` or `vertex_index` list (any integer types), 0-based; every other property
//! and element (colours, normals, `edge`, `material` ...) is skipped by its declared type. In
//! ASCII each instance is one line. Errors in the header or in ASCII data name the line;
//! errors in binary data name the element, the instance (0-based) and the byte offset where
//! that instance starts ([`MeshFileError::byte`]); topology defects of a binary file name the
//! faces (0-based). Nothing after the last element but white space is accepted.
//!
//! Written: `binary_little_endian` ([`write()`], what `.ply` files get) or `ascii`
//! ([`write_ascii`]), with `double x y z` and `list uchar int vertex_indices`, so positions
//! round-trip bit for bit. A face of more than 255 corners cannot be written that way and is
//! refused (`InvalidData`) before anything is written.
//!
//! ```
//! use zipmesh::{gen, io::ply};
//! let mut bytes = Vec::new();
//! ply::write(&gen::cube(2), &mut bytes).unwrap();
//! let (cube, _) = ply::parse_bytes(&bytes).unwrap();
//! assert_eq!(cube.map.num_faces(), 24);
//! let src = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
//!            property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
//!            end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
//! let (tri, _) = ply::parse_bytes(src.as_bytes()).unwrap();
//! assert_eq!(tri.polygons(), vec![vec![0, 1, 2]]);
//! ```

use super::lex::{parse_int, Tokens};
use super::soup::Soup;
use super::write::{live_vertices, Coord};
use super::{ErrorKind, Format, MeshFileError};
use crate::map::BuildReport;
use crate::mesh::Mesh;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use glam::DVec3;
use std::io::{self, Write};

/// A scalar type of the header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_int(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The value stored in `b` (exactly `size()` bytes) in this type.
    fn read(self, b: &[u8], big: bool) -> f64 {
        let mut a = [0u8; 8];
        a[..b.len()].copy_from_slice(b);
        if big {
            a[..b.len()].reverse();
        }
        match self {
            Scalar::I8 => f64::from(a[0] as i8),
            Scalar::U8 => f64::from(a[0]),
            Scalar::I16 => f64::from(i16::from_le_bytes([a[0], a[1]])),
            Scalar::U16 => f64::from(u16::from_le_bytes([a[0], a[1]])),
            Scalar::I32 => f64::from(i32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            Scalar::U32 => f64::from(u32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            Scalar::F32 => f64::from(f32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            Scalar::F64 => f64::from_le_bytes(a),
        }
    }
}

/// A property: one scalar, or a list (its count's type and its items' type).
#[derive(Clone, Copy, Debug)]
enum Prop {
    One(Scalar),
    List(Scalar, Scalar),
}

/// What the reader does with a property.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Skip,
    Coord(usize),
    Corners,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    props: Vec<(Prop, Role)>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// The byte where the data starts, and the 1-based line it is on.
    body: usize,
    body_line: usize,
}

/// A header error at `line`.
fn bad_header(line: usize, problem: impl Into<String>) -> MeshFileError {
    MeshFileError::new(
        Some(line),
        ErrorKind::BadHeader {
            problem: problem.into(),
        },
    )
}

/// A header line with its 1-based number.
type Line<'a> = (usize, &'a [u8]);

/// The header's lines, with their numbers, and the byte after `end_header`'s line end.
fn header_lines(src: &[u8]) -> Result<(Vec<Line<'_>>, usize), MeshFileError> {
    let mut lines = Vec::new();
    let mut at = 0;
    while at < src.len() {
        let end = src[at..].iter().position(|&b| b == b'\n');
        let (line, next) = match end {
            Some(i) => (&src[at..at + i], at + i + 1),
            None => (&src[at..], src.len()),
        };
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        if let Some(&b) = line
            .iter()
            .find(|&&b| b >= 0x80 || (b < 0x20 && b != b'\t'))
        {
            let kind = ErrorKind::NotText { byte: Some(b) };
            return Err(MeshFileError::new(Some(lines.len() + 1), kind));
        }
        lines.push((lines.len() + 1, line));
        at = next;
        if Tokens(line).next() == Some(b"end_header") {
            return Ok((lines, at));
        }
    }
    Err(bad_header(lines.len().max(1), "no `end_header` line"))
}

/// Parses the header (see the [module documentation](self)).
fn header(src: &[u8]) -> Result<Header, MeshFileError> {
    if !src.starts_with(b"ply") || !matches!(src.get(3), Some(b'\n' | b'\r')) {
        return Err(bad_header(
            1,
            "the file does not start with `ply`: not a PLY file",
        ));
    }
    let (lines, body) = header_lines(src)?;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    for &(no, line) in &lines[1..] {
        let mut t = Tokens(line);
        match t.next() {
            None | Some(b"comment" | b"obj_info" | b"end_header") => {}
            Some(b"format") => encoding = Some(format_line(t, no)?),
            Some(b"element") => elements.push(element_line(t, no, src.len())?),
            Some(b"property") => {
                let e = elements
                    .last_mut()
                    .ok_or_else(|| bad_header(no, "a property before any element"))?;
                e.props.push(property_line(t, no, &e.name)?);
            }
            Some(w) => {
                let w = String::from_utf8_lossy(w);
                return Err(bad_header(no, alloc::format!("unknown keyword `{w}`")));
            }
        }
    }
    let encoding = encoding.ok_or_else(|| bad_header(1, "no `format` line"))?;
    check_roles(&elements, lines.len())?;
    Ok(Header {
        encoding,
        elements,
        body,
        body_line: lines.len() + 1,
    })
}

fn format_line(mut t: Tokens<'_>, no: usize) -> Result<Encoding, MeshFileError> {
    let encoding = match t.next() {
        Some(b"ascii") => Encoding::Ascii,
        Some(b"binary_little_endian") => Encoding::Little,
        Some(b"binary_big_endian") => Encoding::Big,
        other => {
            let found = String::from_utf8_lossy(other.unwrap_or_default()).into_owned();
            return Err(bad_header(no, alloc::format!("unknown format `{found}`")));
        }
    };
    match t.next() {
        Some(b"1.0" | b"1") => Ok(encoding),
        v => {
            let v = String::from_utf8_lossy(v.unwrap_or_default()).into_owned();
            Err(bad_header(
                no,
                alloc::format!("unknown version `{v}` (1.0 is read)"),
            ))
        }
    }
}

fn element_line(mut t: Tokens<'_>, no: usize, len: usize) -> Result<Element, MeshFileError> {
    let name = t
        .next()
        .ok_or_else(|| bad_header(no, "an element without a name"))?;
    let count = t
        .next()
        .and_then(parse_int)
        .filter(|&n| n >= 0)
        .ok_or_else(|| bad_header(no, "an element without a count"))? as usize;
    let name = String::from_utf8_lossy(name).into_owned();
    // Each instance takes at least one byte (binary) or two (ASCII): more cannot be there.
    if (name == "vertex" || name == "face") && count > len {
        let problem = alloc::format!("{count} {name} instances in a file of {len} bytes");
        return Err(bad_header(no, problem));
    }
    Ok(Element {
        name,
        count,
        props: Vec::new(),
    })
}

fn property_line(
    mut t: Tokens<'_>,
    no: usize,
    element: &str,
) -> Result<(Prop, Role), MeshFileError> {
    let scalar = |t: Option<&[u8]>| {
        let w = t.unwrap_or_default();
        Scalar::parse(w).ok_or_else(|| {
            let w = String::from_utf8_lossy(w);
            bad_header(no, alloc::format!("unknown property type `{w}`"))
        })
    };
    let first = t.next();
    let prop = if first == Some(b"list") {
        Prop::List(scalar(t.next())?, scalar(t.next())?)
    } else {
        Prop::One(scalar(first)?)
    };
    let name = t
        .next()
        .ok_or_else(|| bad_header(no, "a property without a name"))?;
    let role = match (element, name, prop) {
        ("vertex", b"x", Prop::One(_)) => Role::Coord(0),
        ("vertex", b"y", Prop::One(_)) => Role::Coord(1),
        ("vertex", b"z", Prop::One(_)) => Role::Coord(2),
        ("face", b"vertex_indices" | b"vertex_index", Prop::List(c, i)) => {
            if !c.is_int() || !i.is_int() {
                return Err(bad_header(no, "the face corners' list must hold integers"));
            }
            Role::Corners
        }
        _ => Role::Skip,
    };
    Ok((prop, role))
}

/// A `vertex` element with `x`, `y`, `z` once each; a `face` element, if any, with one
/// corner list.
fn check_roles(elements: &[Element], end: usize) -> Result<(), MeshFileError> {
    let vertex = elements
        .iter()
        .find(|e| e.name == "vertex")
        .ok_or_else(|| bad_header(end, "no `vertex` element"))?;
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let n = vertex
            .props
            .iter()
            .filter(|p| p.1 == Role::Coord(k))
            .count();
        if n != 1 {
            let problem =
                alloc::format!("the `vertex` element has {n} `{axis}` properties, 1 is read");
            return Err(bad_header(end, problem));
        }
    }
    if let Some(face) = elements.iter().find(|e| e.name == "face") {
        if face.props.iter().filter(|p| p.1 == Role::Corners).count() != 1 {
            let problem = "the `face` element needs one `vertex_indices` (or `vertex_index`) list";
            return Err(bad_header(end, problem));
        }
    }
    for name in ["vertex", "face"] {
        if elements.iter().filter(|e| e.name == name).count() > 1 {
            let problem = alloc::format!("the `{name}` element is declared twice");
            return Err(bad_header(end, problem));
        }
    }
    Ok(())
}

/// Parses PLY from bytes. Never panics; see the [module documentation](self).
///
/// ```
/// use zipmesh::io::{ply, ErrorKind};
/// let head = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n\
///             property float y\nproperty float z\nend_header\n";
/// let mut bytes = head.as_bytes().to_vec();
/// bytes.extend(1.5f32.to_le_bytes());
/// let e = ply::parse_bytes(&bytes).unwrap_err();
/// assert!(matches!(e.kind(), ErrorKind::Truncated { .. }));
/// assert_eq!(e.byte(), Some(head.len() as u64));
/// assert_eq!(e.to_string(), format!("byte {}: the data ends inside vertex 0 of 1: truncated", head.len()));
/// ```
pub fn parse_bytes(src: &[u8]) -> Result<(Mesh, BuildReport), MeshFileError> {
    let h = header(src)?;
    let mut soup = Soup::new();
    let nv = h
        .elements
        .iter()
        .find(|e| e.name == "vertex")
        .map_or(0, |e| e.count);
    soup.positions.reserve(nv.min(src.len()));
    let body = &src[h.body..];
    match h.encoding {
        Encoding::Ascii => ascii_body(&h, body, nv, &mut soup)?,
        Encoding::Little | Encoding::Big => binary_body(&h, body, nv, &mut soup)?,
    }
    soup.finish(Format::Ply)
}

/// Reads ASCII data: one instance per line.
fn ascii_body(h: &Header, body: &[u8], nv: usize, soup: &mut Soup) -> Result<(), MeshFileError> {
    let mut lines = body
        .split(|&b| b == b'\n')
        .enumerate()
        .map(|(i, l)| (h.body_line + i, l.strip_suffix(b"\r").unwrap_or(l)))
        .filter(|(_, l)| Tokens(l).next().is_some());
    for e in &h.elements {
        for index in 0..e.count {
            let Some((no, line)) = lines.next() else {
                let kind = ErrorKind::Truncated {
                    element: e.name.clone(),
                    index,
                    count: e.count,
                };
                return Err(MeshFileError::new(None, kind));
            };
            ascii_instance(e, Tokens(line), no, nv, soup)?;
        }
    }
    match lines.next() {
        None => Ok(()),
        Some((no, _)) => Err(MeshFileError::new(Some(no), ErrorKind::TrailingData)),
    }
}

fn ascii_instance(
    e: &Element,
    mut t: Tokens<'_>,
    no: usize,
    nv: usize,
    soup: &mut Soup,
) -> Result<(), MeshFileError> {
    let mut p = DVec3::ZERO;
    let number = |t: &mut Tokens<'_>, ty: Scalar, what: &'static str| {
        let tok = t
            .next()
            .ok_or_else(|| super::lex::missing_number(no, what))?;
        let x = if ty.is_int() {
            parse_int(tok).map(|i| i as f64)
        } else {
            core::str::from_utf8(tok)
                .ok()
                .and_then(|s| s.parse::<f64>().ok())
        };
        x.ok_or_else(|| super::lex::bad_number(no, what, tok))
    };
    for &(prop, role) in &e.props {
        match (prop, role) {
            (Prop::One(ty), Role::Coord(k)) => p[k] = number(&mut t, ty, "a vertex coordinate")?,
            (Prop::One(ty), _) => {
                number(&mut t, ty, "a property value")?;
            }
            (Prop::List(c, i), role) => {
                let n = number(&mut t, c, "a list length")?;
                if n < 0.0 {
                    return Err(super::lex::bad_number(no, "a list length", b"(negative)"));
                }
                for _ in 0..n as usize {
                    let what = if role == Role::Corners {
                        "a vertex index"
                    } else {
                        "a list item"
                    };
                    let x = number(&mut t, i, what)?;
                    if role == Role::Corners {
                        soup.corners
                            .push(corner(x, nv).ok_or_else(|| out_of_range(x, nv, Some(no)))?);
                    }
                }
            }
        }
    }
    if let Some(tok) = t.next() {
        return Err(super::lex::bad_number(no, "the end of the instance", tok));
    }
    finish_instance(e, p, soup, no as u64)
}

/// Records what an instance of `e` gave: a vertex's position, or the end of a face.
fn finish_instance(e: &Element, p: DVec3, soup: &mut Soup, at: u64) -> Result<(), MeshFileError> {
    if e.name == "vertex" {
        if !p.is_finite() {
            let kind = ErrorKind::BadNumber {
                expected: "a finite vertex coordinate",
                found: p.to_string(),
            };
            return Err(soup.error_at(at, kind));
        }
        soup.positions.push(p);
    } else if e.name == "face" {
        soup.end_face_at(at)?;
    }
    Ok(())
}

/// The vertex an index names, if it is an integer below `nv`.
fn corner(x: f64, nv: usize) -> Option<u32> {
    (x >= 0.0 && x < nv as f64 && x.fract() == 0.0).then_some(x as u32)
}

fn out_of_range(x: f64, nv: usize, line: Option<usize>) -> MeshFileError {
    let kind = ErrorKind::IndexOutOfRange {
        index: x as i64,
        written: (x as i64).to_string(),
        vertices: nv,
        format: Format::Ply,
    };
    MeshFileError::new(line, kind)
}

/// Reads binary data, element by element.
fn binary_body(h: &Header, body: &[u8], nv: usize, soup: &mut Soup) -> Result<(), MeshFileError> {
    soup.binary = true;
    let big = h.encoding == Encoding::Big;
    let mut at = 0usize;
    // An element without properties takes no bytes, whatever its count (a loop over it
    // would only spin).
    for e in h.elements.iter().filter(|e| !e.props.is_empty()) {
        for index in 0..e.count {
            let start = at;
            let byte = (h.body + start) as u64;
            let truncated = || {
                let kind = ErrorKind::Truncated {
                    element: e.name.clone(),
                    index,
                    count: e.count,
                };
                MeshFileError::new(None, kind).with_byte(byte)
            };
            let mut take = |ty: Scalar| -> Result<f64, MeshFileError> {
                let b = body.get(at..at + ty.size()).ok_or_else(truncated)?;
                at += ty.size();
                Ok(ty.read(b, big))
            };
            let mut p = DVec3::ZERO;
            for &(prop, role) in &e.props {
                match (prop, role) {
                    (Prop::One(ty), Role::Coord(k)) => p[k] = take(ty)?,
                    (Prop::One(ty), _) => {
                        take(ty)?;
                    }
                    (Prop::List(c, i), role) => {
                        let n = take(c)?;
                        if n < 0.0 {
                            let kind = ErrorKind::BadNumber {
                                expected: "a list length",
                                found: n.to_string(),
                            };
                            return Err(MeshFileError::new(None, kind).with_byte(byte));
                        }
                        for _ in 0..n as usize {
                            let x = take(i)?;
                            if role == Role::Corners {
                                let v = corner(x, nv)
                                    .ok_or_else(|| out_of_range(x, nv, None).with_byte(byte))?;
                                soup.corners.push(v);
                            }
                        }
                    }
                }
            }
            finish_instance(e, p, soup, byte)?;
        }
    }
    match body[at..].iter().position(|b| !b.is_ascii_whitespace()) {
        None => Ok(()),
        Some(k) => {
            Err(MeshFileError::new(None, ErrorKind::TrailingData)
                .with_byte((h.body + at + k) as u64))
        }
    }
}

/// The header [`write`] and [`write_ascii`] give `mesh`, with `format` (the live vertex
/// count and the face count), or `InvalidData` for a face of more than 255 corners.
fn write_header<W: Write>(w: &mut W, mesh: &Mesh, nv: usize, format: &str) -> io::Result<()> {
    if let Some(f) = mesh.map.faces().find(|&f| mesh.map.degree(f) > 255) {
        let msg = alloc::format!(
            "face {f} has {} corners; PLY's `list uchar int` holds at most 255",
            mesh.map.degree(f)
        );
        return Err(io::Error::new(io::ErrorKind::InvalidData, msg));
    }
    write!(
        w,
        "ply\nformat {format} 1.0\ncomment written by zipmesh\nelement vertex {nv}\n\
         property double x\nproperty double y\nproperty double z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        mesh.map.num_faces()
    )
}

/// Writes `mesh` as binary little-endian PLY (`double x y z`, `list uchar int
/// vertex_indices`): dead slots dropped, live vertices renumbered in slot order.
///
/// Fails with `InvalidData`, before writing anything, if a position is not finite or a face
/// has more than 255 corners.
///
/// ```
/// use zipmesh::{gen, io::ply};
/// let mut out = Vec::new();
/// ply::write(&gen::grid(1, 1), &mut out).unwrap();
/// assert!(out.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
/// // 4 vertices of 24 bytes, 1 face of 1 + 4 * 4 bytes after the header.
/// let body = out.len() - (out.windows(11).position(|w| w == b"end_header\n").unwrap() + 11);
/// assert_eq!(body, 4 * 24 + 17);
/// ```
pub fn write<W: Write>(mesh: &Mesh, mut w: W) -> io::Result<()> {
    let (new_index, positions) = live_vertices(mesh)?;
    write_header(&mut w, mesh, positions.len(), "binary_little_endian")?;
    for p in &positions {
        for x in p.to_array() {
            w.write_all(&x.to_le_bytes())?;
        }
    }
    for f in mesh.map.faces() {
        w.write_all(&[mesh.map.degree(f) as u8])?;
        for d in mesh.map.face_darts(f) {
            let i = new_index
                .get(mesh.map.origin(d).index())
                .copied()
                .unwrap_or(0);
            w.write_all(&(i as i32).to_le_bytes())?;
        }
    }
    w.flush()
}

/// Writes `mesh` as ASCII PLY, one vertex or face per line, with the same properties and
/// the same failures as [`write()`].
///
/// ```
/// use zipmesh::{gen, io::ply};
/// let mut out = Vec::new();
/// ply::write_ascii(&gen::grid(1, 1), &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.starts_with("ply\nformat ascii 1.0\n"));
/// let body: Vec<&str> = text.split("end_header\n").nth(1).unwrap().lines().collect();
/// assert_eq!(body.len(), 4 + 1); // four vertices, one face
/// assert!(body[4].starts_with("4 "));
/// ```
pub fn write_ascii<W: Write>(mesh: &Mesh, mut w: W) -> io::Result<()> {
    let (new_index, positions) = live_vertices(mesh)?;
    write_header(&mut w, mesh, positions.len(), "ascii")?;
    for p in &positions {
        writeln!(w, "{} {} {}", Coord(p.x), Coord(p.y), Coord(p.z))?;
    }
    for f in mesh.map.faces() {
        write!(w, "{}", mesh.map.degree(f))?;
        super::write::write_face(&mut w, mesh, f, &new_index, 0)?;
    }
    w.flush()
}
