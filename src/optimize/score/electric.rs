//! Electric push and pull between singularities.

use super::super::marks::Memo;
use super::bfs::Bfs;
use super::{Context, ScoreTerm};

/// Electric push and pull: each singularity `s` with charge `q_s = -defect` (v3 +1, v5 -1)
/// and its three closest singularities `t` (graph distance `d`, at most `radius`) give
/// `q_s q_t / d` (like charges repel, unlike attract), and the closest boundary or feature
/// vertex `b` gives `boundary_weight |q_s| / d_b` (a weak push). Summed over singularities.
///
/// ```
/// use zipmesh::{gen, optimize::{singularities, Context, Electric, ScoreTerm}};
/// let m = gen::subdivided_icosahedron(1);
/// let s = singularities(&m);
/// let ctx = Context { mesh: &m, singularities: &s, features: &[], target_area: 1.0, target_faces: 0, faces: None, walls: true };
/// // Each v5 is one edge from a v3: attraction wins.
/// assert!(Electric::default().score(&ctx) < 0.0);
/// ```
#[derive(Clone, Debug)]
pub struct Electric {
    /// How far (edges) a singularity looks for others.
    pub radius: u32,
    /// The weight of the boundary and feature push.
    pub boundary_weight: f64,
    /// How far (edges) a singularity looks for the boundary or a feature.
    pub boundary_radius: u32,
    /// How a pair's energy falls with distance.
    pub potential: Potential,
    bfs: Bfs,
    defects: Memo<i64>,
}

/// The pair potential of [`Electric`], for charges `q`, `q'` at graph distance `d`.
///
/// ```
/// use zipmesh::optimize::Potential;
/// // Unlike charges attract: the energy rises with the distance, for both potentials.
/// for p in [Potential::Inverse, Potential::Log] {
///     assert!(p.energy(1.0, -1.0, 3, 16) < p.energy(1.0, -1.0, 4, 16));
/// }
/// // The logarithm reaches 0 at the search radius, so no pair gains by leaving it.
/// assert_eq!(Potential::Log.energy(1.0, -1.0, 16, 16), 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Potential {
    /// The paper's "sum of the inverse of these signed distances": `q q' / d`. Its pull on
    /// a pair `d` edges apart falls as `1 / d^2`.
    Inverse,
    /// The potential of charges in the plane (2D Coulomb): `-q q' ln(d / R)`, `R` the
    /// search radius, 0 from `R` on. Its pull falls only as `1 / d`, so far pairs still
    /// attract (`docs/optimize.md`).
    Log,
}

impl Potential {
    /// The energy of charges `q`, `p` at distance `d` (at least 1) with search radius `r`.
    ///
    /// See [`Potential`] for an example.
    pub fn energy(self, q: f64, p: f64, d: u32, r: u32) -> f64 {
        let d = d.max(1) as f64;
        match self {
            Potential::Inverse => q * p / d,
            Potential::Log => {
                let x = libm::log(d / r.max(1) as f64);
                -q * p * x.min(0.0)
            }
        }
    }
}

impl Default for Electric {
    fn default() -> Self {
        Electric {
            radius: 16,
            boundary_weight: 0.5,
            boundary_radius: 4,
            potential: Potential::Inverse,
            bfs: Bfs::default(),
            defects: Memo::default(),
        }
    }
}

impl ScoreTerm for Electric {
    builtin_term!("electric");
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        let map = &ctx.mesh.map;
        let mut total = 0.0;
        // Each singularity's search reads the defects round it: an interior vertex's from
        // the valence the search counts ([`super::defect::defect`]: valence - 4), a
        // boundary vertex's (its angle's) kept for the other searches of this call.
        self.defects.begin(map.vertex_slots());
        let defects = &mut self.defects;
        for s in ctx.singularities {
            let q = s.charge();
            // No wall to find: as if found, so the search stops at the third singularity.
            let (mut found, mut wall) = (0, s.boundary || !ctx.walls);
            let (bw, br) = (self.boundary_weight, self.boundary_radius);
            let (pot, radius) = (self.potential, self.radius);
            self.bfs
                .run_counting(ctx.mesh, s.vertex, self.radius, |v, d, k| {
                    if d == 0 {
                        return true;
                    }
                    let dv = if map.is_boundary_vertex(v) {
                        defects.get(v.index(), || super::super::defect::defect(ctx.mesh, v))
                    } else {
                        k as i64 - 4
                    };
                    if dv != 0 && found < 3 {
                        found += 1;
                        total += pot.energy(q, -(dv as f64), d, radius);
                    }
                    if !wall && d <= br && (map.is_boundary_vertex(v) || ctx.is_feature(v)) {
                        wall = true;
                        total += bw * q.abs() / d as f64;
                    }
                    found < 3 || (!wall && d < br)
                });
        }
        total
    }
}
