//! The kernel workload: `cargo run --release --example workload -- [N] [REPS] [qzip]`.
//!
//! Builds the N x N torus (default 1000) as quads and as triangles (each quad cut along the
//! same diagonal) and prints one line per measurement, the median of REPS (default 5) runs,
//! each from a fresh copy:
//!
//! `RESULT zipmesh <tri|quad> <what> <median> <min> <max> <unit> <count> <reps>`
//!
//! Peer programs print the same format so that one run can compare them. Operator rows
//! give ns per attempted operation on 100,000 random darts, refusals included;
//! how many were applied goes to stderr. Q-zip rows give microseconds per Q-zip
//! on the same N x N torus (at least 128 x 128, and wider than 2 L + 20 for L-edge paths)
//! and on a real mesh; see `qzip_rows`. With the third argument `qzip`, only the Q-zip rows
//! (with `optimize`, only the optimizer rows: `optimize_rows`; with `tri_moves`, only the
//! triangle-edit rows: `tri_moves_rows`, on tori of fixed sizes, N unused; with `canonical`,
//! only the canonical code rows: `canonical_rows`, N unused (with a folder after it, the tori are
//! also written there as OFF files for `benches/peers/traces_canon.c`); with `chains`,
//! only the chain rows: `chain_rows`; with `check`, the check beside a sequential read of
//! as much memory: `check_rows`; with `build`, only the two build rows (quad, tri); with
//! `ops [KIND_NAME]`, only the operator rows, or
//! the one named like `tri_op_flip`, and the memory latency rows: `memory_latency`)
//! are run.

use std::time::Instant;
use zipmesh::invariants::canonical::{CanonicalCode, CanonicalWorkspace};
use zipmesh::invariants::{euler_characteristic, Counts, Histograms};
use zipmesh::ops::{quad, tri};
use zipmesh::qzip::{self, SketchOptions, Tag};
use zipmesh::rng::Rng;
use zipmesh::{Dart, Face, Map, Vert};

fn triangulate(quads: &[[u32; 4]]) -> Vec<[u32; 3]> {
    quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect()
}

/// The quads with `k` of them (chosen from a fixed seed) cut into two triangles.
fn cut_some(quads: &[[u32; 4]], k: usize, seed: u64) -> Vec<Vec<u32>> {
    let mut rng = Rng::new(seed);
    let mut cut = vec![false; quads.len()];
    for _ in 0..k {
        cut[rng.below(quads.len())] = true;
    }
    let mut out = Vec::with_capacity(quads.len() + k);
    for (q, &c) in quads.iter().zip(&cut) {
        if c {
            out.push(vec![q[0], q[1], q[2]]);
            out.push(vec![q[0], q[2], q[3]]);
        } else {
            out.push(q.to_vec());
        }
    }
    out
}

/// Runs `f` on a fresh `setup()` value `reps` times and returns (median, min, max) seconds.
fn measure<T, R>(
    reps: usize,
    mut setup: impl FnMut() -> T,
    mut f: impl FnMut(T) -> R,
) -> (f64, f64, f64) {
    let mut times: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let input = setup();
            let t = Instant::now();
            let r = f(input);
            let s = t.elapsed().as_secs_f64();
            std::hint::black_box(r);
            s
        })
        .collect();
    times.sort_by(|a, b| a.total_cmp(b));
    (times[times.len() / 2], times[0], times[times.len() - 1])
}

fn report(
    kind: &str,
    what: &str,
    (med, min, max): (f64, f64, f64),
    unit: &str,
    count: usize,
    reps: usize,
) {
    let scale = match unit {
        "ns/face" | "ns/vertex" | "ns/dart" | "ns/op" => 1e9 / count as f64,
        "us/chain" | "us/qzip" | "us/move" => 1e6 / count as f64,
        "ms" => 1e3,
        _ => 1.0,
    };
    println!(
        "RESULT zipmesh {kind} {what} {:.3} {:.3} {:.3} {unit} {count} {reps}",
        med * scale,
        min * scale,
        max * scale
    );
}

