//! # zipmesh
//!
//! A small, `no_std` combinatorial-map kernel for editing the connectivity of quad, triangle
//! and quad-dominant meshes, with the invariants the editing papers state as checkable
//! identities.
//!
//! The data flows one way, and so do the modules:
//! mesh file ([`io`], `std`) → [`Map`] ([`map`], built by [`Map::from_polygons`]) with
//! per-vertex data ([`mesh`]) → edits ([`ops`], [`qzip`]), each returning a
//! [`mesh::Edited`] whose undo restores map and data → checks ([`Map::check`],
//! [`invariants`], `campaign`) and measures of the geometry ([`quality`]) → mesh file. [`gen`] makes the test meshes.
//!
//! ```
//! use zipmesh::{gen, invariants::Counts};
//! let torus = gen::torus_grid(8, 6).map;
//! torus.check().unwrap();
//! let c = Counts::of(&torus);
//! assert_eq!((c.euler_characteristic, c.genus), (0, 1));
//! ```
//!
//! What is proven and what is tested is listed in `docs/VERIFICATION.md`: exhaustive
//! enumeration of every map up to a bound (`proofs/`), property tests, and fuzz targets.
//!
//! ## Features
//! * `std` (default): mesh files ([`io`]), `std::error::Error` for the error types.
//! * `campaign`: [`campaign`], property campaigns over generated or given meshes (rayon).
//! * `parallel`: the optimizer's candidate search on every core (rayon); the same output
//!   without it.
//! * `parry`: [`quality::Reference`] answers closest-point queries with parry3d-f64's
//!   `TriMesh`: the same distances, 2 to 5 times faster than the built-in grid for vertices
//!   moved off the surface.
//! * `render`: [`render`], pictures of meshes (SVG, and PNG through resvg).
//! * `arbitrary`: `arbitrary::Arbitrary` for the fuzzers' input types.
//!
//! ## The papers
//! * The Q-zip paper: *Q-zip: Singularity Editing Primitive for Quad Meshes*, ACM
//!   Transactions on Graphics (Q-zip, Sec. 2; triangles in quad meshes, Sec. 3.2;
//!   the batch optimizer, Sec. 4): [`qzip`], [`optimize`].
//! * The triangle paper: Yuanyuan Li, Eugene Zhang, Yoshihiro Kobayashi, Peter Wonka,
//!   *Editing Operations for Irregular Vertices in Triangle Meshes*, ACM Transactions on
//!   Graphics 29(6), 2010 (the semantic edits, Sec. 6-7; relaxation,
//!   Sec. 8): [`tri_edit`], [`optimize`] on triangle meshes.
#![no_std]
#![warn(missing_docs)]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(feature = "arbitrary")]
pub mod arbitrary;
#[cfg(feature = "campaign")]
pub mod campaign;
pub mod geometry;
#[cfg(feature = "std")]
pub mod io;
pub mod optimize;
pub mod quality;
pub mod qzip;
#[cfg(feature = "render")]
pub mod render;
pub mod tri_edit;

// The kernel's modules and root items, at the paths they have always had here.
pub use zipmesh_kernel::{gen, invariants, map, mesh, ops, quad_dominant, rng};
pub use zipmesh_kernel::{
    is_isomorphic, is_isomorphic_mirror, BuildError, BuildReport, Compaction, Dart, Edge, Face,
    Map, Mesh, RawError, Vert, Violation,
};

/// The README's Rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
