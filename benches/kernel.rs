//! Criterion benches of the kernel: build per face, check per dart, canonical code per face,
//! on the 1000 x 1000 torus, the same torus with a few quads cut into triangles, and the
//! largest mesh in `tests/data/`. Numbers go to `docs/benchmarks.md`.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::rng::Rng;
use zipmesh::Map;

fn torus_polygons(n: usize, cut: usize, seed: u64) -> Vec<Vec<u32>> {
    let id = |i: usize, j: usize| ((j % n) * n + (i % n)) as u32;
    let mut rng = Rng::new(seed);
    let mut is_cut = vec![false; n * n];
    for _ in 0..cut {
        is_cut[rng.below(n * n)] = true;
    }
    let mut faces = Vec::with_capacity(n * n + cut);
    for j in 0..n {
        for i in 0..n {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if is_cut[j * n + i] {
                faces.push(vec![q[0], q[1], q[2]]);
                faces.push(vec![q[0], q[2], q[3]]);
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    faces
}

fn inputs() -> Vec<(String, usize, Vec<Vec<u32>>)> {
    let n = 1000;
    let mut out = vec![
        ("torus1000".to_string(), n * n, torus_polygons(n, 0, 0)),
        (
            "torus1000_cut10".to_string(),
            n * n,
            torus_polygons(n, 10, 7),
        ),
    ];
    let largest = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/quad/blub_quadrangulated.obj"
    );
    if let Ok((mesh, _)) = zipmesh::io::read_mesh(largest) {
        out.push((
            "blub_quadrangulated".to_string(),
            mesh.positions.len(),
            mesh.polygons(),
        ));
    }
    out
}

fn kernel(c: &mut Criterion) {
    for (name, nv, faces) in inputs() {
        let map = Map::from_polygons(nv, &faces).expect("valid input");
        let mut g = c.benchmark_group(name.as_str());
        g.sample_size(10);
        g.throughput(Throughput::Elements(faces.len() as u64));
        g.bench_function("build (per face)", |b| {
            b.iter(|| Map::from_polygons(nv, &faces))
        });
        g.bench_function("canonical code (per face)", |b| {
            b.iter_batched(
                || map.clone(),
                |m| CanonicalCode::of(&m).hash(),
                BatchSize::LargeInput,
            )
        });
        g.throughput(Throughput::Elements(map.num_darts() as u64));
        g.bench_function("check (per dart)", |b| b.iter(|| map.check()));
        g.finish();
    }
}

criterion_group!(benches, kernel);
criterion_main!(benches);
