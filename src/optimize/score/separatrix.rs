//! Separatrix alignment: singularities on each other's separatrices.

use super::super::marks::Memo;
use super::bfs::Bfs;
use super::{Context, ScoreTerm};
use crate::Vert;

/// Separatrix alignment: each interior singularity at graph distance `d` (1 to `radius`)
/// from the closest separatrix of another singularity adds `1 / d^2`; one on such a
/// separatrix (aligned) or farther adds nothing. Separatrices are traced straight through
/// regular interior vertices from every edge of an interior singularity, at most `length`
/// edges.
///
/// ```
/// use zipmesh::{gen, optimize::{singularities, Context, Separatrix, ScoreTerm}};
/// let m = gen::subdivided_icosahedron(2);
/// let s = singularities(&m);
/// let ctx = Context { mesh: &m, singularities: &s, features: &[], target_area: 1.0, target_faces: 0, faces: None, walls: true };
/// assert!(Separatrix::default().score(&ctx) >= 0.0);
/// ```
#[derive(Clone, Debug)]
pub struct Separatrix {
    /// How far (edges) a singularity looks for a separatrix.
    pub radius: u32,
    /// The longest traced separatrix (edges).
    pub length: usize,
    /// Per vertex, the separatrices through it: one's index, or [`MANY_OWNERS`].
    owner: Memo<i64>,
    /// Per vertex, 1 if a separatrix goes on through it (regular and interior).
    through: Memo<i64>,
    bfs: Bfs,
}

impl Default for Separatrix {
    fn default() -> Self {
        Separatrix {
            radius: 3,
            length: 32,
            owner: Memo::default(),
            through: Memo::default(),
            bfs: Bfs::default(),
        }
    }
}

const MANY_OWNERS: i64 = -1;

impl Separatrix {
    fn trace(&mut self, ctx: &Context<'_>, id: i64, s: Vert) {
        let map = &ctx.mesh.map;
        for start in map.vertex_darts(s) {
            let mut d = start;
            for _ in 0..self.length {
                let v = map.dest(d);
                let o = match self.owner.peek(v.index()) {
                    None => id,
                    Some(o) if o == id => id,
                    Some(_) => MANY_OWNERS,
                };
                self.owner.set(v.index(), o);
                let on = self.through.get(v.index(), || {
                    i64::from(map.valence(v) == 4 && !map.is_boundary_vertex(v))
                });
                if on == 0 {
                    break;
                }
                d = map.rotate_cw(map.rotate_cw(d.twin()));
            }
        }
    }
}

impl ScoreTerm for Separatrix {
    builtin_term!("separatrix");
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        // Stamped, not cleared: a window's call touches a few vertices of a large mesh.
        let slots = ctx.mesh.map.vertex_slots();
        self.owner.begin(slots);
        self.through.begin(slots);
        let interior = || ctx.singularities.iter().filter(|s| !s.boundary);
        for (i, s) in interior().enumerate() {
            self.trace(ctx, i as i64, s.vertex);
        }
        let mut total = 0.0;
        for (i, s) in interior().enumerate() {
            let owner = &self.owner;
            let mut best = None;
            self.bfs.run(ctx.mesh, s.vertex, self.radius, |v, d| {
                let o = owner.peek(v.index());
                if o.is_some_and(|o| o != i as i64 || o == MANY_OWNERS) {
                    best = Some(d);
                    return false;
                }
                true
            });
            if let Some(d) = best.filter(|&d| d > 0) {
                total += 1.0 / (d * d) as f64;
            }
        }
        total
    }
}
