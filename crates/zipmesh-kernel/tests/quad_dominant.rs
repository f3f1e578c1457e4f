//! Triangles in quad meshes (Q-zip paper, Sec. 3.2): the four moves (VE, EV, LE, RE) with
//! their contract, effect, exact undo and reverses, the effective-valence properties, the
//! generator, and the collisions of Fig. 15.

use proptest::prelude::*;
use std::collections::BTreeMap;
use zipmesh_kernel::ops::Refusal;
use zipmesh_kernel::quad_dominant::{self, collide, Collision, Move};
use zipmesh_kernel::{gen, is_isomorphic, Dart, Map, Mesh, Vert};

fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: n,
        ..ProptestConfig::default()
    }
}

/// A generated quad-dominant mesh: a torus grid, or a random quad mesh of some genus and
/// holes, with triangle pairs walked apart.
fn mesh_strategy() -> impl Strategy<Value = (Mesh, Vec<Dart>)> {
    prop_oneof![
        (6usize..12, 6usize..12, 1usize..3, any::<u64>())
            .prop_map(|(nx, ny, p, s)| gen::quad_dominant(nx, ny, p, s)),
        (0usize..3, 0usize..2, 1usize..3, 0usize..20, any::<u64>()).prop_map(
            |(g, h, p, steps, s)| gen::with_triangle_pairs(
                gen::random_quad(250, g, h, s),
                p,
                steps,
                s ^ 1
            )
        ),
    ]
}

/// Every vertex's effective valence.
fn effective(map: &Map, tips: &[Dart]) -> BTreeMap<Vert, i64> {
    map.vertices()
        .map(|v| (v, quad_dominant::effective_valence(map, tips, v)))
        .collect()
}

/// The tip darts after a move of triangle `i`: its new one, the others followed.
fn with_tip(tips: &[Dart], i: usize, rec: &quad_dominant::TriangleMove) -> Vec<Dart> {
    let mut out: Vec<Dart> = tips.iter().map(|&d| rec.follow(d)).collect();
    out[i] = rec.tip();
    out
}

/// One move of triangle `i`, every check: `can` agrees, a refusal changes nothing, an
/// application is valid, has its documented effect, keeps the triangle's face, keeps the
/// effective valences as stated, and undoes `==`.
fn check_move(map: &Map, tips: &[Dart], i: usize, mv: Move) -> Result<bool, TestCaseError> {
    let t = tips[i];
    let mut m = map.clone();
    let can = quad_dominant::can_move_triangle(map, t, mv);
    let effect = mv.effect(map, t);
    match quad_dominant::move_triangle(&mut m, t, mv) {
        Err(r) => {
            prop_assert_eq!(Err(r), can);
            prop_assert_eq!(effect.err(), Some(r));
            prop_assert_eq!(&m, map);
            Ok(false)
        }
        Ok(rec) => {
            prop_assert_eq!(can, Ok(()));
            prop_assert_eq!(m.check(), Ok(()));
            let effect = effect.map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            prop_assert_eq!(effect.check(map, &m, &rec), Ok(()));
            prop_assert_eq!(
                m.face(rec.tip()),
                map.face(t),
                "the triangle keeps its face"
            );
            prop_assert_eq!(m.degree(m.face(rec.tip()).unwrap()), 3);
            let after = with_tip(tips, i, &rec);
            let (eb, ea) = (effective(map, tips), effective(&m, &after));
            match mv {
                // Every effective valence is kept.
                Move::LE | Move::RE => prop_assert_eq!(&eb, &ea),
                // The irregular ones are kept as a multiset (when no other triangle has the
                // same tip: which half keeps its tip decides the halves' valences).
                Move::VE => {
                    if tips
                        .iter()
                        .filter(|&&x| map.origin(x) == map.origin(t))
                        .count()
                        == 1
                    {
                        prop_assert_eq!(
                            quad_dominant::irregular_effective(map, tips),
                            quad_dominant::irregular_effective(&m, &after)
                        );
                    }
                }
                Move::EV => {
                    let (a, b) = (map.dest(t), map.dest(map.next(t)));
                    if eb[&a] == 4 || eb[&b] == 4 {
                        prop_assert_eq!(
                            quad_dominant::irregular_effective(map, tips),
                            quad_dominant::irregular_effective(&m, &after)
                        );
                    }
                }
            }
            check_reverse(map, &m, t, &rec)?;
            rec.undo(&mut m).unwrap();
            prop_assert_eq!(&m, map);
            Ok(true)
        }
    }
}

