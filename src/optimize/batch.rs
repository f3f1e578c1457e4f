//! One batch (Q-zip paper, Sec. 4.1, "Batch of best Q-zips"): sample half of the
//! singularities, find each one's best of 24 candidate surgeries, execute the best half
//! serially, skipping any that would touch a region already operated on in this batch.

use alloc::vec;
use alloc::vec::Vec;

use glam::DVec3;

use super::constraints::Constraints;
use super::defect::{singularities, Singularity};
use super::folds::{folded_near, FoldCount};
use super::marks::Marks;
use super::score::{Bfs, Scorer};
use super::{BatchStats, StopWhen};
use crate::geometry::Surface;
use crate::qzip::{Path, Qzip, Tag, ZipReport};
use crate::rng::Rng;
use crate::{Mesh, Vert};

/// How far (edges) from a candidate's path its score change is read. The change is exact
/// for the terms that sum over vertices and faces (count, isotropy, sizing, faces; a unit
/// test checks it) and an estimate for the electric and separatrix terms; the executed Q-zips are
/// re-scored on the whole mesh. 4 was measured as good as 6 at about half the time
/// (docs/results.md).
const WINDOW: u32 = 4;

/// At most this many singularities left, a batch samples every one of them.
const FULL_SAMPLE: usize = 64;

/// At most this many parts of a batch's candidate search ([`Batcher::search`]), each on its
/// own copy of the mesh: enough to keep a few cores busy, few enough that the copies cost
/// little next to the search.
const PARTS: usize = 16;

/// At least this many singularities per part, so that a small sample is not cut for nothing.
const MIN_PART: usize = 8;

/// Laplacian steps on a candidate's scar before it is scored, without a surface.
pub(super) const RELAX_STEPS: usize = 2;

/// Whether the fold guard also drops, when scoring, the candidates that fold a quad after
/// the cheap relaxation of scoring (Laplacian, off the surface). Off: the guard judges at
/// execution only, after the scar is relaxed on the surface, which mends most of what the
/// cheap relaxation folds. Measured (docs/quality.md, "After the optimizer"): on, Blub keeps
/// 18 of 38 singularities and Spot 14 of 100; off, 12 and 12, no folded quad either way.
const SCORE_GUARD: bool = false;

/// The relaxation of an executed Q-zip's scar on the input surface.
pub(super) const RELAX: crate::geometry::RelaxOptions = crate::geometry::RelaxOptions {
    rings: 2,
    sweeps: 10,
};

/// How far (edges) round a Q-zip's path the fold guard counts folded quads: the scar's
/// corners are at most one edge from the path, so every quad a Q-zip changes has a corner
/// within this ball or among the vertices it made.
const FOLD_REACH: u32 = 2;

/// How far the fold guard counts at execution, where the scar's relaxation moves vertices
/// up to [`RELAX`]'s rings beyond the scar: every quad they are corners of has a corner
/// within this ball of the path (scar 1, rings 2, the quad 1).
const EXEC_REACH: u32 = 4;

/// At most this many dart slots, a candidate's four movements are each made on a copy of
/// the mesh, kept until it is scored: copying a mesh this small costs less than the second
/// Q-zip and the two undos that editing the mesh itself takes per movement.
pub(super) const COPY_DARTS: usize = 4096;

/// The four initial operations, in compass order.
pub(super) const TAGS: [Tag; 4] = [Tag::LS, Tag::RC, Tag::LC, Tag::RS];

/// A candidate surgery: from a sampled singularity to a target, with an initial operation,
/// and the score change it made when tried.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Candidate {
    pub(crate) from: Vert,
    pub(crate) to: Vert,
    pub(crate) tag: Tag,
    pub(crate) delta: f64,
}

/// What one executed batch did.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct BatchRun {
    pub(crate) qzips: usize,
    pub(crate) stats: BatchStats,
    pub(crate) paths: Vec<Vec<DVec3>>,
    /// Vertices near what the batch's Q-zips changed (for smoothing).
    pub(crate) scar: Vec<Vert>,
}

