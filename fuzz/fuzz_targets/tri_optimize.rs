//! The triangle-mesh optimizer (`optimize_triangles`) on small fuzzer-chosen random
//! triangle meshes (20 to 110 faces, genus 0 to 2, 0 or 1 hole), with fuzzer-chosen jitter
//! of the positions (so the fold checks and their undo run) and options (1 to 3 batches,
//! search radius 1 to 8, relaxation on or off, face drift 0 to 15 %). The library must
//! never panic; the oracle is the `optimize-triangles` campaign property's
//! (`campaign::check_optimize_triangles`): a valid all-triangle map with the input's
//! Euler characteristic, boundary loops, components and boundary valences, an irregular
//! count that never rises (nor the score while it stays), the face count within the drift,
//! counts that match. The look-ahead is on for one input in four.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::campaign::check_optimize_triangles;
use zipmesh::gen;
use zipmesh::optimize::TriOptimizeOptions;

fuzz_target!(|data: &[u8]| {
    let byte = |i: usize| data.get(i).copied().unwrap_or(0);
    let seed = u64::from(byte(3)) | (u64::from(byte(4)) << 8);
    let faces = 20 + 6 * usize::from(byte(0) % 16);
    let mut mesh = gen::random_triangle(
        faces,
        usize::from(byte(1) % 3),
        usize::from(byte(2) % 2),
        seed,
    );
    // Up to 8 vertices pushed by up to 0.05 (the mesh spans the unit cube) along fuzzer-chosen axes.
    for ch in data.get(9..).unwrap_or(&[]).chunks(3).take(8) {
        let n = mesh.positions.len().max(1);
        let (i, axis, amount) = (
            usize::from(ch[0]) % n,
            ch.get(1).copied().unwrap_or(0) % 3,
            ch.get(2).copied().unwrap_or(0),
        );
        let shift = (f64::from(amount) - 127.5) / 2550.0;
        if let Some(p) = mesh.positions.get_mut(i) {
            p[usize::from(axis)] += shift;
        }
    }
    let options = TriOptimizeOptions {
        max_batches: 1 + usize::from(byte(5) % 3),
        search_radius: 1 + usize::from(byte(6) % 8),
        relax: byte(7) % 2 == 0,
        // One input in four: a look-ahead pass costs about 1 ms per irregular vertex here.
        lookahead: byte(7) & 6 == 0,
        face_drift: f64::from(byte(8) % 16) / 100.0,
    };
    let outcome = check_optimize_triangles(&mesh, &options);
    assert!(!outcome.is_fail(), "{outcome:?}");
});
