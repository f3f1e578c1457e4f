//! v7 movement with 5-7 generation and removal, and 5-5-7 / 5-7-7 triple cancellation
//! (`zipmesh::tri_edit`, triangle paper Sec. 6.2 and 7.2-7.3): every configuration
//! at a lone v7 of a lattice cone and at the v5 of a geodesic sphere, and random meshes
//! (refusal equal to the `can_*` with the map unchanged, or the documented effect and exact
//! undo).

use proptest::prelude::*;
use zipmesh::gen::{cone_disk, geodesic_sphere};
use zipmesh::invariants::{irregular_valences, MeshKind};
use zipmesh::tri_edit::{
    can_cancel_triple, can_generate_pair_v7, can_remove_pair_v7, cancel_triple,
    cancel_triple_along, generate_pair, generate_pair_v7, remove_pair_v7, Generation, Moved,
    TripleEdit, Via, Via7,
};
use zipmesh::{gen, is_isomorphic, Map, Vert};

fn irregular(map: &Map) -> Vec<(usize, bool)> {
    irregular_valences(map, MeshKind::Triangle)
}

/// `before`'s irregular multiset with `add` added and `remove` taken out.
fn changed(before: &Map, add: &[usize], remove: &[usize]) -> Vec<(usize, bool)> {
    let mut v = irregular(before);
    v.extend(add.iter().map(|&k| (k, false)));
    for &k in remove {
        let i = v.iter().position(|&x| x == (k, false)).expect("present");
        v.remove(i);
    }
    v.sort();
    v
}

/// Every v7 generation at every interior v7 of `map`, both configurations and readings:
/// refused as `can_*` says with the map unchanged, or one v5 and one v7 more with the named
/// vertices as documented and exact undo; then the removal and the triple cancellation of
/// the generated 5-7-7 both give back `map` up to isomorphism. Returns how many applied.
fn check_v7_generations(map: &Map) -> usize {
    let mut applied = 0;
    let v7: Vec<Vert> = map
        .vertices()
        .filter(|&v| map.valence(v) == 7 && !map.is_boundary_vertex(v))
        .collect();
    for v in v7 {
        for d in map.vertex_darts(v).collect::<Vec<_>>() {
            for via in Via7::ALL {
                for moved in [Moved::First, Moved::Second] {
                    let mut m = map.clone();
                    let can = can_generate_pair_v7(&m, d, via);
                    let g = match generate_pair_v7(&mut m, d, via, moved) {
                        Ok(g) => g,
                        Err(e) => {
                            assert_eq!(can, Err(e));
                            assert_eq!(&m, map);
                            continue;
                        }
                    };
                    assert_eq!(can, Ok(()));
                    applied += 1;
                    m.check().unwrap();
                    let (p, q) = g.pair().unwrap();
                    let vals = (m.valence(g.moved()), m.valence(p), m.valence(q));
                    assert_eq!(vals, (7, 5, 7), "{via:?}");
                    assert!(m.dart_between(p, q).is_some());
                    assert!(m.dart_between(p, g.moved()).is_some());
                    assert_eq!(m.valence(v), 6);
                    assert_eq!(irregular(&m), changed(map, &[5, 7], &[]));
                    let generated = m.clone();
                    g.undo(&mut m).unwrap();
                    assert_eq!(&m, map);
                    // Removal: the moved v7 steps back.
                    let mut r = generated.clone();
                    assert_eq!(can_remove_pair_v7(&r, g.moved(), p, q), Ok(()));
                    let back = remove_pair_v7(&mut r, g.moved(), p, q).unwrap();
                    r.check().unwrap();
                    assert_eq!(r.valence(back.moved()), 7);
                    assert!(is_isomorphic(&r, map), "{via:?} {moved:?}");
                    // The same as a triple cancellation, in any order of the three.
                    for three in [[g.moved(), p, q], [p, q, g.moved()]] {
                        let mut c = generated.clone();
                        let t = cancel_triple(&mut c, &three).unwrap();
                        assert!(matches!(*t, TripleEdit::Seven(_)));
                        assert_eq!(c.valence(t.remaining()), 7);
                        assert!(is_isomorphic(&c, map));
                        t.undo(&mut c).unwrap();
                        assert_eq!(c, generated);
                    }
                }
            }
        }
    }
    applied
}

#[test]
fn v7_moves_with_pair_generation_and_removal() {
    // A lone v7 at the centre of a lattice cone: every configuration applies.
    let cone = cone_disk(7, 5);
    assert_eq!(check_v7_generations(&cone), 7 * 2 * 2);
}

