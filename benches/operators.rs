//! Criterion benches of the operators on the 1000 x 1000 torus (quads, and triangulated):
//! each iteration applies one operator at the next of 4,096 random darts (fixed seed) and
//! undoes it, so the mesh stays the same; refused attempts count as iterations.

use criterion::{criterion_group, criterion_main, Criterion};
use zipmesh::ops::{quad, tri};
use zipmesh::rng::Rng;
use zipmesh::{Dart, Map};

fn torus(n: usize, triangles: bool) -> Map {
    let quads = zipmesh::gen::torus_quads(n, n);
    if triangles {
        let tris: Vec<[u32; 3]> = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        Map::from_polygons(n * n, &tris).expect("valid torus")
    } else {
        Map::from_polygons(n * n, &quads).expect("valid torus")
    }
}

fn darts(m: &Map) -> Vec<Dart> {
    let mut rng = Rng::new(99);
    (0..4096)
        .map(|_| Dart::new(rng.below(m.dart_slots()) as u32))
        .collect()
}

fn operators(c: &mut Criterion) {
    let mut g = c.benchmark_group("operators (apply + undo, torus 1000)");
    g.sample_size(20);
    let mut m = torus(1000, true);
    let ds = darts(&m);
    let mut i = 0;
    let mut next = || {
        i = (i + 1) % ds.len();
        ds[i]
    };
    g.bench_function("tri flip", |b| {
        b.iter(|| tri::flip_edge(&mut m, next()).map(|r| r.undo(&mut m)))
    });
    g.bench_function("tri collapse", |b| {
        b.iter(|| tri::collapse_edge(&mut m, next()).map(|r| r.undo(&mut m)))
    });
    g.bench_function("tri edge split", |b| {
        b.iter(|| tri::split_edge(&mut m, next()).map(|r| r.undo(&mut m)))
    });
    g.bench_function("tri vertex split", |b| {
        b.iter(|| {
            let d = next();
            let d2 = (0..3).fold(d, |x, _| m.rotate_cw(x));
            tri::split_vertex(&mut m, d, d2).map(|r| r.undo(&mut m))
        })
    });
    let mut q = torus(1000, false);
    g.bench_function("quad collapse", |b| {
        b.iter(|| quad::collapse_quad(&mut q, next()).map(|r| r.undo(&mut q)))
    });
    g.bench_function("quad vertex split", |b| {
        b.iter(|| {
            let d = next();
            let d2 = q.rotate_cw(q.rotate_cw(d));
            quad::split_vertex(&mut q, d, d2).map(|r| r.undo(&mut q))
        })
    });
    g.bench_function("quad edge rotation", |b| {
        b.iter(|| {
            quad::rotate_edge(&mut q, next(), quad::Rotation::Clockwise).map(|r| r.undo(&mut q))
        })
    });
    // The strip collapse of Q-zip along a grid row, then the restoring splits, on a warm
    // mesh (the workload example measures the same chains on a fresh copy).
    for k in [7usize, 100] {
        let (n, row) = (1000usize, 500usize);
        g.bench_function(
            format!("quad chain of {k} collapses + restoring splits"),
            |b| {
                b.iter(|| {
                    let mut records = Vec::with_capacity(k);
                    for i in 0..k {
                        let f = zipmesh::Face::new((row * n + 10 + i) as u32);
                        let corner = zipmesh::Vert::new((row * n + 10 + i) as u32);
                        let d = q
                            .face_darts(f)
                            .find(|&d| q.origin(d) == corner)
                            .expect("corner");
                        records.push(quad::collapse_quad(&mut q, d).expect("chain collapse"));
                    }
                    for r in records.iter().rev() {
                        r.undo(&mut q).expect("restoring split");
                    }
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, operators);
criterion_main!(benches);
