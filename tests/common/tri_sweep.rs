//! Sweeps of the semantic triangle edits over every start of a mesh: each attempt's
//! contract is asserted (a refusal equal to the `can_*`'s with the map `==`, or the
//! documented effect and an exact undo) and the outcomes are counted. Shared by
//! `tests/tri_real_meshes.rs`, which asserts the counts are not vacuous, and
//! `examples/tri_real_counts.rs`, which prints them; it uses only `zipmesh` so that the
//! example can include it by path. `tests/tri_edit.rs` uses its effect checks.

use std::collections::BTreeMap;
use zipmesh::invariants::{irregular_valences, MeshKind};
use zipmesh::tri_edit::{
    can_generate_pair, can_generate_quadruple, can_move_pair, generate_pair, generate_quadruple,
    move_pair, Direction, Moved, PairMove, Quadruple, TriEditError, Via,
};
use zipmesh::{Map, Vert};

/// Every `CHECK_EVERY`-th applied edit of a sweep (the first, the 51st, ..) also runs
/// `Map::check`; the other checks run on every attempt.
pub const CHECK_EVERY: usize = 50;

/// The three operations of [`generate_pair`], in the order of `docs/tri-edit.md`.
pub const VIAS: [Via; 3] = [Via::Flip, Via::Collapse, Via::Split];

/// How many attempts applied, and how many refused for each reason (the `TriEditError`
/// as `Debug` prints it, e.g. `Irregular` or `Refused(WrongDegree)`).
#[derive(Clone, Debug, Default)]
pub struct Tally {
    pub applied: usize,
    pub refused: BTreeMap<String, usize>,
}

impl Tally {
    fn refuse(&mut self, e: TriEditError) {
        *self.refused.entry(format!("{e:?}")).or_default() += 1;
    }

    /// Applied and refused together.
    pub fn attempts(&self) -> usize {
        self.applied + self.refused.values().sum::<usize>()
    }
}

/// The outcome of one sweep: how many starting vertices (pairs for the 5-7 movement) and a
/// tally per configuration (direction, `Quadruple`, `Via`).
#[derive(Clone, Debug)]
pub struct Sweep<const N: usize> {
    pub starts: usize,
    pub tallies: [Tally; N],
}

impl<const N: usize> Sweep<N> {
    fn new(starts: usize) -> Self {
        Sweep {
            starts,
            tallies: std::array::from_fn(|_| Tally::default()),
        }
    }

    /// Applied attempts over every configuration.
    pub fn applied(&self) -> usize {
        self.tallies.iter().map(|t| t.applied).sum()
    }

    /// Counts one applied attempt of configuration `k`; true when this one is to be
    /// `check()`ed (every [`CHECK_EVERY`]-th over the sweep, the first included).
    fn apply(&mut self, k: usize) -> bool {
        self.tallies[k].applied += 1;
        (self.applied() - 1) % CHECK_EVERY == 0
    }
}

/// The sorted multiset of (valence, on the boundary) of the irregular vertices of a
/// triangle mesh.
pub fn tri_multiset(map: &Map) -> Vec<(usize, bool)> {
    irregular_valences(map, MeshKind::Triangle)
}

/// `before`'s irregular multiset with `add` added.
pub fn with_added(before: &Map, add: &[(usize, bool)]) -> Vec<(usize, bool)> {
    let mut v = tri_multiset(before);
    v.extend_from_slice(add);
    v.sort();
    v
}

/// The valence of every vertex slot (0 for a dead slot).
pub fn valences(map: &Map) -> Vec<usize> {
    (0..map.vertex_slots() as u32)
        .map(Vert::new)
        .map(|v| {
            if map.is_live_vertex(v) {
                map.valence(v)
            } else {
                0
            }
        })
        .collect()
}

/// Every adjacent (v5, v7) pair of interior vertices.
pub fn adjacent_pairs(map: &Map) -> Vec<(Vert, Vert)> {
    let interior = |v: Vert, k: usize| !map.is_boundary_vertex(v) && map.valence(v) == k;
    map.vertices()
        .filter(|&p| interior(p, 5))
        .flat_map(|p| map.vertex_darts(p).map(move |d| (p, map.dest(d))))
        .filter(|&(_, q)| interior(q, 7))
        .collect()
}

/// The interior vertices of valence `k`.
pub fn interior_of_valence(map: &Map, k: usize) -> Vec<Vert> {
    map.vertices()
        .filter(|&v| !map.is_boundary_vertex(v) && map.valence(v) == k)
        .collect()
}

