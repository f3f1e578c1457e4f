//! An independent model of a map as raw permutations, used as the oracle.
//!
//! Everything here is computed from `next` and the boundary marks alone, by direct orbit
//! walks, without the library's code paths.

use crate::choice::Choice;
use std::collections::BTreeMap;
use zipmesh_kernel::{Dart, Map, RawError};

/// A map as its raw data: darts `0..next.len()`, twin `d ^ 1`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct RawMap {
    pub next: Vec<u32>,
    pub boundary: Vec<bool>,
}

/// Orbit numbers of every dart, numbered by smallest dart.
pub fn orbits(n: usize, step: impl Fn(usize) -> usize) -> (Vec<usize>, usize) {
    let mut id = vec![usize::MAX; n];
    let mut count = 0;
    for s in 0..n {
        if id[s] == usize::MAX {
            let mut d = s;
            while id[d] == usize::MAX {
                id[d] = count;
                d = step(d);
            }
            count += 1;
        }
    }
    (id, count)
}

/// What `Map::from_permutation` must answer for a permutation with cycle-constant marks.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Expected {
    Ok,
    /// Any of these errors (more than one defect may be present).
    OneOf(Vec<RawError>),
}

impl RawMap {
    /// Any map on `2 * n_edges` darts: any `next` permutation, then one mark per `next` cycle.
    pub fn any(c: &mut impl Choice, n_edges: usize) -> RawMap {
        let next: Vec<u32> = c
            .any_permutation(2 * n_edges)
            .into_iter()
            .map(|x| x as u32)
            .collect();
        let mut raw = RawMap {
            boundary: vec![false; next.len()],
            next,
        };
        let (cycle, n_cycles) = raw.face_cycles();
        let marks: Vec<bool> = (0..n_cycles).map(|_| c.any_bool()).collect();
        for d in 0..raw.next.len() {
            raw.boundary[d] = marks[cycle[d]];
        }
        raw
    }

    /// The raw data of a map whose darts are `0..num_darts` (a compacted map).
    pub fn of(map: &Map) -> RawMap {
        assert_eq!(map.dart_slots(), map.num_darts(), "map must be compact");
        let nd = map.num_darts() as u32;
        RawMap {
            next: (0..nd)
                .map(|d| map.next(Dart::new(d)).index() as u32)
                .collect(),
            boundary: (0..nd)
                .map(|d| map.is_boundary_dart(Dart::new(d)))
                .collect(),
        }
    }

    pub fn darts(&self) -> usize {
        self.next.len()
    }

    /// Cycles of `next` (faces and boundary loops).
    pub fn face_cycles(&self) -> (Vec<usize>, usize) {
        orbits(self.darts(), |d| self.next[d] as usize)
    }

    /// Vertices: orbits of `d -> next(twin(d))`, the darts leaving one vertex.
    pub fn vertex_orbits(&self) -> (Vec<usize>, usize) {
        orbits(self.darts(), |d| self.next[d ^ 1] as usize)
    }

    /// Connected components (closure under `next` and twin), numbered by smallest dart.
    pub fn components(&self) -> (Vec<usize>, usize) {
        let n = self.darts();
        let mut id = vec![usize::MAX; n];
        let mut count = 0;
        for s in 0..n {
            if id[s] != usize::MAX {
                continue;
            }
            let mut stack = vec![s];
            id[s] = count;
            while let Some(d) = stack.pop() {
                for x in [self.next[d] as usize, d ^ 1] {
                    if id[x] == usize::MAX {
                        id[x] = count;
                        stack.push(x);
                    }
                }
            }
            count += 1;
        }
        (id, count)
    }