/// Optimizer rows: seconds for the first batch (the one with the most
/// singularities) on one Catmull-Clark step of a random genus-3 triangle mesh of 250, 1,000
/// and 4,000 triangles (750 to 12,000 quads), and on Spot; `count` is the number of
/// singularities before the batch. With the third argument `optimize`.
fn optimize_rows(reps: usize) {
    use zipmesh::optimize::{optimize, Constraints, OptimizeOptions, SingularityCounts};
    let mut meshes: Vec<(String, zipmesh::Mesh)> = [250, 1000, 4000]
        .iter()
        .map(|&t| {
            let m = zipmesh::gen::catmull_clark(&zipmesh::gen::random_triangle(t, 3, 0, 1));
            (format!("cc-genus3-{}q", m.map.num_faces()), m)
        })
        .collect();
    let spot = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/quad/spot_quadrangulated.obj"
    );
    if let Ok((m, _)) = zipmesh::io::read_mesh(spot) {
        meshes.push(("spot".to_string(), m));
    }
    for (name, mesh) in meshes {
        let count = SingularityCounts::of(&mesh).singularities();
        let t = measure(
            reps,
            || mesh.clone(),
            |mut m| {
                let o = OptimizeOptions::default().batches(1);
                optimize(&mut m, Constraints::default(), o, |_| {})
            },
        );
        report(
            "quad",
            &format!("optimize-batch-{name}"),
            t,
            "s/batch",
            count,
            reps,
        );
    }
}

#[path = "../benches/support/qzip_torus.rs"]
mod qzip_torus;

#[path = "../benches/support/tri_torus.rs"]
mod tri_torus;

/// Triangle-edit rows, microseconds per edit with its undo (both timed; the map is
/// the same after each), on the `n x n` triangulated torus for `n` = 48 and 192 (4,608 and
/// 73,728 faces), with a lone 5-7 pair made by `tri_torus::far_pair`:
///
/// * `tri{n}_move_{D}`: the atomic 5-7 move (`move_pair`) of an adjacent pair in direction
///   `D` (0 to 5), 2,000 per repetition;
/// * `tri{n}_far{L}`: the composite move (`move_far_pair`, Sec. 7.1.1) of a pair `L` edges
///   apart, started at its v5, every direction `far_pair_directions` finds, 20 each;
/// * `tri{n}_triple{L}`: the same moves' steps 2 and 3 alone (`cancel_triple_along` of the
///   generated pair and the v7; the generation done before, not timed).
///
/// A `#` line per `L` gives the directions found and the walk's atomic moves (mean, min, max).
fn tri_moves_rows(reps: usize) {
    use zipmesh::tri_edit::{move_pair, Direction};
    for n in [48usize, 192] {
        let (mut map, s, t) = tri_torus::far_pair(n, 1);
        let before = map.clone();
        let rounds = 2000;
        for dir in Direction::ALL {
            let time = measure(
                reps,
                || (),
                |_| {
                    for _ in 0..rounds {
                        let r = move_pair(&mut map, s, t, dir).expect("a lone pair moves");
                        r.undo(&mut map).expect("undo of a move just made");
                    }
                },
            );
            assert!(map == before, "undo restores the map");
            let what = format!("tri{n}_move_{}", dir.index());
            report("tri", &what, time, "us/move", rounds, reps);
        }
        for len in [2usize, 3, 4, 6, 8] {
            far_rows(n, len, reps);
        }
    }
}

/// For each composite start towards `t` (untimed): the walk's length, and a copy of `map`
/// with the start's generation done and the triple `[t, p, q]` it leaves.
fn triple_cases(
    map: &mut Map,
    starts: &[zipmesh::tri_edit::FarStart],
    t: Vert,
) -> (Vec<usize>, Vec<(Map, [Vert; 3])>) {
    use zipmesh::tri_edit::{generate_pair, generate_pair_v7, move_far_pair, Start};
    let mut walks = Vec::new();
    let mut cases = Vec::new();
    for &(d, start, moved) in starts {
        let m = move_far_pair(map, d, start, moved, t, 64).expect("a direction found");
        walks.push(m.walk().moves().len());
        m.undo(map).expect("undo");
        let mut g = map.clone();
        let made = match start {
            Start::Five(via) => generate_pair(&mut g, d, via, moved),
            Start::Seven(via) => generate_pair_v7(&mut g, d, via, moved),
        };
        let (p, q) = made.expect("its generation").pair().expect("a pair");
        cases.push((g, [t, p, q]));
    }
    (walks, cases)
}

