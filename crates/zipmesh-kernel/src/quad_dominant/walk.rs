//! The four moves of a triangle by one edge (Q-zip paper, Sec. 3.2, Fig. 14): VE, EV, LE, RE.
//!
//! A triangle is named by its **tip dart** `t`: the dart of the triangle that leaves its tip
//! `T`. Faces run counter-clockwise, so with the tip drawn on top the triangle is
//! `t: T→A`, `b = next(t): A→B` (the **base**), `s = next(b): B→T`; `A` is the left base
//! corner, `B` the right one, `t` the left side and `s` the right side. The moves (diagrams
//! in `docs/qzip.md`):
//!
//! * **VE** (vertex split to edge, towards the tip): `T` splits into an edge `Ta–Tb`; the
//!   triangle becomes the quad `Ta, A, B, Tb` and a new triangle `U, Ta, Tb` appears, tip
//!   `U`, where `T→U` is the dart two steps clockwise from `t` (the edge opposite the
//!   triangle when `T` has valence 5). `Ta` keeps `T`'s slot and valence 4, `Tb` is new.
//! * **EV** (edge collapse to vertex, towards the base): the base `A–B` collapses into `A`
//!   (`B` is deleted); the triangle's two sides become one edge, and the quad across the
//!   base becomes the new triangle, tip the merged vertex. EV at VE's result undoes VE.
//! * **LE** / **RE** (left / right edge flip): the side `T–A` (`T–B`) turns inside the
//!   pentagon the triangle forms with the quad across it, so that the triangle moves onto
//!   that quad; its tip moves to the quad's corner next to `T`. LE and RE undo each other.
//!
//! The triangle keeps its face handle through every move (the quad involved keeps or gets
//! the other face slot), so a walk of many moves follows one face.

use super::patch::{Patch, SlotChange};
use crate::map::{Dart, Face, Map, Vert};
use crate::ops::slots::Slots;
use crate::ops::{Refusal, VertexChanges};
use alloc::vec::Vec;
use core::fmt;
use core::str::FromStr;

/// One of the four moves of a triangle by one edge.
///
/// ```
/// use zipmesh_kernel::quad_dominant::Move;
/// assert_eq!(Move::VE.reverse(), Move::EV);
/// assert_eq!(Move::LE.reverse(), Move::RE);
/// assert_eq!("re".parse::<Move>(), Ok(Move::RE));
/// assert_eq!(Move::EV.to_string(), "EV");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Move {
    /// Vertex split to edge: the triangle moves one edge towards its tip.
    VE,
    /// Edge collapse to vertex: the triangle moves one edge towards its base.
    EV,
    /// Left edge flip: the triangle moves onto the quad across its left side.
    LE,
    /// Right edge flip: the triangle moves onto the quad across its right side.
    RE,
}

impl Move {
    /// All four, in the order VE, EV, LE, RE.
    pub const ALL: [Move; 4] = [Move::VE, Move::EV, Move::LE, Move::RE];

    /// The move that takes the triangle back (VE and EV, LE and RE).
    ///
    /// See [`Move`] for an example.
    pub fn reverse(self) -> Move {
        match self {
            Move::VE => Move::EV,
            Move::EV => Move::VE,
            Move::LE => Move::RE,
            Move::RE => Move::LE,
        }
    }

    /// The short name (`VE`, `EV`, `LE`, `RE`).
    ///
    /// See [`Move`] for an example.
    pub fn name(self) -> &'static str {
        match self {
            Move::VE => "VE",
            Move::EV => "EV",
            Move::LE => "LE",
            Move::RE => "RE",
        }
    }
}

impl fmt::Display for Move {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A move name that is not one of `VE`, `EV`, `LE`, `RE` (any case).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownMove;

impl fmt::Display for UnknownMove {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("not a triangle move (VE, EV, LE or RE)")
    }
}

#[cfg(feature = "std")]
impl std::error::Error for UnknownMove {}

