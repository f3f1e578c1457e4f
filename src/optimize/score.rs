//! The score a batch decreases (Q-zip paper, Sec. 4.1, "Scoring strategy"): a weighted sum of
//! terms, each a [`ScoreTerm`], so that library users can add their own.
//!
//! Every term is a function of the whole mesh; a candidate Q-zip is scored by applying it,
//! scoring, and undoing it exactly. `docs/optimize.md` gives each formula.

use alloc::boxed::Box;
use alloc::vec;
use alloc::vec::Vec;

use glam::DVec3;

use super::defect::{singularities, Singularity};
use super::marks::{Marks, Memo};
use crate::{Mesh, Vert};

/// What a term may read: the mesh, its singularities, and what the run fixed at the start.
///
/// See [`ScoreTerm`] for an example.
#[derive(Debug)]
pub struct Context<'a> {
    /// The mesh being scored.
    pub mesh: &'a Mesh,
    /// Its vertices with a non-zero defect ([`super::singularities`]).
    pub singularities: &'a [Singularity],
    /// Whether a vertex (by index) lies on a sharp feature; shorter than the vertex slots
    /// means "no" for the rest.
    pub features: &'a [bool],
    /// The mean face area of the input: the size the sizing term aims for.
    pub target_area: f64,
    /// The input's face count (before preprocessing): what [`FaceBudget`] keeps.
    pub target_faces: usize,
    /// When set, the faces whose terms are summed (a window around a candidate);
    /// `singularities` is then the window's too.
    pub faces: Option<&'a [crate::Face]>,
    /// Whether the mesh may have boundary or feature vertices; `false` lets [`Electric`]
    /// skip its search for a wall (on a closed mesh without features it never finds one).
    pub walls: bool,
}

impl Context<'_> {
    fn position(&self, v: Vert) -> DVec3 {
        self.mesh
            .positions
            .get(v.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    }

    fn is_feature(&self, v: Vert) -> bool {
        self.features.get(v.index()).copied().unwrap_or(false)
    }

    /// The faces a face term sums over: the window's, or every face.
    pub fn scored_faces(&self) -> alloc::boxed::Box<dyn Iterator<Item = crate::Face> + '_> {
        match self.faces {
            Some(f) => alloc::boxed::Box::new(f.iter().copied()),
            None => alloc::boxed::Box::new(self.mesh.map.faces()),
        }
    }

    fn corners(&self, f: crate::Face) -> Option<[DVec3; 4]> {
        let map = &self.mesh.map;
        let d = map.face_dart(f);
        let mut c = [DVec3::ZERO; 4];
        let mut n = 0;
        for x in map.face_cycle(d) {
            *c.get_mut(n)? = self.position(map.origin(x));
            n += 1;
        }
        (n == 4).then_some(c)
    }
}

