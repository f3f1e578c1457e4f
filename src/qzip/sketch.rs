//! Stage 1 of Q-zip, sketching: a simple edge path between two vertices.
//!
//! [`sketch`] finds a shortest path (breadth-first search on unit weights, or Dijkstra on
//! caller-given per-edge weights) that avoids forbidden edges and the edges of forbidden faces,
//! and, when asked, prefers paths whose interior vertices are not on the boundary.
//! [`validate_path`] accepts a caller-given vertex list under the same rules or refuses it with
//! a [`SketchError`] naming the defect.
//!
//! **Tie-breaking.** Both searches are deterministic, so the same map and options give the same
//! path: the outgoing darts of a vertex are expanded in increasing dart index, the breadth-first
//! queue is first-in first-out, Dijkstra settles the vertex of smallest (distance, vertex index)
//! first, and a vertex keeps the first predecessor that reached it at its final distance.
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

use alloc::collections::{BinaryHeap, VecDeque};
use alloc::vec::Vec;
use core::cmp::Ordering;
use core::fmt;

use hashbrown::{HashMap, HashSet};

use crate::{Dart, Face, Map, Vert};

/// Options of [`sketch`] and [`validate_path`].
///
/// Edges are named by their index `e`: the edge of darts `2e` and `2e + 1`, that is
/// `dart.index() / 2`.
///
/// ```
/// use zipmesh::Face;
/// use zipmesh::qzip::SketchOptions;
/// let opts = SketchOptions {
///     avoid_boundary: true,
///     forbidden_edges: vec![3, 4],
///     forbidden_faces: vec![Face::new(0)],
///     weights: None,
/// };
/// assert!(opts.avoid_boundary);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SketchOptions {
    /// Prefer paths whose interior vertices are not on the boundary; when no such path exists,
    /// fall back to any path. Ignored by [`validate_path`].
    pub avoid_boundary: bool,
    /// Edge indices that no path may use (sharp features).
    pub forbidden_edges: Vec<u32>,
    /// Faces whose edges no path may use (protected regions).
    pub forbidden_faces: Vec<Face>,
    /// Per-edge weights indexed by edge index (length at least `map.dart_slots() / 2`), each
    /// finite and non-negative; `None` means unit weights and breadth-first search. Path
    /// lengths whose sum overflows to infinity count as unreachable.
    pub weights: Option<Vec<f64>>,
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
        /// The edge index.
        edge: u32,
        /// The weight given.
        weight: f64,
    },
    /// A given path has fewer than two vertices.
    TooShort(usize),
    /// A given path does not start or end on the requested vertex.
    WrongEnd {
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
        /// The edge index (the lowest, when several edges join the two vertices).
        edge: u32,
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
                "edge {edge} has weight {weight}; weights must be finite and non-negative"
            ),
            Self::TooShort(n) => write!(f, "a path needs at least two vertices, got {n}"),
            Self::WrongEnd { expected, found } => write!(
                f,
                "the path should end on vertex {} but has vertex {} there",
                expected.index(),
                found.index()
            ),
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
                "path edge at position {index} is forbidden (edge {edge})"
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

/// The edge masks and checked weights shared by both searches and the validation.
struct Rules<'a> {
    /// Forbidden edge indices; a set, so a search costs what it explores, not O(E).
    forbidden: HashSet<u32>,
    weights: Option<&'a [f64]>,
}