impl FromStr for Move {
    type Err = UnknownMove;
    fn from_str(s: &str) -> Result<Move, UnknownMove> {
        Move::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(s))
            .ok_or(UnknownMove)
    }
}

/// The darts and corners of a triangle named by its tip dart.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tri {
    pub(crate) t: Dart,
    pub(crate) b: Dart,
    pub(crate) s: Dart,
    pub(crate) face: Face,
    pub(crate) tip: Vert,
    pub(crate) a: Vert,
    pub(crate) bb: Vert,
}

/// The triangle of tip dart `t`: live, on a face of degree 3 with three distinct corners.
pub(crate) fn triangle(map: &Map, t: Dart) -> Result<Tri, Refusal> {
    if !map.is_live_dart(t) {
        return Err(Refusal::DeadHandle);
    }
    let face = map.face(t).ok_or(Refusal::Boundary)?;
    let (b, s) = (map.next(t), map.next(map.next(t)));
    if map.next(s) != t {
        return Err(Refusal::WrongDegree);
    }
    let (tip, a, bb) = (map.origin(t), map.origin(b), map.origin(s));
    if tip == a || a == bb || bb == tip {
        return Err(Refusal::DegenerateTriangle);
    }
    Ok(Tri {
        t,
        b,
        s,
        face,
        tip,
        a,
        bb,
    })
}

/// The four darts of the quad of `d` (which must not be the face `not`), from `d`.
fn quad_across(map: &Map, d: Dart, not: Face) -> Result<[Dart; 4], Refusal> {
    let f = map.face(d).ok_or(Refusal::Boundary)?;
    if f == not {
        return Err(Refusal::SameFace);
    }
    let q = [d, map.next(d), map.next(map.next(d)), map.prev(d)];
    if map.next(q[2]) != q[3] {
        return Err(Refusal::WrongDegree);
    }
    Ok(q)
}

fn distinct(vs: &[Vert]) -> bool {
    (1..vs.len()).all(|i| !vs[..i].contains(&vs[i]))
}

/// Whether an edge other than `except` joins `p` and `q`.
fn joined(map: &Map, p: Vert, q: Vert, except: Option<Dart>) -> bool {
    map.vertex_darts(p)
        .any(|d| map.dest(d) == q && Some(d.edge()) != except.map(Dart::edge))
}

/// No loop and no two edges to one neighbour at `v`.
pub(super) fn simple_at(map: &Map, v: Vert) -> Result<(), Refusal> {
    let mut seen: Vec<Vert> = Vec::new();
    for d in map.vertex_darts(v) {
        let w = map.dest(d);
        if w == v {
            return Err(Refusal::Loop);
        }
        if seen.contains(&w) {
            return Err(Refusal::MultiEdge);
        }
        seen.push(w);
    }
    Ok(())
}

/// What a move will write, worked out on the map before.
#[derive(Clone, Debug)]
pub(crate) enum Plan {
    Flip {
        tri: Tri,
        left: bool,
        quad: [Dart; 4],
    },
    Split {
        tri: Tri,
        u: Dart,
        arc: Vec<Dart>,
    },
    Collapse {
        tri: Tri,
        quad: [Dart; 4],
        arc: Vec<Dart>,
    },
}

pub(crate) fn plan(map: &Map, t: Dart, mv: Move) -> Result<Plan, Refusal> {
    let tri = triangle(map, t)?;
    match mv {
        Move::LE | Move::RE => plan_flip(map, tri, mv == Move::LE),
        Move::VE => plan_split(map, tri),
        Move::EV => plan_collapse(map, tri),
    }
}

