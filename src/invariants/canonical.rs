//! Canonical codes of maps: a numbering-independent code, its 128-bit hash, and isomorphism.
//!
//! # Algorithm
//! For a connected map and a start dart `s`, number the darts breadth-first from `s`, taking
//! for each dart in turn its `next` and then its `twin`; emit, per dart in that order, the
//! numbers of its `next` and `twin` and its boundary bit. Two starts give the same code iff an
//! orientation-preserving isomorphism maps one start to the other, so the smallest code over
//! all starts is canonical. Only starts in one isomorphism-invariant class are tried: the
//! darts are keyed by (boundary bit, length of their face or boundary cycle, valence of their
//! origin, valence of their destination), and the rarest key (smallest key on a tie) wins.
//! A start is abandoned at the first symbol where its code exceeds the best so far. When a
//! start ties with the best, the two numberings give an automorphism; its cycles are merged
//! in a union-find over darts, and a later start already in the orbit of a tried start is
//! skipped (it would give the same code).
//!
//! Cost: O(n) per fully computed start plus O(n α(n)) per automorphism found. An irregular
//! mesh has a small rarest class; a regular torus has every dart in one class, but after a few
//! automorphisms (translations, rotations) every start is in a tried orbit, so it costs a
//! handful of full passes, not O(n²). Components are coded separately and their codes sorted.

use super::counts::component_of_darts;
use crate::map::{Map, NONE};
use alloc::vec;
use alloc::vec::Vec;

/// A canonical code: equal for two maps exactly when they are isomorphic (orientation
/// preserving, boundary included), whatever their handle numbering and dead slots.
///
/// ```
/// use zipmesh::{gen, invariants::canonical::CanonicalCode};
/// let a = CanonicalCode::of(&gen::torus_grid(5, 4).map);
/// let b = CanonicalCode::of(&gen::torus_grid(4, 5).map);
/// assert_eq!(a, b); // the same torus, turned a quarter
/// ```
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct CanonicalCode(pub Vec<u32>);

impl CanonicalCode {
    /// The canonical code of `map`.
    ///
    /// ```
    /// use zipmesh::{invariants::canonical::CanonicalCode, Map};
    /// let a = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    /// let b = Map::from_polygons(4, &[[3u32, 1, 0], [1, 2, 0]]).unwrap();
    /// assert_eq!(CanonicalCode::of(&a), CanonicalCode::of(&b));
    /// ```
    pub fn of(map: &Map) -> CanonicalCode {
        Canonizer::new(map).code()
    }

    /// The 128-bit XXH3 hash of the code.
    ///
    /// ```
    /// use zipmesh::{gen, invariants::canonical::CanonicalCode};
    /// let h = CanonicalCode::of(&gen::torus_grid(4, 4).map).hash();
    /// assert_ne!(h, CanonicalCode::of(&gen::torus_grid(4, 5).map).hash());
    /// ```
    pub fn hash(&self) -> u128 {
        let mut bytes = Vec::with_capacity(self.0.len() * 4);
        for x in &self.0 {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
        xxhash_rust::xxh3::xxh3_128(&bytes)
    }
}

/// The 128-bit hash of the canonical code of `map`.
///
/// ```
/// use zipmesh::{gen, invariants::canonical::canonical_hash};
/// assert_eq!(canonical_hash(&gen::cube(2).map), canonical_hash(&gen::cube(2).map));
/// ```
pub fn canonical_hash(map: &Map) -> u128 {
    CanonicalCode::of(map).hash()
}

/// Whether an orientation-preserving isomorphism maps `a` onto `b`.
///
/// ```
/// use zipmesh::{gen, is_isomorphic};
/// assert!(is_isomorphic(&gen::torus_grid(4, 3).map, &gen::torus_grid(3, 4).map));
/// assert!(!is_isomorphic(&gen::torus_grid(4, 3).map, &gen::torus_grid(4, 4).map));
/// ```
pub fn is_isomorphic(a: &Map, b: &Map) -> bool {
    a.num_darts() == b.num_darts()
        && a.num_vertices() == b.num_vertices()
        && a.num_faces() == b.num_faces()
        && CanonicalCode::of(a) == CanonicalCode::of(b)
}

/// Whether `a` is isomorphic to `b` or to its mirror image.
///
/// ```
/// use zipmesh::{is_isomorphic, is_isomorphic_mirror, Map};
/// let a = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
/// assert!(is_isomorphic_mirror(&a, &a.mirror()));
/// ```
pub fn is_isomorphic_mirror(a: &Map, b: &Map) -> bool {
    is_isomorphic(a, b) || is_isomorphic(&a.mirror(), b)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Cmp {
    Better,
    Equal,
    Worse,
}

struct Canonizer<'a> {
    map: &'a Map,
    label: Vec<u32>,
    order: Vec<u32>,
    code: Vec<u32>,
    best_order: Vec<u32>,
    best_code: Vec<u32>,
    parent: Vec<u32>,
    rank: Vec<u8>,
    /// Per union-find root: whether a start in its orbit was tried.
    tried: Vec<bool>,
}

impl<'a> Canonizer<'a> {
    fn new(map: &'a Map) -> Self {
        let nd = map.next.len();
        Canonizer {
            map,
            label: vec![NONE; nd],
            order: Vec::new(),
            code: Vec::new(),
            best_order: Vec::new(),
            best_code: Vec::new(),
            parent: Vec::new(),
            rank: Vec::new(),
            tried: vec![false; nd],
        }
    }

