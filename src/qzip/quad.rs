//! Queries on the quads round a path edge or a short closed walk, shared by the preparation
//! (stage 3) and the execution (stage 4).

use crate::{Dart, Map, Vert};

/// Whether the closed walk `ring[0] -> ring[1] -> ring[2] -> ring[3] -> ring[0]` goes round
/// one quad of `map` whose corners other than `ring[0]` are not one of `ends` and, when
/// `regular` is set, are regular interior vertices: cutting it out of a path is a homotopy
/// across that quad.
pub(super) fn bounds_one_quad(map: &Map, ring: [Vert; 4], ends: [Vert; 2], regular: bool) -> bool {
    let ok = |w: Vert| {
        map.is_live_vertex(w)
            && !ends.contains(&w)
            && (!regular || (map.valence(w) == 4 && !map.is_boundary_vertex(w)))
    };
    ring[1..].iter().all(|&w| ok(w))
        && map.dart_between(ring[0], ring[1]).is_some_and(|d| {
            [d, d.twin()].iter().any(|&x| {
                map.face(x).is_some_and(|f| {
                    map.degree(f) == 4 && map.face_darts(f).all(|y| ring.contains(&map.origin(y)))
                })
            })
        })
}

/// The two corners of the quad on the `left` (or right) of `d: a -> b` other than `a` and
/// `b`: `(corner next to a, corner next to b)`.
pub(super) fn side_quad(map: &Map, d: Dart, left: bool) -> Option<(Vert, Vert)> {
    let e = if left { d } else { d.twin() };
    let f = map.face(e)?;
    if map.degree(f) != 4 {
        return None;
    }
    let (near_origin, near_dest) = (map.origin(map.prev(e)), map.dest(map.next(e)));
    Some(if left {
        (near_origin, near_dest)
    } else {
        (near_dest, near_origin)
    })
}