/// Applies the generation `inverse_generation` names after cancelling `three` in
/// `generated`; whether it gives back `generated` up to isomorphism (`None` when no
/// generation was named).
fn named_inverse_restores(generated: &Map, three: [Vert; 3]) -> Option<bool> {
    let mut m = generated.clone();
    let t = cancel_triple_along(&mut m, &three, 0).unwrap();
    let (d, config) = t.inverse_generation(&m, generated)?;
    assert_eq!(m.origin(d), t.remaining());
    let done = match Generation::of(m.valence(t.remaining()), config)? {
        Generation::Five(via) => generate_pair(&mut m, d, via, Moved::First).is_ok(),
        Generation::Seven(via) => generate_pair_v7(&mut m, d, via, Moved::First).is_ok(),
        Generation::Quadruple(_) => false,
    };
    Some(done && is_isomorphic(&m, generated))
}

/// Every adjacent triple generated at the v5 of a sphere and at the v7 of a cone names the
/// generation that undoes its cancellation, and that generation restores the triple.
#[test]
fn triple_cancellations_name_the_generation_that_undoes_them() {
    let (mut named, mut all) = (0, 0);
    let starts = [(geodesic_sphere(2), 5), (cone_disk(7, 5), 7)];
    for (map, k) in &starts {
        for v in map.vertices().filter(|&v| map.valence(v) == *k) {
            if map.is_boundary_vertex(v) {
                continue;
            }
            for d in map.vertex_darts(v).collect::<Vec<_>>() {
                for g in [Via::Flip, Via::Collapse, Via::Split] {
                    let mut m = map.clone();
                    let r = match (k, g) {
                        (5, via) => generate_pair(&mut m, d, via, Moved::First)
                            .map(|g| (g.moved(), g.pair())),
                        (_, Via::Flip) => generate_pair_v7(&mut m, d, Via7::Flip, Moved::First)
                            .map(|g| (g.moved(), g.pair())),
                        (_, Via::Split) => generate_pair_v7(&mut m, d, Via7::Split, Moved::First)
                            .map(|g| (g.moved(), g.pair())),
                        _ => continue,
                    };
                    let Ok((moved, Some((p, q)))) = r else {
                        continue;
                    };
                    all += 1;
                    match named_inverse_restores(&m, [moved, p, q]) {
                        Some(ok) => {
                            assert!(ok, "v{k} {g:?}");
                            named += 1;
                        }
                        None => panic!("v{k} {g:?}: no inverse generation named"),
                    }
                }
            }
        }
    }
    // 12 v5 x 5 darts x 3 configurations, and one v7 x 7 darts x 2.
    assert_eq!((named, all), (12 * 5 * 3 + 7 * 2, 12 * 5 * 3 + 7 * 2));
}

#[test]
fn five_five_seven_triples_cancel_into_one_v5() {
    // Sec. 7.3 then 7.2: each v5 of the sphere generates a 5-5-7 triple in every
    // configuration, and the cancellation gives one v5 and a map isomorphic to the sphere.
    let sphere = geodesic_sphere(2);
    let mut done = 0;
    for v in (0..12).map(Vert::new) {
        for d in sphere.vertex_darts(v).collect::<Vec<_>>() {
            for via in [Via::Flip, Via::Collapse, Via::Split] {
                let mut m = sphere.clone();
                let g = generate_pair(&mut m, d, via, Moved::First).unwrap();
                let (p, q) = g.pair().unwrap();
                let generated = m.clone();
                assert_eq!(can_cancel_triple(&m, &[q, p, g.moved()]), Ok(()));
                let t = cancel_triple(&mut m, &[q, p, g.moved()]).unwrap();
                assert!(matches!(*t, TripleEdit::Five(_)));
                m.check().unwrap();
                assert_eq!(m.valence(t.remaining()), 5);
                assert_eq!(irregular(&m), irregular(&sphere));
                assert!(is_isomorphic(&m, &sphere), "{via:?}");
                t.undo(&mut m).unwrap();
                assert_eq!(m, generated);
                done += 1;
            }
        }
    }
    assert_eq!(done, 12 * 5 * 3);
}

#[test]
fn layers_follow_v7_generation_and_triple_cancellation() {
    let mut map = cone_disk(7, 4);
    let mut marks: Vec<f64> = (0..map.vertex_slots()).map(|i| i as f64).collect();
    let before = (map.clone(), marks.clone());
    let d = map.vertex_dart(Vert::new(0));
    let g = generate_pair_v7(&mut (&mut map, &mut marks), d, Via7::Split, Moved::First).unwrap();
    assert_eq!(marks.len(), map.vertex_slots());
    let (p, q) = g.record().pair().unwrap();
    let mid = (map.clone(), marks.clone());
    let c = cancel_triple(&mut (&mut map, &mut marks), &[g.record().moved(), p, q]).unwrap();
    c.undo(&mut (&mut map, &mut marks)).unwrap();
    assert_eq!((map.clone(), marks.clone()), mid);
    g.undo(&mut (&mut map, &mut marks)).unwrap();
    assert_eq!((map, marks), before);
}

