//! Q-zip stages 3 and 4 (`prepare`, `execute`, `zip`): grid preservation, exact undo, the
//! four movements, and refusals that leave the map untouched.

mod common;
#[path = "../benches/support/qzip_torus.rs"]
mod qzip_torus;

use common::{check_zip, ico_cc, pairs_within, shared, torus_with_splits};
use proptest::prelude::*;
use zipmesh::invariants::canonical::canonical_hash;
use zipmesh::invariants::{irregular_vertices, MeshKind};
use zipmesh::ops::quad::QuadRecord;
use zipmesh::qzip::{
    moves, plan, prepare, sketch, validate_path, EndRule, PrepareError, Qzip, QzipError,
    SketchOptions, StartRule, Tag, ZipReport,
};
use zipmesh::{gen, Edge, Map, Vert};

#[derive(Default, Debug)]
struct Tally {
    ok: usize,
    refused: usize,
    starts: [usize; 4],
    ends: [usize; 3],
}

/// Every ordered pair of singularities within `max_len` edges, every initial operation.
fn sweep(map: &Map, max_len: usize) -> Tally {
    let mut t = Tally::default();
    for path in pairs_within(map, max_len) {
        for tag in Tag::CCW {
            match check_zip(map, &path, tag) {
                Ok((_, r)) => {
                    t.ok += 1;
                    t.starts[r.surgery().start_rule() as usize] += 1;
                    t.ends[r.surgery().end_rule() as usize] += 1;
                }
                Err(_) => t.refused += 1,
            }
        }
    }
    t
}

/// The subdivided cube: eight isolated v3s, every 3-3 movement along every shortest path.
#[test]
fn cube_pairs_all_move() {
    let t = sweep(&gen::cube(6).map, 100);
    assert_eq!(t.refused, 0, "{t:?}");
    assert_eq!(t.ok, 8 * 7 * 4);
}

/// The twice-subdivided icosahedron: 12 isolated v5s and 20 isolated v3s; every pair
/// within 8 edges and every initial operation moves, through every start and end rule.
#[test]
fn icosahedron_pairs_all_move() {
    let t = sweep(&ico_cc(2), 8);
    assert_eq!(t.refused, 0, "{t:?}");
    assert!(t.ok >= 2000, "{t:?}");
    assert!(t.starts.iter().all(|&n| n > 100), "{t:?}");
    assert!(t.ends.iter().all(|&n| n > 100), "{t:?}");
}

/// Crowded clusters (two vertex splits on a torus): each movement keeps the grid or is
/// refused untouched (`check_zip` asserts both), and some do move.
#[test]
fn crowded_clusters_keep_the_grid_or_refuse() {
    let t = sweep(&torus_with_splits(16, &[3 * 16 + 3, 9 * 16 + 10]), 100);
    assert!(t.ok >= 50, "{t:?}");
    assert!(t.refused > 0, "{t:?}");
}

/// On a pair inside a regular region the four movements give four different maps.
#[test]
fn four_movements_differ() {
    let map = ico_cc(2);
    let sing = irregular_vertices(&map, MeshKind::Quad);
    let mut pairs = 0;
    for &a in &sing {
        for &b in &sing {
            let Ok(path) = sketch(&map, a, b, &SketchOptions::default()) else {
                continue;
            };
            if a == b || path.len() > 4 {
                continue;
            }
            let mut hashes: Vec<u128> = moves(&map, &path)
                .iter()
                .map(|m| canonical_hash(&m.outcome.as_ref().expect("realizable").0))
                .collect();
            hashes.sort_unstable();
            hashes.dedup();
            assert_eq!(hashes.len(), 4);
            pairs += 1;
        }
    }
    assert!(pairs >= 100, "{pairs}");
}

