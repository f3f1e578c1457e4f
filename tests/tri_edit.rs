//! Semantic triangle edits (`zipmesh::tri_edit`, irregular-vertex paper Sec. 6.2-6.3) on a
//! regular triangulated torus and on random triangle meshes: valence effects, exact undo,
//! refusals that leave the map unchanged, and the six directions of a 5-7 movement.

use proptest::prelude::*;
use zipmesh::invariants::{irregular_valences, MeshKind};
use zipmesh::ops::tri;
use zipmesh::tri_edit::{can_move_pair, move_pair, move_pair_with, Direction, PairMove};
use zipmesh::{gen, is_isomorphic, Map, Vert};

/// A quad torus grid with every quad cut along the same diagonal: every vertex of valence 6.
fn torus_triangles(nx: usize, ny: usize) -> Map {
    let quads = gen::torus_quads(nx, ny);
    let tris: Vec<[u32; 3]> = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    Map::from_polygons(nx * ny, &tris).unwrap()
}

/// The torus with the diagonal 0-(nx+1) flipped: v5 at 0 and nx+1, v7 at 1 and nx.
/// Returns the map and the adjacent pair (v5 0, v7 1).
fn torus_with_pair(nx: usize, ny: usize) -> (Map, Vert, Vert) {
    let mut map = torus_triangles(nx, ny);
    let d = map.dart_between(vert(0), vert(nx + 1)).unwrap();
    tri::flip_edge(&mut map, d).unwrap();
    (map, vert(0), vert(1))
}

/// A vertex handle from a slot number.
fn vert(i: usize) -> Vert {
    Vert::new(i as u32)
}

fn irregular(map: &Map) -> Vec<(usize, bool)> {
    irregular_valences(map, MeshKind::Triangle)
}

/// The valence of every live vertex slot (0 for a dead slot).
fn valences(map: &Map) -> Vec<usize> {
    (0..map.vertex_slots())
        .map(vert)
        .map(|v| {
            if map.is_live_vertex(v) {
                map.valence(v)
            } else {
                0
            }
        })
        .collect()
}

/// Asserts the documented effect of a 5-7 movement from `before` to `map`: a valid map, the
/// new pair an adjacent interior v5 and v7, the irregular multiset unchanged, and every
/// vertex other than the old and new pair (and a split's new vertex) with its old valence.
fn assert_moved(before: &Map, map: &Map, m: &PairMove) {
    map.check().unwrap();
    assert_eq!((map.valence(m.p()), map.valence(m.q())), (5, 7), "{m:?}");
    assert!(map.dart_between(m.p(), m.q()).is_some());
    assert_eq!(irregular(before), irregular(map));
    let (old, new) = (valences(before), valences(map));
    let (p0, q0) = m.before();
    for (i, (&a, &b)) in old.iter().zip(&new).enumerate() {
        let v = vert(i);
        // A split may reuse a freed slot for its new, regular vertex.
        let created = a == 0 && b == 6;
        if a != b && !created && ![p0, q0, m.p(), m.q()].contains(&v) {
            panic!("{v:?} changed valence {a} -> {b} in {m:?}");
        }
    }
    // Only a split creates a vertex, and it is regular.
    for (i, &b) in new.iter().enumerate().skip(old.len()) {
        assert!(b == 0 || b == 6, "new vertex {i} of valence {b}");
    }
}

/// Moves the pair `k` steps in `dir`, asserting the documented effect at each step.
fn walk(map: &mut Map, mut pq: (Vert, Vert), dir: Direction, k: usize) -> (Vert, Vert) {
    for _ in 0..k {
        let before = map.clone();
        let m = move_pair(map, pq.0, pq.1, dir).unwrap();
        assert_moved(&before, map, &m);
        pq = (m.p(), m.q());
    }
    pq
}

/// A 5-7 pair in a regular neighbourhood: the flip's pair moved three steps away from the
/// other pair the flip made.
fn lone_pair() -> (Map, Vert, Vert) {
    let (mut map, p, q) = torus_with_pair(14, 14);
    let (p, q) = walk(&mut map, (p, q), Direction::SplitRight, 3);
    (map, p, q)
}

