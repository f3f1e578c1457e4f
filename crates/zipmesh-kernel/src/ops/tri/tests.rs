//! Unit tests: one small hand-built map per refusal reason and per success case, and the
//! known failures of other libraries as regressions.

use super::*;
use crate::invariants::canonical::CanonicalCode;
use crate::invariants::Counts;
use crate::map::{Dart, Map, Vert};
use alloc::vec;
use alloc::vec::Vec;

fn polys<const N: usize>(n: usize, faces: &[[u32; N]]) -> Map {
    Map::from_polygons(n, faces).unwrap()
}

/// The dart from vertex `a` to vertex `b`.
fn dart(m: &Map, a: u32, b: u32) -> Dart {
    m.darts()
        .find(|&d| m.origin(d) == Vert(a) && m.dest(d) == Vert(b))
        .unwrap_or_else(|| panic!("no dart {a} -> {b}"))
}

fn val(m: &Map, v: u32) -> usize {
    m.valence(Vert(v))
}

fn counts(m: &Map) -> [usize; 3] {
    [m.num_vertices(), m.num_edges(), m.num_faces()]
}

/// Center 0 with the ring 1..=6 around it: a disk of six triangles.
fn hexagon() -> Map {
    polys(
        7,
        &[
            [0u32, 1, 2],
            [0, 2, 3],
            [0, 3, 4],
            [0, 4, 5],
            [0, 5, 6],
            [0, 6, 1],
        ],
    )
}

/// An `n` x `n` grid of vertices `j * n + i`, each square cut along the same diagonal.
fn tri_grid(n: u32) -> Map {
    let id = |i: u32, j: u32| j * n + i;
    let mut f = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    polys((n * n) as usize, &f)
}