/// The start and end rules of Sec. 2.6 as printed by the preparation.
#[test]
fn end_point_rules_by_valence_and_tag() {
    let map = ico_cc(2);
    let v3 = map.vertices().find(|&v| map.valence(v) == 3).unwrap();
    let v5 = map.vertices().find(|&v| map.valence(v) == 5).unwrap();
    let opts = SketchOptions::default();
    let p35 = sketch(&map, v3, v5, &opts).unwrap();
    let p53 = sketch(&map, v5, v3, &opts).unwrap();
    for tag in Tag::CCW {
        let s = prepare(&map, &plan(&map, &p35, tag).unwrap()).unwrap();
        let want = if tag.is_split() {
            StartRule::V3Split
        } else {
            StartRule::V3Collapse
        };
        assert_eq!(s.start_rule(), want);
        assert_ne!(s.end_rule(), EndRule::V3);
        if tag.is_split() {
            assert_eq!(s.steps()[0].op, None);
        } else {
            // Rerouted: the first vertex is a neighbour of the v3, not the v3.
            let first = s.steps()[0].vertex;
            assert_ne!(first, v3);
            assert!(map.vertex_darts(v3).any(|d| map.dest(d) == first));
        }
        let s = prepare(&map, &plan(&map, &p53, tag).unwrap()).unwrap();
        assert_eq!(s.end_rule(), EndRule::V3);
        if tag.is_split() {
            assert_eq!(s.start_rule(), StartRule::V5Split);
            assert_eq!(s.steps()[0].op, None);
            assert_eq!(s.steps()[1].vertex, v5);
        } else {
            assert_eq!(s.start_rule(), StartRule::V5Collapse);
            assert_eq!(s.steps()[0].vertex, v5);
        }
    }
}

/// Refusals by stage, each naming its reason, with the map untouched.
#[test]
fn refusals_leave_the_map_untouched() {
    let opts = SketchOptions::default();
    // A regular end.
    let mut map = gen::torus_grid(8, 8).map;
    let before = map.clone();
    let e = Qzip::with_options(opts.clone())
        .zip(&mut map, Vert::new(0), Vert::new(3), Tag::LC)
        .unwrap_err();
    assert!(
        matches!(e, QzipError::Prepare(PrepareError::End { valence: 4, .. })),
        "{e}"
    );
    assert_eq!(map, before);
    // A boundary end (grid corners have valence 2).
    let mut map = gen::grid(6, 6).map;
    let before = map.clone();
    let e = Qzip::with_options(opts.clone())
        .zip(&mut map, Vert::new(0), Vert::new(6), Tag::LS)
        .unwrap_err();
    assert!(
        matches!(
            e,
            QzipError::Prepare(PrepareError::End { boundary: true, .. })
        ),
        "{e}"
    );
    assert_eq!(map, before);
    // A one-edge path between two v3s (a cube's corners) with a split: nothing left to do.
    let map = gen::cube(1).map;
    let a = Vert::new(0);
    let b = map.dest(map.vertex_dart(a));
    let path = validate_path(&map, a, b, &[a, b], &opts).unwrap();
    let e = prepare(&map, &plan(&map, &path, Tag::LS).unwrap()).unwrap_err();
    assert_eq!(e, PrepareError::Empty);
    // A valence-6 vertex inside the path is refused by the plan, by name.
    let mut map = ico_cc(2);
    let v = map.vertices().find(|&v| map.valence(v) == 4).unwrap();
    let d = map.vertex_dart(v);
    zipmesh::ops::quad::collapse_quad(&mut map, d).unwrap();
    assert_eq!(map.valence(v), 6);
    let before = map.clone();
    let (x, y) = (
        map.dest(map.vertex_dart(v)),
        map.dest(map.rotate_cw(map.vertex_dart(v))),
    );
    let path = validate_path(&map, x, y, &[x, v, y], &opts).unwrap();
    let e = Qzip::new().zip_along(&mut map, &path, Tag::LC).unwrap_err();
    assert!(
        matches!(
            e,
            QzipError::Plan(zipmesh::qzip::PlanError::Valence { valence: 6, .. })
        ),
        "{e}"
    );
    assert_eq!(map, before);
}

