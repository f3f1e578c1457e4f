//! Unit tests: one small hand-built map per refusal reason of every operator, the success
//! cases on grids, tori and cubes with exact deltas, and the known failures of other kernels.

use super::*;
use crate::gen;
use crate::map::{Dart, Map, Vert};
use crate::ops::Refusal;
use alloc::vec;
use alloc::vec::Vec;

/// The dart from `u` to `v` (panics if there is none: test maps are built to have it).
fn dart(m: &Map, u: u32, v: u32) -> Dart {
    m.darts()
        .find(|&d| m.origin(d) == Vert(u) && m.dest(d) == Vert(v) && m.face(d).is_some())
        .or_else(|| {
            m.darts()
                .find(|&d| m.origin(d) == Vert(u) && m.dest(d) == Vert(v))
        })
        .expect("no such dart")
}

fn polys(n: usize, faces: &[&[u32]]) -> Map {
    Map::from_polygons(n, faces).expect("test map")
}

/// Two quads glued along their boundary: a sphere whose four vertices have valence 2.
fn pillow() -> Map {
    polys(4, &[&[0, 1, 2, 3], &[0, 3, 2, 1]])
}

/// Three quads between the poles 0 and 1 (valence 3) and the equator 2, 3, 4 (valence 2).
fn three_quad_sphere() -> Map {
    polys(5, &[&[0, 2, 1, 3], &[0, 3, 1, 4], &[0, 4, 1, 2]])
}

/// The torus made of one quad: one vertex, two loops.
fn one_quad_torus() -> Map {
    Map::from_permutation(&[2, 3, 1, 0], &[false; 4]).unwrap()
}

/// A sphere of two digons: two vertices joined by two edges.
fn digons() -> Map {
    Map::from_permutation(&[3, 2, 1, 0], &[false; 4]).unwrap()
}

/// A sphere cut along a path 1 - 0 - 2: one face of degree 4, vertex 0 of valence 2.
fn path() -> Map {
    Map::from_permutation(&[1, 2, 3, 0], &[false; 4]).unwrap()
}

fn valences(m: &Map) -> Vec<usize> {
    (0..m.vertex_slots())
        .map(|v| m.valence(Vert(v as u32)))
        .collect()
}

fn counts(m: &Map) -> (usize, usize, usize) {
    (m.num_vertices(), m.num_edges(), m.num_faces())
}

/// Applies `op`, checks validity and that undo restores the map exactly; returns the map
/// after the operation.
fn applied(m: &Map, op: impl FnOnce(&mut Map) -> Result<QuadRecord, Refusal>) -> Map {
    let mut after = m.clone();
    let rec = op(&mut after).expect("operator refused");
    assert_eq!(after.check(), Ok(()));
    let mut back = after.clone();
    rec.undo(&mut back).expect("undo");
    assert_eq!(&back, m);
    after
}

/// The refusal `op` gives, checking that the map is untouched.
fn refused<R: core::fmt::Debug>(
    m: &Map,
    op: impl FnOnce(&mut Map) -> Result<R, Refusal>,
) -> Refusal {
    let mut after = m.clone();
    let r = op(&mut after).expect_err("operator applied");
    assert_eq!(&after, m);
    r
}

// ------------------------------------------------------------------ quad collapse

#[test]
fn collapse_refusals() {
    let torus = gen::torus_grid(4, 4).map;
    let c = |m: &Map, d: Dart| {
        let r = refused(m, |m| collapse_quad(m, d));
        assert_eq!(can_collapse_quad(m, d), Err(r));
        r
    };
    assert_eq!(c(&torus, Dart(10_000)), Refusal::DeadHandle);
    let square = gen::grid(1, 1).map;
    let outside = square.vertex_dart(Vert(0));
    assert_eq!(c(&square, outside), Refusal::Boundary);
    let tri = polys(3, &[&[0, 1, 2]]);
    assert_eq!(c(&tri, Dart(0)), Refusal::WrongDegree);
    assert_eq!(c(&one_quad_torus(), Dart(0)), Refusal::CornersCoincide);
    // A triangle on the far side of 0-3 and 3-2 adds the edge 2-0, which would become a loop.
    let diag = polys(4, &[&[0, 1, 2, 3], &[0, 3, 2]]);
    assert_eq!(c(&diag, dart(&diag, 0, 1)), Refusal::Loop);
    // The poles share the third equator vertex: merging them doubles an edge.
    let s = three_quad_sphere();
    assert_eq!(c(&s, dart(&s, 0, 2)), Refusal::MultiEdge);
    // The middle quad of a 3 x 1 strip: all four corners on the boundary.
    let strip = gen::grid(3, 1).map;
    assert_eq!(c(&strip, dart(&strip, 1, 2)), Refusal::BoundaryPinch);
    // The pillow: b and d have valence 2 and would keep one edge.
    let p = pillow();
    assert_eq!(c(&p, Dart(0)), Refusal::ValenceTooLow);
    // Only d (vertex 3) has valence 2: quad 0-1-2-3 beside a pentagon through 0-3-2, on a
    // closed sphere, so that no other rule applies. Refused from either diagonal end, since
    // d is b for the other end. ValenceTooLow is the last rule checked, so every other rule
    // passes here.
    let m = polys(
        7,
        &[
            &[0, 1, 2, 3],
            &[0, 3, 2, 4, 5],
            &[0, 5, 6, 1],
            &[6, 5, 4, 2, 1],
        ],
    );
    assert_eq!(m.valence(Vert(3)), 2);
    assert_eq!(m.valence(Vert(1)), 3);
    assert_eq!(c(&m, dart(&m, 0, 1)), Refusal::ValenceTooLow);
    assert_eq!(c(&m, dart(&m, 2, 3)), Refusal::ValenceTooLow);
}

