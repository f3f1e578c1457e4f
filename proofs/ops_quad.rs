//! The quad operators on every map up to a bound, and every sequence of two operators on
//! every map up to a smaller bound.
//!
//! Every valid map with up to `MAX_EDGES` = 4 edges (8 darts; 103 981 maps, the enumeration of
//! `maps.rs`) gets every operator at every argument: quad collapse, valence-2 removal, doublet
//! insertion, high-valence split and both edge rotations at every dart, and the vertex split at
//! every ordered pair of darts. Each attempt must either
//! * be refused with the same reason `can_*` gives and the map `==` the original, or
//! * be applied with `check()` passing, the documented V/E/F deltas, the documented valence of
//!   every involved vertex, every other valence and every surviving face's degree unchanged,
//!   new faces quads, the inverse operator allowed on the result and giving back the original
//!   canonical code, and `record.undo` giving a map `==` the original.
//!
//! Sequences: every map with up to `SEQ_EDGES` = 3 edges (6 darts; 1 837 maps) gets every
//! operator at every argument, and every result gets every operator at every argument again,
//! each checked as above, then the first record is undone (`==` the original).
//! Collapses past the bound: every map obtained by an applied vertex split of a map with up to
//! 4 edges (so up to 12 darts) gets a quad collapse at every dart, checked as above. Every
//! collapse that applies to a map of up to 12 darts is among them up to isomorphism, since its
//! result has at most 8 darts and the split of that result along the merged edges gives the
//! map back. The tallies are printed with `-- --nocapture`.

use crate::choice::Exhaustive;
use crate::oracle::RawMap;
use std::collections::BTreeMap;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::ops::quad::{self, QuadRecord, Rotation};
use zipmesh::ops::Refusal;
use zipmesh::{Dart, Face, Map, Vert};

/// The exhaustive bound on edges for single operators, and for two-operator sequences.
const MAX_EDGES: usize = 4;
const SEQ_EDGES: usize = 3;

/// One operator with its arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    Collapse(Dart),
    Split(Dart, Dart),
    HighValence(Dart),
    RemoveValence2(Dart),
    InsertDoublet(Dart),
    Rotate(Dart, Rotation),
}

impl Op {
    pub fn name(self) -> &'static str {
        match self {
            Op::Collapse(_) => "collapse",
            Op::Split(..) => "split",
            Op::HighValence(_) => "high-valence split",
            Op::RemoveValence2(_) => "valence-2 removal",
            Op::InsertDoublet(_) => "doublet insertion",
            Op::Rotate(_, Rotation::Clockwise) => "rotation cw",
            Op::Rotate(_, Rotation::CounterClockwise) => "rotation ccw",
        }
    }

    pub fn can(self, m: &Map) -> Result<(), Refusal> {
        match self {
            Op::Collapse(d) => quad::can_quad_collapse(m, d),
            Op::Split(a, b) => quad::can_vertex_split(m, a, b),
            Op::HighValence(d) => quad::can_split_high_valence(m, m.origin(d), d),
            Op::RemoveValence2(d) => quad::can_remove_valence2(m, d),
            Op::InsertDoublet(d) => quad::can_insert_doublet(m, d),
            Op::Rotate(d, r) => quad::can_rotate_edge(m, d, r),
        }
    }

    pub fn apply(self, m: &mut Map) -> Result<QuadRecord, Refusal> {
        Ok(match self {
            Op::Collapse(d) => quad::quad_collapse(m, d)?.into(),
            Op::Split(a, b) => quad::vertex_split(m, a, b)?.into(),
            Op::HighValence(d) => quad::split_high_valence(m, m.origin(d), d)?.into(),
            Op::RemoveValence2(d) => quad::remove_valence2(m, d)?.into(),
            Op::InsertDoublet(d) => quad::insert_doublet(m, d)?.into(),
            Op::Rotate(d, r) => quad::rotate_edge(m, d, r)?.into(),
        })
    }
}

/// Every operator at every argument on a map whose darts are `0..n`.
pub fn all_ops(m: &Map) -> Vec<Op> {
    let darts: Vec<Dart> = m.darts().collect();
    let mut ops = Vec::new();
    for &d in &darts {
        ops.push(Op::Collapse(d));
        ops.push(Op::HighValence(d));
        ops.push(Op::RemoveValence2(d));
        ops.push(Op::InsertDoublet(d));
        ops.push(Op::Rotate(d, Rotation::Clockwise));
        ops.push(Op::Rotate(d, Rotation::CounterClockwise));
        for &e in &darts {
            ops.push(Op::Split(d, e));
        }
    }
    ops
}

