//! Stage 2 of Q-zip, planning: the compass carried along the surgery path.
//!
//! The compass has four hands ([`Tag`]): LS north, RC west, LC south, RS east, so the
//! counter-clockwise order is LS -> RC -> LC -> RS -> LS. [`plan`] starts with the caller's
//! initial tag at the path's first vertex and carries it along: at each interior vertex a
//! straight step keeps the tag, a left turn takes the next counter-clockwise tag and a right
//! turn the next clockwise one.
//!
//! The turn is read from a count of quads around the vertex between the incoming and the
//! outgoing path edge, on the side the previous tag names ([`Tag::counting_side`]): the left
//! after LS or RC, the right after RS or LC. On the left one quad is a left turn, two are
//! straight and three or more a right turn; on the right it is mirrored (one is a right turn,
//! three or more a left turn). At a regular interior vertex (valence 4) both sides give the
//! same turn; at an irregular one this is the paper's deterministic rule (its Fig. 8).
//!
//! ```
//! use zipmesh::{gen, Vert};
//! use zipmesh::qzip::{plan, validate_path, SketchOptions, Tag, Turn};
//! // Torus 6 x 6, vertex (i, j) is 6 j + i; path east then north: a left turn at (2, 0).
//! let map = gen::torus_grid(6, 6).map;
//! let v = |i: u32, j: u32| Vert::new(6 * j + i);
//! let path = validate_path(&map, v(0, 0), v(2, 1), &[v(0, 0), v(1, 0), v(2, 0), v(2, 1)],
//!     &SketchOptions::default()).unwrap();
//! let p = plan(&map, &path, Tag::LS).unwrap();
//! let tags: Vec<Tag> = p.steps().iter().map(|s| s.tag).collect();
//! assert_eq!(tags, [Tag::LS, Tag::LS, Tag::RC, Tag::RC]);
//! assert_eq!(p.steps()[2].turn, Some(Turn::Left));
//! ```

use alloc::string::String;
use alloc::vec::Vec;
use core::fmt;
use core::str::FromStr;

use super::sketch::Path;
use crate::invariants::{regular_valence, MeshKind};
use crate::{Dart, Face, Map, Vert};

/// One of the four strip operations of the compass: left/right split, left/right collapse.
///
/// ```
/// use zipmesh::qzip::Tag;
/// assert_eq!(Tag::LS.ccw(), Tag::RC);
/// assert_eq!("lc".parse::<Tag>().unwrap(), Tag::LC);
/// assert_eq!(Tag::RS.to_string(), "RS");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Tag {
    /// Left split (compass north).
    LS,
    /// Right split (compass east).
    RS,
    /// Left collapse (compass south).
    LC,
    /// Right collapse (compass west).
    RC,
}

impl Tag {
    /// The four tags in counter-clockwise compass order, starting at north.
    ///
    /// ```
    /// use zipmesh::qzip::Tag;
    /// for (i, t) in Tag::CCW.iter().enumerate() {
    ///     assert_eq!(t.ccw(), Tag::CCW[(i + 1) % 4]);
    /// }
    /// ```
    pub const CCW: [Tag; 4] = [Tag::LS, Tag::RC, Tag::LC, Tag::RS];

    /// The next tag counter-clockwise (taken on a left turn).
    ///
    /// ```
    /// use zipmesh::qzip::Tag;
    /// assert_eq!(Tag::RS.ccw(), Tag::LS);
    /// ```
    pub fn ccw(self) -> Tag {
        match self {
            Tag::LS => Tag::RC,
            Tag::RC => Tag::LC,
            Tag::LC => Tag::RS,
            Tag::RS => Tag::LS,
        }
    }

    /// The next tag clockwise (taken on a right turn).
    ///
    /// ```
    /// use zipmesh::qzip::Tag;
    /// assert_eq!(Tag::LS.cw(), Tag::RS);
    /// assert_eq!(Tag::LS.cw().ccw(), Tag::LS);
    /// ```
    pub fn cw(self) -> Tag {
        match self {
            Tag::LS => Tag::RS,
            Tag::RS => Tag::LC,
            Tag::LC => Tag::RC,
            Tag::RC => Tag::LS,
        }
    }

