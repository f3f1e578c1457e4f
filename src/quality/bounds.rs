//! The bounds an optimizer's output is held to (docs/results.md, "The bounds"), in one place:
//! the tests, the campaign and fuzz oracles, `optimize --json` and `scripts/results.py` all
//! read them from here.

use alloc::vec::Vec;

use super::Summary;

/// The geometry bounds of an optimized mesh against its input: quad and quad-dominant
/// meshes are held to the quad bounds, meshes of triangles only to the triangle bounds
/// ([`Bounds::failures`]). Distances are fractions of the input's bounding-box diagonal.
///
/// ```
/// use zipmesh::quality::Bounds;
/// let b = Bounds::default();
/// assert_eq!((b.max_distance, b.max_mean_distance, b.jacobian_p1), (0.01, 0.001, 0.3));
/// assert_eq!((b.face_drift, b.thin_share, b.max_triangle_distance), (0.05, 0.001, 0.005));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Quads: the largest distance of a vertex from the input surface.
    pub max_distance: f64,
    /// Quads: the largest mean distance of the vertices from the input surface.
    pub max_mean_distance: f64,
    /// Quads: the scaled Jacobian's 1st percentile stays at least the input's or this,
    /// whichever is smaller.
    pub jacobian_p1: f64,
    /// Quads: the face count stays within this fraction of the input's.
    pub face_drift: f64,
    /// Triangles: at most this fraction of the input's faces more triangles under
    /// [`super::THIN_TRIANGLE_DEGREES`] than the input has.
    pub thin_share: f64,
    /// Triangles: the largest distance of a vertex from the input surface.
    pub max_triangle_distance: f64,
}

impl Default for Bounds {
    /// What a user of a quad remesher holds the output to (issue 42 of the tracker): 1 %
    /// and 0.1 % of the diagonal, 0.3, 5 %; for triangles 0.1 % of the faces and 0.5 %.
    fn default() -> Self {
        Bounds {
            max_distance: 0.01,
            max_mean_distance: 0.001,
            jacobian_p1: 0.3,
            face_drift: 0.05,
            thin_share: 0.001,
            max_triangle_distance: 0.005,
        }
    }
}

/// One bound an output breaks ([`Bounds::failures`]).
///
/// ```
/// use zipmesh::quality::Bound;
/// assert_eq!(Bound::Folds.name(), "folded_quads");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bound {
    /// More folded quads than the input.
    Folds,
    /// More quads of negative scaled Jacobian than the input.
    NegativeJacobian,
    /// The scaled Jacobian's 1st percentile below the input's and below the floor.
    JacobianP1,
    /// The face count outside the drift.
    Faces,
    /// More flipped triangles than the input.
    Flips,
    /// More thin triangles than the input's plus the slack.
    Thin,
    /// A vertex, or the mean, farther from the input surface than allowed; also when the
    /// output was measured without a reference.
    Distance,
}

impl Bound {
    /// The bound's name as `optimize --json` reports it (the `Summary` field it reads).
    ///
    /// See [`Bound`] for an example.
    pub fn name(self) -> &'static str {
        match self {
            Bound::Folds => "folded_quads",
            Bound::NegativeJacobian => "negative_scaled_jacobian",
            Bound::JacobianP1 => "scaled_jacobian_p1",
            Bound::Faces => "faces",
            Bound::Flips => "flipped_triangles",
            Bound::Thin => "thin_triangles",
            Bound::Distance => "distance",
        }
    }
}

