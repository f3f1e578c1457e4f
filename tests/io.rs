//! Mesh files: write-read round trips, one hand-made file per error kind with its line,
//! and the atomic writer.

use glam::DVec3;
use proptest::prelude::*;
use std::fs;
use std::path::{Path, PathBuf};
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::io::{self, obj, off, ErrorKind, Format, MeshFileError};
use zipmesh::{gen, BuildError, Mesh};

/// A fresh, empty directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("io-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn dir_entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn to_bytes(format: Format, mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    format.write(mesh, &mut out).unwrap();
    out
}

/// Writes and reads back in memory; the map must be isomorphic and positions equal.
fn assert_round_trip(format: Format, mesh: &Mesh) {
    let bytes = to_bytes(format, mesh);
    let (back, report) = format.parse_bytes(&bytes).unwrap();
    assert!(report.unreferenced.is_empty());
    back.map.check().unwrap();
    assert_eq!(CanonicalCode::of(&back.map), CanonicalCode::of(&mesh.map));
    assert_eq!(back.positions, mesh.positions);
    assert_eq!(normalized(&back), normalized(mesh));
}

/// The polygons, each rotated to start at its smallest vertex: writing keeps every corner
/// cycle but may start it elsewhere (at the face's recorded dart).
fn normalized(mesh: &Mesh) -> Vec<Vec<u32>> {
    mesh.polygons()
        .into_iter()
        .map(|mut p| {
            let k = (0..p.len()).min_by_key(|&i| p[i]).unwrap_or(0);
            p.rotate_left(k);
            p
        })
        .collect()
}

const FORMATS: [Format; 3] = [Format::Obj, Format::Off, Format::Ply];

#[test]
fn generated_meshes_round_trip_in_every_format() {
    for format in FORMATS {
        for mesh in [
            gen::grid(1, 1),
            gen::grid(5, 3),
            gen::torus_grid(3, 3),
            gen::torus_grid(7, 4),
            gen::cube(1),
            gen::cube(3),
        ] {
            assert_round_trip(format, &mesh);
        }
    }
}

#[test]
fn files_round_trip_and_leave_no_temporary_file() {
    let dir = temp_dir("files");
    let mesh = gen::cube(2);
    for name in ["a.obj", "b.off", "C.OBJ", "d.ply"] {
        let path = dir.join(name);
        io::write_mesh(&path, &mesh).unwrap();
        // Writing again replaces the file.
        io::write_mesh(&path, &mesh).unwrap();
        let (back, _) = io::read_mesh(&path).unwrap();
        assert_eq!(CanonicalCode::of(&back.map), CanonicalCode::of(&mesh.map));
        assert_eq!(back.positions, mesh.positions);
    }
    assert_eq!(dir_entries(&dir), ["C.OBJ", "a.obj", "b.off", "d.ply"]);
}

#[test]
fn dead_slots_are_dropped_when_writing() {
    // Vertex 2 (file line 3) is used by no face: a dead slot after reading.
    let src = "v 0 0 0\nv 1 0 0\nv 9 9 9\nv 1 1 0\nv 0 1 0\nf 1 2 4 5\n";
    let (mesh, report) = obj::parse(src).unwrap();
    assert_eq!(report.unreferenced, vec![zipmesh::Vert::new(2)]);
    assert_eq!(mesh.positions.len(), 5, "the unreferenced position is kept");
    for format in FORMATS {
        let (back, report) = format.parse_bytes(&to_bytes(format, &mesh)).unwrap();
        assert!(report.unreferenced.is_empty());
        assert_eq!(back.map.vertex_slots(), 4);
        assert!(!back.positions.contains(&DVec3::splat(9.0)));
        assert_eq!(CanonicalCode::of(&back.map), CanonicalCode::of(&mesh.map));
    }
}

#[test]
fn extreme_coordinates_round_trip_exactly() {
    let values = [
        0.1,
        -0.0,
        1e-300,
        -5e-324,
        f64::MAX,
        f64::MIN_POSITIVE,
        1.0 / 3.0,
        123456789012345680.0,
        1e-5,
        f64::from_bits(1e16f64.to_bits() - 1), // the largest value written without exponent
    ];
    for format in FORMATS {
        for &x in &values {
            let positions = vec![
                DVec3::new(x, 0.0, 1.0),
                DVec3::new(1.0, x, 0.0),
                DVec3::new(0.0, 1.0, x),
            ];
            let (mesh, _) = Mesh::from_polygons(positions.clone(), &[[0u32, 1, 2]]).unwrap();
            let (back, _) = format.parse_bytes(&to_bytes(format, &mesh)).unwrap();
            for (a, b) in back.positions.iter().zip(&positions) {
                assert_eq!(
                    a.to_array().map(f64::to_bits),
                    b.to_array().map(f64::to_bits)
                );
            }
        }
    }
}

