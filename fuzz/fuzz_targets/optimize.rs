//! The batch optimizer on small generated quad meshes (a Catmull-Clark step of a random
//! triangle mesh, or a random quad mesh), with a fuzzer-chosen seed, batch count, smoothing
//! switch and a few protected faces and feature edges. The library must never panic; the
//! oracle: a valid pure-quad map with the input's Euler characteristic, boundary loops and
//! components, a score that never rises, counts that match a recount, batch stats whose
//! face change is the batch's, and the constraints holding.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::invariants::Counts;
use zipmesh::optimize::{optimize, Constraints, OptimizeOptions, SingularityCounts};
use zipmesh::{gen, Face};

fuzz_target!(|data: &[u8]| {
    let byte = |i: usize| data.get(i).copied().unwrap_or(0);
    let (faces, genus, holes) = (
        20 + usize::from(byte(0) % 30),
        usize::from(byte(1) % 3),
        usize::from(byte(2) % 2),
    );
    let seed = u64::from(byte(3)) | u64::from(byte(4)) << 8;
    let mut mesh = if byte(5) % 2 == 0 {
        gen::catmull_clark(&gen::random_triangle(faces, genus, holes, seed))
    } else {
        gen::random_quad(faces, genus, holes, seed)
    };
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
    let options = OptimizeOptions::default()
        .batches(1 + usize::from(byte(15) % 2))
        .seed(u64::from(byte(16)))
        .smoothing(byte(17) % 2 == 0);
    let out = optimize(&mut mesh, c, options, |_| {}).expect("a quad mesh is accepted");
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
        if let Some(prev) = i.checked_sub(1).map(|j| &out.batches[j]) {
            let change = b.counts.faces as isize - prev.counts.faces as isize;
            assert_eq!(change, b.stats.face_change, "the stats miss a face change");
        }
    }
    assert_eq!(out.final_counts, SingularityCounts::of(&mesh));
    assert!(check.holds(&mesh), "a constraint broke");
});
