//! Q-zip stages 1 and 2: sketching a path and planning the compass along it.
//!
//! Paths are compared with an independent breadth-first search and Bellman-Ford written here
//! over a plain edge list; the compass is checked on grids, tori and hand-built fans around a
//! vertex of valence 3, 4, 5 and 6, with the expected turns written out from the counting rule.

use proptest::prelude::*;
use std::collections::{HashSet, VecDeque};
use zipmesh::qzip::{
    plan, sketch, validate_path, PlanError, Side, SketchError, SketchOptions, Tag, Turn,
};
use zipmesh::{gen, Dart, Edge, Face, Map, Vert};

/// (edge index, u, v) for every live edge.
fn edge_list(map: &Map) -> Vec<(u32, usize, usize)> {
    map.darts()
        .filter(|d| d.index() % 2 == 0)
        .map(|d| {
            (
                d.index() as u32 / 2,
                map.origin(d).index(),
                map.dest(d).index(),
            )
        })
        .collect()
}

/// Hop distance from `from` to `to` over allowed edges, through allowed interior vertices.
fn ref_bfs(
    map: &Map,
    from: usize,
    to: usize,
    edge_ok: &dyn Fn(u32) -> bool,
    vert_ok: &dyn Fn(usize) -> bool,
) -> Option<usize> {
    let mut adj = vec![Vec::new(); map.vertex_slots()];
    for (e, u, v) in edge_list(map) {
        if edge_ok(e) {
            adj[u].push(v);
            adj[v].push(u);
        }
    }
    let mut dist = vec![usize::MAX; map.vertex_slots()];
    dist[from] = 0;
    let mut q = VecDeque::from([from]);
    while let Some(u) = q.pop_front() {
        for &w in &adj[u] {
            if dist[w] == usize::MAX && (w == to || vert_ok(w)) {
                dist[w] = dist[u] + 1;
                q.push_back(w);
            }
        }
    }
    (dist[to] != usize::MAX).then_some(dist[to])
}