/// What the documentation promises for an applied operator, computed from the map before.
struct Expect {
    dv: i64,
    de: i64,
    df: i64,
    /// Valence changes of surviving vertices (summed if a vertex is listed twice).
    deltas: Vec<(Vert, i64)>,
    /// The deleted vertex, and the new vertex's valence.
    removed: Option<Vert>,
    created: Option<usize>,
    /// The vertex whose handle must be the origin of a given dart after (kept copies).
    origins: Vec<(Dart, Vert)>,
}

fn steps_cw(m: &Map, from: Dart, to: Dart) -> usize {
    let mut x = from;
    let mut k = 0;
    while x != to {
        x = m.rotate_cw(x);
        k += 1;
        assert!(k <= m.num_darts());
    }
    k
}

fn expect(m: &Map, op: Op) -> Expect {
    let o = |d: Dart| m.origin(d);
    let n = |d: Dart| m.next(d);
    let val = |v: Vert| m.valence(v) as i64;
    match op {
        Op::Collapse(d) => {
            let (a, b, c, e) = (o(d), o(n(d)), o(n(n(d))), o(n(n(n(d)))));
            Expect {
                dv: -1,
                de: -2,
                df: -1,
                deltas: vec![(a, val(c) - 2), (b, -1), (e, -1)],
                removed: Some(c),
                created: None,
                origins: vec![(d, a), (n(n(d)), a)],
            }
        }
        Op::Split(s1, _) | Op::HighValence(s1) => {
            let s2 = match op {
                Op::Split(_, s2) => s2,
                _ => {
                    let k = m.valence(o(s1));
                    let mut x = s1;
                    for _ in 0..k / 2 {
                        x = m.rotate_cw(x);
                    }
                    x
                }
            };
            let w = o(s1);
            let arc1 = steps_cw(m, s1, s2) as i64 - 1;
            let arc2 = val(w) - arc1 - 2;
            Expect {
                dv: 1,
                de: 2,
                df: 1,
                deltas: vec![(w, arc1 + 2 - val(w)), (m.dest(s1), 1), (m.dest(s2), 1)],
                removed: None,
                created: Some((arc2 + 2) as usize),
                origins: vec![(s1, w)],
            }
        }
        Op::RemoveValence2(x) => {
            let y = m.rotate_cw(x);
            Expect {
                dv: -1,
                de: -2,
                df: -1,
                deltas: vec![(m.dest(x), -1), (m.dest(y), -1)],
                removed: Some(o(x)),
                created: None,
                origins: vec![],
            }
        }
        Op::InsertDoublet(d) => Expect {
            dv: 1,
            de: 2,
            df: 1,
            deltas: vec![(o(d), 1), (o(n(n(d))), 1)],
            removed: None,
            created: Some(2),
            origins: vec![(d, o(d))],
        },
        Op::Rotate(h, r) => {
            let t = h.twin();
            // Counter-clockwise h becomes z→x, clockwise y→w (hexagon v x y u z w).
            let (from, to) = match r {
                Rotation::CounterClockwise => (o(n(n(t))), o(n(n(h)))),
                Rotation::Clockwise => (o(n(n(n(h)))), o(n(n(n(t))))),
            };
            Expect {
                dv: 0,
                de: 0,
                df: 0,
                deltas: vec![(o(h), -1), (o(t), -1), (from, 1), (to, 1)],
                removed: None,
                created: None,
                origins: vec![(h, from), (t, to)],
            }
        }
    }
}

/// Checks the documented deltas of an applied operator.
fn check_deltas(before: &Map, after: &Map, op: Op, e: &Expect) {
    let c = |m: &Map| {
        (
            m.num_vertices() as i64,
            m.num_edges() as i64,
            m.num_faces() as i64,
        )
    };
    let (b, a) = (c(before), c(after));
    assert_eq!(
        (a.0 - b.0, a.1 - b.1, a.2 - b.2),
        (e.dv, e.de, e.df),
        "{op:?}"
    );
    let mut want: BTreeMap<Vert, i64> = BTreeMap::new();
    for &(v, d) in &e.deltas {
        *want.entry(v).or_default() += d;
    }
    let mut created = Vec::new();
    for i in 0..after.vertex_slots().max(before.vertex_slots()) {
        let v = Vert::new(i as u32);
        match (before.is_live_vertex(v), after.is_live_vertex(v)) {
            (true, true) => assert_eq!(
                after.valence(v) as i64,
                before.valence(v) as i64 + want.get(&v).copied().unwrap_or(0),
                "{op:?}: valence of {v:?}"
            ),
            (true, false) => assert_eq!(Some(v), e.removed, "{op:?}: {v:?} deleted"),
            (false, true) => created.push(v),
            (false, false) => {}
        }
    }
    match e.created {
        Some(k) => {
            assert_eq!(created.len(), 1, "{op:?}");
            assert_eq!(after.valence(created[0]), k, "{op:?}: new vertex");
        }
        None => assert!(created.is_empty(), "{op:?}"),
    }
    // Surviving faces keep their degree; new faces are quads.
    for i in 0..after.face_slots() {
        let f = Face::new(i as u32);
        if after.is_live_face(f) {
            let want = if before.is_live_face(f) {
                before.degree(f)
            } else {
                4
            };
            assert_eq!(after.degree(f), want, "{op:?}: degree of {f:?}");
        }
    }
    // Untouched handles stay valid: darts die or appear in whole deleted or new edges.
    let died = before.darts().filter(|&d| !after.is_live_dart(d)).count();
    let born = after.darts().filter(|&d| !before.is_live_dart(d)).count();
    assert_eq!(
        (born as i64 - died as i64, born.min(died)),
        (2 * e.de, 0),
        "{op:?}"
    );
    for &(d, v) in &e.origins {
        assert_eq!(after.origin(d), v, "{op:?}: origin of {d:?}");
    }
}