/// The `tri{n}_far{len}` and `tri{n}_triple{len}` rows of [`tri_moves_rows`].
fn far_rows(n: usize, len: usize, reps: usize) {
    use zipmesh::tri_edit::{cancel_triple_along, far_pair_directions, move_far_pair};
    let (mut map, s, t) = tri_torus::far_pair(n, len);
    let before = map.clone();
    let starts = far_pair_directions(&map, s, t, 64).expect("the pair's directions");
    assert!(
        !starts.is_empty(),
        "torus {n}, distance {len}: no direction"
    );
    let (walks, mut cases) = triple_cases(&mut map, &starts, t);
    assert!(map == before, "undo restores the map");
    let rounds = 20;
    let count = starts.len() * rounds;
    let time = measure(
        reps,
        || (),
        |_| {
            for _ in 0..rounds {
                for &(d, start, moved) in &starts {
                    let m = move_far_pair(&mut map, d, start, moved, t, 64).expect("applies");
                    m.undo(&mut map).expect("undo");
                }
            }
        },
    );
    report(
        "tri",
        &format!("tri{n}_far{len}"),
        time,
        "us/move",
        count,
        reps,
    );
    let time = measure(
        reps,
        || (),
        |_| {
            for _ in 0..rounds {
                for (g, three) in &mut cases {
                    let c = cancel_triple_along(g, &three[..], 64).expect("cancels");
                    c.undo(g).expect("undo");
                }
            }
        },
    );
    report(
        "tri",
        &format!("tri{n}_triple{len}"),
        time,
        "us/move",
        count,
        reps,
    );
    let mean = walks.iter().sum::<usize>() as f64 / walks.len() as f64;
    let (lo, hi) = (walks.iter().min(), walks.iter().max());
    println!(
        "# tri{n}_far{len}: {} directions, walk of {mean:.2} moves ({}..{})",
        starts.len(),
        lo.unwrap_or(&0),
        hi.unwrap_or(&0)
    );
}

/// Times `op` on each case in turn, `rounds` times over, on the same map: only `op` is inside
/// the timing; the Q-zip it returns is undone after the clock stops (so the map is the same
/// for every call). Returns (median, min, max) over `reps` of the total time per repetition.
fn measure_zips<C>(
    reps: usize,
    map: &mut Map,
    cases: &[C],
    rounds: usize,
    mut op: impl FnMut(&mut Map, &C) -> zipmesh::mesh::Edited<qzip::ZipReport, ()>,
) -> (f64, f64, f64) {
    let mut times: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let mut total = 0.0;
            for _ in 0..rounds {
                for c in cases {
                    let t = Instant::now();
                    let r = op(map, c);
                    total += t.elapsed().as_secs_f64();
                    r.undo(map).expect("undo of a Q-zip just done");
                }
            }
            total
        })
        .collect();
    times.sort_by(|a, b| a.total_cmp(b));
    (times[times.len() / 2], times[0], times[times.len() - 1])
}

/// Times `sketch` over every pair, `rounds` times over, and prints its row (microseconds per
/// sketch).
fn sketch_row(
    name: &str,
    reps: usize,
    rounds: usize,
    ends: &[(Vert, Vert)],
    mut sketch: impl FnMut(Vert, Vert) -> qzip::Path,
) {
    let t = measure(
        reps,
        || (),
        |_| {
            for _ in 0..rounds {
                for &(a, b) in ends {
                    std::hint::black_box(sketch(a, b));
                }
            }
        },
    );
    report("quad", name, t, "us/qzip", ends.len() * rounds, reps);
}

