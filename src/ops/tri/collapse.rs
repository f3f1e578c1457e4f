//! Edge collapse with the link condition, and vertex split, its exact inverse.
//!
//! Names used throughout (faces counter-clockwise):
//! ```text
//!              c                       the collapsed dart h runs v -> u; t = twin(h)
//!            /   \                     L = (v, u, c): h, h1 = u->c, h2 = c->v
//!          h2  L  h1                   R = (u, v, d): t, t1 = v->d, t2 = d->u
//!          /       \                   "moved" darts: the other darts of v, which
//!    ... v ---h---> u ...              become darts of u
//!          \       /
//!          t1  R  t2
//!            \   /
//!              d
//! ```
//! A boundary edge has only one of L and R.

use super::{
    distinct_corners, fc, fresh_tail, gather, joined, min_valence, nx, on_boundary, org, prev_of,
    release_edge, release_face, release_vert, rot, triangle, valence_at_least, Lens, Undo, SMALL,
};
use crate::map::{Dart, Map, Vert, NONE};
use crate::ops::Refusal;

/// The darts and vertices of a collapse, found by [`plan`].
#[derive(Clone, Copy, Debug)]
struct Plan {
    h: u32,
    /// `h1`, `h2` of L, or `NONE` when `h` is a boundary dart.
    h1: u32,
    h2: u32,
    /// `t1`, `t2` of R, or `NONE` when `twin(h)` is a boundary dart.
    t1: u32,
    t2: u32,
    u: u32,
    v: u32,
    /// Apexes of L and R (`NONE` when absent).
    c: u32,
    d: u32,
    /// The moved darts: `count` darts clockwise from `first`; `last` is the dart just
    /// before `oh2` (or before `h` when there is no L) in the rotation of `v`.
    first: u32,
    count: u32,
    last: u32,
}

/// Finds the collapse's darts; with `policy`, also applies every rule of [`can_collapse_edge`].
/// Without it (undoing a vertex split) only the rules that keep the map valid apply (proper
/// triangles, not both ends on the boundary of an interior edge, distinct apexes).
fn plan(map: &Map, hd: Dart, policy: bool) -> Result<Plan, Refusal> {
    plan_with(map, hd, policy, SMALL)
}

/// [`plan`] with the limit of neighbours gathered on the stack.
fn plan_with(map: &Map, hd: Dart, policy: bool, small: usize) -> Result<Plan, Refusal> {
    if !map.is_live_dart(hd) {
        return Err(Refusal::DeadHandle);
    }
    let h = hd.0;
    let t = h ^ 1;
    let l = if fc(map, h) != NONE {
        Some(triangle(map, h)?)
    } else {
        None
    };
    let r = if fc(map, t) != NONE {
        Some(triangle(map, t)?)
    } else {
        None
    };
    if l.is_some_and(|x| !distinct_corners(map, x)) || r.is_some_and(|x| !distinct_corners(map, x))
    {
        return Err(Refusal::DegenerateTriangle);
    }
    let (v, u) = (org(map, h), org(map, t));
    let interior = l.is_some() && r.is_some();
    let (bu, bv) = (on_boundary(map, u), on_boundary(map, v));
    // These two rules keep the result a valid map, so they hold even without `policy`.
    if interior && bu && bv {
        return Err(Refusal::Boundary);
    }
    let c = l.map_or(NONE, |x| org(map, x[2]));
    let d = r.map_or(NONE, |x| org(map, x[2]));
    if interior && c == d {
        return Err(Refusal::LinkCondition);
    }
    // The rotation of v clockwise from h: h, [t1], moved darts, [twin(h2)], back to h.
    let start = r.map_or(h, |x| x[1]);
    let stop = l.map_or(h, |x| x[2] ^ 1);
    let first = rot(map, start);
    // The neighbours of u, when u has few; otherwise each candidate's rotation is walked
    // instead of u's, so that a growing u (repeated collapses into it) costs nothing more.
    let near_u = if policy {
        gather(map, t, NONE, small)
    } else {
        None
    };
    let (mut y, mut last, mut count) = (first, start, 0u32);
    while y != stop {
        if count as usize > map.next.len() {
            // Unreachable in a valid map: the rotation of v holds `stop`.
            return Err(Refusal::StaleRecord);
        }
        if policy {
            // Vertex part of the link condition: a neighbour of v other than u, c, d must
            // not be u nor a neighbour of u.
            let x = org(map, y ^ 1);
            let adjacent = match &near_u {
                Some(n) => n.contains(x),
                None => joined(map, y ^ 1, u),
            };
            if x == u || adjacent {
                return Err(Refusal::LinkCondition);
            }
        }
        last = y;
        count += 1;
        y = rot(map, y);
    }
    if policy {
        if let (Some(l), true) = (l, interior) {
            // Edge part: the edge c-d lies in a triangle with u and in one with v, as in a
            // tetrahedron; collapsing would fold two triangles onto each other.
            if third_corner(map, l[1] ^ 1) == d && third_corner(map, l[2] ^ 1) == d {
                return Err(Refusal::LinkCondition);
            }
        }
        let dv = count as usize + 1 + usize::from(l.is_some()) + usize::from(r.is_some());
        let loss = if interior { 4 } else { 3 };
        let need_u = (min_valence(bu || bv) + loss).saturating_sub(dv);
        let enough = match &near_u {
            Some(n) => n.len() >= need_u,
            None => valence_at_least(map, t, need_u),
        };
        if !enough {
            return Err(Refusal::ValenceTooLow);
        }
        for apex in [l.map(|x| x[2]), r.map(|x| x[2])].into_iter().flatten() {
            let need = min_valence(on_boundary(map, org(map, apex))) + 1;
            if !valence_at_least(map, apex, need) {
                return Err(Refusal::ValenceTooLow);
            }
        }
    }
    Ok(Plan {
        h,
        h1: l.map_or(NONE, |x| x[1]),
        h2: l.map_or(NONE, |x| x[2]),
        t1: r.map_or(NONE, |x| x[1]),
        t2: r.map_or(NONE, |x| x[2]),
        u,
        v,
        c,
        d,
        first: if count > 0 { first } else { NONE },
        count,
        last,
    })
}

