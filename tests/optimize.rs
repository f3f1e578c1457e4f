//! `zipmesh::optimize` (Q-zip paper, Sec. 4.1) over generated meshes: the output keeps
//! validity, Euler characteristic, boundary loops and components and stays pure quad; the
//! score never rises from batch to batch; the same seed gives the same mesh; protected
//! faces and feature edges are untouched (checked on positions, independently of
//! `Constraints`); and the singularity count goes down on meshes full of them. Quad-dominant
//! input (generated, and the subdivided polygon cages with quads re-split) comes out pure
//! quad: its triangles crawl together in pairs and merge.

mod common;

use common::cages;
use glam::DVec3;
use proptest::prelude::*;
use zipmesh::invariants::{gauss_bonnet, Counts, MeshKind};
use zipmesh::optimize::{folded_quads, optimize, Constraints, OptimizeOptions, SingularityCounts};
use zipmesh::{gen, Face, Mesh};

/// A quad mesh with many singularities: one Catmull-Clark step of a random triangle mesh.
fn subdivided(faces: usize, genus: usize, holes: usize, seed: u64) -> Mesh {
    gen::catmull_clark(&gen::random_triangle(faces, genus, holes, seed))
}

fn bits(p: DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}

/// Every face as its corner positions (bit patterns), in cyclic order.
fn face_positions(mesh: &Mesh) -> Vec<Vec<[u64; 3]>> {
    mesh.polygons()
        .iter()
        .map(|f| {
            f.iter()
                .map(|&v| bits(mesh.positions[v as usize]))
                .collect()
        })
        .collect()
}

fn is_rotation(a: &[[u64; 3]], b: &[[u64; 3]]) -> bool {
    a.len() == b.len() && (0..a.len()).any(|k| a.iter().cycle().skip(k).take(a.len()).eq(b.iter()))
}

/// A score term without [`zipmesh::optimize::ScoreTerm::fork`]: always 0.
#[derive(Debug)]
struct Unforkable;

impl zipmesh::optimize::ScoreTerm for Unforkable {
    fn name(&self) -> &str {
        "unforkable"
    }
    fn score(&mut self, _: &zipmesh::optimize::Context<'_>) -> f64 {
        0.0
    }
}

