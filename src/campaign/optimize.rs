//! The optimizer's property (Q-zip paper, Sec. 4.1): batches of Q-zips keep the mesh a valid
//! pure-quad map with the same Euler characteristic, boundary loops and components, and the
//! score never rises from one batch to the next. On quad-dominant cases (triangles and
//! quads) the triangle stage runs first: every pair merged takes two triangles, and no
//! face of another degree appears.

use super::{Case, Outcome, Property};
use crate::invariants::{Counts, MeshKind};
use crate::optimize::{optimize, Constraints, OptimizeOptions, SingularityCounts};
use std::format;

/// The largest case (faces) the property runs on; larger ones are skipped (and counted):
/// a batch costs about a millisecond per singularity.
pub const OPTIMIZE_MAX_FACES: usize = 400;

/// `optimize`: two batches on each quad or quad-dominant (triangles and quads) case of at
/// most [`OPTIMIZE_MAX_FACES`] faces.
///
/// ```
/// use zipmesh::campaign::{optimize_property, Case};
/// let case = Case::from_mesh(zipmesh::gen::subdivided_icosahedron(1), 0, 0, "ico");
/// assert!(optimize_property().check(&case).is_pass());
/// ```
pub fn optimize_property() -> Property {
    Property::new(
        "optimize",
        "two optimizer batches keep validity, pure quad (quad-dominant: triangles only by pairs merged), chi, boundary loops, components; the score never rises; the counts match",
        check,
    )
}

fn check(case: &Case) -> Outcome {
    let map = &case.mesh.map;
    let count = |k: usize| map.faces().filter(|&f| map.degree(f) == k).count();
    let (tris, quads) = (count(3), count(4));
    let fits = quads > 0 && tris + quads == map.num_faces();
    if !fits || map.num_faces() > OPTIMIZE_MAX_FACES {
        return Outcome::Skip;
    }
    let mut mesh = case.mesh.clone();
    let before = Counts::of(&mesh.map);
    let options = OptimizeOptions::default()
        .batches(2)
        .seed(case.seed ^ case.index);
    let out = match optimize(&mut mesh, Constraints::default(), options, |_| {}) {
        Ok(o) => o,
        Err(e) => return Outcome::fail(format!("refused a quad-dominant mesh: {e}"), None),
    };
    if let Err(v) = mesh.map.check() {
        return Outcome::fail(format!("invalid map: {v:?}"), None);
    }
    let after = Counts::of(&mesh.map);
    let kept = (
        after.euler_characteristic,
        after.boundary_loops,
        after.components,
    ) == (
        before.euler_characteristic,
        before.boundary_loops,
        before.components,
    );
    if !kept {
        return Outcome::fail(format!("topology changed: {before:?} -> {after:?}"), None);
    }
    let left = mesh
        .map
        .faces()
        .filter(|&f| mesh.map.degree(f) == 3)
        .count();
    if tris == 0 && MeshKind::of(&mesh.map) != MeshKind::Quad {
        return Outcome::fail("not pure quad any more", None);
    }
    let t = out.triangles;
    let accounted = tris.checked_sub(2 * t.merged) == Some(left);
    if t.input != tris || !accounted || out.final_counts.triangles != left {
        return Outcome::fail(format!("triangles: {tris} in, {left} out, {t:?}"), None);
    }
    if mesh
        .map
        .faces()
        .any(|f| !matches!(mesh.map.degree(f), 3 | 4))
    {
        return Outcome::fail("a face neither a quad nor a triangle", None);
    }
    let mut last = out.initial_score;
    for b in &out.batches {
        if b.score > last {
            return Outcome::fail(
                format!("batch {} raised the score {last} -> {}", b.batch, b.score),
                None,
            );
        }
        last = b.score;
    }
    if out.final_counts != SingularityCounts::of(&mesh) {
        return Outcome::fail("the reported counts differ from a recount", None);
    }
    Outcome::Pass {
        checks: 4 + out.batches.len() as u64,
    }
}
