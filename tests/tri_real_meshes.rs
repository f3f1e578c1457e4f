//! The semantic triangle edits (`zipmesh::tri_edit`) on the shared triangle meshes of
//! `tests/data/tri/`: every adjacent interior 5-7 pair in every direction,
//! every regular interior vertex x dart x 5-5-7-7 configuration, and every interior v5 x
//! dart x 5-7 generation x reading. Each attempt is a refusal equal to its `can_*`'s with the
//! map `==`, or the documented effect and an exact undo (`common::tri_sweep`); every 50th
//! applied edit is also `check()`ed. The counts are printed (`--nocapture`) and, measured,
//! in `docs/tri-edit.md` ("On the shared meshes", `examples/tri_real_counts.rs`); the
//! assertions below only keep the sweeps from being vacuous.

mod common;

use common::tri_sweep::{sweep_pair_generations, sweep_pair_moves, sweep_quadruples, Sweep};
use zipmesh::Map;

/// The three shared triangle meshes: (file name, map).
fn meshes() -> Vec<(&'static str, Map)> {
    ["circle_disk.obj", "spot_triangulated.obj", "torus.obj"]
        .into_iter()
        .map(|name| {
            let path = common::shared(&format!("tri/{name}"));
            let (mesh, _) = zipmesh::io::read_mesh(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
            (name, mesh.map)
        })
        .collect()
}

/// Prints a sweep's counts: starts, then per configuration applied and refused by reason.
fn show<const N: usize>(what: &str, name: &str, s: &Sweep<N>) {
    let per: Vec<String> = s
        .tallies
        .iter()
        .map(|t| format!("{} {:?}", t.applied, t.refused))
        .collect();
    println!("{what} {name}: {} starts; {}", s.starts, per.join(" | "));
}

#[test]
fn every_pair_in_every_direction() {
    for (name, map) in meshes() {
        let s = sweep_pair_moves(name, &map);
        show("pair moves", name, &s);
        for t in &s.tallies {
            assert_eq!(t.attempts(), s.starts, "{name}: one attempt per pair");
        }
        match name {
            // The torus is regular: no pair at all.
            "torus.obj" => assert_eq!(s.starts, 0),
            // Measured: 90 pairs, 459 of 540 applied (disk); 420, 1,180 of 2,520 (Spot).
            _ => {
                assert!(s.starts >= 50, "{name}: {} pairs", s.starts);
                assert!(s.applied() >= 250, "{name}: {} applied", s.applied());
                // Every direction applies somewhere, and something is refused.
                assert!(s.tallies.iter().all(|t| t.applied > 0), "{name}");
                assert!(s.applied() < 6 * s.starts, "{name}");
            }
        }
    }
}

#[test]
fn every_regular_vertex_generates_quadruples() {
    for (name, map) in meshes() {
        let s = sweep_quadruples(name, &map);
        show("quadruples", name, &s);
        for t in &s.tallies {
            assert_eq!(t.attempts(), 6 * s.starts, "{name}: every dart tried");
        }
        // Measured: 740, 2,285 and 768 regular vertices; each configuration applies at
        // least 1,450 times on each mesh.
        assert!(s.starts >= 500, "{name}: {} regular vertices", s.starts);
        for (k, t) in s.tallies.iter().enumerate() {
            assert!(t.applied >= 500, "{name}: configuration {k}: {}", t.applied);
        }
        if name == "torus.obj" {
            // A regular neighbourhood everywhere: nothing is refused as irregular.
            assert!(s
                .tallies
                .iter()
                .all(|t| !t.refused.contains_key("Irregular")));
        }
    }
}

#[test]
fn every_v5_generates_pairs() {
    for (name, map) in meshes() {
        let s = sweep_pair_generations(name, &map);
        show("pair generations", name, &s);
        if name == "torus.obj" {
            assert_eq!(s.starts, 0);
            continue;
        }
        // Measured: 92 and 302 v5; each operation applies at least 350 times.
        assert!(s.starts >= 50, "{name}: {} v5", s.starts);
        for t in &s.tallies {
            assert_eq!(t.attempts(), 2 * 5 * s.starts, "{name}: every dart tried");
            assert!(t.applied >= 100, "{name}: {}", t.applied);
        }
    }
}
