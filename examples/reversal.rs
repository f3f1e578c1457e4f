//! How each movement's reverse run is found on the given quad meshes (every
//! `tests/data/quad/*.obj` without arguments), as given and after the preprocessing: the
//! markdown table of docs/VERIFICATION.md ("Reversal"):
//! `cargo run --release --example reversal -- [--max-distance D] [--pairs N] [FILE...]`.
//!
//! For the first N pairs of interior singularities (in vertex order) whose shortest path has
//! at most D edges (default 8 and 60), every movement done is reversed by
//! [`find_reverse`]: derived from the report, found by the fallback search, or missed. A
//! miss whose edit ran the v2/v6 clean-up is counted apart, and so is how many of those a
//! Q-zip reverses once the clean-up's own records are undone (the map the chain left): when
//! none is, the misses lie in the chain, not in the clean-up.

use std::path::PathBuf;

use zipmesh::invariants::{is_irregular, MeshKind};
use zipmesh::qzip::{
    find_reverse, preprocess, sketch, Qzip, ReverseWay, SketchOptions, Tag, ZipReport,
};
use zipmesh::{Map, Vert};

/// Movements, derived, searched, missed, missed after a clean-up, and of the last those
/// reversed from the map before the clean-up.
#[derive(Default)]
struct Count([usize; 6]);

/// Whether a Q-zip reverses the chain of the edit `r` that turned `map` into `edited`: its
/// clean-up records undone first, then [`find_reverse`] on that map.
fn reversed_before_cleanup(edited: &Map, r: &ZipReport, map: &Map) -> bool {
    let (v2, v6) = r.cleanup_counts();
    let records = r.records();
    let mut chain_only = edited.clone();
    let cleanup = &records[records.len() - v2 - v6..];
    cleanup
        .iter()
        .rev()
        .all(|c| c.undo(&mut chain_only).is_ok())
        && find_reverse(&chain_only, r, map).is_some()
}

fn count(map: &Map, max_distance: usize, max_pairs: usize) -> Count {
    let sing: Vec<Vert> = map
        .vertices()
        .filter(|&v| is_irregular(map, MeshKind::Quad, v) && !map.is_boundary_vertex(v))
        .collect();
    let mut c = Count::default();
    let pairs = sing
        .iter()
        .enumerate()
        .flat_map(|(i, &a)| sing[i + 1..].iter().map(move |&b| (a, b)))
        .filter_map(|(a, b)| sketch(map, a, b, &SketchOptions::default()).ok())
        .filter(|p| p.len() <= max_distance)
        .take(max_pairs);
    for path in pairs {
        for tag in Tag::CCW {
            let mut m = map.clone();
            let Ok(r) = Qzip::new().zip_along(&mut m, &path, tag) else {
                continue;
            };
            c.0[0] += 1;
            match find_reverse(&m, &r, map).map(|b| b.way) {
                Some(ReverseWay::Derived) => c.0[1] += 1,
                Some(ReverseWay::Searched) => c.0[2] += 1,
                None if r.cleanup_counts() != (0, 0) => {
                    c.0[4] += 1;
                    c.0[5] += usize::from(reversed_before_cleanup(&m, &r, map));
                }
                None => c.0[3] += 1,
            }
        }
    }
    c
}

/// One table cell: `n (p %)` of the movements.
fn cell(n: usize, of: usize) -> String {
    let pct = if of == 0 {
        0.0
    } else {
        100.0 * n as f64 / of as f64
    };
    format!("{n} ({pct:.1} %)")
}

fn main() {
    let (mut max_distance, mut max_pairs, mut files) = (8, 60, Vec::<PathBuf>::new());
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut number = || args.next().and_then(|x| x.parse().ok()).expect("a number");
        match a.as_str() {
            "--max-distance" => max_distance = number(),
            "--pairs" => max_pairs = number(),
            _ => files.push(a.into()),
        }
    }
    if files.is_empty() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/quad");
        files = std::fs::read_dir(dir)
            .expect("tests/data/quad")
            .flatten()
            .map(|e| e.path())
            .collect();
        files.sort();
    }
    println!(
        "| mesh | input | movements | derived | searched | missed | missed after a clean-up \
         | of those, reversed with the clean-up undone |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for f in &files {
        let (mesh, _) = zipmesh::io::read_mesh(f).unwrap_or_else(|e| panic!("{e}"));
        let mut pre = mesh.map.clone();
        let changed = preprocess(&mut pre).is_ok_and(|p| !p.records().is_empty());
        let inputs = [
            ("as given", Some(&mesh.map)),
            ("preprocessed", changed.then_some(&pre)),
        ];
        for (kind, map) in inputs {
            let Some(map) = map else { continue };
            let Count([n, d, s, m, mc, pre]) = count(map, max_distance, max_pairs);
            let name = f
                .file_stem()
                .map_or(String::new(), |s| s.to_string_lossy().into_owned());
            println!(
                "| {name} | {kind} | {n} | {} | {} | {} | {} | {pre} |",
                cell(d, n),
                cell(s, n),
                cell(m, n),
                cell(mc, n)
            );
        }
    }
}
