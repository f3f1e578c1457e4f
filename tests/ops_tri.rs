//! Property tests of the triangle operators on large meshes: random triangle meshes of
//! thousands of faces (several genera and holes), a triangulated torus grid, a random
//! quad-dominant mesh, and the triangle meshes in `tests/data/tri/`.
//!
//! Each case runs a random sequence of operators at random darts, half of them next to the
//! previous edits so that operators meet each other's results. Every step goes through the
//! oracle in `ops_tri/check.rs`: refused with the `can_*` reason and the map unchanged
//! (`==`), or applied with `check()` passing and V, E, F, every vertex's valence and every old
//! handle exactly as documented. At the end the whole sequence is undone in reverse order and
//! the map must equal the original. Separate properties check the public inverses (split
//! then collapse, collapse then split, flip twice, edge split then collapse) by canonical
//! code, and the `Mesh` wrappers' positions.

#[path = "../crates/zipmesh-kernel/tests/ops_tri/check.rs"]
mod check;

use check::{checked, Op, Rec};
use proptest::prelude::*;
use std::path::PathBuf;
use std::sync::OnceLock;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::invariants::Counts;
use zipmesh::ops::tri;
use zipmesh::ops::{Refusal, VertexChanges};
use zipmesh::rng::Rng;
use zipmesh::{gen, Dart, Map, Mesh};

/// A quad torus grid with every quad cut along the same diagonal: every vertex of valence 6.
fn torus_triangles(nx: usize, ny: usize) -> Mesh {
    let quads = gen::torus_grid(nx, ny);
    let mut tris = Vec::new();
    for p in quads.polygons() {
        tris.push([p[0], p[1], p[2]]);
        tris.push([p[0], p[2], p[3]]);
    }
    Mesh::from_polygons(quads.positions, &tris).unwrap().0
}

fn data(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(rel)
}

const SHARED: [&str; 3] = [
    "tri/circle_disk.obj",
    "tri/spot_triangulated.obj",
    "tri/torus.obj",
];

/// The test meshes: 0..3 shared, then generated ones (built once).
fn mesh(i: usize) -> &'static Mesh {
    static MESHES: OnceLock<Vec<Mesh>> = OnceLock::new();
    &MESHES.get_or_init(|| {
        let mut v: Vec<Mesh> = SHARED
            .iter()
            .map(|p| {
                zipmesh::io::read_mesh(data(p))
                    .unwrap_or_else(|e| panic!("{p}: {e}"))
                    .0
            })
            .collect();
        v.push(gen::random_triangle(3000, 0, 0, 1));
        v.push(gen::random_triangle(4000, 2, 1, 2));
        v.push(gen::random_triangle(2500, 1, 3, 3));
        v.push(torus_triangles(40, 30));
        // Mostly quads: the operators must refuse them and still work on the triangles.
        v.push(gen::random_mixed(3000, 1, 2, 4));
        v
    })[i]
}

const N_MESHES: usize = 8;

/// A live dart, near one of the `hot` darts (recent edits) half of the time.
fn random_dart(m: &Map, rng: &mut Rng, hot: &[Dart]) -> Dart {
    if !hot.is_empty() && rng.chance(1, 2) {
        let mut d = hot[rng.below(hot.len())];
        if m.is_live_dart(d) {
            for _ in 0..rng.below(4) {
                d = if rng.chance(1, 2) {
                    m.next(d)
                } else {
                    m.rotate_cw(d)
                };
            }
            return if rng.chance(1, 2) { d } else { d.twin() };
        }
    }
    loop {
        let d = Dart::new(rng.below(m.dart_slots()) as u32);
        if m.is_live_dart(d) {
            return d;
        }
    }
}

/// A random operator; one in forty calls gets a dead or out-of-range dart.
fn random_op(m: &Map, rng: &mut Rng, hot: &[Dart]) -> Op {
    let mut d = random_dart(m, rng, hot);
    if rng.chance(1, 40) {
        d = Dart::new((m.dart_slots() + rng.below(3)) as u32);
    }
    match rng.below(4) {
        0 => Op::Flip(d),
        1 => Op::Collapse(d),
        2 => Op::SplitEdge(d),
        _ => {
            // Mostly a second dart of the same vertex, so that splits often apply.
            let e = if m.is_live_dart(d) && rng.chance(7, 8) {
                let mut e = d;
                for _ in 0..rng.below(m.valence(m.origin(d)) + 1) {
                    e = m.rotate_cw(e);
                }
                e
            } else {
                random_dart(m, rng, hot)
            };
            Op::SplitVertex(d, e)
        }
    }
}