/// One term of the score: a number for the whole mesh, smaller is better.
///
/// A user term is added with [`super::OptimizeOptions::term`]:
///
/// ```
/// use zipmesh::optimize::{Context, ScoreTerm};
/// /// The number of faces: prefer coarser meshes.
/// #[derive(Debug)]
/// struct Faces;
/// impl ScoreTerm for Faces {
///     fn name(&self) -> &str { "faces" }
///     fn score(&mut self, ctx: &Context<'_>) -> f64 { ctx.mesh.map.num_faces() as f64 }
/// }
/// let options = zipmesh::optimize::OptimizeOptions::default().term(0.001, Box::new(Faces));
/// assert!(options.terms().iter().any(|(_, t)| t.name() == "faces"));
/// ```
pub trait ScoreTerm: core::fmt::Debug {
    /// A short name (used in reports).
    fn name(&self) -> &str;
    /// The term's value on `ctx.mesh`.
    fn score(&mut self, ctx: &Context<'_>) -> f64;
    /// A copy for another thread, or `None` (the default) if the term cannot be copied: the
    /// optimizer's candidate search then runs on one thread. Results are the same either
    /// way; every built-in term can be copied.
    ///
    /// ```
    /// use zipmesh::optimize::{Context, Count, Electric, ScoreTerm};
    /// assert_eq!(Count.fork().unwrap().name(), "count");
    /// assert_eq!(Electric::default().fork().unwrap().name(), "electric");
    /// #[derive(Debug)]
    /// struct Mine;
    /// impl ScoreTerm for Mine {
    ///     fn name(&self) -> &str { "mine" }
    ///     fn score(&mut self, _: &Context<'_>) -> f64 { 0.0 }
    /// }
    /// assert!(Mine.fork().is_none());
    /// ```
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        None
    }
    /// If the term is a sum over the scored quads (in [`Context::scored_faces`] order, from
    /// 0) of a function of each quad's corners (from the face's dart, in cycle order) and
    /// [`Context::target_area`]: that function. The optimizer then reuses the value of a
    /// quad whose corners did not move, with the same score to the last bit. `None` (the
    /// default) for any other term.
    ///
    /// ```
    /// use zipmesh::{gen, optimize::{Context, Count, Isotropy, ScoreTerm, Sizing}};
    /// let m = gen::grid(2, 2);
    /// let ctx = Context { mesh: &m, singularities: &[], features: &[], target_area: 2.0, target_faces: 0, faces: None, walls: true };
    /// let square = [0.0, 1.0].map(|x| [0.0, 1.0].map(|y| glam::DVec3::new(x, y, 0.0)));
    /// let one = Sizing.quad_value().unwrap()(&[square[0][0], square[1][0], square[1][1], square[0][1]], 2.0);
    /// assert_eq!(Sizing.score(&ctx), 4.0 * one); // four unit squares
    /// assert!(Isotropy.quad_value().is_some() && Count.quad_value().is_none());
    /// ```
    fn quad_value(&self) -> Option<QuadValue> {
        None
    }
}

/// A quad term's value of one quad: its corners in cycle order and the target area
/// ([`ScoreTerm::quad_value`]).
pub type QuadValue = fn(&[DVec3; 4], f64) -> f64;

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
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        Some(Box::new(*self))
    }
    fn name(&self) -> &str {
        "count"
    }
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        ctx.singularities
            .iter()
            .map(|s| s.defect.unsigned_abs() as f64)
            .sum()
    }
}

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
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        Some(Box::new(*self))
    }
    fn name(&self) -> &str {
        "faces"
    }
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        let off = ctx.mesh.map.num_faces().abs_diff(ctx.target_faces) as f64;
        let band = self.tolerance * ctx.target_faces as f64;
        off + self.steepness * (off - band).max(0.0)
    }
}

/// Epoch-stamped breadth-first search scratch, reused between calls.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bfs {
    seen: Marks,
    /// The vertices reached, in order, with their distances: read from the front, never
    /// popped (cheaper than a ring buffer; one search pushes each vertex once).
    queue: Vec<(Vert, u32)>,
}

impl Bfs {
    /// Visits vertices from `from` in order of graph distance up to `radius`, calling
    /// `visit(v, d)`; stops early when `visit` returns `false`.
    pub(crate) fn run(
        &mut self,
        mesh: &Mesh,
        from: Vert,
        radius: u32,
        visit: impl FnMut(Vert, u32) -> bool,
    ) {
        self.run_from(mesh, [from], radius, visit);
    }

