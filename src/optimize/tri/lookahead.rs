//! The triangle optimizer's two-edit look-ahead ([`super::optimize_triangles`]): around an
//! interior irregular vertex, every atomic edit (edge flip, edge collapse, vertex split) and
//! every pair of them that can do better than one edit (the first adds no irregular vertex,
//! the second changes a vertex the first changed and an irregular one), is scored by the valence
//! changes the operators' documented effects give ([`TriOp::effect`]); the pair (or single
//! edit) that leaves the fewest irregular vertices, then the least spread, is made if it
//! leaves fewer than before. It reaches what the greedy passes cannot: a flip that gains
//! nothing alone and lets a collapse or split remove two irregular vertices, where no
//! single edit lowers the count. `docs/optimize.md` ("Look-ahead") gives the measurements.
//!
//! Only the first edit of each pair is applied while searching (and undone); the second is
//! scored from its effect on the map the first left, and checked (`can`) only when it
//! would be the best so far.

use alloc::collections::BTreeSet;
use alloc::vec::Vec;

use super::guard::{facing, folds, Budget};
use crate::ops::tri::{TriOp, TriRecord};
use crate::ops::Effect;
use crate::{Dart, Map, Mesh, Vert};

/// A change of the interior irregular count and of the spread `sum (valence - 6)^2`
/// (negative is better); ordered count first.
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Debug)]
struct Gain {
    irregular: i64,
    spread: i64,
}

impl Gain {
    fn of(valence: usize) -> Gain {
        let d = valence.abs_diff(6) as i64;
        Gain {
            irregular: i64::from(d > 0),
            spread: d * d,
        }
    }

    fn add(self, o: Gain) -> Gain {
        Gain {
            irregular: self.irregular + o.irregular,
            spread: self.spread + o.spread,
        }
    }

    fn sub(self, o: Gain) -> Gain {
        Gain {
            irregular: self.irregular - o.irregular,
            spread: self.spread - o.spread,
        }
    }
}

/// What `effect` changes in the interior cost of `map` (the map it was computed on);
/// `None` when it changes a boundary vertex's valence, which the optimizer never does.
fn gain(map: &Map, effect: &Effect) -> Option<Gain> {
    let mut g = Gain::default();
    for (v, before, after) in effect.changes() {
        if map.is_boundary_vertex(v) {
            return None;
        }
        g = g.add(Gain::of(after)).sub(Gain::of(before));
    }
    if let Some(v) = effect.removed() {
        if map.is_boundary_vertex(v) {
            return None;
        }
        g = g.sub(Gain::of(map.valence(v)));
    }
    if let Some(k) = effect.created_valence() {
        g = g.add(Gain::of(k));
    }
    Some(g)
}

/// `verts` and their neighbours (the live ones).
fn ring(map: &Map, verts: &[Vert]) -> Vec<Vert> {
    let mut out: BTreeSet<Vert> = BTreeSet::new();
    for &v in verts.iter().filter(|&&v| map.is_live_vertex(v)) {
        out.insert(v);
        out.extend(map.vertex_darts(v).map(|d| map.dest(d)));
    }
    out.into_iter().collect()
}

/// The edits the search tries at `verts`: flip and both collapses of every edge at one of
/// them, and every vertex split of one of valence 6 or more (smaller ones only make
/// vertices of valence 3 to 6 from a v5 or less, never fewer irregular ones).
fn edits_at(map: &Map, verts: &[Vert], out: &mut Vec<TriOp>) {
    out.clear();
    let mut edges: Vec<Dart> = verts
        .iter()
        .flat_map(|&v| map.vertex_darts(v))
        .map(|d| {
            if d.index() < d.twin().index() {
                d
            } else {
                d.twin()
            }
        })
        .collect();
    edges.sort_unstable();
    edges.dedup();
    for e in edges {
        out.extend([
            TriOp::Flip(e),
            TriOp::Collapse(e),
            TriOp::Collapse(e.twin()),
        ]);
    }
    for &v in verts {
        if map.is_boundary_vertex(v) || map.valence(v) < 6 {
            continue;
        }
        let darts: Vec<Dart> = map.vertex_darts(v).collect();
        for (i, &a) in darts.iter().enumerate() {
            out.extend(darts[i + 1..].iter().map(|&b| TriOp::SplitVertex(a, b)));
        }
    }
}

/// The most irregular vertices a first edit may add and still be followed by a second.
/// With the far pair moves, 0 leaves the disk at 43 and Spot at 164 irregular vertices, 1
/// at 43 and 166 in about twice the time (`docs/optimize.md`, "Look-ahead").
const MAX_FIRST: i64 = 0;

