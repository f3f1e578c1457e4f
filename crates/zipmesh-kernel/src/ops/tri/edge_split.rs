//! Edge split: a new vertex on an edge, joined to the apexes of its triangles.

use super::{prev_of, sides, Undo};
use crate::map::{Dart, Face, Map, Vert, NONE};
use crate::ops::guard::Guard;
use crate::ops::slots::Slots;
use crate::ops::Refusal;

/// Record of a [`split_edge`]: the new vertex and dart, and what the exact undo needs.
///
/// ```
/// use zipmesh_kernel::{ops::tri, Dart, Map, Vert};
/// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
/// let rec = tri::split_edge(&mut map, Dart::new(0)).unwrap();
/// assert_eq!(map.valence(rec.created()), 4);
/// assert_eq!((map.origin(rec.dart()), map.dest(rec.dart())), (rec.created(), Vert::new(1)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeSplit {
    /// `h`; `h1, h2, t1, t2` of the old triangles (`NONE` for an absent side).
    h: Dart,
    darts: [Dart; 4],
    /// The new vertex `m`, the new edges (`m->b`, then `m->c` and `m->d` where present) and
    /// the new faces (beside `m->c`, then beside `m->d`).
    slots: Slots,
    /// `prev(twin h)` when `twin(h)` is a boundary dart.
    pt: Dart,
    /// Old record of b and of the two faces.
    old_vb: Dart,
    old_fdart: [Dart; 2],
}

/// The darts of the triangles of `h` and of `twin(h)` (absent on a boundary side).
type Sides = [Option<[Dart; 3]>; 2];

/// The triangles at the edge, or why the split does not apply.
fn plan(map: &Map, h: Dart) -> Result<Sides, Refusal> {
    if !map.is_live_dart(h) {
        return Err(Refusal::DeadHandle);
    }
    let [l, r] = sides(map, h)?;
    if let (Some(l), Some(r)) = (l, r) {
        if map.origin(l[2]) == map.origin(r[2]) {
            return Err(Refusal::MultiEdge);
        }
    }
    Ok([l, r])
}

/// Checks whether [`split_edge`] applies to the edge of `h`, without changing anything.
///
/// The rules, in the order checked, with `(a, b, c)` the triangle of `h` and `(b, a, d)`
/// that of `twin(h)` (one may be absent: boundary edges are allowed):
/// 1. [`Refusal::DeadHandle`]: `h` is not live.
/// 2. [`Refusal::WrongDegree`]: a face of the edge is not a triangle.
/// 3. [`Refusal::DegenerateTriangle`]: a triangle has a repeated corner.
/// 4. [`Refusal::MultiEdge`]: `c == d`: the new vertex would have two edges to `c`.
///
/// ```
/// use zipmesh_kernel::{ops::{tri, Refusal}, Dart, Map};
/// let map = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
/// assert_eq!(tri::can_split_edge(&map, Dart::new(0)), Err(Refusal::WrongDegree));
/// ```
pub fn can_split_edge(map: &Map, h: Dart) -> Result<(), Refusal> {
    plan(map, h).map(|_| ())
}

