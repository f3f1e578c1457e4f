//! Building a map from a polygon list, with a typed error for every defect of real files.

use super::{Map, NONE};
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;
use hashbrown::hash_map::{Entry, HashMap};

/// The most corners a polygon list may have: at most twice as many darts, and the
/// canonical code needs dart numbers below 2^31.
pub const MAX_CORNERS: usize = 1 << 30;

/// Why a polygon list does not describe an oriented manifold surface.
///
/// Face numbers are 0-based positions in the input list; vertex numbers are the input's
/// indices. The I/O layer turns face numbers into file lines.
///
/// ```
/// use zipmesh_kernel::{BuildError, Map};
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
    /// use zipmesh_kernel::{BuildError, Map};
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
/// let (_, report) = zipmesh_kernel::Map::from_polygons_with_report(4, &[[0u32, 1, 2]]).unwrap();
/// assert_eq!(report.unreferenced, vec![zipmesh_kernel::Vert::new(3)]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BuildReport {
    /// Vertices no face refers to. They are dropped from the topology: their slots stay
    /// dead (so every other vertex keeps its input number) and are reused by later edits.
    pub unreferenced: Vec<super::Vert>,
}

/// The capacity of an array of `n` entries with room for edits: operators that add elements
/// (splits) then grow the arrays in place instead of copying a whole large map on the first
/// edit. The room is n/32 + 64 entries (3% more memory).
fn room(n: usize) -> usize {
    n + n / 32 + 64
}

/// Edge lists longer than this are not scanned; their edges are looked up in a map.
const SCAN_MAX: usize = 16;

impl Map {
    /// Builds a map from polygons given as vertex indices in counter-clockwise order.
    ///
    /// Vertex `i` of the input becomes `Vert::new(i)`; vertices no face uses become dead slots
    /// (see [`Map::from_polygons_with_report`]). Runs in O(corners) expected time (the edges
    /// at a vertex with more than 32 half-edges, and some boundary edges, go to a hash map);
    /// a non-manifold or misoriented edge also costs a sort of the half-edges, to report the
    /// first one.
    ///
    /// ```
    /// use zipmesh_kernel::{BuildError, Map};
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
    /// use zipmesh_kernel::{Map, Vert};
    /// let (map, report) = Map::from_polygons_with_report(5, &[[0u32, 1, 3]]).unwrap();
    /// assert_eq!(report.unreferenced, vec![Vert::new(2), Vert::new(4)]);
    /// assert!(!map.is_live_vertex(Vert::new(2)));
    /// ```
    pub fn from_polygons_with_report<F: AsRef<[u32]>>(
        n_vertices: usize,
        faces: &[F],
    ) -> Result<(Map, BuildReport), BuildError> {
        let total = faces
            .iter()
            .fold(0usize, |t, f| t.saturating_add(f.as_ref().len()));
        if total > MAX_CORNERS || n_vertices >= NONE as usize {
            return Err(BuildError::TooLarge { corners: total });
        }
        build(n_vertices, faces)
    }

    /// Builds a map from a flat corner list: face `f` is `corners[offsets[f]..offsets[f+1]]`.
    ///
    /// `offsets` must start at 0, be non-decreasing and end at `corners.len()`; otherwise
    /// the faces it does describe are checked as usual and a bad offset is reported as a
    /// face with too few corners.
    ///
    /// ```
    /// use zipmesh_kernel::Map;
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
        let flat = Flat { corners, offsets };
        if offsets.first().is_some_and(|&o| o != 0) || (flat.count() == 0 && h_count != 0) {
            return Err(BuildError::FaceTooSmall {
                face: 0,
                corners: 0,
            });
        }
        build(n_vertices, &flat)
    }
}

/// The input faces: a slice of polygons, or a flat corner list with offsets.
trait Polygons {
    /// The number of faces.
    fn count(&self) -> usize;
    /// Face `f`, or the error its offsets give (flat lists only).
    fn checked(&self, f: usize) -> Result<&[u32], BuildError>;
    /// An error found only after every face was checked (a flat list's last offset).
    fn check_end(&self) -> Result<(), BuildError>;
    /// Face `f` of a list that passed both checks.
    fn face(&self, f: usize) -> &[u32];
}

