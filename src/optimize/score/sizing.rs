//! Uniform sizing: quads close to the target area.

use alloc::boxed::Box;

use glam::DVec3;

use super::isotropy::log_ratio_sq;
use super::{Context, QuadValue, ScoreTerm};

/// Uniform sizing: each quad's `ln(area / target)^2` (the log capped at 2), with the target
/// the input's mean face area: collapses where quads are already large and splits where they
/// are already small raise it.
///
/// ```
/// use zipmesh::{gen, optimize::{Context, Sizing, ScoreTerm}};
/// let m = gen::grid(3, 3);
/// let at = |t| Sizing.score(&Context { mesh: &m, singularities: &[], features: &[], target_area: t, target_faces: 0, faces: None, walls: true });
/// assert_eq!(at(1.0), 0.0);
/// assert!(at(2.0) > 0.0);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Sizing;

impl ScoreTerm for Sizing {
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        Some(Box::new(*self))
    }
    fn name(&self) -> &str {
        "sizing"
    }
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        let mut total = 0.0;
        for f in ctx.scored_faces() {
            if let Some(c) = ctx.corners(f) {
                total += sizing(&c, ctx.target_area);
            }
        }
        total
    }
    fn quad_value(&self) -> Option<QuadValue> {
        Some(sizing)
    }
}

/// One quad's [`Sizing`].
fn sizing(&[p0, p1, p2, p3]: &[DVec3; 4], target_area: f64) -> f64 {
    let area = 0.5 * (p2 - p0).cross(p3 - p1).length();
    log_ratio_sq(area, target_area)
}