/// Splits the edge of `h` (from `a` to `b`) at a new vertex `m` joined to the apexes.
///
/// ```text
///         c                 c
///        / \               /|\
///       /   \             / | \
///      a-h->-b    ==>    a-h-m->-b     record.dart() runs from m to b
///       \   /             \ | /
///        \ /               \|/
///         d                 d
/// ```
/// Interior edge: V +1, E +3, F +2, `m` has valence 4. Boundary edge: V +1, E +2, F +1, `m`
/// has valence 3. The apexes gain one; `a`, `b` and every other vertex keep their valence.
/// `h` now runs from `a` to `m` and keeps its faces; the face of `twin(h)` (now `m -> a`)
/// keeps its slot too. Every existing handle stays valid. Refusals: see [`can_split_edge`].
/// The inverse is the collapse of `twin(h)` (`m` into `a`), exactly [`EdgeSplit::undo`].
/// O(1), plus O(d(b)) when the face is on the side of `h` only (finding `prev(twin h)`).
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri, Dart};
/// let mut map = gen::random_triangle(100, 0, 0, 4).map;
/// let before = map.clone();
/// let rec = tri::split_edge(&mut map, Dart::new(10)).unwrap();
/// assert_eq!(map.num_vertices(), before.num_vertices() + 1);
/// assert_eq!(map.num_faces(), before.num_faces() + 2);
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn split_edge(map: &mut Map, h: Dart) -> Result<EdgeSplit, Refusal> {
    let [l, r] = plan(map, h)?;
    let t = h.twin();
    let (fl, fr) = (map.face(h), map.face(t));
    let sides = usize::from(l.is_some()) + usize::from(r.is_some());
    let pick = |x: Option<[Dart; 3]>, i: usize| x.map_or(Dart(NONE), |x| x[i]);
    let old_fdart = [fl, fr].map(|f| f.map_or(Dart(NONE), |f| map.face_dart(f)));
    let old_next_h = map.next(h);
    let rec = EdgeSplit {
        h,
        darts: [pick(l, 1), pick(l, 2), pick(r, 1), pick(r, 2)],
        pt: if r.is_none() {
            prev_of(map, t)
        } else {
            Dart(NONE)
        },
        old_vb: map.vertex_dart(map.origin(t)),
        old_fdart,
        slots: Slots::alloc(map, 1 + sides, sides),
    };
    let (m, n, b) = (rec.created(), rec.dart(), map.origin(t));
    map.set_origin(t, m);
    if let (Some([_, h1, h2]), Some(g), Some(l2)) = (l, rec.spoke(0), rec.new_face(0)) {
        // (a, m, c) keeps the face of h; (m, b, c) is new.
        let c = map.origin(h2);
        map.set_next(h, g);
        map.set_dart(g, h2, m, fl);
        map.set_dart(n, h1, m, Some(l2));
        map.set_dart(h1, g.twin(), b, Some(l2));
        map.set_dart(g.twin(), n, c, Some(l2));
        map.set_face_dart(Some(l2), n);
        if old_fdart[0] == h1 {
            map.set_face_dart(fl, h);
        }
    } else {
        map.set_dart(n, old_next_h, m, None);
        map.set_next(h, n);
    }
    if let (Some([_, t1, t2]), Some(k), Some(r1)) = (r, rec.spoke(1), rec.new_face(1)) {
        // (m, a, d) keeps the face of twin(h); (b, m, d) is new.
        let d = map.origin(t2);
        map.set_dart(n.twin(), k, b, Some(r1));
        map.set_dart(k, t2, m, Some(r1));
        map.set_dart(t2, n.twin(), d, Some(r1));
        map.set_next(t1, k.twin());
        map.set_dart(k.twin(), t, d, fr);
        map.set_face_dart(Some(r1), n.twin());
        if old_fdart[1] == t2 {
            map.set_face_dart(fr, t);
        }
    } else {
        map.set_dart(n.twin(), t, b, None);
        map.set_next(rec.pt, n.twin());
    }
    // m's boundary dart, if any: n when h is a boundary dart, twin(h) when that one is.
    map.set_vertex_dart(m, if r.is_none() { t } else { n });
    if rec.old_vb == t {
        map.set_vertex_dart(b, n.twin());
    }
    Ok(rec)
}

impl EdgeSplit {
    /// The new vertex `m` on the edge.
    ///
    /// ```
    /// use zipmesh_kernel::{ops::tri, Dart, Map};
    /// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
    /// let rec = tri::split_edge(&mut map, Dart::new(0)).unwrap();
    /// assert_eq!(map.dest(Dart::new(0)), rec.created());
    /// ```
    pub fn created(&self) -> Vert {
        self.slots.vert()
    }

    /// The new dart from `m` to `b` (the argument `h` now runs from `a` to `m`).
    ///
    /// ```
    /// use zipmesh_kernel::{ops::tri, Dart, Map, Vert};
    /// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
    /// let rec = tri::split_edge(&mut map, Dart::new(0)).unwrap();
    /// assert_eq!(map.dest(rec.dart()), Vert::new(1));
    /// ```
    pub fn dart(&self) -> Dart {
        self.slots.edge(0)
    }

