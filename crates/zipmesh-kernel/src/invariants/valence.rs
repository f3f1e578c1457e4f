use crate::map::{Map, Vert, NONE};
use alloc::collections::BTreeMap;
use alloc::vec::Vec;

/// Which regular valences a mesh is judged by.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::MeshKind};
/// assert_eq!(MeshKind::of(&gen::cube(2).map), MeshKind::Quad);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshKind {
    /// Every face is a triangle: regular is 6 inside, 4 on the boundary.
    Triangle,
    /// Every face is a quad: regular is 4 inside, 3 on the boundary.
    Quad,
    /// Faces of other or mixed degrees. Judged by the quad rule (4 inside, 3 on the
    /// boundary), which is what quad-dominant meshes mean by regular.
    Mixed,
}

impl MeshKind {
    /// The kind of `map`, from its face degrees (an empty map is `Mixed`).
    ///
    /// ```
    /// use zipmesh_kernel::{invariants::MeshKind, Map};
    /// let tri = Map::from_polygons(3, &[[0u32, 1, 2]]).unwrap();
    /// assert_eq!(MeshKind::of(&tri), MeshKind::Triangle);
    /// ```
    pub fn of(map: &Map) -> MeshKind {
        let mut degrees = map.faces().map(|f| map.degree(f));
        match degrees.next() {
            Some(3) if degrees.all(|d| d == 3) => MeshKind::Triangle,
            Some(4) if degrees.all(|d| d == 4) => MeshKind::Quad,
            _ => MeshKind::Mixed,
        }
    }
}

/// The regular valence of an interior (`boundary == false`) or boundary vertex.
///
/// Boundary rule: a regular boundary vertex sits on a straight stretch of boundary, where half
/// of the interior fan fits: 3 edges for quads (two boundary edges and one inner edge), 4 for
/// triangles. With these values the boundary Gauss-Bonnet identity holds (see [`gauss_bonnet`](super::gauss_bonnet)).
///
/// ```
/// use zipmesh_kernel::invariants::{regular_valence, MeshKind};
/// assert_eq!(regular_valence(MeshKind::Quad, false), 4);
/// assert_eq!(regular_valence(MeshKind::Triangle, true), 4);
/// ```
pub fn regular_valence(kind: MeshKind, boundary: bool) -> usize {
    match (kind, boundary) {
        (MeshKind::Triangle, false) => 6,
        (MeshKind::Triangle, true) => 4,
        (_, false) => 4,
        (_, true) => 3,
    }
}

/// Whether `v` is irregular (a singularity) under the rule of `kind`.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::{is_irregular, MeshKind}, Vert};
/// let torus = gen::torus_grid(4, 4).map;
/// assert!(!is_irregular(&torus, MeshKind::Quad, Vert::new(0)));
/// ```
pub fn is_irregular(map: &Map, kind: MeshKind, v: Vert) -> bool {
    map.is_live_vertex(v) && map.valence(v) != regular_valence(kind, map.is_boundary_vertex(v))
}

/// Whether `v` is a live interior vertex of regular valence under the rule of `kind`: the
/// vertices a quad sweep or a grid-preserving edit may pass through unchanged.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::{is_regular_interior, MeshKind}, Vert};
/// let grid = gen::grid(2, 2).map;
/// assert!(is_regular_interior(&grid, MeshKind::Quad, Vert::new(4))); // the centre
/// assert!(!is_regular_interior(&grid, MeshKind::Quad, Vert::new(1))); // on the boundary
/// ```
pub fn is_regular_interior(map: &Map, kind: MeshKind, v: Vert) -> bool {
    map.is_live_vertex(v)
        && !map.is_boundary_vertex(v)
        && map.valence(v) == regular_valence(kind, false)
}

/// Every irregular vertex of `map` under the rule of `kind`, in slot order.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::{irregular_vertices, MeshKind}};
/// let cube = gen::cube(2).map;
/// assert_eq!(irregular_vertices(&cube, MeshKind::Quad).len(), 8); // the corners, valence 3
/// ```
pub fn irregular_vertices(map: &Map, kind: MeshKind) -> Vec<Vert> {
    map.vertices()
        .filter(|&v| is_irregular(map, kind, v))
        .collect()
}

/// The irregular vertices as a sorted multiset of (valence, on the boundary): what a
/// grid-preserving edit such as Q-zip must keep (it moves singularities, never makes or
/// removes one).
///
/// ```
/// use zipmesh_kernel::{gen, invariants::{irregular_valences, MeshKind}};
/// let cube = gen::cube(2).map;
/// assert_eq!(irregular_valences(&cube, MeshKind::Quad), vec![(3, false); 8]);
/// ```
pub fn irregular_valences(map: &Map, kind: MeshKind) -> Vec<(usize, bool)> {
    let mut v: Vec<(usize, bool)> = irregular_vertices(map, kind)
        .into_iter()
        .map(|v| (map.valence(v), map.is_boundary_vertex(v)))
        .collect();
    v.sort_unstable();
    v
}

/// Valence and face-degree histograms (value to count).
///
/// ```
/// use zipmesh_kernel::{gen, invariants::Histograms};
/// let h = Histograms::of(&gen::grid(1, 1).map);
/// assert_eq!(h.boundary_valences.get(&2), Some(&4));
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Histograms {
    /// Face degree to number of faces.
    pub face_degrees: BTreeMap<usize, usize>,
    /// Valence to number of interior vertices.
    pub interior_valences: BTreeMap<usize, usize>,
    /// Valence to number of boundary vertices.
    pub boundary_valences: BTreeMap<usize, usize>,
}

impl Histograms {
    /// Computes the three histograms in O(darts). Valence counts darts leaving a vertex, so
    /// a loop counts twice; without loops it is the number of distinct edges at the vertex.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, invariants::Histograms};
    /// let h = Histograms::of(&gen::torus_grid(5, 4).map);
    /// assert_eq!(h.interior_valences.get(&4), Some(&20));
    /// assert_eq!(h.face_degrees.get(&4), Some(&20));
    /// assert!(h.boundary_valences.is_empty());
    /// ```
    pub fn of(map: &Map) -> Histograms {
        let mut h = Histograms::default();
        let mut valence = alloc::vec![0usize; map.vdart.len()];
        let mut degree = alloc::vec![0usize; map.fdart.len()];
        for d in 0..map.next.len() {
            if map.next[d] != NONE {
                valence[map.vert[d] as usize] += 1;
                if map.face[d] != NONE {
                    degree[map.face[d] as usize] += 1;
                }
            }
        }
        for v in map.vertices() {
            let which = if map.is_boundary_vertex(v) {
                &mut h.boundary_valences
            } else {
                &mut h.interior_valences
            };
            *which.entry(valence[v.index()]).or_default() += 1;
        }
        for f in map.faces() {
            *h.face_degrees.entry(degree[f.index()]).or_default() += 1;
        }
        h
    }
}
