//! Two triangles that meet (Q-zip paper, Sec. 3.2, Fig. 15): splitting a quad into a
//! triangle pair, merging two triangles that share an edge, and what the merge leaves, by
//! how the two triangles meet.
//!
//! Two triangles meet along an edge that is, for each, its left side, its base or its right
//! side (see [`super::walk`]). In a regular region every move keeps a triangle's direction
//! (tip to base), so two triangles that crawl into each other meet in one of four ways,
//! which fix their relative direction. Counting each triangle's extra corner against its
//! tip ([`super::effective_valence`]), [`merge_collision`] changes effective valences by
//! the [`Collision`] kind:
//!
//! | kind | shared edge | directions | merge | effective valences after |
//! |---|---|---|---|---|
//! | [`Collision::Opposite`] | the same side of both: the tips are its two ends | opposite | remove the edge | all kept: regular if they were |
//! | [`Collision::BaseToBase`] | the base of both | opposite | collapse the edge (both triangles go) | the merged vertex `k + l − 4`: regular if both were |
//! | [`Collision::Orthogonal`] | the base of one, a side of the other | orthogonal | remove the edge | the base triangle's tip +1, its base corner that is not the other tip −1: an adjacent 3-5 pair |
//! | [`Collision::SameDirection`] | the left side of one, the right side of the other: one tip for both | the same | remove the edge | the tip +1, the edge's other end −1: a v5 and a v3 on opposite corners of the new quad |
//!
//! Which geometric directions go with which kind was read off planar grids (tip-to-base
//! vectors of colliding triangles, `docs/qzip.md`); the kinds themselves are combinatorial.

use super::patch::{Patch, SlotChange};
use super::walk::{simple_at, triangle, Tri};
use crate::map::{Dart, Face, Map, Vert};
use crate::ops::slots::Slots;
use crate::ops::{Refusal, VertexChanges};
use alloc::vec::Vec;

/// How two triangles meet along an edge; see the [module docs](self).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Collision {
    /// The same side of both (the tips are the edge's two ends): oppositely oriented.
    Opposite,
    /// The base of both: oppositely oriented, meeting base first.
    BaseToBase,
    /// The base of one and a side of the other: orthogonally oriented.
    Orthogonal,
    /// The left side of one and the right side of the other (one tip for both): the same
    /// direction.
    SameDirection,
}

/// Where the triangles of tip darts `t1` and `t2` meet: the kind and the dart of `t1`'s
/// triangle on the shared edge; `None` if they share no edge, are the same face, or one is
/// not a triangle.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{self, Collision}, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let s = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap();
/// let [t1, t2] = s.tips();
/// assert_eq!(quad_dominant::collision(&map, t1, t2).map(|c| c.0), Some(Collision::Opposite));
/// ```
pub fn collision(map: &Map, t1: Dart, t2: Dart) -> Option<(Collision, Dart)> {
    let (a, b) = (triangle(map, t1).ok()?, triangle(map, t2).ok()?);
    if a.face == b.face {
        return None;
    }
    let roles = |x: &super::walk::Tri| [x.t, x.b, x.s];
    let (ra, rb) = (roles(&a), roles(&b));
    for (i, &d) in ra.iter().enumerate() {
        if let Some(j) = rb.iter().position(|&e| e == d.twin()) {
            let kind = match (i, j) {
                (1, 1) => Collision::BaseToBase,
                (1, _) | (_, 1) => Collision::Orthogonal,
                _ if i == j => Collision::Opposite,
                _ => Collision::SameDirection,
            };
            return Some((kind, d));
        }
    }
    None
}

/// Each surviving vertex whose effective valence changes, with the change, and the vertex
/// deleted: what [`effective_changes`] returns.
pub type EffectiveChanges = (Vec<(Vert, i64)>, Option<Vert>);

