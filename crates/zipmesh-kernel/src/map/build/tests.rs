//! The builder against a straightforward reference on random polygon soups.

use super::*;
use crate::rng::Rng;
use alloc::collections::BTreeMap;
use proptest::prelude::*;

/// Builds like [`Map::from_flat_polygons`], one rule at a time, with maps and full scans
/// instead of the builder's lists: what the builder must give, every error included.
fn reference(
    n_vertices: usize,
    corners: &[u32],
    offsets: &[u32],
) -> Result<(Map, BuildReport), BuildError> {
    let h_count = corners.len();
    if h_count > MAX_CORNERS || n_vertices >= NONE as usize {
        return Err(BuildError::TooLarge { corners: h_count });
    }
    let n_faces = offsets.len().saturating_sub(1);
    if offsets.first().is_some_and(|&o| o != 0) || (n_faces == 0 && h_count != 0) {
        return Err(BuildError::FaceTooSmall {
            face: 0,
            corners: 0,
        });
    }
    // Face checks, in face order.
    for f in 0..n_faces {
        let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
        if e < s || e > h_count || e - s < 3 {
            let corners = e.saturating_sub(s);
            return Err(BuildError::FaceTooSmall { face: f, corners });
        }
        let poly = &corners[s..e];
        if let Some(&v) = poly.iter().find(|&&v| v as usize >= n_vertices) {
            return Err(BuildError::IndexOutOfRange {
                face: f,
                vertex: v,
                n_vertices,
            });
        }
        // Up to 12 corners the first repeat in order, beyond that the smallest repeated vertex.
        let repeats: Vec<u32> = (1..poly.len())
            .filter(|&i| poly[..i].contains(&poly[i]))
            .map(|i| poly[i])
            .collect();
        let first = if poly.len() <= 12 {
            repeats.first()
        } else {
            repeats.iter().min()
        };
        if let Some(&vertex) = first {
            return Err(BuildError::RepeatedCorner { face: f, vertex });
        }
    }
    if offsets.last().is_some_and(|&o| o as usize != h_count) {
        return Err(BuildError::FaceTooSmall {
            face: n_faces,
            corners: 0,
        });
    }
    // Half-edge h runs from corner h to the next corner of its face.
    let mut face_of = Vec::new();
    let mut dest = Vec::new();
    for f in 0..n_faces {
        let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
        for h in s..e {
            face_of.push(f);
            dest.push(corners[if h + 1 == e { s } else { h + 1 }]);
        }
    }
    // Half-edges by their two ends; the first bad group in the documented order.
    let mut groups: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    let mut per_low: BTreeMap<u32, usize> = BTreeMap::new();
    for h in 0..h_count {
        let (a, b) = (corners[h], dest[h]);
        groups.entry((a.min(b), a.max(b))).or_default().push(h);
        *per_low.entry(a.min(b)).or_default() += 1;
    }
    let mut first_bad: Option<((u32, usize), BuildError)> = None;
    for (&(lo, hi), hs) in &groups {
        let error = match hs[..] {
            [h1, h2, h3, ..] => BuildError::NonManifoldEdge {
                a: lo,
                b: hi,
                faces: [face_of[h1], face_of[h2], face_of[h3]],
            },
            [h1, h2] if corners[h1] == corners[h2] => BuildError::InconsistentOrientation {
                a: corners[h1],
                b: dest[h1],
                faces: [face_of[h1], face_of[h2]],
            },
            _ => continue,
        };
        let key = (
            lo,
            if per_low[&lo] > 16 {
                hi as usize
            } else {
                hs[0]
            },
        );
        if first_bad.as_ref().is_none_or(|(k, _)| key < *k) {
            first_bad = Some((key, error));
        }
    }
    if let Some((_, error)) = first_bad {
        return Err(error);
    }
    // Edges numbered by first half-edge; the first gets the even dart.
    let mut dart = vec![NONE; h_count];
    let mut n_edges = 0u32;
    for h in 0..h_count {
        if dart[h] == NONE {
            dart[h] = 2 * n_edges;
            let hs = &groups[&(corners[h].min(dest[h]), corners[h].max(dest[h]))];
            if let Some(&m) = hs.iter().find(|&&m| m != h) {
                dart[m] = 2 * n_edges + 1;
            }
            n_edges += 1;
        }
    }
    let n_darts = 2 * n_edges as usize;
    let with_room = |n: usize, value: u32| {
        let mut v = Vec::with_capacity(n + n / 32 + 64);
        v.resize(n, value);
        v
    };
    let mut map = Map {
        next: with_room(n_darts, NONE),
        vert: with_room(n_darts, NONE),
        face: with_room(n_darts, NONE),
        vdart: with_room(n_vertices, NONE),
        fdart: with_room(n_faces, NONE),
        free_edges: Vec::new(),
        free_verts: Vec::new(),
        free_faces: Vec::new(),
    };
    for f in 0..n_faces {
        let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
        map.fdart[f] = dart[s];
        for h in s..e {
            let d = dart[h] as usize;
            map.next[d] = dart[if h + 1 == e { s } else { h + 1 }];
            map.vert[d] = corners[h];
            map.face[d] = f as u32;
            map.vdart[corners[h] as usize] = d as u32; // the last one stays
        }
    }
    // Boundary darts in half-edge order; at most one leaves each vertex.
    let mut boundary_out = vec![NONE; n_vertices];
    for h in 0..h_count {
        let t = (dart[h] ^ 1) as usize;
        if map.vert[t] == NONE {
            map.vert[t] = dest[h];
            if boundary_out[dest[h] as usize] != NONE {
                let (vertex, face) = (dest[h], face_of[h]);
                return Err(BuildError::NonManifoldVertex { vertex, face });
            }
            boundary_out[dest[h] as usize] = t as u32;
        }
    }
    for h in 0..h_count {
        let t = (dart[h] ^ 1) as usize;
        if map.next[t] == NONE {
            map.next[t] = boundary_out[corners[h] as usize];
        }
    }
    for (v, &t) in boundary_out.iter().enumerate() {
        if t != NONE {
            map.vdart[v] = t;
        }
    }
    // One fan per vertex, in vertex order: the rotation from the record has every dart.
    for v in 0..n_vertices {
        let d0 = map.vdart[v];
        if d0 == NONE {
            continue;
        }
        let out = map.vert.iter().filter(|&&o| o as usize == v).count();
        let mut orbit = vec![d0];
        let mut d = map.next[(d0 ^ 1) as usize];
        while d != d0 && orbit.len() <= out {
            orbit.push(d);
            d = map.next[(d ^ 1) as usize];
        }
        if orbit.len() != out {
            let f = map.face[d0 as usize];
            let face = if f == NONE {
                map.face[(d0 ^ 1) as usize]
            } else {
                f
            } as usize;
            return Err(BuildError::NonManifoldVertex {
                vertex: v as u32,
                face,
            });
        }
    }
    for v in (0..n_vertices).rev() {
        if map.vdart[v] == NONE {
            map.free_verts.push(v as u32);
        }
    }
    let unreferenced = map
        .free_verts
        .iter()
        .rev()
        .map(|&v| super::super::Vert(v))
        .collect();
    Ok((map, BuildReport { unreferenced }))
}

