//! Quad collapse and its exact inverse, the vertex split (and the high-valence split built on it).
//!
//! Names used throughout: the quad `f` has darts `h0: a→b`, `h1: b→c`, `h2: c→d`, `h3: d→a`
//! (counter-clockwise), `oi = twin(hi)`. The collapse keeps the edges of `h0` (a–b) and `h2`
//! (c–d), deletes those of `h1` and `h3`, and merges `c` into `a`: `h0` takes the place of
//! `o1` in the face beyond b–c, `h2` the place of `o3` in the face beyond d–a. The split undoes
//! exactly that, so a split's separators are the collapse's `h0` and `h2`.

use super::{
    fdart_of, quad_of, replace_fdart, replace_vdart, restore_fdart, restore_vdart,
    valence_at_most_2, Neighbours, Slots,
};
use crate::map::{Dart, Face, Map, Vert, NONE};
use crate::ops::guard::Guard;
use crate::ops::Refusal;

/// The smallest valence [`split_high_valence`] splits.
pub const MIN_HIGH_VALENCE: usize = 6;

/// Visits the darts leaving `origin(from)` strictly between `from` and `to`, clockwise, and
/// returns the last dart before `to` (`from` itself if there is none in between).
/// `BadArguments` if `to` is not met within one turn (it does not leave the same vertex).
fn arc(map: &Map, from: Dart, to: Dart, mut visit: impl FnMut(Dart)) -> Result<Dart, Refusal> {
    let mut last = from;
    let mut x = map.rotate_cw(from);
    for _ in 0..map.dart_slots() {
        if x == to {
            return Ok(last);
        }
        if x == from {
            break;
        }
        visit(x);
        last = x;
        x = map.rotate_cw(x);
    }
    Err(Refusal::BadArguments)
}

/// What a quad collapse needs, found by its check.
#[derive(Clone, Copy, Debug)]
pub(super) struct CollapsePlan {
    h: [Dart; 4],
    /// a, b, c, d.
    v: [Vert; 4],
    /// `prev(o1)` and `prev(o3)`.
    p1: Dart,
    p3: Dart,
}

fn plan_collapse(map: &Map, d: Dart) -> Result<CollapsePlan, Refusal> {
    let h = quad_of(map, d)?;
    let v = h.map(|x| map.origin(x));
    let [a, b, c, dv] = v;
    if a == c {
        return Err(Refusal::CornersCoincide);
    }
    // The merged vertex's neighbours: b, d, and those of a and c off the quad.
    let mut nb = Neighbours::new();
    nb.push(b);
    nb.push(dv);
    let last_a = arc(map, h[0], h[3].twin(), |x| nb.push(map.dest(x)))?;
    let last_c = arc(map, h[2], h[1].twin(), |x| nb.push(map.dest(x)))?;
    nb.check([a, c])?;
    if map.is_boundary_vertex(a) && map.is_boundary_vertex(c) {
        return Err(Refusal::BoundaryPinch);
    }
    if valence_at_most_2(map, h[1]) || valence_at_most_2(map, h[3]) {
        return Err(Refusal::ValenceTooLow);
    }
    Ok(CollapsePlan {
        h,
        v,
        p1: last_c.twin(),
        p3: last_a.twin(),
    })
}

/// Rewires the map for a checked collapse; the caller frees the edges of `h1` and `h3`,
/// vertex `c` and the quad.
fn collapse_raw(map: &mut Map, p: &CollapsePlan) {
    let [h0, h1, h2, h3] = p.h;
    let (o0, o1, o2, o3) = (h0.twin(), h1.twin(), h2.twin(), h3.twin());
    let [a, b, c, d] = p.v;
    let (g1, g3) = (map.face(o1), map.face(o3));
    let (n1, n3) = (map.next(o1), map.next(o3));
    // Record for the merged vertex: its boundary dart if it has one, with o1 and o3 replaced
    // by the darts that take their places.
    let keep = if map.is_boundary_vertex(c) {
        map.vertex_dart(c)
    } else {
        map.vertex_dart(a)
    };
    let keep = if keep == o1 {
        h0
    } else if keep == o3 {
        h2
    } else {
        keep
    };
    // c's darts h2, C1..Cj move to a (rotate_cw reads no origins, so relabelling as we go
    // is safe).
    let mut x = h2;
    for _ in 0..map.dart_slots() {
        if x == o1 {
            break;
        }
        map.set_origin(x, a);
        x = map.rotate_cw(x);
    }
    map.set_next(p.p1, h0);
    map.set_next(h0, n1);
    map.set_face(h0, g1);
    map.set_next(p.p3, h2);
    map.set_next(h2, n3);
    map.set_face(h2, g3);
    map.set_vertex_dart(a, keep);
    replace_vdart(map, b, h1, o0);
    replace_vdart(map, d, h3, o2);
    replace_fdart(map, g1, o1, h0);
    replace_fdart(map, g3, o3, h2);
}

