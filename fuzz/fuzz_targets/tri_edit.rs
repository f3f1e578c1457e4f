//! Semantic triangle edits (irregular-vertex paper, Sec. 6-7) on fuzzer-chosen random
//! triangle meshes: atomic 5-7 moves of adjacent pairs and composite moves (Sec. 7.1) of
//! fuzzer-chosen pairs of irregular vertices keep the contract (a refusal agrees with the
//! `can_*` and leaves the map `==`; an application leaves a valid map with the pair's
//! valences where the record says and the irregular multiset unchanged), and undoing
//! everything, last first, gives the start back `==`. One step in eight is instead a
//! 5-5-7-7 generation with the pairs apart (Sec. 7.3: v5, v7, v5, v7, multiset + {5, 5, 7,
//! 7}) or a type split and the aggregation of what it left (one vertex of the split's
//! valence, the multiset as before), with the same contract.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::tri_edit::{
    aggregate_type, can_aggregate_type, can_generate_quadruple_apart, can_move_far_pair,
    can_move_pair, can_split_type, generate_quadruple_apart, move_far_pair, move_pair, split_type,
    Direction, FarPairMove, Moved, PairMove, Quadruple, QuadrupleEdit, Start, TypeEdit,
};
use zipmesh::{gen, Map, Vert};

enum Done {
    Atomic(Box<PairMove>),
    Composite(Box<FarPairMove>),
    Quadruple(QuadrupleEdit),
    Type(TypeEdit),
}

/// Interior vertices whose valence `want` accepts.
fn interior(map: &Map, want: impl Fn(usize) -> bool) -> Vec<Vert> {
    map.vertices()
        .filter(|&v| !map.is_boundary_vertex(v) && want(map.valence(v)))
        .collect()
}

/// A quadruple with its pairs apart at the `pick`-th regular vertex.
fn quadruple_apart(map: &mut Map, pick: usize, sel: usize, done: &mut Vec<Done>) {
    let regular = interior(map, |k| k == 6);
    let Some(&v) = regular.get(pick % regular.len().max(1)) else {
        return;
    };
    let d = (0..sel % 6).fold(map.vertex_dart(v), |x, _| map.rotate_cw(x));
    let how = [Quadruple::Flip, Quadruple::Split][(sel >> 1) & 1];
    let dir = Direction::ALL[(sel >> 2) % 6];
    let steps = 1 + (pick >> 4) % 4;
    let (before, mut want) = (map.clone(), irregular(map));
    let can = can_generate_quadruple_apart(map, d, how, dir, steps);
    match generate_quadruple_apart(map, d, how, dir, steps) {
        Err(e) => {
            assert_eq!(can, Err(e));
            assert!(*map == before, "a refused generation changed the map");
        }
        Ok(g) => {
            assert_eq!(can, Ok(()));
            let vals: Vec<usize> = g.vertices().iter().map(|&x| map.valence(x)).collect();
            assert_eq!(vals, [5, 7, 5, 7]);
            want.extend([5, 5, 7, 7]);
            want.sort_unstable();
            assert_eq!(irregular(map), want, "generation apart: multiset");
            done.push(Done::Quadruple(g.into_record()));
        }
    }
}

/// A type split of the `pick`-th v3, v4 or vk (k > 7), then the aggregation of what it left.
fn split_and_aggregate(map: &mut Map, pick: usize, done: &mut Vec<Done>) {
    let odd = interior(map, |k| k == 3 || k == 4 || k > 7);
    let Some(&v) = odd.get(pick % odd.len().max(1)) else {
        return;
    };
    let (before, multiset, k) = (map.clone(), irregular(map), map.valence(v));
    let can = can_split_type(map, v);
    let s = match split_type(map, v) {
        Err(e) => {
            assert_eq!(can, Err(e));
            assert!(*map == before, "a refused split changed the map");
            return;
        }
        Ok(s) => s,
    };
    assert_eq!(can, Ok(()));
    let split = map.clone();
    let can = can_aggregate_type(map, s.vertices());
    match aggregate_type(map, s.vertices()) {
        Err(e) => {
            assert_eq!(can, Err(e));
            assert!(*map == split, "a refused aggregation changed the map");
            done.push(Done::Type(s.into_record()));
        }
        Ok(a) => {
            assert_eq!(can, Ok(()));
            assert_eq!(map.valence(a.vertices()[0]), k);
            assert_eq!(irregular(map), multiset, "aggregation: multiset");
            done.extend([Done::Type(s.into_record()), Done::Type(a.into_record())]);
        }
    }
}

