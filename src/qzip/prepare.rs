//! Stage 3 of Q-zip, preparation: the end-point adjustments of Sec. 2.6.
//!
//! [`prepare`] turns a [`Plan`] (one compass tag per path vertex) into a [`Surgery`]: the
//! vertex list the execution walks, and for each vertex but the last either an operation
//! (the compass hand along its outgoing edge) or a no-op. The adjustments are restricted to
//! the one-rings of the two singularities, and every one of them is plain compass transport
//! along a path that is either rerouted around one quad of the singularity's one-ring or
//! extended by one guide edge (see `docs/qzip.md` for the diagrams):
//!
//! | end | tag | adjustment |
//! | --- | --- | --- |
//! | start v3 | split | the first operation becomes a no-op |
//! | start v5 | collapse | none |
//! | start v3 | LC (RC) | start at the v3's neighbour on the left (right) of the first edge, go round that quad: LC (RC) there, RC (LC) at the turn, and the compass carried along the reroute from the first path vertex on |
//! | start v5 | LS (RS) | prepend the guide edge from the second neighbour counter-clockwise (clockwise) of the first edge; no-op there |
//! | end v3 | any | none |
//! | end v5 | LC (RC) | replace the last edge by the two sides of the quad on its left (right): RS (LS) at the turn, LC (RC) on the last edge |
//! | end v5 | LS (RS) | append the guide edge to the second neighbour counter-clockwise (clockwise) of the incoming edge |
//!
//! Before the end rule, a path that reaches the terminal singularity by going round a quad
//! that touches it (`a -> b -> c -> end`, `a` and `end` joined by the quad's fourth side) is
//! shortened to `a -> end` (a homotopy across that quad; the hand along `a -> end` is the
//! hand along the parallel side `b -> c`); a path swept round a regular quad just before that
//! U-turn (`p -> x -> y -> b -> c -> end`, `p x y b` a quad) is first straightened to
//! `p -> b`, so that it is shortened the same way; both are repeated until neither applies.
//! After the adjustments, edges crossed twice in opposite directions (`a -> b -> a`) cancel
//! in pairs, keeping the compass unchanged: the surviving vertex takes the hand of the edge
//! that leaves the fold; loops that go round one quad with regular corners
//! (`a -> x -> y -> z -> a`) are cut the same way. If a v3 start's reroute folds back so
//! that the first operation is a split, the v3 is put back in front as its guide with a
//! no-op (as in a v3 start with a split).
//!
//! ```
//! use zipmesh::{gen, Vert};
//! use zipmesh::qzip::{plan, prepare, validate_path, SketchOptions, StartRule, Tag};
//! let map = gen::subdivided_icosahedron(2).map;
//! let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
//! let path = zipmesh::qzip::sketch(&map, v3, v5, &SketchOptions::default()).unwrap();
//! let s = prepare(&map, &plan(&map, &path, Tag::LS).unwrap()).unwrap();
//! assert_eq!(s.start_rule(), StartRule::V3Split);
//! assert_eq!(s.steps()[0].op, None); // the v3 start with a split is a no-op
//! ```

use alloc::vec::Vec;
use core::fmt;

use super::compass::{turn_at, Plan, PlanError, Tag};
use super::quad::{bounds_one_quad, quad_on_edge, side_quad, SideQuad};
use crate::invariants::{is_regular_interior, MeshKind};
use crate::{Dart, Map, Vert};

/// How the start of the path was adjusted (Sec. 2.6).
///
/// ```
/// use zipmesh::qzip::StartRule;
/// assert_eq!(StartRule::V5Split.to_string(), "v5 start with a split: guide edge prepended");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StartRule {
    /// A v3 start with a split: the first operation is a no-op.
    V3Split,
    /// A v5 start with a collapse: no adjustment.
    V5Collapse,
    /// A v3 start with a collapse: rerouted round one quad of the one-ring.
    V3Collapse,
    /// A v5 start with a split: a guide edge is prepended, with a no-op.
    V5Split,
}

impl fmt::Display for StartRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::V3Split => "v3 start with a split: first operation is a no-op",
            Self::V5Collapse => "v5 start with a collapse: no adjustment",
            Self::V3Collapse => "v3 start with a collapse: rerouted round one quad",
            Self::V5Split => "v5 start with a split: guide edge prepended",
        })
    }
}

/// How the end of the path was adjusted (Sec. 2.6).
///
/// ```
/// use zipmesh::qzip::EndRule;
/// assert_eq!(EndRule::V3.to_string(), "v3 end: no adjustment");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EndRule {
    /// A v3 end: no adjustment.
    V3,
    /// A v5 end reached with a collapse: the last edge is rerouted round one quad.
    V5Collapse,
    /// A v5 end reached with a split: a guide edge is appended.
    V5Split,
}

impl fmt::Display for EndRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::V3 => "v3 end: no adjustment",
            Self::V5Collapse => "v5 end with a collapse: last edge rerouted round one quad",
            Self::V5Split => "v5 end with a split: guide edge appended",
        })
    }
}