    /// The answer `from_permutation` must give (marks are assumed constant on cycles).
    pub fn expected(&self) -> Expected {
        let mut errs = Vec::new();
        if (0..self.darts()).any(|d| self.boundary[d] && self.boundary[d ^ 1]) {
            errs.push(RawError::FacelessEdge);
        }
        let (v, nv) = self.vertex_orbits();
        let mut out_boundary = vec![0; nv];
        for d in 0..self.darts() {
            out_boundary[v[d]] += usize::from(self.boundary[d]);
        }
        if out_boundary.iter().any(|&k| k > 1) {
            errs.push(RawError::PinchedBoundary);
        }
        if errs.is_empty() {
            Expected::Ok
        } else {
            Expected::OneOf(errs)
        }
    }

    /// The map under the relabelling that sends edge `e` to `perm[e]`, swapping its two
    /// darts when `swap[e]`: dart `d` becomes `2 perm[d/2] + (d%2 ^ swap[d/2])`.
    pub fn relabel(&self, perm: &[usize], swap: &[bool]) -> RawMap {
        let phi = |d: usize| 2 * perm[d / 2] + ((d & 1) ^ usize::from(swap[d / 2]));
        let mut out = RawMap {
            next: vec![0; self.darts()],
            boundary: vec![false; self.darts()],
        };
        for d in 0..self.darts() {
            out.next[phi(d)] = phi(self.next[d] as usize) as u32;
            out.boundary[phi(d)] = self.boundary[d];
        }
        out
    }

    /// Brute-force canonical form: the smallest encoding over every relabelling of edges
    /// and orientations of edges (the whole group of renumberings that keep twin = d ^ 1).
    /// Two maps are isomorphic exactly when their forms are equal. At most 8 darts.
    pub fn brute_form(&self) -> u64 {
        let n = self.darts() / 2;
        assert!(n <= 4, "brute force is for tiny maps");
        let mut best = u64::MAX;
        let mut phi = [0usize; 8];
        let mut inv = [0usize; 8];
        for perm in permutations(n) {
            for swaps in 0..(1usize << n) {
                for d in 0..2 * n {
                    phi[d] = 2 * perm[d / 2] + ((d & 1) ^ ((swaps >> (d / 2)) & 1));
                    inv[phi[d]] = d;
                }
                // Encode the relabelled map dart by dart: (next, mark) in 4 bits each.
                let mut key = n as u64;
                for &d in &inv[..2 * n] {
                    let sym = (phi[self.next[d] as usize] << 1) | usize::from(self.boundary[d]);
                    key = (key << 4) | sym as u64;
                }
                best = best.min(key);
            }
        }
        best
    }

    /// Per-vertex valence and boundary flag, per-face degree (oracle for histograms).
    pub fn histograms(
        &self,
    ) -> (
        BTreeMap<usize, usize>,
        BTreeMap<usize, usize>,
        BTreeMap<usize, usize>,
    ) {
        let (v, nv) = self.vertex_orbits();
        let (f, nf) = self.face_cycles();
        let mut val = vec![0; nv];
        let mut bnd = vec![false; nv];
        let mut deg = vec![0; nf];
        for d in 0..self.darts() {
            val[v[d]] += 1;
            bnd[v[d]] |= self.boundary[d];
            deg[f[d]] += 1;
        }
        let mut inner = BTreeMap::new();
        let mut outer = BTreeMap::new();
        for x in 0..nv {
            *if bnd[x] { &mut outer } else { &mut inner }
                .entry(val[x])
                .or_insert(0) += 1;
        }
        let mut faces = BTreeMap::new();
        for d in 0..self.darts() {
            // Count each face cycle once, at its smallest dart.
            if !self.boundary[d] && (0..d).all(|e| f[e] != f[d]) {
                *faces.entry(deg[f[d]]).or_insert(0) += 1;
            }
        }
        (inner, outer, faces)
    }
}

/// Every permutation of `0..n`.
pub fn permutations(n: usize) -> Vec<Vec<usize>> {
    if n == 0 {
        return vec![Vec::new()];
    }
    let mut out = Vec::new();
    for p in permutations(n - 1) {
        for i in 0..n {
            let mut q = p.clone();
            q.insert(i, n - 1);
            out.push(q);
        }
    }
    out
}
