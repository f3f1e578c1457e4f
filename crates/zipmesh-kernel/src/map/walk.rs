//! Orbits: around a face, around a vertex, boundary loops, and the live elements.
//!
//! Every walk is bounded by the number of dart slots, so even a foreign or dead handle
//! cannot make one loop forever.

use super::{Dart, Edge, Face, Map, Vert, NONE};

impl Map {
    /// The dart before `d` around its face or boundary loop.
    ///
    /// Costs O(degree) for a face dart and O(valence of the origin) for a boundary dart,
    /// because `prev` is not stored (see `docs/design.md`).
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// let d = map.face_dart(Face::new(0));
    /// assert_eq!(map.next(map.prev(d)), d);
    /// let b = d.twin();
    /// assert_eq!(map.next(map.prev(b)), b);
    /// ```
    pub fn prev(&self, d: Dart) -> Dart {
        if !self.is_live_dart(d) {
            return Dart(NONE);
        }
        if self.is_boundary_dart(d) {
            // Around the origin: the dart x with next(twin(x)) == d gives prev(d) = twin(x).
            let mut x = d;
            for _ in 0..self.next.len() {
                let y = self.rotate_cw(x);
                if y == d {
                    return x.twin();
                }
                x = y;
            }
            Dart(NONE)
        } else {
            let mut x = d;
            for _ in 0..self.next.len() {
                let y = self.next(x);
                if y == d {
                    return x;
                }
                x = y;
            }
            Dart(NONE)
        }
    }

    /// The next outgoing dart of `origin(d)` clockwise: `next(twin(d))`.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    /// let d = map.vertex_dart(Vert::new(0));
    /// assert_eq!(map.origin(map.rotate_cw(d)), Vert::new(0));
    /// assert_eq!(map.rotate_ccw(map.rotate_cw(d)), d);
    /// ```
    #[inline]
    pub fn rotate_cw(&self, d: Dart) -> Dart {
        self.next(d.twin())
    }

    /// The next outgoing dart of `origin(d)` counter-clockwise: `twin(prev(d))`.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    /// let d = map.vertex_dart(Vert::new(0));
    /// assert_eq!(map.rotate_cw(map.rotate_ccw(d)), d);
    /// ```
    #[inline]
    pub fn rotate_ccw(&self, d: Dart) -> Dart {
        self.prev(d).twin()
    }