/// Checks whether [`collapse_quad`] applies to `d`; changes nothing.
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad, Refusal}, Dart};
/// let torus = gen::torus_grid(4, 4).map;
/// assert_eq!(quad::can_collapse_quad(&torus, Dart::new(0)), Ok(()));
/// // On a 1 x 1 grid every corner is on the boundary.
/// let square = gen::grid(1, 1).map;
/// let d = square.face_dart(zipmesh_kernel::Face::new(0));
/// assert_eq!(quad::can_collapse_quad(&square, d), Err(Refusal::BoundaryPinch));
/// ```
pub fn can_collapse_quad(map: &Map, d: Dart) -> Result<(), Refusal> {
    plan_collapse(map, d).map(|_| ())
}

/// Quad collapse: deletes the quad of `d` by merging its corner `a = origin(d)` with the
/// opposite corner `c = origin(next(next(d)))`.
///
/// ```text
///          d                        d
///        /   \                      |
///      h3     h2                    h2
///      /  f    \                    |
///     a         c       ==>         a   (c merged into a)
///      \       /                    |
///      h0     h1                    h0
///        \   /                      |
///          b                        b
/// ```
///
/// With the quad's darts `h0 = d: a→b`, `h1: b→c`, `h2: c→d`, `h3: d→a`: the face, the vertex
/// `c` and the edges of `h1` and `h3` disappear; the edge of `h0` now joins the merged vertex
/// to `b` and that of `h2` joins it to `d`. **Deltas:** V −1, E −2, F −1; the merged vertex
/// (handle `a`) has valence `val(a) + val(c) − 2`; `b` and `d` lose one each; every other
/// valence and every other face's degree is unchanged.
///
/// **Refusals, in the order checked:**
/// * [`Refusal::DeadHandle`]: `d` is not live.
/// * [`Refusal::Boundary`]: `d` is a boundary dart (there is no face to collapse).
/// * [`Refusal::WrongDegree`]: the face of `d` is not a quad.
/// * [`Refusal::CornersCoincide`]: `a == c`; the quad touches itself and merging a vertex
///   with itself is not a collapse.
/// * [`Refusal::Loop`]: the merged vertex would have a loop: an edge a–c off the quad, a loop
///   at `a` or `c`, or a quad corner `b` or `d` equal to `a` or `c`.
/// * [`Refusal::MultiEdge`]: the merged vertex would have two edges to one vertex: a common
///   neighbour of `a` and `c` other than through the quad, `b == d`, or an existing
///   multi-edge at `a` or `c` (the merged vertex must be simple, which is exactly what the
///   inverse split requires of the vertex it splits).
/// * [`Refusal::BoundaryPinch`]: `a` and `c` are both boundary vertices; the merged vertex
///   would have two boundary darts. This is exact: with one of them inside, the boundary
///   simply runs through the merged vertex, and no case with both on the boundary is safe.
/// * [`Refusal::ValenceTooLow`]: `b` or `d` has valence 2 and would be left with valence 1
///   (a dangling edge). A `b` or `d` of valence 3 is allowed to become a valence-2 vertex:
///   Q-zip makes such vertices on purpose and removes them with
///   [`remove_valence2`](super::remove_valence2).
///
/// Cost: O(val(a) + val(c)), no allocation unless the merged vertex has valence over 32.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let before = map.clone();
/// let d = Dart::new(0);
/// let (a, c) = (map.origin(d), map.origin(map.next(map.next(d))));
/// let rec = quad::collapse_quad(&mut map, d).unwrap();
/// assert_eq!((rec.kept(), rec.removed()), (a, c));
/// assert_eq!(map.valence(a), 4 + 4 - 2);
/// assert_eq!(map.num_vertices(), before.num_vertices() - 1);
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn collapse_quad(map: &mut Map, d: Dart) -> Result<QuadCollapse, Refusal> {
    let p = plan_collapse(map, d)?;
    let [h0, h1, _, h3] = p.h;
    let face = map.face(h0).unwrap_or(Face(NONE));
    let rec = QuadCollapse {
        h: p.h,
        v: p.v,
        face,
        faces: [map.face(h1.twin()), map.face(h3.twin())],
        old_vdart: p.v.map(|v| map.vertex_dart(v)),
        old_fdart: [
            map.face_dart(face),
            fdart_of(map, map.face(h1.twin())),
            fdart_of(map, map.face(h3.twin())),
        ],
    };
    collapse_raw(map, &p);
    Slots::deleted(&[h1, h3], p.v[2], &[face]).free(map);
    Ok(rec)
}