#[test]
fn non_finite_positions_are_refused_by_the_writer() {
    let p = vec![DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0), DVec3::Y];
    let (mesh, _) = Mesh::from_polygons(p, &[[0u32, 1, 2]]).unwrap();
    for format in FORMATS {
        let mut out = Vec::new();
        let err = format.write(&mesh, &mut out).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidData);
        assert!(out.is_empty(), "nothing is written before the check");
    }
}

#[test]
fn obj_syntax_variants_are_read() {
    // Comments, CRLF, tabs, vt/vn/g/o/s/usemtl/mtllib/l, i/t, i//n, i/t/n, negative indices,
    // a continued line, and a comment that is not UTF-8.
    let mut src = b"# hello \xff\xfe\r\nmtllib a.mtl\r\no thing\nv 0 0 0 1\nv 1 0 0\n\
vt 0 0\nvn 0 0 1\ng grp\ns off\nusemtl m\nv 1 1 0 0.5 0.5 0.5\nv 0 1\\\n 0\n\
f 1/1 2//1 3/1/1 -1 # trailing comment\nl 1 2\nv 2 0 0\n\tf\t-4 -5 -1\n"
        .to_vec();
    src.extend_from_slice(b"\n\n");
    let (mesh, report) = obj::parse_bytes(&src).unwrap();
    assert!(report.unreferenced.is_empty());
    assert_eq!(mesh.positions.len(), 5);
    assert_eq!(mesh.positions[3], DVec3::new(0.0, 1.0, 0.0));
    assert_eq!(mesh.map.num_faces(), 2);
    let mut degrees: Vec<usize> = mesh.map.faces().map(|f| mesh.map.degree(f)).collect();
    degrees.sort();
    assert_eq!(degrees, [3, 4]);
}

#[test]
fn off_syntax_variants_are_read() {
    let src = "# comment\n\nCOFF 4 2 0 # counts on the header line\n0 0 0 1 0 0 1\n1 0 0 1 0 0 1\n\
1 1 0 1 0 0 1\n0 1 0 1 0 0 1\n3 0 1 2 255 0 0\n\n3  0 2 3\n";
    let (mesh, _) = off::parse(src).unwrap();
    assert_eq!(mesh.map.num_faces(), 2);
    assert_eq!(mesh.positions[2], DVec3::new(1.0, 1.0, 0.0));
    assert!(off::parse("NOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n").is_ok());
}

// ---- Every error kind, from a small hand-made file, at its line. ----

fn obj_err(src: &str) -> MeshFileError {
    obj::parse(src).unwrap_err()
}

fn off_err(src: &str) -> MeshFileError {
    off::parse(src).unwrap_err()
}

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 2 0\n";

/// The kernel's error in a topology error, the format that numbers its vertices, and the
/// lines of its faces.
fn topology(e: &MeshFileError) -> (&BuildError, Format, &[usize]) {
    match e.kind() {
        ErrorKind::Topology {
            error,
            format,
            lines,
        } => (error, *format, lines),
        kind => panic!("not a topology error: {kind:?} ({e})"),
    }
}

#[test]
fn bad_numbers() {
    let e = obj_err("v 0 0 0\nv 0 x 0\n");
    assert_eq!(e.line(), Some(2));
    assert!(
        matches!(e.kind(), ErrorKind::BadNumber { found, .. } if found == "x"),
        "{e}"
    );
    let e = obj_err("v 0 0 0\n\nv 0 0 nan\n");
    assert_eq!(e.line(), Some(3));
    assert!(matches!(e.kind(), ErrorKind::BadNumber { .. }));
    let e = obj_err(&format!("{TRI}f 1 2/1 q/3\n"));
    assert_eq!(e.line(), Some(6));
    assert!(matches!(e.kind(), ErrorKind::BadNumber { found, .. } if found == "q/3"));
    let e = off_err("OFF\n3 one 0\n");
    assert_eq!(e.line(), Some(2));
    assert!(matches!(e.kind(), ErrorKind::BadNumber { found, .. } if found == "one"));
    let e = off_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n");
    assert_eq!(e.line(), Some(6));
    assert!(matches!(e.kind(), ErrorKind::BadNumber { .. }));
    assert!(e.to_string().contains("bad number"), "{e}");
}

