//! Q-zip (Sec. 2 and 3.1 of the Q-zip paper): moving a pair of singularities of a quad mesh
//! along a surgery path.
//!
//! The edit runs in four stages; the first two are implemented, the fourth in part:
//!
//! 1. [`sketch`](mod@sketch): a simple edge path between two vertices ([`Path`]), shortest by default,
//!    or a caller-given path, validated.
//! 2. [`compass`](mod@compass): the compass tags ([`Tag`]) parallel-transported along the path into a
//!    printable [`Plan`].
//! 3. Preparation (end-point adjustments): not yet implemented.
//! 4. Execution (the serial collapses and splits): so far only straight collapse chains
//!    from a v5 to a v3 through a regular strip ([`execute_collapse_chain`]); split chains,
//!    turns, the v2/v6 clean-up and reversal are not yet implemented.
//!
//! See `docs/qzip.md` for the reading of the paper behind each rule.
//!
//! ```
//! use zipmesh::{gen, Vert};
//! use zipmesh::qzip::{plan, sketch, SketchOptions, Tag};
//! let map = gen::torus_grid(8, 8).map;
//! let path = sketch(&map, Vert::new(0), Vert::new(3), &SketchOptions::default()).unwrap();
//! assert_eq!(path.len(), 3);
//! let p = plan(&map, &path, Tag::LS).unwrap();
//! assert_eq!(p.steps().len(), 4);
//! ```

pub mod compass;
mod execute;
pub mod sketch;

pub use compass::{plan, Plan, PlanError, PlanStep, Side, Tag, TagParseError, Turn};
pub use execute::{execute_collapse_chain, ZipError, ZipReport};
pub use sketch::{sketch, validate_path, Path, SketchError, SketchOptions};
