//! Edge split: a new vertex on an edge, joined to the apexes of its triangles.

use super::{
    distinct_corners, fc, fresh_tail, nx, org, prev_of, release_edge, release_face, release_vert,
    triangle, Lens, Undo,
};
use crate::map::{Dart, Map, Vert, NONE};
use crate::ops::Refusal;

/// Record of a [`split_edge`]: the new vertex and dart, and what the exact undo needs.
///
/// ```
/// use zipmesh::{ops::tri, Dart, Map, Vert};
/// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
/// let rec = tri::split_edge(&mut map, Dart::new(0)).unwrap();
/// assert_eq!(map.valence(rec.created()), 4);
/// assert_eq!((map.origin(rec.dart()), map.dest(rec.dart())), (rec.created(), Vert::new(1)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeSplit {
    /// The new vertex and dart (see [`EdgeSplit::created`], [`EdgeSplit::dart`]).
    vertex: Vert,
    dart: Dart,
    /// `h`; `h1, h2, t1, t2` of the old triangles (`NONE` for an absent side).
    h: u32,
    darts: [u32; 4],
    /// New spokes `m->c`, `m->d` (`NONE` if absent) and new faces.
    spokes: [u32; 2],
    new_faces: [u32; 2],
    /// `prev(twin h)` when `twin(h)` is a boundary dart.
    pt: u32,
    /// Old record of b and of the two faces.
    old_vb: u32,
    old_fdart: [u32; 2],
    lens: Lens,
}

/// `h` and the darts of the triangles of `h` and of `twin(h)` (absent on a boundary side).
type Sides = (u32, Option<[u32; 3]>, Option<[u32; 3]>);