/// A closed map from faces given as dart lists (`2e` runs from the first to the second end of
/// edge `e`, `2e + 1` back): lets tests build multi-edges, which polygon lists cannot.
fn from_dart_faces(faces: &[&[u32]]) -> Map {
    let n = faces.iter().map(|f| f.len()).sum::<usize>();
    let mut next = vec![0u32; n];
    for f in faces {
        for (i, &d) in f.iter().enumerate() {
            next[d as usize] = f[(i + 1) % f.len()];
        }
    }
    Map::from_permutation(&next, &vec![false; n]).unwrap()
}

/// Two quads F = (u, v, x, y) and G = (v, u, z, w) whose ends u, v are also joined by a
/// second edge (the sphere is closed by two more quads along it).
fn rotation_with_parallel_edge() -> Map {
    // Edges: 0 u-v, 1 v-x, 2 x-y, 3 y-u, 4 u-z, 5 z-w, 6 w-v, 7 u-v (parallel).
    from_dart_faces(&[
        &[0, 2, 4, 6],    // F: u->v->x->y
        &[1, 8, 10, 12],  // G: v->u->z->w
        &[7, 5, 3, 15],   // u->y->x->v, back to u along edge 7
        &[14, 13, 11, 9], // u->v along edge 7, v->w->z->u
    ])
}

#[test]
fn collapse_on_torus_grid_and_cube() {
    for m in [
        gen::torus_grid(5, 4).map,
        gen::grid(4, 4).map,
        gen::cube(3).map,
    ] {
        let mut n = 0;
        for d in m.darts() {
            if can_collapse_quad(&m, d).is_err() {
                continue;
            }
            n += 1;
            let [a, b, c, e] = [0, 1, 2, 3].map(|k| {
                let mut x = d;
                for _ in 0..k {
                    x = m.next(x);
                }
                m.origin(x)
            });
            let before = valences(&m);
            let after = applied(&m, |m| collapse_quad(m, d).map(Into::into));
            let (v, e0, f) = counts(&m);
            assert_eq!(counts(&after), (v - 1, e0 - 2, f - 1));
            let now = valences(&after);
            for (i, (&x, &y)) in before.iter().zip(&now).enumerate() {
                let want = match Vert(i as u32) {
                    w if w == a => before[a.index()] + before[c.index()] - 2,
                    w if w == b || w == e => x - 1,
                    w if w == c => 0,
                    _ => x,
                };
                assert_eq!(y, want, "vertex {i} after collapse at {d:?}");
            }
        }
        assert!(n > 0);
    }
}

/// VCGLib's diagonal collapse applied only half of the boundary rule. Here: one merged corner
/// on the boundary is fine from either side, both are refused from either side, and the
/// merged vertex records its boundary dart.
#[test]
fn collapse_boundary_rule_from_both_corners() {
    let g = gen::grid(3, 3).map;
    // Corner quad (0, 1, 5, 4): 0 is a boundary corner, 5 interior.
    for (u, v) in [(0, 1), (5, 4)] {
        let d = dart(&g, u, v);
        let after = applied(&g, |m| collapse_quad(m, d).map(Into::into));
        let kept = g.origin(d);
        assert!(after.is_boundary_vertex(kept));
        assert!(after.is_boundary_dart(after.vertex_dart(kept)));
    }
    // The middle quad (1, 2, 6, 5) of a 3 x 1 strip: both diagonals join two boundary
    // vertices; refused from either end.
    let strip = gen::grid(3, 1).map;
    for (u, v) in [(1, 2), (6, 5)] {
        let d = dart(&strip, u, v);
        assert_eq!(can_collapse_quad(&strip, d), Err(Refusal::BoundaryPinch));
    }
}

