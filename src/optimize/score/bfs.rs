//! The breadth-first search the distance terms share.

use alloc::vec::Vec;

use super::super::marks::Marks;
use crate::{Mesh, Vert};

/// Epoch-stamped breadth-first search scratch, reused between calls.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bfs {
    seen: Marks,
    /// The vertices reached, in order, with their distances: read from the front, never
    /// popped (cheaper than a ring buffer; one search pushes each vertex once).
    queue: Vec<(Vert, u32)>,
}

impl Bfs {
    /// Visits vertices from `from` in order of graph distance up to `radius`, calling
    /// `visit(v, d)`; stops early when `visit` returns `false`.
    pub(crate) fn run(
        &mut self,
        mesh: &Mesh,
        from: Vert,
        radius: u32,
        visit: impl FnMut(Vert, u32) -> bool,
    ) {
        self.run_from(mesh, [from], radius, visit);
    }

    /// [`Bfs::run`] with each vertex's valence: `visit(v, d, valence)`, called once the
    /// vertex's darts have been walked (counted, and its neighbours queued when `d` is under
    /// `radius`), so the valence costs no walk of its own. The same vertices in the same
    /// order as [`Bfs::run`]: what a stopped search queued is never visited.
    pub(crate) fn run_counting(
        &mut self,
        mesh: &Mesh,
        from: Vert,
        radius: u32,
        mut visit: impl FnMut(Vert, u32, usize) -> bool,
    ) {
        let map = &mesh.map;
        self.seen.begin(map.vertex_slots());
        self.queue.clear();
        if map.is_live_vertex(from) && self.seen.first(from.index()) {
            self.queue.push((from, 0));
        }
        let mut head = 0;
        while let Some(&(v, d)) = self.queue.get(head) {
            head += 1;
            let mut valence = 0;
            for x in map.vertex_darts(v) {
                valence += 1;
                if d < radius {
                    let u = map.dest(x);
                    if self.seen.first(u.index()) {
                        self.queue.push((u, d + 1));
                    }
                }
            }
            if !visit(v, d, valence) {
                return;
            }
        }
    }

    /// [`Bfs::run`] from several sources at distance 0.
    pub(crate) fn run_from(
        &mut self,
        mesh: &Mesh,
        from: impl IntoIterator<Item = Vert>,
        radius: u32,
        mut visit: impl FnMut(Vert, u32) -> bool,
    ) {
        let map = &mesh.map;
        self.seen.begin(map.vertex_slots());
        self.queue.clear();
        for v in from {
            if map.is_live_vertex(v) && self.seen.first(v.index()) {
                self.queue.push((v, 0));
            }
        }
        let mut head = 0;
        while let Some(&(v, d)) = self.queue.get(head) {
            head += 1;
            if !visit(v, d) {
                return;
            }
            if d >= radius {
                continue;
            }
            for x in map.vertex_darts(v) {
                let u = map.dest(x);
                if self.seen.first(u.index()) {
                    self.queue.push((u, d + 1));
                }
            }
        }
    }
}