fn plan_flip(map: &Map, tri: Tri, left: bool) -> Result<Plan, Refusal> {
    let side = if left { tri.t } else { tri.s };
    let quad = quad_across(map, side.twin(), tri.face)?;
    let o = |d: Dart| map.origin(d);
    // The pentagon's two quad corners: next to T (the new tip) and next to the base corner.
    let (near_tip, near_base) = if left {
        (o(quad[2]), o(quad[3]))
    } else {
        (o(quad[3]), o(quad[2]))
    };
    if !distinct(&[tri.tip, tri.a, tri.bb, near_tip, near_base]) {
        return Err(Refusal::CornersCoincide);
    }
    // The side's base corner gets an edge to the new tip; the reverse flip recreates the side.
    let corner = if left { tri.a } else { tri.bb };
    if joined(map, corner, near_tip, None) || joined(map, tri.tip, corner, Some(side)) {
        return Err(Refusal::MultiEdge);
    }
    Ok(Plan::Flip { tri, left, quad })
}

fn plan_split(map: &Map, tri: Tri) -> Result<Plan, Refusal> {
    if map.is_boundary_vertex(tri.tip) {
        return Err(Refusal::Boundary);
    }
    if map.valence(tri.tip) < 4 {
        return Err(Refusal::WrongValence);
    }
    simple_at(map, tri.tip)?;
    let u = map.rotate_cw(map.rotate_cw(tri.t));
    // Tb takes the darts from twin(s) counter-clockwise up to u (exclusive).
    let mut arc = Vec::new();
    let mut d = tri.s.twin();
    while d != u && arc.len() <= map.valence(tri.tip) {
        arc.push(d);
        d = map.rotate_ccw(d);
    }
    Ok(Plan::Split { tri, u, arc })
}

fn plan_collapse(map: &Map, tri: Tri) -> Result<Plan, Refusal> {
    let (ta, tb, u) = (tri.a, tri.bb, tri.tip);
    if map.is_boundary_vertex(ta) || map.is_boundary_vertex(tb) {
        return Err(Refusal::Boundary);
    }
    let quad = quad_across(map, tri.b.twin(), tri.face)?;
    let (qa, qb) = (map.origin(quad[2]), map.origin(quad[3]));
    if !distinct(&[ta, tb, qa, qb, u]) {
        return Err(Refusal::CornersCoincide);
    }
    simple_at(map, ta)?;
    simple_at(map, tb)?;
    let common = map
        .vertex_darts(ta)
        .map(|d| map.dest(d))
        .filter(|&w| w != tb && w != u && joined(map, tb, w, None))
        .count();
    if common > 0 {
        return Err(Refusal::LinkCondition);
    }
    if map.valence(u) < 3 {
        return Err(Refusal::ValenceTooLow);
    }
    let dead = [tri.b.twin(), tri.s];
    let arc = map.vertex_darts(tb).filter(|d| !dead.contains(d)).collect();
    Ok(Plan::Collapse { tri, quad, arc })
}

/// Checks whether [`move_triangle`] applies to the triangle of tip dart `t`; changes nothing.
///
/// **Refusals**, as checked: [`Refusal::DeadHandle`] (`t` is not live),
/// [`Refusal::Boundary`] (`t` is a boundary dart; VE: the tip is on the boundary; EV: a base
/// corner is; a face the move needs across a side or the base is missing),
/// [`Refusal::WrongDegree`] (`t`'s face is not a triangle, or the face across is not a quad),
/// [`Refusal::DegenerateTriangle`] (two corners coincide), [`Refusal::SameFace`] (the face
/// across is the triangle itself), [`Refusal::CornersCoincide`] (the pentagon of a flip, or
/// EV's triangle and quad, have a repeated corner), [`Refusal::WrongValence`] (VE: the tip
/// has valence below 4), [`Refusal::Loop`] / [`Refusal::MultiEdge`] (a loop or a doubled edge
/// at a vertex whose edges the move redistributes, or one would result),
/// [`Refusal::LinkCondition`] (EV: the base corners share a neighbour besides the tip),
/// [`Refusal::ValenceTooLow`] (EV: the tip has valence 2).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
/// let (mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
/// let map = mesh.map;
/// for mv in Move::ALL {
///     assert!(quad_dominant::can_move_triangle(&map, tips[0], mv).is_ok());
/// }
/// ```
pub fn can_move_triangle(map: &Map, t: Dart, mv: Move) -> Result<(), Refusal> {
    plan(map, t, mv).map(|_| ())
}

