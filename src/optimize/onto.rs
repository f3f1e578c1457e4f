//! The endgame's second stage (our addition): one singularity walked onto an opposite
//! one, each step a Q-zip between it and a third singularity, the driver.
//!
//! A Q-zip between a v3 and a v5 moves both by one edge the same way: the pair is a
//! dislocation, and its Burgers vector (which, in a flat region, fixes the vector from
//! one end to the other) is the same after the Q-zip as before. So a chain that zips a
//! pair with itself only translates it (measured on Blub: 93 % of such steps kept the
//! distance). A Q-zip with a third singularity is not bound that way: the mover `m` can
//! step in any of four directions (the driver `s` takes the matching step), so `m` walks
//! onto the target `u` and the two cancel (a v3 onto a v5, or onto a v6+ which loses one).
//!
//! ```text
//!   s . . . m . . u      s' . . . m' . u      s'' . . . m''u      s''' . . .  (m, u gone)
//!   step 0 (zip s..m)    step 1               step k              the count falls by 2
//! ```

use alloc::vec::Vec;

use super::batch::TAGS;
use super::chain::{ChainRun, Step};
use super::defect::{defect, singularities};
use crate::qzip::{Path, Tag};
use crate::{Mesh, Vert};

/// Targets tried per mover: its closest singularities of the opposite sign.
const TARGETS: usize = 2;

/// Drivers tried per mover and target: the mover's closest other unit singularities.
const DRIVERS: usize = 2;

/// Steps that did not bring the mover closer allowed in one walk.
const STALLS: usize = 4;

/// One walk to try: the mover's graph distance to its target first (closest first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Walk {
    dist: u32,
    mover: Vert,
    target: Vert,
    driver: Vert,
}

/// What a step aims at: the target, the mover's distance to it, the chain's face change
/// so far and the total defect when the walk began.
#[derive(Clone, Copy, Debug)]
struct Aim {
    target: Vert,
    dist: u32,
    faces: isize,
    start: i64,
}

/// Where a probed movement left the mover and the driver.
#[derive(Clone, Copy, Debug)]
struct Probe {
    tag: Tag,
    cancels: bool,
    mover: Vert,
    driver: Vert,
    dist: u32,
    faces: isize,
    space: f64,
}

impl Probe {
    /// Smaller is better: cancelling, then the distance to the target, then the distance
    /// in space (as the pair chains), then the chain's running face change.
    fn better_than(&self, other: &Probe, run: isize) -> bool {
        let key = |p: &Probe| (!p.cancels, p.dist);
        key(self)
            .cmp(&key(other))
            .then(self.space.total_cmp(&other.space))
            .then(
                (run + self.faces)
                    .unsigned_abs()
                    .cmp(&(run + other.faces).unsigned_abs()),
            )
            .is_lt()
    }
}

/// The sum of |defect| over the interior singularities.
fn total_defect(mesh: &Mesh) -> i64 {
    singularities(mesh)
        .iter()
        .filter(|s| !s.boundary)
        .map(|s| s.defect.abs())
        .sum()
}

