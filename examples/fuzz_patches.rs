//! Seeds the Q-zip fuzz targets with patches of the real meshes: for the first N (4) pairs of
//! interior singularities (in vertex order) within 6 edges of each given quad mesh (the
//! default list below), the faces within 3 rings of the shortest path between them, written
//! as a [`qzip_case`] patch input with that pair, each of the four tags in turn, into
//! `fuzz/corpus/{qzip,qzip_four_moves,qzip_homotopy,qzip_reverse}/patch-MESH-K`:
//! `cargo run --release --example fuzz_patches -- [--pairs N] [FILE...]`.
//!
//! Each seed is decoded again by the targets' decoder before it is written, so every file
//! written is a usable case whose path joins the pair.

#[path = "../fuzz/fuzz_targets/common/qzip_case.rs"]
mod qzip_case;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path as FsPath, PathBuf};

use zipmesh::invariants::{is_irregular, MeshKind};
use zipmesh::qzip::{sketch, Path, SketchOptions};
use zipmesh::{Map, Vert};

/// The meshes the committed seeds come from.
const DEFAULT: [&str; 8] = [
    "spot_quadrangulated",
    "blub_quadrangulated",
    "cubespikes",
    "loki",
    "gear",
    "fandisk_quads",
    "amo_quad",
    "bunny_poly",
];

const TARGETS: [&str; 4] = ["qzip", "qzip_four_moves", "qzip_homotopy", "qzip_reverse"];

/// The faces with a corner within `rings` edges of the path, renumbered from 0 in the
/// order met, and the new numbers of the path's ends.
fn patch(map: &Map, path: &Path, rings: usize) -> (Vec<Vec<u16>>, u16, u16) {
    let mut near: BTreeSet<Vert> = path.vertices().iter().copied().collect();
    let mut front: Vec<Vert> = near.iter().copied().collect();
    for _ in 0..rings {
        let mut next = Vec::new();
        for v in front {
            for d in map.vertex_darts(v) {
                if near.insert(map.dest(d)) {
                    next.push(map.dest(d));
                }
            }
        }
        front = next;
    }
    let mut faces: BTreeSet<zipmesh::Face> = BTreeSet::new();
    for &v in &near {
        faces.extend(map.vertex_darts(v).filter_map(|d| map.face(d)));
    }
    let mut number: BTreeMap<Vert, u16> = BTreeMap::new();
    let mut id = |v: Vert| {
        let n = number.len() as u16;
        *number.entry(v).or_insert(n)
    };
    let (a, b) = (id(path.start()), id(path.end()));
    let list = faces
        .iter()
        .map(|&f| map.face_darts(f).map(|d| id(map.origin(d))).collect())
        .collect();
    (list, a, b)
}

fn main() {
    let (mut pairs, mut files) = (4usize, Vec::<PathBuf>::new());
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--pairs" => pairs = args.next().and_then(|x| x.parse().ok()).expect("a number"),
            _ => files.push(a.into()),
        }
    }
    let root = FsPath::new(env!("CARGO_MANIFEST_DIR"));
    if files.is_empty() {
        files = DEFAULT
            .iter()
            .map(|m| root.join(format!("tests/data/quad/{m}.obj")))
            .collect();
    }
    let mut written = 0;
    for f in &files {
        let (mesh, _) = zipmesh::io::read_mesh(f).unwrap_or_else(|e| panic!("{e}"));
        let map = &mesh.map;
        let stem = f.file_stem().unwrap().to_string_lossy().into_owned();
        let sing: Vec<Vert> = map
            .vertices()
            .filter(|&v| is_irregular(map, MeshKind::Quad, v) && !map.is_boundary_vertex(v))
            .collect();
        let paths = sing
            .iter()
            .enumerate()
            .flat_map(|(i, &a)| sing[i + 1..].iter().map(move |&b| (a, b)))
            .filter_map(|(a, b)| sketch(map, a, b, &SketchOptions::default()).ok())
            .filter(|p| (2..=6).contains(&p.len()));
        let mut k = 0;
        for path in paths {
            if k == pairs {
                break;
            }
            let (faces, a, b) = patch(map, &path, 3);
            let nv = faces.iter().flatten().max().map_or(0, |&m| m + 1);
            let mut data = qzip_case::encode_patch(nv, &faces);
            // Tag LS, the pair (low bit 0: by vertex number), the shortest path, sweep 0.
            data.push(0);
            data.extend((a << 1).to_le_bytes());
            data.extend((b << 1).to_le_bytes());
            data.extend([0, 0]);
            let Some(c) = qzip_case::case(&data) else {
                continue;
            };
            assert_eq!(c.original.num_faces(), faces.len(), "{stem}");
            assert_eq!(c.path.len(), path.len(), "{stem}");
            for t in TARGETS {
                let dir = root.join("fuzz/corpus").join(t);
                std::fs::write(dir.join(format!("patch-{stem}-{k}")), &data).unwrap();
            }
            k += 1;
            written += 1;
        }
    }
    println!(
        "{written} patches written to each of {}",
        TARGETS.join(", ")
    );
}