    /// The compass rotated by pi: LS <-> LC, RS <-> RC.
    ///
    /// ```
    /// use zipmesh::qzip::Tag;
    /// assert_eq!(Tag::LS.rotate_pi(), Tag::LC);
    /// assert_eq!(Tag::RC.rotate_pi(), Tag::RS);
    /// ```
    pub fn rotate_pi(self) -> Tag {
        self.ccw().ccw()
    }

    /// The compass turned by `k` quarter turns counter-clockwise (negative: clockwise).
    ///
    /// ```
    /// use zipmesh::qzip::Tag;
    /// assert_eq!(Tag::LS.turned(1), Tag::RC);
    /// assert_eq!(Tag::LS.turned(-1), Tag::RS);
    /// assert_eq!(Tag::LC.turned(6), Tag::LS);
    /// ```
    pub fn turned(self, k: i32) -> Tag {
        let i = Tag::CCW.iter().position(|&t| t == self).unwrap_or(0) as i32;
        Tag::CCW[(i + k).rem_euclid(4) as usize]
    }

    /// The tag after a turn: straight keeps it, left is [`Tag::ccw`], right is [`Tag::cw`].
    ///
    /// ```
    /// use zipmesh::qzip::{Tag, Turn};
    /// assert_eq!(Tag::LS.after(Turn::Left), Tag::RC);
    /// assert_eq!(Tag::LS.after(Turn::Straight), Tag::LS);
    /// ```
    pub fn after(self, turn: Turn) -> Tag {
        match turn {
            Turn::Left => self.ccw(),
            Turn::Straight => self,
            Turn::Right => self.cw(),
        }
    }

    /// The side whose quads are counted at the next vertex: left after LS or RC, right after
    /// RS or LC.
    ///
    /// ```
    /// use zipmesh::qzip::{Side, Tag};
    /// assert_eq!(Tag::RC.counting_side(), Side::Left);
    /// assert_eq!(Tag::LC.counting_side(), Side::Right);
    /// ```
    pub fn counting_side(self) -> Side {
        match self {
            Tag::LS | Tag::RC => Side::Left,
            Tag::RS | Tag::LC => Side::Right,
        }
    }

    /// Whether the tag is a split (LS, RS) rather than a collapse (LC, RC).
    ///
    /// ```
    /// use zipmesh::qzip::Tag;
    /// assert!(Tag::RS.is_split() && !Tag::RC.is_split());
    /// ```
    pub fn is_split(self) -> bool {
        matches!(self, Tag::LS | Tag::RS)
    }
}

impl fmt::Display for Tag {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Tag::LS => "LS",
            Tag::RS => "RS",
            Tag::LC => "LC",
            Tag::RC => "RC",
        })
    }
}

/// A string that names no tag (the accepted names are LS, RS, LC, RC in any case).
///
/// ```
/// use zipmesh::qzip::Tag;
/// let e = "XX".parse::<Tag>().unwrap_err();
/// assert!(e.to_string().contains("XX"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TagParseError(pub String);

impl fmt::Display for TagParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown move {:?}: expected LS, RS, LC or RC", self.0)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for TagParseError {}

impl FromStr for Tag {
    type Err = TagParseError;

    fn from_str(s: &str) -> Result<Tag, TagParseError> {
        Tag::CCW
            .into_iter()
            .find(|t| s.eq_ignore_ascii_case(t.as_str()))
            .ok_or_else(|| TagParseError(s.into()))
    }
}

impl Tag {
    fn as_str(self) -> &'static str {
        match self {
            Tag::LS => "LS",
            Tag::RS => "RS",
            Tag::LC => "LC",
            Tag::RC => "RC",
        }
    }
}

/// The direction the path takes at a vertex, seen along the path.
///
/// ```
/// use zipmesh::qzip::{Side, Turn};
/// assert_eq!(Turn::from_count(Side::Left, 1), Some(Turn::Left));
/// assert_eq!(Turn::from_count(Side::Right, 1), Some(Turn::Right));
/// assert_eq!(Turn::Left.to_string(), "left");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Turn {
    /// A left turn.
    Left,
    /// Straight on.
    Straight,
    /// A right turn.
    Right,
}