/// The effective-valence changes [`merge_collision`] makes on the triangles of `t1` and
/// `t2` (see the [module docs](self)), computed before, with `others` the tip darts of the
/// map's other triangles: each surviving vertex whose effective valence changes, with the
/// change, and the vertex deleted (BaseToBase).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let [t1, t2] = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap().tips();
/// assert_eq!(quad_dominant::collide::effective_changes(&map, t1, t2, &[]), Some((vec![], None)));
/// ```
pub fn effective_changes(
    map: &Map,
    t1: Dart,
    t2: Dart,
    others: &[Dart],
) -> Option<EffectiveChanges> {
    let (kind, d) = collision(map, t1, t2)?;
    let (a, b) = (triangle(map, t1).ok()?, triangle(map, t2).ok()?);
    let mut tips = others.to_vec();
    tips.extend([t1, t2]);
    let eff = |v: Vert| super::effective_valence(map, &tips, v);
    Some(match kind {
        Collision::Opposite => (Vec::new(), None),
        // The edge's end kept is `d`'s origin; the other end's extra valence joins it.
        Collision::BaseToBase => {
            let (x, y) = (map.origin(d), map.dest(d));
            let change = eff(y) - 4;
            let v = if change == 0 {
                Vec::new()
            } else {
                [(x, change)].into()
            };
            (v, Some(y))
        }
        Collision::Orthogonal => {
            let (base, side) = if d == a.b { (a, b) } else { (b, a) };
            let corner = if base.a == side.tip { base.bb } else { base.a };
            ([(base.tip, 1), (corner, -1)].into(), None)
        }
        // The shared tip gains, the shared edge's other end loses.
        Collision::SameDirection => {
            let other = if map.origin(d) == a.tip {
                map.dest(d)
            } else {
                map.origin(d)
            };
            ([(a.tip, 1), (other, -1)].into(), None)
        }
    })
}

/// Merges the triangles of tip darts `t1` and `t2`, which share an edge, as their
/// [`Collision`] kind says: [`collapse_shared_base`] for [`Collision::BaseToBase`],
/// [`merge_triangles`] (remove the shared edge) for the others. The refusal of the
/// operation, or [`Refusal::BadArguments`] if they share no edge.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let grid = map.clone();
/// let [t1, t2] = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap().tips();
/// quad_dominant::merge_collision(&mut map, t1, t2).unwrap();
/// assert!(zipmesh_kernel::is_isomorphic(&map, &grid));
/// ```
pub fn merge_collision(map: &mut Map, t1: Dart, t2: Dart) -> Result<TriangleMerge, Refusal> {
    match collision(map, t1, t2) {
        None => Err(Refusal::BadArguments),
        Some((Collision::BaseToBase, d)) => collapse_shared_base(map, d),
        Some((_, d)) => merge_triangles(map, d),
    }
}

/// Checks whether [`split_quad`] applies; changes nothing.
///
/// **Refusals**: [`Refusal::DeadHandle`], [`Refusal::Boundary`] (`d` is a boundary dart),
/// [`Refusal::WrongDegree`] (its face is not a quad), [`Refusal::CornersCoincide`] (the
/// quad has a repeated corner), [`Refusal::MultiEdge`] (the diagonal's ends are already
/// joined).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, ops::Refusal, Dart};
/// let map = gen::torus_grid(4, 4).map;
/// assert_eq!(quad_dominant::can_split_quad(&map, Dart::new(0)), Ok(()));
/// assert_eq!(quad_dominant::can_split_quad(&gen::grid(1, 1).map, Dart::new(1)), Err(Refusal::Boundary));
/// ```
pub fn can_split_quad(map: &Map, d: Dart) -> Result<(), Refusal> {
    plan_split(map, d).map(|_| ())
}

fn plan_split(map: &Map, d: Dart) -> Result<[Dart; 4], Refusal> {
    if !map.is_live_dart(d) {
        return Err(Refusal::DeadHandle);
    }
    map.face(d).ok_or(Refusal::Boundary)?;
    let q = [d, map.next(d), map.next(map.next(d)), map.prev(d)];
    if map.next(q[2]) != q[3] {
        return Err(Refusal::WrongDegree);
    }
    let c = q.map(|x| map.origin(x));
    if (1..4).any(|i| c[..i].contains(&c[i])) {
        return Err(Refusal::CornersCoincide);
    }
    if map.dart_between(c[0], c[2]).is_some() {
        return Err(Refusal::MultiEdge);
    }
    Ok(q)
}

