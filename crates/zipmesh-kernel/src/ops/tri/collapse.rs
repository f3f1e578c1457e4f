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
    gather, joined, min_valence, prev_of, sides, triangle, valence_at_least, Ends, Undo, SMALL,
};
use crate::map::{Dart, Face, Map, Vert, NONE};
use crate::ops::guard::Guard;
use crate::ops::slots::Slots;
use crate::ops::Refusal;

/// An absent dart, vertex or face in a plan or a record (a boundary edge has one side only).
const NO_DART: Dart = Dart(NONE);
const NO_VERT: Vert = Vert(NONE);
const NO_FACE: Face = Face(NONE);

/// The face of `d` as a slot, [`NO_FACE`] for a boundary dart (the records keep faces so).
#[inline]
fn face_slot(map: &Map, d: Dart) -> Face {
    map.face(d).unwrap_or(NO_FACE)
}

/// The darts and vertices of a collapse, found by [`plan`].
#[derive(Clone, Copy, Debug)]
pub(super) struct Plan {
    h: Dart,
    /// `h1`, `h2` of L, or [`NO_DART`] when `h` is a boundary dart.
    h1: Dart,
    h2: Dart,
    /// `t1`, `t2` of R, or [`NO_DART`] when `twin(h)` is a boundary dart.
    t1: Dart,
    t2: Dart,
    u: Vert,
    v: Vert,
    /// Apexes of L and R ([`NO_VERT`] when absent).
    c: Vert,
    d: Vert,
    /// The moved darts: `count` darts clockwise from `first`; `last` is the dart just
    /// before `oh2` (or before `h` when there is no L) in the rotation of `v`.
    first: Dart,
    count: u32,
    last: Dart,
}

impl Plan {
    fn has_l(&self) -> bool {
        self.h1 != NO_DART
    }

    fn has_r(&self) -> bool {
        self.t1 != NO_DART
    }

    /// `twin(h2)` and `twin(t1)`, [`NO_DART`] for an absent side.
    fn outer(&self) -> [Dart; 2] {
        [
            if self.has_l() {
                self.h2.twin()
            } else {
                NO_DART
            },
            if self.has_r() {
                self.t1.twin()
            } else {
                NO_DART
            },
        ]
    }

    /// The dart that takes the place of `x`: h1 that of twin(h2), t2 that of twin(t1).
    fn replacement(&self, x: Dart) -> Dart {
        let [oh2, ot1] = self.outer();
        if x == oh2 && self.has_l() {
            self.h1
        } else if x == ot1 && self.has_r() {
            self.t2
        } else {
            x
        }
    }
}

/// Finds the collapse's darts; with `policy`, also applies every rule of [`can_collapse_edge`].
/// Without it (undoing a vertex split) only the rules that keep the map valid apply (proper
/// triangles, not both ends on the boundary of an interior edge, distinct apexes).
fn plan(map: &Map, hd: Dart, policy: bool) -> Result<Plan, Refusal> {
    plan_with(map, hd, policy, SMALL)
}

/// [`plan`] with the limit of neighbours gathered on the stack.
fn plan_with(map: &Map, h: Dart, policy: bool, small: usize) -> Result<Plan, Refusal> {
    if !map.is_live_dart(h) {
        return Err(Refusal::DeadHandle);
    }
    let t = h.twin();
    let [l, r] = sides(map, h)?;
    let (v, u) = (map.origin(h), map.origin(t));
    let interior = l.is_some() && r.is_some();
    let boundary = [map.is_boundary_vertex(u), map.is_boundary_vertex(v)];
    // These two rules keep the result a valid map, so they hold even without `policy`.
    if interior && boundary[0] && boundary[1] {
        return Err(Refusal::Boundary);
    }
    let c = l.map_or(NO_VERT, |x| map.origin(x[2]));
    let d = r.map_or(NO_VERT, |x| map.origin(x[2]));
    if interior && c == d {
        return Err(Refusal::LinkCondition);
    }
    // The rotation of v clockwise from h: h, [t1], moved darts, [twin(h2)], back to h.
    let start = r.map_or(h, |x| x[1]);
    let stop = l.map_or(h, |x| x[2].twin());
    let first = map.rotate_cw(start);
    // The neighbours of u, when u has few; otherwise each candidate's rotation is walked
    // instead of u's, so that a growing u (repeated collapses into it) costs nothing more.
    let near_u = if policy {
        gather(map, t, None, small)
    } else {
        None
    };
    let link = policy.then_some((u, &near_u));
    let (last, count) = moved_arc(map, [first, start, stop], link)?;
    let pick = |x: Option<[Dart; 3]>, i: usize| x.map_or(NO_DART, |x| x[i]);
    let p = Plan {
        h,
        h1: pick(l, 1),
        h2: pick(l, 2),
        t1: pick(r, 1),
        t2: pick(r, 2),
        u,
        v,
        c,
        d,
        first: if count > 0 { first } else { NO_DART },
        count,
        last,
    };
    if policy {
        policy_rules(map, &p, boundary[0] || boundary[1], &near_u)?;
    }
    Ok(p)
}

