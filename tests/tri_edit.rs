//! Semantic triangle edits (`zipmesh::tri_edit`, triangle paper Sec. 6.2-6.3) on a
//! regular triangulated torus and on random triangle meshes: valence effects, exact undo,
//! refusals that leave the map unchanged, the six directions of a 5-7 movement, 5-7 generation, type splits, 5-5-7-7 quadruples.

mod common;

use common::tri_sweep::{adjacent_pairs, assert_pair_moved, tri_multiset, with_added};
use proptest::prelude::*;
use zipmesh::gen::{geodesic_sphere, subdivided_bipyramid, subdivided_tetrahedron};
use zipmesh::ops::tri;
use zipmesh::tri_edit::{
    aggregate_type, can_aggregate_type, can_generate_pair, can_generate_quadruple, can_move_pair,
    can_remove_pair, can_remove_quadruple, can_split_type, generate_pair, generate_quadruple,
    move_pair, remove_pair, remove_quadruple, split_type, Direction, Moved, PairMove, Quadruple,
    TriEditError, Via,
};
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

/// The third corner of `d`'s face when it is a triangle.
fn tri_apex(map: &Map, d: zipmesh::Dart) -> Option<Vert> {
    map.face(d)?;
    let n = map.next(d);
    (map.next(map.next(n)) == d).then(|| map.dest(n))
}

/// Asserts the documented effect of a 5-7 movement from `before` to `map`: a valid map and
/// `assert_pair_moved`.
fn assert_moved(before: &Map, map: &Map, m: &PairMove) {
    map.check().unwrap();
    assert_pair_moved(before, map, m);
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
        let e = move_pair(&mut (&mut m, &mut a), p, q, dir).unwrap();
        assert_moved(&map, &m, e.record());
        assert!(a.len() >= m.vertex_slots());
        e.undo(&mut (&mut m, &mut a)).unwrap();
        assert_eq!((m, a), (map.clone(), marks.clone()));
    }
}