/// The record of a [`collapse_quad`]: what was merged, and everything its exact undo needs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct QuadCollapse {
    h: [Dart; 4],
    v: [Vert; 4],
    face: Face,
    /// The faces beyond b–c and d–a (`None` for the boundary).
    faces: [Option<Face>; 2],
    old_vdart: [Dart; 4],
    old_fdart: [Dart; 3],
}

impl QuadCollapse {
    /// The merged vertex (the handle of the corner `a = origin(d)`, which survives).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let a = map.origin(Dart::new(0));
    /// assert_eq!(quad::collapse_quad(&mut map, Dart::new(0)).unwrap().kept(), a);
    /// ```
    pub fn kept(&self) -> Vert {
        self.v[0]
    }

    /// The deleted corner `c` (its slot is now free).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let r = quad::collapse_quad(&mut map, Dart::new(0)).unwrap();
    /// assert!(!map.is_live_vertex(r.removed()));
    /// ```
    pub fn removed(&self) -> Vert {
        self.v[2]
    }

    /// The darts of the two merged edges, both leaving the merged vertex: to `b` (the old
    /// `h0`) and to `d` (the old `h2`). They are the separators of the inverse split.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let r = quad::collapse_quad(&mut map, Dart::new(0)).unwrap();
    /// let [to_b, to_d] = r.merged_edges();
    /// assert_eq!((map.origin(to_b), map.origin(to_d)), (r.kept(), r.kept()));
    /// ```
    pub fn merged_edges(&self) -> [Dart; 2] {
        [self.h[0], self.h[2]]
    }

    /// The deleted face.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let f = map.face(Dart::new(0)).unwrap();
    /// assert_eq!(quad::collapse_quad(&mut map, Dart::new(0)).unwrap().face(), f);
    /// ```
    pub fn face(&self) -> Face {
        self.face
    }

    /// Undoes the collapse: the vertex split of the merged vertex along its two merged edges,
    /// with the deleted slots taken back from the free lists, and every vertex and face record
    /// put back. With the map as the collapse left it (or restored to that by undoing later
    /// records in reverse order) the result is `==` the map before the collapse.
    ///
    /// [`Refusal::StaleRecord`] (map unchanged) if the freed slots are no longer on top of the
    /// free lists, the merged edges no longer leave the merged vertex, or the split would be
    /// refused. A foreign record that passes these checks still leaves a valid map.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::{quad, Refusal}, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let before = map.clone();
    /// let r = quad::collapse_quad(&mut map, Dart::new(0)).unwrap();
    /// r.clone().undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// assert_eq!(r.undo(&mut map), Err(Refusal::StaleRecord));
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        let (guard, plan) = self.guard(map);
        guard.result()?;
        let plan = plan.ok_or(Refusal::StaleRecord)?;
        let [_, h1, _, h3] = self.h;
        self.deleted().reclaim(map)?;
        split_raw(map, &plan, h1, h3, self.v[2], self.face);
        for (v, old) in self.v.into_iter().zip(self.old_vdart) {
            restore_vdart(map, v, old);
        }
        restore_fdart(map, Some(self.face), self.old_fdart[0]);
        restore_fdart(map, self.faces[0], self.old_fdart[1]);
        restore_fdart(map, self.faces[1], self.old_fdart[2]);
        Ok(())
    }

    /// The slots the collapse freed, in its order: the edges of `h1`, `h3`, `c`, the quad.
    fn deleted(&self) -> Slots {
        Slots::deleted(&[self.h[1], self.h[3]], self.v[2], &[self.face])
    }

    /// The staleness checks of [`QuadCollapse::undo`], in order, and the plan of the split
    /// it makes.
    pub(super) fn guard(&self, map: &Map) -> (Guard, Option<SplitPlan>) {
        let [h0, h1, h2, h3] = self.h;
        let [a, b, c, d] = self.v;
        let g = Guard::new()
            .check("removed vertex in range", || c.index() < map.vertex_slots())
            .check("face in range", || self.face.index() < map.face_slots())
            .check("h1 in range", || h1.index() < map.dart_slots())
            .check("h3 in range", || h3.index() < map.dart_slots())
            .check("h0 live", || map.is_live_dart(h0))
            .check("h2 live", || map.is_live_dart(h2))
            .check("h0 leaves a", || map.origin(h0) == a)
            .check("h2 leaves a", || map.origin(h2) == a)
            .check("h0 ends at b", || map.dest(h0) == b)
            .check("h2 ends at d", || map.dest(h2) == d)
            .check("removed vertex dead", || !map.is_live_vertex(c))
            .check("face dead", || !map.is_live_face(self.face));
        if g.failed().is_some() {
            return (g, None);
        }
        let plan = plan_split(map, h0, h2).ok();
        let g = g
            .check("split applies", || plan.is_some())
            .check("freed slots on the free lists", || {
                self.deleted().on_free_lists(map)
            });
        (g, plan)
    }
}