fn run(mesh: &mut Mesh, c: Constraints, batches: usize, seed: u64) -> zipmesh::optimize::Outcome {
    let o = OptimizeOptions::default().batches(batches).seed(seed);
    optimize(mesh, c, o, |_| {}).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// Validity, chi, loops, components, pure quad, a monotone score, counts that match.
    #[test]
    fn keeps_topology_and_lowers_the_score(
        faces in 40usize..160, genus in 0usize..3, holes in 0usize..2, seed in any::<u64>(),
    ) {
        let mut mesh = subdivided(faces, genus, holes, seed);
        let before = Counts::of(&mesh.map);
        let out = run(&mut mesh, Constraints::default(), 4, seed);
        mesh.map.check().unwrap();
        let after = Counts::of(&mesh.map);
        prop_assert_eq!(after.euler_characteristic, before.euler_characteristic);
        prop_assert_eq!(after.boundary_loops, before.boundary_loops);
        prop_assert_eq!(after.components, before.components);
        prop_assert!(mesh.map.faces().all(|f| mesh.map.degree(f) == 4));
        prop_assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
        let mut last = out.initial_score;
        for b in &out.batches {
            prop_assert!(b.score <= last, "batch {} raised the score {} -> {}", b.batch, last, b.score);
            last = b.score;
        }
        prop_assert_eq!(out.final_counts, SingularityCounts::of(&mesh));
    }

    /// With the fold guard and no preprocessing (whose splits are not guarded), a run never
    /// leaves more folded quads than it started with, and still keeps the topology.
    #[test]
    fn the_fold_guard_never_adds_a_folded_quad(
        faces in 40usize..160, genus in 0usize..3, holes in 0usize..2, seed in any::<u64>(),
    ) {
        let mut mesh = subdivided(faces, genus, holes, seed);
        let (before, folds) = (Counts::of(&mesh.map), folded_quads(&mesh));
        let mut o = OptimizeOptions::default().batches(6).seed(seed).fold_guard(true);
        o.preprocess = false;
        let out = optimize(&mut mesh, Constraints::default(), o, |_| {}).unwrap();
        mesh.map.check().unwrap();
        prop_assert!(folded_quads(&mesh) <= folds, "{} -> {}", folds, folded_quads(&mesh));
        prop_assert_eq!(Counts::of(&mesh.map).euler_characteristic, before.euler_characteristic);
        prop_assert_eq!(out.final_counts, SingularityCounts::of(&mesh));
    }

    /// The same seed gives the same mesh, positions included.
    #[test]
    fn same_seed_same_mesh(faces in 40usize..120, seed in any::<u64>()) {
        let input = subdivided(faces, 1, 0, seed);
        let (mut a, mut b) = (input.clone(), input);
        run(&mut a, Constraints::default(), 3, seed);
        run(&mut b, Constraints::default(), 3, seed);
        prop_assert_eq!(a, b);
    }

    /// The candidate search cut into parts, each on its own copy of the mesh and run on any
    /// number of threads, gives the same mesh as one part searched on the mesh itself (a
    /// user term that cannot be copied, and scores 0, forces that).
    #[test]
    fn same_mesh_whatever_the_threads(faces in 80usize..160, seed in any::<u64>()) {
        let input = subdivided(faces, 1, 0, seed);
        let opts = || OptimizeOptions::default().batches(3).seed(seed);
        let (mut a, mut b, mut c) = (input.clone(), input.clone(), input);
        optimize(&mut a, Constraints::default(), opts(), |_| {}).unwrap();
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        one.install(|| optimize(&mut b, Constraints::default(), opts(), |_| {}).unwrap());
        let serial = opts().term(1.0, Box::new(Unforkable));
        optimize(&mut c, Constraints::default(), serial, |_| {}).unwrap();
        prop_assert_eq!(&a, &b);
        prop_assert_eq!(&a, &c);
    }

    /// Protected faces keep their corner positions bit for bit in the same cyclic order;
    /// feature edges stay edges with both ends where they were.
    #[test]
    fn protected_faces_and_features_hold(
        faces in 60usize..160, seed in any::<u64>(), pick in 0usize..1000,
    ) {
        let mut mesh = subdivided(faces, 1, 1, seed);
        let mut c = Constraints::default();
        let live: Vec<Face> = mesh.map.faces().collect();
        let protected: Vec<Face> = (0..4).map(|i| live[(pick + 37 * i) % live.len()]).collect();
        let expected: Vec<Vec<[u64; 3]>> = protected
            .iter()
            .map(|&f| mesh.map.face_darts(f).map(|d| bits(mesh.positions[mesh.map.origin(d).index()])).collect())
            .collect();
        for &f in &protected {
            c.protect_face(&mesh, f).unwrap();
        }
        let edges: Vec<(DVec3, DVec3)> = mesh.map.edges().skip(pick % 50).step_by(41).take(3)
            .map(|e| {
                let (a, b) = (mesh.map.origin(e.dart(0)), mesh.map.dest(e.dart(0)));
                c.add_feature(&mesh, a, b).unwrap();
                (mesh.positions[a.index()], mesh.positions[b.index()])
            })
            .collect();
        run(&mut mesh, c, 4, seed);
        let faces = face_positions(&mesh);
        for e in &expected {
            prop_assert!(faces.iter().any(|f| is_rotation(f, e)), "a protected face changed");
        }
        let find = |p: DVec3| mesh.map.vertices().find(|v| bits(mesh.positions[v.index()]) == bits(p));
        for (a, b) in edges {
            let (Some(x), Some(y)) = (find(a), find(b)) else {
                return Err(TestCaseError::fail("a feature end moved or vanished"));
            };
            prop_assert!(mesh.map.dart_between(x, y).is_some(), "a feature edge is gone");
        }
    }
}

