//! Edge rotation: the quad analogue of an edge flip.
//!
//! Names: the edge's dart `h: u→v` lies in the quad `[h, h1: v→x, h2: x→y, h3: y→u]`, its
//! twin `t: v→u` in `[t, t1: u→z, t2: z→w, t3: w→v]`. Without the edge the two quads form the
//! hexagon `v, x, y, u, z, w` (counter-clockwise); the edge is one of its three long
//! diagonals, and a rotation replaces it by the next one: `x–z` counter-clockwise (each end
//! moves one corner counter-clockwise), `y–w` clockwise.

use super::{quad_of, replace_fdart, replace_vdart, restore_fdart, restore_vdart};
use crate::map::{Dart, Face, Map, Vert};
use crate::ops::guard::Guard;
use crate::ops::Refusal;

/// The direction an edge rotation turns the edge (seen from the front, where faces are
/// counter-clockwise).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rotation {
    /// Each end moves one corner of the hexagon clockwise.
    Clockwise,
    /// Each end moves one corner of the hexagon counter-clockwise.
    CounterClockwise,
}

impl Rotation {
    /// The other direction, which undoes a rotation.
    ///
    /// ```
    /// use zipmesh_kernel::ops::quad::Rotation;
    /// assert_eq!(Rotation::Clockwise.reverse(), Rotation::CounterClockwise);
    /// ```
    pub fn reverse(self) -> Rotation {
        match self {
            Rotation::Clockwise => Rotation::CounterClockwise,
            Rotation::CounterClockwise => Rotation::Clockwise,
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub(super) struct RotationPlan {
    h: [Dart; 4],
    t: [Dart; 4],
}

fn plan_rotation(map: &Map, h: Dart, dir: Rotation) -> Result<RotationPlan, Refusal> {
    crate::ops::check_two_faces(map, h)?;
    let t = h.twin();
    let hq = quad_of(map, h)?;
    let tq = quad_of(map, t)?;
    let o = |d: Dart| map.origin(d);
    // Hexagon corners v, x, y, u, z, w.
    let hex = [o(tq[0]), o(hq[2]), o(hq[3]), o(hq[0]), o(tq[2]), o(tq[3])];
    if (1..6).any(|i| hex[..i].contains(&hex[i])) {
        return Err(Refusal::CornersCoincide);
    }
    let [v, x, y, u, z, w] = hex;
    // No second u–v edge (the inverse rotation would recreate u–v beside it) and no edge
    // already between the new ends.
    let (n0, n1) = match dir {
        Rotation::CounterClockwise => (x, z),
        Rotation::Clockwise => (y, w),
    };
    if map.vertex_darts(u).any(|e| e != h && map.dest(e) == v)
        || map.vertex_darts(n0).any(|e| map.dest(e) == n1)
    {
        return Err(Refusal::MultiEdge);
    }
    Ok(RotationPlan { h: hq, t: tq })
}

fn rotation_raw(map: &mut Map, p: &RotationPlan, dir: Rotation) {
    let [h, h1, h2, h3] = p.h;
    let [t, t1, t2, t3] = p.t;
    let (fh, ft) = (map.face(h), map.face(t));
    let (u, v) = (map.origin(h), map.origin(t));
    let set = |map: &mut Map, links: [(Dart, Dart); 6]| {
        for (a, b) in links {
            map.set_next(a, b);
        }
    };
    match dir {
        Rotation::CounterClockwise => {
            // [h, h2, h3, t1] and [t, t2, t3, h1]: h becomes z→x.
            let (z, x) = (map.origin(t2), map.origin(h2));
            set(
                map,
                [(h, h2), (h3, t1), (t1, h), (t, t2), (t3, h1), (h1, t)],
            );
            map.set_face(t1, fh);
            map.set_face(h1, ft);
            map.set_origin(h, z);
            map.set_origin(t, x);
            replace_fdart(map, fh, h1, h);
            replace_fdart(map, ft, t1, t);
        }
        Rotation::Clockwise => {
            // [h, t3, h1, h2] and [t, h3, t1, t2]: h becomes y→w.
            let (y, w) = (map.origin(h3), map.origin(t3));
            set(
                map,
                [(h, t3), (t3, h1), (h2, h), (t, h3), (h3, t1), (t2, t)],
            );
            map.set_face(t3, fh);
            map.set_face(h3, ft);
            map.set_origin(h, y);
            map.set_origin(t, w);
            replace_fdart(map, fh, h3, h);
            replace_fdart(map, ft, t3, t);
        }
    }
    // The old ends lose h and t; neither is a boundary dart, so any remaining dart will do.
    replace_vdart(map, u, h, t1);
    replace_vdart(map, v, t, h1);
}

/// Checks whether [`rotate_edge`] applies; changes nothing.
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad::{self, Rotation}, Refusal}, Dart};
/// let map = gen::torus_grid(4, 4).map;
/// assert_eq!(quad::can_rotate_edge(&map, Dart::new(0), Rotation::Clockwise), Ok(()));
/// let grid = gen::grid(1, 1).map;
/// assert_eq!(quad::can_rotate_edge(&grid, Dart::new(0), Rotation::Clockwise), Err(Refusal::Boundary));
/// ```
pub fn can_rotate_edge(map: &Map, h: Dart, dir: Rotation) -> Result<(), Refusal> {
    plan_rotation(map, h, dir).map(|_| ())
}

/// Edge rotation: replaces the edge of `h` (between two distinct quads) by the next diagonal
/// of the hexagon the two quads form, in direction `dir`; the dart handles `h` and `twin(h)`
/// now name the new edge.
///
/// ```text
///                     counter-clockwise        clockwise
///     y ---- x          y ---- x            y ---- x
///     |      |          |     /|            |\     |
///     u -h-> v   ==>    u   /  v     or     u  \   v
///     |      |          | /    |            |    \ |
///     z ---- w          z ---- w            z ---- w
/// ```
///
/// (`h: u→v` on the quad above, `twin(h)` on the one below; counter-clockwise `h` becomes
/// `z→x`, clockwise `y→w`.) **Deltas:** V, E, F unchanged; the old ends `u`, `v` lose one
/// each, the new ends gain one each; both faces stay quads. Rotating back the other way is
/// the exact inverse.
///
/// **Refusals, in the order checked:**
/// * [`Refusal::DeadHandle`]: `h` is not live.
/// * [`Refusal::Boundary`]: the edge is on the boundary.
/// * [`Refusal::SameFace`]: the same face lies on both sides of the edge.
/// * [`Refusal::WrongDegree`]: a face beside the edge is not a quad.
/// * [`Refusal::CornersCoincide`]: the hexagon's six corners are not distinct (so the new
///   edge could be a loop, or an end could be left dangling). With six distinct corners the
///   old ends keep valence at least 2.
/// * [`Refusal::MultiEdge`]: the new ends are already joined by an edge, or another edge
///   joins the old ends (the inverse rotation would duplicate it).
///
/// Cost: O(val(u) + val(new end)).
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad::{self, Rotation}, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let before = map.clone();
/// let h = Dart::new(0);
/// let (u, v) = (map.origin(h), map.dest(h));
/// let r = quad::rotate_edge(&mut map, h, Rotation::CounterClockwise).unwrap();
/// assert_eq!((map.valence(u), map.valence(v)), (3, 3));
/// assert_eq!((map.valence(map.origin(h)), map.valence(map.dest(h))), (5, 5));
/// r.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn rotate_edge(map: &mut Map, h: Dart, dir: Rotation) -> Result<EdgeRotation, Refusal> {
    let p = plan_rotation(map, h, dir)?;
    let (fh, ft) = (map.face(h), map.face(h.twin()));
    let ends = [map.origin(h), map.dest(h)];
    let rec = EdgeRotation {
        h,
        dir,
        ends,
        old_vdart: ends.map(|v| map.vertex_dart(v)),
        faces: [fh, ft],
        old_fdart: [fh, ft].map(|f| super::fdart_of(map, f)),
    };
    rotation_raw(map, &p, dir);
    Ok(rec)
}