impl<F: AsRef<[u32]>> Polygons for [F] {
    fn count(&self) -> usize {
        self.len()
    }
    fn checked(&self, f: usize) -> Result<&[u32], BuildError> {
        Ok(self[f].as_ref())
    }
    fn check_end(&self) -> Result<(), BuildError> {
        Ok(())
    }
    #[inline]
    fn face(&self, f: usize) -> &[u32] {
        self[f].as_ref()
    }
}

/// `Map::from_flat_polygons`' input.
struct Flat<'a> {
    corners: &'a [u32],
    offsets: &'a [u32],
}

impl Polygons for Flat<'_> {
    fn count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }
    fn checked(&self, f: usize) -> Result<&[u32], BuildError> {
        let (s, e) = (self.offsets[f] as usize, self.offsets[f + 1] as usize);
        self.corners.get(s..e).ok_or(BuildError::FaceTooSmall {
            face: f,
            corners: e.saturating_sub(s),
        })
    }
    fn check_end(&self) -> Result<(), BuildError> {
        match self.offsets.last() {
            Some(&o) if o as usize != self.corners.len() => Err(BuildError::FaceTooSmall {
                face: self.count(),
                corners: 0,
            }),
            _ => Ok(()),
        }
    }
    #[inline]
    fn face(&self, f: usize) -> &[u32] {
        self.checked(f).unwrap_or(&[])
    }
}

/// The build after the size checks. Two passes over the corners, each writing only what
/// it keeps: check the faces and count the half-edges at each edge's smaller end; then,
/// face by face, find each half-edge's edge in its smaller end's list or number a new one
/// there, and write the darts. Last, link the boundary and check every vertex's fan.
fn build<P: Polygons + ?Sized>(
    n_vertices: usize,
    polys: &P,
) -> Result<(Map, BuildReport), BuildError> {
    let mut begin = count_corners(n_vertices, polys)?;
    polys.check_end()?;
    let mut vdart = Vec::with_capacity(room(n_vertices));
    // A closed surface has two half-edges per edge, so half as many entries as half-edges
    // (rounded up) hold every list; a boundary's edges overflow into the map.
    let (mut corners, mut sum) = (0usize, 0u32);
    for v in 0..n_vertices {
        let d = begin[v + 1];
        corners += d as usize;
        sum += d.div_ceil(2);
        begin[v + 1] = sum;
        vdart.push(NONE);
    }
    let mut out = Darts::new(corners, polys.count(), vdart);
    let mut edges = Edges {
        slot: vec![0u32; sum as usize],
        begin,
        more: HashMap::new(),
    };
    out.add_faces(polys, &mut edges)?;
    drop(edges);
    out.finish()
}

/// Checks every face in input order and counts, for each vertex `v`, the half-edges whose
/// smaller end it is in `count[v + 1]`.
fn count_corners<P: Polygons + ?Sized>(
    n_vertices: usize,
    polys: &P,
) -> Result<Vec<u32>, BuildError> {
    let mut count = vec![0u32; n_vertices + 1];
    let mut scratch = Vec::new();
    for f in 0..polys.count() {
        let poly = polys.checked(f)?;
        if poly.len() < 3 {
            return Err(BuildError::FaceTooSmall {
                face: f,
                corners: poly.len(),
            });
        }
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
        let mut a = poly[poly.len() - 1];
        for &b in poly {
            count[a.min(b) as usize + 1] += 1;
            a = b;
        }
    }
    Ok(count)
}

/// The edges numbered so far, by smaller end. An edge's first half-edge is its even dart,
/// so its ends are that dart's origin and the odd dart's (`vert`).
struct Edges {
    /// Vertex `v` owns `slot[begin[v]..begin[v + 1]]`: half an entry per half-edge whose
    /// smaller end it is, rounded up.
    begin: Vec<u32>,
    /// Per edge whose smaller end the vertex is, `(edge + 1) << 1 | TWINNED`; then zeros.
    slot: Vec<u32>,
    /// The edges that did not fit, and all edges of vertices with more than `SCAN_MAX`
    /// entries (which then cost no scan of all of them per corner), by (smaller end,
    /// larger end), with the same bit.
    more: HashMap<(u32, u32), u32>,
}

