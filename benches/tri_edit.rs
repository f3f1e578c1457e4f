//! Criterion benches of the semantic triangle edits (`zipmesh::tri_edit`) on triangulated
//! tori of two sizes: an atomic 5-7 move, and a composite move (Sec. 7.1) of a 5-7 pair at
//! distance 2, each applied and undone so the mesh stays the same. Timings of the composite
//! move by path length: `cargo run --release --example workload -- 0 7 tri_moves`.
//! Relaxation (Sec. 8): local (10 sweeps) and global (5 solves) on regions of 1 to 8 rings
//! around a flip in a bumpy lattice.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use glam::DVec3;
use zipmesh::ops::tri;
use zipmesh::optimize::Surface;
use zipmesh::tri_edit::{
    far_pair_directions, generate_pair_v7, move_far_pair, move_pair, relax_global, relax_local,
    relax_region, touched_vertices, Direction, Moved, Via7,
};
use zipmesh::{Map, Mesh, Vert};

// The bench uses the flipped torus; `far_pair` (any distance) is the workload's.
#[allow(dead_code)]
#[path = "support/tri_torus.rs"]
mod tri_torus;

/// An `n x n` triangulated torus with one diagonal flipped and that flip's first pair moved
/// 4 steps away; returns the map and that pair (v5, v7).
fn flipped(n: usize) -> (Map, Vert, Vert) {
    let (mut map, [(mut p, mut q), _]) = tri_torus::flipped(n);
    for _ in 0..4 {
        let m = move_pair(&mut map, p, q, Direction::SplitRight).expect("move");
        (p, q) = (m.p(), m.q());
    }
    (map, p, q)
}

/// A 5-7 pair at distance 2: the flip's other v7 moved by a v7 generation, whose pair is
/// walked 4 steps away (the first configuration that works).
fn far_pair(n: usize) -> (Map, Vert, Vert) {
    let (map, p, _) = flipped(n);
    let five = map
        .vertices()
        .find(|&v| map.valence(v) == 5 && v != p)
        .expect("the other v5");
    let seven = map
        .vertex_darts(five)
        .map(|d| map.dest(d))
        .find(|&w| map.valence(w) == 7);
    let seven = seven.expect("its v7");
    for d in map.vertex_darts(seven).collect::<Vec<_>>() {
        for via in Via7::ALL {
            let mut m = map.clone();
            let Ok(g) = generate_pair_v7(&mut m, d, via, Moved::First) else {
                continue;
            };
            if m.dart_between(five, g.moved()).is_some() {
                continue;
            }
            let (mut a, mut b) = g.pair().expect("pair");
            let ok = (0..4).all(|_| {
                move_pair(&mut m, a, b, Direction::FlipLeft)
                    .map(|s| (a, b) = (s.p(), s.q()))
                    .is_ok()
            });
            if ok
                && !far_pair_directions(&m, five, g.moved(), 64)
                    .unwrap_or_default()
                    .is_empty()
            {
                return (m, five, g.moved());
            }
        }
    }
    panic!("no far pair on the {n} x {n} torus");
}

fn tri_edits(c: &mut Criterion) {
    let mut g = c.benchmark_group("tri_edit (apply + undo)");
    g.sample_size(10);
    for n in [24, 96] {
        let (mut map, p, q) = flipped(n);
        g.bench_function(format!("atomic 5-7 move, torus {n}"), |b| {
            b.iter(|| move_pair(&mut map, p, q, Direction::FlipLeft).map(|r| r.undo(&mut map)))
        });
        let (mut map, s, o) = far_pair(n);
        let (d, start, moved) = far_pair_directions(&map, s, o, 64).expect("directions")[0];
        g.bench_function(format!("composite 5-7 move, torus {n}"), |b| {
            b.iter(|| {
                let m = move_far_pair(&mut map, d, start, moved, o, 64).expect("applies");
                m.undo(&mut map).expect("undo")
            })
        });
    }
    g.finish();
}

/// An `n x n` equilateral lattice on a bumpy height field and the same with a spoke of its
/// centre flipped; returns both and the flip's four corners.
fn bumpy_flip(n: usize) -> (Mesh, Mesh, Vec<Vert>) {
    let mut p = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 + j as f64 * 0.5, j as f64 * 3f64.sqrt() / 2.0);
            p.push(DVec3::new(x, y, 0.8 * (0.4 * x).sin() * (0.5 * y).cos()));
        }
    }
    let mut tris = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = (j * n + i) as u32;
            let (b, c) = (a + 1, a + n as u32);
            tris.extend([[a, b, c], [b, c + 1, c]]);
        }
    }
    let input = Mesh::from_polygons(p, &tris).expect("lattice").0;
    let mut edited = input.clone();
    let centre = Vert::new(((n / 2) * n + n / 2) as u32);
    let d = edited.map.vertex_darts(centre).next().expect("spoke");
    tri::flip_edge(&mut edited.map, d).expect("flip");
    let touched = touched_vertices(&input.map, &edited.map);
    (input, edited, touched)
}

fn relaxation(c: &mut Criterion) {
    let mut g = c.benchmark_group("tri_edit relaxation");
    g.sample_size(10);
    let (input, edited, touched) = bumpy_flip(64);
    let surface = Surface::new(&input);
    for rings in [1, 2, 4, 8] {
        let region = relax_region(&edited.map, &touched, rings);
        let n = region.len();
        g.bench_function(
            format!("local, 10 sweeps, {rings} rings ({n} vertices)"),
            |b| {
                b.iter_batched(
                    || edited.clone(),
                    |mut m| relax_local(&mut m, &surface, &region, 10).expect("relaxes"),
                    BatchSize::SmallInput,
                )
            },
        );
        g.bench_function(
            format!("global, 5 solves, {rings} rings ({n} vertices)"),
            |b| {
                b.iter_batched(
                    || edited.clone(),
                    |mut m| relax_global(&mut m, &surface, &region, 5).expect("relaxes"),
                    BatchSize::SmallInput,
                )
            },
        );
    }
    g.finish();
}

criterion_group!(benches, tri_edits, relaxation);
criterion_main!(benches);
