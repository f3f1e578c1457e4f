//! PLY reading and writing: ASCII and binary in both byte orders, every integer type of the
//! corner list, unknown properties and elements skipped, the writers' round trips, and
//! errors that name the line (header, ASCII) or the element and byte (binary).

use glam::DVec3;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::io::{ply, ErrorKind, Format};
use zipmesh::{gen, BuildError, Mesh};

/// A PLY file with `header` (after `ply` and the format line) and `body`.
fn file(format: &str, header: &str, body: &[u8]) -> Vec<u8> {
    let mut out = format!("ply\nformat {format} 1.0\n{header}end_header\n").into_bytes();
    out.extend_from_slice(body);
    out
}

/// The unit square as two triangles, positions and corners, for the hand-made files.
const SQUARE: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];
const TRIANGLES: [[u32; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

/// `value` in `ty`, in either byte order.
fn bytes(ty: &str, value: f64, big: bool) -> Vec<u8> {
    let mut b = match ty {
        "char" => vec![value as i8 as u8],
        "uchar" | "uint8" => vec![value as u8],
        "short" => (value as i16).to_le_bytes().to_vec(),
        "ushort" => (value as u16).to_le_bytes().to_vec(),
        "int" | "int32" => (value as i32).to_le_bytes().to_vec(),
        "uint" => (value as u32).to_le_bytes().to_vec(),
        "float" => (value as f32).to_le_bytes().to_vec(),
        "double" => value.to_le_bytes().to_vec(),
        _ => panic!("{ty}"),
    };
    if big {
        b.reverse();
    }
    b
}

/// A binary square with a normal and a colour per vertex, a flag per face, and an `edge`
/// element after the faces: every one of them skipped by its declared type.
fn binary_square(big: bool, coord: &str, count: &str, index: &str, list: &str) -> Vec<u8> {
    let header = format!(
        "comment made by hand\nobj_info test\nelement vertex 4\nproperty {coord} x\n\
         property {coord} y\nproperty float nx\nproperty {coord} z\nproperty uchar red\n\
         element face 2\nproperty uchar flag\nproperty list {count} {index} {list}\n\
         element edge 1\nproperty int vertex1\nproperty int vertex2\n"
    );
    let mut body = Vec::new();
    for p in SQUARE {
        for (k, x) in p.iter().enumerate() {
            body.extend(bytes(coord, *x, big));
            if k == 1 {
                body.extend(bytes("float", 0.5, big));
            }
        }
        body.push(200);
    }
    for t in TRIANGLES {
        body.push(7);
        body.extend(bytes(count, 3.0, big));
        for i in t {
            body.extend(bytes(index, f64::from(i), big));
        }
    }
    body.extend(bytes("int", 0.0, big));
    body.extend(bytes("int", 1.0, big));
    let format = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    file(format, &header, &body)
}

fn square_read(mesh: &Mesh) {
    assert_eq!(mesh.polygons(), vec![vec![0, 1, 2], vec![0, 2, 3]]);
    let want: Vec<DVec3> = SQUARE.iter().map(|p| DVec3::from_array(*p)).collect();
    assert_eq!(mesh.positions, want);
}

#[test]
fn binary_in_both_byte_orders_and_every_integer_type_is_read() {
    for big in [false, true] {
        for coord in ["float", "double"] {
            for (count, index) in [
                ("uchar", "int"),
                ("uint8", "uint"),
                ("ushort", "short"),
                ("int", "uchar"),
                ("uchar", "ushort"),
                ("char", "int32"),
            ] {
                for list in ["vertex_indices", "vertex_index"] {
                    let src = binary_square(big, coord, count, index, list);
                    let (mesh, _) = ply::parse_bytes(&src)
                        .unwrap_or_else(|e| panic!("{big} {coord} {count} {index} {list}: {e}"));
                    square_read(&mesh);
                }
            }
        }
    }
}

#[test]
fn ascii_with_extra_properties_and_elements_is_read() {
    let header = "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n\
                  property list uchar float texcoord\nelement face 2\n\
                  property list uchar int vertex_indices\nproperty int material\n";
    let body = "0 0 0 2 0.5 0.5\n1 0 0 0\n\n1 1 0 1 7\r\n0 1 0 0\n3 0 1 2 5\n3 0 2 3 5\n\n";
    let (mesh, _) = ply::parse_bytes(&file("ascii", header, body.as_bytes())).unwrap();
    square_read(&mesh);
}

#[test]
fn both_writers_round_trip_bit_for_bit() {
    for mesh in [
        gen::cube(3),
        gen::torus_grid(5, 4),
        gen::subdivided_icosahedron(2),
    ] {
        let mut wrapped = mesh.clone();
        for p in &mut wrapped.positions {
            *p = *p * 0.1 + DVec3::new(1e-7, -3.0e12, 0.3);
        }
        for ascii in [false, true] {
            let mut out = Vec::new();
            if ascii {
                ply::write_ascii(&wrapped, &mut out).unwrap();
            } else {
                ply::write(&wrapped, &mut out).unwrap();
            }
            let (back, _) = ply::parse_bytes(&out).unwrap();
            assert_eq!(
                CanonicalCode::of(&back.map),
                CanonicalCode::of(&wrapped.map)
            );
            let bits = |m: &Mesh| -> Vec<[u64; 3]> {
                m.positions
                    .iter()
                    .map(|p| p.to_array().map(f64::to_bits))
                    .collect()
            };
            assert_eq!(bits(&back), bits(&wrapped), "ascii {ascii}");
            assert_eq!(back.polygons(), wrapped.polygons());
        }
    }
}

#[test]
fn a_face_of_more_than_255_corners_is_refused_before_writing() {
    let n = 300u32;
    let positions: Vec<DVec3> = (0..n)
        .map(|i| DVec3::new(f64::from(i).cos(), f64::from(i).sin(), 0.0))
        .collect();
    let ring: Vec<u32> = (0..n).collect();
    let (mesh, _) = Mesh::from_polygons(positions, &[ring]).unwrap();
    let mut out = Vec::new();
    let e = ply::write(&mesh, &mut out).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidData);
    assert!(e.to_string().contains("300 corners"), "{e}");
    assert!(out.is_empty());
}

fn err(src: &[u8]) -> zipmesh::io::MeshFileError {
    ply::parse_bytes(src).unwrap_err()
}

const VERTS: &str = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
const FACES: &str = "element face 1\nproperty list uchar int vertex_indices\n";

#[test]
fn header_errors_name_their_line() {
    let e = err(b"plx\nformat ascii 1.0\n");
    assert_eq!(
        e.to_string(),
        "line 1: the file does not start with `ply`: not a PLY file: bad PLY header"
    );
    let e = err(b"ply\nformat ascii 2.0\nend_header\n");
    assert_eq!(
        (e.line(), matches!(e.kind(), ErrorKind::BadHeader { .. })),
        (Some(2), true)
    );
    let e = err(format!("ply\nformat ascii 1.0\n{VERTS}property list uchar int16 idx\nproperty quad w\nend_header\n").as_bytes());
    assert_eq!(
        e.to_string(),
        "line 8: unknown property type `quad`: bad PLY header"
    );
    let e = err(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n");
    assert!(e.to_string().contains("has 0 `z` properties"), "{e}");
    let e = err(format!("ply\nformat ascii 1.0\n{VERTS}element face 1\nproperty list uchar float vertex_indices\nend_header\n").as_bytes());
    assert!(
        e.to_string()
            .starts_with("line 8: the face corners' list must hold integers"),
        "{e}"
    );
    let e = err(format!("ply\nformat ascii 1.0\n{VERTS}").as_bytes());
    assert!(
        e.to_string()
            .ends_with("no `end_header` line: bad PLY header"),
        "{e}"
    );
    let e = err(b"ply\nformat ascii 1.0\nelement vertex 99999999\nproperty float x\nend_header\n");
    assert_eq!(e.line(), Some(3));
}

#[test]
fn ascii_errors_name_their_line() {
    let header = format!("{VERTS}{FACES}");
    let e = err(&file("ascii", &header, b"0 0 0\n1 0 0\n0 1 x\n3 0 1 2\n"));
    assert_eq!((e.line(), e.byte()), (Some(12), None));
    assert!(matches!(e.kind(), ErrorKind::BadNumber { .. }), "{e}");
    let e = err(&file("ascii", &header, b"0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"));
    assert_eq!(
        e.to_string(),
        "line 13: vertex 3 is out of range for 3 vertices (0 to 2): index out of range"
    );
    let e = err(&file("ascii", &header, b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2 9\n"));
    assert_eq!(e.line(), Some(13));
    let e = err(&file(
        "ascii",
        &header,
        b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
    ));
    assert_eq!(
        (e.line(), e.to_string().ends_with("trailing data")),
        (Some(14), true)
    );
    let e = err(&file("ascii", &header, b"0 0 0\n1 0 0\n0 1 0\n"));
    assert!(
        matches!(
            e.kind(),
            ErrorKind::Truncated {
                index: 0,
                count: 1,
                ..
            }
        ),
        "{e}"
    );
    // A topology defect names the face's line.
    let two = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
               element face 2\nproperty list uchar int vertex_indices\n";
    let e = err(&file(
        "ascii",
        two,
        b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
    ));
    assert!(
        e.to_string()
            .starts_with("line 14: the faces on lines 13 and 14 both run"),
        "{e}"
    );
}

#[test]
fn binary_errors_name_the_element_and_the_byte() {
    let good = binary_square(false, "float", "uchar", "int", "vertex_indices");
    let body = good.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    // Cut inside the second face: 4 vertices of 17 bytes, the first face of 14.
    let cut = &good[..body + 4 * 17 + 14 + 5];
    let e = err(cut);
    assert_eq!(e.line(), None);
    assert_eq!(e.byte(), Some((body + 4 * 17 + 14) as u64));
    assert_eq!(
        e.to_string(),
        format!(
            "byte {}: the data ends inside face 1 of 2: truncated",
            body + 4 * 17 + 14
        )
    );
    // A corner out of range: the second face's last index set to 9.
    let mut bad = good.clone();
    let last = body + 4 * 17 + 14 + 2 + 2 * 4;
    bad[last..last + 4].copy_from_slice(&9i32.to_le_bytes());
    let e = err(&bad);
    assert_eq!(e.byte(), Some((body + 4 * 17 + 14) as u64));
    assert!(
        e.to_string()
            .contains("vertex 9 is out of range for 4 vertices"),
        "{e}"
    );
    // Bytes after the last element.
    let mut long = good.clone();
    long.extend_from_slice(b"\n\0");
    let e = err(&long);
    assert_eq!(
        (e.byte(), e.to_string().ends_with("trailing data")),
        (Some(good.len() as u64 + 1), true)
    );
    long.truncate(good.len() + 1);
    assert!(
        ply::parse_bytes(&long).is_ok(),
        "a final line end is white space"
    );
}

#[test]
fn a_binary_topology_defect_names_the_faces() {
    // The square's second triangle repeated: two faces run 0 -> 2.
    let header = format!(
        "{}element face 2\nproperty list uchar int vertex_indices\n",
        VERTS.replace('3', "4")
    );
    let mut body = Vec::new();
    for p in SQUARE {
        for x in p {
            body.extend((x as f32).to_le_bytes());
        }
    }
    let face: Vec<u8> = std::iter::once(3u8)
        .chain(TRIANGLES[1].iter().flat_map(|&i| (i as i32).to_le_bytes()))
        .collect();
    body.extend_from_slice(&face);
    body.extend_from_slice(&face);
    let src = file("binary_little_endian", &header, &body);
    let e = err(&src);
    let ErrorKind::Topology {
        error,
        format,
        lines,
    } = e.kind()
    else {
        panic!("{e}")
    };
    assert!(matches!(error, BuildError::InconsistentOrientation { .. }));
    assert_eq!((*format, lines.is_empty()), (Format::Ply, true));
    assert!(
        e.to_string()
            .contains("the faces on faces 0 and 1 both run"),
        "{e}"
    );
    assert_eq!(e.byte(), Some((src.len() - 13) as u64));
}

/// Writes the seeds of the `ply_reader` fuzz target (`fuzz/corpus/ply_reader/`): run with
/// `--ignored` after a change to the hand-made files above.
#[test]
#[ignore]
fn write_fuzz_seeds() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/ply_reader");
    std::fs::create_dir_all(&dir).unwrap();
    let mut cube = Vec::new();
    ply::write(&gen::cube(1), &mut cube).unwrap();
    let mut ascii = Vec::new();
    ply::write_ascii(&gen::grid(2, 1), &mut ascii).unwrap();
    let seeds = [
        ("cube-binary-le.ply", cube),
        ("grid-ascii.ply", ascii),
        (
            "square-be-skips.ply",
            binary_square(true, "double", "ushort", "short", "vertex_index"),
        ),
        (
            "square-le-skips.ply",
            binary_square(false, "float", "uchar", "int", "vertex_indices"),
        ),
    ];
    for (name, bytes) in seeds {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}

/// An element without properties takes no bytes, however many instances it declares: a
/// binary file with four billion of them is read at once.
#[test]
fn an_element_without_properties_takes_no_time() {
    let header = format!("{VERTS}element empty 4000000000\n");
    let mut body = Vec::new();
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for x in p {
            body.extend(x.to_le_bytes());
        }
    }
    let (mesh, _) = ply::parse_bytes(&file("binary_little_endian", &header, &body)).unwrap();
    assert_eq!(mesh.positions.len(), 3);
}
