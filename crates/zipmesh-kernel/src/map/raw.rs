//! Building a map directly from its dart permutations (used by the exhaustive enumeration
//! in `proofs/`, the fuzzers, and [`Map::mirror`]).

use super::{Map, NONE};
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

/// Why a pair (`next`, boundary marks) does not describe a valid map.
///
/// ```
/// use zipmesh_kernel::{Map, RawError};
/// // Both darts of the only edge marked boundary: an edge without a face.
/// assert_eq!(Map::from_permutation(&[1, 0], &[true, true]), Err(RawError::FacelessEdge));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RawError {
    /// The number of darts is odd, the arrays differ in length, or it exceeds the handle range.
    Size,
    /// `next` is not a permutation of the darts.
    NotPermutation,
    /// The boundary mark is not constant along a `next` cycle.
    MixedCycle,
    /// An edge has boundary marks on both darts (no face on either side).
    FacelessEdge,
    /// A vertex would have two outgoing boundary darts (a pinched boundary).
    PinchedBoundary,
}

impl fmt::Display for RawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            RawError::Size => "odd or mismatched dart count",
            RawError::NotPermutation => "next is not a permutation",
            RawError::MixedCycle => "boundary mark not constant on a next cycle",
            RawError::FacelessEdge => "edge with no face on either side",
            RawError::PinchedBoundary => "vertex with two outgoing boundary darts",
        })
    }
}

#[cfg(feature = "std")]
impl std::error::Error for RawError {}

impl Map {
    /// Builds the map whose darts are `0..next.len()`, with `twin(d) = d ^ 1`, the given
    /// `next` permutation, and `boundary[d]` marking boundary darts.
    ///
    /// Vertices are the orbits of `next ∘ twin` and faces the unmarked `next` cycles, each
    /// numbered in the order of its smallest dart. Every valid map arises this way, which is
    /// what the exhaustive checks in `proofs/` enumerate.
    ///
    /// ```
    /// use zipmesh_kernel::Map;
    /// // One triangle: darts 0, 2, 4 run around the face, 1, 5, 3 around the boundary.
    /// let next = [2, 5, 4, 1, 0, 3];
    /// let boundary = [false, true, false, true, false, true];
    /// let map = Map::from_permutation(&next, &boundary).unwrap();
    /// assert_eq!((map.num_vertices(), map.num_faces()), (3, 1));
    /// assert!(map.check().is_ok());
    /// ```
    pub fn from_permutation(next: &[u32], boundary: &[bool]) -> Result<Map, RawError> {
        let nd = next.len();
        if nd % 2 != 0 || boundary.len() != nd || nd > 2 * super::build::MAX_CORNERS {
            return Err(RawError::Size);
        }
        let mut seen = vec![false; nd];
        for &n in next {
            if n as usize >= nd || seen[n as usize] {
                return Err(RawError::NotPermutation);
            }
            seen[n as usize] = true;
        }
        for d in 0..nd {
            if boundary[d] != boundary[next[d] as usize] {
                return Err(RawError::MixedCycle);
            }
            if boundary[d] && boundary[d ^ 1] {
                return Err(RawError::FacelessEdge);
            }
        }
        let mut map = Map {
            next: next.to_vec(),
            vert: vec![NONE; nd],
            face: vec![NONE; nd],
            vdart: Vec::new(),
            fdart: Vec::new(),
            free_edges: Vec::new(),
            free_verts: Vec::new(),
            free_faces: Vec::new(),
        };
        for d0 in 0..nd {
            if !boundary[d0] && map.face[d0] == NONE {
                let f = map.fdart.len() as u32;
                map.fdart.push(d0 as u32);
                let mut d = d0;
                loop {
                    map.face[d] = f;
                    d = next[d] as usize;
                    if d == d0 {
                        break;
                    }
                }
            }
            if map.vert[d0] == NONE {
                let v = map.vdart.len() as u32;
                let mut rec = d0 as u32;
                let mut n_boundary = 0;
                let mut d = d0;
                loop {
                    map.vert[d] = v;
                    if boundary[d] {
                        n_boundary += 1;
                        rec = d as u32;
                    }
                    d = next[d ^ 1] as usize;
                    if d == d0 {
                        break;
                    }
                }
                if n_boundary > 1 {
                    return Err(RawError::PinchedBoundary);
                }
                map.vdart.push(rec);
            }
        }
        Ok(map)
    }

    /// The mirror image: every face and boundary loop traversed the other way.
    ///
    /// Dart `d ^ 1` of the mirror is dart `d` of (the compacted) `self` walked backwards, on
    /// the same face: its `next` is `prev(d) ^ 1`. Faces and boundary loops keep their darts
    /// in reverse order, vertex rotations are reversed, and `mirror(mirror(m))` is isomorphic
    /// to `m` (vertex and face numbers are those of the orbits' smallest darts).
    ///
    /// ```
    /// use zipmesh_kernel::Map;
    /// let m = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    /// let mm = m.mirror().mirror();
    /// assert!(zipmesh_kernel::is_isomorphic(&m, &mm));
    /// ```
    pub fn mirror(&self) -> Map {
        let mut m = self.clone();
        m.compact();
        // In the mirror, dart d runs from dest(d) to origin(d) along the same face: that is
        // the original twin's direction, so store it as dart d ^ 1 with next = twin∘prev∘twin.
        let nd = m.next.len();
        let mut next = vec![0u32; nd];
        let mut boundary = vec![false; nd];
        for d in 0..nd {
            let p = m.prev(super::Dart(d as u32));
            next[d ^ 1] = p.0 ^ 1;
            boundary[d ^ 1] = m.face[d] == NONE;
        }
        // A valid map's mirror is valid; fall back to the original only if that were violated.
        Map::from_permutation(&next, &boundary).unwrap_or(m)
    }
}