/// Walks the moved darts of `v`, clockwise from `first` up to `stop`: returns the last one
/// (`start` if there is none) and their number. With `link` (`u` and its gathered
/// neighbours), also applies the vertex part of the link condition: a neighbour of v other
/// than u, c, d must not be u nor a neighbour of u.
fn moved_arc(
    map: &Map,
    [first, start, stop]: [Dart; 3],
    link: Option<(Vert, &Option<Ends>)>,
) -> Result<(Dart, u32), Refusal> {
    let (mut y, mut last, mut count) = (first, start, 0u32);
    while y != stop {
        if count as usize > map.dart_slots() {
            // Unreachable in a valid map: the rotation of v holds `stop`.
            return Err(Refusal::StaleRecord);
        }
        if let Some((u, near_u)) = link {
            let x = map.dest(y);
            let adjacent = match near_u {
                Some(n) => n.contains(x),
                None => joined(map, y.twin(), u),
            };
            if x == u || adjacent {
                return Err(Refusal::LinkCondition);
            }
        }
        last = y;
        count += 1;
        y = map.rotate_cw(y);
    }
    Ok((last, count))
}

/// The rules of [`can_collapse_edge`] past the ones that keep the map valid: the edge part
/// of the link condition and the valence minimum (`boundary`: u or v is on the boundary).
fn policy_rules(map: &Map, p: &Plan, boundary: bool, near_u: &Option<Ends>) -> Result<(), Refusal> {
    let interior = p.has_l() && p.has_r();
    // Edge part: the edge c-d lies in a triangle with u and in one with v, as in a
    // tetrahedron; collapsing would fold two triangles onto each other.
    if interior && third_corner(map, p.h1.twin()) == p.d && third_corner(map, p.h2.twin()) == p.d {
        return Err(Refusal::LinkCondition);
    }
    let dv = p.count as usize + 1 + usize::from(p.has_l()) + usize::from(p.has_r());
    let loss = if interior { 4 } else { 3 };
    let need_u = (min_valence(boundary) + loss).saturating_sub(dv);
    let enough = match near_u {
        Some(n) => n.len() >= need_u,
        None => valence_at_least(map, p.h.twin(), need_u),
    };
    if !enough {
        return Err(Refusal::ValenceTooLow);
    }
    for apex in [p.h2, p.t2] {
        if apex == NO_DART {
            continue;
        }
        let need = min_valence(map.is_boundary_vertex(map.origin(apex))) + 1;
        if !valence_at_least(map, apex, need) {
            return Err(Refusal::ValenceTooLow);
        }
    }
    Ok(())
}

/// The face of `x` once the planned collapse is applied: h1 takes the face of twin(h2), t2
/// that of twin(t1); every other surviving dart keeps its face.
fn face_after_collapse(map: &Map, p: &Plan, x: Dart) -> Option<Face> {
    if x == p.h1 && p.has_l() {
        map.face(p.h2.twin())
    } else if x == p.t2 && p.has_r() {
        map.face(p.t1.twin())
    } else {
        map.face(x)
    }
}

/// The corner opposite the edge of `x` in its face, if that face is a triangle.
fn third_corner(map: &Map, x: Dart) -> Vert {
    if map.face(x).is_none() {
        return NO_VERT;
    }
    triangle(map, x).map_or(NO_VERT, |tr| map.origin(tr[2]))
}

/// Record of a [`collapse_edge`]: the kept and removed vertices, and what the exact undo needs.
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri, Dart};
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
    /// `h, h1, h2, t1, t2` before the collapse ([`NO_DART`] for an absent side).
    darts: [Dart; 5],
    /// Apexes c and d.
    apex: [Vert; 2],
    /// Faces L, R, and X, Z: the faces of `twin(h2)` and `twin(t1)` before.
    faces: [Face; 4],
    /// Every `next` entry rewritten in a surviving dart: (dart, old, new).
    writes: [(Dart, Dart, Dart); 5],
    n_writes: u8,
    /// Old `next` of the removed darts `h, t, h2, twin h2, t1, twin t1`.
    dead_next: [Dart; 6],
    /// The moved darts: `count` clockwise from `first` in the restored rotation of v.
    first: Dart,
    count: u32,
    /// Old vertex records of u, v, c, d and face records of L, R, X, Z.
    old_vdart: [Dart; 4],
    old_fdart: [Dart; 4],
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
/// use zipmesh_kernel::{ops::{tri, Refusal}, Dart, Map};
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
/// use zipmesh_kernel::{gen, invariants::Counts, ops::tri};
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

/// Applies a planned collapse. With `created`, the removed slots are un-allocated (undo of
/// the vertex split that allocated them) instead of freed.
fn apply(map: &mut Map, p: &Plan, created: Option<&Slots>) -> EdgeCollapse {
    let (writes, n_writes) = next_writes(map, p);
    let rec = EdgeCollapse::before(map, p, writes, n_writes);
    let bv = map.is_boundary_vertex(p.v);
    rewire_collapse(map, p, &rec, bv);
    match created {
        None => rec.deleted().free(map),
        Some(slots) => slots.release(map),
    }
    rec
}