fn tetrahedron() -> Map {
    polys(4, &[[0u32, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
}

/// Poles 0 (+z) and 5 (-z), equator 1, 2, 3, 4 counter-clockwise seen from +z.
fn octahedron() -> Map {
    polys(
        6,
        &[
            [0u32, 1, 2],
            [0, 2, 3],
            [0, 3, 4],
            [0, 4, 1],
            [5, 2, 1],
            [5, 3, 2],
            [5, 4, 3],
            [5, 1, 4],
        ],
    )
}

/// Two triangles glued along all three edges: a sphere with three vertices of valence 2.
fn two_triangle_sphere() -> Map {
    Map::from_permutation(&[2, 4, 5, 1, 3, 0], &[false; 6]).unwrap()
}

/// A triangle with a loop at one corner: darts 0, 2, 3 form the triangle, dart 1 alone a
/// face of degree 1; the triangle's corners are not distinct.
fn looped_triangle() -> Map {
    Map::from_permutation(&[2, 1, 3, 0], &[false; 4]).unwrap()
}

fn code(m: &Map) -> CanonicalCode {
    CanonicalCode::of(m)
}

fn refused_flip(m: &Map, h: Dart, want: Refusal) {
    assert_eq!(can_flip_edge(m, h), Err(want));
    let mut x = m.clone();
    assert_eq!(flip_edge(&mut x, h).err(), Some(want));
    assert_eq!(x, *m);
}

fn refused_collapse(m: &Map, h: Dart, want: Refusal) {
    assert_eq!(can_collapse_edge(m, h), Err(want));
    let mut x = m.clone();
    assert_eq!(collapse_edge(&mut x, h).err(), Some(want));
    assert_eq!(x, *m);
}

fn refused_split_vertex(m: &Map, d1: Dart, d2: Dart, want: Refusal) {
    assert_eq!(can_split_vertex(m, d1, d2), Err(want));
    let mut x = m.clone();
    assert_eq!(split_vertex(&mut x, d1, d2).err(), Some(want));
    assert_eq!(x, *m);
}

fn refused_split_edge(m: &Map, h: Dart, want: Refusal) {
    assert_eq!(can_split_edge(m, h), Err(want));
    let mut x = m.clone();
    assert_eq!(split_edge(&mut x, h).err(), Some(want));
    assert_eq!(x, *m);
}

/// Every interior vertex has valence at least 3.
fn no_interior_valence_below_3(m: &Map) -> bool {
    m.vertices()
        .all(|v| m.is_boundary_vertex(v) || m.valence(v) >= 3)
}

// ---------------------------------------------------------------- flip

#[test]
fn flip_interior_spoke_of_a_hexagon() {
    let m = hexagon();
    let h = dart(&m, 0, 1); // triangles (0, 1, 2) and (1, 0, 6)
    assert_eq!(can_flip_edge(&m, h), Ok(()));
    let mut x = m.clone();
    let rec = flip_edge(&mut x, h).unwrap();
    assert_eq!(x.check(), Ok(()));
    assert_eq!(counts(&x), counts(&m));
    assert_eq!(
        (x.origin(rec.dart()), x.dest(rec.dart())),
        (Vert(6), Vert(2))
    );
    assert_eq!(
        [0, 1, 2, 6].map(|v| val(&x, v)),
        [6 - 1, 3 - 1, 3 + 1, 3 + 1]
    );
    for v in [3, 4, 5] {
        assert_eq!(val(&x, v), val(&m, v));
    }
    // Flipping again gives back the map up to the names of h and twin(h); undo, exactly.
    let mut y = x.clone();
    flip_edge(&mut y, h).unwrap();
    assert_eq!(code(&y), code(&m));
    rec.undo(&mut x).unwrap();
    assert_eq!(x, m);
}

#[test]
fn flip_may_leave_a_boundary_vertex_with_valence_2() {
    // Two triangles: 0 and 1 are boundary vertices of valence 3, which may drop to 2.
    let m = polys(4, &[[0u32, 1, 2], [1, 0, 3]]);
    let mut x = m.clone();
    let rec = flip_edge(&mut x, dart(&m, 0, 1)).unwrap();
    assert_eq!([0, 1, 2, 3].map(|v| val(&x, v)), [2, 2, 3, 3]);
    rec.undo(&mut x).unwrap();
    assert_eq!(x, m);
}

#[test]
fn flip_refusals() {
    let m = hexagon();
    refused_flip(&m, Dart(999), Refusal::DeadHandle);
    refused_flip(&m, dart(&m, 1, 2), Refusal::Boundary);
    refused_flip(&m, dart(&m, 2, 1), Refusal::Boundary);
    let q = Map::from_polygons(5, &[vec![0u32, 1, 2, 3], vec![1, 0, 4]]).unwrap();
    refused_flip(&q, dart(&q, 0, 1), Refusal::WrongDegree);
    refused_flip(&looped_triangle(), Dart(2), Refusal::DegenerateTriangle);
    // Both apexes are the same vertex: the new edge would be a loop.
    let s = two_triangle_sphere();
    for d in s.darts() {
        refused_flip(&s, d, Refusal::Loop);
    }
    // In a tetrahedron the apexes are always joined already.
    let t = tetrahedron();
    for d in t.darts() {
        refused_flip(&t, d, Refusal::MultiEdge);
    }
}

#[test]
fn flip_refuses_to_leave_an_interior_vertex_of_valence_2() {
    // 0 is interior of valence 3 (triangles (0,1,2), (1,0,3) and the quad (0,2,4,3)), and
    // 2, 3 are not joined: only the valence rule stops the flip of 0-1.
    let m = Map::from_polygons(5, &[vec![0u32, 1, 2], vec![1, 0, 3], vec![0, 2, 4, 3]]).unwrap();
    assert!(!m.is_boundary_vertex(Vert(0)));
    assert_eq!(val(&m, 0), 3);
    refused_flip(&m, dart(&m, 0, 1), Refusal::ValenceTooLow);
}

// ---------------------------------------------------------------- collapse

#[test]
fn collapse_interior_edge_of_a_grid() {
    let m = tri_grid(5); // interior vertices have valence 6
    let (v, u) = (6u32, 7u32); // interior, joined by a horizontal edge
    let h = dart(&m, v, u);
    let (c, d) = (m.dest(m.next(h)).0, m.dest(m.next(h.twin())).0);
    let mut x = m.clone();
    let rec = collapse_edge(&mut x, h).unwrap();
    assert_eq!(x.check(), Ok(()));
    assert_eq!((rec.kept(), rec.removed()), (Vert(u), Vert(v)));
    let [nv, ne, nf] = counts(&m);
    assert_eq!(counts(&x), [nv - 1, ne - 3, nf - 2]);
    assert_eq!(val(&x, u), val(&m, u) + val(&m, v) - 4);
    assert_eq!((val(&x, c), val(&x, d)), (val(&m, c) - 1, val(&m, d) - 1));
    assert!(!x.is_live_vertex(Vert(v)));
    // The inverse: split u at its darts to c and d.
    let mut y = x.clone();
    split_vertex(&mut y, m.next(h), m.next(m.next(h.twin())).twin()).unwrap();
    assert_eq!(code(&y), code(&m));
    rec.undo(&mut x).unwrap();
    assert_eq!(x, m);
}

#[test]
fn collapse_boundary_edge_either_way_round() {
    let m = tri_grid(4);
    for (v, u) in [(1u32, 2u32), (2, 1)] {
        let h = dart(&m, v, u);
        let face_side = if m.face(h).is_some() { h } else { h.twin() };
        let c = m.dest(m.next(face_side)).0;
        let mut x = m.clone();
        let rec = collapse_edge(&mut x, h).unwrap();
        assert_eq!(x.check(), Ok(()));
        let [nv, ne, nf] = counts(&m);
        assert_eq!(counts(&x), [nv - 1, ne - 2, nf - 1]);
        assert_eq!(val(&x, u), val(&m, u) + val(&m, v) - 3);
        assert_eq!(val(&x, c), val(&m, c) - 1);
        assert!(x.is_boundary_vertex(Vert(u)));
        rec.undo(&mut x).unwrap();
        assert_eq!(x, m);
    }
}

#[test]
fn collapse_refusals() {
    let g = tri_grid(3);
    refused_collapse(&g, Dart(999), Refusal::DeadHandle);
    let q = Map::from_polygons(5, &[vec![0u32, 1, 2, 3], vec![1, 0, 4]]).unwrap();
    refused_collapse(&q, dart(&q, 0, 1), Refusal::WrongDegree);
    refused_collapse(&looped_triangle(), Dart(2), Refusal::DegenerateTriangle);
    // The diagonal of a square cut in two: both ends on the boundary, the edge interior.
    let s = tri_grid(2);
    refused_collapse(&s, dart(&s, 0, 3), Refusal::Boundary);
    // Apexes equal.
    let t2 = two_triangle_sphere();
    for d in t2.darts() {
        refused_collapse(&t2, d, Refusal::LinkCondition);
    }
    // A lone triangle: collapsing a side would leave the apex with one edge and no face.
    let one = polys(3, &[[0u32, 1, 2]]);
    for d in one.darts() {
        refused_collapse(&one, d, Refusal::ValenceTooLow);
    }
}

#[test]
fn collapse_link_condition_vertex_part() {
    // Triangle 1-2-3 cut into three around 0: the boundary edge 1-2 has apex 0, but 1 and 2
    // also share the neighbour 3, so collapsing 1-2 would pinch (honeycomb's collapse has no
    // such test; pmp-library's issue 245 shows the apex 0 dropping to valence 2).
    let m = polys(4, &[[0u32, 1, 2], [0, 2, 3], [0, 3, 1]]);
    refused_collapse(&m, dart(&m, 1, 2), Refusal::LinkCondition);
    refused_collapse(&m, dart(&m, 2, 1), Refusal::LinkCondition);
    // Collapsing a spoke is fine: it leaves one triangle.
    let mut x = m.clone();
    collapse_edge(&mut x, dart(&m, 1, 0)).unwrap();
    assert_eq!(counts(&x), [3, 3, 1]);
}

#[test]
fn tetrahedron_never_collapses() {
    let t = tetrahedron();
    for d in t.darts() {
        refused_collapse(&t, d, Refusal::LinkCondition);
    }
}

#[test]
fn octahedron_collapses_to_a_tetrahedron_and_stops() {
    let o = octahedron();
    let mut x = o.clone();
    // Pole 0 into equator vertex 1: the apexes 2 and 4 are the only common neighbours.
    let r1 = collapse_edge(&mut x, dart(&o, 0, 1)).unwrap();
    assert_eq!(counts(&x), [5, 9, 6]); // a triangular bipyramid
    assert_eq!([1, 2, 3, 4, 5].map(|v| val(&x, v)), [4, 3, 4, 3, 4]);
    // Equator of the bipyramid: 1, 3, 5 are pairwise joined; 1-3 has apexes 2 and 4 but
    // also the common neighbour 5.
    refused_collapse(&x, dart(&x, 1, 3), Refusal::LinkCondition);
    // A pole into the equator gives the tetrahedron, which then refuses every collapse.
    let h2 = dart(&x, 2, 1);
    let r2 = collapse_edge(&mut x, h2).unwrap();
    assert_eq!(code(&x), code(&tetrahedron()));
    for d in x.darts() {
        refused_collapse(&x, d, Refusal::LinkCondition);
    }
    r2.undo(&mut x).unwrap();
    r1.undo(&mut x).unwrap();
    assert_eq!(x, o);
}

#[test]
fn no_collapse_leaves_an_interior_vertex_of_valence_2() {
    // pmp-library issue 245: an interior vertex of valence 3 joined to both ends of the
    // collapsed edge. Here vertex 0 (valence 3) sits inside the triangle 1-2-3, which lies
    // inside a larger disk, so that 1-2, 2-3, 3-1 are interior edges.
    let m = polys(
        7,
        &[
            [0u32, 1, 2],
            [0, 2, 3],
            [0, 3, 1],
            [2, 1, 4],
            [3, 2, 5],
            [1, 3, 6],
            [1, 6, 4],
            [2, 4, 5],
            [3, 5, 6],
        ],
    );
    assert!(!m.is_boundary_vertex(Vert(0)) && val(&m, 0) == 3);
    assert!(no_interior_valence_below_3(&m));
    let mut applied = 0;
    for d in m.darts() {
        let mut x = m.clone();
        if collapse_edge(&mut x, d).is_ok() {
            applied += 1;
            assert!(no_interior_valence_below_3(&x), "collapse of {d:?}");
        }
    }
    assert!(applied > 0);
    refused_collapse(&m, dart(&m, 1, 2), Refusal::LinkCondition);
}

#[test]
fn collapse_keeps_the_boundary_record_of_the_merged_vertex() {
    // Interior edge with v on the boundary and u inside: u becomes a boundary vertex.
    let m = tri_grid(4);
    let h = dart(&m, 1, 5); // 1 on the boundary, 5 inside
    assert!(m.face(h).is_some() && m.face(h.twin()).is_some());
    let mut x = m.clone();
    collapse_edge(&mut x, h).unwrap();
    assert_eq!(x.check(), Ok(()));
    assert!(x.is_boundary_vertex(Vert(5)));
}

// ---------------------------------------------------------------- vertex split

#[test]
fn split_the_hexagon_center_every_way() {
    let m = hexagon();
    let w = Vert(0);
    let darts: Vec<Dart> = m.vertex_darts(w).collect();
    for (i, &d1) in darts.iter().enumerate() {
        for (j, &d2) in darts.iter().enumerate() {
            if i == j {
                refused_split_vertex(&m, d1, d2, Refusal::BadArguments);
                continue;
            }
            let k_w = (j + 6 - i) % 6 - 1; // strictly inside the kept arc d1 .. d2
            let k_v = 6 - 2 - k_w;
            let (a, b) = (m.dest(d1).0, m.dest(d2).0);
            let mut x = m.clone();
            let rec = split_vertex(&mut x, d1, d2).unwrap();
            assert_eq!(x.check(), Ok(()));
            let [nv, ne, nf] = counts(&m);
            assert_eq!(counts(&x), [nv + 1, ne + 3, nf + 2]);
            assert_eq!(x.valence(w), k_w + 3);
            assert_eq!(x.valence(rec.created()), k_v + 3);
            assert_eq!((val(&x, a), val(&x, b)), (val(&m, a) + 1, val(&m, b) + 1));
            assert!(!x.is_boundary_vertex(w) && !x.is_boundary_vertex(rec.created()));
            let mut y = x.clone();
            collapse_edge(&mut y, rec.edge()).unwrap();
            assert_eq!(code(&y), code(&m));
            rec.undo(&mut x).unwrap();
            assert_eq!(x, m);
        }
    }
}

#[test]
fn split_a_boundary_vertex_keeps_one_copy_on_the_boundary() {
    let m = tri_grid(4);
    let w = Vert(1); // on the bottom row, valence 4
    let darts: Vec<Dart> = m.vertex_darts(w).collect();
    let mut applied = 0;
    for &d1 in &darts {
        for &d2 in &darts {
            let mut x = m.clone();
            let Ok(rec) = split_vertex(&mut x, d1, d2) else {
                continue;
            };
            applied += 1;
            assert_eq!(x.check(), Ok(()));
            let bw = x.is_boundary_vertex(w);
            let bv = x.is_boundary_vertex(rec.created());
            assert!(bw != bv, "exactly one copy keeps the boundary corner");
            // v keeps it exactly when w's boundary dart moved or was d1.
            let boundary_dart = m.vertex_dart(w);
            let moved = {
                let mut y = m.rotate_cw(d2);
                let mut found = false;
                while y != d1 {
                    found |= y == boundary_dart;
                    y = m.rotate_cw(y);
                }
                found
            };
            assert_eq!(bv, moved || d1 == boundary_dart);
            rec.undo(&mut x).unwrap();
            assert_eq!(x, m);
        }
    }
    assert_eq!(applied, 4 * 3);
}

#[test]
fn split_vertex_refusals() {
    let m = hexagon();
    let d = m.vertex_dart(Vert(0));
    refused_split_vertex(&m, Dart(999), d, Refusal::DeadHandle);
    refused_split_vertex(&m, d, dart(&m, 1, 2), Refusal::BadArguments);
    // A loop as split edge: one vertex, one loop edge, two faces of degree 1.
    let l = Map::from_permutation(&[0, 1], &[false, false]).unwrap();
    refused_split_vertex(&l, Dart(0), Dart(1), Refusal::DegenerateTriangle);
    // Both darts end at the same vertex (a double edge, two faces of degree 2).
    let de = Map::from_permutation(&[3, 2, 1, 0], &[false; 4]).unwrap();
    assert_eq!(de.dest(Dart(0)), de.dest(Dart(2)));
    refused_split_vertex(&de, Dart(0), Dart(2), Refusal::MultiEdge);
    // The two-triangle sphere: splitting a vertex of valence 2 would give the tetrahedron,
    // whose edges fail the link condition (so the split could not be collapsed back).
    let s = two_triangle_sphere();
    let w = Vert(0);
    let ds: Vec<Dart> = s.vertex_darts(w).collect();
    refused_split_vertex(&s, ds[0], ds[1], Refusal::LinkCondition);
    // A moved dart that reaches a vertex also reached by a kept dart (found by enumeration:
    // three edges, one face of degree 1, one of degree 2, one of degree 3).
    let lc = Map::from_permutation(&[4, 2, 3, 1, 5, 0], &[false; 6]).unwrap();
    refused_split_vertex(&lc, Dart(2), Dart(4), Refusal::LinkCondition);
}

// ---------------------------------------------------------------- edge split

#[test]
fn split_interior_and_boundary_edges() {
    let m = hexagon();
    for (h, interior) in [
        (dart(&m, 0, 1), true),
        (dart(&m, 1, 2), false),
        (dart(&m, 2, 1), false),
    ] {
        let (a, b) = (m.origin(h).0, m.dest(h).0);
        let apexes: Vec<u32> = [h, h.twin()]
            .iter()
            .filter(|&&x| m.face(x).is_some())
            .map(|&x| m.dest(m.next(x)).0)
            .collect();
        let mut x = m.clone();
        let rec = split_edge(&mut x, h).unwrap();
        assert_eq!(x.check(), Ok(()));
        let [nv, ne, nf] = counts(&m);
        let want = if interior {
            [nv + 1, ne + 3, nf + 2]
        } else {
            [nv + 1, ne + 2, nf + 1]
        };
        assert_eq!(counts(&x), want);
        assert_eq!(x.valence(rec.created()), if interior { 4 } else { 3 });
        for &c in &apexes {
            assert_eq!(val(&x, c), val(&m, c) + 1);
        }
        assert_eq!((val(&x, a), val(&x, b)), (val(&m, a), val(&m, b)));
        assert_eq!((x.origin(h), x.dest(h)), (Vert(a), rec.created()));
        assert_eq!(
            (x.origin(rec.dart()), x.dest(rec.dart())),
            (rec.created(), Vert(b))
        );
        let mut y = x.clone();
        collapse_edge(&mut y, h.twin()).unwrap();
        assert_eq!(code(&y), code(&m));
        rec.undo(&mut x).unwrap();
        assert_eq!(x, m);
    }
}

#[test]
fn split_edge_refusals() {
    let m = hexagon();
    refused_split_edge(&m, Dart(999), Refusal::DeadHandle);
    let q = Map::from_polygons(5, &[vec![0u32, 1, 2, 3], vec![1, 0, 4]]).unwrap();
    refused_split_edge(&q, dart(&q, 0, 1), Refusal::WrongDegree);
    refused_split_edge(&looped_triangle(), Dart(2), Refusal::DegenerateTriangle);
    let s = two_triangle_sphere();
    for d in s.darts() {
        refused_split_edge(&s, d, Refusal::MultiEdge);
    }
}

// ---------------------------------------------------------------- records

#[test]
fn stale_and_foreign_records_are_refused_without_change() {
    let m = tri_grid(4);
    let h = dart(&m, 5, 6);
    let mut x = m.clone();
    let f = flip_edge(&mut x, h).unwrap();
    f.undo(&mut x).unwrap();
    let before = x.clone();
    // The flip's triangles are back as they were: a second undo does not fit.
    assert_eq!(f.undo(&mut x), Err(Refusal::StaleRecord));
    assert_eq!(x, before);

    let c = collapse_edge(&mut x, h).unwrap();
    c.undo(&mut x).unwrap();
    assert_eq!(c.undo(&mut x), Err(Refusal::StaleRecord));
    assert_eq!(x, m);

    let s = split_vertex(&mut x, m.vertex_dart(Vert(5)), h).unwrap();
    let e = split_edge(&mut x, h).unwrap();
    // Out of order: the vertex split's edge is still there, but its slots are not last.
    let snapshot = x.clone();
    let r = s.undo(&mut x);
    if r.is_err() {
        assert_eq!(x, snapshot);
    } else {
        assert_eq!(x.check(), Ok(()));
        x = snapshot;
    }
    e.undo(&mut x).unwrap();
    s.undo(&mut x).unwrap();
    assert_eq!(x, m);
    // Records on a foreign map: refused, nothing changes.
    let mut other = hexagon();
    let o = other.clone();
    for r in [
        f.undo(&mut other),
        c.undo(&mut other),
        s.undo(&mut other),
        e.undo(&mut other),
    ] {
        assert_eq!(r, Err(Refusal::StaleRecord));
    }
    assert_eq!(other, o);
}

#[test]
fn a_long_chain_of_collapses_and_its_undo() {
    // Collapse a row of the grid into its first vertex, then undo in reverse order.
    let m = tri_grid(12);
    let mut x = m.clone();
    let mut recs = Vec::new();
    for i in 2..10u32 {
        let row = 5 * 12;
        let h = dart(&x, row + i, row + 1);
        recs.push(collapse_edge(&mut x, h).unwrap());
        assert_eq!(x.check(), Ok(()));
    }
    assert_eq!(Counts::of(&x).vertices, 144 - 8);
    assert_eq!(val(&x, 61), 6 + 8 * 2); // each collapse adds d(v) - 4 = 2
                                        // The public inverse, splitting the merged vertex back one by one (the kept arc is long,
                                        // so this takes the fallback path of the link test), gives the same map up to slots.
    let mut y = x.clone();
    for i in (2..10u32).rev() {
        let row = 5 * 12;
        // The collapsed dart ran from row + i to its left neighbour (merged by then); its
        // triangles are the original ones.
        let h = dart(&m, row + i, row + i - 1);
        let h1 = m.next(h);
        let t2 = m.next(m.next(h.twin()));
        split_vertex(&mut y, h1, t2.twin()).unwrap();
    }
    assert_eq!(code(&y), code(&m));
    for r in recs.iter().rev() {
        r.undo(&mut x).unwrap();
    }
    assert_eq!(x, m);
}

#[test]
fn records_are_small_and_copy() {
    // Records are returned by value and kept by callers: no heap, a fixed small size.
    assert_eq!(core::mem::size_of::<EdgeCollapse>(), 180);
    assert!(core::mem::size_of::<VertexSplit>() <= 48);
    assert!(core::mem::size_of::<EdgeSplit>() <= 80);
    assert!(core::mem::size_of::<EdgeFlip>() <= 32);
}

#[test]
fn stack_and_fallback_link_tests_agree() {
    // The link tests gather up to 16 neighbours on the stack and otherwise walk each
    // candidate's rotation: both paths must give the same answer everywhere.
    let mut maps = vec![
        hexagon(),
        tri_grid(5),
        tetrahedron(),
        octahedron(),
        two_triangle_sphere(),
        looped_triangle(),
        Map::from_permutation(&[4, 2, 3, 1, 5, 0], &[false; 6]).unwrap(),
        Map::from_permutation(&[3, 2, 1, 0], &[false; 4]).unwrap(),
        crate::gen::random_triangle(300, 1, 2, 11).map,
        crate::gen::random_mixed(300, 1, 1, 12).map,
    ];
    // A vertex of high valence: a row of a grid collapsed into one vertex.
    let mut chain = tri_grid(12);
    for i in 2..10u32 {
        let h = dart(&chain, 60 + i, 61);
        collapse_edge(&mut chain, h).unwrap();
    }
    assert!(chain.valence(Vert(61)) > 16);
    maps.push(chain);
    // Random closed maps of up to 12 darts: multi-edges and loops, where a moved dart's end
    // can also be a kept dart's (the shared-neighbour rule).
    let mut rng = crate::rng::Rng::new(5);
    while maps.len() < 1_500 {
        let n = 2 * rng.range(1, 7);
        let mut next: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            next.swap(i, rng.below(i + 1));
        }
        if let Ok(m) = Map::from_permutation(&next, &vec![false; n]) {
            maps.push(m);
        }
    }
    let mut compared = 0;
    for m in &maps {
        for h in m.darts() {
            let fast = super::collapse::can_with(m, h, None, 16);
            assert_eq!(
                fast,
                super::collapse::can_with(m, h, None, 0),
                "collapse {h:?}"
            );
            assert_eq!(fast, can_collapse_edge(m, h));
            for d2 in m.vertex_darts(m.origin(h)) {
                let fast = super::collapse::can_with(m, h, Some(d2), 16);
                let slow = super::collapse::can_with(m, h, Some(d2), 0);
                assert_eq!(fast, slow, "split {h:?} {d2:?}");
                compared += 1;
            }
        }
    }
    assert!(compared > 10_000);
}

#[test]
fn refusal_text() {
    assert_eq!(
        alloc::format!("{}", Refusal::DegenerateTriangle),
        "a triangle with a repeated corner is involved"
    );
}

// ---------------------------------------------------------------- undo guards, pinned
//
// As in the quad tests: each check of each undo guard has an edit of the map after the
// operation that it is the first to catch: one more operator anywhere, or a raw change of
// one array entry for the checks no operator reaches. Dropping or negating any check changes
// the set of names found.

use crate::map::NONE;
use crate::ops::guard::pin;
use alloc::boxed::Box;
use alloc::collections::BTreeSet;

use pin::Edit;

/// Every triangle operator at every dart of `m` (vertex splits at each dart and the next
/// one or two clockwise).
fn tri_ops(m: &Map) -> Vec<TriOp> {
    let mut ops = Vec::new();
    for d in m.darts() {
        let e = m.rotate_cw(d);
        ops.extend([
            TriOp::Flip(d),
            TriOp::Collapse(d),
            TriOp::SplitEdge(d),
            TriOp::SplitVertex(d, e),
            TriOp::SplitVertex(d, m.rotate_cw(e)),
        ]);
    }
    ops
}

fn caught_t(
    after: &Map,
    raw: Vec<Edit>,
    reason: &dyn Fn(&Map) -> Option<&'static str>,
    undo: &dyn Fn(&mut Map) -> Result<(), Refusal>,
) -> BTreeSet<&'static str> {
    let legit = pin::edits(tri_ops(after), TriOp::apply);
    pin::caught(after, &legit, &raw, reason, undo)
}

fn set(n: &[&'static str]) -> BTreeSet<&'static str> {
    n.iter().copied().collect()
}

#[test]
fn edge_flip_undo_guard_pinned() {
    let base = tri_grid(5);
    let mut got = BTreeSet::new();
    for h in base.darts().filter(|&h| can_flip_edge(&base, h).is_ok()) {
        let (l2, r2) = (base.next(base.next(h)), base.next(base.next(h.twin())));
        let (fa, fb) = (
            base.face_dart(base.face(h).unwrap()),
            base.face_dart(base.face(h.twin()).unwrap()),
        );
        let mut m = base.clone();
        let r = flip_edge(&mut m, h).unwrap();
        let t = h.twin();
        let (h1, t1) = (m.next(m.next(t)), m.next(m.next(h)));
        let (va, vb) = (
            base.vertex_dart(m.origin(t1)),
            base.vertex_dart(m.origin(h1)),
        );
        // A dart far from the flip, spliced into a triangle in place of its second dart.
        let far = m
            .darts()
            .find(|&x| {
                base.face(x) != base.face(h) && base.face(x) != base.face(t) && x.edge() != h.edge()
            })
            .unwrap();
        let mut raw: Vec<Edit> = vec![
            Box::new(move |m| m.next[h.index()] = NONE),
            Box::new(move |m| m.face[h.index()] = NONE),
            Box::new(move |m| m.face[t.index()] = NONE),
            Box::new(move |m| m.next[h.index()] = h.0),
            Box::new(move |m| m.next[t1.index()] = t1.0),
            Box::new(move |m| m.next[h1.index()] = h1.0),
            Box::new(move |m| {
                let i = m.origin(h).index();
                m.vdart[i] = h.0;
            }),
            Box::new(move |m| {
                let i = m.origin(t).index();
                m.vdart[i] = t.0;
            }),
        ];
        if va != h && va != t1 {
            raw.push(Box::new(move |m| {
                let o = m.origin(h).0;
                m.vert[va.index()] = o;
            }));
            raw.push(Box::new(move |m| m.face[va.index()] = NONE));
        }
        if vb != t && vb != h1 {
            raw.push(Box::new(move |m| {
                let o = m.origin(h).0;
                m.vert[vb.index()] = o;
            }));
            raw.push(Box::new(move |m| m.face[vb.index()] = NONE));
        }
        if fa == l2 {
            raw.push(Box::new(move |m| {
                let t1 = m.next(m.next(h));
                m.next[h.index()] = far.0;
                m.next[far.index()] = t1.0;
            }));
        }
        if fb == r2 {
            raw.push(Box::new(move |m| {
                let h1 = m.next(m.next(t));
                m.next[t.index()] = far.0;
                m.next[far.index()] = h1.0;
            }));
        }
        got.extend(caught_t(&m, raw, &|m| r.guard(m).failed(), &|m| r.undo(m)));
    }
    let want = set(&[
        "dart live",
        "face of h",
        "face of twin(h)",
        "triangle of h",
        "triangle of twin(h)",
        "edge once in its triangles",
        "ends",
        "h not recorded",
        "twin(h) not recorded",
        "old record of a leaves a",
        "old record of a on the boundary",
        "old record of b leaves b",
        "old record of b on the boundary",
        "old record of the face of h",
        "old record of the face of twin(h)",
    ]);
    assert_eq!(got, want);
}

#[test]
fn edge_split_undo_guard_pinned() {
    let base = tri_grid(4);
    let mut got = BTreeSet::new();
    for h in base.darts() {
        let mut m = base.clone();
        let r = split_edge(&mut m, h).unwrap();
        let (n, mv) = (r.dart(), r.created());
        let raw: Vec<Edit> = vec![
            Box::new(move |m| m.next[n.index()] = NONE),
            Box::new(move |m| m.vert[n.index()] = 0),
            Box::new(move |m| m.vdart.truncate(mv.index())),
            // The apex c's record names the new spoke c -> m.
            Box::new(move |m| {
                if m.face(h).is_some() {
                    let g = m.next(h).twin();
                    let c = m.origin(g).index();
                    m.vdart[c] = g.0;
                }
            }),
        ];
        got.extend(caught_t(&m, raw, &|m| r.guard(m).failed(), &|m| r.undo(m)));
    }
    let want = set(&[
        "darts live",
        "m is the origin of n and twin(h)",
        "left triangles",
        "right triangles",
        "old records",
        "spokes not recorded",
        "slots releasable",
    ]);
    assert_eq!(got, want);
}

#[test]
fn vertex_split_undo_guard_pinned() {
    let base = tri_grid(4);
    let mut got = BTreeSet::new();
    for d1 in base.darts() {
        let d2 = base.rotate_cw(base.rotate_cw(d1));
        let mut m = base.clone();
        let Ok(r) = split_vertex(&mut m, d1, d2) else {
            continue;
        };
        let e = r.edge();
        let raw: Vec<Edit> = vec![
            Box::new(move |m| m.next[e.index()] = NONE),
            Box::new(move |m| m.face[e.index()] = 999),
        ];
        got.extend(caught_t(&m, raw, &|m| r.guard(m).0.failed(), &|m| {
            r.undo(m)
        }));
    }
    let want = set(&[
        "collapse of the edge applies",
        "new vertex",
        "both triangles",
        "new edges",
        "new faces",
        "old record of w",
        "slots releasable",
    ]);
    assert_eq!(got, want);
}

#[test]
fn edge_collapse_undo_guard_pinned() {
    let base = tri_grid(5);
    let mut got = BTreeSet::new();
    for h in base
        .darts()
        .filter(|&h| can_collapse_edge(&base, h).is_ok())
    {
        let mut m = base.clone();
        let r = collapse_edge(&mut m, h).unwrap();
        let (u, v) = (r.kept(), r.removed());
        let (first, held) = r.held();
        let five = held[..5].iter().map(|d| d.index() | 1).max().unwrap();
        let most = held.iter().map(|d| d.index() | 1).max().unwrap();
        let h1 = base.next(h);
        let interior = base.face(h).is_some() && base.face(h.twin()).is_some();
        let mut raw: Vec<Edit> = vec![
            Box::new(move |m| m.next[h.index()] = 0),
            Box::new(move |m| m.vdart[u.index()] = NONE),
            Box::new(move |m| m.vdart[v.index()] = 0),
            Box::new(move |m| m.vdart.truncate(v.index())),
            Box::new(move |m| {
                let f = *m.free_faces.last().unwrap();
                m.fdart.truncate(f as usize);
            }),
        ];
        let cut = |m: &mut Map, at: usize| {
            m.next.truncate(at);
            m.vert.truncate(at);
            m.face.truncate(at);
        };
        if first != Dart(NONE) && first.index() > five {
            raw.push(Box::new(move |m| cut(m, first.index() & !1)));
        }
        if most > five.max(first.index() | 1) {
            raw.push(Box::new(move |m| cut(m, most & !1)));
        }
        if interior {
            // h1 keeps its place but leaves another vertex, or lies in another face.
            let c = base.dest(h1);
            raw.push(Box::new(move |m| m.vert[h1.index()] = c.0));
            raw.push(Box::new(move |m| m.face[h1.index()] = 999));
        }
        got.extend(caught_t(&m, raw, &|m| r.guard(m).failed(), &|m| r.undo(m)));
    }
    let want = set(&[
        "collapsed edge dead",
        "left side",
        "right side",
        "kept vertex live",
        "removed vertex dead",
        "apexes live",
        "faces in range",
        "moved arc in range",
        "old values in range",
        "rewritten successors",
        "freed slots on the free lists",
        "moved arc",
        "restored successors",
        "restored vertex records",
        "restored face records",
    ]);
    assert_eq!(got, want);
}

/// Reports name each operator as its documentation does (one name per operator).
#[test]
fn operator_names() {
    let d = Dart(0);
    let names = [
        TriOp::Flip(d),
        TriOp::Collapse(d),
        TriOp::SplitVertex(d, d),
        TriOp::SplitEdge(d),
    ]
    .map(TriOp::name);
    assert_eq!(names, ["flip", "collapse", "vertex split", "edge split"]);
}

/// A record's dart is a dead slot only inside the arrays: a slot past their end (the
/// arrays were cut) is no slot at all, and the undo must not take it for a freed one.
#[test]
fn dead_slots_lie_inside_the_arrays() {
    let mut m = tri_grid(3);
    let h = m
        .darts()
        .find(|&h| can_collapse_edge(&m, h).is_ok())
        .unwrap();
    collapse_edge(&mut m, h).unwrap();
    let end = m.dart_slots() as u32;
    assert!(super::collapse::is_dead(&m, h));
    assert!(!super::collapse::is_dead(&m, Dart(end)));
    let live = m.darts().next().unwrap();
    assert!(!super::collapse::is_dead(&m, live));
}