    /// [`Bfs::run`] with each vertex's valence: `visit(v, d, valence)`, called once the
    /// vertex's darts have been walked (counted, and its neighbours queued when `d` is under
    /// `radius`), so the valence costs no walk of its own. The same vertices in the same
    /// order as [`Bfs::run`]: what a stopped search queued is never visited.
    pub(crate) fn run_counting(
        &mut self,
        mesh: &Mesh,
        from: Vert,
        radius: u32,
        mut visit: impl FnMut(Vert, u32, usize) -> bool,
    ) {
        let map = &mesh.map;
        self.seen.begin(map.vertex_slots());
        self.queue.clear();
        if map.is_live_vertex(from) && self.seen.first(from.index()) {
            self.queue.push((from, 0));
        }
        let mut head = 0;
        while let Some(&(v, d)) = self.queue.get(head) {
            head += 1;
            let mut valence = 0;
            for x in map.vertex_darts(v) {
                valence += 1;
                if d < radius {
                    let u = map.dest(x);
                    if self.seen.first(u.index()) {
                        self.queue.push((u, d + 1));
                    }
                }
            }
            if !visit(v, d, valence) {
                return;
            }
        }
    }

    /// [`Bfs::run`] from several sources at distance 0.
    pub(crate) fn run_from(
        &mut self,
        mesh: &Mesh,
        from: impl IntoIterator<Item = Vert>,
        radius: u32,
        mut visit: impl FnMut(Vert, u32) -> bool,
    ) {
        let map = &mesh.map;
        self.seen.begin(map.vertex_slots());
        self.queue.clear();
        for v in from {
            if map.is_live_vertex(v) && self.seen.first(v.index()) {
                self.queue.push((v, 0));
            }
        }
        let mut head = 0;
        while let Some(&(v, d)) = self.queue.get(head) {
            head += 1;
            if !visit(v, d) {
                return;
            }
            if d >= radius {
                continue;
            }
            for x in map.vertex_darts(v) {
                let u = map.dest(x);
                if self.seen.first(u.index()) {
                    self.queue.push((u, d + 1));
                }
            }
        }
    }
}

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
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        Some(Box::new(self.clone()))
    }
    fn name(&self) -> &str {
        "electric"
    }
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
                        defects.get(v.index(), || super::defect::defect(ctx.mesh, v))
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

fn log_ratio_sq(a: f64, b: f64) -> f64 {
    let r = libm::log(a / b);
    let r = if r.is_finite() { r.abs().min(2.0) } else { 2.0 };
    r * r
}

impl ScoreTerm for Isotropy {
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        Some(Box::new(*self))
    }
    fn name(&self) -> &str {
        "isotropy"
    }
    fn score(&mut self, ctx: &Context<'_>) -> f64 {
        let mut total = 0.0;
        for f in ctx.scored_faces() {
            if let Some(c) = ctx.corners(f) {
                total += isotropy(&c, ctx.target_area);
            }
        }
        total
    }
    fn quad_value(&self) -> Option<QuadValue> {
        Some(isotropy)
    }
}

/// One quad's [`Isotropy`].
fn isotropy(&[p0, p1, p2, p3]: &[DVec3; 4], _target_area: f64) -> f64 {
    let a = p0.distance(p1) + p2.distance(p3);
    let b = p1.distance(p2) + p3.distance(p0);
    log_ratio_sq(a, b) + log_ratio_sq(p0.distance(p2), p1.distance(p3))
}

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
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        Some(Box::new(self.clone()))
    }
    fn name(&self) -> &str {
        "separatrix"
    }
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

/// The weighted terms and the singularity list they share: scores a mesh.
#[derive(Debug)]
pub(crate) struct Scorer {
    pub(crate) terms: Vec<(f64, Box<dyn ScoreTerm + Send>)>,
    pub(crate) features: Vec<bool>,
    pub(crate) target_area: f64,
    pub(crate) target_faces: usize,
    /// Whether the mesh has a boundary or features ([`Context::walls`]).
    pub(crate) walls: bool,
    /// [`Scorer::local`]'s buffers and quad values, kept between calls.
    pub(crate) scratch: LocalScratch,
}