/// The `next` entries a planned collapse rewrites, as (dart, old, new): the predecessors of
/// the replaced and vanishing darts, and the replaced darts themselves (their successor goes
/// to the replacement). At most five.
fn next_writes(map: &Map, p: &Plan) -> ([(Dart, Dart, Dart); 5], usize) {
    let t = p.h.twin();
    let [oh2, ot1] = p.outer();
    // A boundary dart of the edge vanishes from its loop without replacement.
    let vanish = if !p.has_l() {
        p.h
    } else if !p.has_r() {
        t
    } else {
        NO_DART
    };
    let mut pos = [NO_DART; 5];
    let mut np = 0;
    let mut push = |x: Dart| {
        pos[np] = x;
        np += 1;
    };
    push(p.last.twin()); // prev(twin h2), or prev(h) when there is no L
    if p.has_l() {
        push(oh2);
    }
    if p.has_r() {
        push(prev_of(map, ot1));
        push(ot1);
    }
    if vanish == t {
        push(prev_of(map, t));
    }
    let mut writes = [(NO_DART, NO_DART, NO_DART); 5];
    let mut nw = 0;
    for &y in &pos[..np] {
        if y == vanish {
            continue; // its predecessor is in the list and skips it
        }
        let mut s = map.next(y);
        if s == vanish {
            s = map.next(s);
        }
        let cell = p.replacement(y);
        writes[nw] = (cell, map.next(cell), p.replacement(s));
        nw += 1;
    }
    (writes, nw)
}

/// Rewrites the map for a planned collapse whose record `rec` was taken (`bv`: `v` is on
/// the boundary); leaves the removed slots for the caller.
fn rewire_collapse(map: &mut Map, p: &Plan, rec: &EdgeCollapse, bv: bool) {
    let t = p.h.twin();
    let [oh2, ot1] = p.outer();
    let [.., fx, fz] = rec.faces;
    let [ou, ov, oc, od] = rec.old_vdart;
    // The moved darts first, while the rotation of v is intact.
    let mut y = p.first;
    for _ in 0..p.count {
        map.set_origin(y, p.u);
        y = map.rotate_cw(y);
    }
    for &(cell, _, new) in &rec.writes[..rec.n_writes as usize] {
        map.set_next(cell, new);
    }
    if p.has_l() {
        map.set_face(p.h1, fx);
    }
    if p.has_r() {
        map.set_face(p.t2, fz);
    }
    // The kept vertex records its boundary dart if it has one: v's when v is on the
    // boundary and L exists (without R, u's own boundary dart t vanishes and v's is
    // next(t)); without L, v's boundary dart h vanishes and u keeps its own.
    let new_u = if p.has_l() && (!p.has_r() || bv) {
        p.replacement(ov)
    } else if ou == t {
        p.h1
    } else {
        ou
    };
    map.set_vertex_dart(p.u, new_u);
    if p.has_l() && oc == p.h2 {
        map.set_vertex_dart(p.c, p.h1.twin());
    }
    if p.has_r() && od == ot1 {
        map.set_vertex_dart(p.d, p.t2);
    }
    if fx != NO_FACE && rec.old_fdart[2] == oh2 {
        map.set_face_dart(fx, p.h1);
    }
    if fz != NO_FACE && rec.old_fdart[3] == ot1 {
        map.set_face_dart(fz, p.t2);
    }
}

impl EdgeCollapse {
    /// The record of a planned collapse, taken before the map changes.
    fn before(map: &Map, p: &Plan, writes: [(Dart, Dart, Dart); 5], nw: usize) -> EdgeCollapse {
        let (h, t) = (p.h, p.h.twin());
        let [oh2, ot1] = p.outer();
        let dead = [h, t, p.h2, oh2, p.t1, ot1];
        let (fl, fr) = (face_slot(map, h), face_slot(map, t));
        let fx = if p.has_l() {
            face_slot(map, oh2)
        } else {
            NO_FACE
        };
        let fz = if p.has_r() {
            face_slot(map, ot1)
        } else {
            NO_FACE
        };
        let faces = [fl, fr, fx, fz];
        EdgeCollapse {
            kept: p.u,
            removed: p.v,
            darts: [h, p.h1, p.h2, p.t1, p.t2],
            apex: [p.c, p.d],
            faces,
            writes,
            n_writes: nw as u8,
            dead_next: dead.map(|x| if x == NO_DART { NO_DART } else { map.next(x) }),
            first: p.first,
            count: p.count,
            old_vdart: [p.u, p.v, p.c, p.d].map(|v| map.vertex_dart(v)),
            old_fdart: faces.map(|f| map.face_dart(f)),
        }
    }