    fn code(mut self) -> CanonicalCode {
        let map = self.map;
        let comp = component_of_darts(map);
        let n_comp = comp
            .iter()
            .filter(|&&c| c != NONE)
            .max()
            .map_or(0, |&m| m as usize + 1);
        let keys = Keys::new(map);
        // Darts grouped by component (a counting sort), then the rarest key class of each.
        let mut comp_start = vec![0usize; n_comp + 1];
        for &c in comp.iter().filter(|&&c| c != NONE) {
            comp_start[c as usize + 1] += 1;
        }
        for c in 0..n_comp {
            comp_start[c + 1] += comp_start[c];
        }
        let mut by_comp = vec![0u32; comp_start[n_comp]];
        {
            let mut fill = comp_start.clone();
            for (d, &c) in comp.iter().enumerate().filter(|(_, &c)| c != NONE) {
                by_comp[fill[c as usize]] = d as u32;
                fill[c as usize] += 1;
            }
        }
        drop(comp);
        let mut parts: Vec<Vec<u32>> = Vec::with_capacity(n_comp);
        self.parent = (0..map.next.len() as u32).collect();
        self.rank = vec![0; map.next.len()];
        for c in 0..n_comp {
            let darts = &by_comp[comp_start[c]..comp_start[c + 1]];
            let best_key = rarest(darts.iter().map(|&d| keys.of(map, d as usize)));
            let starts: Vec<u32> = darts
                .iter()
                .copied()
                .filter(|&d| keys.of(map, d as usize) == best_key)
                .collect();
            parts.push(self.component_code(&starts));
        }
        parts.sort_unstable_by(|a, b| a.len().cmp(&b.len()).then_with(|| a.cmp(b)));
        let mut out =
            Vec::with_capacity(1 + parts.len() + parts.iter().map(Vec::len).sum::<usize>());
        out.push(parts.len() as u32);
        for p in parts {
            out.push(p.len() as u32);
            out.extend(p);
        }
        CanonicalCode(out)
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let p = self.parent[x as usize];
            self.parent[x as usize] = self.parent[p as usize];
            x = p;
        }
        x
    }

    fn component_code(&mut self, starts: &[u32]) -> Vec<u32> {
        self.best_code.clear();
        self.best_order.clear();
        for &s in starts {
            let r = self.find(s);
            if self.tried[r as usize] {
                continue;
            }
            self.tried[r as usize] = true;
            let first = self.best_order.is_empty();
            match self.run(s, first) {
                Cmp::Better => {
                    core::mem::swap(&mut self.best_code, &mut self.code);
                    core::mem::swap(&mut self.best_order, &mut self.order);
                }
                Cmp::Equal => {
                    // The two numberings differ by an automorphism: merge its cycles.
                    for k in 0..self.order.len() {
                        let (a, b) = (self.best_order[k], self.order[k]);
                        let (ra, rb) = (self.find(a), self.find(b));
                        if ra != rb {
                            // Union by rank keeps the trees shallow; the merged orbit is
                            // tried if either part was.
                            let (lo, hi) = if self.rank[ra as usize] < self.rank[rb as usize] {
                                (ra, rb)
                            } else {
                                (rb, ra)
                            };
                            self.parent[lo as usize] = hi;
                            if self.rank[lo as usize] == self.rank[hi as usize] {
                                self.rank[hi as usize] += 1;
                            }
                            self.tried[hi as usize] |= self.tried[lo as usize];
                        }
                    }
                }
                Cmp::Worse => {}
            }
        }
        core::mem::take(&mut self.best_code)
    }

