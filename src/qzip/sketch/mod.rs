//! Stage 1 of Q-zip, sketching: a simple edge path between two vertices.
//!
//! [`sketch`] finds a shortest path (breadth-first search on unit weights, or Dijkstra on
//! caller-given per-edge weights) that avoids forbidden edges and the edges of forbidden faces,
//! and, when asked, prefers paths whose interior vertices are not on the boundary.
//! [`validate_path`] accepts a caller-given vertex list under the same rules or refuses it with
//! a [`SketchError`] naming the defect.
//!
//! **Speed.** On unit weights the search is bidirectional (two breadth-first searches that
//! meet in the middle), or, with a [`Guide`] (a point per vertex and a bound on the edge
//! length), an A* search that explores about the path's length on a regular grid. A
//! [`SketchWorkspace`] keeps epoch-stamped per-vertex arrays between calls, so repeated
//! sketches on a large map neither allocate nor clear O(V) memory; [`sketch`] alone uses hash
//! maps sized by what it explores.
//!
//! **Tie-breaking.** Every search is deterministic and gives the same path for the same map
//! and options, with or without a workspace or a guide (a correct one). The path is the one a
//! one-sided breadth-first search from `from` would give: the outgoing darts of a vertex are
//! expanded in increasing dart index, the queue is first-in first-out, and a vertex keeps the
//! first predecessor that reached it. That path is the least shortest path in the order of
//! dart sequences (compared dart index by dart index from `from`), so the bidirectional and
//! A* searches mark the vertices of the shortest paths and walk from `from` taking the
//! smallest dart that stays on one. Dijkstra settles the vertex of smallest (distance,
//! vertex index) first, and a vertex keeps the first predecessor that reached it at its
//! final distance.
//!
//! ```
//! use zipmesh::{gen, Vert};
//! use zipmesh::qzip::{sketch, SketchOptions};
//! // 5 x 5 grid: vertex (i, j) is 6 j + i.
//! let map = gen::grid(5, 5).map;
//! let path = sketch(&map, Vert::new(7), Vert::new(10), &SketchOptions::default()).unwrap();
//! assert_eq!(path.vertices().first(), Some(&Vert::new(7)));
//! assert_eq!(path.vertices().last(), Some(&Vert::new(10)));
//! assert_eq!(path.len(), 3);
//! ```

mod heap;
mod search;
mod store;
mod validate;

pub use validate::validate_path;

use alloc::vec::Vec;
use core::fmt;

use glam::DVec3;
use hashbrown::HashMap;

use self::search::{search, Ctx};
use self::store::{ArrayStore, Buffers, HashStore, Slot, Store};
use crate::{Dart, Edge, Face, Map, Mesh, Vert};

/// Options of [`sketch`] and [`validate_path`].
///
/// Edges are [`Edge`] handles (`dart.edge()`); per-edge data is indexed by [`Edge::index`].
/// Start from [`SketchOptions::default`] (shortest path, nothing
/// forbidden) and chain the setters:
///
/// ```
/// use zipmesh::{Edge, Face};
/// use zipmesh::qzip::SketchOptions;
/// let opts = SketchOptions::default()
///     .avoid_boundary(true)
///     .forbid_edges([Edge::new(3), Edge::new(4)])
///     .forbid_faces([Face::new(0)]);
/// assert!(opts.avoid_boundary);
/// assert_eq!(opts.forbidden_edges, vec![Edge::new(3), Edge::new(4)]);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct SketchOptions<'a> {
    /// Prefer paths whose interior vertices are not on the boundary; when no such path exists,
    /// fall back to any path. Ignored by [`validate_path`].
    pub avoid_boundary: bool,
    /// Edges that no path may use (sharp features).
    pub forbidden_edges: Vec<Edge>,
    /// Faces whose edges no path may use (protected regions).
    pub forbidden_faces: Vec<Face>,
    /// Per-edge weights indexed by [`Edge::index`] (length at least `map.edge_slots()`), each
    /// finite and non-negative; `None` means unit weights and breadth-first search. Path
    /// lengths whose sum overflows to infinity count as unreachable.
    pub weights: Option<Vec<f64>>,
    /// Points that direct a unit-weight search towards `to` (A*); the path is the same, the
    /// work smaller. See [`Guide`], also for what a wrong bound does. Ignored with `weights`
    /// and by [`validate_path`].
    pub guide: Option<Guide<'a>>,
}

