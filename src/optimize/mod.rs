//! Automatic singularity reduction of quad meshes by batches of Q-zips (Q-zip paper,
//! Sec. 4.1): scores ([`score`](mod@score)), batches (`batch`), boundary defects
//! ([`defect`](mod@defect)), features and protected regions ([`Constraints`]) and smoothing
//! near the scars ([`smooth`](mod@smooth)); quad-dominant input has its triangle pairs
//! merged first ([`TriangleStage`]). `docs/optimize.md` gives our reading of the paper.
//!
//! ```
//! use zipmesh::{gen, optimize::{optimize, Constraints, OptimizeOptions}};
//! let mut mesh = gen::catmull_clark(&gen::random_triangle(60, 1, 0, 3));
//! let out = optimize(&mut mesh, Constraints::default(), OptimizeOptions::default().batches(3), |_| {}).unwrap();
//! assert!(out.final_counts.singularities() <= out.input.singularities());
//! assert!(out.batches.windows(2).all(|w| w[1].score <= w[0].score));
//! ```

mod batch;
mod chain;
pub mod constraints;
pub mod defect;
mod folds;
mod marks;
mod onto;
mod quad_dominant;
pub mod score;
pub mod smooth;
mod tri;

use alloc::boxed::Box;
use alloc::vec::Vec;

use glam::DVec3;

pub use crate::geometry::Surface;
pub use constraints::{ConstraintError, Constraints};
pub use defect::{
    at_defect_minimum, defect, ideal_boundary_valence, singularities, vertex_angle, Singularity,
};
pub use folds::{folded_quads, is_folded};
pub use quad_dominant::TriangleStage;
pub use score::{
    Context, Count, Electric, FaceBudget, Isotropy, Potential, ScoreTerm, Separatrix, Sizing,
};
pub use smooth::{smooth, spring_stiffness};
pub use tri::{
    optimize_triangles, tri_score, TriBatch, TriCounts, TriOptimizeError, TriOptimizeOptions,
    TriOutcome,
};

use crate::invariants::{Counts, MeshKind};
use crate::qzip::{preprocess, Qzip, SketchOptions};
use crate::rng::Rng;
use crate::{Mesh, Vert};

/// How a run goes: the score's terms and weights, the number of batches, the seed, the
/// smoothing. Start from [`OptimizeOptions::default`] and chain the setters.
///
/// The default weights: count 1, electric 0.1, isotropy 0.002, sizing 0.002, separatrix
/// 0.05, faces 0.01 (see `docs/optimize.md` for why the count dominates and how the weights
/// were chosen). A weight of 0 switches a term off.
///
/// ```
/// use zipmesh::optimize::OptimizeOptions;
/// let o = OptimizeOptions::default().batches(5).seed(7).smoothing(false).weight("isotropy", 0.0);
/// assert_eq!((o.max_batches, o.seed, o.smooth), (5, 7, false));
/// assert_eq!(o.terms().iter().find(|(_, t)| t.name() == "isotropy").unwrap().0, 0.0);
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub struct OptimizeOptions {
    /// The most batches to run; by default no limit: the run goes on while batches execute
    /// Q-zips (each lowers the score), and ends after [`OptimizeOptions::patience`] idle
    /// batches or when [`OptimizeOptions::until`]'s test answers true.
    pub max_batches: usize,
    /// Stop after this many batches in a row that executed no Q-zip (each samples another
    /// half of the singularities).
    pub patience: usize,
    /// The seed of the sampling.
    pub seed: u64,
    /// Smooth near the scars after each batch.
    pub smooth: bool,
    /// Laplacian steps per batch.
    pub smooth_iterations: usize,
    /// Run the valence-2 / valence-6+ preprocessing first.
    pub preprocess: bool,
    /// How far (edges) a singularity looks for its six targets.
    pub search_radius: u32,
    /// After a batch that executed nothing, walk v3/v5 pairs together by chains of Q-zips,
    /// then singularities onto opposite ones ([`ChainStats`]).
    pub chains: bool,
    /// Keep no Q-zip, chain or smoothing that leaves more folded quads (any fold test of
    /// [`crate::quality`]: what `zipmesh stats` counts, negative scaled Jacobians included)
    /// than there were round it. On by default: with the footprints relaxed on the input
    /// surface it costs few singularities (docs/quality.md, "After the optimizer").
    pub fold_guard: bool,
    terms: Vec<(f64, Box<dyn ScoreTerm + Send>)>,
    stop: StopWhen,
}

