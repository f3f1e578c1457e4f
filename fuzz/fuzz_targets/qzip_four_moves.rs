//! The four movements of a pair are pairwise different inside a regular region, on
//! fuzzer-chosen cases (`common/qzip_case.rs`): when the path is a shortest one of 3 edges or
//! more and every vertex within two edges of it is regular apart from the two ends, the
//! realizable movements give pairwise non-isomorphic maps. Refusals leave the map untouched.
//! (Shortest, because a path bent round a quad is homotopic to a shorter one: this target
//! found 0 -> 3 -> 2 -> 1 -> 4 round quad 0-3-2-1, homotopic to 0 -> 1 -> 4 between two v3s,
//! along which LS and RS are one and the same vertex split.)
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::qzip::{sketch, Path, Qzip, SketchOptions, Tag};
use zipmesh::{Map, Vert};

#[path = "common/qzip_case.rs"]
mod qzip_case;

/// Every vertex within two edges of the path is regular and interior, ends excepted.
fn in_regular_region(map: &Map, p: &Path) -> bool {
    let ok = |y: Vert| {
        y == p.start() || y == p.end() || (map.valence(y) == 4 && !map.is_boundary_vertex(y))
    };
    p.len() >= 3
        && p.vertices().iter().all(|&x| {
            map.vertex_darts(x).all(|d| {
                let y = map.dest(d);
                ok(y) && map.vertex_darts(y).all(|e| ok(map.dest(e)))
            })
        })
}

fuzz_target!(|data: &[u8]| {
    let Some(c) = qzip_case::case(data) else {
        return;
    };
    if !in_regular_region(&c.original, &c.path) {
        return;
    }
    let shortest = sketch(
        &c.original,
        c.path.start(),
        c.path.end(),
        &SketchOptions::default(),
    );
    if shortest.map_or(true, |s| s.len() != c.path.len()) {
        return;
    }
    let codes: Vec<(Tag, CanonicalCode)> = Tag::CCW
        .iter()
        .filter_map(|&t| {
            let mut m = c.original.clone();
            match Qzip::new().zip_along(&mut m, &c.path, t) {
                Ok(_) => Some((t, CanonicalCode::of(&m))),
                Err(e) => {
                    assert!(m == c.original, "a refused Q-zip changed the map: {e}");
                    None
                }
            }
        })
        .collect();
    for (i, (ti, ci)) in codes.iter().enumerate() {
        for (tj, cj) in &codes[..i] {
            assert!(
                ci != cj,
                "movements {ti} and {tj} along {} are isomorphic",
                c.path
            );
        }
    }
});
