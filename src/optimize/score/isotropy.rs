//! Isotropy: quads close to squares.

use glam::DVec3;

use super::{Context, QuadValue, ScoreTerm};

/// Isotropy: each quad's stretch along four directions, the two pairs of opposite sides and
/// the two diagonals: `ln(a / b)^2 + ln(c / e)^2` with `a`, `b` the summed lengths of the
/// opposite side pairs and `c`, `e` the diagonals (each log ratio capped at 2). Summed over
/// quads; the anticipated effect of a Q-zip is read on the mesh it leaves.
///
/// ```
/// use zipmesh::{gen, optimize::{Context, Isotropy, ScoreTerm}};
/// let m = gen::grid(3, 3);
/// let ctx = Context { mesh: &m, singularities: &[], features: &[], target_area: 1.0, target_faces: 0, faces: None, walls: true };
/// assert_eq!(Isotropy.score(&ctx), 0.0); // unit squares
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Isotropy;

/// `ln(a / b)^2`, the log capped at 2 (a zero or infinite ratio counts as the cap).
pub(super) fn log_ratio_sq(a: f64, b: f64) -> f64 {
    let r = libm::log(a / b);
    let r = if r.is_finite() { r.abs().min(2.0) } else { 2.0 };
    r * r
}

quad_term!(Isotropy, "isotropy", isotropy);

/// One quad's [`Isotropy`].
fn isotropy(&[p0, p1, p2, p3]: &[DVec3; 4], _target_area: f64) -> f64 {
    let a = p0.distance(p1) + p2.distance(p3);
    let b = p1.distance(p2) + p3.distance(p0);
    log_ratio_sq(a, b) + log_ratio_sq(p0.distance(p2), p1.distance(p3))
}
