//! Which vertices an edit touched, and the region around them that a relaxation moves.

use alloc::vec;
use alloc::vec::Vec;

use crate::{Map, Vert};

/// The live vertices of `after` whose neighbours (as vertex slots) differ from those they
/// have in `before`, or which are not live in `before`: what an edit from `before` to
/// `after` touched, in slot order. Positions play no part.
///
/// ```
/// use zipmesh::ops::tri;
/// use zipmesh::geometry::touched_vertices;
/// use zipmesh::{gen, Vert};
/// let before = gen::random_triangle(60, 0, 0, 2).map;
/// let mut after = before.clone();
/// let d = after.darts().find(|&d| tri::can_flip_edge(&after, d).is_ok()).unwrap();
/// let (a, b) = (after.origin(d), after.dest(d));
/// tri::flip_edge(&mut after, d).unwrap();
/// let t = touched_vertices(&before, &after);
/// assert_eq!(t.len(), 4); // the edge's ends and the two apexes
/// assert!(t.contains(&a) && t.contains(&b));
/// ```
pub fn touched_vertices(before: &Map, after: &Map) -> Vec<Vert> {
    let ring = |m: &Map, v: Vert| {
        let mut r: Vec<Vert> = m.vertex_darts(v).map(|d| m.dest(d)).collect();
        r.sort_unstable();
        r
    };
    after
        .vertices()
        .filter(|&v| !before.is_live_vertex(v) || ring(before, v) != ring(after, v))
        .collect()
}

/// The live vertices within `rings` edges of a live vertex of `seeds`, boundary vertices
/// left out (they keep their place), in slot order: the vertices a relaxation moves.
///
/// ```
/// use zipmesh::geometry::relax_region;
/// use zipmesh::{gen, Vert};
/// let map = gen::random_triangle(200, 1, 0, 3).map; // a torus: no boundary
/// let v = Vert::new(7);
/// assert_eq!(relax_region(&map, &[v], 0), vec![v]);
/// assert_eq!(relax_region(&map, &[v], 1).len(), map.valence(v) + 1);
/// ```
pub fn relax_region(map: &Map, seeds: &[Vert], rings: usize) -> Vec<Vert> {
    let mut seen = vec![false; map.vertex_slots()];
    let mut frontier: Vec<Vert> = Vec::new();
    for &v in seeds {
        if map.is_live_vertex(v) && !seen[v.index()] {
            seen[v.index()] = true;
            frontier.push(v);
        }
    }
    for _ in 0..rings {
        let mut next = Vec::new();
        for &v in &frontier {
            for d in map.vertex_darts(v) {
                let w = map.dest(d);
                if let Some(s) = seen.get_mut(w.index()).filter(|s| !**s) {
                    *s = true;
                    next.push(w);
                }
            }
        }
        if next.is_empty() {
            break;
        }
        frontier = next;
    }
    (0..seen.len() as u32)
        .map(Vert::new)
        .filter(|&v| seen[v.index()] && !map.is_boundary_vertex(v))
        .collect()
}