/// One vertex of a [`Surgery`].
///
/// ```
/// use zipmesh::qzip::{SurgeryStep, Tag};
/// use zipmesh::Vert;
/// let s = SurgeryStep { vertex: Vert::new(4), hand: Tag::LC, op: Some(Tag::LC) };
/// assert!(s.op.is_some());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SurgeryStep {
    /// The path vertex.
    pub vertex: Vert,
    /// The compass hand along the outgoing edge (at the last vertex: the hand the compass
    /// arrives with).
    pub hand: Tag,
    /// The operation run here: `Some(hand)`, or `None` for a no-op and at the last vertex.
    pub op: Option<Tag>,
}

/// A prepared surgery: the adjusted path and its operations, ready for execution.
///
/// Its `Display` prints one line per vertex.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{plan, prepare, sketch, EndRule, SketchOptions, Tag};
/// let map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let path = sketch(&map, v3, v5, &SketchOptions::default()).unwrap();
/// let s = prepare(&map, &plan(&map, &path, Tag::RS).unwrap()).unwrap();
/// assert_eq!(s.end_rule(), EndRule::V5Split);
/// assert_eq!(s.steps().len(), path.vertices().len() + 1);
/// assert!(s.to_string().contains("no-op"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Surgery {
    steps: Vec<SurgeryStep>,
    from: Vert,
    to: Vert,
    initial: Tag,
    start: StartRule,
    end: EndRule,
    folds: usize,
    /// Dart `i` joins steps `i` and `i + 1` in the map the surgery was prepared on.
    darts: Vec<Dart>,
}

impl Surgery {
    /// The adjusted path with its operations, from the first vertex to the last.
    ///
    /// See [`Surgery`] for an example.
    pub fn steps(&self) -> &[SurgeryStep] {
        &self.steps
    }

    /// The initial singularity (the planned path's first vertex).
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, prepare, sketch, SketchOptions, Tag};
    /// let map = gen::subdivided_icosahedron(2).map;
    /// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
    /// let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
    /// let s = prepare(&map, &plan(&map, &path, Tag::LS).unwrap()).unwrap();
    /// assert_eq!((s.from(), s.to()), (v5, v3));
    /// assert_ne!(s.steps()[0].vertex, v5); // the guide vertex comes first
    /// ```
    pub fn from(&self) -> Vert {
        self.from
    }

    /// The terminal singularity (the planned path's last vertex).
    ///
    /// See [`Surgery::from`] for an example.
    pub fn to(&self) -> Vert {
        self.to
    }

    /// The initial operation chosen by the caller.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, prepare, sketch, SketchOptions, Tag};
    /// let map = gen::subdivided_icosahedron(2).map;
    /// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
    /// let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
    /// assert_eq!(prepare(&map, &plan(&map, &path, Tag::RC).unwrap()).unwrap().initial(), Tag::RC);
    /// ```
    pub fn initial(&self) -> Tag {
        self.initial
    }

    /// Which start adjustment was made.
    ///
    /// See the module example.
    pub fn start_rule(&self) -> StartRule {
        self.start
    }

    /// Which end adjustment was made.
    ///
    /// See [`Surgery`] for an example.
    pub fn end_rule(&self) -> EndRule {
        self.end
    }

    /// How many folds (`a -> b -> a`) and loops round one quad were cancelled.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, prepare, sketch, SketchOptions, Tag};
    /// let map = gen::subdivided_icosahedron(2).map;
    /// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
    /// let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
    /// assert!(prepare(&map, &plan(&map, &path, Tag::LC).unwrap()).unwrap().folds() <= 2);
    /// ```
    pub fn folds(&self) -> usize {
        self.folds
    }

    /// The number of operations (steps that are not no-ops).
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, prepare, sketch, SketchOptions, Tag};
    /// let map = gen::subdivided_icosahedron(2).map;
    /// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
    /// let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
    /// let s = prepare(&map, &plan(&map, &path, Tag::LC).unwrap()).unwrap();
    /// assert_eq!(s.operations(), s.steps().iter().filter(|x| x.op.is_some()).count());
    /// ```
    pub fn operations(&self) -> usize {
        self.steps.iter().filter(|s| s.op.is_some()).count()
    }

    /// The darts of the adjusted path: dart `i` goes from the vertex of step `i` to that of
    /// step `i + 1`, in the map the surgery was prepared on.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, prepare, sketch, SketchOptions, Tag};
    /// let map = gen::subdivided_icosahedron(2).map;
    /// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
    /// let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
    /// let s = prepare(&map, &plan(&map, &path, Tag::LS).unwrap()).unwrap();
    /// for (d, w) in s.darts().iter().zip(s.steps().windows(2)) {
    ///     assert_eq!((map.origin(*d), map.dest(*d)), (w[0].vertex, w[1].vertex));
    /// }
    /// ```
    pub fn darts(&self) -> &[Dart] {
        &self.darts
    }
}

impl fmt::Display for Surgery {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{}; {}", self.start, self.end)?;
        let last = self.steps.len() - 1;
        for (i, s) in self.steps.iter().enumerate() {
            match s.op {
                Some(t) => writeln!(f, "vertex {}: {t}", s.vertex.index())?,
                None if i == last => writeln!(f, "vertex {}: end", s.vertex.index())?,
                None => writeln!(f, "vertex {}: no-op", s.vertex.index())?,
            }
        }
        Ok(())
    }
}