#[test]
fn missing_numbers() {
    let e = obj_err("v 0 0 0\nv 1 0\n");
    assert_eq!(e.line(), Some(2));
    assert!(matches!(e.kind(), ErrorKind::MissingNumber { .. }));
    let e = off_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
    assert_eq!(e.line(), Some(6));
    assert!(matches!(e.kind(), ErrorKind::MissingNumber { .. }));
    let e = off_err("OFF\n3\n");
    assert_eq!(e.line(), Some(2));
    assert!(matches!(e.kind(), ErrorKind::MissingNumber { .. }));
}

#[test]
fn index_out_of_range() {
    // Positive beyond the last vertex: found after parsing, traced back to the face's line.
    let e = obj_err(&format!("{TRI}f 1 2 3\n\nf 1 2 6\n"));
    assert_eq!(e.line(), Some(8));
    assert!(matches!(
        e.kind(),
        ErrorKind::IndexOutOfRange {
            index: 6,
            vertices: 5,
            ..
        }
    ));
    // The message numbers the vertex from 0, as the command line does, and quotes the file.
    assert_eq!(
        e.to_string(),
        "line 8: vertex 5 (0-based; `6` in the file) is out of range for 5 vertices (0 to 4): \
         index out of range"
    );
    // Negative before the first vertex, and zero.
    let e = obj_err("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
    assert_eq!(e.line(), Some(3));
    assert!(matches!(
        e.kind(),
        ErrorKind::IndexOutOfRange {
            index: -3,
            vertices: 2,
            ..
        }
    ));
    assert!(
        e.to_string().contains("vertex index `-3` counts back"),
        "{e}"
    );
    let e = obj_err(&format!("{TRI}f 0 1 2\n"));
    assert_eq!(e.line(), Some(6));
    assert!(matches!(
        e.kind(),
        ErrorKind::IndexOutOfRange { index: 0, .. }
    ));
    assert!(e.to_string().contains("`0` is not valid in OBJ"), "{e}");
    let e = obj_err(&format!("{TRI}f 1 2 99999999999999999999999\n"));
    assert_eq!(e.line(), Some(6));
    assert!(matches!(e.kind(), ErrorKind::IndexOutOfRange { .. }));
    // Shown as written, not clamped to 10^18; a token of any length is cut for the message.
    assert!(
        e.to_string()
            .contains("vertex index `99999999999999999999999` "),
        "{e}"
    );
    let e = off_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -99999999999999999999\n");
    assert!(
        e.to_string().contains("index `-99999999999999999999` "),
        "{e}"
    );
    let long = "9".repeat(100_000);
    let e = obj_err(&format!("{TRI}f 1 2 {long}\n"));
    assert!(
        e.to_string()
            .contains(&format!("index `{}...` ", &long[..40])),
        "{e}"
    );
    let e = off_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
    assert_eq!(e.line(), Some(6));
    assert!(matches!(
        e.kind(),
        ErrorKind::IndexOutOfRange {
            index: 3,
            vertices: 3,
            ..
        }
    ));
    assert_eq!(
        e.to_string(),
        "line 6: vertex 3 is out of range for 3 vertices (0 to 2): index out of range"
    );
}

#[test]
fn face_too_small() {
    let e = obj_err(&format!("{TRI}f 1 2 3\nf 3 4\n"));
    assert_eq!(e.line(), Some(7));
    assert!(matches!(
        topology(&e),
        (
            BuildError::FaceTooSmall { corners: 2, .. },
            Format::Obj,
            [7]
        )
    ));
    let e = obj_err(&format!("{TRI}f\n"));
    assert_eq!(e.line(), Some(6));
    assert!(matches!(
        topology(&e).0,
        BuildError::FaceTooSmall { corners: 0, .. }
    ));
    let e = off_err("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n");
    assert_eq!(e.line(), Some(7));
    assert!(matches!(
        topology(&e),
        (
            BuildError::FaceTooSmall { corners: 2, .. },
            Format::Off,
            [7]
        )
    ));
    assert!(e.to_string().contains("face too small"), "{e}");
}

#[test]
fn repeated_corner() {
    let e = obj_err(&format!("{TRI}f 1 2 3\nf 2 4 -4\n"));
    assert_eq!(e.line(), Some(7));
    // The kernel's slot 1 is the file's vertex 2 (OBJ numbers vertices from 1).
    let (error, format, _) = topology(&e);
    let &BuildError::RepeatedCorner { vertex, .. } = error else {
        panic!("{e}")
    };
    assert_eq!((vertex, format.vertex_number(vertex)), (1, 2));
    assert!(
        e.to_string()
            .contains("vertex 1 (0-based; `2` in the file) twice: repeated corner"),
        "{e}"
    );
    // OFF numbers vertices from 0.
    let e = off_err("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 3 1\n");
    assert_eq!(e.line(), Some(7));
    let (error, format, _) = topology(&e);
    let &BuildError::RepeatedCorner { vertex, .. } = error else {
        panic!("{e}")
    };
    assert_eq!((vertex, format.vertex_number(vertex)), (1, 1));
    assert!(e.to_string().contains("vertex 1 twice"), "{e}");
}

#[test]
fn non_manifold_edge() {
    // Edge 1-2 in three triangles.
    let e = obj_err(&format!("{TRI}f 1 2 3\n# x\nf 2 1 4\nf 1 2 5\n"));
    assert_eq!(e.line(), Some(9));
    let (error, format, lines) = topology(&e);
    let &BuildError::NonManifoldEdge { a, b, .. } = error else {
        panic!("{e}")
    };
    assert_eq!((format.vertex_number(a), format.vertex_number(b)), (1, 2));
    assert_eq!(lines, [6, 8, 9]);
    let msg = e.to_string();
    assert!(
        msg.contains("edge 0-1 (0-based; `1`-`2` in the file) ")
            && msg.contains("lines 6, 8 and 9"),
        "{msg}"
    );
    assert!(msg.starts_with("line 9: "), "{msg}");
    assert!(msg.contains("non-manifold edge"), "{msg}");
}

#[test]
fn inconsistent_orientation() {
    let e = obj_err(&format!("{TRI}f 1 2 3\nf 1 2 4\n"));
    assert_eq!(e.line(), Some(7));
    let (error, format, lines) = topology(&e);
    let &BuildError::InconsistentOrientation { a, b, .. } = error else {
        panic!("{e}")
    };
    assert_eq!((format.vertex_number(a), format.vertex_number(b)), (1, 2));
    assert_eq!(lines, [6, 7]);
    assert_eq!(
        e.to_string(),
        "line 7: the faces on lines 6 and 7 both run from vertex 0 to vertex 1 \
         (0-based; `1` to `2` in the file): inconsistent orientation"
    );
}

#[test]
fn non_manifold_vertex() {
    // Two triangles touching only at vertex 1 (a bow tie).
    let e = obj_err(&format!("{TRI}f 1 2 3\nf 1 4 5\n"));
    let (error, format, _) = topology(&e);
    let &BuildError::NonManifoldVertex { vertex, .. } = error else {
        panic!("{e}")
    };
    assert_eq!(format.vertex_number(vertex), 1);
    assert_eq!(e.line(), Some(7));
    assert!(
        e.to_string().contains(
            "around vertex 0 (0-based; `1` in the file) form more than one fan: \
             non-manifold vertex"
        ),
        "{e}"
    );
}

#[test]
fn off_header_and_counts() {
    let e = off_err("# no header\n3 1 0\n0 0 0\n");
    assert_eq!(e.line(), Some(2));
    assert!(matches!(e.kind(), ErrorKind::MissingHeader));
    let e = off_err("# only a comment\n");
    assert_eq!(e.line(), None);
    assert!(matches!(e.kind(), ErrorKind::MissingHeader));
    let e = off_err("OFF\n3 1 0\n0 0 0\n1 0 0\n");
    assert_eq!(e.line(), Some(2));
    assert!(matches!(
        e.kind(),
        ErrorKind::CountsMismatch {
            what: "vertices",
            declared: 3,
            found: 2
        }
    ));
    let e = off_err("OFF\n\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    assert_eq!(e.line(), Some(3));
    assert!(matches!(
        e.kind(),
        ErrorKind::CountsMismatch {
            what: "faces",
            declared: 2,
            found: 1
        }
    ));
    assert!(e.to_string().contains("counts mismatch"), "{e}");
    let e = off_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n");
    assert_eq!(e.line(), Some(7));
    assert!(matches!(
        e.kind(),
        ErrorKind::ExtraData { declared_faces: 1 }
    ));
    // A header that declares more vertices than 32-bit handles allow.
    let e = off_err("OFF\n4294967295 0 0\n");
    assert_eq!(e.line(), Some(2));
    assert!(matches!(e.kind(), ErrorKind::TooLarge));
    // A lying header must not make the reader reserve its counts.
    let e = off_err("OFF\n4000000000 4000000000 0\n0 0 0\n");
    assert!(matches!(e.kind(), ErrorKind::CountsMismatch { .. }));
}

#[test]
fn file_errors_name_path_and_line() {
    let dir = temp_dir("errors");
    let path = dir.join("bad.off");
    fs::write(
        &path,
        "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 0 3\n3 0 1 3\n",
    )
    .unwrap();
    let e = io::read_mesh(&path).unwrap_err();
    assert_eq!(e.path(), Some(path.as_path()));
    assert_eq!(e.line(), Some(9));
    let msg = e.to_string();
    assert!(msg.starts_with(&format!("{}:9: ", path.display())), "{msg}");
    assert!(msg.contains("non-manifold edge"), "{msg}");

    let missing = dir.join("missing.obj");
    let e = io::read_mesh(&missing).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::Io(_)));
    assert_eq!(e.line(), None);
    assert!(std::error::Error::source(&e).is_some());
    assert!(e.to_string().starts_with(&missing.display().to_string()));

    let e = io::read_mesh(dir.join("mesh.stl")).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::UnknownFormat));
    let e = io::write_mesh(dir.join("mesh.stl"), &gen::grid(1, 1)).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::UnknownFormat));
    assert_eq!(dir_entries(&dir), ["bad.off"], "nothing written for .stl");
}