/// Q-zip rows, microseconds per Q-zip, undo not timed (see `measure_zips`):
///
/// * `qzip{L}_{TAG}`: the full Q-zip (`qzip::Qzip::zip`: sketch in the entry point's reused
///   workspace, plan, prepare, execute) of a v5
///   and a v3 `L` edges apart on the n x n torus, 16 pairs (each made by two vertex
///   splits, see `benches/support/qzip_torus.rs`) on rows n / 16 apart, with the initial
///   operation TAG (LC: `L` collapses; RC: one split and `L - 1` collapses);
///   `qzip{L}_{TAG}_along` the same without the sketch (`Qzip::zip_along` a path found before),
///   `qzip{L}_sketch` the sketch alone.
/// * The fast stage 1 (`qzip::SketchWorkspace`, reused): `qzip{L}_sketch_ws` the bidirectional
///   BFS, `qzip{L}_sketch_guided` A* guided by the torus's positions (`qzip::Guide`, split
///   copies at the mean of their neighbours), `qzip{L}_sketch_layout` A* guided by a flat
///   layout of the torus (`flat_layout` in `benches/support/qzip_torus.rs`: points whose
///   distance follows the rows, not the geometry), and `qzip{L}_{TAG}_guided`,
///   `qzip{L}_{TAG}_layout` the full Q-zip with those sketches (`Qzip::zip` with the guide in its
///   options; the same path, so the same edit). A `#` line gives the vertices each sketch
///   explored, mean over the pairs.
/// * `qzip_spot`: the full Q-zip of every realizable (pair, initial operation) of irregular
///   vertices within 12 edges on `spot_quadrangulated.obj` (skipped if the file is missing),
///   the mean per Q-zip.
fn qzip_rows(n: usize, reps: usize) {
    let opts = SketchOptions::default();
    for (len, rounds) in [(7usize, 32usize), (100, 2)] {
        // At least 128, and wide enough that the row is the one shortest way round.
        let n = n.max(128).max(2 * len + 21);
        let (mesh, ends) = qzip_torus::torus_mesh_with_pairs(n, 16, len);
        let bound = qzip::max_edge_length(&mesh);
        let (flat, flat_bound) = qzip_torus::flat_layout(n, &mesh);
        let zipmesh::Mesh { mut map, positions } = mesh;
        let guided = SketchOptions::default().guide(qzip::Guide::new(&positions, bound));
        let layout = SketchOptions::default().guide(qzip::Guide::new(&flat, flat_bound));
        let mut ws = qzip::SketchWorkspace::new();
        let mut q = qzip::Qzip::new();
        let before = map.clone();
        let paths: Vec<qzip::Path> = ends
            .iter()
            .map(|&(a, b)| qzip::sketch(&map, a, b, &opts).expect("a path"))
            .collect();
        assert!(paths.iter().all(|p| p.len() == len));
        for tag in [Tag::LC, Tag::RC] {
            // Realizable, and undone exactly: checked once, outside the timing.
            for &(a, b) in &ends {
                let r = q.zip(&mut map, a, b, tag).expect("a realizable Q-zip");
                r.undo(&mut map).expect("undo");
                assert!(map == before, "undo restores the map");
            }
            let count = ends.len() * rounds;
            let t = measure_zips(reps, &mut map, &ends, rounds, |m, &(a, b)| {
                q.zip(m, a, b, tag).expect("realizable")
            });
            report(
                "quad",
                &format!("qzip{len}_{tag}"),
                t,
                "us/qzip",
                count,
                reps,
            );
            let t = measure_zips(reps, &mut map, &paths, rounds, |m, p| {
                q.zip_along(m, p, tag).expect("realizable")
            });
            report(
                "quad",
                &format!("qzip{len}_{tag}_along"),
                t,
                "us/qzip",
                count,
                reps,
            );
        }
        sketch_row(&format!("qzip{len}_sketch"), reps, rounds, &ends, |a, b| {
            qzip::sketch(&map, a, b, &opts).expect("a path")
        });
        // The fast sketches give the same paths; count what each explores.
        let mut explored = [0usize; 3];
        for (&(a, b), p) in ends.iter().zip(&paths) {
            for (k, o) in [&opts, &guided, &layout].into_iter().enumerate() {
                assert_eq!(&ws.sketch(&map, a, b, o).expect("a path"), p);
                explored[k] += ws.explored();
            }
        }
        let fast = [(&opts, "ws"), (&guided, "guided"), (&layout, "layout")];
        for (k, &(o, name)) in fast.iter().enumerate() {
            sketch_row(
                &format!("qzip{len}_sketch_{name}"),
                reps,
                rounds,
                &ends,
                |a, b| ws.sketch(&map, a, b, o).expect("a path"),
            );
            println!(
                "# qzip{len}_sketch_{name}: {:.0} vertices explored per sketch",
                explored[k] as f64 / ends.len() as f64
            );
        }
        for (tag, (o, name)) in [Tag::LC, Tag::RC]
            .into_iter()
            .flat_map(|t| [(t, (&guided, "guided")), (t, (&layout, "layout"))])
        {
            let mut q = qzip::Qzip::with_options(o.clone());
            let t = measure_zips(reps, &mut map, &ends, rounds, |m, &(a, b)| {
                q.zip(m, a, b, tag).expect("realizable")
            });
            report(
                "quad",
                &format!("qzip{len}_{tag}_{name}"),
                t,
                "us/qzip",
                ends.len() * rounds,
                reps,
            );
        }
        assert!(map == before);
    }

    let spot = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/quad/spot_quadrangulated.obj"
    );
    let Ok((mesh, _)) = zipmesh::io::read_mesh(spot) else {
        eprintln!("# qzip_spot skipped: cannot read {spot}");
        return;
    };
    let bound = qzip::max_edge_length(&mesh);
    let zipmesh::Mesh { mut map, positions } = mesh;
    let sing: Vec<Vert> =
        zipmesh::invariants::irregular_vertices(&map, zipmesh::invariants::MeshKind::Quad);
    let mut q = qzip::Qzip::new();
    let mut cases = Vec::new();
    let mut tried = 0;
    for &a in &sing {
        for &b in &sing {
            let Ok(p) = qzip::sketch(&map, a, b, &opts) else {
                continue;
            };
            if a == b || p.len() > 12 {
                continue;
            }
            for tag in Tag::CCW {
                tried += 1;
                if let Ok(r) = q.zip_along(&mut map, &p, tag) {
                    r.undo(&mut map).expect("undo");
                    cases.push((a, b, tag, p.len()));
                }
            }
        }
    }
    let mean_len = cases.iter().map(|c| c.3).sum::<usize>() as f64 / cases.len().max(1) as f64;
    eprintln!(
        "# qzip_spot: {} realizable of {tried} (pair, tag) within 12 edges, mean path {mean_len:.2} edges",
        cases.len()
    );
    let t = measure_zips(reps, &mut map, &cases, 1, |m, &(a, b, tag, _)| {
        q.zip(m, a, b, tag).expect("realizable")
    });
    report("quad", "qzip_spot", t, "us/qzip", cases.len(), reps);
    // The same Q-zips with the sketch guided by Spot's own positions (A*), and without the
    // sketch (paths found before): what the sketch costs on a real mesh.
    let guide = SketchOptions::default().guide(qzip::Guide::new(&positions, bound));
    let mut guided = qzip::Qzip::with_options(guide);
    let t = measure_zips(reps, &mut map, &cases, 1, |m, &(a, b, tag, _)| {
        guided.zip(m, a, b, tag).expect("realizable")
    });
    report("quad", "qzip_spot_guided", t, "us/qzip", cases.len(), reps);
    let along: Vec<(qzip::Path, Tag)> = cases
        .iter()
        .map(|&(a, b, tag, _)| (qzip::sketch(&map, a, b, &opts).expect("a path"), tag))
        .collect();
    let t = measure_zips(reps, &mut map, &along, 1, |m, (p, tag)| {
        q.zip_along(m, p, *tag).expect("realizable")
    });
    report("quad", "qzip_spot_along", t, "us/qzip", cases.len(), reps);
    spot_movements(&mut map, &cases, reps);
}

