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
//! A start is abandoned at the first symbol where its code exceeds the best so far; the best
//! start's numbering is itself advanced only as far as a challenger needs, so only the final
//! winner is numbered in full (a start that wins for a while costs its prefix, not O(n)). When
//! a start ties with the best, the two numberings give an automorphism; the starts reachable
//! from tried ones under the automorphisms found are skipped (they would give the same code).
//!
//! Cost: O(n) per fully computed start plus O(k g) for the orbits (k starts, g <= log2 n
//! automorphisms kept: each at least doubles the group). An irregular
//! mesh has a small rarest class; a regular torus has every dart in one class, but after a few
//! automorphisms (translations, rotations) every start is in a tried orbit, so it costs a
//! handful of full passes, not O(n²). Components are coded separately and their codes sorted.

use super::counts::vertex_components;
use crate::map::{Map, NONE};
use alloc::vec;
use alloc::vec::Vec;

/// A canonical code: equal for two maps exactly when they are isomorphic (orientation
/// preserving, boundary included), whatever their handle numbering and dead slots.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::canonical::CanonicalCode};
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
    /// use zipmesh_kernel::{invariants::canonical::CanonicalCode, Map};
    /// let a = Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    /// let b = Map::from_polygons(4, &[[3u32, 1, 0], [1, 2, 0]]).unwrap();
    /// assert_eq!(CanonicalCode::of(&a), CanonicalCode::of(&b));
    /// ```
    pub fn of(map: &Map) -> CanonicalCode {
        Canonizer::new(map, Buffers::default()).code()
    }

    /// The 128-bit XXH3 hash of the code.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, invariants::canonical::CanonicalCode};
    /// let h = CanonicalCode::of(&gen::torus_grid(4, 4).map).hash();
    /// assert_ne!(h, CanonicalCode::of(&gen::torus_grid(4, 5).map).hash());
    /// ```
    pub fn hash(&self) -> u128 {
        // Streamed in chunks: the same hash as of the whole byte string, without a copy of it.
        let mut h = xxhash_rust::xxh3::Xxh3::new();
        let mut buf = [0u8; 4096];
        for chunk in self.0.chunks(buf.len() / 4) {
            for (b, x) in buf.chunks_exact_mut(4).zip(chunk) {
                b.copy_from_slice(&x.to_le_bytes());
            }
            h.update(&buf[..chunk.len() * 4]);
        }
        h.digest128()
    }
}

/// The arrays of canonical coding, kept from one map to the next: for many codes of large
/// maps. [`CanonicalCode::of`] allocates its dart-sized arrays per call, and on a large map
/// their fresh pages cost a quarter to a third of its time (the 99,856-quad torus: about
/// 22 ms a call, 16 ms with a workspace; cut, 14 and 9.5 ms; `docs/benchmarks.md`). The codes
/// are the same.
///
/// The workspace holds what its largest map needed: about 35 bytes per dart on those tori
/// (the runs' labels, order and code, the keys, the closure's lists, one array per
/// automorphism found).
///
/// ```
/// use zipmesh_kernel::{gen, invariants::canonical::{CanonicalCode, CanonicalWorkspace}};
/// let mut ws = CanonicalWorkspace::new();
/// for m in [gen::torus_grid(6, 5).map, gen::cube(2).map, gen::grid(3, 4).map] {
///     assert_eq!(ws.code(&m), &CanonicalCode::of(&m));
///     assert_eq!(ws.hash(&m), CanonicalCode::of(&m).hash());
/// }
/// ```
pub struct CanonicalWorkspace {
    buffers: Buffers,
    code: CanonicalCode,
}

impl Default for CanonicalWorkspace {
    fn default() -> Self {
        CanonicalWorkspace {
            buffers: Buffers::default(),
            code: CanonicalCode(Vec::new()),
        }
    }
}

impl core::fmt::Debug for CanonicalWorkspace {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("CanonicalWorkspace")
            .field("code_len", &self.code.0.len())
            .finish_non_exhaustive()
    }
}

impl CanonicalWorkspace {
    /// An empty workspace; its arrays grow with the maps it codes.
    ///
    /// See [`CanonicalWorkspace`] for an example.
    pub fn new() -> Self {
        Self::default()
    }

    /// The canonical code of `map` ([`CanonicalCode::of`]), kept until the next call.
    ///
    /// See [`CanonicalWorkspace`] for an example.
    pub fn code(&mut self, map: &Map) -> &CanonicalCode {
        let mut buffers = core::mem::take(&mut self.buffers);
        // The last code's array is written again, as the best run's code.
        if buffers.best.code.capacity() < self.code.0.capacity() {
            buffers.best.code = core::mem::take(&mut self.code.0);
        }
        let mut cz = Canonizer::new(map, buffers);
        self.code = cz.code();
        self.buffers = cz.buffers();
        &self.code
    }

    /// The 128-bit hash of the canonical code of `map` ([`CanonicalCode::hash`]).
    ///
    /// See [`CanonicalWorkspace`] for an example.
    pub fn hash(&mut self, map: &Map) -> u128 {
        self.code(map).hash()
    }
}

/// The 128-bit hash of the canonical code of `map`.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::canonical::canonical_hash};
/// assert_eq!(canonical_hash(&gen::cube(2).map), canonical_hash(&gen::cube(2).map));
/// ```
pub fn canonical_hash(map: &Map) -> u128 {
    CanonicalCode::of(map).hash()
}

/// Whether an orientation-preserving isomorphism maps `a` onto `b`.
///
/// ```
/// use zipmesh_kernel::{gen, is_isomorphic};
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
/// use zipmesh_kernel::{is_isomorphic, is_isomorphic_mirror, Map};
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

/// Room at the front of a run's code for the output's header (component count and length),
/// so that a connected map's code is returned without a copy.
const HEAD: usize = 2;

/// One component's start class: every dart of a map with no dead slot, kept implicit (the
/// list would be the identity, 1.6 MB written on a 100,000-quad torus), or a list.
enum Starts {
    All(usize),
    Listed(Vec<u32>),
}

impl Starts {
    fn len(&self) -> usize {
        match self {
            Starts::All(n) => *n,
            Starts::Listed(l) => l.len(),
        }
    }

