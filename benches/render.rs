//! Criterion benches of `render`: a scene (camera, depth buffer, visibility of
//! faces, balls and paths), its SVG text, and its PNG (resvg), on the shared Spot quad mesh
//! (2,928 quads) and a Catmull-Clark sphere of 3,840 quads (the icosahedron, four steps), at the default 800 x 600.

use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use zipmesh::render::{Options, Scene};
use zipmesh::{gen, io, Mesh};

fn meshes() -> Vec<(&'static str, Mesh)> {
    let spot =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/quad/spot_quadrangulated.obj");
    let mut out = vec![("sphere 3840 quads", gen::subdivided_icosahedron(4))];
    if let Ok((mesh, _)) = io::read_mesh(spot) {
        out.insert(0, ("spot 2928 quads", mesh));
    }
    out
}

fn render(c: &mut Criterion) {
    let mut g = c.benchmark_group("render 800x600");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(3));
    let options = Options::default();
    for (name, mesh) in meshes() {
        g.bench_function(format!("{name}: scene"), |b| {
            b.iter(|| Scene::new(&mesh, &options).map(|s| s.faces().len()))
        });
        let scene = Scene::new(&mesh, &options).expect("a scene");
        g.bench_function(format!("{name}: svg"), |b| b.iter(|| scene.svg().len()));
        g.bench_function(format!("{name}: png"), |b| {
            b.iter(|| scene.png().map(|p| p.len()))
        });
    }
    g.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
