//! Typed 32-bit handles for darts, edges, vertices and faces.

use core::fmt;

/// The value stored in the arrays for "no element" (boundary face, dead slot).
pub(crate) const NONE: u32 = u32::MAX;

macro_rules! handle {
    ($(#[$doc:meta])* $name:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name(pub(crate) u32);

        impl $name {
            /// The handle with slot number `index`.
            ///
            /// Handles are plain slot numbers: whether the slot is alive in a given map is
            /// checked by the map's `is_live_*` methods, never assumed.
            ///
            /// ```
            #[doc = concat!("let h = zipmesh_kernel::", stringify!($name), "::new(7);")]
            /// assert_eq!(h.index(), 7);
            /// ```
            #[inline]
            pub const fn new(index: u32) -> Self {
                Self(index)
            }

            /// The slot number of this handle.
            ///
            /// ```
            #[doc = concat!("assert_eq!(zipmesh_kernel::", stringify!($name), "::new(3).index(), 3);")]
            /// ```
            #[inline]
            pub const fn index(self) -> usize {
                self.0 as usize
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($prefix, "{}"), self.0)
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($prefix, "{}"), self.0)
            }
        }
    };
}

handle!(
    /// A dart (half-edge). The two darts of edge `e` are `2e` and `2e + 1`, so the twin of a
    /// dart is its index with the lowest bit flipped and needs no storage.
    Dart,
    "d"
);
handle!(
    /// An edge: the pair of darts `2e` and `2e + 1` (see [`Edge::dart`]). Per-edge data
    /// (weights, marks) is indexed by [`Edge::index`], from 0 to [`crate::Map::edge_slots`].
    Edge,
    "e"
);
handle!(
    /// A vertex.
    Vert,
    "v"
);
handle!(
    /// A face (a polygon; boundary loops are not faces).
    Face,
    "f"
);

impl Dart {
    /// The other dart of the same edge.
    ///
    /// ```
    /// use zipmesh_kernel::Dart;
    /// assert_eq!(Dart::new(4).twin(), Dart::new(5));
    /// assert_eq!(Dart::new(5).twin(), Dart::new(4));
    /// ```
    #[inline]
    pub const fn twin(self) -> Dart {
        Dart(self.0 ^ 1)
    }

    /// The edge of this dart (its index halved).
    ///
    /// ```
    /// use zipmesh_kernel::{Dart, Edge};
    /// assert_eq!(Dart::new(5).edge(), Edge::new(2));
    /// assert_eq!(Dart::new(4).edge(), Dart::new(5).edge());
    /// ```
    #[inline]
    pub const fn edge(self) -> Edge {
        Edge(self.0 >> 1)
    }
}

impl Edge {
    /// The edge's dart on `side` 0 (`2e`) or 1 (`2e + 1`); only the lowest bit of `side`
    /// counts.
    ///
    /// ```
    /// use zipmesh_kernel::{Dart, Edge};
    /// let e = Edge::new(3);
    /// assert_eq!((e.dart(0), e.dart(1)), (Dart::new(6), Dart::new(7)));
    /// assert_eq!(e.dart(1).edge(), e);
    /// ```
    #[inline]
    pub const fn dart(self, side: u32) -> Dart {
        Dart((self.0 << 1) | (side & 1))
    }
}
