//! Criterion benches of Q-zip on the 1000 x 1000 torus with 16 inserted
//! singularity pairs (two vertex splits each, `benches/support/qzip_torus.rs`): a v5 and a v3
//! 7 or 100 edges apart, initial operation LC (all collapses). Iterations cycle through the
//! 16 pairs on one warm map. `zip` and `zip_along` time only the Q-zip: each is undone after
//! the clock stops (`iter_custom`); `zip + undo` times both. The fast stage 1: `sketch (workspace)`
//! is the bidirectional BFS in a reused `SketchWorkspace`, `sketch (guided)` A* guided by the
//! torus's positions, `sketch (layout)` A* guided by a flat layout (`flat_layout`), and
//! `zip guided` / `zip layout` the full Q-zip with those sketches then `zip_along`.

#[path = "support/qzip_torus.rs"]
mod qzip_torus;

use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, Criterion};
use zipmesh::mesh::Edited;
use zipmesh::qzip::{self, SketchOptions, Tag};
use zipmesh::Map;

fn qzip_torus(c: &mut Criterion) {
    let mut g = c.benchmark_group("qzip (torus 1000, 16 pairs)");
    g.sample_size(20);
    g.measurement_time(Duration::from_secs(4));
    let opts = SketchOptions::default();
    for len in [7usize, 100] {
        let (mesh, ends) = qzip_torus::torus_mesh_with_pairs(1000, 16, len);
        let bound = qzip::max_edge_length(&mesh);
        let zipmesh::Mesh { mut map, positions } = mesh;
        let guided = SketchOptions::default().guide(qzip::Guide::new(&positions, bound));
        let (flat, flat_bound) = qzip_torus::flat_layout(
            1000,
            &zipmesh::Mesh {
                map: map.clone(),
                positions: positions.clone(),
            },
        );
        let layout = SketchOptions::default().guide(qzip::Guide::new(&flat, flat_bound));
        let mut ws = qzip::SketchWorkspace::new();
        let paths: Vec<qzip::Path> = ends
            .iter()
            .map(|&(a, b)| qzip::sketch(&map, a, b, &opts).expect("a path"))
            .collect();
        let mut q = qzip::Qzip::with_options(opts.clone());
        g.bench_function(
            format!("zip {len} edges (sketch+plan+prepare+execute)"),
            |b| {
                b.iter_custom(|iters| {
                    timed_zips(iters, &mut map, |m, i| {
                        let (a, v) = ends[i % ends.len()];
                        q.zip(m, a, v, Tag::LC)
                    })
                })
            },
        );
        g.bench_function(
            format!("zip_along {len} edges (plan+prepare+execute)"),
            |b| {
                b.iter_custom(|iters| {
                    timed_zips(iters, &mut map, |m, i| {
                        q.zip_along(m, &paths[i % paths.len()], Tag::LC)
                    })
                })
            },
        );
        let mut i = 0;
        g.bench_function(format!("zip + undo {len} edges"), |b| {
            b.iter(|| {
                i = (i + 1) % ends.len();
                let (a, v) = ends[i];
                let r = q.zip(&mut map, a, v, Tag::LC).expect("realizable");
                r.undo(&mut map).expect("undo")
            })
        });
        g.bench_function(format!("sketch {len} edges"), |b| {
            b.iter(|| {
                i = (i + 1) % ends.len();
                let (a, v) = ends[i];
                qzip::sketch(&map, a, v, &opts).expect("a path")
            })
        });
        for (name, o) in [
            ("workspace", &opts),
            ("guided", &guided),
            ("layout", &layout),
        ] {
            g.bench_function(format!("sketch {len} edges ({name})"), |b| {
                b.iter(|| {
                    i = (i + 1) % ends.len();
                    let (a, v) = ends[i];
                    ws.sketch(&map, a, v, o).expect("a path")
                })
            });
        }
        for (name, o) in [("guided", &guided), ("layout", &layout)] {
            let mut q = qzip::Qzip::with_options(o.clone());
            g.bench_function(
                format!("zip {name} {len} edges (workspace sketch+plan+prepare+execute)"),
                |b| {
                    b.iter_custom(|iters| {
                        timed_zips(iters, &mut map, |m, i| {
                            let (a, v) = ends[i % ends.len()];
                            q.zip(m, a, v, Tag::LC)
                        })
                    })
                },
            );
        }
    }
    g.finish();
}

/// Runs `iters` Q-zips (`zip(map, i)`), timing only the Q-zip; each is undone outside the
/// clock so every call sees the same map.
fn timed_zips(
    iters: u64,
    map: &mut Map,
    mut zip: impl FnMut(&mut Map, usize) -> Result<Edited<qzip::ZipReport, ()>, qzip::QzipError>,
) -> Duration {
    let mut total = Duration::ZERO;
    for i in 0..iters as usize {
        let t = Instant::now();
        let r = zip(map, i).expect("realizable");
        total += t.elapsed();
        r.undo(map).expect("undo");
    }
    total
}

criterion_group!(benches, qzip_torus);
criterion_main!(benches);