/// The reverse move from the new tip gives the map back up to isomorphism: always for VE
/// and the flips, for EV when the left base corner (the kept one) had valence 4.
fn check_reverse(
    before: &Map,
    after: &Map,
    t: Dart,
    rec: &quad_dominant::TriangleMove,
) -> Result<(), TestCaseError> {
    let mv = rec.kind();
    if mv == Move::EV && before.valence(before.dest(t)) != 4 {
        return Ok(());
    }
    let mut back = after.clone();
    let r = quad_dominant::move_triangle(&mut back, rec.tip(), mv.reverse());
    prop_assert!(
        r.is_ok(),
        "{} back from {}: {:?}",
        mv.reverse(),
        mv,
        r.err()
    );
    prop_assert!(is_isomorphic(&back, before), "{} then {}", mv, mv.reverse());
    Ok(())
}

proptest! {
    #![proptest_config(cases(48))]

    /// Every move of every triangle of a generated quad-dominant mesh.
    #[test]
    fn moves_keep_the_contract((mesh, tips) in mesh_strategy()) {
        prop_assert_eq!(mesh.map.check(), Ok(()));
        let mut applied = 0;
        for i in 0..tips.len() {
            for mv in Move::ALL {
                applied += check_move(&mesh.map, &tips, i, mv)? as usize;
            }
        }
        prop_assert!(applied > 0);
    }

    /// Random walks: after each move the checks hold, and undoing the whole walk gives the
    /// start back `==` (map and positions).
    #[test]
    fn walks_undo_exactly((mesh, tips) in mesh_strategy(), seq in proptest::collection::vec((0usize..4, 0usize..4), 1..24)) {
        let mut m = mesh.clone();
        let mut tips = tips;
        let mut done = Vec::new();
        for (i, k) in seq {
            let i = i % tips.len();
            if check_move(&m.map, &tips, i, Move::ALL[k])? {
                let e = Move::ALL[k].apply(&mut m, tips[i]).unwrap();
                prop_assert_eq!(m.positions.len(), m.map.vertex_slots());
                tips = with_tip(&tips, i, e.record());
                done.push(e);
            }
        }
        for e in done.iter().rev() {
            e.undo(&mut m).unwrap();
        }
        prop_assert_eq!(m, mesh);
    }
}

/// The generator makes the paper's triangles on a torus grid: tip of valence 5, two corners
/// of valence 4, every other vertex regular, no two triangles touching.
#[test]
fn generator_makes_paper_triangles() {
    for seed in 0..20 {
        let (mesh, tips) = gen::quad_dominant(12, 12, 2, seed);
        let m = &mesh.map;
        assert_eq!(m.check(), Ok(()));
        assert_eq!(tips.len(), 4, "seed {seed}");
        assert_eq!(quad_dominant::triangles(m).len(), 4);
        for &t in &tips {
            let c = [m.origin(t), m.dest(t), m.dest(m.next(t))].map(|v| m.valence(v));
            assert_eq!(c, [5, 4, 4], "seed {seed}");
            assert_eq!(quad_dominant::default_tip(m, m.face(t).unwrap()), Some(t));
        }
        assert!(quad_dominant::irregular_effective(m, &tips).is_empty());
        let irregular = m.vertices().filter(|&v| m.valence(v) != 4).count();
        assert_eq!(irregular, 4, "only the four tips, seed {seed}");
    }
}

/// In a regular neighbourhood each move moves the tip one edge and leaves a paper triangle.
#[test]
fn paper_triangle_moves_one_edge() {
    let (mesh, tips) = gen::quad_dominant(14, 14, 1, 5);
    for mv in Move::ALL {
        let mut m = mesh.map.clone();
        let t = tips[0];
        let tip = m.origin(t);
        let r = quad_dominant::move_triangle(&mut m, t, mv).unwrap();
        let nt = r.tip();
        let c = [m.origin(nt), m.dest(nt), m.dest(m.next(nt))].map(|v| m.valence(v));
        assert_eq!(c, [5, 4, 4], "{mv}");
        let new_tip = m.origin(nt);
        if mv == Move::VE || m.is_live_vertex(tip) && mv != Move::EV {
            assert!(m.dart_between(tip, new_tip).is_some(), "{mv}: one edge");
        }
        assert_eq!(m.valence(tip), 4, "{mv}: the old tip is regular");
    }
}