/// pmp issue 245: a collapse that leaves an interior valence-2 vertex. Here it is a
/// documented choice: a `b` of valence 3 may end with valence 2 (Q-zip removes it later),
/// valence 1 is refused, and the valence-2 vertex can then be removed.
#[test]
fn collapse_leaving_valence_two_then_removal() {
    let m = gen::cube(2).map;
    // A quad (corner, m1, centre, m2) at a cube corner of valence 3: collapse at m2 -> corner
    // merges the edge midpoints m2 and m1, so b is the corner.
    let corner = m.vertices().find(|&v| m.valence(v) == 3).unwrap();
    let d0 = m.vertex_dart(corner);
    let d = m.next(m.next(m.next(d0)));
    assert_eq!(m.origin(m.next(d)), corner);
    let mut after = m.clone();
    let rec = collapse_quad(&mut after, d).unwrap();
    assert_eq!(after.valence(corner), 2);
    assert!(!after.is_boundary_vertex(corner));
    assert_eq!(after.check(), Ok(()));
    // The new valence-2 vertex lies between two quads with distinct corners: removable.
    let x = after.vertex_dart(corner);
    let mut removed = after.clone();
    let r2 = remove_valence2(&mut removed, x).unwrap();
    assert_eq!(removed.check(), Ok(()));
    assert!(removed.faces().all(|f| removed.degree(f) == 4));
    r2.undo(&mut removed).unwrap();
    assert_eq!(removed, after);
    rec.undo(&mut after).unwrap();
    assert_eq!(after, m);
}

// ------------------------------------------------------------------ vertex split

#[test]
fn split_refusals() {
    let torus = gen::torus_grid(4, 4).map;
    let c = |m: &Map, s1: Dart, s2: Dart| {
        let r = refused(m, |m| split_vertex(m, s1, s2));
        assert_eq!(can_split_vertex(m, s1, s2), Err(r));
        r
    };
    let s1 = torus.vertex_dart(Vert(5));
    assert_eq!(c(&torus, s1, Dart(10_000)), Refusal::DeadHandle);
    assert_eq!(c(&torus, s1, s1), Refusal::BadArguments);
    let other = torus.vertex_dart(Vert(6));
    assert_eq!(c(&torus, s1, other), Refusal::BadArguments);
    assert_eq!(c(&one_quad_torus(), Dart(0), Dart(2)), Refusal::Loop);
    assert_eq!(c(&digons(), Dart(0), Dart(2)), Refusal::MultiEdge);
    // Vertex 0 of the path joins two vertices of valence 1.
    assert_eq!(c(&path(), Dart(0), Dart(2)), Refusal::ValenceTooLow);
}

#[test]
fn split_deltas_every_pair_on_a_torus_vertex() {
    let m = gen::torus_grid(4, 4).map;
    let w = Vert(5);
    let darts: Vec<Dart> = m.vertex_darts(w).collect();
    for (i, &s1) in darts.iter().enumerate() {
        for (j, &s2) in darts.iter().enumerate() {
            if i == j {
                continue;
            }
            let arc1 = (j + 4 - i) % 4 - 1;
            let arc2 = 4 - 2 - arc1;
            let mut after = m.clone();
            let r = split_vertex(&mut after, s1, s2).unwrap();
            assert_eq!(after.check(), Ok(()));
            assert_eq!(r.kept(), w);
            assert_eq!(after.origin(s1), w);
            assert_eq!(after.origin(s2), r.created());
            assert_eq!(after.valence(w), arc1 + 2);
            assert_eq!(after.valence(r.created()), arc2 + 2);
            assert_eq!(after.valence(m.dest(s1)), 5);
            assert_eq!(after.valence(m.dest(s2)), 5);
            assert_eq!(counts(&after), (17, 34, 17));
            assert_eq!(after.degree(r.face()), 4);
            r.undo(&mut after).unwrap();
            assert_eq!(after, m);
        }
    }
}

/// Every split of a boundary vertex is allowed and leaves exactly one copy on the boundary.
#[test]
fn split_boundary_vertex_every_pair() {
    let m = gen::grid(3, 3).map;
    for v in m.vertices().filter(|&v| m.is_boundary_vertex(v)) {
        let darts: Vec<Dart> = m.vertex_darts(v).collect();
        for &s1 in &darts {
            for &s2 in &darts {
                if s1 == s2 {
                    continue;
                }
                let mut after = m.clone();
                let r = split_vertex(&mut after, s1, s2).unwrap();
                assert_eq!(after.check(), Ok(()));
                let on_boundary = [r.kept(), r.created()]
                    .iter()
                    .filter(|&&x| after.is_boundary_vertex(x))
                    .count();
                assert_eq!(on_boundary, 1);
                // The inverse collapse is allowed (one merged corner on the boundary).
                assert_eq!(can_collapse_quad(&after, s1), Ok(()));
                r.undo(&mut after).unwrap();
                assert_eq!(after, m);
            }
        }
    }
}

