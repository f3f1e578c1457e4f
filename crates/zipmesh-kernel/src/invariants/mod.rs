//! The theorem layer: counts, Euler characteristic, genus, histograms, irregular vertices,
//! discrete Gauss-Bonnet, and canonical codes for isomorphism.
//!
//! Every function here reads a [`Map`](crate::Map) and never changes it.

pub mod canonical;
mod counts;
mod gauss_bonnet;
mod valence;

pub use counts::{euler_characteristic, non_simple_edges, Counts};
pub use gauss_bonnet::{gauss_bonnet, GaussBonnet};
pub use valence::{
    irregular_valences, irregular_vertices, is_irregular, is_regular_interior, regular_valence,
    Histograms, MeshKind,
};
