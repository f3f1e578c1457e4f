//! Criterion benches of the quad-dominant edits (`zipmesh::quad_dominant`, Q-zip paper Sec. 3.2) on
//! torus grids with triangle pairs (`gen::quad_dominant`) of two sizes: each triangle move
//! applied and undone; a move and its inverse applied (no undo); a compass walk straight on
//! (4 and 11 edges on the small torus, 8 and 32 on the large) applied and undone, and there
//! and back (no undo); and the optimizer's triangle stage (crawl and merge every pair;
//! `optimize` with no batch, on a fresh copy each iteration, the copy not timed).

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use zipmesh::optimize::{optimize, Constraints, OptimizeOptions};
use zipmesh::quad_dominant::{self, compass, Move};
use zipmesh::{gen, Dart, Map, Vert};

/// The vertex `k` edges straight on from the tip along the VE direction.
fn ahead(m: &Map, tip: Dart, k: usize) -> Vert {
    let straight = |d: Dart| m.rotate_cw(m.rotate_cw(d.twin()));
    let mut d = m.rotate_cw(m.rotate_cw(tip));
    for _ in 1..k {
        d = straight(d);
    }
    m.dest(d)
}

fn moves(c: &mut Criterion) {
    let mut g = c.benchmark_group("quad-dominant (apply + undo)");
    g.sample_size(10);
    for n in [24, 256] {
        let (mut mesh, tips) = gen::quad_dominant(n, n, 1, 3);
        let t = tips[0];
        for mv in Move::ALL {
            assert!(
                quad_dominant::can_move_triangle(&mesh.map, t, mv).is_ok(),
                "{mv}"
            );
            g.bench_function(format!("{mv}, torus {n}"), |b| {
                b.iter(|| {
                    let e = mv.apply(&mut mesh, t).expect("applies");
                    e.undo(&mut mesh).expect("undo")
                })
            });
        }
        // A move then its inverse from the new tip dart: the map stays the same up to
        // isomorphism, each move applied without an undo (which copies and checks the map).
        for (a, z) in [(Move::VE, Move::EV), (Move::LE, Move::RE)] {
            let mut tip = t;
            g.bench_function(format!("{a} then {z}, apply only, torus {n}"), |b| {
                b.iter(|| {
                    let r = quad_dominant::move_triangle(&mut mesh.map, tip, a).expect("applies");
                    let r =
                        quad_dominant::move_triangle(&mut mesh.map, r.tip(), z).expect("applies");
                    tip = r.tip();
                })
            });
            assert_eq!(mesh.map.check(), Ok(()));
        }
        // Straight on, short of the way round (the 24 torus wraps at 12).
        for k in if n < 64 { [4, 11] } else { [8, 32] } {
            let target = ahead(&mesh.map, t, k);
            g.bench_function(format!("walk {k} edges, torus {n}"), |b| {
                b.iter(|| {
                    let w = compass::walk_to(&mut mesh, t, target).expect("walks");
                    w.undo(&mut mesh).expect("undo")
                })
            });
            // There and back again by the compass: the moves alone, no undo.
            let (home, mut tip) = (mesh.map.origin(t), t);
            g.bench_function(format!("walk {k} edges there and back, torus {n}"), |b| {
                b.iter(|| {
                    let w = compass::walk_to(&mut mesh, tip, target).expect("walks there");
                    tip = compass::walk_to(&mut mesh, w.tip(), home)
                        .expect("and back")
                        .tip();
                })
            });
            assert_eq!(mesh.map.check(), Ok(()));
        }
    }
    g.finish();
    let mut g = c.benchmark_group("optimize triangle stage");
    g.sample_size(10);
    for (n, pairs) in [(24, 2), (64, 8)] {
        let (mesh, tips) = gen::quad_dominant(n, n, pairs, 5);
        assert_eq!(tips.len(), 2 * pairs);
        g.bench_function(format!("{pairs} pairs, torus {n}"), |b| {
            b.iter_batched(
                || mesh.clone(),
                |mut m| {
                    let o = OptimizeOptions::default().batches(0);
                    let out = optimize(&mut m, Constraints::default(), o, |_| {}).expect("runs");
                    assert_eq!(out.final_counts.triangles, 0);
                },
                BatchSize::LargeInput,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, moves);
criterion_main!(benches);