#[test]
fn split_then_collapse_and_collapse_then_split_restore_the_code() {
    use crate::invariants::canonical::CanonicalCode;
    let m = gen::torus_grid(5, 5).map;
    let code = CanonicalCode::of(&m);
    let s1 = m.vertex_dart(Vert(7));
    let s2 = m.rotate_cw(m.rotate_cw(s1));
    let mut x = m.clone();
    split_vertex(&mut x, s1, s2).unwrap();
    collapse_quad(&mut x, s1).unwrap();
    assert_eq!(CanonicalCode::of(&x), code);
    assert_eq!(x.check(), Ok(()));
    let mut y = m.clone();
    let c = collapse_quad(&mut y, Dart(0)).unwrap();
    let [to_b, to_d] = c.merged_edges();
    split_vertex(&mut y, to_b, to_d).unwrap();
    assert_eq!(CanonicalCode::of(&y), code);
}

// ------------------------------------------------------------------ high-valence split

#[test]
fn high_valence_refusals_and_deltas() {
    let torus = gen::torus_grid(5, 5).map;
    let v = Vert(0);
    let first = torus.vertex_dart(v);
    let c = |m: &Map, v: Vert, d: Dart| {
        let r = refused(m, |m| split_high_valence(m, v, d));
        assert_eq!(can_split_high_valence(m, v, d), Err(r));
        r
    };
    assert_eq!(c(&torus, Vert(999), first), Refusal::DeadHandle);
    assert_eq!(
        c(&torus, v, torus.vertex_dart(Vert(1))),
        Refusal::BadArguments
    );
    assert_eq!(c(&torus, v, first), Refusal::WrongValence);
    // A single vertex with three loops (valence 6): the split's own Loop refusal.
    let bouquet = (0..720u32)
        .filter_map(|k| {
            let mut pool: Vec<u32> = (0..6).collect();
            let mut k = k as usize;
            let next: Vec<u32> = (1..=6)
                .rev()
                .map(|n| {
                    let x = pool.remove(k % n);
                    k /= n;
                    x
                })
                .collect();
            Map::from_permutation(&next, &[false; 6]).ok()
        })
        .find(|m| m.num_vertices() == 1)
        .unwrap();
    let b = Vert(0);
    assert_eq!(bouquet.valence(b), 6);
    assert_eq!(c(&bouquet, b, bouquet.vertex_dart(b)), Refusal::Loop);
    // Valences 6 to 9 made by collapses on a torus; each split gives floor/ceil halves + 1.
    let mut m = torus.clone();
    collapse_quad(&mut m, Dart(0)).unwrap();
    for k in 6..=9 {
        let w = m.origin(Dart(0));
        assert_eq!(m.valence(w), k);
        for d in m.vertex_darts(w).collect::<Vec<_>>() {
            let mut x = m.clone();
            let r = split_high_valence(&mut x, w, d).unwrap();
            assert_eq!(x.check(), Ok(()));
            assert_eq!(x.valence(r.kept()), k / 2 + 1);
            assert_eq!(x.valence(r.created()), k - k / 2 + 1);
            r.undo(&mut x).unwrap();
            assert_eq!(x, m);
        }
        // A doublet with w at one end of its diagonal raises w by one.
        let f = m.face(Dart(0)).unwrap();
        let d = m.face_darts(f).find(|&d| m.origin(d) == w).unwrap();
        insert_doublet(&mut m, d).unwrap();
    }
}

// ------------------------------------------------------------------ valence-2 removal

#[test]
fn removal_refusals() {
    let c = |m: &Map, x: Dart| {
        let r = refused(m, |m| remove_valence2(m, x));
        assert_eq!(can_remove_valence2(m, x), Err(r));
        r
    };
    let torus = gen::torus_grid(4, 4).map;
    assert_eq!(c(&torus, Dart(10_000)), Refusal::DeadHandle);
    let square = gen::grid(1, 1).map;
    assert_eq!(c(&square, square.vertex_dart(Vert(0))), Refusal::Boundary);
    assert_eq!(c(&torus, Dart(0)), Refusal::WrongValence);
    assert_eq!(c(&path(), Dart(0)), Refusal::SameFace);
    let quad_pentagon = polys(6, &[&[0, 1, 2, 3], &[0, 3, 4, 5, 1]]);
    assert_eq!(
        c(&quad_pentagon, dart(&quad_pentagon, 0, 1)),
        Refusal::WrongDegree
    );
    assert_eq!(c(&pillow(), Dart(0)), Refusal::CornersCoincide);
}

#[test]
fn removal_deltas() {
    let m = gen::torus_grid(4, 4).map;
    for d in m.darts() {
        let mut x = m.clone();
        let ins = insert_doublet(&mut x, d).unwrap();
        let v = ins.vertex();
        let (p, q) = (m.origin(d), m.origin(m.next(m.next(d))));
        for y in x.vertex_darts(v).collect::<Vec<_>>() {
            let before = valences(&x);
            let after = applied(&x, |m| remove_valence2(m, y).map(Into::into));
            assert_eq!(counts(&after), (16, 32, 16));
            let now = valences(&after);
            for (i, (&a, &b)) in before.iter().zip(&now).enumerate() {
                let w = Vert(i as u32);
                let want = if w == v {
                    0
                } else if w == p || w == q {
                    a - 1
                } else {
                    a
                };
                assert_eq!(b, want);
            }
            assert!(after.faces().all(|f| after.degree(f) == 4));
        }
    }
}

