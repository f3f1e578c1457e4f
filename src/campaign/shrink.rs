//! Shrinking: the smallest sub-mesh around a failure that still fails.

use super::case::{Case, Origin};
use super::property::{Outcome, Property};
use crate::map::Vert;
use crate::mesh::Mesh;
use alloc::collections::VecDeque;
use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;

/// How many times the property is re-run while shrinking, at most.
///
/// ```
/// use zipmesh::campaign::{shrink, Case, Outcome, Property, SHRINK_BUDGET};
/// let always = Property::new("always-fails", "", |_| Outcome::fail("no", None));
/// let case = Case::generate(0, 1, 1000);
/// let s = shrink(&always, &case, always.check(&case)).unwrap();
/// assert!(s.evaluations <= SHRINK_BUDGET);
/// assert_eq!(s.mesh.map.num_faces(), 1); // any single face still "fails"
/// ```
pub const SHRINK_BUDGET: usize = 600;

/// A shrunk counterexample: a mesh on which the property still fails.
///
/// ```
/// use zipmesh::campaign::{shrink, Case, Outcome, Property};
/// use zipmesh::gen;
/// // Fails whenever the mesh has a vertex of valence 3 (the cube's corners).
/// let p = Property::new("no-valence-3", "", |c| {
///     let m = &c.mesh.map;
///     match m.vertices().find(|&v| m.valence(v) == 3) {
///         Some(v) => Outcome::fail("valence 3", Some(v)),
///         None => Outcome::Pass { checks: 1 },
///     }
/// });
/// let case = Case::from_mesh(gen::cube(4), 0, 0, "cube");
/// let s = shrink(&p, &case, p.check(&case)).unwrap();
/// assert!(s.mesh.map.num_faces() < 96);
/// assert!(p.check(&s.case(0)).is_fail());
/// ```
#[derive(Clone, Debug)]
pub struct Shrunk {
    /// The smallest failing mesh found, without dead slots (so that writing it as OBJ and
    /// reading it back gives the same map).
    pub mesh: Mesh,
    /// The vertex the last failure named, in the shrunk mesh's numbering.
    pub focus: Option<Vert>,
    /// The failure message on the shrunk mesh.
    pub message: String,
    /// How many times the property was re-run.
    pub evaluations: usize,
}

impl Shrunk {
    /// The case that replays the shrunk failure: the shrunk mesh with the focus set, index 0
    /// and the given campaign seed (what `zipmesh check FILE --seed S --focus V` builds).
    ///
    /// ```
    /// use zipmesh::{campaign::Shrunk, gen};
    /// let s = Shrunk { mesh: gen::cube(1), focus: None, message: String::new(), evaluations: 0 };
    /// assert_eq!(s.case(5).seed, 5);
    /// ```
    pub fn case(&self, seed: u64) -> Case {
        let mut case = Case::from_mesh(self.mesh.clone(), seed, 0, "shrunk counterexample");
        case.focus = self.focus;
        case
    }
}