/// A test the run asks between batches and between the candidates of a batch (set by
/// [`OptimizeOptions::until`]); none by default. A closure, so that the no_std library can
/// keep a deadline read from a clock it does not have.
#[derive(Clone, Default)]
pub(crate) struct StopWhen(Option<alloc::sync::Arc<dyn Fn() -> bool + Send + Sync>>);

impl StopWhen {
    /// Whether the run should stop now.
    pub(crate) fn now(&self) -> bool {
        self.0.as_ref().is_some_and(|f| f())
    }
}

impl core::fmt::Debug for StopWhen {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(if self.0.is_some() { "Some(..)" } else { "None" })
    }
}

impl Default for OptimizeOptions {
    fn default() -> Self {
        OptimizeOptions {
            max_batches: usize::MAX,
            patience: 2,
            seed: 0,
            smooth: true,
            smooth_iterations: 3,
            preprocess: true,
            search_radius: 64,
            chains: true,
            fold_guard: true,
            stop: StopWhen::default(),
            terms: alloc::vec![
                (1.0, Box::new(Count) as Box<dyn ScoreTerm + Send>),
                (0.1, Box::new(Electric::default())),
                (0.002, Box::new(Isotropy)),
                (0.002, Box::new(Sizing)),
                (0.05, Box::new(Separatrix::default())),
                (0.01, Box::new(FaceBudget::default())),
            ],
        }
    }
}

impl OptimizeOptions {
    /// Sets [`OptimizeOptions::max_batches`].
    ///
    /// See [`OptimizeOptions`] for an example.
    pub fn batches(mut self, n: usize) -> Self {
        self.max_batches = n;
        self
    }

    /// Stops the run when `stop` answers true: it is asked before each batch and before
    /// each singularity's search and each Q-zip of a batch, so a deadline is kept to about
    /// one candidate's time. The mesh is then as the last executed Q-zip left it, settled on
    /// the input surface, and [`Outcome::stopped`] is true.
    ///
    /// ```
    /// use zipmesh::{gen, optimize::{optimize, Constraints, OptimizeOptions}};
    /// let mut mesh = gen::subdivided_icosahedron(3);
    /// let out = optimize(&mut mesh, Constraints::default(), OptimizeOptions::default().until(|| true), |_| {}).unwrap();
    /// assert!(out.stopped && out.batches.is_empty());
    /// assert_eq!(mesh.map.check(), Ok(()));
    /// ```
    pub fn until(mut self, stop: impl Fn() -> bool + Send + Sync + 'static) -> Self {
        self.stop = StopWhen(Some(alloc::sync::Arc::new(stop)));
        self
    }

    /// Sets [`OptimizeOptions::seed`].
    ///
    /// See [`OptimizeOptions`] for an example.
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`OptimizeOptions::smooth`].
    ///
    /// See [`OptimizeOptions`] for an example.
    pub fn smoothing(mut self, on: bool) -> Self {
        self.smooth = on;
        self
    }

    /// Sets [`OptimizeOptions::chains`].
    ///
    /// ```
    /// use zipmesh::optimize::OptimizeOptions;
    /// assert!(OptimizeOptions::default().chains);
    /// assert!(!OptimizeOptions::default().chains(false).chains);
    /// ```
    pub fn chains(mut self, on: bool) -> Self {
        self.chains = on;
        self
    }

    /// Sets [`OptimizeOptions::fold_guard`].
    ///
    /// ```
    /// use zipmesh::optimize::OptimizeOptions;
    /// assert!(OptimizeOptions::default().fold_guard);
    /// assert!(!OptimizeOptions::default().fold_guard(false).fold_guard);
    /// ```
    pub fn fold_guard(mut self, on: bool) -> Self {
        self.fold_guard = on;
        self
    }

    /// Sets the weight of every term named `name` (non-finite weights read as 0).
    ///
    /// See [`OptimizeOptions`] for an example.
    pub fn weight(mut self, name: &str, weight: f64) -> Self {
        let w = if weight.is_finite() { weight } else { 0.0 };
        for (x, t) in &mut self.terms {
            if t.name() == name {
                *x = w;
            }
        }
        self
    }

    /// Adds a term with its weight.
    ///
    /// See [`ScoreTerm`] for an example.
    pub fn term(mut self, weight: f64, term: Box<dyn ScoreTerm + Send>) -> Self {
        self.terms
            .push((if weight.is_finite() { weight } else { 0.0 }, term));
        self
    }

    /// The terms and their weights.
    ///
    /// See [`OptimizeOptions`] for an example.
    pub fn terms(&self) -> &[(f64, Box<dyn ScoreTerm + Send>)] {
        &self.terms
    }
}