// ------------------------------------------------------------------ doublet insertion

#[test]
fn insertion_refusals_and_deltas() {
    let c = |m: &Map, d: Dart| {
        let r = refused(m, |m| insert_doublet(m, d));
        assert_eq!(can_insert_doublet(m, d), Err(r));
        r
    };
    let g = gen::grid(2, 2).map;
    assert_eq!(c(&g, Dart(10_000)), Refusal::DeadHandle);
    assert_eq!(c(&g, g.vertex_dart(Vert(0))), Refusal::Boundary);
    assert_eq!(c(&polys(3, &[&[0, 1, 2]]), Dart(0)), Refusal::WrongDegree);
    assert_eq!(c(&one_quad_torus(), Dart(0)), Refusal::CornersCoincide);
    for d in g.darts().filter(|&d| g.face(d).is_some()) {
        let before = valences(&g);
        let after = applied(&g, |m| insert_doublet(m, d).map(Into::into));
        assert_eq!(counts(&after), (10, 14, 5));
        let (p, q) = (g.origin(d), g.origin(g.next(g.next(d))));
        let now = valences(&after);
        assert_eq!(now[9], 2);
        for (i, &a) in before.iter().enumerate() {
            let w = Vert(i as u32);
            assert_eq!(now[i], a + usize::from(w == p || w == q));
        }
        assert!(after.faces().all(|f| after.degree(f) == 4));
    }
}

// ------------------------------------------------------------------ edge rotation

#[test]
fn rotation_refusals() {
    let c = |m: &Map, h: Dart, r: Rotation| {
        let x = refused(m, |m| rotate_edge(m, h, r));
        assert_eq!(can_rotate_edge(m, h, r), Err(x));
        x
    };
    let cw = Rotation::Clockwise;
    let torus = gen::torus_grid(4, 4).map;
    assert_eq!(c(&torus, Dart(10_000), cw), Refusal::DeadHandle);
    let g = gen::grid(2, 1).map;
    assert_eq!(c(&g, dart(&g, 0, 1), cw), Refusal::Boundary);
    assert_eq!(c(&path(), Dart(0), cw), Refusal::SameFace);
    let qt = polys(5, &[&[0, 1, 2, 3], &[1, 0, 4]]);
    assert_eq!(c(&qt, dart(&qt, 0, 1), cw), Refusal::WrongDegree);
    assert_eq!(c(&pillow(), Dart(0), cw), Refusal::CornersCoincide);
    // The hexagon (1, 2, 3, 0, 4, 5) of edge 0-1; a third face joins 2 and 4 already.
    let m = polys(6, &[&[0, 1, 2, 3], &[1, 0, 4, 5], &[2, 4, 0, 3]]);
    let h = dart(&m, 0, 1);
    assert_eq!(c(&m, h, Rotation::CounterClockwise), Refusal::MultiEdge);
    // Clockwise the new ends are 3 and 5, which are not joined: allowed.
    assert_eq!(can_rotate_edge(&m, h, cw), Ok(()));
    // A second edge joins the old ends: rotating would remove one of a pair of parallel edges
    // and the inverse rotation would recreate it; refused both ways.
    let m = rotation_with_parallel_edge();
    assert_eq!(m.check(), Ok(()));
    let (u, v) = (m.origin(Dart(0)), m.dest(Dart(0)));
    assert_eq!(m.dest(Dart(14)), v);
    assert_eq!(m.origin(Dart(14)), u);
    for r in [cw, Rotation::CounterClockwise] {
        assert_eq!(c(&m, Dart(0), r), Refusal::MultiEdge);
    }
}

#[test]
fn rotation_deltas_and_inverse() {
    let m = gen::grid(2, 1).map;
    let h = dart(&m, 1, 4);
    for (dir, ends) in [
        (Rotation::CounterClockwise, (2, 3)),
        (Rotation::Clockwise, (0, 5)),
    ] {
        let after = applied(&m, |m| rotate_edge(m, h, dir).map(Into::into));
        assert_eq!(
            (after.origin(h), after.dest(h)),
            (Vert(ends.0), Vert(ends.1))
        );
        assert_eq!(counts(&after), counts(&m));
        let (b, a) = (valences(&m), valences(&after));
        for i in 0..6 {
            let want = match i {
                1 | 4 => b[i] - 1,
                i if i == ends.0 as usize || i == ends.1 as usize => b[i] + 1,
                _ => b[i],
            };
            assert_eq!(a[i], want);
        }
        // Rotating back the other way as an ordinary operator brings the edge back.
        let mut back = after.clone();
        rotate_edge(&mut back, h, dir.reverse()).unwrap();
        assert_eq!(back.check(), Ok(()));
        assert_eq!((back.origin(h), back.dest(h)), (Vert(1), Vert(4)));
    }
}

