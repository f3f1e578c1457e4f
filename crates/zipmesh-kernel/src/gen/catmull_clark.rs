//! One step of Catmull-Clark subdivision on any map.

use crate::map::{Dart, Face, Map};
use crate::mesh::Mesh;
use alloc::vec;
use alloc::vec::Vec;
use glam::DVec3;
use hashbrown::HashSet;

/// One Catmull-Clark step: every face of degree `k` becomes `k` quads.
///
/// **Connectivity.** One new vertex per old vertex, per edge and per face. The quad at the
/// corner of face `f` where dart `p` arrives at vertex `v` and dart `d` leaves it is
/// `[v, edge point of d, face point of f, edge point of p]`, so orientation is kept. Hence
/// `V' = V + E + F`, `E' = 2E + sum of degrees`, `F' = sum of degrees`; the Euler
/// characteristic, genus and boundary loops are unchanged.
///
/// **Numbering.** When the map is simple (no loop, no two edges joining the same two
/// vertices, no face running along both sides of an edge) the result is built from a polygon
/// list: old vertex slot `v` keeps number `v`, the point of edge `e` (darts `2e`, `2e + 1`) is
/// `vertex_slots + e` and the point of face slot `f` is `vertex_slots + edge_slots + f`
/// (`edge_slots = dart_slots / 2`); slots of dead input elements stay dead. Otherwise the
/// result has parallel edges, which a polygon list cannot express, so it is built from its
/// darts with [`Map::from_permutation`] and numbered as that function numbers vertices.
///
/// **Positions.** The standard rules: face point = centroid; interior edge point = mean of
/// the two ends and the two face points; vertex point `(Q + 2R + (n - 3) P) / n` with `Q` the
/// mean of the face points around it, `R` the mean of its edge midpoints and `n` its valence.
/// On the boundary the crease rules apply: a boundary edge point is the midpoint, a boundary
/// vertex moves to `3/4 P + 1/8 (A + B)` with `A`, `B` its two boundary neighbours. Missing
/// positions read as the origin.
///
/// Returns an empty mesh if the result would not fit 32-bit handles.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::Counts};
/// let cube = gen::cube(1);
/// let sub = gen::catmull_clark(&cube);
/// let (c0, c1) = (Counts::of(&cube.map), Counts::of(&sub.map));
/// assert_eq!(c1.vertices, c0.vertices + c0.edges + c0.faces);
/// assert_eq!(c1.faces, 24);
/// assert_eq!(c1.genus, 0);
/// sub.map.check().unwrap();
/// ```
pub fn catmull_clark(mesh: &Mesh) -> Mesh {
    let map = &mesh.map;
    let points = Points::of(mesh);
    if is_simple(map) {
        by_polygons(map, &points)
    } else {
        by_darts(map, &points)
    }
}

/// The new positions, indexed by old vertex, edge and face slot.
struct Points {
    vertex: Vec<DVec3>,
    edge: Vec<DVec3>,
    face: Vec<DVec3>,
}

impl Points {
    fn of(mesh: &Mesh) -> Points {
        let map = &mesh.map;
        let pos = |d: Dart| {
            mesh.positions
                .get(map.origin(d).index())
                .copied()
                .unwrap_or(DVec3::ZERO)
        };
        let mut face = vec![DVec3::ZERO; map.face_slots()];
        for f in map.faces() {
            let (sum, n) = map
                .face_darts(f)
                .fold((DVec3::ZERO, 0.0), |(s, n), d| (s + pos(d), n + 1.0));
            face[f.index()] = sum / n;
        }
        let fp = |f: Option<Face>| f.map(|f| face[f.index()]);
        let mut edge = vec![DVec3::ZERO; map.dart_slots() / 2];
        for d in map.darts().filter(|d| d.index() % 2 == 0) {
            let (a, b) = (pos(d), pos(d.twin()));
            edge[d.edge().index()] = match (fp(map.face(d)), fp(map.face(d.twin()))) {
                (Some(f), Some(g)) => (a + b + f + g) / 4.0,
                _ => (a + b) / 2.0,
            };
        }
        let mut vertex = vec![DVec3::ZERO; map.vertex_slots()];
        for v in map.vertices() {
            let first = map.vertex_dart(v);
            let p = pos(first);
            vertex[v.index()] = if map.is_boundary_dart(first) {
                // The last outgoing dart is the twin of the incoming boundary dart.
                let last = map.vertex_darts(v).last().unwrap_or(first);
                0.75 * p + 0.125 * (pos(first.twin()) + pos(last.twin()))
            } else {
                let (mut q, mut r, mut n) = (DVec3::ZERO, DVec3::ZERO, 0.0);
                for d in map.vertex_darts(v) {
                    q += fp(map.face(d)).unwrap_or(p);
                    r += (p + pos(d.twin())) / 2.0;
                    n += 1.0;
                }
                (q / n + 2.0 * r / n + (n - 3.0) * p) / n
            };
        }
        Points { vertex, edge, face }
    }
}