/// The state a batch works with.
pub(crate) struct Batcher<'q> {
    pub(crate) qzip: Qzip<'q>,
    pub(crate) scorer: Scorer,
    pub(crate) constraints: Constraints,
    pub(crate) locked: Vec<bool>,
    pub(crate) bfs: Bfs,
    pub(crate) search_radius: u32,
    pub(crate) eps: f64,
    pub(crate) fold_guard: bool,
    /// The input surface: with it, a Q-zip's scar is relaxed on it
    /// ([`crate::geometry::relax_footprint`]) rather than by free Laplacian steps.
    pub(crate) surface: Option<&'q Surface>,
    /// The copies [`Batcher::try_path`] makes a small mesh's movements on.
    pub(crate) copies: Vec<Mesh>,
    /// The window [`Batcher::try_path`] builds.
    pub(crate) window: Window,
    /// The fold guard's face marks.
    pub(crate) marks: Marks,
    /// At most this many dart slots, movements are made on copies ([`COPY_DARTS`]; a test
    /// sets 0 to compare with the edits).
    pub(crate) copy_darts: usize,
    /// The live vertices of the last window scored on the mesh a search leaves unchanged,
    /// its score, and a list to build the next key in ([`Batcher::score_before`]); the
    /// score is forgotten when a search begins.
    pub(crate) before: (Vec<Vert>, Option<f64>, Vec<Vert>),
    /// When it answers true, the batch stops searching and executing ([`super::StopWhen`]).
    pub(crate) stop: StopWhen,
}

impl<'q> Batcher<'q> {
    pub(super) fn is_locked(&self, v: Vert) -> bool {
        self.locked.get(v.index()).copied().unwrap_or(false)
    }

    /// The locked-vertex marks and the sketch's forbidden edges for the current mesh.
    pub(crate) fn refresh_constraints(&mut self, mesh: &Mesh) {
        self.locked.clear();
        self.locked.resize(mesh.map.vertex_slots(), false);
        for v in self.constraints.locked_vertices() {
            if let Some(l) = self.locked.get_mut(v.index()) {
                *l = true;
            }
        }
        let o = self.qzip.options_mut();
        o.forbidden_edges = self.constraints.forbidden_edges(mesh);
        o.forbidden_faces.clear();
        // On a quad-dominant mesh the paths wind around the triangles (Sec. 3.2).
        if mesh.map.faces().any(|f| mesh.map.degree(f) == 3) {
            let t = crate::qzip::avoid_triangles(&mesh.map, crate::qzip::SketchOptions::default());
            o.forbidden_edges.extend(t.forbidden_edges);
            o.forbidden_faces = t.forbidden_faces;
        }
    }

    /// Relaxes the scar's vertices, so that the new quads are scored with the shape
    /// smoothing will give them rather than the degenerate one of a fresh split: on the
    /// input surface, the scar projected and its footprint smoothed tangentially, never into
    /// a worse fan ([`crate::geometry::relax_footprint`]); without a surface, two
    /// Laplacian steps. Returns the previous positions.
    fn relax(&self, mesh: &mut Mesh, r: &ZipReport, on_surface: bool) -> Vec<(Vert, DVec3)> {
        let map = &mesh.map;
        let mut vs: Vec<Vert> = r
            .scar_faces()
            .iter()
            .flat_map(|&f| map.face_darts(f).map(|d| map.origin(d)))
            .chain(
                r.scar_edges()
                    .iter()
                    .flat_map(|e| [map.origin(e.dart(0)), map.dest(e.dart(0))]),
            )
            .collect();
        vs.sort_unstable();
        vs.dedup();
        match self.surface.filter(|_| on_surface) {
            Some(surface) => {
                let mut saved = Vec::new();
                crate::geometry::relax_footprint_fixed(
                    mesh,
                    surface,
                    &vs,
                    RELAX,
                    &self.locked,
                    &mut saved,
                );
                saved
            }
            None => super::smooth::laplacian(mesh, None, &vs, &self.locked, RELAX_STEPS),
        }
    }

    /// Adds the vertices within [`WINDOW`] edges of `seeds` to the window being built:
    /// where a candidate is scored.
    fn add_window(&mut self, mesh: &Mesh, seeds: impl IntoIterator<Item = Vert>) {
        let window = &mut self.window;
        self.bfs.run_from(mesh, seeds, WINDOW, |v, _| {
            window.insert(v);
            true
        });
    }

    /// With the fold guard on, the vertices within [`FOLD_REACH`] edges of `verts`: where a
    /// Q-zip along them can fold a quad.
    fn fold_ball(&mut self, mesh: &Mesh, verts: &[Vert]) -> Option<Vec<Vert>> {
        if !self.fold_guard {
            return None;
        }
        let mut ball = Vec::new();
        self.bfs
            .run_from(mesh, verts.iter().copied(), FOLD_REACH, |v, _| {
                ball.push(v);
                true
            });
        Some(ball)
    }

    /// With the fold guard on, the folded quads round `path` before a Q-zip along it: the
    /// ball they are counted on, and the count.
    fn folds_before(&mut self, mesh: &Mesh, path: &Path) -> Option<(Vec<Vert>, FoldCount)> {
        let ball = self.fold_ball(mesh, path.vertices())?;
        let n = folded_near(mesh, &ball, &mut self.marks);
        Some((ball, n))
    }