// ---- Text that is not what the reader assumes. ----

const QUAD_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
const QUAD_OFF: &str = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

fn parse(format: Format, bytes: &[u8]) -> Result<Mesh, MeshFileError> {
    format.parse_bytes(bytes).map(|(m, _)| m)
}

#[test]
fn a_utf8_byte_order_mark_is_skipped() {
    for (format, text) in [(Format::Obj, QUAD_OBJ), (Format::Off, QUAD_OFF)] {
        let plain = parse(format, text.as_bytes()).unwrap();
        let with_bom = parse(format, &[b"\xEF\xBB\xBF", text.as_bytes()].concat()).unwrap();
        assert_eq!(with_bom.positions, plain.positions, "{format:?}");
        assert_eq!(with_bom.polygons(), plain.polygons(), "{format:?}");
    }
}

#[test]
fn bare_carriage_returns_end_lines_and_line_numbers_stay_right() {
    for (format, text) in [(Format::Obj, QUAD_OBJ), (Format::Off, QUAD_OFF)] {
        let plain = parse(format, text.as_bytes()).unwrap();
        for end in ["\r", "\r\n"] {
            let other = parse(format, text.replace('\n', end).as_bytes()).unwrap();
            assert_eq!(other.polygons(), plain.polygons(), "{format:?} {end:?}");
        }
    }
    // Line 3 of a bare-CR file, line 4 of a mixed one.
    let e = obj::parse("v 0 0 0\rv 1 0 0\rv 0 x 0\r").unwrap_err();
    assert_eq!(e.line(), Some(3), "{e}");
    let e = obj::parse("v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2\r").unwrap_err();
    assert_eq!(e.line(), Some(4), "{e}");
    let e = off::parse("OFF\r3 1 0\r0 0 0\r1 0 0\r0 1 0\r3 0 1 7\r").unwrap_err();
    assert_eq!(e.line(), Some(6), "{e}");
}

