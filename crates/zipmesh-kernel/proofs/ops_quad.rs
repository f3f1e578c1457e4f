//! The quad operators on every map up to a bound, and on every sequence of operators from
//! smaller maps and from small quad meshes.
//!
//! Every attempt of an operator on a map is checked the same way (`try_op`): its `can_*`
//! answer must equal `oracle`, an independent restatement of the documented rules in their
//! documented order; then it is either refused with that reason and the map `==` the
//! original, or applied with `check()` passing and its documented effect
//! (`QuadOp::effect`: the V/E/F deltas, the valence of every involved vertex, every other
//! valence and every surviving face's degree unchanged, new faces quads), as many loops and parallel edges as before, and `undo`
//! giving a map `==` the original; in the first two families below the inverse operator,
//! applied as an ordinary operator, must also be allowed and give back the canonical code.
//!
//! Families (counts asserted or printed with `-- --nocapture`):
//! 1. Every valid map with up to `MAX_EDGES` = 4 edges (8 darts; 103 981 maps, the
//!    enumeration of `maps.rs`), every operator at every dart and the vertex split at every
//!    ordered pair of darts: 11.6 M attempts, 19 728 applied. Only splits and doublet
//!    insertions apply at this size (a collapse needs 12 darts, an edge rotation 14).
//! 2. Every map an applied split or insertion of family 1 produces (19 728 maps of up to 12
//!    darts), every operator at every argument again: 4.25 M attempts, 368 736 applied
//!    (44 832 collapses, 6 912 valence-2 removals). Every collapse and
//!    every valence-2 removal that applies to any map of up to 12 darts is here up to
//!    isomorphism: its result has at most 8 darts, and the inverse split or insertion of
//!    that result (allowed, by the inverse check) gives the map back.
//! 3. Every sequence of up to three operators from every map with up to `SEQ_EDGES` = 3
//!    edges (1 837 maps; 3 168 maps reached after two operators): 0.98 M attempts, 123 696
//!    applied.
//! 4. Every sequence of two operators from four small quad meshes (2 x 1 and 2 x 2 grids, the
//!    cube, the 3 x 3 torus): the exhaustive check of applied edge rotations and high-valence
//!    splits, which need maps past the enumeration: 0.62 M attempts, 94 080 applied
//!    (23 420 edge rotations, 216 high-valence splits).

use crate::choice::Exhaustive;
use crate::oracle::RawMap;
use std::collections::BTreeMap;
use zipmesh_kernel::invariants::canonical::CanonicalCode;
use zipmesh_kernel::ops::quad::{QuadRecord, Rotation};
use zipmesh_kernel::ops::Refusal;
use zipmesh_kernel::{Dart, Map, Vert};

/// The exhaustive bound on edges for single operators, and for two-operator sequences.
const MAX_EDGES: usize = 4;
const SEQ_EDGES: usize = 3;

/// One operator with its arguments (the library's own value type).
pub use zipmesh_kernel::ops::quad::QuadOp as Op;

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

/// The documented refusal rules, restated independently: whole rotations from
/// `vertex_darts`, degrees from `face_cycle`, distinctness by sorting. Each operator's checks
/// in its documented order.
fn oracle(m: &Map, op: Op) -> Result<(), Refusal> {
    use Refusal::*;
    let o = |d: Dart| m.origin(d);
    let n = |d: Dart| m.next(d);
    let quad = |d: Dart| -> Result<[Dart; 4], Refusal> {
        if m.face(d).is_none() {
            Err(Boundary)
        } else if m.face_cycle(d).count() != 4 {
            Err(WrongDegree)
        } else {
            Ok([d, n(d), n(n(d)), n(n(n(d)))])
        }
    };
    let distinct = |vs: &[Vert]| {
        let mut s = vs.to_vec();
        s.sort();
        s.dedup();
        s.len() == vs.len()
    };
    let simple = |list: &[Vert], forbidden: &[Vert]| {
        if list.iter().any(|v| forbidden.contains(v)) {
            Err(Loop)
        } else if !distinct(list) {
            Err(MultiEdge)
        } else {
            Ok(())
        }
    };
    let split = |s1: Dart, s2: Dart| {
        if !m.is_live_dart(s1) || !m.is_live_dart(s2) {
            return Err(DeadHandle);
        }
        if s1 == s2 || o(s1) != o(s2) {
            return Err(BadArguments);
        }
        let w = o(s1);
        let dests: Vec<Vert> = m.vertex_darts(w).map(|x| m.dest(x)).collect();
        simple(&dests, &[w])?;
        if m.valence(m.dest(s1)) < 2 || m.valence(m.dest(s2)) < 2 {
            return Err(ValenceTooLow);
        }
        Ok(())
    };
    if let Op::Split(s1, s2) = op {
        return split(s1, s2);
    }
    let d = match op {
        Op::Collapse(d)
        | Op::HighValence(d)
        | Op::RemoveValence2(d)
        | Op::InsertDoublet(d)
        | Op::Rotate(d, _) => d,
        Op::Split(..) => unreachable!(),
    };
    if !m.is_live_dart(d) {
        return Err(DeadHandle);
    }
    match op {
        Op::Collapse(d) => {
            let h = quad(d)?;
            let [a, b, c, e] = h.map(o);
            if a == c {
                return Err(CornersCoincide);
            }
            let quad_darts = [h[0], h[3].twin(), h[2], h[1].twin()];
            let mut dests = vec![b, e];
            dests.extend(
                m.vertex_darts(a)
                    .chain(m.vertex_darts(c))
                    .filter(|x| !quad_darts.contains(x))
                    .map(|x| m.dest(x)),
            );
            simple(&dests, &[a, c])?;
            if m.is_boundary_vertex(a) && m.is_boundary_vertex(c) {
                return Err(BoundaryPinch);
            }
            if m.valence(b) <= 2 || m.valence(e) <= 2 {
                return Err(ValenceTooLow);
            }
            Ok(())
        }
        Op::HighValence(d) => {
            let k = m.valence(o(d));
            if k < 6 {
                return Err(WrongValence);
            }
            let s2 = (0..k / 2).fold(d, |x, _| m.rotate_cw(x));
            split(d, s2)
        }
        Op::RemoveValence2(x) => {
            let v = o(x);
            if m.is_boundary_vertex(v) {
                return Err(Boundary);
            }
            if m.valence(v) != 2 {
                return Err(WrongValence);
            }
            let y = m.vertex_darts(v).find(|&y| y != x).unwrap();
            if m.face(x) == m.face(y) {
                return Err(SameFace);
            }
            let (qx, qy) = (quad(x)?, quad(y)?);
            if !distinct(&[v, o(qx[1]), o(qx[2]), o(qy[1]), o(qy[2])]) {
                return Err(CornersCoincide);
            }
            Ok(())
        }
        Op::InsertDoublet(d) => {
            let q = quad(d)?;
            if !distinct(&q.map(o)) {
                return Err(CornersCoincide);
            }
            Ok(())
        }
        Op::Rotate(h, r) => {
            let t = h.twin();
            if m.face(h).is_none() || m.face(t).is_none() {
                return Err(Boundary);
            }
            if m.face(h) == m.face(t) {
                return Err(SameFace);
            }
            let (hq, tq) = (quad(h)?, quad(t)?);
            let (u, v) = (o(h), o(t));
            let hex = [v, o(hq[2]), o(hq[3]), u, o(tq[2]), o(tq[3])];
            if !distinct(&hex) {
                return Err(CornersCoincide);
            }
            let (p, q) = match r {
                Rotation::CounterClockwise => (hex[1], hex[4]),
                Rotation::Clockwise => (hex[2], hex[5]),
            };
            let joined = |a: Vert, b: Vert, except: Option<Dart>| {
                m.vertex_darts(a)
                    .any(|x| Some(x) != except && m.dest(x) == b)
            };
            if joined(u, v, Some(h)) || joined(p, q, None) {
                return Err(MultiEdge);
            }
            Ok(())
        }
        Op::Split(..) => unreachable!(),
    }
}