/// Why [`prepare`] refused; nothing is changed in any case.
///
/// ```
/// use zipmesh::qzip::PrepareError;
/// use zipmesh::Vert;
/// let e = PrepareError::End { index: 0, vertex: Vert::new(2), valence: 4, boundary: false };
/// assert!(e.to_string().contains("valence 4"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PrepareError {
    /// An end is not an interior v3 or v5 (Sec. 2.6 covers those only).
    End {
        /// 0 for the start, the last position for the end.
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// Its valence.
        valence: usize,
        /// Whether it is on the boundary.
        boundary: bool,
    },
    /// The quad an adjustment goes round is missing (boundary) or not a quad.
    NoQuad {
        /// The singularity whose one-ring it is in.
        vertex: Vert,
    },
    /// The adjusted path visits a vertex twice (other than a cancelled fold or loop).
    NotSimple {
        /// The repeated vertex.
        vertex: Vert,
    },
    /// No operation is left: for example a one-edge path between two v3s with a split,
    /// whose only operation is the start's no-op.
    Empty,
    /// The plan does not fit the map (made for another map, or the map changed).
    StalePlan,
    /// The compass cannot be carried along the adjusted path (a counted side at a vertex the
    /// adjustment enters along a new edge reaches the boundary or meets a face that is not a
    /// quad); the position is in the adjusted path.
    Carry(PlanError),
}

impl fmt::Display for PrepareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::End {
                index,
                vertex,
                valence,
                boundary,
            } => write!(
                f,
                "path end {} (position {index}) has valence {valence}{}; the end-point \
                 adjustments of Sec. 2.6 need an interior v3 or v5",
                vertex.index(),
                if *boundary { " on the boundary" } else { "" }
            ),
            Self::NoQuad { vertex } => write!(
                f,
                "the end-point adjustment at vertex {} needs a quad of its one-ring that is \
                 missing (boundary) or not a quad",
                vertex.index()
            ),
            Self::NotSimple { vertex } => write!(
                f,
                "the adjusted path visits vertex {} twice",
                vertex.index()
            ),
            Self::Empty => f.write_str("no operation is left after the end-point adjustments"),
            Self::StalePlan => f.write_str("the plan does not fit this map"),
            Self::Carry(e) => write!(f, "along the adjusted path: {e}"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for PrepareError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Carry(e) => Some(e),
            _ => None,
        }
    }
}

fn end_error(map: &Map, index: usize, vertex: Vert) -> PrepareError {
    PrepareError::End {
        index,
        vertex,
        valence: map.valence(vertex),
        boundary: map.is_boundary_vertex(vertex),
    }
}

/// Valence 3 or 5 of an interior end, or the refusal.
fn end_valence(map: &Map, index: usize, v: Vert) -> Result<usize, PrepareError> {
    match map.valence(v) {
        k @ (3 | 5) if !map.is_boundary_vertex(v) => Ok(k),
        _ => Err(end_error(map, index, v)),
    }
}

/// A vertex that occurs twice in `v`, if any: short lists by a scan (no allocation),
/// long ones by sorting a copy.
fn repeated(v: &[Vert]) -> Option<Vert> {
    if v.len() <= 24 {
        return (1..v.len()).find_map(|i| v[..i].contains(&v[i]).then_some(v[i]));
    }
    let mut sorted = v.to_vec();
    sorted.sort_unstable();
    sorted.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
}

/// The dart `a -> d` if `a -> b -> c -> d` goes round one quad (its fourth side joins `d`
/// to `a`) whose corners `b` and `c` are regular.
fn round_regular_quad(map: &Map, [a, b, c, d]: [Vert; 4]) -> Option<Dart> {
    let regular = |w: Vert| is_regular_interior(map, MeshKind::Quad, w);
    // Not a path dart: the quad's fourth side, looked up in the map.
    quad_on_edge(map, a, d, [a, b, c, d]).filter(|_| regular(b) && regular(c))
}

/// Vertices the end rules may add to a draft beyond the plan's (two at each end).
const SLACK: usize = 4;

/// The path being adjusted: its vertices and, per edge `i` (from vertex `i` to `i + 1`), the
/// dart, the compass hand and whether vertex `i` does nothing (a no-op).
struct Draft {
    vertices: Vec<Vert>,
    darts: Vec<Dart>,
    hands: Vec<Tag>,
    noops: Vec<bool>,
}

impl Draft {
    /// The plan's path, every vertex with its operation.
    fn new(plan: &Plan) -> Self {
        let steps = plan.steps();
        // Room for the vertices the start and end rules add (a quad's corners at each end),
        // so that no vector regrows: `prepend` and `append` were 5 % of a Q-zip's instructions.
        let room = steps.len().saturating_add(SLACK);
        let mut d = Draft {
            vertices: Vec::with_capacity(room),
            darts: Vec::with_capacity(room),
            hands: Vec::with_capacity(room),
            noops: Vec::with_capacity(room),
        };
        d.vertices.extend(steps.iter().map(|s| s.vertex));
        d.darts.extend_from_slice(plan.darts());
        d.hands
            .extend(steps[..steps.len() - 1].iter().map(|s| s.tag));
        d.noops.resize(d.hands.len(), false);
        d
    }

