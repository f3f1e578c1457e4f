//! Negative checks: `Map::from_permutation` rejects every invalid input.
//!
//! A valid map's internals cannot be mutated through the public API, so the rejection side
//! is checked at the only door that takes raw data. Enumeration: every `next` array of
//! length <= 4 with entries in `0..=len` (one out of range) and every boundary array of
//! length `len - 1..=len + 1`; then every permutation of even length <= 6 with every
//! marking, constant on cycles or not (46 473 cases).

use crate::choice::{Choice, Exhaustive};
use crate::oracle::orbits;
use std::collections::BTreeMap;
use zipmesh_kernel::{Map, RawError};

/// What `from_permutation` may answer: `None` for Ok, else the errors that are true of it.
fn allowed(next: &[u32], boundary: &[bool]) -> Option<Vec<RawError>> {
    let n = next.len();
    if n % 2 == 1 || boundary.len() != n {
        return Some(vec![RawError::Size]);
    }
    let mut sorted = next.to_vec();
    sorted.sort();
    if sorted != (0..n as u32).collect::<Vec<_>>() {
        return Some(vec![RawError::NotPermutation]);
    }
    let mut errs = Vec::new();
    if (0..n).any(|d| boundary[d] != boundary[next[d] as usize]) {
        errs.push(RawError::MixedCycle);
    }
    if (0..n).any(|d| boundary[d] && boundary[d ^ 1]) {
        errs.push(RawError::FacelessEdge);
    }
    if !errs.is_empty() {
        return Some(errs);
    }
    let (v, nv) = orbits(n, |d| next[d ^ 1] as usize);
    let mut out = vec![0; nv];
    for d in 0..n {
        out[v[d]] += usize::from(boundary[d]);
    }
    out.iter()
        .any(|&k| k > 1)
        .then(|| vec![RawError::PinchedBoundary])
}

/// Property: `from_permutation` answers what `allowed` says, and Ok maps pass `check()`.
pub fn raw_properties(next: &[u32], boundary: &[bool]) -> String {
    let got = Map::from_permutation(next, boundary);
    match (allowed(next, boundary), &got) {
        (None, Ok(m)) => assert_eq!(m.check(), Ok(()), "{next:?} {boundary:?}"),
        (Some(errs), Err(e)) => assert!(
            errs.contains(e),
            "{next:?} {boundary:?}: {e:?} not in {errs:?}"
        ),
        (want, _) => panic!("{next:?} {boundary:?}: expected {want:?}, got {got:?}"),
    }
    match got {
        Ok(_) => "Ok".into(),
        Err(e) => format!("{e:?}"),
    }
}

#[test]
fn rejects_every_small_invalid_array() {
    let mut tally: BTreeMap<String, u64> = BTreeMap::new();
    let paths = Exhaustive::run(
        |c| {
            let len = c.any(5);
            let next: Vec<u32> = (0..len).map(|_| c.any(len + 1) as u32).collect();
            let blen = (len + c.any(3)).saturating_sub(1);
            let boundary: Vec<bool> = (0..blen).map(|_| c.any_bool()).collect();
            raw_properties(&next, &boundary)
        },
        |o| *tally.entry(o).or_default() += 1,
    );
    eprintln!("{paths} arbitrary arrays: {tally:?}");
    for kind in [
        "Ok",
        "Size",
        "NotPermutation",
        "MixedCycle",
        "FacelessEdge",
        "PinchedBoundary",
    ] {
        assert!(tally.contains_key(kind), "no case reached {kind}");
    }
}

#[test]
fn rejects_every_mixed_marking() {
    let mut tally: BTreeMap<String, u64> = BTreeMap::new();
    let paths = Exhaustive::run(
        |c| {
            let len = 2 * c.any(4);
            let next: Vec<u32> = c
                .any_permutation(len)
                .into_iter()
                .map(|x| x as u32)
                .collect();
            let boundary: Vec<bool> = (0..len).map(|_| c.any_bool()).collect();
            raw_properties(&next, &boundary)
        },
        |o| *tally.entry(o).or_default() += 1,
    );
    // sum over len = 0, 2, 4, 6 of len! 2^len.
    assert_eq!(paths, 1 + 2 * 4 + 24 * 16 + 720 * 64);
    eprintln!("{paths} permutations with any marking: {tally:?}");
    assert!(tally.contains_key("MixedCycle"));
}