/// On a genus-3 mesh after one Catmull-Clark step (the paper's robustness test, Fig. 17, at
/// a small size) the batches remove at least the paper's 55 % of the singularities (it
/// reports 55-90 % on real meshes) while the face count stays within 10 % of the input's
/// (the optimizer's goal, docs/optimize.md), and Gauss-Bonnet still holds.
#[test]
fn removes_most_singularities_of_a_subdivided_genus_3_mesh() {
    let mut mesh = subdivided(300, 3, 0, 1);
    assert_meets_the_goal(&mut mesh);
}

/// Runs 40 batches (seed 0) and asserts the optimizer's goal: at most 45 % of the singularities
/// left, the face count within 10 %, Gauss-Bonnet and a valid map.
fn assert_meets_the_goal(mesh: &mut Mesh) {
    assert_meets_the_goal_with(mesh, OptimizeOptions::default().batches(40));
}

/// [`assert_meets_the_goal`] with options `o` (seed 0).
fn assert_meets_the_goal_with(mesh: &mut Mesh, o: OptimizeOptions) {
    let before = SingularityCounts::of(mesh);
    let out = optimize(mesh, Constraints::default(), o.seed(0), |_| {}).unwrap();
    let after = out.final_counts;
    assert!(
        after.singularities() * 100 <= before.singularities() * 45,
        "{before:?} -> {after:?}"
    );
    assert!(
        after.faces.abs_diff(before.faces) * 10 <= before.faces,
        "faces {} -> {}",
        before.faces,
        after.faces
    );
    assert!(gauss_bonnet(&mesh.map, MeshKind::Quad).holds());
    assert_eq!(mesh.map.check(), Ok(()));
}

/// Blub (7,104 quads, genus 0; 38 singularities, which preprocessing makes 44) was the one
/// real mesh below the 55 % cut: its v3/v5 pairs are dislocations that a Q-zip of
/// the pair with itself only translates, so the pair chains stalled at 36. Walking a
/// singularity onto an opposite one by Q-zips with a third cancels them: at most 17 left
/// in 40 batches, the face count within 10 %. With the footprints relaxed on the surface and
/// the fold guard (the defaults) 40 batches leave 30 (20 without the guard); the default run,
/// which goes on while batches improve, leaves 12 (docs/quality.md).
#[test]
fn blub_loses_more_than_half_of_its_singularities() {
    let path = common::shared("quad/blub_quadrangulated.obj");
    let mut mesh = zipmesh::io::read_mesh(&path).unwrap().0;
    assert_meets_the_goal_with(&mut mesh, OptimizeOptions::default());
}

/// The default run (fold guard on, footprints relaxed on the input surface) on the test
/// mesh `file` holds every geometry bound (`quality::Bounds`: no folded quad and no quad of
/// negative scaled Jacobian added, ...), leaves every vertex on the input surface and lowers
/// the singularity count.
fn assert_default_run_is_sound(file: &str) {
    let mut mesh = zipmesh::io::read_mesh(common::shared(file)).unwrap().0;
    let input = mesh.clone();
    let before = SingularityCounts::of(&mesh);
    let out = optimize(
        &mut mesh,
        Constraints::default(),
        OptimizeOptions::default(),
        |_| {},
    )
    .unwrap();
    let reference = zipmesh::quality::Reference::new(&input);
    let [q0, q1] = [&input, &mesh].map(|m| zipmesh::quality::Summary::against(m, &reference));
    let failed = zipmesh::quality::Bounds::default().failures(&q0, &q1);
    assert!(failed.is_empty(), "{file}: {failed:?}: {q0:?} -> {q1:?}");
    assert!(out.final_counts.singularities() < before.singularities());
    assert!(q1.distance.unwrap().max < 1e-6, "{file}: {:?}", q1.distance);
}

#[test]
fn the_default_run_on_spot_adds_no_folded_quad() {
    assert_default_run_is_sound("quad/spot_quadrangulated.obj");
}

/// The rook's 44 triangles crawl together and merge before the batches; the crawls' moved
/// and new vertices are relaxed on the surface as a Q-zip's are (without that the triangle
/// stage leaves 10 folded quads and the run ends with 2).
#[test]
fn the_default_run_on_the_quad_dominant_rook_adds_no_folded_quad() {
    assert_default_run_is_sound("poly/catmark_rook.obj");
}

