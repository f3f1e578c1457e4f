//! Stage 4 of Q-zip (partial): executing a plan made only of collapses.
//!
//! The simplest case of the paper's Sec. 2.6: a straight collapse chain that starts at a v5
//! and ends at a v3 needs no end-point adjustment. [`execute_collapse_chain`] applies one quad
//! collapse per path edge `P -> N`, on the side the tag names: for LC the quad on the right of
//! the edge, for RC the quad on the left; in both cases `N` (which keeps its handle) is merged
//! with that quad's corner next to `P`. The v5 moves to the first merged vertex and the v3 to
//! the last quad's corner next to the path's end (see `docs/qzip.md`).
//!
//! ```
//! use zipmesh::{gen, ops::quad, Vert};
//! use zipmesh::qzip::{execute_collapse_chain, plan, validate_path, SketchOptions, Tag};
//! // Split a regular vertex along two opposite edges: two v3 copies, two v5 ends.
//! let mut map = gen::torus_grid(8, 8).map;
//! let s1 = map.vertex_dart(Vert::new(27));
//! let s2 = map.rotate_cw(map.rotate_cw(s1));
//! quad::vertex_split(&mut map, s1, s2).unwrap();
//! let before = map.clone();
//! let mut moved = 0;
//! for v5 in before.vertices().filter(|&v| before.valence(v) == 5) {
//!     for v3 in before.vertex_darts(v5).map(|d| before.dest(d)) {
//!         if before.valence(v3) != 3 {
//!             continue;
//!         }
//!         let path = validate_path(&before, v5, v3, &[v5, v3], &SketchOptions::default()).unwrap();
//!         for tag in [Tag::LC, Tag::RC] {
//!             // Either the pair moves by one edge, or a third singularity on the strip makes
//!             // the executor refuse; both leave a map that undo or refusal restores exactly.
//!             if let Ok(r) = execute_collapse_chain(&mut map, &plan(&before, &path, tag).unwrap()) {
//!                 assert_eq!((map.valence(r.moved_from()), map.valence(r.moved_to())), (5, 3));
//!                 r.undo(&mut map).unwrap();
//!                 moved += 1;
//!             }
//!             assert_eq!(map, before);
//!         }
//!     }
//! }
//! assert!(moved > 0);
//! ```

use alloc::vec::Vec;
use core::fmt;

use super::compass::{Plan, Tag};
use crate::ops::quad::{quad_collapse, QuadCollapse};
use crate::ops::Refusal;
use crate::{Dart, Map, Vert};

/// What an executed collapse chain did, with the records for an exact undo.
///
/// ```
/// use zipmesh::{gen, ops::quad, Vert};
/// use zipmesh::qzip::{execute_collapse_chain, plan, validate_path, SketchOptions, Tag};
/// let mut map = gen::torus_grid(8, 8).map;
/// let s1 = map.vertex_dart(Vert::new(27));
/// let s2 = map.rotate_cw(map.rotate_cw(s1));
/// quad::vertex_split(&mut map, s1, s2).unwrap();
/// let mut reports = Vec::new();
/// for v5 in map.vertices().filter(|&v| map.valence(v) == 5) {
///     for v3 in map.vertex_darts(v5).map(|d| map.dest(d)).filter(|&v| map.valence(v) == 3) {
///         let path = validate_path(&map, v5, v3, &[v5, v3], &SketchOptions::default()).unwrap();
///         for tag in [Tag::LC, Tag::RC] {
///             let mut copy = map.clone();
///             if let Ok(r) = execute_collapse_chain(&mut copy, &plan(&map, &path, tag).unwrap()) {
///                 assert_eq!(r.tag(), tag);
///                 reports.push(r);
///             }
///         }
///     }
/// }
/// assert!(!reports.is_empty());
/// for r in &reports {
///     assert_eq!(r.records().len(), r.collapses());
///     assert_eq!(r.collapses(), 1);
/// }
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ZipReport {
    tag: Tag,
    from: Vert,
    to: Vert,
    records: Vec<QuadCollapse>,
}

impl ZipReport {
    /// The number of quad collapses applied (the path's edge count).
    ///
    /// See [`ZipReport`] for an example.
    pub fn collapses(&self) -> usize {
        self.records.len()
    }

    /// The collapse tag the chain ran with (LC or RC).
    ///
    /// See [`ZipReport`] for an example.
    pub fn tag(&self) -> Tag {
        self.tag
    }

    /// Where the initial singularity (the v5) went: the first merged vertex, which keeps the
    /// handle of the path's second vertex.
    ///
    /// See the example on [`execute_collapse_chain`].
    pub fn moved_from(&self) -> Vert {
        self.from
    }

    /// Where the terminal singularity (the v3) went: the last collapsed quad's corner next to
    /// the path's end.
    ///
    /// See the example on [`execute_collapse_chain`].
    pub fn moved_to(&self) -> Vert {
        self.to
    }