/// What [`Scorer::local`] keeps between calls: its lists, and per face slot the corners
/// the quad terms ([`ScoreTerm::quad_value`]) last read and their values, so that a quad
/// no candidate moved is not measured again.
#[derive(Clone, Debug, Default)]
pub(crate) struct LocalScratch {
    sing: Vec<Singularity>,
    faces: Vec<crate::Face>,
    /// The faces listed by this call (a face is listed once per call).
    listed: Marks,
    /// Per face slot, the corners its row of `values` was computed from.
    corners: Vec<Option<[DVec3; 4]>>,
    /// Per face slot, one value per term (0 for the terms that are not quad terms).
    values: Vec<f64>,
    /// Per term, its quad function, if any.
    quad: Vec<Option<QuadValue>>,
    totals: Vec<f64>,
    /// The target area and the number of terms `values` were computed with.
    area: f64,
    width: usize,
}

impl LocalScratch {
    /// The window's singularities, in window order, and `faces` sorted, each once: listing
    /// first and sorting the few left is cheaper than sorting every corner's face. One walk
    /// round each vertex gives its faces and its valence, so an interior vertex's defect
    /// ([`super::defect::defect`]: valence - 4) costs no walk of its own.
    fn list(&mut self, mesh: &Mesh, window: &[Vert]) {
        let map = &mesh.map;
        self.sing.clear();
        self.faces.clear();
        self.listed.begin(map.face_slots());
        for &v in window {
            let mut valence = 0;
            for d in map.vertex_darts(v) {
                valence += 1;
                if let Some(f) = map.face(d) {
                    if self.listed.first(f.index()) {
                        self.faces.push(f);
                    }
                }
            }
            let boundary = map.is_boundary_vertex(v);
            let defect = match (map.is_live_vertex(v), boundary) {
                (false, _) => 0,
                (true, true) => super::defect::defect(mesh, v),
                (true, false) => valence - 4,
            };
            if defect != 0 {
                self.sing.push(Singularity {
                    vertex: v,
                    defect,
                    boundary,
                });
            }
        }
        self.faces.sort_unstable();
    }

    /// Each weighted quad term's value of every listed quad added into `totals`, in face
    /// order, measuring only the quads whose corners changed since they were last measured.
    fn quad_totals(
        &mut self,
        terms: &[(f64, Box<dyn ScoreTerm + Send>)],
        mesh: &Mesh,
        target_area: f64,
    ) {
        self.quad.clear();
        self.quad.extend(
            terms
                .iter()
                .map(|(w, t)| t.quad_value().filter(|_| *w != 0.0)),
        );
        let width = self.quad.len();
        self.totals.clear();
        self.totals.resize(width, 0.0);
        if self.quad.iter().all(Option::is_none) {
            return;
        }
        if self.area.to_bits() != target_area.to_bits() || self.width != width {
            self.corners.clear();
            self.values.clear();
            (self.area, self.width) = (target_area, width);
        }
        let slots = mesh.map.face_slots().max(self.corners.len());
        self.corners.resize(slots, None);
        self.values.resize(slots * width, 0.0);
        for &f in &self.faces {
            let Some(c) = quad_corners(mesh, f) else {
                continue;
            };
            let (Some(known), Some(row)) = (
                self.corners.get_mut(f.index()),
                self.values
                    .get_mut(f.index() * width..(f.index() + 1) * width),
            ) else {
                continue;
            };
            if known.is_none_or(|k| !same_bits(&k, &c)) {
                for (x, q) in row.iter_mut().zip(&self.quad) {
                    *x = q.map_or(0.0, |q| q(&c, target_area));
                }
                *known = Some(c);
            }
            for (t, x) in self.totals.iter_mut().zip(row.iter()) {
                *t += *x;
            }
        }
    }
}

/// The corners of `f` if it is a quad ([`Context::corners`]).
fn quad_corners(mesh: &Mesh, f: crate::Face) -> Option<[DVec3; 4]> {
    let map = &mesh.map;
    let mut c = [DVec3::ZERO; 4];
    let mut n = 0;
    for x in map.face_cycle(map.face_dart(f)) {
        *c.get_mut(n)? = mesh
            .positions
            .get(map.origin(x).index())
            .copied()
            .unwrap_or(DVec3::ZERO);
        n += 1;
    }
    (n == 4).then_some(c)
}