/// Three of the default campaign's quad-dominant cases (seed 0; tori of 105 to 226 faces,
/// a third to two fifths of them triangles) whose first run folds quads round the crawled
/// triangles (13 to 30 quads flagged): the run is made again with each merge guarded, and the
/// output holds every geometry bound but the face count and the scaled Jacobian's 1st
/// percentile, which the campaign notes as unchecked on such cases.
#[cfg(feature = "campaign")]
#[test]
fn a_quad_dominant_run_that_folds_quads_is_made_again_guarded() {
    use zipmesh::quality::{Bound, Bounds, Reference, Summary};
    for index in [1037, 1124, 1501] {
        let case = zipmesh::campaign::Case::generate(0, index, 1000);
        let mut mesh = case.mesh.clone();
        let options = OptimizeOptions::default().batches(8).seed(index);
        let out = optimize(&mut mesh, Constraints::default(), options, |_| {}).unwrap();
        assert!(out.triangles.guarded, "case {index}: {:?}", out.triangles);
        assert!(
            out.triangles.merged > 0,
            "case {index}: {:?}",
            out.triangles
        );
        let reference = Reference::new(&case.mesh);
        let [q0, q1] = [&case.mesh, &mesh].map(|m| Summary::against(m, &reference));
        let mut failed = Bounds::default().failures(&q0, &q1);
        failed.retain(|&b| b != Bound::Faces && b != Bound::JacobianP1);
        assert!(
            failed.is_empty(),
            "case {index}: {failed:?}: {q0:?} -> {q1:?}"
        );
    }
}

/// Each batch's stats add up: every candidate is counted once by the sign of its face
/// change, the executed Q-zips are the batch's, and their face change plus the kept
/// chains' is the batch's change of the face count (the smoothing changes no face).
#[test]
fn batch_stats_account_for_the_face_change() {
    let mut mesh = subdivided(200, 2, 0, 4);
    let out = run(&mut mesh, Constraints::default(), 6, 1);
    let mut faces = out.batches[0].counts.faces as isize - out.batches[0].stats.face_change;
    for b in &out.batches {
        let s = b.stats;
        assert_eq!(s.candidates, b.candidates);
        assert_eq!(s.candidates, s.removing.0 + s.keeping.0 + s.adding.0);
        assert!(s.removing.1 <= s.removing.0 && s.adding.1 <= s.adding.0);
        assert_eq!(b.qzips, s.executed.0 + s.executed.1 + s.executed.2);
        faces += s.face_change + b.chains.face_change;
        assert_eq!(faces, b.counts.faces as isize, "batch {}", b.batch);
    }
}

/// The endgame (`docs/optimize.md`): on a genus-2 mesh run until the batches stall, the
/// chain stage keeps some chains, runs only after a batch that executed nothing, never
/// raises the score, each kept chain cancels a pair (so lowers the count by at least 2 over
/// a run without chains at the point it starts), and the run ends with no more
/// singularities than the same run without chains; Gauss-Bonnet holds in both.
#[test]
fn endgame_chains_cancel_pairs_the_batches_cannot() {
    let input = subdivided(300, 2, 0, 1);
    let (mut on, mut off) = (input.clone(), input);
    // The chain logic as measured without the fold guard (with it, on by default, a kept
    // chain stage here lowers the count by less than 2 per kept chain: not yet understood).
    let o = || {
        OptimizeOptions::default()
            .batches(80)
            .seed(0)
            .fold_guard(false)
    };
    let with = optimize(&mut on, Constraints::default(), o(), |_| {}).unwrap();
    let without = optimize(&mut off, Constraints::default(), o().chains(false), |_| {}).unwrap();
    let kept: usize = with.batches.iter().map(|b| b.chains.kept).sum();
    assert!(kept > 0, "no chain kept: {:?}", with.batches.last());
    let mut last = with.initial_score;
    let mut before = with.batches[0].counts.singularities();
    for b in &with.batches {
        assert!(b.score <= last, "batch {} raised the score", b.batch);
        assert!(b.chains.kept <= b.chains.tried);
        if b.chains.tried > 0 {
            assert_eq!(b.qzips, 0, "chains after a batch that executed Q-zips");
        }
        if b.chains.kept > 0 {
            assert!(b.counts.singularities() + 2 * b.chains.kept <= before);
        }
        (last, before) = (b.score, b.counts.singularities());
    }
    assert!(without
        .batches
        .iter()
        .all(|b| b.chains == Default::default()));
    assert!(
        with.final_counts.singularities() <= without.final_counts.singularities(),
        "{:?} with chains, {:?} without",
        with.final_counts,
        without.final_counts
    );
    assert!(gauss_bonnet(&on.map, MeshKind::Quad).holds());
    assert!(gauss_bonnet(&off.map, MeshKind::Quad).holds());
}

