//! The input surface as a set of triangles, and the closest point on it: what relaxation,
//! smoothing and the distance measures put vertices back onto. A uniform grid of cells over
//! the triangles' boxes, searched in growing shells. Written here rather than taken from
//! parry3d (the `parry` feature's BVH, used by `quality::Reference`): parry is 2 to 5 times
//! faster only for points far off the surface, and as fast or slower for the points on or
//! near it that relaxation and smoothing ask about (docs/quality.md).

use alloc::vec;
use alloc::vec::Vec;

use glam::DVec3;

use crate::{Mesh, Vert};

/// `mesh`'s faces as triangles, each fanned from its first corner (corners without a
/// position at the origin); faces of fewer than three corners give none.
fn fan_triangles(mesh: &Mesh) -> Vec<[DVec3; 3]> {
    let at = |v: Vert| {
        mesh.positions
            .get(v.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    };
    // Two triangles per quad: one allocation for a quad mesh.
    let mut triangles = Vec::with_capacity(2 * mesh.map.num_faces());
    // Each face as a fan from its first corner, read as the walk goes (no list per face).
    for f in mesh.map.faces() {
        let mut corners = mesh.map.face_darts(f).map(|d| at(mesh.map.origin(d)));
        let (Some(first), Some(mut last)) = (corners.next(), corners.next()) else {
            continue;
        };
        for p in corners {
            triangles.push([first, last, p]);
            last = p;
        }
    }
    triangles
}

/// The cell size and the cells per axis of a grid over a box of `extent` holding `n`
/// triangles: about two triangles per cell along the surface, at most 256 cells per axis
/// and about two cells per triangle in all (a volume-filling box of a dense surface would
/// otherwise ask for 256^3 cells).
fn grid_shape(extent: DVec3, n: usize) -> (f64, [usize; 3]) {
    let mut cell = libm::sqrt(
        (extent.x * extent.y + extent.y * extent.z + extent.z * extent.x) / n as f64 * 2.0,
    )
    .max(extent.max_element() / 256.0);
    let dim = |e: f64, cell: f64| ((e / cell) as usize + 1).min(256);
    let dims_at = |cell: f64| {
        [
            dim(extent.x, cell),
            dim(extent.y, cell),
            dim(extent.z, cell),
        ]
    };
    let budget = 2 * n + 64;
    let mut dims = dims_at(cell);
    while dims[0] * dims[1] * dims[2] > budget {
        cell *= 1.25;
        dims = dims_at(cell);
    }
    (cell, dims)
}

/// Surfaces of at most this many triangles are searched whole: below it one pass over the
/// triangles costs less than the shells of cells (measured on the `tri_optimize` fuzz
/// target's meshes of 12 to 60 triangles, docs/fuzzing.md).
const SMALL: usize = 64;

/// The input surface as triangles (each face fanned from its first corner) in a uniform
/// grid, for closest-point queries. Written by hand: a grid of a few hundred thousand
/// triangles is all a projection after a small move needs.
///
/// ```
/// use zipmesh::{gen, optimize::Surface};
/// use glam::DVec3;
/// let s = Surface::new(&gen::grid(4, 4));
/// let p = s.closest(DVec3::new(1.5, 2.5, 3.0));
/// assert!((p - DVec3::new(1.5, 2.5, 0.0)).length() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct Surface {
    triangles: Vec<[DVec3; 3]>,
    /// Each triangle's bounding box (lower and upper corners), on a surface of at most
    /// [`SMALL`] triangles: a triangle whose box is farther than the best point so far is
    /// not measured. Empty on larger surfaces, whose grid search does not read them.
    boxes: Vec<[DVec3; 2]>,
    /// The largest coordinate's magnitude: the scale of the rounding in a distance.
    scale: f64,
    min: DVec3,
    cell: f64,
    dims: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl Surface {
    /// The surface of `mesh`'s faces.
    ///
    /// See [`Surface`] for an example.
    pub fn new(mesh: &Mesh) -> Self {
        Self::from_triangles(fan_triangles(mesh))
    }

    /// The surface of `triangles` (`quality::Reference` gives it the finite ones of a mesh).
    pub(crate) fn from_triangles(triangles: Vec<[DVec3; 3]>) -> Self {
        let (mut min, mut max) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for t in &triangles {
            for p in t {
                min = min.min(*p);
                max = max.max(*p);
            }
        }
        if triangles.is_empty() || !min.is_finite() || !max.is_finite() {
            return Surface {
                triangles: Vec::new(),
                boxes: Vec::new(),
                scale: 0.0,
                min: DVec3::ZERO,
                cell: 1.0,
                dims: [1; 3],
                cells: vec![Vec::new()],
            };
        }
        let (cell, dims) = grid_shape((max - min).max(DVec3::splat(1e-9)), triangles.len());
        let mut cells = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let mut s = Surface {
            triangles: Vec::new(),
            boxes: Vec::new(),
            scale: min.abs().max(max.abs()).max_element(),
            min,
            cell,
            dims,
            cells: Vec::new(),
        };
        for (i, t) in triangles.iter().enumerate() {
            let lo = s.cell_of(t[0].min(t[1]).min(t[2]));
            let hi = s.cell_of(t[0].max(t[1]).max(t[2]));
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        cells[(x * dims[1] + y) * dims[2] + z].push(i as u32);
                    }
                }
            }
        }
        // Only the whole search of a small surface reads the boxes.
        if triangles.len() <= SMALL {
            s.boxes = triangles
                .iter()
                .map(|t| [t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2])])
                .collect();
        }
        s.triangles = triangles;
        s.cells = cells;
        s
    }

    /// How far `p` is from the walls of its cell ([`Surface::cell_of`]): a triangle none of
    /// whose points is in that cell is at least this far. 0 outside the grid, where
    /// `cell_of` clamps. The shell search stops sooner by it: a point just off the surface,
    /// as smoothing makes, is usually settled by its own cell.
    fn margin(&self, p: DVec3) -> f64 {
        let q = (p - self.min) / self.cell;
        let mut m = f64::INFINITY;
        for (x, &n) in q.to_array().into_iter().zip(&self.dims) {
            if !(x >= 0.0 && x < n as f64) {
                return 0.0;
            }
            // `x` is in [0, n): `as` truncates to its cell's index.
            let f = x - (x as usize) as f64;
            m = m.min(f).min(1.0 - f);
        }
        m * self.cell
    }

    fn cell_of(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.min) / self.cell;
        let c = |x: f64, n: usize| {
            if x.is_finite() && x > 0.0 {
                (x as usize).min(n - 1)
            } else {
                0
            }
        };
        [
            c(q.x, self.dims[0]),
            c(q.y, self.dims[1]),
            c(q.z, self.dims[2]),
        ]
    }

    /// The closest point of the surface to `p` (`p` itself for an empty surface). Searches
    /// shells of cells around `p` until the best distance is inside the searched box.
    ///
    /// See [`Surface`] for an example.
    pub fn closest(&self, p: DVec3) -> DVec3 {
        if self.triangles.is_empty() || !p.is_finite() {
            return p;
        }
        if self.triangles.len() <= SMALL {
            return self.closest_of_all(p);
        }
        let c = self.cell_of(p);
        let margin = self.margin(p);
        let mut best = Best::new(p, self.scale);
        let max_r = self.dims.iter().copied().max().unwrap_or(1);
        for r in 0..=max_r {
            let range = |i: usize, n: usize| i.saturating_sub(r)..=(i + r).min(n - 1);
            for x in range(c[0], self.dims[0]) {
                for y in range(c[1], self.dims[1]) {
                    for z in range(c[2], self.dims[2]) {
                        let on_shell = [x, y, z].iter().zip(&c).any(|(&a, &b)| a.abs_diff(b) == r);
                        if !on_shell {
                            continue;
                        }
                        // No box test here: a cell's triangles are near the point.
                        for &t in &self.cells[(x * self.dims[1] + y) * self.dims[2] + z] {
                            if let Some(tri) = self.triangles.get(t as usize) {
                                best.measure(tri);
                            }
                        }
                    }
                }
            }
            // Every triangle with a point within r cells of p's cell has been seen: the
            // others are farther than r cells and p's margin in its own cell.
            if best.d.is_finite() && libm::sqrt(best.d) <= r as f64 * self.cell + margin {
                break;
            }
        }
        best.q
    }
}