/// Refusals on hand-made cases: a quad is not a triangle; VE at a boundary tip.
#[test]
fn refusals() {
    let map = gen::torus_grid(4, 4).map;
    assert_eq!(
        quad_dominant::can_move_triangle(&map, Dart::new(0), Move::VE),
        Err(Refusal::WrongDegree)
    );
    // A grid with a split quad at the corner: the tips are on the boundary.
    let mut g = gen::grid(3, 3).map;
    let s = quad_dominant::split_quad(&mut g, Dart::new(0)).unwrap();
    assert_eq!(
        quad_dominant::can_move_triangle(&g, s.tips()[0], Move::VE),
        Err(Refusal::Boundary)
    );
    // The two halves of a split quad: each side flip runs into the other triangle.
    let mut t = gen::torus_grid(6, 6).map;
    let [a, b] = quad_dominant::split_quad(&mut t, Dart::new(0))
        .unwrap()
        .tips();
    assert_eq!(
        quad_dominant::can_move_triangle(&t, a, Move::RE),
        Err(Refusal::WrongDegree)
    );
    assert_eq!(
        quad_dominant::can_move_triangle(&t, b, Move::RE),
        Err(Refusal::WrongDegree)
    );
}

/// Walks the triangles of two pairs at random until two share an edge; returns the map,
/// the tips of all triangles, the indices of the two and the collision kind.
fn collide_by_walking(seed: u64) -> Option<(Map, Vec<Dart>, [usize; 2], Collision)> {
    let (mesh, tips) = gen::quad_dominant(9, 9, 2, seed);
    let mut m = mesh.map;
    let mut tips = tips;
    let mut rng = zipmesh_kernel::rng::Rng::new(seed);
    for _ in 0..600 {
        for i in 0..tips.len() {
            for j in i + 1..tips.len() {
                if let Some((kind, _)) = quad_dominant::collision(&m, tips[i], tips[j]) {
                    return Some((m, tips, [i, j], kind));
                }
            }
        }
        let i = rng.below(tips.len());
        if let Ok(r) = quad_dominant::move_triangle(&mut m, tips[i], Move::ALL[rng.below(4)]) {
            tips = with_tip(&tips, i, &r);
        }
    }
    None
}