    /// The carried dart `i` when it still joins vertices `i` and `i + 1` of `map`.
    fn dart(&self, map: &Map, i: usize) -> Result<Dart, PrepareError> {
        let d = *self.darts.get(i).ok_or(PrepareError::StalePlan)?;
        let joins = map.is_live_dart(d)
            && map.origin(d) == self.vertices[i]
            && map.dest(d) == self.vertices[i + 1];
        joins.then_some(d).ok_or(PrepareError::StalePlan)
    }

    /// Puts `vertex` in front, joined to the old first vertex by `dart`.
    fn prepend(&mut self, vertex: Vert, dart: Dart, hand: Tag, noop: bool) {
        self.vertices.insert(0, vertex);
        self.darts.insert(0, dart);
        self.hands.insert(0, hand);
        self.noops.insert(0, noop);
    }

    /// Appends `vertex`, joined to the old last vertex by `dart`.
    fn append(&mut self, vertex: Vert, dart: Dart, hand: Tag) {
        self.vertices.push(vertex);
        self.darts.push(dart);
        self.hands.push(hand);
        self.noops.push(false);
    }

    /// The start rule of Sec. 2.6 for the initial operation `initial`.
    fn adjust_start(&mut self, map: &Map, initial: Tag) -> Result<StartRule, PrepareError> {
        let from = self.vertices[0];
        Ok(match (end_valence(map, 0, from)?, initial.is_split()) {
            (3, true) => {
                self.noops[0] = true;
                StartRule::V3Split
            }
            (3, false) => {
                // Round the quad on the collapse's side: x -> x' -> p1.
                let left = initial == Tag::LC;
                let quad = side_quad(map, self.dart(map, 0)?, left)
                    .ok_or(PrepareError::NoQuad { vertex: from })?;
                self.vertices[0] = quad.near_dest(map);
                self.darts[0] = quad.back;
                self.hands[0] = if left { initial.cw() } else { initial.ccw() };
                self.prepend(quad.near_origin(map), quad.across, initial, false);
                self.carry_from(map, 2)?;
                StartRule::V3Collapse
            }
            (_, false) => StartRule::V5Collapse,
            (_, true) => {
                let guide = second_neighbour(map, self.dart(map, 0)?, initial == Tag::LS);
                self.prepend(map.dest(guide), guide.twin(), initial, true);
                StartRule::V5Split
            }
        })
    }

    /// Carries the compass along the draft from vertex `i` on (Sec. 2.5): the hand along
    /// each edge is the hand along the edge before, turned by the turn between them (the
    /// counting rule at an irregular vertex). Stops at a fold (`a -> b -> a`), which
    /// [`Draft::cancel_folds`] cuts keeping the hand of the edge that leaves it.
    ///
    /// A v3 start's reroute enters the first path vertex `p1` along another edge than the
    /// planned path did, with another hand; at a regular `p1` the two give the same hand on,
    /// at an irregular one the reroute's quad is counted on one side and not on the other, so
    /// only the compass carried along the rerouted path is consistent with it.
    fn carry_from(&mut self, map: &Map, i: usize) -> Result<(), PrepareError> {
        for k in i..self.hands.len() {
            if self.vertices[k + 1] == self.vertices[k - 1] {
                return Ok(());
            }
            let (back, out) = (self.darts[k - 1].twin(), self.darts[k]);
            let (turn, ..) =
                turn_at(map, self.hands[k - 1], back, out, k).map_err(PrepareError::Carry)?;
            self.hands[k] = self.hands[k - 1].after(turn);
        }
        Ok(())
    }

    /// A path that reaches the terminal singularity by going round a quad touching it
    /// (a -> b -> c -> end, with a and end joined by that quad's fourth side) is shortened to
    /// a -> end, a homotopy across that quad inside the one-ring: the compass along a -> end
    /// is the hand along b -> c, the parallel side. Adjusting the end of the U-turn instead
    /// would reroute back over it. Returns whether it shortened the path.
    fn shorten_round_quad_end(&mut self, map: &Map) -> bool {
        let v = &self.vertices;
        if v.len() < 4 {
            return false;
        }
        let m = v.len() - 1;
        if self.noops[m - 3] {
            return false;
        }
        let side = round_regular_quad(map, [v[m - 3], v[m - 2], v[m - 1], v[m]]);
        if let Some(side) = side {
            self.cut_round_quad(m - 3, side);
        }
        side.is_some()
    }

