//! Criterion benches of the campaign: for each built-in property, the time to check one
//! case, averaged over the first 64 cases of the default campaign (seed 0, at most 1000
//! faces; generated once, outside the measurement); and the time to generate one case.
//! Cases per second per property = 1 / the time per case.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use zipmesh::campaign::{self, Case, Config};

const CASES: u64 = 64;

fn properties(c: &mut Criterion) {
    let config = Config::default();
    let cases: Vec<Case> = (0..CASES)
        .map(|i| Case::generate(config.seed, i, config.max_faces))
        .collect();
    let mut g = c.benchmark_group("campaign (one case, 64 default cases in turn)");
    g.sample_size(20);
    g.measurement_time(std::time::Duration::from_secs(2));
    g.warm_up_time(std::time::Duration::from_millis(500));
    for p in campaign::builtin() {
        let mut i = 0;
        g.bench_function(p.name(), |b| {
            b.iter(|| {
                i = (i + 1) % cases.len();
                black_box(p.check(&cases[i]))
            })
        });
    }
    let mut i = 0;
    g.bench_function("generate a case", |b| {
        b.iter(|| {
            i = (i + 1) % CASES;
            black_box(Case::generate(config.seed, i, config.max_faces))
        })
    });
    g.finish();
}

criterion_group!(benches, properties);
criterion_main!(benches);
