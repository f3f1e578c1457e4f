//! Atomic editing operators, each paired with a pure precondition check and an exact inverse.
//!
//! Contract of every operator `x` (see `docs/operators.md`):
//! * `can_x(&map, ...) -> Result<(), Refusal>` says, without changing anything, whether `x`
//!   applies and if not why (a typed [`Refusal`]).
//! * `x(&mut map, ...) -> Result<XRecord, Refusal>` applies it, or refuses with the same reason
//!   as `can_x` and leaves the map exactly as it was (every array, not only the shape).
//! * The record names the handles created and holds what the exact inverse needs;
//!   `record.undo(&mut map)` restores a map equal (`==`) to the one before, as long as the
//!   map has not been changed in between (other records undone in reverse order are fine).
//! * Handles of elements the operator did not touch stay valid.
//!
//! Modules: [`quad`] (Q-zip paper, Sec. 2.2) and [`tri`] (triangle paper, Sec. 6.1).

pub use effect::{Effect, EffectMismatch, VertexChanges};

mod effect;
pub(crate) mod guard;
pub mod quad;
pub(crate) mod slots;
pub mod tri;

pub use crate::edit::{Refusal, Undo};

/// Checks that the edge of `d` is live, interior and between two different faces: the rule
/// every edge-pair operator (rotation, the quad-dominant collisions) starts with. Refuses
/// with [`Refusal::DeadHandle`], [`Refusal::Boundary`] or [`Refusal::SameFace`].
pub(crate) fn check_two_faces(map: &crate::map::Map, d: crate::map::Dart) -> Result<(), Refusal> {
    if !map.is_live_dart(d) {
        return Err(Refusal::DeadHandle);
    }
    let (Some(f), Some(g)) = (map.face(d), map.face(d.twin())) else {
        return Err(Refusal::Boundary);
    };
    if f == g {
        return Err(Refusal::SameFace);
    }
    Ok(())
}