impl Surface {
    /// The closest point of every triangle's, tried in turn: on a small surface cheaper
    /// than walking the cells' shells.
    fn closest_of_all(&self, p: DVec3) -> DVec3 {
        self.search_all(p).q
    }

    fn search_all(&self, p: DVec3) -> Best {
        let mut best = Best::new(p, self.scale);
        for t in 0..self.triangles.len() {
            best.try_triangle(self, t);
        }
        best
    }
}

/// The squared distance from `p` to the box `[lo, hi]` (0 inside).
fn box_gap(&[lo, hi]: &[DVec3; 2], p: DVec3) -> f64 {
    (lo - p).max(p - hi).max(DVec3::ZERO).length_squared()
}

/// The closest point to `p` found so far (`p` itself, at distance infinity, before any)
/// and its squared distance `d`.
struct Best {
    p: DVec3,
    q: DVec3,
    d: f64,
    /// A triangle whose box is at a squared distance above this is farther than `q`, even
    /// after the rounding of either distance: `(sqrt(d) + tol)^2`.
    limit: f64,
    tol: f64,
    /// How many triangles were measured (the others were skipped by their boxes).
    measured: usize,
}

impl Best {
    fn new(p: DVec3, scale: f64) -> Self {
        // Rounding moves a computed closest point by about 1e-16 of the coordinates, far
        // below this tolerance, so a skipped triangle could not have won: the results are
        // those of measuring every triangle, to the bit.
        let tol = 1e-9 * (scale + p.abs().max_element());
        Best {
            p,
            q: p,
            d: f64::INFINITY,
            limit: f64::INFINITY,
            tol,
            measured: 0,
        }
    }