/// Darts next to what the record created or kept, for the next operators to aim at.
fn touched(m: &Map, op: Op, rec: &Rec) -> Vec<Dart> {
    let mut out = vec![];
    match (op, rec) {
        (_, Rec::Flip(r)) => out.push(r.dart()),
        (_, Rec::Collapse(r)) => out.push(m.vertex_dart(r.kept())),
        (_, Rec::SplitVertex(r)) => out.push(r.edge()),
        (_, Rec::SplitEdge(r)) => out.push(r.dart()),
    }
    out
}

#[derive(Default, Debug)]
struct Stats {
    applied: [usize; 4],
    refused: usize,
}

fn kind(op: Op) -> usize {
    match op {
        Op::Flip(_) => 0,
        Op::Collapse(_) => 1,
        Op::SplitVertex(..) => 2,
        Op::SplitEdge(_) => 3,
    }
}

/// A random sequence of `steps` checked operators, then undone in reverse order.
fn run_sequence(original: &Map, seed: u64, steps: usize) -> Stats {
    let mut rng = Rng::new(seed);
    let mut map = original.clone();
    let mut recs = Vec::new();
    let mut hot = Vec::new();
    let mut stats = Stats::default();
    for _ in 0..steps {
        let op = random_op(&map, &mut rng, &hot);
        match checked(&mut map, op) {
            Ok(rec) => {
                stats.applied[kind(op)] += 1;
                hot.extend(touched(&map, op, &rec));
                if hot.len() > 8 {
                    hot.remove(0);
                }
                recs.push(rec);
            }
            Err(_) => stats.refused += 1,
        }
        if recs.len() > 1 && rng.chance(1, 6) {
            // An earlier record undone out of order: refused with nothing changed, or a
            // valid map (never a panic).
            let rec = recs[rng.below(recs.len() - 1)];
            let mut m = map.clone();
            match rec.undo(&mut m) {
                Err(e) => {
                    assert_eq!(e, Refusal::StaleRecord);
                    assert!(m == map, "a refused undo changed the map");
                }
                Ok(()) => assert_eq!(m.check(), Ok(()), "out-of-order undo of {rec:?}"),
            }
        }
    }
    for rec in recs.iter().rev() {
        rec.undo(&mut map).expect("undo in reverse order");
    }
    assert!(
        map == *original,
        "undoing the sequence did not restore the map"
    );
    stats
}

/// An undo of a `Mesh` wrapper's result.
type UndoFn = Box<dyn Fn(&mut Mesh) -> Result<(), Refusal>>;

fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: n,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(cases(48))]

    /// Random sequences on every test mesh: each step checked, the whole sequence undone.
    #[test]
    fn random_sequences(which in 0..N_MESHES, seed in any::<u64>()) {
        run_sequence(&mesh(which).map, seed, 60);
    }
}

proptest! {
    #![proptest_config(cases(24))]

    /// The public inverses: each applied operator followed by its inverse gives back the map
    /// up to isomorphism, and the inverse is accepted wherever the documentation promises.
    #[test]
    fn inverses_restore_the_canonical_code(which in 3..7usize, seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let map = &mesh(which).map;
        let mut applied = 0;
        for _ in 0..40 {
            let op = random_op(map, &mut rng, &[]);
            let mut m = map.clone();
            if let Ok(rec) = checked(&mut m, op) {
                check::inverse(map, &m, op, &rec);
                applied += 1;
                if applied == 3 {
                    break;
                }
            }
        }
        prop_assert!(applied > 0);
    }

    /// The Mesh wrappers place positions by the documented rules and undo restores the
    /// whole mesh, positions included.
    #[test]
    fn mesh_wrappers_place_and_restore(which in 0..N_MESHES, seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let original = mesh(which).clone();
        let mut mesh = original.clone();
        let mut undo: Vec<UndoFn> = Vec::new();
        for _ in 0..30 {
            let op = random_op(&mesh.map, &mut rng, &[]);
            let before = mesh.clone();
            let pos = |m: &Mesh, v: zipmesh::Vert| m.positions[v.index()];
            match op {
                Op::Flip(h) => {
                    if let Ok(p) = Op::Flip(h).apply(&mut mesh) {
                        prop_assert_eq!(&mesh.positions, &before.positions);
                        undo.push(Box::new(move |m| p.undo(m)));
                    }
                }
                Op::Collapse(h) => {
                    if let Ok(p) = Op::Collapse(h).apply(&mut mesh) {
                        let (v, u) = (before.map.origin(h), before.map.dest(h));
                        prop_assert_eq!(pos(&mesh, u), (pos(&before, u) + pos(&before, v)) * 0.5);
                        undo.push(Box::new(move |m| p.undo(m)));
                    }
                }
                Op::SplitVertex(d1, d2) => {
                    if let Ok(p) = Op::SplitVertex(d1, d2).apply(&mut mesh) {
                        let w = before.map.origin(d1);
                        let v = p.created_vertex().unwrap();
                        prop_assert_eq!(pos(&mesh, w), pos(&before, w));
                        let ns: Vec<_> = mesh.map.vertex_darts(v).map(|d| mesh.map.dest(d)).filter(|&x| x != w).collect();
                        let avg = ns.iter().map(|&x| pos(&mesh, x)).sum::<glam::DVec3>() / ns.len() as f64;
                        let want = (pos(&before, w) + avg) * 0.5;
                        prop_assert!((pos(&mesh, v) - want).length() < 1e-12);
                        undo.push(Box::new(move |m| p.undo(m)));
                    }
                }
                Op::SplitEdge(h) => {
                    if let Ok(p) = Op::SplitEdge(h).apply(&mut mesh) {
                        let (a, b) = (before.map.origin(h), before.map.dest(h));
                        prop_assert_eq!(pos(&mesh, p.created_vertex().unwrap()), (pos(&before, a) + pos(&before, b)) * 0.5);
                        undo.push(Box::new(move |m| p.undo(m)));
                    }
                }
            }
        }
        for u in undo.iter().rev() {
            u(&mut mesh).unwrap();
        }
        prop_assert!(mesh == original);
    }
}

