use crate::map::{Map, NONE};
use alloc::vec;
use alloc::vec::Vec;

/// Element counts and the topological invariants derived from them.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::Counts};
/// let c = Counts::of(&gen::grid(2, 2).map);
/// assert_eq!((c.vertices, c.edges, c.faces, c.euler_characteristic), (9, 12, 4, 1));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Counts {
    /// Live vertices.
    pub vertices: usize,
    /// Live edges.
    pub edges: usize,
    /// Live faces.
    pub faces: usize,
    /// Boundary loops (cycles of boundary darts).
    pub boundary_loops: usize,
    /// Connected components.
    pub components: usize,
    /// `V - E + F`.
    pub euler_characteristic: i64,
    /// Sum over components of `(2 - chi_c - b_c) / 2`; every valid map is an orientable
    /// surface, so each term is a whole number.
    pub genus: i64,
}

/// The Euler characteristic `V - E + F`, in O(1) from the live counts.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::euler_characteristic};
/// assert_eq!(euler_characteristic(&gen::cube(3).map), 2);
/// assert_eq!(euler_characteristic(&gen::torus_grid(5, 4).map), 0);
/// ```
pub fn euler_characteristic(map: &Map) -> i64 {
    map.num_vertices() as i64 - map.num_edges() as i64 + map.num_faces() as i64
}

impl Counts {
    /// Computes every count in O(darts · α).
    ///
    /// ```
    /// use zipmesh_kernel::{invariants::Counts, Map};
    /// let disk = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// let c = Counts::of(&disk);
    /// assert_eq!((c.vertices, c.edges, c.faces, c.boundary_loops), (4, 4, 1, 1));
    /// assert_eq!((c.euler_characteristic, c.components, c.genus), (1, 1, 0));
    /// ```
    pub fn of(map: &Map) -> Counts {
        let (vcomp, n_comp) = vertex_components(map);
        // Per component: V - E + F + b, from which chi and genus follow.
        let mut chi_b = vec![0i64; n_comp];
        for c in vcomp.iter().filter(|&&c| c != NONE) {
            chi_b[*c as usize] += 1;
        }
        let comp_of_dart = |d: usize| vcomp[map.vert[d] as usize] as usize;
        for &d in map.fdart.iter().filter(|&&d| d != NONE) {
            chi_b[comp_of_dart(d as usize)] += 1;
        }
        let mut boundary_darts = 0usize;
        for e in 0..map.next.len() / 2 {
            let d = 2 * e;
            if map.next[d] != NONE {
                chi_b[comp_of_dart(d)] -= 1;
                boundary_darts +=
                    usize::from(map.face[d] == NONE) + usize::from(map.face[d + 1] == NONE);
            }
        }
        let mut loops = 0;
        if boundary_darts > 0 {
            let mut seen = vec![0u64; map.next.len().div_ceil(64)];
            for d in 0..map.next.len() {
                if map.next[d] == NONE || map.face[d] != NONE || seen[d / 64] >> (d % 64) & 1 == 1 {
                    continue;
                }
                loops += 1;
                chi_b[comp_of_dart(d)] += 1;
                let mut x = d;
                while seen[x / 64] >> (x % 64) & 1 == 0 {
                    seen[x / 64] |= 1 << (x % 64);
                    x = map.next[x] as usize;
                }
            }
        }
        let genus = chi_b.iter().map(|&s| (2 - s) / 2).sum();
        Counts {
            vertices: map.num_vertices(),
            edges: map.num_edges(),
            faces: map.num_faces(),
            boundary_loops: loops,
            components: n_comp,
            euler_characteristic: euler_characteristic(map),
            genus,
        }
    }
}

/// Component number of every vertex slot (`NONE` for dead slots), numbered in slot order of
/// each component's first vertex, and the number of components. Union-find over the edges.
pub(crate) fn vertex_components(map: &Map) -> (Vec<u32>, usize) {
    let nv = map.vdart.len();
    let mut parent: Vec<u32> = (0..nv as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let p = parent[x as usize];
            parent[x as usize] = parent[p as usize];
            x = p;
        }
        x
    }
    for e in 0..map.next.len() / 2 {
        if map.next[2 * e] == NONE {
            continue;
        }
        let a = find(&mut parent, map.vert[2 * e]);
        let b = find(&mut parent, map.vert[2 * e + 1]);
        if a != b {
            // Point the larger root at the smaller: roots stay the first vertex of a component.
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            parent[hi as usize] = lo;
        }
    }
    let mut comp = vec![NONE; nv];
    let mut n = 0u32;
    for v in 0..nv {
        if map.vdart[v] == NONE {
            continue;
        }
        let r = find(&mut parent, v as u32) as usize;
        if comp[r] == NONE {
            comp[r] = n;
            n += 1;
        }
        comp[v] = comp[r];
    }
    (comp, n as usize)
}

/// The number of edges that keep the map from being a simple graph: every loop, plus every
/// edge beyond the first between the same two vertices. Zero for a simple mesh; operators
/// that neither create nor remove loops and multi-edges keep it unchanged.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::non_simple_edges, Map};
/// assert_eq!(non_simple_edges(&gen::torus_grid(4, 4).map), 0);
/// // Two triangles glued into a sphere: still one edge per pair of vertices.
/// let m = Map::from_polygons(3, &[[0u32, 1, 2], [2, 1, 0]]).unwrap();
/// assert_eq!(non_simple_edges(&m), 0);
/// let loop_map = Map::from_permutation(&[0, 1], &[false, false]).unwrap(); // one loop
/// assert_eq!(non_simple_edges(&loop_map), 1);
/// ```
pub fn non_simple_edges(map: &Map) -> usize {
    let mut pairs: Vec<(u32, u32)> = (0..map.next.len() / 2)
        .filter(|&e| map.next[2 * e] != NONE)
        .map(|e| {
            let (a, b) = (map.vert[2 * e], map.vert[2 * e + 1]);
            (a.min(b), a.max(b))
        })
        .collect();
    let loops = pairs.iter().filter(|(a, b)| a == b).count();
    let n = pairs.len();
    pairs.sort_unstable();
    pairs.dedup();
    loops + n - pairs.len()
}
