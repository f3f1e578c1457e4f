//! Valence-2 removal (doublet removal) and its exact inverse, the doublet insertion.
//!
//! Names: the valence-2 vertex `v` has darts `x: v→p` and `y: v→q`. The quad of `x` is
//! `[x, x1: p→r, x2: r→q, ty]` and the quad of `y` is `[y, y1: q→s, y2: s→p, tx]`
//! (`tx`, `ty` the twins). Removal keeps the face of `x` as the merged quad
//! `[x1, x2, y1, y2] = (p, r, q, s)`; insertion splits that quad back along its diagonal p–q.

use super::{fdart_of, quad_of, replace_vdart, restore_fdart, restore_vdart, Slots};
use crate::map::{Dart, Face, Map, Vert, NONE};
use crate::ops::guard::Guard;
use crate::ops::Refusal;

/// Whether the vertices are pairwise distinct.
fn distinct<const N: usize>(v: [Vert; N]) -> bool {
    (1..N).all(|i| !v[..i].contains(&v[i]))
}

/// What a removal needs: the two quads from `x` and from `y`.
#[derive(Clone, Copy, Debug)]
pub(super) struct RemovalPlan {
    qx: [Dart; 4],
    qy: [Dart; 4],
}

fn plan_removal(map: &Map, x: Dart) -> Result<RemovalPlan, Refusal> {
    if !map.is_live_dart(x) {
        return Err(Refusal::DeadHandle);
    }
    let v = map.origin(x);
    if map.is_boundary_vertex(v) {
        return Err(Refusal::Boundary);
    }
    let y = map.rotate_cw(x);
    if y == x || map.rotate_cw(y) != x {
        return Err(Refusal::WrongValence);
    }
    if map.face(x) == map.face(y) {
        return Err(Refusal::SameFace);
    }
    let qx = quad_of(map, x)?;
    let qy = quad_of(map, y)?;
    // Valence 2: next(ty) = rotate_cw(y) = x, so the quad of x ends with ty (and that of y
    // with tx).
    let corners = [
        v,
        map.origin(qx[1]),
        map.origin(qx[2]),
        map.origin(qy[1]),
        map.origin(qy[2]),
    ];
    if !distinct(corners) {
        return Err(Refusal::CornersCoincide);
    }
    Ok(RemovalPlan { qx, qy })
}

/// Rewires the map for a checked removal; the caller frees the edges of `x` and `y`, `v` and
/// the face of `y`.
fn removal_raw(map: &mut Map, p: &RemovalPlan) {
    let [x, x1, x2, ty] = p.qx;
    let [_, y1, y2, tx] = p.qy;
    let f = map.face(x);
    let (pv, qv) = (map.origin(x1), map.origin(y1));
    map.set_next(x2, y1);
    map.set_next(y2, x1);
    map.set_face(y1, f);
    map.set_face(y2, f);
    replace_vdart(map, pv, tx, x1);
    replace_vdart(map, qv, ty, y1);
    let fd = fdart_of(map, f);
    if fd == x || fd == ty {
        map.set_face_dart(f, x1);
    }
}

/// Checks whether [`remove_valence2`] applies to `x`; changes nothing.
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad, Refusal}, Dart};
/// let map = gen::torus_grid(4, 4).map;
/// assert_eq!(quad::can_remove_valence2(&map, Dart::new(0)), Err(Refusal::WrongValence));
/// ```
pub fn can_remove_valence2(map: &Map, x: Dart) -> Result<(), Refusal> {
    plan_removal(map, x).map(|_| ())
}

