//! The three searches of a sketch (bidirectional BFS, A*, Dijkstra) and the replay of the
//! one-sided BFS's tie-breaking over the vertices of all shortest paths.

use alloc::vec::Vec;
use core::cmp::Ordering;

use super::store::{Buffers, Slot, Store, BWD, DAG, DONE, FWD, PRED};
use super::{sorted_darts, Guide, Path, Rules};
use crate::{Dart, Map, Vert};

/// Dijkstra heap entry: smallest (distance, vertex) first.
#[derive(PartialEq)]
pub(super) struct Entry(f64, u32);

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed so that BinaryHeap (a max-heap) pops the smallest; weights are finite.
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| other.1.cmp(&self.1))
    }
}

/// A* heap entry `(f, g, vertex)` packed in one integer: smallest f first, then the deepest
/// (largest g), which walks straight down a run of ties, then the smallest vertex. The order
/// only changes the work, not the path. `f >= 0`, so its bits order as the numbers do.
#[derive(PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct AEntry(core::cmp::Reverse<u128>);

impl AEntry {
    pub(super) fn new(f: f64, g: u32, v: Vert) -> Self {
        let key =
            (u128::from(f.to_bits()) << 64) | (u128::from(u32::MAX - g) << 32) | v.index() as u128;
        AEntry(core::cmp::Reverse(key))
    }

    pub(super) fn f(&self) -> f64 {
        f64::from_bits((self.0 .0 >> 64) as u64)
    }

    pub(super) fn g(&self) -> u32 {
        u32::MAX - (self.0 .0 >> 32) as u32
    }

    pub(super) fn vertex(&self) -> Vert {
        Vert::new(self.0 .0 as u32)
    }
}

/// One search pass's fixed inputs.
pub(super) struct Ctx<'m, 'r> {
    pub(super) map: &'m Map,
    pub(super) from: Vert,
    pub(super) to: Vert,
    pub(super) rules: &'r Rules<'r>,
    /// Exclude boundary vertices other than the ends.
    pub(super) avoid: bool,
}

impl Ctx<'_, '_> {
    /// Whether every edge may be stepped along (no forbidden edge, no excluded vertex): the
    /// common case, tested once per pass instead of per dart.
    pub(super) fn open(&self) -> bool {
        self.rules.forbidden.is_empty() && !self.avoid
    }

    /// The vertex `d` leads to, if the search may step along `d` (an allowed edge to an
    /// allowed vertex); `open` is [`Ctx::open`].
    #[inline]
    fn step(&self, open: bool, d: Dart) -> Option<Vert> {
        let w = self.map.dest(d);
        let allowed = open
            || (self.rules.usable(d)
                && !(self.avoid
                    && w != self.to
                    && w != self.from
                    && self.map.is_boundary_vertex(w)));
        allowed.then_some(w)
    }
}

pub(super) fn search<S: Store>(
    cx: &Ctx<'_, '_>,
    guide: Option<&Guide<'_>>,
    st: &mut S,
    b: &mut Buffers,
) -> Option<Path> {
    match (cx.rules.weights, guide) {
        (Some(w), _) => dijkstra(cx, w, st, b),
        (None, Some(g)) if g.usable(cx.to) => astar(cx, g, st, b),
        (None, _) => bfs(cx, st, b),
    }
}