/// In an edge's entry: a second half-edge took its odd dart, so a third one is an error.
/// Edges are below 2^30 (at most one per corner), so the shifted number fits.
const TWINNED: u32 = 1;

impl Edges {
    /// The entry of the edge `a`-`b`, or a new one numbered `new` (then `Err`). The entry
    /// is returned with its `TWINNED` bit as found, and that bit is set in the table.
    #[inline(always)]
    fn find_or_add(&mut self, a: u32, b: u32, vert: &[u32], new: u32) -> Result<u32, ()> {
        let (lo, hi) = (a.min(b), a.max(b));
        let (s, e) = (
            self.begin[lo as usize] as usize,
            self.begin[lo as usize + 1] as usize,
        );
        if let Some(list) = self.slot.get_mut(s..e).filter(|l| l.len() <= SCAN_MAX) {
            for x in list {
                if *x == 0 {
                    *x = (new + 1) << 1;
                    return Err(());
                }
                let edge = 2 * ((*x >> 1) - 1) as usize;
                // One end is lo, so this is the other.
                if vert
                    .get(edge..edge + 2)
                    .is_some_and(|v| v[0] ^ v[1] ^ lo == hi)
                {
                    let found = *x;
                    *x |= TWINNED;
                    return Ok(found);
                }
            }
        }
        self.find_or_add_more(lo, hi, new)
    }

    /// `find_or_add` in the map.
    #[cold]
    #[inline(never)]
    fn find_or_add_more(&mut self, lo: u32, hi: u32, new: u32) -> Result<u32, ()> {
        match self.more.entry((lo, hi)) {
            Entry::Occupied(mut x) => {
                let found = *x.get();
                *x.get_mut() |= TWINNED;
                Ok(found)
            }
            Entry::Vacant(x) => {
                x.insert((new + 1) << 1);
                Err(())
            }
        }
    }
}

/// The map's arrays while the faces come in, in dart order: a new edge takes both darts,
/// and its second half-edge fills in the odd dart's `next` and face later.
struct Darts {
    next: Vec<u32>,
    vert: Vec<u32>,
    face: Vec<u32>,
    fdart: Vec<u32>,
    vdart: Vec<u32>,
    /// The number of corners: as many darts as that means no boundary.
    h_count: usize,
}

impl Darts {
    fn new(h_count: usize, n_faces: usize, vdart: Vec<u32>) -> Darts {
        // A closed surface has one dart per corner; a boundary adds one per boundary edge.
        Darts {
            next: vec![0; room(h_count)],
            vert: vec![0; room(h_count)],
            face: vec![0; room(h_count)],
            fdart: Vec::with_capacity(room(n_faces)),
            vdart,
            h_count,
        }
    }