impl<'a> SketchOptions<'a> {
    /// Sets [`SketchOptions::avoid_boundary`].
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// // 4 x 1 grid: every vertex is on the boundary, so the fallback runs.
    /// let map = gen::grid(4, 1).map;
    /// let opts = SketchOptions::default().avoid_boundary(true);
    /// assert_eq!(sketch(&map, Vert::new(0), Vert::new(4), &opts).unwrap().len(), 4);
    /// ```
    pub fn avoid_boundary(mut self, avoid: bool) -> Self {
        self.avoid_boundary = avoid;
        self
    }

    /// Adds `edges` to [`SketchOptions::forbidden_edges`].
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(3, 3).map;
    /// let (a, b) = (Vert::new(0), Vert::new(1));
    /// let direct = sketch(&map, a, b, &SketchOptions::default()).unwrap();
    /// let opts = SketchOptions::default().forbid_edges([direct.darts()[0].edge()]);
    /// assert_eq!(sketch(&map, a, b, &opts).unwrap().len(), 3);
    /// ```
    pub fn forbid_edges(mut self, edges: impl IntoIterator<Item = Edge>) -> Self {
        self.forbidden_edges.extend(edges);
        self
    }

    /// Adds `faces` to [`SketchOptions::forbidden_faces`].
    ///
    /// ```
    /// use zipmesh::{gen, Face, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(3, 3).map;
    /// let opts = SketchOptions::default().forbid_faces([Face::new(0)]);
    /// // Both edges at corner 0 lie on face 0: no path leaves it.
    /// assert!(sketch(&map, Vert::new(0), Vert::new(5), &opts).is_err());
    /// ```
    pub fn forbid_faces(mut self, faces: impl IntoIterator<Item = Face>) -> Self {
        self.forbidden_faces.extend(faces);
        self
    }

    /// Sets [`SketchOptions::weights`]: per-edge weights, Dijkstra instead of breadth-first
    /// search.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(3, 3).map;
    /// let opts = SketchOptions::default().weights(vec![2.0; map.edge_slots()]);
    /// assert_eq!(sketch(&map, Vert::new(0), Vert::new(3), &opts).unwrap().len(), 3);
    /// ```
    pub fn weights(mut self, weights: Vec<f64>) -> Self {
        self.weights = Some(weights);
        self
    }

    /// Sets [`SketchOptions::guide`]: an A* search towards the end, the same path.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, Guide, SketchOptions};
    /// let mesh = gen::grid(10, 10);
    /// let guided = SketchOptions::default().guide(Guide::from_mesh(&mesh));
    /// let (a, b) = (Vert::new(0), Vert::new(120));
    /// assert_eq!(
    ///     sketch(&mesh.map, a, b, &guided),
    ///     sketch(&mesh.map, a, b, &SketchOptions::default())
    /// );
    /// ```
    pub fn guide(mut self, guide: Guide<'a>) -> Self {
        self.guide = Some(guide);
        self
    }
}

/// A simple edge path: its vertices `v0 .. vn` and the darts `v(i) -> v(i+1)`.
///
/// Built only by [`sketch`] and [`validate_path`], so it is always simple, has at least one
/// edge and `darts()[i]` goes from `vertices()[i]` to `vertices()[i + 1]` in the map it came
/// from.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{validate_path, SketchOptions};
/// let map = gen::grid(3, 3).map;
/// let path = validate_path(&map, Vert::new(0), Vert::new(5), &[Vert::new(0), Vert::new(1), Vert::new(5)], &SketchOptions::default()).unwrap();
/// assert_eq!(path.len(), 2);
/// assert_eq!(map.origin(path.darts()[1]), Vert::new(1));
/// assert_eq!(path.to_string(), "0 -> 1 -> 5");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Path {
    vertices: Vec<Vert>,
    darts: Vec<Dart>,
}