    /// The darts of the face (or boundary loop) of `d`, starting at `d`, following `next`.
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// let d = map.face_dart(Face::new(0));
    /// assert_eq!(map.face_cycle(d).count(), 4);
    /// assert_eq!(map.face_cycle(d.twin()).count(), 4); // the boundary loop
    /// ```
    pub fn face_cycle(&self, d: Dart) -> FaceDarts<'_> {
        FaceDarts {
            map: self,
            start: d,
            cur: self.live_or_none(d),
            left: self.next.len(),
        }
    }

    /// The darts of face `f`.
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(5, &[[0u32, 1, 2, 3, 4]]).unwrap();
    /// let verts: Vec<_> = map.face_darts(Face::new(0)).map(|d| map.origin(d).index()).collect();
    /// assert_eq!(verts.len(), 5);
    /// ```
    pub fn face_darts(&self, f: Face) -> FaceDarts<'_> {
        self.face_cycle(self.face_dart(f))
    }

    /// The outgoing darts of `v`, clockwise; for a boundary vertex the first is its boundary
    /// dart and the last is the dart whose twin is a boundary dart.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    /// assert_eq!(map.vertex_darts(Vert::new(0)).count(), 3);
    /// ```
    pub fn vertex_darts(&self, v: Vert) -> VertexDarts<'_> {
        let d = self.vertex_dart(v);
        VertexDarts {
            map: self,
            start: d,
            cur: self.live_or_none(d),
            left: self.next.len(),
        }
    }

    /// The number of darts leaving `v` (a loop counts twice); 0 for a dead vertex.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    /// assert_eq!(map.valence(Vert::new(0)), 3);
    /// assert_eq!(map.valence(Vert::new(1)), 2);
    /// ```
    pub fn valence(&self, v: Vert) -> usize {
        self.vertex_darts(v).count()
    }

    /// The number of darts of face `f`; 0 for a dead face.
    ///
    /// ```
    /// use zipmesh_kernel::{Face, Map};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// assert_eq!(map.degree(Face::new(0)), 4);
    /// ```
    pub fn degree(&self, f: Face) -> usize {
        self.face_darts(f).count()
    }

    /// The live darts, in slot order.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.darts().count(), 6);
    /// ```
    pub fn darts(&self) -> impl Iterator<Item = Dart> + '_ {
        (0..self.next.len() as u32)
            .filter(|&i| self.next[i as usize] != NONE)
            .map(Dart)
    }

    /// The live edges, in slot order.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// assert_eq!(map.edges().count(), 4);
    /// ```
    pub fn edges(&self) -> impl Iterator<Item = Edge> + '_ {
        (0..self.edge_slots() as u32)
            .map(Edge)
            .filter(|&e| self.is_live_edge(e))
    }

    /// The dart from `p` to `n` when exactly one edge joins them; `None` when there is no
    /// such edge, several (a multi-edge), or either vertex is not live. The kernel's
    /// "find half-edge" query; O(valence of `p`).
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// let d = map.dart_between(Vert::new(1), Vert::new(2)).unwrap();
    /// assert_eq!((map.origin(d), map.dest(d)), (Vert::new(1), Vert::new(2)));
    /// assert_eq!(map.dart_between(Vert::new(0), Vert::new(2)), None);
    /// ```
    pub fn dart_between(&self, p: Vert, n: Vert) -> Option<Dart> {
        if !self.is_live_vertex(p) || !self.is_live_vertex(n) {
            return None;
        }
        let mut found = None;
        for d in self.vertex_darts(p) {
            if self.dest(d) == n {
                if found.is_some() {
                    return None;
                }
                found = Some(d);
            }
        }
        found
    }

    /// The live vertices, in slot order.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.vertices().count(), 3);
    /// ```
    pub fn vertices(&self) -> impl Iterator<Item = Vert> + '_ {
        (0..self.vdart.len() as u32)
            .filter(|&i| self.vdart[i as usize] != NONE)
            .map(Vert)
    }

    /// The live faces, in slot order.
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(map.faces().count(), 1);
    /// ```
    pub fn faces(&self) -> impl Iterator<Item = Face> + '_ {
        (0..self.fdart.len() as u32)
            .filter(|&i| self.fdart[i as usize] != NONE)
            .map(Face)
    }

    /// The graph distance (edges) from `from` to every vertex slot, by breadth-first search:
    /// `usize::MAX` for vertices in another component, for dead slots, and everywhere when
    /// `from` is not a live vertex. O(vertices + darts).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, Vert};
    /// let map = gen::grid(3, 3).map; // 4 x 4 vertices, row by row
    /// let d = map.distances(Vert::new(0));
    /// assert_eq!((d[0], d[1], d[5], d[15]), (0, 1, 2, 6));
    /// assert!(map.distances(Vert::new(99)).iter().all(|&x| x == usize::MAX));
    /// ```
    pub fn distances(&self, from: Vert) -> alloc::vec::Vec<usize> {
        let mut dist = alloc::vec![usize::MAX; self.vdart.len()];
        if !self.is_live_vertex(from) {
            return dist;
        }
        dist[from.index()] = 0;
        let mut queue = alloc::collections::VecDeque::from([from]);
        while let Some(v) = queue.pop_front() {
            let next = dist[v.index()] + 1;
            for d in self.vertex_darts(v) {
                let w = self.dest(d).index();
                if dist.get(w) == Some(&usize::MAX) {
                    dist[w] = next;
                    queue.push_back(Vert(w as u32));
                }
            }
        }
        dist
    }

    /// One boundary dart of each boundary loop (the loop's smallest dart).
    ///
    /// ```
    /// use zipmesh_kernel::Map;
    /// let map = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// assert_eq!(map.boundary_loops().len(), 1);
    /// ```
    pub fn boundary_loops(&self) -> alloc::vec::Vec<Dart> {
        let mut out = alloc::vec::Vec::new();
        for d in self.darts() {
            if self.is_boundary_dart(d) && self.face_cycle(d).all(|x| x >= d) {
                out.push(d);
            }
        }
        out
    }

    #[inline]
    fn live_or_none(&self, d: Dart) -> u32 {
        if self.is_live_dart(d) {
            d.0
        } else {
            NONE
        }
    }
}

/// Iterator over one orbit of darts: a face or boundary cycle (`next`) when `AROUND_VERTEX` is
/// false, the outgoing darts of a vertex clockwise (`rotate_cw`) when it is true. Stops after
/// returning to its start, at a dead dart, or after as many steps as there are dart slots.
///
/// ```
/// use zipmesh_kernel::{gen, Face, Vert};
/// let m = gen::torus_grid(3, 3).map;
/// assert_eq!(m.face_darts(Face::new(0)).count(), 4);
/// assert_eq!(m.vertex_darts(Vert::new(0)).count(), 4);
/// ```
#[derive(Clone, Debug)]
pub struct Orbit<'a, const AROUND_VERTEX: bool> {
    map: &'a Map,
    start: Dart,
    cur: u32,
    left: usize,
}

/// Iterator over a face or boundary cycle; see [`Map::face_cycle`].
pub type FaceDarts<'a> = Orbit<'a, false>;

/// Iterator over the outgoing darts of a vertex, clockwise; see [`Map::vertex_darts`].
pub type VertexDarts<'a> = Orbit<'a, true>;

impl<const AROUND_VERTEX: bool> Iterator for Orbit<'_, AROUND_VERTEX> {
    type Item = Dart;
    #[inline]
    fn next(&mut self) -> Option<Dart> {
        if self.cur == NONE || self.left == 0 {
            return None;
        }
        self.left -= 1;
        let d = Dart(self.cur);
        let n = if AROUND_VERTEX {
            self.map.rotate_cw(d)
        } else {
            self.map.next(d)
        };
        self.cur = if n == self.start { NONE } else { n.0 };
        Some(d)
    }
}
