//! Quad-dominant meshes (Q-zip paper, Sec. 3.2): moving a triangle through a quad mesh by one
//! edge ([`walk`]: VE, EV, LE, RE), walking it to a vertex ([`compass`]), and merging two
//! triangles that meet ([`collide`], Fig. 15). Our reading of the section, with diagrams, is
//! in `docs/qzip.md` ("Triangles in quad meshes").
//!
//! The paper's triangles have one valence-5 corner, the **tip**, and two valence-4 corners.
//! A triangle is handled by its tip dart (the dart of the triangle leaving the tip), which
//! every move hands on, so the tip is never guessed again after the first time
//! ([`default_tip`]).
//!
//! **What is kept.** Count a triangle's extra corner against its tip: the *effective valence*
//! of a vertex is its valence minus the number of triangles whose tip it is. LE and RE keep
//! every effective valence; VE splits the tip (effective valence `k`) into a regular vertex
//! and one of effective valence `k`; EV merges the base corners, which keeps the multiset of
//! irregular effective valences when one of them is regular. So on the paper's triangles the
//! irregular valences of the quad vertices ([`irregular_effective`]) never change.
//!
//! ```
//! use zipmesh_kernel::{gen, quad_dominant::{self, Move}};
//! let (mut mesh, tips) = gen::quad_dominant(8, 8, 1, 3);
//! let before = quad_dominant::irregular_effective(&mesh.map, &tips);
//! assert!(before.is_empty()); // a torus grid with one triangle pair: nothing irregular
//! let r = quad_dominant::move_triangle(&mut mesh.map, tips[0], Move::VE).unwrap();
//! assert_eq!(quad_dominant::irregular_effective(&mesh.map, &[r.tip(), tips[1]]), before);
//! ```

use crate::map::{Dart, Face, Map, Vert};
use alloc::vec::Vec;

pub mod collide;
pub mod compass;
mod effect;
mod mesh;
mod patch;
pub mod walk;

pub use collide::{
    can_collapse_shared_base, can_merge_triangles, can_split_quad, collapse_shared_base, collision,
    merge_collision, merge_triangles, split_quad, Collision, QuadSplit, TriangleMerge,
};
pub use compass::{reverse_restores, walk_to, Walk, WalkError};
pub use walk::{can_move_triangle, move_triangle, probe_move, Move, TriangleMove, UnknownMove};

/// The tip dart of triangle `f` by valence: the dart of `f` leaving its corner of strictly
/// highest valence (the paper's v5 among two v4). `None` if `f` is not a live triangle or no
/// corner's valence is the highest alone.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant};
/// let (mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
/// let f = mesh.map.face(tips[0]).unwrap();
/// assert_eq!(quad_dominant::default_tip(&mesh.map, f), Some(tips[0]));
/// ```
pub fn default_tip(map: &Map, f: Face) -> Option<Dart> {
    if !map.is_live_face(f) || map.degree(f) != 3 {
        return None;
    }
    let darts: Vec<Dart> = map.face_darts(f).collect();
    let val = |d: &Dart| map.valence(map.origin(*d));
    let best = darts.iter().map(val).max()?;
    let mut top = darts.iter().filter(|d| val(d) == best);
    match (top.next(), top.next()) {
        (Some(&d), None) => Some(d),
        _ => None,
    }
}

/// The tip vertex of each tip dart (a vertex is counted once per triangle it tips).
fn tip_count(map: &Map, tips: &[Dart], v: Vert) -> usize {
    tips.iter().filter(|&&t| map.origin(t) == v).count()
}

/// The effective valence of `v`: its valence minus the number of triangles of `tips` (tip
/// darts) whose tip it is. See the [module docs](self).
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant};
/// let (mesh, tips) = gen::quad_dominant(6, 6, 1, 7);
/// let tip = mesh.map.origin(tips[0]);
/// assert_eq!(mesh.map.valence(tip), 5);
/// assert_eq!(quad_dominant::effective_valence(&mesh.map, &tips, tip), 4);
/// ```
pub fn effective_valence(map: &Map, tips: &[Dart], v: Vert) -> i64 {
    map.valence(v) as i64 - tip_count(map, tips, v) as i64
}

/// The irregular effective valences, sorted, each with whether its vertex is on the
/// boundary: every live vertex whose [`effective_valence`] is not 4 inside or 3 on the
/// boundary. See the [module docs](self) for an example.
pub fn irregular_effective(map: &Map, tips: &[Dart]) -> Vec<(i64, bool)> {
    let mut out: Vec<(i64, bool)> = map
        .vertices()
        .map(|v| (effective_valence(map, tips, v), map.is_boundary_vertex(v)))
        .filter(|&(k, b)| k != if b { 3 } else { 4 })
        .collect();
    out.sort_unstable();
    out
}

/// Every triangle of the map, as its face, in face order.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant};
/// let (mesh, _) = gen::quad_dominant(6, 6, 2, 7);
/// assert_eq!(quad_dominant::triangles(&mesh.map).len(), 4);
/// ```
pub fn triangles(map: &Map) -> Vec<Face> {
    map.faces().filter(|&f| map.degree(f) == 3).collect()
}

/// Every triangle corner and every neighbour of one, sorted: the vertices
/// Q-zip's `avoid_triangles` keeps every path off.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant};
/// let (mesh, tips) = gen::quad_dominant(12, 12, 1, 3);
/// let near = quad_dominant::near_triangles(&mesh.map);
/// assert!(near.contains(&mesh.map.origin(tips[0])));
/// ```
pub fn near_triangles(map: &Map) -> Vec<Vert> {
    let mut near = Vec::new();
    for f in triangles(map) {
        for d in map.face_darts(f) {
            let c = map.origin(d);
            near.push(c);
            near.extend(map.vertex_darts(c).map(|e| map.dest(e)));
        }
    }
    near.sort_unstable();
    near.dedup();
    near
}