impl Path {
    /// The path's vertices, from the start to the end.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(2, 1).map;
    /// let p = sketch(&map, Vert::new(0), Vert::new(2), &SketchOptions::default()).unwrap();
    /// assert_eq!(p.vertices(), &[Vert::new(0), Vert::new(1), Vert::new(2)]);
    /// ```
    pub fn vertices(&self) -> &[Vert] {
        &self.vertices
    }

    /// The path's darts; dart `i` goes from vertex `i` to vertex `i + 1`.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(2, 1).map;
    /// let p = sketch(&map, Vert::new(0), Vert::new(2), &SketchOptions::default()).unwrap();
    /// assert_eq!(map.dest(p.darts()[1]), Vert::new(2));
    /// ```
    pub fn darts(&self) -> &[Dart] {
        &self.darts
    }

    /// The number of edges.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(2, 1).map;
    /// assert_eq!(sketch(&map, Vert::new(0), Vert::new(1), &SketchOptions::default()).unwrap().len(), 1);
    /// ```
    #[allow(clippy::len_without_is_empty)] // a path always has at least one edge
    pub fn len(&self) -> usize {
        self.darts.len()
    }

    /// The first vertex.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(2, 1).map;
    /// let p = sketch(&map, Vert::new(4), Vert::new(2), &SketchOptions::default()).unwrap();
    /// assert_eq!((p.start(), p.end()), (Vert::new(4), Vert::new(2)));
    /// ```
    pub fn start(&self) -> Vert {
        self.vertices[0]
    }

    /// The last vertex.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{sketch, SketchOptions};
    /// let map = gen::grid(2, 1).map;
    /// let p = sketch(&map, Vert::new(0), Vert::new(5), &SketchOptions::default()).unwrap();
    /// assert_eq!(p.end(), Vert::new(5));
    /// ```
    pub fn end(&self) -> Vert {
        self.vertices[self.vertices.len() - 1]
    }
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, v) in self.vertices.iter().enumerate() {
            if i > 0 {
                f.write_str(" -> ")?;
            }
            write!(f, "{}", v.index())?;
        }
        Ok(())
    }
}

/// Why no path was found or a given path was refused.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, SketchError, SketchOptions};
/// let map = gen::grid(2, 2).map;
/// let e = sketch(&map, Vert::new(4), Vert::new(4), &SketchOptions::default()).unwrap_err();
/// assert_eq!(e, SketchError::SameVertex(Vert::new(4)));
/// assert!(e.to_string().contains("4"));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SketchError {
    /// The two ends are the same vertex.
    SameVertex(Vert),
    /// A vertex is not a live vertex of the map.
    DeadVertex(Vert),
    /// No allowed path joins the two vertices.
    NoPath {
        /// The start.
        from: Vert,
        /// The end.
        to: Vert,
    },
    /// The weight list is shorter than the number of edge slots.
    WeightsTooShort {
        /// The number of edge slots.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// A weight is negative, infinite or NaN.
    BadWeight {
        /// The edge.
        edge: Edge,
        /// The weight given.
        weight: f64,
    },
    /// A given path has fewer than two vertices.
    TooShort(usize),
    /// A given path does not start or end on the requested vertex.
    WrongEnd {
        /// Whether it is the start (`from`) that is wrong; otherwise the end (`to`).
        start: bool,
        /// The requested vertex.
        expected: Vert,
        /// The path's vertex there.
        found: Vert,
    },
    /// Two consecutive vertices of a given path share no edge.
    NotAdjacent {
        /// Position of the first of the two in the path.
        index: usize,
        /// The first vertex.
        a: Vert,
        /// The second vertex.
        b: Vert,
    },
    /// A given path visits a vertex twice.
    Repeated {
        /// The vertex.
        vertex: Vert,
        /// Its first position.
        first: usize,
        /// Its second position.
        second: usize,
    },
    /// Every edge joining two consecutive vertices of a given path is forbidden.
    ForbiddenEdge {
        /// Position of the first of the two in the path.
        index: usize,
        /// The edge (the lowest, when several edges join the two vertices).
        edge: Edge,
    },
    /// Every edge joining two consecutive vertices of a given path lies on a forbidden face.
    ForbiddenFace {
        /// Position of the first of the two in the path.
        index: usize,
        /// The forbidden face.
        face: Face,
    },
}