/// Fig. 15: merging two triangles that meet changes effective valences exactly as the
/// collision kind says; from the paper's triangles in a regular mesh that is: oppositely
/// oriented ones (Opposite, BaseToBase) leave everything regular, orthogonal ones an
/// adjacent 3-5 pair, same-direction ones a v3 and a v5 on opposite corners of a quad.
/// Every kind is met, and every merge undoes `==`.
#[test]
fn collisions() {
    let mut seen: BTreeMap<Collision, usize> = BTreeMap::new();
    let mut checked_regular: BTreeMap<Collision, usize> = BTreeMap::new();
    for seed in 0..240 {
        let Some((mut m, tips, [i, j], kind)) = collide_by_walking(seed) else {
            continue;
        };
        let before = m.clone();
        let eb = effective(&m, &tips);
        let regular_before = eb.values().all(|&k| k == 4);
        let others: Vec<Dart> = (0..tips.len())
            .filter(|&k| k != i && k != j)
            .map(|k| tips[k])
            .collect();
        let (t1, t2) = (tips[i], tips[j]);
        let (want, removed) = collide::effective_changes(&m, t1, t2, &others).unwrap();
        let Ok(rec) = quad_dominant::merge_collision(&mut m, t1, t2) else {
            continue;
        };
        assert_eq!(m.check(), Ok(()));
        assert_eq!(
            zipmesh_kernel::ops::VertexChanges::removed_vertex(&rec),
            removed
        );
        let rest: Vec<Dart> = others.iter().map(|&d| rec.follow(d)).collect();
        let ea = effective(&m, &rest);
        let mut got: Vec<(Vert, i64)> = ea
            .iter()
            .filter(|(v, k)| eb[v] != **k)
            .map(|(&v, &k)| (v, k - eb[&v]))
            .collect();
        let mut want = want;
        got.sort();
        want.sort();
        assert_eq!(got, want, "seed {seed}: {kind:?}");
        assert!(removed.is_none_or(|y| !m.is_live_vertex(y)));
        if regular_before {
            let irregular: Vec<Vert> = m
                .vertices()
                .filter(|&v| quad_dominant::effective_valence(&m, &rest, v) != 4)
                .collect();
            match kind {
                Collision::Opposite | Collision::BaseToBase => {
                    assert!(irregular.is_empty(), "seed {seed}: {kind:?}")
                }
                Collision::Orthogonal | Collision::SameDirection => {
                    let [p, q] = irregular[..] else {
                        panic!("seed {seed}: {kind:?} {irregular:?}");
                    };
                    let e = |v| quad_dominant::effective_valence(&m, &rest, v);
                    let mut vals = [e(p), e(q)];
                    vals.sort();
                    assert_eq!(vals, [3, 5], "seed {seed}");
                    let adjacent = m.dart_between(p, q).is_some();
                    let quad = m.face(rec.quad()).unwrap();
                    let corners: Vec<Vert> = m.face_darts(quad).map(|d| m.origin(d)).collect();
                    let diagonal = |a: Vert, b: Vert| {
                        let i = corners.iter().position(|&c| c == a);
                        i.is_some_and(|i| corners[(i + 2) % 4] == b)
                    };
                    if kind == Collision::Orthogonal {
                        assert!(adjacent, "seed {seed}: an adjacent 3-5 pair");
                    } else {
                        assert!(!adjacent && diagonal(p, q), "seed {seed}: across the quad");
                    }
                }
            }
            *checked_regular.entry(kind).or_default() += 1;
        }
        rec.undo(&mut m).unwrap();
        assert_eq!(m, before);
        *seen.entry(kind).or_default() += 1;
    }
    eprintln!("collisions by kind: {seen:?}; from regular: {checked_regular:?}");
    for kind in [
        Collision::Opposite,
        Collision::BaseToBase,
        Collision::Orthogonal,
        Collision::SameDirection,
    ] {
        let n = checked_regular.get(&kind).copied().unwrap_or(0);
        assert!(
            n > 0,
            "{kind:?} never met from regular: {checked_regular:?}"
        );
    }
}

/// A split quad is the opposite kind, and merging it back gives the quad mesh `==`
/// up to isomorphism; undo of the split is `==`.
#[test]
fn split_and_merge_are_inverse() {
    let grid = gen::torus_grid(5, 5).map;
    for d in grid.darts() {
        let mut m = grid.clone();
        let s = quad_dominant::split_quad(&mut m, d).unwrap();
        assert_eq!(m.check(), Ok(()));
        let [a, b] = s.tips();
        let (kind, e) = quad_dominant::collision(&m, a, b).unwrap();
        assert_eq!(kind, Collision::Opposite);
        let mut merged = m.clone();
        quad_dominant::merge_triangles(&mut merged, e).unwrap();
        assert!(is_isomorphic(&merged, &grid));
        s.undo(&mut m).unwrap();
        assert_eq!(m, grid);
    }
}

/// An undo out of order, or on another map, is refused with the map unchanged.
#[test]
fn stale_records_are_refused() {
    let (mesh, tips) = gen::quad_dominant(10, 10, 1, 2);
    for mv in Move::ALL {
        let mut m = mesh.map.clone();
        let first = quad_dominant::move_triangle(&mut m, tips[0], mv).unwrap();
        let second = quad_dominant::move_triangle(&mut m, first.tip(), mv).unwrap();
        let snapshot = m.clone();
        assert_eq!(first.undo(&mut m), Err(Refusal::StaleRecord), "{mv}");
        assert_eq!(m, snapshot);
        // On the map before the move: refused too.
        let mut fresh = mesh.map.clone();
        assert_eq!(first.undo(&mut fresh), Err(Refusal::StaleRecord), "{mv}");
        assert_eq!(fresh, mesh.map);
        second.undo(&mut m).unwrap();
        first.undo(&mut m).unwrap();
        assert_eq!(m, mesh.map);
    }
}