    /// The slots the collapse frees, in the order it frees them: the edges of `h`, `h2`,
    /// `t1`, the vertex `v`, the faces L, R (absent sides left out).
    fn deleted(&self) -> Slots {
        let [h, _, h2, t1, _] = self.darts;
        let [fl, fr, ..] = self.faces;
        let mut edges = [h; 3];
        let mut ne = 1;
        for x in [h2, t1] {
            if x != NO_DART {
                edges[ne] = x;
                ne += 1;
            }
        }
        let mut faces = [fl; 2];
        let mut nf = 0;
        for f in [fl, fr] {
            if f != NO_FACE {
                faces[nf] = f;
                nf += 1;
            }
        }
        Slots::deleted(&edges[..ne], self.removed, &faces[..nf])
    }
}

impl EdgeCollapse {
    /// The vertex that stays (`dest(h)`); it received every dart of the removed one.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri};
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
    /// use zipmesh_kernel::{gen, ops::tri};
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
    /// use zipmesh_kernel::{gen, ops::{tri, Refusal}, Map};
    /// let mut map = gen::random_triangle(100, 0, 1, 2).map;
    /// let before = map.clone();
    /// let h = map.darts().find(|&d| tri::can_collapse_edge(&map, d).is_ok()).unwrap();
    /// let rec = tri::collapse_edge(&mut map, h).unwrap();
    /// assert_eq!(rec.undo(&mut Map::new()), Err(Refusal::StaleRecord));
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.guard(map).result()?;
        self.deleted().reclaim(map)?;
        let [h, h1, h2, t1, t2] = self.darts;
        let t = h.twin();
        let (u, v) = (self.kept, self.removed);
        let [c, d] = self.apex;
        let [fl, fr, fx, fz] = self.faces;
        let [oh2, ot1] = self.outer();
        let dead = [
            (h, v, fl),
            (t, u, fr),
            (h2, c, fl),
            (oh2, v, fx),
            (t1, v, fr),
            (ot1, d, fz),
        ];
        for (&(x, o, f), &n) in dead.iter().zip(&self.dead_next) {
            if x != NO_DART {
                map.set_dart(x, n, o, f);
            }
        }
        for &(cell, old, _) in self.writes[..self.n_writes as usize].iter().rev() {
            map.set_next(cell, old);
        }
        if self.has_l() {
            map.set_face(h1, fl);
        }
        if self.has_r() {
            map.set_face(t2, fr);
        }
        let mut y = self.first;
        for _ in 0..self.count {
            if y.index() >= map.dart_slots() {
                break;
            }
            map.set_origin(y, v);
            y = map.rotate_cw(y);
        }
        for (&x, &old) in [u, v, c, d].iter().zip(&self.old_vdart) {
            if x != NO_VERT {
                map.set_vertex_dart(x, old);
            }
        }
        for (&f, &old) in self.faces.iter().zip(&self.old_fdart) {
            map.set_face_dart(f, old);
        }
        Ok(())
    }

    fn has_l(&self) -> bool {
        self.darts[1] != NO_DART
    }

    /// For the tests: the first moved dart and every dart index the record holds.
    #[cfg(test)]
    pub(super) fn held(&self) -> (Dart, alloc::vec::Vec<Dart>) {
        let mut all = alloc::vec::Vec::new();
        all.extend(self.darts);
        all.extend(self.dead_next);
        all.extend(self.old_vdart);
        all.extend(self.old_fdart);
        all.extend(self.writes.iter().flat_map(|&(a, b, c)| [a, b, c]));
        all.retain(|&d| d != NO_DART);
        (self.first, all)
    }

    fn has_r(&self) -> bool {
        self.darts[3] != NO_DART
    }

    /// `twin(h2)` and `twin(t1)`, [`NO_DART`] for an absent side.
    fn outer(&self) -> [Dart; 2] {
        let [_, _, h2, t1, _] = self.darts;
        [
            if self.has_l() { h2.twin() } else { NO_DART },
            if self.has_r() { t1.twin() } else { NO_DART },
        ]
    }

    /// The staleness checks of [`EdgeCollapse::undo`], in order: the map is as the collapse
    /// left it, as far as the undo depends on it: every index in range, the freed slots on
    /// top of the free lists, the rewritten successors and the moved arc as the collapse left
    /// them, and every entry the undo restores consistent with its neighbours (so the result
    /// satisfies every axiom locally).
    pub(super) fn guard(&self, map: &Map) -> Guard {
        let g = Guard::new()
            .check("a side exists", || self.has_l() || self.has_r())
            .check("collapsed edge dead", || is_dead(map, self.darts[0]))
            .check("left side", || self.left_fits(map))
            .check("right side", || self.right_fits(map))
            .check("kept vertex live", || map.is_live_vertex(self.kept))
            .check("removed vertex dead", || {
                self.removed.index() < map.vertex_slots() && !map.is_live_vertex(self.removed)
            })
            .check("apexes live", || {
                let [c, d] = self.apex;
                let fits = |x: Vert, present: bool| {
                    if present {
                        x.index() < map.vertex_slots()
                            && (x == self.removed || map.is_live_vertex(x))
                    } else {
                        x == NO_VERT
                    }
                };
                fits(c, self.has_l()) && fits(d, self.has_r())
            })
            .check("faces in range", || {
                self.faces
                    .iter()
                    .all(|&f| f == NO_FACE || f.index() < map.face_slots())
            })
            .check("moved arc in range", || {
                self.count as usize <= map.dart_slots()
                    && (self.count == 0 || self.first.index() < map.dart_slots())
            })
            .check("old values in range", || self.olds_in_range(map))
            .check("rewritten successors", || {
                self.writes[..self.n_writes as usize]
                    .iter()
                    .all(|&(c, _, new)| map.is_live_dart(c) && map.next(c) == new)
            })
            .check("freed slots on the free lists", || {
                self.deleted().on_free_lists(map)
            });
        if g.failed().is_some() {
            return g;
        }
        let restored = self.restored(map);
        let g = g.check("moved arc", || restored.is_some());
        let Some(r) = restored else {
            return g;
        };
        g.check("restored successors", || self.successors_fit(map, &r))
            .check("restored vertex records", || {
                self.vertex_records_fit(map, &r)
            })
            .check("restored face records", || self.face_records_fit(map))
    }

    /// With L: `h1` live, `h2` dead, L a face; without: no `h2`, L, X.
    fn left_fits(&self, map: &Map) -> bool {
        let [_, h1, h2, ..] = self.darts;
        let [fl, _, fx, _] = self.faces;
        if self.has_l() {
            map.is_live_dart(h1) && is_dead(map, h2) && fl != NO_FACE
        } else {
            h2 == NO_DART && fl == NO_FACE && fx == NO_FACE
        }
    }

    /// With R: `t2` live, `t1` dead, R a face; without: no `t2`, R, Z.
    fn right_fits(&self, map: &Map) -> bool {
        let [.., t1, t2] = self.darts;
        let [_, fr, _, fz] = self.faces;
        if self.has_r() {
            map.is_live_dart(t2) && is_dead(map, t1) && fr != NO_FACE
        } else {
            t2 == NO_DART && fr == NO_FACE && fz == NO_FACE
        }
    }

    /// Every old value the undo writes back is a dart slot of this map.
    fn olds_in_range(&self, map: &Map) -> bool {
        let in_range = |x: Dart| x.index() < map.dart_slots();
        let [oh2, ot1] = self.outer();
        let [h, _, h2, t1, _] = self.darts;
        let removed = [h, h.twin(), h2, oh2, t1, ot1];
        removed
            .iter()
            .zip(self.dead_next)
            .all(|(&x, n)| x == NO_DART || in_range(n))
            && self
                .old_vdart
                .iter()
                .zip([true, true, self.has_l(), self.has_r()])
                .all(|(&x, p)| !p || in_range(x))
            && self
                .old_fdart
                .iter()
                .zip(self.faces)
                .all(|(&x, f)| f == NO_FACE || in_range(x))
            && self.writes[..self.n_writes as usize]
                .iter()
                .all(|&(_, old, _)| in_range(old))
    }

    /// The successors the undo restores (removed darts and rewritten cells with their old
    /// `next`), and which of the darts whose origin the undo decides are in the moved arc;
    /// `None` unless the moved darts are still the arc of u that ends just before h1 (or
    /// before u's own boundary dart, the old next of h, when there is no L).
    fn restored(&self, map: &Map) -> Option<Restored> {
        let [h, h1, h2, t1, _] = self.darts;
        let [oh2, ot1] = self.outer();
        let mut r = Restored {
            pairs: [(NO_DART, NO_DART); 11],
            np: 0,
            moved: [false; 24],
            record_moves: false,
            moved_boundary: false,
        };
        for (&x, n) in [h, h.twin(), h2, oh2, t1, ot1].iter().zip(self.dead_next) {
            if x != NO_DART {
                r.pairs[r.np] = (x, n);
                r.np += 1;
            }
        }
        for &(cell, old, _) in &self.writes[..self.n_writes as usize] {
            r.pairs[r.np] = (cell, old);
            r.np += 1;
        }
        // Probes: per pair, twin(x) and next; then the old records of u and v.
        let mut probes = [NO_DART; 24];
        for (k, &(x, n)) in r.pairs[..r.np].iter().enumerate() {
            probes[2 * k] = x.twin();
            probes[2 * k + 1] = n;
        }
        probes[22] = self.old_vdart[0];
        probes[23] = self.old_vdart[1];
        let arc_end = if self.has_l() { h1 } else { self.dead_next[0] };
        let u = self.kept;
        let mut y = self.first;
        for _ in 0..self.count {
            if !map.is_live_dart(y) || map.origin(y) != u {
                return None;
            }
            r.record_moves |= map.vertex_dart(u) == y;
            r.moved_boundary |= map.face(y).is_none();
            for (p, m) in probes.iter().zip(r.moved.iter_mut()) {
                *m |= *p == y;
            }
            y = map.rotate_cw(y);
        }
        (self.count == 0 || y == arc_end).then_some(r)
    }

    /// The origin of `x` after the undo (`is_moved`: `x` is in the moved arc).
    fn vert_after(&self, map: &Map, x: Dart, is_moved: bool) -> Vert {
        let [h, _, h2, t1, _] = self.darts;
        let [oh2, ot1] = self.outer();
        let v = self.removed;
        match x {
            _ if is_moved || x == h || x == oh2 || x == t1 => v,
            _ if x == h.twin() => self.kept,
            _ if x == h2 => self.apex[0],
            _ if x == ot1 => self.apex[1],
            _ => map.origin(x),
        }
    }

    /// The face of `x` after the undo.
    fn face_after(&self, map: &Map, x: Dart) -> Face {
        let [h, h1, h2, t1, t2] = self.darts;
        let [oh2, ot1] = self.outer();
        let [fl, fr, fx, fz] = self.faces;
        match x {
            _ if x == h || x == h1 || x == h2 => fl,
            _ if x == h.twin() || x == t1 || x == t2 => fr,
            _ if x == oh2 => fx,
            _ if x == ot1 => fz,
            _ => face_slot(map, x),
        }
    }

    /// Each restored successor: origin(twin x) == origin(next x), one face along next.
    fn successors_fit(&self, map: &Map, r: &Restored) -> bool {
        r.pairs[..r.np].iter().enumerate().all(|(k, &(x, n))| {
            self.vert_after(map, x.twin(), r.moved[2 * k])
                == self.vert_after(map, n, r.moved[2 * k + 1])
                && self.face_after(map, x) == self.face_after(map, n)
        })
    }

    /// Each restored vertex record names a dart of its vertex after the undo, the boundary
    /// one for a boundary vertex. u's present boundary dart stays with u unless it moves to
    /// v or is h1 (back to L).
    fn vertex_records_fit(&self, map: &Map, r: &Restored) -> bool {
        let [h, h1, h2, t1, _] = self.darts;
        let [_, ot1] = self.outer();
        let [.., fx, _] = self.faces;
        let (u, [c, d]) = (self.kept, self.apex);
        let [ou, ov, oc, od] = self.old_vdart;
        let boundary_after = |x: Dart| self.face_after(map, x) == NO_FACE;
        let u_keeps = map.is_boundary_vertex(u) && !r.record_moves && map.vertex_dart(u) != h1;
        let u_boundary = u_keeps || !self.has_r();
        let v_boundary = !self.has_l() || fx == NO_FACE || r.moved_boundary;
        let leaves_u =
            ou == h.twin() || (!r.moved[22] && map.is_live_dart(ou) && map.origin(ou) == u);
        let leaves_v = r.moved[23] || (ov != NO_DART && [h, t1, self.outer()[0]].contains(&ov));
        let apex_ok = |o: Dart, own: Dart, x: Vert| {
            (o == own || (map.is_live_dart(o) && map.origin(o) == x))
                && boundary_after(o) == map.is_boundary_vertex(x)
        };
        leaves_u
            && boundary_after(ou) == u_boundary
            && leaves_v
            && boundary_after(ov) == v_boundary
            && (!self.has_l() || apex_ok(oc, h2, c))
            && (!self.has_r() || apex_ok(od, ot1, d))
    }

    /// Each restored face record names a dart of its face after the undo, and h1, t2 are
    /// still in the faces X, Z the collapse gave them.
    fn face_records_fit(&self, map: &Map) -> bool {
        let [h, h1, h2, t1, t2] = self.darts;
        let [oh2, ot1] = self.outer();
        let [.., fx, fz] = self.faces;
        let removed = [h, h.twin(), h2, oh2, t1, ot1];
        let in_face = |x: Dart, f: Face| {
            x != NO_DART
                && (map.is_live_dart(x) || removed.contains(&x))
                && self.face_after(map, x) == f
        };
        self.faces
            .iter()
            .zip(self.old_fdart)
            .all(|(&f, x)| f == NO_FACE || in_face(x, f))
            && (!self.has_l() || face_slot(map, h1) == fx)
            && (!self.has_r() || face_slot(map, t2) == fz)
    }
}

