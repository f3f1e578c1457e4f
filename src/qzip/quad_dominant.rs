//! Q-zip on quad-dominant maps (Sec. 3.2): the sketch keeps its paths off the triangles.

use super::SketchOptions;
use crate::map::Map;
use crate::quad_dominant;
use alloc::vec::Vec;

/// Sketch options for Q-zip on a quad-dominant map (Sec. 3.2, "wind the path around the
/// triangle"): `opts` with every triangle forbidden and every edge at a triangle's corner or
/// at a neighbour of one, so that a surgery path keeps two edges away from each triangle and
/// no quad the chain collapses or splits has a triangle corner. A movement whose end is
/// that close to a triangle finds no path (the triangle would have to move first).
///
/// ```
/// use zipmesh::{gen, qzip::{avoid_triangles, sketch, SketchOptions}};
/// let (mesh, tips) = gen::quad_dominant(12, 12, 1, 3);
/// let opts = avoid_triangles(&mesh.map, SketchOptions::default());
/// let tip = mesh.map.origin(tips[0]);
/// let far = mesh.map.vertices().find(|&v| v != tip).unwrap();
/// // A path may not reach the tip.
/// assert!(sketch(&mesh.map, far, tip, &opts).is_err());
/// ```
pub fn avoid_triangles<'a>(map: &Map, opts: SketchOptions<'a>) -> SketchOptions<'a> {
    let tris = quad_dominant::triangles(map);
    let near = quad_dominant::near_triangles(map);
    let edges: Vec<crate::map::Edge> = near
        .iter()
        .flat_map(|&v| map.vertex_darts(v).map(|d| d.edge()))
        .collect();
    opts.forbid_faces(tris).forbid_edges(edges)
}