/// Valence-2 removal: deletes the interior valence-2 vertex `v = origin(x)` and its two edges;
/// its two quads become one quad. The face of `x` survives as the merged quad.
///
/// ```text
///        r                     r
///      /   \                 /   \
///     p--v--q      ==>      p     q
///      \   /                 \   /
///        s                     s
/// ```
///
/// **Deltas:** V −1, E −2, F −1; the two neighbours `p = dest(x)` and `q` lose one each;
/// every other valence is unchanged; the merged face is a quad `(p, r, q, s)`.
///
/// **Refusals, in the order checked:**
/// * [`Refusal::DeadHandle`]: `x` is not live.
/// * [`Refusal::Boundary`]: `v` is on the boundary (its two edges do not bound two faces).
/// * [`Refusal::WrongValence`]: `v` does not have valence 2.
/// * [`Refusal::SameFace`]: both edges of `v` lie on one face (deleting them would not merge
///   two faces).
/// * [`Refusal::WrongDegree`]: one of the two faces is not a quad.
/// * [`Refusal::CornersCoincide`]: `v`, `p`, `r`, `q`, `s` are not pairwise distinct. This
///   keeps the merged quad proper, ensures `p` and `q` keep valence at least 2 (each has
///   edges to `r` and `s`), and is exactly what the inverse insertion requires.
///
/// Cost: O(1).
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let before = map.clone();
/// let ins = quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
/// let x = map.vertex_dart(ins.vertex());
/// let rem = quad::remove_valence2(&mut map, x).unwrap();
/// assert_eq!(map.num_faces(), before.num_faces());
/// rem.undo(&mut map).unwrap();
/// ins.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn remove_valence2(map: &mut Map, x: Dart) -> Result<Valence2Removal, Refusal> {
    let p = plan_removal(map, x)?;
    let x1 = p.qx[1];
    let [y, y1, ..] = p.qy;
    let f = map.face(x).unwrap_or(Face(NONE));
    let g = map.face(y).unwrap_or(Face(NONE));
    let v = map.origin(x);
    let (pv, qv) = (map.origin(x1), map.origin(y1));
    let rec = Valence2Removal {
        qx: p.qx,
        qy: p.qy,
        v: [v, pv, qv],
        faces: [f, g],
        old_vdart: [v, pv, qv].map(|u| map.vertex_dart(u)),
        old_fdart: [map.face_dart(f), map.face_dart(g)],
    };
    removal_raw(map, &p);
    Slots::deleted(&[x, y], v, &[g]).free(map);
    Ok(rec)
}

/// The record of a [`remove_valence2`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Valence2Removal {
    qx: [Dart; 4],
    qy: [Dart; 4],
    /// v, p, q.
    v: [Vert; 3],
    /// The kept face and the deleted one.
    faces: [Face; 2],
    old_vdart: [Dart; 3],
    old_fdart: [Dart; 2],
}

impl Valence2Removal {
    /// The deleted vertex.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let ins = quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
    /// let x = map.vertex_dart(ins.vertex());
    /// let rem = quad::remove_valence2(&mut map, x).unwrap();
    /// assert_eq!(rem.removed(), ins.vertex());
    /// ```
    pub fn removed(&self) -> Vert {
        self.v[0]
    }

    /// The merged quad (the face of `x`, which survives).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let ins = quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
    /// let x = map.vertex_dart(ins.vertex());
    /// let rem = quad::remove_valence2(&mut map, x).unwrap();
    /// assert_eq!(map.degree(rem.face()), 4);
    /// ```
    pub fn face(&self) -> Face {
        self.faces[0]
    }

    /// The quad merged away (its slot is free after the removal).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let ins = quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
    /// let before = map.clone();
    /// let x = map.vertex_dart(ins.vertex());
    /// let rem = quad::remove_valence2(&mut map, x).unwrap();
    /// assert!(before.is_live_face(rem.deleted_face()) && !map.is_live_face(rem.deleted_face()));
    /// ```
    pub fn deleted_face(&self) -> Face {
        self.faces[1]
    }