    /// Every face, in input order: a dart per corner (the odd dart of an edge first met the
    /// other way, else the even dart of a new edge) with its arrays. A directed edge met
    /// twice, or an edge met a third time, gives the first bad edge's error. The arrays are
    /// locals in the loop so that their lengths stay in registers.
    fn add_faces<P: Polygons + ?Sized>(
        &mut self,
        polys: &P,
        edges: &mut Edges,
    ) -> Result<(), BuildError> {
        let mut next = core::mem::take(&mut self.next);
        let mut vert = core::mem::take(&mut self.vert);
        let mut face = core::mem::take(&mut self.face);
        let mut vdart = core::mem::take(&mut self.vdart);
        let mut fdart = core::mem::take(&mut self.fdart);
        let (mut n, mut result) = (0usize, Ok(()));
        'faces: for f in 0..polys.count() {
            let poly = polys.face(f);
            let (mut first, mut prev) = (NONE, NONE);
            for (i, &a) in poly.iter().enumerate() {
                if a as usize >= vdart.len() {
                    // Only if a face reads differently now (an `AsRef` that changes).
                    let n_vertices = vdart.len();
                    result = Err(BuildError::IndexOutOfRange {
                        face: f,
                        vertex: a,
                        n_vertices,
                    });
                    break 'faces;
                }
                let b = poly.get(i + 1).copied().unwrap_or(poly[0]);
                let d = match edges.find_or_add(a, b, &vert[..n], (n / 2) as u32) {
                    Ok(entry) => {
                        let d = ((entry >> 1) - 1) as usize * 2 + 1;
                        // Met the same way (the odd dart leaves the other end), or a third time.
                        if entry & TWINNED != 0 || vert[d] == b {
                            // The first bad edge in the documented order; the one met is a
                            // fallback that the search never needs.
                            let (lo, hi) = (a.min(b), a.max(b));
                            let met = BuildError::NonManifoldEdge {
                                a: lo,
                                b: hi,
                                faces: [f; 3],
                            };
                            result = Err(pairing_error(polys).unwrap_or(met));
                            break 'faces;
                        }
                        face[d] = f as u32;
                        d
                    }
                    Err(()) => {
                        if n + 2 > next.len().min(vert.len()).min(face.len()) {
                            grow(&mut [&mut next, &mut vert, &mut face], n + 2);
                        }
                        // The even dart's `next` comes with the face's next corner, the odd
                        // dart's with its own face or the boundary.
                        (vert[n], vert[n + 1]) = (a, b);
                        (face[n], face[n + 1]) = (f as u32, NONE);
                        n += 2;
                        n - 2
                    }
                };
                vdart[a as usize] = d as u32;
                match prev {
                    NONE => first = d as u32,
                    p => next[p as usize] = d as u32,
                }
                prev = d as u32;
            }
            if let Some(last) = next.get_mut(prev as usize) {
                *last = first;
            }
            fdart.push(first);
        }
        for a in [&mut next, &mut vert, &mut face] {
            a.truncate(n);
        }
        (self.next, self.vert, self.face) = (next, vert, face);
        (self.vdart, self.fdart) = (vdart, fdart);
        result
    }

    /// Links the boundary loops, checks every vertex's fan and gives the map.
    fn finish(mut self) -> Result<(Map, BuildReport), BuildError> {
        self.link_boundary()?;
        self.check_fans()?;
        let n_darts = self.next.len();
        for a in [&mut self.next, &mut self.vert, &mut self.face] {
            if a.capacity() > room(n_darts) {
                a.shrink_to(room(n_darts));
            } else {
                a.reserve_exact(room(n_darts) - n_darts);
            }
        }
        let mut free_verts = Vec::new();
        for v in (0..self.vdart.len()).rev() {
            if self.vdart[v] == NONE {
                free_verts.push(v as u32);
            }
        }
        let report = BuildReport {
            unreferenced: free_verts.iter().rev().map(|&v| super::Vert(v)).collect(),
        };
        let map = Map {
            next: self.next,
            vert: self.vert,
            face: self.face,
            vdart: self.vdart,
            fdart: self.fdart,
            free_edges: Vec::new(),
            free_verts,
            free_faces: Vec::new(),
        };
        Ok((map, report))
    }

    /// The boundary: an edge whose odd dart no face took. Each boundary dart leaves its
    /// edge's destination, follows the boundary dart leaving its own destination, and is
    /// its origin's record; a second one leaving a vertex is a pinched vertex (the first in
    /// edge order is reported).
    fn link_boundary(&mut self) -> Result<(), BuildError> {
        if self.next.len() == self.h_count {
            return Ok(());
        }
        let mut boundary_out = vec![NONE; self.vdart.len()];
        let mut boundary = Vec::new();
        for t in (1..self.next.len()).step_by(2) {
            if self.face[t] == NONE {
                let b = self.vert[t] as usize;
                if boundary_out[b] != NONE {
                    return Err(BuildError::NonManifoldVertex {
                        vertex: b as u32,
                        face: self.face[t - 1] as usize,
                    });
                }
                boundary_out[b] = t as u32;
                boundary.push(t);
            }
        }
        for &t in &boundary {
            let a = self.vert[t - 1];
            self.next[t] = boundary_out[a as usize];
            self.vdart[self.vert[t] as usize] = t as u32;
        }
        Ok(())
    }

    /// One fan per vertex: the rotation from each record visits every dart leaving the
    /// vertex. Rotations of distinct vertices are disjoint and each stays among its
    /// vertex's darts, so all are whole exactly when their lengths add up to the darts;
    /// only then is the first vertex with a broken fan looked for, by counting.
    fn check_fans(&self) -> Result<(), BuildError> {
        let n_darts = self.next.len();
        let mut seen = 0usize;
        for &d0 in &self.vdart {
            if d0 == NONE {
                continue;
            }
            let mut d = d0;
            loop {
                seen += 1;
                d = self.next.get((d ^ 1) as usize).copied().unwrap_or(d0);
                if d == d0 || seen > n_darts {
                    break;
                }
            }
        }
        if seen == n_darts {
            return Ok(());
        }
        let mut out_deg = vec![0u32; self.vdart.len()];
        for &v in &self.vert {
            out_deg[v as usize] += 1;
        }
        for (v, &d0) in self.vdart.iter().enumerate() {
            if d0 != NONE && !whole_fan(&self.next, d0, out_deg[v]) {
                let face = match self.face[d0 as usize] {
                    NONE => self.face[(d0 ^ 1) as usize],
                    f => f,
                };
                return Err(BuildError::NonManifoldVertex {
                    vertex: v as u32,
                    face: face as usize,
                });
            }
        }
        Ok(())
    }
}