/// The counts a run reports: faces, triangles, vertices, interior vertices by valence (2, 3,
/// 5, 6 and more; a triangle's corners are counted by their valence like any other) and the
/// sum of |defect| over boundary vertices.
///
/// ```
/// use zipmesh::{gen, optimize::SingularityCounts};
/// let c = SingularityCounts::of(&gen::subdivided_icosahedron(1));
/// assert_eq!((c.v3, c.v5, c.singularities()), (20, 12, 32));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SingularityCounts {
    /// Faces.
    pub faces: usize,
    /// Faces that are triangles (the others are quads).
    pub triangles: usize,
    /// Vertices.
    pub vertices: usize,
    /// Interior vertices of valence 2.
    pub v2: usize,
    /// Interior vertices of valence 3.
    pub v3: usize,
    /// Interior vertices of valence 5.
    pub v5: usize,
    /// Interior vertices of valence 6 or more.
    pub v6plus: usize,
    /// The sum of |defect| over boundary vertices ([`defect()`]).
    pub boundary_defects: usize,
}

impl SingularityCounts {
    /// Counts `mesh`.
    ///
    /// See [`SingularityCounts`] for an example.
    pub fn of(mesh: &Mesh) -> Self {
        let map = &mesh.map;
        let mut c = SingularityCounts {
            faces: map.num_faces(),
            triangles: map.faces().filter(|&f| map.degree(f) == 3).count(),
            vertices: map.num_vertices(),
            ..Default::default()
        };
        for v in map.vertices() {
            if map.is_boundary_vertex(v) {
                c.boundary_defects += defect(mesh, v).unsigned_abs() as usize;
                continue;
            }
            match map.valence(v) {
                2 => c.v2 += 1,
                3 => c.v3 += 1,
                5 => c.v5 += 1,
                k if k >= 6 => c.v6plus += 1,
                _ => {}
            }
        }
        c
    }

    /// Interior irregular vertices (valences 0 and 1 are not counted: a quad mesh has none).
    ///
    /// See [`SingularityCounts`] for an example.
    pub fn singularities(&self) -> usize {
        self.v2 + self.v3 + self.v5 + self.v6plus
    }
}

/// Where a batch's face changes came from: its candidates by sign of their face change
/// (a Q-zip changes the face count by its splits minus its collapses, plus its clean-up),
/// those that the window estimate ranked as improving, and the executed ones.
///
/// ```
/// use zipmesh::{gen, optimize::{optimize, Constraints, OptimizeOptions}};
/// let mut mesh = gen::catmull_clark(&gen::random_triangle(60, 1, 0, 3));
/// let out = optimize(&mut mesh, Constraints::default(), OptimizeOptions::default().batches(2), |_| {}).unwrap();
/// let s = out.batches[0].stats;
/// assert_eq!(s.candidates, s.removing.0 + s.keeping.0 + s.adding.0);
/// assert_eq!(out.batches[0].qzips, s.executed.0 + s.executed.1 + s.executed.2);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct BatchStats {
    /// Candidates tried (applied, scored, undone).
    pub candidates: usize,
    /// Candidates that removed faces: (tried, ranked improving).
    pub removing: (usize, usize),
    /// Candidates that kept the face count: (tried, ranked improving).
    pub keeping: (usize, usize),
    /// Candidates that added faces: (tried, ranked improving).
    pub adding: (usize, usize),
    /// Executed Q-zips that removed, kept and added faces.
    pub executed: (usize, usize, usize),
    /// The executed Q-zips' total face change.
    pub face_change: isize,
}