fn same_bits(a: &[DVec3; 4], b: &[DVec3; 4]) -> bool {
    a.iter()
        .zip(b)
        .all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits))
}

impl Scorer {
    /// A copy for another thread, if every term can be copied ([`ScoreTerm::fork`]).
    pub(crate) fn fork(&self) -> Option<Scorer> {
        let terms = self
            .terms
            .iter()
            .map(|(w, t)| Some((*w, t.fork()?)))
            .collect::<Option<Vec<_>>>()?;
        Some(Scorer {
            terms,
            features: self.features.clone(),
            target_area: self.target_area,
            target_faces: self.target_faces,
            walls: self.walls,
            scratch: LocalScratch::default(),
        })
    }

    /// The weighted total, and each term's unweighted value. The quad terms read the
    /// values [`LocalScratch`] keeps for quads that did not move, summed over every face in
    /// slot order as the terms' own sums are, so the value is the same to the bit; a Q-zip
    /// moves a few dozen quads, and this is called once per executed one.
    pub(crate) fn score(&mut self, mesh: &Mesh) -> (f64, Vec<f64>) {
        let s = singularities(mesh);
        let sc = &mut self.scratch;
        sc.faces.clear();
        sc.faces.extend(mesh.map.faces());
        sc.quad_totals(&self.terms, mesh, self.target_area);
        let ctx = Context {
            mesh,
            singularities: &s,
            features: &self.features,
            target_area: self.target_area,
            target_faces: self.target_faces,
            faces: None,
            walls: self.walls,
        };
        let mut parts = vec![0.0; self.terms.len()];
        let mut total = 0.0;
        let terms = self.terms.iter_mut().zip(&sc.quad).zip(&sc.totals);
        for ((((w, t), quad), sum), p) in terms.zip(&mut parts) {
            if *w != 0.0 {
                *p = match quad {
                    Some(_) => *sum,
                    None => t.score(&ctx),
                };
                total += *w * *p;
            }
        }
        (total, parts)
    }

    /// The weighted sum of the terms over a window (vertices, sorted): its singularities and
    /// the faces at its vertices. The quad terms read the
    /// values [`LocalScratch`] keeps for quads that did not move.
    pub(crate) fn local(&mut self, mesh: &Mesh, window: &[Vert]) -> f64 {
        let sc = &mut self.scratch;
        sc.list(mesh, window);
        sc.quad_totals(&self.terms, mesh, self.target_area);
        let ctx = Context {
            mesh,
            singularities: &sc.sing,
            features: &self.features,
            target_area: self.target_area,
            target_faces: self.target_faces,
            faces: Some(&sc.faces),
            walls: self.walls,
        };
        let (quad, totals) = (&sc.quad, &sc.totals);
        self.terms
            .iter_mut()
            .enumerate()
            .filter(|(_, (w, _))| *w != 0.0)
            .map(|(i, (w, t))| match quad[i] {
                Some(_) => *w * totals[i],
                None => *w * t.score(&ctx),
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scorer() -> Scorer {
        Scorer {
            terms: crate::optimize::OptimizeOptions::default().terms,
            features: Vec::new(),
            target_area: 0.7,
            target_faces: 50,
            walls: true,
            scratch: LocalScratch::default(),
        }
    }

    /// A scorer that kept the quad values of earlier calls scores a window as a new one
    /// does, to the bit, after corners moved and after a face changed its corners.
    #[test]
    fn kept_quad_values_give_the_fresh_score() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 0, 2));
        let window: Vec<Vert> = mesh.map.vertices().take(30).collect();
        let mut kept = scorer();
        let first = kept.local(&mesh, &window);
        assert_eq!(first.to_bits(), scorer().local(&mesh, &window).to_bits());
        for (i, &v) in window.iter().enumerate().step_by(3) {
            mesh.positions[v.index()] += DVec3::splat(0.01 * (i + 1) as f64);
            let again = kept.local(&mesh, &window);
            assert_eq!(again.to_bits(), scorer().local(&mesh, &window).to_bits());
            assert_ne!(again.to_bits(), first.to_bits());
        }
        // A flip of the edge at a window vertex gives two faces new corners.
        let d = mesh.map.vertex_dart(window[0]);
        crate::ops::quad::rotate_edge(&mut mesh.map, d, crate::ops::quad::Rotation::Clockwise)
            .unwrap();
        let flipped = kept.local(&mesh, &window);
        assert_eq!(flipped.to_bits(), scorer().local(&mesh, &window).to_bits());
    }

