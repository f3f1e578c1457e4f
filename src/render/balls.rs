//! Which vertices get a ball, and its colour: the interior singularities, coloured by
//! valence as in the Q-zip paper's figures.

use crate::invariants::{is_irregular, MeshKind};
use crate::map::{Map, Vert};
use alloc::vec::Vec;

/// The colour of a singularity's ball.
///
/// ```
/// use zipmesh::render::BallColour;
/// assert_eq!(BallColour::Blue.rgb(), [40, 100, 215]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BallColour {
    /// Quad meshes: valence 3. Triangle meshes: valence 5.
    Blue,
    /// Quad meshes: valence 5. Triangle meshes: valence 7.
    Orange,
    /// Quad meshes: valence 6 or more (and 1). Triangle meshes: any other irregular valence.
    Red,
    /// Quad meshes: valence 2.
    Green,
}

impl BallColour {
    /// The ball's base colour (sRGB).
    pub fn rgb(self) -> [u8; 3] {
        match self {
            BallColour::Blue => [40, 100, 215],
            BallColour::Orange => [240, 140, 20],
            BallColour::Red => [210, 30, 30],
            BallColour::Green => [30, 160, 60],
        }
    }

    /// A lighter tint of the same hue, for the ball's highlight.
    ///
    /// ```
    /// use zipmesh::render::BallColour;
    /// assert_eq!(BallColour::Blue.highlight(), [147, 177, 235]);
    /// ```
    pub fn highlight(self) -> [u8; 3] {
        self.rgb().map(|c| c + (255 - c) / 2)
    }

    /// Its name, as used in the SVG's gradient ids (`ball-blue`, ...).
    ///
    /// ```
    /// assert_eq!(zipmesh::render::BallColour::Green.name(), "green");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            BallColour::Blue => "blue",
            BallColour::Orange => "orange",
            BallColour::Red => "red",
            BallColour::Green => "green",
        }
    }

    /// Every colour, in a fixed order.
    ///
    /// ```
    /// assert_eq!(zipmesh::render::BallColour::ALL.len(), 4);
    /// ```
    pub const ALL: [BallColour; 4] = [
        BallColour::Blue,
        BallColour::Orange,
        BallColour::Red,
        BallColour::Green,
    ];
}

/// The colour of an interior vertex of valence `valence` in a mesh of kind `kind`, or `None`
/// when that valence is regular there. Quad-dominant (`Mixed`) meshes use the quad colours.
///
/// ```
/// use zipmesh::{invariants::MeshKind, render::{ball_colour, BallColour}};
/// assert_eq!(ball_colour(MeshKind::Quad, 3), Some(BallColour::Blue));
/// assert_eq!(ball_colour(MeshKind::Quad, 4), None);
/// assert_eq!(ball_colour(MeshKind::Triangle, 7), Some(BallColour::Orange));
/// assert_eq!(ball_colour(MeshKind::Triangle, 4), Some(BallColour::Red));
/// ```
pub fn ball_colour(kind: MeshKind, valence: usize) -> Option<BallColour> {
    match (kind, valence) {
        (MeshKind::Triangle, 6) | (MeshKind::Quad | MeshKind::Mixed, 4) => None,
        (MeshKind::Triangle, 5) | (MeshKind::Quad | MeshKind::Mixed, 3) => Some(BallColour::Blue),
        (MeshKind::Triangle, 7) | (MeshKind::Quad | MeshKind::Mixed, 5) => Some(BallColour::Orange),
        (MeshKind::Quad | MeshKind::Mixed, 2) => Some(BallColour::Green),
        _ => Some(BallColour::Red),
    }
}

/// The interior singularities of `map` (live, not on the boundary, irregular for its kind)
/// with their valences, in slot order: the vertices that get a ball.
///
/// ```
/// use zipmesh::{gen, render::singularities};
/// let s = singularities(&gen::cube(2).map);
/// assert_eq!(s.len(), 8);
/// assert!(s.iter().all(|&(_, valence)| valence == 3));
/// assert!(singularities(&gen::grid(3, 3).map).is_empty()); // its corners are on the boundary
/// ```
pub fn singularities(map: &Map) -> Vec<(Vert, usize)> {
    let kind = MeshKind::of(map);
    map.vertices()
        .filter(|&v| !map.is_boundary_vertex(v) && is_irregular(map, kind, v))
        .map(|v| (v, map.valence(v)))
        .collect()
}
