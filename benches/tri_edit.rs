//! Criterion benches of the semantic triangle edits (`zipmesh::tri_edit`) on triangulated
//! tori of two sizes: an atomic 5-7 move, and a composite move (Sec. 7.1) of a 5-7 pair at
//! distance 2, each applied and undone so the mesh stays the same. The composite move
//! probes each walk step on a copy of the map, so its cost grows with the map's size.

use criterion::{criterion_group, criterion_main, Criterion};
use zipmesh::ops::tri;
use zipmesh::tri_edit::{
    far_pair_directions, generate_pair_v7, move_far_pair, move_pair, Direction, Moved, Via7,
};
use zipmesh::{Map, Vert};

/// An `n x n` triangulated torus with one diagonal flipped and that flip's first pair moved
/// 4 steps away; returns the map and that pair (v5, v7).
fn flipped(n: usize) -> (Map, Vert, Vert) {
    let tris: Vec<[u32; 3]> = zipmesh::gen::torus_quads(n, n)
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let mut map = Map::from_polygons(n * n, &tris).expect("valid torus");
    let d = map
        .dart_between(Vert::new(0), Vert::new(n as u32 + 1))
        .expect("diagonal");
    tri::flip_edge(&mut map, d).expect("flip");
    let (mut p, mut q) = (Vert::new(0), Vert::new(1));
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

criterion_group!(benches, tri_edits);
criterion_main!(benches);