impl BatchStats {
    fn tried(&mut self, faces: isize, improving: bool) {
        self.candidates += 1;
        let slot = match faces.signum() {
            -1 => &mut self.removing,
            0 => &mut self.keeping,
            _ => &mut self.adding,
        };
        slot.0 += 1;
        slot.1 += usize::from(improving);
    }

    /// Adds the candidate counts of `o` (a part of the same batch's search).
    fn add_tried(&mut self, o: &BatchStats) {
        self.candidates += o.candidates;
        for (a, b) in [
            (&mut self.removing, o.removing),
            (&mut self.keeping, o.keeping),
            (&mut self.adding, o.adding),
        ] {
            a.0 += b.0;
            a.1 += b.1;
        }
    }

    fn executed(&mut self, faces: isize) {
        match faces.signum() {
            -1 => self.executed.0 += 1,
            0 => self.executed.1 += 1,
            _ => self.executed.2 += 1,
        }
        self.face_change += faces;
    }
}

/// What the chain stage of a batch did (our addition to Sec. 4.1, `docs/optimize.md`,
/// "The endgame"). It runs after a batch that executed nothing: each v3-like singularity
/// and its two closest v5-like ones (and the other way round), closest pairs first, are
/// walked together by Q-zips, one movement at a time, until they cancel; a chain is kept
/// only if it cancelled its pair and the whole score fell, else undone exactly. If no pair
/// chain is kept, each unit singularity is walked onto a close one of the opposite sign
/// by Q-zips with a third singularity (a pair zipped with itself only translates), kept
/// on the same terms; the counts here are both stages'.
///
/// ```
/// use zipmesh::{gen, optimize::{optimize, Constraints, OptimizeOptions}};
/// let mut mesh = gen::catmull_clark(&gen::random_triangle(60, 1, 0, 3));
/// let out = optimize(&mut mesh, Constraints::default(), OptimizeOptions::default().batches(8), |_| {}).unwrap();
/// for b in &out.batches {
///     assert!(b.chains.kept <= b.chains.tried && b.chains.qzips >= b.chains.kept);
///     if b.chains.tried > 0 {
///         assert_eq!(b.qzips, 0); // only after a batch that executed nothing
///     }
/// }
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ChainStats {
    /// Chains started.
    pub tried: usize,
    /// Chains that walked their pair until it cancelled (kept or not: the rest stalled).
    pub cancelled: usize,
    /// Chains kept (cancelled, and the whole score fell).
    pub kept: usize,
    /// Q-zips of the kept chains.
    pub qzips: usize,
    /// How the kept chains changed the face count (a quad mesh's Q-zip changes it as much
    /// as the vertex count).
    pub face_change: isize,
}

/// What one batch did.
///
/// See [`optimize`] for an example.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct BatchReport {
    /// The batch number, from 1.
    pub batch: usize,
    /// Q-zips executed by the batch (the chain stage's are in [`BatchReport::chains`]).
    pub qzips: usize,
    /// What the chain stage did (nothing unless the batch executed nothing).
    pub chains: ChainStats,
    /// Candidate surgeries applied, scored and undone.
    pub candidates: usize,
    /// How the candidates and the executed Q-zips changed the face count.
    pub stats: BatchStats,
    /// The counts after the batch (and its smoothing).
    pub counts: SingularityCounts,
    /// The total score after the batch.
    pub score: f64,
    /// Whether the smoothing was kept (it is undone when it would raise the score).
    pub smoothed: bool,
    /// The executed surgery paths (the batch's, then the kept chains' steps), as the
    /// positions of their vertices before each Q-zip.
    pub paths: Vec<Vec<DVec3>>,
}

/// The result of [`optimize`].
///
/// See [`optimize`] for an example.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Outcome {
    /// The counts of the input.
    pub input: SingularityCounts,
    /// What the triangle stage did (quad-dominant input; all zero on a pure quad mesh).
    pub triangles: TriangleStage,
    /// The total score before the first batch (after preprocessing).
    pub initial_score: f64,
    /// Whether the preprocessing ran and was kept.
    pub preprocessed: bool,
    /// Whether the mesh already carried the least total defect Gauss-Bonnet allows
    /// ([`at_defect_minimum`]), so that no batch ran and the mesh is returned as it was
    /// (after the triangle stage, if any).
    pub minimal: bool,
    /// One report per batch run (the last may have executed nothing).
    pub batches: Vec<BatchReport>,
    /// Whether [`OptimizeOptions::until`]'s test stopped the run.
    pub stopped: bool,
    /// The counts of the result.
    pub final_counts: SingularityCounts,
}

