//! What every edit shares: why it refuses ([`Refusal`]) and how its record restores the map
//! ([`Undo`]). Below both the operators ([`crate::ops`]) and the per-vertex values
//! ([`crate::mesh`]), which use them.

use crate::map::Map;
use core::fmt;

/// Why an operator refuses, or why an undo does not fit. Each variant's documentation says
/// which rule it enforces. One taxonomy for both families, in five groups:
///
/// * **Argument errors** (the call itself is wrong): [`Refusal::DeadHandle`],
///   [`Refusal::BadArguments`].
/// * **Rules shared by both families** (the result would not be a mesh the operators
///   accept): [`Refusal::Boundary`], [`Refusal::WrongDegree`], [`Refusal::FaceTooSmall`],
///   [`Refusal::ValenceTooLow`], [`Refusal::MultiEdge`], [`Refusal::Loop`].
/// * **Quad only** ([`crate::ops::quad`]): [`Refusal::CornersCoincide`], [`Refusal::BoundaryPinch`],
///   [`Refusal::WrongValence`], [`Refusal::SameFace`].
/// * **Triangle only** ([`crate::ops::tri`]): [`Refusal::LinkCondition`],
///   [`Refusal::DegenerateTriangle`].
/// * **Record errors** (from `undo`, never from an operator): [`Refusal::StaleRecord`]. Every
///   undo runs its record's checks in order (one mechanism for every record, see
///   `ops/guard.rs`); the first that fails makes the undo refuse with the map unchanged.
///   The checks are structural (the elements the record names are as its operation left
///   them, the slots it gives back are where it left them), so a record that passes them
///   restores a valid map even when it comes from another map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Refusal {
    /// A handle argument is not a live element of this map.
    DeadHandle,
    /// The arguments do not fit together (for example a split's two edges do not leave the
    /// vertex, or are the same edge).
    BadArguments,
    /// The operator needs an interior element and this one is on the boundary.
    Boundary,
    /// A face involved does not have the degree the operator works on.
    WrongDegree,
    /// The result would have a face of degree below 3.
    FaceTooSmall,
    /// The result would have a vertex of valence below the operator's minimum.
    ValenceTooLow,
    /// The result would have two edges between the same two vertices.
    MultiEdge,
    /// The result would have an edge from a vertex to itself.
    Loop,
    /// Edge collapse: the link condition fails (the two ends share a neighbour other than the
    /// two apexes), so the collapse would pinch the surface.
    LinkCondition,
    /// The record does not match the map (it was changed since, or the record is foreign).
    StaleRecord,
    // Quad-specific reasons: add below this line (quad operators only).
    /// Two corners the operator needs distinct are the same vertex: the corners a quad
    /// collapse would merge, the four corners of a valence-2 removal's merged quad or of a
    /// doublet insertion's quad, or the six corners of an edge rotation's hexagon.
    CornersCoincide,
    /// Quad collapse: both merged corners are on the boundary, so the merged vertex would
    /// have two boundary darts (the surface would be pinched there).
    BoundaryPinch,
    /// The vertex does not have the valence the operator works on (valence-2 removal needs
    /// exactly 2, the high-valence split at least 6).
    WrongValence,
    /// The two faces the operator would merge or re-divide (valence-2 removal, edge
    /// rotation) are one and the same face.
    SameFace,

    // Triangle-specific reasons: add below this line (triangle operators only).
    /// Triangle operators: a triangle involved has two equal corners (so one of its edges is
    /// a loop), or an edge argument is a loop. The triangle operators work on triangles with
    /// three distinct corners, where their valence changes are the ones documented.
    DegenerateTriangle,
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            Refusal::DeadHandle => "a handle is not live in this map",
            Refusal::BadArguments => "the arguments do not fit together",
            Refusal::Boundary => "the element is on the boundary",
            Refusal::WrongDegree => "a face has the wrong degree for this operator",
            Refusal::FaceTooSmall => "a face of degree below 3 would result",
            Refusal::ValenceTooLow => "a vertex of too low valence would result",
            Refusal::MultiEdge => "a multi-edge would result",
            Refusal::Loop => "a loop edge would result",
            Refusal::LinkCondition => "the link condition fails",
            Refusal::StaleRecord => "the record does not match the map",
            Refusal::CornersCoincide => "two corners that must differ are the same vertex",
            Refusal::BoundaryPinch => "the merge would pinch the boundary",
            Refusal::WrongValence => "a vertex has the wrong valence for this operator",
            Refusal::SameFace => "the two faces involved are the same face",
            Refusal::DegenerateTriangle => "a triangle with a repeated corner is involved",
        };
        f.write_str(s)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for Refusal {}

/// A record that restores the map it was made on: implemented by every operator's record,
/// quad and triangle alike, so that one undo stack can hold them all (`Vec<Box<dyn Undo>>`).
///
/// ```
/// use zipmesh_kernel::ops::{quad, tri, Undo};
/// use zipmesh_kernel::{gen, Dart};
/// let mut map = gen::torus_grid(5, 5).map;
/// let before = map.clone();
/// let mut stack: Vec<Box<dyn Undo>> = Vec::new();
/// stack.push(Box::new(quad::collapse_quad(&mut map, Dart::new(0)).unwrap()));
/// stack.push(Box::new(quad::insert_doublet(&mut map, Dart::new(40)).unwrap()));
/// while let Some(r) = stack.pop() {
///     r.undo(&mut map).unwrap();
/// }
/// assert_eq!(map, before);
/// let mut tet = zipmesh_kernel::Map::from_polygons(4, &[[0u32, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]).unwrap();
/// let r = tri::split_edge(&mut tet, Dart::new(0)).unwrap();
/// Undo::undo(&r, &mut tet).unwrap();
/// assert_eq!(tet.num_vertices(), 4);
/// ```
pub trait Undo {
    /// Restores the map as it was before the operation (see the record's own `undo`).
    fn undo(&self, map: &mut Map) -> Result<(), Refusal>;
}