// ------------------------------------------------------------------ shared pieces

#[test]
fn neighbour_lists_inline_and_on_the_heap() {
    // One neighbour repeated at once is the smallest repeat the filter must not pass.
    for n in [1usize, 3, 31, 32, 33, 100] {
        let mut nb = Neighbours::new();
        for i in 0..n {
            nb.push(Vert(10 + i as u32));
        }
        assert_eq!(nb.check([Vert(0), Vert(1)]), Ok(()));
        nb.push(Vert(10 + n as u32 / 2));
        assert_eq!(nb.check([Vert(0), Vert(1)]), Err(Refusal::MultiEdge));
        nb.push(Vert(1));
        assert_eq!(nb.check([Vert(0), Vert(1)]), Err(Refusal::Loop));
    }
}

/// A fan of 40 quads: the centre's valence (40) takes the neighbour list past its inline part.
#[test]
fn high_valence_fan() {
    let n = 40u32;
    let faces: Vec<Vec<u32>> = (0..n)
        .map(|i| vec![0, 1 + 2 * i, 2 + 2 * i, 1 + (2 * i + 2) % (2 * n)])
        .collect();
    let m = Map::from_polygons(1 + 2 * n as usize, &faces).unwrap();
    let c = Vert(0);
    assert_eq!(m.valence(c), n as usize);
    let s1 = m.vertex_dart(c);
    let s2 = m.rotate_cw(m.rotate_cw(s1));
    applied(&m, |m| split_vertex(m, s1, s2).map(Into::into));
    applied(&m, |m| split_high_valence(m, c, s1).map(Into::into));
    // Merge the centre with an outer corner: valence 40 + 2 - 2.
    let after = applied(&m, |m| collapse_quad(m, s1).map(Into::into));
    assert_eq!(after.valence(c), 40);
}

#[test]
fn stale_records_are_refused_without_change() {
    let m = gen::torus_grid(4, 4).map;
    let mut x = m.clone();
    let r1 = collapse_quad(&mut x, Dart(0)).unwrap();
    let d2 = x
        .darts()
        .find(|&d| can_collapse_quad(&x, d).is_ok())
        .unwrap();
    let r2 = collapse_quad(&mut x, d2).unwrap();
    // Undoing the first before the second: its slots are not on top of the free lists.
    let snapshot = x.clone();
    assert_eq!(r1.clone().undo(&mut x), Err(Refusal::StaleRecord));
    assert_eq!(x, snapshot);
    r2.undo(&mut x).unwrap();
    r1.undo(&mut x).unwrap();
    assert_eq!(x, m);
    // A split's record after its quad was collapsed by hand.
    let mut y = m.clone();
    let s1 = y.vertex_dart(Vert(5));
    let s2 = y.rotate_cw(s1);
    let r = split_vertex(&mut y, s1, s2).unwrap();
    collapse_quad(&mut y, s1).unwrap();
    let snapshot = y.clone();
    assert_eq!(r.undo(&mut y), Err(Refusal::StaleRecord));
    assert_eq!(y, snapshot);
    // Rotation records and doublet records likewise.
    let mut z = m.clone();
    let rr = rotate_edge(&mut z, Dart(0), Rotation::Clockwise).unwrap();
    rotate_edge(&mut z, Dart(0), Rotation::CounterClockwise).unwrap();
    let snapshot = z.clone();
    assert_eq!(rr.undo(&mut z), Err(Refusal::StaleRecord));
    assert_eq!(z, snapshot);
    let mut w = m.clone();
    let ins = insert_doublet(&mut w, Dart(0)).unwrap();
    remove_valence2(&mut w, ins.darts()[0]).unwrap();
    let snapshot = w.clone();
    assert_eq!(ins.undo(&mut w), Err(Refusal::StaleRecord));
    assert_eq!(w, snapshot);
}