    /// The collapse records, in the order applied.
    ///
    /// See [`ZipReport`] for an example.
    pub fn records(&self) -> &[QuadCollapse] {
        &self.records
    }

    /// Undoes the whole chain (records in reverse order): with the map as the chain left it,
    /// the result is `==` the map before. On a refusal the records already undone stay undone
    /// and the error is returned.
    ///
    /// See the example on [`execute_collapse_chain`].
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        for r in self.records.iter().rev() {
            r.undo(map)?;
        }
        Ok(())
    }
}

/// Why [`execute_collapse_chain`] refused; the map is unchanged in every case.
///
/// ```
/// use zipmesh::{qzip::{Tag, ZipError}, Vert};
/// let e = ZipError::NotCollapse { index: 0, vertex: Vert::new(3), tag: Tag::LS };
/// assert!(e.to_string().contains("LS"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ZipError {
    /// A plan step's tag is a split (or differs from the first tag): this executor only runs
    /// chains whose every tag is the same collapse, i.e. straight collapse paths.
    NotCollapse {
        /// Position in the plan.
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// Its tag.
        tag: Tag,
    },
    /// An end is not the one this executor handles without end-point adjustment: the start
    /// must be an interior v5 and the end an interior v3.
    WrongEnd {
        /// Position in the plan (0 or the last).
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// Its valence.
        valence: usize,
        /// Whether it is on the boundary.
        boundary: bool,
    },
    /// A vertex the chain's analysis needs regular is not: an interior path vertex, or a
    /// corner of a quad to be collapsed off the path. The chain would then merge or touch a
    /// third singularity and the pair would not simply move (Sec. 2.6 assumes them apart).
    Irregular {
        /// Position in the plan of the edge whose quad (or whose first vertex) it is.
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// Its valence.
        valence: usize,
        /// Whether it is on the boundary.
        boundary: bool,
    },
    /// The plan does not fit the map: a vertex is dead, or the edge from plan vertex `index`
    /// to the next is missing or not unique (when the chain reaches it).
    StalePlan {
        /// Position in the plan.
        index: usize,
    },
    /// A quad collapse was refused by the operator.
    Refused {
        /// Position in the plan of the edge's first vertex.
        index: usize,
        /// That vertex.
        vertex: Vert,
        /// The operator's reason.
        refusal: Refusal,
    },
}