/// The optimizer's form on Spot ("per movement" in docs/benchmarks.md): one sketch per pair, then
/// each of its realizable movements along that path (each undone outside the clock), so a
/// movement costs its share of the sketch plus one `zip_along`. Microseconds per movement.
fn spot_movements(map: &mut Map, cases: &[(Vert, Vert, Tag, usize)], reps: usize) {
    let mut groups: Vec<(Vert, Vert, Vec<Tag>)> = Vec::new();
    for &(a, b, tag, _) in cases {
        match groups.last_mut() {
            Some(g) if (g.0, g.1) == (a, b) => g.2.push(tag),
            _ => groups.push((a, b, vec![tag])),
        }
    }
    let mut ws = qzip::SketchWorkspace::new();
    let q = qzip::Qzip::new();
    let opts = SketchOptions::default();
    let mut sketching = 0.0;
    let mut times: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let mut total = 0.0;
            for (a, b, tags) in &groups {
                let t = Instant::now();
                let path = ws.sketch(map, *a, *b, &opts).expect("a path");
                let s = t.elapsed().as_secs_f64();
                total += s;
                sketching += s;
                for &tag in tags {
                    let t = Instant::now();
                    let r = q.zip_along(map, &path, tag).expect("realizable");
                    total += t.elapsed().as_secs_f64();
                    r.undo(map).expect("undo of a Q-zip just done");
                }
            }
            total
        })
        .collect();
    times.sort_by(|a, b| a.total_cmp(b));
    let t = (times[times.len() / 2], times[0], times[times.len() - 1]);
    report(
        "quad",
        "qzip_spot_per_movement",
        t,
        "us/qzip",
        cases.len(),
        reps,
    );
    eprintln!(
        "# qzip_spot_per_movement: {} paths, {} movements, {:.3} us per sketch",
        groups.len(),
        cases.len(),
        sketching * 1e6 / (groups.len() * reps.max(1)) as f64
    );
}

/// Collapses `k` quads along grid row `row` from column `col` (each merging a quad's
/// lower-left corner with its upper-right one, the strip collapse of Q-zip; columns wrap
/// round the torus), then undoes them in reverse; false if any step was refused.
fn collapse_chain(m: &mut Map, n: usize, row: usize, col: usize, k: usize) -> bool {
    let mut records = Vec::with_capacity(k);
    for i in 0..k {
        let at = (row * n + (col + i) % n) as u32;
        let corner = Vert::new(at);
        let Some(d) = m.face_darts(Face::new(at)).find(|&d| m.origin(d) == corner) else {
            return false;
        };
        match quad::collapse_quad(m, d) {
            Ok(r) => records.push(r),
            Err(_) => return false,
        }
    }
    records.into_iter().rev().all(|r| r.undo(m).is_ok())
}