/// Dijkstra: settles the vertex of smallest (distance, index); a vertex keeps the first
/// predecessor that reached it at its final distance.
fn dijkstra<S: Store>(
    cx: &Ctx<'_, '_>,
    weights: &[f64],
    st: &mut S,
    b: &mut Buffers,
) -> Option<Path> {
    let (map, from, to, open) = (cx.map, cx.from, cx.to, cx.open());
    let heap = &mut b.dijkstra;
    heap.clear();
    let s = st.get_mut(from);
    s.set(FWD);
    s.set_dist(0.0);
    heap.push(Entry(0.0, from.index() as u32));
    while let Some(Entry(dv, vi)) = heap.pop() {
        let v = Vert::new(vi);
        let s = st.get_mut(v);
        if s.has(DONE) {
            continue;
        }
        s.set(DONE);
        if v == to {
            break;
        }
        sorted_darts(map, v, &mut b.darts);
        for &d in &b.darts {
            let Some(w) = cx.step(open, d) else {
                continue;
            };
            let sw = st.get_mut(w);
            if sw.has(DONE) {
                continue;
            }
            let nd = dv
                + weights
                    .get(d.edge().index())
                    .copied()
                    .unwrap_or(f64::INFINITY);
            let old = if sw.has(FWD) {
                sw.dist()
            } else {
                f64::INFINITY
            };
            if nd < old {
                sw.set(FWD | PRED);
                sw.set_dist(nd);
                sw.pred = d.index() as u32;
                heap.push(Entry(nd, w.index() as u32));
            }
        }
    }
    trace(cx, st, 0, |s| s.has(PRED).then_some(s.pred))
}

/// The path ending at `to` read back through `pred` (darts); `None` when the chain breaks or
/// runs longer than the map has vertices. `len` is the expected length (room reserved once).
fn trace<S: Store>(
    cx: &Ctx<'_, '_>,
    st: &S,
    len: usize,
    pred: impl Fn(&Slot) -> Option<u32>,
) -> Option<Path> {
    let map = cx.map;
    let mut darts = Vec::with_capacity(len);
    let mut v = cx.to;
    while v != cx.from {
        if darts.len() > map.vertex_slots() {
            return None;
        }
        let d = Dart::new(pred(&st.get(v))?);
        darts.push(d);
        v = map.origin(d);
    }
    darts.reverse();
    let mut vertices = Vec::with_capacity(darts.len() + 1);
    vertices.push(cx.from);
    vertices.extend(darts.iter().map(|&d| map.dest(d)));
    Some(Path { vertices, darts })
}

/// Bidirectional breadth-first search, then the path the one-sided search would give.
///
/// The two sides grow by whole layers, the smaller frontier first (forward on a tie), until a
/// vertex is labelled by both: with forward layers `0..=kf` and backward layers `0..=kb`
/// complete, the distance is `kf + kb + 1` and the shortest paths cross from forward layer
/// `kf` to backward layer `kb` over one edge. The vertices of shortest paths are then marked
/// (the middle layer, down the backward labels, [`mark_back`] up the forward ones) and
/// [`replay`] replays the one-sided BFS over them.
fn bfs<S: Store>(cx: &Ctx<'_, '_>, st: &mut S, b: &mut Buffers) -> Option<Path> {
    let (kf, kb) = meet(cx, st, b)?;
    let total = kf + kb + 1;
    mark_shortest(cx, st, b, kf, kb);
    // Labels are exact BFS distances, so a marked vertex's position is either.
    replay(cx, st, b, total, |s| {
        if s.has(FWD) {
            s.fwd
        } else {
            total.saturating_sub(s.bwd)
        }
    })
}

/// The two searches of [`bfs`], grown by whole layers until a vertex is labelled by both:
/// the complete layers `(kf, kb)`, or `None` when a side runs out (no path). The backward
/// layer `kb` is left in `b.b`.
fn meet<S: Store>(cx: &Ctx<'_, '_>, st: &mut S, b: &mut Buffers) -> Option<(u32, u32)> {
    let (map, from, to, open) = (cx.map, cx.from, cx.to, cx.open());
    let s = st.get_mut(from);
    s.set(FWD);
    s.fwd = 0;
    let s = st.get_mut(to);
    s.set(BWD);
    s.bwd = 0;
    let (fr, bk, next) = (&mut b.a, &mut b.b, &mut b.c);
    fr.clear();
    bk.clear();
    fr.push(from);
    bk.push(to);
    let (mut kf, mut kb) = (0u32, 0u32);
    loop {
        if fr.is_empty() || bk.is_empty() {
            return None;
        }
        let forward = fr.len() <= bk.len();
        let (front, mine, theirs, k) = if forward {
            (&*fr, FWD, BWD, kf)
        } else {
            (&*bk, BWD, FWD, kb)
        };
        next.clear();
        let mut met = false;
        'layer: for &u in front {
            for d in map.vertex_darts(u) {
                let Some(w) = cx.step(open, d) else {
                    continue;
                };
                let s = st.get_mut(w);
                if s.has(mine) {
                    continue;
                }
                s.set(mine);
                if forward {
                    s.fwd = k + 1;
                } else {
                    s.bwd = k + 1;
                }
                if s.has(theirs) {
                    met = true;
                    break 'layer;
                }
                next.push(w);
            }
        }
        if met {
            return Some((kf, kb));
        }
        if forward {
            core::mem::swap(fr, next);
            kf += 1;
        } else {
            core::mem::swap(bk, next);
            kb += 1;
        }
    }
}

