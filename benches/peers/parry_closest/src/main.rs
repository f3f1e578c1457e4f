//! Closest-point queries on a quad mesh's surface (each face fanned from its first corner):
//! zipmesh's `optimize::Surface` against parry3d-f64's `TriMesh` (0.21 and 0.31), on every
//! vertex of the mesh (distance 0) and on every vertex moved off the surface by up to 1% of
//! the bounding-box diagonal (what an edited mesh asks). Prints the median of 5 builds and
//! of 5 query passes, and the largest difference of the distances found. Distances are
//! taken from the projected point (parry's `distance_to_local_point` is negative for a
//! point it reads as inside).

use std::time::Instant;

use glam::DVec3;
use parry21::query::PointQuery as _;
use parry31::query::PointQuery as _;
use zipmesh::optimize::Surface;

/// The faces as triangles fanned from their first corner, as `Surface` reads them.
fn fan(mesh: &zipmesh::Mesh) -> Vec<[u32; 3]> {
    let mut t = Vec::new();
    for f in mesh.map.faces() {
        let c: Vec<u32> = mesh
            .map
            .face_darts(f)
            .map(|d| mesh.map.origin(d).index() as u32)
            .collect();
        for k in 1..c.len().saturating_sub(1) {
            t.push([c[0], c[k], c[k + 1]]);
        }
    }
    t
}

/// A fixed sequence in [-0.5, 0.5) (xorshift), so each run asks the same points.
fn offsets(n: usize, size: f64) -> Vec<DVec3> {
    let mut s = 0x9E37_79B9_7F4A_7C15u64;
    let mut u = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    (0..n).map(|_| DVec3::new(u(), u(), u()) * size).collect()
}

/// The median time of 5 runs of `f`, in seconds, and its last result.
fn median<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let mut times = Vec::new();
    let mut out = f();
    for _ in 0..5 {
        let t = Instant::now();
        out = f();
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    (times[2], out)
}

fn main() {
    for path in std::env::args().skip(1) {
        let (mesh, _) = zipmesh::io::read_mesh(&path).expect("a mesh file");
        let tris = fan(&mesh);
        let (lo, hi) = mesh.positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let diag = (hi - lo).length();
        println!(
            "{path}: {} vertices, {} triangles",
            mesh.positions.len(),
            tris.len()
        );

        let (b_s, surface) = median(|| Surface::new(&mesh));
        let (b_21, tm21) = median(|| {
            let v = mesh
                .positions
                .iter()
                .map(|p| parry21::math::Point::new(p.x, p.y, p.z))
                .collect();
            parry21::shape::TriMesh::new(v, tris.clone()).unwrap()
        });
        let (b_31, tm31) = median(|| {
            let v = mesh
                .positions
                .iter()
                .map(|p| parry31::math::Vector::from_array(p.to_array()))
                .collect();
            parry31::shape::TriMesh::new(v, tris.clone()).unwrap()
        });
        println!(
            "  build (ms): Surface {:.2}, parry 0.21 {:.2}, parry 0.31 {:.2}",
            b_s * 1e3,
            b_21 * 1e3,
            b_31 * 1e3
        );

        for (label, size) in [
            ("on the vertices", 0.0),
            ("moved <=1% of the diagonal", 0.01 * diag),
        ] {
            let pts: Vec<DVec3> = mesh
                .positions
                .iter()
                .zip(offsets(mesh.positions.len(), size))
                .map(|(p, o)| *p + o)
                .collect();
            let (ts, ds) = median(|| {
                pts.iter()
                    .map(|p| surface.closest(*p).distance(*p))
                    .collect::<Vec<f64>>()
            });
            let (t21, d21) = median(|| {
                pts.iter()
                    .map(|p| {
                        let q = parry21::math::Point::new(p.x, p.y, p.z);
                        (tm21.project_local_point(&q, false).point - q).norm()
                    })
                    .collect::<Vec<f64>>()
            });
            let (t31, d31) = median(|| {
                pts.iter()
                    .map(|p| {
                        let q = parry31::math::Vector::from_array(p.to_array());
                        (tm31.project_local_point(q, false).point - q).length()
                    })
                    .collect::<Vec<f64>>()
            });
            let diff = |a: &[f64], b: &[f64]| {
                a.iter()
                    .zip(b)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max)
                    / diag
            };
            let n = pts.len() as f64;
            println!(
                "  {label} (us/query): Surface {:.2}, parry 0.21 {:.2}, parry 0.31 {:.2}; max |difference|/diagonal {:.0e}, {:.0e}",
                ts / n * 1e6, t21 / n * 1e6, t31 / n * 1e6, diff(&ds, &d21), diff(&ds, &d31)
            );
            println!(
                "  {label}, build + one pass (ms): Surface {:.1}, parry 0.21 {:.1}, parry 0.31 {:.1}",
                (b_s + ts) * 1e3, (b_21 + t21) * 1e3, (b_31 + t31) * 1e3
            );
        }
    }
}