/// Chain rows (issues 3 and 15), in two forms. `chain{k}_collapse_restore`: one chain on a
/// fresh copy of the torus (cold caches), as before. `chain{k}_random_places`: the peers'
/// form, 10,000 chains at random places (row and column from a fixed seed) on one copy,
/// each restored before the next, so the map is the same for every chain; per chain.
fn chain_rows(quad_map: &Map, n: usize, reps: usize) {
    const CHAINS: usize = 10_000;
    // A chain longer than the row would wrap onto itself.
    for k in [7usize, 100].into_iter().filter(|&k| k + 2 <= n) {
        let mut ok = true;
        let t = measure(
            reps,
            || quad_map.clone(),
            |mut m| {
                ok &= collapse_chain(&mut m, n, n / 2, 10, k);
                m
            },
        );
        assert!(ok, "the chain of {k} collapses applies and restores");
        report(
            "quad",
            &format!("chain{k}_collapse_restore"),
            t,
            "us/chain",
            1,
            reps,
        );
        let mut rng = Rng::new(k as u64);
        let places: Vec<(usize, usize)> =
            (0..CHAINS).map(|_| (rng.below(n), rng.below(n))).collect();
        let mut warm = quad_map.clone();
        let t = measure(
            reps,
            || (),
            |_| {
                let done = places
                    .iter()
                    .filter(|&&(r, c)| collapse_chain(&mut warm, n, r, c, k))
                    .count();
                ok &= done == CHAINS;
            },
        );
        assert!(ok, "every chain of {k} collapses applies and restores");
        assert!(&warm == quad_map, "the chains leave the map as it was");
        report(
            "quad",
            &format!("chain{k}_random_places"),
            t,
            "us/chain",
            CHAINS,
            reps,
        );
    }
}

/// Applies `op` at every dart in turn; the number applied. Not inlined, so that
/// `valgrind --tool=callgrind --toggle-collect=*apply_all*` counts the operators alone.
#[inline(never)]
fn apply_all(m: &mut Map, darts: &[Dart], op: fn(&mut Map, Dart) -> bool) -> usize {
    darts.iter().filter(|&&d| op(m, d)).count()
}

/// Operator rows: 100,000 random darts from a fixed seed per repetition (one per
/// eight quads on smaller tori, such as the 64 x 64 one that fits in the L2 cache), each
/// repetition on a fresh copy; refused attempts are included in the time. With `only`,
/// just the rows whose name is `only` (`ops NAME` on the command line).
fn operator_rows(tri_map: &Map, quad_map: &Map, reps: usize, only: Option<&str>) {
    let count = (quad_map.num_faces() / 8).clamp(1, 100_000);
    let random_darts = |m: &Map, seed: u64| -> Vec<Dart> {
        let mut rng = Rng::new(seed);
        (0..count)
            .map(|_| Dart::new(rng.below(m.dart_slots()) as u32))
            .collect()
    };
    type Op = fn(&mut Map, Dart) -> bool;
    let tri_ops: [(&str, Op); 4] = [
        ("op_flip", |m, d| tri::flip_edge(m, d).is_ok()),
        ("op_collapse", |m, d| tri::collapse_edge(m, d).is_ok()),
        ("op_edge_split", |m, d| tri::split_edge(m, d).is_ok()),
        ("op_vertex_split", |m, d| {
            let d2 = (0..3).fold(d, |x, _| m.rotate_cw(x));
            tri::split_vertex(m, d, d2).is_ok()
        }),
    ];
    let quad_ops: [(&str, Op); 4] = [
        ("op_quad_collapse", |m, d| quad::collapse_quad(m, d).is_ok()),
        ("op_vertex_split", |m, d| {
            let d2 = m.rotate_cw(m.rotate_cw(d));
            quad::split_vertex(m, d, d2).is_ok()
        }),
        ("op_rotate_edge", |m, d| {
            quad::rotate_edge(m, d, quad::Rotation::Clockwise).is_ok()
        }),
        ("op_doublet_insert", |m, d| {
            quad::insert_doublet(m, d).is_ok()
        }),
    ];
    for (kind, base, ops) in [
        ("tri", tri_map, &tri_ops[..]),
        ("quad", quad_map, &quad_ops[..]),
    ] {
        for (k, &(what, op)) in ops.iter().enumerate() {
            if only.is_some_and(|o| o != format!("{kind}_{what}")) {
                continue;
            }
            let darts = random_darts(base, 1000 + k as u64);
            let mut applied = 0;
            let t = measure(
                reps,
                || base.clone(),
                |mut m| {
                    applied = apply_all(&mut m, &darts, op);
                    m
                },
            );
            report(kind, what, t, "ns/op", count, reps);
            eprintln!("# {kind} {what}: {applied} of {count} applied");
            // The operators that add elements, with room reserved outside the clock: what
            // the first growth of the freshly cloned arrays costs inside the row above.
            if what.contains("split") || what.contains("doublet") {
                let t = measure(
                    reps,
                    || {
                        let mut m = base.clone();
                        m.reserve(3 * count, count, 2 * count).expect("memory");
                        m
                    },
                    |mut m| {
                        apply_all(&mut m, &darts, op);
                        m
                    },
                );
                report(kind, &format!("{what}_reserved"), t, "ns/op", count, reps);
            }
        }
    }
}