/// Splits the quad of `d` along the diagonal from `origin(d)` into two triangles: the
/// triangle of `d` (tip `origin(d)`, keeping the quad's face handle) and the opposite one
/// (tip the opposite corner, a new face). The diagonal is the right side of both, so the
/// pair is [`Collision::Opposite`] and [`merge_triangles`] takes it back. **Effect:** V 0,
/// E +1, F +1; the diagonal's ends gain one each, and their effective valences are kept.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let before = map.clone();
/// let s = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap();
/// assert_eq!(map.check(), Ok(()));
/// assert_eq!(s.tips()[0], Dart::new(0));
/// s.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn split_quad(map: &mut Map, d: Dart) -> Result<QuadSplit, Refusal> {
    let [d0, d1, d2, d3] = plan_split(map, d)?;
    let f = map.face(d0);
    let patch = Patch::before(map, &[d1, d2, d3], &[], &[f.unwrap_or(Face::new(0))]);
    let slots = SlotChange::alloc_edge_face(map);
    let SlotChange::EdgeFace(x, _, f2, _) = slots else {
        return Err(Refusal::BadArguments);
    };
    // Triangle d0, d1, x (R→P); triangle d2, d3, twin(x) (P→R).
    let (p, r) = (map.origin(d0), map.origin(d2));
    map.set_dart(x, d0, r, f);
    map.set_dart(x.twin(), d2, p, f2);
    map.set_next(d1, x);
    map.set_next(d3, x.twin());
    map.set_face(d2, f2);
    map.set_face(d3, f2);
    map.set_face_dart(f, d0);
    map.set_face_dart(f2, d2);
    let patch = patch.seal(map, slots);
    Ok(QuadSplit {
        tips: [d0, d2],
        patch,
    })
}

/// The record of a [`split_quad`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct QuadSplit {
    tips: [Dart; 2],
    patch: Patch,
}

impl QuadSplit {
    /// The tip darts of the two triangles (the split dart, and the dart two steps after it).
    ///
    /// See [`split_quad`] for an example.
    pub fn tips(&self) -> [Dart; 2] {
        self.tips
    }

    /// Undoes the split (`==` the map before); [`Refusal::StaleRecord`] and no change if the
    /// map is not as the split left it.
    ///
    /// See [`split_quad`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.patch.undo(map)
    }
}

fn plan_merge(map: &Map, d: Dart) -> Result<[Dart; 5], Refusal> {
    crate::ops::check_two_faces(map, d)?;
    let a = triangle(map, d)?;
    let b = triangle(map, d.twin())?;
    if a.bb == b.bb {
        return Err(Refusal::CornersCoincide);
    }
    if map.valence(a.tip) < 3 || map.valence(a.a) < 3 {
        return Err(Refusal::ValenceTooLow);
    }
    Ok([d, a.b, a.s, b.b, b.s])
}

/// Checks whether [`merge_triangles`] applies; changes nothing.
///
/// **Refusals**: [`Refusal::DeadHandle`], [`Refusal::Boundary`] (the edge is on the
/// boundary), [`Refusal::SameFace`], [`Refusal::WrongDegree`] (a side is not a triangle),
/// [`Refusal::DegenerateTriangle`], [`Refusal::CornersCoincide`] (the triangles' third
/// corners are one vertex), [`Refusal::ValenceTooLow`] (an end of the edge has valence 2).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, ops::Refusal, Dart};
/// let map = gen::torus_grid(4, 4).map;
/// assert_eq!(quad_dominant::can_merge_triangles(&map, Dart::new(0)), Err(Refusal::WrongDegree));
/// ```
pub fn can_merge_triangles(map: &Map, d: Dart) -> Result<(), Refusal> {
    plan_merge(map, d).map(|_| ())
}

/// Merges the two triangles on either side of `d`'s edge into one quad by removing the
/// edge (the face of `d` keeps its handle). **Effect:** V 0, E −1, F −1, the edge's ends
/// lose one each; effective valences change by the [`Collision`] kind (module docs).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, Dart};
/// let mut map = gen::torus_grid(4, 4).map;
/// let grid = map.clone();
/// let s = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap();
/// let split = map.clone();
/// let (_, d) = quad_dominant::collision(&map, s.tips()[0], s.tips()[1]).unwrap();
/// let m = quad_dominant::merge_triangles(&mut map, d).unwrap();
/// assert!(zipmesh_kernel::is_isomorphic(&map, &grid));
/// m.undo(&mut map).unwrap();
/// assert_eq!(map, split);
/// ```
pub fn merge_triangles(map: &mut Map, d: Dart) -> Result<TriangleMerge, Refusal> {
    let [d, d1, d2, e1, e2] = plan_merge(map, d)?;
    let (f1, f2) = (map.face(d), map.face(d.twin()));
    let (x, y) = (map.origin(d), map.dest(d));
    let f2h = f2.unwrap_or(Face::new(0));
    let patch = Patch::before(
        map,
        &[d, d.twin(), d1, d2, e1, e2],
        &[x, y],
        &[f1.unwrap_or(f2h), f2h],
    );
    // The quad d1 (Y→Z1), d2 (Z1→X), e1 (X→Z2), e2 (Z2→Y).
    map.set_next(d2, e1);
    map.set_next(e2, d1);
    map.set_face(e1, f1);
    map.set_face(e2, f1);
    map.set_face_dart(f1, d1);
    if map.vertex_dart(x) == d {
        map.set_vertex_dart(x, e1);
    }
    if map.vertex_dart(y) == d.twin() {
        map.set_vertex_dart(y, d1);
    }
    map.free_edge(d);
    map.free_face(f2h);
    let patch = patch.seal(map, SlotChange::FreedEdgeFace(d, f2h));
    Ok(TriangleMerge {
        quad: d1,
        patch,
        removed: None,
        renamed: [None; 2],
    })
}