    /// A path swept round a regular quad just before the U-turn that
    /// [`Draft::shorten_round_quad_end`] shortens (`p -> x -> y -> b -> c -> end`, with
    /// `[p, x, y, b]` and `[p, b, c, end]` quads and `x`, `y`, `b`, `c` regular) is
    /// straightened to `p -> b` (the hand along `x -> y`, the parallel side), so that the end
    /// rule then shortens it to `p -> end` as it shortens the path it was swept from; again
    /// while the pattern holds. Found by the `qzip_homotopy` fuzz target (`docs/qzip.md`).
    fn straighten_before_end_quad(&mut self, map: &Map) {
        while self.vertices.len() >= 6 {
            let v = &self.vertices;
            let m = v.len() - 1;
            let (p, b) = (v[m - 5], v[m - 2]);
            let end_turn = round_regular_quad(map, [p, b, v[m - 1], v[m]]).is_some();
            let swept = round_regular_quad(map, [p, v[m - 4], v[m - 3], b]);
            let (Some(side), true) = (swept, end_turn) else {
                return;
            };
            if self.noops[m - 5..=m - 3].iter().any(|&n| n) {
                return;
            }
            self.cut_round_quad(m - 5, side);
        }
    }

    /// Replaces `v[i] -> x -> y -> v[i + 3]` by `side` (`v[i] -> v[i + 3]`), which takes the
    /// hand along `x -> y`, the parallel side.
    fn cut_round_quad(&mut self, i: usize, side: Dart) {
        self.hands[i] = self.hands[i + 1];
        self.darts[i] = side;
        self.vertices.drain(i + 1..i + 3);
        self.darts.drain(i + 1..i + 3);
        self.hands.drain(i + 1..i + 3);
        self.noops.drain(i + 1..i + 3);
    }

    /// The end rule of Sec. 2.6 for the compass arriving with `arriving`; `index` is the end's
    /// position in the plan.
    fn adjust_end(
        &mut self,
        map: &Map,
        index: usize,
        arriving: Tag,
    ) -> Result<EndRule, PrepareError> {
        let m = self.vertices.len() - 1;
        let to = self.vertices[m];
        if end_valence(map, index, to)? == 3 {
            return Ok(EndRule::V3);
        }
        let last = self.dart(map, m - 1)?;
        if arriving.is_split() {
            let guide = second_neighbour(map, last.twin(), arriving == Tag::LS);
            self.append(map.dest(guide), guide, arriving);
            return Ok(EndRule::V5Split);
        }
        // Replace the last edge q' -> q by the two other sides q' -> f -> f' of the quad.
        let left = arriving == Tag::LC;
        let quad: SideQuad =
            side_quad(map, last, left).ok_or(PrepareError::NoQuad { vertex: to })?;
        self.vertices[m] = quad.near_origin(map);
        self.darts[m - 1] = quad.out;
        self.hands[m - 1] = if left { arriving.ccw() } else { arriving.cw() };
        self.append(quad.near_dest(map), quad.across, arriving);
        Ok(EndRule::V5Collapse)
    }

    /// Cuts the closed walk of `len` edges that starts at position `i` (`v[i] == v[i + len]`):
    /// the surviving `v[i]` takes the hand (and the dart) of the edge leaving the walk, so the
    /// compass after it is unchanged.
    fn cut_closed_walk(&mut self, i: usize, len: usize) {
        // noops is per outgoing edge: if the walk ends the path, vertex i becomes last.
        if i + len == self.vertices.len() - 1 {
            self.noops.drain(i..i + len);
        } else {
            self.noops.drain(i + 1..i + len + 1);
        }
        self.vertices.drain(i + 1..i + len + 1);
        self.hands.drain(i..i + len);
        self.darts.drain(i..i + len);
    }

    /// Cancels the folds a -> b -> a: vertex a takes the hand of the edge leaving the fold.
    fn cancel_folds(&mut self) -> usize {
        let mut folds = 0;
        let mut i = 0;
        while i + 2 < self.vertices.len() {
            if self.vertices[i] == self.vertices[i + 2] {
                self.cut_closed_walk(i, 2);
                folds += 1;
                i = i.saturating_sub(1);
            } else {
                i += 1;
            }
        }
        folds
    }

    /// Cancels the loops a -> x -> y -> z -> a round one quad whose other corners are regular:
    /// a homotopy across that quad (an end reroute after a path that went round the quad on
    /// the other side makes them). Vertex a takes the hand of the edge leaving the loop, as at
    /// a fold.
    fn cancel_quad_loops(&mut self, map: &Map, ends: [Vert; 2]) -> usize {
        let mut loops = 0;
        let mut i = 0;
        while i + 4 < self.vertices.len() {
            let v = &self.vertices;
            let round_quad = v[i] == v[i + 4]
                && bounds_one_quad(map, [v[i], v[i + 1], v[i + 2], v[i + 3]], ends, true);
            if round_quad {
                self.cut_closed_walk(i, 4);
                loops += 1;
            } else {
                i += 1;
            }
        }
        loops
    }

    /// A v3 start's reroute folded back onto the path so that the first operation is a split:
    /// it needs a guide, and the v3 `from` it started from is one (as in a v3 start with a
    /// split, whose no-op start guides the first split).
    fn restore_v3_guide(&mut self, map: &Map, from: Vert) {
        let first_is_split =
            self.hands.first().is_some_and(|h| h.is_split()) && self.noops.first() == Some(&false);
        if !first_is_split || self.vertices.contains(&from) {
            return;
        }
        // Not a path dart: the edge back to the v3, looked up in the map.
        if let Some(d) = map.dart_between(from, self.vertices[0]) {
            let hand = self.hands[0];
            self.prepend(from, d, hand, true);
        }
    }

