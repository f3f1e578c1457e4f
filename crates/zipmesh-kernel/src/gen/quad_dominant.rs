//! Quad-dominant meshes with the paper's triangles (Q-zip paper, Sec. 3.2): a quad mesh with
//! pairs of triangles inserted by splitting a quad along a diagonal and walking the two
//! halves apart.

use crate::map::{Dart, Face, Map, Vert};
use crate::mesh::Mesh;
use crate::quad_dominant::{self, Move};
use crate::rng::Rng;
use alloc::vec::Vec;

/// Whether `v` is a corner of a triangle or next to one.
fn near_triangle(map: &Map, v: Vert) -> bool {
    let on = |w: Vert| {
        map.vertex_darts(w)
            .any(|d| map.face(d).is_some_and(|f| map.degree(f) == 3))
    };
    on(v) || map.vertex_darts(v).any(|d| on(map.dest(d)))
}

/// Whether two triangles of `tips` share a vertex.
fn touching(map: &Map, tips: &[Dart]) -> bool {
    let corners = |t: Dart| [map.origin(t), map.dest(t), map.dest(map.next(t))];
    tips.iter().enumerate().any(|(i, &a)| {
        tips[i + 1..]
            .iter()
            .any(|&b| corners(a).iter().any(|v| corners(b).contains(v)))
    })
}

/// A quad whose corners are interior, of valence 4 and away from every triangle.
fn pick_quad(map: &Map, rng: &mut Rng) -> Option<Dart> {
    let faces: Vec<Face> = map.faces().collect();
    for _ in 0..64 {
        let f = *faces.get(rng.below(faces.len().max(1)))?;
        let d = map.face_darts(f).nth(rng.below(4))?;
        let corners: Vec<Vert> = map.face_darts(f).map(|d| map.origin(d)).collect();
        let fits = map.degree(f) == 4
            && corners.iter().all(|&v| {
                !map.is_boundary_vertex(v) && map.valence(v) == 4 && !near_triangle(map, v)
            });
        if fits && quad_dominant::can_split_quad(map, d).is_ok() {
            return Some(d);
        }
    }
    None
}

/// `mesh` with up to `pairs` triangle pairs, and the tip darts of all its triangles (two per
/// pair, in insertion order). Each pair: a quad with four regular interior corners, away
/// from the other triangles, is split along a diagonal ([`quad_dominant::split_quad`]); each half
/// makes one VE away from the other, so both are the paper's triangles (tip of valence 5,
/// two corners of valence 4, effective valences all kept); then `steps` random moves of
/// the pair's triangles follow, each kept only if no two triangles share a vertex after
/// it. Fewer pairs are made when no such quad is found in 64 tries. Deterministic in `seed`.
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant};
/// let (mesh, tips) = gen::with_triangle_pairs(gen::random_quad(300, 2, 0, 5), 2, 10, 9);
/// assert_eq!(mesh.map.check(), Ok(()));
/// assert_eq!(tips.len(), 4);
/// assert_eq!(quad_dominant::triangles(&mesh.map).len(), 4);
/// ```
pub fn with_triangle_pairs(
    mut mesh: Mesh,
    pairs: usize,
    steps: usize,
    seed: u64,
) -> (Mesh, Vec<Dart>) {
    let mut rng = Rng::new(seed);
    let mut tips: Vec<Dart> = Vec::new();
    for _ in 0..pairs {
        let Some(d) = pick_quad(&mesh.map, &mut rng) else {
            break;
        };
        let Ok(split) = quad_dominant::split_quad(&mut mesh.map, d) else {
            break;
        };
        let mut pair = split.tips();
        for t in &mut pair {
            if let Ok(e) = Move::VE.apply(&mut mesh, *t) {
                *t = e.record().tip();
            }
        }
        tips.extend(pair);
        for _ in 0..steps {
            let i = tips.len() - 2 + rng.below(2);
            let mv = Move::ALL[rng.below(4)];
            if let Ok(e) = mv.apply(&mut mesh, tips[i]) {
                let old = tips.clone();
                tips = tips.iter().map(|&d| e.record().follow(d)).collect();
                tips[i] = e.record().tip();
                if touching(&mesh.map, &tips) {
                    tips = old;
                    let _ = e.undo(&mut mesh);
                }
            }
        }
    }
    (mesh, tips)
}

/// The `nx` x `ny` torus grid (clamped to at least 3) with up to `pairs` triangle pairs
/// walked apart by `nx + ny` random moves each: [`with_triangle_pairs`].
///
/// ```
/// use zipmesh_kernel::{gen, quad_dominant};
/// let (mesh, tips) = gen::quad_dominant(8, 8, 1, 3);
/// for &t in &tips {
///     let m = &mesh.map;
///     let corners = [m.origin(t), m.dest(t), m.dest(m.next(t))].map(|v| m.valence(v));
///     assert_eq!(corners, [5, 4, 4]);
/// }
/// ```
pub fn quad_dominant(nx: usize, ny: usize, pairs: usize, seed: u64) -> (Mesh, Vec<Dart>) {
    with_triangle_pairs(super::torus_grid(nx, ny), pairs, nx + ny, seed)
}