impl Turn {
    /// The turn given by `count` quads on `side` between the incoming and outgoing edges:
    /// one is a turn towards that side, two is straight, three or more a turn away from it;
    /// `None` for zero.
    ///
    /// ```
    /// use zipmesh::qzip::{Side, Turn};
    /// assert_eq!(Turn::from_count(Side::Left, 2), Some(Turn::Straight));
    /// assert_eq!(Turn::from_count(Side::Left, 5), Some(Turn::Right));
    /// assert_eq!(Turn::from_count(Side::Right, 3), Some(Turn::Left));
    /// assert_eq!(Turn::from_count(Side::Right, 0), None);
    /// ```
    pub fn from_count(side: Side, count: usize) -> Option<Turn> {
        let (toward, away) = match side {
            Side::Left => (Turn::Left, Turn::Right),
            Side::Right => (Turn::Right, Turn::Left),
        };
        match count {
            0 => None,
            1 => Some(toward),
            2 => Some(Turn::Straight),
            _ => Some(away),
        }
    }
}

impl fmt::Display for Turn {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Turn::Left => "left",
            Turn::Straight => "straight",
            Turn::Right => "right",
        })
    }
}

/// A side of the path, seen along it.
///
/// ```
/// use zipmesh::qzip::Side;
/// assert_eq!(Side::Left.to_string(), "left");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// The left-hand side.
    Left,
    /// The right-hand side.
    Right,
}

impl fmt::Display for Side {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Side::Left => "left",
            Side::Right => "right",
        })
    }
}

/// One vertex of a [`Plan`].
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{plan, sketch, SketchOptions, Tag};
/// let map = gen::torus_grid(5, 5).map;
/// let path = sketch(&map, Vert::new(0), Vert::new(1), &SketchOptions::default()).unwrap();
/// let step = plan(&map, &path, Tag::RS).unwrap().steps()[0];
/// assert_eq!((step.vertex, step.tag, step.turn, step.count), (Vert::new(0), Tag::RS, None, None));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanStep {
    /// The path vertex.
    pub vertex: Vert,
    /// The tag of the operation at this vertex; at the last vertex, the tag the compass
    /// arrives with.
    pub tag: Tag,
    /// The turn taken here; `None` at the two ends.
    pub turn: Option<Turn>,
    /// The side counted and the number of quads found there; `None` at the two ends.
    pub count: Option<(Side, usize)>,
}

/// The compass tags along a path: one [`PlanStep`] per path vertex.
///
/// Its `Display` prints one line per vertex.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{plan, sketch, SketchOptions, Tag};
/// let map = gen::torus_grid(6, 6).map;
/// let path = sketch(&map, Vert::new(0), Vert::new(2), &SketchOptions::default()).unwrap();
/// let p = plan(&map, &path, Tag::LC).unwrap();
/// assert_eq!(p.to_string().lines().count(), 3);
/// assert!(p.to_string().contains("vertex 1: LC (straight, 2 quads on the right)"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    steps: Vec<PlanStep>,
    /// The path's darts, carried on to the preparation: dart `i` joins steps `i` and `i + 1`.
    darts: Vec<Dart>,
}

impl Plan {
    /// The steps, one per path vertex, from the start to the end.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, sketch, SketchOptions, Tag};
    /// let map = gen::torus_grid(6, 6).map;
    /// let path = sketch(&map, Vert::new(0), Vert::new(3), &SketchOptions::default()).unwrap();
    /// let p = plan(&map, &path, Tag::LS).unwrap();
    /// assert!(p.steps().iter().all(|s| s.tag == Tag::LS));
    /// ```
    pub fn steps(&self) -> &[PlanStep] {
        &self.steps
    }