/// No loops, no parallel edges, no face on both sides of an edge: then every new polygon
/// has distinct corners and no two new edges join the same two vertices.
fn is_simple(map: &Map) -> bool {
    let mut pairs = HashSet::with_capacity(map.num_edges());
    map.darts().filter(|d| d.index() % 2 == 0).all(|d| {
        let (a, b) = (map.origin(d), map.dest(d));
        let two_sided = map.face(d).is_some() && map.face(d) == map.face(d.twin());
        a != b && !two_sided && pairs.insert((a.min(b), a.max(b)))
    })
}

fn by_polygons(map: &Map, points: &Points) -> Mesh {
    let vs = map.vertex_slots();
    let es = map.dart_slots() / 2;
    let total = vs + es + map.face_slots();
    if total >= u32::MAX as usize {
        return Mesh::default();
    }
    let mut positions = Vec::with_capacity(total);
    positions.extend_from_slice(&points.vertex);
    positions.extend_from_slice(&points.edge);
    positions.extend_from_slice(&points.face);
    let mut quads = Vec::new();
    let mut darts = Vec::new();
    for f in map.faces() {
        darts.clear();
        darts.extend(map.face_darts(f));
        let center = (vs + es + f.index()) as u32;
        let mut p = darts.last().copied().unwrap_or(Dart::new(0));
        for &d in &darts {
            let v = map.origin(d).index() as u32;
            quads.push([
                v,
                (vs + d.edge().index()) as u32,
                center,
                (vs + p.edge().index()) as u32,
            ]);
            p = d;
        }
    }
    match Mesh::from_polygons(positions, &quads) {
        Ok((mesh, _)) => mesh,
        Err(_) => Mesh::default(),
    }
}

