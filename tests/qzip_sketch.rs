//! Q-zip stage 1, the fast searches: the bidirectional BFS, the guided A* and the reusable
//! workspace give the path of the documented rule (a one-sided BFS from `from`, darts in
//! increasing index, first predecessor kept), written out independently here, and the same
//! shortest length as a plain BFS or Bellman-Ford over an edge list.

use glam::DVec3;
use proptest::prelude::*;
use std::collections::{HashSet, VecDeque};
use zipmesh::ops::quad;
use zipmesh::qzip::{
    max_edge_length, sketch, Guide, Path, Qzip, SketchError, SketchOptions, SketchWorkspace, Tag,
};
use zipmesh::{gen, Dart, Edge, Face, Map, Mesh, Vert};

/// The documented one-sided BFS: FIFO queue, the outgoing darts of a vertex in increasing
/// index, a vertex keeps the first dart that reaches it; `edge_ok` and `vert_ok` (interior
/// vertices only) as the options say.
fn rule_bfs(
    map: &Map,
    from: Vert,
    to: Vert,
    edge_ok: &dyn Fn(u32) -> bool,
    vert_ok: &dyn Fn(Vert) -> bool,
) -> Option<Vec<Vert>> {
    let mut pred: Vec<Option<Dart>> = vec![None; map.vertex_slots()];
    let mut seen = vec![false; map.vertex_slots()];
    seen[from.index()] = true;
    let mut q = VecDeque::from([from]);
    while let Some(u) = q.pop_front() {
        let mut darts: Vec<Dart> = map.vertex_darts(u).collect();
        darts.sort();
        for d in darts {
            let w = map.dest(d);
            if !seen[w.index()] && edge_ok(d.index() as u32 / 2) && (w == to || vert_ok(w)) {
                seen[w.index()] = true;
                pred[w.index()] = Some(d);
                q.push_back(w);
            }
        }
    }
    if !seen[to.index()] {
        return None;
    }
    let mut vs = vec![to];
    let mut v = to;
    while v != from {
        v = map.origin(pred[v.index()].unwrap());
        vs.push(v);
    }
    vs.reverse();
    Some(vs)
}

/// Bellman-Ford distance over the edge list with per-edge weights.
fn ref_weighted(map: &Map, from: Vert, to: Vert, w: &[f64]) -> f64 {
    let mut dist = vec![f64::INFINITY; map.vertex_slots()];
    dist[from.index()] = 0.0;
    let edges: Vec<(usize, usize, usize)> = map
        .darts()
        .filter(|d| d.index() % 2 == 0)
        .map(|d| (d.index() / 2, map.origin(d).index(), map.dest(d).index()))
        .collect();
    loop {
        let mut changed = false;
        for &(e, u, v) in &edges {
            for (a, b) in [(u, v), (v, u)] {
                if dist[a] + w[e] < dist[b] {
                    dist[b] = dist[a] + w[e];
                    changed = true;
                }
            }
        }
        if !changed {
            return dist[to.index()];
        }
    }
}

/// A path's promises: its ends, simple, darts joining consecutive vertices, no bad edge.
fn check_path(map: &Map, p: &Path, from: Vert, to: Vert, bad: &HashSet<u32>) {
    assert_eq!((p.start(), p.end()), (from, to));
    assert_eq!(p.vertices().len(), p.len() + 1);
    let set: HashSet<Vert> = p.vertices().iter().copied().collect();
    assert_eq!(set.len(), p.vertices().len(), "not simple: {p}");
    for (i, &d) in p.darts().iter().enumerate() {
        assert!(map.is_live_dart(d));
        assert_eq!(map.origin(d), p.vertices()[i]);
        assert_eq!(map.dest(d), p.vertices()[i + 1]);
        assert!(
            !bad.contains(&(d.index() as u32 / 2)),
            "forbidden edge in {p}"
        );
    }
}

