//! Queries on the quads round a path edge or a short closed walk, shared by the preparation
//! (stage 3) and the execution (stage 4).

use crate::invariants::{is_regular_interior, MeshKind};
use crate::{Dart, Map, Vert};

/// Whether the closed walk `ring[0] -> ring[1] -> ring[2] -> ring[3] -> ring[0]` goes round
/// one quad of `map` whose corners other than `ring[0]` are not one of `ends` and, when
/// `regular` is set, are regular interior vertices: cutting it out of a path is a homotopy
/// across that quad.
pub(super) fn bounds_one_quad(map: &Map, ring: [Vert; 4], ends: [Vert; 2], regular: bool) -> bool {
    let ok = |w: Vert| {
        map.is_live_vertex(w)
            && !ends.contains(&w)
            && (!regular || is_regular_interior(map, MeshKind::Quad, w))
    };
    ring[1..].iter().all(|&w| ok(w)) && quad_on_edge(map, ring[0], ring[1], ring).is_some()
}

/// The dart `a -> b` if a quad on either side of the edge `a`-`b` has all its corners among
/// `corners`.
pub(super) fn quad_on_edge(map: &Map, a: Vert, b: Vert, corners: [Vert; 4]) -> Option<Dart> {
    map.dart_between(a, b).filter(|&d| {
        [d, d.twin()].iter().any(|&x| {
            map.face(x).is_some_and(|f| {
                map.degree(f) == 4 && map.face_darts(f).all(|y| corners.contains(&map.origin(y)))
            })
        })
    })
}

/// The quad on one side of a dart `d: a -> b`, as its three other sides read from `a` to `b`.
#[derive(Clone, Copy, Debug)]
pub(super) struct SideQuad {
    /// From `a` to the corner next to `a`.
    pub(super) out: Dart,
    /// From the corner next to `a` to the corner next to `b`.
    pub(super) across: Dart,
    /// From the corner next to `b` to `b`.
    pub(super) back: Dart,
}

impl SideQuad {
    /// The corner next to `a`.
    pub(super) fn near_origin(&self, map: &Map) -> Vert {
        map.dest(self.out)
    }

    /// The corner next to `b`.
    pub(super) fn near_dest(&self, map: &Map) -> Vert {
        map.dest(self.across)
    }
}

/// The quad on the `left` (or right) of `d: a -> b`; `None` at the boundary or when that face
/// is not a quad.
pub(super) fn side_quad(map: &Map, d: Dart, left: bool) -> Option<SideQuad> {
    let e = if left { d } else { d.twin() };
    let f = map.face(e)?;
    if map.degree(f) != 4 {
        return None;
    }
    // The face of `e` is on its left: walking it from `e` goes round the quad.
    let (after, opposite, before) = (map.next(e), map.next(map.next(e)), map.prev(e));
    Some(if left {
        SideQuad {
            out: before.twin(),
            across: opposite.twin(),
            back: after.twin(),
        }
    } else {
        SideQuad {
            out: after,
            across: opposite,
            back: before,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;

    /// A walk round one quad bounds it; a straight 4-cycle round a thin torus does not; a
    /// corner that is an end, or irregular when regular corners are asked for, refuses it.
    #[test]
    fn one_quad_is_bounded_only_by_its_own_corners() {
        let v = |i: u32| Vert::new(i);
        let grid = gen::grid(5, 5).map; // 6 vertices a row
        let ring = [v(7), v(8), v(14), v(13)];
        assert!(bounds_one_quad(&grid, ring, [v(0), v(35)], true));
        assert!(
            !bounds_one_quad(&grid, ring, [v(14), v(35)], true),
            "an end"
        );
        // 6 is on the boundary: refused when regular corners are asked for.
        let edge = [v(13), v(7), v(6), v(12)];
        assert!(!bounds_one_quad(&grid, edge, [v(0), v(35)], true));
        assert!(bounds_one_quad(&grid, edge, [v(0), v(35)], false));
        // A row of the 4 x 4 torus closes after four edges without bounding a quad.
        let torus = gen::torus_grid(4, 4).map;
        let row = [v(0), v(1), v(2), v(3)];
        assert!(torus.dart_between(v(3), v(0)).is_some());
        assert!(!bounds_one_quad(&torus, row, [v(5), v(10)], false));
        assert_eq!(quad_on_edge(&torus, v(0), v(1), row), None);
    }
}