impl fmt::Display for ZipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotCollapse { index, vertex, tag } => write!(
                f,
                "plan vertex {} (position {index}) has tag {tag}; only chains of one collapse \
                 tag (straight LC or RC paths) can be executed so far",
                vertex.index()
            ),
            Self::WrongEnd {
                index,
                vertex,
                valence,
                boundary,
            } => write!(
                f,
                "plan end {} (position {index}) has valence {valence}{}; a collapse chain \
                 without end-point adjustment needs an interior v5 start and an interior v3 end",
                vertex.index(),
                if *boundary { " on the boundary" } else { "" }
            ),
            Self::Irregular {
                index,
                vertex,
                valence,
                boundary,
            } => write!(
                f,
                "vertex {} (at the plan's edge {index}) has valence {valence}{}; a collapse \
                 chain needs a regular interior path and regular strip corners",
                vertex.index(),
                if *boundary { " on the boundary" } else { "" }
            ),
            Self::StalePlan { index } => write!(
                f,
                "the plan's edge {index} is missing or not unique in this map"
            ),
            Self::Refused {
                index,
                vertex,
                refusal,
            } => write!(
                f,
                "the collapse at plan vertex {} (position {index}) was refused: {refusal}",
                vertex.index()
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ZipError {}

/// The unique dart from `p` to `n`; `None` if there is none or more than one.
fn dart_between(map: &Map, p: Vert, n: Vert) -> Option<Dart> {
    if !map.is_live_vertex(p) || !map.is_live_vertex(n) {
        return None;
    }
    let mut found = None;
    for d in map.vertex_darts(p) {
        if map.dest(d) == n {
            if found.is_some() {
                return None;
            }
            found = Some(d);
        }
    }
    found
}

/// The dart of the quad collapsed at edge `e` that leaves `N = dest(e)` (collapsing at it
/// merges `N` into the corner next to `P`), and that quad's corner next to `N`.
fn strip_quad(map: &Map, e: Dart, tag: Tag) -> (Dart, Vert) {
    if tag == Tag::LC {
        let d = e.twin();
        (d, map.origin(map.prev(d)))
    } else {
        let d = map.next(e);
        (d, map.dest(d))
    }
}

/// Before anything changes: every interior path vertex and both off-path corners of every
/// strip quad are regular interior vertices (the chain's valence count assumes it).
fn check_strip(map: &Map, plan: &Plan, tag: Tag) -> Result<(), ZipError> {
    let steps = plan.steps();
    let regular = |index: usize, vertex: Vert| {
        let valence = map.valence(vertex);
        let boundary = map.is_boundary_vertex(vertex);
        if valence == 4 && !boundary {
            Ok(())
        } else {
            Err(ZipError::Irregular {
                index,
                vertex,
                valence,
                boundary,
            })
        }
    };
    for index in 0..steps.len() - 1 {
        let (p, n) = (steps[index].vertex, steps[index + 1].vertex);
        if index > 0 {
            regular(index, p)?;
        }
        let e = dart_between(map, p, n).ok_or(ZipError::StalePlan { index })?;
        let (d, far_n) = strip_quad(map, e, tag);
        // A missing or non-quad face is left to the operator, which refuses it by name.
        if map.face(d).is_some_and(|f| map.degree(f) == 4) {
            let far_p = map.origin(map.next(map.next(d)));
            regular(index, far_p)?;
            regular(index, far_n)?;
        }
    }
    Ok(())
}

fn undo_all(map: &mut Map, records: &[QuadCollapse]) {
    // The records were made in order on this map, so undoing in reverse cannot be stale;
    // should it be, nothing better than stopping is possible, and the error is reported anyway.
    for r in records.iter().rev() {
        if r.undo(map).is_err() {
            break;
        }
    }
}

/// Executes a plan whose every tag is the same collapse (LC or RC) from an interior v5 to an
/// interior v3: the case of Sec. 2.6 that needs no end-point adjustment.
///
/// For each path edge `P -> N` (in order) it collapses the quad on the right of the edge
/// (LC) or on its left (RC), merging `N` (which keeps its handle) with the quad's corner next
/// to `P`. Along a straight chain the v5 start loses one edge, the first merged vertex is a
/// transient v6 that the next collapse brings down to 5, every later merged vertex ends
/// regular, and the v3 end is absorbed while the last quad's far corner becomes the v3: both
/// singularities move by one edge to the chain's side. V drops by the path length, the
/// irregular valences are unchanged.
///
/// Before anything changes it checks that every interior path vertex and both off-path
/// corners of every quad to be collapsed are regular interior vertices
/// ([`ZipError::Irregular`] otherwise): the valence count above assumes it, and a third
/// singularity on the strip would be merged or moved too (the paper's Sec. 2.6 treats the
/// pair as isolated). Paths through or along other singularities are later work.
///
/// All or nothing: on any refusal (see [`ZipError`]) every collapse already applied is undone
/// and the map is left `==` to what it was.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{execute_collapse_chain, plan, sketch, SketchOptions, Tag, ZipError};
/// // On a regular torus there is no v5 to start from: refused, map unchanged.
/// let mut map = gen::torus_grid(6, 6).map;
/// let before = map.clone();
/// let path = sketch(&map, Vert::new(0), Vert::new(2), &SketchOptions::default()).unwrap();
/// let p = plan(&map, &path, Tag::LC).unwrap();
/// assert!(matches!(execute_collapse_chain(&mut map, &p), Err(ZipError::WrongEnd { index: 0, .. })));
/// // A split tag is refused too.
/// let p = plan(&map, &path, Tag::LS).unwrap();
/// assert!(matches!(execute_collapse_chain(&mut map, &p), Err(ZipError::NotCollapse { index: 0, .. })));
/// assert_eq!(map, before);
/// ```
pub fn execute_collapse_chain(map: &mut Map, plan: &Plan) -> Result<ZipReport, ZipError> {
    let steps = plan.steps();
    if steps.len() < 2 {
        return Err(ZipError::StalePlan { index: 0 });
    }
    let tag = steps[0].tag;
    for (index, s) in steps.iter().enumerate() {
        if s.tag.is_split() || s.tag != tag {
            return Err(ZipError::NotCollapse {
                index,
                vertex: s.vertex,
                tag: s.tag,
            });
        }
        if !map.is_live_vertex(s.vertex) {
            return Err(ZipError::StalePlan { index });
        }
    }
    let last = steps.len() - 1;
    for (index, want) in [(0, 5), (last, 3)] {
        let vertex = steps[index].vertex;
        let valence = map.valence(vertex);
        let boundary = map.is_boundary_vertex(vertex);
        if boundary || valence != want {
            return Err(ZipError::WrongEnd {
                index,
                vertex,
                valence,
                boundary,
            });
        }
    }
    check_strip(map, plan, tag)?;
    let mut records: Vec<QuadCollapse> = Vec::with_capacity(last);
    let mut to = steps[last].vertex;
    for index in 0..last {
        let (p, n) = (steps[index].vertex, steps[index + 1].vertex);
        let Some(e) = dart_between(map, p, n) else {
            undo_all(map, &records);
            return Err(ZipError::StalePlan { index });
        };
        // The dart of the collapsed quad leaving N, and that quad's corner next to N.
        let (d, far) = strip_quad(map, e, tag);
        match quad_collapse(map, d) {
            Ok(r) => records.push(r),
            Err(refusal) => {
                undo_all(map, &records);
                return Err(ZipError::Refused {
                    index,
                    vertex: p,
                    refusal,
                });
            }
        }
        to = far;
    }
    Ok(ZipReport {
        tag,
        from: steps[1].vertex,
        to,
        records,
    })
}