fn mesh(kind: usize, seed: u64) -> Mesh {
    match kind {
        0 => gen::random_quad(200, 1, 1, seed),
        1 => gen::random_quad(200, 0, 2, seed),
        2 => gen::random_triangle(300, 1, 1, seed),
        3 => gen::random_mixed(250, 0, 1, seed),
        4 => gen::torus_grid(9, 7),
        _ => gen::grid(8, 6),
    }
}

fn pick(map: &Map, k: u64) -> Vert {
    let vs: Vec<Vert> = map.vertices().collect();
    vs[(k % vs.len() as u64) as usize]
}

/// The edges of the forbidden faces plus the forbidden edges.
fn bad_edges(map: &Map, edges: &[u32], faces: &[Face]) -> HashSet<u32> {
    let mut bad: HashSet<u32> = edges.iter().copied().collect();
    for &f in faces {
        bad.extend(map.face_darts(f).map(|d| d.index() as u32 / 2));
    }
    bad
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Plain, guided, workspace and guided workspace sketches all give the path of the rule
    /// (so the same length as BFS), with forbidden edges and faces and with avoid_boundary.
    #[test]
    fn every_search_gives_the_rule_path(
        kind in 0usize..6, seed in 0u64..4, a in any::<u64>(), b in any::<u64>(),
        cut in prop::collection::vec(any::<u64>(), 0..40),
        prot in prop::collection::vec(any::<u64>(), 0..4),
        avoid in any::<bool>(),
    ) {
        let m = mesh(kind, seed);
        let map = &m.map;
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let n_edges = (map.dart_slots() / 2) as u64;
        let edges: Vec<u32> = cut.iter().map(|&k| (k % n_edges) as u32)
            .filter(|&e| map.is_live_dart(Dart::new(2 * e))).collect();
        let faces: Vec<Face> = prot.iter().map(|&k| {
            let fs: Vec<Face> = map.faces().collect();
            fs[(k % fs.len() as u64) as usize]
        }).collect();
        let bad = bad_edges(map, &edges, &faces);
        let edge_ok = |e: u32| !bad.contains(&e);
        let expected = if avoid {
            rule_bfs(map, from, to, &edge_ok, &|v| !map.is_boundary_vertex(v))
                .or_else(|| rule_bfs(map, from, to, &edge_ok, &|_| true))
        } else {
            rule_bfs(map, from, to, &edge_ok, &|_| true)
        };
        let plain = SketchOptions::default().avoid_boundary(avoid).forbid_edges(edges.iter().map(|&e| Edge::new(e))).forbid_faces(faces.clone());
        let guided = plain.clone().guide(Guide::from_mesh(&m));
        let mut ws = SketchWorkspace::new();
        let results = [
            sketch(map, from, to, &plain),
            sketch(map, from, to, &guided),
            ws.sketch(map, from, to, &plain),
            ws.sketch(map, from, to, &guided),
        ];
        for r in results {
            match (&expected, r) {
                (Some(vs), Ok(p)) => {
                    check_path(map, &p, from, to, &bad);
                    prop_assert_eq!(p.vertices(), &vs[..]);
                }
                (None, Err(e)) => prop_assert_eq!(e, SketchError::NoPath { from, to }),
                (e, r) => prop_assert!(false, "expected {:?}, got {:?}", e, r),
            }
        }
    }

    /// Dijkstra through the workspace: the same path as `sketch`, of Bellman-Ford's cost; a
    /// guide plays no part with weights.
    #[test]
    fn weighted_workspace_matches(
        kind in 0usize..6, seed in 0u64..4, a in any::<u64>(), b in any::<u64>(),
        wseed in any::<u64>(), avoid in any::<bool>(),
    ) {
        let m = mesh(kind, seed);
        let map = &m.map;
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let mut rng = zipmesh::rng::Rng::new(wseed);
        let w: Vec<f64> = (0..map.dart_slots() / 2).map(|_| rng.below(5) as f64).collect();
        let opts = SketchOptions::default().weights(w.clone()).avoid_boundary(avoid);
        let p = sketch(map, from, to, &opts).unwrap();
        check_path(map, &p, from, to, &HashSet::new());
        if !avoid {
            let cost: f64 = p.darts().iter().map(|d| w[d.index() / 2]).sum();
            prop_assert_eq!(cost, ref_weighted(map, from, to, &w));
        }
        let mut ws = SketchWorkspace::new();
        prop_assert_eq!(&ws.sketch(map, from, to, &opts).unwrap(), &p);
        let guided = opts.clone().guide(Guide::from_mesh(&m));
        prop_assert_eq!(&ws.sketch(map, from, to, &guided).unwrap(), &p);
    }

    /// Any points give a correct guide with their own longest edge as the bound: random
    /// points on a torus still give the rule's path.
    #[test]
    fn arbitrary_points_with_their_bound_give_the_rule_path(
        pseed in any::<u64>(), a in any::<u64>(), b in any::<u64>(),
    ) {
        let mut m = gen::torus_grid(12, 9);
        let mut rng = zipmesh::rng::Rng::new(pseed);
        for p in &mut m.positions {
            *p = DVec3::new(rng.below(100) as f64, rng.below(100) as f64, rng.below(3) as f64);
        }
        let map = &m.map;
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let expected = rule_bfs(map, from, to, &|_| true, &|_| true).unwrap();
        let guided = SketchOptions::default().guide(Guide::from_mesh(&m));
        let p = sketch(map, from, to, &guided).unwrap();
        prop_assert_eq!(p.vertices(), &expected[..]);
    }

    /// A bound that is too small: the path is still valid, simple, between the two ends and
    /// never shorter than the shortest.
    #[test]
    fn a_wrong_bound_still_gives_a_valid_path(
        kind in 0usize..6, seed in 0u64..4, a in any::<u64>(), b in any::<u64>(),
        shrink in 1u32..1000,
    ) {
        let m = mesh(kind, seed);
        let map = &m.map;
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let shortest = rule_bfs(map, from, to, &|_| true, &|_| true).unwrap().len() - 1;
        let bound = max_edge_length(&m) / f64::from(shrink);
        let wrong = SketchOptions::default().guide(Guide::new(&m.positions, bound));
        let mut ws = SketchWorkspace::new();
        for p in [sketch(map, from, to, &wrong).unwrap(), ws.sketch(map, from, to, &wrong).unwrap()] {
            check_path(map, &p, from, to, &HashSet::new());
            prop_assert!(p.len() >= shortest);
        }
    }
}