fn arb_tag() -> impl Strategy<Value = Tag> {
    (0usize..4).prop_map(|i| Tag::CCW[i])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Random cluster placements on a torus, random pair and initial operation: the grid is
    /// kept, or the map is untouched (`check_zip`).
    #[test]
    fn random_clusters(x1 in 0u32..14, y1 in 0u32..14, x2 in 0u32..14, y2 in 0u32..14,
                       i in 0usize..64, j in 0usize..64, tag in arb_tag()) {
        let (a1, a2) = (y1 * 14 + x1, y2 * 14 + x2);
        prop_assume!(a1 != a2);
        let map = torus_with_splits(14, &[a1]);
        let mut map2 = map.clone();
        // The second split may hit a vertex the first made irregular: skip then.
        let s1 = map2.vertex_dart(Vert::new(a2));
        let s2 = map2.rotate_cw(map2.rotate_cw(s1));
        prop_assume!(map2.valence(Vert::new(a2)) == 4);
        prop_assume!(zipmesh::ops::quad::split_vertex(&mut map2, s1, s2).is_ok());
        let sing = irregular_vertices(&map2, MeshKind::Quad);
        let (a, b) = (sing[i % sing.len()], sing[j % sing.len()]);
        prop_assume!(a != b);
        if let Ok(path) = sketch(&map2, a, b, &SketchOptions::default()) {
            let _ = check_zip(&map2, &path, tag);
        }
    }

    /// Random pairs on the icosahedron subdivided twice or three times: always realizable.
    #[test]
    fn random_icosahedron_pairs(levels in 2usize..4, i in 0usize..32, j in 0usize..32,
                                tag in arb_tag()) {
        let map = ico_cc(levels);
        let sing = irregular_vertices(&map, MeshKind::Quad);
        let (a, b) = (sing[i % sing.len()], sing[j % sing.len()]);
        prop_assume!(a != b);
        let path = sketch(&map, a, b, &SketchOptions::default()).unwrap();
        prop_assume!(path.len() <= 8);
        prop_assert!(check_zip(&map, &path, tag).is_ok());
    }
}

/// Paths that touch the boundary: the subdivided icosahedron with a hole cut round one v3
/// (its faces removed). Every movement along a path through boundary vertices keeps the
/// grid or is refused untouched, and some are done.
#[test]
fn paths_touching_the_boundary() {
    let ico = gen::subdivided_icosahedron(2);
    let hole = Vert::new(45);
    let faces: Vec<Vec<u32>> = ico
        .polygons()
        .into_iter()
        .filter(|f| !f.contains(&(hole.index() as u32)))
        .collect();
    let (mesh, _) = zipmesh::Mesh::from_polygons(ico.positions.clone(), &faces).unwrap();
    let map = mesh.map;
    assert_eq!(map.boundary_loops().len(), 1);
    let sing = irregular_vertices(&map, MeshKind::Quad);
    let (mut touching, mut done) = (0, 0);
    for &a in &sing {
        for &b in &sing {
            if a == b || map.is_boundary_vertex(a) || map.is_boundary_vertex(b) {
                continue;
            }
            let Ok(path) = sketch(&map, a, b, &SketchOptions::default()) else {
                continue;
            };
            if path.len() > 8 || !path.vertices().iter().any(|&v| map.is_boundary_vertex(v)) {
                continue;
            }
            touching += 1;
            for tag in Tag::CCW {
                done += usize::from(check_zip(&map, &path, tag).is_ok());
            }
        }
    }
    assert!(touching > 0);
    assert!(
        done > 0,
        "{touching} paths touch the boundary, no movement done"
    );
    eprintln!("boundary: {touching} paths touch it, {done} movements done");
}

/// With cancellation allowed, every movement the grid guard refuses as
/// `NotGridPreserving` is done instead: a valid map, the report's two vertices live, and an
/// exact undo. When the singularities cancelled and no vertex carries them any more, both
/// report vertices are one touched vertex (the fallback), which must happen on crowded
/// clusters.
#[test]
fn cancellation_does_what_the_guard_refuses() {
    use zipmesh::qzip::ZipError;
    let map = torus_with_splits(16, &[3 * 16 + 3, 4 * 16 + 5, 9 * 16 + 10]);
    let (mut refused, mut fallback) = (0, 0);
    for path in pairs_within(&map, 100) {
        for tag in Tag::CCW {
            let mut guarded = map.clone();
            let err = Qzip::new().zip_along(&mut guarded, &path, tag);
            if !matches!(
                err,
                Err(QzipError::Execute(ZipError::NotGridPreserving { .. }))
            ) {
                continue;
            }
            refused += 1;
            let mut m = map.clone();
            let r = Qzip::new()
                .allow_cancellation(true)
                .zip_along(&mut m, &path, tag)
                .unwrap_or_else(|e| panic!("cancellation refused what the guard did: {e}"));
            assert!(m.check().is_ok());
            assert!(m.is_live_vertex(r.moved_from()) && m.is_live_vertex(r.moved_to()));
            fallback += usize::from(r.moved_from() == r.moved_to());
            r.undo(&mut m).unwrap();
            assert_eq!(m, map);
        }
    }
    assert!(
        refused >= 10,
        "only {refused} movements changed the singularities"
    );
    assert!(
        fallback >= 1,
        "no cancellation fell back ({refused} refused)"
    );
}