    /// The initial tag (the operation chosen at the start).
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, sketch, SketchOptions, Tag};
    /// let map = gen::torus_grid(6, 6).map;
    /// let path = sketch(&map, Vert::new(0), Vert::new(3), &SketchOptions::default()).unwrap();
    /// assert_eq!(plan(&map, &path, Tag::RC).unwrap().initial(), Tag::RC);
    /// ```
    pub fn initial(&self) -> Tag {
        self.steps[0].tag
    }

    /// The darts of the planned path: dart `i` goes from the vertex of step `i` to that of
    /// step `i + 1`, in the map the plan was made on.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, sketch, SketchOptions, Tag};
    /// let map = gen::torus_grid(6, 6).map;
    /// let path = sketch(&map, Vert::new(0), Vert::new(3), &SketchOptions::default()).unwrap();
    /// assert_eq!(plan(&map, &path, Tag::LS).unwrap().darts(), path.darts());
    /// ```
    pub fn darts(&self) -> &[Dart] {
        &self.darts
    }

    /// The tag the compass arrives with at the last vertex.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{plan, sketch, SketchOptions, Tag};
    /// let map = gen::torus_grid(6, 6).map;
    /// let path = sketch(&map, Vert::new(0), Vert::new(3), &SketchOptions::default()).unwrap();
    /// assert_eq!(plan(&map, &path, Tag::RC).unwrap().terminal(), Tag::RC);
    /// ```
    pub fn terminal(&self) -> Tag {
        self.steps[self.steps.len() - 1].tag
    }
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, s) in self.steps.iter().enumerate() {
            write!(f, "vertex {}: {}", s.vertex.index(), s.tag)?;
            match (s.turn, s.count) {
                (Some(t), Some((side, n))) => {
                    let q = if n == 1 { "quad" } else { "quads" };
                    write!(f, " ({t}, {n} {q} on the {side})")?;
                }
                _ if i == 0 => f.write_str(" (start)")?,
                _ => f.write_str(" (end)")?,
            }
            writeln!(f)?;
        }
        Ok(())
    }
}

/// Why a plan was refused: the position in the path, the vertex, and the reason.
///
/// ```
/// use zipmesh::{Vert};
/// use zipmesh::qzip::PlanError;
/// let e = PlanError::Valence { index: 0, vertex: Vert::new(7), valence: 6 };
/// assert!(e.to_string().contains("valence 6"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PlanError {
    /// The path does not fit this map (it was made for another map, or the map changed).
    StalePath {
        /// Position of the offending edge in the path.
        index: usize,
    },
    /// An interior (non-boundary) path vertex of valence 2 or less, or 6 or more: outside the
    /// cases Sec. 2.6 covers.
    Valence {
        /// Position in the path.
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// Its valence.
        valence: usize,
    },
    /// A boundary vertex inside the path where the counted side reaches the boundary, so the
    /// quad count (and the turn) is undefined.
    Boundary {
        /// Position in the path.
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// The side that would be counted.
        side: Side,
    },
    /// A face counted at a path vertex is not a quad.
    NotQuad {
        /// Position in the path.
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// The face.
        face: Face,
    },
}

