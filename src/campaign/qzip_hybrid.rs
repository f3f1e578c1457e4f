//! The Q-zip properties on quad-dominant meshes (Q-zip paper, Sec. 3.2): grid preservation,
//! reversal and homotopy with the paths winding around the triangles
//! ([`crate::qzip::avoid_triangles`]), and the triangles counted as what they are: every
//! triangle keeps its face and its corner valences, so the irregular valences of the quad
//! vertices are those of the input.

use std::borrow::Cow;
use std::format;
use std::string::String;
use std::vec::Vec;

use super::qzip::{grid_on, homotopy_on, reversal_on, Subject};
use super::{Case, Outcome, PairChoice};
use crate::qzip::{self, SketchOptions};
use crate::{gen, hybrid, Map};

/// The quad-dominant map a case is checked on: a case of triangles and quads (at least one
/// of each) as it is; a pure-quad case with two triangle pairs inserted
/// ([`gen::with_triangle_pairs`], eight random moves each); `None` for anything else
/// (pure triangle, other polygons) or when no pair fits.
fn hybrid_map(case: &Case) -> Option<Cow<'_, Map>> {
    let m = &case.mesh.map;
    let count = |k: usize| m.faces().filter(|&f| m.degree(f) == k).count();
    let (tris, quads) = (count(3), count(4));
    if quads == 0 || tris + quads != m.num_faces() {
        return None;
    }
    if tris > 0 {
        return Some(Cow::Borrowed(m));
    }
    let seed = case.rng(0x6879_6272).next_u64();
    let (mesh, tips) = gen::with_triangle_pairs(case.mesh.clone(), 2, 8, seed);
    (!tips.is_empty()).then_some(Cow::Owned(mesh.map))
}

impl<'c> Subject<'c> {
    /// The quad-dominant subject of a case ([`hybrid_map`]): singularities are the interior
    /// irregular vertices away from the triangles.
    fn hybrid(case: &'c Case) -> Option<Subject<'c>> {
        let map = hybrid_map(case)?;
        let near = hybrid::near_triangles(&map);
        let sing = map
            .vertices()
            .filter(|&v| {
                !map.is_boundary_vertex(v) && map.valence(v) != 4 && near.binary_search(&v).is_err()
            })
            .collect();
        let opts = qzip::avoid_triangles(&map, SketchOptions::default());
        Some(Subject {
            map,
            sing,
            opts,
            near: Some(near),
        })
    }
}

/// The triangles of `map`, each with its sorted corner valences.
fn corner_valences(map: &Map) -> Vec<(crate::Face, [usize; 3])> {
    hybrid::triangles(map)
        .into_iter()
        .map(|f| {
            let mut v = [0; 3];
            for (x, d) in v.iter_mut().zip(map.face_darts(f)) {
                *x = map.valence(map.origin(d));
            }
            v.sort_unstable();
            (f, v)
        })
        .collect()
}

/// Whether every triangle of `before` is still a triangle of `after` (same face handle)
/// with the same corner valences, and there are no others.
pub(super) fn triangles_kept(before: &Map, after: &Map) -> Result<(), String> {
    let (b, a) = (corner_valences(before), corner_valences(after));
    if a == b {
        return Ok(());
    }
    // Only the triangles that differ: a real mesh has dozens that do not.
    let changed: Vec<String> = b
        .iter()
        .filter(|t| !a.contains(t))
        .map(|&(f, v)| match a.iter().find(|&&(g, _)| g == f) {
            Some((_, w)) => format!("{f:?} {v:?} -> {w:?}"),
            None => format!("{f:?} {v:?} -> gone"),
        })
        .chain(
            a.iter()
                .filter(|&&(f, _)| !b.iter().any(|&(g, _)| g == f))
                .map(|(f, w)| format!("{f:?} new {w:?}")),
        )
        .collect();
    Err(format!(
        "the triangles changed (corner valences): {}",
        changed.join(", ")
    ))
}

/// `qzip-hybrid-grid`.
pub(super) fn grid(case: &Case, choice: PairChoice) -> Outcome {
    Subject::hybrid(case).map_or(Outcome::Skip, |s| grid_on(case, &s, choice))
}

/// `qzip-hybrid-reversal`.
pub(super) fn reversal(case: &Case, choice: PairChoice) -> Outcome {
    Subject::hybrid(case).map_or(Outcome::Skip, |s| reversal_on(case, &s, choice))
}

/// `qzip-hybrid-homotopy`.
pub(super) fn homotopy(case: &Case, choice: PairChoice) -> Outcome {
    Subject::hybrid(case).map_or(Outcome::Skip, |s| homotopy_on(case, &s, choice))
}

#[cfg(test)]
mod tests {
    use super::triangles_kept;
    use crate::Map;

    /// The message names only the triangle whose corner valences changed.
    #[test]
    fn a_changed_triangle_is_named_alone() {
        // Two triangles and a quad; a quad added on edge 3-4 raises the valences of 3 and 4,
        // corners of the second triangle only.
        let polys: [&[u32]; 3] = [&[0, 1, 2], &[2, 3, 4], &[1, 5, 3, 2]];
        let before = Map::from_polygons(6, &polys).unwrap();
        assert_eq!(triangles_kept(&before, &before), Ok(()));
        let more: [&[u32]; 4] = [&[0, 1, 2], &[2, 3, 4], &[1, 5, 3, 2], &[4, 3, 6, 7]];
        let after = Map::from_polygons(8, &more).unwrap();
        let e = triangles_kept(&before, &after).unwrap_err();
        assert!(e.ends_with(": f1 [2, 3, 4] -> [3, 4, 4]"), "{e}");
        assert!(!e.contains("f0"), "{e}");
    }
}