/// Long sequences on every test mesh, with every operator applied many times.
#[test]
fn long_sequences_apply_every_operator() {
    for which in 0..N_MESHES {
        let s = run_sequence(&mesh(which).map, 0xC0FFEE + which as u64, 1500);
        eprintln!("mesh {which}: {s:?}");
        assert!(
            s.applied.iter().all(|&n| n >= 20) && s.refused > 0,
            "mesh {which}: {s:?}"
        );
    }
}

/// The shared meshes load as documented in SOURCES.md (independent counts).
#[test]
fn shared_meshes_have_their_published_counts() {
    let want = [
        (1014, 2947, 1934, 1),
        (2930, 8784, 5856, 0),
        (768, 2304, 1536, 0),
    ];
    for (i, w) in want.iter().enumerate() {
        let c = Counts::of(&mesh(i).map);
        assert_eq!(
            (c.vertices, c.edges, c.faces, c.boundary_loops),
            *w,
            "{}",
            SHARED[i]
        );
    }
}

/// Vertex split then collapse of the new edge, and collapse then split at the two apex
/// darts, give back the canonical code, on every kind of vertex of the regular torus.
#[test]
fn split_collapse_round_trips_on_the_regular_torus() {
    let map = &mesh(6).map;
    let code = CanonicalCode::of(map);
    let w = map.vertices().next().unwrap();
    let darts: Vec<Dart> = map.vertex_darts(w).collect();
    for &d1 in &darts {
        for &d2 in &darts {
            let mut m = map.clone();
            let Ok(rec) = tri::split_vertex(&mut m, d1, d2) else {
                assert_eq!(d1, d2);
                continue;
            };
            // Valence 6 split along d1, d2: w gets k_w + 3, v gets k_v + 3, k_w + k_v = 4.
            assert_eq!(m.valence(w) + m.valence(rec.created()), 6 + 4);
            tri::collapse_edge(&mut m, rec.edge()).unwrap();
            assert_eq!(CanonicalCode::of(&m), code);
        }
    }
    // Every edge at w (all edge directions of the lattice, both ways) collapses
    // (valence 6 + 6 - 4 = 8) and splits back, and flips twice back.
    for &h in darts
        .iter()
        .chain(darts.iter().map(|d| d.twin()).collect::<Vec<_>>().iter())
    {
        let mut m = map.clone();
        let rec = tri::collapse_edge(&mut m, h).unwrap();
        assert_eq!(m.valence(rec.kept()), 8);
        let h1 = map.next(h);
        let t2 = map.next(map.next(h.twin()));
        tri::split_vertex(&mut m, h1, t2.twin()).unwrap();
        assert_eq!(CanonicalCode::of(&m), code);
        // Flip twice: the same map up to isomorphism.
        let mut f = map.clone();
        tri::flip_edge(&mut f, h).unwrap();
        tri::flip_edge(&mut f, h).unwrap();
        assert_eq!(CanonicalCode::of(&f), code);
    }
}
