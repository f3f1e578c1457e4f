use crate::map::{Map, NONE};
use alloc::vec;
use alloc::vec::Vec;

/// Element counts and the topological invariants derived from them.
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

impl Counts {
    /// Computes every count in O(darts).
    ///
    /// ```
    /// use zipmesh::{invariants::Counts, Map};
    /// let disk = Map::from_polygons(4, &[[0u32, 1, 2, 3]]).unwrap();
    /// let c = Counts::of(&disk);
    /// assert_eq!((c.vertices, c.edges, c.faces, c.boundary_loops), (4, 4, 1, 1));
    /// assert_eq!((c.euler_characteristic, c.components, c.genus), (1, 1, 0));
    /// ```
    pub fn of(map: &Map) -> Counts {
        let comp = component_of_darts(map);
        let n_comp = comp
            .iter()
            .filter(|&&c| c != NONE)
            .max()
            .map_or(0, |&m| m as usize + 1);
        // Per component: V - E + F + b, from which chi and genus follow.
        let mut chi_b = vec![0i64; n_comp];
        for &d in map.vdart.iter().filter(|&&d| d != NONE) {
            chi_b[comp[d as usize] as usize] += 1;
        }
        for &d in map.fdart.iter().filter(|&&d| d != NONE) {
            chi_b[comp[d as usize] as usize] += 1;
        }
        let mut seen = vec![false; map.next.len()];
        let mut loops = 0;
        for d in 0..map.next.len() {
            if map.next[d] == NONE {
                continue;
            }
            let c = comp[d] as usize;
            if d % 2 == 0 {
                chi_b[c] -= 1;
            }
            if map.face[d] == NONE && !seen[d] {
                loops += 1;
                chi_b[c] += 1;
                let mut x = d;
                while !seen[x] {
                    seen[x] = true;
                    x = map.next[x] as usize;
                }
            }
        }
        let genus = chi_b.iter().map(|&s| (2 - s) / 2).sum();
        let (vertices, edges, faces) = (map.num_vertices(), map.num_edges(), map.num_faces());
        Counts {
            vertices,
            edges,
            faces,
            boundary_loops: loops,
            components: n_comp,
            euler_characteristic: vertices as i64 - edges as i64 + faces as i64,
            genus,
        }
    }
}

/// Component number of every dart (`NONE` for dead darts), numbered in order of smallest dart.
pub(crate) fn component_of_darts(map: &Map) -> Vec<u32> {
    let nd = map.next.len();
    let mut comp = vec![NONE; nd];
    let mut stack = Vec::new();
    let mut n = 0u32;
    for s in 0..nd {
        if map.next[s] == NONE || comp[s] != NONE {
            continue;
        }
        comp[s] = n;
        stack.push(s as u32);
        while let Some(d) = stack.pop() {
            for x in [map.next[d as usize], d ^ 1] {
                if comp[x as usize] == NONE {
                    comp[x as usize] = n;
                    stack.push(x);
                }
            }
        }
        n += 1;
    }
    comp
}