/// What a vertex split needs, found by its check.
#[derive(Clone, Copy, Debug)]
pub(super) struct SplitPlan {
    w: Vert,
    s: [Dart; 2],
    /// The clockwise predecessors of `s[0]` and `s[1]` around `w`.
    pred: [Dart; 2],
}

fn plan_split(map: &Map, s1: Dart, s2: Dart) -> Result<SplitPlan, Refusal> {
    if !map.is_live_dart(s1) || !map.is_live_dart(s2) {
        return Err(Refusal::DeadHandle);
    }
    let w = map.origin(s1);
    if s1 == s2 || map.origin(s2) != w {
        return Err(Refusal::BadArguments);
    }
    let mut nb = Neighbours::new();
    nb.push(map.dest(s1));
    nb.push(map.dest(s2));
    let pred2 = arc(map, s1, s2, |x| nb.push(map.dest(x)))?;
    let pred1 = arc(map, s2, s1, |x| nb.push(map.dest(x)))?;
    nb.check([w, w])?;
    if map.rotate_cw(s1.twin()) == s1.twin() || map.rotate_cw(s2.twin()) == s2.twin() {
        return Err(Refusal::ValenceTooLow);
    }
    Ok(SplitPlan {
        w,
        s: [s1, s2],
        pred: [pred1, pred2],
    })
}

/// Rewires the map for a checked split into the given (dead) slots: `h1` and `h3` are the
/// new edges' darts `b→c` and `d→a`, `c` the new vertex, `f` the new quad.
fn split_raw(map: &mut Map, p: &SplitPlan, h1: Dart, h3: Dart, c: Vert, f: Face) {
    let [h0, h2] = p.s;
    let (o1, o3) = (h1.twin(), h3.twin());
    let a = p.w;
    let (b, d) = (map.dest(h0), map.dest(h2));
    let (p1, p3) = (p.pred[0].twin(), p.pred[1].twin());
    let (n1, n3) = (map.next(h0), map.next(h2));
    let (g1, g3) = (map.face(h0), map.face(h2));
    let va = map.vertex_dart(a);
    let a_boundary = map.is_boundary_dart(va);
    // h2 and the darts clockwise after it, up to h0, move to c.
    let mut va_moves = false;
    let mut x = h2;
    for _ in 0..map.dart_slots() {
        if x == h0 {
            break;
        }
        va_moves |= x == va;
        map.set_origin(x, c);
        x = map.rotate_cw(x);
    }
    // o1 takes h0's place beyond b–c, o3 takes h2's place beyond d–a.
    map.set_next(p1, o1);
    map.set_next(o1, n1);
    map.set_face(o1, g1);
    map.set_origin(o1, c);
    map.set_next(p3, o3);
    map.set_next(o3, n3);
    map.set_face(o3, g3);
    map.set_origin(o3, a);
    for (x, n) in [(h0, h1), (h1, h2), (h2, h3), (h3, h0)] {
        map.set_next(x, n);
        map.set_face(x, f);
    }
    map.set_origin(h1, b);
    map.set_origin(h3, d);
    map.set_face_dart(f, h0);
    replace_fdart(map, g1, h0, o1);
    replace_fdart(map, g3, h2, o3);
    // Vertex records: a boundary dart keeps its role, through the dart that took its place.
    let (ra, rc) = if a_boundary {
        if va == h0 {
            (h0, o1)
        } else if va == h2 {
            (o3, h2)
        } else if va_moves {
            (h0, va)
        } else {
            (va, h2)
        }
    } else if va_moves {
        (h0, h2)
    } else {
        (va, h2)
    };
    map.set_vertex_dart(a, ra);
    map.set_vertex_dart(c, rc);
}

