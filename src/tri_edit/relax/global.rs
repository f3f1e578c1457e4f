//! The global relaxation of Sec. 8 (Eq. 5 on tangent planes), solved by the sparse
//! Cholesky factorization of `nalgebra-sparse`, which needs std.

use alloc::vec;
use alloc::vec::Vec;

use glam::DVec3;
use nalgebra_sparse::factorization::CscCholesky;
use nalgebra_sparse::na::DMatrix;
use nalgebra_sparse::{CooMatrix, CscMatrix};

use super::{centres, energy, finish, finite, frame, targets, RelaxError, Relaxed, Start, Targets};
use crate::geometry::Surface;
use crate::{Map, Mesh, Vert};

/// Added to the diagonal of the normal equations: a region free to slide as a whole (a
/// flat surface, no fixed neighbour) still has one minimiser, the one closest to the start.
const RIDGE: f64 = 1e-9;

/// The fractions of a solved step tried, in order, until one lowers the energy.
const SCALES: [f64; 3] = [1.0, 0.5, 0.25];

/// Global relaxation (Eq. 5; see [`crate::tri_edit::relax`]):
/// up to `iterations` solves, each minimising Eq. 5 with the interior vertices of `region`
/// on their tangent planes, projecting them onto `surface` and recomputing the targets. A
/// step that would raise the energy is halved twice, then relaxation stops, so
/// `energy_after <= energy_before` always. Vertices outside the region keep their positions
/// bit for bit; the map is not touched. Needs the `sparse` feature (the sparse solver).
///
/// # Errors
/// [`RelaxError::DeadHandle`] or [`RelaxError::NonFinite`] for a region vertex (or a
/// neighbour's position), [`RelaxError::Solver`] when the factorization fails; the mesh is
/// then unchanged.
///
/// ```
/// use zipmesh::optimize::Surface;
/// use zipmesh::tri_edit::{relax_global, relax_region};
/// use zipmesh::{gen, Vert};
/// let mut mesh = gen::random_triangle(300, 0, 0, 5);
/// let surface = Surface::new(&mesh);
/// let region = relax_region(&mesh.map, &[Vert::new(10)], 2);
/// let before = mesh.clone();
/// let r = relax_global(&mut mesh, &surface, &region, 3).unwrap();
/// assert!(r.energy_after <= r.energy_before);
/// let outside = (0..mesh.positions.len()).filter(|&i| !region.contains(&Vert::new(i as u32)));
/// assert!(outside.into_iter().all(|i| mesh.positions[i] == before.positions[i]));
/// assert_eq!(mesh.map, before.map);
/// ```
pub fn relax_global(
    mesh: &mut Mesh,
    surface: &Surface,
    region: &[Vert],
    iterations: usize,
) -> Result<Relaxed, RelaxError> {
    let Start {
        moving,
        d,
        mut pos,
        mask,
        before,
    } = Start::new(mesh, region)?;
    let map = &mesh.map;
    let (mut e, mut count) = (before, 0);
    for _ in 0..iterations {
        let step = solve(map, &pos, region, &moving, &mask, d)?;
        let start: Vec<DVec3> = moving.iter().map(|v| pos[v.index()]).collect();
        let mut accepted = false;
        for scale in SCALES {
            for ((&v, s), &p) in moving.iter().zip(&step).zip(&start) {
                let q = s.map_or(p, |s| surface.closest(p + s * scale));
                pos[v.index()] = if q.is_finite() { q } else { p };
            }
            let trial = energy(map, &pos, region, &mask, d);
            if trial < e {
                (e, accepted) = (trial, true);
                break;
            }
        }
        if !accepted {
            for (&v, &p) in moving.iter().zip(&start) {
                pos[v.index()] = p;
            }
            break;
        }
        count += 1;
    }
    Ok(finish(mesh, &moving, &pos, (d, before, e), count))
}

/// One linearised solve: for each vertex of `moving`, its displacement in its tangent plane
/// that minimises Eq. 5 with the current targets (`None` for a vertex without a plane).
fn solve(
    map: &Map,
    pos: &[DVec3],
    region: &[Vert],
    moving: &[Vert],
    mask: &[bool],
    d: f64,
) -> Result<Vec<Option<DVec3>>, RelaxError> {
    let mut col = vec![usize::MAX; map.vertex_slots()];
    let mut basis: Vec<[DVec3; 2]> = Vec::new();
    for &v in moving {
        if let Some([_, x, y]) = frame(map, pos, v) {
            col[v.index()] = basis.len();
            basis.push([x, y]);
        }
    }
    let unknown = |v: Vert| col.get(v.index()).copied().filter(|&c| c != usize::MAX);
    let n = 2 * basis.len();
    if n == 0 {
        return Ok(vec![None; moving.len()]);
    }
    let mut coo = CooMatrix::new(n, n);
    let mut rhs = vec![0.0; n];
    (0..n).for_each(|k| coo.push(k, k, RIDGE));
    let inside = |v: Vert| mask.get(v.index()).copied().unwrap_or(false);
    let mut buf = Targets::default();
    for i in centres(map, region) {
        let (Some(p), Some(t)) = (finite(pos, i), targets(map, pos, i, &mut buf)) else {
            continue;
        };
        for &(j, u) in t {
            let blocks = [(unknown(j), 1.0), (unknown(i), -1.0)];
            let Some(q) = finite(pos, j) else { continue };
            if (inside(i) || inside(j)) && blocks.iter().any(|b| b.0.is_some()) {
                add_term(&mut coo, &mut rhs, &basis, &blocks, q - p - u * d);
            }
        }
    }
    let chol = CscCholesky::factor(&CscMatrix::from(&coo)).map_err(|_| RelaxError::Solver)?;
    let x = chol.solve(&DMatrix::from_column_slice(n, 1, &rhs));
    if x.iter().any(|v| !v.is_finite()) {
        return Err(RelaxError::Solver);
    }
    Ok(moving
        .iter()
        .map(|&v| unknown(v).map(|c| basis[c][0] * x[2 * c] + basis[c][1] * x[2 * c + 1]))
        .collect())
}

/// Adds one term `|g + sum_k s_k T_k x_k|^2` to the normal equations, `T_k` the tangent
/// basis of unknown `k` and `s_k` its sign (`+1` for `p_j`, `-1` for `p_i`).
fn add_term(
    coo: &mut CooMatrix<f64>,
    rhs: &mut [f64],
    basis: &[[DVec3; 2]],
    blocks: &[(Option<usize>, f64); 2],
    g: DVec3,
) {
    for &(a, sa) in blocks {
        let Some(a) = a else { continue };
        for r in 0..2 {
            rhs[2 * a + r] -= sa * basis[a][r].dot(g);
        }
        for &(b, sb) in blocks {
            let Some(b) = b else { continue };
            for r in 0..2 {
                for s in 0..2 {
                    let v = sa * sb * basis[a][r].dot(basis[b][s]);
                    coo.push(2 * a + r, 2 * b + s, v);
                }
            }
        }
    }
}
