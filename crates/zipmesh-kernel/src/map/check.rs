//! The axioms of a valid map, each a variant of [`Violation`], and `check()`.

use super::{Dart, Face, Map, Vert, NONE};
use alloc::vec;
use core::fmt;

/// The first axiom a map violates, as found by [`Map::check`].
///
/// Maps built through the public API are valid, so `check()` finds nothing; it is the oracle
/// the tests and fuzzers call after every operation.
///
/// ```
/// let map = zipmesh_kernel::gen::cube(2).map;
/// assert_eq!(map.check(), Ok::<(), zipmesh_kernel::Violation>(()));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Violation {
    /// The per-dart arrays differ in length or hold an odd number of darts.
    Layout,
    /// A free list names a live slot, names a slot twice, or misses a dead slot.
    FreeList,
    /// A live dart's edge partner, `next`, origin or face is out of range or dead.
    DeadReference(Dart),
    /// `next` is not a permutation: this dart is the `next` of two darts.
    NextNotPermutation(Dart),
    /// The origin of `twin(d)` differs from the origin of `next(d)`.
    TwinOrigin(Dart),
    /// `d` and `next(d)` have different faces (or one is a boundary dart and the other not).
    FaceNotConstant(Dart),
    /// Both darts of this edge are boundary darts: an edge with no face.
    FacelessEdge(Dart),
    /// The face's dart is dead or belongs to another face.
    FaceRecord(Face),
    /// Some face's darts form more than one cycle.
    FaceSplit,
    /// The vertex's dart is dead or leaves another vertex.
    VertexRecord(Vert),
    /// Some vertex's darts form more than one rotation (a non-manifold vertex).
    VertexSplit,
    /// Two boundary darts leave this vertex (a pinched boundary).
    PinchedBoundary(Vert),
    /// A boundary dart leaves this vertex but its recorded dart is not that one.
    BoundaryRecord(Vert),
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Violation::Layout => write!(f, "dart arrays have inconsistent lengths"),
            Violation::FreeList => write!(f, "a free list disagrees with the dead slots"),
            Violation::DeadReference(d) => {
                write!(f, "dart {d} refers to a dead or missing element")
            }
            Violation::NextNotPermutation(d) => write!(f, "dart {d} is the next of two darts"),
            Violation::TwinOrigin(d) => {
                write!(f, "origin of twin({d}) differs from origin of next({d})")
            }
            Violation::FaceNotConstant(d) => {
                write!(f, "dart {d} and its next have different faces")
            }
            Violation::FacelessEdge(d) => {
                write!(f, "the edge of dart {d} has no face on either side")
            }
            Violation::FaceRecord(x) => write!(f, "face {x} records a dart that is not its own"),
            Violation::FaceSplit => write!(f, "a face has more than one dart cycle"),
            Violation::VertexRecord(v) => {
                write!(f, "vertex {v} records a dart that does not leave it")
            }
            Violation::VertexSplit => write!(f, "a vertex has more than one rotation"),
            Violation::PinchedBoundary(v) => write!(f, "two boundary darts leave vertex {v}"),
            Violation::BoundaryRecord(v) => {
                write!(f, "boundary vertex {v} records a non-boundary dart")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for Violation {}

/// What the per-edge pass counts for the record and cover checks.
#[derive(Default)]
struct EdgeTally {
    /// Live darts.
    live: usize,
    /// Live darts with a face.
    face_darts: usize,
    /// Dead edge slots.
    dead_edges: usize,
}

impl Map {
    /// Checks every axiom of a valid map and returns the first one violated.
    ///
    /// The axioms: array layout; free lists equal the dead slots; live darts refer only to
    /// live elements and edges are live as a whole; `next` is a permutation;
    /// `origin(twin(d)) == origin(next(d))`; the face is constant along `next`; every edge has
    /// a face on at least one side; every boundary dart is its origin's record (so at most one
    /// leaves a vertex); face records point into their own single cycle; vertex records point
    /// to a dart leaving them, whose rotation holds every dart leaving the vertex. `twin` is a
    /// fixed-point-free involution by construction (`d ^ 1`). The order of the checks is in
    /// `docs/design.md`.
    ///
    /// Runs in O(darts) time, with no scratch memory when the map is valid (one bit per dart
    /// when it is not, to name the first violation).
    ///
    /// ```
    /// let map = zipmesh_kernel::Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// assert_eq!(map.check(), Ok(()));
    /// ```
    pub fn check(&self) -> Result<(), Violation> {
        // Without the bitset that proves `next` a permutation (a quarter of the time): when
        // every other axiom holds, the vertex rotations covering every live dart imply it
        // (docs/design.md, "Checking a map fast"). On any failure the full check runs, so the
        // violation reported is the first in the documented order, as before.
        if self.axioms::<false>().is_ok() {
            return Ok(());
        }
        self.axioms::<true>()
    }

    /// The axioms in their documented order; `PERMUTATION` adds the explicit proof that
    /// `next` is a permutation ([`Violation::NextNotPermutation`]).
    fn axioms<const PERMUTATION: bool>(&self) -> Result<(), Violation> {
        let nd = self.next.len();
        if self.vert.len() != nd || self.face.len() != nd || nd % 2 != 0 {
            return Err(Violation::Layout);
        }
        self.check_free_lists()?;
        let tally = self.check_edges::<PERMUTATION>()?;
        if tally.dead_edges != self.free_edges.len() {
            return Err(Violation::FreeList);
        }
        // Each face record starts a cycle of its own face; the cycles cover all face darts.
        self.records(&self.fdart, &self.face, self.free_faces.len(), |f| {
            Violation::FaceRecord(Face(f))
        })?;
        if self.cover(&self.fdart, 0, tally.face_darts) != tally.face_darts {
            return Err(Violation::FaceSplit);
        }
        // Each vertex record starts a rotation; the rotations cover all live darts.
        self.records(&self.vdart, &self.vert, self.free_verts.len(), |v| {
            Violation::VertexRecord(Vert(v))
        })?;
        if self.cover(&self.vdart, 1, tally.live) != tally.live {
            return Err(Violation::VertexSplit);
        }
        Ok(())
    }

    /// Records of faces (or vertices): each live one names a live dart of its own
    /// (`owner[dart]` is the element), and the dead ones are as many as the free list.
    fn records(
        &self,
        records: &[u32],
        owner: &[u32],
        free: usize,
        bad: impl Fn(u32) -> Violation,
    ) -> Result<(), Violation> {
        let mut dead = 0usize;
        for (x, &d0) in records.iter().enumerate() {
            if d0 == NONE {
                dead += 1;
            } else if self.next.get(d0 as usize).is_none_or(|&n| n == NONE)
                || owner[d0 as usize] != x as u32
            {
                return Err(bad(x as u32));
            }
        }
        if dead != free {
            return Err(Violation::FreeList);
        }
        Ok(())
    }

    /// The per-edge axioms, edge by edge so that each dart's twin fields are loaded once:
    /// live references, `next` a permutation (with `PERMUTATION`), boundary records, twin
    /// origins, constant faces, no faceless edge. Counts what the later checks need.
    fn check_edges<const PERMUTATION: bool>(&self) -> Result<EdgeTally, Violation> {
        let nd = self.next.len();
        let mut has_pred = if PERMUTATION {
            vec![0u64; nd.div_ceil(64)]
        } else {
            vec![]
        };
        let mut t = EdgeTally::default();
        for e in 0..nd / 2 {
            let (d0, d1) = (2 * e, 2 * e + 1);
            let (n0, n1) = (self.next[d0], self.next[d1]);
            if n0 == NONE || n1 == NONE {
                if n0 != n1 {
                    let live = if n0 == NONE { d1 } else { d0 };
                    return Err(Violation::DeadReference(Dart(live as u32)));
                }
                t.dead_edges += 1;
                continue;
            }
            t.live += 2;
            let (v0, v1) = (self.vert[d0], self.vert[d1]);
            let (f0, f1) = (self.face[d0], self.face[d1]);
            let dead = |x: u32, rec: &[u32]| rec.get(x as usize).is_none_or(|&r| r == NONE);
            for (d, n, v, f) in [(d0, n0, v0, f0), (d1, n1, v1, f1)] {
                if self.next.get(n as usize).is_none_or(|&x| x == NONE)
                    || dead(v, &self.vdart)
                    || (f != NONE && dead(f, &self.fdart))
                {
                    return Err(Violation::DeadReference(Dart(d as u32)));
                }
                if PERMUTATION {
                    let (w, b) = (n as usize / 64, 1u64 << (n % 64));
                    if has_pred[w] & b != 0 {
                        return Err(Violation::NextNotPermutation(Dart(n)));
                    }
                    has_pred[w] |= b;
                }
                // A boundary dart must be its origin's record: so at most one leaves a vertex.
                if f == NONE && self.vdart[v as usize] != d as u32 {
                    let rec = self.vdart[v as usize] as usize;
                    return Err(if self.face.get(rec) == Some(&NONE) {
                        Violation::PinchedBoundary(Vert(v))
                    } else {
                        Violation::BoundaryRecord(Vert(v))
                    });
                }
            }
            self.check_twins(d0, d1, [n0, n1], [v0, v1], [f0, f1])?;
            t.face_darts += usize::from(f0 != NONE) + usize::from(f1 != NONE);
        }
        Ok(t)
    }

    /// Twin origins, constant faces along `next`, and a face on some side of the edge.
    #[inline]
    fn check_twins(
        &self,
        d0: usize,
        d1: usize,
        [n0, n1]: [u32; 2],
        [v0, v1]: [u32; 2],
        [f0, f1]: [u32; 2],
    ) -> Result<(), Violation> {
        if self.vert[n0 as usize] != v1 {
            return Err(Violation::TwinOrigin(Dart(d0 as u32)));
        }
        if self.vert[n1 as usize] != v0 {
            return Err(Violation::TwinOrigin(Dart(d1 as u32)));
        }
        if self.face[n0 as usize] != f0 {
            return Err(Violation::FaceNotConstant(Dart(d0 as u32)));
        }
        if self.face[n1 as usize] != f1 {
            return Err(Violation::FaceNotConstant(Dart(d1 as u32)));
        }
        if f0 == NONE && f1 == NONE {
            return Err(Violation::FacelessEdge(Dart(d0 as u32)));
        }
        Ok(())
    }

    /// Total length of the cycles of `d -> next(d ^ flip)` through each live record (each a
    /// live dart, checked before); stops once past `limit`.
    fn cover(&self, records: &[u32], flip: u32, limit: usize) -> usize {
        let mut covered = 0usize;
        for &d0 in records.iter().filter(|&&d| d != NONE) {
            let mut d = d0;
            loop {
                covered += 1;
                d = self.next[(d ^ flip) as usize];
                if d == d0 || covered > limit {
                    break;
                }
            }
        }
        covered
    }

    fn check_free_lists(&self) -> Result<(), Violation> {
        // Each entry is a dead slot, named once; the loops in `check` count the dead slots.
        fn one(free: &[u32], slots: usize, dead: impl Fn(usize) -> bool) -> Result<(), Violation> {
            // Free lists are short: a sorted copy finds repeats without a per-slot array.
            let mut sorted = free.to_vec();
            sorted.sort_unstable();
            if sorted.windows(2).any(|w| w[0] == w[1])
                || sorted
                    .iter()
                    .any(|&s| s as usize >= slots || !dead(s as usize))
            {
                return Err(Violation::FreeList);
            }
            Ok(())
        }
        one(&self.free_edges, self.next.len() / 2, |e| {
            self.next[2 * e] == NONE
        })?;
        one(&self.free_verts, self.vdart.len(), |v| {
            self.vdart[v] == NONE
        })?;
        one(&self.free_faces, self.fdart.len(), |f| {
            self.fdart[f] == NONE
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use alloc::vec::Vec;

    /// The fast path never accepts what the full check rejects: maps corrupted by random
    /// writes into their arrays (valid handles, out-of-range ones and `NONE`) and by merged
    /// vertices or faces, one to three corruptions each, on closed and bounded quad and
    /// triangle meshes. How many of them are invalid is printed.
    #[test]
    fn fast_check_agrees_with_the_full_check() {
        let bases = [
            crate::gen::torus_grid(4, 3).map,
            crate::gen::grid(3, 3).map,
            crate::gen::cube(1).map,
            crate::gen::random_triangle(12, 1, 1, 3).map,
        ];
        let mut rng = Rng::new(11);
        let (mut invalid, mut total) = (0, 0);
        for base in &bases {
            for _ in 0..4000 {
                let mut m = base.clone();
                for _ in 0..1 + rng.below(3) {
                    corrupt(&mut m, &mut rng);
                }
                let full = m.axioms::<true>();
                assert_eq!(m.check(), full, "fast and full checks disagree");
                invalid += usize::from(full.is_err());
                total += 1;
            }
        }
        #[cfg(feature = "std")]
        std::println!("{invalid} of {total} corrupted maps invalid");
        assert!(invalid > total / 2 && invalid < total);
    }

    /// Two random live elements made one: the darts of the second (by `owner`) relabelled
    /// to the first, its record (`records`) freed onto `free`.
    fn merge(owner: &mut [u32], records: &mut [u32], free: &mut Vec<u32>, rng: &mut Rng) {
        let n = records.len().max(1);
        let (a, b) = (rng.below(n), rng.below(n));
        if a == b || records.get(a).is_none_or(|&d| d == NONE) || records[b] == NONE {
            return;
        }
        owner
            .iter_mut()
            .filter(|x| **x == b as u32)
            .for_each(|x| *x = a as u32);
        records[b] = NONE;
        free.push(b as u32);
    }

    /// One random corruption: a write into one of the map's arrays, a swap of two `next`
    /// entries, or two vertices (faces) merged into one.
    fn corrupt(m: &mut Map, rng: &mut Rng) {
        let nd = m.next.len() as u32;
        let value = match rng.below(4) {
            0 => NONE,
            1 => nd + rng.below(3) as u32,
            _ => rng.below(nd.max(1) as usize) as u32,
        };
        let small = |rng: &mut Rng, n: usize| rng.below(n.max(1));
        match rng.below(7) {
            // Two vertices (faces) made one, their darts relabelled and a record freed: every
            // per-edge axiom still holds, only the covers see the two rotations (cycles).
            5 => merge(&mut m.vert, &mut m.vdart, &mut m.free_verts, rng),
            6 => merge(&mut m.face, &mut m.fdart, &mut m.free_faces, rng),
            0 => {
                let i = small(rng, m.next.len());
                m.next[i] = value;
            }
            1 => {
                let i = small(rng, m.vert.len());
                m.vert[i] = value % (m.vdart.len() as u32 + 2);
            }
            2 => {
                let i = small(rng, m.face.len());
                m.face[i] = if value == NONE {
                    NONE
                } else {
                    value % (m.fdart.len() as u32 + 2)
                };
            }
            3 => {
                let i = small(rng, m.vdart.len());
                m.vdart[i] = value;
            }
            _ => {
                // Swapping two `next` entries keeps a permutation but breaks faces or vertices.
                let (i, j) = (small(rng, m.next.len()), small(rng, m.next.len()));
                m.next.swap(i, j);
            }
        }
    }
}
