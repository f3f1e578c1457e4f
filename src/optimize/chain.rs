//! The endgame (our addition to Sec. 4.1): chains of Q-zips that walk one v3/v5 pair
//! together until it cancels, kept only if the whole score falls.
//!
//! When a batch executes nothing, the pairs left are typically 5 to 20 edges apart, and a
//! single Q-zip between them moves each by one edge and keeps the count: the batch's
//! one-step look-ahead sees no gain. A chain looks as far as the pair needs:
//!
//! ```text
//!   3 . . . . 5      3 . . . 5        3 . 5        3 5        (gone)
//!   step 0           step 1 ...       step k       cancels    the count falls by 2
//! ```
//!
//! Each step sketches the path between the pair's current vertices, tries the four
//! movements, and takes the one that cancels the pair, else the one that leaves the pair
//! closest (graph distance, then distance in space, then the smaller face change). A chain
//! gives up after [`STALLS`] steps that did not shorten the distance, or `3 d + 8` steps in
//! all, and is then tried the other way round (from `b` to `a`: a Q-zip from one end is not
//! one from the other); a failed or unprofitable chain is undone exactly, step by step in
//! reverse.

use alloc::vec::Vec;

use glam::DVec3;

use super::batch::{touched_region, Batcher, RELAX_STEPS, TAGS};
use super::defect::{defect, singularities};
use crate::mesh::Edited;
use crate::qzip::{Path, Tag, ZipReport};
use crate::{Mesh, Vert};

/// Partners tried per singularity: its closest ones of the opposite kind.
const PARTNERS: usize = 2;

/// Steps that did not shorten the pair's distance allowed in one chain.
const STALLS: usize = 8;

/// What one chain stage did.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct ChainRun {
    /// Chains started.
    pub(crate) tried: usize,
    /// Chains that cancelled their pair (kept or not).
    pub(crate) cancelled: usize,
    /// Chains kept (each cancelled its pair and lowered the score).
    pub(crate) kept: usize,
    /// Q-zips of the kept chains.
    pub(crate) qzips: usize,
    /// The face count change of the kept chains.
    pub(crate) face_change: isize,
    /// The kept steps' paths, as positions before each step.
    pub(crate) paths: Vec<Vec<DVec3>>,
    /// Vertices near what the kept chains changed (for smoothing).
    pub(crate) scar: Vec<Vert>,
}

impl ChainRun {
    /// Adds what another stage did (the walks onto a target after the pair chains).
    pub(crate) fn absorb(&mut self, other: ChainRun) {
        self.tried += other.tried;
        self.cancelled += other.cancelled;
        self.kept += other.kept;
        self.qzips += other.qzips;
        self.face_change += other.face_change;
        self.paths.extend(other.paths);
        self.scar.extend(other.scar);
    }
}

/// A pair to walk together: its graph distance first (pairs sort closest first), its ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Pair {
    dist: u32,
    a: Vert,
    b: Vert,
}

/// Where a probed movement left the pair.
#[derive(Clone, Copy, Debug)]
struct Probe {
    tag: Tag,
    cancels: bool,
    a: Vert,
    b: Vert,
    dist: u32,
    space: f64,
    faces: isize,
}

impl Probe {
    /// Smaller is better: cancelling first, then graph distance, space, face change.
    fn key(&self) -> (bool, u32, f64, usize) {
        (
            !self.cancels,
            self.dist,
            self.space,
            self.faces.unsigned_abs(),
        )
    }

    fn better_than(&self, other: &Probe) -> bool {
        let (a, b) = (self.key(), other.key());
        (a.0, a.1)
            .cmp(&(b.0, b.1))
            .then(a.2.total_cmp(&b.2))
            .then(a.3.cmp(&b.3))
            == core::cmp::Ordering::Less
    }
}

/// The positions of `path`'s vertices.
fn path_points(mesh: &Mesh, path: &Path) -> Vec<DVec3> {
    path.vertices()
        .iter()
        .map(|v| mesh.positions[v.index()])
        .collect()
}

/// One applied step of a chain, with what it needs to be undone and reported.
pub(super) struct Step {
    edit: Edited<ZipReport>,
    points: Vec<DVec3>,
    /// What the step touched, read right after it (later steps may reuse handles).
    region: Vec<Vert>,
}