/// Looks at the map a move would give without keeping it: makes [`move_triangle`], hands
/// `read` the moved map and the move's record, then undoes the move in O(entries touched)
/// (nothing can change the map between, so the record cannot be stale). The refusal if the
/// move does not apply, and then the map is untouched. The undo of a move just made is
/// never refused (its guard sees exactly what the move wrote); if it ever were, that
/// refusal comes back and the map holds the move, still valid.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
/// let (mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
/// let mut map = mesh.map;
/// let before = map.clone();
/// let v = quad_dominant::probe_move(&mut map, tips[0], Move::VE, |m, r| m.valence(m.origin(r.tip())));
/// assert_eq!(v, Ok(5));
/// assert_eq!(map, before);
/// ```
pub fn probe_move<R>(
    map: &mut Map,
    t: Dart,
    mv: Move,
    read: impl FnOnce(&Map, &TriangleMove) -> R,
) -> Result<R, Refusal> {
    let r = move_triangle(map, t, mv)?;
    let out = read(map, &r);
    // The fresh undo's guard has never refused a move made just before; the full undo is
    // the fallback that keeps "as it was" if it ever did.
    r.undo_fresh(map).or_else(|_| r.undo(map))?;
    Ok(out)
}

/// Moves the triangle of tip dart `t` by one edge in direction `mv` (see the
/// [module docs](self)), or refuses as [`can_move_triangle`] does and leaves the map as it
/// was. The record names the triangle's new tip dart and undoes the move exactly.
///
/// **Effect** ([`Move::effect`] as code): VE: V +1, E +2, F +1, the tip becomes a vertex
/// of valence 4, the new vertex has the tip's valence − 1, `U` gains one, the new face is a
/// quad. EV: V −1, E −2, F −1, `A` takes valence `val(A) + val(B) − 3`, `B` is deleted, the
/// tip loses one. LE / RE: counts unchanged, the tip loses one, the new tip gains one. Every
/// other vertex keeps its valence and every surviving face its degree.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
/// let (mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
/// let mut map = mesh.map;
/// let (before, face) = (map.clone(), map.face(tips[0]));
/// let r = quad_dominant::move_triangle(&mut map, tips[0], Move::VE).unwrap();
/// assert_eq!(map.check(), Ok(()));
/// assert_eq!(map.valence(map.origin(r.tip())), 5);
/// assert_eq!(map.face(r.tip()), face); // the triangle keeps its face
/// r.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn move_triangle(map: &mut Map, t: Dart, mv: Move) -> Result<TriangleMove, Refusal> {
    let p = plan(map, t, mv)?;
    let (tip, patch, created, removed, renamed) = match p {
        Plan::Flip { tri, left, quad } => flip(map, &tri, left, &quad),
        Plan::Split { tri, u, arc } => split(map, &tri, u, &arc),
        Plan::Collapse { tri, quad, arc } => collapse(map, &tri, &quad, &arc),
    };
    Ok(TriangleMove {
        mv,
        from: t,
        tip,
        patch,
        created,
        removed,
        renamed,
    })
}

/// The new tip dart, the patch, the vertex created and deleted, and the dart of a
/// neighbouring face renamed (old, new).
type Applied = (
    Dart,
    Patch,
    Option<Vert>,
    Option<Vert>,
    Option<(Dart, Dart)>,
);