/// The straight rows and columns of a flat grid: A* explores a few vertices per path edge,
/// the plain search a number growing with the square of the length.
#[test]
fn guided_search_is_linear_on_a_grid() {
    let n = 120;
    let m = gen::grid(n, n);
    let at = |i: usize, j: usize| Vert::new((j * (n + 1) + i) as u32);
    let guided = SketchOptions::default().guide(Guide::from_mesh(&m));
    let plain = SketchOptions::default();
    let mut ws = SketchWorkspace::new();
    for len in [5usize, 20, 50, 100] {
        for (a, b) in [
            (at(10, 60), at(10 + len, 60)),
            (at(60, 10 + len), at(60, 10)),
        ] {
            let p = ws.sketch(&m.map, a, b, &guided).unwrap();
            let explored = ws.explored();
            assert_eq!(p, sketch(&m.map, a, b, &plain).unwrap());
            assert_eq!(p.len(), len);
            assert!(
                explored <= 4 * (len + 1),
                "{explored} vertices for a path of {len}"
            );
            ws.sketch(&m.map, a, b, &plain).unwrap();
            if len >= 20 {
                // Quadratic, but two balls of half the length (about len^2 vertices), not
                // one of the whole length (about 2 len^2): the smaller side grows first.
                let plain = ws.explored();
                assert!(plain >= len * len / 2, "{plain}");
                assert!(plain <= len * len * 6 / 5 + 4 * len, "{plain}");
            }
        }
    }
}

