//! Stage 4 (partial) of Q-zip: straight collapse chains from a v5 to a v3
//! (`zipmesh::qzip::execute_collapse_chain`).

use proptest::prelude::*;
use zipmesh::invariants::Counts;
use zipmesh::ops::quad;
use zipmesh::qzip::{
    execute_collapse_chain, plan, sketch, validate_path, Plan, SketchOptions, Tag, ZipError,
    ZipReport,
};
use zipmesh::{gen, Dart, Map, Vert};

/// Splits the regular vertex `v` along its `k`-th edge and the opposite one: the two copies
/// are v3s, the two far ends of the separators v5s (two 3-5 pairs).
fn insert_pairs(map: &mut Map, v: Vert, k: usize) -> bool {
    let Some(s1) = map.vertex_darts(v).nth(k % 4) else {
        return false;
    };
    let s2 = map.rotate_cw(map.rotate_cw(s1));
    quad::vertex_split(map, s1, s2).is_ok()
}

fn irregular(map: &Map) -> Vec<usize> {
    let mut v: Vec<usize> = map
        .vertices()
        .map(|v| map.valence(v))
        .filter(|&k| k != 4)
        .collect();
    v.sort_unstable();
    v
}

fn is_pure_quad(map: &Map) -> bool {
    map.faces().all(|f| map.degree(f) == 4)
}

fn chi(map: &Map) -> i64 {
    map.num_vertices() as i64 - map.num_edges() as i64 + map.num_faces() as i64
}

/// Every (v5, v3, tag) whose shortest path has a plan of one collapse tag throughout.
fn collapse_plans(map: &Map) -> Vec<Plan> {
    let v5s: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 5).collect();
    let v3s: Vec<Vert> = map.vertices().filter(|&v| map.valence(v) == 3).collect();
    let mut out = Vec::new();
    for &a in &v5s {
        for &b in &v3s {
            let Ok(path) = sketch(map, a, b, &SketchOptions::default()) else {
                continue;
            };
            for tag in [Tag::LC, Tag::RC] {
                if let Ok(p) = plan(map, &path, tag) {
                    if p.steps().iter().all(|s| s.tag == tag) {
                        out.push(p);
                    }
                }
            }
        }
    }
    out
}

/// Runs the chain and checks grid preservation, the report and the exact undo.
/// A refusal must name a third singularity near the strip and leave the map unchanged.
fn run_and_check(map: &mut Map, p: &Plan) -> Option<ZipReport> {
    let before = map.clone();
    let n = p.steps().len() - 1;
    let r = match execute_collapse_chain(map, p) {
        Ok(r) => r,
        Err(e) => {
            assert!(matches!(e, ZipError::Irregular { .. }), "{e}");
            assert_eq!(*map, before);
            return None;
        }
    };
    assert_eq!(map.check(), Ok(()));
    assert!(is_pure_quad(map));
    assert_eq!(chi(map), chi(&before));
    assert_eq!(irregular(map), irregular(&before));
    assert_eq!(map.num_vertices() + n, before.num_vertices());
    assert_eq!(r.collapses(), n);
    assert_eq!(map.valence(r.moved_from()), 5);
    assert_eq!(map.valence(r.moved_to()), 3);
    // The old ends became regular: the start survives, the end keeps its handle as the last
    // merged vertex (for one edge that is the first merged vertex, the new v5).
    let (s, e) = (p.steps()[0].vertex, p.steps()[n].vertex);
    assert_eq!(map.valence(s), 4);
    if n >= 2 {
        assert_eq!(map.valence(e), 4);
    }
    let c = Counts::of(map);
    let c0 = Counts::of(&before);
    assert_eq!(c.boundary_loops, c0.boundary_loops);
    r.undo(map).unwrap();
    assert_eq!(*map, before);
    Some(r)
}

/// Torus 12 x 12 with two vertex splits: vertex `(x, y)` along its `k1`-th edge and vertex
/// `(x + dx, y + dy)` along its `k2`-th edge (four 3-5 pairs, each v3 next to two v5s).
fn two_splits(x: u32, y: u32, k1: usize, dx: u32, dy: u32, k2: usize) -> Option<Map> {
    let id = |i: u32, j: u32| Vert::new((j % 12) * 12 + (i % 12));
    let mut map = gen::torus_grid(12, 12).map;
    let ok = insert_pairs(&mut map, id(x, y), k1) && insert_pairs(&mut map, id(x + dx, y + dy), k2);
    ok.then_some(map)
}

/// The straight continuation of `d` through its (valence-4) destination.
fn straight(map: &Map, d: Dart) -> Dart {
    map.rotate_cw(map.rotate_cw(d.twin()))
}