impl super::batch::Batcher<'_> {
    /// The stage: each walk closest first; returns what it kept. The score never rises.
    pub(crate) fn onto(&mut self, mesh: &mut Mesh, total: &mut f64) -> ChainRun {
        self.refresh_constraints(mesh);
        let mut out = ChainRun::default();
        for w in self.walks(mesh) {
            if self.stop.now() {
                break;
            }
            let (dm, du, ds) = (
                defect(mesh, w.mover),
                defect(mesh, w.target),
                defect(mesh, w.driver),
            );
            // An earlier walk may have cancelled or moved any of the three.
            if dm.abs() != 1 || ds.abs() != 1 || dm * du >= 0 {
                continue;
            }
            let Some(dist) = self.distance(mesh, w.mover, w.target, self.search_radius) else {
                continue;
            };
            out.tried += 1;
            let folds = self.fold_guard.then(|| super::folds::unsound_quads(mesh));
            // A Q-zip from s to m is not one from m to s: if one way stalls, try the other.
            let walked = self
                .walk_onto(mesh, w, dist, true)
                .or_else(|| self.walk_onto(mesh, w, dist, false));
            if let Some(steps) = walked {
                out.cancelled += 1;
                self.keep_or_undo(mesh, steps, total, folds, &mut out);
            }
        }
        out
    }

    /// Each unit-defect singularity as a mover, with its [`TARGETS`] closest singularities
    /// of the opposite sign and, for each, its [`DRIVERS`] closest other unit ones.
    fn walks(&mut self, mesh: &Mesh) -> Vec<Walk> {
        let mut kind = alloc::vec![0i64; mesh.map.vertex_slots()];
        for s in singularities(mesh) {
            if !s.boundary && !self.is_locked(s.vertex) {
                kind[s.vertex.index()] = s.defect;
            }
        }
        let mut walks = Vec::new();
        let movers: Vec<Vert> = mesh
            .map
            .vertices()
            .filter(|v| kind[v.index()].abs() == 1)
            .collect();
        for m in movers {
            let d = kind[m.index()];
            let (mut targets, mut drivers) = (Vec::new(), Vec::new());
            self.bfs.run(mesh, m, self.search_radius, |v, dist| {
                let k = kind.get(v.index()).copied().unwrap_or(0);
                if v != m && k * d < 0 && targets.len() < TARGETS {
                    targets.push((v, dist));
                } else if v != m && k.abs() == 1 && drivers.len() < DRIVERS + TARGETS {
                    drivers.push(v);
                }
                targets.len() < TARGETS || drivers.len() < DRIVERS + TARGETS
            });
            for &(u, dist) in &targets {
                let mut ds = drivers.iter().copied().filter(|&s| s != u).take(DRIVERS);
                walks.extend(ds.by_ref().map(|driver| Walk {
                    dist,
                    mover: m,
                    target: u,
                    driver,
                }));
            }
        }
        walks.sort_unstable();
        walks
    }

    /// Walks `w.mover` onto `w.target` (at distance `dist`) by Q-zips with the driver
    /// (from the driver if `forward`, else to it); returns the applied steps if the last
    /// one cancelled, else undoes them all and returns `None`.
    fn walk_onto(
        &mut self,
        mesh: &mut Mesh,
        w: Walk,
        dist: u32,
        forward: bool,
    ) -> Option<Vec<Step>> {
        let (mut m, mut s, u, mut dist) = (w.mover, w.driver, w.target, dist);
        let start = total_defect(mesh);
        let cap = 2 * dist as usize + 8;
        let (mut steps, mut stalls, mut faces) = (Vec::new(), 0, 0isize);
        while steps.len() < cap && stalls <= STALLS {
            let (a, b) = if forward { (s, m) } else { (m, s) };
            let Ok(path) = self.qzip.sketch(&mesh.map, a, b) else {
                break;
            };
            let aim = Aim {
                target: u,
                dist,
                faces,
                start,
            };
            let Some(best) = self.probe_onto(mesh, &path, forward, aim) else {
                break;
            };
            let Some(step) = self.step(mesh, &path, best.tag) else {
                break;
            };
            steps.push(step);
            faces += best.faces;
            if best.cancels {
                return Some(steps);
            }
            stalls += usize::from(best.dist >= dist);
            (m, s, dist) = (best.mover, best.driver, best.dist);
        }
        self.undo_steps(mesh, &steps);
        None
    }

    /// The best of the four movements along `path` (each applied and undone): one that
    /// cancels the mover (the total defect `start` falls by 2), else one that keeps the
    /// three singularities apart with their defects, closest to the target first.
    fn probe_onto(
        &mut self,
        mesh: &mut Mesh,
        path: &Path,
        forward: bool,
        aim: Aim,
    ) -> Option<Probe> {
        let u = aim.target;
        let ends = path.vertices();
        let (first, last) = (*ends.first()?, *ends.last()?);
        let (m, s) = if forward {
            (last, first)
        } else {
            (first, last)
        };
        let (dm, ds, du) = (defect(mesh, m), defect(mesh, s), defect(mesh, u));
        let mut best: Option<Probe> = None;
        for tag in TAGS {
            let Some(z) = self.apply(mesh, path, tag) else {
                continue;
            };
            let r = z.record();
            let (nm, ns) = if forward {
                (r.moved_to(), r.moved_from())
            } else {
                (r.moved_from(), r.moved_to())
            };
            let live = mesh.map.is_live_vertex(u);
            // The mover is gone or on the target: did the total defect fall?
            let off = defect(mesh, nm) != dm || nm == u || !live;
            let cancels = off && total_defect(mesh) <= aim.start - 2;
            let kept = live
                && nm != ns
                && nm != u
                && ns != u
                && defect(mesh, nm) == dm
                && defect(mesh, ns) == ds
                && defect(mesh, u) == du;
            let d = if kept {
                self.distance(mesh, nm, u, aim.dist + 4)
            } else {
                None
            };
            let p = Probe {
                tag,
                cancels,
                mover: nm,
                driver: ns,
                dist: d.unwrap_or(0),
                faces: r.vertex_delta(),
                space: if live {
                    mesh.positions[nm.index()].distance(mesh.positions[u.index()])
                } else {
                    0.0
                },
            };
            // An exact undo of an edit just made cannot be refused.
            let _ = z.undo(mesh);
            if (cancels || d.is_some()) && best.as_ref().is_none_or(|b| p.better_than(b, aim.faces))
            {
                best = Some(p);
            }
        }
        best
    }
}