#[test]
fn utf16_and_binary_bytes_are_refused_as_not_text() {
    let utf16 = |text: &str, bom: &[u8], le: bool| -> Vec<u8> {
        let mut out = bom.to_vec();
        for u in text.encode_utf16() {
            out.extend(if le { u.to_le_bytes() } else { u.to_be_bytes() });
        }
        out
    };
    for (format, text) in [(Format::Obj, QUAD_OBJ), (Format::Off, QUAD_OFF)] {
        for (bytes, line) in [
            (utf16(text, b"\xFF\xFE", true), 1),
            (utf16(text, b"\xFE\xFF", false), 1),
            (utf16(text, b"", true), 1),
            (
                [text.as_bytes(), b"\x00\x01\x02garbage"].concat(),
                6 + (format == Format::Off) as usize * 2,
            ),
        ] {
            let e = parse(format, &bytes).unwrap_err();
            assert!(
                matches!(e.kind(), ErrorKind::NotText { .. }),
                "{format:?}: {e}"
            );
            assert!(e.to_string().contains("not text"), "{e}");
            assert_eq!(e.line(), Some(line), "{format:?}: {e}");
        }
    }
    let e = obj::parse_bytes(b"v 0 0 0\nv 1 0 0\n\x7F\x05ELF").unwrap_err();
    assert!(
        matches!(e.kind(), ErrorKind::NotText { byte: Some(0x7F) }),
        "{e}"
    );
    // Latin-1 in a comment is still text.
    assert!(obj::parse_bytes(b"# caf\xE9\nv 0 0 0\n").is_ok());
}