/// The record of a [`merge_triangles`] or [`collapse_shared_base`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TriangleMerge {
    quad: Dart,
    patch: Patch,
    removed: Option<Vert>,
    renamed: [Option<(Dart, Dart)>; 2],
}

impl TriangleMerge {
    /// A dart of the merged quad ([`merge_triangles`]), or a dart leaving the merged vertex
    /// ([`collapse_shared_base`]).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, quad_dominant, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let s = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap();
    /// let (_, d) = quad_dominant::collision(&map, s.tips()[0], s.tips()[1]).unwrap();
    /// let m = quad_dominant::merge_triangles(&mut map, d).unwrap();
    /// assert_eq!(map.degree(map.face(m.quad()).unwrap()), 4);
    /// ```
    pub fn quad(&self) -> Dart {
        self.quad
    }

    /// A dart handle held from before, as it names the same place after (see
    /// [`super::TriangleMove::follow`]): the collapse replaces a dart in each face beside
    /// the two triangles.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, quad_dominant, Dart};
    /// let mut map = gen::torus_grid(4, 4).map;
    /// let [t1, t2] = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap().tips();
    /// let m = quad_dominant::merge_collision(&mut map, t1, t2).unwrap();
    /// assert_eq!(m.follow(Dart::new(5)), Dart::new(5));
    /// ```
    pub fn follow(&self, d: Dart) -> Dart {
        self.renamed
            .iter()
            .flatten()
            .find(|r| r.0 == d)
            .map_or(d, |r| r.1)
    }

    /// Undoes the merge (`==` the map before); [`Refusal::StaleRecord`] and no change if
    /// the map is not as the merge left it.
    ///
    /// See [`merge_triangles`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.patch.undo(map)
    }
}

impl VertexChanges for TriangleMerge {
    fn created_vertex(&self) -> Option<Vert> {
        None
    }
    fn removed_vertex(&self) -> Option<Vert> {
        self.removed
    }
}

fn plan_collapse_base(map: &Map, d: Dart) -> Result<(Tri, Tri), Refusal> {
    crate::ops::check_two_faces(map, d)?;
    // As tip darts: the triangle of d from its third corner, and the other likewise.
    let a = triangle(map, map.prev(d))?;
    let b = triangle(map, map.prev(d.twin()))?;
    let (x, y) = (map.origin(d), map.dest(d));
    if a.tip == b.tip {
        return Err(Refusal::CornersCoincide);
    }
    if map.is_boundary_vertex(x) || map.is_boundary_vertex(y) {
        return Err(Refusal::Boundary);
    }
    if map.valence(x) < 4 || map.valence(y) < 4 {
        return Err(Refusal::WrongValence);
    }
    if map.valence(a.tip) < 3 || map.valence(b.tip) < 3 {
        return Err(Refusal::ValenceTooLow);
    }
    simple_at(map, x)?;
    simple_at(map, y)?;
    let shared = map
        .vertex_darts(x)
        .map(|e| map.dest(e))
        .filter(|&w| w != y && w != a.tip && w != b.tip)
        .any(|w| map.dart_between(y, w).is_some());
    if shared {
        return Err(Refusal::LinkCondition);
    }
    Ok((a, b))
}

