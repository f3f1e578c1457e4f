//! The preprocessing Sec. 2.6 assumes: no interior vertex of valence 2 or of 6 and more.

use alloc::collections::BinaryHeap;
use alloc::vec::Vec;
use core::cmp::Reverse;

use super::placement::place_created;
use crate::mesh::{EditTarget, Edited, Journal};
use crate::ops::quad::{remove_valence2, split_high_valence, QuadRecord};
use crate::ops::Refusal;
use crate::{Dart, Map, Vert};

/// What [`preprocess`] did, with the records for an exact undo.
///
/// See [`preprocess`] for an example.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Preprocessed {
    records: Vec<QuadRecord>,
}

impl Preprocessed {
    /// The operations applied, in order (valence-6+ splits and valence-2 removals).
    ///
    /// See [`preprocess`] for an example.
    pub fn records(&self) -> &[QuadRecord] {
        &self.records
    }

    /// Undoes the preprocessing (the map comes back `==`).
    ///
    /// See [`preprocess`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        super::execute::undo_records(&self.records, map)
    }
}

/// The preprocessing Sec. 2.6 assumes: every interior vertex of valence 6 or more is split
/// along a pair of opposite edges (a 6 becomes two regular vertices and two v5s at the far
/// ends; a 7 a 4 and a 5), and every interior valence-2 vertex is removed (its two quads
/// merge), until none is left. The vertex handled next is always the one of the smallest
/// slot. Pairs whose far ends have valence 4 or less are preferred (the first such pair
/// clockwise from the vertex's [`Map::vertex_dart`], else that dart's) so no new valence-6
/// vertex appears. All or nothing: on a refusal everything is undone.
///
/// Cost: O(n log n) in the darts, also around one vertex of huge valence: the splits halve
/// it, each split costs O(k) and one walk around the vertex, and the next vertex comes from
/// a heap (a step changes at most four valences).
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// use zipmesh::qzip::preprocess;
/// let mut map = gen::torus_grid(8, 8).map;
/// quad::collapse_quad(&mut map, Dart::new(0)).unwrap(); // makes a valence 6
/// let before = map.clone();
/// let p = preprocess(&mut map).unwrap();
/// assert!(map.vertices().all(|v| (3..=5).contains(&map.valence(v))));
/// assert_eq!(p.records().len(), 1);
/// p.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
///
/// On a bare map, a [`crate::Mesh`] or a map with any per-vertex values ([`EditTarget`]):
/// the vertices the splits create are placed as a Q-zip places them (the value of the
/// vertex split, then the mean of their neighbours; see [`super::Qzip::zip_along`]), and
/// the undo restores the values too.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// use zipmesh::qzip::preprocess;
/// let mut mesh = gen::torus_grid(8, 8);
/// quad::collapse_quad(&mut mesh.map, Dart::new(0)).unwrap();
/// let before = mesh.clone();
/// let p = preprocess(&mut mesh).unwrap();
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// p.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// // Marks spread to the vertices made from a marked one.
/// let mut map = gen::torus_grid(8, 8).map;
/// quad::collapse_quad(&mut map, Dart::new(0)).unwrap();
/// let mut marks = vec![true; map.vertex_slots()];
/// let p = preprocess(&mut (&mut map, &mut marks)).unwrap();
/// assert_eq!(marks.len(), map.vertex_slots());
/// assert!(marks.iter().all(|&m| m));
/// ```
pub fn preprocess<T: EditTarget>(
    target: &mut T,
) -> Result<Edited<Preprocessed, T::Values>, Refusal> {
    let (map, values) = target.parts();
    let mut journal = Journal::start(values);
    let p = preprocess_counted(map, &mut 0)?;
    place_created(map, values, &mut journal, p.records());
    Ok(Edited::new(p, journal))
}

/// [`preprocess`], adding to `work` the vertices and darts its own searches visit (the
/// operators' O(k) excluded), so a test can bound it without timing.
fn preprocess_counted(map: &mut Map, work: &mut u64) -> Result<Preprocessed, Refusal> {
    let mut out = Preprocessed::default();
    let mut pending = Pending::new(map, work);
    // Each step lowers the sum of (valence - 5) over high vertices or removes a vertex, so
    // this bound is never reached on a valid map; it keeps a corrupt one from looping.
    let bound = 4 * map.dart_slots() + 16;
    for _ in 0..bound {
        let Some((v, k)) = pending.next(map, work) else {
            return Ok(out);
        };
        let step = if k == 2 {
            let d = map.vertex_dart(v);
            let ends = [map.dest(d), map.dest(map.rotate_cw(d))];
            let r = remove_valence2(map, d).map(QuadRecord::from);
            // The two neighbours lose one edge each; no other valence changes.
            ends.into_iter().for_each(|x| pending.push(x));
            r
        } else {
            split(map, v, &mut pending, work)
        };
        match step {
            Ok(r) => out.records.push(r),
            Err(e) => {
                let _ = out.undo(map);
                return Err(e);
            }
        }
    }
    let _ = out.undo(map);
    Err(Refusal::BadArguments)
}

/// The vertices that may still need a step, smallest slot first: the order a scan of
/// [`Map::vertices`] from the start would give, without repeating it after every step
/// (O(V) each, quadratic in all). An entry that no longer needs a step is dropped.
struct Pending {
    heap: BinaryHeap<Reverse<u32>>,
}

