//! Reversal of Q-zip on fuzzer-chosen cases (`common/qzip_case.rs`): `qzip::find_reverse`
//! never panics, and a reverse run it names is realizable and gives back a map isomorphic
//! to the original (the oracle re-runs it on a fresh copy and compares canonical codes).
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::qzip::{find_reverse, Qzip};

#[path = "common/qzip_case.rs"]
mod qzip_case;

fuzz_target!(|data: &[u8]| {
    let Some(c) = qzip_case::case(data) else {
        return;
    };
    let mut edited = c.original.clone();
    let Ok(report) = Qzip::new().zip_along(&mut edited, &c.path, c.tag) else {
        return;
    };
    if let Some(back) = find_reverse(&edited, &report, &c.original) {
        let mut m = edited.clone();
        let r = Qzip::new().zip_along(&mut m, &back.path, back.tag);
        assert!(r.is_ok(), "the named reverse run is refused: {:?}", r.err());
        assert!(
            CanonicalCode::of(&m) == CanonicalCode::of(&c.original),
            "the named reverse run {} along {} does not restore the original",
            back.tag,
            back.path
        );
    }
});
