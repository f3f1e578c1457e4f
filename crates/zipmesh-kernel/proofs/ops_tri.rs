//! The triangle operators (flip, collapse, vertex split, edge split) on every small map.
//!
//! The oracle is `tests/ops_tri/check.rs`: each operator, called with any argument, is either
//! refused with the same reason as its `can_*` and the map left equal (`==`) to before, or
//! applied with `check()` passing, V, E, F, every vertex's valence (as `TriOp::effect` states
//! them) and the liveness of every old element exactly as documented, and its record's `undo` giving back an equal map; the
//! public inverse (flip again, collapse of a split, split of a collapse) gives back an
//! isomorphic map, and is accepted wherever the documentation promises it.
//!
//! Enumerations (bounds and counts are asserted or printed with `-- --nocapture`):
//! * **All maps** up to 4 edges (8 darts), as in `maps.rs`: 368 047 candidates, 103 981
//!   valid maps; each operator at every dart, the vertex split at every ordered pair of darts
//!   (plus a dead handle), so every operator meets loops, multi-edges, faces of degree 1 and
//!   2, and non-orientable-looking gluings of small genus.
//! * **All triangle gluings** of up to 4 triangles: face `i` has half-edges `3i..3i+3`, and
//!   any partial matching of the half-edges glues them (the rest are boundary). That is
//!   T(3) + T(6) + T(9) + T(12) = 4 + 76 + 2 620 + 140 152 labelled gluings (T the telephone
//!   numbers: partial matchings), every one a valid map (asserted), reduced to isomorphism
//!   classes by canonical code. These hold the tetrahedron, the two-triangle sphere, disks,
//!   strips and tori, where flips and interior collapses apply. Each operator at every dart
//!   and dart pair of every class.
//! * **Sequences**: every pair of operators (the second at every argument on the result of
//!   every applied first) on all maps up to 3 edges and on the gluing classes of up to 3
//!   triangles; every triple on the gluing classes of up to 2 triangles. After each step the
//!   step is checked as above; undoing the steps in reverse order gives back the original
//!   arrays; and undoing the first step while the second is applied never panics (it
//!   refuses, or gives a valid map).
//! * Random sequences of 12 operators on random gluings of 5 to 8 triangles, past the bound.

#[path = "../tests/ops_tri/check.rs"]
mod check;

use crate::choice::{Choice, Exhaustive, Random};
use crate::oracle::RawMap;
use check::{checked, Op};
use std::collections::{BTreeMap, HashSet};
use std::sync::OnceLock;
use zipmesh_kernel::invariants::canonical::CanonicalCode;
use zipmesh_kernel::ops::Refusal;
use zipmesh_kernel::rng::Rng;
use zipmesh_kernel::{Dart, Map};

/// Every operator call on `map`: each operator at every dart, the vertex split at every
/// ordered pair of darts, and each with a dead handle.
fn all_ops(map: &Map) -> Vec<Op> {
    let darts: Vec<Dart> = map.darts().collect();
    let dead = Dart::new(map.dart_slots() as u32);
    let mut ops = vec![
        Op::Flip(dead),
        Op::Collapse(dead),
        Op::SplitEdge(dead),
        Op::SplitVertex(dead, dead),
    ];
    for &d in &darts {
        ops.extend([Op::Flip(d), Op::Collapse(d), Op::SplitEdge(d)]);
        ops.extend(darts.iter().map(|&e| Op::SplitVertex(d, e)));
    }
    ops
}

fn kind(op: Op) -> &'static str {
    match op {
        Op::Flip(_) => "flip",
        Op::Collapse(_) => "collapse",
        Op::SplitVertex(..) => "split_vertex",
        Op::SplitEdge(_) => "split_edge",
    }
}

