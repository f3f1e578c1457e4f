//! The four stages in one call ([`Qzip`], the entry point), and the four movements of a pair.

use core::fmt;

use super::compass::{plan, PlanError, Tag};
use super::execute::{execute_owned, Guard, ZipError, ZipReport};
use super::placement::place_created;
use super::prepare::{prepare, PrepareError};
use super::sketch::{Path, SketchError, SketchOptions, SketchWorkspace};
use crate::mesh::{EditTarget, Edited, Journal, VertexAttributes};
use crate::{Map, Vert};

/// Why a Q-zip was refused, by stage; the map is unchanged in every case.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{Qzip, QzipError, Tag};
/// let mut map = gen::torus_grid(6, 6).map;
/// // A regular torus has no singularity to move.
/// let e = Qzip::new().zip(&mut map, Vert::new(0), Vert::new(2), Tag::LC);
/// assert!(matches!(e, Err(QzipError::Prepare(_))));
/// assert!(e.unwrap_err().to_string().contains("valence 4"));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
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
impl std::error::Error for QzipError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(match self {
            Self::Sketch(e) => e,
            Self::Plan(e) => e,
            Self::Prepare(e) => e,
            Self::Execute(e) => e,
        })
    }
}

/// Stages 2 to 4 along `path`: all or nothing.
pub(crate) fn zip_along(map: &mut Map, path: &Path, initial: Tag) -> Result<ZipReport, QzipError> {
    zip_along_guarded(map, path, initial, Guard::GridPreserving)
}

/// [`zip_along`] with the given guard.
fn zip_along_guarded(
    map: &mut Map,
    path: &Path,
    initial: Tag,
    guard: Guard,
) -> Result<ZipReport, QzipError> {
    let p = plan(map, path, initial).map_err(QzipError::Plan)?;
    let s = prepare(map, &p).map_err(QzipError::Prepare)?;
    execute_owned(map, s, guard).map_err(QzipError::Execute)
}

/// The Q-zip entry point: the sketch options and a reusable [`SketchWorkspace`], and the four
/// stages run at once on a [`Map`] or, keeping positions, on a [`crate::Mesh`].
///
/// Every Q-zip is all or nothing: on an error the map (and the positions) are unchanged. One
/// value serves any number of Q-zips on any maps; its workspace makes repeated sketches on a
/// large map cost what they explore (no O(V) set-up per call), with the same path as
/// [`super::sketch()`]. The staged API ([`super::sketch()`], [`super::plan`],
/// [`super::prepare()`], [`super::execute()`]) gives each stage's result to inspect.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{Qzip, SketchOptions, Tag};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let mut q = Qzip::with_options(SketchOptions::default().avoid_boundary(true));
/// let r = q.zip(&mut map, v3, v5, Tag::LC).unwrap();
/// assert_eq!(map.valence(r.moved_from()), 3);
/// r.undo(&mut map).unwrap();
/// ```
#[derive(Debug, Default)]
pub struct Qzip<'a> {
    options: SketchOptions<'a>,
    workspace: SketchWorkspace,
    allow_cancellation: bool,
}

impl Qzip<'static> {
    /// An entry point with the default options (shortest path, nothing forbidden).
    ///
    /// ```
    /// use zipmesh::qzip::{Qzip, SketchOptions};
    /// assert_eq!(Qzip::new().options(), &SketchOptions::default());
    /// ```
    pub fn new() -> Self {
        Self::default()
    }
}

impl<'a> Qzip<'a> {
    /// An entry point that sketches with `options`.
    ///
    /// ```
    /// use zipmesh::Edge;
    /// use zipmesh::qzip::{Qzip, SketchOptions};
    /// let q = Qzip::with_options(SketchOptions::default().forbid_edges([Edge::new(3)]));
    /// assert_eq!(q.options().forbidden_edges, vec![Edge::new(3)]);
    /// ```
    pub fn with_options(options: SketchOptions<'a>) -> Self {
        Qzip {
            options,
            workspace: SketchWorkspace::new(),
            allow_cancellation: false,
        }
    }

    /// Lets the edits of this entry point cancel singularities: the guard that refuses an
    /// edit changing the irregular valences of the vertices it touched
    /// ([`super::ZipError::NotGridPreserving`]) is off. A moved singularity may then meet a
    /// complementary one and both vanish (what the batch optimizer, [`crate::optimize`], needs
    /// to reduce their number), or a crowded cluster may gain some. The map stays valid and
    /// the undo exact; when a singularity cancelled, [`ZipReport::moved_from`] and
    /// [`ZipReport::moved_to`] name a vertex the edit touched.
    ///
    /// ```
    /// use zipmesh::qzip::Qzip;
    /// let q = Qzip::new().allow_cancellation(true);
    /// assert!(q.allows_cancellation());
    /// ```
    pub fn allow_cancellation(mut self, allow: bool) -> Self {
        self.allow_cancellation = allow;
        self
    }

    /// Whether [`Qzip::allow_cancellation`] is on.
    ///
    /// See [`Qzip::allow_cancellation`] for an example.
    pub fn allows_cancellation(&self) -> bool {
        self.allow_cancellation
    }

    fn guard(&self) -> Guard {
        if self.allow_cancellation {
            Guard::AllowCancellation
        } else {
            Guard::GridPreserving
        }
    }

