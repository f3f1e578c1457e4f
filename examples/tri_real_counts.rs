//! The semantic triangle edits on every start of the shared triangle meshes:
//! `cargo run --release --example tri_real_counts`.
//!
//! For each mesh of `tests/data/tri/`, runs the sweeps of `tests/common/tri_sweep.rs`
//! (every adjacent interior 5-7 pair x six directions; every regular interior vertex x dart
//! x 5-5-7-7 configuration; every interior v5 x dart x 5-7 generation x reading), which
//! assert each attempt's contract as `tests/tri_real_meshes.rs` does, and prints markdown
//! tables of the counts: per configuration `applied / attempts`, the refusals by
//! `TriEditError` variant, and the time of the sweep (checks included). The tables are in
//! `docs/tri-edit.md`, "On the shared meshes".

use std::collections::BTreeMap;
use std::time::Instant;

#[allow(dead_code)]
#[path = "../tests/common/tri_sweep.rs"]
mod tri_sweep;

use tri_sweep::{Sweep, Tally};

const MESHES: [&str; 3] = ["circle_disk.obj", "spot_triangulated.obj", "torus.obj"];

/// A count with thousands separators.
fn n(x: usize) -> String {
    let s = x.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// The refusals of every configuration together, by reason.
fn reasons(tallies: &[Tally]) -> String {
    let mut all: BTreeMap<&str, usize> = BTreeMap::new();
    for t in tallies {
        for (k, v) in &t.refused {
            *all.entry(k).or_default() += v;
        }
    }
    if all.is_empty() {
        return "none".to_string();
    }
    let parts: Vec<String> = all
        .iter()
        .map(|(k, v)| format!("`{k}` {}", n(*v)))
        .collect();
    parts.join(", ")
}

/// One table row: the mesh, its starts, `applied / attempts` per configuration, the total,
/// the refusals by reason and the time.
fn row<const N: usize>(name: &str, s: &Sweep<N>, seconds: f64) -> String {
    let cells: Vec<String> = s
        .tallies
        .iter()
        .map(|t| format!("{} / {}", n(t.applied), n(t.attempts())))
        .collect();
    let total: usize = s.tallies.iter().map(Tally::attempts).sum();
    format!(
        "| {name} | {} | {} | {} / {} | {} | {:.2} s |",
        n(s.starts),
        cells.join(" | "),
        n(s.applied()),
        n(total),
        reasons(&s.tallies),
        seconds
    )
}

/// Runs `sweep` on every mesh and prints its table under `title`.
fn table<const N: usize>(
    title: &str,
    header: &str,
    maps: &[(&str, zipmesh::Map)],
    sweep: fn(&str, &zipmesh::Map) -> Sweep<N>,
) {
    println!("{title}\n\n{header}");
    println!("|{}", "---|".repeat(N + 5));
    for (name, map) in maps {
        let t = Instant::now();
        let s = sweep(name, map);
        println!("{}", row(name, &s, t.elapsed().as_secs_f64()));
    }
    println!();
}

fn main() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tri");
    let maps: Vec<(&str, zipmesh::Map)> = MESHES
        .iter()
        .map(|&name| {
            let (mesh, _) = zipmesh::io::read_mesh(dir.join(name))
                .unwrap_or_else(|e| panic!("{}: {e}", dir.join(name).display()));
            (name, mesh.map)
        })
        .collect();
    table(
        "5-7 pair moves (`move_pair`): every adjacent interior 5-7 pair x direction 0..5",
        "| mesh | pairs | 0 `SplitLeft` | 1 `FlipLeft` | 2 `CollapseLeft` | 3 `CollapseRight` \
         | 4 `FlipRight` | 5 `SplitRight` | all | refused by reason | time |",
        &maps,
        tri_sweep::sweep_pair_moves,
    );
    table(
        "5-5-7-7 generation (`generate_quadruple`): every regular interior vertex x dart",
        "| mesh | regular vertices | `Flip` | `Split` | `CollapseFlip` | all \
         | refused by reason | time |",
        &maps,
        tri_sweep::sweep_quadruples,
    );
    table(
        "5-7 generation at a v5 (`generate_pair`): every interior v5 x dart x reading",
        "| mesh | v5 | `Flip` | `Collapse` | `Split` | all | refused by reason | time |",
        &maps,
        tri_sweep::sweep_pair_generations,
    );
}
