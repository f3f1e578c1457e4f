//! Homotopy invariance of Q-zip (Sec. 3.1) on fuzzer-chosen cases (`common/qzip_case.rs`):
//! the path and one of its one-quad sweeps (`qzip::one_quad_sweeps`, picked by the fuzzer)
//! give the same map up to isomorphism for matching movements (labels matched by
//! `qzip::start_turn`) whenever both are done. Refusals leave the map untouched. Paths that
//! wrap round a handle (`qzip::wraps`, where the theorem's lifting does not hold) list no
//! sweep and are skipped.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::qzip::{one_quad_sweeps, start_turn, Qzip};

#[path = "common/qzip_case.rs"]
mod qzip_case;

fuzz_target!(|data: &[u8]| {
    let Some(mut c) = qzip_case::case(data) else {
        return;
    };
    let sweeps = one_quad_sweeps(&c.original, &c.path);
    if sweeps.is_empty() {
        return;
    }
    let (_, swept) = &sweeps[usize::from(c.rest.u8()) % sweeps.len()];
    let k = start_turn(&c.original, &c.path, swept).expect("a sweep keeps the start");
    let run = |p, t| {
        let mut m = c.original.clone();
        match Qzip::new().zip_along(&mut m, p, t) {
            Ok(_) => Some(CanonicalCode::of(&m)),
            Err(e) => {
                assert!(m == c.original, "a refused Q-zip changed the map: {e}");
                None
            }
        }
    };
    if let (Some(a), Some(b)) = (run(&c.path, c.tag), run(swept, c.tag.turned(k))) {
        assert!(
            a == b,
            "movement {} along {} and {} along {} differ",
            c.tag,
            c.path,
            c.tag.turned(k),
            swept
        );
    }
});
