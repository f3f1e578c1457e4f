//! Allocation of edges, vertices and faces in dead slots, and `compact()`.

use super::{Dart, Face, Map, Vert, NONE};
use alloc::vec;
use alloc::vec::Vec;

/// Old-to-new slot maps returned by [`Map::compact`]; `None` for a removed (dead) slot.
///
/// ```
/// let mut map = zipmesh_kernel::Map::from_polygons(4, &[[0u32, 2, 3]]).unwrap();
/// let c = map.compact();
/// assert_eq!(c.vertices.iter().filter(|v| v.is_some()).count(), 3);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Compaction {
    /// Per old dart slot, its new dart.
    pub darts: Vec<Option<Dart>>,
    /// Per old vertex slot, its new vertex.
    pub vertices: Vec<Option<Vert>>,
    /// Per old face slot, its new face.
    pub faces: Vec<Option<Face>>,
}

impl Map {
    /// Reserves room for at least `edges` more edges, `vertices` more vertices and `faces`
    /// more faces than the map has slots, so that edits adding that many do not reallocate.
    ///
    /// The map is unchanged (`==` to what it was) whatever the outcome. Without it, the first
    /// edit that adds an element to a freshly built or cloned map (whose arrays are full)
    /// copies every per-dart array once: on a million-face map that copy, and touching the
    /// fresh pages, cost more than the edit (`docs/benchmarks.md`, "What bounds the operator rows").
    ///
    /// # Errors
    /// When the allocator cannot give that much memory, or the sizes overflow; the map may
    /// then have reserved part of it.
    ///
    /// ```
    /// let mut map = zipmesh_kernel::gen::torus_grid(8, 8).map;
    /// let before = map.clone();
    /// map.reserve(100, 50, 50).unwrap();
    /// assert!(map.heap_bytes() >= before.heap_bytes() + 4 * (3 * 200 + 50 + 50));
    /// assert_eq!(map, before);
    /// assert!(map.reserve(usize::MAX, 0, 0).is_err());
    /// ```
    pub fn reserve(
        &mut self,
        edges: usize,
        vertices: usize,
        faces: usize,
    ) -> Result<(), alloc::collections::TryReserveError> {
        let darts = edges.saturating_mul(2);
        self.next.try_reserve(darts)?;
        self.vert.try_reserve(darts)?;
        self.face.try_reserve(darts)?;
        self.vdart.try_reserve(vertices)?;
        self.fdart.try_reserve(faces)
    }

    /// Removes every dead slot, keeping the order of live elements, and returns the
    /// old-to-new maps. Handles held before the call must be translated through them.
    ///
    /// ```
    /// use zipmesh_kernel::{Map, Vert};
    /// let mut map = Map::from_polygons(5, &[[0u32, 1, 4]]).unwrap();
    /// let c = map.compact();
    /// assert_eq!(c.vertices[4], Some(Vert::new(2)));
    /// assert_eq!(c.vertices[2], None);
    /// assert_eq!(map.vertex_slots(), 3);
    /// assert!(map.check().is_ok());
    /// ```
    pub fn compact(&mut self) -> Compaction {
        fn renumber(live: impl Iterator<Item = bool>) -> (Vec<u32>, u32) {
            let mut n = 0u32;
            let map = live
                .map(|l| {
                    if l {
                        n += 1;
                        n - 1
                    } else {
                        NONE
                    }
                })
                .collect();
            (map, n)
        }
        let (dmap, nd) = renumber(self.next.iter().map(|&n| n != NONE));
        let (vmap, _) = renumber(self.vdart.iter().map(|&d| d != NONE));
        let (fmap, _) = renumber(self.fdart.iter().map(|&d| d != NONE));
        let tr = |m: &[u32], x: u32| if x == NONE { NONE } else { m[x as usize] };
        let mut next = vec![NONE; nd as usize];
        let mut vert = vec![NONE; nd as usize];
        let mut face = vec![NONE; nd as usize];
        for (d, &nd) in dmap.iter().enumerate() {
            if nd != NONE {
                next[nd as usize] = dmap[self.next[d] as usize];
                vert[nd as usize] = tr(&vmap, self.vert[d]);
                face[nd as usize] = tr(&fmap, self.face[d]);
            }
        }
        let vdart = self
            .vdart
            .iter()
            .filter(|&&d| d != NONE)
            .map(|&d| dmap[d as usize])
            .collect();
        let fdart = self
            .fdart
            .iter()
            .filter(|&&d| d != NONE)
            .map(|&d| dmap[d as usize])
            .collect();
        *self = Map {
            next,
            vert,
            face,
            vdart,
            fdart,
            free_edges: Vec::new(),
            free_verts: Vec::new(),
            free_faces: Vec::new(),
        };
        Compaction {
            darts: opt(dmap, Dart),
            vertices: opt(vmap, Vert),
            faces: opt(fmap, Face),
        }
    }
}

