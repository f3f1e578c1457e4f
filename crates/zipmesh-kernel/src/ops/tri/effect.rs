//! [`TriOp::effect`]: the table of the module docs as code.

use super::{TriOp, TriRecord};
use crate::map::{Dart, Map, Vert};
use crate::ops::effect::{cw_steps, Effect, VertexChanges};
use crate::ops::Refusal;

impl TriOp {
    /// The documented effect of applying the operator to `m` (the table in the
    /// [module docs](super) is its statement in prose), computed on `m` before: the V/E/F
    /// deltas (for a collapse and an edge split they depend on whether the edge is
    /// interior), the valence after of every vertex the table names, the vertex deleted and
    /// the new vertex's valence. The refusal if the operator does not apply.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri::TriOp};
    /// let mut map = gen::random_triangle(200, 0, 0, 3).map;
    /// let before = map.clone();
    /// let d = map.darts().find(|&d| TriOp::SplitEdge(d).can(&map).is_ok()).unwrap();
    /// let effect = TriOp::SplitEdge(d).effect(&map).unwrap();
    /// assert_eq!(effect.deltas(), [1, 3, 2]);
    /// assert_eq!(effect.created_valence(), Some(4));
    /// let record = TriOp::SplitEdge(d).apply(&mut map).unwrap();
    /// assert_eq!(effect.check(&before, &map, &record), Ok(()));
    /// ```
    pub fn effect(self, m: &Map) -> Result<Effect, Refusal> {
        self.can(m)?;
        Ok(self.effect_unchecked(m))
    }

    /// [`TriOp::effect`] without the `can` check, for searches that score many operators and
    /// check only the few they pick: the darts must be live and, for a vertex split, leave
    /// one origin; what it says of an operator that `can` refuses is not an effect (it is
    /// still an answer: any handles, live or not, give one without a panic).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri::TriOp, Dart};
    /// let map = gen::random_triangle(200, 0, 0, 3).map;
    /// let d = map.darts().find(|&d| TriOp::Flip(d).can(&map).is_ok()).unwrap();
    /// assert_eq!(TriOp::Flip(d).effect_unchecked(&map), TriOp::Flip(d).effect(&map).unwrap());
    /// let _ = TriOp::Collapse(Dart::new(1 << 30)).effect_unchecked(&map);
    /// ```
    pub fn effect_unchecked(self, m: &Map) -> Effect {
        let val = |v: Vert| m.valence(v) as i64;
        // The third corner of the face of `d`, if `d` is not a boundary dart.
        let apex = |d: Dart| m.face(d).map(|_| m.dest(m.next(d)));
        let apexes = |e: Effect, h: Dart, k: i64| {
            let e = match apex(h) {
                Some(c) => e.change(m, c, "apex c", k),
                None => e,
            };
            match apex(h.twin()) {
                Some(d) => e.change(m, d, "apex d", k),
                None => e,
            }
        };
        let interior = |h: Dart| m.face(h).is_some() && m.face(h.twin()).is_some();
        match self {
            TriOp::Flip(h) => apexes(
                Effect::new([0, 0, 0], 3)
                    .change(m, m.origin(h), "end a", -1)
                    .change(m, m.dest(h), "end b", -1),
                h,
                1,
            ),
            TriOp::Collapse(h) => {
                let (v, u) = (m.origin(h), m.dest(h));
                let e = if interior(h) {
                    Effect::new([-1, -3, -2], 3).change(m, u, "the kept vertex u", val(v) - 4)
                } else {
                    Effect::new([-1, -2, -1], 3).change(m, u, "the kept vertex u", val(v) - 3)
                };
                apexes(e.removes(v), h, -1)
            }
            TriOp::SplitVertex(d1, d2) => {
                let w = m.origin(d1);
                // k_w: the darts strictly between d1 and d2 clockwise (they stay at w).
                let k_w = cw_steps(m, d1, d2) as i64 - 1;
                let k_v = val(w) - k_w - 2;
                Effect::new([1, 3, 2], 3)
                    .change(m, w, "the split vertex w", k_w + 3 - val(w))
                    .change(m, m.dest(d1), "end a", 1)
                    .change(m, m.dest(d2), "end b", 1)
                    .creates((k_v + 3) as usize)
            }
            TriOp::SplitEdge(h) => {
                let e = if interior(h) {
                    Effect::new([1, 3, 2], 3).creates(4)
                } else {
                    Effect::new([1, 2, 1], 3).creates(3)
                };
                apexes(e, h, 1)
            }
        }
    }
}

impl VertexChanges for TriRecord {
    fn created_vertex(&self) -> Option<Vert> {
        match self {
            TriRecord::SplitVertex(r) => Some(r.created()),
            TriRecord::SplitEdge(r) => Some(r.created()),
            _ => None,
        }
    }

    fn removed_vertex(&self) -> Option<Vert> {
        match self {
            TriRecord::Collapse(r) => Some(r.removed()),
            _ => None,
        }
    }
}