/// A random polygon soup on `n` vertices, built from a mesh-like start and then spoiled.
fn soup(rng: &mut Rng) -> (usize, Vec<Vec<u32>>) {
    let (n, mut faces): (usize, Vec<Vec<u32>>) = match rng.below(5) {
        // Small random faces: every kind of defect, often.
        0 => {
            let n = 1 + rng.below(7);
            let faces = (0..rng.below(8))
                .map(|_| (0..rng.below(7)).map(|_| rng.below(n + 1) as u32).collect())
                .collect();
            (n, faces)
        }
        // A torus of quads, or of triangles.
        1 | 2 => {
            let (w, h) = (3 + rng.below(4), 3 + rng.below(4));
            let quads = crate::gen::torus_quads(w, h);
            let faces = if rng.chance(1, 2) {
                quads.iter().map(|q| q.to_vec()).collect()
            } else {
                quads
                    .iter()
                    .flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]])
                    .collect()
            };
            (w * h, faces)
        }
        // A grid of quads: a disk with a boundary.
        3 => {
            let (w, h) = (1 + rng.below(5), 1 + rng.below(5));
            let at = |i: usize, j: usize| (j * (w + 1) + i) as u32;
            let faces = (0..h)
                .flat_map(|j| {
                    (0..w)
                        .map(move |i| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
                })
                .collect();
            ((w + 1) * (h + 1), faces)
        }
        // A wheel: one centre with more than 16 half-edges (the sorted lists), closed into a
        // double cone or not.
        _ => {
            let k = 3 + rng.below(24);
            let rim = |i: usize| 1 + (i % k) as u32;
            let mut faces: Vec<Vec<u32>> = (0..k).map(|i| vec![0, rim(i), rim(i + 1)]).collect();
            if rng.chance(1, 2) {
                let tip = (k + 1) as u32;
                faces.extend((0..k).map(|i| vec![tip, rim(i + 1), rim(i)]));
            }
            (k + 2, faces)
        }
    };
    for _ in 0..rng.below(4) {
        spoil(rng, n, &mut faces);
    }
    // Shuffle the face order sometimes: numbering follows it.
    if rng.chance(1, 4) {
        for i in (1..faces.len()).rev() {
            faces.swap(i, rng.below(i + 1));
        }
    }
    (n, faces)
}