/// The record of a [`rotate_edge`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EdgeRotation {
    h: Dart,
    dir: Rotation,
    /// The old ends u, v.
    ends: [Vert; 2],
    old_vdart: [Dart; 2],
    faces: [Option<Face>; 2],
    old_fdart: [Dart; 2],
}

impl EdgeRotation {
    /// The rotated dart (`h`, now on the new diagonal).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::{self, Rotation}, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// assert_eq!(quad::rotate_edge(&mut map, Dart::new(3), Rotation::Clockwise).unwrap().dart(), Dart::new(3));
    /// ```
    pub fn dart(&self) -> Dart {
        self.h
    }

    /// The direction of the rotation.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::{self, Rotation}, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let r = quad::rotate_edge(&mut map, Dart::new(3), Rotation::Clockwise).unwrap();
    /// assert_eq!(r.rotation(), Rotation::Clockwise);
    /// ```
    pub fn rotation(&self) -> Rotation {
        self.dir
    }

    /// Undoes the rotation: the rotation of the same dart the other way, with the old vertex
    /// and face records put back (`==` the map before, with the map as the rotation left it).
    ///
    /// [`Refusal::StaleRecord`] (map unchanged) if the reverse rotation would be refused or
    /// would not bring the edge back to its old ends.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::{self, Rotation}, Dart};
    /// let mut map = gen::torus_grid(5, 4).map;
    /// let before = map.clone();
    /// let r = quad::rotate_edge(&mut map, Dart::new(7), Rotation::Clockwise).unwrap();
    /// r.undo(&mut map).unwrap();
    /// assert_eq!(map, before);
    /// ```
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        let (guard, plan) = self.guard(map);
        guard.result()?;
        let p = plan.ok_or(Refusal::StaleRecord)?;
        rotation_raw(map, &p, self.dir.reverse());
        for (v, old) in self.ends.into_iter().zip(self.old_vdart) {
            restore_vdart(map, v, old);
        }
        for (f, old) in self.faces.into_iter().zip(self.old_fdart) {
            restore_fdart(map, f, old);
        }
        Ok(())
    }

    /// The staleness checks of [`EdgeRotation::undo`], in order, and the plan of the
    /// reverse rotation it makes.
    pub(super) fn guard(&self, map: &Map) -> (Guard, Option<RotationPlan>) {
        let back = self.dir.reverse();
        let plan = plan_rotation(map, self.h, back).ok();
        let o = |d: Dart| map.origin(d);
        // The reverse rotation's new ends must be the old ends.
        let new_ends = plan.map(|p| match back {
            Rotation::CounterClockwise => [o(p.t[2]), o(p.h[2])],
            Rotation::Clockwise => [o(p.h[3]), o(p.t[3])],
        });
        let g = Guard::new()
            .check("reverse rotation applies", || plan.is_some())
            .check("new ends are the old ends", || new_ends == Some(self.ends))
            .check("same faces", || {
                [map.face(self.h), map.face(self.h.twin())] == self.faces
            });
        (g, plan)
    }
}
