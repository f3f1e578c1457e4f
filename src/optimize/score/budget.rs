//! The face budget: faces away from the input's count cost.

use super::{Context, ScoreTerm};

/// The face budget: `|F - F0| + steepness * max(0, |F - F0| - tolerance * F0)`, the change
/// of the face count from the input's, much steeper outside a band of `tolerance` (a
/// fraction of `F0`). Not a term of the paper (see `docs/optimize.md`): inside the band
/// it prefers, among cancelling Q-zips, the ones that keep the density (at weight 0.01 a
/// face costs 0.01, a cancelled pair gains 2); outside it a face costs as much as a
/// singularity (at the default steepness 100), so the count stays near the input's. Whole-
/// mesh and O(1), also in a window.
///
/// ```
/// use zipmesh::{gen, optimize::{Context, FaceBudget, ScoreTerm}};
/// let m = gen::grid(3, 3); // 9 faces
/// let at = |f0| FaceBudget::default().score(&Context { mesh: &m, singularities: &[], features: &[], target_area: 1.0, target_faces: f0, faces: None, walls: true });
/// assert_eq!(at(9), 0.0);
/// assert_eq!(at(100), 91.0 + 100.0 * 86.0); // 91 faces off, 86 of them past 5 % of 100
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FaceBudget {
    /// The band (a fraction of the input's face count) inside which a face costs 1.
    pub tolerance: f64,
    /// What a face costs on top outside the band.
    pub steepness: f64,
}

impl Default for FaceBudget {
    fn default() -> Self {
        FaceBudget {
            tolerance: 0.05,
            steepness: 100.0,
        }
    }
}

impl ScoreTerm for FaceBudget {
    builtin_term!("faces");
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        let off = ctx.mesh.map.num_faces().abs_diff(ctx.target_faces) as f64;
        let band = self.tolerance * ctx.target_faces as f64;
        off + self.steepness * (off - band).max(0.0)
    }
}