impl<'a> Rules<'a> {
    fn new(map: &Map, opts: &'a SketchOptions) -> Result<Self, SketchError> {
        let n_edges = map.dart_slots() / 2;
        let mut forbidden: HashSet<u32> = opts.forbidden_edges.iter().copied().collect();
        for &f in &opts.forbidden_faces {
            if map.is_live_face(f) {
                forbidden.extend(map.face_darts(f).map(|d| (d.index() / 2) as u32));
            }
        }
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
                    if !(x.is_finite() && x >= 0.0) && map.is_live_dart(Dart::new(2 * e as u32)) {
                        return Err(SketchError::BadWeight {
                            edge: e as u32,
                            weight: x,
                        });
                    }
                }
                Some(&w[..])
            }
        };
        Ok(Rules { forbidden, weights })
    }

    fn usable(&self, d: Dart) -> bool {
        self.forbidden.is_empty() || !self.forbidden.contains(&((d.index() / 2) as u32))
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

/// A shortest allowed path from `from` to `to`.
///
/// With `opts.weights == None` the length is the number of edges (breadth-first search);
/// otherwise the sum of the weights (Dijkstra). Ties are broken as the module documentation
/// says. With `opts.avoid_boundary`, boundary vertices other than the two ends are first
/// excluded from the search; if that leaves no path, the search runs again without the
/// exclusion.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, SketchOptions};
/// // 4 x 1 grid, vertices 0..5 on the bottom row, 5..10 on the top row.
/// let map = gen::grid(4, 1).map;
/// let opts = SketchOptions { avoid_boundary: true, ..Default::default() };
/// let p = sketch(&map, Vert::new(0), Vert::new(4), &opts).unwrap(); // every vertex is on the boundary
/// assert_eq!(p.len(), 4);
/// ```
pub fn sketch(map: &Map, from: Vert, to: Vert, opts: &SketchOptions) -> Result<Path, SketchError> {
    for v in [from, to] {
        if !map.is_live_vertex(v) {
            return Err(SketchError::DeadVertex(v));
        }
    }
    if from == to {
        return Err(SketchError::SameVertex(from));
    }
    let rules = Rules::new(map, opts)?;
    if opts.avoid_boundary {
        if let Some(p) = search(map, from, to, &rules, true) {
            return Ok(p);
        }
    }
    search(map, from, to, &rules, false).ok_or(SketchError::NoPath { from, to })
}

/// Dijkstra heap entry: smallest (distance, vertex) first.
#[derive(PartialEq)]
struct Entry(f64, u32);

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed so that BinaryHeap (a max-heap) pops the smallest; weights are finite.
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| other.1.cmp(&self.1))
    }
}

fn search(map: &Map, from: Vert, to: Vert, rules: &Rules<'_>, avoid: bool) -> Option<Path> {
    const START: u32 = u32::MAX;
    // pred[v]: the dart that reached v (START for `from`). Hash maps, not arrays over all
    // vertices: a short path on a large mesh costs what the search explores.
    let mut pred: HashMap<u32, u32> = HashMap::with_capacity(256);
    let mut buf = Vec::new();
    let blocked = |v: Vert| avoid && v != to && map.is_boundary_vertex(v);
    match rules.weights {
        None => {
            let mut queue = VecDeque::new();
            pred.insert(from.index() as u32, START);
            queue.push_back(from);
            // A vertex's predecessor is fixed when it is first reached, so the search can stop
            // as soon as `to` is reached: the same path as popping it, a layer sooner.
            'search: while let Some(v) = queue.pop_front() {
                if v == to {
                    break;
                }
                sorted_darts(map, v, &mut buf);
                for &d in &buf {
                    let w = map.dest(d);
                    if rules.usable(d) && !blocked(w) {
                        if let hashbrown::hash_map::Entry::Vacant(e) = pred.entry(w.index() as u32)
                        {
                            e.insert(d.index() as u32);
                            if w == to {
                                break 'search;
                            }
                            queue.push_back(w);
                        }
                    }
                }
            }
        }
        Some(weights) => {
            let mut dist: HashMap<u32, f64> = HashMap::new();
            let mut done: HashSet<u32> = HashSet::new();
            let mut heap = BinaryHeap::new();
            dist.insert(from.index() as u32, 0.0);
            pred.insert(from.index() as u32, START);
            heap.push(Entry(0.0, from.index() as u32));
            while let Some(Entry(dv, vi)) = heap.pop() {
                let v = Vert::new(vi);
                if !done.insert(vi) {
                    continue;
                }
                if v == to {
                    break;
                }
                sorted_darts(map, v, &mut buf);
                for &d in &buf {
                    let w = map.dest(d);
                    let wi = w.index() as u32;
                    if !rules.usable(d) || done.contains(&wi) || blocked(w) {
                        continue;
                    }
                    let nd = dv + weights.get(d.index() / 2).copied().unwrap_or(f64::INFINITY);
                    if nd < dist.get(&wi).copied().unwrap_or(f64::INFINITY) {
                        dist.insert(wi, nd);
                        pred.insert(wi, d.index() as u32);
                        heap.push(Entry(nd, wi));
                    }
                }
            }
        }
    }
    pred.get(&(to.index() as u32))?;
    let mut darts = Vec::new();
    let mut v = to;
    while v != from {
        let d = Dart::new(*pred.get(&(v.index() as u32))?);
        darts.push(d);
        v = map.origin(d);
    }
    darts.reverse();
    let mut vertices = Vec::with_capacity(darts.len() + 1);
    vertices.push(from);
    vertices.extend(darts.iter().map(|&d| map.dest(d)));
    Some(Path { vertices, darts })
}