/// The triangles at the edge, or why the split does not apply.
fn plan(map: &Map, h: Dart) -> Result<Sides, Refusal> {
    if !map.is_live_dart(h) {
        return Err(Refusal::DeadHandle);
    }
    let h = h.0;
    let side = |x: u32| {
        if fc(map, x) == NONE {
            Ok(None)
        } else {
            triangle(map, x).map(Some)
        }
    };
    let l = side(h)?;
    let r = side(h ^ 1)?;
    if l.is_some_and(|x| !distinct_corners(map, x)) || r.is_some_and(|x| !distinct_corners(map, x))
    {
        return Err(Refusal::DegenerateTriangle);
    }
    if let (Some(l), Some(r)) = (l, r) {
        if org(map, l[2]) == org(map, r[2]) {
            return Err(Refusal::MultiEdge);
        }
    }
    Ok((h, l, r))
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
/// use zipmesh::{ops::{tri, Refusal}, Dart, Map};
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
/// use zipmesh::{gen, ops::tri, Dart};
/// let mut map = gen::random_triangle(100, 0, 0, 4).map;
/// let before = map.clone();
/// let rec = tri::split_edge(&mut map, Dart::new(10)).unwrap();
/// assert_eq!(map.num_vertices(), before.num_vertices() + 1);
/// assert_eq!(map.num_faces(), before.num_faces() + 2);
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn split_edge(map: &mut Map, h: Dart) -> Result<EdgeSplit, Refusal> {
    let (h, l, r) = plan(map, h)?;
    let t = h ^ 1;
    let lens = Lens::of(map);
    let b = org(map, t);
    let (fl, fr) = (fc(map, h), fc(map, t));
    let pt = if r.is_none() { prev_of(map, t) } else { NONE };
    let old_next_h = nx(map, h);
    let old_vb = map.vdart[b as usize];
    let fd = |map: &Map, f: u32| {
        if f == NONE {
            NONE
        } else {
            map.fdart[f as usize]
        }
    };
    let old_fdart = [fd(map, fl), fd(map, fr)];

    let m = map.alloc_vert().0;
    let n = map.alloc_edge().0; // n: m -> b
    let g = if l.is_some() {
        map.alloc_edge().0
    } else {
        NONE
    }; // g: m -> c
    let k = if r.is_some() {
        map.alloc_edge().0
    } else {
        NONE
    }; // k: m -> d
    let l2 = if l.is_some() {
        map.alloc_face().0
    } else {
        NONE
    };
    let r1 = if r.is_some() {
        map.alloc_face().0
    } else {
        NONE
    };
    let on = n ^ 1;
    let set = |map: &mut Map, x: u32, next: u32, vert: u32, face: u32| {
        map.next[x as usize] = next;
        map.vert[x as usize] = vert;
        map.face[x as usize] = face;
    };
    map.vert[t as usize] = m;
    if let Some([_, h1, h2]) = l {
        // (a, m, c) keeps the face of h; (m, b, c) is new.
        let c = org(map, h2);
        map.next[h as usize] = g;
        set(map, g, h2, m, fl);
        set(map, n, h1, m, l2);
        set(map, h1, g ^ 1, b, l2);
        set(map, g ^ 1, n, c, l2);
        map.fdart[l2 as usize] = n;
        if old_fdart[0] == h1 {
            map.fdart[fl as usize] = h;
        }
    } else {
        set(map, n, old_next_h, m, NONE);
        map.next[h as usize] = n;
    }
    if let Some([_, t1, t2]) = r {
        // (m, a, d) keeps the face of twin(h); (b, m, d) is new.
        let d = org(map, t2);
        set(map, on, k, b, r1);
        set(map, k, t2, m, r1);
        set(map, t2, on, d, r1);
        map.next[t1 as usize] = k ^ 1;
        set(map, k ^ 1, t, d, fr);
        map.fdart[r1 as usize] = on;
        if old_fdart[1] == t2 {
            map.fdart[fr as usize] = t;
        }
    } else {
        set(map, on, t, b, NONE);
        map.next[pt as usize] = on;
    }
    // m's boundary dart, if any: n when h is a boundary dart, twin(h) when that one is.
    map.vdart[m as usize] = if r.is_none() { t } else { n };
    if old_vb == t {
        map.vdart[b as usize] = on;
    }
    Ok(EdgeSplit {
        vertex: Vert(m),
        dart: Dart(n),
        h,
        darts: [
            l.map_or(NONE, |x| x[1]),
            l.map_or(NONE, |x| x[2]),
            r.map_or(NONE, |x| x[1]),
            r.map_or(NONE, |x| x[2]),
        ],
        spokes: [g, k],
        new_faces: [l2, r1],
        pt,
        old_vb,
        old_fdart,
        lens,
    })
}

impl EdgeSplit {
    /// The new vertex `m` on the edge.
    ///
    /// ```
    /// use zipmesh::{ops::tri, Dart, Map};
    /// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
    /// let rec = tri::split_edge(&mut map, Dart::new(0)).unwrap();
    /// assert_eq!(map.dest(Dart::new(0)), rec.created());
    /// ```
    pub fn created(&self) -> Vert {
        self.vertex
    }

    /// The new dart from `m` to `b` (the argument `h` now runs from `a` to `m`).
    ///
    /// ```
    /// use zipmesh::{ops::tri, Dart, Map, Vert};
    /// let mut map = Map::from_polygons(4, &[[0u32, 1, 2], [1, 0, 3]]).unwrap();
    /// let rec = tri::split_edge(&mut map, Dart::new(0)).unwrap();
    /// assert_eq!(map.dest(rec.dart()), Vert::new(1));
    /// ```
    pub fn dart(&self) -> Dart {
        self.dart
    }

    /// Undoes the split: the map becomes equal (`==`) to the one before, provided it has not
    /// been changed since (other records undone in reverse order are fine).
    ///
    /// Returns [`Refusal::StaleRecord`] and changes nothing when the new vertex and its
    /// faces are not as the split left them. Never panics, whatever the map.
    ///
    /// ```
    /// use zipmesh::{gen, ops::{tri, Refusal}, Dart, Map};
    /// let mut map = gen::random_triangle(100, 0, 1, 4).map;
    /// let before = map.clone();
    /// let rec = tri::split_edge(&mut map, Dart::new(3)).unwrap();
    /// assert_eq!(rec.undo(&mut Map::new()), Err(Refusal::StaleRecord));
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        if !self.fits(map) {
            return Err(Refusal::StaleRecord);
        }
        let (h, n) = (self.h, self.dart.0);
        let t = h ^ 1;
        let on = n ^ 1;
        let [h1, h2, t1, t2] = self.darts;
        let [g, k] = self.spokes;
        let [l2, r1] = self.new_faces;
        let b = org(map, on);
        let (fl, fr) = (fc(map, h), fc(map, t));
        if h1 != NONE {
            map.next[h as usize] = h1;
            map.next[h1 as usize] = h2;
            map.face[h1 as usize] = fl;
            map.fdart[fl as usize] = self.old_fdart[0];
        } else {
            map.next[h as usize] = nx(map, n);
        }
        if t1 != NONE {
            map.next[t1 as usize] = t2;
            map.next[t2 as usize] = t;
            map.face[t2 as usize] = fr;
            map.fdart[fr as usize] = self.old_fdart[1];
        } else {
            map.next[self.pt as usize] = t;
        }
        map.vert[t as usize] = b;
        map.vdart[b as usize] = self.old_vb;
        // Reverse of the allocation order: vertex, edges n, g, k, faces L2, R1.
        let lens = self.lens;
        for f in [r1, l2] {
            if f != NONE {
                release_face(map, f, lens);
            }
        }
        for e in [k, g, n] {
            if e != NONE {
                release_edge(map, e, lens);
            }
        }
        release_vert(map, self.vertex.0, lens);
        Ok(())
    }

    /// Whether the map is as the split left it, as far as the undo depends on it; also makes
    /// every index the undo uses in range.
    fn fits(&self, map: &Map) -> bool {
        let nd = map.next.len();
        let live = |x: u32| (x as usize) < nd && map.next[x as usize] != NONE;
        let (h, n, m) = (self.h, self.dart.0, self.vertex.0);
        let t = h ^ 1;
        let [h1, h2, t1, t2] = self.darts;
        let [g, k] = self.spokes;
        let [l2, r1] = self.new_faces;
        let has_l = h1 != NONE;
        let has_r = t1 != NONE;
        if !(has_l || has_r)
            || !live(h)
            || !live(n)
            || (m as usize) >= map.vdart.len()
            || org(map, n) != m
            || org(map, t) != m
            || (has_l != (g != NONE && l2 != NONE && live(h2) && live(g)))
            || (has_r != (k != NONE && r1 != NONE && live(t2) && live(k)))
            || (!has_r && !live(self.pt))
            || !live(self.old_vb)
        {
            return false;
        }
        let (fl, fr) = (fc(map, h), fc(map, t));
        let shape_l = if has_l {
            live(h1)
                && nx(map, h) == g
                && nx(map, g) == h2
                && nx(map, n) == h1
                && nx(map, h1) == g ^ 1
                && fl != NONE
                && fc(map, n) == l2
                && (self.old_fdart[0] as usize) < nd
        } else {
            fl == NONE && nx(map, h) == n
        };
        let shape_r = if has_r {
            live(t1)
                && nx(map, t) == t1
                && nx(map, t1) == k ^ 1
                && nx(map, k) == t2
                && nx(map, t2) == n ^ 1
                && fr != NONE
                && fc(map, k) == r1
                && (self.old_fdart[1] as usize) < nd
        } else {
            fr == NONE && nx(map, self.pt) == n ^ 1
        };
        let mut edges = [n >> 1, NONE, NONE];
        let mut ne = 1;
        for e in [g, k] {
            if e != NONE {
                edges[ne] = e >> 1;
                ne += 1;
            }
        }
        let mut faces = [NONE; 2];
        let mut nf = 0;
        for f in [l2, r1] {
            if f != NONE {
                faces[nf] = f;
                nf += 1;
            }
        }
        // The restored records name darts of their element (b's boundary one if any; the
        // undo changes no boundary status).
        let b = org(map, n ^ 1);
        let vb = self.old_vb;
        let vb_ok = (vb == t || (org(map, vb) == b && vb != n ^ 1))
            && (fc(map, vb) == NONE) == super::on_boundary(map, b);
        let fl_ok = !has_l || [h, h1, h2].contains(&self.old_fdart[0]);
        let fr_ok = !has_r || [t, t1, t2].contains(&self.old_fdart[1]);
        // The apexes lose their spokes again: their records must not name them.
        let spokes_free = (!has_l || map.vdart[org(map, g ^ 1) as usize] != g ^ 1)
            && (!has_r || map.vdart[org(map, k ^ 1) as usize] != k ^ 1);
        vb_ok
            && spokes_free
            && fl_ok
            && fr_ok
            && shape_l
            && shape_r
            && fresh_tail(&[m], self.lens.verts, map.vdart.len())
            && fresh_tail(&edges[..ne], self.lens.darts / 2, nd / 2)
            && fresh_tail(&faces[..nf], self.lens.faces, map.fdart.len())
    }
}

impl Undo for EdgeSplit {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        EdgeSplit::undo(self, map)
    }
}
