//! `Map::from_permutation` on any arrays (raw, or shuffled into a permutation with
//! cycle-constant marks): never a panic; every map it returns is valid and keeps `next`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::arbitrary::PermutationInput;
use zipmesh::{Dart, Map};
use zipmesh_fuzz::assert_valid;

fuzz_target!(|input: PermutationInput| {
    let (next, boundary) = input.arrays();
    let Ok(map) = Map::from_permutation(&next, &boundary) else {
        return;
    };
    assert_valid(&map);
    for (d, (&n, &b)) in next.iter().zip(&boundary).enumerate() {
        let d = Dart::new(d as u32);
        assert_eq!(map.next(d), Dart::new(n));
        assert_eq!(map.is_boundary_dart(d), b);
    }
});