    /// The sketch options.
    ///
    /// See [`Qzip::with_options`] for an example.
    pub fn options(&self) -> &SketchOptions<'a> {
        &self.options
    }

    /// The sketch options, to change between Q-zips.
    ///
    /// ```
    /// use zipmesh::qzip::Qzip;
    /// let mut q = Qzip::new();
    /// q.options_mut().avoid_boundary = true;
    /// assert!(q.options().avoid_boundary);
    /// ```
    pub fn options_mut(&mut self) -> &mut SketchOptions<'a> {
        &mut self.options
    }

    /// The workspace of the sketches (for [`SketchWorkspace::explored`]).
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{Qzip, Tag};
    /// let mut map = gen::subdivided_icosahedron(2).map;
    /// let mut q = Qzip::new();
    /// q.zip(&mut map, Vert::new(42), Vert::new(0), Tag::LS).unwrap();
    /// assert!(q.workspace().explored() > 0);
    /// ```
    pub fn workspace(&self) -> &SketchWorkspace {
        &self.workspace
    }

    /// Stage 1 alone: the path from `from` to `to` under the options, sketched in the
    /// workspace (the path [`super::sketch()`] gives).
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::Qzip;
    /// let map = gen::grid(5, 5).map;
    /// assert_eq!(Qzip::new().sketch(&map, Vert::new(7), Vert::new(10)).unwrap().len(), 3);
    /// ```
    pub fn sketch(&mut self, map: &Map, from: Vert, to: Vert) -> Result<Path, SketchError> {
        self.workspace.sketch(map, from, to, &self.options)
    }

    /// The four stages: the path from `from` to `to` sketched under the options, then
    /// [`Qzip::zip_along`] it with the initial operation `initial`, on a bare map, a
    /// [`crate::Mesh`] or a map with any per-vertex values ([`EditTarget`]). A [`super::Guide`] in
    /// the options cannot borrow the positions being edited: guide with a copy of the
    /// points, or zip the bare map.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{Qzip, Tag};
    /// let mut map = gen::subdivided_icosahedron(2).map;
    /// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
    /// let r = Qzip::new().zip(&mut map, v3, v5, Tag::LC).unwrap();
    /// assert_eq!(map.valence(r.moved_from()), 3);
    /// // On a mesh, positions are kept in step and undo restores both.
    /// let mut mesh = gen::subdivided_icosahedron(2);
    /// let before = mesh.clone();
    /// let z = Qzip::new().zip(&mut mesh, Vert::new(42), Vert::new(0), Tag::LS).unwrap();
    /// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
    /// z.undo(&mut mesh).unwrap();
    /// assert_eq!((mesh.map, mesh.positions), (before.map, before.positions));
    /// ```
    pub fn zip<T: EditTarget>(
        &mut self,
        target: &mut T,
        from: Vert,
        to: Vert,
        initial: Tag,
    ) -> Result<Edited<ZipReport, T::Values>, QzipError> {
        let (map, values) = target.parts();
        let path = self.sketch(map, from, to).map_err(QzipError::Sketch)?;
        self.along(map, values, &path, initial)
    }

    /// Stages 2 to 4 along a given path (from [`super::sketch()`], [`super::validate_path`] or
    /// [`Qzip::sketch`]) with the initial operation `initial`; the options play no part.
    ///
    /// Per-vertex values are kept in step (positions, marks, or a pair of layers, see
    /// [`EditTarget`]): each vertex a split creates first takes the value of the vertex it
    /// was split from (read in the order the splits ran, so at the time of its split), then
    /// the mean of its neighbours' values on the edited map, in the order created. The first
    /// pass is why no neighbour read holds the default value or the value of a vertex a
    /// collapse removed (a mean of those puts vertices far off the surface). Merged vertices
    /// keep the value of the vertex that keeps the handle; every other vertex keeps its
    /// value. The undo restores map and values `==`. [`crate::geometry::relax_footprint`]
    /// then puts the edit on the input surface, as `zipmesh zip` does.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, Qzip, SketchOptions, Tag};
    /// let mut map = gen::subdivided_icosahedron(2).map;
    /// let mut q = Qzip::new();
    /// let path = q.sketch(&map, Vert::new(42), Vert::new(0)).unwrap(); // v3 to v5
    /// let r = q.zip_along(&mut map, &path, Tag::RS).unwrap();
    /// assert_eq!(map.valence(r.moved_to()), 5);
    /// // A layer of marks: a mark spreads to the vertices split from it.
    /// let mut mesh = gen::subdivided_icosahedron(2);
    /// let mut marks = vec![false; mesh.map.vertex_slots()];
    /// marks[42] = true;
    /// let before = (mesh.map.clone(), marks.clone());
    /// let path = sketch(&mesh.map, Vert::new(42), Vert::new(0), &SketchOptions::default()).unwrap();
    /// let z = Qzip::new().zip_along(&mut (&mut mesh.map, &mut marks), &path, Tag::LS).unwrap();
    /// assert_eq!(marks.len(), mesh.map.vertex_slots());
    /// z.undo(&mut (&mut mesh.map, &mut marks)).unwrap();
    /// assert_eq!((mesh.map, marks), before);
    /// ```
    pub fn zip_along<T: EditTarget>(
        &self,
        target: &mut T,
        path: &Path,
        initial: Tag,
    ) -> Result<Edited<ZipReport, T::Values>, QzipError> {
        let (map, values) = target.parts();
        self.along(map, values, path, initial)
    }

    /// [`Qzip::zip_along`] on the parts of its target.
    fn along<A: VertexAttributes>(
        &self,
        map: &mut Map,
        attrs: &mut A,
        path: &Path,
        initial: Tag,
    ) -> Result<Edited<ZipReport, A>, QzipError> {
        let mut journal = Journal::start(attrs);
        let report = zip_along_guarded(map, path, initial, self.guard())?;
        place_created(map, attrs, &mut journal, report.records());
        Ok(Edited::new(report, journal))
    }
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
