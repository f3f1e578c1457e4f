//! Bounded model checking by exhaustive enumeration.
//!
//! Each property is a plain function that takes its inputs from a [`choice::Choice`]
//! source: [`choice::Exhaustive`] runs it on every input up to a stated bound, and
//! [`choice::Random`] samples inputs past the bound. The bounds and counts are in each
//! module's header and printed by the tests (`cargo test -p zipmesh-kernel --test proofs -- --nocapture`).

mod choice;
mod maps;
mod ops_quad;
mod ops_tri;
mod oracle;
mod polygons;
mod raw;