/// Shrinks a failing case: keeps the faces within `k` vertex rings of the failure's focus
/// for the smallest `k` that still fails, then deletes faces one chunk at a time, farthest
/// from the focus first (chunks halve down to single faces), keeping every deletion after
/// which the mesh still builds with [`Mesh::from_polygons`] and the property still fails.
/// Unused vertices are dropped and the rest renumbered in their old order. At most
/// [`SHRINK_BUDGET`] re-runs. `None` if `failure` is not a failure, or if no candidate
/// fails (not even the whole mesh renumbered, as the replay would build it).
///
/// Candidate cases use the failing case's seed, index 0 and the focus, exactly as
/// [`Shrunk::case`] rebuilds them, so the result replays.
///
/// ```
/// use zipmesh::campaign::{shrink, Case, Outcome, Property};
/// let p = Property::new("never", "", |_| Outcome::Pass { checks: 1 });
/// let case = Case::generate(0, 0, 200);
/// assert!(shrink(&p, &case, p.check(&case)).is_none());
/// ```
pub fn shrink(property: &Property, case: &Case, failure: Outcome) -> Option<Shrunk> {
    let Outcome::Fail { message, focus } = failure else {
        return None;
    };
    let map = &case.mesh.map;
    let polys = case.mesh.polygons();
    let n_slots = map.vertex_slots();
    let mut state = State {
        property,
        case,
        polys: &polys,
        n_slots,
        evaluations: 0,
    };
    // Everything in the original numbering: `keep` over the original faces.
    let mut keep = vec![true; polys.len()];
    let mut best = Best {
        message,
        focus,
        mesh: None,
    };
    if let Some(f) = focus {
        let rings = face_rings(&polys, n_slots, f);
        let max_ring = rings.iter().copied().filter(|&r| r != usize::MAX).max();
        if let Some(max_ring) = max_ring {
            for k in 0..max_ring {
                let candidate: Vec<bool> = rings.iter().map(|&r| r <= k).collect();
                if state.try_candidate(&candidate, best.focus, &mut best) {
                    keep = candidate;
                    break;
                }
            }
        }
    }
    // Chunked deletion, farthest faces first.
    let mut chunk = keep.iter().filter(|&&k| k).count() / 2;
    while chunk >= 1 && state.evaluations < SHRINK_BUDGET {
        let order: Vec<usize> = farthest_first(&polys, n_slots, best.focus, &keep);
        let mut removed_any = false;
        for group in order.chunks(chunk) {
            if state.evaluations >= SHRINK_BUDGET {
                break;
            }
            let mut candidate = keep.clone();
            for &i in group {
                candidate[i] = false;
            }
            if !candidate.iter().any(|&k| k) {
                continue;
            }
            if state.try_candidate(&candidate, best.focus, &mut best) {
                keep = candidate;
                removed_any = true;
            }
        }
        if !removed_any {
            chunk /= 2;
        }
    }
    // Nothing smaller failed: the whole mesh, renumbered, must fail by itself to count.
    if best.mesh.is_none() {
        let all = vec![true; polys.len()];
        if !state.try_candidate(&all, best.focus, &mut best) {
            return None;
        }
    }
    let (mesh, renumber) = best.mesh.take()?;
    let focus = best
        .focus
        .and_then(|v| renumber.get(v.index()).copied().flatten());
    Some(Shrunk {
        mesh,
        focus,
        message: best.message,
        evaluations: state.evaluations,
    })
}

struct State<'a> {
    property: &'a Property,
    case: &'a Case,
    polys: &'a [Vec<u32>],
    n_slots: usize,
    evaluations: usize,
}

/// The best failing candidate so far; its focus in the original numbering.
struct Best {
    message: String,
    focus: Option<Vert>,
    mesh: Option<(Mesh, Vec<Option<Vert>>)>,
}

impl State<'_> {
    /// Builds the candidate and re-runs the property on it; on a failure records it in
    /// `best` and returns true.
    fn try_candidate(&mut self, keep: &[bool], focus: Option<Vert>, best: &mut Best) -> bool {
        let Some((mesh, renumber)) =
            build(self.polys, self.n_slots, &self.case.mesh.positions, keep)
        else {
            return false;
        };
        self.evaluations += 1;
        let mut case = Case {
            seed: self.case.seed,
            index: 0,
            mesh,
            origin: Origin::Given(String::from("shrunk counterexample")),
            focus: focus.and_then(|v| renumber.get(v.index()).copied().flatten()),
        };
        let outcome = super::guarded(self.property, &case);
        if let Outcome::Fail { message, focus } = outcome {
            // Back to the original numbering.
            let old_of = |v: Vert| renumber.iter().position(|&n| n == Some(v));
            best.focus = focus
                .and_then(old_of)
                .map(|i| Vert::new(i as u32))
                .or(best.focus);
            best.message = message;
            let mesh = core::mem::take(&mut case.mesh);
            best.mesh = Some((mesh, renumber));
            true
        } else {
            false
        }
    }
}

/// The kept polygons as a mesh without unused vertices, and the map old → new vertex.
fn build(
    polys: &[Vec<u32>],
    n_slots: usize,
    positions: &[glam::DVec3],
    keep: &[bool],
) -> Option<(Mesh, Vec<Option<Vert>>)> {
    let mut used = vec![false; n_slots];
    for (p, _) in polys.iter().zip(keep).filter(|(_, &k)| k) {
        for &v in p {
            *used.get_mut(v as usize)? = true;
        }
    }
    let mut renumber = vec![None; n_slots];
    let mut new_positions = Vec::new();
    for (old, _) in used.iter().enumerate().filter(|(_, &u)| u) {
        renumber[old] = Some(Vert::new(new_positions.len() as u32));
        new_positions.push(positions.get(old).copied().unwrap_or_default());
    }
    let faces: Vec<Vec<u32>> = polys
        .iter()
        .zip(keep)
        .filter(|(_, &k)| k)
        .map(|(p, _)| {
            p.iter()
                .map(|&v| renumber[v as usize].map_or(0, |n| n.index() as u32))
                .collect()
        })
        .collect();
    let (mesh, _) = Mesh::from_polygons(new_positions, &faces).ok()?;
    Some((mesh, renumber))
}