/// Checks whether [`collapse_shared_base`] applies; changes nothing.
///
/// **Refusals**: [`Refusal::DeadHandle`], [`Refusal::Boundary`] (the edge or an end is on
/// the boundary), [`Refusal::SameFace`], [`Refusal::WrongDegree`] (a side is not a
/// triangle), [`Refusal::DegenerateTriangle`], [`Refusal::CornersCoincide`] (the two third
/// corners are one vertex), [`Refusal::WrongValence`] (an end has valence below 4),
/// [`Refusal::ValenceTooLow`] (a third corner has valence 2), [`Refusal::Loop`] /
/// [`Refusal::MultiEdge`] at an end, [`Refusal::LinkCondition`] (the ends share a
/// neighbour besides the two third corners).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, ops::Refusal, Dart};
/// let map = gen::torus_grid(4, 4).map;
/// assert_eq!(quad_dominant::can_collapse_shared_base(&map, Dart::new(0)), Err(Refusal::WrongDegree));
/// ```
pub fn can_collapse_shared_base(map: &Map, d: Dart) -> Result<(), Refusal> {
    plan_collapse_base(map, d).map(|_| ())
}

/// Collapses the edge of `d`, shared by two triangles, into `origin(d)`: both triangles
/// go, `dest(d)` is deleted, and each triangle's two other edges become one. **Effect:**
/// V −1, E −3, F −2; the merged vertex has valence `val(x) + val(y) − 4`, the two third
/// corners lose one each. For two triangles sharing their base (the tips the third
/// corners) every effective valence but the merged one's is kept, and that is the sum of
/// the two minus 4: regular from regular.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant, Dart};
/// // A quad split along a diagonal, then split across the other half: build two
/// // triangles on one base by splitting a quad and flipping the diagonal.
/// let mut map = gen::torus_grid(6, 6).map;
/// let before = map.clone();
/// let [t1, _] = quad_dominant::split_quad(&mut map, Dart::new(0)).unwrap().tips();
/// let d = map.next(map.next(t1)); // the diagonal, a base for both as seen from the third corners
/// let split = map.clone();
/// let r = quad_dominant::collapse_shared_base(&mut map, d).unwrap();
/// assert_eq!(map.check(), Ok(()));
/// assert_eq!(map.num_vertices() + 1, split.num_vertices());
/// r.undo(&mut map).unwrap();
/// assert_eq!(map, split);
/// ```
pub fn collapse_shared_base(map: &mut Map, d: Dart) -> Result<TriangleMerge, Refusal> {
    let (a, b) = plan_collapse_base(map, d)?;
    // a: t1 = T1→X, b1 = d (X→Y), s1 = Y→T1; b: t2 = T2→Y, b2 = twin(d), s2 = X→T2.
    let (x, y) = (map.origin(d), map.dest(d));
    let (t1, s1, t2, s2) = (a.t, a.s, b.t, b.s);
    let (s1o, t2o) = (s1.twin(), t2.twin());
    let (p1, n1, g1) = (map.prev(s1o), map.next(s1o), map.face(s1o));
    let (p2, n2, g2) = (map.prev(t2o), map.next(t2o), map.face(t2o));
    let ydarts: Vec<Dart> = map.vertex_darts(y).collect();
    let mut darts: Vec<Dart> = [d, d.twin(), t1, s1, s1o, t2, t2o, s2, p1, p2].into();
    darts.extend_from_slice(&ydarts);
    let faces = [a.face, b.face, g1.unwrap_or(a.face), g2.unwrap_or(a.face)];
    let patch = Patch::before(map, &darts, &[x, y, a.tip, b.tip], &faces);
    // t1 takes s1o's place in g1, s2 takes t2o's place in g2.
    map.set_next(p1, t1);
    map.set_next(t1, n1);
    map.set_face(t1, g1);
    map.set_next(p2, s2);
    map.set_next(s2, n2);
    map.set_face(s2, g2);
    for &e in &ydarts {
        map.set_origin(e, x);
    }
    map.set_vertex_dart(x, s2);
    // The third corners keep a boundary record; an interior one may have named a dead dart.
    if map.vertex_dart(a.tip) == s1o {
        map.set_vertex_dart(a.tip, t1);
    }
    if map.vertex_dart(b.tip) == t2 {
        map.set_vertex_dart(b.tip, s2.twin());
    }
    map.set_face_dart(g1, t1);
    map.set_face_dart(g2, s2);
    let slots = Slots::deleted(&[d, s1, t2], y, &[a.face, b.face]);
    slots.free(map);
    Ok(TriangleMerge {
        quad: s2,
        patch: patch.seal(map, SlotChange::Freed(slots)),
        removed: Some(y),
        renamed: [Some((s1o, t1)), Some((t2o, s2))],
    })
}
