//! Q-zip benchmark fixtures shared by `benches/qzip.rs` and `examples/workload.rs`: the
//! n x n torus with singularity pairs inserted at a chosen distance.

use zipmesh::ops::quad;
use zipmesh::{gen, Map, Mesh, Vert};

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
    quad::split_vertex(map, s1, s2).expect("split of a regular vertex along opposite edges");
}

/// The `n` x `n` torus with `pairs` singularity pairs, each on its own row (rows `n / pairs`
/// apart), returned with the `(v5, v3)` ends of each pair, `len` edges apart along the row.
///
/// A vertex split of a regular vertex along its east and west edges makes the two copies v3s
/// and the two far ends of the split edges v5s (a cluster of four). Cluster A is the split of
/// `(x, y)`, cluster B the split of `(x + len + 1, y)`; the pair is A's east v5 `(x + 1, y)`
/// and B's v3 that keeps the handle of `(x + len + 1, y)`. The shortest path between them is
/// the straight row, `len` edges, passing through B's west v5 just before its end (needs
/// `n > 2 len + 20`, so the way round the other side is longer).
#[allow(dead_code)] // each includer uses one of the two forms
pub fn torus_with_pairs(n: usize, pairs: usize, len: usize) -> (Map, Vec<(Vert, Vert)>) {
    let (mesh, ends) = torus_mesh_with_pairs(n, pairs, len);
    (mesh.map, ends)
}

/// [`torus_with_pairs`] with positions: the torus of `gen::torus_grid` (radii 2 and 0.75),
/// the new copy made by each vertex split at the point of the vertex it was split from (so no
/// edge is longer than on the plain torus).
#[allow(dead_code)]
pub fn torus_mesh_with_pairs(n: usize, pairs: usize, len: usize) -> (Mesh, Vec<(Vert, Vert)>) {
    // The row must be the only shortest way round: the other way is n - len edges.
    assert!(
        2 * len + 20 < n && pairs > 0 && pairs * 8 <= n,
        "torus too small"
    );
    let mut mesh = gen::torus_grid(n, n);
    let mut ends = Vec::with_capacity(pairs);
    for p in 0..pairs {
        let (x, y) = (10 + 3 * p, 5 + p * (n / pairs));
        let xb = x + len + 1;
        for c in [x, xb] {
            let v = at(n, c, y);
            let old = mesh.map.vertex_slots();
            split(&mut mesh.map, v, at(n, c + 1, y), at(n, c + n - 1, y));
            let copy = mesh.positions[v.index()];
            mesh.positions.resize(mesh.map.vertex_slots(), copy);
            assert_eq!(mesh.map.vertex_slots(), old + 1, "one new vertex per split");
        }
        let (v5, v3) = (at(n, x + 1, y), at(n, xb, y));
        assert_eq!((mesh.map.valence(v5), mesh.map.valence(v3)), (5, 3));
        ends.push((v5, v3));
    }
    (mesh, ends)
}

/// A flat layout of [`torus_mesh_with_pairs`]'s vertices for `qzip::Guide`, with its bound
/// on the edge length (measured, so the guide is exact): vertex `(i, j)` at
/// `(r cos(2 pi i / n), r sin(2 pi i / n), min(j, n - j))` with `2 r sin(pi / n) = 1`, so a
/// step along a row or a column moves at most 1 and the row direction wraps without a seam;
/// a split's new copy at the point of the vertex it was split from. Not the torus's geometry:
/// points chosen so that `|p(v) - p(to)|` is close to the number of edges along rows (the
/// guide needs only the bound, see `qzip::Guide`).
#[allow(dead_code)]
pub fn flat_layout(n: usize, mesh: &Mesh) -> (Vec<glam::DVec3>, f64) {
    let r = 0.5 / (core::f64::consts::PI / n as f64).sin();
    let map = &mesh.map;
    let point = |v: usize| {
        let (i, j) = (v % n, v / n);
        let a = core::f64::consts::TAU * i as f64 / n as f64;
        glam::DVec3::new(r * a.cos(), r * a.sin(), j.min(n - j) as f64)
    };
    let mut p: Vec<glam::DVec3> = (0..n * n).map(point).collect();
    // The copies, in split order, each at the point of the vertex it came from.
    for v in n * n..map.vertex_slots() {
        let twin = mesh.positions[v];
        let from = (0..n * n).find(|&u| mesh.positions[u] == twin);
        p.push(from.map_or(glam::DVec3::ZERO, point));
    }
    let laid = Mesh {
        map: map.clone(),
        positions: p,
    };
    let bound = zipmesh::qzip::max_edge_length(&laid);
    (laid.positions, bound)
}