/// OpenSubdiv's helmet: its movements within 12 edges all pass `verify_edit`, including
/// those whose clean-up removes a valence-2 vertex (three of the 13); such a removal deletes
/// a face the footprint does not list, which the footprint check must allow.
#[test]
fn helmet_movements_with_a_valence_2_clean_up_verify() {
    let map = zipmesh::io::read_mesh(shared("quad/osd_catmark_helmet.obj"))
        .unwrap()
        .0
        .map;
    let mut with_v2 = 0;
    for path in pairs_within(&map, 12) {
        for tag in Tag::CCW {
            if let Ok((_, r)) = check_zip(&map, &path, tag) {
                with_v2 += usize::from(r.cleanup_counts().0 > 0);
            }
        }
    }
    assert!(
        with_v2 >= 3,
        "{with_v2} movements with a valence-2 clean-up"
    );
}

/// The footprint's edges by their definition, from the maps the chain went through: a
/// split's two split edges that had been edges from the map before up to that split,
/// without a break (a slot freed and reused in between is another edge). The maps are
/// found by undoing the records one at a time from the end.
fn footprint_edges_by_definition(before: &Map, after: &Map, r: &ZipReport) -> Vec<Edge> {
    let records = r.records();
    let mut states = vec![after.clone()];
    for rec in records.iter().rev() {
        let mut m = states.last().unwrap().clone();
        rec.undo(&mut m).unwrap();
        states.push(m);
    }
    states.reverse(); // states[k]: the map before record k
    assert!(&states[0] == before);
    let chain = r.splits() + r.collapses();
    let mut out = Vec::new();
    for (k, rec) in records[..chain].iter().enumerate() {
        if let QuadRecord::Split(s) = rec {
            let q = s.quad();
            for e in [q[0].edge(), q[2].edge()] {
                if states[..=k].iter().all(|m| m.is_live_edge(e)) {
                    out.push(e);
                }
            }
        }
    }
    out
}

/// Every movement within 6 edges on the subdivided icosahedron after one Q-zip (so its
/// arrays hold dead slots that later splits reuse) and on the quad-dominant cages: the
/// footprint's edges are exactly those of the definition, in order.
#[test]
fn footprint_edges_match_their_definition() {
    // Two quads collapsed: their edge slots are free for the splits to reuse.
    let mut ico = ico_cc(2);
    for f in [10, 200] {
        let d = ico.face_dart(zipmesh::Face::new(f));
        zipmesh::ops::quad::collapse_quad(&mut ico, d).unwrap();
    }
    assert!(
        ico.edge_slots() > ico.num_edges(),
        "dead edge slots to reuse"
    );
    let (mut checked, mut reused) = (0, 0);
    for map in [ico, ico_cc(1)] {
        for path in pairs_within(&map, 6) {
            for tag in Tag::CCW {
                let mut m = map.clone();
                let Ok(r) = Qzip::new().zip_along(&mut m, &path, tag) else {
                    continue;
                };
                let want = footprint_edges_by_definition(&map, &m, &r);
                assert_eq!(r.footprint_edges(), want, "{tag}");
                checked += 1;
                let split = r.records()[..r.splits() + r.collapses()]
                    .iter()
                    .filter(|x| matches!(x, QuadRecord::Split(_)))
                    .count();
                reused += usize::from(want.len() < 2 * split && r.collapses() > 0);
            }
        }
    }
    assert!(
        checked > 1000 && reused > 100,
        "{checked} checked, {reused} with made edges split again and collapses"
    );
}

/// Chains long enough to touch more vertices than the touched-vertex index keeps inline
/// (about 15 operations): 100-edge Q-zips along a row of a torus keep every promise, for
/// both initial collapses.
#[test]
fn long_chains_keep_every_promise() {
    let (map, ends) = qzip_torus::torus_with_pairs(221, 1, 100);
    let (a, b) = ends[0];
    let path = sketch(&map, a, b, &SketchOptions::default()).unwrap();
    assert_eq!(path.len(), 100);
    for tag in [Tag::LC, Tag::RC] {
        let (_, r) = check_zip(&map, &path, tag).unwrap_or_else(|e| panic!("{tag}: {e}"));
        // LC: a collapse per edge; RC: a split, then a collapse per remaining edge.
        assert_eq!(r.splits() + r.collapses(), 100, "{tag}");
    }
}