    /// The three closest v3-like and the three closest v5-like singularities of `s`.
    fn targets(&mut self, mesh: &Mesh, s: Vert, defects: &[i64]) -> Vec<Vert> {
        let (mut minus, mut plus) = (Vec::new(), Vec::new());
        let locked = &self.locked;
        self.bfs.run(mesh, s, self.search_radius, |v, d| {
            if d > 0 && !locked.get(v.index()).copied().unwrap_or(false) {
                match defects.get(v.index()).copied().unwrap_or(0) {
                    x if x < 0 && minus.len() < 3 => minus.push(v),
                    x if x > 0 && plus.len() < 3 => plus.push(v),
                    _ => {}
                }
            }
            minus.len() < 3 || plus.len() < 3
        });
        minus.extend(plus);
        minus
    }

    /// Applies the movement, keeping it only if the constraints hold.
    pub(super) fn apply(
        &self,
        mesh: &mut Mesh,
        path: &Path,
        tag: Tag,
    ) -> Option<crate::mesh::Edited<ZipReport>> {
        let z = self.qzip.zip_along(mesh, path, tag).ok()?;
        if self.constraints.holds(mesh) {
            Some(z)
        } else {
            // An exact undo of an edit just made cannot be refused.
            let _ = z.undo(mesh);
            None
        }
    }

    /// Adds the window round what the movement `r` along `path` changed, on the mesh it
    /// left (the relaxation moves no edge, so it is left out).
    fn add_window_of(&mut self, mesh: &Mesh, path: &Path, r: &ZipReport) {
        let map = &mesh.map;
        let seeds = path
            .vertices()
            .iter()
            .copied()
            .chain([r.moved_from(), r.moved_to()])
            .chain(r.scar_faces().iter().map(|&f| map.origin(map.face_dart(f))))
            .filter(|&v| map.is_live_vertex(v));
        self.add_window(mesh, seeds);
    }

    /// The score over `window` after the movement `tag` and its scar's relaxation (then
    /// undone), and the movement's face change; `None` if the fold guard (given the count
    /// before, `folds`) would refuse it at execution, so that ranking sees what executes.
    fn score_after(
        &mut self,
        mesh: &mut Mesh,
        path: &Path,
        tag: Tag,
        window: &[Vert],
        folds: Option<&(Vec<Vert>, FoldCount)>,
    ) -> Option<(f64, isize)> {
        let z = self.apply(mesh, path, tag)?;
        let saved = self.relax(mesh, z.record(), false);
        let folded = folds.is_some_and(|f| {
            folds_rise(
                mesh,
                f,
                &touched_region(mesh, path, z.record()),
                &mut self.marks,
            )
        });
        let after = (!folded).then(|| self.scorer.local(mesh, window));
        let faces = z.record().vertex_delta();
        for (v, p) in saved.into_iter().rev() {
            mesh.positions[v.index()] = p;
        }
        let _ = z.undo(mesh);
        Some((after?, faces))
    }

    /// Tries the four movements along `path` ([`TAGS`] order): for each, the score change
    /// and the face change, or `None` if it is not realizable or breaks a constraint.
    ///
    /// All of them are read on one window, the union of the path's window before and of
    /// every movement's window after: a split lengthens distances and a collapse shortens
    /// them, so separate windows before and after covered less after a split and more after
    /// a collapse, and biased the ranking towards splits (docs/optimize.md, "Scoring a
    /// candidate"). One window for the four also scores the mesh before only once.
    fn try_path(&mut self, mesh: &mut Mesh, path: &Path) -> [Option<(f64, isize)>; 4] {
        if mesh.map.dart_slots() <= self.copy_darts {
            self.try_path_on_copies(mesh, path)
        } else {
            self.try_path_by_edits(mesh, path)
        }
    }

    /// [`Batcher::try_path`] on `mesh` itself: each movement made, undone, made again to be
    /// scored and undone again.
    fn try_path_by_edits(&mut self, mesh: &mut Mesh, path: &Path) -> [Option<(f64, isize)>; 4] {
        self.window.clear();
        self.add_window(mesh, path.vertices().iter().copied());
        let mut ok = [false; 4];
        for (i, tag) in TAGS.into_iter().enumerate() {
            if let Some(z) = self.apply(mesh, path, tag) {
                self.add_window_of(mesh, path, z.record());
                // An exact undo of an edit just made cannot be refused.
                let _ = z.undo(mesh);
                ok[i] = true;
            }
        }
        let mut out = [None; 4];
        if !ok.iter().any(|&x| x) {
            return out;
        }
        let folds = self.folds_before(mesh, path).filter(|_| SCORE_GUARD);
        let window = self.window.take_sorted();
        for (i, tag) in TAGS.into_iter().enumerate() {
            if ok[i] {
                out[i] = self.score_after(mesh, path, tag, &window, folds.as_ref());
            }
        }
        let before = self.score_before(mesh, &window);
        self.window.give_back(window);
        out.map(|x| x.map(|(after, faces)| (after - before, faces)))
    }

