//! What an edit changes: a map and the per-vertex values kept in step with it.

use super::{Mesh, Positions, VertexAttributes};
use crate::map::Map;

/// A map with the per-vertex values an edit keeps in step: every edit that keeps values
/// (the operators through [`crate::ops::quad::QuadOp::apply`], the quad-dominant moves,
/// and the library's Q-zip and triangle edits) takes one, so each edit is one function for
/// a bare [`Map`] (values `()`), a [`Mesh`] (its positions) or a map with any layer
/// `(&mut map, &mut values)`. The edit returns an [`super::Edited`], whose
/// [`undo`](super::Edited::undo) takes the same target back.
///
/// ```
/// use zipmesh_kernel::{gen, mesh::EditTarget, ops::quad::QuadOp, Dart};
/// let mut mesh = gen::torus_grid(4, 4);
/// let mut marks = vec![false; mesh.map.vertex_slots()];
/// let before = (mesh.map.clone(), marks.clone());
/// // The map with a layer of marks: the new vertex gets a mark, undo cuts it off.
/// let mut target = (&mut mesh.map, &mut marks);
/// let e = QuadOp::InsertDoublet(Dart::new(0)).apply(&mut target).unwrap();
/// e.undo(&mut target).unwrap();
/// assert_eq!((mesh.map, marks), before);
/// ```
pub trait EditTarget {
    /// The per-vertex values kept in step (`()` for none).
    type Values: VertexAttributes;
    /// The map and its values, borrowed together.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, mesh::EditTarget};
    /// let mut mesh = gen::grid(1, 1);
    /// let (map, positions) = mesh.parts();
    /// assert_eq!(map.vertex_slots() + positions.len(), 8);
    /// ```
    fn parts(&mut self) -> (&mut Map, &mut Self::Values);
}

/// A bare map: no values.
impl EditTarget for Map {
    type Values = ();
    fn parts(&mut self) -> (&mut Map, &mut ()) {
        // A unit box takes no memory (nothing is allocated or leaked).
        (self, alloc::boxed::Box::leak(alloc::boxed::Box::new(())))
    }
}

/// A mesh: its positions.
impl EditTarget for Mesh {
    type Values = Positions;
    fn parts(&mut self) -> (&mut Map, &mut Positions) {
        (&mut self.map, &mut self.positions)
    }
}

/// A map and a layer of any values (marks, colours, positions with marks as a pair).
impl<A: VertexAttributes> EditTarget for (&mut Map, &mut A) {
    type Values = A;
    fn parts(&mut self) -> (&mut Map, &mut A) {
        (&mut *self.0, &mut *self.1)
    }
}

/// A target borrowed again (`&mut mesh` where `mesh: &mut Mesh`).
impl<T: EditTarget> EditTarget for &mut T {
    type Values = T::Values;
    fn parts(&mut self) -> (&mut Map, &mut T::Values) {
        (**self).parts()
    }
}