impl fmt::Display for SketchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::SameVertex(v) => {
                write!(f, "the path's two ends are the same vertex {}", v.index())
            }
            Self::DeadVertex(v) => write!(f, "vertex {} is not in the map", v.index()),
            Self::NoPath { from, to } => write!(
                f,
                "no allowed path joins vertex {} and vertex {}",
                from.index(),
                to.index()
            ),
            Self::WeightsTooShort { expected, got } => {
                write!(f, "{got} edge weights given, {expected} needed")
            }
            Self::BadWeight { edge, weight } => write!(
                f,
                "edge {} has weight {weight}; weights must be finite and non-negative",
                edge.index()
            ),
            Self::TooShort(n) => write!(f, "a path needs at least two vertices, got {n}"),
            Self::WrongEnd {
                start,
                expected,
                found,
            } => {
                let (which, verb) = if *start {
                    ("start at", "starts at")
                } else {
                    ("end on", "ends on")
                };
                write!(
                    f,
                    "the path should {which} vertex {} but {verb} vertex {}",
                    expected.index(),
                    found.index()
                )
            }
            Self::NotAdjacent { index, a, b } => write!(
                f,
                "path vertices {} and {} (positions {index} and {}) share no edge",
                a.index(),
                b.index(),
                index + 1
            ),
            Self::Repeated {
                vertex,
                first,
                second,
            } => write!(
                f,
                "the path is not simple: vertex {} at positions {first} and {second}",
                vertex.index()
            ),
            Self::ForbiddenEdge { index, edge } => write!(
                f,
                "path edge at position {index} is forbidden (edge {})",
                edge.index()
            ),
            Self::ForbiddenFace { index, face } => write!(
                f,
                "path edge at position {index} lies on the forbidden face {}",
                face.index()
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for SketchError {}

/// A guide for the goal-directed search of [`sketch`]: a point per vertex and an upper bound
/// on the distance between the points of the two ends of any edge.
///
/// With unit weights (`weights: None`), a guided sketch is an A* search whose heuristic is
/// `|p(v) - p(to)| / max_edge_length`, a lower bound on the number of edges from `v` to `to`
/// when the bound holds. It returns **the same path** as the unguided search (the tie-breaking
/// rule of the module documentation) while exploring, on a regular grid with a straight
/// shortest path, a number of vertices proportional to the path's length instead of to its
/// square.
///
/// The points need not be the mesh's geometry: any points with `|p(a) - p(b)| <=
/// max_edge_length` for every edge `ab` will do, and the closer they are to the graph
/// distance, the less the search explores. A vertex without a point (index past the end of
/// `positions`) or with a non-finite point gets the heuristic 0, which is still a lower bound.
/// A guide is ignored (the unguided search runs) when `max_edge_length` is not finite and
/// positive or when `to` has no finite point, and with `weights`, where Dijkstra runs.
///
/// **If the bound is wrong** (some edge longer than `max_edge_length`), the heuristic may
/// overestimate: the path is still a valid simple path between the two ends that respects
/// every option, and `NoPath` is still only returned when there is no path, but the path may
/// be longer than the shortest one.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, Guide, SketchOptions};
/// let mesh = gen::grid(40, 40);
/// let guided = SketchOptions::default().guide(Guide::from_mesh(&mesh));
/// let (a, b) = (Vert::new(41 * 20 + 3), Vert::new(41 * 20 + 30));
/// let p = sketch(&mesh.map, a, b, &guided).unwrap();
/// assert_eq!(p, sketch(&mesh.map, a, b, &SketchOptions::default()).unwrap());
/// assert_eq!(p.len(), 27);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Guide<'a> {
    /// A point per vertex, indexed by vertex index.
    pub positions: &'a [DVec3],
    /// An upper bound on `|p(a) - p(b)|` over the edges `ab` of the map.
    pub max_edge_length: f64,
}

