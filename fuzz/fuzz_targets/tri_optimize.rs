//! The triangle-mesh optimizer (`optimize_triangles`) on small fuzzer-chosen random
//! triangle meshes (12 to 28 faces asked for; genus 0 or 1, genus 2 for one input in four,
//! whose generator's minimum is about 60 faces; one boundary loop for half the inputs: the
//! generator's own hole on genus 1, elsewhere a closed mesh with one fuzzer-chosen triangle
//! left out, as the generator's smallest genus-0 disk has about 300 faces), with
//! fuzzer-chosen jitter of the positions (so the fold checks and their undo run) and options
//! (1 to 3 batches, search radius 1 to 8, relaxation on for one input in four, face drift 0
//! to 15 %). The library must never panic; the oracle is the `optimize-triangles` campaign
//! property's (`campaign::check_optimize_triangles`): a valid all-triangle map with the
//! input's Euler characteristic, boundary loops, components and boundary valences, an
//! irregular count that never rises (nor the score while it stays), the face count within
//! the drift, counts that match (the last batch's or the restored one's), and with the
//! relaxation on the geometry bounds: no new flipped triangle, no more thin triangles than
//! the input's and the slack, every vertex within 0.5 % of the input's diagonal from its
//! surface.
//!
//! The look-ahead is on for one input in 64, chosen by a hash of the whole input, on the
//! smallest meshes (12 faces asked for, genus 0 or 1). Even there one input with it costs
//! about 1 to 3 ms (every pair of edits near every irregular vertex), against about 0.1 to
//! 0.2 ms without it. Chosen by a byte, it would be kept by most mutations of an input that
//! has it, and as the look-ahead's code gives new coverage such inputs fill the corpus:
//! one in 64 by a byte still made a fifth of the corpus and about half the time
//! (`docs/fuzzing.md`). By the hash, every mutation draws again.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::cell::RefCell;
use std::collections::HashMap;
use zipmesh::campaign::check_optimize_triangles;
use zipmesh::optimize::TriOptimizeOptions;
use zipmesh::{gen, Mesh};

/// The mesh's arguments: faces asked for, genus, hole (`None`, or the generator's own
/// `Some(None)`, or `Some(Some(i))`: the face of index `i mod F` left out), seed.
type Key = (usize, usize, Option<Option<u8>>, u16);

thread_local! {
    /// Meshes built by earlier runs (`zipmesh_fuzz::cached`).
    static MESHES: RefCell<HashMap<Key, Mesh>> = RefCell::new(HashMap::new());
}

/// The mesh the key names, from the cache.
fn generated(key: Key) -> Mesh {
    MESHES.with(|cache| {
        zipmesh_fuzz::cached(cache, key, |(faces, genus, hole, seed)| {
            let seed = u64::from(seed);
            match hole {
                None => gen::random_triangle(faces, genus, 0, seed),
                Some(None) => gen::random_triangle(faces, genus, 1, seed),
                Some(Some(i)) => {
                    // A closed mesh with one triangle left out: one boundary loop of three
                    // vertices, each keeping at least two faces (every vertex had three).
                    let closed = gen::random_triangle(faces, genus, 0, seed);
                    let mut polygons = closed.polygons();
                    polygons.remove(usize::from(i) % polygons.len());
                    Mesh::from_polygons(closed.positions, &polygons)
                        .expect("a closed manifold less one face is a manifold")
                        .0
                }
            }
        })
    })
}

fuzz_target!(|data: &[u8]| {
    let byte = |i: usize| data.get(i).copied().unwrap_or(0);
    // One input in 64, by a hash of all its bytes (FNV-1a): see the module docs.
    let hash = data.iter().fold(0x811c_9dc5_u32, |h, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    });
    let lookahead = hash % 64 == 0;
    let seed = u16::from(byte(3)) | (u16::from(byte(4)) << 8);
    // 12 to 28 faces asked for (20 to 110 before): a batch's passes grow with the faces.
    let faces = if lookahead {
        12
    } else {
        12 + 4 * usize::from(byte(0) % 5)
    };
    // Genus 2 (60 faces or more) for one input in four, genus 0 and 1 otherwise.
    let genus = [0, 1, 0, 2][usize::from(byte(1) % 4)] % if lookahead { 2 } else { 3 };
    let hole = match (byte(2) % 2, genus) {
        (0, _) => None,
        (_, 1) => Some(None),
        _ => Some(Some(byte(2) / 2)),
    };
    let mut mesh = generated((faces, genus, hole, seed));
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
        // One input in four (one in two before): the relaxation's projections onto the
        // input surface (`Surface::closest`) were about a quarter of the time.
        relax: byte(7) % 4 == 0,
        lookahead,
        face_drift: f64::from(byte(8) % 16) / 100.0,
    };
    let outcome = check_optimize_triangles(&mesh, &options);
    assert!(!outcome.is_fail(), "{outcome:?}");
});