impl Batcher<'_> {
    /// The chain stage: tries the pairs closest first; returns what it kept. The score
    /// never rises.
    pub(crate) fn chains(&mut self, mesh: &mut Mesh, total: &mut f64) -> ChainRun {
        self.refresh_constraints(mesh);
        let mut out = ChainRun::default();
        for p in self.pairs(mesh) {
            if self.stop.now() {
                break;
            }
            let (da, db) = (defect(mesh, p.a), defect(mesh, p.b));
            // An earlier chain may have cancelled or moved either end.
            if da * db != -1 || self.is_locked(p.a) || self.is_locked(p.b) {
                continue;
            }
            let Some(dist) = self.distance(mesh, p.a, p.b, self.search_radius) else {
                continue;
            };
            out.tried += 1;
            // A chain walks far: the guard counts the folds of the whole mesh (a few chains
            // per stage).
            let folds = self.fold_guard.then(|| super::folds::unsound_quads(mesh));
            // A Q-zip from a to b is not one from b to a: if one way stalls, try the other.
            let walked = self
                .walk(mesh, p.a, p.b, dist)
                .or_else(|| self.walk(mesh, p.b, p.a, dist));
            if let Some(steps) = walked {
                out.cancelled += 1;
                self.keep_or_undo(mesh, steps, total, folds, &mut out);
            }
        }
        out
    }

    /// Each unit-defect singularity with its [`PARTNERS`] closest singularities of the
    /// opposite unit defect, closest pairs first, each pair once.
    fn pairs(&mut self, mesh: &Mesh) -> Vec<Pair> {
        let sing: Vec<(Vert, i64)> = singularities(mesh)
            .into_iter()
            .filter(|s| s.defect.abs() == 1 && !self.is_locked(s.vertex))
            .map(|s| (s.vertex, s.defect))
            .collect();
        let mut kind = alloc::vec![0i64; mesh.map.vertex_slots()];
        for &(v, d) in &sing {
            kind[v.index()] = d;
        }
        let mut pairs = Vec::new();
        for &(s, d) in &sing {
            let mut found = 0;
            self.bfs.run(mesh, s, self.search_radius, |v, dist| {
                if kind.get(v.index()).copied() == Some(-d) {
                    pairs.push(Pair {
                        dist,
                        a: s.min(v),
                        b: s.max(v),
                    });
                    found += 1;
                }
                found < PARTNERS
            });
        }
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }

    /// The graph distance from `a` to `b`, if at most `radius`.
    pub(super) fn distance(&mut self, mesh: &Mesh, a: Vert, b: Vert, radius: u32) -> Option<u32> {
        let mut found = None;
        self.bfs.run(mesh, a, radius, |v, d| {
            if v == b {
                found = Some(d);
            }
            found.is_none()
        });
        found
    }

    /// Walks the pair `a`, `b` (at distance `dist`) together; returns the applied steps if
    /// the last one cancelled the pair, else undoes them all and returns `None`.
    fn walk(&mut self, mesh: &mut Mesh, a: Vert, b: Vert, dist: u32) -> Option<Vec<Step>> {
        let (mut a, mut b, mut dist) = (a, b, dist);
        let cap = 3 * dist as usize + 8;
        let (mut steps, mut stalls) = (Vec::new(), 0);
        while steps.len() < cap && stalls <= STALLS {
            let Ok(path) = self.qzip.sketch(&mesh.map, a, b) else {
                break;
            };
            let Some((best, step)) = self.probe_and_step(mesh, &path, a, b, dist) else {
                break;
            };
            steps.push(step);
            if best.cancels {
                return Some(steps);
            }
            stalls += usize::from(best.dist >= dist);
            (a, b, dist) = (best.a, best.b, best.dist);
        }
        self.undo_steps(mesh, &steps);
        None
    }

    /// Applies the movement `tag` along `path` as a chain step (`None` if refused).
    pub(super) fn step(&mut self, mesh: &mut Mesh, path: &Path, tag: Tag) -> Option<Step> {
        let points = path_points(mesh, path);
        let edit = self.apply(mesh, path, tag)?;
        Some(self.made_step(mesh, path, edit, points))
    }

    /// The step of a movement just made on `mesh` (`points`: its path's positions before).
    fn made_step(
        &mut self,
        mesh: &Mesh,
        path: &Path,
        edit: Edited<ZipReport>,
        points: Vec<DVec3>,
    ) -> Step {
        let region = touched_region(mesh, path, edit.record());
        self.refresh_constraints(mesh);
        Step {
            edit,
            points,
            region,
        }
    }

    /// The best of the four movements along `path`, or `None` if none cancels the pair or
    /// keeps both ends singular with their defects; and that movement made as a step. On a
    /// small mesh each movement is made once, on a copy, and the chosen copy becomes the
    /// mesh; else each is made on the mesh and undone, and the chosen one made again.
    fn probe_and_step(
        &mut self,
        mesh: &mut Mesh,
        path: &Path,
        a: Vert,
        b: Vert,
        dist: u32,
    ) -> Option<(Probe, Step)> {
        let (da, db) = (defect(mesh, a), defect(mesh, b));
        let on_copies = mesh.map.dart_slots() <= self.copy_darts;
        let mut copies = core::mem::take(&mut self.copies);
        copies.resize_with(TAGS.len(), Mesh::default);
        let mut made: [Option<Edited<ZipReport>>; 4] = [None, None, None, None];
        let mut best: Option<(Probe, usize)> = None;
        for (i, tag) in TAGS.into_iter().enumerate() {
            let m = if on_copies {
                copies[i].map.clone_from(&mesh.map);
                copies[i].positions.clone_from(&mesh.positions);
                &mut copies[i]
            } else {
                &mut *mesh
            };
            let Some(z) = self.apply(m, path, tag) else {
                continue;
            };
            let p = self.probe_one(m, z.record(), tag, (da, db), dist);
            if on_copies {
                made[i] = Some(z);
            } else {
                // An exact undo of an edit just made cannot be refused.
                let _ = z.undo(m);
            }
            if let Some(p) = p.filter(|p| best.as_ref().is_none_or(|(b, _)| p.better_than(b))) {
                best = Some((p, i));
            }
        }
        let step = match (best, on_copies) {
            (Some((_, i)), true) => made[i].take().map(|edit| {
                let points = path_points(mesh, path);
                core::mem::swap(mesh, &mut copies[i]);
                self.made_step(mesh, path, edit, points)
            }),
            (Some((p, _)), false) => self.step(mesh, path, p.tag),
            (None, _) => None,
        };
        self.copies = copies;
        Some((best?.0, step?))
    }

    /// What the movement `tag` just made (`r`, on `mesh`) did to the pair whose ends had the
    /// defects `d`: the probe if it cancels the pair or keeps both ends singular with their
    /// defects, at most `dist + 4` apart.
    fn probe_one(
        &mut self,
        mesh: &Mesh,
        r: &ZipReport,
        tag: Tag,
        (da, db): (i64, i64),
        dist: u32,
    ) -> Option<Probe> {
        let (na, nb) = (r.moved_from(), r.moved_to());
        let cancels = defect(mesh, na) == 0 && defect(mesh, nb) == 0;
        let kept = na != nb && defect(mesh, na) == da && defect(mesh, nb) == db;
        let d = if kept {
            self.distance(mesh, na, nb, dist + 4)
        } else {
            None
        };
        (cancels || d.is_some()).then(|| Probe {
            tag,
            cancels,
            a: na,
            b: nb,
            dist: d.unwrap_or(0),
            space: mesh.positions[na.index()].distance(mesh.positions[nb.index()]),
            faces: r.vertex_delta(),
        })
    }

    /// Relaxes the chain's scar and keeps the chain if the whole score falls, the
    /// constraints hold and the mesh has no more folded quads than `folds` (when given);
    /// else restores the positions and undoes the steps.
    pub(super) fn keep_or_undo(
        &mut self,
        mesh: &mut Mesh,
        steps: Vec<Step>,
        total: &mut f64,
        folds: Option<super::folds::FoldCount>,
        out: &mut ChainRun,
    ) {
        let mut region: Vec<Vert> = steps
            .iter()
            .flat_map(|s| s.region.iter().copied())
            .collect();
        region.retain(|&v| mesh.map.is_live_vertex(v));
        region.sort_unstable();
        region.dedup();
        let saved = match self.surface {
            Some(surface) => {
                let mut saved = Vec::new();
                crate::geometry::relax_footprint_fixed(
                    mesh,
                    surface,
                    &region,
                    super::batch::RELAX,
                    &self.locked,
                    &mut saved,
                );
                saved
            }
            None => super::smooth::laplacian(mesh, None, &region, &self.locked, RELAX_STEPS),
        };
        let after = self.scorer.score(mesh).0;
        let folded = folds.is_some_and(|n| super::folds::unsound_quads(mesh).rises_from(n));
        if after < *total - self.eps && self.constraints.holds(mesh) && !folded {
            *total = after;
            out.kept += 1;
            out.qzips += steps.len();
            out.face_change += steps
                .iter()
                .map(|s| s.edit.record().vertex_delta())
                .sum::<isize>();
            out.paths.extend(steps.into_iter().map(|s| s.points));
            out.scar.extend(region);
            return;
        }
        for (v, p) in saved.into_iter().rev() {
            mesh.positions[v.index()] = p;
        }
        self.undo_steps(mesh, &steps);
    }

    pub(super) fn undo_steps(&mut self, mesh: &mut Mesh, steps: &[Step]) {
        for s in steps.iter().rev() {
            // Exact undos of edits just made, in reverse, cannot be refused.
            let _ = s.edit.undo(mesh);
        }
        self.refresh_constraints(mesh);
    }
}
