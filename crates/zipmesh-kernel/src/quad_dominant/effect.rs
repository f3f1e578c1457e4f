//! [`Move::effect`]: the effect stated in [`super::move_triangle`]'s documentation, as code.

use super::walk::{triangle, Move};
use crate::map::{Dart, Map};
use crate::ops::{Effect, Refusal};

impl Move {
    /// The documented effect of this move of the triangle of tip dart `t` on `m`, computed
    /// on `m` before: V/E/F deltas, the valence after of each vertex it names, the vertex
    /// deleted (EV) and the new vertex's valence (VE). The refusal if the move does not
    /// apply. Every face that survives keeps its degree (the triangle keeps its face
    /// handle), and VE's new face is a quad.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
    /// let (mut mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
    /// let before = mesh.map.clone();
    /// let effect = Move::EV.effect(&mesh.map, tips[0]).unwrap();
    /// assert_eq!(effect.deltas(), [-1, -2, -1]);
    /// let r = quad_dominant::move_triangle(&mut mesh.map, tips[0], Move::EV).unwrap();
    /// assert_eq!(effect.check(&before, &mesh.map, &r), Ok(()));
    /// ```
    pub fn effect(self, m: &Map, t: Dart) -> Result<Effect, Refusal> {
        super::can_move_triangle(m, t, self)?;
        let tri = triangle(m, t)?;
        let val = |v| m.valence(v) as i64;
        Ok(match self {
            Move::VE => {
                // The new tip: two darts clockwise from t around the tip.
                let u = m.dest(m.rotate_cw(m.rotate_cw(t)));
                Effect::new([1, 2, 1], 4)
                    .change(m, tri.tip, "the old tip (Ta)", 4 - val(tri.tip))
                    .change(m, u, "the new tip", 1)
                    .creates(m.valence(tri.tip) - 1)
            }
            Move::EV => Effect::new([-1, -2, -1], 4)
                .change(m, tri.a, "the merged base corner", val(tri.bb) - 3)
                .change(m, tri.tip, "the old tip", -1)
                .removes(tri.bb),
            Move::LE | Move::RE => {
                // The new tip: the quad's corner next to the tip across the side.
                let new_tip = if self == Move::LE {
                    m.dest(m.rotate_cw(t))
                } else {
                    m.dest(m.rotate_ccw(m.rotate_ccw(t)))
                };
                Effect::new([0, 0, 0], 4)
                    .change(m, tri.tip, "the old tip", -1)
                    .change(m, new_tip, "the new tip", 1)
            }
        })
    }
}