/// A hand-made collapse chain of `m` quads from a regular vertex (walking straight from its
/// `k`-th edge): it leaves two 3-5 pairs, a v3 at the start beside a v5, and a v5 beside a
/// v3 at the far end, with the v3s' other quads clean.
fn chain_pairs(map: &mut Map, start: Vert, k: usize, m: usize) -> bool {
    let Some(mut d) = map.vertex_darts(start).nth(k % 4) else {
        return false;
    };
    let mut verts = vec![start];
    for _ in 0..m {
        verts.push(map.dest(d));
        d = straight(map, d);
    }
    for w in verts.windows(2) {
        let Some(e) = map.vertex_darts(w[0]).find(|&e| map.dest(e) == w[1]) else {
            return false;
        };
        if quad::quad_collapse(map, e.twin()).is_err() {
            return false;
        }
    }
    true
}

/// Every straight path (through valence-4 vertices) from a v5 to a v3 whose LC or RC plan
/// keeps the collapse tag.
fn straight_plans(map: &Map) -> Vec<Plan> {
    let mut out = Vec::new();
    for v5 in map.vertices().filter(|&v| map.valence(v) == 5) {
        for d0 in map.vertex_darts(v5) {
            let (mut verts, mut d) = (vec![v5], d0);
            for _ in 0..24 {
                let n = map.dest(d);
                if verts.contains(&n) {
                    break;
                }
                verts.push(n);
                if map.valence(n) != 4 || map.is_boundary_vertex(n) {
                    break;
                }
                d = straight(map, d);
            }
            let end = verts[verts.len() - 1];
            if verts.len() < 2 || map.valence(end) != 3 {
                continue;
            }
            let opts = SketchOptions::default();
            let Ok(path) = validate_path(map, v5, end, &verts, &opts) else {
                continue;
            };
            for tag in [Tag::LC, Tag::RC] {
                if let Ok(p) = plan(map, &path, tag) {
                    if p.steps().iter().all(|s| s.tag == tag) {
                        out.push(p);
                    }
                }
            }
        }
    }
    out
}

/// Torus 16 x 16 with two hand-made collapse chains (see [`chain_pairs`]).
#[allow(clippy::too_many_arguments)]
fn two_chains(
    x1: u32,
    y1: u32,
    k1: usize,
    m1: usize,
    x2: u32,
    y2: u32,
    k2: usize,
    m2: usize,
) -> Option<Map> {
    let id = |i: u32, j: u32| Vert::new((j % 16) * 16 + (i % 16));
    let mut map = gen::torus_grid(16, 16).map;
    let ok = chain_pairs(&mut map, id(x1, y1), k1, m1) && chain_pairs(&mut map, id(x2, y2), k2, m2);
    ok.then_some(map)
}

#[derive(Default, Debug)]
struct Tally {
    ran: usize,
    /// Chains run with LC and with RC.
    by_tag: [usize; 2],
    refused: usize,
    longest: usize,
}

impl Tally {
    fn run_all(&mut self, map: &mut Map, plans: &[Plan]) {
        for p in plans {
            match run_and_check(map, p) {
                Some(r) => {
                    self.ran += 1;
                    self.by_tag[usize::from(r.tag() == Tag::RC)] += 1;
                    self.longest = self.longest.max(r.collapses());
                }
                None => self.refused += 1,
            }
        }
    }
}

/// Vertex-split pairs: every v3 touches two v5s, so only one-edge chains (moving a v5 onto
/// its own pair's v3 side) are clean; longer ones must be refused untouched.
#[test]
fn sweep_of_split_tori() {
    let mut t = Tally::default();
    for dx in 2..8 {
        for dy in 0..2 {
            for k1 in 0..4 {
                for k2 in 0..4 {
                    if let Some(mut map) = two_splits(3, 4, k1, dx, dy, k2) {
                        let plans = collapse_plans(&map);
                        t.run_all(&mut map, &plans);
                        let plans = straight_plans(&map);
                        t.run_all(&mut map, &plans);
                    }
                }
            }
        }
    }
    eprintln!("split tori: {t:?}");
    assert!(t.ran >= 20, "{t:?}");
}

