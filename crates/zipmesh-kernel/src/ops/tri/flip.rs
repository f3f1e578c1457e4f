//! Edge flip: the diagonal of the two triangles at an edge turns a quarter turn.

use super::{distinct_corners, joined, min_valence, triangle, valence_at_least, Undo};
use crate::map::{Dart, Face, Map, Vert};
use crate::ops::guard::Guard;
use crate::ops::Refusal;

/// Record of an [`flip_edge`]: the flipped dart and what its exact undo needs.
///
/// ```
/// use zipmesh_kernel::{ops::tri, Dart, Map};
/// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
/// let rec = tri::flip_edge(&mut map, Dart::new(0)).unwrap();
/// assert_eq!((map.origin(rec.dart()).index(), map.dest(rec.dart()).index()), (3, 2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeFlip {
    /// The flipped dart (see [`EdgeFlip::dart`]).
    dart: Dart,
    /// Before the flip: `vdart[a]`, `vdart[b]`, `fdart[f0]`, `fdart[f1]`.
    old: [Dart; 4],
    /// After the flip: the ends `d`, `c` of the dart (tells a flipped edge from a restored one).
    ends: [Vert; 2],
}

/// Checks whether [`flip_edge`] applies to the edge of `h`, without changing anything.
///
/// With `h` running from `a` to `b`, `(a, b, c)` the triangle of `h` and `(b, a, d)` the
/// triangle of `twin(h)`, the rules, in the order checked:
/// 1. [`Refusal::DeadHandle`]: `h` is not a live dart.
/// 2. [`Refusal::Boundary`]: the edge has a boundary side (there is no second triangle).
/// 3. [`Refusal::WrongDegree`]: a face of the edge is not a triangle.
/// 4. [`Refusal::DegenerateTriangle`]: a triangle has a repeated corner.
/// 5. [`Refusal::Loop`]: `c == d`, so the new edge would be a loop.
/// 6. [`Refusal::MultiEdge`]: an edge `c-d` exists already.
/// 7. [`Refusal::ValenceTooLow`]: `a` or `b` would fall below the valence minimum (an interior
///    vertex of valence 3; in a simple triangle mesh rule 6 already catches it).
///
/// ```
/// use zipmesh_kernel::{ops::{tri, Refusal}, Dart, Map};
/// let map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
/// assert_eq!(tri::can_flip_edge(&map, Dart::new(0)), Ok(()));
/// assert_eq!(tri::can_flip_edge(&map, Dart::new(2)), Err(Refusal::Boundary));
/// ```
pub fn can_flip_edge(map: &Map, h: Dart) -> Result<(), Refusal> {
    plan(map, h).map(|_| ())
}

/// Flips the edge of `h`: triangles `(a, b, c)` and `(b, a, d)` become `(d, c, a)` and
/// `(c, d, b)`, and `h` now runs from `d` to `c` (a quarter turn counter-clockwise).
///
/// ```text
///         c                 c
///        / \               /|\
///       /   \             / | \
///      a-h->-b    ==>    a  h  b
///       \   /             \ ^ /
///        \ /               \|/
///         d                 d
/// ```
/// V, E and F do not change; `a` and `b` lose one valence, `c` and `d` gain one; no other
/// vertex changes. Face `face(h)` becomes `(d, c, a)` and `face(twin h)` becomes `(c, d, b)`;
/// every handle stays valid. Refusals: see [`can_flip_edge`]; on refusal the map is unchanged.
/// Flipping the same dart twice gives back the map up to the names of `h` and `twin(h)`;
/// [`EdgeFlip::undo`] restores it exactly. O(valence of `c`).
///
/// ```
/// use zipmesh_kernel::{ops::tri, Dart, Map, Vert};
/// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
/// let before = map.clone();
/// let rec = tri::flip_edge(&mut map, Dart::new(0)).unwrap();
/// assert_eq!(map.valence(Vert::new(0)), 2);
/// assert_eq!(map.valence(Vert::new(2)), 3);
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn flip_edge(map: &mut Map, h: Dart) -> Result<EdgeFlip, Refusal> {
    let ([h, h1, h2, t, t1, t2], [f0, f1]) = plan(map, h)?;
    let (a, b, c, d) = (map.origin(h), map.origin(t), map.origin(h2), map.origin(t2));
    let old = [
        map.vertex_dart(a),
        map.vertex_dart(b),
        map.face_dart(f0),
        map.face_dart(f1),
    ];
    rewire(map, [h, h2, t1], d, f0, 2);
    rewire(map, [t, t2, h1], c, f1, 2);
    // a and b lose h and t; their records must name a dart they keep. h and t are interior,
    // so a boundary record is never one of them.
    if old[0] == h {
        map.set_vertex_dart(a, t1);
    }
    if old[1] == t {
        map.set_vertex_dart(b, h1);
    }
    if old[2] == h1 {
        map.set_face_dart(f0, h);
    }
    if old[3] == t1 {
        map.set_face_dart(f1, t);
    }
    Ok(EdgeFlip {
        dart: h,
        old,
        ends: [d, c],
    })
}

/// Makes `x = [x0, x1, x2]` the triangle `x0 -> x1 -> x2` of face `f`, with `x0` leaving `o`;
/// `x[joins]` is the one dart that comes from the other face (the others are in `f`).
#[inline]
fn rewire(map: &mut Map, x: [Dart; 3], o: Vert, f: impl Into<Option<Face>>, joins: usize) {
    map.set_next(x[0], x[1]);
    map.set_next(x[1], x[2]);
    map.set_next(x[2], x[0]);
    map.set_origin(x[0], o);
    map.set_face(x[joins], f);
}