    /// Undoes the removal: the doublet insertion into the merged quad along `p–q`, with the
    /// deleted slots taken back from the free lists and every record put back (`==` the map
    /// before, with the map as the removal left it).
    ///
    /// [`Refusal::StaleRecord`] (map unchanged) if the slots are not on top of the free lists
    /// or the merged quad is gone or changed.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::{quad, Refusal}, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let ins = quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
    /// let before = map.clone();
    /// let x = map.vertex_dart(ins.vertex());
    /// let rem = quad::remove_valence2(&mut map, x).unwrap();
    /// rem.clone().undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// assert_eq!(rem.undo(&mut map), Err(Refusal::StaleRecord));
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.guard(map).result()?;
        let [x, x1, x2, _] = self.qx;
        let [y, y1, y2, _] = self.qy;
        let [v, ..] = self.v;
        Slots::deleted(&[x, y], v, &[self.faces[1]]).reclaim(map)?;
        insertion_raw(map, [x1, x2, y1, y2], x, y, v, self.faces[1]);
        for (u, old) in self.v.into_iter().zip(self.old_vdart) {
            restore_vdart(map, u, old);
        }
        restore_fdart(map, Some(self.faces[0]), self.old_fdart[0]);
        restore_fdart(map, Some(self.faces[1]), self.old_fdart[1]);
        Ok(())
    }

    /// The staleness checks of [`Valence2Removal::undo`], in order.
    pub(super) fn guard(&self, map: &Map) -> Guard {
        let [x, x1, x2, _] = self.qx;
        let [y, y1, y2, _] = self.qy;
        let [v, ..] = self.v;
        let g = Guard::new()
            .check("x in range", || x.index() < map.dart_slots())
            .check("y in range", || y.index() < map.dart_slots())
            .check("removed vertex in range", || v.index() < map.vertex_slots())
            .check("face in range", || self.faces[1].index() < map.face_slots())
            .check("x dead", || !map.is_live_dart(x))
            .check("y dead", || !map.is_live_dart(y))
            .check("merged face kept", || map.face(x1) == Some(self.faces[0]));
        if g.failed().is_some() {
            return g;
        }
        let plan = plan_insertion(map, x1);
        g.check("insertion applies", || plan.is_ok())
            .check("same quad", || plan == Ok([x1, x2, y1, y2]))
            .check("freed slots on the free lists", || {
                Slots::deleted(&[x, y], v, &[self.faces[1]]).on_free_lists(map)
            })
    }
}

fn plan_insertion(map: &Map, d: Dart) -> Result<[Dart; 4], Refusal> {
    let q = quad_of(map, d)?;
    if !distinct(q.map(|x| map.origin(x))) {
        return Err(Refusal::CornersCoincide);
    }
    Ok(q)
}

/// Rewires the map for a checked insertion into the quad `[x1, x2, y1, y2]`, with `x` and `y`
/// the new darts leaving the new vertex `v` and `g` the new face.
fn insertion_raw(map: &mut Map, q: [Dart; 4], x: Dart, y: Dart, v: Vert, g: Face) {
    let [x1, x2, y1, y2] = q;
    let (tx, ty) = (x.twin(), y.twin());
    let f = map.face(x1);
    let (pv, qv) = (map.origin(x1), map.origin(y1));
    for (a, b) in [(x, x1), (x2, ty), (ty, x), (y, y1), (y2, tx), (tx, y)] {
        map.set_next(a, b);
    }
    for d in [x, ty] {
        map.set_face(d, f);
    }
    for d in [y, y1, y2, tx] {
        map.set_face(d, g);
    }
    map.set_origin(x, v);
    map.set_origin(y, v);
    map.set_origin(tx, pv);
    map.set_origin(ty, qv);
    map.set_vertex_dart(v, x);
    map.set_face_dart(g, y);
    let fd = fdart_of(map, f);
    if fd == y1 || fd == y2 {
        map.set_face_dart(f, x1);
    }
}

/// Checks whether [`insert_doublet`] applies to `d`; changes nothing.
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad, Refusal}, Dart};
/// let map = gen::grid(2, 2).map;
/// assert_eq!(quad::can_insert_doublet(&map, Dart::new(0)), Ok(()));
/// let outside = map.vertex_dart(zipmesh_kernel::Vert::new(0)); // a boundary dart
/// assert_eq!(quad::can_insert_doublet(&map, outside), Err(Refusal::Boundary));
/// ```
pub fn can_insert_doublet(map: &Map, d: Dart) -> Result<(), Refusal> {
    plan_insertion(map, d).map(|_| ())
}

