//! Runs the triangle-mesh optimizer on the shared triangle meshes and on generated ones and
//! prints one row per mesh (the numbers of `docs/optimize.md`):
//! `cargo run --release --example tri_optimize_results`.

use std::time::Instant;
use zipmesh::optimize::{optimize_triangles, TriOptimizeOptions};
use zipmesh::{gen, io, Mesh};

fn row(name: &str, mut mesh: Mesh) {
    let t = Instant::now();
    let out = optimize_triangles(&mut mesh, &TriOptimizeOptions::default(), |_| {})
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let (a, b) = (out.input, out.final_counts);
    let sum =
        |f: fn(&zipmesh::optimize::TriBatch) -> usize| out.batches.iter().map(f).sum::<usize>();
    let (flips, cancels, looks) = (
        sum(|x| x.flips),
        sum(|x| x.cancellations),
        sum(|x| x.lookaheads),
    );
    let (moves, far) = (sum(|x| x.pair_moves), sum(|x| x.far_pair_moves));
    let cut = match a.irregular() {
        0 => "none to remove".to_string(),
        n => format!(
            "{:.0} % fewer",
            100.0 * (1.0 - b.irregular() as f64 / n as f64)
        ),
    };
    println!(
        "| {name} | {} -> {} | {} -> {} ({cut}) | v5 {} v7 {} v4- {} v8+ {} | {} | {flips} / {cancels} / {looks} / {moves} / {far} | {:.3} |",
        a.faces,
        b.faces,
        a.irregular(),
        b.irregular(),
        b.v5,
        b.v7,
        b.v3 + b.v4,
        b.v8plus,
        out.batches.len(),
        t.elapsed().as_secs_f64()
    );
}

fn main() {
    println!(
        "| mesh | faces | irregular | left | batches | flips / cancellations / look-aheads / pair moves / far pair moves | s |"
    );
    println!("|---|---|---|---|---|---|---|");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tri");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    names.sort();
    for p in names {
        let (mesh, _) = io::read_mesh(&p).unwrap_or_else(|e| panic!("{e}"));
        row(&p.file_name().unwrap_or_default().to_string_lossy(), mesh);
    }
    for (faces, genus, seed) in [
        (2_000, 0, 1),
        (2_000, 2, 2),
        (20_000, 1, 3),
        (100_000, 3, 4),
    ] {
        let name = format!("random_triangle({faces}, genus {genus}, seed {seed})");
        row(&name, gen::random_triangle(faces, genus, 0, seed));
    }
}