/// Asserts the documented effect of a 5-7 movement from `before` to `map` (`check()`
/// aside): the new pair an adjacent interior v5 and v7, the irregular multiset unchanged,
/// and every vertex other than the old and new pair (and a split's new, regular vertex)
/// with its old valence.
pub fn assert_pair_moved(before: &Map, map: &Map, m: &PairMove) {
    assert_eq!((map.valence(m.p()), map.valence(m.q())), (5, 7), "{m:?}");
    assert!(!map.is_boundary_vertex(m.p()) && !map.is_boundary_vertex(m.q()));
    assert!(map.dart_between(m.p(), m.q()).is_some());
    assert_eq!(tri_multiset(before), tri_multiset(map));
    let (old, new) = (valences(before), valences(map));
    let (p0, q0) = m.before();
    for (i, (&a, &b)) in old.iter().zip(&new).enumerate() {
        let v = Vert::new(i as u32);
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

/// Every adjacent interior 5-7 pair of `base` in every [`Direction`] (tallied by
/// direction), each on the one working copy: a refusal equal to `can_move_pair`'s with the
/// map `==`, or [`assert_pair_moved`] and an exact undo.
pub fn sweep_pair_moves(name: &str, base: &Map) -> Sweep<6> {
    let pairs = adjacent_pairs(base);
    let mut out = Sweep::new(pairs.len());
    let mut m = base.clone();
    for &(p, q) in &pairs {
        for dir in Direction::ALL {
            let can = can_move_pair(&m, p, q, dir);
            match move_pair(&mut m, p, q, dir) {
                Err(e) => {
                    assert_eq!(can, Err(e), "{name}: {p:?} {q:?} {dir:?}");
                    assert!(m == *base, "{name}: a refusal changed the map");
                    out.tallies[dir.index()].refuse(e);
                }
                Ok(r) => {
                    assert_eq!(can, Ok(()), "{name}: {p:?} {q:?} {dir:?}");
                    assert_pair_moved(base, &m, &r);
                    if out.apply(dir.index()) {
                        m.check().unwrap();
                    }
                    r.undo(&mut m).unwrap();
                    assert!(m == *base, "{name}: undo of {r:?}");
                }
            }
        }
    }
    out
}

/// Every regular interior vertex of `base`, every dart at it and every [`Quadruple`]
/// configuration (tallied by configuration): a refusal equal to `can_generate_quadruple`'s
/// with the map `==`, or the multiset plus exactly {5, 5, 7, 7}, the four vertices named
/// with those valences, and an exact undo.
pub fn sweep_quadruples(name: &str, base: &Map) -> Sweep<3> {
    let regular = interior_of_valence(base, 6);
    let want = with_added(base, &[(5, false), (5, false), (7, false), (7, false)]);
    let mut out = Sweep::new(regular.len());
    let mut m = base.clone();
    for &v in &regular {
        for d in base.vertex_darts(v) {
            for (k, how) in Quadruple::ALL.into_iter().enumerate() {
                let can = can_generate_quadruple(&m, d, how);
                match generate_quadruple(&mut m, d, how) {
                    Err(e) => {
                        assert_eq!(can, Err(e), "{name}: {d:?} {how:?}");
                        assert!(m == *base, "{name}: a refusal changed the map");
                        out.tallies[k].refuse(e);
                    }
                    Ok(g) => {
                        assert_eq!(can, Ok(()), "{name}: {d:?} {how:?}");
                        assert_eq!(tri_multiset(&m), want, "{name}: {d:?} {how:?}");
                        let mut got: Vec<usize> =
                            g.vertices().iter().map(|&x| m.valence(x)).collect();
                        got.sort();
                        assert_eq!(got, [5, 5, 7, 7], "{name}: {d:?} {how:?}");
                        if out.apply(k) {
                            m.check().unwrap();
                        }
                        g.undo(&mut m).unwrap();
                        assert!(m == *base, "{name}: undo of {how:?} at {d:?}");
                    }
                }
            }
        }
    }
    out
}

/// Every interior v5 of `base`, every dart at it, every [`Via`] and both readings
/// ([`Moved`]; tallied by `Via`): a refusal equal to `can_generate_pair`'s with the map
/// `==`, or the moved vertex and the new pair a v5 and an adjacent v5-v7, the multiset plus
/// exactly {5, 7}, and an exact undo.
pub fn sweep_pair_generations(name: &str, base: &Map) -> Sweep<3> {
    let fives = interior_of_valence(base, 5);
    let want = with_added(base, &[(5, false), (7, false)]);
    let mut out = Sweep::new(fives.len());
    let mut m = base.clone();
    for &v in &fives {
        for d in base.vertex_darts(v) {
            for (k, via) in VIAS.into_iter().enumerate() {
                for moved in [Moved::First, Moved::Second] {
                    let can = can_generate_pair(&m, d, via);
                    match generate_pair(&mut m, d, via, moved) {
                        Err(e) => {
                            assert_eq!(can, Err(e), "{name}: {d:?} {via:?}");
                            assert!(m == *base, "{name}: a refusal changed the map");
                            out.tallies[k].refuse(e);
                        }
                        Ok(g) => {
                            assert_eq!(can, Ok(()), "{name}: {d:?} {via:?}");
                            let (p, q) = g.pair().unwrap();
                            let got = (m.valence(g.moved()), m.valence(p), m.valence(q));
                            assert_eq!(got, (5, 5, 7), "{name}: {d:?} {via:?} {moved:?}");
                            assert!(m.dart_between(p, q).is_some() && g.moved() != p);
                            assert_eq!(tri_multiset(&m), want, "{name}: {d:?} {via:?}");
                            if out.apply(k) {
                                m.check().unwrap();
                            }
                            g.undo(&mut m).unwrap();
                            assert!(m == *base, "{name}: undo of {via:?} at {d:?}");
                        }
                    }
                }
            }
        }
    }
    out
}