    /// The surgery steps: each vertex with the hand along its outgoing edge and its operation;
    /// the last with the hand the compass arrives with.
    fn steps(&self, arriving: Tag) -> Vec<SurgeryStep> {
        let hands = &self.hands;
        let mut out: Vec<SurgeryStep> = self
            .vertices
            .iter()
            .enumerate()
            .map(|(i, &vertex)| {
                let hand = hands.get(i).copied().unwrap_or(arriving);
                let op = (i < hands.len() && !self.noops[i]).then_some(hand);
                SurgeryStep { vertex, hand, op }
            })
            .collect();
        if let Some(l) = out.last_mut() {
            l.hand = hands.last().copied().unwrap_or(arriving);
            l.op = None;
        }
        out
    }
}

/// The dart from the origin of `d` to its second neighbour counter-clockwise (`ccw`) or
/// clockwise from `d`: the guide edge of a split at a v5 end.
fn second_neighbour(map: &Map, d: Dart, ccw: bool) -> Dart {
    if ccw {
        map.rotate_ccw(map.rotate_ccw(d))
    } else {
        map.rotate_cw(map.rotate_cw(d))
    }
}

/// Applies the end-point adjustments of Sec. 2.6 to a plan, then cancels folds and loops
/// round one quad.
///
/// Both ends must be interior v3s or v5s ([`PrepareError::End`] otherwise: boundary ends and
/// other valences are outside Sec. 2.6). The adjustments are listed in the
/// [module documentation](self); each reads only the one-ring of its singularity. Reads the map,
/// never changes it.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{plan, prepare, sketch, EndRule, SketchOptions, StartRule, Tag};
/// let map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
/// let s = prepare(&map, &plan(&map, &path, Tag::LC).unwrap()).unwrap();
/// assert_eq!((s.start_rule(), s.end_rule()), (StartRule::V5Collapse, EndRule::V3));
/// ```
pub fn prepare(map: &Map, plan: &Plan) -> Result<Surgery, PrepareError> {
    let steps = plan.steps();
    if steps.len() < 2 {
        return Err(PrepareError::StalePlan);
    }
    let mut draft = Draft::new(plan);
    let initial = plan.initial();
    let (from, to) = (steps[0].vertex, steps[steps.len() - 1].vertex);
    let start = draft.adjust_start(map, initial)?;
    // Until neither applies: a shortened end can be a U-turn again (a path swept round the
    // quad at the end turns round the next one), and its sweep must end as the path does.
    // Each round drops two vertices, so the path's length bounds the rounds.
    for _ in 0..steps.len() {
        draft.straighten_before_end_quad(map);
        if !draft.shorten_round_quad_end(map) {
            break;
        }
    }
    let arriving = draft.hands[draft.hands.len() - 1];
    let end = draft.adjust_end(map, steps.len() - 1, arriving)?;
    let mut folds = draft.cancel_folds();
    folds += draft.cancel_quad_loops(map, [from, to]);
    if start == StartRule::V3Collapse {
        draft.restore_v3_guide(map, from);
    }
    if let Some(w) = repeated(&draft.vertices) {
        return Err(PrepareError::NotSimple { vertex: w });
    }
    let s = Surgery {
        steps: draft.steps(arriving),
        from,
        to,
        initial,
        start,
        end,
        folds,
        darts: draft.darts,
    };
    if s.operations() == 0 {
        return Err(PrepareError::Empty);
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;
    use crate::qzip::{plan, sketch, validate_path, SketchOptions, Tag};
    use alloc::string::ToString;

    /// The simplicity test finds a repeat in short lists (scanned) and long ones (sorted).
    #[test]
    fn repeated_vertices_are_found_at_every_length() {
        for n in [2u32, 5, 24, 25, 200] {
            let mut v: Vec<Vert> = (0..n).map(|i| Vert::new(3 * i)).collect();
            assert_eq!(repeated(&v), None, "{n} distinct");
            v.push(Vert::new(3 * (n / 2)));
            assert_eq!(
                repeated(&v),
                Some(Vert::new(3 * (n / 2))),
                "{n} and a repeat"
            );
        }
        assert_eq!(repeated(&[]), None);
    }

    /// A surgery prints its rules, one line per vertex, and ends with the end vertex.
    #[test]
    fn surgery_reads_one_line_per_vertex_ending_at_the_end() {
        let map = gen::subdivided_icosahedron(2).map;
        let (v5, v3) = (Vert::new(0), Vert::new(42));
        let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
        let s = prepare(&map, &plan(&map, &path, Tag::LC).unwrap()).unwrap();
        let text = s.to_string();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            alloc::format!("{}; {}", s.start_rule(), s.end_rule())
        );
        assert_eq!(lines.len(), s.steps().len() + 1);
        let last = s.steps()[s.steps().len() - 1].vertex;
        assert_eq!(
            lines[lines.len() - 1],
            alloc::format!("vertex {}: end", last.index())
        );
        for (line, step) in lines[1..lines.len() - 1].iter().zip(s.steps()) {
            let op = step.op.map_or("no-op".to_string(), |t| t.to_string());
            assert_eq!(
                *line,
                alloc::format!("vertex {}: {op}", step.vertex.index())
            );
        }
    }

    /// A draft along the vertices `v` of `map` (consecutive ones joined), edge `i` with hand
    /// `hands[i]`, vertex 0 a no-op.
    fn draft(map: &Map, v: &[Vert], hands: &[Tag]) -> Draft {
        let darts = v
            .windows(2)
            .map(|w| map.dart_between(w[0], w[1]).unwrap())
            .collect();
        let mut noops = alloc::vec![false; hands.len()];
        noops[0] = true;
        Draft {
            vertices: v.to_vec(),
            darts,
            hands: hands.to_vec(),
            noops,
        }
    }

    /// The vertices straight on from `d` (through regular vertices) until the walk closes.
    fn straight_cycle(map: &Map, d: crate::Dart) -> Vec<Vert> {
        let (mut out, mut d) = (alloc::vec![map.origin(d)], d);
        while map.dest(d) != out[0] {
            out.push(map.dest(d));
            d = map.rotate_cw(map.rotate_cw(d.twin()));
        }
        out
    }

    const HANDS: [Tag; 6] = [Tag::LS, Tag::RS, Tag::LC, Tag::RC, Tag::RS, Tag::LC];

    /// Cutting a closed walk keeps vertex i's no-op flag and the hand and dart of the edge
    /// leaving the walk; one that ends the path leaves vertex i last, with no edge.
    #[test]
    fn cutting_a_closed_walk_keeps_the_flag_and_the_leaving_edge() {
        let map = gen::grid(5, 5).map;
        let [a, b, c, d, e] = [7u32, 8, 14, 13, 6].map(Vert::new);
        // a -> b -> c -> d -> a is one quad; e follows.
        for i in [0usize, 1] {
            let mut v = alloc::vec![e; i];
            v.extend([a, b, c, d, a, e]);
            let hands = &HANDS[..v.len() - 1];
            let mut dr = draft(&map, &v, hands);
            let keep = dr.darts[i + 4];
            dr.cut_closed_walk(i, 4);
            let mut want = alloc::vec![e; i];
            want.extend([a, e]);
            assert_eq!(dr.vertices, want, "walk at {i}");
            assert_eq!(dr.darts.len(), i + 1);
            assert_eq!(dr.darts[i], keep);
            assert_eq!(dr.hands, [&hands[..i], &hands[i + 4..]].concat());
            let mut noops = alloc::vec![false; i + 1];
            noops[0] = true;
            assert_eq!(dr.noops, noops, "walk at {i}");
        }
        // The walk ends the path: a is last and its flag goes with its edge.
        let v = [e, a, b, c, d, a].to_vec();
        let mut dr = draft(&map, &v, &HANDS[..5]);
        dr.cut_closed_walk(1, 4);
        assert_eq!(dr.vertices, [e, a]);
        assert_eq!((dr.darts.len(), dr.hands.len()), (1, 1));
        assert_eq!(dr.noops, [true]);
    }

    /// A path swept round a regular quad just before the end's U-turn is straightened there
    /// (the parallel side's hand), and the end rule then shortens it as it shortens the path
    /// it was swept from; without the U-turn, or with a no-op on the quad, it is kept.
    #[test]
    fn a_sweep_before_the_end_turn_is_straightened() {
        let map = gen::grid(6, 6).map;
        // 16 -> 17 -> 24 -> 23 goes round the end's quad; 16 -> 9 -> 10 -> 17 round the
        // quad on the other side of 16 -> 17.
        let [p, x, y, b, c, e] = [16u32, 9, 10, 17, 24, 23].map(Vert::new);
        let mut dr = draft(&map, &[p, x, y, b, c, e], &HANDS[..5]);
        dr.noops[0] = false;
        dr.straighten_before_end_quad(&map);
        assert_eq!(dr.vertices, [p, b, c, e]);
        assert_eq!(dr.darts[0], map.dart_between(p, b).unwrap());
        assert_eq!(dr.hands, [HANDS[1], HANDS[3], HANDS[4]]);
        assert_eq!(dr.noops, [false; 3]);
        dr.shorten_round_quad_end(&map);
        assert_eq!(
            (dr.vertices.as_slice(), dr.hands.as_slice()),
            (&[p, e][..], &HANDS[3..4])
        );
        // One vertex more in front (15), so that the sweep is not at the path's start.
        let q = Vert::new(15);
        let mut dr = draft(&map, &[q, p, x, y, b, c, e], &HANDS[..6]);
        dr.straighten_before_end_quad(&map);
        dr.shorten_round_quad_end(&map);
        assert_eq!(dr.vertices, [q, p, e]);
        assert_eq!(dr.hands, [HANDS[0], HANDS[4]]);
        // The same sweep before a straight end (b -> c -> 25 bounds no quad with p).
        let straight = [p, x, y, b, c, Vert::new(25)];
        let mut dr = draft(&map, &straight, &HANDS[..5]);
        dr.noops[0] = false;
        dr.straighten_before_end_quad(&map);
        assert_eq!(dr.vertices, straight);
        // A no-op where the sweep starts, or on its far side, keeps it.
        for i in [0, 2] {
            let mut dr = draft(&map, &[p, x, y, b, c, e], &HANDS[..5]);
            (dr.noops[0], dr.noops[i]) = (false, true);
            dr.straighten_before_end_quad(&map);
            assert_eq!(dr.vertices.len(), 6, "no-op at {i}");
        }
    }

    /// A path that goes round one quad to the end is shortened across it; three edges whose
    /// ends are joined without bounding a quad (a straight wrap of a thin torus) are kept.
    #[test]
    fn only_a_round_quad_end_is_shortened() {
        let map = gen::grid(5, 5).map;
        let [a, b, c, e] = [7u32, 8, 14, 13].map(Vert::new);
        let mut dr = draft(&map, &[a, b, c, e], &HANDS[..3]);
        dr.noops[0] = false;
        dr.shorten_round_quad_end(&map);
        assert_eq!(dr.vertices, [a, e]);
        assert_eq!(dr.darts, [map.dart_between(a, e).unwrap()]);
        assert_eq!(
            (dr.hands.as_slice(), dr.noops.as_slice()),
            (&HANDS[1..2], &[false][..])
        );
        // A no-op first vertex keeps its edge.
        let mut dr = draft(&map, &[a, b, c, e], &HANDS[..3]);
        dr.shorten_round_quad_end(&map);
        assert_eq!(dr.vertices.len(), 4);
        // So does a quad with a boundary corner: 13 -> 7 -> 6 -> 12 (6 on the boundary).
        let round = [13u32, 7, 6, 12].map(Vert::new);
        let mut dr = draft(&map, &round, &HANDS[..3]);
        dr.noops[0] = false;
        dr.shorten_round_quad_end(&map);
        assert_eq!(dr.vertices, round);
        let torus = gen::torus_grid(4, 8).map;
        let d = (0..4)
            .map(|k| {
                let mut d = torus.vertex_dart(Vert::new(0));
                for _ in 0..k {
                    d = torus.rotate_cw(d);
                }
                d
            })
            .find(|&d| straight_cycle(&torus, d).len() == 4)
            .unwrap();
        let row = straight_cycle(&torus, d);
        let mut dr = draft(&torus, &row, &HANDS[..3]);
        dr.noops[0] = false;
        dr.shorten_round_quad_end(&torus);
        assert_eq!(dr.vertices, row);
        assert_eq!(dr.hands.len(), 3);
    }

    /// The preparation's errors say what went wrong, each in its own words.
    #[test]
    fn prepare_errors_read_as_documented() {
        assert_eq!(
            PrepareError::Empty.to_string(),
            "no operation is left after the end-point adjustments"
        );
        assert_eq!(
            PrepareError::StalePlan.to_string(),
            "the plan does not fit this map"
        );
        assert_eq!(
            PrepareError::NotSimple {
                vertex: Vert::new(7)
            }
            .to_string(),
            "the adjusted path visits vertex 7 twice"
        );
    }

    /// A v3 start with a collapse whose path turns into the reroute's quad at once
    /// (`v3 -> p1 -> x`, `x` the quad's corner next to `p1`): the reroute comes back along
    /// `x -> p1` and the path goes `p1 -> x`, a fold at `p1`. The compass is carried up to
    /// the fold only (carried through it, the U-turn reads as a stale path and fails); the
    /// fold is cancelled and `p1` leaves the surgery.
    #[test]
    fn a_reroute_folding_into_the_path_is_carried_up_to_the_fold() {
        let map = gen::cube(3).map;
        let opts = SketchOptions::default();
        let corners: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 3).collect();
        let mut found = 0;
        for &a in &corners {
            for d in map.vertex_darts(a) {
                for (tag, left) in [(Tag::LC, true), (Tag::RC, false)] {
                    let Some(q) = side_quad(&map, d, left) else {
                        continue;
                    };
                    let (p1, x) = (map.dest(d), q.near_dest(&map));
                    for &b in corners.iter().filter(|&&b| b != a) {
                        let Ok(tail) = sketch(&map, x, b, &opts) else {
                            continue;
                        };
                        let mut v = alloc::vec![a, p1];
                        v.extend_from_slice(tail.vertices());
                        let Ok(path) = validate_path(&map, a, b, &v, &opts) else {
                            continue;
                        };
                        let s = prepare(&map, &plan(&map, &path, tag).unwrap()).unwrap();
                        assert_eq!(s.start_rule(), StartRule::V3Collapse);
                        assert!(s.folds() >= 1, "{path} {tag}");
                        // The fold is gone: p1 is not in the surgery.
                        assert!(
                            s.steps().iter().all(|x| x.vertex != p1),
                            "{path} {tag}\n{s}"
                        );
                        found += 1;
                    }
                }
            }
        }
        assert!(found >= 8, "{found}");
    }
}