/// Why [`optimize`] refused; the mesh is unchanged.
///
/// ```
/// use zipmesh::{gen, optimize::{optimize, Constraints, OptimizeError, OptimizeOptions}};
/// let mut tri = gen::random_triangle(40, 0, 0, 1);
/// let e = optimize(&mut tri, Constraints::default(), OptimizeOptions::default(), |_| {});
/// assert_eq!(e.unwrap_err(), OptimizeError::NotQuad);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum OptimizeError {
    /// A face is neither a quad nor a triangle, or no face is a quad.
    NotQuad,
    /// The constraints do not hold on the input (they were recorded on another mesh).
    ConstraintsBroken,
    /// Fewer positions than vertex slots.
    MissingPositions,
}

impl core::fmt::Display for OptimizeError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NotQuad => f.write_str("not a quad or quad-dominant mesh"),
            Self::ConstraintsBroken => f.write_str("the constraints do not hold on this mesh"),
            Self::MissingPositions => f.write_str("fewer positions than vertices"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for OptimizeError {}

fn mean_face_area(mesh: &Mesh) -> f64 {
    let at = |v: Vert| {
        mesh.positions
            .get(v.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    };
    let (mut sum, mut n) = (0.0, 0usize);
    for f in mesh.map.faces() {
        let c: Vec<DVec3> = mesh
            .map
            .face_darts(f)
            .map(|d| at(mesh.map.origin(d)))
            .collect();
        if let [p0, p1, p2, p3] = c[..] {
            sum += 0.5 * (p2 - p0).cross(p3 - p1).length();
            n += 1;
        }
    }
    if n > 0 && sum > 0.0 && sum.is_finite() {
        sum / n as f64
    } else {
        1.0
    }
}

/// Relaxes on `surface` the vertices an edit of `before` moved or made (and their rings),
/// the constraints' locked vertices held where they are.
fn relax_edited(mesh: &mut Mesh, before: &Mesh, surface: &Surface, constraints: &Constraints) {
    let mut fixed = alloc::vec![false; mesh.map.vertex_slots()];
    for v in constraints.locked_vertices() {
        if let Some(x) = fixed.get_mut(v.index()) {
            *x = true;
        }
    }
    let seeds = crate::geometry::edited_vertices(before, mesh);
    crate::geometry::relax_footprint_fixed(
        mesh,
        surface,
        &seeds,
        batch::RELAX,
        &fixed,
        &mut Vec::new(),
    );
}

/// Runs batches of Q-zips on `mesh` until a batch improves nothing
/// ([`OptimizeOptions::patience`] times in a row) or [`OptimizeOptions::max_batches`] ran,
/// calling `progress` after each batch. The score never rises from one batch to the next;
/// the mesh stays a valid map with the same Euler characteristic, boundary loops and
/// components, and `constraints` hold throughout. Deterministic for a given seed.
///
/// **Quad-dominant input** (triangles and quads, at least one quad): first pairs of
/// triangles crawl towards each other and merge ([`TriangleStage`], Tarini et al. 2010,
/// Sec. 6.1), closest pair first; a merge is kept only if it does not raise the interior
/// singularities plus boundary defects; the crawls' moved and new vertices are then relaxed
/// on the input surface. The preprocessing runs only if the result is pure
/// quad; the batches' Q-zips wind around the triangles left
/// ([`crate::qzip::avoid_triangles`]), which they never change. Under the fold guard, a run
/// whose output has more folded quads than the input ([`folded_quads`] and the other fold
/// tests of [`crate::quality`]) is made again from the input with each merged crawl relaxed
/// at once and undone if it folds a quad ([`TriangleStage::guarded`]; `progress` then
/// hears the second run's batches from 1 again). The crawls between randomly placed
/// triangles can fold quads that the joint relaxation does not mend; guarding every merge
/// always would refuse crawls that later batches mend (the OpenSubdiv rook would keep 6 of
/// its 44 triangles instead of 2).
///
/// ```
/// use zipmesh::{gen, optimize::{optimize, Constraints, OptimizeOptions}};
/// let (mut mesh, _) = gen::with_triangle_pairs(gen::subdivided_icosahedron(2), 2, 6, 1);
/// let out = optimize(&mut mesh, Constraints::default(), OptimizeOptions::default().batches(2), |_| {}).unwrap();
/// assert_eq!(out.input.triangles, 4);
/// assert_eq!(out.final_counts.triangles, 4 - 2 * out.triangles.merged);
/// assert_eq!(mesh.map.check(), Ok(()));
/// ```
pub fn optimize(
    mesh: &mut Mesh,
    constraints: Constraints,
    mut options: OptimizeOptions,
    mut progress: impl FnMut(&BatchReport),
) -> Result<Outcome, OptimizeError> {
    check_input(mesh, &constraints)?;
    let surface = Surface::new(mesh);
    let mut terms = core::mem::take(&mut options.terms);
    let with_triangles = mesh.map.faces().any(|f| mesh.map.degree(f) == 3);
    let start =
        (options.fold_guard && with_triangles).then(|| (mesh.clone(), folds::unsound_quads(mesh)));
    let c = constraints.clone();
    let mut out = run(
        mesh,
        c,
        &options,
        &mut terms,
        &surface,
        false,
        &mut progress,
    );
    if let Some((start, folds)) = start {
        if out.triangles.merged > 0 && folds::unsound_quads(mesh).rises_from(folds) {
            *mesh = start;
            out = run(
                mesh,
                constraints,
                &options,
                &mut terms,
                &surface,
                true,
                progress,
            );
            out.triangles.guarded = true;
        }
    }
    Ok(out)
}

/// One run of [`optimize`] on checked input: the triangle stage (each merge guarded by the
/// fold tests if `guard`), the preprocessing, the batches and the settle. `terms` are the
/// score's terms, handed back at the end.
fn run(
    mesh: &mut Mesh,
    constraints: Constraints,
    options: &OptimizeOptions,
    terms: &mut Vec<(f64, Box<dyn ScoreTerm + Send>)>,
    surface: &Surface,
    guard: bool,
    progress: impl FnMut(&BatchReport),
) -> Outcome {
    let input = SingularityCounts::of(mesh);
    let input_faces = mesh.map.num_faces();
    let with_triangles = input.triangles > 0;
    let before = with_triangles.then(|| mesh.clone());
    let triangles = quad_dominant::pair_triangles(mesh, &constraints, guard.then_some(surface));
    if let (Some(before), true) = (&before, triangles.merged > 0 && !guard) {
        // The crawls' moved and new vertices go onto the surface, as a Q-zip's scar does
        // (a guarded stage relaxed each at its merge: relaxing them again together folds
        // the quads the guard kept unfolded).
        relax_edited(mesh, before, surface, &constraints);
    }
    let quad = MeshKind::of(&mesh.map) == MeshKind::Quad;
    // Nothing can lower the total defect: leave the mesh as it is (no v6 splits either).
    let minimal = quad && at_defect_minimum(mesh);
    let preprocessed = quad && !minimal && preprocess_kept(mesh, options, &constraints, surface);
    let scorer = score::Scorer {
        terms: core::mem::take(terms),
        features: Vec::new(),
        target_area: mean_face_area(mesh),
        target_faces: input_faces,
        walls: mesh.map.vertices().any(|v| mesh.map.is_boundary_vertex(v))
            || constraints.feature_vertices().next().is_some(),
        scratch: Default::default(),
    };
    let mut b = batch::Batcher {
        qzip: Qzip::with_options(SketchOptions::default()).allow_cancellation(true),
        scorer,
        constraints,
        locked: Vec::new(),
        bfs: Default::default(),
        search_radius: options.search_radius,
        eps: 1e-9,
        fold_guard: options.fold_guard,
        surface: Some(surface),
        copies: Vec::new(),
        window: Default::default(),
        marks: Default::default(),
        before: Default::default(),
        copy_darts: batch::COPY_DARTS,
        stop: options.stop.clone(),
    };
    mark_features(&mut b, mesh);
    let initial_score = b.scorer.score(mesh).0;
    let (batches, stopped) = if minimal {
        (Vec::new(), false)
    } else {
        let chi = Counts::of(&mesh.map).euler_characteristic;
        let run = run_batches(&mut b, mesh, surface, options, initial_score, progress);
        debug_assert_eq!(Counts::of(&mesh.map).euler_characteristic, chi);
        run
    };
    b.refresh_constraints(mesh);
    settle(mesh, surface, &b.locked);
    *terms = core::mem::take(&mut b.scorer.terms);
    Outcome {
        input,
        triangles,
        initial_score,
        preprocessed,
        minimal,
        batches,
        stopped,
        final_counts: SingularityCounts::of(mesh),
    }
}

/// Runs the preprocessing on a pure quad `mesh` not at the defect minimum, if `options` ask
/// for it, and keeps it (its new vertices relaxed on `surface`) if `constraints` still hold.
fn preprocess_kept(
    mesh: &mut Mesh,
    options: &OptimizeOptions,
    constraints: &Constraints,
    surface: &Surface,
) -> bool {
    if !options.preprocess {
        return false;
    }
    let before = mesh.clone();
    let Ok(p) = preprocess(mesh) else {
        return false;
    };
    if !constraints.holds(mesh) {
        let _ = p.undo(mesh);
        return false;
    }
    // The splits' new vertices go onto the surface, as a Q-zip's scar does.
    relax_edited(mesh, &before, surface, constraints);
    true
}

/// Puts every vertex that is off the input `surface` (by more than a part in 1e9 of the
/// mesh's size) back on it, and relaxes a ring round them tangentially, never into a worse
/// fan ([`crate::geometry::relax_footprint`]); vertices marked in `fixed` stay. What the
/// preprocessing, the chains and the refused smoothings left off the surface ends on it.
fn settle(mesh: &mut Mesh, surface: &Surface, fixed: &[bool]) {
    let (lo, hi) = mesh.map.vertices().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), v| {
            let p = mesh.positions[v.index()];
            (lo.min(p), hi.max(p))
        },
    );
    let tol = 1e-9 * (hi - lo).length();
    let off: Vec<Vert> = mesh
        .map
        .vertices()
        .filter(|&v| {
            let p = mesh.positions[v.index()];
            p.is_finite() && surface.closest(p).distance(p) > tol
        })
        .collect();
    if off.is_empty() {
        return;
    }
    // Each goes on the surface unless that folds one of its quads more: then it stays.
    let mut stay = fixed.to_vec();
    stay.resize(mesh.map.vertex_slots(), false);
    let mut on = Vec::new();
    for v in off {
        if stay[v.index()] {
            continue;
        }
        let (p, before) = (mesh.positions[v.index()], folds::folds_round(mesh, v));
        mesh.positions[v.index()] = surface.closest(p);
        if folds::folds_round(mesh, v).rises_from(before) {
            mesh.positions[v.index()] = p;
            stay[v.index()] = true;
        } else {
            on.push(v);
        }
    }
    let o = crate::geometry::RelaxOptions {
        rings: 1,
        sweeps: 10,
    };
    let before = folds::unsound_quads(mesh);
    let mut saved = Vec::new();
    crate::geometry::relax_footprint_fixed(mesh, surface, &on, o, &stay, &mut saved);
    // The sweeps keep each fan's count of bad faces, not which test flags them.
    if folds::unsound_quads(mesh).rises_from(before) {
        for (v, p) in saved.into_iter().rev() {
            mesh.positions[v.index()] = p;
        }
    }
}

