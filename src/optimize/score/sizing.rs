//! Uniform sizing: quads close to the target area.

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

quad_term!(Sizing, "sizing", sizing);

/// One quad's [`Sizing`].
fn sizing(&[p0, p1, p2, p3]: &[DVec3; 4], target_area: f64) -> f64 {
    let area = 0.5 * (p2 - p0).cross(p3 - p1).length();
    log_ratio_sq(area, target_area)
}