/// The vertices whose valence `effect` changes, and the one `record` made.
fn changed(effect: &Effect, record: &TriRecord) -> Vec<Vert> {
    let mut out: Vec<Vert> = effect.valences().map(|(v, _)| v).collect();
    if let TriRecord::SplitVertex(r) = record {
        out.push(r.created());
    }
    out
}

/// The vertices whose valence `op` changes, read cheaply from its ends and apexes (before
/// its effect is computed): the two ends and two apexes of an edge, the split vertex and
/// its two ends.
fn named(map: &Map, op: TriOp) -> [Option<Vert>; 4] {
    let apex = |d: Dart| map.face(d).map(|_| map.dest(map.next(d)));
    match op {
        TriOp::Flip(e) | TriOp::Collapse(e) | TriOp::SplitEdge(e) => [
            Some(map.origin(e)),
            Some(map.dest(e)),
            apex(e),
            apex(e.twin()),
        ],
        TriOp::SplitVertex(a, b) => [
            Some(map.origin(a)),
            Some(map.dest(a)),
            Some(map.dest(b)),
            None,
        ],
    }
}

/// Whether a second edit `op` can make a pair better than its first alone: it must change
/// a vertex of `near` (otherwise the two are independent, and an edit that gains alone is
/// found as a first edit of a search at a vertex it changes) and one of the irregular
/// vertices `irregular` (an edit that changes only regular vertices makes at least one
/// irregular).
fn worth(map: &Map, op: TriOp, near: &[Vert], irregular: &[Vert]) -> bool {
    let n = named(map, op);
    let any = |set: &[Vert]| n.iter().flatten().any(|x| set.contains(x));
    any(near) && any(irregular)
}

/// The best edit or pair of edits near `v`, with its gain, if it lowers the irregular count.
/// The map is as it was afterwards.
fn best_near(map: &mut Map, v: Vert) -> Option<(Gain, TriOp, Option<TriOp>)> {
    let mut best: Option<(Gain, TriOp, Option<TriOp>)> = None;
    let better = |g: Gain, best: &Option<(Gain, TriOp, Option<TriOp>)>| {
        g.irregular < 0 && best.as_ref().is_none_or(|b| g < b.0)
    };
    let (mut first, mut second) = (Vec::new(), Vec::new());
    edits_at(map, &ring(map, &[v]), &mut first);
    for &op in &first {
        let Ok(effect) = op.effect(map) else {
            continue;
        };
        let Some(g1) = gain(map, &effect) else {
            continue;
        };
        if better(g1, &best) {
            best = Some((g1, op, None));
        }
        if g1.irregular > MAX_FIRST {
            continue;
        }
        let Ok(record) = op.apply(map) else {
            continue;
        };
        let mut near = changed(&effect, &record);
        near.push(v);
        let around = ring(map, &near);
        edits_at(map, &around, &mut second);
        let irregular: Vec<Vert> = ring(map, &around)
            .into_iter()
            .filter(|&x| !map.is_boundary_vertex(x) && map.valence(x) != 6)
            .collect();
        for &op2 in second
            .iter()
            .filter(|&&op2| worth(map, op2, &near, &irregular))
        {
            let Some(g2) = gain(map, &op2.effect_unchecked(map)) else {
                continue;
            };
            let g = g1.add(g2);
            if better(g, &best) && op2.can(map).is_ok() {
                best = Some((g, op, Some(op2)));
            }
        }
        // Made on this map just now: the undo is not refused.
        let _ = record.undo(map);
    }
    best
}

/// The look-ahead's memory across batches: the vertices whose search found nothing to
/// keep, searched again only once an edit comes within [`REACH`] edges of them.
#[derive(Default)]
pub(super) struct Lookahead {
    settled: BTreeSet<Vert>,
}

impl Lookahead {
    /// Forgets the settled vertices within [`REACH`] edges of `verts`.
    pub(super) fn forget_near(&mut self, map: &Map, verts: &[Vert]) {
        if self.settled.is_empty() {
            return;
        }
        let mut ball: Vec<Vert> = verts.to_vec();
        for _ in 0..REACH {
            ball = ring(map, &ball);
        }
        for v in ball {
            self.settled.remove(&v);
        }
    }