impl Bounds {
    /// The bounds `output` breaks against `input`, in [`Bound`] order; empty when all hold.
    /// `output` is measured against the input surface ([`Summary::against`]); without
    /// distances it breaks [`Bound::Distance`]. A mesh with quads is held to the quad
    /// bounds, one of triangles only to the triangle bounds.
    ///
    /// ```
    /// use zipmesh::{gen, quality::{Bound, Bounds, Reference, Summary}};
    /// let input = gen::grid(4, 4);
    /// let reference = Reference::new(&input);
    /// let b = Bounds::default();
    /// let same = Summary::against(&input, &reference);
    /// assert!(b.failures(&Summary::of(&input), &same).is_empty());
    /// let mut off = input.clone();
    /// off.positions[6].z += 0.2; // 2 % of the diagonal off the plane
    /// let far = Summary::against(&off, &reference);
    /// assert_eq!(b.failures(&Summary::of(&input), &far), vec![Bound::Distance]);
    /// ```
    pub fn failures(&self, input: &Summary, output: &Summary) -> Vec<Bound> {
        let mut out = Vec::new();
        let mut fail = |broken: bool, b: Bound| {
            if broken {
                out.push(b);
            }
        };
        let (mean, max) = output
            .distance
            .map_or((f64::INFINITY, f64::INFINITY), |d| (d.mean, d.max));
        if input.quads > 0 || output.quads > 0 {
            fail(output.folded_quads > input.folded_quads, Bound::Folds);
            fail(
                output.negative_jacobian > input.negative_jacobian,
                Bound::NegativeJacobian,
            );
            fail(self.jacobian_p1_falls(input, output), Bound::JacobianP1);
            let drift = input.faces.abs_diff(output.faces) as f64;
            fail(drift > self.face_drift * input.faces as f64, Bound::Faces);
            let near = within(max, self.max_distance) && within(mean, self.max_mean_distance);
            fail(!near, Bound::Distance);
        } else {
            fail(
                output.flipped_triangles > input.flipped_triangles,
                Bound::Flips,
            );
            let slack = self.thin_share * input.faces as f64;
            fail(
                output.thin_triangles as f64 > input.thin_triangles as f64 + slack,
                Bound::Thin,
            );
            fail(!within(max, self.max_triangle_distance), Bound::Distance);
        }
        out
    }

    /// Whether the output's scaled Jacobian 1st percentile is below min(input's, floor);
    /// an output without quads where the input had them falls.
    fn jacobian_p1_falls(&self, input: &Summary, output: &Summary) -> bool {
        let Some(before) = input.jacobian.map(|j| j.p1) else {
            return false;
        };
        let after = output.jacobian.map_or(f64::NEG_INFINITY, |j| j.p1);
        after < before.min(self.jacobian_p1) - 1e-9
    }
}

/// `x <= limit`, false for NaN: a distance that cannot be read breaks its bound.
fn within(x: f64, limit: f64) -> bool {
    x <= limit
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::Reference;
    use crate::{gen, Mesh};
    use glam::DVec3;

    fn failures(input: &Mesh, output: &Mesh) -> Vec<Bound> {
        let after = Summary::against(output, &Reference::new(input));
        Bounds::default().failures(&Summary::of(input), &after)
    }

    /// A vertex pushed into the next quad, on the plane: a fold, a negative scaled Jacobian
    /// and a lower 1st percentile, and nothing else.
    #[test]
    fn a_planted_fold_breaks_the_quad_bounds() {
        let input = gen::grid(4, 4);
        let mut bad = input.clone();
        bad.positions[6] = DVec3::new(1.9, 1.9, 0.0);
        let want = [Bound::Folds, Bound::NegativeJacobian, Bound::JacobianP1];
        assert_eq!(failures(&input, &bad), want);
        assert!(failures(&input, &input).is_empty());
    }

    /// Within 1 % of the diagonal a vertex holds; a mean above 0.1 % does not.
    #[test]
    fn the_distance_bounds_are_the_max_and_the_mean() {
        let input = gen::grid(4, 4);
        let diagonal = Reference::new(&input).diagonal();
        let mut near = input.clone();
        near.positions[6].z = 0.009 * diagonal;
        assert!(failures(&input, &near).is_empty());
        for p in &mut near.positions {
            p.z = 0.002 * diagonal;
        }
        assert_eq!(failures(&input, &near), [Bound::Distance]);
        let unmeasured = Summary::of(&input);
        let b = Bounds::default().failures(&Summary::of(&input), &unmeasured);
        assert_eq!(b, [Bound::Distance]);
    }

    /// A triangle mesh with a vertex pulled onto the middle of a neighbour's edge gains thin
    /// triangles; one pulled across its ring flips some.
    #[test]
    fn planted_thin_and_flipped_triangles_break_the_triangle_bounds() {
        let p = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/tri/torus.obj");
        let (input, _) = crate::io::read_mesh(p).unwrap();
        let m = &input.map;
        let v = crate::Vert::new(5);
        let ring: Vec<DVec3> = m
            .vertex_darts(v)
            .map(|d| input.positions[m.dest(d).index()])
            .collect();
        let mut thin = input.clone();
        thin.positions[5] = (ring[0] + ring[1]) / 2.0 * 0.999 + input.positions[5] * 0.001;
        assert!(failures(&input, &thin).contains(&Bound::Thin));
        let mut flipped = input.clone();
        flipped.positions[5] = ring[0] * 2.0 - input.positions[5];
        assert!(failures(&input, &flipped).contains(&Bound::Flips));
    }
}
