//! Fixtures and checks shared by the Q-zip tests.
#![allow(dead_code)]

pub mod svg;
pub mod tri;
pub mod tri_sweep;

use zipmesh::invariants::{irregular_valences, irregular_vertices, MeshKind};
use zipmesh::ops::quad;
use zipmesh::qzip::{sketch, verify_edit, Path, Qzip, QzipError, SketchOptions, Tag, ZipReport};
use zipmesh::{gen, Map, Mesh, Vert};

/// Relaxed zips put every output vertex on the input surface (to rounding: this many
/// diagonals; measured at most 5e-16).
pub const RELAXED_DISTANCE: f64 = 1e-9;
/// The raw placement (`zip --no-relax`) keeps every output vertex within this fraction of
/// the diagonal of the input surface (measured at most 0.0112, on fandisk).
pub const RAW_DISTANCE: f64 = 0.02;

/// Catmull-Clark of an icosahedron, `levels` times: 12 v5s and 20 v3s, isolated
/// (2^(levels-1) edges apart), everything else regular.
pub fn ico_cc(levels: usize) -> Map {
    let mut mesh: Mesh = gen::icosahedron();
    for _ in 0..levels {
        mesh = gen::catmull_clark(&mesh);
    }
    mesh.map
}

/// A regular torus with vertex splits along opposite edges at the given vertices (each makes
/// two v3s and two v5s, a crowded cluster).
pub fn torus_with_splits(n: usize, at: &[u32]) -> Map {
    let mut map = gen::torus_grid(n, n).map;
    for &a in at {
        let s1 = map.vertex_dart(Vert::new(a));
        let s2 = map.rotate_cw(map.rotate_cw(s1));
        quad::split_vertex(&mut map, s1, s2).expect("split of a regular vertex");
    }
    map
}

/// The sorted multiset of (valence, boundary) of the irregular vertices.
pub fn irregular_multiset(map: &Map) -> Vec<(usize, bool)> {
    irregular_valences(map, MeshKind::Quad)
}

/// Every ordered pair of singularities of `map` within `max_len` edges, with its shortest
/// path.
pub fn pairs_within(map: &Map, max_len: usize) -> Vec<Path> {
    let sing = irregular_vertices(map, MeshKind::Quad);
    let mut out = Vec::new();
    for &a in &sing {
        for &b in &sing {
            if a == b {
                continue;
            }
            if let Ok(p) = sketch(map, a, b, &SketchOptions::default()) {
                if p.len() <= max_len {
                    out.push(p);
                }
            }
        }
    }
    out
}

/// Runs a Q-zip on `map` and checks everything Q-zip promises: on success a valid pure-quad
/// map with the same Euler characteristic, boundary loops and irregular valences, `V`
/// changed by the report's delta, the two moved vertices carrying the pair's valences, the
/// old ends regular unless they are the moved ones, and an exact undo; on refusal the map
/// untouched. Leaves `map` as it was and returns the edited copy with the report.
pub fn check_zip(map: &Map, path: &Path, tag: Tag) -> Result<(Map, ZipReport), QzipError> {
    let mut m = map.clone();
    let r = match Qzip::new().zip_along(&mut m, path, tag) {
        Ok(r) => r.into_record(),
        Err(e) => {
            assert_eq!(&m, map, "a refusal changed the map: {e}");
            return Err(e);
        }
    };
    if let Err(b) = verify_edit(map, &m, path, &r) {
        panic!("{b}\n{}", r.surgery());
    }
    Ok((m, r))
}

/// A mesh of `tests/data`, which must exist.
pub fn shared(rel: &str) -> std::path::PathBuf {
    let p = repository().join("tests/data").join(rel);
    assert!(p.is_file(), "missing shared test mesh {}", p.display());
    p
}

/// The polygon cages of `tests/data/poly/` after one Catmull-Clark step (quads only,
/// singularities where the cage had non-quads or irregular vertices), with `pairs` quads
/// re-split into triangle pairs walked apart (`gen::with_triangle_pairs`).
pub fn cages(pairs: usize, seed: u64) -> Vec<(String, Mesh)> {
    let dir = repository().join("tests/data/poly");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    names.sort();
    assert!(names.len() >= 2, "cages in {dir:?}");
    names
        .into_iter()
        .map(|p| {
            let (cage, _) = zipmesh::io::read_mesh(&p).unwrap();
            assert!(cage.map.faces().any(|f| cage.map.degree(f) != 4));
            let quads = gen::catmull_clark(&cage);
            let (mesh, tips) = gen::with_triangle_pairs(quads, pairs, 12, seed);
            assert_eq!(tips.len(), 2 * pairs);
            (p.file_name().unwrap().to_string_lossy().into_owned(), mesh)
        })
        .collect()
}

/// The repository's root (where `tests/data/` is), from the root crate's tests or another
/// crate's that include this module.
pub fn repository() -> std::path::PathBuf {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors()
        .find(|p| p.join("tests/data").is_dir())
        .unwrap_or(here)
        .to_path_buf()
}