impl<'a> Guide<'a> {
    /// A guide from points and a bound on the edge length (see [`max_edge_length`]).
    ///
    /// ```
    /// use zipmesh::gen;
    /// use zipmesh::qzip::{max_edge_length, Guide};
    /// let mesh = gen::grid(3, 3);
    /// let g = Guide::new(&mesh.positions, max_edge_length(&mesh));
    /// assert_eq!(g.positions.len(), 16);
    /// ```
    pub fn new(positions: &'a [DVec3], max_edge_length: f64) -> Self {
        Guide {
            positions,
            max_edge_length,
        }
    }

    /// A guide from a mesh's positions and its longest edge ([`max_edge_length`], O(E)):
    /// compute it once and reuse it for many sketches on an unchanged mesh. To sketch on
    /// `mesh.map` while it is borrowed mutably, use [`Guide::new`] on `&mesh.positions`.
    ///
    /// ```
    /// use zipmesh::gen;
    /// use zipmesh::qzip::Guide;
    /// let mesh = gen::grid(3, 3);
    /// assert_eq!(Guide::from_mesh(&mesh).max_edge_length, 1.0);
    /// ```
    pub fn from_mesh(mesh: &'a Mesh) -> Self {
        Guide::new(&mesh.positions, max_edge_length(mesh))
    }

    /// The point of `v`, when it has a finite one.
    fn point(&self, v: Vert) -> Option<DVec3> {
        self.positions
            .get(v.index())
            .copied()
            .filter(|p| p.is_finite())
    }

    /// Whether the guide can direct a search towards `to`.
    fn usable(&self, to: Vert) -> bool {
        self.max_edge_length.is_finite() && self.max_edge_length > 0.0 && self.point(to).is_some()
    }
}

/// The longest edge of `mesh`: the largest `|p(a) - p(b)|` over its live edges, the bound
/// that makes [`Guide`] exact; `0.0` without edges, and infinity when an edge has an end
/// without a finite position (a guide with that bound is ignored).
///
/// ```
/// use zipmesh::gen;
/// use zipmesh::qzip::max_edge_length;
/// assert_eq!(max_edge_length(&gen::grid(4, 2)), 1.0);
/// ```
pub fn max_edge_length(mesh: &Mesh) -> f64 {
    let map = &mesh.map;
    let point = |v: Vert| {
        mesh.positions
            .get(v.index())
            .copied()
            .filter(|p| p.is_finite())
    };
    let mut longest: f64 = 0.0;
    for e in map.edges() {
        let d = e.dart(0);
        match (point(map.origin(d)), point(map.dest(d))) {
            (Some(a), Some(b)) => {
                let l = a.distance(b);
                if l.is_finite() {
                    longest = longest.max(l);
                } else {
                    return f64::INFINITY;
                }
            }
            _ => return f64::INFINITY,
        }
    }
    longest
}

/// The edge masks and checked weights shared by the searches and the validation.
struct Rules<'a> {
    /// Forbidden edges, sorted without repeats: a lookup costs O(log k), and a search
    /// costs what it explores, not O(E).
    forbidden: Vec<Edge>,
    weights: Option<&'a [f64]>,
}