/// What [`EdgeCollapse::restored`] finds.
struct Restored {
    pairs: [(Dart, Dart); 11],
    np: usize,
    /// Per probe (twin and next of each pair, then the old records of u and v): moved.
    moved: [bool; 24],
    /// The present record of u is a moved dart; a moved dart is a boundary dart.
    record_moves: bool,
    moved_boundary: bool,
}

/// Whether `x` is a dead dart slot of this map.
pub(super) fn is_dead(map: &Map, x: Dart) -> bool {
    x.index() < map.dart_slots() && !map.is_live_dart(x)
}

impl Undo for EdgeCollapse {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        EdgeCollapse::undo(self, map)
    }
}

/// Record of a [`split_vertex`]: the new vertex and edge, and what the exact undo needs.
///
/// ```
/// use zipmesh_kernel::{gen, ops::tri, Vert};
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
    /// Old record of w.
    old_w: Dart,
    /// The new edges `v->w` (the record's edge), `a->v`, `v->b`, the new vertex `v` and the
    /// new faces L, R.
    slots: Slots,
}

/// The checked arguments of a vertex split.
struct SplitPlan {
    d1: Dart,
    d2: Dart,
    w: Vert,
    a: Vert,
    b: Vert,
    first: Dart,
    last: Dart,
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
/// use zipmesh_kernel::{ops::{tri, Refusal}, Dart, Map, Vert};
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
    let w = map.origin(d1);
    if d1 == d2 || map.origin(d2) != w {
        return Err(Refusal::BadArguments);
    }
    let (a, b) = (map.dest(d1), map.dest(d2));
    if a == w || b == w {
        return Err(Refusal::DegenerateTriangle);
    }
    if a == b {
        return Err(Refusal::MultiEdge);
    }
    // Edge part of the new edge's link condition (see `plan`): the triangles on both sides
    // of d1 have b as third corner, so a-b would lie in the links of both v and w.
    if third_corner(map, d1) == b && third_corner(map, d1.twin()) == b {
        return Err(Refusal::LinkCondition);
    }
    let mut p = SplitPlan {
        d1,
        d2,
        w,
        a,
        b,
        first: map.rotate_cw(d2),
        last: d2,
        count: 0,
        record_moves: false,
    };
    // The ends of the kept darts (d1 through d2), when there are few; otherwise each moved
    // dart's end is searched for an edge back to w.
    let kept = gather(map, d1, Some(d2), small);
    let rec = map.vertex_dart(w);
    let mut y = p.first;
    while y != d1 {
        moved_dart_rules(map, &p, y, &kept)?;
        p.record_moves |= y == rec;
        p.last = y;
        p.count += 1;
        y = map.rotate_cw(y);
    }
    Ok(p)
}

