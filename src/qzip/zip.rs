//! The four stages in one call, and the four movements of a pair.

use core::fmt;

use super::compass::{plan, PlanError, Tag};
use super::execute::{execute_owned, ZipError, ZipReport};
use super::prepare::{prepare, PrepareError};
use super::sketch::{sketch, Path, SketchError, SketchOptions, SketchWorkspace};
use crate::{Map, Vert};

/// Why a Q-zip was refused, by stage; the map is unchanged in every case.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{zip, QzipError, SketchOptions, Tag};
/// let mut map = gen::torus_grid(6, 6).map;
/// // A regular torus has no singularity to move.
/// let e = zip(&mut map, Vert::new(0), Vert::new(2), Tag::LC, &SketchOptions::default());
/// assert!(matches!(e, Err(QzipError::Prepare(_))));
/// assert!(e.unwrap_err().to_string().contains("valence 4"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum QzipError {
    /// Stage 1: no path.
    Sketch(SketchError),
    /// Stage 2: the compass cannot be carried along the path.
    Plan(PlanError),
    /// Stage 3: the ends cannot be adjusted.
    Prepare(PrepareError),
    /// Stage 4: an operation is not realizable.
    Execute(ZipError),
}

impl fmt::Display for QzipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Sketch(e) => write!(f, "sketching: {e}"),
            Self::Plan(e) => write!(f, "planning: {e}"),
            Self::Prepare(e) => write!(f, "preparation: {e}"),
            Self::Execute(e) => write!(f, "execution: {e}"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for QzipError {}

/// Runs stages 2 to 4 along a given path with the initial operation `initial`.
///
/// All or nothing: on an error the map is unchanged.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, zip_along, SketchOptions, Tag};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let path = sketch(&map, v3, v5, &SketchOptions::default()).unwrap();
/// let r = zip_along(&mut map, &path, Tag::RS).unwrap();
/// assert_eq!(map.valence(r.moved_to()), 5);
/// ```
pub fn zip_along(map: &mut Map, path: &Path, initial: Tag) -> Result<ZipReport, QzipError> {
    let p = plan(map, path, initial).map_err(QzipError::Plan)?;
    let s = prepare(map, &p).map_err(QzipError::Prepare)?;
    execute_owned(map, s).map_err(QzipError::Execute)
}

/// Runs the four stages: the path from `from` to `to` sketched with `opts`, then
/// [`zip_along`] it with the initial operation `initial`.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{zip, SketchOptions, Tag};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let r = zip(&mut map, v3, v5, Tag::LC, &SketchOptions::default()).unwrap();
/// assert_eq!(map.valence(r.moved_from()), 3);
/// ```
pub fn zip(
    map: &mut Map,
    from: Vert,
    to: Vert,
    initial: Tag,
    opts: &SketchOptions,
) -> Result<ZipReport, QzipError> {
    let path = sketch(map, from, to, opts).map_err(QzipError::Sketch)?;
    zip_along(map, &path, initial)
}

/// [`zip`] with the sketch done in a reusable [`SketchWorkspace`] (the same path, without
/// per-call allocation proportional to the explored region): for many Q-zips on one large
/// map. With a [`super::Guide`] in `opts` the sketch explores about O(path length) vertices.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{zip, zip_with, SketchOptions, SketchWorkspace, Tag};
/// let mut ws = SketchWorkspace::new();
/// let mut a = gen::subdivided_icosahedron(2).map;
/// let mut b = a.clone();
/// let (v5, v3) = (Vert::new(0), Vert::new(42));
/// let o = SketchOptions::default();
/// let ra = zip_with(&mut ws, &mut a, v3, v5, Tag::LC, &o).unwrap();
/// let rb = zip(&mut b, v3, v5, Tag::LC, &o).unwrap();
/// assert_eq!((a, ra), (b, rb));
/// ```
pub fn zip_with(
    ws: &mut SketchWorkspace,
    map: &mut Map,
    from: Vert,
    to: Vert,
    initial: Tag,
    opts: &SketchOptions<'_>,
) -> Result<ZipReport, QzipError> {
    let path = ws.sketch(map, from, to, opts).map_err(QzipError::Sketch)?;
    zip_along(map, &path, initial)
}

/// One of the four movements of a pair: the initial operation and its outcome (the edited
/// copy of the map and the report, or the refusal).
///
/// See [`moves`] for an example.
#[derive(Clone, Debug)]
pub struct Move {
    /// The initial operation.
    pub tag: Tag,
    /// The edited copy and the report, or why this movement is not realizable.
    pub outcome: Result<(Map, ZipReport), QzipError>,
}

/// The four movements of the pair at the ends of `path`: each initial operation in compass
/// order (LS, RC, LC, RS), run on a copy of the map.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{moves, sketch, SketchOptions};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let path = sketch(&map, v3, v5, &SketchOptions::default()).unwrap();
/// let all = moves(&map, &path);
/// assert_eq!(all.len(), 4);
/// assert!(all.iter().any(|m| m.outcome.is_ok()));
/// ```
pub fn moves(map: &Map, path: &Path) -> [Move; 4] {
    Tag::CCW.map(|tag| {
        let mut copy = map.clone();
        let outcome = zip_along(&mut copy, path, tag).map(|r| (copy, r));
        Move { tag, outcome }
    })
}