    /// A window's listed singularities are the mesh's singularities in the window, in
    /// window order, with boundary vertices (defects from their angles) and a dead slot
    /// (none) among them; its faces are those at its vertices, sorted, each once.
    #[test]
    fn window_lists_its_singularities_and_faces() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 1, 8));
        // A dead vertex slot in the window: a collapse frees one.
        let darts: Vec<_> = mesh.map.darts().collect();
        let gone = darts
            .into_iter()
            .find_map(|d| crate::ops::quad::collapse_quad(&mut mesh.map, d).ok())
            .unwrap()
            .removed();
        assert!(!mesh.map.is_live_vertex(gone));
        let mut window: Vec<Vert> = (0..mesh.map.vertex_slots() as u32)
            .map(Vert::new)
            .rev()
            .step_by(2)
            .collect();
        window.push(gone);
        let mut s = scorer();
        s.local(&mesh, &window);
        let all = singularities(&mesh);
        let want: Vec<Singularity> = window
            .iter()
            .filter_map(|&v| all.iter().find(|x| x.vertex == v).copied())
            .collect();
        assert!(want.iter().any(|x| x.boundary) && want.iter().any(|x| !x.boundary));
        assert_eq!(s.scratch.sing, want);
        let mut faces: Vec<crate::Face> = window
            .iter()
            .flat_map(|&v| mesh.map.vertex_darts(v).filter_map(|d| mesh.map.face(d)))
            .collect();
        faces.sort_unstable();
        faces.dedup();
        assert_eq!(s.scratch.faces, faces);
    }

    /// The counting search visits what [`Bfs::run`] visits, in its order, stopped anywhere,
    /// and counts each vertex's valence.
    #[test]
    fn counting_search_is_the_search_with_valences() {
        let random = crate::gen::catmull_clark(&crate::gen::random_triangle(30, 1, 1, 4));
        for mesh in [crate::gen::grid(4, 3), random] {
            let (mut plain, mut counting) = (Bfs::default(), Bfs::default());
            for from in mesh.map.vertices().step_by(5) {
                for (radius, stop) in [(0, 9), (1, 3), (3, 40), (5, usize::MAX)] {
                    let mut want = Vec::new();
                    plain.run(&mesh, from, radius, |v, d| {
                        want.push((v, d, mesh.map.valence(v)));
                        want.len() < stop
                    });
                    let mut got = Vec::new();
                    counting.run_counting(&mesh, from, radius, |v, d, k| {
                        got.push((v, d, k));
                        got.len() < stop
                    });
                    assert_eq!(got, want, "from {from:?}, radius {radius}, stop {stop}");
                }
            }
        }
    }

    /// The electric term as it was written before its search counted valences: a plain
    /// search, every defect from [`super::super::defect::defect`].
    fn electric_reference(e: &Electric, ctx: &Context<'_>) -> f64 {
        let (map, mut total, mut bfs) = (&ctx.mesh.map, 0.0, Bfs::default());
        for s in ctx.singularities {
            let q = s.charge();
            let (mut found, mut wall) = (0, s.boundary || !ctx.walls);
            bfs.run(ctx.mesh, s.vertex, e.radius, |v, d| {
                if d == 0 {
                    return true;
                }
                let dv = super::super::defect::defect(ctx.mesh, v);
                if dv != 0 && found < 3 {
                    found += 1;
                    total += e.potential.energy(q, -(dv as f64), d, e.radius);
                }
                let b = map.is_boundary_vertex(v) || ctx.is_feature(v);
                if !wall && d <= e.boundary_radius && b {
                    wall = true;
                    total += e.boundary_weight * q.abs() / d as f64;
                }
                found < 3 || (!wall && d < e.boundary_radius)
            });
        }
        total
    }

    /// The electric term, to the bit, is the reference's on meshes with and without
    /// boundary (whose vertices' defects come from their angles), whole and in windows.
    #[test]
    fn electric_is_its_reference() {
        let meshes = [
            crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 1, 6)),
            crate::gen::catmull_clark(&crate::gen::random_triangle(30, 0, 0, 7)),
            crate::gen::subdivided_icosahedron(2),
        ];
        for mesh in &meshes {
            let all = singularities(mesh);
            assert!(all.len() > 4);
            for sing in [&all[..], &all[..all.len() / 2]] {
                let ctx = Context {
                    mesh,
                    singularities: sing,
                    features: &[],
                    target_area: 1.0,
                    target_faces: 0,
                    faces: None,
                    walls: true,
                };
                let mut e = Electric::default();
                let want = electric_reference(&e, &ctx);
                assert_eq!(e.score(&ctx).to_bits(), want.to_bits());
                assert_ne!(want, 0.0);
            }
        }
    }

    /// Each term's own sum over the whole mesh, weighted and added in term order: what
    /// [`Scorer::score`] gave before it read kept quad values.
    fn own_sums(s: &mut Scorer, mesh: &Mesh) -> (f64, Vec<f64>) {
        let sing = singularities(mesh);
        let ctx = Context {
            mesh,
            singularities: &sing,
            features: &s.features,
            target_area: s.target_area,
            target_faces: s.target_faces,
            faces: None,
            walls: s.walls,
        };
        let mut parts = vec![0.0; s.terms.len()];
        let mut total = 0.0;
        for ((w, t), p) in s.terms.iter_mut().zip(&mut parts) {
            if *w != 0.0 {
                *p = t.score(&ctx);
                total += *w * *p;
            }
        }
        (total, parts)
    }

    /// The whole-mesh score with kept quad values (warmed by windows and earlier scores)
    /// is each term's own sum, to the bit, as quads move and an edge turns.
    #[test]
    fn whole_score_with_kept_quad_values_is_the_terms_own() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 0, 3));
        let window: Vec<Vert> = mesh.map.vertices().take(30).collect();
        let mut kept = scorer();
        let bits = |x: &(f64, Vec<f64>)| {
            let mut b = vec![x.0.to_bits()];
            b.extend(x.1.iter().map(|p| p.to_bits()));
            b
        };
        let first = kept.score(&mesh);
        assert_eq!(bits(&first), bits(&own_sums(&mut scorer(), &mesh)));
        for (i, &v) in window.iter().enumerate().step_by(4) {
            mesh.positions[v.index()] += DVec3::splat(0.02 * (i + 1) as f64);
            kept.local(&mesh, &window[..i + 1]);
            let again = kept.score(&mesh);
            assert_eq!(bits(&again), bits(&own_sums(&mut scorer(), &mesh)));
            assert_ne!(again.0.to_bits(), first.0.to_bits());
        }
        let d = mesh.map.vertex_dart(window[1]);
        crate::ops::quad::rotate_edge(&mut mesh.map, d, crate::ops::quad::Rotation::Clockwise)
            .unwrap();
        let turned = kept.score(&mesh);
        assert_eq!(bits(&turned), bits(&own_sums(&mut scorer(), &mesh)));
    }
}
