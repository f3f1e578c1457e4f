//! The quality summary of each given mesh (every `tests/data/quad/*.obj` without arguments),
//! as the markdown table of docs/quality.md, with the time of each summary:
//! `cargo run --release --example quality [--features parry] -- [--reference IN] [FILE...]`.
//!
//! With `--reference IN`, each mesh's vertices are also measured against IN's surface, and
//! the time of building the [`Reference`] and asking it once per vertex is printed (what
//! the `parry` feature speeds up).

use std::path::PathBuf;
use std::time::Instant;

use zipmesh::io;
use zipmesh::quality::{self, Reference, Summary};

/// A number with three decimals, or `-` for none.
fn f3(x: Option<f64>) -> String {
    x.map_or("-".into(), |x| format!("{x:.3}"))
}

fn main() {
    let mut files: Vec<PathBuf> = Vec::new();
    let mut reference = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--reference" => reference = Some(args.next().expect("--reference IN")),
            _ => files.push(a.into()),
        }
    }
    let reference = reference.map(|p| io::read_mesh(&p).unwrap_or_else(|e| panic!("{e}")).0);
    if files.is_empty() {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/quad");
        files = std::fs::read_dir(&dir)
            .expect("tests/data/quad")
            .map(|e| e.expect("a directory entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "obj"))
            .collect();
        files.sort();
    }
    println!("| mesh | faces | quads | folded (a/b/c) | SJ < 0 | SJ min | SJ 1st | SJ 5th | SJ median | min angle | tris < 10 deg | flipped tris | max edge ratio | degenerate | ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for path in &files {
        let (mesh, _) = io::read_mesh(path).unwrap_or_else(|e| panic!("{e}"));
        let t = Instant::now();
        let s = Summary::of(&mesh);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let j = s.jacobian;
        let name = path
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into());
        println!(
            "| {name} | {} | {} | {} ({}/{}/{}) | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {ms:.1} |",
            s.faces,
            s.quads,
            s.folded_quads,
            s.folded_by.diagonal,
            s.folded_by.corner,
            s.folded_by.neighbours,
            s.negative_jacobian,
            f3(j.map(|j| j.min)),
            f3(j.map(|j| j.p1)),
            f3(j.map(|j| j.p5)),
            f3(j.map(|j| j.median)),
            f3(s.min_angle),
            s.thin_triangles,
            s.flipped_triangles,
            f3(s.max_edge_ratio),
            s.degenerate_faces,
        );
        if let Some(input) = &reference {
            // The median of five: the build and one query per vertex.
            let mut times = Vec::new();
            let mut d = None;
            for _ in 0..5 {
                let t = Instant::now();
                d = quality::Distances::of(&mesh, &Reference::new(input));
                times.push(t.elapsed().as_secs_f64() * 1e3);
            }
            times.sort_by(f64::total_cmp);
            let d = d.expect("a reference with triangles");
            println!(
                "  distance to the reference: mean {:.6}, 99th pct {:.6}, max {:.6} of its diagonal; {:.1} ms ({})",
                d.mean,
                d.p99,
                d.max,
                times[2],
                if cfg!(feature = "parry") { "parry" } else { "optimize::Surface" }
            );
        }
    }
}
