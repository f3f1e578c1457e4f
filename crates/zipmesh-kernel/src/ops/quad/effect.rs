//! [`QuadOp::effect`]: the table of the module docs as code.

use super::{QuadOp, QuadRecord, Rotation};
use crate::map::{Dart, Map, Vert};
use crate::ops::effect::{cw_steps, Effect, VertexChanges};
use crate::ops::Refusal;

impl QuadOp {
    /// The documented effect of applying the operator to `m` (the table in the
    /// [module docs](super) is its statement in prose), computed on `m` before: the V/E/F
    /// deltas, the valence after of every vertex the table names, the vertex deleted and
    /// the new vertex's valence. The refusal if the operator does not apply.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::QuadOp, Dart};
    /// let mut map = gen::torus_grid(5, 5).map;
    /// let before = map.clone();
    /// let op = QuadOp::Collapse(Dart::new(0));
    /// let effect = op.effect(&map).unwrap();
    /// assert_eq!(effect.deltas(), [-1, -2, -1]);
    /// let record = op.apply(&mut map).unwrap();
    /// assert_eq!(effect.check(&before, &map, &record), Ok(()));
    /// ```
    pub fn effect(self, m: &Map) -> Result<Effect, Refusal> {
        self.can(m)?;
        let o = |d: Dart| m.origin(d);
        let n = |d: Dart| m.next(d);
        let val = |v: Vert| m.valence(v) as i64;
        let grow = Effect::new([1, 2, 1], 4);
        let shrink = Effect::new([-1, -2, -1], 4);
        Ok(match self {
            QuadOp::Collapse(d) => {
                let (a, b, c, e) = (o(d), o(n(d)), o(n(n(d))), o(n(n(n(d)))));
                shrink
                    .change(m, a, "the merged vertex", val(c) - 2)
                    .change(m, b, "corner b", -1)
                    .change(m, e, "corner d", -1)
                    .removes(c)
            }
            QuadOp::Split(s1, _) | QuadOp::HighValence(s1) => {
                let w = o(s1);
                let s2 = match self {
                    QuadOp::Split(_, s2) => s2,
                    _ => (0..m.valence(w) / 2).fold(s1, |x, _| m.rotate_cw(x)),
                };
                // The kept arc: the darts strictly between s1 and s2 clockwise.
                let arc1 = cw_steps(m, s1, s2) as i64 - 1;
                grow.change(m, w, "the split vertex", arc1 + 2 - val(w))
                    .change(m, m.dest(s1), "end a", 1)
                    .change(m, m.dest(s2), "end b", 1)
                    .creates((val(w) - arc1) as usize)
            }
            QuadOp::RemoveValence2(x) => shrink
                .change(m, m.dest(x), "neighbour p", -1)
                .change(m, m.dest(m.rotate_cw(x)), "neighbour q", -1)
                .removes(o(x)),
            QuadOp::InsertDoublet(d) => grow
                .change(m, o(d), "diagonal end p", 1)
                .change(m, o(n(n(d))), "diagonal end q", 1)
                .creates(2),
            QuadOp::Rotate(h, r) => {
                let t = h.twin();
                // The hexagon v x y u z w around h = u→v: counter-clockwise h becomes z→x,
                // clockwise y→w.
                let (p, q) = match r {
                    Rotation::CounterClockwise => (o(n(n(t))), o(n(n(h)))),
                    Rotation::Clockwise => (o(n(n(n(h)))), o(n(n(n(t))))),
                };
                Effect::new([0, 0, 0], 4)
                    .change(m, o(h), "old end u", -1)
                    .change(m, o(t), "old end v", -1)
                    .change(m, p, "new end", 1)
                    .change(m, q, "new end", 1)
            }
        })
    }
}

impl VertexChanges for QuadRecord {
    fn created_vertex(&self) -> Option<Vert> {
        match self {
            QuadRecord::Split(r) => Some(r.created()),
            QuadRecord::InsertDoublet(r) => Some(r.vertex()),
            _ => None,
        }
    }

    fn removed_vertex(&self) -> Option<Vert> {
        match self {
            QuadRecord::Collapse(r) => Some(r.removed()),
            QuadRecord::RemoveValence2(r) => Some(r.removed()),
            _ => None,
        }
    }
}