/// The rules for one moved dart `y` of a planned split (rule 6 of [`can_split_vertex`]);
/// `kept` holds the ends of the kept darts when there are few.
fn moved_dart_rules(map: &Map, p: &SplitPlan, y: Dart, kept: &Option<Ends>) -> Result<(), Refusal> {
    let x = map.dest(y);
    if x == p.w {
        return Err(Refusal::LinkCondition);
    }
    if x == p.a || x == p.b {
        return Err(Refusal::MultiEdge);
    }
    // Another edge x-w whose w end stays with w: v and w would share the neighbour x.
    let shared = match kept {
        Some(k) => k.contains(x),
        None => {
            let in_moved = |z: Dart| {
                let mut m = p.first;
                while m != p.d1 {
                    if m == z {
                        return true;
                    }
                    m = map.rotate_cw(m);
                }
                false
            };
            let mut z = map.rotate_cw(y.twin());
            let mut found = false;
            while z != y.twin() && !found {
                found = map.dest(z) == p.w && !in_moved(z.twin());
                z = map.rotate_cw(z);
            }
            found
        }
    };
    if shared {
        return Err(Refusal::LinkCondition);
    }
    Ok(())
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
/// use zipmesh_kernel::{ops::tri, Map, Vert};
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
    let t2 = p.d2.twin();
    // Old neighbourhood: d1 sits between p1 and s1 in face X, twin(d2) between q2 and r2.
    let around = [
        p.last.twin(),
        map.next(p.d1),
        prev_of(map, t2),
        map.next(t2),
    ];
    let rec = VertexSplit {
        old_w: map.vertex_dart(p.w),
        slots: Slots::alloc(map, 3, 2),
    };
    rewire_split(map, &p, &rec, around);
    Ok(rec)
}

