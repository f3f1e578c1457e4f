//! Homotopy (Sec. 3.1): the one-quad sweeps of a path and the start turn that matches the
//! labels of homotopic paths.

use alloc::vec::Vec;

use super::sketch::{validate_path, Path, SketchOptions};
use crate::invariants::{is_regular_interior, MeshKind};
use crate::{Dart, Map, Vert};

/// The turn, in quarter turns counter-clockwise, from the first edge of `a` to the first
/// edge of `b` around their common start: the number of quads between them on the side with
/// fewer quads (positive counter-clockwise, negative clockwise).
///
/// Homotopy invariance (Sec. 3.1) compares movements, not labels: when two homotopic paths
/// leave the start along different edges, the movement with initial operation `t` along `a`
/// is the one with `t.turned(k)` along `b`, where `k` counts the quads the homotopy sweeps
/// at the start (a quad corner is a quarter turn whatever the valence). `None` if the starts
/// differ or a face between the two edges is missing (boundary) or not a quad.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{start_turn, validate_path, SketchOptions};
/// let map = gen::torus_grid(6, 6).map;
/// let v = |i: u32, j: u32| Vert::new(6 * j + i);
/// let o = SketchOptions::default();
/// let east = validate_path(&map, v(0, 0), v(1, 1), &[v(0, 0), v(1, 0), v(1, 1)], &o).unwrap();
/// let north = validate_path(&map, v(0, 0), v(1, 1), &[v(0, 0), v(0, 1), v(1, 1)], &o).unwrap();
/// assert_eq!(start_turn(&map, &east, &north), Some(1));
/// assert_eq!(start_turn(&map, &north, &east), Some(-1));
/// ```
pub fn start_turn(map: &Map, a: &Path, b: &Path) -> Option<i32> {
    let (&da, &db) = (a.darts().first()?, b.darts().first()?);
    if a.start() != b.start() || !map.is_live_dart(da) || !map.is_live_dart(db) {
        return None;
    }
    let quad = |d: Dart| map.face(d).is_some_and(|f| map.degree(f) == 4);
    let mut ccw = 0;
    let mut x = da;
    while x != db {
        if !quad(x) || ccw > map.valence(a.start()) {
            ccw = usize::MAX;
            break;
        }
        x = map.rotate_ccw(x);
        ccw += 1;
    }
    let mut cw = 0;
    let mut x = da;
    while x != db {
        let y = map.rotate_cw(x);
        if !quad(y) || cw > map.valence(a.start()) {
            cw = usize::MAX;
            break;
        }
        x = y;
        cw += 1;
    }
    match (ccw, cw) {
        (usize::MAX, usize::MAX) => None,
        (c, w) if c <= w => Some(c as i32),
        (_, w) => Some(-(w as i32)),
    }
}

/// The paths homotopic to `path` by sweeping one quad across one of its edges: the edge
/// `v[i] -> v[i+1]` is replaced by the quad's three other sides. Only sweeps that pass no
/// third singularity are listed: the quad's two new corners are regular, interior and off
/// the path, the edge's ends are regular unless they are the path's ends, and every
/// neighbour of the quad's corners is regular or one of the path's ends. Each comes with the
/// index `i` of the swept edge. Homotopy invariance (Sec. 3.1) says Q-zip gives the same maps
/// along them, labels matched by [`start_turn`].
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{one_quad_sweeps, sketch, start_turn, SketchOptions};
/// let map = gen::subdivided_icosahedron(2).map;
/// let p = sketch(&map, Vert::new(0), Vert::new(42), &SketchOptions::default()).unwrap();
/// let sweeps = one_quad_sweeps(&map, &p);
/// assert!(!sweeps.is_empty());
/// for (i, q) in &sweeps {
///     assert_eq!(q.len(), p.len() + 2);
///     assert_eq!(start_turn(&map, &p, q) == Some(0), *i > 0);
/// }
/// ```
pub fn one_quad_sweeps(map: &Map, path: &Path) -> Vec<(usize, Path)> {
    let regular = |v: Vert| is_regular_interior(map, MeshKind::Quad, v);
    let v = path.vertices();
    let ends = [path.start(), path.end()];
    let mut out = Vec::new();
    for (i, &d) in path.darts().iter().enumerate() {
        for left in [true, false] {
            let e = if left { d } else { d.twin() };
            let Some(f) = map.face(e) else { continue };
            if map.degree(f) != 4 {
                continue;
            }
            let (x, y) = (map.origin(map.prev(e)), map.dest(map.next(e)));
            let (ni, nj) = if left { (x, y) } else { (y, x) };
            // The new corners need no test of their own: each is a neighbour of v[i] or
            // v[i + 1], so `clear` below makes it regular or an end, and a corner on the path
            // is refused by `validate_path` (no vertex twice).
            if (i > 0 && !regular(v[i])) || (i + 2 < v.len() && !regular(v[i + 1])) {
                continue;
            }
            let clear = [v[i], v[i + 1], ni, nj].iter().all(|&c| {
                map.vertex_darts(c)
                    .all(|d| ends.contains(&map.dest(d)) || regular(map.dest(d)))
            });
            if !clear {
                continue;
            }
            let mut q = v[..=i].to_vec();
            q.extend([ni, nj]);
            q.extend_from_slice(&v[i + 1..]);
            let opts = SketchOptions::default();
            if let Ok(p) = validate_path(map, path.start(), path.end(), &q, &opts) {
                out.push((i, p));
            }
        }
    }
    out
}