/// Checks a caller-given path (`vertices`) that should run from `from` to `to` and returns it as a [`Path`].
///
/// The checks, in order: at least two vertices; every vertex live; the first is `from` and
/// the last is `to`; no vertex twice; consecutive vertices joined by an edge that is neither
/// forbidden nor on a forbidden face (when several edges join them, the lowest-index allowed
/// one is used). `opts.avoid_boundary` and `opts.weights` play no part.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{validate_path, SketchError, SketchOptions};
/// let map = gen::grid(3, 3).map;
/// let v = |i| Vert::new(i);
/// let opts = SketchOptions::default();
/// assert!(validate_path(&map, v(0), v(2), &[v(0), v(1), v(2)], &opts).is_ok());
/// assert!(matches!(
///     validate_path(&map, v(0), v(2), &[v(0), v(2)], &opts),
///     Err(SketchError::NotAdjacent { index: 0, .. })
/// ));
/// ```
pub fn validate_path(
    map: &Map,
    from: Vert,
    to: Vert,
    vertices: &[Vert],
    opts: &SketchOptions,
) -> Result<Path, SketchError> {
    if vertices.len() < 2 {
        return Err(SketchError::TooShort(vertices.len()));
    }
    for &v in vertices {
        if !map.is_live_vertex(v) {
            return Err(SketchError::DeadVertex(v));
        }
    }
    for (expected, found) in [(from, vertices[0]), (to, vertices[vertices.len() - 1])] {
        if expected != found {
            return Err(SketchError::WrongEnd { expected, found });
        }
    }
    for i in 0..vertices.len() {
        for j in 0..i {
            if vertices[i] == vertices[j] {
                return Err(SketchError::Repeated {
                    vertex: vertices[i],
                    first: j,
                    second: i,
                });
            }
        }
    }
    // Weights play no part in validation, so they are not checked either.
    let unweighted = SketchOptions {
        weights: None,
        ..opts.clone()
    };
    let rules = Rules::new(map, &unweighted)?;
    let forbidden_face = |d: Dart| {
        opts.forbidden_faces
            .iter()
            .copied()
            .find(|&f| map.face(d) == Some(f) || map.face(d.twin()) == Some(f))
    };
    let mut darts = Vec::with_capacity(vertices.len() - 1);
    let mut buf = Vec::new();
    for (i, w) in vertices.windows(2).enumerate() {
        sorted_darts(map, w[0], &mut buf);
        let joining: Vec<Dart> = buf
            .iter()
            .copied()
            .filter(|&d| map.dest(d) == w[1])
            .collect();
        let Some(&first) = joining.first() else {
            return Err(SketchError::NotAdjacent {
                index: i,
                a: w[0],
                b: w[1],
            });
        };
        match joining.iter().copied().find(|&d| rules.usable(d)) {
            Some(d) => darts.push(d),
            None => {
                return Err(match forbidden_face(first) {
                    Some(face) => SketchError::ForbiddenFace { index: i, face },
                    None => SketchError::ForbiddenEdge {
                        index: i,
                        edge: (first.index() / 2) as u32,
                    },
                })
            }
        }
    }
    Ok(Path {
        vertices: vertices.to_vec(),
        darts,
    })
}
