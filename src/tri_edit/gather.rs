//! Type aggregation of v7 (Sec. 6.3): m >= 2 interior v7 gathered into one v(6 + m) by edge
//! collapses, the inverse of the vk split of [`super::split_type`].
//!
//! A collapse of `x` into `y` gives `y` the valence `d(x) + d(y) - 4` and takes one from
//! each apex: with both apexes v7 of the set, the apexes become regular and their two units
//! of `valence - 6` move into `y`, with those of `x` and `y`. So each step collapses an
//! edge whose two apexes are v7 still to gather; its ends are the vertex gathered so far
//! (kept), v7 of the set, or regular vertices (the first step: any two of these). The search
//! is depth first on a copy of the map, each collapse undone on a dead end; it keeps the
//! first way found and gives up after [`BUDGET`] collapses tried (a refusal, never a long
//! run).
//!
//! ```text
//!        a(7)                 a(6)
//!       /    \                 |
//!   x(6)------y(6)   =>      y(8)        two v7 into a v8; with x a v7: a v9,
//!       \    /                 |         with x and y v7: a v10
//!        b(7)                 b(6)
//! ```

use super::{apex, regular, TriEditError};
use crate::map::{Dart, Map, Vert};
use crate::ops::tri::TriOp;
use alloc::vec::Vec;

/// The most collapses the search tries before it refuses.
pub(super) const BUDGET: usize = 4096;

/// The most v7 gathered at once (the search recurses once per collapse, at most `MOST / 2`
/// deep, so the stack stays small).
pub(super) const MOST: usize = 64;

/// The search's state: the copy it edits, the v7 still to gather, the gathering vertex,
/// the collapses kept so far and the collapses left to try.
struct Search {
    map: Map,
    left: Vec<Vert>,
    gathered: Option<Vert>,
    ops: Vec<TriOp>,
    budget: usize,
}

/// The collapses that gather the interior v7 `v7s` (distinct, 2 to [`MOST`]) into one
/// vertex, and that vertex, or [`TriEditError::NotAPair`] when the search finds none.
pub(super) fn gather_v7(map: &Map, v7s: &[Vert]) -> Result<(Vec<TriOp>, Vert), TriEditError> {
    let mut left = v7s.to_vec();
    left.sort();
    left.dedup();
    if left.len() != v7s.len() || left.len() > MOST {
        return Err(TriEditError::NotAPair);
    }
    let mut s = Search {
        map: map.clone(),
        left,
        gathered: None,
        ops: Vec::new(),
        budget: BUDGET,
    };
    match (s.step(), s.gathered) {
        (true, Some(g)) => Ok((s.ops, g)),
        _ => Err(TriEditError::NotAPair),
    }
}

impl Search {
    /// Whether the v7 left can all be gathered from here; on `true` the map, `ops` and
    /// `gathered` hold the way, on `false` they are as on entry.
    fn step(&mut self) -> bool {
        if self.left.is_empty() {
            return self.gathered.is_some();
        }
        for h in self.candidates() {
            if self.budget == 0 {
                return false;
            }
            let kept = self.map.dest(h);
            let Ok(record) = TriOp::Collapse(h).apply(&mut self.map) else {
                continue;
            };
            self.budget -= 1;
            let (left, gathered) = (self.left.clone(), self.gathered);
            // The apexes are now regular, a removed end dead, the kept end of valence 8+.
            self.left
                .retain(|&v| self.map.is_live_vertex(v) && self.map.valence(v) == 7);
            self.gathered = Some(kept);
            self.ops.push(TriOp::Collapse(h));
            if self.step() {
                return true;
            }
            self.ops.pop();
            (self.left, self.gathered) = (left, gathered);
            // A fresh record of this map: its undo does not refuse.
            let _ = record.undo(&mut self.map);
        }
        false
    }

    /// The darts `x -> y` whose collapse gathers: both apexes v7 still to gather, `y` the
    /// gathering vertex if there is one, and every end gathering, to gather or regular.
    fn candidates(&self) -> Vec<Dart> {
        let m = &self.map;
        let end_ok =
            |v: Vert| Some(v) == self.gathered || self.left.contains(&v) || regular(m, v).is_ok();
        let apexes_left = |d: Dart| {
            let (a, b) = (apex(m, d), apex(m, d.twin()));
            matches!((a, b), (Some(a), Some(b)) if a != b
                && self.left.contains(&a) && self.left.contains(&b))
        };
        let darts: Vec<Dart> = match self.gathered {
            Some(g) => m.vertex_darts(g).map(Dart::twin).collect(),
            // Every edge opposite a v7 to gather in one of its triangles.
            None => self
                .left
                .iter()
                .flat_map(|&v| m.vertex_darts(v).map(|d| m.next(d)).collect::<Vec<_>>())
                .flat_map(|e| [e, e.twin()])
                .collect(),
        };
        darts
            .into_iter()
            .filter(|&d| apexes_left(d) && end_ok(m.origin(d)) && end_ok(m.dest(d)))
            .collect()
    }
}
