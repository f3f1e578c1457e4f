//! Q-zip benchmark fixtures shared by `benches/qzip.rs` and `examples/workload.rs`: the
//! n x n torus with singularity pairs inserted at a chosen distance.

use zipmesh::ops::quad;
use zipmesh::{gen, Map, Vert};

/// The vertex `(i, j)` of the `n` x `n` torus grid (coordinates taken mod `n`).
fn at(n: usize, i: usize, j: usize) -> Vert {
    Vert::new(((j % n) * n + i % n) as u32)
}

/// Splits the regular vertex `v` along its edges to `a` and to `b` (opposite neighbours).
fn split(map: &mut Map, v: Vert, a: Vert, b: Vert) {
    let dart_to = |m: &Map, w: Vert| m.vertex_darts(v).find(|&d| m.dest(d) == w);
    let (s1, s2) = (dart_to(map, a), dart_to(map, b));
    let (Some(s1), Some(s2)) = (s1, s2) else {
        panic!("({}) is not next to both neighbours", v.index());
    };
    quad::vertex_split(map, s1, s2).expect("split of a regular vertex along opposite edges");
}

/// The `n` x `n` torus with `pairs` singularity pairs, each on its own row (rows `n / pairs`
/// apart), returned with the `(v5, v3)` ends of each pair, `len` edges apart along the row.
///
/// A vertex split of a regular vertex along its east and west edges makes the two copies v3s
/// and the two far ends of the split edges v5s (a cluster of four). Cluster A is the split of
/// `(x, y)`, cluster B the split of `(x + len + 1, y)`; the pair is A's east v5 `(x + 1, y)`
/// and B's v3 that keeps the handle of `(x + len + 1, y)`. The shortest path between them is
/// the straight row, `len` edges, passing through B's west v5 just before its end.
pub fn torus_with_pairs(n: usize, pairs: usize, len: usize) -> (Map, Vec<(Vert, Vert)>) {
    assert!(
        len + 20 < n && pairs > 0 && pairs * 8 <= n,
        "torus too small"
    );
    let mut map = gen::torus_grid(n, n).map;
    let mut ends = Vec::with_capacity(pairs);
    for p in 0..pairs {
        let (x, y) = (10 + 3 * p, 5 + p * (n / pairs));
        let xb = x + len + 1;
        for c in [x, xb] {
            split(&mut map, at(n, c, y), at(n, c + 1, y), at(n, c + n - 1, y));
        }
        let (v5, v3) = (at(n, x + 1, y), at(n, xb, y));
        assert_eq!((map.valence(v5), map.valence(v3)), (5, 3));
        ends.push((v5, v3));
    }
    (map, ends)
}
