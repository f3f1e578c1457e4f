//! Generators of test meshes (feature `testkit`): grids, tori, boxes, Catmull-Clark
//! refinement and random meshes.
//!
//! Every generator is deterministic; the random ones take a seed.

use crate::mesh::Mesh;
use alloc::vec::Vec;
use glam::DVec3;

mod catmull_clark;
mod quad_dominant;
mod random;
mod solids;

pub use catmull_clark::catmull_clark;
pub use quad_dominant::{quad_dominant, with_triangle_pairs};
pub use random::{random_mixed, random_quad, random_triangle, MAX_RANDOM_FACES, MAX_RANDOM_GENUS};
pub use solids::{cone_disk, geodesic_sphere, subdivided_bipyramid, subdivided_tetrahedron};

/// An `nx` x `ny` grid of quads in the plane z = 0: a disk with one boundary loop.
/// `nx` and `ny` are clamped to at least 1.
///
/// ```
/// let g = zipmesh_kernel::gen::grid(3, 2);
/// assert_eq!((g.map.num_vertices(), g.map.num_faces()), (12, 6));
/// ```
pub fn grid(nx: usize, ny: usize) -> Mesh {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut positions = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            positions.push(DVec3::new(i as f64, j as f64, 0.0));
        }
    }
    let mut faces = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    build(positions, &faces)
}

/// An `nx` x `ny` quad grid on a torus (genus 1, every vertex of valence 4).
/// `nx` and `ny` are clamped to at least 3 so that the map has no multi-edges.
///
/// ```
/// let t = zipmesh_kernel::gen::torus_grid(4, 3);
/// assert_eq!((t.map.num_vertices(), t.map.num_edges(), t.map.num_faces()), (12, 24, 12));
/// ```
pub fn torus_grid(nx: usize, ny: usize) -> Mesh {
    let (nx, ny) = (nx.max(3), ny.max(3));
    build(torus_positions(nx, ny), &torus_quads(nx, ny))
}

/// The quads of the `nx` x `ny` torus grid as vertex index lists (counter-clockwise),
/// vertex `(i, j)` numbered `j * nx + i`, quad `(i, j)` at position `j * nx + i`: the polygon
/// list behind [`torus_grid`], for callers that build maps themselves (benchmarks, tests).
/// `nx` and `ny` are clamped to at least 3.
///
/// ```
/// let quads = zipmesh_kernel::gen::torus_quads(4, 3);
/// assert_eq!(quads.len(), 12);
/// assert!(zipmesh_kernel::Map::from_polygons(12, &quads).is_ok());
/// ```
pub fn torus_quads(nx: usize, ny: usize) -> Vec<[u32; 4]> {
    let (nx, ny) = (nx.max(3), ny.max(3));
    let id = |i: usize, j: usize| ((j % ny) * nx + (i % nx)) as u32;
    let mut faces = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    faces
}

pub(crate) fn torus_positions(nx: usize, ny: usize) -> Vec<DVec3> {
    let (big, small) = (2.0, 0.75);
    let tau = core::f64::consts::TAU;
    let mut positions = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        let b = tau * j as f64 / ny as f64;
        for i in 0..nx {
            let a = tau * i as f64 / nx as f64;
            let r = big + small * libm::cos(b);
            positions.push(DVec3::new(
                r * libm::cos(a),
                r * libm::sin(a),
                small * libm::sin(b),
            ));
        }
    }
    positions
}

/// The surface of a cube with each side cut into `n` x `n` quads (genus 0; the eight
/// corners have valence 3). `n` is clamped to at least 1.
///
/// ```
/// let c = zipmesh_kernel::gen::cube(2);
/// assert_eq!((c.map.num_vertices(), c.map.num_faces()), (26, 24));
/// ```
pub fn cube(n: usize) -> Mesh {
    let n = n.max(1);
    let m = n + 1;
    let mut index = alloc::vec![u32::MAX; m * m * m];
    let mut positions = Vec::new();
    let on_surface = |c: [usize; 3]| c.iter().any(|&x| x == 0 || x == n);
    for z in 0..m {
        for y in 0..m {
            for x in 0..m {
                if on_surface([x, y, z]) {
                    index[(z * m + y) * m + x] = positions.len() as u32;
                    positions.push(DVec3::new(x as f64, y as f64, z as f64) / n as f64);
                }
            }
        }
    }
    let at = |c: [usize; 3]| index[(c[2] * m + c[1]) * m + c[0]];
    let mut faces = Vec::with_capacity(6 * n * n);
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, n] {
            for j in 0..n {
                for i in 0..n {
                    let corner = |di: usize, dj: usize| {
                        let mut c = [0; 3];
                        c[axis] = side;
                        c[u] = i + di;
                        c[v] = j + dj;
                        at(c)
                    };
                    // (u, v, axis) is right-handed, so counter-clockwise in (u, v) faces +axis.
                    let q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                    faces.push(if side == n {
                        q
                    } else {
                        [q[0], q[3], q[2], q[1]]
                    });
                }
            }
        }
    }
    build(positions, &faces)
}

/// The regular icosahedron: 12 vertices of valence 5, 20 triangles (genus 0).
///
/// Its Catmull-Clark subdivisions are quad meshes with 12 isolated v5s (the icosahedron's
/// vertices) and 20 isolated v3s (its face centres), `2^(levels - 1)` edges apart: the test
/// bed for moving singularity pairs.
///
/// ```
/// use zipmesh_kernel::gen::{catmull_clark, icosahedron};
/// let ico = icosahedron();
/// assert_eq!((ico.map.num_vertices(), ico.map.num_faces()), (12, 20));
/// let q = catmull_clark(&catmull_clark(&ico));
/// let valence = |k| q.map.vertices().filter(|&v| q.map.valence(v) == k).count();
/// assert_eq!((valence(3), valence(5)), (20, 12));
/// ```
pub fn icosahedron() -> Mesh {
    let t = (1.0 + libm::sqrt(5.0)) / 2.0;
    let positions: Vec<DVec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|p| DVec3::from_array(*p))
    .collect();
    let faces: [[u32; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    build(positions, &faces)
}

/// The icosahedron after `levels` Catmull-Clark steps: 12 v5s (vertices 0 to 11, the
/// icosahedron's vertices) and, for `levels >= 1`, 20 v3s (vertices 42 to 61, its face
/// centres, face `f` at `42 + f`), `2^(levels - 1)` edges from their neighbours, the rest
/// regular. With two levels, vertex 0 (v5) and vertex 42 (v3) are four edges apart.
///
/// ```
/// use zipmesh_kernel::{gen, Vert};
/// let m = gen::subdivided_icosahedron(2).map;
/// assert_eq!((m.valence(Vert::new(0)), m.valence(Vert::new(42))), (5, 3));
/// assert_eq!(m.num_faces(), 20 * 3 * 4);
/// ```
pub fn subdivided_icosahedron(levels: usize) -> Mesh {
    let mut mesh = icosahedron();
    for _ in 0..levels {
        mesh = catmull_clark(&mesh);
    }
    mesh
}

/// Builds a generated mesh; generators only produce valid polygon lists.
fn build<F: AsRef<[u32]>>(positions: Vec<DVec3>, faces: &[F]) -> Mesh {
    match Mesh::from_polygons(positions, faces) {
        Ok((mesh, _)) => mesh,
        // Unreachable for the generators above; an empty mesh keeps the API panic-free.
        Err(_) => Mesh::default(),
    }
}
