//! Input types for the fuzz targets (feature `arbitrary`).
//!
//! Each type derives [`arbitrary::Arbitrary`], so a fuzzer turns raw bytes into it, and
//! converts itself into the arguments of one builder. Small integer types keep the inputs
//! dense: most byte strings decode to a polygon list that refers to existing vertices.

use ::arbitrary::Arbitrary;
use alloc::vec::Vec;

/// A polygon list for [`Map::from_polygons`](crate::Map::from_polygons): up to 255
/// vertices, faces of any length with any corners (in range or not).
///
/// ```
/// use arbitrary::{Arbitrary, Unstructured};
/// use zipmesh::arbitrary::PolygonSoup;
/// let soup = PolygonSoup::arbitrary(&mut Unstructured::new(&[4, 1, 3, 0, 1, 2])).unwrap();
/// let faces = soup.faces();
/// // Whatever the bytes, building never panics.
/// let _ = zipmesh::Map::from_polygons(soup.n_vertices as usize, &faces);
/// ```
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub struct PolygonSoup {
    /// The number of vertices.
    pub n_vertices: u8,
    /// The faces, as vertex indices.
    pub faces: Vec<Vec<u8>>,
}

impl PolygonSoup {
    /// The faces with `u32` indices, as the builders take them.
    ///
    /// ```
    /// let soup = zipmesh::arbitrary::PolygonSoup { n_vertices: 3, faces: vec![vec![0, 1, 2]] };
    /// assert_eq!(soup.faces(), vec![vec![0u32, 1, 2]]);
    /// ```
    pub fn faces(&self) -> Vec<Vec<u32>> {
        self.faces
            .iter()
            .map(|f| f.iter().map(|&v| u32::from(v)).collect())
            .collect()
    }
}

/// Arguments for [`Map::from_permutation`](crate::Map::from_permutation).
///
/// Raw bytes rarely form a permutation, so unless `raw` is set the input is first turned
/// into one: `next` drives a Fisher-Yates shuffle of the darts `0..2k` (`k` = half its
/// length) and each `next` cycle takes the boundary mark of its smallest dart. Every
/// permutation with cycle-constant marks is reachable that way, so the fuzzer reaches valid
/// maps with loops, multi-edges and any genus, as well as every rejection.
///
/// ```
/// use zipmesh::arbitrary::PermutationInput;
/// let input = PermutationInput { next: vec![1, 0], boundary: vec![false, true], raw: false };
/// let (next, boundary) = input.arrays();
/// assert_eq!(next, vec![1, 0]); // one edge, one face of degree 2
/// assert_eq!(boundary, vec![false, false]); // both darts on one cycle: its first mark wins
/// assert!(zipmesh::Map::from_permutation(&next, &boundary).is_ok());
/// ```
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub struct PermutationInput {
    /// Shuffle offsets, or the raw `next` array when `raw`.
    pub next: Vec<u16>,
    /// Boundary marks (missing marks are `false`).
    pub boundary: Vec<bool>,
    /// Pass the arrays through unchanged.
    pub raw: bool,
}

impl PermutationInput {
    /// The `(next, boundary)` arrays to build from.
    ///
    /// ```
    /// use zipmesh::arbitrary::PermutationInput;
    /// let input = PermutationInput { next: vec![5, 5, 5], boundary: vec![true], raw: true };
    /// assert_eq!(input.arrays(), (vec![5, 5, 5], vec![true]));
    /// ```
    pub fn arrays(&self) -> (Vec<u32>, Vec<bool>) {
        if self.raw {
            let next = self.next.iter().map(|&x| u32::from(x)).collect();
            return (next, self.boundary.clone());
        }
        let n = self.next.len() & !1;
        let mut perm: Vec<u32> = (0..n as u32).collect();
        for i in 0..n {
            let j = i + usize::from(self.next[i]) % (n - i);
            perm.swap(i, j);
        }
        let mut boundary = alloc::vec![false; n];
        let mut seen = alloc::vec![false; n];
        for s in 0..n {
            if seen[s] {
                continue;
            }
            let mark = self.boundary.get(s).copied().unwrap_or(false);
            let mut d = s;
            while !seen[d] {
                seen[d] = true;
                boundary[d] = mark;
                d = perm[d] as usize;
            }
        }
        (perm, boundary)
    }
}