    /// The start at position `k` (below [`Starts::len`]).
    fn get(&self, k: usize) -> u32 {
        match self {
            Starts::All(_) => k as u32,
            Starts::Listed(l) => l[k],
        }
    }

    #[cfg(test)]
    fn to_vec(&self) -> Vec<u32> {
        (0..self.len()).map(|k| self.get(k)).collect()
    }
}

/// What a walk reads of the map: `next`, and the boundary bits packed (a small array that
/// stays in cache, where `face` would be one more stream of misses).
struct Links<'a> {
    next: &'a [u32],
    boundary: Vec<u64>,
}

impl Links<'_> {
    /// The links of `map`, the bits written into `boundary` (a buffer reused).
    fn new(map: &Map, mut boundary: Vec<u64>) -> Links<'_> {
        boundary.clear();
        boundary.resize(map.face.len().div_ceil(64), 0);
        for (d, &f) in map.face.iter().enumerate() {
            boundary[d / 64] |= u64::from(f == NONE) << (d % 64);
        }
        Links {
            next: &map.next,
            boundary,
        }
    }

    #[inline(always)]
    fn boundary(&self, d: usize) -> u32 {
        (self.boundary[d / 64] >> (d % 64)) as u32 & 1
    }
}

/// One breadth-first numbering in progress.
#[derive(Default)]
struct Run {
    /// Per dart: its number, or `NONE`.
    label: Vec<u32>,
    /// The darts in numbering order; one spare entry for a write that is not kept.
    order: Vec<u32>,
    /// How many darts are numbered, and how many of them have emitted their symbol.
    len: usize,
    i: usize,
    /// `HEAD` spare entries, then two entries per symbol; sized only for the best run.
    code: Vec<u32>,
}

impl Run {
    /// Ready for a map of `nd` dart slots, reusing the arrays of the last map: its labels
    /// cleared (as [`Run::clear`] does), then the arrays sized. Whether the labels needed a
    /// new array.
    fn prepare(&mut self, nd: usize, spare: &mut Vec<Vec<u32>>) -> bool {
        let fresh = self.restock(spare) || self.label.capacity() < nd;
        self.clear();
        self.label.resize(nd, NONE);
        room(&mut self.order, nd + 1);
        fresh
    }

    /// If an automorphism took the labels (`Canonizer::automorphism`): new ones, every dart
    /// unnumbered, in an array from `spare` when there is one (a fresh array costs a page
    /// fault per 1,024 darts). Whether a fresh array was needed.
    fn restock(&mut self, spare: &mut Vec<Vec<u32>>) -> bool {
        if self.label.len() + 1 == self.order.len() {
            return false;
        }
        let nd = self.order.len().saturating_sub(1);
        let mut label = spare.pop().unwrap_or_default();
        let fresh = label.capacity() < nd;
        label.clear();
        label.resize(nd, NONE);
        self.label = label;
        self.len = 0;
        self.i = 0;
        fresh
    }

    /// Clears the labels of the last numbering.
    fn clear(&mut self) {
        if self.len * 4 >= self.label.len() {
            // Most darts were numbered: one sequential fill beats scattered resets.
            self.label.fill(NONE);
        } else {
            for &d in &self.order[..self.len] {
                self.label[d as usize] = NONE;
            }
        }
        self.len = 0;
        self.i = 0;
    }

    /// Clears the last numbering and starts a new one at `s`. Whether the labels needed a
    /// new array: only if an automorphism took them and [`Run::restock`] was not called.
    fn start(&mut self, s: u32) -> bool {
        self.clear();
        let nd = self.order.len() - 1;
        let fresh = self.label.len() != nd;
        if fresh {
            self.label = vec![NONE; nd];
        }
        self.label[s as usize] = 0;
        self.order[0] = s;
        self.len = 1;
        fresh
    }

    /// The walk state in locals, so that the hot loop keeps it in registers.
    fn walker(&mut self) -> (Walker<'_>, &mut Vec<u32>) {
        let w = Walker {
            label: &mut self.label,
            order: &mut self.order,
            len: self.len,
            i: self.i,
        };
        (w, &mut self.code)
    }
}

/// A [`Run`]'s numbering, borrowed for a stretch of steps; `len` and `i` are written back.
struct Walker<'r> {
    label: &'r mut [u32],
    order: &'r mut [u32],
    len: usize,
    i: usize,
}

impl Walker<'_> {
    /// The label of `x`, numbering it next if it has none. (A branch-free version was about
    /// 10 % slower: measured, `docs/benchmarks.md`.)
    #[inline(always)]
    fn label(&mut self, x: usize) -> u32 {
        let old = self.label[x];
        if old != NONE {
            return old;
        }
        let l = self.len as u32;
        self.label[x] = l;
        self.order[self.len] = x as u32;
        self.len += 1;
        l
    }

    /// The next symbol of the code, `None` once the component is numbered.
    #[inline(always)]
    fn step(&mut self, links: &Links) -> Option<[u32; 2]> {
        if self.i >= self.len {
            return None;
        }
        let d = self.order[self.i] as usize;
        let n = links.next[d] as usize;
        let sym = [self.label(n), self.label(d ^ 1) * 2 + links.boundary(d)];
        self.i += 1;
        Some(sym)
    }
}

/// The starts (by position in one component's start class) that the automorphisms found so
/// far reach from the tried ones. Closing under the generators (images only: in a finite
/// group the inverses are powers) gives exactly the orbits of the group they generate.
#[derive(Default)]
struct Orbits {
    /// Per automorphism found: the position of the image of each start.
    gens: Vec<Vec<u32>>,
    /// Per start: whether it is in the orbit of a tried start; and those starts, listed in
    /// `members[..len]` (one spare entry past the last start, see [`Orbits::mark`]).
    reached: Vec<bool>,
    members: Vec<u32>,
    len: usize,
}

impl Orbits {
    fn reset(&mut self, k: usize) {
        self.gens.clear();
        self.reached.clear();
        self.reached.resize(k, false);
        // Every start ends up listed once (tried or reached), plus the spare entry.
        self.members.clear();
        self.members.resize(k + 1, 0);
        self.len = 0;
    }

    /// The starts reached so far.
    #[cfg(test)]
    fn members(&self) -> &[u32] {
        &self.members[..self.len]
    }