impl<'a> Rules<'a> {
    /// The rules of `opts`, their forbidden list built in `forbidden` (a reused buffer).
    fn new(
        map: &Map,
        opts: &'a SketchOptions<'_>,
        mut forbidden: Vec<Edge>,
    ) -> Result<Self, SketchError> {
        let n_edges = map.edge_slots();
        forbidden.clear();
        forbidden.extend_from_slice(&opts.forbidden_edges);
        for &f in &opts.forbidden_faces {
            if map.is_live_face(f) {
                forbidden.extend(map.face_darts(f).map(Dart::edge));
            }
        }
        forbidden.sort_unstable();
        forbidden.dedup();
        let weights = match &opts.weights {
            None => None,
            Some(w) => {
                if w.len() < n_edges {
                    return Err(SketchError::WeightsTooShort {
                        expected: n_edges,
                        got: w.len(),
                    });
                }
                for (e, &x) in w.iter().enumerate().take(n_edges) {
                    let edge = Edge::new(e as u32);
                    if !(x.is_finite() && x >= 0.0) && map.is_live_edge(edge) {
                        return Err(SketchError::BadWeight { edge, weight: x });
                    }
                }
                Some(&w[..])
            }
        };
        Ok(Rules { forbidden, weights })
    }

    fn usable(&self, d: Dart) -> bool {
        self.forbidden.is_empty() || self.forbidden.binary_search(&d.edge()).is_err()
    }
}

/// The outgoing darts of `v` in increasing dart index (the documented tie-breaking order).
fn sorted_darts(map: &Map, v: Vert, buf: &mut Vec<Dart>) {
    buf.clear();
    buf.extend(map.vertex_darts(v));
    // Most rings come out sorted or nearly so; skip the sort when they already are.
    if !buf.windows(2).all(|w| w[0] <= w[1]) {
        buf.sort_unstable();
    }
}

/// Reusable memory for many sketches: per-vertex arrays stamped with a search epoch, so a
/// sketch on a million-vertex map costs what it explores, with no O(V) clear or allocation
/// per call (the arrays grow to the largest map seen, once). The results are those of
/// [`sketch`], path for path.
///
/// One workspace serves any number of maps, one after another, and stays correct after the
/// map is edited: nothing is cached between calls but memory.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, SketchOptions, SketchWorkspace};
/// let map = gen::torus_grid(50, 50).map;
/// let opts = SketchOptions::default();
/// let mut ws = SketchWorkspace::new();
/// for (a, b) in [(0, 7), (120, 1300), (7, 0)] {
///     let (a, b) = (Vert::new(a), Vert::new(b));
///     assert_eq!(ws.sketch(&map, a, b, &opts), sketch(&map, a, b, &opts));
/// }
/// ```
#[derive(Default)]
pub struct SketchWorkspace {
    slots: Vec<Slot>,
    epoch: u32,
    forbidden: Vec<Edge>,
    bufs: Buffers,
    explored: usize,
}

impl fmt::Debug for SketchWorkspace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SketchWorkspace")
            .field("vertex_slots", &self.slots.len())
            .field("epoch", &self.epoch)
            .field("explored", &self.explored)
            .finish()
    }
}

impl SketchWorkspace {
    /// An empty workspace; its arrays grow on first use.
    ///
    /// ```
    /// let ws = zipmesh::qzip::SketchWorkspace::new();
    /// assert_eq!(ws.explored(), 0);
    /// ```
    pub fn new() -> Self {
        Self::default()
    }

    /// The same as [`sketch`] (the same path or error), using this workspace's memory.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{SketchOptions, SketchWorkspace};
    /// let map = gen::grid(5, 5).map;
    /// let mut ws = SketchWorkspace::new();
    /// let p = ws.sketch(&map, Vert::new(7), Vert::new(10), &SketchOptions::default()).unwrap();
    /// assert_eq!(p.len(), 3);
    /// ```
    pub fn sketch(
        &mut self,
        map: &Map,
        from: Vert,
        to: Vert,
        opts: &SketchOptions<'_>,
    ) -> Result<Path, SketchError> {
        self.explored = 0;
        check_ends(map, from, to)?;
        if self.slots.len() < map.vertex_slots() {
            self.slots.resize(map.vertex_slots(), Slot::default());
        }
        let rules = Rules::new(map, opts, core::mem::take(&mut self.forbidden))?;
        let mut store = ArrayStore {
            slots: &mut self.slots,
            epoch: self.epoch,
            touched: 0,
        };
        let found = run_passes(map, from, to, opts, &rules, &mut store, &mut self.bufs);
        (self.epoch, self.explored) = (store.epoch, store.touched);
        self.forbidden = rules.forbidden;
        found.ok_or(SketchError::NoPath { from, to })
    }