/// The inverse operator, as an ordinary operator on the result, is allowed and gives back
/// the original up to isomorphism.
fn inverse_op(before: &Map, after: &Map, op: Op, rec: &QuadRecord) -> Op {
    let n = |d: Dart| before.next(d);
    match (op, rec) {
        (Op::Collapse(d), _) => Op::Split(d, n(n(d))),
        (Op::Split(s1, _) | Op::HighValence(s1), _) => Op::Collapse(s1),
        (Op::RemoveValence2(x), _) => Op::InsertDoublet(n(x)),
        (Op::InsertDoublet(d), QuadRecord::InsertDoublet(r)) => {
            let x = r.darts()[0];
            assert_eq!(after.next(x), d);
            Op::RemoveValence2(x)
        }
        (Op::Rotate(h, r), _) => Op::Rotate(h, r.reverse()),
        _ => unreachable!(),
    }
}

#[derive(Default)]
pub struct Tally {
    /// Per operator: applied count and refusals by reason.
    per_op: BTreeMap<&'static str, (u64, BTreeMap<String, u64>)>,
    maps: u64,
}

impl Tally {
    fn add(&mut self, op: Op, r: &Result<(), Refusal>) {
        let e = self.per_op.entry(op.name()).or_default();
        match r {
            Ok(()) => e.0 += 1,
            Err(x) => *e.1.entry(format!("{x:?}")).or_default() += 1,
        }
    }

    fn print(&self, title: &str) {
        eprintln!("{title}: {} maps", self.maps);
        for (name, (ok, refused)) in &self.per_op {
            let total: u64 = ok + refused.values().sum::<u64>();
            eprintln!("  {name}: {total} attempts, {ok} applied, refused {refused:?}");
        }
    }
}

/// Runs one operator on `m` and checks the whole contract; returns the result and its record
/// if it applied. `inverse` also runs the inverse operator (costs a canonical code).
pub fn try_op(m: &Map, op: Op, tally: &mut Tally, inverse: bool) -> Option<(Map, QuadRecord)> {
    let can = op.can(m);
    let mut after = m.clone();
    let res = op.apply(&mut after);
    tally.add(op, &res.as_ref().map(|_| ()).map_err(|e| *e));
    match res {
        Err(r) => {
            assert_eq!(Err(r), can, "{op:?}: apply and can_ disagree on {m:?}");
            assert_eq!(after, *m, "{op:?} refused ({r:?}) but changed the map");
            None
        }
        Ok(rec) => {
            assert_eq!(can, Ok(()), "{op:?}: applied but can_ said no on {m:?}");
            if let Err(v) = after.check() {
                panic!("{op:?} on {m:?} gave an invalid map: {v:?}\n{after:?}");
            }
            check_deltas(m, &after, op, &expect(m, op));
            if inverse {
                let inv = inverse_op(m, &after, op, &rec);
                let mut back = after.clone();
                match inv.apply(&mut back) {
                    Ok(_) => {}
                    Err(r) => panic!("{op:?} on {m:?}: inverse {inv:?} refused: {r:?}"),
                }
                assert_eq!(back.check(), Ok(()));
                assert_eq!(
                    CanonicalCode::of(&back),
                    CanonicalCode::of(m),
                    "{op:?} then {inv:?} on {m:?}"
                );
            }
            let mut undone = after.clone();
            rec.clone()
                .undo(&mut undone)
                .expect("undo of a fresh record");
            assert_eq!(undone, *m, "{op:?}: undo did not restore {m:?}");
            Some((after, rec))
        }
    }
}