/// Why `mesh` cannot be optimized with `constraints`, if it cannot.
fn check_input(mesh: &Mesh, constraints: &Constraints) -> Result<(), OptimizeError> {
    let map = &mesh.map;
    let quads = map.faces().filter(|&f| map.degree(f) == 4).count();
    let tris = map.faces().filter(|&f| map.degree(f) == 3).count();
    if map.num_faces() > 0 && (quads == 0 || quads + tris != map.num_faces()) {
        return Err(OptimizeError::NotQuad);
    }
    if mesh.positions.len() < mesh.map.vertex_slots() {
        return Err(OptimizeError::MissingPositions);
    }
    if !constraints.holds(mesh) {
        return Err(OptimizeError::ConstraintsBroken);
    }
    Ok(())
}

/// The batches, from the score `total`: each a batch of Q-zips, the endgame's chains and
/// walks when the batch executed nothing, and the smoothing of the scars; until
/// `options.patience` batches in a row execute nothing, `options.max_batches`, or the stop
/// test answers true (then also true in the result).
fn run_batches(
    b: &mut batch::Batcher<'_>,
    mesh: &mut Mesh,
    surface: &Surface,
    options: &OptimizeOptions,
    mut total: f64,
    mut progress: impl FnMut(&BatchReport),
) -> (Vec<BatchReport>, bool) {
    let mut rng = Rng::new(options.seed);
    let mut batches = Vec::new();
    let mut idle = 0;
    // Chains are deterministic: after a stage that kept nothing, another one finds
    // nothing until a batch changes the mesh.
    let mut chains_stale = false;
    let mut stopped = false;
    for i in 1..=options.max_batches {
        if options.stop.now() {
            stopped = true;
            break;
        }
        let mut run = b.run(mesh, &mut rng, &mut total);
        let mut chains = ChainStats::default();
        if run.qzips == 0 && options.chains && !chains_stale {
            let mut c = b.chains(mesh, &mut total);
            // Pairs that only translate (dislocations) may still cancel with a third.
            if c.kept == 0 {
                c.absorb(b.onto(mesh, &mut total));
            }
            chains = ChainStats {
                tried: c.tried,
                cancelled: c.cancelled,
                kept: c.kept,
                qzips: c.qzips,
                face_change: c.face_change,
            };
            run.paths.extend(c.paths);
            run.scar.extend(c.scar);
        }
        let executed = run.qzips + chains.qzips;
        chains_stale = executed == 0;
        let smoothed = options.smooth
            && executed > 0
            && smooth_scars(
                b,
                mesh,
                surface,
                &run.scar,
                options.smooth_iterations,
                &mut total,
            );
        let report = BatchReport {
            batch: i,
            qzips: run.qzips,
            chains,
            candidates: run.stats.candidates,
            stats: run.stats,
            counts: SingularityCounts::of(mesh),
            score: total,
            smoothed,
            paths: run.paths,
        };
        progress(&report);
        batches.push(report);
        idle = if executed == 0 { idle + 1 } else { 0 };
        // A batch the test cut short may have executed nothing: that is not idleness.
        if options.stop.now() {
            stopped = true;
            break;
        }
        if idle >= options.patience.max(1) {
            break;
        }
    }
    (batches, stopped)
}

