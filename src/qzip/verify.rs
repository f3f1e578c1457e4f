//! The promises of a Q-zip, checked after the fact: for tests, fuzzers and campaigns that
//! want one oracle instead of their own copy.

use alloc::vec::Vec;
use core::fmt;

use super::execute::ZipReport;
use super::sketch::Path;
use crate::invariants::{irregular_valences, Counts, MeshKind};
use crate::ops::quad::QuadRecord;
use crate::Map;
use crate::Violation;

/// A broken promise of a Q-zip, found by [`verify_edit`].
///
/// ```
/// use zipmesh::qzip::Broken;
/// assert!(Broken::NotQuad.to_string().contains("quad"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Broken {
    /// The edited map fails [`Map::check`].
    Invalid(Violation),
    /// A face of the edited map is not a quad, beyond the non-quad faces the map had before
    /// (in number and degree).
    NotQuad,
    /// The Euler characteristic or the number of boundary loops changed.
    Topology,
    /// The multiset of irregular valences changed: a singularity was made or lost.
    Singularities,
    /// The vertex count changed by other than [`ZipReport::vertex_delta`].
    VertexCount,
    /// The reported moved vertices do not carry the pair's valences, or are one vertex.
    Moved {
        /// Their valences in the edited map.
        found: (usize, usize),
        /// The pair's valences before.
        expected: (usize, usize),
    },
    /// The report's footprint or scar does not match the edit: a footprint face that was not
    /// a face before or is still one (but for a slot the scar or a clean-up v6 split reused),
    /// a face the edit deleted that is neither in the footprint nor deleted by a clean-up
    /// valence-2 removal, a footprint edge that was not an edge before, or a scar face or
    /// edge that is not one after.
    Footprint,
    /// Undoing the report does not give back the map before, `==`.
    Undo,
}

impl fmt::Display for Broken {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Invalid(v) => write!(f, "the edited map fails check(): {v:?}"),
            Self::NotQuad => f.write_str("a face of the edited map is not a quad"),
            Self::Topology => f.write_str("the Euler characteristic or the boundary loops changed"),
            Self::Singularities => f.write_str("the irregular valences changed"),
            Self::VertexCount => f.write_str("V changed by other than the report's delta"),
            Self::Moved { found, expected } => write!(
                f,
                "the moved vertices have valences {found:?}, the pair had {expected:?}"
            ),
            Self::Footprint => f.write_str("the footprint or scar does not match the edit"),
            Self::Undo => f.write_str("undo does not restore the map exactly"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for Broken {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Invalid(v) => Some(v),
            _ => None,
        }
    }
}

/// The degrees of the faces that are not quads, sorted.
fn non_quads(map: &Map) -> alloc::vec::Vec<usize> {
    let mut d: alloc::vec::Vec<usize> = map
        .faces()
        .map(|f| map.degree(f))
        .filter(|&k| k != 4)
        .collect();
    d.sort_unstable();
    d
}

/// Checks everything a done Q-zip promises: `after` is a valid quad map (on a quad-dominant
/// `before`, with the same number of triangles and other non-quad faces) with the
/// Euler characteristic, boundary loops and irregular valences of `before`; its vertex count
/// changed by the report's delta; the two moved vertices are distinct and carry the valences
/// of the path's ends; the footprint and scar match the edit ([`Broken::Footprint`]); and
/// undoing the report on a copy of `after` gives `before` exactly.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{sketch, verify_edit, Qzip, SketchOptions, Tag};
/// let before = gen::subdivided_icosahedron(2).map;
/// let path = sketch(&before, Vert::new(0), Vert::new(42), &SketchOptions::default()).unwrap();
/// let mut after = before.clone();
/// let r = Qzip::new().zip_along(&mut after, &path, Tag::RS).unwrap();
/// assert_eq!(verify_edit(&before, &after, &path, &r), Ok(()));
/// // Against the wrong "before", the promises do not hold.
/// assert!(verify_edit(&after, &after, &path, &r).is_err());
/// ```
pub fn verify_edit(
    before: &Map,
    after: &Map,
    path: &Path,
    report: &ZipReport,
) -> Result<(), Broken> {
    after.check().map_err(Broken::Invalid)?;
    // A quad-dominant map keeps its other faces: Q-zip never edits a triangle.
    if non_quads(after) != non_quads(before) {
        return Err(Broken::NotQuad);
    }
    let (c, c0) = (Counts::of(after), Counts::of(before));
    if (c.euler_characteristic, c.boundary_loops) != (c0.euler_characteristic, c0.boundary_loops) {
        return Err(Broken::Topology);
    }
    if irregular_valences(after, MeshKind::Quad) != irregular_valences(before, MeshKind::Quad) {
        return Err(Broken::Singularities);
    }
    if after.num_vertices() as isize != before.num_vertices() as isize + report.vertex_delta() {
        return Err(Broken::VertexCount);
    }
    let (from, to) = (report.moved_from(), report.moved_to());
    let found = (after.valence(from), after.valence(to));
    let expected = (before.valence(path.start()), before.valence(path.end()));
    if found != expected || from == to {
        return Err(Broken::Moved { found, expected });
    }
    if !footprint_matches(before, after, report) {
        return Err(Broken::Footprint);
    }
    let mut undone = after.clone();
    if report.undo(&mut undone).is_err() || &undone != before {
        return Err(Broken::Undo);
    }
    Ok(())
}

/// The promise of [`Broken::Footprint`]: footprint faces were faces and are gone (or their
/// slots reused by the scar or a clean-up v6 split), every deleted face is in the footprint
/// or deleted by a clean-up v2 removal, footprint edges were edges, and scar faces and edges
/// are there after. The clean-up's faces are read off its records.
fn footprint_matches(before: &Map, after: &Map, r: &ZipReport) -> bool {
    let (scar, footprint) = (r.scar_faces(), r.footprint_faces());
    let (mut deleted, mut made) = (Vec::new(), Vec::new());
    for record in r.records().get(r.splits() + r.collapses()..).unwrap_or(&[]) {
        match record {
            QuadRecord::RemoveValence2(x) => deleted.push(x.deleted_face()),
            QuadRecord::Split(x) => made.push(x.face()),
            _ => {}
        }
    }
    let listed = footprint.iter().all(|&f| {
        before.is_live_face(f) && (!after.is_live_face(f) || scar.contains(&f) || made.contains(&f))
    });
    // Faces die only by the chain's collapses (listed) and the clean-up's v2 removals.
    let complete = before
        .faces()
        .all(|f| after.is_live_face(f) || footprint.contains(&f) || deleted.contains(&f));
    listed
        && complete
        && r.footprint_edges().iter().all(|&e| before.is_live_edge(e))
        && scar.iter().all(|&f| after.is_live_face(f))
        && r.scar_edges().iter().all(|&e| after.is_live_edge(e))
}