    /// Marks the orbit of start `t` as tried.
    fn add(&mut self, t: u32) {
        let from = self.len;
        self.mark(t);
        self.close(from);
    }

    /// Adds an automorphism: applied to every start reached so far, then closed.
    fn add_gen(&mut self, g: Vec<u32>) {
        // The old members are closed under the old generators already.
        let old = self.len;
        for k in 0..old {
            self.mark(g[self.members[k] as usize]);
        }
        self.gens.push(g);
        self.close(old);
    }

    /// Lists `t` if it is new. Without a branch: in a closure about half the images are
    /// new, at random, and the mispredicted branch cost more than the rest of the step. The
    /// write always lands (on the spare entry once every start is listed) and counts only
    /// when `t` is new.
    #[inline]
    fn mark(&mut self, t: u32) {
        let new = !core::mem::replace(&mut self.reached[t as usize], true);
        self.members[self.len] = t;
        self.len += usize::from(new);
    }

    /// Applies every generator to the members from index `from` on (and to the new ones).
    fn close(&mut self, mut from: usize) {
        while from < self.len {
            let x = self.members[from] as usize;
            for j in 0..self.gens.len() {
                let y = self.gens[j][x];
                self.mark(y);
            }
            from += 1;
        }
    }
}

/// The arrays of a [`Canonizer`], kept by a [`CanonicalWorkspace`] from one map to the next.
#[derive(Default)]
struct Buffers {
    boundary: Vec<u64>,
    keys: Keys,
    best: Run,
    cand: Run,
    orbits: Orbits,
    pos: Vec<u32>,
    /// Dart-sized arrays that automorphisms took and gave back: the next labels to use.
    spare: Vec<Vec<u32>>,
}

struct Canonizer<'a> {
    map: &'a Map,
    links: Links<'a>,
    keys: Keys,
    /// The best run so far (recording) and the candidate run.
    best: Run,
    cand: Run,
    orbits: Orbits,
    /// Per dart: its position in the current component's start class, once needed.
    pos: Vec<u32>,
    spare: Vec<Vec<u32>>,
    /// Every automorphism found, with its start class (the tests check each one).
    #[cfg(test)]
    found: Vec<(Vec<u32>, Vec<u32>)>,
    /// How many label or automorphism arrays were new (none on a second call with the same
    /// workspace).
    fresh: usize,
}

impl<'a> Canonizer<'a> {
    /// A canonizer of `map` working in `b`'s arrays (given back by [`Canonizer::buffers`]).
    fn new(map: &'a Map, b: Buffers) -> Self {
        let nd = map.next.len();
        let mut cz = Canonizer {
            map,
            links: Links::new(map, b.boundary),
            keys: b.keys,
            best: b.best,
            cand: b.cand,
            orbits: b.orbits,
            pos: b.pos,
            spare: b.spare,
            #[cfg(test)]
            found: Vec::new(),
            fresh: 0,
        };
        let fresh = [
            cz.best.prepare(nd, &mut cz.spare),
            cz.cand.prepare(nd, &mut cz.spare),
        ];
        cz.fresh = fresh.iter().filter(|&&f| f).count();
        cz
    }

    /// The arrays back, for the next map.
    fn buffers(self) -> Buffers {
        let (mut spare, mut orbits) = (self.spare, self.orbits);
        spare.append(&mut orbits.gens);
        Buffers {
            boundary: self.links.boundary,
            keys: self.keys,
            best: self.best,
            cand: self.cand,
            orbits,
            pos: self.pos,
            spare,
        }
    }

    fn code(&mut self) -> CanonicalCode {
        let mut keys = core::mem::take(&mut self.keys);
        keys.fill(self.map);
        let code = self.code_with(&keys);
        self.keys = keys;
        code
    }