/// On the torus with its own geometry (edges of different lengths), A* and the plain search
/// agree on every pair from one vertex, and A* never explores more.
#[test]
fn guided_search_on_the_torus_matches() {
    let m = gen::torus_grid(30, 20);
    let guided = SketchOptions::default().guide(Guide::from_mesh(&m));
    let plain = SketchOptions::default();
    let (mut ws, mut ws2) = (SketchWorkspace::new(), SketchWorkspace::new());
    let from = Vert::new(31);
    for to in m.map.vertices().filter(|&v| v != from) {
        let expected = rule_bfs(&m.map, from, to, &|_| true, &|_| true).unwrap();
        let p = ws.sketch(&m.map, from, to, &guided).unwrap();
        assert_eq!(p.vertices(), &expected[..]);
        let q = ws2.sketch(&m.map, from, to, &plain).unwrap();
        assert_eq!(q, p);
    }
}

/// One workspace across maps of different sizes and across edits of one map gives what a
/// fresh `sketch` gives.
#[test]
fn workspace_reuse_across_maps_and_edits() {
    let mut ws = SketchWorkspace::new();
    let plain = SketchOptions::default();
    let big = gen::torus_grid(40, 40);
    let small = gen::grid(4, 3);
    let tri = gen::random_triangle(400, 1, 2, 5);
    for round in 0..3u64 {
        for m in [&big, &small, &tri, &big] {
            let guided = SketchOptions::default().guide(Guide::from_mesh(m));
            for k in 0..20u64 {
                let (a, b) = (
                    pick(&m.map, k * 7919 + round),
                    pick(&m.map, k * 104_729 + 3),
                );
                if a == b {
                    continue;
                }
                let expected = sketch(&m.map, a, b, &plain);
                assert_eq!(ws.sketch(&m.map, a, b, &plain), expected);
                assert_eq!(ws.sketch(&m.map, a, b, &guided), expected);
            }
        }
    }
    // Edits: vertex splits add vertices and darts past the arrays' old size; Q-zips move
    // singularities. After each edit the workspace agrees with a fresh sketch.
    let mut map = gen::torus_grid(20, 20).map;
    let at = |i: u32, j: u32| Vert::new(j * 20 + i);
    for (k, &(i, j)) in [(3u32, 3u32), (12, 3), (5, 14)].iter().enumerate() {
        let (v, e, w) = (at(i, j), at(i + 1, j), at(i - 1, j));
        let s1 = map.vertex_darts(v).find(|&d| map.dest(d) == e).unwrap();
        let s2 = map.vertex_darts(v).find(|&d| map.dest(d) == w).unwrap();
        quad::split_vertex(&mut map, s1, s2).unwrap();
        for t in 0..map.vertex_slots() as u32 {
            let (a, b) = (at(1, 1), Vert::new(t));
            if a == b || !map.is_live_vertex(b) {
                continue;
            }
            assert_eq!(ws.sketch(&map, a, b, &plain), sketch(&map, a, b, &plain));
        }
        // Move the pair between the first two clusters (a v5 and a v3, 8 edges apart).
        if k == 1 {
            let (v5, v3) = (at(4, 3), at(12, 3));
            let p = ws.sketch(&map, v5, v3, &plain).unwrap();
            assert_eq!(p, sketch(&map, v5, v3, &plain).unwrap());
            Qzip::new().zip_along(&mut map, &p, Tag::LC).unwrap();
        }
    }
    assert!(map.check().is_ok());
}

/// The errors are those of `sketch`.
#[test]
fn workspace_errors_match() {
    let map = gen::grid(3, 3).map;
    let mut ws = SketchWorkspace::new();
    let v = Vert::new;
    let o = SketchOptions::default();
    assert_eq!(
        ws.sketch(&map, v(4), v(4), &o),
        Err(SketchError::SameVertex(v(4)))
    );
    assert_eq!(
        ws.sketch(&map, v(0), v(99), &o),
        Err(SketchError::DeadVertex(v(99)))
    );
    let short = SketchOptions::default().weights(vec![1.0; 2]);
    assert_eq!(
        ws.sketch(&map, v(0), v(15), &short),
        sketch(&map, v(0), v(15), &short)
    );
    assert!(matches!(
        ws.sketch(&map, v(0), v(15), &short),
        Err(SketchError::WeightsTooShort { .. })
    ));
    // Every edge at vertex 0 forbidden: no path, whichever search.
    let walls: Vec<Edge> = map.vertex_darts(v(0)).map(|d| d.edge()).collect();
    let m = gen::grid(3, 3);
    for guide in [None, Some(Guide::from_mesh(&m))] {
        let mut o = SketchOptions::default().forbid_edges(walls.clone());
        o.guide = guide;
        let e = Err(SketchError::NoPath {
            from: v(0),
            to: v(15),
        });
        assert_eq!(ws.sketch(&map, v(0), v(15), &o), e);
        assert_eq!(sketch(&map, v(0), v(15), &o), e);
    }
}