#[test]
fn content_without_a_vertex_or_face_is_refused_but_an_empty_file_is_an_empty_mesh() {
    for text in [
        "hello world\n",
        "vt 0 0\nvn 0 0 1\ng group\n",
        "\n\n   usemtl x\n",
    ] {
        let e = obj::parse(text).unwrap_err();
        assert!(
            matches!(
                e.kind(),
                ErrorKind::NoMeshData {
                    format: Format::Obj
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("no OBJ vertex or face found"), "{e}");
    }
    assert_eq!(obj::parse("hello\n").unwrap_err().line(), Some(1));
    assert_eq!(obj::parse("\n\n  x\n").unwrap_err().line(), Some(3));
    for text in [
        "",
        "\n\n",
        "# a comment\n  # another\n",
        "\u{FEFF}# with a mark\r\n",
    ] {
        let (mesh, _) = obj::parse(text).unwrap();
        assert_eq!(
            (mesh.map.num_faces(), mesh.positions.len()),
            (0, 0),
            "{text:?}"
        );
    }
    // OFF says what it holds in its header: without one, random text is refused.
    let e = off::parse("hello world\n").unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::MissingHeader), "{e}");
}

#[test]
fn an_off_header_promising_more_vertices_reports_the_vertices() {
    // Declares 6 vertices; the body has 4 vertices and 2 faces.
    let e = off_err("OFF\n6 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
    assert!(
        matches!(
            e.kind(),
            ErrorKind::CountsMismatch {
                what: "vertices",
                declared: 6,
                found: 4
            }
        ),
        "{e}"
    );
    assert_eq!(e.line(), Some(2));
    // Quads, and vertices with colours (more tokens than a face line).
    let e = off_err(
        "COFF\n5 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n1 1 0 1 1 1 1\n0 1 0 1 1 1 1\n4 0 1 2 3\n",
    );
    assert!(
        matches!(
            e.kind(),
            ErrorKind::CountsMismatch {
                what: "vertices",
                found: 4,
                ..
            }
        ),
        "{e}"
    );
    // Integer vertices (no decimal point) are still vertices: faces really missing.
    let e = off_err("OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n");
    assert!(
        matches!(
            e.kind(),
            ErrorKind::CountsMismatch {
                what: "faces",
                declared: 2,
                found: 1
            }
        ),
        "{e}"
    );
}

// ---- The atomic writer. ----

#[test]
fn writing_into_a_missing_directory_fails_and_creates_nothing() {
    let dir = temp_dir("missing-dir");
    let target = dir.join("no").join("such").join("mesh.obj");
    let e = io::write_mesh(&target, &gen::grid(2, 2)).unwrap_err();
    let ErrorKind::MissingDirectory { dir: missing } = e.kind() else {
        panic!("{e}")
    };
    assert_eq!(missing, &dir.join("no").join("such"));
    assert!(e.to_string().ends_with("such does not exist"), "{e}");
    assert!(!dir.join("no").exists());
    assert!(dir_entries(&dir).is_empty());
}

#[test]
fn targets_and_inputs_that_are_directories_or_under_a_file_are_refused_before_work() {
    let dir = temp_dir("target-checks");
    let file = dir.join("plain.obj");
    io::write_mesh(&file, &gen::grid(1, 1)).unwrap();
    assert!(io::check_target(dir.join("new.obj")).is_ok());
    // The output is a directory; a mesh input is a directory (even one named like a mesh).
    let e = io::check_target(&dir).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::IsDirectory), "{e}");
    let named = dir.join("dir.obj");
    fs::create_dir(&named).unwrap();
    for e in [io::read_mesh(&named), io::read_mesh(&dir)].map(Result::unwrap_err) {
        assert!(matches!(e.kind(), ErrorKind::IsDirectory), "{e}");
        assert!(e.to_string().ends_with(": is a directory"), "{e}");
    }
    // The output's directory is a file, or lies under one.
    for target in [file.join("x.obj"), file.join("a").join("b").join("x.obj")] {
        let e = io::check_target(&target).unwrap_err();
        let ErrorKind::NotADirectory { dir: found } = e.kind() else {
            panic!("{e}")
        };
        assert_eq!(found, &file, "{e}");
        assert!(
            e.to_string().ends_with("plain.obj is not a directory"),
            "{e}"
        );
    }
}