    /// Measures triangle `t` of `s` unless its box (if the surface keeps boxes) is farther
    /// than the best point.
    #[inline]
    fn try_triangle(&mut self, s: &Surface, t: usize) {
        let Some(tri) = s.triangles.get(t) else {
            return;
        };
        if s.boxes
            .get(t)
            .is_none_or(|b| box_gap(b, self.p) <= self.limit)
        {
            self.measure(tri);
        }
    }

    /// Measures triangle `tri`.
    #[inline]
    fn measure(&mut self, tri: &[DVec3; 3]) {
        self.measured += 1;
        let q = closest_on_triangle(self.p, tri);
        let d = q.distance_squared(self.p);
        if d < self.d {
            let r = libm::sqrt(d) + self.tol;
            (self.q, self.d, self.limit) = (q, d, r * r);
        }
    }
}

/// The closest point of triangle `t` to `p` (Ericson, Real-Time Collision Detection, 5.1.5).
fn closest_on_triangle(p: DVec3, t: &[DVec3; 3]) -> DVec3 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        return a;
    }
    a + ab * (vb / denom) + ac * (vc / denom)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// The shell search stops once the best distance is within `p`'s margin in its cell
    /// ([`Surface::margin`]). Its distance equals the search over every triangle for points
    /// just off a sphere (as smoothing makes: most settle in their own cell) and anywhere in
    /// its box (where the nearest triangle is often cells away).
    #[test]
    fn shell_search_is_the_search_of_all() {
        let mesh = crate::gen::subdivided_icosahedron(3);
        let s = Surface::new(&mesh);
        assert!(s.triangles.len() > SMALL, "the cells are searched");
        let mut rng = Rng::new(5);
        let mut u = |k: f64| (rng.below(1_000_001) as f64 / 1_000_000.0 - 0.5) * k;
        let (lo, hi) = mesh.positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let mut settled = 0;
        for i in 0..4_000 {
            let p = if i % 2 == 0 {
                // Within 0.01 of the surface, relative to its size.
                let [a, b, c] = s.triangles[i % s.triangles.len()];
                let (x, y) = (u(1.0) + 0.5, u(1.0) + 0.5);
                let (x, y) = if x + y > 1.0 {
                    (1.0 - x, 1.0 - y)
                } else {
                    (x, y)
                };
                let off = DVec3::new(u(1.0), u(1.0), u(1.0)) * 0.02 * (hi - lo).length();
                a + (b - a) * x + (c - a) * y + off
            } else {
                lo + (hi - lo) * DVec3::new(u(1.2) + 0.5, u(1.2) + 0.5, u(1.2) + 0.5)
            };
            let (grid, all) = (s.closest(p), s.closest_of_all(p));
            assert!(
                (grid.distance(p) - all.distance(p)).abs() <= 1e-12,
                "{p}: {grid} against {all}"
            );
            settled += usize::from(i % 2 == 0 && grid.distance(p) <= s.margin(p));
            // The margin is the distance to the nearest wall of p's cell, 0 off the grid.
            let c = s.cell_of(p);
            let mut walls = f64::INFINITY;
            for k in 0..3 {
                let lo = s.min[k] + c[k] as f64 * s.cell;
                let inside = p[k] >= s.min[k] && p[k] < s.min[k] + s.dims[k] as f64 * s.cell;
                walls = walls.min(if inside {
                    (p[k] - lo).min(lo + s.cell - p[k])
                } else {
                    0.0
                });
            }
            assert!((s.margin(p) - walls).abs() <= 1e-9 * s.cell, "{p}");
        }
        assert!(
            settled > 400,
            "the near points settled in their cell: {settled} of 2000"
        );
    }

    /// The closest point of every triangle's, tried in order, the first strictly nearer
    /// kept: what the search measured before it skipped triangles by their boxes.
    fn every_triangle(s: &Surface, p: DVec3) -> DVec3 {
        let (mut best, mut best_d) = (p, f64::INFINITY);
        for t in &s.triangles {
            let q = closest_on_triangle(p, t);
            let d = q.distance_squared(p);
            if d < best_d {
                (best, best_d) = (q, d);
            }
        }
        best
    }

    /// Skipping the triangles whose boxes are farther than the best point so far gives the
    /// point of measuring every triangle, to the bit: on the corners themselves, points
    /// 1e-12 off them and 1e-3 off the surface, anywhere in the box and far outside it;
    /// and it does skip.
    #[test]
    fn box_skips_change_no_bit() {
        let s = Surface::new(&crate::gen::cube(2));
        assert!(s.triangles.len() <= SMALL, "every triangle is tried");
        let mut rng = Rng::new(9);
        let mut u = |k: f64| (rng.below(1_000_001) as f64 / 1_000_000.0 - 0.5) * k;
        let (mut measured, mut points) = (0, 0);
        for (i, t) in s.triangles.iter().enumerate() {
            for off in [0.0, 1e-12, 1e-3, 3.0, 30.0] {
                let p = t[i % 3] + DVec3::new(u(off), u(off), u(off));
                let best = s.search_all(p);
                assert_eq!(best.q, every_triangle(&s, p), "{p}");
                measured += best.measured;
                points += 1;
            }
        }
        let all = points * s.triangles.len();
        assert!(
            points <= measured && measured < all / 2,
            "the boxes skip: {measured} of {all} measured"
        );
    }

    /// The skip leaves a margin above the best distance, not below: a triangle tried
    /// later and nearer by less than the margin (1e-11 here, its box as near as itself)
    /// still wins.
    #[test]
    fn a_nearer_triangle_within_the_margin_is_measured() {
        let z = [1.0, 1.0 + 1e-11];
        let corners =
            |h: f64| [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| DVec3::new(x, y, h));
        let positions: Vec<DVec3> = z.iter().flat_map(|&h| corners(h)).collect();
        let mesh = Mesh::from_polygons(positions, &[[0u32, 1, 2], [3, 4, 5]])
            .unwrap()
            .0;
        let s = Surface::new(&mesh);
        let p = DVec3::new(0.25, 0.25, 2.0);
        assert_eq!(s.closest(p), DVec3::new(0.25, 0.25, z[1]));
    }
}