/// The face of `x` once the planned collapse is applied: h1 takes the face of twin(h2), t2
/// that of twin(t1); every other surviving dart keeps its face.
fn face_after_collapse(map: &Map, p: &Plan, x: u32) -> u32 {
    if x == p.h1 && p.h1 != NONE {
        fc(map, p.h2 ^ 1)
    } else if x == p.t2 && p.t2 != NONE {
        fc(map, p.t1 ^ 1)
    } else {
        fc(map, x)
    }
}

/// The corner opposite the edge of `x` in its face, if that face is a triangle.
fn third_corner(map: &Map, x: u32) -> u32 {
    if fc(map, x) == NONE {
        return NONE;
    }
    triangle(map, x).map_or(NONE, |tr| org(map, tr[2]))
}

/// Record of a [`collapse_edge`]: the kept and removed vertices, and what the exact undo needs.
///
/// ```
/// use zipmesh::{gen, ops::tri, Dart};
/// let mut mesh = gen::random_triangle(200, 1, 0, 5);
/// let h = mesh.map.darts().find(|&d| tri::can_collapse_edge(&mesh.map, d).is_ok()).unwrap();
/// let (v, u) = (mesh.map.origin(h), mesh.map.dest(h));
/// let rec = tri::collapse_edge(&mut mesh.map, h).unwrap();
/// assert_eq!((rec.kept(), rec.removed()), (u, v));
/// assert!(!mesh.map.is_live_vertex(v));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeCollapse {
    /// `dest(h)` and `origin(h)` (see [`EdgeCollapse::kept`], [`EdgeCollapse::removed`]).
    kept: Vert,
    removed: Vert,
    /// `h, h1, h2, t1, t2` before the collapse (`NONE` for an absent side).
    darts: [u32; 5],
    /// Apexes c and d.
    apex: [u32; 2],
    /// Faces L, R, and X, Z: the faces of `twin(h2)` and `twin(t1)` before.
    faces: [u32; 4],
    /// Every `next` entry rewritten in a surviving dart: (dart, old, new).
    writes: [(u32, u32, u32); 5],
    n_writes: u8,
    /// Old `next` of the removed darts `h, t, h2, twin h2, t1, twin t1`.
    dead_next: [u32; 6],
    /// The moved darts: `count` clockwise from `first` in the restored rotation of v.
    first: u32,
    count: u32,
    /// Old vertex records of u, v, c, d and face records of L, R, X, Z.
    old_vdart: [u32; 4],
    old_fdart: [u32; 4],
}

/// Checks whether [`collapse_edge`] applies to the dart `h`, without changing anything.
///
/// `h` runs from the vertex `v` that is removed to the vertex `u` that is kept. With `L =
/// (v, u, c)` the triangle of `h` and `R = (u, v, d)` that of `twin(h)` (one of them absent
/// on a boundary edge), the rules in the order checked:
/// 1. [`Refusal::DeadHandle`]: `h` is not live.
/// 2. [`Refusal::WrongDegree`]: L or R is not a triangle.
/// 3. [`Refusal::DegenerateTriangle`]: L or R has a repeated corner (this covers loops).
/// 4. [`Refusal::Boundary`]: the edge is interior but `u` and `v` are both on the boundary:
///    the merged vertex would touch the boundary twice (a pinch), or the edges `u-c` and
///    `v-c` would merge into an edge without a face.
/// 5. [`Refusal::LinkCondition`], the link condition `N(u) ∩ N(v) = {c, d}` (`{c}` on a
///    boundary edge), counted in darts so that multi-edges and loops count as well:
///    `c == d`; or a dart of `v` other than `h`, `v->c`, `v->d` ends at `u` or at a
///    neighbour of `u` (checked in clockwise order from `h`); or, for an interior edge, the
///    triangles across `u-c` and `v-c` both have `d` as third corner (the edge `c-d` is in
///    both links: a tetrahedron, which would fold into two triangles on three vertices).
/// 6. [`Refusal::ValenceTooLow`]: `u` would end below the minimum (3 inside, 2 on the
///    boundary; `u` ends on the boundary if `u` or `v` was), then `c`, then `d`.
///
/// Cost: O(d(v) + the valences of v's other neighbours) for the link condition; `u`'s
/// rotation is walked only as far as the valence rule needs (at most 4 darts).
///
/// ```
/// use zipmesh::{ops::{tri, Refusal}, Dart, Map};
/// // A tetrahedron: every collapse fails the link condition.
/// let tet = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]).unwrap();
/// assert!(tet.darts().all(|d| tri::can_collapse_edge(&tet, d) == Err(Refusal::LinkCondition)));
/// ```
pub fn can_collapse_edge(map: &Map, h: Dart) -> Result<(), Refusal> {
    plan(map, h, true).map(|_| ())
}

