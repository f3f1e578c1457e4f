//! Homotopy invariance of Q-zip (Sec. 3.1): along two paths that differ by sweeping across
//! regular quads, the four movements give the same four maps up to isomorphism, with labels
//! matched by the turn at the start ([`start_turn`]).

mod common;

use common::{ico_cc, singular};
use zipmesh::invariants::canonical::canonical_hash;
use zipmesh::qzip::{plan, sketch, start_turn, validate_path, zip_along, Path, SketchOptions, Tag};
use zipmesh::{gen, Map, Vert};

fn regular(map: &Map, v: Vert) -> bool {
    map.valence(v) == 4 && !map.is_boundary_vertex(v)
}

/// Paths homotopic to `p` by sweeping one quad on either side of one of its edges: the
/// edge `p[i] -> p[i+1]` is replaced by the quad's three other sides. The quad's two new
/// corners must be regular and off the path, and the edge's ends regular unless they are
/// the path's ends (so no singularity is swept or passed on another side).
fn one_quad_sweeps(map: &Map, p: &Path) -> Vec<(usize, Path)> {
    let v = p.vertices();
    let mut out = Vec::new();
    for (i, &d) in p.darts().iter().enumerate() {
        for left in [true, false] {
            let e = if left { d } else { d.twin() };
            let Some(f) = map.face(e) else { continue };
            if map.degree(f) != 4 {
                continue;
            }
            let (x, y) = (map.origin(map.prev(e)), map.dest(map.next(e)));
            let (near_i, near_j) = if left { (x, y) } else { (y, x) };
            if v.contains(&near_i) || v.contains(&near_j) {
                continue;
            }
            if !regular(map, near_i) || !regular(map, near_j) {
                continue;
            }
            if (i > 0 && !regular(map, v[i])) || (i + 2 < v.len() && !regular(map, v[i + 1])) {
                continue;
            }
            let mut q = v[..=i].to_vec();
            q.extend([near_i, near_j]);
            q.extend_from_slice(&v[i + 1..]);
            if let Ok(path) = validate_path(map, p.start(), p.end(), &q, &SketchOptions::default())
            {
                out.push((i, path));
            }
        }
    }
    out
}

/// The canonical hash of each of the four movements (in `Tag::CCW` order), `None` where
/// not realizable.
fn outcomes(map: &Map, p: &Path) -> [Option<u128>; 4] {
    Tag::CCW.map(|t| {
        let mut m = map.clone();
        zip_along(&mut m, p, t).ok().map(|_| canonical_hash(&m))
    })
}

#[derive(Default, Debug)]
struct Tally {
    path_pairs: usize,
    compared: usize,
    at_start: usize,
    one_side_refused: usize,
}

fn sweep(map: &Map, max_len: usize) -> Tally {
    let mut t = Tally::default();
    let sing = singular(map);
    for &a in &sing {
        for &b in &sing {
            let Ok(p) = sketch(map, a, b, &SketchOptions::default()) else {
                continue;
            };
            if a == b || p.len() > max_len {
                continue;
            }
            let h0 = outcomes(map, &p);
            for (i, q) in one_quad_sweeps(map, &p) {
                t.path_pairs += 1;
                let k = start_turn(map, &p, &q).expect("shared start");
                assert_eq!(k == 0, i > 0);
                t.at_start += usize::from(i == 0);
                let h1 = outcomes(map, &q);
                for (j, tag) in Tag::CCW.into_iter().enumerate() {
                    let jq = Tag::CCW.iter().position(|&u| u == tag.turned(k)).unwrap();
                    match (h0[j], h1[jq]) {
                        (Some(x), Some(y)) => {
                            assert_eq!(x, y, "movement {tag} along {:?} vs {:?}", p, q);
                            t.compared += 1;
                        }
                        _ => t.one_side_refused += 1,
                    }
                }
            }
        }
    }
    t
}

#[test]
fn homotopic_paths_give_isomorphic_maps_on_the_cube() {
    let t = sweep(&gen::cube(6).map, 7);
    assert!(t.compared >= 500, "{t:?}");
    assert!(t.at_start > 0, "{t:?}");
    eprintln!("{t:?}");
}

#[test]
fn homotopic_paths_give_isomorphic_maps_on_the_icosahedron() {
    let t = sweep(&ico_cc(2), 5);
    assert!(t.compared >= 3000, "{t:?}");
    assert!(t.at_start > 100, "{t:?}");
    eprintln!("{t:?}");
}

/// Passing a third singularity on its other side is not a homotopy: there is a pair and a
/// movement whose maps differ. Paths through a v3 `s` between two singularities, bent
/// round `s` on the left and on the right.
#[test]
fn the_other_side_of_a_singularity_can_differ() {
    let map = ico_cc(2);
    let sing = singular(&map);
    let mut differing = 0;
    for &a in &sing {
        for &b in &sing {
            let Ok(p) = sketch(&map, a, b, &SketchOptions::default()) else {
                continue;
            };
            let v = p.vertices();
            let Some(i) = (1..v.len() - 1).find(|&i| !regular(&map, v[i])) else {
                continue;
            };
            // Detours round v[i] through its one-ring, one on each side.
            let ring: Vec<Vert> = map.vertex_darts(v[i]).map(|d| map.dest(d)).collect();
            let k_in = ring.iter().position(|&x| x == v[i - 1]).unwrap();
            let k_out = ring.iter().position(|&x| x == v[i + 1]).unwrap();
            let n = ring.len();
            let mut sides = Vec::new();
            for dir in [1, n - 1] {
                // Walk the one-ring's border from the in-spoke to the out-spoke.
                let mut q = v[..i].to_vec();
                let mut k = k_in;
                let mut ok = true;
                while k != k_out {
                    k = (k + dir) % n;
                    // The diagonal corner between two spokes, then the next spoke.
                    let spoke = ring[k];
                    let prev = *q.last().unwrap();
                    let corner = map
                        .vertex_darts(prev)
                        .map(|e| map.dest(e))
                        .find(|&c| c != v[i] && map.vertex_darts(c).any(|e| map.dest(e) == spoke));
                    match corner {
                        Some(c) if !q.contains(&c) && !v[i + 1..].contains(&c) => q.push(c),
                        _ => ok = false,
                    }
                    if k != k_out {
                        if q.contains(&spoke) || v[i + 1..].contains(&spoke) {
                            ok = false;
                        }
                        q.push(spoke);
                    }
                }
                q.extend_from_slice(&v[i + 1..]);
                if ok {
                    if let Ok(path) = validate_path(&map, a, b, &q, &SketchOptions::default()) {
                        if plan(&map, &path, Tag::LS).is_ok() {
                            sides.push(path);
                        }
                    }
                }
            }
            if sides.len() == 2 {
                let (h0, h1) = (outcomes(&map, &sides[0]), outcomes(&map, &sides[1]));
                let mut s0: Vec<u128> = h0.iter().flatten().copied().collect();
                let mut s1: Vec<u128> = h1.iter().flatten().copied().collect();
                s0.sort_unstable();
                s1.sort_unstable();
                if s0.len() == 4 && s1.len() == 4 && s0 != s1 {
                    differing += 1;
                }
            }
        }
    }
    assert!(differing > 0);
}