#[test]
fn mesh_wrappers_place_and_restore() {
    use glam::DVec3;
    let mesh = gen::grid(2, 2);
    let mut m = mesh.clone();
    let d = m.map.face_dart(crate::map::Face(0));
    let (p, q) = (m.map.origin(d), m.map.origin(m.map.next(m.map.next(d))));
    let e = QuadOp::InsertDoublet(d).apply(&mut m).unwrap();
    let v = crate::ops::VertexChanges::created_vertex(&e).unwrap();
    assert_eq!(
        m.positions[v.index()],
        (mesh.positions[p.index()] + mesh.positions[q.index()]) / 2.0
    );
    assert_eq!(m.positions.len(), m.map.vertex_slots());
    e.undo(&mut m).unwrap();
    assert_eq!(m, mesh);
    // A split placing its new vertex into a reused slot: undo puts the old position back.
    let mut t = gen::torus_grid(4, 4);
    let t0 = t.clone();
    let c = QuadOp::Collapse(Dart(0)).apply(&mut t).unwrap();
    // The edit changes the vertices its record does (the record's removed one is not 0).
    let removed = crate::ops::VertexChanges::removed_vertex(c.record());
    assert!(removed.is_some_and(|v| v != Vert(0)));
    assert_eq!(crate::ops::VertexChanges::removed_vertex(&c), removed);
    let t1 = t.clone();
    let s1 = t.map.vertex_dart(Vert(9));
    let s2 = t.map.rotate_cw(t.map.rotate_cw(s1));
    let s = QuadOp::Split(s1, s2).apply(&mut t).unwrap();
    assert_ne!(t.positions, t1.positions);
    assert!(t.positions.iter().all(|p| p.is_finite()));
    s.undo(&mut t).unwrap();
    assert_eq!(t, t1);
    c.undo(&mut t).unwrap();
    assert_eq!(t, t0);
    assert!(t.positions.iter().all(|p| *p != DVec3::splat(f64::NAN)));
}

// ---------------------------------------------------------------- undo guards, pinned
//
// Each check of each undo guard has an edit of the map after the operation that it alone
// catches (it is the first check to fail): one more operator anywhere on the map, or, for
// the checks no operator reaches (indices out of range, records that cannot arise), a raw
// change of one array entry. Dropping or negating any check changes the set of names found.

use crate::ops::guard::pin;
use crate::ops::guard::Guard;
use alloc::boxed::Box;
use alloc::collections::BTreeSet;

use pin::Edit;

/// Every quad operator at every dart of `m` (splits at each dart and the dart two steps on).
fn quad_ops(m: &Map) -> Vec<QuadOp> {
    let mut ops = Vec::new();
    for d in m.darts() {
        ops.extend([
            QuadOp::Collapse(d),
            QuadOp::HighValence(d),
            QuadOp::RemoveValence2(d),
            QuadOp::InsertDoublet(d),
            QuadOp::Rotate(d, Rotation::Clockwise),
            QuadOp::Rotate(d, Rotation::CounterClockwise),
            QuadOp::Split(d, m.rotate_cw(m.rotate_cw(d))),
            QuadOp::Split(d, m.rotate_cw(d)),
        ]);
    }
    ops
}

/// The names of the checks that catch one more operator anywhere, or one of the `raw` edits.
fn caught_q(
    after: &Map,
    raw: Vec<Edit>,
    reason: &dyn Fn(&Map) -> Option<&'static str>,
    undo: &dyn Fn(&mut Map) -> Result<(), Refusal>,
) -> BTreeSet<&'static str> {
    let legit = pin::edits(quad_ops(after), QuadOp::apply);
    pin::caught(after, &legit, &raw, reason, undo)
}

fn names(g: &Guard) -> Option<&'static str> {
    g.failed()
}

