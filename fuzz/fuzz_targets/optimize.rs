//! The batch optimizer on small generated quad meshes (a cube, a torus or a grid with
//! boundary, 4 to 25 faces, with fuzzer-chosen vertex splits making clustered v3/v5
//! singularities), with a fuzzer-chosen seed, one or two batches, a search radius of 1 to
//! 4 edges, smoothing and chain switches and a few protected faces and feature edges. The
//! library must never panic; the oracle: a valid pure-quad map with the input's Euler
//! characteristic, boundary loops and components, a score that never rises, counts that
//! match a recount, batch and chain stats whose face changes are the batch's, a chain stage
//! only after a batch that executed nothing, and the constraints holding; with the fold
//! guard (on for some inputs, with the preprocessing off), no more folded quads than the
//! input had; a mesh whose defects all have one sign comes back unchanged, with no batch;
//! every vertex within 1 % of the input's bounding-box diagonal from its surface.
//!
//! The meshes are small on purpose: on the random meshes of hundreds of faces used before,
//! one input took tens of milliseconds (12 exec/s); see `docs/fuzzing.md`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::invariants::Counts;
use zipmesh::ops::quad;
use zipmesh::optimize::{
    at_defect_minimum, folded_quads, optimize, Constraints, OptimizeOptions, SingularityCounts,
};
use zipmesh::quality::{Reference, Summary};
use zipmesh::{gen, Dart, Face, Mesh};

/// The mesh bytes 0 to 4 ask for: a small cube, torus or grid with up to two vertex splits
/// (at darts named by bytes 3 and 4; refused splits and boundary vertices are skipped).
fn mesh(byte: impl Fn(usize) -> u8) -> Mesh {
    let (a, b) = (usize::from(byte(1) % 3), usize::from(byte(2) % 3));
    let mut mesh = match byte(0) % 3 {
        0 => gen::cube(1 + a % 2),
        1 => gen::torus_grid(3 + a, 3 + b),
        _ => gen::grid(2 + a, 2 + b),
    };
    for i in 0..usize::from(byte(0) / 4 % 3) {
        let slots = mesh.map.dart_slots().max(1) as u32;
        let d = Dart::new(u32::from(byte(3 + i)) * 13 % slots);
        if !mesh.map.is_live_dart(d) || mesh.map.is_boundary_vertex(mesh.map.origin(d)) {
            continue;
        }
        let d2 = mesh.map.rotate_cw(mesh.map.rotate_cw(d));
        let Ok(split) = quad::split_vertex(&mut mesh.map, d, d2) else {
            continue;
        };
        // The new vertex sits halfway to the centroid of its neighbours (none is new).
        let v = split.created();
        let p = mesh.positions[split.kept().index()];
        let ring: Vec<_> = mesh.map.vertex_darts(v).map(|d| mesh.map.dest(d)).collect();
        let mut c = glam::DVec3::ZERO;
        for w in &ring {
            c += mesh.positions.get(w.index()).copied().unwrap_or(p);
        }
        let c = c / ring.len().max(1) as f64;
        mesh.positions.resize(mesh.map.vertex_slots(), p);
        mesh.positions[v.index()] = (p + c) / 2.0;
    }
    mesh
}

fuzz_target!(|data: &[u8]| {
    let byte = |i: usize| data.get(i).copied().unwrap_or(0);
    let mut mesh = mesh(byte);
    let mut c = Constraints::default();
    let live: Vec<Face> = mesh.map.faces().collect();
    for i in 0..usize::from(byte(6) % 4) {
        if let Some(&f) = live.get(usize::from(byte(7 + i)) % live.len().max(1)) {
            c.protect_face(&mesh, f).unwrap();
        }
    }
    let edges: Vec<_> = mesh.map.edges().collect();
    for i in 0..usize::from(byte(11) % 3) {
        if let Some(e) = edges.get(usize::from(byte(12 + i)) * 7 % edges.len().max(1)) {
            let (a, b) = (mesh.map.origin(e.dart(0)), mesh.map.dest(e.dart(0)));
            c.add_feature(&mesh, a, b).unwrap();
        }
    }
    let before = Counts::of(&mesh.map);
    let check = c.clone();
    let mut options = OptimizeOptions::default()
        .batches(1 + usize::from(byte(15) % 2))
        .seed(u64::from(byte(16)))
        .smoothing(byte(17) % 2 == 0)
        .chains(byte(19) % 4 != 3);
    // A singularity looks for targets at most 1 to 4 edges away (64 by default, more than
    // these meshes span), and smoothing takes one step: the batch's work stays small.
    options.search_radius = 1 + u32::from(byte(18) % 4);
    options.smooth_iterations = 1;
    // With the fold guard (and no preprocessing, whose splits it does not guard) the
    // folded quads never grow in number.
    let guard = byte(19) & 4 != 0;
    if guard {
        options = options.fold_guard(true);
        options.preprocess = false;
    }
    let folds = folded_quads(&mesh);
    let input = mesh.clone();
    // A mesh whose defects all have one sign is returned as it was, with no batch.
    let minimal = at_defect_minimum(&mesh).then(|| mesh.clone());
    let out = optimize(&mut mesh, c, options, |_| {}).expect("a quad mesh is accepted");
    assert_eq!(out.minimal, minimal.is_some());
    if let Some(input) = minimal {
        assert!(
            mesh == input && out.batches.is_empty(),
            "a minimal mesh was changed"
        );
    }
    if guard {
        assert!(
            folded_quads(&mesh) <= folds,
            "the fold guard let a fold through"
        );
    }
    mesh.map.check().expect("a valid map");
    let after = Counts::of(&mesh.map);
    assert_eq!(
        (
            after.euler_characteristic,
            after.boundary_loops,
            after.components
        ),
        (
            before.euler_characteristic,
            before.boundary_loops,
            before.components
        )
    );
    assert!(mesh.map.faces().all(|f| mesh.map.degree(f) == 4));
    let mut last = out.initial_score;
    for (i, b) in out.batches.iter().enumerate() {
        assert!(b.score <= last, "the score rose");
        last = b.score;
        let c = b.chains;
        assert!(
            c.tried == 0 || b.qzips == 0,
            "chains after a batch that executed Q-zips"
        );
        assert!(
            c.kept <= c.cancelled && c.cancelled <= c.tried && c.qzips >= c.kept,
            "{c:?}"
        );
        if let Some(prev) = i.checked_sub(1).map(|j| &out.batches[j]) {
            let change = b.counts.faces as isize - prev.counts.faces as isize;
            let stated = b.stats.face_change + c.face_change;
            assert_eq!(change, stated, "the stats miss a face change");
        }
    }
    assert_eq!(out.final_counts, SingularityCounts::of(&mesh));
    assert!(check.holds(&mesh), "a constraint broke");
    // Every vertex stays within 1 % of the input's diagonal from its surface.
    let far = Summary::against(&mesh, &Reference::new(&input))
        .distance
        .map_or(0.0, |d| d.max);
    assert!(
        far <= 0.01,
        "a vertex {far} of the diagonal off the input surface"
    );
});