/// One random defect or change: a face removed, repeated, reversed or added, two vertices
/// merged, a corner moved, or a face rotated.
fn spoil(rng: &mut Rng, n: usize, faces: &mut Vec<Vec<u32>>) {
    if faces.is_empty() {
        return;
    }
    let f = rng.below(faces.len());
    match rng.below(8) {
        0 | 1 => {
            faces.remove(f);
        }
        2 => faces.push(faces[f].clone()),
        3 => faces[f].reverse(),
        4 => {
            let (a, b) = (rng.below(n) as u32, rng.below(n) as u32);
            for face in faces.iter_mut() {
                face.iter_mut().filter(|v| **v == a).for_each(|v| *v = b);
            }
        }
        5 => {
            let i = rng.below(faces[f].len().max(1));
            if let Some(v) = faces[f].get_mut(i) {
                *v = rng.below(n + 1) as u32;
            }
        }
        6 => {
            let k = faces[f].len();
            faces[f].rotate_left(rng.below(k.max(1)));
        }
        _ => faces.push((0..3 + rng.below(2)).map(|_| rng.below(n) as u32).collect()),
    }
}

fn flatten(faces: &[Vec<u32>]) -> (Vec<u32>, Vec<u32>) {
    let corners: Vec<u32> = faces.concat();
    let mut offsets = vec![0u32];
    for f in faces {
        offsets.push(offsets[offsets.len() - 1] + f.len() as u32);
    }
    (corners, offsets)
}

/// The kind of a result, for the tally.
fn kind(r: &Result<(Map, BuildReport), BuildError>) -> usize {
    match r {
        Ok((m, _)) if m.face.contains(&NONE) => 1,
        Ok(_) => 0,
        Err(BuildError::FaceTooSmall { .. }) => 2,
        Err(BuildError::RepeatedCorner { .. }) => 3,
        Err(BuildError::IndexOutOfRange { .. }) => 4,
        Err(BuildError::NonManifoldEdge { .. }) => 5,
        Err(BuildError::InconsistentOrientation { .. }) => 6,
        Err(BuildError::NonManifoldVertex { .. }) => 7,
        Err(BuildError::TooLarge { .. }) => 8,
    }
}

/// The builder, through both entries, gives exactly the reference's map (capacities
/// included) or error on random soups: closed and bounded meshes, pinched vertices,
/// non-manifold and misoriented edges (some around a vertex with more than 16 half-edges,
/// where the error order differs), bad faces and bad offsets. Every kind of result occurs.
#[test]
fn the_builder_matches_the_reference() {
    let mut rng = Rng::new(17);
    let mut tally = [0usize; 9];
    for _ in 0..ROUNDS {
        let (n, faces) = soup(&mut rng);
        let (corners, mut offsets) = flatten(&faces);
        let want = reference(n, &corners, &offsets);
        let got = Map::from_polygons_with_report(n, &faces);
        assert_eq!(got, want, "{n} vertices, faces {faces:?}");
        if let (Ok((got, _)), Ok((want, _))) = (&got, &want) {
            assert_eq!(got.heap_bytes(), want.heap_bytes());
        }
        assert_eq!(Map::from_flat_polygons(n, &corners, &offsets), want);
        tally[kind(&want)] += 1;
        if !offsets.is_empty() && rng.chance(1, 4) {
            let i = rng.below(offsets.len());
            offsets[i] = rng.below(corners.len() + 3) as u32;
            let want = reference(n, &corners, &offsets);
            assert_eq!(Map::from_flat_polygons(n, &corners, &offsets), want);
        }
    }
    for (k, &count) in tally.iter().enumerate().take(8) {
        assert!(
            count >= ROUNDS / 1000,
            "kind {k}: {count} of {ROUNDS} ({tally:?})"
        );
    }
    let too_many = Map::from_polygons(NONE as usize, &[[0u32, 1, 2]]);
    assert_eq!(too_many, Err(BuildError::TooLarge { corners: 3 }));
}