/// Builds the subdivided map from its darts; works for every valid map.
///
/// New darts, on the compacted input with `G` face darts: the `g`-th face dart `d` (faces in
/// order, each from its recorded dart) gives the inner edge `2g` (edge point of `d` to face
/// point) / `2g + 1` (back); old dart `d` gives the halves `a(d)` (from its origin to its
/// edge point) and `b(d)` (from the edge point on), paired so that `a(d)` and `b(twin d)` are
/// twins. Listing inner edges first numbers the new faces face by face.
fn by_darts(map: &Map, points: &Points) -> Mesh {
    let mut m = map.clone();
    let c = m.compact();
    let nd = m.dart_slots();
    let mut g_of = vec![u32::MAX; nd];
    let mut g = 0usize;
    for f in m.faces() {
        for d in m.face_darts(f) {
            g_of[d.index()] = g as u32;
            g += 1;
        }
    }
    let new_darts = 2 * g + 2 * nd;
    if new_darts >= u32::MAX as usize {
        return Mesh::default();
    }
    let base = 2 * g as u32;
    let a = |d: Dart| base + 4 * (d.edge().index() as u32) + 3 * (d.index() as u32 & 1);
    let b = |d: Dart| base + 4 * (d.edge().index() as u32) + 2 - (d.index() as u32 & 1);
    let s = |d: Dart| 2 * g_of[d.index()];
    let t = |d: Dart| 2 * g_of[d.index()] + 1;
    let mut next = vec![0u32; new_darts];
    let mut boundary = vec![false; new_darts];
    let mut darts = Vec::new();
    for f in m.faces() {
        darts.clear();
        darts.extend(m.face_darts(f));
        let mut p = darts.last().copied().unwrap_or(Dart::new(0));
        for &d in &darts {
            // The quad at the corner between p and d: a(d), s(d), t(p), b(p).
            next[a(d) as usize] = s(d);
            next[s(d) as usize] = t(p);
            next[t(p) as usize] = b(p);
            next[b(p) as usize] = a(d);
            p = d;
        }
    }
    for d in m.darts().filter(|&d| m.is_boundary_dart(d)) {
        next[a(d) as usize] = b(d);
        next[b(d) as usize] = a(m.next(d));
        boundary[a(d) as usize] = true;
        boundary[b(d) as usize] = true;
    }
    let Ok(sub) = Map::from_permutation(&next, &boundary) else {
        return Mesh::default();
    };
    let mut positions = vec![DVec3::ZERO; sub.vertex_slots()];
    let mut put = |d: u32, p: DVec3| {
        if let Some(slot) = positions.get_mut(sub.origin(Dart::new(d)).index()) {
            *slot = p;
        }
    };
    for (old, new) in c.vertices.iter().enumerate() {
        if let Some(v) = new {
            put(a(m.vertex_dart(*v)), points.vertex[old]);
        }
    }
    for (old, new) in c.darts.iter().enumerate().step_by(2) {
        if let Some(d) = new {
            put(b(*d), points.edge[old / 2]);
        }
    }
    for (old, new) in c.faces.iter().enumerate() {
        if let Some(f) = new {
            put(t(m.face_dart(*f)), points.face[old]);
        }
    }
    Mesh {
        map: sub,
        positions,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen::{cube, grid, torus_grid};
    use crate::invariants::Counts;
    use crate::is_isomorphic;

    /// Both construction paths give the same map on simple inputs, and the same positions
    /// per kind of point.
    #[test]
    fn both_paths_agree() {
        let meshes = [
            grid(3, 2),
            torus_grid(4, 3),
            cube(2),
            Mesh::from_polygons(
                vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE, DVec3::Z],
                &[vec![0u32, 1, 3, 2], vec![1, 4, 3]],
            )
            .unwrap()
            .0,
        ];
        for mesh in &meshes {
            assert!(is_simple(&mesh.map));
            let points = Points::of(mesh);
            let p = by_polygons(&mesh.map, &points);
            let d = by_darts(&mesh.map, &points);
            p.map.check().unwrap();
            d.map.check().unwrap();
            assert!(is_isomorphic(&p.map, &d.map));
            assert_eq!(Counts::of(&p.map), Counts::of(&d.map));
            let mut pp: Vec<[i64; 3]> = p.positions.iter().map(|x| key(*x)).collect();
            let mut dp: Vec<[i64; 3]> = d.positions.iter().map(|x| key(*x)).collect();
            pp.sort_unstable();
            dp.sort_unstable();
            assert_eq!(pp, dp);
        }
    }

    fn key(p: DVec3) -> [i64; 3] {
        [p.x, p.y, p.z].map(|c| (c * 1e9).round() as i64)
    }

    /// A face with a loop and a face along both sides of an edge take the dart path.
    #[test]
    fn non_simple_inputs() {
        // A single edge with one face on both sides: a sphere with V = 2, E = 1, F = 1.
        let m = Map::from_permutation(&[1, 0], &[false, false]).unwrap();
        assert!(!is_simple(&m));
        let sub = catmull_clark(&Mesh {
            map: m,
            positions: vec![DVec3::ZERO, DVec3::X],
        });
        sub.map.check().unwrap();
        let c = Counts::of(&sub.map);
        assert_eq!((c.vertices, c.faces, c.genus), (4, 2, 0));
        assert!(sub.map.faces().all(|f| sub.map.degree(f) == 4));
    }

    #[test]
    fn quad_positions_on_a_flat_grid_stay_flat_and_regular() {
        // Interior of a regular planar grid: CC reproduces the midpoint grid there.
        let g = grid(4, 4);
        let s = catmull_clark(&g);
        let v = 2 * 5 + 2; // the centre vertex (2, 2)
        assert_eq!(s.positions[v], DVec3::new(2.0, 2.0, 0.0));
        assert!(s.positions.iter().all(|p| p.z == 0.0));
    }
}
