//! Triangle-edit benchmark fixtures shared by `benches/tri_edit.rs` and
//! `examples/workload.rs`: the n x n triangulated torus with a lone 5-7 pair, adjacent or
//! at a chosen graph distance.

use zipmesh::ops::tri;
use zipmesh::tri_edit::{generate_pair_v7, move_pair, Direction, Moved, Via7};
use zipmesh::{Map, Vert};

/// An `n x n` triangulated torus (each quad cut along the same diagonal) with the diagonal
/// `0 - (n + 1)` flipped: v5 at `0` and `n + 1`, v7 at `1` and `n`. Returns the map and the
/// two adjacent pairs `(0, 1)` and `(n + 1, n)` as (v5, v7).
pub fn flipped(n: usize) -> (Map, [(Vert, Vert); 2]) {
    let tris: Vec<[u32; 3]> = zipmesh::gen::torus_quads(n, n)
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let mut map = Map::from_polygons(n * n, &tris).expect("valid torus");
    let v = |i: usize| Vert::new(i as u32);
    let d = map.dart_between(v(0), v(n + 1)).expect("diagonal");
    tri::flip_edge(&mut map, d).expect("flip");
    (map, [(v(0), v(1)), (v(n + 1), v(n))])
}

/// Whether `x` is clear of the pair `(s, t)` that is to end `want` edges apart, `t` having
/// `left` more steps to go: `d(x, s) + d(x, t) - left >= want + 6`, so that `x` stays off
/// every short path between them and out of the 2-ring their edits need regular.
fn clear(ds: &[usize], dt: &[usize], x: Vert, want: usize, left: usize) -> bool {
    // A vertex made after the distances were measured is not clear.
    let (a, b) = (ds.get(x.index()), dt.get(x.index()));
    let (Some(&a), Some(&b)) = (a, b) else {
        return false;
    };
    a != usize::MAX && b != usize::MAX && a + b >= want + 6 + left
}

/// Walks the adjacent 5-7 pair `(p, q)` by atomic moves, in the first direction and the
/// fewest steps (at most `max_steps`) that leave both vertices [`clear`] of `(s, t)`
/// (distances `ds`, `dt` measured before the walk). Returns false with the map unchanged
/// when no direction does.
fn send_away(
    map: &mut Map,
    (p, q): (Vert, Vert),
    fields: (&[usize], &[usize]),
    goal: (usize, usize),
    max_steps: usize,
) -> bool {
    let (ds, dt) = fields;
    let (want, left) = goal;
    for dir in Direction::ALL {
        let mut m = map.clone();
        let (mut a, mut b) = (p, q);
        for _ in 0..max_steps {
            let Ok(s) = move_pair(&mut m, a, b, dir) else {
                break;
            };
            (a, b) = (s.p(), s.q());
            if clear(ds, dt, a, want, left) && clear(ds, dt, b, want, left) {
                *map = m;
                return true;
            }
        }
    }
    false
}

/// The irregular vertices of `map` other than `s` and `t`.
fn others(map: &Map, s: Vert, t: Vert) -> Vec<Vert> {
    map.vertices()
        .filter(|&v| map.valence(v) != 6 && v != s && v != t)
        .collect()
}

/// A lone 5-7 pair `want` edges apart (1: adjacent) on the `n x n` triangulated torus:
/// the flip's first pair walks away ([`send_away`]); the second pair's v7 `t` then moves
/// one edge further from its v5 `s` at a time by the v7 movement with 5-7 generation
/// (`generate_pair_v7`, the first dart and configuration that works), each generated pair
/// being walked away. Every other irregular vertex ends clear of both (the sum of its
/// distances to them at least `want + 6`). Returns (map, v5 `s`, v7 `t`); panics when the
/// torus is too small for `want`.
pub fn far_pair(n: usize, want: usize) -> (Map, Vert, Vert) {
    let (mut map, [a, (s, mut t)]) = flipped(n);
    let (ds, dt) = (map.distances(s), map.distances(t));
    assert!(
        send_away(&mut map, a, (&ds, &dt), (want, want - 1), n),
        "torus {n}: first pair"
    );
    let mut at = 1;
    while at < want {
        let ds = map.distances(s);
        let mut grown = None;
        'search: for d in map.vertex_darts(t).collect::<Vec<_>>() {
            for via in Via7::ALL {
                let mut m = map.clone();
                let Ok(g) = generate_pair_v7(&mut m, d, via, Moved::First) else {
                    continue;
                };
                let Some(pair) = g.pair() else { continue };
                if ds.get(g.moved().index()) != Some(&(at + 1)) {
                    continue;
                }
                let dt = m.distances(g.moved());
                // The walk can change distances (a 5-7 pair is a dislocation): measure again.
                if send_away(&mut m, pair, (&ds, &dt), (want, want - at - 1), n)
                    && m.distances(s)[g.moved().index()] == at + 1
                {
                    grown = Some((m, g.moved()));
                    break 'search;
                }
            }
        }
        (map, t) = grown.unwrap_or_else(|| panic!("torus {n}: no step from {at} to {}", at + 1));
        at += 1;
    }
    let (ds, dt) = (map.distances(s), map.distances(t));
    assert_eq!(ds[t.index()], want, "torus {n}");
    assert!((map.valence(s), map.valence(t)) == (5, 7));
    for x in others(&map, s, t) {
        assert!(
            clear(&ds, &dt, x, want, 0),
            "torus {n}, distance {want}: {x:?} in the way"
        );
    }
    (map, s, t)
}
