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
    /// Runs `f` on the map and its values.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, mesh::EditTarget};
    /// let mut mesh = gen::grid(1, 1);
    /// let n = mesh.with_parts(|map, positions| map.vertex_slots() + positions.len());
    /// assert_eq!(n, 8);
    /// ```
    fn with_parts<R>(&mut self, f: impl FnOnce(&mut Map, &mut Self::Values) -> R) -> R;
}

/// A bare map: no values.
impl EditTarget for Map {
    type Values = ();
    fn with_parts<R>(&mut self, f: impl FnOnce(&mut Map, &mut ()) -> R) -> R {
        f(self, &mut ())
    }
}

/// A mesh: its positions.
impl EditTarget for Mesh {
    type Values = Positions;
    fn with_parts<R>(&mut self, f: impl FnOnce(&mut Map, &mut Positions) -> R) -> R {
        f(&mut self.map, &mut self.positions)
    }
}

/// A map and a layer of any values (marks, colours, positions with marks as a pair).
impl<A: VertexAttributes> EditTarget for (&mut Map, &mut A) {
    type Values = A;
    fn with_parts<R>(&mut self, f: impl FnOnce(&mut Map, &mut A) -> R) -> R {
        f(self.0, self.1)
    }
}

/// A target borrowed again (`&mut mesh` where `mesh: &mut Mesh`).
impl<T: EditTarget> EditTarget for &mut T {
    type Values = T::Values;
    fn with_parts<R>(&mut self, f: impl FnOnce(&mut Map, &mut T::Values) -> R) -> R {
        (**self).with_parts(f)
    }
}