/// Marks (`DAG`) the vertices of all shortest paths once the searches met after layers
/// `kf` and `kb`: the backward layer `kb` vertices one edge from forward layer `kf`, down the
/// backward labels to `to`, and up the forward labels to `from`.
fn mark_shortest<S: Store>(cx: &Ctx<'_, '_>, st: &mut S, b: &mut Buffers, kf: u32, kb: u32) {
    let (map, open) = (cx.map, cx.open());
    let bk = &b.b;
    // The middle: backward layer kb vertices one edge from forward layer kf.
    let total = kf + kb + 1;
    b.m.clear();
    for &v in bk.iter() {
        let crosses = map.vertex_darts(v).any(|d| {
            cx.step(open, d).is_some_and(|w| {
                let s = st.get(w);
                s.has(FWD) && s.fwd == kf
            })
        });
        if crosses {
            let s = st.get_mut(v);
            s.set(DAG);
            b.m.push(v);
        }
    }
    // Down to `to` along backward labels, then back to `from` along forward labels.
    let (cur, nxt) = (&mut b.a, &mut b.c);
    cur.clear();
    cur.extend_from_slice(&b.m);
    for pos in kf + 1..total {
        nxt.clear();
        for &v in cur.iter() {
            for d in map.vertex_darts(v) {
                let Some(w) = cx.step(open, d) else {
                    continue;
                };
                let s = st.get(w);
                if s.has(BWD) && !s.has(DAG) && s.bwd == total - pos - 1 {
                    let s = st.get_mut(w);
                    s.set(DAG);
                    nxt.push(w);
                }
            }
        }
        core::mem::swap(cur, nxt);
    }
    cur.clear();
    cur.extend_from_slice(&b.m);
    mark_back(cx, st, cur, nxt, kf + 1, |s| s.has(FWD).then_some(s.fwd));
}

/// Marks, from the `DAG` vertices at position `pos` in `cur`, the vertices at positions
/// `pos - 1` down to 0 whose exact distance from `from` (`dist`) is their position.
fn mark_back<S: Store>(
    cx: &Ctx<'_, '_>,
    st: &mut S,
    cur: &mut Vec<Vert>,
    nxt: &mut Vec<Vert>,
    pos: u32,
    dist: impl Fn(&Slot) -> Option<u32>,
) {
    let (map, open) = (cx.map, cx.open());
    for pos in (1..=pos).rev() {
        nxt.clear();
        for &v in cur.iter() {
            for d in map.vertex_darts(v) {
                let Some(u) = cx.step(open, d) else {
                    continue;
                };
                let s = st.get(u);
                if !s.has(DAG) && dist(&s) == Some(pos - 1) {
                    let s = st.get_mut(u);
                    s.set(DAG);
                    nxt.push(u);
                }
            }
        }
        core::mem::swap(cur, nxt);
    }
}