    /// [`Batcher::try_path`] with each movement made once, on its own copy of `mesh`, and
    /// scored there: the same windows and scores, `mesh` untouched.
    fn try_path_on_copies(&mut self, mesh: &Mesh, path: &Path) -> [Option<(f64, isize)>; 4] {
        let mut copies = core::mem::take(&mut self.copies);
        copies.resize_with(TAGS.len(), Mesh::default);
        self.window.clear();
        self.add_window(mesh, path.vertices().iter().copied());
        let mut made = [None, None, None, None];
        for ((tag, copy), made) in TAGS.into_iter().zip(&mut copies).zip(&mut made) {
            copy.map.clone_from(&mesh.map);
            copy.positions.clone_from(&mesh.positions);
            if let Some(z) = self.apply(copy, path, tag) {
                self.add_window_of(copy, path, z.record());
                *made = Some(z);
            }
        }
        let mut out = [None; 4];
        if made.iter().any(Option::is_some) {
            let folds = self.folds_before(mesh, path).filter(|_| SCORE_GUARD);
            let window = self.window.take_sorted();
            for ((copy, made), out) in copies.iter_mut().zip(&made).zip(&mut out) {
                if let Some(z) = made {
                    self.relax(copy, z.record(), false);
                    // What the fold guard would refuse at execution is not ranked.
                    let folded = folds.as_ref().is_some_and(|f| {
                        let region = touched_region(copy, path, z.record());
                        folds_rise(copy, f, &region, &mut self.marks)
                    });
                    if !folded {
                        let after = self.scorer.local(copy, &window);
                        *out = Some((after, z.record().vertex_delta()));
                    }
                }
            }
            let before = self.score_before(mesh, &window);
            out = out.map(|x| x.map(|(after, faces)| (after - before, faces)));
            self.window.give_back(window);
        }
        self.copies = copies;
        out
    }

    /// The score of `window` on the mesh the search leaves as it is: the one kept if the
    /// window's live vertices are the last scored window's. [`Scorer::local`] depends on the
    /// mesh and the window only, and a vertex that is not live adds nothing to it (no defect,
    /// no face); the windows of one singularity's paths differ mostly by the vertices their
    /// movements made, and on a small mesh they cover all the rest.
    fn score_before(&mut self, mesh: &Mesh, window: &[Vert]) -> f64 {
        let (last, score, key) = &mut self.before;
        key.clear();
        key.extend(window.iter().filter(|&&v| mesh.map.is_live_vertex(v)));
        match *score {
            Some(x) if last == key => x,
            _ => {
                let x = self.scorer.local(mesh, window);
                core::mem::swap(last, key);
                *score = Some(x);
                x
            }
        }
    }

    /// The best of the 24 candidates of `s` (score change, most negative first), if any
    /// lowers the score.
    fn best_candidate(
        &mut self,
        mesh: &mut Mesh,
        s: Vert,
        defects: &[i64],
        stats: &mut BatchStats,
    ) -> Option<Candidate> {
        let mut best: Option<Candidate> = None;
        for t in self.targets(mesh, s, defects) {
            let Ok(path) = self.qzip.sketch(&mesh.map, s, t) else {
                continue;
            };
            for (tag, tried) in TAGS.into_iter().zip(self.try_path(mesh, &path)) {
                let Some((delta, faces)) = tried else {
                    continue;
                };
                stats.tried(faces, delta < -self.eps);
                if delta < -self.eps && best.is_none_or(|b| delta < b.delta) {
                    best = Some(Candidate {
                        from: s,
                        to: t,
                        tag,
                        delta,
                    });
                }
            }
        }
        best
    }