#[test]
fn six_directions_apply_and_differ() {
    let (map, p, q) = lone_pair();
    let mut results = Vec::new();
    for dir in Direction::ALL {
        let mut m = map.clone();
        assert_eq!(can_move_pair(&m, p, q, dir), Ok(()));
        let r = move_pair(&mut m, p, q, dir).unwrap();
        assert_moved(&map, &m, &r);
        assert_eq!(r.direction(), dir);
        assert_eq!(r.before(), (p, q));
        let after = m.clone();
        r.undo(&mut m).unwrap();
        assert_eq!(m, map);
        results.push(after);
    }
    for i in 0..6 {
        for j in i + 1..6 {
            assert!(!is_isomorphic(&results[i], &results[j]), "{i} and {j}");
        }
    }
}

#[test]
fn repeated_moves_keep_the_orientation() {
    // k steps in a direction then k in the opposite one come back (up to isomorphism) only
    // if every step moved the same way: the pair kept its orientation.
    let (map, p, q) = lone_pair();
    for dir in Direction::ALL {
        for k in 1..=3 {
            let mut m = map.clone();
            let pq = walk(&mut m, (p, q), dir, k);
            let pq = walk(&mut m, pq, dir.opposite(), k);
            assert!(is_isomorphic(&m, &map), "{dir:?} x {k}");
            assert!(m.dart_between(pq.0, pq.1).is_some());
        }
    }
}

#[test]
fn torus_pair_moves_and_refusals() {
    // Next to the flip's other pair two directions are refused, with the map unchanged.
    let (map, p, q) = torus_with_pair(12, 12);
    for dir in Direction::ALL {
        let mut m = map.clone();
        match move_pair(&mut m, p, q, dir) {
            Ok(r) => {
                assert_moved(&map, &m, &r);
                r.undo(&mut m).unwrap();
            }
            Err(e) => assert_eq!(can_move_pair(&map, p, q, dir), Err(e)),
        }
        assert_eq!(m, map);
    }
    // Not a pair: refused, unchanged.
    let mut m = map.clone();
    assert!(move_pair(&mut m, q, p, Direction::FlipLeft).is_err());
    assert!(move_pair(&mut m, p, vert(5), Direction::FlipLeft).is_err());
    assert_eq!(m, map);
}

#[test]
fn attributes_follow_and_come_back() {
    let (map, p, q) = lone_pair();
    let marks: Vec<f64> = (0..map.vertex_slots()).map(|i| i as f64).collect();
    for dir in Direction::ALL {
        let (mut m, mut a) = (map.clone(), marks.clone());
        let e = move_pair_with(&mut m, &mut a, p, q, dir).unwrap();
        assert_moved(&map, &m, e.record());
        assert!(a.len() >= m.vertex_slots());
        e.undo_with(&mut m, &mut a).unwrap();
        assert_eq!((m, a), (map.clone(), marks.clone()));
    }
}

/// Every adjacent (v5, v7) pair of interior vertices.
fn pairs(map: &Map) -> Vec<(Vert, Vert)> {
    let mut out = Vec::new();
    for p in map.vertices() {
        if map.is_boundary_vertex(p) || map.valence(p) != 5 {
            continue;
        }
        for d in map.vertex_darts(p) {
            let q = map.dest(d);
            if !map.is_boundary_vertex(q) && map.valence(q) == 7 {
                out.push((p, q));
            }
        }
    }
    out
}

#[test]
fn random_meshes_have_movable_pairs() {
    // The property below is not vacuous: random meshes have pairs that move.
    let mut moved = 0;
    for seed in 0..8 {
        let map = gen::random_triangle(400, 1, 1, seed).map;
        for (p, q) in pairs(&map) {
            moved += Direction::ALL
                .into_iter()
                .filter(|&d| can_move_pair(&map, p, q, d).is_ok())
                .count();
        }
    }
    println!("{moved} movable (pair, direction)");
    assert!(moved > 0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn every_pair_every_direction(faces in 60usize..400, genus in 0usize..3, holes in 0usize..3, seed: u64) {
        let map = gen::random_triangle(faces, genus, holes, seed).map;
        for (p, q) in pairs(&map) {
            for dir in Direction::ALL {
                let mut m = map.clone();
                let can = can_move_pair(&m, p, q, dir);
                match move_pair(&mut m, p, q, dir) {
                    Ok(r) => {
                        prop_assert_eq!(can, Ok(()));
                        assert_moved(&map, &m, &r);
                        r.undo(&mut m).unwrap();
                    }
                    Err(e) => prop_assert_eq!(can, Err(e)),
                }
                prop_assert_eq!(&m, &map);
            }
        }
    }
}
