//! Semantic triangle edits (irregular-vertex paper, Sec. 6-7) on fuzzer-chosen random
//! triangle meshes: atomic 5-7 moves of adjacent pairs and composite moves (Sec. 7.1) of
//! fuzzer-chosen pairs of irregular vertices keep the contract (a refusal agrees with the
//! `can_*` and leaves the map `==`; an application leaves a valid map with the pair's
//! valences where the record says and the irregular multiset unchanged), and undoing
//! everything, last first, gives the start back `==`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::tri_edit::{
    can_move_far_pair, can_move_pair, move_far_pair, move_pair, Direction, FarPairMove, Moved,
    PairMove, Start,
};
use zipmesh::{gen, Map, Vert};

enum Done {
    Atomic(Box<PairMove>),
    Composite(Box<FarPairMove>),
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
                    done.push(Done::Atomic(Box::new(m)));
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
                    done.push(Done::Composite(Box::new(m)));
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
        };
        assert_eq!(r, Ok(()));
    }
    assert!(
        map == start,
        "undoing everything did not give the start back"
    );
});