    /// The best candidate of each singularity of `sample`, in sampling order. The sample is
    /// cut into at most [`PARTS`] parts, each searched on its own copy of the mesh by its own
    /// copy of the batcher: on every core with the `parallel` feature, and the same parts one
    /// after the other without it, so the result never depends on the threads. A user score
    /// term that cannot be copied ([`super::ScoreTerm::fork`]) makes it one part.
    fn search(
        &mut self,
        mesh: &mut Mesh,
        sample: &[Vert],
        defects: &[i64],
        stats: &mut BatchStats,
    ) -> Vec<Candidate> {
        // The kept window score is of another mesh.
        self.before.1 = None;
        let size = sample.len().div_ceil(PARTS).max(MIN_PART);
        // One part, or a term that cannot be copied: no copies, the mesh itself.
        let workers: Option<Vec<Batcher<'q>>> = (sample.len() > size)
            .then(|| sample.chunks(size).map(|_| self.fork()).collect())
            .flatten();
        let Some(workers) = workers else {
            let stop = self.stop.clone();
            return sample
                .iter()
                .take_while(|_| !stop.now())
                .filter_map(|&s| self.best_candidate(mesh, s, defects, stats))
                .collect();
        };
        let jobs: Vec<(Batcher<'q>, &[Vert])> =
            workers.into_iter().zip(sample.chunks(size)).collect();
        let shared: &Mesh = mesh;
        let part = |(mut w, part): (Batcher<'q>, &[Vert])| {
            let mut copy = shared.clone();
            let mut st = BatchStats::default();
            let stop = w.stop.clone();
            let found: Vec<Candidate> = part
                .iter()
                .take_while(|_| !stop.now())
                .filter_map(|&s| w.best_candidate(&mut copy, s, defects, &mut st))
                .collect();
            (found, st)
        };
        #[cfg(feature = "parallel")]
        let parts: Vec<(Vec<Candidate>, BatchStats)> = {
            use rayon::prelude::*;
            jobs.into_par_iter().map(part).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let parts: Vec<(Vec<Candidate>, BatchStats)> = jobs.into_iter().map(part).collect();
        let mut out = Vec::new();
        for (found, st) in parts {
            stats.add_tried(&st);
            out.extend(found);
        }
        out
    }

    /// A copy of the batcher for another thread, or `None` if a score term cannot be copied.
    fn fork(&self) -> Option<Batcher<'q>> {
        Some(Batcher {
            qzip: Qzip::with_options(self.qzip.options().clone())
                .allow_cancellation(self.qzip.allows_cancellation()),
            scorer: self.scorer.fork()?,
            constraints: self.constraints.clone(),
            locked: self.locked.clone(),
            bfs: Bfs::default(),
            search_radius: self.search_radius,
            eps: self.eps,
            fold_guard: self.fold_guard,
            surface: self.surface,
            copies: Vec::new(),
            window: Window::default(),
            marks: Marks::default(),
            before: Default::default(),
            copy_darts: self.copy_darts,
            stop: self.stop.clone(),
        })
    }

    /// One batch: returns what it executed; the score never rises (each executed Q-zip is
    /// re-scored on the current mesh and kept only if it lowers the score).
    pub(crate) fn run(&mut self, mesh: &mut Mesh, rng: &mut Rng, total: &mut f64) -> BatchRun {
        self.refresh_constraints(mesh);
        let mut out = BatchRun::default();
        let sing: Vec<Singularity> = singularities(mesh)
            .into_iter()
            .filter(|s| !self.is_locked(s.vertex))
            .collect();
        let mut defects = vec![0i64; mesh.map.vertex_slots()];
        for s in &sing {
            defects[s.vertex.index()] = s.defect;
        }
        let mut order: Vec<Vert> = sing.iter().map(|s| s.vertex).collect();
        // Half, as the paper; all of them once few are left, where a half-sample often
        // misses the one improving candidate and idle batches end the run early.
        let sample = if order.len() <= FULL_SAMPLE {
            order.len()
        } else {
            order.len().div_ceil(2)
        };
        for i in 0..sample {
            let j = i + rng.below(order.len() - i);
            order.swap(i, j);
        }
        let mut candidates = self.search(mesh, &order[..sample], &defects, &mut out.stats);
        // Most negative first; ties keep sampling order (a stable sort).
        candidates.sort_by(|a, b| a.delta.total_cmp(&b.delta));
        candidates.truncate(candidates.len().div_ceil(2));
        let mut operated = vec![false; mesh.map.vertex_slots()];
        for c in candidates {
            if self.stop.now() {
                break;
            }
            self.execute(mesh, c, total, &mut operated, &mut out);
        }
        out
    }

    /// Executes one chosen candidate on the current mesh if it still applies, touches no
    /// region already operated on, and still lowers the score.
    fn execute(
        &mut self,
        mesh: &mut Mesh,
        c: Candidate,
        total: &mut f64,
        operated: &mut Vec<bool>,
        out: &mut BatchRun,
    ) {
        let map = &mesh.map;
        let marked = |v: Vert, op: &[bool]| op.get(v.index()).copied().unwrap_or(false);
        if !map.is_live_vertex(c.from) || !map.is_live_vertex(c.to) {
            return;
        }
        let Ok(path) = self.qzip.sketch(map, c.from, c.to) else {
            return;
        };
        let near = |v: Vert| core::iter::once(v).chain(map.vertex_darts(v).map(|d| map.dest(d)));
        if path
            .vertices()
            .iter()
            .any(|&v| near(v).any(|u| marked(u, operated)))
        {
            return;
        }
        let points: Vec<DVec3> = path
            .vertices()
            .iter()
            .map(|v| {
                mesh.positions
                    .get(v.index())
                    .copied()
                    .unwrap_or(DVec3::ZERO)
            })
            .collect();
        let folds = self.fold_guard.then(|| {
            let mut ball = Vec::new();
            self.bfs
                .run_from(mesh, path.vertices().iter().copied(), EXEC_REACH, |v, _| {
                    ball.push(v);
                    true
                });
            let n = folded_near(mesh, &ball, &mut self.marks);
            (ball, n)
        });
        let Some(z) = self.apply(mesh, &path, c.tag) else {
            return;
        };
        let saved = self.relax(mesh, z.record(), true);
        let after = self.scorer.score(mesh).0;
        let region = touched_region(mesh, &path, z.record());
        let folded = folds.is_some_and(|f| {
            let mut counted = region.clone();
            counted.extend(saved.iter().map(|&(v, _)| v));
            folds_rise(mesh, &f, &counted, &mut self.marks)
        });
        if after >= *total - self.eps || !self.constraints.holds(mesh) || folded {
            for (v, p) in saved.into_iter().rev() {
                mesh.positions[v.index()] = p;
            }
            let _ = z.undo(mesh);
            return;
        }
        out.stats.executed(z.record().vertex_delta());
        *total = after;
        out.qzips += 1;
        out.paths.push(points);
        operated.resize(mesh.map.vertex_slots(), false);
        for &v in &region {
            operated[v.index()] = true;
        }
        out.scar.extend(region);
        self.refresh_constraints(mesh);
    }
}

/// The union of a candidate's windows as it is built: each vertex once (stamped), sorted
/// when complete.
#[derive(Clone, Debug, Default)]
pub(crate) struct Window {
    marks: Marks,
    verts: Vec<Vert>,
}

impl Window {
    fn clear(&mut self) {
        self.verts.clear();
        // The slots grow as vertices come (a Q-zip may have made new ones).
        self.marks.begin(0);
    }

