//! Building a map from a polygon list, with a typed error for every defect of real files.

use super::{Map, NONE};
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

/// The most corners a polygon list may have: at most twice as many darts, and the
/// canonical code needs dart numbers below 2^31.
pub const MAX_CORNERS: usize = 1 << 30;

/// Why a polygon list does not describe an oriented manifold surface.
///
/// Face numbers are 0-based positions in the input list; vertex numbers are the input's
/// indices. The I/O layer turns face numbers into file lines.
///
/// ```
/// use zipmesh::{BuildError, Map};
/// let err = Map::from_polygons(3, &[[0u32, 1, 5]]).unwrap_err();
/// assert_eq!(err, BuildError::IndexOutOfRange { face: 0, vertex: 5, n_vertices: 3 });
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BuildError {
    /// A face has fewer than three corners.
    FaceTooSmall {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// A vertex appears twice in one face.
    RepeatedCorner {
        /// The face.
        face: usize,
        /// The repeated vertex.
        vertex: u32,
    },
    /// A corner names a vertex that does not exist.
    IndexOutOfRange {
        /// The face.
        face: usize,
        /// The index found.
        vertex: u32,
        /// The number of vertices.
        n_vertices: usize,
    },
    /// The edge `a`-`b` is used by three or more faces (the first three are given).
    NonManifoldEdge {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
        /// Three faces using it.
        faces: [usize; 3],
    },
    /// Two faces traverse the edge `a`-`b` in the same direction (`a` to `b`), so they
    /// disagree on orientation (or one face is repeated).
    InconsistentOrientation {
        /// Origin of both half-edges.
        a: u32,
        /// Destination of both half-edges.
        b: u32,
        /// The two faces.
        faces: [usize; 2],
    },
    /// The faces around a vertex form more than one fan (a pinched or "bow-tie" vertex).
    NonManifoldVertex {
        /// The vertex.
        vertex: u32,
        /// A face at that vertex.
        face: usize,
    },
    /// More corners or vertices than 32-bit handles can address.
    TooLarge {
        /// The number of corners.
        corners: usize,
    },
}

impl BuildError {
    /// The input face the error is about (the first, when several are involved).
    ///
    /// ```
    /// use zipmesh::{BuildError, Map};
    /// let err = Map::from_polygons(3, &[vec![0u32, 1, 2], vec![0, 1]]).unwrap_err();
    /// assert_eq!(err, BuildError::FaceTooSmall { face: 1, corners: 2 });
    /// assert_eq!(err.face(), Some(1));
    /// ```
    pub fn face(&self) -> Option<usize> {
        match *self {
            BuildError::FaceTooSmall { face, .. }
            | BuildError::RepeatedCorner { face, .. }
            | BuildError::IndexOutOfRange { face, .. }
            | BuildError::NonManifoldVertex { face, .. } => Some(face),
            BuildError::NonManifoldEdge { faces, .. } => Some(faces[2]),
            BuildError::InconsistentOrientation { faces, .. } => Some(faces[1]),
            BuildError::TooLarge { .. } => None,
        }
    }
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::FaceTooSmall { face, corners } => {
                write!(f, "face {face} has {corners} corners; at least 3 are needed")
            }
            BuildError::RepeatedCorner { face, vertex } => {
                write!(f, "face {face} uses vertex {vertex} twice")
            }
            BuildError::IndexOutOfRange { face, vertex, n_vertices } => write!(
                f,
                "face {face} refers to vertex {vertex}, but there are only {n_vertices} vertices"
            ),
            BuildError::NonManifoldEdge { a, b, faces } => write!(
                f,
                "edge {a}-{b} is used by three or more faces (faces {}, {} and {}): non-manifold edge",
                faces[0], faces[1], faces[2]
            ),
            BuildError::InconsistentOrientation { a, b, faces } => write!(
                f,
                "faces {} and {} both run from vertex {a} to vertex {b}: their orientations disagree",
                faces[0], faces[1]
            ),
            BuildError::NonManifoldVertex { vertex, face } => write!(
                f,
                "the faces around vertex {vertex} (face {face} among them) form more than one fan: non-manifold vertex"
            ),
            BuildError::TooLarge { corners } => {
                write!(f, "{corners} corners exceed the 32-bit handle range")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for BuildError {}

/// What a successful build found besides the map.
///
/// ```
/// let (_, report) = zipmesh::Map::from_polygons_with_report(4, &[[0u32, 1, 2]]).unwrap();
/// assert_eq!(report.unreferenced, vec![zipmesh::Vert::new(3)]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BuildReport {
    /// Vertices no face refers to. They are dropped from the topology: their slots stay
    /// dead (so every other vertex keeps its input number) and are reused by later edits.
    pub unreferenced: Vec<super::Vert>,
}

/// `n` unset entries with room for edits: operators that add elements (splits) then grow
/// the arrays in place instead of copying a whole large map on the first edit. The room is
/// n/32 + 64 entries (3% more memory).
fn with_room(n: usize) -> Vec<u32> {
    let mut v = Vec::with_capacity(n + n / 32 + 64);
    v.resize(n, NONE);
    v
}

impl Map {
    /// Builds a map from polygons given as vertex indices in counter-clockwise order.
    ///
    /// Vertex `i` of the input becomes `Vert::new(i)`; vertices no face uses become dead slots
    /// (see [`Map::from_polygons_with_report`]). Runs in O(corners) time plus a sort of the
    /// corners of any vertex with more than 16 incident half-edges.
    ///
    /// ```
    /// use zipmesh::{BuildError, Map};
    /// let quad = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// assert_eq!(quad.num_faces(), 1);
    /// let bad = Map::from_polygons(4, &[[0u32, 1, 2], [0, 1, 3]]);
    /// assert!(matches!(bad, Err(BuildError::InconsistentOrientation { .. })));
    /// ```
    pub fn from_polygons<F: AsRef<[u32]>>(
        n_vertices: usize,
        faces: &[F],
    ) -> Result<Map, BuildError> {
        Self::from_polygons_with_report(n_vertices, faces).map(|(m, _)| m)
    }

    /// Like [`Map::from_polygons`], also reporting the unreferenced vertices.
    ///
    /// ```
    /// use zipmesh::{Map, Vert};
    /// let (map, report) = Map::from_polygons_with_report(5, &[[0u32, 1, 3]]).unwrap();
    /// assert_eq!(report.unreferenced, vec![Vert::new(2), Vert::new(4)]);
    /// assert!(!map.is_live_vertex(Vert::new(2)));
    /// ```
    pub fn from_polygons_with_report<F: AsRef<[u32]>>(
        n_vertices: usize,
        faces: &[F],
    ) -> Result<(Map, BuildReport), BuildError> {
        let total: usize = faces.iter().map(|f| f.as_ref().len()).sum();
        let mut corners = Vec::with_capacity(total);
        let mut offsets = Vec::with_capacity(faces.len() + 1);
        offsets.push(0u32);
        for f in faces {
            corners.extend_from_slice(f.as_ref());
            if corners.len() > MAX_CORNERS {
                return Err(BuildError::TooLarge { corners: total });
            }
            offsets.push(corners.len() as u32);
        }
        Self::from_flat_polygons(n_vertices, &corners, &offsets)
    }

    /// Builds a map from a flat corner list: face `f` is `corners[offsets[f]..offsets[f+1]]`.
    ///
    /// `offsets` must start at 0, be non-decreasing and end at `corners.len()`; otherwise
    /// the faces it does describe are checked as usual and a bad offset is reported as a
    /// face with too few corners.
    ///
    /// ```
    /// use zipmesh::Map;
    /// let (map, _) = Map::from_flat_polygons(4, &[0, 1, 2, 0, 2, 3], &[0, 3, 6]).unwrap();
    /// assert_eq!(map.num_faces(), 2);
    /// ```
    pub fn from_flat_polygons(
        n_vertices: usize,
        corners: &[u32],
        offsets: &[u32],
    ) -> Result<(Map, BuildReport), BuildError> {
        let h_count = corners.len();
        if h_count > MAX_CORNERS || n_vertices >= NONE as usize {
            return Err(BuildError::TooLarge { corners: h_count });
        }
        let n_faces = offsets.len().saturating_sub(1);
        // Validate every face and record each half-edge's destination.
        let mut hdest = vec![0u32; h_count];
        if offsets.first().is_some_and(|&o| o != 0) || (n_faces == 0 && h_count != 0) {
            return Err(BuildError::FaceTooSmall {
                face: 0,
                corners: 0,
            });
        }
        let mut scratch: Vec<u32> = Vec::new();
        for f in 0..n_faces {
            let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
            if e < s || e > h_count || e - s < 3 {
                return Err(BuildError::FaceTooSmall {
                    face: f,
                    corners: e.saturating_sub(s),
                });
            }
            let poly = &corners[s..e];
            if let Some(&v) = poly.iter().find(|&&v| v as usize >= n_vertices) {
                return Err(BuildError::IndexOutOfRange {
                    face: f,
                    vertex: v,
                    n_vertices,
                });
            }
            if let Some(v) = repeated(poly, &mut scratch) {
                return Err(BuildError::RepeatedCorner { face: f, vertex: v });
            }
            hdest[s..e - 1].copy_from_slice(&poly[1..]);
            hdest[e - 1] = poly[0];
        }
        if offsets.last().is_some_and(|&o| o as usize != h_count) {
            return Err(BuildError::FaceTooSmall {
                face: n_faces,
                corners: 0,
            });
        }

        // The face of a half-edge, for error reports only.
        let face_of = |h: usize| {
            offsets
                .partition_point(|&o| o as usize <= h)
                .saturating_sub(1)
        };
        // Bucket half-edges by their smaller end (counting sort), the larger end packed beside
        // each, then pair every half-edge with the other one of its edge.
        let mut start = vec![0u32; n_vertices + 1];
        for (&a, &b) in corners.iter().zip(&hdest) {
            start[a.min(b) as usize + 1] += 1;
        }
        for v in 0..n_vertices {
            start[v + 1] += start[v];
        }
        let mut bucket = vec![0u64; h_count];
        for (h, (&a, &b)) in corners.iter().zip(&hdest).enumerate() {
            let lo = a.min(b) as usize;
            bucket[start[lo] as usize] = u64::from(a.max(b)) << 32 | h as u64;
            start[lo] += 1;
        }
        // Now start[v] is the end of v's bucket (and the beginning of v + 1's).
        // mate[h]: the other half-edge of h's edge, or h itself on the boundary. It reuses
        // the destination array, which is not read again.
        let mut mate = hdest;
        mate.fill(NONE);
        let mut n_boundary = 0usize;
        for v in 0..n_vertices {
            let begin = if v == 0 { 0 } else { start[v - 1] as usize };
            let b = &mut bucket[begin..start[v] as usize];
            // Small buckets are scanned; large ones sorted so that equal ends are adjacent.
            let sorted = b.len() > 16;
            if sorted {
                b.sort_unstable();
            }
            for i in 0..b.len() {
                let (hi, h1) = ((b[i] >> 32) as u32, b[i] as u32 as usize);
                if mate[h1] != NONE {
                    continue;
                }
                let mut found = [NONE; 2];
                let mut k = 0;
                let end = if sorted { b.len().min(i + 4) } else { b.len() };
                for &x in &b[i + 1..end] {
                    if (x >> 32) as u32 == hi {
                        if k < 2 {
                            found[k] = x as u32;
                        }
                        k += 1;
                    }
                }
                match k {
                    0 => {
                        mate[h1] = h1 as u32;
                        n_boundary += 1;
                    }
                    1 => {
                        let h2 = found[0] as usize;
                        if corners[h1] == corners[h2] {
                            let mut faces = [face_of(h1), face_of(h2)];
                            faces.sort_unstable();
                            return Err(BuildError::InconsistentOrientation {
                                a: corners[h1],
                                b: if corners[h1] == v as u32 {
                                    hi
                                } else {
                                    v as u32
                                },
                                faces,
                            });
                        }
                        mate[h1] = h2 as u32;
                        mate[h2] = h1 as u32;
                    }
                    _ => {
                        let mut faces = [
                            face_of(h1),
                            face_of(found[0] as usize),
                            face_of(found[1] as usize),
                        ];
                        faces.sort_unstable();
                        return Err(BuildError::NonManifoldEdge {
                            a: v as u32,
                            b: hi,
                            faces,
                        });
                    }
                }
            }
        }
        drop(bucket);
        drop(start);
        // Number edges in face order, so that the darts of a face sit close together in memory.
        // In place: a set top bit marks a slot that already holds its dart (a mate always
        // comes after its half-edge, and corners are below 2^30, so the bit is free).
        const DONE: u32 = 1 << 31;
        let mut dart_of = mate;
        let mut n_edges = 0u32;
        for h in 0..h_count {
            let m = dart_of[h];
            if m & DONE == 0 {
                dart_of[h] = DONE | (2 * n_edges);
                if m as usize != h {
                    dart_of[m as usize] = DONE | (2 * n_edges + 1);
                }
                n_edges += 1;
            }
        }
        for d in &mut dart_of {
            *d &= !DONE;
        }

        let n_darts = 2 * n_edges as usize;
        let mut map = Map {
            next: with_room(n_darts),
            vert: with_room(n_darts),
            face: with_room(n_darts),
            vdart: with_room(n_vertices),
            fdart: with_room(n_faces),
            free_edges: Vec::new(),
            free_verts: Vec::new(),
            free_faces: Vec::new(),
        };
        let mut out_deg = vec![0u32; n_vertices];
        for f in 0..n_faces {
            let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
            // The first corner's dart, so that faces read back in their input order.
            map.fdart[f] = dart_of[s];
            for h in s..e {
                let d = dart_of[h] as usize;
                let a = corners[h];
                map.next[d] = dart_of[if h + 1 == e { s } else { h + 1 }];
                map.vert[d] = a;
                map.face[d] = f as u32;
                map.vdart[a as usize] = d as u32;
                out_deg[a as usize] += 1;
            }
        }
        if n_boundary > 0 {
            // Boundary darts: origin is the face dart's destination; each vertex may own one.
            let mut boundary_out = vec![NONE; n_vertices];
            for (h, &d) in dart_of.iter().enumerate() {
                let t = (d ^ 1) as usize;
                if map.vert[t] == NONE {
                    let b = map.vert[map.next[d as usize] as usize];
                    map.vert[t] = b;
                    if boundary_out[b as usize] != NONE {
                        return Err(BuildError::NonManifoldVertex {
                            vertex: b,
                            face: face_of(h),
                        });
                    }
                    boundary_out[b as usize] = t as u32;
                    out_deg[b as usize] += 1;
                }
            }
            for h in 0..h_count {
                let t = (dart_of[h] ^ 1) as usize;
                if map.next[t] == NONE {
                    map.next[t] = boundary_out[corners[h] as usize];
                }
            }
            for (v, &t) in boundary_out.iter().enumerate() {
                if t != NONE {
                    map.vdart[v] = t;
                }
            }
        }
        // One fan per vertex: the rotation from vdart must visit every outgoing dart.
        for (v, &want) in out_deg.iter().enumerate() {
            let d0 = map.vdart[v];
            if d0 == NONE {
                continue;
            }
            let mut d = d0;
            let mut seen = 0u32;
            loop {
                seen += 1;
                d = map.next[(d ^ 1) as usize];
                if d == d0 || seen > want {
                    break;
                }
            }
            if seen != want {
                let face = map.face[d0 as usize];
                let face = if face == NONE {
                    map.face[(d0 ^ 1) as usize]
                } else {
                    face
                };
                return Err(BuildError::NonManifoldVertex {
                    vertex: v as u32,
                    face: face as usize,
                });
            }
        }
        let mut report = BuildReport::default();
        for v in (0..n_vertices).rev() {
            if map.vdart[v] == NONE {
                map.free_verts.push(v as u32);
            }
        }
        report.unreferenced = map
            .free_verts
            .iter()
            .rev()
            .map(|&v| super::Vert(v))
            .collect();
        Ok((map, report))
    }
}

/// The first vertex repeated in `poly`, if any.
#[inline]
fn repeated(poly: &[u32], scratch: &mut Vec<u32>) -> Option<u32> {
    // Triangles and quads, the common case, without loops; same answer as the general scan.
    if let &[a, b, c, d] = poly {
        return if b == a {
            Some(b)
        } else if c == a || c == b {
            Some(c)
        } else if d == a || d == b || d == c {
            Some(d)
        } else {
            None
        };
    }
    if let &[a, b, c] = poly {
        return if b == a {
            Some(b)
        } else if c == a || c == b {
            Some(c)
        } else {
            None
        };
    }
    if poly.len() <= 12 {
        for i in 1..poly.len() {
            if poly[..i].contains(&poly[i]) {
                return Some(poly[i]);
            }
        }
        None
    } else {
        scratch.clear();
        scratch.extend_from_slice(poly);
        scratch.sort_unstable();
        scratch.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
    }
}
