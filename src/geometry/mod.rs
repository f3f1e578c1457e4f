//! Geometry kept sound through connectivity edits: an edit's footprint relaxed on the input
//! surface ([`relax_footprint`], what `zipmesh zip` does after a Q-zip unless `--no-relax`).
//!
//! The kernel (`map`, `ops`, `qzip`) edits connectivity and places each new vertex by a
//! rule of the attribute layer; this module moves positions afterwards, on the input
//! surface ([`Surface`]), with the measures of one polygon that `quality` reports
//! (`quality::{normal, scaled_jacobian, corner_fold, ...}`).
//! `docs/quality.md` ("Q-zip placement and relaxation") gives the numbers on the shipped
//! meshes.
//!
//! ```
//! use zipmesh::geometry::{edited_vertices, relax_footprint, RelaxOptions, Surface};
//! use zipmesh::qzip::{Qzip, Tag};
//! let input = zipmesh::gen::cube(4);
//! let mut mesh = input.clone();
//! let (a, b) = (zipmesh::Vert::new(0), zipmesh::Vert::new(4));
//! Qzip::new().zip(&mut mesh, a, b, Tag::LS).unwrap();
//! let seeds = edited_vertices(&input, &mesh);
//! let r = relax_footprint(&mut mesh, &Surface::new(&input), &seeds, RelaxOptions::default());
//! assert!(r.region >= seeds.len());
//! ```

pub(crate) mod element;
mod region;
mod relax;
mod surface;

pub use region::{relax_region, touched_vertices};
pub use relax::{edited_vertices, relax_footprint, RelaxOptions, Relaxation};
pub(crate) use relax::{relax_footprint_fixed, widen_thin_triangles};
pub use surface::Surface;