    fn insert(&mut self, v: Vert) {
        if self.marks.first_growing(v.index()) {
            self.verts.push(v);
        }
    }

    /// The vertices, sorted; hand the list back with [`Window::give_back`].
    fn take_sorted(&mut self) -> Vec<Vert> {
        let mut v = core::mem::take(&mut self.verts);
        v.sort_unstable();
        v
    }

    fn give_back(&mut self, v: Vec<Vert>) {
        self.verts = v;
    }
}

/// The fold guard's rule: whether a Q-zip just made, whose [`touched_region`] is `region`,
/// left more folded quads than `before` counted (the ball round its path and the count).
/// They are counted on the same vertices, less the dead, plus what the Q-zip made and moved,
/// so every quad whose corners changed is counted both times.
fn folds_rise(
    mesh: &Mesh,
    before: &(Vec<Vert>, FoldCount),
    region: &[Vert],
    marks: &mut Marks,
) -> bool {
    let (ball, n) = before;
    let mut b: Vec<Vert> = ball
        .iter()
        .copied()
        .filter(|&v| mesh.map.is_live_vertex(v))
        .collect();
    b.extend(region);
    folded_near(mesh, &b, marks).rises_from(*n)
}

/// The vertices a Q-zip operated on, in the mesh it left: the live path vertices, the moved
/// singularities, the corners of the scar faces and the ends of the scar edges, and their
/// one-rings.
pub(super) fn touched_region(mesh: &Mesh, path: &Path, r: &ZipReport) -> Vec<Vert> {
    let map = &mesh.map;
    let mut core: Vec<Vert> = path
        .vertices()
        .iter()
        .copied()
        .chain([r.moved_from(), r.moved_to()])
        .filter(|&v| map.is_live_vertex(v))
        .collect();
    for &f in r.scar_faces() {
        core.extend(map.face_darts(f).map(|d| map.origin(d)));
    }
    for &e in r.scar_edges() {
        core.extend([map.origin(e.dart(0)), map.dest(e.dart(0))]);
    }
    // About five ring vertices per core vertex (quads): one allocation, not a growth per ring.
    let mut out = Vec::with_capacity(5 * core.len());
    out.extend_from_slice(&core);
    for v in core {
        out.extend(map.vertex_darts(v).map(|d| map.dest(d)));
    }
    out.sort_unstable();
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::score::{Count, FaceBudget, Isotropy, ScoreTerm, Sizing};
    use crate::qzip::{preprocess, SketchOptions};
    use alloc::boxed::Box;

    /// A batcher with the default terms on `mesh`.
    fn batcher(mesh: &Mesh) -> Batcher<'static> {
        let o = crate::optimize::OptimizeOptions::default();
        batcher_with(mesh, o.terms, true)
    }