/// Rewrites the map for a planned split into the record's fresh slots; `around` is the old
/// `[p1, s1, q2, r2]`: the darts before and after `d1` in its face X and before and after
/// `twin(d2)` in its face Z.
fn rewire_split(map: &mut Map, p: &SplitPlan, rec: &VertexSplit, around: [Dart; 4]) {
    let (d1, t2) = (p.d1, p.d2.twin());
    let [p1, s1, q2, r2] = around;
    let (fx, fz) = (map.face(d1), map.face(t2));
    let old_w = rec.old_w;
    let boundary_w = map.face(old_w).is_none();
    let s = &rec.slots;
    let [h, h2, t1] = [s.edge(0), s.edge(1), s.edge(2)]; // v -> w, a -> v, v -> b
    let (v, fl, fr) = (s.vert(), s.face(0), s.face(1));
    let (t, oh2, ot1) = (h.twin(), h2.twin(), t1.twin());
    // twin(h2) takes the place of d1 in X, twin(t1) that of twin(d2) in Z.
    let repl = |x: Dart| {
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
        map.set_origin(y, v);
        y = map.rotate_cw(y);
    }
    map.set_next(repl(p1), oh2);
    map.set_next(oh2, repl(s1));
    map.set_next(repl(q2), ot1);
    map.set_next(ot1, repl(r2));
    for (x, n, o, f) in [
        (h, d1, v, fl),
        (d1, h2, p.w, fl),
        (h2, h, p.a, fl),
        (t, t1, p.w, fr),
        (t1, t2, v, fr),
        (t2, t, p.b, fr),
    ] {
        map.set_dart(x, n, o, f);
    }
    map.set_origin(oh2, v);
    map.set_face(oh2, fx);
    map.set_origin(ot1, p.b);
    map.set_face(ot1, fz);
    // The boundary corner of w goes with the arc that holds it.
    let vd = if boundary_w && p.record_moves {
        old_w
    } else if boundary_w && old_w == d1 {
        oh2
    } else {
        h
    };
    map.set_vertex_dart(v, vd);
    if p.record_moves {
        map.set_vertex_dart(p.w, d1);
    }
    // twin(t1) replaces twin(d2), possibly as b's boundary dart.
    if map.vertex_dart(p.b) == t2 {
        map.set_vertex_dart(p.b, ot1);
    }
    map.set_face_dart(fl, h);
    map.set_face_dart(fr, t);
    if fx.is_some_and(|f| map.face_dart(f) == d1) {
        map.set_face_dart(fx, oh2);
    }
    if fz.is_some_and(|f| map.face_dart(f) == t2) {
        map.set_face_dart(fz, ot1);
    }
}