    /// For each interior irregular vertex not settled, the best edit or pair of edits near
    /// it ([`best_near`]), kept unless a triangle round it turns over or the face count
    /// leaves `budget`; the vertices it changed go to `touched`. Returns how many were kept.
    pub(super) fn pass(
        &mut self,
        mesh: &mut Mesh,
        budget: &Budget,
        touched: &mut Vec<Vert>,
    ) -> usize {
        let mut kept = 0;
        let map = &mesh.map;
        let irregular: Vec<Vert> = map
            .vertices()
            .filter(|&v| !map.is_boundary_vertex(v) && map.valence(v) != 6)
            .filter(|v| !self.settled.contains(v))
            .collect();
        for v in irregular {
            let map = &mesh.map;
            if !map.is_live_vertex(v) || map.valence(v) == 6 || self.settled.contains(&v) {
                continue;
            }
            match keep_best_near(mesh, v, budget) {
                Some(changed) => {
                    self.forget_near(&mesh.map, &changed);
                    touched.extend(changed);
                    kept += 1;
                }
                None => {
                    self.settled.insert(v);
                }
            }
        }
        kept
    }
}

/// The irregular count and spread of the live interior vertices among `verts`.
fn cost(map: &Map, verts: &[Vert]) -> Gain {
    verts
        .iter()
        .filter(|&&v| map.is_live_vertex(v) && !map.is_boundary_vertex(v))
        .fold(Gain::default(), |g, &v| g.add(Gain::of(map.valence(v))))
}

/// How far (edges) from the searched vertex its search reads and its two edits change
/// valences, with a margin: the first edit is at an edge of its ring (ends and apexes two
/// edges away), the second at an edge of the ring of what the first changed (four away),
/// and a valence read there depends on the next ring; a collapse brings vertices one edge
/// nearer.
const REACH: usize = 6;

/// Makes the best edit or pair of edits near `v` ([`best_near`]) unless it does not lower
/// the irregular count after all (checked on the map), a triangle round it turns over or
/// the face count leaves `budget`: the vertices round what it changed, or `None` with the
/// mesh as it was.
fn keep_best_near(mesh: &mut Mesh, v: Vert, budget: &Budget) -> Option<Vec<Vert>> {
    let (_, op, then) = best_near(&mut mesh.map, v)?;
    let region = ring(&mesh.map, &[v]);
    let mut zone = region.clone();
    for _ in 1..REACH {
        zone = ring(&mesh.map, &zone);
    }
    let before = cost(&mesh.map, &zone);
    let reference = facing(mesh, &region);
    let first = op.apply(mesh).ok()?;
    let second = match then.map(|op2| op2.apply(mesh)) {
        Some(Ok(e)) => Some(e),
        Some(Err(_)) => {
            let _ = first.undo(mesh);
            return None;
        }
        None => None,
    };
    let created = second
        .iter()
        .chain([&first])
        .filter_map(|e| match e.record() {
            TriRecord::SplitVertex(r) => Some(r.created()),
            _ => None,
        });
    let created: Vec<Vert> = created.collect();
    // A split may reuse the slot of the vertex a collapse removed: count it once.
    zone.extend(&created);
    zone.sort_unstable();
    zone.dedup();
    let after = ring(&mesh.map, &[region, created].concat());
    let fewer = cost(&mesh.map, &zone).irregular < before.irregular;
    if !fewer || folds(mesh, &after, &reference) || !budget.holds(&mesh.map) {
        // Both were made on this mesh just now, last undone first: not refused.
        if let Some(e) = &second {
            let _ = e.undo(mesh);
        }
        let _ = first.undo(mesh);
        return None;
    }
    Some(after)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;
    use crate::optimize::{tri_score, TriCounts};

    fn whole(map: &Map) -> Gain {
        Gain {
            irregular: TriCounts::of(map).irregular() as i64,
            spread: tri_score(map) as i64,
        }
    }

    /// The search leaves the map `==`, and what it predicts is what its edits do to the
    /// whole mesh's count and spread.
    #[test]
    fn the_predicted_gain_is_the_change_of_the_whole_mesh() {
        let mut found = [0usize; 2];
        for seed in 0..6 {
            let mut map =
                gen::random_triangle(300, (seed % 3) as usize, (seed % 2) as usize, seed).map;
            let verts: Vec<Vert> = map.vertices().collect();
            for v in verts {
                if map.is_boundary_vertex(v) || map.valence(v) == 6 {
                    continue;
                }
                let before = map.clone();
                let Some((g, op, then)) = best_near(&mut map, v) else {
                    continue;
                };
                assert_eq!(map, before);
                assert!(g.irregular < 0);
                let start = whole(&map);
                let r1 = op.apply(&mut map).unwrap();
                let r2 = then.map(|op2| op2.apply(&mut map).unwrap());
                assert_eq!(whole(&map).sub(start), g, "{op:?} {then:?}");
                found[usize::from(then.is_some())] += 1;
                if let Some(r) = r2 {
                    r.undo(&mut map).unwrap();
                }
                r1.undo(&mut map).unwrap();
                assert_eq!(map, before);
            }
        }
        std::eprintln!("{found:?} single edits and pairs checked");
        assert!(found[1] > 100, "{found:?}");
    }
}