/// The darts whose origin the documentation names after an applied operator (kept copies
/// keep their handles), from the map before.
fn origins(m: &Map, op: Op) -> Vec<(Dart, Vert)> {
    let o = |d: Dart| m.origin(d);
    let n = |d: Dart| m.next(d);
    match op {
        Op::Collapse(d) => vec![(d, o(d)), (n(n(d)), o(d))],
        Op::Split(s1, _) | Op::HighValence(s1) => vec![(s1, o(s1))],
        Op::RemoveValence2(_) => vec![],
        Op::InsertDoublet(d) => vec![(d, o(d))],
        Op::Rotate(h, r) => {
            let t = h.twin();
            // Counter-clockwise h becomes z→x, clockwise y→w (hexagon v x y u z w).
            match r {
                Rotation::CounterClockwise => vec![(h, o(n(n(t)))), (t, o(n(n(h))))],
                Rotation::Clockwise => vec![(h, o(n(n(n(h))))), (t, o(n(n(n(t)))))],
            }
        }
    }
}

/// Checks an applied operator against its documented effect ([`Op::effect`]: V/E/F, the
/// valence of every vertex, the degree of every face), whole edges born or deleted, and the
/// documented origins.
fn check_applied(before: &Map, after: &Map, op: Op, rec: &QuadRecord) {
    let effect = op.effect(before).expect("an applied operator is allowed");
    if let Err(e) = effect.check(before, after, rec) {
        panic!("{op:?} on {before:?}: {e}");
    }
    // Untouched handles stay valid: darts die or appear in whole deleted or new edges.
    let died = before.darts().filter(|&d| !after.is_live_dart(d)).count();
    let born = after.darts().filter(|&d| !before.is_live_dart(d)).count();
    assert_eq!(
        (born as i64 - died as i64, born.min(died)),
        (2 * effect.deltas()[1], 0),
        "{op:?}"
    );
    for (d, v) in origins(before, op) {
        assert_eq!(after.origin(d), v, "{op:?}: origin of {d:?}");
    }
}

/// Loops plus surplus parallel edges: operators neither create nor remove any.
fn defects(m: &Map) -> usize {
    zipmesh_kernel::invariants::non_simple_edges(m)
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
    assert_eq!(
        can,
        oracle(m, op),
        "{op:?}: can_ disagrees with the rules on {m:?}"
    );
    let mut after = m.clone();
    let res = op.apply(&mut after).map(|e| e.into_record());
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
            check_applied(m, &after, op, &rec);
            assert_eq!(defects(&after), defects(m), "{op:?} on {m:?}");
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
                for op2 in all_ops(&big) {
                    try_op(&big, op2, &mut past, true);
                }
            }
        }
    });
    t.print(&format!("single operators, maps up to {MAX_EDGES} edges"));
    past.print("every operator on every split or insertion result (up to 6 edges)");
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
        ("grid 2x1", zipmesh_kernel::gen::grid(2, 1).map),
        ("grid 2x2", zipmesh_kernel::gen::grid(2, 2).map),
        ("cube 1", zipmesh_kernel::gen::cube(1).map),
        ("torus 3x3", zipmesh_kernel::gen::torus_grid(3, 3).map),
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