/// Bellman-Ford distance with per-edge weights.
fn ref_weighted(map: &Map, from: usize, to: usize, w: &[f64]) -> f64 {
    let mut dist = vec![f64::INFINITY; map.vertex_slots()];
    dist[from] = 0.0;
    let edges = edge_list(map);
    for _ in 0..map.vertex_slots() {
        let mut changed = false;
        for &(e, u, v) in &edges {
            for (a, b) in [(u, v), (v, u)] {
                if dist[a] + w[e as usize] < dist[b] {
                    dist[b] = dist[a] + w[e as usize];
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    dist[to]
}

/// The structural promises of a path: ends, simple, connected by its darts, allowed edges.
fn check_path(map: &Map, p: &zipmesh::qzip::Path, from: Vert, to: Vert, bad_edges: &HashSet<u32>) {
    assert_eq!(p.start(), from);
    assert_eq!(p.end(), to);
    assert_eq!(p.vertices().len(), p.len() + 1);
    let set: HashSet<Vert> = p.vertices().iter().copied().collect();
    assert_eq!(set.len(), p.vertices().len(), "path not simple: {p}");
    for (i, &d) in p.darts().iter().enumerate() {
        assert!(map.is_live_dart(d));
        assert_eq!(map.origin(d), p.vertices()[i]);
        assert_eq!(map.dest(d), p.vertices()[i + 1]);
        assert!(
            !bad_edges.contains(&(d.index() as u32 / 2)),
            "forbidden edge used"
        );
    }
}

fn meshes() -> Vec<Map> {
    vec![
        gen::grid(7, 5).map,
        gen::torus_grid(9, 7).map,
        gen::cube(3).map,
        gen::random_quad(300, 1, 1, 11).map,
        gen::random_quad(300, 0, 2, 12).map,
        gen::random_quad(300, 2, 0, 13).map,
    ]
}

fn pick(map: &Map, k: u64) -> Vert {
    let vs: Vec<Vert> = map.vertices().collect();
    vs[(k % vs.len() as u64) as usize]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn shortest_paths_match_independent_bfs(m in 0usize..6, a in any::<u64>(), b in any::<u64>()) {
        let map = &meshes()[m];
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let opts = SketchOptions::default();
        let p = sketch(map, from, to, &opts).unwrap();
        check_path(map, &p, from, to, &HashSet::new());
        let d = ref_bfs(map, from.index(), to.index(), &|_| true, &|_| true);
        prop_assert_eq!(Some(p.len()), d);
        // Deterministic: the same call gives the same path.
        prop_assert_eq!(&sketch(map, from, to, &opts).unwrap(), &p);
        // Unit-weight Dijkstra finds a path of the same length.
        let unit = SketchOptions::default().weights(vec![1.0; map.dart_slots() / 2]);
        let q = sketch(map, from, to, &unit).unwrap();
        check_path(map, &q, from, to, &HashSet::new());
        prop_assert_eq!(q.len(), p.len());
        // A found path validates as a given path.
        prop_assert_eq!(&validate_path(map, from, to, p.vertices(), &opts).unwrap(), &p);
    }

    #[test]
    fn forbidden_edges_and_faces_are_never_used(
        m in 0usize..6, a in any::<u64>(), b in any::<u64>(), seed in any::<u64>(),
    ) {
        let map = &meshes()[m];
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let mut rng = zipmesh::rng::Rng::new(seed);
        let edges: Vec<u32> = edge_list(map).iter().map(|e| e.0).filter(|_| rng.chance(1, 6)).collect();
        let faces: Vec<Face> = map.faces().filter(|_| rng.chance(1, 12)).collect();
        let mut bad: HashSet<u32> = edges.iter().copied().collect();
        for &f in &faces {
            bad.extend(map.face_darts(f).map(|d: Dart| d.index() as u32 / 2));
        }
        let opts = SketchOptions::default().forbid_edges(edges.iter().map(|&e| Edge::new(e))).forbid_faces(faces);
        let expected = ref_bfs(map, from.index(), to.index(), &|e| !bad.contains(&e), &|_| true);
        match sketch(map, from, to, &opts) {
            Ok(p) => {
                check_path(map, &p, from, to, &bad);
                prop_assert_eq!(Some(p.len()), expected);
            }
            Err(e) => {
                prop_assert_eq!(e, SketchError::NoPath { from, to });
                prop_assert_eq!(expected, None);
            }
        }
    }

    #[test]
    fn avoid_boundary_prefers_interior_paths(m in 0usize..6, a in any::<u64>(), b in any::<u64>()) {
        let map = &meshes()[m];
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let opts = SketchOptions::default().avoid_boundary(true);
        let p = sketch(map, from, to, &opts).unwrap();
        check_path(map, &p, from, to, &HashSet::new());
        let inner = ref_bfs(map, from.index(), to.index(), &|_| true,
            &|v| !map.is_boundary_vertex(Vert::new(v as u32)));
        match inner {
            Some(d) => {
                prop_assert_eq!(p.len(), d);
                let n = p.vertices().len();
                prop_assert!(p.vertices()[1..n - 1].iter().all(|&v| !map.is_boundary_vertex(v)));
            }
            None => prop_assert_eq!(Some(p.len()), ref_bfs(map, from.index(), to.index(), &|_| true, &|_| true)),
        }
    }

    #[test]
    fn dijkstra_matches_bellman_ford(m in 0usize..6, a in any::<u64>(), b in any::<u64>(), seed in any::<u64>()) {
        let map = &meshes()[m];
        let (from, to) = (pick(map, a), pick(map, b));
        prop_assume!(from != to);
        let mut rng = zipmesh::rng::Rng::new(seed);
        // Small integers keep the sums exact.
        let w: Vec<f64> = (0..map.dart_slots() / 2).map(|_| rng.below(5) as f64).collect();
        let opts = SketchOptions::default().weights(w.clone());
        let p = sketch(map, from, to, &opts).unwrap();
        check_path(map, &p, from, to, &HashSet::new());
        let cost: f64 = p.darts().iter().map(|d| w[d.index() / 2]).sum();
        prop_assert_eq!(cost, ref_weighted(map, from.index(), to.index(), &w));
    }

    #[test]
    fn compass_rotations(i in 0usize..4) {
        let t = Tag::CCW[i];
        prop_assert_eq!(t.ccw().ccw().ccw().ccw(), t);
        prop_assert_eq!(t.cw().cw().cw().cw(), t);
        prop_assert_eq!(t.rotate_pi().rotate_pi(), t);
        prop_assert_ne!(t.rotate_pi(), t);
        prop_assert_eq!(t.ccw().cw(), t);
        prop_assert_eq!(t.after(Turn::Left).after(Turn::Right), t);
        prop_assert_eq!(t.to_string().parse::<Tag>().unwrap(), t);
        prop_assert_eq!(t.to_string().to_lowercase().parse::<Tag>().unwrap(), t);
    }
}

#[test]
fn compass_order_and_pi() {
    use Tag::*;
    assert_eq!([LS.ccw(), RC.ccw(), LC.ccw(), RS.ccw()], [RC, LC, RS, LS]);
    assert_eq!(
        [
            LS.rotate_pi(),
            LC.rotate_pi(),
            RS.rotate_pi(),
            RC.rotate_pi()
        ],
        [LC, LS, RC, RS]
    );
    assert!("L S".parse::<Tag>().is_err());
    assert!("".parse::<Tag>().is_err());
}

/// Vertex (i, j) of the `n` x `n` torus grid.
fn tv(n: u32, i: u32, j: u32) -> Vert {
    Vert::new((j % n) * n + (i % n))
}

fn given(map: &Map, vs: &[Vert]) -> zipmesh::qzip::Path {
    validate_path(map, vs[0], vs[vs.len() - 1], vs, &SketchOptions::default()).unwrap()
}

#[test]
fn straight_row_keeps_every_tag() {
    let map = gen::torus_grid(10, 10).map;
    let vs: Vec<Vert> = (0..8).map(|i| tv(10, i, 3)).collect();
    let path = given(&map, &vs);
    for t in Tag::CCW {
        let p = plan(&map, &path, t).unwrap();
        assert!(p.steps().iter().all(|s| s.tag == t));
        assert!(p.steps()[1..7]
            .iter()
            .all(|s| s.turn == Some(Turn::Straight)));
        assert_eq!(p.terminal(), t);
    }
}

#[test]
fn left_then_right_restores_the_tag_and_turns_are_geometric() {
    let n = 10u32;
    let map = gen::torus_grid(n as usize, n as usize).map;
    // East, north (left turn at (2,0)), east (right turn at (2,1)).
    let vs = [
        tv(n, 0, 0),
        tv(n, 1, 0),
        tv(n, 2, 0),
        tv(n, 2, 1),
        tv(n, 3, 1),
    ];
    let path = given(&map, &vs);
    for t in Tag::CCW {
        let p = plan(&map, &path, t).unwrap();
        let s = p.steps();
        assert_eq!(s[1].turn, Some(Turn::Straight));
        assert_eq!(s[2].turn, Some(Turn::Left));
        assert_eq!(s[2].tag, t.ccw());
        assert_eq!(s[3].turn, Some(Turn::Right));
        assert_eq!(s[3].tag, t);
        assert_eq!(p.terminal(), t);
    }
    // A full counter-clockwise loop of four left turns around a 2 x 2 block, open at the end:
    // three left turns take the tag three steps counter-clockwise.
    let vs = [
        tv(n, 5, 5),
        tv(n, 6, 5),
        tv(n, 6, 6),
        tv(n, 5, 6),
        tv(n, 4, 6),
    ];
    let p = plan(&map, &given(&map, &vs), Tag::LS).unwrap();
    let tags: Vec<Tag> = p.steps().iter().map(|s| s.tag).collect();
    assert_eq!(tags, [Tag::LS, Tag::RC, Tag::LC, Tag::LC, Tag::LC]);
}

/// A disk of `k` quads around vertex 0: quad i is (0, s_i, m_i, s_(i+1)) with spoke ends
/// s_i = 1 + 2i and rim middles m_i = 2 + 2i. Going counter-clockwise around 0 from spoke i
/// one meets quad i, then spoke i + 1.
fn fan(k: u32) -> Map {
    let s = |i: u32| 1 + 2 * (i % k);
    let faces: Vec<[u32; 4]> = (0..k).map(|i| [0, s(i), 2 + 2 * i, s(i + 1)]).collect();
    Map::from_polygons((1 + 2 * k) as usize, &faces).unwrap()
}

/// The turn the documented rule gives, written out as a table rather than computed by the
/// library: `left` quads on the left out of `k`, counted on the left after LS/RC, on the
/// right (k - left quads) after RS/LC.
fn expected_turn(tag: Tag, left: u32, k: u32) -> Turn {
    let on_left = matches!(tag, Tag::LS | Tag::RC);
    let n = if on_left { left } else { k - left };
    match (on_left, n) {
        (true, 1) => Turn::Left,
        (false, 1) => Turn::Right,
        (_, 2) => Turn::Straight,
        (true, _) => Turn::Right,
        (false, _) => Turn::Left,
    }
}

#[test]
fn irregular_rule_on_fans_of_valence_3_4_5() {
    for k in [3u32, 4, 5] {
        let map = fan(k);
        assert_eq!(map.valence(Vert::new(0)), k as usize);
        assert!(!map.is_boundary_vertex(Vert::new(0)));
        for i in 0..k {
            for j in 0..k {
                if i == j {
                    continue;
                }
                // In at spoke i, out at spoke j: going ccw from j to i passes (i - j) mod k quads.
                let left = (i + k - j) % k;
                let vs = [Vert::new(1 + 2 * i), Vert::new(0), Vert::new(1 + 2 * j)];
                let path = given(&map, &vs);
                for t in Tag::CCW {
                    let p = plan(&map, &path, t).unwrap();
                    let want = expected_turn(t, left, k);
                    assert_eq!(
                        p.steps()[1].turn,
                        Some(want),
                        "k={k} in={i} out={j} tag={t}"
                    );
                    let tag = match want {
                        Turn::Left => t.ccw(),
                        Turn::Straight => t,
                        Turn::Right => t.cw(),
                    };
                    assert_eq!(p.steps()[1].tag, tag);
                    assert_eq!(p.terminal(), tag);
                }
            }
        }
    }
}

#[test]
fn irregular_rule_documented_cases() {
    // Valence 5, two quads on the left and three on the right.
    let map = fan(5);
    let path = given(&map, &[Vert::new(1 + 2 * 2), Vert::new(0), Vert::new(1)]);
    assert_eq!(
        plan(&map, &path, Tag::LS).unwrap().steps()[1].turn,
        Some(Turn::Straight)
    );
    assert_eq!(
        plan(&map, &path, Tag::RC).unwrap().steps()[1].turn,
        Some(Turn::Straight)
    );
    assert_eq!(
        plan(&map, &path, Tag::RS).unwrap().steps()[1].turn,
        Some(Turn::Left)
    );
    assert_eq!(
        plan(&map, &path, Tag::LC).unwrap().steps()[1].turn,
        Some(Turn::Left)
    );
    // Valence 3, one quad on the left and two on the right.
    let map = fan(3);
    let path = given(&map, &[Vert::new(3), Vert::new(0), Vert::new(1)]);
    assert_eq!(
        plan(&map, &path, Tag::LS).unwrap().steps()[1].turn,
        Some(Turn::Left)
    );
    assert_eq!(
        plan(&map, &path, Tag::LC).unwrap().steps()[1].turn,
        Some(Turn::Straight)
    );
}

#[test]
fn valence_6_is_refused_with_the_vertex() {
    let map = fan(6);
    let path = given(&map, &[Vert::new(1), Vert::new(0), Vert::new(7)]);
    let e = plan(&map, &path, Tag::LS).unwrap_err();
    assert_eq!(
        e,
        PlanError::Valence {
            index: 1,
            vertex: Vert::new(0),
            valence: 6
        }
    );
    assert!(e.to_string().contains("valence 6"));
    // As an end too.
    let path = given(&map, &[Vert::new(0), Vert::new(1)]);
    assert!(matches!(
        plan(&map, &path, Tag::RS),
        Err(PlanError::Valence { index: 0, .. })
    ));
}

#[test]
fn boundary_counting() {
    // Grid 3 x 3, (i, j) = 4 j + i. Along the bottom row the right side is the boundary.
    let map = gen::grid(3, 3).map;
    let path = given(&map, &[Vert::new(0), Vert::new(1), Vert::new(2)]);
    for t in Tag::CCW {
        // Vertex 1 is a regular boundary vertex: counted on the free side, straight.
        let p = plan(&map, &path, t).unwrap();
        assert_eq!(p.steps()[1].turn, Some(Turn::Straight));
        assert_eq!(p.terminal(), t);
    }
    // Rim vertex m_0 of a fan has valence 2 on the boundary (irregular): its left side is the
    // quad, its right side the boundary.
    let map = fan(5);
    let path = given(&map, &[Vert::new(1), Vert::new(2), Vert::new(3)]);
    assert_eq!(
        plan(&map, &path, Tag::LS).unwrap().steps()[1].turn,
        Some(Turn::Left)
    );
    let e = plan(&map, &path, Tag::RS).unwrap_err();
    assert!(matches!(e, PlanError::Boundary { index: 1, vertex, .. } if vertex == Vert::new(2)));
    assert!(e.to_string().contains("boundary"));
}

#[test]
fn non_quads_are_refused() {
    // A fan of four faces around 0, the last one (0, 7, .., 1) a triangle, a pentagon or a
    // hexagon: whatever its degree, a face other than a quad is refused.
    for k in [3u32, 5, 6] {
        let mut last: Vec<u32> = vec![0, 7];
        last.extend(8..8 + (k - 3));
        last.push(1);
        let faces: Vec<Vec<u32>> = vec![vec![0, 1, 2, 3], vec![0, 3, 4, 5], vec![0, 5, 6, 7], last];
        let map = Map::from_polygons(8 + (k - 3) as usize, &faces).unwrap();
        let path = given(&map, &[Vert::new(3), Vert::new(0), Vert::new(1)]);
        // From spoke 1 going ccw to spoke 3 meets the quad (0, 1, 2, 3): fine on the left.
        assert!(plan(&map, &path, Tag::LS).is_ok(), "degree {k}");
        // On the right the other face is met.
        assert!(
            matches!(
                plan(&map, &path, Tag::RS),
                Err(PlanError::NotQuad { index: 1, .. })
            ),
            "degree {k}"
        );
    }
}

#[test]
fn a_path_from_another_map_is_refused() {
    let small = gen::grid(2, 2).map;
    let big = gen::grid(5, 5).map;
    let path = given(&small, &[Vert::new(0), Vert::new(1), Vert::new(4)]);
    assert!(matches!(
        plan(&big, &path, Tag::LS),
        Err(PlanError::StalePath { .. })
    ));
}

#[test]
fn given_path_defects_are_refused_with_the_reason() {
    // Grid 3 x 3, (i, j) = 4 j + i.
    let map = gen::grid(3, 3).map;
    let v = Vert::new;
    let o = SketchOptions::default();
    let err = |vs: &[Vert], from, to, o: &SketchOptions| {
        validate_path(&map, from, to, vs, o).unwrap_err()
    };
    assert_eq!(err(&[v(0)], v(0), v(0), &o), SketchError::TooShort(1));
    assert_eq!(err(&[], v(0), v(1), &o), SketchError::TooShort(0));
    assert_eq!(
        err(&[v(0), v(99)], v(0), v(99), &o),
        SketchError::DeadVertex(v(99))
    );
    assert_eq!(
        err(&[v(0), v(1)], v(4), v(1), &o),
        SketchError::WrongEnd {
            start: true,
            expected: v(4),
            found: v(0)
        }
    );
    assert_eq!(
        err(&[v(0), v(1)], v(4), v(1), &o).to_string(),
        "the path should start at vertex 4 but starts at vertex 0"
    );
    assert_eq!(
        err(&[v(0), v(1)], v(0), v(2), &o),
        SketchError::WrongEnd {
            start: false,
            expected: v(2),
            found: v(1)
        }
    );
    assert_eq!(
        err(&[v(0), v(1)], v(0), v(2), &o).to_string(),
        "the path should end on vertex 2 but ends on vertex 1"
    );
    assert_eq!(
        err(&[v(0), v(1), v(6)], v(0), v(6), &o),
        SketchError::NotAdjacent {
            index: 1,
            a: v(1),
            b: v(6)
        }
    );
    assert_eq!(
        err(&[v(0), v(1), v(5), v(4), v(0), v(1)], v(0), v(1), &o),
        SketchError::Repeated {
            vertex: v(0),
            first: 0,
            second: 4
        }
    );
    // Forbid the edge 1-5.
    let e15 = map
        .vertex_darts(v(1))
        .find(|&d| map.dest(d) == v(5))
        .unwrap()
        .edge();
    let fe = SketchOptions::default().forbid_edges(vec![e15]);
    assert_eq!(
        err(&[v(0), v(1), v(5)], v(0), v(5), &fe),
        SketchError::ForbiddenEdge {
            index: 1,
            edge: e15
        }
    );
    // Forbid face 0 = (0, 1, 5, 4): its edges 0-1 is refused, and 1-2 is still fine.
    let ff = SketchOptions::default().forbid_faces(vec![Face::new(0)]);
    assert_eq!(
        err(&[v(0), v(1), v(2)], v(0), v(2), &ff),
        SketchError::ForbiddenFace {
            index: 0,
            face: Face::new(0)
        }
    );
    assert!(validate_path(&map, v(1), v(3), &[v(1), v(2), v(3)], &ff).is_ok());
    // Every message names something concrete.
    for e in [
        SketchError::TooShort(1),
        SketchError::NotAdjacent {
            index: 1,
            a: v(1),
            b: v(6),
        },
        SketchError::ForbiddenEdge {
            index: 1,
            edge: e15,
        },
    ] {
        assert!(!e.to_string().is_empty());
    }
}

#[test]
fn sketch_errors() {
    let map = gen::grid(3, 3).map;
    let v = Vert::new;
    let o = SketchOptions::default();
    assert_eq!(
        sketch(&map, v(5), v(5), &o),
        Err(SketchError::SameVertex(v(5)))
    );
    assert_eq!(
        sketch(&map, v(5), v(50), &o),
        Err(SketchError::DeadVertex(v(50)))
    );
    // Wall off vertex 0 (corner, edges 0-1 and 0-4).
    let walls: Vec<Edge> = map.vertex_darts(v(0)).map(|d| d.edge()).collect();
    let walled = SketchOptions::default().forbid_edges(walls);
    assert_eq!(
        sketch(&map, v(0), v(15), &walled),
        Err(SketchError::NoPath {
            from: v(0),
            to: v(15)
        })
    );
    // Protecting the corner face has the same effect for vertex 0.
    let prot = SketchOptions::default().forbid_faces(vec![Face::new(0)]);
    assert_eq!(
        sketch(&map, v(0), v(15), &prot),
        Err(SketchError::NoPath {
            from: v(0),
            to: v(15)
        })
    );
    let n = map.dart_slots() / 2;
    let short = SketchOptions::default().weights(vec![1.0; n - 1]);
    assert_eq!(
        sketch(&map, v(0), v(15), &short),
        Err(SketchError::WeightsTooShort {
            expected: n,
            got: n - 1
        })
    );
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        let mut w = vec![1.0; n];
        w[3] = bad;
        let o = SketchOptions::default().weights(w);
        assert!(matches!(
            sketch(&map, v(0), v(15), &o),
            Err(SketchError::BadWeight { edge, .. }) if edge == Edge::new(3)
        ));
    }
}

#[test]
fn weights_steer_the_path() {
    // Grid 4 x 1: bottom row 0..=4, top row 5..=9. Make the bottom row expensive.
    let map = gen::grid(4, 1).map;
    let n = map.dart_slots() / 2;
    let mut w = vec![1.0; n];
    for d in map.darts() {
        let (a, b) = (map.origin(d).index(), map.dest(d).index());
        if a <= 4 && b <= 4 {
            w[d.index() / 2] = 10.0;
        }
    }
    let o = SketchOptions::default().weights(w);
    let p = sketch(&map, Vert::new(0), Vert::new(4), &o).unwrap();
    assert_eq!(p.len(), 6);
    assert!(p.vertices()[1..6].iter().all(|v| v.index() >= 5));
    // Without weights the bottom row is the shortest path.
    let p = sketch(&map, Vert::new(0), Vert::new(4), &SketchOptions::default()).unwrap();
    assert_eq!(p.len(), 4);
}

#[test]
fn valence_2_is_refused_with_the_vertex() {
    let mut map = gen::torus_grid(8, 8).map;
    let r = zipmesh::ops::quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
    let w = r.vertex();
    assert_eq!(map.valence(w), 2);
    let ns: Vec<Vert> = map.vertex_darts(w).map(|d| map.dest(d)).collect();
    let path = given(&map, &[ns[0], w, ns[1]]);
    for t in Tag::CCW {
        assert_eq!(
            plan(&map, &path, t),
            Err(PlanError::Valence {
                index: 1,
                vertex: w,
                valence: 2
            })
        );
    }
    // A path that only passes beside it is fine.
    let far = sketch(
        &map,
        Vert::new(36),
        Vert::new(40),
        &SketchOptions::default(),
    )
    .unwrap();
    assert!(plan(&map, &far, Tag::LS).is_ok());
}

/// A self-avoiding walk on the `n` x `n` torus grid from (0, 0): each step turns by a random
/// quarter (never back); the walk stops before revisiting a vertex. Returns lattice points.
fn lattice_walk(n: u32, seed: u64, max_len: usize) -> Vec<(u32, u32)> {
    let mut rng = zipmesh::rng::Rng::new(seed);
    let dirs: [(i64, i64); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];
    let mut dir = rng.below(4);
    let mut pts = vec![(0u32, 0u32)];
    let mut seen = HashSet::from([(0u32, 0u32)]);
    for _ in 0..max_len {
        // 0 = straight, 1 = left, 3 = right.
        dir = (dir + [0, 0, 1, 3][rng.below(4)]) % 4;
        let (x, y) = pts[pts.len() - 1];
        let nx = (x as i64 + dirs[dir].0).rem_euclid(n as i64) as u32;
        let ny = (y as i64 + dirs[dir].1).rem_euclid(n as i64) as u32;
        if !seen.insert((nx, ny)) {
            break;
        }
        pts.push((nx, ny));
    }
    pts
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// On a regular torus grid the plan's turns are the lattice walk's geometric turns (the
    /// sign of the cross product of consecutive steps), and carrying the terminal tag rotated
    /// by pi back along the reversed path gives the initial tag rotated by pi.
    #[test]
    fn lattice_turns_and_reversal(seed in any::<u64>(), t in 0usize..4) {
        let n = 16u32;
        let map = gen::torus_grid(n as usize, n as usize).map;
        let pts = lattice_walk(n, seed, 12);
        prop_assume!(pts.len() >= 3);
        let vs: Vec<Vert> = pts.iter().map(|&(x, y)| tv(n, x, y)).collect();
        let path = given(&map, &vs);
        let initial = Tag::CCW[t];
        let p = plan(&map, &path, initial).unwrap();
        let step = |a: (u32, u32), b: (u32, u32)| {
            let w = |d: i64| if d > 1 { d - n as i64 } else if d < -1 { d + n as i64 } else { d };
            (w(b.0 as i64 - a.0 as i64), w(b.1 as i64 - a.1 as i64))
        };
        let mut tag = initial;
        for i in 1..pts.len() - 1 {
            let (a, b) = (step(pts[i - 1], pts[i]), step(pts[i], pts[i + 1]));
            let cross = a.0 * b.1 - a.1 * b.0;
            let want = match cross.signum() { 1 => Turn::Left, -1 => Turn::Right, _ => Turn::Straight };
            prop_assert_eq!(p.steps()[i].turn, Some(want));
            tag = tag.after(want);
            prop_assert_eq!(p.steps()[i].tag, tag);
        }
        let back: Vec<Vert> = vs.iter().rev().copied().collect();
        let r = plan(&map, &given(&map, &back), p.terminal().rotate_pi()).unwrap();
        prop_assert_eq!(r.terminal(), initial.rotate_pi());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Arbitrary handles, forbidden lists and weights never panic; every answer is a valid path
    /// or a typed error, and a plan along random walks on mixed meshes (boundaries, triangles,
    /// irregular vertices) is either refused with a reason or has tags that follow its turns.
    #[test]
    fn no_panics_on_arbitrary_input(
        seed in any::<u64>(),
        a in 0u32..2000, b in 0u32..2000,
        fe in proptest::collection::vec(any::<u32>(), 0..40),
        ff in proptest::collection::vec(0u32..2000, 0..10),
        w in proptest::collection::vec(prop_oneof![Just(f64::NAN), Just(-1.0), 0.0..10.0f64], 0..20),
        mixed in any::<bool>(),
    ) {
        let map = if mixed { gen::random_mixed(300, 1, 2, seed).map } else { gen::random_quad(300, 0, 3, seed).map };
        let (from, to) = (Vert::new(a % (map.vertex_slots() as u32 + 5)), Vert::new(b % (map.vertex_slots() as u32 + 5)));
        let mut weights = vec![1.0; map.dart_slots() / 2];
        for (i, &x) in w.iter().enumerate() {
            let k = (seed as usize).wrapping_add(i * 7919) % weights.len().max(1);
            if let Some(slot) = weights.get_mut(k) { *slot = x; }
        }
        for opts in [
            SketchOptions::default().forbid_edges(fe.iter().map(|&e| Edge::new(e))).forbid_faces(ff.iter().map(|&f| Face::new(f))),
            SketchOptions::default().weights(weights.clone()).avoid_boundary(true),
        ] {
            if let Ok(p) = sketch(&map, from, to, &opts) {
                check_path(&map, &p, from, to, &HashSet::new());
            }
        }
        // A random walk, made simple by cutting it at its first repeat.
        let mut rng = zipmesh::rng::Rng::new(seed);
        let verts: Vec<Vert> = map.vertices().collect();
        prop_assume!(!verts.is_empty());
        let mut walk = vec![verts[rng.below(verts.len())]];
        for _ in 0..20 {
            let darts: Vec<Dart> = map.vertex_darts(walk[walk.len() - 1]).collect();
            let next = map.dest(darts[rng.below(darts.len())]);
            if walk.contains(&next) { break; }
            walk.push(next);
        }
        prop_assume!(walk.len() >= 2);
        let path = given(&map, &walk);
        for t in Tag::CCW {
            match plan(&map, &path, t) {
                Ok(p) => {
                    prop_assert_eq!(p.steps().len(), walk.len());
                    for (i, s) in p.steps().iter().enumerate() {
                        prop_assert_eq!(s.vertex, walk[i]);
                        if i > 0 {
                            let turn = s.turn.unwrap_or(Turn::Straight);
                            prop_assert_eq!(s.tag, p.steps()[i - 1].tag.after(turn));
                        }
                    }
                    prop_assert!(!p.to_string().is_empty());
                }
                Err(e) => prop_assert!(!e.to_string().is_empty()),
            }
        }
    }
}

/// What the plan, its parts and its errors print: one line per vertex with the tag, the turn
/// and the count that gave it, in the words of Sec. 2.6.
#[test]
fn plans_and_their_parts_read_as_the_paper_words_them() {
    let n = 10u32;
    let map = gen::torus_grid(n as usize, n as usize).map;
    // East, east, north: straight at (1, 0), a left turn at (2, 0) (one quad on the left).
    let vs = [tv(n, 0, 0), tv(n, 1, 0), tv(n, 2, 0), tv(n, 2, 1)];
    let p = plan(&map, &given(&map, &vs), Tag::LS).unwrap();
    let lines: Vec<String> = p.to_string().lines().map(String::from).collect();
    let want = [
        format!("vertex {}: LS (start)", vs[0].index()),
        format!(
            "vertex {}: LS (straight, 2 quads on the left)",
            vs[1].index()
        ),
        format!("vertex {}: RC (left, 1 quad on the left)", vs[2].index()),
        format!("vertex {}: RC (end)", vs[3].index()),
    ];
    assert_eq!(lines, want);
    let words = [
        (Turn::Left.to_string(), "left"),
        (Turn::Straight.to_string(), "straight"),
        (Turn::Right.to_string(), "right"),
        (Side::Left.to_string(), "left"),
        (Side::Right.to_string(), "right"),
    ];
    for (got, want) in words {
        assert_eq!(got, want);
    }
    let e = "up".parse::<Tag>().unwrap_err();
    assert_eq!(
        e.to_string(),
        "unknown move \"up\": expected LS, RS, LC or RC"
    );
}

/// Sec. 2.6's counting rule for every count on both sides, and quarter turns of the compass
/// as repeated single turns.
#[test]
fn turns_from_counts_and_compass_quarter_turns() {
    for side in [Side::Left, Side::Right] {
        let (toward, away) = match side {
            Side::Left => (Turn::Left, Turn::Right),
            Side::Right => (Turn::Right, Turn::Left),
        };
        assert_eq!(Turn::from_count(side, 0), None);
        assert_eq!(Turn::from_count(side, 1), Some(toward));
        assert_eq!(Turn::from_count(side, 2), Some(Turn::Straight));
        for k in 3..8 {
            assert_eq!(
                Turn::from_count(side, k),
                Some(away),
                "{k} quads on the {side}"
            );
        }
    }
    for t in Tag::CCW {
        let (mut ccw, mut cw) = (t, t);
        for k in 0..9 {
            assert_eq!(t.turned(k), ccw, "{t} turned {k}");
            assert_eq!(t.turned(-k), cw, "{t} turned -{k}");
            ccw = ccw.ccw();
            cw = cw.cw();
        }
    }
}

/// A path whose edge is still live and still ends where the path says, but no longer starts
/// there (a collapse moved its origin), is stale.
#[test]
fn a_path_whose_edge_moved_its_origin_is_refused() {
    let mut map = gen::torus_grid(8, 8).map;
    let r = zipmesh::ops::quad::collapse_quad(&mut map.clone(), Dart::new(0)).unwrap();
    let c = r.removed();
    // An edge of the removed corner to a vertex outside the collapsed quad.
    let quad: Vec<Vert> = map.face_darts(r.face()).map(|d| map.origin(d)).collect();
    let out = map
        .vertex_darts(c)
        .find(|&d| !quad.contains(&map.dest(d)))
        .unwrap();
    let path = given(&map, &[c, map.dest(out)]);
    zipmesh::ops::quad::collapse_quad(&mut map, Dart::new(0)).unwrap();
    assert!(map.is_live_dart(out) && map.dest(out) == path.vertices()[1]);
    assert_ne!(map.origin(out), c);
    assert_eq!(
        plan(&map, &path, Tag::LS),
        Err(PlanError::StalePath { index: 0 })
    );
}