    /// Numbers the component from `s`, comparing with the best code as it goes.
    fn run(&mut self, s: u32, first: bool) -> Cmp {
        let map = self.map;
        self.order.clear();
        self.code.clear();
        self.label[s as usize] = 0;
        self.order.push(s);
        let mut state = if first { Cmp::Better } else { Cmp::Equal };
        let mut i = 0;
        while i < self.order.len() {
            let d = self.order[i] as usize;
            let n = map.next[d] as usize;
            if self.label[n] == NONE {
                self.label[n] = self.order.len() as u32;
                self.order.push(n as u32);
            }
            let t = d ^ 1;
            if self.label[t] == NONE {
                self.label[t] = self.order.len() as u32;
                self.order.push(t as u32);
            }
            let sym = [
                self.label[n],
                self.label[t] * 2 + u32::from(map.face[d] == NONE),
            ];
            if state == Cmp::Equal {
                let b = [self.best_code[2 * i], self.best_code[2 * i + 1]];
                if sym < b {
                    // Only a better code is kept: its prefix so far is the best one's.
                    state = Cmp::Better;
                    self.code.extend_from_slice(&self.best_code[..2 * i]);
                } else if sym > b {
                    state = Cmp::Worse;
                    break;
                }
            }
            if state == Cmp::Better {
                self.code.extend_from_slice(&sym);
            }
            i += 1;
        }
        if self.order.len() * 4 >= self.label.len() {
            // Most darts were numbered: one sequential fill beats scattered resets.
            self.label.fill(NONE);
        } else {
            for &d in &self.order {
                self.label[d as usize] = NONE;
            }
        }
        state
    }
}

/// Per dart: an isomorphism-invariant key (boundary bit, cycle length, origin and
/// destination valences, each capped to 21 bits), computed on demand.
struct Keys {
    valence: Vec<u32>,
    cycle: Vec<u32>,
}

impl Keys {
    fn new(map: &Map) -> Keys {
        let nd = map.next.len();
        let mut valence = vec![0u32; map.vdart.len()];
        for d in 0..nd {
            if map.next[d] != NONE {
                valence[map.vert[d] as usize] += 1;
            }
        }
        let mut cycle = vec![0u32; nd];
        for d0 in 0..nd {
            if map.next[d0] == NONE || cycle[d0] != 0 {
                continue;
            }
            let mut len = 0u32;
            let mut d = d0;
            loop {
                len += 1;
                d = map.next[d] as usize;
                if d == d0 {
                    break;
                }
            }
            loop {
                cycle[d] = len;
                d = map.next[d] as usize;
                if d == d0 {
                    break;
                }
            }
        }
        Keys { valence, cycle }
    }

    #[inline]
    fn of(&self, map: &Map, d: usize) -> u64 {
        let cap = |x: u32| u64::from(x.min((1 << 21) - 1));
        u64::from(map.face[d] == NONE) << 63
            | cap(self.cycle[d]) << 42
            | cap(self.valence[map.vert[d] as usize]) << 21
            | cap(self.valence[map.vert[d ^ 1] as usize])
    }
}

/// The key with the fewest darts (the smallest key on a tie). Meshes have few distinct
/// keys, so a short list is scanned before a hash map is needed.
fn rarest(keys: impl Iterator<Item = u64>) -> u64 {
    let mut few: Vec<(u64, u32)> = Vec::new();
    let mut many: hashbrown::HashMap<u64, u32> = hashbrown::HashMap::new();
    for k in keys {
        if let Some(e) = few.iter_mut().find(|e| e.0 == k) {
            e.1 += 1;
        } else if few.len() < 16 {
            few.push((k, 1));
        } else {
            *many.entry(k).or_insert(0) += 1;
        }
    }
    few.iter()
        .map(|&(k, c)| (c, k))
        .chain(many.iter().map(|(&k, &c)| (c, k)))
        .min()
        .map_or(0, |(_, k)| k)
}