/// Collapses the edge of `h` into its destination: `v = origin(h)` is removed, `u = dest(h)`
/// is kept and receives every other dart of `v`; the triangles L and R disappear and the
/// edge pairs `u-c`, `v-c` and `u-d`, `v-d` each merge into one edge (the one of `u`).
///
/// ```text
///          c                     c
///        /   \                   |
///      /   L   \                 |
///   - v ---h--> u -    ==>   --- u ---
///      \   R   /                 |
///        \   /                   |
///          d                     d
/// ```
/// Interior edge: V -1, E -3, F -2; `d(u)` becomes `d(u) + d(v) - 4`; `c` and `d` lose one.
/// Boundary edge: V -1, E -2, F -1; `d(u)` becomes `d(u) + d(v) - 3`; the apex loses one.
/// Every other vertex keeps its valence. Handles of `u`, of the edges `u-c`, `u-d`, of every
/// other element stay valid; `v`, L, R, the edge `u-v` and the edges `v-c`, `v-d` are freed.
/// Refusals: see [`can_collapse_edge`]; on refusal the map is unchanged. The inverse is
/// [`split_vertex`] at `u`'s darts to `c` and `d` (interior edges) or, exactly,
/// [`EdgeCollapse::undo`].
///
/// ```
/// use zipmesh::{gen, invariants::Counts, ops::tri};
/// let mut map = gen::random_triangle(300, 1, 0, 1).map;
/// let before = map.clone();
/// let h = map.darts().find(|&d| tri::can_collapse_edge(&map, d).is_ok()).unwrap();
/// let rec = tri::collapse_edge(&mut map, h).unwrap();
/// assert!(map.check().is_ok());
/// assert_eq!(Counts::of(&map).genus, 1);
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn collapse_edge(map: &mut Map, h: Dart) -> Result<EdgeCollapse, Refusal> {
    let p = plan(map, h, true)?;
    Ok(apply(map, &p, None))
}

/// Applies a planned collapse. With `release`, the removed slots are un-allocated (undo of a
/// vertex split that allocated them after `release`) instead of freed.
fn apply(map: &mut Map, p: &Plan, release: Option<Lens>) -> EdgeCollapse {
    let (h, t) = (p.h, p.h ^ 1);
    let has_l = p.h1 != NONE;
    let has_r = p.t1 != NONE;
    let oh2 = if has_l { p.h2 ^ 1 } else { NONE };
    let ot1 = if has_r { p.t1 ^ 1 } else { NONE };
    // A boundary dart of the edge vanishes from its loop without replacement.
    let vanish = if !has_l {
        h
    } else if !has_r {
        t
    } else {
        NONE
    };
    // h1 takes the place of twin(h2), t2 that of twin(t1).
    let repl = |x: u32| {
        if x == oh2 && has_l {
            p.h1
        } else if x == ot1 && has_r {
            p.t2
        } else {
            x
        }
    };
    // Darts whose successor changes: the predecessors of the replaced and vanishing darts,
    // and the replaced darts themselves (their successor goes to the replacement).
    let mut pos = [NONE; 5];
    let mut np = 0;
    let mut push = |x: u32| {
        pos[np] = x;
        np += 1;
    };
    push(p.last ^ 1); // prev(twin h2), or prev(h) when there is no L
    if has_l {
        push(oh2);
    }
    if has_r {
        push(prev_of(map, ot1));
        push(ot1);
    }
    if vanish == t {
        push(prev_of(map, t));
    }
    let mut writes = [(NONE, NONE, NONE); 5];
    let mut nw = 0;
    for &y in &pos[..np] {
        if y == vanish {
            continue; // its predecessor is in the list and skips it
        }
        let mut s = nx(map, y);
        if s == vanish {
            s = nx(map, s);
        }
        let cell = repl(y);
        writes[nw] = (cell, nx(map, cell), repl(s));
        nw += 1;
    }
    let dead = [h, t, p.h2, oh2, p.t1, ot1];
    let mut dead_next = [NONE; 6];
    for (k, &x) in dead.iter().enumerate() {
        if x != NONE {
            dead_next[k] = nx(map, x);
        }
    }
    let (fl, fr) = (fc(map, h), fc(map, t));
    let fx = if has_l { fc(map, oh2) } else { NONE };
    let fz = if has_r { fc(map, ot1) } else { NONE };
    let fd = |map: &Map, f: u32| {
        if f == NONE {
            NONE
        } else {
            map.fdart[f as usize]
        }
    };
    let old_fdart = [fd(map, fl), fd(map, fr), fd(map, fx), fd(map, fz)];
    let vd = |map: &Map, v: u32| {
        if v == NONE {
            NONE
        } else {
            map.vdart[v as usize]
        }
    };
    let bv = on_boundary(map, p.v);
    let old_vdart = [vd(map, p.u), vd(map, p.v), vd(map, p.c), vd(map, p.d)];

    // Rewrite. The moved darts first, while the rotation of v is intact.
    let mut y = p.first;
    for _ in 0..p.count {
        map.vert[y as usize] = p.u;
        y = rot(map, y);
    }
    for &(cell, _, new) in &writes[..nw] {
        map.next[cell as usize] = new;
    }
    if has_l {
        map.face[p.h1 as usize] = fx;
    }
    if has_r {
        map.face[p.t2 as usize] = fz;
    }
    // The kept vertex records its boundary dart if it has one: v's when v is on the
    // boundary and L exists (without R, u's own boundary dart t vanishes and v's is
    // next(t)); without L, v's boundary dart h vanishes and u keeps its own.
    let new_u = if has_l && (!has_r || bv) {
        repl(old_vdart[1])
    } else if old_vdart[0] == t {
        p.h1
    } else {
        old_vdart[0]
    };
    map.vdart[p.u as usize] = new_u;
    if has_l && old_vdart[2] == p.h2 {
        map.vdart[p.c as usize] = p.h1 ^ 1;
    }
    if has_r && old_vdart[3] == ot1 {
        map.vdart[p.d as usize] = p.t2;
    }
    if fx != NONE && old_fdart[2] == oh2 {
        map.fdart[fx as usize] = p.h1;
    }
    if fz != NONE && old_fdart[3] == ot1 {
        map.fdart[fz as usize] = p.t2;
    }
    match release {
        None => {
            map.free_edge(Dart(h));
            if has_l {
                map.free_edge(Dart(p.h2));
            }
            if has_r {
                map.free_edge(Dart(p.t1));
            }
            map.free_vert(Vert(p.v));
            if has_l {
                map.free_face(crate::map::Face(fl));
            }
            if has_r {
                map.free_face(crate::map::Face(fr));
            }
        }
        Some(lens) => {
            // Reverse of the split's allocation order: edges h, h2, t1, vertex, faces L, R.
            release_face(map, fr, lens);
            release_face(map, fl, lens);
            release_vert(map, p.v, lens);
            release_edge(map, p.t1, lens);
            release_edge(map, p.h2, lens);
            release_edge(map, h, lens);
        }
    }
    EdgeCollapse {
        kept: Vert(p.u),
        removed: Vert(p.v),
        darts: [h, p.h1, p.h2, p.t1, p.t2],
        apex: [p.c, p.d],
        faces: [fl, fr, fx, fz],
        writes,
        n_writes: nw as u8,
        dead_next,
        first: p.first,
        count: p.count,
        old_vdart,
        old_fdart,
    }
}

