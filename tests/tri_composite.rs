//! Composite movement of a pair of irregular vertices that need not be adjacent
//! (`zipmesh::tri_edit::move_far_pair`, triangle paper Sec. 7.1): a 5-7 pair at
//! distance 2 on a triangulated torus, 5-5 pairs of a geodesic sphere; and the general
//! solution of Sec. 7.1.2's equations.

mod common;

use common::tri::{distance, far_five_seven, irregular};
use std::collections::BTreeSet;
use zipmesh::gen::geodesic_sphere;
use zipmesh::invariants::canonical::canonical_hash;
use zipmesh::tri_edit::{
    can_move_far_pair, far_pair_directions, far_pair_inverse, far_pair_start, move_far_pair, Moved,
    Start,
};
use zipmesh::{Map, Vert};

/// Every pipeline start at `s` (every dart, configuration and reading) towards `o`: a
/// refusal equal to `can_move_far_pair`'s with the map `==`, or the pair's two vertices
/// with their old valences at `pair()`, every other irregular vertex where and what it was,
/// `check()`, and exact undo. Returns the canonical hashes of the results and how many
/// kept the pair's graph distance.
fn check_starts(map: &Map, s: Vert, o: Vert) -> (BTreeSet<u128>, usize, usize) {
    let (ks, ko) = (map.valence(s), map.valence(o));
    let rest: BTreeSet<_> = irregular(map)
        .into_iter()
        .filter(|&(v, _)| v != s && v != o)
        .collect();
    let dist = distance(map, s, o);
    let (mut results, mut applied, mut kept) = (BTreeSet::new(), 0, 0);
    for d in map.vertex_darts(s).collect::<Vec<_>>() {
        for &start in Start::all(ks) {
            for moved in [Moved::First, Moved::Second] {
                let mut m = map.clone();
                let can = can_move_far_pair(&m, d, start, moved, o, 64);
                let e = match move_far_pair(&mut m, d, start, moved, o, 64) {
                    Ok(e) => e,
                    Err(err) => {
                        assert_eq!(can, Err(err));
                        assert_eq!(&m, map);
                        continue;
                    }
                };
                assert_eq!(can, Ok(()));
                applied += 1;
                m.check().unwrap();
                let (a, b) = e.pair();
                assert_eq!((m.valence(a), m.valence(b)), (ks, ko), "{start:?}");
                let now: BTreeSet<_> = irregular(&m)
                    .into_iter()
                    .filter(|&(v, _)| v != a && v != b)
                    .collect();
                assert_eq!(now, rest, "{start:?}: another irregular vertex changed");
                kept += usize::from(distance(&m, a, b) == dist);
                results.insert(canonical_hash(&m));
                e.undo(&mut m).unwrap();
                assert_eq!(&m, map);
            }
        }
    }
    (results, applied, kept)
}

/// Sec. 7.1.1: a 5-7 pair at distance 2 moves from its v5 in exactly six different
/// directions (the results of the 30 starts fall into six isomorphism classes), each a
/// translation (the pair's distance kept, "the relative position of the two vertices
/// remains the same"); the reverse sequence, started from the v7, gives no other result;
/// `far_pair_directions` names the six.
#[test]
fn far_five_seven_pair_moves_in_six_directions() {
    let (map, p, q) = far_five_seven();
    assert_eq!(distance(&map, p, q), 2);
    let (from5, applied5, kept5) = check_starts(&map, p, q);
    assert_eq!(from5.len(), 6, "{applied5} starts applied");
    assert_eq!(kept5, applied5, "every move is a translation");
    let (from7, applied7, kept7) = check_starts(&map, q, p);
    assert!(applied7 > 0);
    assert_eq!(kept7, applied7);
    assert!(
        from7.is_subset(&from5),
        "the v7's starts give the same moves"
    );
    let dirs = far_pair_directions(&map, p, q, 64).unwrap();
    assert_eq!(dirs.len(), 6);
    let named: BTreeSet<u128> = dirs
        .iter()
        .map(|&(d, start, moved)| {
            let mut m = map.clone();
            move_far_pair(&mut m, d, start, moved, q, 64).unwrap();
            canonical_hash(&m)
        })
        .collect();
    assert_eq!(named, from5);
}