/// The dart of `candidates` whose breadth-first numbering (the one of the canonical code,
/// started from it) reads smallest; `None` if there are none. Two candidates related by an
/// isomorphism read the same, so the choice depends on the map, not on its handles.
///
/// The walks are compared symbol by symbol and stop at the first difference, which near an
/// irregular vertex comes within a few rings: the cost is local, not O(map), unless two
/// candidates are related by an automorphism (then the whole component is read, O(n log n),
/// and either is right). Labels live in a `BTreeMap` so that a short walk allocates little.
pub(crate) fn least_start(map: &Map, candidates: &[crate::Dart]) -> Option<crate::Dart> {
    let mut best = *candidates.first()?;
    for &c in &candidates[1..] {
        if compare_starts((map, c), (map, best)) == core::cmp::Ordering::Less {
            best = c;
        }
    }
    Some(best)
}

/// How the reading from `a` compares with the one from `b` (each dart with its map): `Equal`
/// exactly when an isomorphism of their components maps `a` to `b`.
fn compare_starts(a: (&Map, crate::Dart), b: (&Map, crate::Dart)) -> core::cmp::Ordering {
    let (mut wa, mut wb) = (Walk::new(a.1), Walk::new(b.1));
    loop {
        match (wa.step(a.0), wb.step(b.0)) {
            (Some(x), Some(y)) if x == y => continue,
            (x, y) => return x.cmp(&y),
        }
    }
}

/// Whether an isomorphism of the whole maps takes dart `a` of the first to dart `b` of the
/// second: the breadth-first readings from the two agree (as in [`compare_starts`]) and each
/// reads every live dart of its map, so both maps are connected. `true` implies equal
/// canonical codes; `false` says nothing when an isomorphism exists that moves the anchor.
/// Dense labels (one slot per dart): the walk reads the whole map when it succeeds.
pub(crate) fn same_from(a: (&Map, crate::Dart), b: (&Map, crate::Dart)) -> bool {
    let ((ma, sa), (mb, sb)) = ((a.0, a.1.index()), (b.0, b.1.index()));
    if ma.num_darts() != mb.num_darts() || !ma.is_live_dart(a.1) || !mb.is_live_dart(b.1) {
        return false;
    }
    let (mut la, mut lb) = (vec![NONE; ma.next.len()], vec![NONE; mb.next.len()]);
    let (mut oa, mut ob) = (vec![sa as u32], vec![sb as u32]);
    la[sa] = 0;
    lb[sb] = 0;
    let mut i = 0;
    while i < oa.len() {
        let (da, db) = (oa[i] as usize, ob[i] as usize);
        if (ma.face[da] == NONE) != (mb.face[db] == NONE) {
            return false;
        }
        for (xa, xb) in [
            (ma.next[da] as usize, mb.next[db] as usize),
            (da ^ 1, db ^ 1),
        ] {
            match (la[xa], lb[xb]) {
                // Both new: the readings stay in step, so both get the same number.
                (NONE, NONE) => {
                    la[xa] = oa.len() as u32;
                    lb[xb] = ob.len() as u32;
                    oa.push(xa as u32);
                    ob.push(xb as u32);
                }
                (p, q) if p == q => {}
                _ => return false,
            }
        }
        i += 1;
    }
    oa.len() == ma.num_darts()
}

/// A breadth-first numbering from one dart, one symbol at a time.
struct Walk {
    label: alloc::collections::BTreeMap<u32, u32>,
    order: Vec<u32>,
    i: usize,
}

impl Walk {
    fn new(s: crate::Dart) -> Walk {
        let s = s.index() as u32;
        Walk {
            label: [(s, 0)].into_iter().collect(),
            order: vec![s],
            i: 0,
        }
    }

    fn label(&mut self, d: u32) -> u32 {
        let next = self.order.len() as u32;
        let l = *self.label.entry(d).or_insert(next);
        if l == next {
            self.order.push(d);
        }
        l
    }

