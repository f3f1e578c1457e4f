//! Q-zip (Sec. 2 and 3.1 of the Q-zip paper): moving a pair of singularities of a quad mesh
//! along a surgery path.
//!
//! The edit runs in four stages, each a public step whose result can be inspected:
//!
//! 1. [`sketch`](mod@sketch): a simple edge path between two vertices ([`Path`]), shortest by
//!    default, or a caller-given path, validated.
//! 2. [`compass`](mod@compass): the compass tags ([`Tag`]) parallel-transported along the path
//!    into a printable [`Plan`].
//! 3. [`prepare`](mod@prepare): the end-point adjustments of Sec. 2.6 and the cancellation of
//!    folded edges, giving a printable [`Surgery`].
//! 4. [`execute`](mod@execute): the serial collapses and splits, the v2/v6 clean-up, and a
//!    [`ZipReport`] (moved singularities, footprint, scar, exact undo).
//!
//! [`Qzip`] is the entry point that runs the four stages at once (on a [`crate::Map`], or on a
//! [`crate::Mesh`] keeping positions); [`moves`] tries the four initial operations.
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
pub mod execute;
mod homotopy;
mod placement;
pub mod prepare;
mod preprocess;
mod quad;
mod quad_dominant;
mod reverse;
pub mod sketch;
mod verify;
mod zip;

pub use compass::{plan, Plan, PlanError, PlanStep, Side, Tag, TagParseError, Turn};
pub use execute::{execute, ZipError, ZipReport};
pub use homotopy::{one_quad_sweeps, start_turn, wraps};
pub use prepare::{prepare, EndRule, PrepareError, StartRule, Surgery, SurgeryStep};
pub use preprocess::{preprocess, Preprocessed};
pub use quad_dominant::avoid_triangles;
pub use reverse::{derive_reverse, find_reverse, ReverseRun, ReverseWay};
pub use sketch::{
    max_edge_length, sketch, validate_path, Guide, Path, SketchError, SketchOptions,
    SketchWorkspace,
};
pub use verify::{verify_edit, Broken};
pub use zip::{moves, Move, Qzip, QzipError};
