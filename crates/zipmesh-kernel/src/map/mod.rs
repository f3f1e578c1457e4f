//! The oriented 2-map: darts with `next`, `twin`, origin vertex and face.
//!
//! Storage is structure-of-arrays with 12 bytes per dart (`next`, origin, face) and 4 bytes per
//! vertex and per face (one dart each). `twin` is implicit (`d ^ 1`) and `prev` is computed
//! (around the face for face darts, around the origin for boundary darts), which keeps a closed
//! quad mesh at about 56 bytes of topology per face. See `docs/design.md` for the axioms.

mod build;
mod check;
mod handle;
mod raw;
mod store;
mod walk;

pub use build::{BuildError, BuildReport, MAX_CORNERS};
pub use check::Violation;
pub(crate) use handle::NONE;
pub use handle::{Dart, Edge, Face, Vert};
pub use raw::RawError;
pub use store::Compaction;
pub use walk::{FaceDarts, Orbit, VertexDarts};

use alloc::vec::Vec;

/// An oriented 2-map of a surface with boundary.
///
/// * Every dart has a `next` (the following dart around its face or boundary loop, counter-
///   clockwise seen from the front side), a `twin` (the dart of the same edge in the other
///   direction), an origin vertex, and a face, or no face when it lies on a boundary loop.
/// * Every live vertex has exactly one rotation (its darts form one cycle), so the map is a
///   manifold by construction; a boundary vertex has exactly one outgoing boundary dart.
/// * Deleted elements are dead slots; [`Map::compact`] removes them.
///
/// ```
/// use zipmesh_kernel::Map;
/// // Two triangles sharing the edge 1-2.
/// let map = Map::from_polygons(4, &[[0u32, 1, 2], [2, 1, 3]]).unwrap();
/// assert_eq!((map.num_vertices(), map.num_edges(), map.num_faces()), (4, 5, 2));
/// assert!(map.check().is_ok());
/// ```
#[derive(Debug, PartialEq, Eq, Default)]
pub struct Map {
    /// Per dart: the next dart around its face or boundary loop; `NONE` for a dead dart.
    pub(crate) next: Vec<u32>,
    /// Per dart: its origin vertex.
    pub(crate) vert: Vec<u32>,
    /// Per dart: its face; `NONE` for a boundary dart.
    pub(crate) face: Vec<u32>,
    /// Per vertex: one outgoing dart, the boundary one if there is one; `NONE` if dead.
    pub(crate) vdart: Vec<u32>,
    /// Per face: one of its darts; `NONE` if dead.
    pub(crate) fdart: Vec<u32>,
    /// Dead edge, vertex and face slots, reused last-in first-out.
    pub(crate) free_edges: Vec<u32>,
    pub(crate) free_verts: Vec<u32>,
    pub(crate) free_faces: Vec<u32>,
}