fn flip(map: &mut Map, tri: &Tri, left: bool, q: &[Dart; 4]) -> Applied {
    let (t, b, s, f) = (tri.t, tri.b, tri.s, tri.face);
    let g = map.face(q[0]);
    let darts = [t, b, s, q[0], q[1], q[2], q[3]];
    let patch = Patch::before(map, &darts, &[tri.tip], &[f, g.unwrap_or(f)]);
    let new_tip = if left {
        // q = [A→T, T→L1, L1→L0, L0→A]: triangle q2, q3, q0; quad t (L1→A), b, s, q1.
        let [t2, p1, p2, p3] = *q;
        map.set_origin(t, map.origin(p2));
        map.set_next(t2, p2);
        map.set_next(s, p1);
        map.set_next(p1, t);
        for d in [t2, p2, p3] {
            map.set_face(d, f);
        }
        for d in [t, b, s] {
            map.set_face(d, g);
        }
        if map.vertex_dart(tri.tip) == t {
            map.set_vertex_dart(tri.tip, s.twin());
        }
        p2
    } else {
        // q = [T→B, B→R0, R0→R1, R1→T]: triangle q0 (R1→B), q1, q2; quad t, b, s, q3.
        let [s2, q1, q2, q3] = *q;
        map.set_origin(s2, map.origin(q3));
        map.set_next(s, q3);
        map.set_next(q3, t);
        map.set_next(q2, s2);
        for d in [s2, q1, q2] {
            map.set_face(d, f);
        }
        for d in [t, b, s] {
            map.set_face(d, g);
        }
        if map.vertex_dart(tri.tip) == s2 {
            map.set_vertex_dart(tri.tip, t);
        }
        s2
    };
    map.set_face_dart(f, new_tip);
    map.set_face_dart(g, t);
    (new_tip, patch.seal(map, SlotChange::None), None, None, None)
}

fn split(map: &mut Map, tri: &Tri, u: Dart, arc: &[Dart]) -> Applied {
    let (t, b, s, f, tip) = (tri.t, tri.b, tri.s, tri.face, tri.tip);
    let u2 = u.twin();
    let (r, w, fu) = (map.prev(u2), map.next(u2), map.face(u2));
    let mut darts: Vec<Dart> = [t, b, s, u2, r].into();
    darts.extend_from_slice(arc);
    let patch = Patch::before(map, &darts, &[tip], &[f, fu.unwrap_or(f)]);
    let slots = Slots::alloc(map, 2, 1);
    let (h, g, tb, qn) = (slots.edge(0), slots.edge(1), slots.vert(), slots.face(0));
    let uv = map.origin(u2);
    // Triangle u2 (U→Ta), h (Ta→Tb), twin(g) (Tb→U); quad t, b, s, twin(h) (Tb→Ta).
    map.set_dart(g, w, uv, fu);
    map.set_next(r, g);
    map.set_next(u2, h);
    map.set_face(u2, f);
    map.set_dart(h, g.twin(), tip, f);
    map.set_dart(g.twin(), u2, tb, f);
    map.set_dart(h.twin(), t, tb, qn);
    map.set_next(s, h.twin());
    for d in [t, b, s] {
        map.set_face(d, qn);
    }
    for &d in arc {
        map.set_origin(d, tb);
    }
    map.set_vertex_dart(tb, s.twin());
    map.set_vertex_dart(tip, t);
    map.set_face_dart(f, u2);
    map.set_face_dart(qn, t);
    if map.face(g).map(|x| map.face_dart(x)) == Some(u2) {
        map.set_face_dart(fu, g);
    }
    (
        u2,
        patch.seal(map, SlotChange::Allocated(slots)),
        Some(tb),
        None,
        Some((u2, g)),
    )
}

