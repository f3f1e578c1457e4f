//! Subdivided solids: test meshes with lone irregular vertices in regular neighbourhoods
//! (v5 on the icosahedron, v3 on the tetrahedron, vk and v4 on a bipyramid).

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
/// let s = zipmesh::gen::geodesic_sphere(2);
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
/// let t = zipmesh::gen::subdivided_tetrahedron(2);
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
/// let b = zipmesh::gen::subdivided_bipyramid(9, 2);
/// assert_eq!(b.valence(zipmesh::Vert::new(0)), 9);
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