impl VertexSplit {
    /// The new vertex `v`, which took the moved arc.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri, Vert};
    /// let mut map = gen::random_triangle(200, 1, 0, 3).map;
    /// let d1 = map.vertex_dart(Vert::new(0));
    /// let d2 = map.rotate_cw(map.rotate_cw(d1));
    /// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
    /// assert!(map.is_live_vertex(rec.created()));
    /// ```
    pub fn created(&self) -> Vert {
        self.slots.vert()
    }

    /// The new edge's dart from `v` to `w`: [`collapse_edge`] of it undoes the split up to
    /// slot numbers (the same map up to isomorphism; `undo` restores the very same arrays).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri, Vert};
    /// let mut map = gen::random_triangle(200, 1, 0, 3).map;
    /// let w = Vert::new(0);
    /// let d1 = map.vertex_dart(w);
    /// let d2 = map.rotate_cw(map.rotate_cw(d1));
    /// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
    /// assert_eq!(map.dest(rec.edge()), w);
    /// ```
    pub fn edge(&self) -> Dart {
        self.slots.edge(0)
    }

    /// Undoes the split: the map becomes equal (`==`) to the one before, provided it has not
    /// been changed since (other records undone in reverse order are fine).
    ///
    /// Returns [`Refusal::StaleRecord`] and changes nothing when the new edge, vertex and
    /// triangles are not as the split left them. Never panics, whatever the map.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri, Vert};
    /// let mut map = gen::random_triangle(200, 0, 2, 9).map;
    /// let before = map.clone();
    /// let d1 = map.vertex_dart(Vert::new(7));
    /// let d2 = map.rotate_cw(d1);
    /// let rec = tri::split_vertex(&mut map, d1, d2).unwrap();
    /// rec.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        let (guard, plan) = self.guard(map);
        guard.result()?;
        let p = plan.ok_or(Refusal::StaleRecord)?;
        apply(map, &p, Some(&self.slots));
        map.set_vertex_dart(p.u, self.old_w);
        Ok(())
    }

    /// The staleness checks of [`VertexSplit::undo`], in order, and the plan of the collapse
    /// of the record's edge that it makes.
    pub(super) fn guard(&self, map: &Map) -> (Guard, Option<Plan>) {
        let plan = plan(map, self.edge(), false).ok();
        let g = Guard::new().check("collapse of the edge applies", || plan.is_some());
        let Some(p) = &plan else {
            return (g, plan);
        };
        (self.guard_plan(g, map, p), plan)
    }

    fn guard_plan(&self, g: Guard, map: &Map, p: &Plan) -> Guard {
        let s = &self.slots;
        let (w, old_w) = (p.u, self.old_w);
        let new_edges = [s.edge(0).edge(), s.edge(1).edge(), s.edge(2).edge()];
        g.check("new vertex", || p.v == s.vert())
            .check("both triangles", || p.has_l() && p.has_r())
            .check("new edges", || {
                [p.h2.edge(), p.t1.edge()] == [new_edges[1], new_edges[2]]
            })
            .check("new faces", || {
                [map.face(p.h), map.face(p.h.twin())] == [Some(s.face(0)), Some(s.face(1))]
            })
            .check("old record of w", || {
                map.is_live_dart(old_w)
                    && !new_edges.contains(&old_w.edge())
                    && (map.origin(old_w) == w || map.origin(old_w) == p.v)
                    && face_after_collapse(map, p, old_w).is_none()
                        == (map.is_boundary_vertex(w) || map.is_boundary_vertex(p.v))
            })
            .check("slots releasable", || s.releasable(map))
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