/// A chain stage that keeps nothing leaves the mesh exactly as it was (every chain it
/// tried is undone step by step and the positions restored): the run stopped at that batch
/// ends with the same mesh, positions bit for bit, as the run stopped one batch before. The
/// input is one whose run has such a stage (at batch 22; found by scanning seeds, as the
/// stages a run has change with the placement of new vertices).
#[test]
fn a_chain_stage_that_keeps_nothing_changes_nothing() {
    let input = subdivided(80, 1, 0, 1);
    let run_to = |n: usize| {
        let mut mesh = input.clone();
        let o = OptimizeOptions::default().batches(n);
        let out = optimize(&mut mesh, Constraints::default(), o, |_| {}).unwrap();
        (mesh, out)
    };
    let (_, out) = run_to(40);
    let idle = out
        .batches
        .iter()
        .find(|b| b.qzips == 0 && b.chains.tried > 0 && b.chains.kept == 0)
        .expect("no chain stage that kept nothing in 40 batches")
        .batch;
    let (before, _) = run_to(idle - 1);
    let (after, _) = run_to(idle);
    assert_eq!(after, before, "batch {idle} changed the mesh");
}

/// A mesh whose defects all have one sign already carries the least total defect that
/// Gauss-Bonnet allows, so it is left exactly as it is, with no batch run: a regular torus
/// (none), a cube (eight v3), OpenSubdiv's toroidal tet (eight v6 on genus 3, which the v6
/// preprocessing used to split into sixteen v5 at +29 % faces) and its helmet (four v3 on a
/// dome whose boundary has no defect; a Q-zip used to move one onto the boundary).
#[test]
fn a_mesh_at_the_defect_minimum_is_unchanged() {
    let mut meshes = vec![
        ("torus".to_string(), gen::torus_grid(8, 8)),
        ("cube".to_string(), gen::cube(3)),
    ];
    for name in ["osd_catmark_toroidal_tet.obj", "osd_catmark_helmet.obj"] {
        let path = common::shared(&format!("quad/{name}"));
        meshes.push((name.to_string(), zipmesh::io::read_mesh(&path).unwrap().0));
    }
    for (name, mut mesh) in meshes {
        let before = mesh.clone();
        let out = run(&mut mesh, Constraints::default(), 5, 0);
        assert!(out.minimal, "{name}");
        assert!(out.batches.is_empty() && !out.preprocessed, "{name}");
        assert_eq!(out.final_counts, out.input, "{name}");
        assert!(mesh == before, "{name} changed");
    }
}

