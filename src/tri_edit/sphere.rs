//! A geodesic sphere: the test mesh for edits around lone v5s.

use crate::map::Map;
use alloc::collections::BTreeMap;
use alloc::vec::Vec;

/// The icosahedron with every triangle cut into four `levels` times (midpoint subdivision,
/// connectivity only): 12 v5s (vertices 0 to 11) `2^levels` edges apart, every other vertex
/// regular. `levels` is clamped to 5 (10,242 vertices).
///
/// ```
/// let s = zipmesh::tri_edit::geodesic_sphere(2);
/// assert_eq!((s.num_vertices(), s.num_faces()), (162, 320));
/// assert_eq!(s.vertices().filter(|&v| s.valence(v) == 5).count(), 12);
/// ```
pub fn geodesic_sphere(levels: usize) -> Map {
    let mut tris: Vec<[u32; 3]> = crate::gen::icosahedron()
        .polygons()
        .iter()
        .filter_map(|p| Some([*p.first()?, *p.get(1)?, *p.get(2)?]))
        .collect();
    let mut n = 12u32;
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