impl EdgeCollapse {
    /// The vertex that stays (`dest(h)`); it received every dart of the removed one.
    ///
    /// ```
    /// use zipmesh::{gen, ops::tri};
    /// let mut map = gen::random_triangle(200, 1, 0, 5).map;
    /// let h = map.darts().find(|&d| tri::can_collapse_edge(&map, d).is_ok()).unwrap();
    /// let u = map.dest(h);
    /// assert_eq!(tri::collapse_edge(&mut map, h).unwrap().kept(), u);
    /// ```
    pub fn kept(&self) -> Vert {
        self.kept
    }

    /// The vertex that was removed (`origin(h)`); its slot is free.
    ///
    /// ```
    /// use zipmesh::{gen, ops::tri};
    /// let mut map = gen::random_triangle(200, 1, 0, 5).map;
    /// let h = map.darts().find(|&d| tri::can_collapse_edge(&map, d).is_ok()).unwrap();
    /// let r = tri::collapse_edge(&mut map, h).unwrap();
    /// assert!(!map.is_live_vertex(r.removed()));
    /// ```
    pub fn removed(&self) -> Vert {
        self.removed
    }

    /// Undoes the collapse: the map becomes equal (`==`) to the one before, free lists
    /// included, provided it has not been changed since (other records undone in reverse
    /// order are fine).
    ///
    /// Returns [`Refusal::StaleRecord`] and changes nothing when the freed slots are not on
    /// top of the free lists or a rewritten dart no longer holds what the collapse wrote.
    /// Never panics, whatever the map.
    ///
    /// ```
    /// use zipmesh::{gen, ops::{tri, Refusal}, Map};
    /// let mut map = gen::random_triangle(100, 0, 1, 2).map;
    /// let before = map.clone();
    /// let h = map.darts().find(|&d| tri::can_collapse_edge(&map, d).is_ok()).unwrap();
    /// let rec = tri::collapse_edge(&mut map, h).unwrap();
    /// assert_eq!(rec.undo(&mut Map::new()), Err(Refusal::StaleRecord));
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        if !self.fits(map) {
            return Err(Refusal::StaleRecord);
        }
        let [h, h1, h2, t1, t2] = self.darts;
        let t = h ^ 1;
        let (u, v) = (self.kept.0, self.removed.0);
        let [c, d] = self.apex;
        let [fl, fr, fx, fz] = self.faces;
        let has_l = h1 != NONE;
        let has_r = t1 != NONE;
        // Take the freed slots back, last freed first.
        if has_r {
            map.free_faces.pop();
        }
        if has_l {
            map.free_faces.pop();
        }
        map.free_verts.pop();
        map.free_edges
            .truncate(map.free_edges.len() - 1 - usize::from(has_l) - usize::from(has_r));
        let oh2 = if has_l { h2 ^ 1 } else { NONE };
        let ot1 = if has_r { t1 ^ 1 } else { NONE };
        let dead = [
            (h, v, fl),
            (t, u, fr),
            (h2, c, fl),
            (oh2, v, fx),
            (t1, v, fr),
            (ot1, d, fz),
        ];
        for (k, &(x, o, f)) in dead.iter().enumerate() {
            if x != NONE {
                map.next[x as usize] = self.dead_next[k];
                map.vert[x as usize] = o;
                map.face[x as usize] = f;
            }
        }
        for &(cell, old, _) in self.writes[..self.n_writes as usize].iter().rev() {
            map.next[cell as usize] = old;
        }
        if has_l {
            map.face[h1 as usize] = fl;
        }
        if has_r {
            map.face[t2 as usize] = fr;
        }
        let mut y = self.first;
        for _ in 0..self.count {
            let Some(o) = map.vert.get_mut(y as usize) else {
                break;
            };
            *o = v;
            y = map.next.get((y ^ 1) as usize).copied().unwrap_or(NONE);
        }
        for (k, &x) in [u, v, c, d].iter().enumerate() {
            if x != NONE {
                map.vdart[x as usize] = self.old_vdart[k];
            }
        }
        for (k, &f) in self.faces.iter().enumerate() {
            if f != NONE {
                map.fdart[f as usize] = self.old_fdart[k];
            }
        }
        Ok(())
    }

    /// Whether the map is as the collapse left it, as far as the undo depends on it: every
    /// index in range, the freed slots on top of the free lists, the rewritten successors
    /// and the moved arc as the collapse left them, and every entry the undo restores
    /// consistent with its neighbours (so the result satisfies every axiom locally).
    fn fits(&self, map: &Map) -> bool {
        let nd = map.next.len();
        let live = |x: u32| (x as usize) < nd && map.next[x as usize] != NONE;
        let dead = |x: u32| (x as usize) < nd && map.next[x as usize] == NONE;
        let in_range = |x: u32| (x as usize) < nd;
        let [h, h1, h2, t1, t2] = self.darts;
        let [fl, fr, fx, fz] = self.faces;
        let [c, d] = self.apex;
        let has_l = h1 != NONE;
        let has_r = t1 != NONE;
        let (u, v) = (self.kept.0, self.removed.0);
        let nw = self.n_writes as usize;
        let vert_ok = |x: u32, present: bool| {
            if present {
                (x as usize) < map.vdart.len() && (x == v || map.vdart[x as usize] != NONE)
            } else {
                x == NONE
            }
        };
        let face_ok = |x: u32| x == NONE || (x as usize) < map.fdart.len();
        let shape = (has_l || has_r)
            && dead(h)
            && (!has_l || (live(h1) && dead(h2) && fl != NONE))
            && (has_l || (h2 == NONE && fl == NONE && fx == NONE))
            && (!has_r || (live(t2) && dead(t1) && fr != NONE))
            && (has_r || (t2 == NONE && fr == NONE && fz == NONE))
            && vert_ok(u, true)
            && map.vdart[u as usize] != NONE
            && vert_ok(v, true)
            && map.vdart[v as usize] == NONE
            && vert_ok(c, has_l)
            && vert_ok(d, has_r)
            && self.faces.iter().all(|&f| face_ok(f))
            && self.count as usize <= nd
            && (self.count == 0 || in_range(self.first))
            && nw <= self.writes.len();
        if !shape {
            return false;
        }
        let oh2 = if has_l { h2 ^ 1 } else { NONE };
        let ot1 = if has_r { t1 ^ 1 } else { NONE };
        let removed = [h, h ^ 1, h2, oh2, t1, ot1];
        let olds_ok = removed
            .iter()
            .zip(self.dead_next)
            .all(|(&x, n)| x == NONE || in_range(n))
            && self
                .old_vdart
                .iter()
                .zip([true, true, has_l, has_r])
                .all(|(&x, p)| !p || in_range(x))
            && self
                .old_fdart
                .iter()
                .zip(self.faces)
                .all(|(&x, f)| f == NONE || in_range(x))
            && self.writes[..nw]
                .iter()
                .all(|&(c, old, new)| live(c) && in_range(old) && map.next[c as usize] == new);
        // The freed slots are on top of the free lists, in the order they were freed.
        let mut edges = [NONE; 3];
        let mut ne = 0;
        for x in [h, h2, t1] {
            if x != NONE {
                edges[ne] = x >> 1;
                ne += 1;
            }
        }
        let mut faces = [NONE; 2];
        let mut nf = 0;
        for f in [fl, fr] {
            if f != NONE {
                faces[nf] = f;
                nf += 1;
            }
        }
        if !olds_ok
            || !map.free_edges.ends_with(&edges[..ne])
            || !map.free_verts.ends_with(&[v])
            || !map.free_faces.ends_with(&faces[..nf])
        {
            return false;
        }
        // The successors the undo restores, and the darts whose origin after the undo
        // depends on whether they are among the moved ones (probes).
        let mut pairs = [(NONE, NONE); 11];
        let mut np = 0;
        for (&x, n) in removed.iter().zip(self.dead_next) {
            if x != NONE {
                pairs[np] = (x, n);
                np += 1;
            }
        }
        for &(cell, old, _) in &self.writes[..nw] {
            pairs[np] = (cell, old);
            np += 1;
        }
        let [ou, ov, oc, od] = self.old_vdart;
        let mut probes = [NONE; 24];
        for (k, &(x, n)) in pairs[..np].iter().enumerate() {
            probes[2 * k] = x ^ 1;
            probes[2 * k + 1] = n;
        }
        probes[22] = ou;
        probes[23] = ov;
        let mut moved = [false; 24];
        // The moved darts are still the arc of u that ends just before h1 (or before u's own
        // boundary dart, the old next of h, when there is no L); where it starts is pinned
        // by a rewritten successor (of t2, or of prev(t) without R).
        let arc_end = if has_l { h1 } else { self.dead_next[0] };
        let mut y = self.first;
        let (mut record_moves, mut moved_boundary) = (false, false);
        for _ in 0..self.count {
            if !live(y) || map.vert[y as usize] != u {
                return false;
            }
            record_moves |= map.vdart[u as usize] == y;
            moved_boundary |= map.face[y as usize] == NONE;
            for (p, m) in probes.iter().zip(moved.iter_mut()) {
                *m |= *p == y;
            }
            y = map.next[(y ^ 1) as usize];
        }
        if self.count > 0 && y != arc_end {
            return false;
        }
        // Origins and faces after the undo.
        let vert_after = |x: u32, is_moved: bool| match x {
            _ if is_moved => v,
            _ if x == h => v,
            _ if x == (h ^ 1) => u,
            _ if x == h2 => c,
            _ if x == oh2 => v,
            _ if x == t1 => v,
            _ if x == ot1 => d,
            _ => map.vert[x as usize],
        };
        let face_after = |x: u32| match x {
            _ if x == h => fl,
            _ if x == (h ^ 1) => fr,
            _ if x == h1 || x == h2 => fl,
            _ if x == t1 || x == t2 => fr,
            _ if x == oh2 => fx,
            _ if x == ot1 => fz,
            _ => map.face[x as usize],
        };
        // Each restored successor: origin(twin x) == origin(next x), one face along next.
        for (k, &(x, n)) in pairs[..np].iter().enumerate() {
            if vert_after(x ^ 1, moved[2 * k]) != vert_after(n, moved[2 * k + 1])
                || face_after(x) != face_after(n)
            {
                return false;
            }
        }
        // Each restored record must name a dart of its element after the undo, the boundary
        // one for a boundary vertex. u's present boundary dart stays with u unless it moves
        // to v or is h1 (back to L).
        let u_keeps = on_boundary(map, u) && !record_moves && map.vdart[u as usize] != h1;
        let u_boundary = u_keeps || !has_r;
        let v_boundary = !has_l || fx == NONE || moved_boundary;
        let leaves_u = ou == (h ^ 1) || (!moved[22] && live(ou) && map.vert[ou as usize] == u);
        let leaves_v = moved[23] || (ov != NONE && [h, t1, oh2].contains(&ov));
        let records_ok = leaves_u
            && (face_after(ou) == NONE) == u_boundary
            && leaves_v
            && (face_after(ov) == NONE) == v_boundary
            && (!has_l
                || ((oc == h2 || (live(oc) && map.vert[oc as usize] == c))
                    && (face_after(oc) == NONE) == on_boundary(map, c)))
            && (!has_r
                || ((od == ot1 || (live(od) && map.vert[od as usize] == d))
                    && (face_after(od) == NONE) == on_boundary(map, d)));
        let in_face =
            |x: u32, f: u32| x != NONE && (live(x) || removed.contains(&x)) && face_after(x) == f;
        records_ok
            && self
                .faces
                .iter()
                .zip(self.old_fdart)
                .all(|(&f, x)| f == NONE || in_face(x, f))
            && (!has_l || map.face[h1 as usize] == fx)
            && (!has_r || map.face[t2 as usize] == fz)
    }
}

