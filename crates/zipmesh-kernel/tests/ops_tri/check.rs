//! The oracle for the triangle operators, shared by the root crate's `tests/ops_tri.rs` and
//! `proofs/ops_tri.rs`: apply an operator and check every documented promise: its effect on
//! counts, valences and face degrees against the library's one statement of it
//! (`TriOp::effect`), the rest using only the public accessors of the map (never the
//! operator's own code paths).

#![allow(dead_code)]

use zipmesh_kernel::invariants::canonical::CanonicalCode;
use zipmesh_kernel::ops::Refusal;
use zipmesh_kernel::{Dart, Edge, Face, Map, Vert};

/// One operator with its arguments, and the record of an applied one: the library's.
pub use zipmesh_kernel::ops::tri::{TriOp as Op, TriRecord as Rec};

pub fn can(map: &Map, op: Op) -> Result<(), Refusal> {
    op.can(map)
}

pub fn run(map: &mut Map, op: Op) -> Result<Rec, Refusal> {
    op.apply(map).map(|e| e.into_record())
}

/// The third corner of the face of `d` (a triangle), from the public accessors.
fn apex(map: &Map, d: Dart) -> Vert {
    map.dest(map.next(d))
}

/// Applies `op` and checks: the refusal equals `can_*`'s and leaves the map equal to
/// before; or the operator applied, `check()` passes, and V, E, F, the valence of every
/// vertex, the degree of every face and the liveness of every old element are exactly as
/// documented. Returns the operator's result.
pub fn checked(map: &mut Map, op: Op) -> Result<Rec, Refusal> {
    let before = map.clone();
    let allowed = can(map, op);
    match run(map, op) {
        Err(e) => {
            assert_eq!(allowed, Err(e), "{op:?}: can_* disagrees with the operator");
            assert!(
                *map == before,
                "{op:?} refused with {e:?} but changed the map"
            );
            Err(e)
        }
        Ok(rec) => {
            assert_eq!(allowed, Ok(()), "{op:?}: applied though can_* refused");
            if let Err(v) = map.check() {
                panic!("{op:?} on {before:?} broke the map: {v:?}\n{map:?}");
            }
            deltas(&before, map, op, &rec);
            Ok(rec)
        }
    }
}

/// The documented changes of an applied operator, checked against the maps before and
/// after: its effect (`TriOp::effect`: V, E, F, the valence of every vertex, the degree of
/// every face), the handles each operator names, the valence minimum and the liveness of
/// every old element.
pub fn deltas(before: &Map, after: &Map, op: Op, rec: &Rec) {
    let effect = op.effect(before).expect("an applied operator is allowed");
    if let Err(e) = effect.check(before, after, rec) {
        panic!("{op:?} on {before:?}: {e}");
    }
    let (dead_edges, dead_faces) = handles(before, after, op, rec);
    // The valence minimum: no vertex is newly left below it (3 inside, 2 on the boundary):
    // every vertex that is new, that lost darts, or that is the kept end of a collapse.
    let kept = match rec {
        Rec::Collapse(r) => Some(r.kept()),
        _ => None,
    };
    for v in after.vertices() {
        let a = after.valence(v);
        if !before.is_live_vertex(v) || a < before.valence(v) || kept == Some(v) {
            let min = if after.is_boundary_vertex(v) { 2 } else { 3 };
            assert!(a >= min, "{op:?} left {v:?} with valence {a} on {before:?}");
        }
    }
    // Every dart and face alive before, and not removed, is alive after (handles stay
    // valid; the effect checked the vertices).
    for d in before.darts() {
        assert_eq!(
            after.is_live_dart(d),
            !dead_edges.contains(&d.edge()),
            "{op:?}: dart {d:?}"
        );
    }
    for f in before.faces() {
        assert_eq!(
            after.is_live_face(f),
            !dead_faces.contains(&f),
            "{op:?}: {f:?}"
        );
    }
}

/// Checks the handles the documentation of `op` names after it; returns the edges and faces
/// it deletes.
fn handles(before: &Map, after: &Map, op: Op, rec: &Rec) -> (Vec<Edge>, Vec<Face>) {
    let mut dead_edges: Vec<Edge> = Vec::new();
    let mut dead_faces: Vec<Face> = Vec::new();
    match (op, rec) {
        (Op::Flip(h), Rec::Flip(r)) => {
            let (c, d) = (apex(before, h), apex(before, h.twin()));
            assert_eq!(r.dart(), h);
            assert_eq!(
                (after.origin(h), after.dest(h)),
                (d, c),
                "{op:?}: h runs d -> c"
            );
        }
        (Op::Collapse(h), Rec::Collapse(r)) => {
            assert_eq!((r.kept(), r.removed()), (before.dest(h), before.origin(h)));
            dead_edges.push(h.edge());
            if let Some(f) = before.face(h) {
                dead_edges.push(before.next(before.next(h)).edge());
                dead_faces.push(f);
            }
            if let Some(f) = before.face(h.twin()) {
                dead_edges.push(before.next(h.twin()).edge());
                dead_faces.push(f);
            }
        }
        (Op::SplitVertex(d1, d2), Rec::SplitVertex(r)) => {
            split_vertex_handles(before, after, [d1, d2], r)
        }
        (Op::SplitEdge(h), Rec::SplitEdge(r)) => {
            let (a, b, m) = (before.origin(h), before.dest(h), r.created());
            assert_eq!((after.origin(h), after.dest(h)), (a, m));
            assert_eq!((after.origin(r.dart()), after.dest(r.dart())), (m, b));
        }
        _ => unreachable!("record kind does not match the operator"),
    }
    (dead_edges, dead_faces)
}

