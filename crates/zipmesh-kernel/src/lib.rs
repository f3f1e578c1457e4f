//! # zipmesh-kernel
//!
//! The `no_std` combinatorial-map kernel of [zipmesh](https://crates.io/crates/zipmesh):
//! half-edge maps of quad, triangle and quad-dominant meshes ([`map`]), per-vertex values kept
//! in step with edits ([`mesh`]), the triangle moves of quad-dominant meshes ([`quad_dominant`]), the invariants and canonical codes the editing papers state
//! as checkable identities ([`invariants`]), and the atomic edits with their undo records
//! ([`ops`]). It is the part of zipmesh that is checked exhaustively up to a bound (`proofs/`
//! in the repository, docs/VERIFICATION.md) and it uses no `unsafe` code.
//!
//! ```
//! use zipmesh_kernel::{invariants::Counts, Map};
//! // Two quads sharing an edge: a disk.
//! let map = Map::from_polygons(6, &[[0u32, 1, 4, 3], [1, 2, 5, 4]]).unwrap();
//! map.check().unwrap();
//! let c = Counts::of(&map);
//! assert_eq!((c.euler_characteristic, c.boundary_loops), (1, 1));
//! ```
//!
//! ## Features
//! * `std` (default): `std::error::Error` for the error types.
//! * `testkit`: [`gen`] (test meshes) and [`rng`] (the seeded generator behind them), for
//!   tests, benchmarks and fuzzers.
//!
//! ## The papers
//! * The Q-zip paper: *Q-zip: Singularity Editing Primitive for Quad Meshes*, ACM
//!   Transactions on Graphics (quad collapse and vertex split, Sec. 2.2; triangles in quad
//!   meshes, Sec. 3.2).
//! * The triangle paper: Yuanyuan Li, Eugene Zhang, Yoshihiro Kobayashi, Peter Wonka,
//!   *Editing Operations for Irregular Vertices in Triangle Meshes*, ACM Transactions on
//!   Graphics 29(6), 2010 (edge flip, edge collapse and vertex split, Sec. 6.1).
#![no_std]
#![warn(missing_docs)]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod edit;
#[cfg(feature = "testkit")]
pub mod gen;
pub mod invariants;
pub mod map;
pub mod mesh;
pub mod ops;
pub mod quad_dominant;
#[cfg(feature = "testkit")]
pub mod rng;

pub use invariants::canonical::{is_isomorphic, is_isomorphic_mirror};
pub use map::{
    BuildError, BuildReport, Compaction, Dart, Edge, Face, Map, RawError, Vert, Violation,
};
pub use mesh::Mesh;