/// The six darts `[h, h1, h2, t, t1, t2]` of the two triangles and their faces, if the flip
/// applies.
fn plan(map: &Map, h: Dart) -> Result<([Dart; 6], [Face; 2]), Refusal> {
    if !map.is_live_dart(h) {
        return Err(Refusal::DeadHandle);
    }
    let t = h.twin();
    let (Some(f0), Some(f1)) = (map.face(h), map.face(t)) else {
        return Err(Refusal::Boundary);
    };
    // Both faces exist: the sides' degrees, then their corners (the order `sides` checks).
    let (l, r) = (triangle(map, h)?, triangle(map, t)?);
    if !distinct_corners(map, l) || !distinct_corners(map, r) {
        return Err(Refusal::DegenerateTriangle);
    }
    let (c, d) = (map.origin(l[2]), map.origin(r[2]));
    if c == d {
        return Err(Refusal::Loop);
    }
    if joined(map, l[2], d) {
        return Err(Refusal::MultiEdge);
    }
    for x in [h, t] {
        let boundary = map.is_boundary_vertex(map.origin(x));
        if !valence_at_least(map, x, min_valence(boundary) + 1) {
            return Err(Refusal::ValenceTooLow);
        }
    }
    Ok(([h, l[1], l[2], t, r[1], r[2]], [f0, f1]))
}

impl EdgeFlip {
    /// The flipped dart, the argument `h`: it ran from `a` to `b`, it now runs from `d` to
    /// `c`.
    ///
    /// ```
    /// use zipmesh_kernel::{ops::tri, Dart, Map};
    /// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
    /// assert_eq!(tri::flip_edge(&mut map, Dart::new(0)).unwrap().dart(), Dart::new(0));
    /// ```
    pub fn dart(&self) -> Dart {
        self.dart
    }

    /// Undoes the flip: the map becomes equal (`==`) to the one before, provided it has not
    /// been changed since (other records undone in reverse order are fine).
    ///
    /// Returns [`Refusal::StaleRecord`] and changes nothing when the two triangles at the
    /// record's dart are not as the flip left them. Never panics, whatever the map.
    ///
    /// ```
    /// use zipmesh_kernel::{ops::{tri, Refusal}, Dart, Map};
    /// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
    /// let before = map.clone();
    /// let rec = tri::flip_edge(&mut map, Dart::new(0)).unwrap();
    /// assert_eq!(rec.undo(&mut Map::new()), Err(Refusal::StaleRecord));
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.guard(map).result()?;
        let [h, h1, h2, t, t1, t2] = self.darts(map);
        let (f0, f1) = (map.face(h), map.face(t));
        let (a, b) = (map.origin(t1), map.origin(h1));
        rewire(map, [h, h1, h2], a, f0, 1);
        rewire(map, [t, t1, t2], b, f1, 1);
        let [va, vb, fa, fb] = self.old;
        map.set_vertex_dart(a, va);
        map.set_vertex_dart(b, vb);
        map.set_face_dart(f0, fa);
        map.set_face_dart(f1, fb);
        Ok(())
    }

    /// The darts `[h, h1, h2, t, t1, t2]` of the flipped pair, read as the flip left them
    /// (the triangles `h -> h2 -> t1` and `t -> t2 -> h1`).
    fn darts(&self, map: &Map) -> [Dart; 6] {
        let h = self.dart;
        let t = h.twin();
        let (h2, t2) = (map.next(h), map.next(t));
        let (t1, h1) = (map.next(h2), map.next(t2));
        [h, h1, h2, t, t1, t2]
    }

    /// The staleness checks of [`EdgeFlip::undo`], in order: the two triangles are as the
    /// flip left them, and the old records name darts of their elements after the undo (a
    /// vertex record a dart of its vertex, the boundary one if there is one: the undo changes
    /// no vertex's boundary status; a face record a dart of its triangle).
    pub(super) fn guard(&self, map: &Map) -> Guard {
        let [h, h1, h2, t, t1, t2] = self.darts(map);
        let [va, vb, fa, fb] = self.old;
        let (a, b) = (map.origin(t1), map.origin(h1));
        let leaves = |x: Dart, v: Vert, own: Dart| {
            x == own || (map.is_live_dart(x) && map.origin(x) == v && x.edge() != h.edge())
        };
        let boundary_ok = |x: Dart, v: Vert| map.face(x).is_none() == map.is_boundary_vertex(v);
        Guard::new()
            .check("dart live", || map.is_live_dart(h))
            .check("face of h", || map.face(h).is_some())
            .check("face of twin(h)", || map.face(t).is_some())
            .check("triangle of h", || map.next(t1) == h)
            .check("triangle of twin(h)", || map.next(h1) == t)
            .check("edge once in its triangles", || {
                [h2, t1, t2, h1].iter().all(|x| x.edge() != h.edge())
            })
            .check("ends", || [map.origin(h), map.origin(t)] == self.ends)
            // d and c lose h and t again: their records must not name them.
            .check("h not recorded", || map.vertex_dart(map.origin(h)) != h)
            .check("twin(h) not recorded", || {
                map.vertex_dart(map.origin(t)) != t
            })
            .check("old record of a leaves a", || leaves(va, a, h))
            .check("old record of a on the boundary", || boundary_ok(va, a))
            .check("old record of b leaves b", || leaves(vb, b, t))
            .check("old record of b on the boundary", || boundary_ok(vb, b))
            .check("old record of the face of h", || [h, h1, h2].contains(&fa))
            .check("old record of the face of twin(h)", || {
                [t, t1, t2].contains(&fb)
            })
    }
}

impl Undo for EdgeFlip {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        EdgeFlip::undo(self, map)
    }
}