#[test]
fn a_failed_write_keeps_the_old_file_and_removes_the_temporary() {
    let dir = temp_dir("failed-write");
    let target = dir.join("mesh.obj");
    io::write_mesh(&target, &gen::grid(1, 1)).unwrap();
    let before = fs::read(&target).unwrap();
    let e = io::write_atomic(&target, |w| {
        use std::io::Write;
        w.write_all(&vec![b'x'; 200_000])?; // more than the buffer: reaches the temp file
        Err(std::io::Error::other("disk full (simulated)"))
    })
    .unwrap_err();
    assert!(e.to_string().contains("disk full (simulated)"), "{e}");
    assert_eq!(fs::read(&target).unwrap(), before);
    assert_eq!(dir_entries(&dir), ["mesh.obj"]);

    // Renaming onto a directory fails too: the directory stays, no temporary remains.
    let sub = dir.join("sub.off");
    fs::create_dir(&sub).unwrap();
    assert!(io::write_mesh(&sub, &gen::grid(1, 1)).is_err());
    assert!(sub.is_dir());
    assert_eq!(dir_entries(&dir), ["mesh.obj", "sub.off"]);

    // A writer refusing its input (a NaN position) leaves nothing either.
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::splat(f64::NAN)];
    let (bad, _) = Mesh::from_polygons(p, &[[0u32, 1, 2]]).unwrap();
    assert!(io::write_mesh(&target, &bad).is_err());
    assert_eq!(fs::read(&target).unwrap(), before);
    assert_eq!(dir_entries(&dir), ["mesh.obj", "sub.off"]);
}

#[test]
fn a_long_target_name_fits_and_a_pending_write_is_invisible_until_committed() {
    let dir = temp_dir("long-name");
    // 250 bytes: valid, but too long for a temporary named after it.
    let name = format!("{}.obj", "m".repeat(246));
    let target = dir.join(&name);
    io::write_mesh(&target, &gen::grid(2, 2)).unwrap();
    assert_eq!(dir_entries(&dir), std::slice::from_ref(&name));
    let before = fs::read(&target).unwrap();

    let pending = io::prepare_mesh(&target, &gen::cube(1)).unwrap();
    assert_eq!(
        fs::read(&target).unwrap(),
        before,
        "not in place before commit"
    );
    assert_eq!(
        dir_entries(&dir),
        std::slice::from_ref(&name),
        "no named temporary while pending"
    );
    drop(pending);
    assert_eq!(
        fs::read(&target).unwrap(),
        before,
        "dropping keeps the old file"
    );
    io::prepare_mesh(&target, &gen::cube(1))
        .unwrap()
        .commit()
        .unwrap();
    assert_eq!(io::read_mesh(&target).unwrap().0.map.num_faces(), 6);
    assert_eq!(dir_entries(&dir), [name]);
}