/// Replays the one-sided BFS over the `DAG` vertices (every vertex of a shortest path, each
/// marked with its distance from `from`): layer by layer, darts in increasing index, a vertex
/// keeps the first predecessor that reaches it. A vertex's BFS predecessor is always on a
/// shortest path too, so this gives the one-sided search's path.
fn replay<S: Store>(
    cx: &Ctx<'_, '_>,
    st: &mut S,
    b: &mut Buffers,
    total: u32,
    position: impl Fn(&Slot) -> u32,
) -> Option<Path> {
    let (map, open) = (cx.map, cx.open());
    let (cur, nxt) = (&mut b.a, &mut b.c);
    cur.clear();
    if !st.get(cx.from).has(DAG) {
        return None;
    }
    cur.push(cx.from);
    for pos in 0..total {
        nxt.clear();
        for &v in cur.iter() {
            // The darts on to the next position, in increasing index: usually one or two,
            // so they are picked before they are sorted.
            let darts = &mut b.darts;
            darts.clear();
            darts.extend(map.vertex_darts(v).filter(|&d| {
                cx.step(open, d).is_some_and(|w| {
                    let s = st.get(w);
                    s.has(DAG) && position(&s) == pos + 1
                })
            }));
            if darts.len() > 1 {
                darts.sort_unstable();
            }
            for &d in darts.iter() {
                let w = map.dest(d);
                let s = st.get_mut(w);
                if !s.has(PRED) {
                    s.set(PRED);
                    s.pred = d.index() as u32;
                    nxt.push(w);
                }
            }
        }
        core::mem::swap(cur, nxt);
    }
    trace(cx, st, total as usize, |s| s.has(PRED).then_some(s.pred))
}

/// A* on unit weights with the guide's heuristic, re-expanding a vertex whose distance
/// improves (so an admissible heuristic suffices), until every vertex that could lie on a
/// shortest path has its exact distance: the open vertices' `g + h` all exceed the best
/// distance to `to` (beyond a margin for the rounding of `h`). Then [`mark_back`] from `to` and [`replay`] give the one-sided BFS's path. With
/// an overestimating heuristic, the last improving darts still form a simple path to `to`,
/// returned when the replay does not reach it.
fn astar<S: Store>(cx: &Ctx<'_, '_>, g: &Guide<'_>, st: &mut S, b: &mut Buffers) -> Option<Path> {
    let (map, from, to, open) = (cx.map, cx.from, cx.to, cx.open());
    let target = g.point(to)?;
    let scale = 1.0 / g.max_edge_length;
    let h = |v: Vert| match g.point(v) {
        Some(p) => {
            let x = p.distance(target) * scale;
            if x.is_finite() {
                x
            } else {
                0.0
            }
        }
        None => 0.0,
    };
    let heap = &mut b.astar;
    heap.clear();
    let s = st.get_mut(from);
    s.set(FWD);
    s.fwd = 0;
    heap.push(AEntry::new(h(from), 0, from));
    let mut best = u32::MAX;
    while let Some(e) = heap.pop() {
        let (f, gv, v) = (e.f(), e.g(), e.vertex());
        // A vertex of a shortest path has f <= best up to the rounding of h (relative error
        // far below 1e-9); the margin keeps rounding from dropping one.
        if best != u32::MAX && f > best as f64 * (1.0 + 1e-9) + 1e-9 {
            break;
        }
        if st.get(v).fwd != gv {
            continue; // stale: improved since it was pushed
        }
        for d in map.vertex_darts(v) {
            let Some(w) = cx.step(open, d) else {
                continue;
            };
            let ng = gv + 1;
            let s = st.get_mut(w);
            if s.has(FWD) && s.fwd <= ng {
                continue;
            }
            s.set(FWD);
            s.fwd = ng;
            s.bwd = d.index() as u32;
            if w == to {
                best = ng;
            } else {
                heap.push(AEntry::new(ng as f64 + h(w), ng, w));
            }
        }
    }
    if best == u32::MAX {
        return None;
    }
    let s = st.get_mut(to);
    s.set(DAG);
    let (cur, nxt) = (&mut b.a, &mut b.c);
    cur.clear();
    cur.push(to);
    mark_back(cx, st, cur, nxt, best, |s| s.has(FWD).then_some(s.fwd));
    replay(cx, st, b, best, |s| s.fwd)
        .or_else(|| trace(cx, st, best as usize, |s| s.has(FWD).then_some(s.bwd)))
}