impl Map {
    /// An empty map.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::new();
    /// assert_eq!(map.num_darts(), 0);
    /// ```
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of live darts (twice the number of edges).
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.num_darts(), 6);
    /// ```
    #[inline]
    pub fn num_darts(&self) -> usize {
        2 * self.num_edges()
    }

    /// Number of live edges.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.num_edges(), 3);
    /// ```
    #[inline]
    pub fn num_edges(&self) -> usize {
        self.next.len() / 2 - self.free_edges.len()
    }

    /// Number of live vertices.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.num_vertices(), 3);
    /// ```
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.vdart.len() - self.free_verts.len()
    }

    /// Number of live faces.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.num_faces(), 1);
    /// ```
    #[inline]
    pub fn num_faces(&self) -> usize {
        self.fdart.len() - self.free_faces.len()
    }

    /// Number of dart slots, live or dead: every live dart has an index below this.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.dart_slots(), 6);
    /// ```
    #[inline]
    pub fn dart_slots(&self) -> usize {
        self.next.len()
    }

    /// Number of edge slots, live or dead: every live edge has an index below this, so
    /// per-edge data of this length covers the map.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.edge_slots(), 3);
    /// ```
    #[inline]
    pub fn edge_slots(&self) -> usize {
        self.next.len() / 2
    }

    /// Number of vertex slots, live or dead.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(5, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.vertex_slots(), 5); // vertices 3 and 4 are unreferenced: dead slots
    /// assert_eq!(map.num_vertices(), 3);
    /// ```
    #[inline]
    pub fn vertex_slots(&self) -> usize {
        self.vdart.len()
    }

    /// Number of face slots, live or dead.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.face_slots(), 1);
    /// ```
    #[inline]
    pub fn face_slots(&self) -> usize {
        self.fdart.len()
    }

    /// Whether `d` names a live dart of this map.
    ///
    /// ```
    /// use zipmesh_kernel::{Dart, Map};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert!(map.is_live_dart(Dart::new(5)));
    /// assert!(!map.is_live_dart(Dart::new(6)));
    /// ```
    #[inline]
    pub fn is_live_dart(&self, d: Dart) -> bool {
        self.next.get(d.index()).is_some_and(|&n| n != NONE)
    }

    /// Whether `e` names a live edge of this map.
    ///
    /// ```
    /// use zipmesh_kernel::{Edge, Map};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert!(map.is_live_edge(Edge::new(2)));
    /// assert!(!map.is_live_edge(Edge::new(3)));
    /// ```
    #[inline]
    pub fn is_live_edge(&self, e: Edge) -> bool {
        self.is_live_dart(e.dart(0))
    }

    /// Whether `v` names a live vertex of this map.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2]]).unwrap();
    /// assert!(map.is_live_vertex(Vert::new(2)));
    /// assert!(!map.is_live_vertex(Vert::new(3)));
    /// ```
    #[inline]
    pub fn is_live_vertex(&self, v: Vert) -> bool {
        self.vdart.get(v.index()).is_some_and(|&d| d != NONE)
    }

    /// Whether `f` names a live face of this map.
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert!(map.is_live_face(Face::new(0)));
    /// assert!(!map.is_live_face(Face::new(1)));
    /// ```
    #[inline]
    pub fn is_live_face(&self, f: Face) -> bool {
        self.fdart.get(f.index()).is_some_and(|&d| d != NONE)
    }

    /// The next dart around the face (or boundary loop) of `d`.
    ///
    /// Never panics: for a handle that is out of range or dead the result is a dart that is
    /// not live (check handles from elsewhere with [`Map::is_live_dart`]).
    ///
    /// ```
    /// use zipmesh_kernel::{Dart, Map};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// let d = map.face_dart(zipmesh_kernel::Face::new(0));
    /// assert_eq!(map.next(map.next(map.next(d))), d);
    /// ```
    #[inline]
    pub fn next(&self, d: Dart) -> Dart {
        Dart(get(&self.next, d.0))
    }

    /// The origin vertex of `d`.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// let d = map.vertex_dart(Vert::new(1));
    /// assert_eq!(map.origin(d), Vert::new(1));
    /// ```
    #[inline]
    pub fn origin(&self, d: Dart) -> Vert {
        Vert(get(&self.vert, d.0))
    }

    /// The vertex `d` points to (the origin of its twin).
    ///
    /// ```
    /// use zipmesh_kernel::Map;
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// let d = map.face_dart(zipmesh_kernel::Face::new(0));
    /// assert_eq!(map.dest(d), map.origin(map.next(d)));
    /// ```
    #[inline]
    pub fn dest(&self, d: Dart) -> Vert {
        Vert(get(&self.vert, d.0 ^ 1))
    }

    /// The face of `d`, or `None` when `d` lies on a boundary loop.
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// let d = map.face_dart(Face::new(0));
    /// assert_eq!(map.face(d), Some(Face::new(0)));
    /// assert_eq!(map.face(d.twin()), None);
    /// ```
    #[inline]
    pub fn face(&self, d: Dart) -> Option<Face> {
        let f = get(&self.face, d.0);
        (f != NONE).then_some(Face(f))
    }

    /// Whether `d` lies on a boundary loop (has no face).
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert!(map.is_boundary_dart(map.face_dart(Face::new(0)).twin()));
    /// ```
    #[inline]
    pub fn is_boundary_dart(&self, d: Dart) -> bool {
        // The face first: most darts have one, so most calls end after one read.
        self.face.get(d.index()) == Some(&NONE)
            && self.next.get(d.index()).is_some_and(|&n| n != NONE)
    }

    /// One outgoing dart of `v`; the outgoing boundary dart when `v` is on the boundary.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert!(map.is_boundary_dart(map.vertex_dart(Vert::new(0))));
    /// ```
    #[inline]
    pub fn vertex_dart(&self, v: Vert) -> Dart {
        Dart(get(&self.vdart, v.0))
    }

    /// One dart of face `f`.
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.face(map.face_dart(Face::new(0))), Some(Face::new(0)));
    /// ```
    #[inline]
    pub fn face_dart(&self, f: Face) -> Dart {
        Dart(get(&self.fdart, f.0))
    }

    /// Heap bytes held by the topology (array capacities, free lists included).
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// assert!(map.heap_bytes() >= 4 * (3 * map.num_darts() + map.num_vertices() + map.num_faces()));
    /// ```
    pub fn heap_bytes(&self) -> usize {
        4 * (self.next.capacity()
            + self.vert.capacity()
            + self.face.capacity()
            + self.vdart.capacity()
            + self.fdart.capacity()
            + self.free_edges.capacity()
            + self.free_verts.capacity()
            + self.free_faces.capacity())
    }

    /// Whether `v` lies on the boundary.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert!(map.is_boundary_vertex(Vert::new(0)));
    /// ```
    #[inline]
    pub fn is_boundary_vertex(&self, v: Vert) -> bool {
        self.is_boundary_dart(self.vertex_dart(v))
    }
}

/// Total array access: out of range reads as `NONE`, so public accessors never panic.
#[inline(always)]
fn get(a: &[u32], i: u32) -> u32 {
    a.get(i as usize).copied().unwrap_or(NONE)
}

/// A copy of `v` with the same spare room, so a copied map edits in place as the original
/// does (a derived clone would drop the room and copy the whole array on the first split).
fn clone_with_room(v: &[u32], capacity: usize) -> Vec<u32> {
    let mut out = Vec::with_capacity(capacity.max(v.len()));
    out.extend_from_slice(v);
    out
}

impl Clone for Map {
    fn clone(&self) -> Map {
        Map {
            next: clone_with_room(&self.next, self.next.capacity()),
            vert: clone_with_room(&self.vert, self.vert.capacity()),
            face: clone_with_room(&self.face, self.face.capacity()),
            vdart: clone_with_room(&self.vdart, self.vdart.capacity()),
            fdart: clone_with_room(&self.fdart, self.fdart.capacity()),
            free_edges: self.free_edges.clone(),
            free_verts: self.free_verts.clone(),
            free_faces: self.free_faces.clone(),
        }
    }

    /// Copies `source` into `self`'s arrays, allocating only where they are too short (the
    /// optimizer copies a small mesh per candidate).
    fn clone_from(&mut self, source: &Map) {
        self.next.clone_from(&source.next);
        self.vert.clone_from(&source.vert);
        self.face.clone_from(&source.face);
        self.vdart.clone_from(&source.vdart);
        self.fdart.clone_from(&source.fdart);
        self.free_edges.clone_from(&source.free_edges);
        self.free_verts.clone_from(&source.free_verts);
        self.free_faces.clone_from(&source.free_faces);
    }
}