fn irregular(map: &Map) -> Vec<usize> {
    let mut v: Vec<usize> = map
        .vertices()
        .filter(|&v| !map.is_boundary_vertex(v) && map.valence(v) != 6)
        .map(|v| map.valence(v))
        .collect();
    v.sort_unstable();
    v
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 6 {
        return;
    }
    let b = |i: usize| data[i] as usize;
    let seed = u64::from(data[3]) | (u64::from(data[4]) << 8);
    let mut map = gen::random_triangle(60 + 10 * (b(0) % 20), b(1) % 3, b(2) % 2, seed).map;
    let start = map.clone();
    let mut done = Vec::new();
    for ch in data[5..].chunks(3).take(16) {
        let sel = ch.get(2).copied().unwrap_or(0) as usize;
        if sel % 8 == 7 {
            let pick = ch.first().copied().unwrap_or(0) as usize;
            if sel & 8 == 0 {
                quadruple_apart(&mut map, pick, sel >> 4, &mut done);
            } else {
                split_and_aggregate(&mut map, pick, &mut done);
            }
            assert_eq!(map.check(), Ok(()));
            continue;
        }
        let odd: Vec<Vert> = map
            .vertices()
            .filter(|&v| !map.is_boundary_vertex(v) && matches!(map.valence(v), 5 | 7))
            .collect();
        if odd.len() < 2 {
            break;
        }
        let at = |i: usize| odd[ch.get(i).copied().unwrap_or(0) as usize % odd.len()];
        let (s, o) = (at(0), at(1));
        let k = ch.get(2).copied().unwrap_or(0) as usize;
        let before = map.clone();
        let multiset = irregular(&map);
        if k & 1 == 0 {
            let dir = Direction::ALL[(k >> 1) % 6];
            let can = can_move_pair(&map, s, o, dir);
            match move_pair(&mut map, s, o, dir) {
                Err(e) => {
                    assert_eq!(can, Err(e));
                    assert!(map == before, "a refused atomic move changed the map");
                    continue;
                }
                Ok(m) => {
                    assert_eq!(can, Ok(()));
                    assert_eq!((map.valence(m.p()), map.valence(m.q())), (5, 7));
                    done.push(Done::Atomic(Box::new(m.into_record())));
                }
            }
        } else {
            let darts: Vec<_> = map.vertex_darts(s).collect();
            let d = darts[(k >> 1) % darts.len()];
            let starts = Start::all(map.valence(s));
            let how = starts[(k >> 4) % starts.len()];
            let moved = if k & 2 == 0 {
                Moved::First
            } else {
                Moved::Second
            };
            let want = (map.valence(s), map.valence(o));
            let can = can_move_far_pair(&map, d, how, moved, o, 16);
            match move_far_pair(&mut map, d, how, moved, o, 16) {
                Err(e) => {
                    assert_eq!(can, Err(e));
                    assert!(map == before, "a refused composite move changed the map");
                    continue;
                }
                Ok(m) => {
                    assert_eq!(can, Ok(()));
                    let (x, y) = m.pair();
                    assert_eq!((map.valence(x), map.valence(y)), want);
                    done.push(Done::Composite(Box::new(m.into_record())));
                }
            }
        }
        assert_eq!(map.check(), Ok(()));
        assert_eq!(irregular(&map), multiset, "the irregular multiset changed");
    }
    for m in done.iter().rev() {
        let r = match m {
            Done::Atomic(m) => m.undo(&mut map),
            Done::Composite(m) => m.undo(&mut map),
            Done::Quadruple(g) => g.undo(&mut map),
            Done::Type(t) => t.undo(&mut map),
        };
        assert_eq!(r, Ok(()));
    }
    assert!(
        map == start,
        "undoing everything did not give the start back"
    );
});