impl Undo for EdgeCollapse {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        EdgeCollapse::undo(self, map)
    }
}

/// Record of a [`split_vertex`]: the new vertex and edge, and what the exact undo needs.
///
/// ```
/// use zipmesh::{gen, ops::tri, Vert};
/// let mut map = gen::random_triangle(200, 1, 0, 3).map;
/// let w = Vert::new(0);
/// let d1 = map.vertex_dart(w);
/// let d2 = map.rotate_cw(map.rotate_cw(map.rotate_cw(d1)));
/// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
/// assert_eq!(map.origin(rec.edge()), rec.created());
/// assert_eq!(map.dest(rec.edge()), w);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct VertexSplit {
    /// The new vertex and edge (see [`VertexSplit::created`], [`VertexSplit::edge`]).
    vertex: Vert,
    edge: Dart,
    /// Old record of w; the new edges of `a` and `b`; faces L, R; slot counts before.
    old_w: u32,
    edges: [u32; 2],
    faces: [u32; 2],
    lens: Lens,
}

/// The checked arguments of a vertex split.
struct SplitPlan {
    d1: u32,
    d2: u32,
    w: u32,
    a: u32,
    b: u32,
    first: u32,
    last: u32,
    count: u32,
    /// Whether the record of `w` is among the moved darts.
    record_moves: bool,
}

