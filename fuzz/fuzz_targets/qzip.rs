//! Q-zip on generated quad meshes with singularities, between fuzzer-chosen vertices (any
//! vertices: irregular, regular, on the boundary), with a fuzzer-chosen initial tag, along
//! the shortest path or a fuzzer-perturbed one (`common/qzip_case.rs`). The library must
//! never panic; these assertions are the oracle: a refusal leaves the map `==` the original;
//! a done edit leaves a valid pure-quad map with the same Euler characteristic, boundary
//! loops and multiset of irregular (valence, boundary) pairs, V changed by the report's
//! delta, the pair's valences on the moved vertices, and an exact undo.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::qzip::{verify_edit, Qzip};

#[path = "common/qzip_case.rs"]
mod qzip_case;

fuzz_target!(|data: &[u8]| {
    let Some(c) = qzip_case::case(data) else {
        return;
    };
    let mut map = c.original.clone();
    let report = match Qzip::new().zip_along(&mut map, &c.path, c.tag) {
        Ok(r) => r,
        Err(e) => {
            assert!(map == c.original, "a refused Q-zip changed the map: {e}");
            return;
        }
    };
    if let Err(b) = verify_edit(&c.original, &map, &c.path, &report) {
        panic!("{b}\n{}", report.surgery());
    }
});
