//! `qzip::preprocess` against the scan it replaced (the first vertex needing a step in
//! `map.vertices()` order, searched again from the start after every step, candidates walked
//! k/2 steps each): the same operations in the same order and the same map, on fans, hubs
//! made by collapses (interior far ends that cascade), random meshes with doublets and the
//! shared meshes; and a valence-20,000 vertex preprocessed to a result with every documented
//! property (its work is bounded in the unit tests of `src/qzip/preprocess.rs`).

use std::path::Path;
use zipmesh::ops::quad::{self, QuadRecord};
use zipmesh::ops::Refusal;
use zipmesh::qzip::preprocess;
use zipmesh::rng::Rng;
use zipmesh::{gen, io, Dart, Map, Vert};

/// The quadratic preprocessing as it was, kept as the reference for the order.
fn reference(map: &mut Map) -> Result<Vec<QuadRecord>, Refusal> {
    let mut out: Vec<QuadRecord> = Vec::new();
    let undo = |out: &[QuadRecord], map: &mut Map| {
        for r in out.iter().rev() {
            r.undo(map).unwrap();
        }
    };
    for _ in 0..4 * map.dart_slots() + 16 {
        let next = map
            .vertices()
            .find(|&v| !map.is_boundary_vertex(v) && (map.valence(v) >= 6 || map.valence(v) == 2));
        let Some(v) = next else {
            return Ok(out);
        };
        let step = if map.valence(v) == 2 {
            quad::remove_valence2(map, map.vertex_dart(v)).map(QuadRecord::from)
        } else {
            let k = map.valence(v);
            let far = |d: Dart| {
                let mut o = d;
                for _ in 0..k / 2 {
                    o = map.rotate_cw(o);
                }
                [map.dest(d), map.dest(o)]
            };
            let first = map
                .vertex_darts(v)
                .find(|&d| far(d).iter().all(|&x| map.valence(x) <= 4))
                .unwrap_or_else(|| map.vertex_dart(v));
            quad::split_high_valence(map, v, first).map(QuadRecord::from)
        };
        match step {
            Ok(r) => out.push(r),
            Err(e) => {
                undo(&out, map);
                return Err(e);
            }
        }
    }
    undo(&out, map);
    Err(Refusal::BadArguments)
}

/// Both preprocessings on copies of `map`: the same records, maps and errors.
fn same_as_reference(map: &Map, what: &str) -> usize {
    let (mut a, mut b) = (map.clone(), map.clone());
    let new = preprocess(&mut a).map(|p| p.records().to_vec());
    let old = reference(&mut b);
    assert_eq!(new, old, "{what}: the operations differ");
    assert!(a == b, "{what}: the maps differ");
    new.map_or(0, |r| r.len())
}

/// The disk of `k` quads around vertex 0 (spoke ends `1 + 2i`, rim middles `2 + 2i`).
fn fan(k: u32) -> Map {
    let s = |i: u32| 1 + 2 * (i % k);
    let faces: Vec<[u32; 4]> = (0..k).map(|i| [0, s(i), 2 + 2 * i, s(i + 1)]).collect();
    Map::from_polygons((1 + 2 * k) as usize, &faces).unwrap()
}

/// An `n x n` torus with `c` quads collapsed into one vertex (valence about 2c + 4), so
/// the far ends of its splits are interior and become high in turn.
fn hub(n: usize, c: usize) -> Map {
    let mut map = gen::torus_grid(n, n).map;
    let mut v = Vert::new(0);
    for _ in 0..c {
        let darts: Vec<Dart> = map.vertex_darts(v).collect();
        let Some(r) = darts
            .into_iter()
            .find_map(|d| quad::collapse_quad(&mut map, d).ok())
        else {
            break;
        };
        v = r.kept();
    }
    assert!(
        map.valence(v) > c,
        "valence {} after {c} collapses",
        map.valence(v)
    );
    map
}

/// Random quad meshes with random collapses (high valences) and doublets (valence 2).
fn scrambled(seed: u64) -> Map {
    let mut rng = Rng::new(seed);
    let mut map = gen::random_quad(400, (seed % 3) as usize, (seed % 2) as usize, seed).map;
    for _ in 0..60 {
        let d = Dart::new(rng.below(map.dart_slots()) as u32);
        if !map.is_live_dart(d) {
            continue;
        }
        let _ = if rng.below(3) == 0 {
            quad::insert_doublet(&mut map, d).map(|_| ())
        } else {
            quad::collapse_quad(&mut map, d).map(|_| ())
        };
    }
    map
}

#[test]
fn same_operations_as_the_scan_on_fans_and_hubs() {
    for k in [2, 3, 5, 6, 7, 8, 13, 64, 101, 1000] {
        same_as_reference(&fan(k), &format!("fan {k}"));
    }
    for (n, c) in [(8, 1), (8, 5), (12, 20), (20, 60), (30, 150)] {
        let steps = same_as_reference(&hub(n, c), &format!("hub {n} {c}"));
        eprintln!("hub {n} {c}: {steps} steps");
        assert!(steps > 0);
    }
}

#[test]
fn same_operations_as_the_scan_on_random_meshes() {
    let mut steps = 0;
    for seed in 0..40 {
        steps += same_as_reference(&scrambled(seed), &format!("seed {seed}"));
    }
    eprintln!("random meshes: {steps} steps");
    assert!(
        steps > 100,
        "{steps} steps: the cases do not exercise the preprocessing"
    );
}

#[test]
fn same_operations_as_the_scan_on_the_shared_meshes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/quad");
    let mut steps = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let (mesh, _) = io::read_mesh(&path).unwrap();
        steps += same_as_reference(&mesh.map, &path.display().to_string());
    }
    // Spot and Blub have a few valence-6 vertices.
    assert!(steps >= 8, "{steps}");
}

/// Valence 20,000: no interior valence 2 or 6+ left, a valid map, the exact undo.
#[test]
fn a_valence_20000_vertex_is_preprocessed() {
    let map = fan(20_000);
    let mut m = map.clone();
    let p = preprocess(&mut m).unwrap();
    assert_eq!(m.check(), Ok(()));
    for v in m.vertices().filter(|&v| !m.is_boundary_vertex(v)) {
        assert!((3..=5).contains(&m.valence(v)), "valence {}", m.valence(v));
    }
    // Every split adds one vertex, one quad and two edges.
    assert_eq!(m.num_vertices(), map.num_vertices() + p.records().len());
    p.undo(&mut m).unwrap();
    assert!(m == map);
}

/// A preprocessing's record undoes through the `Undo` trait as through its own method, so
/// it can sit on one undo stack with the operators' records.
#[test]
fn preprocessing_undoes_through_the_undo_trait() {
    let mut m = hub(9, 3);
    let before = m.clone();
    let p = preprocess(&mut m).unwrap();
    assert!(!p.records().is_empty() && m != before);
    let stack: Vec<Box<dyn zipmesh::ops::Undo>> = vec![Box::new(p)];
    for r in stack.iter().rev() {
        r.undo(&mut m).unwrap();
    }
    assert_eq!(m, before);
}