/// Outcomes per operator: how often applied and how often refused with each reason.
#[derive(Default)]
struct Tally(BTreeMap<&'static str, BTreeMap<String, u64>>);

impl Tally {
    fn add(&mut self, op: Op, r: Option<Refusal>) {
        let key = r.map_or("applied".to_string(), |e| format!("{e:?}"));
        *self.0.entry(kind(op)).or_default().entry(key).or_default() += 1;
    }
    fn get(&self, k: &str, r: &str) -> u64 {
        self.0.get(k).and_then(|m| m.get(r)).copied().unwrap_or(0)
    }
    fn print(&self, what: &str) {
        for (k, m) in &self.0 {
            eprintln!("{what}: {k}: {m:?}");
        }
    }
}

/// Every single operator call on `map`, each checked with its undo and inverse.
fn every_op(map: &Map, tally: &mut Tally) {
    for op in all_ops(map) {
        tally.add(op, check::checked_roundtrip(map, op));
    }
}

/// Every sequence of `depth` operators from `map`, each step checked; the steps undone in
/// reverse order give back `map`. Returns the number of applied sequences.
fn sequences(map: &Map, depth: usize) -> u64 {
    if depth == 0 {
        return 1;
    }
    let mut n = 0;
    for op in all_ops(map) {
        let mut m = map.clone();
        let Ok(rec) = checked(&mut m, op) else {
            continue;
        };
        if depth > 1 {
            n += sequences_after(&m, depth - 1, &rec);
        } else {
            n += 1;
        }
        rec.undo(&mut m)
            .unwrap_or_else(|e| panic!("{op:?}: undo refused: {e:?}"));
        assert!(m == *map, "{op:?}: undo after the sequence");
    }
    n
}

/// The sequences of `depth` more operators from `map`, which `first` produced; also undoes
/// `first` out of order on each result, which must refuse or give a valid map.
fn sequences_after(map: &Map, depth: usize, first: &check::Rec) -> u64 {
    let mut n = 0;
    for op in all_ops(map) {
        let mut m = map.clone();
        let Ok(rec) = checked(&mut m, op) else {
            continue;
        };
        let mut stale = m.clone();
        if first.undo(&mut stale).is_ok() {
            assert_eq!(
                stale.check(),
                Ok(()),
                "out-of-order undo of {first:?} after {op:?} on {map:?}"
            );
        } else {
            assert!(stale == m, "a refused undo changed the map");
        }
        n += if depth > 1 {
            sequences_after(&m, depth - 1, &rec)
        } else {
            1
        };
        rec.undo(&mut m)
            .unwrap_or_else(|e| panic!("{op:?}: undo refused: {e:?}"));
        assert!(m == *map, "{op:?}: undo in a sequence");
    }
    n
}

/// Any map on up to `max_edges` edges (as in `maps.rs`), or `None` if the candidate is not
/// a valid map.
fn any_map(c: &mut impl Choice, max_edges: usize) -> Option<Map> {
    let n = c.any(max_edges + 1);
    let raw = RawMap::any(c, n);
    Map::from_permutation(&raw.next, &raw.boundary).ok()
}

const NOT_GLUED: usize = usize::MAX;

/// Any gluing of `f` triangles (see the module header): half-edge `x` of face `x / 3` is
/// glued to a later free half-edge or left on the boundary.
fn gluing(c: &mut impl Choice, f: usize) -> Map {
    let n = 3 * f;
    let boundary_mark = n;
    let mut partner = vec![NOT_GLUED; n];
    for x in 0..n {
        if partner[x] != NOT_GLUED {
            continue;
        }
        let free: Vec<usize> = (x + 1..n).filter(|&y| partner[y] == NOT_GLUED).collect();
        let k = c.any(free.len() + 1);
        if k == free.len() {
            partner[x] = boundary_mark;
        } else {
            partner[x] = free[k];
            partner[free[k]] = x;
        }
    }
    // Darts: each glued pair is one edge, each boundary half-edge an edge with a boundary twin.
    let mut dart = vec![0u32; n];
    let mut bdart = vec![u32::MAX; n];
    let mut nd = 0u32;
    for x in 0..n {
        if partner[x] == boundary_mark {
            dart[x] = nd;
            bdart[x] = nd + 1;
            nd += 2;
        } else if partner[x] > x {
            dart[x] = nd;
            dart[partner[x]] = nd + 1;
            nd += 2;
        }
    }
    let fnext = |x: usize| 3 * (x / 3) + (x % 3 + 1) % 3;
    let fprev = |x: usize| 3 * (x / 3) + (x % 3 + 2) % 3;
    let mut next = vec![u32::MAX; nd as usize];
    let mut boundary = vec![false; nd as usize];
    for x in 0..n {
        next[dart[x] as usize] = dart[fnext(x)];
        if partner[x] == boundary_mark {
            // The boundary twin of x ends at P = origin(x); its successor is the boundary
            // dart leaving P at the other end of x's fan of triangles.
            let b = bdart[x] as usize;
            boundary[b] = true;
            let mut z = x;
            for _ in 0..=n {
                let w = fprev(z);
                if partner[w] == boundary_mark {
                    next[b] = bdart[w];
                    break;
                }
                z = partner[w];
            }
        }
    }
    Map::from_permutation(&next, &boundary)
        .unwrap_or_else(|e| panic!("gluing {partner:?} is not a valid map: {e:?}"))
}

/// For `f` = 1..=4: the class representatives of gluings of `f` triangles and the number of
/// labelled gluings, enumerated once and shared by the tests.
fn classes(f: usize) -> &'static (Vec<Map>, u64) {
    static CLASSES: OnceLock<Vec<(Vec<Map>, u64)>> = OnceLock::new();
    &CLASSES.get_or_init(|| (1..=4).map(gluing_classes).collect())[f - 1]
}