/// For each face, the number of vertex rings between it and `focus` (0: the faces at
/// `focus`), `usize::MAX` when unreachable.
fn face_rings(polys: &[Vec<u32>], n_slots: usize, focus: Vert) -> Vec<usize> {
    let mut faces_at: Vec<Vec<usize>> = vec![Vec::new(); n_slots];
    for (i, p) in polys.iter().enumerate() {
        for &v in p {
            if let Some(list) = faces_at.get_mut(v as usize) {
                list.push(i);
            }
        }
    }
    let mut ring = vec![usize::MAX; polys.len()];
    let mut vdist = vec![usize::MAX; n_slots];
    let mut queue = VecDeque::new();
    if focus.index() < n_slots {
        vdist[focus.index()] = 0;
        queue.push_back(focus.index());
    }
    // A face is in ring k when its nearest corner is k edges-through-faces from the focus.
    while let Some(v) = queue.pop_front() {
        let d = vdist[v];
        for &f in &faces_at[v] {
            if ring[f] == usize::MAX {
                ring[f] = d;
                for &w in &polys[f] {
                    if vdist[w as usize] == usize::MAX {
                        vdist[w as usize] = d + 1;
                        queue.push_back(w as usize);
                    }
                }
            }
        }
    }
    ring
}

/// The kept faces ordered by ring distance from `focus`, farthest first (input order
/// without a focus).
fn farthest_first(
    polys: &[Vec<u32>],
    n_slots: usize,
    focus: Option<Vert>,
    keep: &[bool],
) -> Vec<usize> {
    let mut order: Vec<usize> = (0..polys.len()).filter(|&i| keep[i]).collect();
    if let Some(f) = focus {
        let rings = face_rings(polys, n_slots, f);
        order.sort_by_key(|&i| core::cmp::Reverse(rings[i]));
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;

    #[test]
    fn rings_grow_by_one_vertex_step_on_a_grid() {
        // 6 x 6 quads, 7 x 7 vertices; the focus is the centre vertex (3, 3).
        let mesh = gen::grid(6, 6);
        let polys = mesh.polygons();
        let centre = Vert::new(3 * 7 + 3);
        let rings = face_rings(&polys, mesh.map.vertex_slots(), centre);
        let count = |k: usize| rings.iter().filter(|&&r| r == k).count();
        // Ring 0: the 4 quads at the centre; ring 1: the rest of the central 4 x 4 block
        // (16 - 4); ring 2: the other 36 - 16.
        assert_eq!((count(0), count(1), count(2)), (4, 12, 20));
        assert!(rings.iter().all(|&r| r <= 2));
    }

    #[test]
    fn build_drops_unused_vertices_and_keeps_their_order() {
        let mesh = gen::grid(3, 1);
        let polys = mesh.polygons();
        let keep = [false, false, true];
        let (small, renumber) =
            build(&polys, mesh.map.vertex_slots(), &mesh.positions, &keep).unwrap();
        assert_eq!(small.map.num_vertices(), 4);
        assert_eq!(small.map.num_faces(), 1);
        let kept: Vec<usize> = (0..renumber.len())
            .filter(|&i| renumber[i].is_some())
            .collect();
        // The last quad's corners, renumbered 0..4 in their old order.
        assert_eq!(kept, [2, 3, 6, 7]);
        for (new, &old) in kept.iter().enumerate() {
            assert_eq!(renumber[old], Some(Vert::new(new as u32)));
            assert_eq!(small.positions[new], mesh.positions[old]);
        }
    }

    #[test]
    fn a_pinched_candidate_does_not_build() {
        // Two quads of a 2 x 2 grid touching only at the centre: a non-manifold vertex.
        let mesh = gen::grid(2, 2);
        let polys = mesh.polygons();
        let keep = [true, false, false, true];
        assert!(build(&polys, mesh.map.vertex_slots(), &mesh.positions, &keep).is_none());
    }
}