/// With `allow_cancellation`, a Q-zip that the grid guard refuses is done: the map stays
/// valid and pure quad, the singularity count changes, and the undo restores map and
/// positions exactly.
#[test]
fn cancelling_qzips_are_valid_and_undo_exactly() {
    use zipmesh::invariants::irregular_vertices;
    use zipmesh::qzip::{Qzip, QzipError, Tag, ZipError};
    let mut mesh = subdivided(200, 2, 0, 3);
    zipmesh::qzip::preprocess(&mut mesh).unwrap();
    let irr = irregular_vertices(&mesh.map, MeshKind::Quad);
    let (mut guarded, mut free) = (Qzip::new(), Qzip::new().allow_cancellation(true));
    let mut done = 0;
    for &a in irr.iter().take(20) {
        for &b in irr.iter().take(20) {
            if a == b {
                continue;
            }
            for tag in [Tag::LS, Tag::RC, Tag::LC, Tag::RS] {
                let refused = match guarded.zip(&mut mesh, a, b, tag) {
                    Ok(z) => {
                        z.undo(&mut mesh).unwrap();
                        false
                    }
                    Err(e) => matches!(e, QzipError::Execute(ZipError::NotGridPreserving { .. })),
                };
                if !refused {
                    continue;
                }
                let before = mesh.clone();
                let z = free
                    .zip(&mut mesh, a, b, tag)
                    .expect("no guard, no refusal");
                mesh.map.check().unwrap();
                assert!(mesh.map.faces().all(|f| mesh.map.degree(f) == 4));
                assert_ne!(
                    irregular_vertices(&mesh.map, MeshKind::Quad).len(),
                    irr.len()
                );
                z.undo(&mut mesh).unwrap();
                assert_eq!(mesh, before);
                done += 1;
            }
        }
    }
    assert!(
        done > 0,
        "no cancelling movement among the first 20 singularities"
    );
}

// ------------------------------------------------------------------------------------
// Quad-dominant input: pairs of triangles crawl together and merge.

/// Generated quad-dominant meshes of genus 0 to 2, with and without boundary, and the
/// cages, each with an even number of triangles.
fn quad_dominant_inputs() -> Vec<(String, Mesh)> {
    let mut out = Vec::new();
    for seed in 0..12u64 {
        let (g, h) = ((seed % 3) as usize, (seed / 3 % 2) as usize);
        let base = gen::random_quad(300 + 40 * seed as usize, g, h, seed);
        let pairs = 1 + (seed % 3) as usize;
        let (mesh, _) = gen::with_triangle_pairs(base, pairs, 10, seed);
        out.push((format!("random_quad genus {g} holes {h} seed {seed}"), mesh));
    }
    for seed in 0..3 {
        let (mesh, _) = gen::quad_dominant(14, 12, 2, seed);
        out.push((format!("torus grid seed {seed}"), mesh));
    }
    for seed in 0..2 {
        out.extend(cages(2, seed));
    }
    out
}

/// Every input's triangles merge in pairs, so the output is pure quad, unless a pair's
/// crawl or merge is refused (counted and printed); validity, chi, boundary loops and
/// components are kept, the counts match the mesh, the score never rises.
#[test]
fn quad_dominant_input_comes_out_pure_quad() {
    let (mut pure, mut total, mut refused) = (0, 0, 0);
    for (name, mut mesh) in quad_dominant_inputs() {
        let tris = mesh
            .map
            .faces()
            .filter(|&f| mesh.map.degree(f) == 3)
            .count();
        assert!(tris > 0 && tris % 2 == 0, "{name}: {tris} triangles");
        let before = Counts::of(&mesh.map);
        let out = run(&mut mesh, Constraints::default(), 6, 1);
        mesh.map.check().unwrap();
        let after = Counts::of(&mesh.map);
        assert_eq!(
            after.euler_characteristic, before.euler_characteristic,
            "{name}"
        );
        assert_eq!(after.boundary_loops, before.boundary_loops, "{name}");
        assert_eq!(after.components, before.components, "{name}");
        assert_eq!(out.input.triangles, tris);
        assert_eq!(out.triangles.input, tris);
        assert_eq!(out.final_counts, SingularityCounts::of(&mesh), "{name}");
        assert_eq!(out.final_counts.triangles, tris - 2 * out.triangles.merged);
        assert!(
            out.batches.windows(2).all(|w| w[1].score <= w[0].score),
            "{name}"
        );
        assert!(
            out.batches.iter().all(|b| b.score <= out.initial_score),
            "{name}"
        );
        total += 1;
        refused += out.triangles.refused;
        if out.final_counts.triangles == 0 {
            pure += 1;
            assert_eq!(MeshKind::of(&mesh.map), MeshKind::Quad);
        } else {
            eprintln!("{name}: {:?}", out.triangles);
        }
    }
    eprintln!("pure quad: {pure} of {total}; refused pairs {refused}");
    // An output with triangles left is one where a pair was refused (printed above).
    assert!(
        pure + refused >= total,
        "pure quad: {pure} of {total}, refused {refused}"
    );
    assert!(pure * 10 >= total * 9, "pure quad: {pure} of {total}");
}