fn opt<T>(m: Vec<u32>, f: fn(u32) -> T) -> Vec<Option<T>> {
    m.into_iter().map(|x| (x != NONE).then(|| f(x))).collect()
}

impl Map {
    /// A fresh edge: its two darts, with every field unset (`NONE`) for the caller to fill.
    #[allow(dead_code)]
    pub(crate) fn alloc_edge(&mut self) -> Dart {
        if let Some(e) = self.free_edges.pop() {
            Dart(2 * e)
        } else {
            let d = self.next.len() as u32;
            self.next.extend([NONE, NONE]);
            self.vert.extend([NONE, NONE]);
            self.face.extend([NONE, NONE]);
            Dart(d)
        }
    }

    /// A fresh vertex slot (its dart unset).
    #[allow(dead_code)]
    pub(crate) fn alloc_vert(&mut self) -> Vert {
        if let Some(v) = self.free_verts.pop() {
            Vert(v)
        } else {
            self.vdart.push(NONE);
            Vert(self.vdart.len() as u32 - 1)
        }
    }

    /// A fresh face slot (its dart unset).
    #[allow(dead_code)]
    pub(crate) fn alloc_face(&mut self) -> Face {
        if let Some(f) = self.free_faces.pop() {
            Face(f)
        } else {
            self.fdart.push(NONE);
            Face(self.fdart.len() as u32 - 1)
        }
    }

    /// Marks an edge dead and puts it on the free list.
    #[allow(dead_code)]
    pub(crate) fn free_edge(&mut self, d: Dart) {
        let e = d.0 & !1;
        for x in [e, e | 1] {
            self.next[x as usize] = NONE;
            self.vert[x as usize] = NONE;
            self.face[x as usize] = NONE;
        }
        self.free_edges.push(e / 2);
    }

    /// Marks a vertex dead.
    #[allow(dead_code)]
    pub(crate) fn free_vert(&mut self, v: Vert) {
        self.vdart[v.index()] = NONE;
        self.free_verts.push(v.0);
    }

    /// Marks a face dead.
    #[allow(dead_code)]
    pub(crate) fn free_face(&mut self, f: Face) {
        self.fdart[f.index()] = NONE;
        self.free_faces.push(f.0);
    }
}

/// The operators' writes: one entry of one array each. Callers have checked that the slots
/// are in range (live, or just allocated); the writes do not keep any axiom by themselves.
impl Map {
    /// Sets `next(d) = n`.
    #[inline]
    pub(crate) fn set_next(&mut self, d: Dart, n: Dart) {
        self.next[d.index()] = n.0;
    }

    /// Sets `origin(d) = v`.
    #[inline]
    pub(crate) fn set_origin(&mut self, d: Dart, v: Vert) {
        self.vert[d.index()] = v.0;
    }

    /// Sets `face(d) = f` (`None`: a boundary dart).
    #[inline]
    pub(crate) fn set_face(&mut self, d: Dart, f: impl Into<Option<Face>>) {
        self.face[d.index()] = f.into().map_or(NONE, |f| f.0);
    }

    /// Sets all three fields of dart `d`.
    #[inline]
    pub(crate) fn set_dart(
        &mut self,
        d: Dart,
        next: Dart,
        origin: Vert,
        f: impl Into<Option<Face>>,
    ) {
        self.set_next(d, next);
        self.set_origin(d, origin);
        self.set_face(d, f);
    }

    /// Sets the record of vertex `v` to `d`.
    #[inline]
    pub(crate) fn set_vertex_dart(&mut self, v: Vert, d: Dart) {
        self.vdart[v.index()] = d.0;
    }

    /// Sets the record of face `f` to `d` (nothing for a boundary loop: `None`, or the
    /// absent face `Face(NONE)` of a record).
    #[inline]
    pub(crate) fn set_face_dart(&mut self, f: impl Into<Option<Face>>, d: Dart) {
        if let Some(f) = f.into().filter(|f| f.0 != NONE) {
            self.fdart[f.index()] = d.0;
        }
    }
}
