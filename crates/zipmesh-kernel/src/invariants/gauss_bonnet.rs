use super::{regular_valence, Counts, Histograms, MeshKind};
use crate::map::Map;

/// The two sides of the discrete Gauss-Bonnet identity in the frame of a mesh kind.
///
/// For regular valence `k` inside and `k_b` on the boundary (see
/// [`regular_valence`]), and regular face degree `r` (4 for quads, 3 for triangles):
///
/// ```text
/// quad frame:      sum_inner (4 - val) + sum_boundary (3 - val) + sum_faces (4 - deg)     = 4 chi
/// triangle frame:  sum_inner (6 - val) + sum_boundary (4 - val) + 2 sum_faces (3 - deg)   = 6 chi
/// ```
///
/// The face term vanishes on pure quad (triangle) meshes, leaving the papers' identities
/// `sum (4 - val) = 4 chi` and `sum (6 - val) = 6 chi` for closed meshes. Derivation: the sum
/// of valences is `2E`, the sum of face degrees is `2E - E_b`, and a manifold boundary has as
/// many vertices as edges (`V_b = E_b`); substituting gives `4V - 4E + 4F` (respectively
/// `6V - 6E + 6F`). Written out in `docs/design.md`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GaussBonnet {
    /// Sum of vertex curvatures (`regular - valence`, boundary rule on the boundary).
    pub vertex_sum: i64,
    /// The face term (0 on a pure mesh of the frame's kind).
    pub face_sum: i64,
    /// `4 chi` in the quad frame, `6 chi` in the triangle frame.
    pub rhs: i64,
}

impl GaussBonnet {
    /// Whether the identity holds.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, invariants::{gauss_bonnet, MeshKind}};
    /// assert!(gauss_bonnet(&gen::cube(3).map, MeshKind::Quad).holds());
    /// ```
    pub fn holds(&self) -> bool {
        self.vertex_sum + self.face_sum == self.rhs
    }
}

/// Evaluates both sides of discrete Gauss-Bonnet for `map` in the frame of `kind`
/// (`Mixed` uses the quad frame). Holds on every valid map; a failure means a broken map.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::{gauss_bonnet, MeshKind}};
/// let gb = gauss_bonnet(&gen::grid(3, 2).map, MeshKind::Quad);
/// assert_eq!((gb.vertex_sum, gb.face_sum, gb.rhs), (4, 0, 4));
/// ```
pub fn gauss_bonnet(map: &Map, kind: MeshKind) -> GaussBonnet {
    let h = Histograms::of(map);
    let (regular_face, face_weight, scale) = match kind {
        MeshKind::Triangle => (3i64, 2i64, 6i64),
        _ => (4, 1, 4),
    };
    let curv = |hist: &alloc::collections::BTreeMap<usize, usize>, reg: usize| -> i64 {
        hist.iter()
            .map(|(&val, &n)| (reg as i64 - val as i64) * n as i64)
            .sum()
    };
    let vertex_sum = curv(&h.interior_valences, regular_valence(kind, false))
        + curv(&h.boundary_valences, regular_valence(kind, true));
    let face_sum = face_weight
        * h.face_degrees
            .iter()
            .map(|(&deg, &n)| (regular_face - deg as i64) * n as i64)
            .sum::<i64>();
    GaussBonnet {
        vertex_sum,
        face_sum,
        rhs: scale * Counts::of(map).euler_characteristic,
    }
}