/// Random triples around each v5 and v7: a refusal equal to `can_cancel_triple`'s with the
/// map unchanged, or one vertex fewer of each of the pair's types and exact undo.
fn check_random_triples(map: &Map) -> usize {
    let mut applied = 0;
    for x in map.vertices() {
        let nb: Vec<Vert> = map.vertex_darts(x).map(|d| map.dest(d)).collect();
        for i in 0..nb.len() {
            for j in 0..nb.len() {
                if i == j {
                    continue;
                }
                let three = [nb[i], x, nb[j]];
                let mut m = map.clone();
                let can = can_cancel_triple(&m, &three);
                match cancel_triple(&mut m, &three) {
                    Err(e) => {
                        assert_eq!(can, Err(e));
                        assert_eq!(&m, map);
                    }
                    Ok(t) => {
                        applied += 1;
                        m.check().unwrap();
                        let k = m.valence(t.remaining());
                        assert!(k == 5 || k == 7);
                        assert_eq!(irregular(&m), changed(map, &[], &[5, 7]));
                        t.undo(&mut m).unwrap();
                        assert_eq!(&m, map);
                    }
                }
            }
        }
    }
    applied
}

#[test]
fn random_meshes_have_cancellable_triples() {
    let mut applied = 0;
    for seed in 0..4 {
        let map = gen::random_triangle(400, 1, 1, seed).map;
        applied += check_random_triples(&map);
        check_v7_generations(&map);
    }
    assert!(applied > 0, "no triple cancelled on four random meshes");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn triples_and_v7_moves_on_random_meshes(faces in 60usize..300, genus in 0usize..3, holes in 0usize..3, seed: u64) {
        let map = gen::random_triangle(faces, genus, holes, seed).map;
        check_random_triples(&map);
        check_v7_generations(&map);
    }
}

/// Sec. 7.2 for triples that are not adjacent: a triple is generated (a v5 of the sphere or
/// the v7 of a cone moves and makes a pair), the pair walks `k` steps away in each
/// direction, and `cancel_triple_along` brings it back and cancels: one vertex of the
/// doubled type left, the start's irregular multiset, exact undo; or a refusal with the map
/// unchanged. Returns (applied, tried).
fn check_far_triples(start: &Map, v: Vert, seven: bool) -> (usize, usize) {
    let (mut applied, mut tried) = (0, 0);
    for k in 1..=3 {
        for dir in zipmesh::tri_edit::Direction::ALL {
            let mut m = start.clone();
            let d = m.vertex_dart(v);
            let (moved, mut pq) = if seven {
                let g = generate_pair_v7(&mut m, d, Via7::Split, Moved::First).unwrap();
                (g.moved(), g.pair().unwrap())
            } else {
                let g = generate_pair(&mut m, d, Via::Flip, Moved::First).unwrap();
                (g.moved(), g.pair().unwrap())
            };
            let walked =
                (0..k).all(
                    |_| match zipmesh::tri_edit::move_pair(&mut m, pq.0, pq.1, dir) {
                        Ok(s) => {
                            pq = (s.p(), s.q());
                            true
                        }
                        Err(_) => false,
                    },
                );
            let lead = if seven { pq.0 } else { pq.1 };
            if !walked || m.dart_between(lead, moved).is_some() {
                continue; // still (or again) adjacent: not the case under test
            }
            tried += 1;
            let before = m.clone();
            match cancel_triple_along(&mut m, &[moved, pq.0, pq.1], 12) {
                Err(_) => assert_eq!(m, before),
                Ok(c) => {
                    applied += 1;
                    m.check().unwrap();
                    assert!(!c.moves().is_empty());
                    assert_eq!(m.valence(c.remaining()), if seven { 7 } else { 5 });
                    assert_eq!(irregular(&m), irregular(start));
                    c.undo(&mut m).unwrap();
                    assert_eq!(m, before);
                }
            }
        }
    }
    (applied, tried)
}

#[test]
fn far_triples_cancel_after_moving_the_pair() {
    let sphere = geodesic_sphere(3);
    let (mut a5, mut t5) = (0, 0);
    for v in (0..12).map(Vert::new) {
        let (a, t) = check_far_triples(&sphere, v, false);
        a5 += a;
        t5 += t;
    }
    let (a7, t7) = check_far_triples(&cone_disk(7, 7), Vert::new(0), true);
    println!("far 5-5-7: {a5} of {t5} cancelled; far 5-7-7: {a7} of {t7}");
    assert!(t5 > 0 && t7 > 0);
    assert!(
        a5 * 2 >= t5 && a7 * 2 >= t7,
        "5-5-7 {a5}/{t5}, 5-7-7 {a7}/{t7}"
    );
}