fn mark_features(b: &mut batch::Batcher<'_>, mesh: &Mesh) {
    let f = &mut b.scorer.features;
    f.clear();
    f.resize(mesh.map.vertex_slots(), false);
    for v in b.constraints.feature_vertices() {
        if let Some(x) = f.get_mut(v.index()) {
            *x = true;
        }
    }
}

/// Smooths the scars' vertices and one more ring; keeps the result only if the score does
/// not rise (so the batch-to-batch score stays monotone) and, with the fold guard, no more
/// quads round the region are folded. Returns whether it was kept.
fn smooth_scars(
    b: &mut batch::Batcher<'_>,
    mesh: &mut Mesh,
    surface: &Surface,
    scar: &[Vert],
    iterations: usize,
    total: &mut f64,
) -> bool {
    let map = &mesh.map;
    let mut region: Vec<Vert> = scar
        .iter()
        .copied()
        .filter(|&v| map.is_live_vertex(v))
        .collect();
    let ring: Vec<Vert> = region
        .iter()
        .flat_map(|&v| map.vertex_darts(v).map(|d| map.dest(d)))
        .collect();
    region.extend(ring);
    region.sort_unstable();
    region.dedup();
    let saved: Vec<DVec3> = region.iter().map(|v| mesh.positions[v.index()]).collect();
    b.refresh_constraints(mesh);
    mark_features(b, mesh);
    let folds = b
        .fold_guard
        .then(|| folds::folded_near(mesh, &region, &mut b.marks));
    smooth(mesh, surface, &region, &b.locked, iterations);
    let after = b.scorer.score(mesh).0;
    let folded =
        folds.is_some_and(|n| folds::folded_near(mesh, &region, &mut b.marks).rises_from(n));
    if after <= *total && b.constraints.holds(mesh) && !folded {
        *total = after;
        true
    } else {
        for (v, p) in region.iter().zip(saved) {
            mesh.positions[v.index()] = p;
        }
        false
    }
}