impl fmt::Display for PlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::StalePath { index } => {
                write!(f, "the path's edge {index} does not belong to this map")
            }
            Self::Valence {
                index,
                vertex,
                valence,
            } => write!(
                f,
                "path vertex {} (position {index}) has valence {valence}; only valences 3 to 5 \
                 can be zipped through without preprocessing",
                vertex.index()
            ),
            Self::Boundary {
                index,
                vertex,
                side,
            } => write!(
                f,
                "path vertex {} (position {index}) is on the boundary and its {side} side, \
                 which the compass rule counts, reaches the boundary",
                vertex.index()
            ),
            Self::NotQuad {
                index,
                vertex,
                face,
            } => write!(
                f,
                "face {} at path vertex {} (position {index}) is not a quad",
                face.index(),
                vertex.index()
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for PlanError {}

/// The faces met turning from `out` to `back` (both leaving the same vertex) on `side`:
/// counter-clockwise for the left, clockwise for the right. `Err(None)` if a boundary gap is
/// crossed, `Err(Some(f))` for a face that is not a quad.
fn count_side(map: &Map, out: Dart, back: Dart, side: Side) -> Result<usize, Option<Face>> {
    let mut x = out;
    // Bounded by the dart count so a corrupt rotation cannot loop forever.
    for n in 0..map.dart_slots() {
        if x == back {
            return Ok(n);
        }
        // The face on `side` of `x` (through its dart `y`) must be a quad; the next dart
        // round the vertex comes from the same four steps round that face.
        let y = match side {
            Side::Left => x,
            Side::Right => x.twin(),
        };
        let f = map.face(y).ok_or(None)?;
        let [.., before] = crate::ops::quad::quad_of(map, y).map_err(|_| Some(f))?;
        x = match side {
            Side::Left => before.twin(),
            Side::Right => map.next(y),
        };
    }
    Err(None)
}

/// The turn at the path vertex `index` (the origin of `out`), entered along the twin of
/// `back` with the compass hand `tag`: the quads between the two edges counted on
/// [`Tag::counting_side`] (at a regular boundary vertex whose counted side reaches the
/// boundary, on the other side), with the side and the count.
pub(crate) fn turn_at(
    map: &Map,
    tag: Tag,
    back: Dart,
    out: Dart,
    index: usize,
) -> Result<(Turn, Side, usize), PlanError> {
    let vertex = map.origin(out);
    let mut side = tag.counting_side();
    let mut result = count_side(map, out, back, side);
    if result == Err(None)
        && map.is_boundary_vertex(vertex)
        && map.valence(vertex) == regular_valence(MeshKind::Quad, true)
    {
        side = match side {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        };
        result = count_side(map, out, back, side);
    }
    let n = match result {
        Ok(n) => n,
        Err(None) => {
            return Err(PlanError::Boundary {
                index,
                vertex,
                side: tag.counting_side(),
            })
        }
        Err(Some(face)) => {
            return Err(PlanError::NotQuad {
                index,
                vertex,
                face,
            })
        }
    };
    // n == 0 would mean the path comes back along the same edge: not a simple path.
    let turn = Turn::from_count(side, n).ok_or(PlanError::StalePath { index })?;
    Ok((turn, side, n))
}

/// Carries the compass along `path`, starting with `initial` at its first vertex.
///
/// Checks, for every path vertex: an interior (non-boundary) vertex must have valence 3, 4
/// or 5 (ends included). At each interior path vertex the quads between the incoming and
/// outgoing edges are counted on [`Tag::counting_side`] of the previous tag and turned into a
/// [`Turn`] by [`Turn::from_count`]. At a boundary vertex whose counted side reaches the
/// boundary, a regular boundary vertex (valence 3) is counted on the other side instead
/// (where it is regular both sides agree); an irregular one is refused with
/// [`PlanError::Boundary`].
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{plan, validate_path, SketchOptions, Tag, Turn};
/// // Grid 4 x 4, vertex (i, j) is 5 j + i: east along j = 2, then a right turn south.
/// let map = gen::grid(4, 4).map;
/// let v = |i: u32, j: u32| Vert::new(5 * j + i);
/// let path = validate_path(&map, v(1, 2), v(2, 1), &[v(1, 2), v(2, 2), v(2, 1)],
///     &SketchOptions::default()).unwrap();
/// let p = plan(&map, &path, Tag::LS).unwrap();
/// assert_eq!(p.steps()[1].turn, Some(Turn::Right));
/// assert_eq!(p.terminal(), Tag::RS);
/// ```
pub fn plan(map: &Map, path: &Path, initial: Tag) -> Result<Plan, PlanError> {
    let (verts, darts) = (path.vertices(), path.darts());
    for (i, &d) in darts.iter().enumerate() {
        if !map.is_live_dart(d) || map.origin(d) != verts[i] || map.dest(d) != verts[i + 1] {
            return Err(PlanError::StalePath { index: i });
        }
    }
    for (index, &vertex) in verts.iter().enumerate() {
        let valence = map.valence(vertex);
        if !map.is_boundary_vertex(vertex) && !(3..=5).contains(&valence) {
            return Err(PlanError::Valence {
                index,
                vertex,
                valence,
            });
        }
    }
    let mut steps = Vec::with_capacity(verts.len());
    steps.push(PlanStep {
        vertex: verts[0],
        tag: initial,
        turn: None,
        count: None,
    });
    let mut tag = initial;
    for index in 1..verts.len() - 1 {
        let vertex = verts[index];
        let (back, out) = (darts[index - 1].twin(), darts[index]);
        let (turn, side, n) = turn_at(map, tag, back, out, index)?;
        tag = tag.after(turn);
        steps.push(PlanStep {
            vertex,
            tag,
            turn: Some(turn),
            count: Some((side, n)),
        });
    }
    steps.push(PlanStep {
        vertex: verts[verts.len() - 1],
        tag,
        turn: None,
        count: None,
    });
    Ok(Plan {
        steps,
        darts: darts.to_vec(),
    })
}