#[test]
fn random_meshes_have_movable_pairs() {
    // The property below is not vacuous: random meshes have pairs that move.
    let mut moved = 0;
    for seed in 0..8 {
        let map = gen::random_triangle(400, 1, 1, seed).map;
        for (p, q) in adjacent_pairs(&map) {
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
        for (p, q) in adjacent_pairs(&map) {
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

/// Every generation at every v5 of `map`, every via, both readings: refused with the map
/// unchanged, or one v5 and one v7 more, the named vertices as documented, exact undo, and
/// the removal of the generated pair gives back `map` up to isomorphism. Returns how many
/// applied.
fn check_generations(map: &Map) -> usize {
    let mut applied = 0;
    let v5: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 5).collect();
    for v in v5 {
        for d in map.vertex_darts(v).collect::<Vec<_>>() {
            for via in [Via::Flip, Via::Collapse, Via::Split] {
                for moved in [Moved::First, Moved::Second] {
                    let mut m = map.clone();
                    let can = can_generate_pair(&m, d, via);
                    let g = match generate_pair(&mut m, d, via, moved) {
                        Ok(g) => g,
                        Err(e) => {
                            assert_eq!(can, Err(e));
                            assert_eq!(&m, map);
                            continue;
                        }
                    };
                    applied += 1;
                    m.check().unwrap();
                    let (p, q) = g.pair().unwrap();
                    assert_eq!(
                        (m.valence(g.moved()), m.valence(p), m.valence(q)),
                        (5, 5, 7)
                    );
                    assert!(m.dart_between(p, q).is_some() && g.moved() != p);
                    assert_eq!(tri_multiset(&m), with_added(map, &[(5, false), (7, false)]));
                    let generated = m.clone();
                    g.undo(&mut m).unwrap();
                    assert_eq!(&m, map);
                    // The inverse reading: remove the pair, the moved v5 steps back.
                    let mut m = generated;
                    assert_eq!(can_remove_pair(&m, g.moved(), p, q), Ok(()));
                    let r = remove_pair(&mut m, g.moved(), p, q).unwrap();
                    m.check().unwrap();
                    assert_eq!(m.valence(r.moved()), 5);
                    assert!(is_isomorphic(&m, map), "{via:?} {moved:?}");
                }
            }
        }
    }
    applied
}

#[test]
fn v5_moves_with_pair_generation_and_removal() {
    // Twelve lone v5 in a regular neighbourhood: every configuration applies.
    let ico = geodesic_sphere(2);
    assert_eq!(check_generations(&ico), 12 * 5 * 3 * 2);
    // Random meshes: refusals or the documented effect.
    for seed in 0..3 {
        check_generations(&gen::random_triangle(300, 1, 1, seed).map);
    }
}

#[test]
fn removal_refusals_leave_the_map() {
    let map = gen::random_triangle(300, 0, 1, 9).map;
    let vs: Vec<Vert> = map.vertices().take(30).collect();
    for &a in &vs {
        for &b in &vs {
            for &c in vs.iter().take(6) {
                let mut m = map.clone();
                let can = can_remove_pair(&m, a, b, c);
                match remove_pair(&mut m, a, b, c) {
                    Ok(r) => {
                        m.check().unwrap();
                        r.undo(&mut m).unwrap();
                    }
                    Err(e) => assert_eq!(can, Err(e)),
                }
                assert_eq!(m, map);
            }
        }
    }
}

#[test]
fn generation_with_attributes_comes_back() {
    let mut map = geodesic_sphere(2);
    let mut marks: Vec<f64> = (0..map.vertex_slots()).map(|i| i as f64).collect();
    let before = (map.clone(), marks.clone());
    for via in [Via::Flip, Via::Collapse, Via::Split] {
        let d = map.vertex_dart(vert(0));
        let e = generate_pair(&mut (&mut map, &mut marks), d, via, Moved::First).unwrap();
        let (p, q) = e.record().pair().unwrap();
        let moved = e.record().moved();
        let r = remove_pair(&mut (&mut map, &mut marks), moved, p, q).unwrap();
        r.undo(&mut (&mut map, &mut marks)).unwrap();
        e.undo(&mut (&mut map, &mut marks)).unwrap();
        assert_eq!((&map, &marks), (&before.0, &before.1));
    }
}

/// `before`'s irregular multiset with one `(k, false)` removed and `add` added.
fn replaced(before: &Map, k: usize, add: &[(usize, bool)]) -> Vec<(usize, bool)> {
    let mut v = tri_multiset(before);
    let i = v.iter().position(|&x| x == (k, false)).unwrap();
    v.remove(i);
    v.extend_from_slice(add);
    v.sort();
    v
}

/// A type split of `v` (valence `k`): refused with the map unchanged, or the documented
/// irregular vertices, `check()`, exact undo; with `back`, aggregation restores the type.
fn check_type_split(map: &Map, v: Vert, back: bool) -> bool {
    let k = map.valence(v);
    let mut m = map.clone();
    let can = can_split_type(&m, v);
    let s = match split_type(&mut m, v) {
        Ok(s) => s,
        Err(e) => {
            assert_eq!(can, Err(e));
            assert_eq!(&m, map);
            return false;
        }
    };
    assert_eq!(can, Ok(()));
    m.check().unwrap();
    let (n, val) = if k > 7 { (k - 6, 7) } else { (6 - k, 5) };
    let got: Vec<usize> = s.vertices().iter().map(|&x| m.valence(x)).collect();
    assert_eq!(got, vec![val; n], "v{k}");
    assert_eq!(tri_multiset(&m), replaced(map, k, &vec![(val, false); n]));
    if back {
        let mut a = m.clone();
        let g = aggregate_type(&mut a, s.vertices()).unwrap();
        a.check().unwrap();
        assert_eq!(a.valence(g.vertices()[0]), k);
        assert!(is_isomorphic(&a, map));
        assert!(s.is_split() && !g.is_split());
        assert!(s.inverse_restores(&m, map));
        // Splitting the aggregated vertex again gives the split's result up to isomorphism.
        let mut again = a.clone();
        let resplit = split_type(&mut again, g.vertices()[0]).is_ok();
        assert_eq!(
            g.inverse_restores(&a, &m),
            resplit && is_isomorphic(&again, &m)
        );
        g.undo(&mut a).unwrap();
        assert_eq!(a, m);
    }
    s.undo(&mut m).unwrap();
    assert_eq!(&m, map);
    true
}

/// The vk `v` split into k - 6 v7 and those gathered back by [`aggregate_type`]: one vk,
/// the irregular multiset as before, `check()`, exact undo. Returns whether the result is
/// isomorphic to `map`.
fn split_and_gather(map: &Map, v: Vert) -> bool {
    let k = map.valence(v);
    let mut m = map.clone();
    let s = split_type(&mut m, v).unwrap();
    let mut a = m.clone();
    assert_eq!(can_aggregate_type(&a, s.vertices()), Ok(()));
    let g = aggregate_type(&mut a, s.vertices()).unwrap();
    a.check().unwrap();
    assert_eq!(
        g.vertices()
            .iter()
            .map(|&x| a.valence(x))
            .collect::<Vec<_>>(),
        [k]
    );
    assert_eq!(tri_multiset(&a), tri_multiset(map));
    g.undo(&mut a).unwrap();
    assert_eq!(a, m);
    let mut again = m.clone();
    aggregate_type(&mut again, s.vertices()).unwrap();
    let same = is_isomorphic(&again, map);
    assert_eq!(s.inverse_restores(&m, map), same);
    same
}

#[test]
fn type_splitting_and_aggregation() {
    let mut same = 0;
    for k in 8..=13 {
        let map = subdivided_bipyramid(k, 2);
        assert!(check_type_split(&map, vert(0), false), "v{k}");
        same += usize::from(split_and_gather(&map, vert(0)));
        // The ring's v4s split into two v5 and aggregate back.
        assert!(check_type_split(&map, vert(2), true));
    }
    // Gathering is a search: it may put the vk elsewhere than the split took it from.
    println!("{same} of 6 apexes gathered back to an isomorphic map");
    assert!(same >= 4, "{same}");
    let tet = subdivided_tetrahedron(2);
    for v in 0..4 {
        assert!(check_type_split(&tet, vert(v), true));
    }
    // Regular and v5 vertices are not split; nothing changes.
    let ico = geodesic_sphere(2);
    let mut m = ico.clone();
    assert_eq!(
        split_type(&mut m, vert(0)).unwrap_err(),
        TriEditError::WrongValence
    );
    assert_eq!(
        split_type(&mut m, vert(100)).unwrap_err(),
        TriEditError::WrongValence
    );
    assert_eq!(m, ico);
}

#[test]
fn type_splits_on_random_meshes() {
    let mut applied = 0;
    for seed in 0..4 {
        let map = gen::random_triangle(300, 1, 1, seed).map;
        for v in map.vertices().collect::<Vec<_>>() {
            applied += usize::from(check_type_split(&map, v, false));
        }
        // Aggregation refusals leave the map: random pairs and triples of v5 and of v7.
        let of =
            |k: usize| -> Vec<Vert> { map.vertices().filter(|&v| map.valence(v) == k).collect() };
        let (v5, v7) = (of(5), of(7));
        let windows = v5.windows(3).take(40).chain(v7.windows(3).take(40));
        for w in windows {
            for args in [&w[..2], w] {
                let mut m = map.clone();
                let can = can_aggregate_type(&m, args);
                match aggregate_type(&mut m, args) {
                    Ok(g) => {
                        m.check().unwrap();
                        g.undo(&mut m).unwrap();
                    }
                    Err(e) => assert_eq!(can, Err(e)),
                }
                assert_eq!(m, map);
            }
        }
    }
    println!("{applied} type splits applied");
    // Too many v7, or one given twice: refused, the map unchanged.
    let map = gen::random_triangle(2000, 1, 0, 9).map;
    let v7: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 7).collect();
    assert!(v7.len() > 64, "{}", v7.len());
    for args in [&v7[..], &[v7[0], v7[0]][..]] {
        let mut m = map.clone();
        assert_eq!(
            aggregate_type(&mut m, args).unwrap_err(),
            TriEditError::NotAPair
        );
        assert_eq!(m, map);
    }
}

/// Two v7 that are the apexes of an edge with regular interior ends gather into a v8 (or
/// the collapse is refused), on random meshes and on the v8 splits of bipyramids.
#[test]
fn two_v7_across_an_edge_gather() {
    let (mut gathered, mut refused) = (0, 0);
    let mut meshes: Vec<Map> = (0..6)
        .map(|s| gen::random_triangle(500, 1, 0, s).map)
        .collect();
    for n in [8, 9, 10] {
        let mut m = subdivided_bipyramid(n, 2);
        split_type(&mut m, vert(0)).unwrap();
        meshes.push(m);
    }
    for map in meshes {
        for d in map.darts() {
            let (Some(a), Some(b)) = (tri_apex(&map, d), tri_apex(&map, d.twin())) else {
                continue;
            };
            let ends_regular = [map.origin(d), map.dest(d)]
                .iter()
                .all(|&v| map.valence(v) == 6 && !map.is_boundary_vertex(v));
            let interior7 = |v: Vert| map.valence(v) == 7 && !map.is_boundary_vertex(v);
            if !(ends_regular && interior7(a) && interior7(b) && a < b && d < d.twin()) {
                continue;
            }
            let mut m = map.clone();
            match aggregate_type(&mut m, &[a, b]) {
                Ok(g) => {
                    gathered += 1;
                    assert_eq!(m.valence(g.vertices()[0]), 8);
                    assert_eq!(tri_multiset(&m).len() + 1, tri_multiset(&map).len());
                }
                Err(e) => {
                    refused += 1;
                    assert_eq!(m, map);
                    assert!(tri::can_collapse_edge(&map, d).is_err(), "{e:?}");
                }
            }
        }
    }
    println!("{gathered} pairs of v7 gathered, {refused} refused by the collapse");
    assert!(gathered >= 10, "{gathered}");
}

#[test]
fn quadruple_generation_and_removal() {
    let map = geodesic_sphere(3);
    let regular_v: Vec<Vert> = map
        .vertices()
        .filter(|&v| map.valence(v) == 6)
        .step_by(37)
        .collect();
    let mut applied = [0usize; 3];
    for &v in &regular_v {
        for d in map.vertex_darts(v).collect::<Vec<_>>() {
            for how in Quadruple::ALL {
                let mut m = map.clone();
                let can = can_generate_quadruple(&m, d, how);
                let g = match generate_quadruple(&mut m, d, how) {
                    Ok(g) => g,
                    Err(e) => {
                        assert_eq!(e, TriEditError::Irregular);
                        assert_eq!(can, Err(e));
                        assert_eq!(m, map);
                        continue;
                    }
                };
                assert_eq!(can, Ok(()));
                applied[how as usize] += 1;
                m.check().unwrap();
                let mut got: Vec<usize> = g.vertices().iter().map(|&x| m.valence(x)).collect();
                got.sort();
                assert_eq!(got, [5, 5, 7, 7], "{how:?}");
                let add = [(5, false), (5, false), (7, false), (7, false)];
                assert_eq!(tri_multiset(&m), with_added(&map, &add));
                // Flip and split give a quadruple in two triangles; collapse-then-flip a chain.
                assert_eq!(
                    g.in_two_triangles(&m),
                    how != Quadruple::CollapseFlip,
                    "{how:?}"
                );
                if how != Quadruple::CollapseFlip {
                    let mut r = m.clone();
                    assert_eq!(can_remove_quadruple(&r, g.vertices()), Ok(()));
                    remove_quadruple(&mut r, g.vertices()).unwrap();
                    r.check().unwrap();
                    assert!(is_isomorphic(&r, &map));
                } else {
                    let r = remove_quadruple(&mut m.clone(), g.vertices());
                    assert_eq!(r.unwrap_err(), TriEditError::NotAPair);
                }
                g.undo(&mut m).unwrap();
                assert_eq!(m, map);
            }
        }
    }
    // Every configuration applies (starts next to a v5 refuse as `Irregular`, below).
    assert!(applied.iter().all(|&n| n > 90), "{applied:?}");
    // A v5 is not a start: refused, unchanged.
    let mut m = map.clone();
    let d = m.vertex_dart(vert(0));
    assert_eq!(
        generate_quadruple(&mut m, d, Quadruple::Flip).unwrap_err(),
        TriEditError::WrongValence
    );
    assert_eq!(m, map);
}

#[test]
fn quadruple_generation_on_random_meshes() {
    for seed in 0..3 {
        let map = gen::random_triangle(300, 1, 1, seed).map;
        for d in map.darts().step_by(5).collect::<Vec<_>>() {
            for how in Quadruple::ALL {
                let mut m = map.clone();
                if let Ok(g) = generate_quadruple(&mut m, d, how) {
                    m.check().unwrap();
                    let add = [(5, false), (5, false), (7, false), (7, false)];
                    assert_eq!(tri_multiset(&m), with_added(&map, &add));
                    g.undo(&mut m).unwrap();
                }
                assert_eq!(m, map);
            }
        }
    }
}

/// The discrete Gauss-Bonnet identity (paper Eq. 2) for a region `R` (a set of triangles)
/// of a closed triangle mesh whose boundary is a union of simple loops:
///
/// `sum over boundary vertices of (3 - t(v)) + sum over interior vertices of (6 - l(v))
///  = 6 chi(R)`,
///
/// with `t(v)` the number of triangles of `R` at `v`, `l(v)` the valence and `chi(R) =
/// V - E + F` of `R`'s closure. With a regular boundary (`l = 6`) `3 - t(v) = m(v) - 3`, the
/// paper's turning term (`m(v)` triangles outside `R`); for a disk `chi(R) = 1` (the paper's
/// right side reads `6 chi(M)`, which is the case `R = M`). Returns whether the region was
/// tested (false when its boundary pinches).
fn gauss_bonnet_region(map: &Map, region: &std::collections::HashSet<zipmesh::Face>) -> bool {
    use std::collections::{HashMap, HashSet};
    let inside = |d: zipmesh::Dart| map.face(d).is_some_and(|f| region.contains(&f));
    let mut t: HashMap<Vert, i64> = HashMap::new();
    let mut edges = HashSet::new();
    let mut boundary_edges: HashMap<Vert, i64> = HashMap::new();
    for &f in region {
        for d in map.face_darts(f) {
            *t.entry(map.origin(d)).or_default() += 1;
            edges.insert(d.edge());
            if !inside(d.twin()) {
                *boundary_edges.entry(map.origin(d)).or_default() += 1;
            }
        }
    }
    if boundary_edges.values().any(|&k| k != 1) {
        return false; // a boundary vertex on two loops: not a surface with boundary
    }
    let chi = t.len() as i64 - edges.len() as i64 + region.len() as i64;
    let total: i64 = t
        .iter()
        .map(|(&v, &tv)| {
            if boundary_edges.contains_key(&v) {
                3 - tv
            } else {
                6 - map.valence(v) as i64
            }
        })
        .sum();
    assert_eq!(total, 6 * chi, "region of {} faces", region.len());
    true
}

#[test]
fn gauss_bonnet_on_random_regions() {
    use std::collections::HashSet;
    let mut rng = zipmesh::rng::Rng::new(13);
    let mut tested = 0;
    for seed in 0..6 {
        let map = gen::random_triangle(400, seed as usize % 3, 0, seed).map;
        let faces: Vec<zipmesh::Face> = map.faces().collect();
        for _ in 0..20 {
            // Grow a region from a random face through random neighbours.
            let mut region = HashSet::new();
            let mut front = vec![faces[rng.below(faces.len())]];
            let size = 1 + rng.below(120);
            while region.len() < size && !front.is_empty() {
                let f = front.swap_remove(rng.below(front.len()));
                if region.insert(f) {
                    front.extend(map.face_darts(f).filter_map(|d| map.face(d.twin())));
                }
            }
            tested += usize::from(gauss_bonnet_region(&map, &region));
        }
        // The whole mesh: chi(M).
        let all: HashSet<_> = faces.iter().copied().collect();
        assert!(gauss_bonnet_region(&map, &all));
    }
    assert!(tested > 60, "{tested}");
}