/// The undo of a composite move, found by `far_pair_inverse`: for every direction of the
/// far 5-7 pair, one and two steps, the direction it names, taken as many steps from the
/// moved pair, gives the input back (up to isomorphism); against another map it names none.
#[test]
fn far_pair_inverse_names_a_direction_that_undoes_the_move() {
    let (map, p, q) = far_five_seven();
    let mut found = 0;
    for dir in 0..6 {
        for steps in 1..=2u32 {
            let mut m = map.clone();
            let (mut s, mut o) = (p, q);
            for _ in 0..steps {
                let (d, start, moved) = far_pair_start(&m, s, o, dir, 64).unwrap();
                (s, o) = move_far_pair(&mut m, d, start, moved, o, 64)
                    .unwrap()
                    .pair();
            }
            let Some(back) = far_pair_inverse(&m, &map, (s, o), steps, 64) else {
                continue;
            };
            found += 1;
            for _ in 0..steps {
                let (d, start, moved) = far_pair_start(&m, s, o, back, 64).unwrap();
                (s, o) = move_far_pair(&mut m, d, start, moved, o, 64)
                    .unwrap()
                    .pair();
            }
            assert_eq!(
                canonical_hash(&m),
                canonical_hash(&map),
                "dir {dir}, {steps} steps"
            );
            let other = geodesic_sphere(2);
            assert_eq!(far_pair_inverse(&m, &other, (s, o), steps, 64), None);
        }
    }
    assert!(found >= 10, "an undo found for {found} of 12 moves");
}

/// Sec. 7.1.2: a 5-5 pair (two neighbouring v5 of a geodesic sphere) moves in six
/// different directions too, but not by a translation: every move changes the pair's
/// distance ("the relative location of the irregular vertices will be changed").
#[test]
fn five_five_pairs_of_a_sphere_move() {
    let map = geodesic_sphere(2);
    let fives: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 5).collect();
    let o = *fives[1..]
        .iter()
        .min_by_key(|&&w| distance(&map, fives[0], w))
        .unwrap();
    let (results, applied, kept) = check_starts(&map, fives[0], o);
    assert_eq!(results.len(), 6, "{applied} applied");
    assert_eq!(kept, 0, "a 5-5 move is not a translation");
    assert_eq!(far_pair_directions(&map, fives[0], o, 64).unwrap().len(), 6);
}

/// Sec. 7.1.2 for a 7-7 pair: the two v7 of the far 5-7 fixture's other pairs.
#[test]
fn seven_seven_pairs_move() {
    let (map, _, q) = far_five_seven();
    let o = irregular(&map)
        .into_iter()
        .filter(|&(v, k)| k == 7 && v != q)
        .map(|(v, _)| v)
        .min_by_key(|&w| distance(&map, q, w))
        .unwrap();
    let (results, applied, _) = check_starts(&map, q, o);
    eprintln!(
        "7-7 at distance {}: {applied} applied, {} distinct",
        distance(&map, q, o),
        results.len()
    );
    assert!(!results.is_empty());
}

/// Sec. 7.1.2's equations `b_i = d_(i-1) + d_(i+1) - d_i + L_p` (`p = 1` for `i` = 1, 3,
/// 2 for 2, 4) against the paper's general solution: over a box of integers, `(d, L)`
/// solves them exactly when `d3 = b1 - b3 + d1`, `d4 = b2 - b4 + d2`,
/// `L1 = b1 + b4 - b2 + d1 - 2 d2`, `L2 = b2 + b3 - b1 + d2 - 2 d1`; so moving one vertex
/// (`d1`, `d2`) moves the other by the same amounts (`Δd1 = Δd3`, `Δd2 = Δd4`).
#[test]
fn general_solution_of_the_five_five_equations() {
    let r = 0i64..5;
    let mut solutions = 0;
    for b in itertools_product4(1..5) {
        for d in itertools_product4(r.clone()) {
            for l1 in -12i64..13 {
                for l2 in -12i64..13 {
                    let dd = |i: usize| d[(i + 3) % 4]; // d_i for i = 1..4, cyclic
                    let eq = (1..=4).all(|i| {
                        let l = if i % 2 == 1 { l1 } else { l2 };
                        b[i - 1] == dd(i - 1 + 4) + dd(i + 1) - dd(i) + l
                    });
                    let general = d[2] == b[0] - b[2] + d[0]
                        && d[3] == b[1] - b[3] + d[1]
                        && l1 == b[0] + b[3] - b[1] + d[0] - 2 * d[1]
                        && l2 == b[1] + b[2] - b[0] + d[1] - 2 * d[0];
                    assert_eq!(eq, general, "b {b:?} d {d:?} L {l1} {l2}");
                    solutions += usize::from(eq);
                }
            }
        }
    }
    assert!(solutions > 0);
}

/// The integer 4-tuples of a range.
fn itertools_product4(r: std::ops::Range<i64>) -> Vec<[i64; 4]> {
    let v: Vec<i64> = r.collect();
    let mut out = Vec::new();
    for &a in &v {
        for &b in &v {
            for &c in &v {
                for &d in &v {
                    out.push([a, b, c, d]);
                }
            }
        }
    }
    out
}
