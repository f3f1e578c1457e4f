//! Triangle-mesh fixtures shared by the triangle editing tests.

use std::collections::BTreeSet;
use zipmesh::gen;
use zipmesh::ops::tri;
use zipmesh::tri_edit::{generate_pair_v7, move_pair, Direction, Moved, Via7};
use zipmesh::{Map, Vert};

/// The irregular interior vertices and their valences, by handle.
pub fn irregular(map: &Map) -> BTreeSet<(Vert, usize)> {
    map.vertices()
        .filter(|&v| !map.is_boundary_vertex(v) && map.valence(v) != 6)
        .map(|v| (v, map.valence(v)))
        .collect()
}

/// Graph distance by breadth-first search.
pub fn distance(map: &Map, a: Vert, b: Vert) -> usize {
    let mut seen = std::collections::HashMap::from([(a, 0usize)]);
    let mut queue = std::collections::VecDeque::from([a]);
    while let Some(v) = queue.pop_front() {
        if v == b {
            return seen[&v];
        }
        let dv = seen[&v];
        for d in map.vertex_darts(v) {
            let w = map.dest(d);
            if let std::collections::hash_map::Entry::Vacant(e) = seen.entry(w) {
                e.insert(dv + 1);
                queue.push_back(w);
            }
        }
    }
    usize::MAX
}

/// An `n x n` triangulated torus with one diagonal flipped (two adjacent 5-7 pairs).
pub fn flipped_torus(n: usize) -> (Map, (Vert, Vert)) {
    let tris: Vec<[u32; 3]> = gen::torus_quads(n, n)
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let mut map = Map::from_polygons(n * n, &tris).unwrap();
    let d = map
        .dart_between(Vert::new(0), Vert::new(n as u32 + 1))
        .unwrap();
    tri::flip_edge(&mut map, d).unwrap();
    (map, (Vert::new(0), Vert::new(1)))
}

/// A 5-7 pair that is not adjacent, in a regular neighbourhood: on a 24 x 24 torus, one
/// flip's pair walks 4 steps away; at the other pair's v7 a v7 movement with generation
/// leaves the v7 at distance 2 from the v5, and the generated pair walks 4 steps away.
/// Returns the map and the far pair (v5, v7).
pub fn far_five_seven() -> (Map, Vert, Vert) {
    let (mut map, (mut p, mut q)) = flipped_torus(24);
    for _ in 0..4 {
        let m = move_pair(&mut map, p, q, Direction::SplitRight).unwrap();
        (p, q) = (m.p(), m.q());
    }
    // The other pair: the v5 and v7 next to each other that are not (p, q).
    let other = irregular(&map)
        .into_iter()
        .find(|&(v, k)| k == 5 && v != p)
        .unwrap()
        .0;
    let seven = map
        .vertex_darts(other)
        .map(|d| map.dest(d))
        .find(|&w| map.valence(w) == 7)
        .unwrap();
    for d in map.vertex_darts(seven).collect::<Vec<_>>() {
        for via in Via7::ALL {
            for moved in [Moved::First, Moved::Second] {
                let mut m = map.clone();
                let Ok(g) = generate_pair_v7(&mut m, d, via, moved) else {
                    continue;
                };
                if distance(&m, other, g.moved()) != 2 {
                    continue;
                }
                let (mut a, mut b) = g.pair().unwrap();
                let walked = Direction::ALL.into_iter().find_map(|dir| {
                    let mut w = m.clone();
                    for _ in 0..4 {
                        let s = move_pair(&mut w, a, b, dir).ok()?;
                        (a, b) = (s.p(), s.q());
                    }
                    let far = |x| distance(&w, x, a).min(distance(&w, x, b));
                    (far(other) >= 4 && far(g.moved()) >= 4).then_some(w)
                });
                if let Some(w) = walked {
                    return (w, other, g.moved());
                }
            }
        }
    }
    panic!("no far 5-7 pair found");
}
