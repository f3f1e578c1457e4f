//! The Q-zip properties on quad-dominant meshes (Q-zip paper, Sec. 3.2): grid preservation,
//! reversal and homotopy with the paths winding around the triangles
//! ([`crate::qzip::avoid_triangles`]), and the triangles counted as what they are: every
//! triangle keeps its face and its corner valences, so the irregular valences of the quad
//! vertices are those of the input.

use std::borrow::Cow;
use std::vec::Vec;

use super::qzip::{grid_on, homotopy_on, quad_properties, reversal_on, with_choice, Subject};
use super::{Case, Outcome, PairChoice, Property};
use crate::qzip::{self, SketchOptions};
use crate::{gen, quad_dominant, Map};

/// The quad-dominant map a case is checked on: a case of triangles and quads (at least one
/// of each) as it is; a pure-quad case with two triangle pairs inserted
/// ([`gen::with_triangle_pairs`], eight random moves each); `None` for anything else
/// (pure triangle, other polygons) or when no pair fits.
fn quad_dominant_map(case: &Case) -> Option<Cow<'_, Map>> {
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
    /// The quad-dominant subject of a case ([`quad_dominant_map`]): singularities are the interior
    /// irregular vertices away from the triangles.
    fn quad_dominant(case: &'c Case) -> Option<Subject<'c>> {
        let map = quad_dominant_map(case)?;
        let near = quad_dominant::near_triangles(&map);
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

/// The Q-zip properties with this choice of pairs: `qzip-grid` (every movement done keeps
/// a valid pure-quad map with the same Euler characteristic, boundary loops and irregular
/// valences, moves the pair's valences, and undoes exactly; a refusal changes nothing),
/// `qzip-reversal` (the reverse run found restores the original up to isomorphism; a
/// movement with no reverse run found is counted in [`Row::unchecked`](super::Row::unchecked),
/// not failed),
/// `qzip-homotopy` (paths one swept quad apart give the same maps, labels matched by
/// [`start_turn`](crate::qzip::start_turn)), `qzip-four-moves` (in a regular region the movements done are pairwise
/// different); then the first three again on quad-dominant meshes (Sec. 3.2):
/// `qzip-quad-dominant-grid`, `qzip-quad-dominant-reversal`, `qzip-quad-dominant-homotopy`. These run on a case of
/// triangles and quads as it is, and on a pure-quad case with two triangle pairs inserted
/// ([`gen::with_triangle_pairs`](crate::gen::with_triangle_pairs)); the paths wind around the
/// triangles ([`avoid_triangles`](crate::qzip::avoid_triangles)); a movement done must
/// also keep every triangle (face handle and corner valences). Cases with other faces, or
/// whose triangles leave no pair of singularities a path can join, are skipped (the
/// `skipped` column); a swept path that comes near a triangle is not compared and is counted
/// in `qzip-quad-dominant-homotopy`'s `unchecked` column.
///
/// ```
/// use zipmesh::campaign::{qzip_properties, Case, PairChoice};
/// let case = Case::from_mesh(zipmesh::gen::subdivided_icosahedron(2), 0, 0, "ico");
/// let props = qzip_properties(PairChoice { max_distance: 4, per_case: Some(2) });
/// assert!(props[0].check(&case).is_pass()); // qzip-grid
/// for p in &props {
///     assert!(!p.check(&case).is_fail(), "{}", p.name());
/// }
/// ```
#[rustfmt::skip]
pub fn qzip_properties(choice: PairChoice) -> Vec<Property> {
    let mut all = quad_properties(choice);
    all.extend(with_choice(&[
        ("qzip-quad-dominant-grid", "on a quad-dominant mesh (triangle pairs inserted into a quad case), a Q-zip winding around the triangles keeps the grid and every triangle (face, corner valences) and undoes exactly", grid),
        ("qzip-quad-dominant-reversal", "on a quad-dominant mesh, the reverse Q-zip found restores the original up to isomorphism", reversal),
        ("qzip-quad-dominant-homotopy", "on a quad-dominant mesh, paths one swept quad apart (both away from the triangles) give the same maps", homotopy),
    ], choice));
    all
}

/// `qzip-quad-dominant-grid`.
pub(super) fn grid(case: &Case, choice: PairChoice) -> Outcome {
    Subject::quad_dominant(case).map_or(Outcome::Skip, |s| grid_on(case, &s, choice))
}

/// `qzip-quad-dominant-reversal`.
pub(super) fn reversal(case: &Case, choice: PairChoice) -> Outcome {
    Subject::quad_dominant(case).map_or(Outcome::Skip, |s| reversal_on(case, &s, choice))
}

/// `qzip-quad-dominant-homotopy`.
pub(super) fn homotopy(case: &Case, choice: PairChoice) -> Outcome {
    Subject::quad_dominant(case).map_or(Outcome::Skip, |s| homotopy_on(case, &s, choice))
}

#[cfg(test)]
mod tests {
    use super::super::qzip::triangles_kept;
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
