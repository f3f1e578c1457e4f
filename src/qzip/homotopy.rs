//! Homotopy (Sec. 3.1): the one-quad sweeps of a path and the start turn that matches the
//! labels of homotopic paths.

use alloc::vec::Vec;

use super::sketch::{validate_path, Path, SketchOptions};
use crate::invariants::{is_regular_interior, MeshKind};
use crate::{Dart, Face, Map, Vert};

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
/// neighbour of the quad's corners is regular or one of the path's ends. Both paths must
/// not wrap round a handle or a hole ([`wraps`]): the theorem's proof lifts them to the
/// universal cover, which is the same surgery only then.
/// Each comes with the index `i` of the swept edge. Homotopy invariance (Sec. 3.1) says
/// Q-zip gives the same maps along them, labels matched by [`start_turn`].
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
    if wraps(map, path) {
        return out;
    }
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
            match validate_path(map, path.start(), path.end(), &q, &opts) {
                Ok(p) if !wraps(map, &p) => out.push((i, p)),
                _ => {}
            }
        }
    }
    out
}

/// Whether `path` wraps round a handle or a hole: some face touches it at two places apart
/// and closes, with the path between them, a loop that does not bound a disk. Homotopy
/// invariance (Sec. 3.1) is proved by lifting to the universal cover, which is the same
/// surgery only when no path wraps: otherwise two lifts of the path's strip meet (on a short
/// loop of a torus the strip runs into itself). Loops that bound a disk, as the bend round
/// a swept quad, are fine. Never true on a sphere or a disk.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{validate_path, wraps, SketchOptions};
/// let map = gen::torus_grid(4, 4).map;
/// let o = SketchOptions::default();
/// let row = |n: u32| (0..n).map(Vert::new).collect::<Vec<_>>();
/// let short = validate_path(&map, Vert::new(0), Vert::new(2), &row(3), &o).unwrap();
/// assert!(!wraps(&map, &short));
/// // 0 -> 1 -> 2 -> 3 ends next to its start: with edge 3 -> 0 it goes round the torus.
/// let round = validate_path(&map, Vert::new(0), Vert::new(3), &row(4), &o).unwrap();
/// assert!(wraps(&map, &round));
/// ```
pub fn wraps(map: &Map, path: &Path) -> bool {
    let v = path.vertices();
    let mut seen = Vec::new();
    for &c in v {
        for d in map.vertex_darts(c) {
            let Some(f) = map.face(d) else { continue };
            if seen.contains(&f) {
                continue;
            }
            seen.push(f);
            if gap_loops(map, path, f)
                .iter()
                .any(|lp| !bounds_disk(map, lp))
            {
                return true;
            }
        }
    }
    false
}

/// The loops closed by face `f` across the gaps in its touches of `path`: for consecutive
/// touches `a < b` with `b > a + 1`, the path's darts from `a` to `b`, then `f`'s darts
/// from `b` on round to `a`. Simple, because no vertex of that arc is on the path between
/// `a` and `b`. (Either arc of `f` would do: `f` is a disk, so both give loops of one kind.)
fn gap_loops(map: &Map, path: &Path, f: Face) -> Vec<Vec<Dart>> {
    let v = path.vertices();
    let ring: Vec<Dart> = map.face_darts(f).collect();
    // (position on the path, index in the ring) of each touch, by position.
    let mut at: Vec<(usize, usize)> = (0..ring.len())
        .filter_map(|k| Some((v.iter().position(|&x| x == map.origin(ring[k]))?, k)))
        .collect();
    at.sort_unstable();
    let gaps = at.windows(2).filter(|w| w[1].0 > w[0].0 + 1);
    gaps.map(|w| {
        let ((a, ia), (b, ib)) = (w[0], w[1]);
        let mut lp = path.darts()[a..b].to_vec();
        lp.extend(ring.iter().cycle().skip(ib).take_while(|&&d| d != ring[ia]));
        lp
    })
    .collect()
}

/// Whether the simple loop of darts `lp` bounds a disk: cut along it, the faces on one side
/// form a piece of Euler characteristic 1. A loop that does not separate its component
/// (round a handle) bounds nothing. Both sides grow in turn, so a loop round a few faces
/// costs a few faces, not the mesh.
fn bounds_disk(map: &Map, lp: &[Dart]) -> bool {
    let cut = |d: Dart| lp.iter().any(|&x| x == d || x == d.twin());
    // The sides are seeded across a dart with a face on each (a loop may run along the
    // boundary for a while); a loop that is boundary all along bounds nothing.
    let seeds = lp
        .iter()
        .find_map(|&d| Some((map.face(d)?, map.face(d.twin())?)));
    let Some((left, right)) = seeds else {
        return false;
    };
    if left == right {
        return false;
    }
    // side[f]: 0 unreached, else the mark of the side that reached it.
    const MARK: [u8; 2] = [1, 2];
    let mut side = alloc::vec![0u8; map.face_slots()];
    let mut grown = [alloc::vec![left], alloc::vec![right]];
    side[left.index()] = MARK[0];
    side[right.index()] = MARK[1];
    let mut next = [0usize; 2];
    loop {
        for s in 0..2 {
            let Some(&f) = grown[s].get(next[s]) else {
                // Side `s` is complete: a disk, or not (then the other side may be one).
                if euler(map, &grown[s]) == 1 {
                    return true;
                }
                let other = 1 - s;
                while let Some(&g) = grown[other].get(next[other]) {
                    next[other] += 1;
                    grow(map, g, MARK[other], &mut side, &mut grown[other], &cut);
                }
                return euler(map, &grown[other]) == 1;
            };
            next[s] += 1;
            if !grow(map, f, MARK[s], &mut side, &mut grown[s], &cut) {
                return false;
            }
        }
    }
}

/// Adds the uncut neighbours of `f` to side `mark`; false when one is on the other side
/// (the loop does not separate).
fn grow(
    map: &Map,
    f: Face,
    mark: u8,
    side: &mut [u8],
    grown: &mut Vec<Face>,
    cut: &dyn Fn(Dart) -> bool,
) -> bool {
    for d in map.face_darts(f) {
        let Some(g) = map.face(d.twin()) else {
            continue;
        };
        if cut(d) {
            continue;
        }
        match side[g.index()] {
            0 => {
                side[g.index()] = mark;
                grown.push(g);
            }
            m if m != mark => return false,
            _ => {}
        }
    }
    true
}

/// V - E + F of the closure of the faces `fs`.
fn euler(map: &Map, fs: &[Face]) -> i64 {
    let mut inside = alloc::vec![false; map.face_slots()];
    fs.iter().for_each(|f| inside[f.index()] = true);
    let mut verts = Vec::new();
    let mut half_edges = 0i64;
    for &f in fs {
        for d in map.face_darts(f) {
            verts.push(map.origin(d));
            // An edge between two faces of the set is seen twice, once from each.
            let shared = map.face(d.twin()).is_some_and(|g| inside[g.index()]);
            half_edges += if shared { 1 } else { 2 };
        }
    }
    verts.sort_unstable();
    verts.dedup();
    verts.len() as i64 - half_edges / 2 + fs.len() as i64
}