/// The validity check of the `n` x `n` quad torus beside what bounds it: one
/// sequential read of as many `u32`s as the map's five arrays hold (three per dart, one per
/// vertex and per face), the least memory traffic of any check that reads every entry once.
/// Milliseconds; with the third argument `check`.
fn check_rows(n: usize, reps: usize) {
    let quads = zipmesh::gen::torus_quads(n, n);
    let map = Map::from_polygons(n * n, &quads).expect("valid torus");
    let nf = map.num_faces();
    // Both on a fresh copy, as the check row of the main table.
    let t = measure(reps, || map.clone(), |m| m.check().is_ok());
    report("quad", "check", t, "ms", nf, reps);
    let words = 3 * map.dart_slots() + map.vertex_slots() + map.face_slots();
    let data: Vec<u32> = (0..words as u32).collect();
    let t = measure(
        reps,
        || data.clone(),
        |d| d.iter().fold(0u32, |a, &x| a.wrapping_add(x)),
    );
    report(
        "mem",
        &format!("stream_read_{}MiB", (4 * words) >> 20),
        t,
        "ms",
        nf,
        reps,
    );
}

/// Nanoseconds per load of a chain of dependent loads through `bytes` of memory in a
/// random cyclic order (every load a cache miss once `bytes` is past the last-level
/// cache): the latency that bounds an operator whose loads depend on each other.
fn memory_latency(bytes: usize, reps: usize) {
    let n = (bytes / 8).max(2);
    // Sattolo's shuffle: one cycle through every slot.
    let mut next: Vec<usize> = (0..n).collect();
    let mut rng = Rng::new(7);
    for i in (1..n).rev() {
        next.swap(i, rng.below(i));
    }
    const LOADS: usize = 2_000_000;
    let t = measure(reps, || (), |_| (0..LOADS).fold(0usize, |i, _| next[i]));
    report(
        "mem",
        &format!("dependent_load_{}MiB", bytes >> 20),
        t,
        "ns/op",
        LOADS,
        reps,
    );
}

/// Writes `faces` over `nv` vertices (all at the origin) as an OFF file, for the peers'
/// harnesses (`benches/peers/traces_canon.c`).
fn write_off<F: AsRef<[u32]>>(path: &std::path::Path, nv: usize, faces: &[F]) {
    use std::fmt::Write as _;
    let mut s = format!("OFF\n{nv} {} 0\n", faces.len());
    s.push_str(&"0 0 0\n".repeat(nv));
    for f in faces {
        let _ = write!(s, "{}", f.as_ref().len());
        for v in f.as_ref() {
            let _ = write!(s, " {v}");
        }
        s.push('\n');
    }
    std::fs::write(path, s).expect("the OFF file is written");
}