    /// How many vertices the last [`SketchWorkspace::sketch`] touched (labelled by any of its
    /// search passes): the measure of its work, for tests and benchmarks.
    ///
    /// ```
    /// use zipmesh::{gen, Vert};
    /// use zipmesh::qzip::{Guide, SketchOptions, SketchWorkspace};
    /// let mesh = gen::grid(60, 60);
    /// let (a, b) = (Vert::new(61 * 30 + 5), Vert::new(61 * 30 + 45));
    /// let mut ws = SketchWorkspace::new();
    /// ws.sketch(&mesh.map, a, b, &SketchOptions::default()).unwrap();
    /// let plain = ws.explored();
    /// let guided = SketchOptions::default().guide(Guide::from_mesh(&mesh));
    /// ws.sketch(&mesh.map, a, b, &guided).unwrap();
    /// assert!(ws.explored() * 5 < plain);
    /// ```
    pub fn explored(&self) -> usize {
        self.explored
    }
}

/// The end checks shared by both entry points.
fn check_ends(map: &Map, from: Vert, to: Vert) -> Result<(), SketchError> {
    for v in [from, to] {
        if !map.is_live_vertex(v) {
            return Err(SketchError::DeadVertex(v));
        }
    }
    if from == to {
        return Err(SketchError::SameVertex(from));
    }
    Ok(())
}

/// The search passes: with `avoid_boundary`, first without boundary vertices, then without
/// the exclusion.
fn passes(opts: &SketchOptions<'_>) -> &'static [bool] {
    if opts.avoid_boundary {
        &[true, false]
    } else {
        &[false]
    }
}

/// A shortest allowed path from `from` to `to`.
///
/// With `opts.weights == None` the length is the number of edges (breadth-first search,
/// bidirectional, or A* with `opts.guide`); otherwise the sum of the weights (Dijkstra). Ties
/// are broken as the module documentation says, so every search gives the same path. With
/// `opts.avoid_boundary`, boundary vertices other than the two ends are first excluded from
/// the search; if that leaves no path, the search runs again without the exclusion.
///
/// Its memory is hash maps sized by what it explores; for many sketches, a
/// [`SketchWorkspace`] gives the same paths faster.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, SketchOptions};
/// // 4 x 1 grid, vertices 0..5 on the bottom row, 5..10 on the top row.
/// let map = gen::grid(4, 1).map;
/// let opts = SketchOptions::default().avoid_boundary(true);
/// let p = sketch(&map, Vert::new(0), Vert::new(4), &opts).unwrap(); // every vertex is on the boundary
/// assert_eq!(p.len(), 4);
/// ```
pub fn sketch(
    map: &Map,
    from: Vert,
    to: Vert,
    opts: &SketchOptions<'_>,
) -> Result<Path, SketchError> {
    check_ends(map, from, to)?;
    let rules = Rules::new(map, opts, Vec::new())?;
    let mut store = HashStore(HashMap::with_capacity(256));
    run_passes(
        map,
        from,
        to,
        opts,
        &rules,
        &mut store,
        &mut Buffers::default(),
    )
    .ok_or(SketchError::NoPath { from, to })
}

/// The search passes of one sketch (avoiding the boundary first when asked), each on a
/// fresh pass of `store`: the first path found.
fn run_passes<S: Store>(
    map: &Map,
    from: Vert,
    to: Vert,
    opts: &SketchOptions<'_>,
    rules: &Rules<'_>,
    store: &mut S,
    bufs: &mut Buffers,
) -> Option<Path> {
    passes(opts).iter().find_map(|&avoid| {
        store.next_pass();
        let cx = Ctx {
            map,
            from,
            to,
            rules,
            avoid,
        };
        search(&cx, opts.guide.as_ref(), store, bufs)
    })
}