/// Doublet insertion: splits the quad of `d` along its diagonal from `p = origin(d)` to
/// `q = origin(next(next(d)))` by a new valence-2 vertex joined to `p` and `q`; the exact
/// inverse of [`remove_valence2`].
///
/// ```text
///        r                     r
///      /   \                 /   \
///     p     q      ==>      p--v--q
///      \   /                 \   /
///        s                     s
/// ```
///
/// The face of `d` keeps `d` and `next(d)` (it becomes `(v, p, r, q)`); the new face holds
/// the other two old darts (`(v, q, s, p)`). **Deltas:** V +1, E +2, F +1; the new vertex has
/// valence 2; `p` and `q` gain one each; every other valence is unchanged; both faces are quads.
///
/// **Refusals, in the order checked:** [`Refusal::DeadHandle`]; [`Refusal::Boundary`] (`d` is
/// a boundary dart); [`Refusal::WrongDegree`] (not a quad); [`Refusal::CornersCoincide`] (the
/// quad's four corners are not distinct: with `p == q` the new vertex would have two edges to
/// one vertex, and the inverse removal requires four distinct corners).
///
/// Cost: O(1) (the arrays grow only when there are no free slots).
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let before = map.clone();
/// let r = quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
/// assert_eq!(map.valence(r.vertex()), 2);
/// assert_eq!(map.check(), Ok(()));
/// r.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn insert_doublet(map: &mut Map, d: Dart) -> Result<DoubletInsertion, Refusal> {
    let q = plan_insertion(map, d)?;
    let f = map.face(d).unwrap_or(Face(NONE));
    let (pv, qv) = (map.origin(q[0]), map.origin(q[2]));
    let old_vdart = [map.vertex_dart(pv), map.vertex_dart(qv)];
    let old_fdart = fdart_of(map, Some(f));
    let slots = Slots::alloc(map, 2, 1);
    let [x, y] = [slots.edge(0), slots.edge(1)];
    insertion_raw(map, q, x, y, slots.vert(), slots.face(0));
    Ok(DoubletInsertion {
        q,
        slots,
        face: f,
        ends: [pv, qv],
        old_vdart,
        old_fdart,
    })
}

/// The record of an [`insert_doublet`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DoubletInsertion {
    q: [Dart; 4],
    slots: Slots,
    face: Face,
    ends: [Vert; 2],
    old_vdart: [Dart; 2],
    old_fdart: Dart,
}

impl DoubletInsertion {
    /// The new valence-2 vertex.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let r = quad::insert_doublet(&mut map, Dart::new(0)).unwrap();
    /// assert_eq!(map.valence(r.vertex()), 2);
    /// ```
    pub fn vertex(&self) -> Vert {
        self.slots.vert()
    }

    /// The new face (the half without `d`).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let d = Dart::new(0);
    /// let r = quad::insert_doublet(&mut map, d).unwrap();
    /// assert_ne!(map.face(d), Some(r.face()));
    /// assert_eq!(map.degree(r.face()), 4);
    /// ```
    pub fn face(&self) -> Face {
        self.slots.face(0)
    }

    /// The new darts leaving the new vertex: to `p` (in the old face) and to `q` (in the new
    /// face).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let d = Dart::new(0);
    /// let r = quad::insert_doublet(&mut map, d).unwrap();
    /// let [to_p, _] = r.darts();
    /// assert_eq!(map.dest(to_p), map.origin(d));
    /// ```
    pub fn darts(&self) -> [Dart; 2] {
        [self.slots.edge(0), self.slots.edge(1)]
    }

    /// Undoes the insertion: the valence-2 removal of the new vertex keeping the old face,
    /// with the new slots given back exactly and the old records put back (`==` the map
    /// before, with the map as the insertion left it).
    ///
    /// [`Refusal::StaleRecord`] (map unchanged) if the new vertex or its quads changed, or
    /// appended slots are no longer the last ones.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad, Dart};
    /// let mut map = gen::grid(2, 2).map;
    /// let before = map.clone();
    /// let r = quad::insert_doublet(&mut map, Dart::new(2)).unwrap();
    /// r.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        let (guard, plan) = self.guard(map);
        guard.result()?;
        let plan = plan.ok_or(Refusal::StaleRecord)?;
        removal_raw(map, &plan);
        self.slots.release(map);
        for (u, old) in self.ends.into_iter().zip(self.old_vdart) {
            restore_vdart(map, u, old);
        }
        restore_fdart(map, Some(self.face), self.old_fdart);
        Ok(())
    }

    /// The staleness checks of [`DoubletInsertion::undo`], in order, and the plan of the
    /// removal it makes.
    pub(super) fn guard(&self, map: &Map) -> (Guard, Option<RemovalPlan>) {
        let [x, y] = self.darts();
        let [x1, x2, y1, y2] = self.q;
        let plan = plan_removal(map, x).ok();
        let g = Guard::new()
            .check("removal applies", || plan.is_some())
            .check("same quad of x", || {
                plan.is_some_and(|p| p.qx == [x, x1, x2, y.twin()])
            })
            .check("same quad of y", || {
                plan.is_some_and(|p| p.qy == [y, y1, y2, x.twin()])
            })
            .check("same face of x", || map.face(x) == Some(self.face))
            .check("same face of y", || map.face(y) == Some(self.slots.face(0)))
            .check("slots releasable", || self.slots.releasable(map));
        (g, plan)
    }
}