/// A vertex split's handles: the moved arc's darts leave the new vertex `v`, the kept ones
/// still leave `w`, and the new triangles are (v, w, a) and (w, v, b).
fn split_vertex_handles(
    before: &Map,
    after: &Map,
    [d1, d2]: [Dart; 2],
    r: &zipmesh_kernel::ops::tri::VertexSplit,
) {
    let w = before.origin(d1);
    let (a, b) = (before.dest(d1), before.dest(d2));
    // Kept arc: clockwise from d1 to d2; moved arc: clockwise from d2 to d1.
    let arc = |from: Dart, to: Dart| {
        let mut out = Vec::new();
        let mut x = before.rotate_cw(from);
        while x != to {
            out.push(x);
            x = before.rotate_cw(x);
        }
        out
    };
    let kept = arc(d1, d2);
    let moved = arc(d2, d1);
    assert_eq!(kept.len() + moved.len() + 2, before.valence(w));
    let v = r.created();
    assert_eq!((after.origin(r.edge()), after.dest(r.edge())), (v, w));
    for &x in &moved {
        assert_eq!(after.origin(x), v, "moved dart {x:?}");
    }
    for &x in kept.iter().chain([&d1, &d2]) {
        assert_eq!(after.origin(x), w, "kept dart {x:?}");
    }
    let corners = |d: Dart| [after.origin(d), after.dest(d), apex(after, d)];
    assert_eq!(corners(r.edge()), [v, w, a]);
    assert_eq!(corners(r.edge().twin()), [w, v, b]);
}

/// Applies `op` checked; if it applied, undoes it and checks the map is equal to before,
/// then checks the inverse operator (when it is one) gives back the map up to isomorphism.
/// Returns whether it applied.
pub fn checked_roundtrip(map: &Map, op: Op) -> Option<Refusal> {
    let mut m = map.clone();
    let rec = match checked(&mut m, op) {
        Err(e) => return Some(e),
        Ok(rec) => rec,
    };
    let after = m.clone();
    rec.undo(&mut m)
        .unwrap_or_else(|e| panic!("{op:?}: undo refused: {e:?}"));
    assert!(
        m == *map,
        "{op:?}: undo did not restore the arrays\n{map:?}\n{m:?}"
    );
    inverse(map, &after, op, &rec);
    None
}

/// Whether the map has no loop and no two edges between the same two vertices.
pub fn is_simple(map: &Map) -> bool {
    let mut pairs = Vec::new();
    for d in map.darts().filter(|d| d.index() % 2 == 0) {
        let (a, b) = (map.origin(d), map.dest(d));
        if a == b {
            return false;
        }
        pairs.push((a.min(b), a.max(b)));
    }
    pairs.sort();
    pairs.windows(2).all(|w| w[0] != w[1])
}

/// Whether every vertex meets the valence minimum (3 inside, 2 on the boundary).
fn meets_minimum(map: &Map, v: Vert) -> bool {
    map.valence(v) >= if map.is_boundary_vertex(v) { 2 } else { 3 }
}

/// The public inverse of an applied operator: flip again, vertex split after an interior
/// collapse, collapse of the new edge after a vertex split, collapse of `twin(h)` after an
/// edge split. Where the documentation promises the inverse applies, it must; whenever it
/// applies, it must give back a map isomorphic to `before` (canonical code).
pub fn inverse(before: &Map, after: &Map, op: Op, rec: &Rec) {
    let mut m = after.clone();
    let (inv, promised) = match (op, rec) {
        (Op::Flip(h), _) => {
            // Flipping back lowers c and d again: promised when they meet the minimum.
            let (c, d) = (apex(before, h), apex(before, h.twin()));
            let ok = is_simple(before) && meets_minimum(before, c) && meets_minimum(before, d);
            (Op::Flip(h), ok)
        }
        (Op::Collapse(h), _) => {
            if before.face(h).is_none() || before.face(h.twin()).is_none() {
                return; // a boundary collapse's inverse is only its record
            }
            let h1 = before.next(h);
            let t2 = before.next(before.next(h.twin()));
            (Op::SplitVertex(h1, t2.twin()), true)
        }
        (Op::SplitVertex(d1, d2), Rec::SplitVertex(r)) => {
            let w = before.origin(d1);
            let (a, b) = (before.dest(d1), before.dest(d2));
            let ok = [w, a, b].iter().all(|&x| meets_minimum(before, x));
            (Op::Collapse(r.edge()), ok)
        }
        (Op::SplitEdge(h), _) => {
            // The collapse lowers a (kept), c and d back: promised when they meet the minimum.
            let mut ends = vec![before.origin(h)];
            for x in [h, h.twin()] {
                if before.face(x).is_some() {
                    ends.push(apex(before, x));
                }
            }
            let ok = is_simple(before) && ends.iter().all(|&x| meets_minimum(before, x));
            (Op::Collapse(h.twin()), ok)
        }
        _ => unreachable!(),
    };
    match checked(&mut m, inv) {
        Ok(_) => assert_eq!(
            CanonicalCode::of(&m),
            CanonicalCode::of(before),
            "{op:?} then {inv:?} is not the identity up to isomorphism"
        ),
        Err(e) => assert!(!promised, "{op:?}: the inverse {inv:?} was refused: {e:?}"),
    }
}