/// Checks whether [`split_vertex`] applies to the separators `s1`, `s2`; changes nothing.
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad, Refusal}, Vert};
/// let map = gen::torus_grid(4, 4).map;
/// let s1 = map.vertex_dart(Vert::new(5));
/// let s2 = map.rotate_cw(map.rotate_cw(s1));
/// assert_eq!(quad::can_split_vertex(&map, s1, s2), Ok(()));
/// assert_eq!(quad::can_split_vertex(&map, s1, s1), Err(Refusal::BadArguments));
/// ```
pub fn can_split_vertex(map: &Map, s1: Dart, s2: Dart) -> Result<(), Refusal> {
    plan_split(map, s1, s2).map(|_| ())
}

/// Vertex split: splits `w = origin(s1) = origin(s2)` along its edges `s1: w→a` and
/// `s2: w→b` into two vertices joined by a new quad; the exact inverse of [`collapse_quad`].
///
/// ```text
///           a                       a
///           |                     /   \
///   (arc₂)  w  (arc₁)     ==>   w'  f   w      w  keeps s1 (to a), arc₁, gets a new edge to b
///           |                     \   /        w' keeps s2 (to b), arc₂, gets a new edge to a
///           b                       b
/// ```
///
/// Let arc₁ be the darts strictly between `s1` and `s2` clockwise around `w`, arc₂ those
/// strictly between `s2` and `s1`. **Which copy keeps the handle:** `w` keeps `s1` and arc₁
/// and gets a new edge to `b`; the new vertex `w'` gets `s2` and arc₂ and a new edge to `a`.
/// The new quad, counter-clockwise, is `s1: w→a`, `a→w'`, `s2: w'→b`, `b→w`. This is what
/// makes the two operators exact inverses: [`collapse_quad`] at `s1` merges `w'` back into
/// `w`, and a collapse's [`QuadCollapse::merged_edges`] are its inverse split's separators.
///
/// **Deltas:** V +1, E +2, F +1; `val(w) = |arc₁| + 2`, `val(w') = |arc₂| + 2`; `a` and `b`
/// gain one each; every other valence and every old face's degree is unchanged.
///
/// **Boundary:** every split of a boundary vertex is allowed. Exactly one boundary dart leaves
/// `w`; after the split it leaves exactly one of the copies (`w'` if it was `s1` or in arc₂,
/// through the new dart that takes `s1`'s place; `w` otherwise), so the boundary is never
/// pinched, and the inverse collapse (one merged corner on the boundary) is allowed.
///
/// **Refusals, in the order checked:**
/// * [`Refusal::DeadHandle`]: a separator is not live.
/// * [`Refusal::BadArguments`]: the separators are equal or leave different vertices.
/// * [`Refusal::Loop`] / [`Refusal::MultiEdge`]: `w` has a loop, or two edges to one vertex.
///   Splitting such a vertex would either keep the defect, create one (a copy with two
///   edges to `a` or `b`), or make a map whose inverse collapse is refused; so, exactly like
///   the collapse, only simple vertices take part.
/// * [`Refusal::ValenceTooLow`]: `a` or `b` has valence 1 (the tip of a dangling edge); the
///   inverse collapse would leave it with valence 1 again.
///
/// Cost: O(val(w)), no allocation unless `w` has valence over 32 (the free lists or the
/// arrays grow only when there are no free slots).
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Vert};
/// let mut map = gen::torus_grid(4, 4).map;
/// let before = map.clone();
/// let s1 = map.vertex_dart(Vert::new(5));
/// let s2 = map.rotate_cw(map.rotate_cw(s1)); // the opposite edge
/// let rec = quad::split_vertex(&mut map, s1, s2).unwrap();
/// assert_eq!((map.valence(rec.kept()), map.valence(rec.created())), (3, 3));
/// assert_eq!(map.num_faces(), before.num_faces() + 1);
/// assert_eq!(map.check(), Ok(()));
/// rec.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn split_vertex(map: &mut Map, s1: Dart, s2: Dart) -> Result<VertexSplit, Refusal> {
    let p = plan_split(map, s1, s2)?;
    Ok(split_with_plan(map, &p))
}