fn collapse(map: &mut Map, tri: &Tri, q: &[Dart; 4], arc: &[Dart]) -> Applied {
    // Triangle x (U→Ta), h (Ta→Tb), y (Tb→U); quad q = [Tb→Ta, Ta→A, A→B, B→Tb].
    let (x, h, y, f) = (tri.t, tri.b, tri.s, tri.face);
    let (ta, tb, u) = (tri.a, tri.bb, tri.tip);
    let y2 = y.twin();
    let (r, w, fy) = (map.prev(y2), map.next(y2), map.face(y2));
    let qn = map.face(q[0]).unwrap_or(f);
    let mut darts: Vec<Dart> = [x, h, h.twin(), y, y2, r, q[1], q[2], q[3]].into();
    darts.extend_from_slice(arc);
    let patch = Patch::before(map, &darts, &[ta, tb, u], &[f, fy.unwrap_or(f), qn]);
    map.set_next(r, x);
    map.set_next(x, w);
    map.set_face(x, fy);
    map.set_next(q[3], q[1]);
    for &d in &q[1..] {
        map.set_face(d, f);
    }
    for &d in arc {
        map.set_origin(d, ta);
    }
    map.set_vertex_dart(ta, q[1]);
    if map.vertex_dart(u) == y2 {
        map.set_vertex_dart(u, x);
    }
    map.set_face_dart(f, q[1]);
    if fy.map(|g| map.face_dart(g)) == Some(y2) {
        map.set_face_dart(fy, x);
    }
    let slots = Slots::deleted(&[h, y], tb, &[qn]);
    slots.free(map);
    (
        q[1],
        patch.seal(map, SlotChange::Freed(slots)),
        None,
        Some(tb),
        Some((y2, x)),
    )
}

/// The record of a [`move_triangle`]: the move, the triangle's tip dart before and after,
/// and what the exact undo needs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TriangleMove {
    mv: Move,
    from: Dart,
    tip: Dart,
    patch: Patch,
    created: Option<Vert>,
    removed: Option<Vert>,
    renamed: Option<(Dart, Dart)>,
}

impl TriangleMove {
    /// A dart handle held from before the move, as it names the same place after: VE hands
    /// the dart `U→T` on to the new triangle and puts a new dart in its place in the face
    /// beside it, and EV replaces the deleted dart `U→B` in the face beside it by `U→A`.
    /// So the tip dart of another triangle next to the moved one is `follow(old tip dart)`.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
    /// let (mesh, tips) = gen::quad_dominant(6, 6, 2, 7);
    /// let mut map = mesh.map;
    /// let r = quad_dominant::move_triangle(&mut map, tips[0], Move::VE).unwrap();
    /// // The other triangles are not beside it: their tip darts stay.
    /// assert_eq!(r.follow(tips[1]), tips[1]);
    /// ```
    pub fn follow(&self, d: Dart) -> Dart {
        match self.renamed {
            Some((old, new)) if old == d => new,
            _ => d,
        }
    }

    /// The move made.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
    /// let (mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
    /// let mut map = mesh.map;
    /// assert_eq!(quad_dominant::move_triangle(&mut map, tips[0], Move::LE).unwrap().kind(), Move::LE);
    /// ```
    pub fn kind(&self) -> Move {
        self.mv
    }

    /// The triangle's tip dart before the move.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
    /// let (mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
    /// let mut map = mesh.map;
    /// assert_eq!(quad_dominant::move_triangle(&mut map, tips[0], Move::RE).unwrap().from(), tips[0]);
    /// ```
    pub fn from(&self) -> Dart {
        self.from
    }

    /// The triangle's tip dart after the move: the dart of the triangle leaving its new tip.
    ///
    /// See [`move_triangle`] for an example.
    pub fn tip(&self) -> Dart {
        self.tip
    }

    /// Undoes the move: the map `==` the one before, if it is as the move left it;
    /// otherwise [`Refusal::StaleRecord`] and no change. The checks: every dart, vertex and
    /// face entry the move wrote still holds what it wrote, and the slots it allocated
    /// (VE) are the last ones or on top of the free lists, or the ones it freed (EV) are on
    /// top of the free lists.
    ///
    /// See [`move_triangle`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.patch.undo(map)
    }

    /// [`TriangleMove::undo`] in place in O(entries touched), for a probe that made the
    /// move on this map and changed nothing since (the optimizer's crawl).
    pub(crate) fn undo_fresh(&self, map: &mut Map) -> Result<(), Refusal> {
        self.patch.undo_fresh(map)
    }
}

impl crate::ops::Undo for TriangleMove {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        TriangleMove::undo(self, map)
    }
}

impl VertexChanges for TriangleMove {
    fn created_vertex(&self) -> Option<Vert> {
        self.created
    }
    fn removed_vertex(&self) -> Option<Vert> {
        self.removed
    }
}
