//! Subdivided solids: test meshes with lone irregular vertices in regular neighbourhoods
//! (v5 on the icosahedron, v3 on the tetrahedron, vk and v4 on a bipyramid), and lattice
//! cones (one vk at the centre of a disk).

use crate::map::Map;
use alloc::collections::BTreeMap;
use alloc::vec::Vec;

/// Cuts every triangle into four `levels` times (midpoint subdivision, connectivity only;
/// `levels` clamped to 5): the old vertices keep their valence, new ones are regular.
fn subdivide(mut tris: Vec<[u32; 3]>, mut n: u32, levels: usize) -> Map {
    for _ in 0..levels.min(5) {
        let mut mid = BTreeMap::new();
        let mut at = |a: u32, b: u32| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                n += 1;
                n - 1
            })
        };
        tris = tris
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (at(a, b), at(b, c), at(c, a));
                [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
            })
            .collect();
    }
    Map::from_polygons(n as usize, &tris).unwrap_or_default()
}

/// The icosahedron subdivided `levels` times (see [`subdivided_tetrahedron`]): 12 v5s
/// (vertices 0 to 11) `2^levels` edges apart, every other vertex regular.
///
/// ```
/// let s = zipmesh_kernel::gen::geodesic_sphere(2);
/// assert_eq!((s.num_vertices(), s.num_faces()), (162, 320));
/// assert_eq!(s.vertices().filter(|&v| s.valence(v) == 5).count(), 12);
/// ```
pub fn geodesic_sphere(levels: usize) -> Map {
    let tris: Vec<[u32; 3]> = crate::gen::icosahedron()
        .polygons()
        .iter()
        .filter_map(|p| Some([*p.first()?, *p.get(1)?, *p.get(2)?]))
        .collect();
    subdivide(tris, 12, levels)
}

/// The tetrahedron with every triangle cut into four `levels` times (connectivity only,
/// `levels` clamped to 5): four v3s (vertices 0 to 3), every other vertex regular.
///
/// ```
/// let t = zipmesh_kernel::gen::subdivided_tetrahedron(2);
/// assert_eq!(t.vertices().filter(|&v| t.valence(v) == 3).count(), 4);
/// ```
pub fn subdivided_tetrahedron(levels: usize) -> Map {
    subdivide(
        alloc::vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]],
        4,
        levels,
    )
}

/// The bipyramid over an `n`-gon (`n` clamped to 3..=64) subdivided `levels` times: two
/// apexes of valence `n` (vertices 0 and 1), `n` v4s (vertices 2 to n + 1), every other
/// vertex regular.
///
/// ```
/// let b = zipmesh_kernel::gen::subdivided_bipyramid(9, 2);
/// assert_eq!(b.valence(zipmesh_kernel::Vert::new(0)), 9);
/// assert_eq!(b.vertices().filter(|&v| b.valence(v) == 4).count(), 9);
/// ```
pub fn subdivided_bipyramid(n: usize, levels: usize) -> Map {
    let n = n.clamp(3, 64) as u32;
    let r = |i: u32| 2 + i % n;
    let tris = (0..n)
        .flat_map(|i| [[0, r(i), r(i + 1)], [1, r(i + 1), r(i)]])
        .collect();
    subdivide(tris, n + 2, levels)
}

/// The disk of the triangular lattice around a centre of valence `k`, out to ring `r`: the
/// cone of `k` lattice sectors (`k` and `r` clamped to 3..=64 and 1..=64). Vertex 0 is the
/// centre, ring `j` holds vertices `1 + k j (j - 1) / 2 ..` (`k j` of them, counter-clockwise,
/// corners first); every other interior vertex is regular, and the boundary is a convex
/// `k`-gon of side `r` (2 triangles at a corner, 3 elsewhere).
///
/// ```
/// let c = zipmesh_kernel::gen::cone_disk(7, 3);
/// assert_eq!((c.num_vertices(), c.num_faces()), (1 + 7 * 6, 7 * 9));
/// assert_eq!(c.valence(zipmesh_kernel::Vert::new(0)), 7);
/// let inner = c.vertices().filter(|&v| !c.is_boundary_vertex(v) && v.index() > 0);
/// assert!(inner.into_iter().all(|v| c.valence(v) == 6));
/// ```
pub fn cone_disk(k: usize, r: usize) -> Map {
    let (k, r) = (k.clamp(3, 64), r.clamp(1, 64));
    let ring = |j: usize, s: usize, t: usize| -> u32 {
        if j == 0 {
            return 0;
        }
        let (s, t) = if t == j { ((s + 1) % k, 0) } else { (s, t) };
        (1 + k * j * (j - 1) / 2 + s * j + t) as u32
    };
    let mut tris = Vec::new();
    for j in 1..=r {
        for s in 0..k {
            // Sector s between rings j - 1 and j: j triangles out, j - 1 back in.
            for t in 0..j {
                let inner = if j == 1 { 0 } else { ring(j - 1, s, t) };
                tris.push([inner, ring(j, s, t), ring(j, s, t + 1)]);
            }
            for t in 0..j.saturating_sub(1) {
                tris.push([ring(j - 1, s, t), ring(j, s, t + 1), ring(j - 1, s, t + 1)]);
            }
        }
    }
    let n = 1 + k * r * (r + 1) / 2;
    Map::from_polygons(n, &tris).unwrap_or_default()
}
