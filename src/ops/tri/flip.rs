//! Edge flip: the diagonal of the two triangles at an edge turns a quarter turn.

use super::{distinct_corners, fc, joined, min_valence, nx, on_boundary, org, triangle, Undo};
use crate::map::{Dart, Map, NONE};
use crate::ops::Refusal;

/// Record of an [`flip_edge`]: the flipped dart and what its exact undo needs.
///
/// ```
/// use zipmesh::{ops::tri, Dart, Map};
/// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
/// let rec = tri::flip_edge(&mut map, Dart::new(0)).unwrap();
/// assert_eq!((map.origin(rec.dart()).index(), map.dest(rec.dart()).index()), (3, 2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeFlip {
    /// The flipped dart (see [`EdgeFlip::dart`]).
    dart: Dart,
    /// Before the flip: `vdart[a]`, `vdart[b]`, `fdart[f0]`, `fdart[f1]`.
    old: [u32; 4],
    /// After the flip: the ends `d`, `c` of the dart (tells a flipped edge from a restored one).
    ends: [u32; 2],
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
/// use zipmesh::{ops::{tri, Refusal}, Dart, Map};
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
/// use zipmesh::{ops::tri, Dart, Map, Vert};
/// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
/// let before = map.clone();
/// let rec = tri::flip_edge(&mut map, Dart::new(0)).unwrap();
/// assert_eq!(map.valence(Vert::new(0)), 2);
/// assert_eq!(map.valence(Vert::new(2)), 3);
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn flip_edge(map: &mut Map, h: Dart) -> Result<EdgeFlip, Refusal> {
    let [h, h1, h2, t, t1, t2] = plan(map, h)?;
    let (f0, f1) = (fc(map, h), fc(map, t));
    let (a, b, c, d) = (org(map, h), org(map, t), org(map, h2), org(map, t2));
    let old = [
        map.vdart[a as usize],
        map.vdart[b as usize],
        map.fdart[f0 as usize],
        map.fdart[f1 as usize],
    ];
    map.next[h as usize] = h2;
    map.next[h2 as usize] = t1;
    map.next[t1 as usize] = h;
    map.next[t as usize] = t2;
    map.next[t2 as usize] = h1;
    map.next[h1 as usize] = t;
    map.vert[h as usize] = d;
    map.vert[t as usize] = c;
    map.face[t1 as usize] = f0;
    map.face[h1 as usize] = f1;
    // a and b lose h and t; their records must name a dart they keep. h and t are interior,
    // so a boundary record is never one of them.
    if old[0] == h {
        map.vdart[a as usize] = t1;
    }
    if old[1] == t {
        map.vdart[b as usize] = h1;
    }
    if old[2] == h1 {
        map.fdart[f0 as usize] = h;
    }
    if old[3] == t1 {
        map.fdart[f1 as usize] = t;
    }
    Ok(EdgeFlip {
        dart: Dart(h),
        old,
        ends: [d, c],
    })
}

/// The six darts `[h, h1, h2, t, t1, t2]` of the two triangles, if the flip applies.
fn plan(map: &Map, h: Dart) -> Result<[u32; 6], Refusal> {
    if !map.is_live_dart(h) {
        return Err(Refusal::DeadHandle);
    }
    let h = h.0;
    let t = h ^ 1;
    if fc(map, h) == NONE || fc(map, t) == NONE {
        return Err(Refusal::Boundary);
    }
    let l = triangle(map, h)?;
    let r = triangle(map, t)?;
    if !distinct_corners(map, l) || !distinct_corners(map, r) {
        return Err(Refusal::DegenerateTriangle);
    }
    let (c, d) = (org(map, l[2]), org(map, r[2]));
    if c == d {
        return Err(Refusal::Loop);
    }
    if joined(map, l[2], d) {
        return Err(Refusal::MultiEdge);
    }
    for x in [h, t] {
        let v = org(map, x);
        if !super::valence_at_least(map, x, min_valence(on_boundary(map, v)) + 1) {
            return Err(Refusal::ValenceTooLow);
        }
    }
    Ok([h, l[1], l[2], t, r[1], r[2]])
}

impl EdgeFlip {
    /// The flipped dart, the argument `h`: it ran from `a` to `b`, it now runs from `d` to
    /// `c`.
    ///
    /// ```
    /// use zipmesh::{ops::tri, Dart, Map};
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
    /// use zipmesh::{ops::{tri, Refusal}, Dart, Map};
    /// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
    /// let before = map.clone();
    /// let rec = tri::flip_edge(&mut map, Dart::new(0)).unwrap();
    /// assert_eq!(rec.undo(&mut Map::new()), Err(Refusal::StaleRecord));
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        let h = self.dart.0;
        let t = h ^ 1;
        if !map.is_live_dart(self.dart) {
            return Err(Refusal::StaleRecord);
        }
        let (f0, f1) = (fc(map, h), fc(map, t));
        if f0 == NONE || f1 == NONE {
            return Err(Refusal::StaleRecord);
        }
        let (h2, t2) = (nx(map, h), nx(map, t));
        let (t1, h1) = (nx(map, h2), nx(map, t2));
        if nx(map, t1) != h
            || nx(map, h1) != t
            || [h2, t1, t2, h1].iter().any(|&x| x >> 1 == h >> 1)
            || [org(map, h), org(map, t)] != self.ends
            // d and c lose h and t again: their records must not name them.
            || map.vdart[org(map, h) as usize] == h
            || map.vdart[org(map, t) as usize] == t
        {
            return Err(Refusal::StaleRecord);
        }
        let (a, b) = (org(map, t1), org(map, h1));
        // A restored record names a dart of its vertex, the boundary one if there is one
        // (the undo changes no vertex's boundary status).
        let leaves = |x: u32, v: u32, own: u32| {
            let of_v =
                x == own || (map.is_live_dart(Dart(x)) && org(map, x) == v && x >> 1 != h >> 1);
            of_v && (fc(map, x) == NONE) == on_boundary(map, v)
        };
        let [va, vb, fa, fb] = self.old;
        if !leaves(va, a, h)
            || !leaves(vb, b, t)
            || ![h, h1, h2].contains(&fa)
            || ![t, t1, t2].contains(&fb)
        {
            return Err(Refusal::StaleRecord);
        }
        map.next[h as usize] = h1;
        map.next[h1 as usize] = h2;
        map.next[h2 as usize] = h;
        map.next[t as usize] = t1;
        map.next[t1 as usize] = t2;
        map.next[t2 as usize] = t;
        map.vert[h as usize] = a;
        map.vert[t as usize] = b;
        map.face[h1 as usize] = f0;
        map.face[t1 as usize] = f1;
        map.vdart[a as usize] = va;
        map.vdart[b as usize] = vb;
        map.fdart[f0 as usize] = fa;
        map.fdart[f1 as usize] = fb;
        Ok(())
    }
}

impl Undo for EdgeFlip {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        EdgeFlip::undo(self, map)
    }
}