/// Chain-made pairs in one row: the straight path from one chain's last v5 to the other
/// chain's first v3 runs clean over many lengths.
#[test]
fn sweep_of_chain_tori() {
    let mut t = Tally::default();
    for gap in 1..9 {
        for m in 1..4 {
            // Chain B from (1, 6) east, chain A from (1 + m + gap, 6) east.
            let Some(mut map) = two_chains(1, 6, 0, m, 1 + m as u32 + gap, 6, 0, m) else {
                continue;
            };
            let plans = straight_plans(&map);
            t.run_all(&mut map, &plans);
        }
    }
    eprintln!("chain tori: {t:?}");
    assert!(t.ran >= 10, "{t:?}");
    assert!(t.by_tag.iter().all(|&n| n >= 5), "{t:?}");
    assert!(t.longest >= 6, "{t:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    /// Random placements of two splits: every straight collapse plan keeps the grid or is
    /// refused untouched.
    #[test]
    fn random_split_tori(x in 0u32..12, y in 0u32..12, k1 in 0usize..4,
                         dx in 2u32..10, dy in 0u32..12, k2 in 0usize..4) {
        if let Some(mut map) = two_splits(x, y, k1, dx, dy, k2) {
            let plans = straight_plans(&map);
            Tally::default().run_all(&mut map, &plans);
        }
    }

    /// Random placements and directions of two hand-made chains, the same check.
    #[test]
    fn random_chain_tori(x1 in 0u32..16, y1 in 0u32..16, k1 in 0usize..4, m1 in 1usize..4,
                         x2 in 0u32..16, y2 in 0u32..16, k2 in 0usize..4, m2 in 1usize..4) {
        if let Some(mut map) = two_chains(x1, y1, k1, m1, x2, y2, k2, m2) {
            let plans = straight_plans(&map);
            Tally::default().run_all(&mut map, &plans);
        }
    }
}

/// Plans the executor does not take are refused by type, with the map untouched.
#[test]
fn refusals_leave_the_map_unchanged() {
    let mut map = two_chains(1, 6, 0, 2, 8, 6, 0, 2).expect("chains apply");
    let before = map.clone();
    let plans = straight_plans(&map);
    let p = plans
        .iter()
        .find(|p| p.steps().len() >= 4)
        .expect("a straight chain of three edges or more");
    let verts: Vec<Vert> = p.steps().iter().map(|s| s.vertex).collect();
    let opts = SketchOptions::default();
    let (a, b) = (verts[0], verts[verts.len() - 1]);
    let path = validate_path(&map, a, b, &verts, &opts).unwrap();
    // The same path with a split tag.
    for tag in [Tag::LS, Tag::RS] {
        let q = plan(&map, &path, tag).unwrap();
        let e = execute_collapse_chain(&mut map, &q).unwrap_err();
        assert!(matches!(e, ZipError::NotCollapse { index: 0, .. }), "{e}");
        assert_eq!(map, before);
    }
    // The reversed path (from the v3 to the v5) with a collapse tag: wrong ends.
    let rev: Vec<Vert> = verts.iter().rev().copied().collect();
    let rpath = validate_path(&map, b, a, &rev, &opts).unwrap();
    for tag in [Tag::LC, Tag::RC] {
        if let Ok(q) = plan(&map, &rpath, tag) {
            let e = execute_collapse_chain(&mut map, &q).unwrap_err();
            assert!(
                matches!(
                    e,
                    ZipError::WrongEnd {
                        index: 0,
                        valence: 3,
                        ..
                    } | ZipError::NotCollapse { .. }
                ),
                "{e}"
            );
            assert_eq!(map, before);
        }
    }
    // The plan again after it ran: its ends are no longer a v5 and a v3.
    let r = execute_collapse_chain(&mut map, p).unwrap();
    let after = map.clone();
    let e = execute_collapse_chain(&mut map, p).unwrap_err();
    assert!(
        matches!(e, ZipError::WrongEnd { .. } | ZipError::StalePlan { .. }),
        "{e}"
    );
    assert_eq!(map, after);
    r.undo(&mut map).unwrap();
    assert_eq!(map, before);
}

/// An L-shaped path: a collapse tag turns into a split at the corner; refused at index 0
/// position of the first split tag, never half-done.
#[test]
fn turning_path_is_refused() {
    let mut map = gen::torus_grid(8, 8).map;
    let before = map.clone();
    let v = |i: u32, j: u32| Vert::new(8 * j + i);
    let verts = [v(0, 0), v(1, 0), v(2, 0), v(2, 1)];
    let path = validate_path(&map, verts[0], verts[3], &verts, &SketchOptions::default()).unwrap();
    for tag in [Tag::LC, Tag::RC] {
        let q = plan(&map, &path, tag).unwrap();
        let e = execute_collapse_chain(&mut map, &q).unwrap_err();
        assert!(matches!(e, ZipError::NotCollapse { index: 2, .. }), "{e}");
        assert_eq!(map, before);
    }
}

/// A strip touching a third singularity is refused before anything changes.
#[test]
fn irregular_strip_is_refused() {
    let mut map = two_splits(3, 4, 0, 5, 0, 1).expect("splits apply");
    let before = map.clone();
    let mut seen = 0;
    for p in collapse_plans(&map)
        .iter()
        .chain(straight_plans(&map).iter())
    {
        if let Err(e @ ZipError::Irregular { .. }) = execute_collapse_chain(&mut map, p) {
            assert!(e.to_string().contains("valence"));
            seen += 1;
        }
        assert_eq!(map.check(), Ok(()));
        map = before.clone();
    }
    assert!(seen > 0);
}