/// Canonical code rows: the regular torus of 1,024, 10,000 and 99,856 quads, and
/// the same with 5 quads cut into triangles, in ns per face; each by [`CanonicalCode::of`]
/// and (`_ws`) by a [`CanonicalWorkspace`] kept from one repetition to the next, used once
/// before them (as Traces keeps its arrays between its runs). With the third argument
/// `canonical`, only these rows are run; with a folder after it, the tori are also written
/// there as OFF files for the peers' harnesses.
fn canonical_rows(reps: usize, dump: Option<&str>) {
    for side in [32usize, 100, 316] {
        let q = zipmesh::gen::torus_quads(side, side);
        let regular = Map::from_polygons(side * side, &q).expect("valid torus");
        let faces = q.len();
        if let Some(dir) = dump {
            let dir = std::path::Path::new(dir);
            std::fs::create_dir_all(dir).expect("the folder is made");
            write_off(&dir.join(format!("torus_{faces}.off")), side * side, &q);
            let cut = cut_some(&q, 5, side as u64);
            write_off(
                &dir.join(format!("torus_{faces}_cut5.off")),
                side * side,
                &cut,
            );
        }
        let cut =
            Map::from_polygons(side * side, &cut_some(&q, 5, side as u64)).expect("valid torus");
        for (map, name) in [
            (&regular, format!("{faces}")),
            (&cut, format!("{faces}_cut5")),
        ] {
            report(
                "quad",
                &format!("canonical_torus_{name}"),
                measure(reps, || map.clone(), |m| CanonicalCode::of(&m).hash()),
                "ns/face",
                map.num_faces(),
                reps,
            );
            let mut ws = CanonicalWorkspace::new();
            ws.hash(map);
            report(
                "quad",
                &format!("canonical_torus_{name}_ws"),
                measure(reps, || map.clone(), |m| ws.hash(&m)),
                "ns/face",
                map.num_faces(),
                reps,
            );
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args
        .get(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000)
        .max(3);
    let reps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    if args.get(3).is_some_and(|s| s == "qzip") {
        qzip_rows(n, reps);
        return;
    }
    if args.get(3).is_some_and(|s| s == "canonical") {
        canonical_rows(reps, args.get(4).map(String::as_str));
        return;
    }
    if args.get(3).is_some_and(|s| s == "tri_moves") {
        tri_moves_rows(reps);
        return;
    }
    if args.get(3).is_some_and(|s| s == "check") {
        check_rows(n, reps);
        return;
    }
    if args.get(3).is_some_and(|s| s == "optimize") {
        optimize_rows(reps);
        return;
    }
    if args.get(3).is_some_and(|s| s == "ops") {
        let quads = zipmesh::gen::torus_quads(n, n);
        let quad_map = Map::from_polygons(n * n, &quads).expect("valid torus");
        let tri_map = Map::from_polygons(n * n, &triangulate(&quads)).expect("valid torus");
        operator_rows(&tri_map, &quad_map, reps, args.get(4).map(String::as_str));
        for mib in [1, 8, 64, 256] {
            memory_latency(mib << 20, reps);
        }
        return;
    }
    if args.get(3).is_some_and(|s| s == "chains") {
        let quads = zipmesh::gen::torus_quads(n, n);
        let map = Map::from_polygons(n * n, &quads).expect("valid torus");
        chain_rows(&map, n, reps);
        return;
    }
    let quads = zipmesh::gen::torus_quads(n, n);
    let tris = triangulate(&quads);
    let nv = n * n;
    let build_only = args.get(3).is_some_and(|s| s == "build");

    for kind in ["quad", "tri"] {
        let build = |nv: usize| -> Map {
            if kind == "quad" {
                Map::from_polygons(nv, &quads).expect("valid torus")
            } else {
                Map::from_polygons(nv, &tris).expect("valid torus")
            }
        };
        let nf = if kind == "quad" {
            quads.len()
        } else {
            tris.len()
        };
        report(
            kind,
            "build",
            measure(reps, || (), |_| build(nv)),
            "ns/face",
            nf,
            reps,
        );
        if build_only {
            continue;
        }
        let map = build(nv);
        let bytes = map.heap_bytes() as f64 / nf as f64;
        report(
            kind,
            "topology_bytes",
            (bytes, bytes, bytes),
            "bytes/face",
            nf,
            1,
        );
        report(
            kind,
            "valence",
            measure(
                reps,
                || map.clone(),
                |m| {
                    (0..nv as u32)
                        .map(|v| m.valence(Vert::new(v)))
                        .sum::<usize>()
                },
            ),
            "ns/vertex",
            nv,
            reps,
        );
        // Euler characteristic is O(1) from the live counts; `counts` adds components,
        // boundary loops and genus, which need a pass over the mesh.
        report(
            kind,
            "euler",
            measure(reps, || map.clone(), |m| euler_characteristic(&m)),
            "ms",
            nf,
            reps,
        );
        report(
            kind,
            "counts",
            measure(reps, || map.clone(), |m| Counts::of(&m)),
            "ms",
            nf,
            reps,
        );
        report(
            kind,
            "histograms",
            measure(reps, || map.clone(), |m| Histograms::of(&m)),
            "ms",
            nf,
            reps,
        );
        report(
            kind,
            "check",
            measure(reps, || map.clone(), |m| m.check().is_ok()),
            "ms",
            nf,
            reps,
        );
        report(
            kind,
            "canonical",
            measure(reps, || map.clone(), |m| CanonicalCode::of(&m).hash()),
            "ms",
            nf,
            reps,
        );
    }
    if build_only {
        return;
    }
    canonical_rows(reps, None);

    let quad_map = Map::from_polygons(nv, &quads).expect("valid torus");
    let tri_map = Map::from_polygons(nv, &tris).expect("valid torus");
    operator_rows(&tri_map, &quad_map, reps, None);
    chain_rows(&quad_map, n, reps);
    qzip_rows(n, reps);
}