    /// A batcher with `terms` on `mesh`, walls as given, the other settings the defaults.
    fn batcher_with(
        mesh: &Mesh,
        terms: Vec<(f64, Box<dyn ScoreTerm + Send>)>,
        walls: bool,
    ) -> Batcher<'static> {
        let mut b = Batcher {
            qzip: Qzip::with_options(SketchOptions::default()).allow_cancellation(true),
            scorer: Scorer {
                terms,
                features: Vec::new(),
                target_area: 0.05,
                target_faces: 300,
                walls,
                scratch: Default::default(),
            },
            constraints: Constraints::default(),
            locked: Vec::new(),
            bfs: Bfs::default(),
            search_radius: 64,
            eps: 1e-9,
            fold_guard: false,
            surface: None,
            copies: Vec::new(),
            window: Window::default(),
            marks: Marks::default(),
            before: Default::default(),
            copy_darts: COPY_DARTS,
            stop: StopWhen::default(),
        };
        b.refresh_constraints(mesh);
        b
    }

    /// A Q-zip's touched region is, sorted and each once, exactly its core (the live path
    /// vertices, the moved singularities, the scar faces' corners and the scar edges' ends)
    /// and the core's one-rings, on the mesh the Q-zip left.
    #[test]
    fn touched_region_is_the_core_and_its_rings() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(80, 1, 1, 7));
        preprocess(&mut mesh).unwrap();
        let mut b = batcher(&mesh);
        let sing = singularities(&mesh);
        let mut checked = 0;
        for (s, t) in sing.iter().zip(sing.iter().skip(1)).take(12) {
            let Ok(path) = b.qzip.sketch(&mesh.map, s.vertex, t.vertex) else {
                continue;
            };
            let Some(z) = b.apply(&mut mesh, &path, Tag::LC) else {
                continue;
            };
            let (map, r) = (&mesh.map, z.record());
            let mut core: Vec<Vert> = path.vertices().to_vec();
            core.extend([r.moved_from(), r.moved_to()]);
            core.retain(|&v| map.is_live_vertex(v));
            for &f in r.scar_faces() {
                core.extend(map.face_darts(f).map(|d| map.origin(d)));
            }
            for &e in r.scar_edges() {
                core.extend([map.origin(e.dart(0)), map.dest(e.dart(0))]);
            }
            let mut want = core.clone();
            for &v in &core {
                want.extend(map.vertex_darts(v).map(|d| map.dest(d)));
            }
            want.sort_unstable();
            want.dedup();
            let region = touched_region(&mesh, &path, r);
            assert_eq!(region, want);
            assert!(region.len() > core.len() / 2 + path.len(), "{region:?}");
            let _ = z.undo(&mut mesh);
            checked += 1;
        }
        assert!(checked >= 4, "{checked}");
    }

    /// The movements made on copies give the scores, to the bit, that editing the mesh
    /// itself gives, and leave the mesh as it was; so do the edits. The scorers keep their
    /// quad values from path to path, so a stale one would show here too.
    #[test]
    fn copies_score_as_edits_do() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(80, 1, 1, 7));
        preprocess(&mut mesh).unwrap();
        let (mut a, mut b) = (batcher(&mesh), batcher(&mesh));
        let sing = singularities(&mesh);
        let mut defects = vec![0i64; mesh.map.vertex_slots()];
        for s in &sing {
            defects[s.vertex.index()] = s.defect;
        }
        let before = mesh.clone();
        let mut scored = 0;
        for s in sing.iter().take(10) {
            for t in a.targets(&mesh, s.vertex, &defects) {
                let Ok(path) = a.qzip.sketch(&mesh.map, s.vertex, t) else {
                    continue;
                };
                let copies = a.try_path_on_copies(&mesh, &path);
                let edits = b.try_path_by_edits(&mut mesh, &path);
                assert_eq!(mesh, before, "the edits were not undone exactly");
                let bits =
                    |x: [Option<(f64, isize)>; 4]| x.map(|c| c.map(|(d, f)| (d.to_bits(), f)));
                assert_eq!(bits(copies), bits(edits));
                scored += copies.iter().flatten().count();
            }
        }
        assert!(scored > 40, "{scored}");
    }

    /// The window score kept for the unchanged mesh is the score a fresh scorer gives, for
    /// a window met again and a new one; and a search on a changed mesh does not read the
    /// one kept by the search before (the candidates match a fresh batcher's, bit for bit).
    #[test]
    fn kept_window_score_is_the_fresh_one() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(80, 1, 1, 7));
        preprocess(&mut mesh).unwrap();
        let mut kept = batcher(&mesh);
        let fresh = |mesh: &Mesh, w: &[Vert]| batcher(mesh).scorer.local(mesh, w);
        let verts: Vec<Vert> = mesh.map.vertices().collect();
        let (w1, w2) = (&verts[..30], &verts[10..50]);
        for w in [w1, w1, w2, w1] {
            let x = kept.score_before(&mesh, w);
            assert_eq!(x.to_bits(), fresh(&mesh, w).to_bits());
        }
        // A small mesh, where every window covers all of it: the last window of one search
        // is the first of the next.
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(12, 0, 0, 3));
        let mut kept = batcher(&mesh);
        let verts: Vec<Vert> = mesh.map.vertices().collect();
        let sing = singularities(&mesh);
        let mut defects = vec![0i64; mesh.map.vertex_slots()];
        for s in &sing {
            defects[s.vertex.index()] = s.defect;
        }
        let sample: Vec<Vert> = sing.iter().take(8).map(|s| s.vertex).collect();
        let bits = |c: Vec<Candidate>| -> Vec<_> {
            c.iter()
                .map(|c| (c.from, c.to, c.tag, c.delta.to_bits()))
                .collect()
        };
        let mut st = BatchStats::default();
        let first = bits(kept.search(&mut mesh, &sample, &defects, &mut st));
        // Moved corners, the same windows: a stale "before" would be read as valid.
        for (i, v) in verts.iter().enumerate().step_by(2) {
            mesh.positions[v.index()] += DVec3::splat(0.003 * (i % 7) as f64);
        }
        let again = bits(kept.search(&mut mesh, &sample, &defects, &mut st));
        let plain = bits(batcher(&mesh).search(&mut mesh, &sample, &defects, &mut st));
        assert!(!again.is_empty());
        assert_eq!(again, plain);
        assert_ne!(again, first);
    }

    /// The chain stage with its probes on copies (the chosen copy becomes the mesh) tries,
    /// cancels and keeps the same chains as with its probes made and undone on the mesh,
    /// and leaves the same mesh and score, to the bit.
    #[test]
    fn chains_on_copies_match_edits() {
        let (mut tried, mut kept) = (0, 0);
        for seed in 0..4 {
            let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(40, 0, 0, seed));
            preprocess(&mut mesh).unwrap();
            let mut edited = mesh.clone();
            let (mut a, mut b) = (batcher(&mesh), batcher(&mesh));
            b.copy_darts = 0;
            let mut ta = a.scorer.score(&mesh).0;
            let mut tb = ta;
            let ra = a.chains(&mut mesh, &mut ta);
            let rb = b.chains(&mut edited, &mut tb);
            assert_eq!(ra, rb);
            assert!(mesh == edited, "seed {seed}");
            assert_eq!(ta.to_bits(), tb.to_bits());
            (tried, kept) = (tried + ra.tried, kept + ra.kept);
        }
        assert!(tried > 4 && kept > 0, "{tried} {kept}");
    }

    /// For the terms that are sums over vertices and faces, the window estimate of a
    /// candidate equals the whole-mesh change: the windows before and after cover the same
    /// vertex handles. Two separate windows failed this (the bias towards splits).
    #[test]
    fn window_estimate_is_exact_for_local_terms() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(120, 1, 0, 5));
        preprocess(&mut mesh).unwrap();
        let terms: Vec<(f64, Box<dyn ScoreTerm + Send>)> = alloc::vec![
            (1.0, Box::new(Count)),
            (0.3, Box::new(Isotropy)),
            (0.7, Box::new(Sizing)),
            (0.01, Box::new(FaceBudget::default())),
        ];
        let mut b = batcher_with(&mesh, terms, false);
        let sing = singularities(&mesh);
        let mut defects = vec![0i64; mesh.map.vertex_slots()];
        for s in &sing {
            defects[s.vertex.index()] = s.defect;
        }
        let (mut checked, mut adding, mut removing) = (0, 0, 0);
        for s in sing.iter().take(12) {
            for t in b.targets(&mesh, s.vertex, &defects) {
                let Ok(path) = b.qzip.sketch(&mesh.map, s.vertex, t) else {
                    continue;
                };
                let before = mesh.clone();
                let tried = b.try_path(&mut mesh, &path);
                assert_eq!(mesh, before, "a candidate was not undone exactly");
                for (tag, tried) in TAGS.into_iter().zip(tried) {
                    let Some((delta, faces)) = tried else {
                        continue;
                    };
                    let z = b.apply(&mut mesh, &path, tag).unwrap();
                    let saved = b.relax(&mut mesh, z.record(), false);
                    let exact_after = b.scorer.score(&mesh).0;
                    for (v, p) in saved.into_iter().rev() {
                        mesh.positions[v.index()] = p;
                    }
                    z.undo(&mut mesh).unwrap();
                    let exact = exact_after - b.scorer.score(&mesh).0;
                    assert!(
                        (delta - exact).abs() < 1e-6 * (1.0 + exact.abs()),
                        "{delta} vs {exact}"
                    );
                    checked += 1;
                    adding += usize::from(faces > 0);
                    removing += usize::from(faces < 0);
                }
            }
        }
        assert!(
            checked > 50 && adding > 5 && removing > 5,
            "{checked} {adding} {removing}"
        );
    }
}
