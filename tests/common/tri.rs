//! Triangle-mesh fixtures shared by the triangle editing tests.

use glam::DVec3;
use std::collections::BTreeSet;
use zipmesh::gen;
use zipmesh::ops::tri;
use zipmesh::tri_edit::{generate_pair_v7, move_pair, Direction, Moved, Via7};
use zipmesh::{Map, Mesh, Vert};

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

/// An `n x n` patch of the equilateral triangle lattice (edge 1) lifted onto the height
/// field `bump * sin(0.4 x) cos(0.5 y)`.
pub fn lattice(n: usize, bump: f64) -> Mesh {
    let mut p = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 + j as f64 * 0.5, j as f64 * 3f64.sqrt() / 2.0);
            p.push(DVec3::new(x, y, bump * (0.4 * x).sin() * (0.5 * y).cos()));
        }
    }
    let mut tris = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = (j * n + i) as u32;
            let (b, c) = (a + 1, a + n as u32);
            tris.push([a, b, c]);
            tris.push([b, c + 1, c]);
        }
    }
    Mesh::from_polygons(p, &tris).unwrap().0
}

/// The distance from `p` to the triangle `t`, by projection onto its plane and, outside,
/// the nearest of its edges.
pub fn to_triangle(p: DVec3, t: [DVec3; 3]) -> f64 {
    let seg = |a: DVec3, b: DVec3| {
        let ab = b - a;
        let s = if ab.length_squared() > 0.0 {
            ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(a + ab * s)
    };
    let edges = seg(t[0], t[1]).min(seg(t[1], t[2])).min(seg(t[2], t[0]));
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    if n.length_squared() == 0.0 {
        return edges;
    }
    let n = n.normalize();
    let q = p - n * n.dot(p - t[0]);
    let inside = (0..3).all(|k| (t[(k + 1) % 3] - t[k]).cross(q - t[k]).dot(n) >= 0.0);
    if inside {
        p.distance(q)
    } else {
        edges
    }
}

/// The distance from `p` to the surface of `mesh`, by brute force over its triangles.
pub fn to_surface(mesh: &Mesh, p: DVec3) -> f64 {
    mesh.polygons()
        .iter()
        .map(|f| {
            let c = |k: usize| mesh.positions[f[k] as usize];
            to_triangle(p, [c(0), c(1), c(2)])
        })
        .fold(f64::INFINITY, f64::min)
}
