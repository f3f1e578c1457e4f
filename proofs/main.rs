//! Bounded model checking by exhaustive enumeration: the triangle paper's retriangulations.
//!
//! The kernel's exhaustive proofs (maps, polygon lists, the atomic operators) are in
//! `crates/zipmesh-kernel/proofs/`; this one needs the triangle edits. Its bounds and counts
//! are in the module's header and printed by `cargo test --test proofs -- --nocapture`.

mod retriangulate;