fn split_with_plan(map: &mut Map, p: &SplitPlan) -> VertexSplit {
    let [h0, h2] = p.s;
    let (b, d) = (map.dest(h0), map.dest(h2));
    let faces = [map.face(h0), map.face(h2)];
    let old_fdart = faces.map(|f| fdart_of(map, f));
    let old_vdart = [p.w, b, d].map(|v| map.vertex_dart(v));
    let slots = Slots::alloc(map, 2, 1);
    let [h1, h3] = [slots.edge(0), slots.edge(1)];
    split_raw(map, p, h1, h3, slots.vert(), slots.face(0));
    VertexSplit {
        h: [h0, h1, h2, h3],
        v: [p.w, b, slots.vert(), d],
        slots,
        faces,
        old_vdart,
        old_fdart,
    }
}

/// The record of a [`split_vertex`] or [`split_high_valence`]: the new elements, and what its
/// exact undo needs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VertexSplit {
    /// The new quad: `s1`, new `a→w'`, `s2`, new `b→w`.
    h: [Dart; 4],
    /// w, a, w', b.
    v: [Vert; 4],
    slots: Slots,
    /// The faces of `s1` and `s2` before the split.
    faces: [Option<Face>; 2],
    /// Records of w, a, b before.
    old_vdart: [Dart; 3],
    old_fdart: [Dart; 2],
}

impl VertexSplit {
    /// The copy that keeps the old handle (with `s1` and arc₁).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Vert};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let s1 = map.vertex_dart(Vert::new(5));
    /// let s2 = map.rotate_cw(s1);
    /// assert_eq!(quad::split_vertex(&mut map, s1, s2).unwrap().kept(), Vert::new(5));
    /// ```
    pub fn kept(&self) -> Vert {
        self.v[0]
    }

    /// The new vertex (with `s2` and arc₂).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Vert};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let s1 = map.vertex_dart(Vert::new(5));
    /// let s2 = map.rotate_cw(s1);
    /// let r = quad::split_vertex(&mut map, s1, s2).unwrap();
    /// assert_eq!(map.origin(s2), r.created());
    /// ```
    pub fn created(&self) -> Vert {
        self.v[2]
    }

    /// The new quad.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Vert};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let s1 = map.vertex_dart(Vert::new(5));
    /// let s2 = map.rotate_cw(s1);
    /// let r = quad::split_vertex(&mut map, s1, s2).unwrap();
    /// assert_eq!(map.degree(r.face()), 4);
    /// assert_eq!(map.face(s1), Some(r.face()));
    /// ```
    pub fn face(&self) -> Face {
        self.slots.face(0)
    }

    /// The new quad's darts counter-clockwise from `s1`: `[s1, a→w', s2, b→w]`; the second
    /// and fourth are the new edges. `quad()[0]` is the dart whose collapse undoes the split.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Vert};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let s1 = map.vertex_dart(Vert::new(5));
    /// let s2 = map.rotate_cw(s1);
    /// let r = quad::split_vertex(&mut map, s1, s2).unwrap();
    /// let q = r.quad();
    /// assert_eq!(map.next(q[0]), q[1]);
    /// assert_eq!(map.origin(q[1]), map.dest(s1));
    /// ```
    pub fn quad(&self) -> [Dart; 4] {
        self.h
    }