/// Lengthens the arrays to at least `len`, doubling (a boundary: more darts than corners).
#[cold]
fn grow(arrays: &mut [&mut Vec<u32>], len: usize) {
    for a in arrays {
        let new_len = len.max(2 * a.len());
        a.resize(new_len, 0);
    }
}

/// Whether the rotation from `d0` (`next` of the twin, the darts leaving `d0`'s origin)
/// visits exactly `want` darts before it returns.
fn whole_fan(next: &[u32], d0: u32, want: u32) -> bool {
    let mut d = d0;
    let mut seen = 0u32;
    loop {
        seen += 1;
        match next.get((d ^ 1) as usize) {
            Some(&n) => d = n,
            None => return false,
        }
        if d == d0 || seen > want {
            return seen == want && d == d0;
        }
    }
}

/// The error of the first bad edge when some directed edge occurs twice. The half-edges are
/// grouped by their two ends; a group is bad with three or more members, or two running the
/// same way. Groups are taken by smaller end, then, among those of one smaller end, by first
/// half-edge, or by larger end when that end has more than 16 half-edges: the order in which
/// the sorting builder (up to ec3658c) met them, kept so that a file reports the same error.
/// Runs only on such input; `None` if there is no bad group (never, given a repeated
/// directed edge).
fn pairing_error<P: Polygons + ?Sized>(polys: &P) -> Option<BuildError> {
    // (smaller end, larger end, half-edge, face, origin)
    let mut half: Vec<(u32, u32, u32, usize, u32)> = Vec::new();
    for f in 0..polys.count() {
        let poly = polys.face(f);
        for (i, &a) in poly.iter().enumerate() {
            let b = poly.get(i + 1).copied().unwrap_or(poly[0]);
            half.push((a.min(b), a.max(b), half.len() as u32, f, a));
        }
    }
    half.sort_unstable();
    for bucket in half.chunk_by(|x, y| x.0 == y.0) {
        let by_end = bucket.len() > 16;
        let bad = bucket
            .chunk_by(|x, y| x.1 == y.1)
            .filter(|g| g.len() > 2 || (g.len() == 2 && g[0].4 == g[1].4))
            .min_by_key(|g| if by_end { g[0].1 } else { g[0].2 });
        match bad {
            Some([p, q, r, ..]) => {
                return Some(BuildError::NonManifoldEdge {
                    a: p.0,
                    b: p.1,
                    faces: [p.3, q.3, r.3],
                })
            }
            Some([p, q]) => {
                return Some(BuildError::InconsistentOrientation {
                    a: p.4,
                    b: if p.4 == p.0 { p.1 } else { p.0 },
                    faces: [p.3, q.3],
                })
            }
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests;

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
