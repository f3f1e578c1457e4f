//! The singularity count, the score's first term.

use super::{Context, ScoreTerm};

/// The singularity count: the sum of |defect| over every vertex (interior valence against 4,
/// boundary valence against its ideal). Not a term of the paper, whose goal it is: the other
/// terms only rank moves that keep or lower it (see `docs/optimize.md`).
///
/// ```
/// use zipmesh::{gen, optimize::{singularities, Context, Count, ScoreTerm}};
/// let m = gen::subdivided_icosahedron(1);
/// let s = singularities(&m);
/// let ctx = Context { mesh: &m, singularities: &s, features: &[], target_area: 1.0, target_faces: 0, faces: None, walls: true };
/// assert_eq!(Count.score(&ctx), 32.0);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Count;

impl ScoreTerm for Count {
    builtin_term!("count");
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        ctx.singularities
            .iter()
            .map(|s| s.defect.unsigned_abs() as f64)
            .sum()
    }
}