/// Every valid map with up to `max_edges` edges, handed to `body`.
fn every_map(max_edges: usize, mut body: impl FnMut(&Map)) -> u64 {
    let mut maps = 0;
    Exhaustive::run(
        |c| {
            let n = crate::choice::Choice::any(c, max_edges + 1);
            RawMap::any(c, n)
        },
        |raw| {
            if let Ok(m) = Map::from_permutation(&raw.next, &raw.boundary) {
                maps += 1;
                body(&m);
            }
        },
    );
    maps
}

/// Every operator at every argument on `m`, and, `depth - 1` more times, on each result.
fn explore(m: &Map, depth: usize, tallies: &mut [Tally], inverse: bool) {
    let (here, below) = tallies.split_first_mut().expect("one tally per level");
    for op in all_ops(m) {
        if let Some((m1, _)) = try_op(m, op, here, inverse) {
            if depth > 1 {
                below[0].maps += 1;
                explore(&m1, depth - 1, below, inverse);
            }
        }
    }
}

/// Every operator whose argument is one dart (all but the vertex split).
fn single_dart_ops(m: &Map) -> impl Iterator<Item = Op> + '_ {
    m.darts().flat_map(|d| {
        [
            Op::Collapse(d),
            Op::HighValence(d),
            Op::RemoveValence2(d),
            Op::InsertDoublet(d),
            Op::Rotate(d, Rotation::Clockwise),
            Op::Rotate(d, Rotation::CounterClockwise),
        ]
    })
}

#[test]
fn every_quad_operator_on_every_map_up_to_the_bound() {
    let mut t = Tally::default();
    let mut past = Tally::default();
    t.maps = every_map(MAX_EDGES, |m| {
        for op in all_ops(m) {
            let applied = try_op(m, op, &mut t, true);
            // Past the bound: every growing operator's result (up to 12 darts) gets every
            // single-dart operator.
            if let (Op::Split(..) | Op::InsertDoublet(_), Some((big, _))) = (op, applied) {
                past.maps += 1;
                for op2 in single_dart_ops(&big) {
                    try_op(&big, op2, &mut past, true);
                }
            }
        }
    });
    t.print(&format!("single operators, maps up to {MAX_EDGES} edges"));
    past.print("single-dart operators on every split or insertion result (up to 6 edges)");
    assert_eq!(t.maps, 103_981);
    for name in ["split", "doublet insertion"] {
        assert!(t.per_op[name].0 > 0, "{name} never applied");
    }
    for name in ["collapse", "valence-2 removal", "doublet insertion"] {
        assert!(
            past.per_op[name].0 > 0,
            "{name} never applied past the bound"
        );
    }
}

#[test]
fn every_sequence_of_up_to_three_operators() {
    let mut t: Vec<Tally> = (0..3).map(|_| Tally::default()).collect();
    t[0].maps = every_map(SEQ_EDGES, |m| explore(m, 3, &mut t, true));
    for (i, x) in t.iter().enumerate() {
        x.print(&format!(
            "sequences from maps up to {SEQ_EDGES} edges, operator {}",
            i + 1
        ));
    }
    assert_eq!(t[0].maps, 1 + 4 + 56 + 1776);
    for name in [
        "collapse",
        "split",
        "valence-2 removal",
        "doublet insertion",
    ] {
        assert!(t[2].per_op[name].0 > 0, "{name} never applied third");
    }
}

/// Every sequence of two operators from small quad meshes: the smallest maps on which an
/// edge rotation applies have 14 darts (two quads with six distinct corners), past the
/// enumeration, so rotations are checked exhaustively around these seeds.
#[test]
fn every_sequence_of_two_operators_from_small_quad_meshes() {
    let seeds = [
        ("grid 2x1", zipmesh::gen::grid(2, 1).map),
        ("grid 2x2", zipmesh::gen::grid(2, 2).map),
        ("cube 1", zipmesh::gen::cube(1).map),
        ("torus 3x3", zipmesh::gen::torus_grid(3, 3).map),
    ];
    let mut all: Vec<Tally> = (0..2).map(|_| Tally::default()).collect();
    for (name, m) in &seeds {
        let mut t: Vec<Tally> = (0..2).map(|_| Tally::default()).collect();
        t[0].maps = 1;
        explore(m, 2, &mut t, true);
        for (i, x) in t.iter().enumerate() {
            x.print(&format!(
                "two-operator sequences from {name}, operator {}",
                i + 1
            ));
        }
        for (a, x) in all.iter_mut().zip(t) {
            a.maps += x.maps;
            for (k, (ok, refused)) in x.per_op {
                let e = a.per_op.entry(k).or_default();
                e.0 += ok;
                for (r, n) in refused {
                    *e.1.entry(r).or_default() += n;
                }
            }
        }
    }
    for (name, _) in all[0].per_op.iter() {
        let applied = all[0].per_op[name].0 + all[1].per_op[name].0;
        assert!(applied > 0, "{name} never applied around the seeds");
    }
}