/// Checks whether [`split_vertex`] applies to `d1`, `d2`, without changing anything.
///
/// The rules, in the order checked, with `w` the origin and `a = dest(d1)`, `b = dest(d2)`:
/// 1. [`Refusal::DeadHandle`]: a dart is not live.
/// 2. [`Refusal::BadArguments`]: `d1 == d2`, or they leave different vertices.
/// 3. [`Refusal::DegenerateTriangle`]: `d1` or `d2` is a loop (a new triangle would repeat
///    a corner).
/// 4. [`Refusal::MultiEdge`]: `a == b` (v would get two edges to `a`).
/// 5. [`Refusal::LinkCondition`]: the faces on both sides of `d1` are triangles with third
///    corner `b` (the edge `a-b` would be in the links of both copies).
/// 6. For each moved dart `y` in clockwise order (those after `d2` and before `d1`):
///    [`Refusal::LinkCondition`] if `y` is a loop at `w`; [`Refusal::MultiEdge`] if `y` ends
///    at `a` or `b`; [`Refusal::LinkCondition`] if `y` ends at a vertex that a kept dart of
///    `w` also reaches (the two copies would share a neighbour other than `a`, `b`).
///
/// These are exactly the cases where the new edge would fail [`can_collapse_edge`]'s link
/// condition, so every allowed split can be collapsed back, except that the collapse also
/// requires the valence minimum of `w`, `a` and `b` before the split (a split never lowers a
/// valence, so it does not ask for it). In a simple mesh whose vertices meet the valence
/// minimum only rules 1 to 3 can refuse.
///
/// ```
/// use zipmesh::{ops::{tri, Refusal}, Dart, Map, Vert};
/// let map = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
/// let d = map.vertex_dart(Vert::new(0));
/// assert_eq!(tri::can_split_vertex(&map, d, d), Err(Refusal::BadArguments));
/// assert_eq!(tri::can_split_vertex(&map, d, map.rotate_cw(d)), Ok(()));
/// ```
pub fn can_split_vertex(map: &Map, d1: Dart, d2: Dart) -> Result<(), Refusal> {
    split_plan(map, d1, d2).map(|_| ())
}

fn split_plan(map: &Map, d1: Dart, d2: Dart) -> Result<SplitPlan, Refusal> {
    split_plan_with(map, d1, d2, SMALL)
}

