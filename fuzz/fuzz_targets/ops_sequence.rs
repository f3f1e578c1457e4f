//! Arbitrary operator sequences on generated quad and triangle meshes: never a panic, every
//! refusal leaves the map unchanged and agrees with its `can_*`, `check()` passes after every
//! step, each applied operator has its documented effect (`QuadOp::effect`,
//! `TriOp::effect`), and undoing the whole sequence gives back the original map (arrays and
//! canonical code).
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::ops::quad::{QuadOp, Rotation};
use zipmesh::ops::tri::TriOp;
use zipmesh::ops::{Effect, Refusal, Undo, VertexChanges};
use zipmesh::{gen, Dart, Map};

/// The mesh the bytes ask for: small, so that sequences run into every refusal rule.
fn mesh(pick: u8, a: u8, b: u8, seed: u64) -> (Map, bool) {
    let (a, b) = (3 + usize::from(a % 5), 3 + usize::from(b % 5));
    let quads = |m: zipmesh::Mesh| (m.map, true);
    let triangulate = |m: &Map| {
        let polys: Vec<Vec<u32>> = m
            .faces()
            .flat_map(|f| {
                let c: Vec<u32> = m
                    .face_darts(f)
                    .map(|d| m.origin(d).index() as u32)
                    .collect();
                [vec![c[0], c[1], c[2]], vec![c[0], c[2], c[3]]]
            })
            .collect();
        Map::from_polygons(m.vertex_slots(), &polys).expect("a triangulated quad mesh")
    };
    match pick % 7 {
        0 => quads(gen::torus_grid(a, b)),
        1 => quads(gen::grid(a - 2, b - 2)),
        2 => quads(gen::cube(a / 2)),
        3 => quads(gen::random_quad(40 + 8 * a, b % 3, a % 2, seed)),
        4 => (triangulate(&gen::torus_grid(a, b).map), false),
        5 => (triangulate(&gen::grid(a - 2, b - 2).map), false),
        _ => (
            gen::random_triangle(40 + 8 * a, b % 3, a % 2, seed).map,
            false,
        ),
    }
}

type Record = Box<dyn Undo>;

/// Applies operator `op` at dart `d` (`e` picks the second dart of a split), checking the
/// refusal contract and the documented effect; returns the record when it applied.
fn apply(map: &mut Map, is_quad: bool, op: u8, d: Dart, e: u8) -> Option<Record> {
    let second = |m: &Map| (0..=usize::from(e % 8)).fold(d, |x, _| m.rotate_cw(x));
    if is_quad {
        let op = match op % 6 {
            0 => QuadOp::Collapse(d),
            1 => QuadOp::Split(d, second(map)),
            2 => QuadOp::RemoveValence2(d),
            3 => QuadOp::InsertDoublet(d),
            4 if e & 1 == 0 => QuadOp::Rotate(d, Rotation::Clockwise),
            4 => QuadOp::Rotate(d, Rotation::CounterClockwise),
            _ => QuadOp::HighValence(d),
        };
        checked(map, op.can(map), op.effect(map), |m| op.apply(m))
    } else {
        let op = match op % 4 {
            0 => TriOp::Flip(d),
            1 => TriOp::Collapse(d),
            2 => TriOp::SplitEdge(d),
            _ => TriOp::SplitVertex(d, second(map)),
        };
        checked(map, op.can(map), op.effect(map), |m| op.apply(m))
    }
}

/// Runs `apply`: a refusal must be `can`'s and change nothing; an application must pass
/// `check()` and meet `effect`.
fn checked<R: Undo + VertexChanges + 'static>(
    map: &mut Map,
    can: Result<(), Refusal>,
    effect: Result<Effect, Refusal>,
    apply: impl FnOnce(&mut Map) -> Result<R, Refusal>,
) -> Option<Record> {
    let before = map.clone();
    match apply(map) {
        Ok(r) => {
            assert_eq!(can, Ok(()), "applied although can_* refused");
            assert_eq!(map.check(), Ok(()));
            let effect = effect.expect("the effect of an allowed operator");
            if let Err(e) = effect.check(&before, map, &r) {
                panic!("not the documented effect: {e}");
            }
            Some(Box::new(r))
        }
        Err(why) => {
            assert_eq!(can, Err(why), "refusal differs from can_*");
            assert!(*map == before, "a refused operator changed the map");
            None
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let [pick, a, b, s, rest @ ..] = data else {
        return;
    };
    let (mut map, is_quad) = mesh(*pick, *a, *b, u64::from(*s));
    let original = map.clone();
    let code = CanonicalCode::of(&map);
    let mut records = Vec::new();
    for step in rest.chunks_exact(4).take(64) {
        let d = Dart::new(
            u32::from(u16::from_le_bytes([step[1], step[2]])) % map.dart_slots().max(1) as u32,
        );
        if !map.is_live_dart(d) {
            continue;
        }
        if let Some(r) = apply(&mut map, is_quad, step[0], d, step[3]) {
            records.push(r);
        }
    }
    while let Some(r) = records.pop() {
        assert_eq!(r.undo(&mut map), Ok(()));
        assert_eq!(map.check(), Ok(()));
    }
    assert!(
        map == original,
        "undoing every step did not restore the map"
    );
    assert_eq!(CanonicalCode::of(&map), code);
});