    /// The next symbol of the code, `None` when the component is read.
    fn step(&mut self, map: &Map) -> Option<[u32; 2]> {
        let d = *self.order.get(self.i)? as usize;
        self.i += 1;
        let n = self.label(map.next[d]);
        let t = self.label(d as u32 ^ 1);
        Some([n, t * 2 + u32::from(map.face[d] == NONE)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{gen, Dart};
    use core::cmp::Ordering;

    fn darts(map: &Map) -> Vec<Dart> {
        (0..map.next.len() as u32)
            .map(Dart::new)
            .filter(|&d| map.is_live_dart(d))
            .collect()
    }

    #[test]
    fn starts_compare_equal_exactly_under_an_automorphism() {
        // A square torus: translations and quarter turns take any dart to any other.
        let square = gen::torus_grid(5, 5).map;
        let all = darts(&square);
        assert!(all
            .iter()
            .all(|&d| compare_starts((&square, all[0]), (&square, d)) == Ordering::Equal));
        // A 5 x 4 torus: no automorphism takes a dart along the 5-cycle to one along the 4-cycle.
        let oblong = gen::torus_grid(5, 4).map;
        let all = darts(&oblong);
        assert!(all
            .iter()
            .any(|&d| compare_starts((&oblong, all[0]), (&oblong, d)) != Ordering::Equal));
    }

    #[test]
    fn the_least_start_does_not_depend_on_handles() {
        // The same cube numbered twice: polygons and vertices listed in another order.
        let mesh = gen::cube(3);
        let polys: Vec<Vec<u32>> = mesh
            .map
            .faces()
            .map(|f| {
                mesh.map
                    .face_darts(f)
                    .map(|d| mesh.map.origin(d).index() as u32)
                    .collect()
            })
            .collect();
        let n = mesh.map.num_vertices() as u32;
        let renamed: Vec<Vec<u32>> = polys
            .iter()
            .rev()
            .map(|p| p.iter().map(|&v| n - 1 - v).collect())
            .collect();
        let a = Map::from_polygons(n as usize, &polys).unwrap();
        let b = Map::from_polygons(n as usize, &renamed).unwrap();
        for v in 0..n {
            let (va, vb) = (crate::Vert::new(v), crate::Vert::new(n - 1 - v));
            let ca: Vec<Dart> = a.vertex_darts(va).collect();
            let cb: Vec<Dart> = b.vertex_darts(vb).collect();
            let (la, lb) = (least_start(&a, &ca).unwrap(), least_start(&b, &cb).unwrap());
            assert_eq!(compare_starts((&a, la), (&b, lb)), Ordering::Equal);
            assert!(ca
                .iter()
                .all(|&d| compare_starts((&a, la), (&a, d)) != Ordering::Greater));
        }
        assert_eq!(least_start(&a, &[]), None);
    }

    #[test]
    fn same_from_agrees_with_the_canonical_code() {
        // Every anchor pair on a pair of maps: `true` exactly when the readings compare
        // equal (both maps connected here), and then the codes agree.
        let cases = [
            (gen::torus_grid(4, 3).map, gen::torus_grid(3, 4).map),
            (gen::cube(2).map, gen::cube(2).map),
            (gen::grid(3, 2).map, gen::grid(2, 3).map),
            (gen::torus_grid(4, 4).map, gen::torus_grid(4, 5).map),
        ];
        let mut agreed = 0;
        for (a, b) in &cases {
            for &x in &darts(a) {
                for &y in darts(b).iter().take(12) {
                    let same = same_from((a, x), (b, y));
                    assert_eq!(same, compare_starts((a, x), (b, y)) == Ordering::Equal);
                    if same {
                        assert_eq!(CanonicalCode::of(a), CanonicalCode::of(b));
                        agreed += 1;
                    }
                }
            }
        }
        assert!(
            agreed > 0,
            "no anchor pair agreed: the test checked only refusals"
        );
        // Two components: the reading from one dart misses the other, so it is refused.
        let two = Map::from_polygons(8, &[[0u32, 1, 2, 3], [4, 5, 6, 7]]).unwrap();
        let d = darts(&two)[0];
        assert_eq!(compare_starts((&two, d), (&two, d)), Ordering::Equal);
        assert!(!same_from((&two, d), (&two, d)));
    }
}