/// [`split_plan`] with the limit of kept ends gathered on the stack.
fn split_plan_with(map: &Map, d1: Dart, d2: Dart, small: usize) -> Result<SplitPlan, Refusal> {
    if !map.is_live_dart(d1) || !map.is_live_dart(d2) {
        return Err(Refusal::DeadHandle);
    }
    let (d1, d2) = (d1.0, d2.0);
    let w = org(map, d1);
    if d1 == d2 || org(map, d2) != w {
        return Err(Refusal::BadArguments);
    }
    let (a, b) = (org(map, d1 ^ 1), org(map, d2 ^ 1));
    if a == w || b == w {
        return Err(Refusal::DegenerateTriangle);
    }
    if a == b {
        return Err(Refusal::MultiEdge);
    }
    // Edge part of the new edge's link condition (see `plan`): the triangles on both sides
    // of d1 have b as third corner, so a-b would lie in the links of both v and w.
    if third_corner(map, d1) == b && third_corner(map, d1 ^ 1) == b {
        return Err(Refusal::LinkCondition);
    }
    let first = rot(map, d2);
    let rec = map.vdart[w as usize];
    // The ends of the kept darts (d1 through d2), when there are few; otherwise each moved
    // dart's end is searched for an edge back to w.
    let kept = gather(map, d1, d2, small);
    let (mut y, mut last, mut count, mut record_moves) = (first, d2, 0u32, false);
    let in_moved = |z: u32| {
        let mut x = first;
        while x != d1 {
            if x == z {
                return true;
            }
            x = rot(map, x);
        }
        false
    };
    while y != d1 {
        let x = org(map, y ^ 1);
        if x == w {
            return Err(Refusal::LinkCondition);
        }
        if x == a || x == b {
            return Err(Refusal::MultiEdge);
        }
        // Another edge x-w whose w end stays with w: v and w would share the neighbour x.
        let shared = match &kept {
            Some(k) => k.contains(x),
            None => {
                let mut z = rot(map, y ^ 1);
                let mut found = false;
                while z != y ^ 1 && !found {
                    found = org(map, z ^ 1) == w && !in_moved(z ^ 1);
                    z = rot(map, z);
                }
                found
            }
        };
        if shared {
            return Err(Refusal::LinkCondition);
        }
        record_moves |= y == rec;
        last = y;
        count += 1;
        y = rot(map, y);
    }
    Ok(SplitPlan {
        d1,
        d2,
        w,
        a,
        b,
        first,
        last,
        count,
        record_moves,
    })
}

/// Splits the vertex `w = origin(d1) = origin(d2)` in two, the inverse of [`collapse_edge`].
///
/// `w` keeps `d1`, `d2` and the darts clockwise after `d1` and before `d2` (the *kept arc*,
/// `k_w` darts strictly inside); a new vertex `v` takes the darts clockwise after `d2` and
/// before `d1` (the *moved arc*, `k_v` darts). A new edge `v-w` and the new triangles
/// `(v, w, a)` and `(w, v, b)` fill the gap, with `a = dest(d1)`, `b = dest(d2)`:
///
/// ```text
///          a                     a
///          |                   /   \
///          d1                 /  L  d1
///  moved - w - kept   ==>   v --e--> w - kept      e = record.edge(), from v to w
///          d2       moved -   \  R  d2
///          |                   \   /
///          b                     b
/// ```
/// V +1, E +3, F +2; `d(w) = k_w + 3`, `d(v) = k_v + 3` (the paper's `d1 + 3`, `d2 + 3`);
/// `a` and `b` gain one; every other vertex keeps its valence. If `w` is on the boundary,
/// the copy whose arc holds the boundary corner stays on the boundary (`v` if `w`'s boundary
/// dart is moved or is `d1`), the other becomes interior: so a split never pinches. Every
/// existing handle stays valid; `w` keeps its handle. Refusals: see [`can_split_vertex`].
///
/// [`collapse_edge`] of `record.edge()` gives back the map up to slot numbers; [`VertexSplit::undo`]
/// gives back the same arrays.
///
/// ```
/// use zipmesh::{ops::tri, Map, Vert};
/// let mut map = Map::from_polygons(7, &[
///     [0u32, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [0, 5, 6], [0, 6, 1],
/// ]).unwrap();
/// let before = map.clone();
/// let w = Vert::new(0);
/// let d1 = map.vertex_dart(w);
/// let d2 = map.rotate_cw(map.rotate_cw(d1)); // kept arc: one dart strictly inside
/// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
/// assert_eq!((map.valence(w), map.valence(rec.created())), (1 + 3, 3 + 3));
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn split_vertex(map: &mut Map, d1: Dart, d2: Dart) -> Result<VertexSplit, Refusal> {
    let p = split_plan(map, d1, d2)?;
    let lens = Lens::of(map);
    let (d1, t2) = (p.d1, p.d2 ^ 1);
    // Old neighbourhood: d1 sits between p1 and s1 in face X, twin(d2) between q2 and r2.
    let p1 = p.last ^ 1;
    let s1 = nx(map, d1);
    let q2 = prev_of(map, t2);
    let r2 = nx(map, t2);
    let (fx, fz) = (fc(map, d1), fc(map, t2));
    let old_w = map.vdart[p.w as usize];
    let boundary_w = fc(map, old_w) == NONE;

    let h = map.alloc_edge().0; // h: v -> w
    let h2 = map.alloc_edge().0; // h2: a -> v
    let t1 = map.alloc_edge().0; // t1: v -> b
    let v = map.alloc_vert().0;
    let fl = map.alloc_face().0;
    let fr = map.alloc_face().0;
    let (t, oh2, ot1) = (h ^ 1, h2 ^ 1, t1 ^ 1);
    // twin(h2) takes the place of d1 in X, twin(t1) that of twin(d2) in Z.
    let repl = |x: u32| {
        if x == d1 {
            oh2
        } else if x == t2 {
            ot1
        } else {
            x
        }
    };
    let mut y = p.first;
    for _ in 0..p.count {
        map.vert[y as usize] = v;
        y = rot(map, y);
    }
    map.next[repl(p1) as usize] = oh2;
    map.next[oh2 as usize] = repl(s1);
    map.next[repl(q2) as usize] = ot1;
    map.next[ot1 as usize] = repl(r2);
    for (x, n, o, f) in [
        (h, d1, v, fl),
        (d1, h2, p.w, fl),
        (h2, h, p.a, fl),
        (t, t1, p.w, fr),
        (t1, t2, v, fr),
        (t2, t, p.b, fr),
    ] {
        map.next[x as usize] = n;
        map.vert[x as usize] = o;
        map.face[x as usize] = f;
    }
    map.vert[oh2 as usize] = v;
    map.face[oh2 as usize] = fx;
    map.vert[ot1 as usize] = p.b;
    map.face[ot1 as usize] = fz;
    // The boundary corner of w goes with the arc that holds it.
    map.vdart[v as usize] = if boundary_w && p.record_moves {
        old_w
    } else if boundary_w && old_w == d1 {
        oh2
    } else {
        h
    };
    if p.record_moves {
        map.vdart[p.w as usize] = d1;
    }
    // twin(t1) replaces twin(d2), possibly as b's boundary dart.
    if map.vdart[p.b as usize] == t2 {
        map.vdart[p.b as usize] = ot1;
    }
    map.fdart[fl as usize] = h;
    map.fdart[fr as usize] = t;
    if fx != NONE && map.fdart[fx as usize] == d1 {
        map.fdart[fx as usize] = oh2;
    }
    if fz != NONE && map.fdart[fz as usize] == t2 {
        map.fdart[fz as usize] = ot1;
    }
    Ok(VertexSplit {
        vertex: Vert(v),
        edge: Dart(h),
        old_w,
        edges: [h2 >> 1, t1 >> 1],
        faces: [fl, fr],
        lens,
    })
}