    /// Undoes the split: the quad collapse of the new quad at `s1`, with the new slots given
    /// back exactly (cut off the arrays if they were appended, returned to the free lists
    /// otherwise) and every vertex and face record put back, giving a map `==` the one before
    /// the split (with the map as the split left it, or restored to that).
    ///
    /// [`Refusal::StaleRecord`] (map unchanged) if the new quad is gone or changed, the
    /// collapse would be refused, or appended slots are no longer the last ones.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Vert};
    /// let mut map = gen::grid(3, 3).map;
    /// let before = map.clone();
    /// let s1 = map.vertex_dart(Vert::new(5));
    /// let s2 = map.rotate_cw(map.rotate_cw(s1));
    /// let r = quad::split_vertex(&mut map, s1, s2).unwrap();
    /// r.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        let (guard, plan) = self.guard(map);
        guard.result()?;
        let plan = plan.ok_or(Refusal::StaleRecord)?;
        collapse_raw(map, &plan);
        self.slots.release(map);
        let [w, a, _, b] = self.v;
        for (v, old) in [w, a, b].into_iter().zip(self.old_vdart) {
            restore_vdart(map, v, old);
        }
        restore_fdart(map, self.faces[0], self.old_fdart[0]);
        restore_fdart(map, self.faces[1], self.old_fdart[1]);
        Ok(())
    }

    /// The staleness checks of [`VertexSplit::undo`], in order, and the plan of the
    /// collapse it makes.
    pub(super) fn guard(&self, map: &Map) -> (Guard, Option<CollapsePlan>) {
        let plan = plan_collapse(map, self.h[0]).ok();
        let g = Guard::new()
            .check("collapse applies", || plan.is_some())
            .check("same quad", || plan.is_some_and(|p| p.h == self.h))
            .check("same corners", || plan.is_some_and(|p| p.v == self.v))
            .check("same face", || {
                map.face(self.h[0]) == Some(self.slots.face(0))
            })
            .check("slots releasable", || self.slots.releasable(map));
        (g, plan)
    }
}

fn plan_high_valence(map: &Map, v: Vert, first: Dart) -> Result<SplitPlan, Refusal> {
    if !map.is_live_vertex(v) || !map.is_live_dart(first) {
        return Err(Refusal::DeadHandle);
    }
    if map.origin(first) != v {
        return Err(Refusal::BadArguments);
    }
    let k = map.valence(v);
    if k < MIN_HIGH_VALENCE {
        return Err(Refusal::WrongValence);
    }
    let mut s2 = first;
    for _ in 0..k / 2 {
        s2 = map.rotate_cw(s2);
    }
    plan_split(map, first, s2)
}

/// Checks whether [`split_high_valence`] applies; changes nothing.
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad, Refusal}, Vert};
/// let map = gen::torus_grid(4, 4).map;
/// let v = Vert::new(0);
/// assert_eq!(quad::can_split_high_valence(&map, v, map.vertex_dart(v)), Err(Refusal::WrongValence));
/// ```
pub fn can_split_high_valence(map: &Map, v: Vert, first: Dart) -> Result<(), Refusal> {
    plan_high_valence(map, v, first).map(|_| ())
}

/// Splits a vertex `v` of valence `k >= 6` ([`MIN_HIGH_VALENCE`]) into two of lower valence:
/// the [`split_vertex`] with separators `first` and the dart `k / 2` steps clockwise from it
/// (the "opposite" edge; for odd `k` the one just before the middle).
///
/// **Deltas:** those of the vertex split with `|arc₁| = k/2 − 1` and `|arc₂| = k − k/2 − 1`:
/// `v` keeps valence `⌊k/2⌋ + 1`, the new vertex gets `⌈k/2⌉ + 1` (a valence 6 becomes two
/// 4s, a 7 a 4 and a 5), and the two separators' far ends gain one each. V +1, E +2, F +1.
///
/// **Refusals:** [`Refusal::DeadHandle`]; [`Refusal::BadArguments`] if `first` does not
/// leave `v`; [`Refusal::WrongValence`] if `k < 6`; then those of [`split_vertex`].
/// Cost: O(k).
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart, Vert};
/// // One collapse on a regular torus makes a valence 6 (4 + 4 - 2); split it again.
/// let mut map = gen::torus_grid(5, 5).map;
/// let c = quad::collapse_quad(&mut map, Dart::new(0)).unwrap();
/// let v = c.kept();
/// assert_eq!(map.valence(v), 6);
/// let first = map.vertex_dart(v);
/// let s = quad::split_high_valence(&mut map, v, first).unwrap();
/// assert_eq!((map.valence(s.kept()), map.valence(s.created())), (4, 4));
/// assert_eq!(map.check(), Ok(()));
/// ```
pub fn split_high_valence(map: &mut Map, v: Vert, first: Dart) -> Result<VertexSplit, Refusal> {
    let p = plan_high_valence(map, v, first)?;
    Ok(split_with_plan(map, &p))
}