#[test]
fn the_next_write_removes_the_temporary_a_killed_write_left() {
    let dir = temp_dir("stale-temp");
    let target = dir.join("mesh.off");
    let stale = io::temporary_path(&target);
    assert_eq!(stale.parent(), Some(dir.as_path()));
    fs::write(&stale, b"OFF\n8 6 0\n0 0 0\n").unwrap(); // a partial file, as after SIGKILL
    io::write_mesh(&target, &gen::cube(1)).unwrap();
    assert_eq!(dir_entries(&dir), ["mesh.off"]);
    // Also when the write fails.
    fs::write(&stale, b"partial").unwrap();
    let e = io::write_atomic(&target, |_| Err(std::io::Error::other("stop")));
    assert!(e.is_err());
    assert_eq!(dir_entries(&dir), ["mesh.off"]);
    assert_eq!(io::read_mesh(&target).unwrap().0.map.num_faces(), 6);
}

// ---- Properties. ----

/// A mesh with the same connectivity under a random numbering: vertices permuted, faces
/// shuffled, each face's corners rotated.
fn relabel(mesh: &Mesh, seed: u64) -> Mesh {
    let mut rng = zipmesh::rng::Rng::new(seed);
    let n = mesh.positions.len();
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        perm.swap(i, rng.below(i + 1));
    }
    let mut positions = vec![DVec3::ZERO; n];
    for (old, &new) in perm.iter().enumerate() {
        positions[new as usize] = mesh.positions[old];
    }
    let mut faces: Vec<Vec<u32>> = mesh
        .polygons()
        .into_iter()
        .map(|p| {
            let mut q: Vec<u32> = p.iter().map(|&v| perm[v as usize]).collect();
            let k = rng.below(q.len());
            q.rotate_left(k);
            q
        })
        .collect();
    for i in (1..faces.len()).rev() {
        faces.swap(i, rng.below(i + 1));
    }
    Mesh::from_polygons(positions, &faces).unwrap().0
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn grids_round_trip(nx in 1usize..12, ny in 1usize..12, torus in any::<bool>(), k in 0usize..3, seed in any::<u64>()) {
        let mesh = if torus { gen::torus_grid(nx, ny) } else { gen::grid(nx, ny) };
        let mesh = relabel(&mesh, seed);
        let format = FORMATS[k];
        let (back, _) = format.parse_bytes(&to_bytes(format, &mesh)).unwrap();
        prop_assert_eq!(CanonicalCode::of(&back.map), CanonicalCode::of(&mesh.map));
        prop_assert_eq!(&back.positions, &mesh.positions);
        prop_assert_eq!(normalized(&back), normalized(&mesh));
    }

    #[test]
    fn coordinates_round_trip_bit_exactly(xs in proptest::collection::vec(any::<f64>().prop_filter("finite", |x| x.is_finite()), 9)) {
        let positions: Vec<DVec3> = xs.chunks(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect();
        let (mesh, _) = Mesh::from_polygons(positions, &[[0u32, 1, 2]]).unwrap();
        for format in FORMATS {
            let (back, _) = format.parse_bytes(&to_bytes(format, &mesh)).unwrap();
            for (a, b) in back.positions.iter().zip(&mesh.positions) {
                prop_assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits));
            }
        }
    }

    #[test]
    fn readers_never_panic_on_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        for format in FORMATS {
            if let Ok((mesh, _)) = format.parse_bytes(&bytes) {
                prop_assert!(mesh.map.check().is_ok());
            }
        }
    }

    #[test]
    fn readers_never_panic_on_near_miss_text(words in proptest::collection::vec(
        prop_oneof![
            Just("v"), Just("f"), Just("OFF"), Just("\n"), Just("\n"), Just("#"), Just("\\"),
            Just("0"), Just("1"), Just("2"), Just("3"), Just("4"), Just("-1"), Just("-2"),
            Just("1/2"), Just("3//1"), Just("1.5"), Just("-0"), Just("1e999"), Just("x"),
            Just("99999999999"), Just("\r"), Just("\t"),
        ], 0..80)) {
        let text = words.join(" ");
        for format in FORMATS {
            match format.parse_bytes(text.as_bytes()) {
                Ok((mesh, _)) => prop_assert!(mesh.map.check().is_ok()),
                Err(e) => {
                    // Every error about the file's content names an existing line (a bare
                    // `\r` ends a line too).
                    let lines = text.replace("\r\n", "\n").replace('\r', "\n").split('\n').count();
                    if let Some(line) = e.line() {
                        prop_assert!(line >= 1 && line <= lines, "{}", e);
                    }
                }
            }
        }
    }
}