    /// Undoes the split: the map becomes equal (`==`) to the one before, provided it has not
    /// been changed since (other records undone in reverse order are fine).
    ///
    /// Returns [`Refusal::StaleRecord`] and changes nothing when the new vertex and its
    /// faces are not as the split left them. Never panics, whatever the map.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::{tri, Refusal}, Dart, Map};
    /// let mut map = gen::random_triangle(100, 0, 1, 4).map;
    /// let before = map.clone();
    /// let rec = tri::split_edge(&mut map, Dart::new(3)).unwrap();
    /// assert_eq!(rec.undo(&mut Map::new()), Err(Refusal::StaleRecord));
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.guard(map).result()?;
        let (h, n) = (self.h, self.dart());
        let t = h.twin();
        let [h1, h2, t1, t2] = self.darts;
        let b = map.origin(n.twin());
        let (fl, fr) = (map.face(h), map.face(t));
        if self.has_l() {
            map.set_next(h, h1);
            map.set_next(h1, h2);
            map.set_face(h1, fl);
            map.set_face_dart(fl, self.old_fdart[0]);
        } else {
            map.set_next(h, map.next(n));
        }
        if self.has_r() {
            map.set_next(t1, t2);
            map.set_next(t2, t);
            map.set_face(t2, fr);
            map.set_face_dart(fr, self.old_fdart[1]);
        } else {
            map.set_next(self.pt, t);
        }
        map.set_origin(t, b);
        map.set_vertex_dart(b, self.old_vb);
        self.slots.release(map);
        Ok(())
    }

    fn has_l(&self) -> bool {
        self.darts[0].0 != NONE
    }

    fn has_r(&self) -> bool {
        self.darts[2].0 != NONE
    }

    /// The new spoke `m->c` (`side` 0) or `m->d` (`side` 1), if that side has a triangle.
    fn spoke(&self, side: usize) -> Option<Dart> {
        match side {
            0 => self.has_l().then(|| self.slots.edge(1)),
            _ => self
                .has_r()
                .then(|| self.slots.edge(1 + usize::from(self.has_l()))),
        }
    }

    /// The new face beside `m->c` (`side` 0) or `m->d` (`side` 1), if that side has one.
    fn new_face(&self, side: usize) -> Option<Face> {
        match side {
            0 => self.has_l().then(|| self.slots.face(0)),
            _ => self
                .has_r()
                .then(|| self.slots.face(usize::from(self.has_l()))),
        }
    }

    /// The staleness checks of [`EdgeSplit::undo`], in order: the map is as the split left
    /// it as far as the undo depends on it, which also makes every slot it writes live.
    pub(super) fn guard(&self, map: &Map) -> Guard {
        let (h, n, m) = (self.h, self.dart(), self.created());
        let t = h.twin();
        let live = |x: Dart| map.is_live_dart(x);
        Guard::new()
            // An edge without a triangle on either side splits, but is never undone (as
            // before the records had accessors): kept so.
            .check("a side has a triangle", || self.has_l() || self.has_r())
            .check("darts live", || live(h) && live(n) && live(self.old_vb))
            // n is live, so its origin is a live vertex: m needs no range check.
            .check("m is the origin of n and twin(h)", || {
                map.origin(n) == m && map.origin(t) == m
            })
            .check("left triangles", || self.left_fits(map))
            .check("right triangles", || self.right_fits(map))
            .check("old records", || self.records_fit(map))
            .check("spokes not recorded", || {
                let free = |s: Option<Dart>| {
                    s.is_none_or(|s| map.vertex_dart(map.origin(s.twin())) != s.twin())
                };
                free(self.spoke(0)) && free(self.spoke(1))
            })
            .check("slots releasable", || self.slots.releasable(map))
    }

    /// The side of `h`: the triangles `(a, m, c)` and `(m, b, c)` as the split made them, or
    /// `h -> n` on the boundary loop.
    fn left_fits(&self, map: &Map) -> bool {
        let (h, n) = (self.h, self.dart());
        let [h1, h2, ..] = self.darts;
        match (self.spoke(0), self.new_face(0)) {
            (Some(g), Some(l2)) => {
                map.is_live_dart(h1)
                    && map.is_live_dart(h2)
                    && map.is_live_dart(g)
                    && map.next(h) == g
                    && map.next(g) == h2
                    && map.next(n) == h1
                    && map.next(h1) == g.twin()
                    && map.face(h).is_some()
                    && map.face(n) == Some(l2)
            }
            _ => map.face(h).is_none() && map.next(h) == n,
        }
    }

    /// The side of `twin(h)`, as [`EdgeSplit::left_fits`].
    fn right_fits(&self, map: &Map) -> bool {
        let (t, on) = (self.h.twin(), self.dart().twin());
        let [_, _, t1, t2] = self.darts;
        match (self.spoke(1), self.new_face(1)) {
            (Some(k), Some(r1)) => {
                map.is_live_dart(t1)
                    && map.is_live_dart(t2)
                    && map.is_live_dart(k)
                    && map.next(t) == t1
                    && map.next(t1) == k.twin()
                    && map.next(k) == t2
                    && map.next(t2) == on
                    && map.face(t).is_some()
                    && map.face(k) == Some(r1)
            }
            _ => map.is_live_dart(self.pt) && map.face(t).is_none() && map.next(self.pt) == on,
        }
    }

    /// The restored records name darts of their element: b's a dart leaving b (its boundary
    /// one if any; the undo changes no boundary status), the faces' a dart of their triangle.
    fn records_fit(&self, map: &Map) -> bool {
        let (h, n) = (self.h, self.dart());
        let t = h.twin();
        let [h1, h2, t1, t2] = self.darts;
        let b = map.origin(n.twin());
        let vb = self.old_vb;
        let vb_ok = (vb == t || (map.origin(vb) == b && vb != n.twin()))
            && map.face(vb).is_none() == map.is_boundary_vertex(b);
        let fl_ok = !self.has_l() || [h, h1, h2].contains(&self.old_fdart[0]);
        let fr_ok = !self.has_r() || [t, t1, t2].contains(&self.old_fdart[1]);
        vb_ok && fl_ok && fr_ok
    }
}

impl Undo for EdgeSplit {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        EdgeSplit::undo(self, map)
    }
}
