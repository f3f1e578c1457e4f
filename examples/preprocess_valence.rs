//! `qzip::preprocess` on one vertex of high valence:
//! `cargo run --release --example preprocess_valence -- [K...]` (default 1000 10000 100000).
//!
//! For each K builds the disk of K quads around one interior vertex (quad i is
//! `(0, s_i, m_i, s_(i+1))`, the rim on the boundary) and prints the median of three runs of
//! `preprocess` (each on a fresh copy) with the number of operations:
//!
//! `RESULT zipmesh preprocess valence K <median s> <min s> <max s> <operations>`

use std::time::Instant;
use zipmesh::qzip;
use zipmesh::Map;

/// The disk of `k` quads around vertex 0 (spoke ends `1 + 2i`, rim middles `2 + 2i`).
fn fan(k: u32) -> Map {
    let s = |i: u32| 1 + 2 * (i % k);
    let faces: Vec<[u32; 4]> = (0..k).map(|i| [0, s(i), 2 + 2 * i, s(i + 1)]).collect();
    Map::from_polygons((1 + 2 * k) as usize, &faces).expect("a fan is a valid disk")
}

fn main() {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a valence"))
        .collect();
    let ks = if args.is_empty() {
        vec![1_000, 10_000, 100_000]
    } else {
        args
    };
    for k in ks {
        let map = fan(k);
        let mut times = Vec::new();
        let mut ops = 0;
        for _ in 0..3 {
            let mut m = map.clone();
            let t = Instant::now();
            let p = qzip::preprocess(&mut m).expect("the fan preprocesses");
            times.push(t.elapsed().as_secs_f64());
            ops = p.records().len();
        }
        times.sort_by(f64::total_cmp);
        println!(
            "RESULT zipmesh preprocess valence {k} {:.4} {:.4} {:.4} {ops}",
            times[1], times[0], times[2]
        );
    }
}