impl Pending {
    fn new(map: &Map, work: &mut u64) -> Pending {
        let heap = map
            .vertices()
            .filter(|&v| needs_step(map, v, work).is_some())
            .map(|v| Reverse(v.index() as u32))
            .collect();
        Pending { heap }
    }

    /// A vertex whose valence a step may have changed.
    fn push(&mut self, v: Vert) {
        self.heap.push(Reverse(v.index() as u32));
    }

    /// The smallest vertex needing a step, with its valence (2, or 6 and more).
    fn next(&mut self, map: &Map, work: &mut u64) -> Option<(Vert, usize)> {
        while let Some(Reverse(i)) = self.heap.pop() {
            let v = Vert::new(i);
            // Duplicates are popped together: the vertex is handled once per step.
            while self.heap.peek() == Some(&Reverse(i)) {
                self.heap.pop();
            }
            if let Some(k) = needs_step(map, v, work) {
                return Some((v, k));
            }
        }
        None
    }
}

/// `Some(valence)` if `v` is an interior vertex of valence 2 or 6 and more; counts at most
/// six darts for the test, the whole valence only when it is high (the split walks it anyway).
fn needs_step(map: &Map, v: Vert, work: &mut u64) -> Option<usize> {
    *work += 1;
    if !map.is_live_vertex(v) || map.is_boundary_vertex(v) {
        return None;
    }
    let n = map.vertex_darts(v).take(6).count();
    *work += n as u64;
    match n {
        2 => Some(2),
        6 => Some(map.valence(v)),
        _ => None,
    }
}

/// Splits `v` (valence k >= 6) along the first pair of opposite darts whose far ends have
/// valence 4 or less, else along its vertex dart. One walk around `v`: the partner of the
/// i-th dart clockwise is the (i + k/2)-th, not k/2 steps away for each candidate.
fn split(
    map: &mut Map,
    v: Vert,
    pending: &mut Pending,
    work: &mut u64,
) -> Result<QuadRecord, Refusal> {
    let ring: Vec<Dart> = map.vertex_darts(v).collect();
    let k = ring.len();
    *work += k as u64;
    let pair = |i: usize| {
        (
            ring.get(i).copied(),
            ring.get((i + k / 2) % k.max(1)).copied(),
        )
    };
    let low = |d: Option<Dart>, work: &mut u64| {
        *work += 5;
        d.is_some_and(|d| map.vertex_darts(map.dest(d)).nth(4).is_none())
    };
    let i = (0..k)
        .find(|&i| {
            let (a, b) = pair(i);
            low(a, work) && low(b, work)
        })
        .unwrap_or(0);
    let (Some(first), Some(opposite)) = pair(i) else {
        return Err(Refusal::WrongValence);
    };
    let ends = [map.dest(first), map.dest(opposite)];
    let s = split_high_valence(map, v, first)?;
    // v, the new vertex and the two far ends: the only valences a split changes.
    for x in [s.kept(), s.created(), ends[0], ends[1]] {
        pending.push(x);
    }
    Ok(QuadRecord::from(s))
}

impl crate::ops::Undo for Preprocessed {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        Preprocessed::undo(self, map)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The disk of `k` quads around vertex 0, the rim on the boundary.
    fn fan(k: u32) -> Map {
        let s = |i: u32| 1 + 2 * (i % k);
        let faces: Vec<[u32; 4]> = (0..k).map(|i| [0, s(i), 2 + 2 * i, s(i + 1)]).collect();
        Map::from_polygons((1 + 2 * k) as usize, &faces).unwrap()
    }

    /// On a mesh, the vertex a split creates is placed (the layer covers it, and a slot it
    /// reuses no longer holds the stale far value), and the undo restores the positions.
    #[test]
    fn preprocessing_a_mesh_places_what_it_creates() {
        let mut mesh = crate::gen::torus_grid(8, 8);
        for p in &mut mesh.positions {
            *p += glam::DVec3::splat(100.0);
        }
        let c = crate::ops::quad::collapse_quad(&mut mesh.map, Dart::new(0)).unwrap();
        mesh.positions[c.removed().index()] = glam::DVec3::splat(-1e9);
        let before = mesh.clone();
        let p = preprocess(&mut mesh).unwrap();
        assert!(!p.records().is_empty());
        assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
        let m = &mesh.map;
        assert!(m
            .vertices()
            .all(|v| mesh.positions[v.index()].min_element() > 50.0));
        p.undo(&mut mesh).unwrap();
        assert_eq!(mesh, before);
    }

    /// The searches' work is linear in the darts: a scan from the start after each step
    /// (about 10^8 vertex visits here) or k/2 steps per candidate would break the bound.
    #[test]
    fn work_is_linear_in_the_valence() {
        for k in [1_000u32, 20_000] {
            let mut map = fan(k);
            let mut work = 0;
            let p = preprocess_counted(&mut map, &mut work).unwrap();
            assert!(p.records().len() > k as usize / 3);
            assert!(
                work <= 20 * map.dart_slots() as u64,
                "valence {k}: {work} visits for {} darts",
                map.dart_slots()
            );
        }
    }
}
