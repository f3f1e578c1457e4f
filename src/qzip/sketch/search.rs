//! The three searches of a sketch (bidirectional BFS, A*, Dijkstra) and the walk that reads
//! the one-sided BFS's path off the vertices of the shortest paths.

use alloc::vec::Vec;

use super::heap::{AEntry, Entry};
use super::store::{Buffers, Slot, Store, BWD, DAG, DONE, FWD, PRED};
use super::{sorted_darts, Guide, Path, Rules};
use crate::{Dart, Map, Vert};

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
/// `kf` to backward layer `kb` over one edge. [`mark_front`] marks the forward half of the
/// shortest paths and [`greedy`] walks the least of them: up to layer `kf` over the marked
/// vertices, beyond it down the backward labels (exact there: a vertex one edge on from a
/// vertex of a shortest path, with the right distance to `to`, is on one too).
fn bfs<S: Store>(cx: &Ctx<'_, '_>, st: &mut S, b: &mut Buffers) -> Option<Path> {
    let (kf, kb) = meet(cx, st, b)?;
    let total = kf + kb + 1;
    mark_front(cx, st, b, kf, kb);
    greedy(cx, st, total, |s, q| {
        if q <= kf {
            s.has(DAG) && s.fwd == q
        } else {
            s.has(BWD) && s.bwd == total - q
        }
    })
}

/// The two searches of [`bfs`], grown by whole layers until a vertex is labelled by both:
/// the complete layers `(kf, kb)`, or `None` when a side runs out (no path). The forward
/// layer `kf` is left in `b.a`.
fn meet<S: Store>(cx: &Ctx<'_, '_>, st: &mut S, b: &mut Buffers) -> Option<(u32, u32)> {
    let (from, to) = (cx.from, cx.to);
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
        let met = if forward {
            grow::<true, S>(cx, st, fr, next, kf + 1)
        } else {
            grow::<false, S>(cx, st, bk, next, kb + 1)
        };
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

/// One layer of one side of [`meet`]: labels the unlabelled neighbours of `front` with
/// distance `k` into `next`; `true` as soon as one carries the other side's label. The side
/// is a constant, so the inner loop has no branch on it.
#[inline]
fn grow<const FORWARD: bool, S: Store>(
    cx: &Ctx<'_, '_>,
    st: &mut S,
    front: &[Vert],
    next: &mut Vec<Vert>,
    k: u32,
) -> bool {
    let (mine, theirs) = if FORWARD { (FWD, BWD) } else { (BWD, FWD) };
    let open = cx.open();
    next.clear();
    for &u in front {
        for d in cx.map.vertex_darts(u) {
            let Some(w) = cx.step(open, d) else {
                continue;
            };
            let s = st.get_mut(w);
            if s.has(mine) {
                continue;
            }
            s.set(mine);
            if FORWARD {
                s.fwd = k;
            } else {
                s.bwd = k;
            }
            if s.has(theirs) {
                return true;
            }
            next.push(w);
        }
    }
    false
}

/// Marks (`DAG`) the vertices of shortest paths in forward layers `0..=kf` once the
/// searches met after layers `kf` and `kb`: the forward layer `kf` vertices one edge from
/// backward layer `kb`, then up the forward labels (beyond layer `kf`, [`greedy`] reads the
/// backward labels).
fn mark_front<S: Store>(cx: &Ctx<'_, '_>, st: &mut S, b: &mut Buffers, kf: u32, kb: u32) {
    let (map, open) = (cx.map, cx.open());
    let (front, cur, nxt) = (&b.a, &mut b.c, &mut b.b);
    cur.clear();
    for &v in front.iter() {
        let crosses = map.vertex_darts(v).any(|d| {
            cx.step(open, d).is_some_and(|w| {
                let s = st.get(w);
                s.has(BWD) && s.bwd == kb
            })
        });
        if crosses {
            st.get_mut(v).set(DAG);
            cur.push(v);
        }
    }
    mark_back(cx, st, cur, nxt, kf, |s| s.has(FWD).then_some(s.fwd));
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

/// The one-sided BFS's path in one walk from `from`: at each vertex, the smallest dart on to
/// a vertex `on` accepts at the next position `q` (`on(slot, q)`: the vertex lies on a
/// shortest path, at distance `q` from `from`).
///
/// The BFS's path to `to` is the least shortest path in the order of dart sequences: a vertex
/// keeps its earliest dequeued predecessor, and by induction on the layers the queue holds a
/// layer in that order. A walk that takes the smallest dart on each step finds it, because
/// each step's choice extends to `to` (every vertex `on` accepts but `to` has an accepted
/// neighbour one position further). It costs `total` rings, where replaying the BFS over the
/// marked vertices took a pass per layer and a trace back. `None` when a step finds no way on
/// or the walk ends elsewhere than `to` (A* with a wrong guide).
fn greedy<S: Store>(
    cx: &Ctx<'_, '_>,
    st: &S,
    total: u32,
    on: impl Fn(&Slot, u32) -> bool,
) -> Option<Path> {
    let (map, open) = (cx.map, cx.open());
    let mut vertices = Vec::with_capacity(total as usize + 1);
    let mut darts = Vec::with_capacity(total as usize);
    let mut v = cx.from;
    vertices.push(v);
    for pos in 0..total {
        let d = map
            .vertex_darts(v)
            .filter(|&d| cx.step(open, d).is_some_and(|w| on(&st.get(w), pos + 1)))
            .min()?;
        v = map.dest(d);
        darts.push(d);
        vertices.push(v);
    }
    (v == cx.to).then_some(Path { vertices, darts })
}

/// A* on unit weights with the guide's heuristic, re-expanding a vertex whose distance
/// improves (so an admissible heuristic suffices), until every vertex that could lie on a
/// shortest path has its exact distance: the open vertices' `g + h` all exceed the best
/// distance to `to` (beyond a margin for the rounding of `h`). Then [`mark_back`] from `to`
/// and [`greedy`] give the one-sided BFS's path. With an overestimating heuristic, the last
/// improving darts still form a simple path to `to`, returned when the walk does not reach it.
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
    greedy(cx, st, best, |s, q| s.has(DAG) && s.fwd == q)
        .or_else(|| trace(cx, st, best as usize, |s| s.has(FWD).then_some(s.bwd)))
}