/// A guide that cannot direct (no bound, or no point for the end) is ignored: the plain path.
#[test]
fn unusable_guides_are_ignored() {
    let m = gen::grid(10, 10);
    let (a, b) = (Vert::new(0), Vert::new(120));
    let expected = sketch(&m.map, a, b, &SketchOptions::default()).unwrap();
    let few = &m.positions[..50];
    for g in [
        Guide::new(&m.positions, 0.0),
        Guide::new(&m.positions, f64::NAN),
        Guide::new(&m.positions, f64::INFINITY),
        Guide::new(few, 1.0),
        Guide::new(&[], 1.0),
    ] {
        let o = SketchOptions::default().guide(g);
        assert_eq!(sketch(&m.map, a, b, &o).unwrap(), expected);
    }
    // Points for only some vertices (the rest count as 0): still the rule's path.
    let o = SketchOptions::default().guide(Guide::new(&m.positions[..100], 1.0));
    assert_eq!(sketch(&m.map, Vert::new(119), a, &o).unwrap().len(), 19);
    assert_eq!(
        sketch(&m.map, Vert::new(119), a, &o).unwrap(),
        sketch(&m.map, Vert::new(119), a, &SketchOptions::default()).unwrap()
    );
}

/// The workspace's epoch wraps after 2^24 searches (one per sketch without avoid_boundary)
/// and clears its arrays then: records left by the first search, on another map, must not
/// be read as current when the epoch comes round again. The calls around the wrap are
/// checked against `sketch`.
#[test]
fn workspace_epoch_wrap_clears_old_records() {
    let big = gen::grid(8, 8).map;
    let small = gen::grid(1, 1).map;
    let plain = SketchOptions::default();
    let mut ws = SketchWorkspace::new();
    // Epoch 1: labels much of `big` (away from vertices 0..4, which `small` relabels).
    let (a, b) = (Vert::new(10), Vert::new(70));
    assert_eq!(ws.sketch(&big, a, b, &plain), sketch(&big, a, b, &plain));
    // Epochs 2 to 2^24 - 1 on `small`; the next search wraps round to epoch 1.
    for _ in 2..1u32 << 24 {
        ws.sketch(&small, Vert::new(0), Vert::new(1), &plain)
            .unwrap();
    }
    // The pair reversed: stale records of the first call would carry predecessors pointing
    // the other way, which the search would take as its own.
    let expected = sketch(&big, b, a, &plain);
    for k in 0..3 {
        assert_eq!(ws.sketch(&big, b, a, &plain), expected, "call {k}");
        assert!(ws.explored() > 40, "every record fresh: {}", ws.explored());
    }
}

/// Validation ignores the weights: a caller's path is checked against the forbidden edges
/// and faces only, so weights a search would refuse (too few, negative) do not refuse it.
#[test]
fn validation_ignores_the_weights() {
    let map = gen::grid(5, 5).map;
    let path: Vec<Vert> = [7u32, 8, 9, 15].map(Vert::new).to_vec();
    let (from, to) = (path[0], path[3]);
    for weights in [vec![1.0; 3], vec![-1.0; map.edge_slots()]] {
        let opts = SketchOptions::default().weights(weights);
        assert!(zipmesh::qzip::sketch(&map, from, to, &opts).is_err());
        let p = zipmesh::qzip::validate_path(&map, from, to, &path, &opts).unwrap();
        assert_eq!(p.vertices(), path.as_slice());
    }
}