/// One representative map per isomorphism class of gluings of exactly `f` triangles, and the
/// number of labelled gluings.
fn gluing_classes(f: usize) -> (Vec<Map>, u64) {
    let mut seen = HashSet::new();
    let mut reps = Vec::new();
    let labelled = Exhaustive::run(
        |c| gluing(c, f),
        |m| {
            assert_eq!(m.check(), Ok(()));
            assert_eq!(m.num_faces(), f);
            assert!(m.faces().all(|x| m.degree(x) == 3));
            if seen.insert(CanonicalCode::of(&m)) {
                reps.push(m);
            }
        },
    );
    (reps, labelled)
}

/// Telephone numbers: partial matchings of `n` things.
fn telephone(n: usize) -> u64 {
    let (mut a, mut b) = (1u64, 1u64); // T(0), T(1)
    for k in 2..=n {
        (a, b) = (b, b + (k as u64 - 1) * a);
    }
    if n == 0 {
        a
    } else {
        b
    }
}

#[test]
fn every_operator_on_every_map_up_to_8_darts() {
    let mut tally = Tally::default();
    let mut valid = 0u64;
    let candidates = Exhaustive::run(
        |c| any_map(c, 4),
        |m| {
            if let Some(m) = m {
                valid += 1;
                every_op(&m, &mut tally);
            }
        },
    );
    // The same enumeration as maps.rs: (2n + 1)! candidates for n = 0..=4 edges, of which
    // the valid ones are the 103 981 that maps.rs counts against published numbers.
    assert_eq!(candidates, 1 + 6 + 120 + 5040 + 362_880);
    assert_eq!(valid, 103_981);
    tally.print("maps <= 8 darts");
    // Every reason a small map can give is reached (flips need two triangles: 5 edges).
    for (k, r) in [
        ("collapse", "applied"),
        ("collapse", "DegenerateTriangle"),
        ("collapse", "LinkCondition"),
        ("collapse", "ValenceTooLow"),
        ("split_vertex", "applied"),
        ("split_vertex", "BadArguments"),
        ("split_vertex", "LinkCondition"),
        ("split_vertex", "MultiEdge"),
        ("split_edge", "applied"),
        ("split_edge", "MultiEdge"),
        ("flip", "Loop"),
        ("flip", "Boundary"),
    ] {
        assert!(tally.get(k, r) > 0, "{k}: {r} never reached");
    }
}