const ROUNDS: usize = 30_000;

proptest! {
    /// Arbitrary small polygon lists (any corner count, indices out of range, repeats,
    /// every pairing defect), then the flat form with offsets overwritten or added (out
    /// of order, past the end): both entries give the reference's map or error.
    #[test]
    fn small_lists_match_the_reference(
        n in 0usize..9,
        faces in proptest::collection::vec(proptest::collection::vec(0u32..10, 0..7), 0..9),
        bad in proptest::collection::vec((0usize..12, 0u32..40), 0..4),
    ) {
        let (corners, mut offsets) = flatten(&faces);
        let want = reference(n, &corners, &offsets);
        prop_assert_eq!(Map::from_polygons_with_report(n, &faces), want.clone());
        prop_assert_eq!(Map::from_flat_polygons(n, &corners, &offsets), want);
        for (i, v) in bad {
            match offsets.get_mut(i) {
                Some(o) => *o = v,
                None => offsets.push(v),
            }
            let want = reference(n, &corners, &offsets);
            prop_assert_eq!(Map::from_flat_polygons(n, &corners, &offsets), want);
        }
    }
}

/// Offsets that run backwards or past the end are faces with too few corners, not panics.
#[test]
fn bad_offsets_are_errors() {
    let corners = [0, 1, 2, 0, 2, 3];
    let small = |face, corners| Err(BuildError::FaceTooSmall { face, corners });
    assert_eq!(
        Map::from_flat_polygons(4, &corners, &[0, 3, 2]),
        small(1, 0)
    );
    assert_eq!(
        Map::from_flat_polygons(4, &corners, &[0, 3, 9]),
        small(1, 6)
    );
    assert_eq!(
        Map::from_flat_polygons(4, &corners, &[0, u32::MAX]),
        small(0, u32::MAX as usize)
    );
    assert_eq!(Map::from_flat_polygons(4, &corners, &[0, 3]), small(1, 0));
    assert_eq!(
        Map::from_flat_polygons(4, &corners, &[1, 3, 6]),
        small(0, 0)
    );
    assert_eq!(Map::from_flat_polygons(4, &corners, &[]), small(0, 0));
    assert!(Map::from_flat_polygons(4, &[], &[]).is_ok());
    assert!(Map::from_flat_polygons(4, &[], &[0]).is_ok());
}

/// A face that reads differently each time (an `AsRef` that changes between the builder's
/// passes) gives an error or a map, never a panic.
#[test]
fn a_changing_face_does_not_panic() {
    use core::cell::Cell;
    struct Shifty(Cell<u32>, [u32; 4], [u32; 4]);
    impl AsRef<[u32]> for Shifty {
        fn as_ref(&self) -> &[u32] {
            self.0.set(self.0.get() + 1);
            // The first two reads (the size, the checks) are good; later ones are not.
            if self.0.get() <= 2 {
                &self.1
            } else {
                &self.2
            }
        }
    }
    for bad in [[0, 1, 2, 9], [0, 1, 1, 1], [3, 2, 1, 0], [7, 7, 7, 7]] {
        let faces = [
            Shifty(Cell::new(0), [0, 1, 2, 3], bad),
            Shifty(Cell::new(0), [3, 2, 1, 0], bad),
        ];
        let _ = Map::from_polygons_with_report(4, &faces);
    }
    let faces = [Shifty(Cell::new(0), [0, 1, 2, 3], [0, 1, 2, 9])];
    let err = BuildError::IndexOutOfRange {
        face: 0,
        vertex: 9,
        n_vertices: 4,
    };
    assert_eq!(Map::from_polygons(4, &faces), Err(err));
}