    fn code_with(&mut self, keys: &Keys) -> CanonicalCode {
        let map = self.map;
        let live = |d: &usize| map.next[*d] != NONE;
        // Most maps are connected: code the map as one component, and label components only
        // when a walk ends short of every dart (the labelling, a union-find over every edge,
        // was about 5 % of a cut torus's time).
        let starts = if keys.uniform && map.num_darts() == map.next.len() {
            Starts::All(map.next.len())
        } else {
            Starts::Listed(class(map, keys, (0..map.next.len()).filter(live)))
        };
        if let Some(mut code) = self.component_code(&starts, map.num_darts(), true) {
            code[0] = 1;
            code[1] = (code.len() - HEAD) as u32;
            return CanonicalCode(code);
        }
        #[cfg(test)]
        self.found.clear();
        let (vcomp, n_comp) = vertex_components(map);
        let comp_of = |d: usize| vcomp[map.vert[d] as usize] as usize;
        // Darts grouped by component (a counting sort), then the rarest key class of each.
        let mut comp_start = vec![0usize; n_comp + 1];
        for d in (0..map.next.len()).filter(live) {
            comp_start[comp_of(d) + 1] += 1;
        }
        for c in 0..n_comp {
            comp_start[c + 1] += comp_start[c];
        }
        let mut by_comp = vec![0u32; comp_start[n_comp]];
        let mut fill = comp_start.clone();
        for d in (0..map.next.len()).filter(live) {
            by_comp[fill[comp_of(d)]] = d as u32;
            fill[comp_of(d)] += 1;
        }
        let mut parts: Vec<Vec<u32>> = Vec::with_capacity(n_comp);
        for c in 0..n_comp {
            let darts = &by_comp[comp_start[c]..comp_start[c + 1]];
            let starts = Starts::Listed(class(map, keys, darts.iter().map(|&d| d as usize)));
            let code = self.component_code(&starts, darts.len(), false);
            parts.push(code.unwrap_or_default().split_off(HEAD));
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

    /// The least code over `starts` (one component's start class), with `HEAD` spare entries
    /// in front. The best run is stepped only as far as a candidate needs it, so a start that
    /// loses is never numbered in full, and only the winner's code is written out. A start in
    /// the orbit of a tried one under the automorphisms found is skipped: it reads the same.
    ///
    /// With `whole`, the starts are the whole map's and `None` says, as soon as a walk ends
    /// short of `size` darts, that the map is not connected (before any automorphism is
    /// taken from two components).
    fn component_code(&mut self, starts: &Starts, size: usize, whole: bool) -> Option<Vec<u32>> {
        if starts.len() == 0 {
            return Some(vec![0; HEAD]);
        }
        let first = starts.get(0);
        let short = |r: &Run| r.i >= r.len && r.len < size;
        // The best run's labels are never taken: its start needs no new array.
        self.best.start(first);
        room(&mut self.best.code, HEAD + 2 * size);
        self.spare.append(&mut self.orbits.gens);
        self.orbits.reset(starts.len());
        self.orbits.add(0);
        let mut pos_ready = false;
        for k in 1..starts.len() {
            if self.orbits.reached[k] {
                continue;
            }
            let result = self.race(starts.get(k), size);
            if whole && (short(&self.best) || short(&self.cand)) {
                return None;
            }
            if result == Cmp::Better {
                core::mem::swap(&mut self.best, &mut self.cand);
            } else if result == Cmp::Equal {
                // Positions are darts when every dart is a start (`automorphism`).
                if !pos_ready && starts.len() != self.map.next.len() {
                    self.pos.resize(self.map.next.len(), 0);
                    for j in 0..starts.len() {
                        self.pos[starts.get(j) as usize] = j as u32;
                    }
                    pos_ready = true;
                }
                let g = self.automorphism(starts);
                #[cfg(test)]
                self.found.push((starts.to_vec(), g.clone()));
                self.orbits.add_gen(g);
            }
            self.orbits.add(k as u32);
        }
        self.finish();
        if whole && short(&self.best) {
            return None;
        }
        // The runs' labels are cleared by their next `start`.
        Some(core::mem::take(&mut self.best.code))
    }

    /// A dart-sized array given back by an old automorphism, if any (its contents stale).
    fn spare_array(&mut self) -> Vec<u32> {
        self.spare.pop().unwrap_or_default()
    }

    /// Candidate and best read the same code, so mapping the candidate's numbering onto the
    /// best's is an automorphism; the start class is invariant under it. Its action on the
    /// starts, by position.
    fn automorphism(&mut self, starts: &Starts) -> Vec<u32> {
        if starts.len() == self.map.next.len() {
            // Every dart is a start (a regular closed map with no dead slot), so positions
            // are darts. Both runs numbered every dart (an `Equal` race): the candidate's
            // labels become the map in place (`label[c]`, the position of `c`, to
            // `best.order` there), and the candidate gets new labels only if another race
            // follows. The identity backs only a broken invariant.
            let mut g = core::mem::take(&mut self.cand.label);
            for (c, x) in g.iter_mut().enumerate() {
                *x = self
                    .best
                    .order
                    .get(*x as usize)
                    .copied()
                    .unwrap_or(c as u32);
            }
            return g;
        }
        // Both runs numbered the component, so every start has an image; the fallback only
        // keeps a broken invariant from indexing out of range.
        let mut g = self.spare_array();
        self.fresh += usize::from(g.capacity() < starts.len());
        let image = |c: u32| {
            let b = self.best.order.get(self.cand.label[c as usize] as usize)?;
            Some(self.pos[*b as usize]).filter(|&p| (p as usize) < starts.len())
        };
        g.clear();
        g.extend((0..starts.len()).map(|x| image(starts.get(x)).unwrap_or(x as u32)));
        g
    }

    /// Numbers the component from `s` in the candidate run, symbol by symbol against the best
    /// run (stepped, and its code written, only as far as needed), until they differ. On
    /// `Better` the candidate gets its code so far, so it can take the best run's place.
    fn race(&mut self, s: u32, size: usize) -> Cmp {
        self.fresh += usize::from(self.cand.restock(&mut self.spare));
        self.fresh += usize::from(self.cand.start(s));
        let links = &self.links;
        let (mut b, code) = self.best.walker();
        let (mut c, _) = self.cand.walker();
        let mut i = 0;
        let (result, x) = loop {
            let x = c.step(links);
            let k = HEAD + 2 * i;
            let y = if i < b.i {
                code.get(k..k + 2).map(|y| [y[0], y[1]])
            } else {
                let y = b.step(links);
                put(code, k, y);
                y
            };
            if x != y {
                break (if x < y { Cmp::Better } else { Cmp::Worse }, x);
            }
            if x.is_none() {
                break (Cmp::Equal, x);
            }
            i += 1;
        };
        (self.best.len, self.best.i) = (b.len, b.i);
        (self.cand.len, self.cand.i) = (c.len, c.i);
        if result == Cmp::Better {
            // The candidate's code so far, in its own array.
            let k = HEAD + 2 * i;
            let new = &mut self.cand.code;
            room(new, HEAD + 2 * size);
            new[..k].copy_from_slice(&self.best.code[..k]);
            put(new, k, x);
        }
        result
    }

    /// Steps the best run to the end of its component.
    fn finish(&mut self) {
        let (mut b, code) = self.best.walker();
        while let Some(y) = b.step(&self.links) {
            put(code, HEAD + 2 * (b.i - 1), Some(y));
        }
        (self.best.len, self.best.i) = (b.len, b.i);
        self.best.code.truncate(HEAD + 2 * self.best.i);
    }
}

/// Sizes `v` to `n` entries whose values do not matter (a run's order and code: each entry
/// is written before it is read): in place if it has the room, else a new zeroed array, whose
/// pages the system provides only where they are written (a run that loses early writes a
/// few; resizing would write every one).
fn room(v: &mut Vec<u32>, n: usize) {
    if v.capacity() < n {
        *v = vec![0; n];
    } else {
        v.resize(n, 0);
    }
}

/// Writes symbol `y` (if any) at `code[k..k + 2]` (if in range).
#[inline(always)]
fn put(code: &mut [u32], k: usize, y: Option<[u32; 2]>) {
    if let (Some(y), Some(at)) = (y, code.get_mut(k..k + 2)) {
        at.copy_from_slice(&y);
    }
}

/// The rarest key class of `darts` (smallest key on a tie), in dart order: every dart when
/// all keys are the same ([`Keys::uniform`]), else from a first pass that notes, per dart,
/// its key's slot in the short list (each key computed once).
fn class(map: &Map, keys: &Keys, darts: impl Iterator<Item = usize> + Clone) -> Vec<u32> {
    // Sized once: collecting through a filter regrew the list about twice over.
    let mut out = Vec::with_capacity(darts.size_hint().1.unwrap_or(0));
    if keys.uniform {
        out.extend(darts.map(|d| d as u32));
        return out;
    }
    let mut slot: Vec<u8> = Vec::with_capacity(darts.size_hint().1.unwrap_or(0));
    let (best_key, best_slot) = rarest(darts.clone().map(|d| keys.of(map, d)), &mut slot);
    out.extend(
        darts
            .zip(&slot)
            .filter(|&(d, &j)| match best_slot {
                Some(b) => j == b,
                None => j == MANY && keys.of(map, d) == best_key,
            })
            .map(|(d, _)| d as u32),
    );
    out
}

/// A dart whose key is not in the short list of [`rarest`].
const MANY: u8 = u8::MAX;

/// Per dart: an isomorphism-invariant key (boundary bit, cycle length, origin and
/// destination valences, each capped to 21 bits), computed on demand. Cycle lengths are kept
/// per face (a face dart's cycle is its face), and per dart only for boundary darts.
#[derive(Default)]
struct Keys {
    /// Per vertex: its valence; per face: its degree.
    valence: Vec<u32>,
    degree: Vec<u32>,
    /// Per dart: its boundary loop's length, 0 off the boundary; empty on a closed map.
    loops: Vec<u32>,
    /// Whether every dart has the same key: a closed map whose live vertices have one
    /// valence and live faces one degree (told from the vertices and faces, without a key).
    uniform: bool,
}

impl Keys {
    #[cfg(test)]
    fn new(map: &Map) -> Keys {
        let mut keys = Keys::default();
        keys.fill(map);
        keys
    }

    /// The keys of `map`, in the arrays of the last map's.
    fn fill(&mut self, map: &Map) {
        let valence = &mut self.valence;
        valence.clear();
        valence.resize(map.vdart.len(), 0);
        for (&n, &v) in map.next.iter().zip(&map.vert) {
            if n != NONE {
                if let Some(x) = valence.get_mut(v as usize) {
                    *x += 1;
                }
            }
        }
        self.degree.clear();
        self.degree.extend(map.fdart.iter().map(|&d| {
            if d == NONE {
                0
            } else {
                cycle_len(map, d as usize)
            }
        }));
        // A vertex with a boundary dart keeps one as its dart, so the vertices tell whether
        // there is a boundary (a quarter of the reads of a pass over the darts).
        let closed = !(map.vdart.iter()).any(|&d| map.face.get(d as usize) == Some(&NONE));
        let one = |x: &[u32], live: &[u32]| {
            let mut values = (x.iter().zip(live)).filter(|p| *p.1 != NONE).map(|p| *p.0);
            values.next().is_none_or(|v| values.all(|w| w == v))
        };
        self.uniform = closed && one(&self.valence, &map.vdart) && one(&self.degree, &map.fdart);
        self.loops.clear();
        if !closed {
            boundary_loops(map, &mut self.loops);
        }
    }

    #[inline]
    fn of(&self, map: &Map, d: usize) -> u64 {
        let cap = |x: u32| u64::from(x.min((1 << 21) - 1));
        let f = map.face[d];
        let cycle = if f == NONE {
            self.loops.get(d)
        } else {
            self.degree.get(f as usize)
        };
        u64::from(f == NONE) << 63
            | cap(cycle.copied().unwrap_or(0)) << 42
            | cap(self.valence[map.vert[d] as usize]) << 21
            | cap(self.valence[map.vert[d ^ 1] as usize])
    }
}

/// The key with the fewest darts (the smallest key on a tie); per key, its slot in the short
/// list (or [`MANY`]) is pushed to `slot`, and the winner's slot is returned with it. Meshes
/// have few distinct keys, so a short list is scanned before a hash map is needed.
fn rarest(keys: impl Iterator<Item = u64>, slot: &mut Vec<u8>) -> (u64, Option<u8>) {
    let mut few: Vec<(u64, u32)> = Vec::new();
    let mut many: hashbrown::HashMap<u64, u32> = hashbrown::HashMap::new();
    for k in keys {
        if let Some(j) = few.iter().position(|e| e.0 == k) {
            few[j].1 += 1;
            slot.push(j as u8);
        } else if few.len() < 16 {
            slot.push(few.len() as u8);
            few.push((k, 1));
        } else {
            *many.entry(k).or_insert(0) += 1;
            slot.push(MANY);
        }
    }
    let (_, key, j) = few
        .iter()
        .enumerate()
        .map(|(j, &(k, c))| (c, k, Some(j as u8)))
        .chain(many.iter().map(|(&k, &c)| (c, k, None)))
        .min()
        .unwrap_or((0, 0, None));
    (key, j)
}

/// The length of the `next` cycle through `d0` (bounded by the dart count, so that a broken
/// cycle cannot loop forever).
fn cycle_len(map: &Map, d0: usize) -> u32 {
    let (mut len, mut d) = (0u32, d0);
    while len as usize <= map.next.len() {
        len += 1;
        d = map.next.get(d).map_or(d0, |&n| n as usize);
        if d == d0 {
            break;
        }
    }
    len
}

/// Per dart: the length of its boundary loop, 0 for a dart with a face (into `loops`,
/// empty).
fn boundary_loops(map: &Map, loops: &mut Vec<u32>) {
    loops.clear();
    loops.resize(map.next.len(), 0);
    for d0 in 0..map.next.len() {
        if map.next[d0] == NONE || map.face[d0] != NONE || loops[d0] != 0 {
            continue;
        }
        let len = cycle_len(map, d0);
        let mut d = d0;
        for _ in 0..len {
            if let Some(x) = loops.get_mut(d) {
                *x = len;
            }
            d = map.next.get(d).map_or(d0, |&n| n as usize);
        }
    }
}

/// The dart of `candidates` whose breadth-first numbering (the one of the canonical code,
/// started from it) reads smallest; `None` if there are none. Two candidates related by an
/// isomorphism read the same, so the choice depends on the map, not on its handles.
///
/// The walks are compared symbol by symbol and stop at the first difference, which near an
/// irregular vertex comes within a few rings: the cost is local, not O(map), unless two
/// candidates are related by an automorphism (then the whole component is read, and either
/// is right). The two walks' labels and lists are reused from one comparison to the next.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::canonical::least_start};
/// let map = gen::torus_grid(4, 4).map;
/// let darts: Vec<_> = map.darts().collect();
/// // Every dart of the regular torus reads the same: the first is kept.
/// assert_eq!(least_start(&map, &darts), Some(darts[0]));
/// assert_eq!(least_start(&map, &[]), None);
/// ```
pub fn least_start(map: &Map, candidates: &[crate::Dart]) -> Option<crate::Dart> {
    let mut best = *candidates.first()?;
    let (mut wa, mut wb) = (Walk::new(map, best), Walk::new(map, best));
    for &c in &candidates[1..] {
        wa.restart(c);
        wb.restart(best);
        if compare_walks(map, &mut wa, map, &mut wb) == core::cmp::Ordering::Less {
            best = c;
        }
    }
    Some(best)
}

/// How the reading from `a` compares with the one from `b` (each dart with its map): `Equal`
/// exactly when an isomorphism of their components maps `a` to `b`.
#[cfg(test)]
fn compare_starts(a: (&Map, crate::Dart), b: (&Map, crate::Dart)) -> core::cmp::Ordering {
    let (mut wa, mut wb) = (Walk::new(a.0, a.1), Walk::new(b.0, b.1));
    compare_walks(a.0, &mut wa, b.0, &mut wb)
}

/// [`compare_starts`] on two walks just started (`wa` on `ma`, `wb` on `mb`).
fn compare_walks(ma: &Map, wa: &mut Walk, mb: &Map, wb: &mut Walk) -> core::cmp::Ordering {
    loop {
        match (wa.step(ma), wb.step(mb)) {
            (Some(x), Some(y)) if x == y => continue,
            (x, y) => return x.cmp(&y),
        }
    }
}

/// Whether an isomorphism of the whole maps takes dart `a` of the first to dart `b` of the
/// second: the breadth-first readings from the two agree (the walk of [`least_start`]) and each
/// reads every live dart of its map, so both maps are connected. `true` implies equal
/// canonical codes; `false` says nothing when an isomorphism exists that moves the anchor.
/// Dense labels (one slot per dart): the walk reads the whole map when it succeeds.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::canonical::same_from};
/// let (a, b) = (gen::cube(2).map, gen::cube(2).map);
/// let d = a.darts().next().unwrap();
/// assert!(same_from((&a, d), (&b, d)));
/// assert!(!same_from((&a, d), (&gen::cube(3).map, d)));
/// ```
pub fn same_from(a: (&Map, crate::Dart), b: (&Map, crate::Dart)) -> bool {
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
    label: Labels,
    order: Vec<u32>,
    i: usize,
}

/// At most this many dart slots, a [`Walk`]'s labels are an array (at most 16 KiB, cleared
/// walk by walk); beyond, a hash map, so that a walk that stops after a few rings touches
/// little of a large map.
const DENSE_LABELS: usize = 4096;

/// A walk's labels by dart.
enum Labels {
    Dense(Vec<u32>),
    Sparse(hashbrown::HashMap<u32, u32>),
}

impl Walk {
    fn new(map: &Map, s: crate::Dart) -> Walk {
        let n = map.next.len();
        let label = if n <= DENSE_LABELS {
            Labels::Dense(vec![NONE; n])
        } else {
            Labels::Sparse(hashbrown::HashMap::new())
        };
        Walk::with(label, s)
    }

    /// A walk from `s` with the given (empty) labels.
    fn with(label: Labels, s: crate::Dart) -> Walk {
        let mut w = Walk {
            label,
            order: Vec::new(),
            i: 0,
        };
        w.restart(s);
        w
    }

    /// Forgets the last numbering (keeping its memory) and starts again at `s`.
    fn restart(&mut self, s: crate::Dart) {
        match &mut self.label {
            Labels::Dense(l) => {
                for &d in &self.order {
                    l[d as usize] = NONE;
                }
            }
            Labels::Sparse(l) => l.clear(),
        }
        self.order.clear();
        self.i = 0;
        self.label(s.index() as u32);
    }

    /// The label of dart `d`, numbering it next if it has none.
    fn label(&mut self, d: u32) -> u32 {
        let next = self.order.len() as u32;
        let l = match &mut self.label {
            Labels::Dense(l) => match l.get_mut(d as usize) {
                Some(x) if *x == NONE => {
                    *x = next;
                    next
                }
                Some(x) => *x,
                // Not a slot of this map: a broken map's dart, numbered but never kept.
                None => next,
            },
            Labels::Sparse(l) => *l.entry(d).or_insert(next),
        };
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

    /// The code from its definition: per component, the least full reading over the starts
    /// of the rarest key (smallest key on a tie), no early exit and no orbit pruning.
    fn reference_code(map: &Map) -> CanonicalCode {
        let (vcomp, n_comp) = vertex_components(map);
        let keys = Keys::new(map);
        let mut parts: Vec<Vec<u32>> = (0..n_comp as u32)
            .map(|c| {
                let darts: Vec<usize> = (0..map.next.len())
                    .filter(|&d| map.next[d] != NONE && vcomp[map.vert[d] as usize] == c)
                    .collect();
                let mut count = alloc::collections::BTreeMap::new();
                for &d in &darts {
                    *count.entry(keys.of(map, d)).or_insert(0usize) += 1;
                }
                let (_, key) = count.iter().map(|(&k, &n)| (n, k)).min().unwrap();
                darts
                    .iter()
                    .filter(|&&d| keys.of(map, d) == key)
                    .map(|&d| {
                        let mut w = Walk::new(map, Dart::new(d as u32));
                        core::iter::from_fn(|| w.step(map)).flatten().collect()
                    })
                    .min()
                    .unwrap()
            })
            .collect();
        parts.sort_by(|a: &Vec<u32>, b| a.len().cmp(&b.len()).then_with(|| a.cmp(b)));
        let mut out = vec![parts.len() as u32];
        for p in parts {
            out.push(p.len() as u32);
            out.extend(p);
        }
        CanonicalCode(out)
    }

    /// A torus with `cuts` quads (from `seed`) cut into two triangles, plus `extra` polygons.
    fn cut_torus(nx: usize, ny: usize, cuts: usize, seed: u64) -> Vec<Vec<u32>> {
        let mut rng = crate::rng::Rng::new(seed);
        let mut quads: Vec<Vec<u32>> = gen::torus_quads(nx, ny)
            .iter()
            .map(|q| q.to_vec())
            .collect();
        for _ in 0..cuts {
            let i = rng.below(quads.len());
            if quads[i].len() == 4 {
                let q = quads.swap_remove(i);
                quads.push(vec![q[0], q[1], q[2]]);
                quads.push(vec![q[0], q[2], q[3]]);
            }
        }
        quads
    }

    #[test]
    fn the_code_is_the_least_reading_over_the_start_class() {
        // The early exits, the lazily stepped best run and the orbit pruning must not change
        // the code: compare with the definition on symmetric, irregular, bounded and
        // disconnected maps.
        let mut maps = vec![
            gen::cube(2).map,
            gen::grid(4, 3).map,
            gen::icosahedron().map,
            gen::random_quad(60, 1, 2, 7).map,
            gen::random_triangle(80, 2, 0, 8).map,
            gen::random_mixed(70, 0, 3, 9).map,
            // A soup of 30 triangles: 30 isomorphic components.
            Map::from_polygons(
                90,
                &(0..30u32)
                    .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
                    .collect::<Vec<_>>(),
            )
            .unwrap(),
        ];
        for (nx, ny) in [(3, 3), (4, 4), (6, 5), (9, 9)] {
            maps.push(gen::torus_grid(nx, ny).map);
            // Two plain tori: one key everywhere, every dart a start, two components.
            let plain = cut_torus(nx, ny, 0, 0);
            let shift = |p: &Vec<u32>| p.iter().map(|&v| v + (nx * ny) as u32).collect();
            let two: Vec<Vec<u32>> = plain
                .iter()
                .cloned()
                .chain(plain.iter().map(shift))
                .collect();
            maps.push(Map::from_polygons(2 * nx * ny, &two).unwrap());
            for (cuts, seed) in [(1, 1), (2, 2), (3, 3), (5, 4)] {
                let polys = cut_torus(nx, ny, cuts, seed);
                maps.push(Map::from_polygons(nx * ny, &polys).unwrap());
                // Two copies side by side, and the cut torus beside a plain one.
                let shift = |p: &Vec<u32>| p.iter().map(|&v| v + (nx * ny) as u32).collect();
                let plain = cut_torus(nx, ny, 0, 0);
                for other in [&polys, &plain] {
                    let mut two = polys.clone();
                    two.extend(other.iter().map(shift));
                    maps.push(Map::from_polygons(2 * nx * ny, &two).unwrap());
                }
            }
        }
        for map in &maps {
            assert_eq!(CanonicalCode::of(map), reference_code(map));
        }
    }

    /// The keys as defined, dart by dart: the cycle length walked from each live dart, its
    /// boundary bit and both valences, on closed and bounded maps and on one with dead slots
    /// (the per-face degrees and the boundary-only loop lengths must give the same); and
    /// `uniform` exactly when every key is the same, and a loop length only on the
    /// boundary.
    #[test]
    fn keys_follow_their_definition() {
        let mut edited = gen::random_quad(40, 0, 1, 3).map;
        let collapsed = (0..edited.next.len() as u32)
            .filter(|&d| crate::ops::quad::collapse_quad(&mut edited, Dart::new(d)).is_ok())
            .take(3)
            .count();
        assert_eq!(collapsed, 3);
        let maps = [
            gen::torus_grid(5, 4).map,
            gen::cube(2).map,
            gen::icosahedron().map,
            gen::grid(4, 3).map,
            gen::random_quad(60, 1, 2, 7).map,
            gen::random_mixed(70, 0, 3, 9).map,
            Map::from_polygons(9, &cut_torus(3, 3, 2, 1)).unwrap(),
            edited,
        ];
        for map in &maps {
            let keys = Keys::new(map);
            let mut loops = Vec::new();
            boundary_loops(map, &mut loops);
            let live: Vec<usize> = (0..map.next.len())
                .filter(|&d| map.next[d] != NONE)
                .collect();
            let first = keys.of(map, live[0]);
            let same = live.iter().all(|&d| keys.of(map, d) == first);
            assert_eq!(keys.uniform, same);
            for &d in &live {
                let mut len = 1u64;
                let mut x = map.next[d] as usize;
                while x != d {
                    len += 1;
                    x = map.next[x] as usize;
                }
                let valence = |v: u32| {
                    (map.vert.iter().zip(&map.next))
                        .filter(|&(&w, &n)| w == v && n != NONE)
                        .count() as u64
                };
                let want = u64::from(map.face[d] == NONE) << 63
                    | len << 42
                    | valence(map.vert[d]) << 21
                    | valence(map.vert[d ^ 1]);
                assert_eq!(keys.of(map, d), want, "dart {d}");
                let on_boundary = map.face[d] == NONE;
                assert_eq!(u64::from(loops[d]), if on_boundary { len } else { 0 });
            }
            // Dead slots have no loop either.
            for d in (0..map.next.len()).filter(|&d| map.next[d] == NONE) {
                assert_eq!(loops[d], 0, "dead dart {d}");
            }
        }
    }

    #[test]
    fn every_automorphism_found_takes_each_start_to_an_equivalent_one() {
        // The orbit pruning skips the images of tried starts: a wrong image would skip a
        // start that reads differently (the code's tests above cannot see it on maps whose
        // class is one orbit). Tori, oblong and square, and cut tori with two orbits or more.
        let mut maps = vec![gen::torus_grid(5, 4).map, gen::torus_grid(6, 6).map];
        // Two oblong tori: each component's class is its darts, not the map's.
        let two: Vec<Vec<u32>> = (gen::torus_quads(5, 4).iter())
            .chain(&gen::torus_quads(5, 4))
            .enumerate()
            .map(|(i, q)| q.iter().map(|&v| v + 20 * u32::from(i >= 20)).collect())
            .collect();
        maps.push(Map::from_polygons(40, &two).unwrap());
        for (n, seed) in [(4, 1), (6, 2), (6, 3)] {
            let mut polys = cut_torus(n, n, 1, seed);
            let shift = |p: &Vec<u32>| p.iter().map(|&v| v + (n * n) as u32).collect();
            // The cut torus twice over: two components, each coded with its own class.
            polys.extend(cut_torus(n, n, 1, seed).iter().map(shift));
            maps.push(Map::from_polygons(2 * n * n, &polys).unwrap());
        }
        let mut checked = 0;
        // One set of arrays for every map, as a workspace keeps them.
        let mut kept = Buffers::default();
        for map in &maps {
            let mut cz = Canonizer::new(map, core::mem::take(&mut kept));
            assert_eq!(cz.code(), reference_code(map));
            for (starts, g) in &cz.found {
                let mut seen = vec![false; g.len()];
                for (x, &y) in g.iter().enumerate() {
                    assert!(!core::mem::replace(&mut seen[y as usize], true));
                    let (a, b) = (Dart::new(starts[x]), Dart::new(starts[y as usize]));
                    assert_eq!(compare_starts((map, a), (map, b)), Ordering::Equal);
                }
                checked += 1;
            }
            kept = cz.buffers();
        }
        assert!(checked >= maps.len(), "only {checked} automorphisms found");
    }

    /// A second coding of a regular torus in the same arrays finds its automorphisms
    /// again (their labels taken from the runs) and needs no new label array: the arrays
    /// the first coding's automorphisms took came back as spares. Then a smaller map in them
    /// codes as a fresh call does.
    #[test]
    fn a_workspace_gives_automorphisms_their_arrays_back() {
        let torus = gen::torus_grid(12, 12).map;
        let mut cz = Canonizer::new(&torus, Buffers::default());
        let first = cz.code();
        let found = cz.found.len();
        assert!(found >= 2, "{found} automorphisms");
        // Both runs' first labels, and new ones for a race after an automorphism.
        assert!(cz.fresh >= 3, "{} fresh label arrays", cz.fresh);
        let mut cz = Canonizer::new(&torus, cz.buffers());
        assert_eq!(cz.code(), first);
        assert_eq!((cz.found.len(), cz.fresh), (found, 0));
        // Every array an automorphism took is a spare again, and no other.
        let kept = cz.buffers();
        assert_eq!(kept.spare.len(), found);
        let small = gen::random_quad(40, 1, 1, 3).map;
        let mut cz = Canonizer::new(&small, kept);
        assert_eq!(cz.code(), reference_code(&small));
        // A map whose start class is a list (two valences): its automorphisms' arrays come
        // back too.
        let cube = gen::cube(2).map;
        let mut cz = Canonizer::new(&cube, cz.buffers());
        let first_cube = cz.code();
        let found = cz.found.len();
        assert!(found >= 1, "{found} automorphisms of the cube");
        let mut cz = Canonizer::new(&cube, cz.buffers());
        assert_eq!(cz.code(), first_cube);
        assert_eq!((cz.found.len(), cz.fresh), (found, 0));
        // The public workspace: the same code and hash; it shows its last code's length.
        let mut ws = CanonicalWorkspace::new();
        assert_eq!(ws.code(&torus), &first);
        assert_eq!(ws.hash(&torus), first.hash());
        let shown = alloc::format!("{ws:?}");
        let len = first.0.len();
        assert_eq!(
            shown,
            alloc::format!("CanonicalWorkspace {{ code_len: {len}, .. }}")
        );
    }

    #[test]
    fn orbits_are_the_closure_under_the_generators() {
        // Random permutations of up to 70 starts against a closure by repeated sweeps.
        let mut rng = crate::rng::Rng::new(5);
        for _ in 0..300 {
            let k = 1 + rng.below(70);
            let mut orbits = Orbits::default();
            orbits.reset(k);
            let (mut gens, mut tried) = (Vec::new(), Vec::new());
            for _ in 0..1 + rng.below(4) {
                if rng.below(2) == 0 {
                    let mut g: Vec<u32> = (0..k as u32).collect();
                    // A cycle on a random run of positions, the rest fixed.
                    let (a, b) = (rng.below(k), rng.below(k));
                    g[a.min(b)..=a.max(b)].rotate_left(usize::from(a != b));
                    orbits.add_gen(g.clone());
                    gens.push(g);
                } else {
                    let t = rng.below(k) as u32;
                    orbits.add(t);
                    tried.push(t);
                }
            }
            let mut want = vec![false; k];
            for &t in &tried {
                want[t as usize] = true;
            }
            let mut grew = true;
            while grew {
                grew = false;
                for x in 0..k {
                    for g in &gens {
                        if want[x] && !want[g[x] as usize] {
                            want[g[x] as usize] = true;
                            grew = true;
                        }
                    }
                }
            }
            for (x, &w) in want.iter().enumerate() {
                assert_eq!(orbits.reached[x], w);
            }
            assert_eq!(orbits.members().len(), want.iter().filter(|&&w| w).count());
        }
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

    /// Walks reused from comparison to comparison (dense labels on a small map, cleared walk
    /// by walk; and sparse ones) compare every pair of starts as fresh walks do, on a cut
    /// torus whose pairs read less, equal (a symmetric cut) and greater.
    #[test]
    fn reused_walks_compare_as_fresh_ones() {
        let map = Map::from_polygons(36, &cut_torus(6, 6, 2, 3)).unwrap();
        let all = darts(&map);
        let fresh = |a: Dart, b: Dart| {
            let sparse = || Labels::Sparse(hashbrown::HashMap::new());
            let (mut wa, mut wb) = (Walk::with(sparse(), a), Walk::with(sparse(), b));
            compare_walks(&map, &mut wa, &map, &mut wb)
        };
        let mut seen = [0usize; 3];
        for dense in [true, false] {
            let walk = || match dense {
                true => Walk::new(&map, all[0]),
                false => Walk::with(Labels::Sparse(hashbrown::HashMap::new()), all[0]),
            };
            let (mut wa, mut wb) = (walk(), walk());
            assert_eq!(matches!(wa.label, Labels::Dense(_)), dense);
            for (i, &a) in all.iter().enumerate() {
                for &b in all.iter().skip(i % 7).step_by(7) {
                    wa.restart(a);
                    wb.restart(b);
                    let reused = compare_walks(&map, &mut wa, &map, &mut wb);
                    assert_eq!(reused, fresh(a, b), "{a:?} against {b:?}");
                    seen[(reused as i8 + 1) as usize] += 1;
                }
            }
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
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