fn set(n: &[&'static str]) -> BTreeSet<&'static str> {
    n.iter().copied().collect()
}

/// Cuts the dart arrays off at `d` (so `d` and every later dart are out of range).
fn cut_darts(m: &mut Map, d: Dart) {
    m.next.truncate(d.index());
    m.vert.truncate(d.index());
    m.face.truncate(d.index());
}

#[test]
fn quad_collapse_undo_guard_pinned() {
    let base = gen::torus_grid(4, 4).map;
    // A collapse whose first freed edge comes before the second (so each can be cut alone).
    let (m, r) = base
        .darts()
        .find_map(|d| {
            let mut m = base.clone();
            let r = collapse_quad(&mut m, d).ok()?;
            let n = m.free_edges.len();
            (m.free_edges[n - 2] < m.free_edges[n - 1]).then_some((m, r))
        })
        .unwrap();
    let n = m.free_edges.len();
    let (h1, h3) = (Dart(2 * m.free_edges[n - 2]), Dart(2 * m.free_edges[n - 1]));
    let [h0, h2] = r.merged_edges();
    let (a, c, f) = (r.kept(), r.removed(), r.face());
    let (b, d) = (m.dest(h0), m.dest(h2));
    let other = m.vertex_darts(a).find(|&x| x != h0 && x != h2).unwrap();
    let raw: Vec<Edit> = vec![
        Box::new(move |m| m.vdart.truncate(c.index())),
        Box::new(move |m| m.fdart.truncate(f.index())),
        Box::new(move |m| cut_darts(m, h1)),
        Box::new(move |m| cut_darts(m, h3)),
        Box::new(move |m| m.next[h0.index()] = NONE),
        Box::new(move |m| m.next[h2.index()] = NONE),
        Box::new(move |m| m.vert[h0.index()] = b.0),
        Box::new(move |m| m.vert[h2.index()] = b.0),
        Box::new(move |m| m.vert[h0.twin().index()] = d.0),
        Box::new(move |m| m.vert[h2.twin().index()] = b.0),
        Box::new(move |m| m.vdart[c.index()] = 0),
        Box::new(move |m| m.fdart[f.index()] = 0),
        // A second edge a-b: the split refuses the multi-edge.
        Box::new(move |m| m.vert[other.twin().index()] = b.0),
    ];
    let got = caught_q(&m, raw, &|m| names(&r.guard(m).0), &|m| r.undo(m));
    let want = set(&[
        "removed vertex in range",
        "face in range",
        "h1 in range",
        "h3 in range",
        "h0 live",
        "h2 live",
        "h0 leaves a",
        "h2 leaves a",
        "h0 ends at b",
        "h2 ends at d",
        "removed vertex dead",
        "face dead",
        "split applies",
        "freed slots on the free lists",
    ]);
    assert_eq!(got, want);
}

#[test]
fn vertex_split_undo_guard_pinned() {
    let mut m = gen::torus_grid(4, 4).map;
    let s1 = m.vertex_dart(Vert(5));
    let s2 = m.rotate_cw(m.rotate_cw(s1));
    let r = split_vertex(&mut m, s1, s2).unwrap();
    let [h0, ..] = r.quad();
    let other = m.face(h0.twin()).unwrap();
    let raw: Vec<Edit> = vec![
        Box::new(move |m| m.next[h0.index()] = NONE),
        Box::new(move |m| m.face[h0.index()] = other.0),
    ];
    let got = caught_q(&m, raw, &|m| names(&r.guard(m).0), &|m| r.undo(m));
    let want = set(&[
        "collapse applies",
        "same quad",
        "same corners",
        "same face",
        "slots releasable",
    ]);
    assert_eq!(got, want);
}

#[test]
fn valence2_removal_undo_guard_pinned() {
    let base = gen::torus_grid(4, 4).map;
    let (m, r) = base
        .darts()
        .find_map(|d| {
            let mut m = base.clone();
            let ins = insert_doublet(&mut m, d).ok()?;
            let x = m.vertex_dart(ins.vertex());
            let r = remove_valence2(&mut m, x).ok()?;
            let n = m.free_edges.len();
            (m.free_edges[n - 2] < m.free_edges[n - 1]).then_some((m, r))
        })
        .unwrap();
    let n = m.free_edges.len();
    let (x, y) = (Dart(2 * m.free_edges[n - 2]), Dart(2 * m.free_edges[n - 1]));
    let (v, g) = (r.removed(), Face(*m.free_faces.last().unwrap()));
    let kept = r.face();
    let raw: Vec<Edit> = vec![
        Box::new(move |m| cut_darts(m, x)),
        Box::new(move |m| cut_darts(m, y)),
        Box::new(move |m| m.vdart.truncate(v.index())),
        Box::new(move |m| m.fdart.truncate(g.index())),
        Box::new(move |m| m.next[x.index()] = 0),
        Box::new(move |m| m.next[y.index()] = 0),
        // Two equal corners in the merged quad: the insertion refuses.
        Box::new(move |m| {
            let q = m.face_dart(kept);
            let (i, o) = (m.next(q).index(), m.origin(q).0);
            m.vert[i] = o;
        }),
    ];
    let got = caught_q(&m, raw, &|m| names(&r.guard(m)), &|m| r.undo(m));
    let want = set(&[
        "x in range",
        "y in range",
        "removed vertex in range",
        "face in range",
        "x dead",
        "y dead",
        "merged face kept",
        "insertion applies",
        "same quad",
        "freed slots on the free lists",
    ]);
    assert_eq!(got, want);
}

#[test]
fn doublet_insertion_undo_guard_pinned() {
    let mut m = gen::torus_grid(4, 4).map;
    let r = insert_doublet(&mut m, Dart(0)).unwrap();
    let [x, y] = r.darts();
    let raw: Vec<Edit> = vec![
        Box::new(move |m| m.face[x.index()] = 999),
        Box::new(move |m| m.face[y.index()] = 999),
    ];
    let got = caught_q(&m, raw, &|m| names(&r.guard(m).0), &|m| r.undo(m));
    let want = set(&[
        "removal applies",
        "same quad of x",
        "same quad of y",
        "same face of x",
        "same face of y",
        "slots releasable",
    ]);
    assert_eq!(got, want);
}

#[test]
fn edge_rotation_undo_guard_pinned() {
    let mut m = gen::torus_grid(4, 4).map;
    let r = rotate_edge(&mut m, Dart(0), Rotation::Clockwise).unwrap();
    let h = r.dart();
    let raw: Vec<Edit> = vec![Box::new(move |m| m.face[h.index()] = 999)];
    let got = caught_q(&m, raw, &|m| names(&r.guard(m).0), &|m| r.undo(m));
    let want = set(&[
        "reverse rotation applies",
        "new ends are the old ends",
        "same faces",
    ]);
    assert_eq!(got, want);
}