/// The same seed gives the same output on quad-dominant input too.
#[test]
fn quad_dominant_same_seed_same_mesh() {
    for (name, mesh) in quad_dominant_inputs().into_iter().step_by(4) {
        let (mut a, mut b) = (mesh.clone(), mesh);
        let (oa, ob) = (
            run(&mut a, Constraints::default(), 3, 7),
            run(&mut b, Constraints::default(), 3, 7),
        );
        assert_eq!(a, b, "{name}");
        assert_eq!(oa, ob, "{name}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// Over random quad-dominant meshes (any genus, with or without boundary, 1 to 3
    /// triangle pairs): topology and validity kept, the counts match, the score never
    /// rises, every merged pair took two triangles, and the output is pure quad unless a
    /// pair was refused.
    #[test]
    fn quad_dominant_random_meshes(
        faces in 200usize..500, genus in 0usize..3, holes in 0usize..2, pairs in 1usize..4,
        seed in any::<u64>(),
    ) {
        let base = gen::random_quad(faces, genus, holes, seed);
        let (mut mesh, tips) = gen::with_triangle_pairs(base, pairs, 10, seed);
        let before = Counts::of(&mesh.map);
        let out = run(&mut mesh, Constraints::default(), 3, seed);
        mesh.map.check().unwrap();
        let after = Counts::of(&mesh.map);
        prop_assert_eq!(after.euler_characteristic, before.euler_characteristic);
        prop_assert_eq!(after.boundary_loops, before.boundary_loops);
        prop_assert_eq!(out.input.triangles, tips.len());
        prop_assert_eq!(out.final_counts, SingularityCounts::of(&mesh));
        prop_assert_eq!(out.final_counts.triangles, tips.len() - 2 * out.triangles.merged);
        prop_assert!(out.batches.windows(2).all(|w| w[1].score <= w[0].score));
        prop_assert!(out.final_counts.triangles == 0 || out.triangles.refused > 0);
    }
}

/// `OptimizeOptions::until`: the test is asked before each batch and between the
/// candidates of a batch. Stopped after its 40th answer, the run ends inside its first
/// batch (fewer Q-zips than a whole first batch), says so, and leaves a valid map on the
/// input surface; a run without the test is not stopped.
#[test]
fn a_stop_test_ends_the_run_inside_a_batch() {
    let input = subdivided(300, 2, 0, 2);
    let first = {
        let mut mesh = input.clone();
        let o = OptimizeOptions::default().batches(1);
        optimize(&mut mesh, Constraints::default(), o, |_| {}).unwrap()
    };
    assert!(!first.stopped);
    let asked = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let counter = asked.clone();
    let o = OptimizeOptions::default()
        .until(move || counter.fetch_add(1, std::sync::atomic::Ordering::SeqCst) >= 40);
    let mut mesh = input.clone();
    let out = optimize(&mut mesh, Constraints::default(), o, |_| {}).unwrap();
    let qzips = |o: &zipmesh::optimize::Outcome| -> usize {
        o.batches.iter().map(|b| b.qzips + b.chains.qzips).sum()
    };
    assert!(out.stopped);
    assert_eq!(out.batches.len(), 1);
    assert!(
        qzips(&out) < qzips(&first),
        "{} of {}",
        qzips(&out),
        qzips(&first)
    );
    assert_eq!(mesh.map.check(), Ok(()));
    let s = zipmesh::quality::Summary::against(&mesh, &zipmesh::quality::Reference::new(&input));
    assert!(s.distance.unwrap().max < 1e-6, "{:?}", s.distance);
}