#[test]
fn every_operator_on_every_gluing_of_up_to_4_triangles() {
    let mut tally = Tally::default();
    let mut n_classes = 0;
    let mut tetrahedra = 0;
    let tet = CanonicalCode::of(
        &Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]).unwrap(),
    );
    for f in 1..=4 {
        let (reps, labelled) = classes(f);
        assert_eq!(*labelled, telephone(3 * f), "gluings of {f} triangles");
        eprintln!("{f} triangles: {labelled} gluings, {} classes", reps.len());
        n_classes += reps.len();
        for m in reps {
            if CanonicalCode::of(m) == tet {
                tetrahedra += 1;
                // The known failure elsewhere: no collapse of a tetrahedron is allowed.
                for d in m.darts() {
                    assert_eq!(
                        zipmesh_kernel::ops::tri::can_collapse_edge(m, d),
                        Err(Refusal::LinkCondition)
                    );
                }
            }
            every_op(m, &mut tally);
        }
    }
    assert_eq!(
        tetrahedra, 1,
        "the tetrahedron is one of the gluing classes"
    );
    eprintln!("{n_classes} classes of gluings of 1 to 4 triangles");
    tally.print("gluings <= 4 triangles");
    for (k, r) in [
        ("flip", "applied"),
        ("flip", "MultiEdge"),
        ("flip", "Loop"),
        ("collapse", "applied"),
        ("collapse", "Boundary"),
        ("collapse", "LinkCondition"),
        ("collapse", "ValenceTooLow"),
        ("split_vertex", "applied"),
        ("split_edge", "applied"),
        ("split_edge", "MultiEdge"),
    ] {
        assert!(tally.get(k, r) > 0, "{k}: {r} never reached");
    }
}

#[test]
fn every_pair_of_operators_on_maps_up_to_6_darts() {
    let mut applied = 0;
    let candidates = Exhaustive::run(
        |c| any_map(c, 3),
        |m| {
            if let Some(m) = m {
                applied += sequences(&m, 2);
            }
        },
    );
    assert_eq!(candidates, 1 + 6 + 120 + 5040);
    eprintln!("maps <= 6 darts: {applied} applied sequences of two operators");
    assert!(applied > 0);
}

#[test]
fn every_pair_and_triple_of_operators_on_small_gluings() {
    let mut pairs = 0;
    let mut triples = 0;
    let mut n_classes = 0;
    for f in 1..=4 {
        let (reps, _) = classes(f);
        n_classes += reps.len();
        for m in reps {
            pairs += sequences(m, 2);
            if f <= 2 {
                triples += sequences(m, 3);
            }
        }
    }
    eprintln!(
        "gluing classes of <= 4 triangles ({n_classes}): {pairs} applied pairs; \
         of <= 2 triangles: {triples} applied triples"
    );
    assert!(pairs > 0 && triples > 0);
}

/// Random operator sequences on random gluings of 5 to 8 triangles (past the bound).
#[test]
fn random_sequences_on_larger_gluings() {
    let mut c = Random(Rng::new(31));
    let mut applied = 0;
    for _ in 0..400 {
        let f = 5 + c.any(4);
        let original = gluing(&mut c, f);
        let mut map = original.clone();
        let mut recs = Vec::new();
        for _ in 0..12 {
            let op = random_op(&mut c, &map);
            if let Ok(rec) = checked(&mut map, op) {
                applied += 1;
                recs.push(rec);
            }
        }
        for rec in recs.iter().rev() {
            rec.undo(&mut map).expect("undo in reverse order");
        }
        assert!(map == original);
    }
    eprintln!("random sequences: {applied} applied operators");
    assert!(applied > 200);
}

/// One operator of a random kind at random darts (a dead one now and then).
fn random_op(c: &mut impl Choice, map: &Map) -> Op {
    let slots = map.dart_slots() + 1;
    let dart = |c: &mut dyn FnMut(usize) -> usize| Dart::new(c(slots) as u32);
    let mut any = |n: usize| c.any(n);
    match any(4) {
        0 => Op::Flip(dart(&mut any)),
        1 => Op::Collapse(dart(&mut any)),
        2 => Op::SplitEdge(dart(&mut any)),
        _ => {
            let d1 = dart(&mut any);
            // Mostly two darts of one vertex, so that splits apply often.
            let d2 = if map.is_live_dart(d1) && any(4) > 0 {
                let mut d = d1;
                for _ in 0..1 + any(map.valence(map.origin(d1))) {
                    d = map.rotate_cw(d);
                }
                d
            } else {
                dart(&mut any)
            };
            Op::SplitVertex(d1, d2)
        }
    }
}

#[test]
fn telephone_numbers() {
    // T(n) = T(n-1) + (n-1) T(n-2): 1, 1, 2, 4, 10, 26, 76, ... (OEIS A000085).
    let t: Vec<u64> = (0..=7).map(telephone).collect();
    assert_eq!(t, [1, 1, 2, 4, 10, 26, 76, 232]);
    assert_eq!(telephone(9), 2620);
    assert_eq!(telephone(12), 140_152);
}