impl VertexSplit {
    /// The new vertex `v`, which took the moved arc.
    ///
    /// ```
    /// use zipmesh::{gen, ops::tri, Vert};
    /// let mut map = gen::random_triangle(200, 1, 0, 3).map;
    /// let d1 = map.vertex_dart(Vert::new(0));
    /// let d2 = map.rotate_cw(map.rotate_cw(d1));
    /// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
    /// assert!(map.is_live_vertex(rec.created()));
    /// ```
    pub fn created(&self) -> Vert {
        self.vertex
    }

    /// The new edge's dart from `v` to `w`: [`collapse_edge`] of it undoes the split up to
    /// slot numbers (the same map up to isomorphism; `undo` restores the very same arrays).
    ///
    /// ```
    /// use zipmesh::{gen, ops::tri, Vert};
    /// let mut map = gen::random_triangle(200, 1, 0, 3).map;
    /// let w = Vert::new(0);
    /// let d1 = map.vertex_dart(w);
    /// let d2 = map.rotate_cw(map.rotate_cw(d1));
    /// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
    /// assert_eq!(map.dest(rec.edge()), w);
    /// ```
    pub fn edge(&self) -> Dart {
        self.edge
    }

    /// Undoes the split: the map becomes equal (`==`) to the one before, provided it has not
    /// been changed since (other records undone in reverse order are fine).
    ///
    /// Returns [`Refusal::StaleRecord`] and changes nothing when the new edge, vertex and
    /// triangles are not as the split left them. Never panics, whatever the map.
    ///
    /// ```
    /// use zipmesh::{gen, ops::tri, Vert};
    /// let mut map = gen::random_triangle(200, 0, 2, 9).map;
    /// let before = map.clone();
    /// let d1 = map.vertex_dart(Vert::new(7));
    /// let d2 = map.rotate_cw(d1);
    /// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        let p = match plan(map, self.edge, false) {
            Ok(p) => p,
            Err(_) => return Err(Refusal::StaleRecord),
        };
        let lens = self.lens;
        let w = p.u;
        let (h, h2, t1) = (p.h, p.h2, p.t1);
        let [fl, fr] = self.faces;
        let old_w = self.old_w;
        if p.v != self.vertex.0
            || p.h1 == NONE
            || p.t1 == NONE
            || [h2 >> 1, t1 >> 1] != self.edges
            || [fc(map, h), fc(map, h ^ 1)] != self.faces
            || !map.is_live_dart(Dart(old_w))
            || [h >> 1, h2 >> 1, t1 >> 1].contains(&(old_w >> 1))
            || (org(map, old_w) != w && org(map, old_w) != p.v)
            || (face_after_collapse(map, &p, old_w) == NONE)
                != (on_boundary(map, w) || on_boundary(map, p.v))
            || !fresh_tail(
                &[h >> 1, h2 >> 1, t1 >> 1],
                lens.darts / 2,
                map.next.len() / 2,
            )
            || !fresh_tail(&[p.v], lens.verts, map.vdart.len())
            || !fresh_tail(&[fl, fr], lens.faces, map.fdart.len())
        {
            return Err(Refusal::StaleRecord);
        }
        apply(map, &p, Some(lens));
        map.vdart[w as usize] = self.old_w;
        Ok(())
    }
}

impl Undo for VertexSplit {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        VertexSplit::undo(self, map)
    }
}

/// [`can_collapse_edge`] and [`can_split_vertex`] with at most `small` neighbours on the stack, so
/// that unit tests can compare the stack path with the fallback.
#[cfg(test)]
pub(super) fn can_with(map: &Map, h: Dart, d2: Option<Dart>, small: usize) -> Result<(), Refusal> {
    match d2 {
        None => plan_with(map, h, true, small).map(|_| ()),
        Some(d2) => split_plan_with(map, h, d2, small).map(|_| ()),
    }
}
