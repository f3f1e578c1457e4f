//! The preprocessing Sec. 2.6 assumes: no interior vertex of valence 2 or of 6 and more.

use alloc::vec::Vec;

use super::placement::place_created;
use crate::mesh::{Edited, Journal, VertexAttributes};
use crate::ops::quad::{remove_valence2, split_high_valence, QuadRecord};
use crate::ops::Refusal;
use crate::{Dart, Map, Mesh, Vert};

/// [`preprocess`] on a mesh: the vertices its splits create are placed at the mean of their
/// neighbours, and the undo restores the positions too.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// use zipmesh::qzip::mesh_preprocess;
/// let mut mesh = gen::torus_grid(8, 8);
/// quad::collapse_quad(&mut mesh.map, Dart::new(0)).unwrap();
/// let before = mesh.clone();
/// let p = mesh_preprocess(&mut mesh).unwrap();
/// assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
/// p.undo(&mut mesh).unwrap();
/// assert_eq!(mesh, before);
/// ```
pub fn mesh_preprocess(mesh: &mut Mesh) -> Result<Edited<Preprocessed>, Refusal> {
    preprocess_with(&mut mesh.map, &mut mesh.positions)
}

/// [`preprocess`] keeping any per-vertex data in step, as [`super::Qzip::zip_along_with`]
/// does: created vertices take the mean of their neighbours' values.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// use zipmesh::qzip::preprocess_with;
/// let mut map = gen::torus_grid(8, 8).map;
/// quad::collapse_quad(&mut map, Dart::new(0)).unwrap();
/// let mut marks = vec![true; map.vertex_slots()];
/// let p = preprocess_with(&mut map, &mut marks).unwrap();
/// assert_eq!(marks.len(), map.vertex_slots());
/// assert!(marks.iter().all(|&m| m)); // a mark spreads to the vertices made from it
/// p.undo_with(&mut map, &mut marks).unwrap();
/// ```
pub fn preprocess_with<A: VertexAttributes>(
    map: &mut Map,
    attrs: &mut A,
) -> Result<Edited<Preprocessed, A>, Refusal> {
    let mut journal = Journal::start(attrs);
    let p = preprocess(map)?;
    place_created(map, attrs, &mut journal, p.records());
    Ok(Edited::new(p, journal))
}

/// What [`preprocess`] did, with the records for an exact undo.
///
/// See [`preprocess`] for an example.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Preprocessed {
    records: Vec<QuadRecord>,
}

impl Preprocessed {
    /// The operations applied, in order (valence-6+ splits and valence-2 removals).
    ///
    /// See [`preprocess`] for an example.
    pub fn records(&self) -> &[QuadRecord] {
        &self.records
    }

    /// Undoes the preprocessing (the map comes back `==`).
    ///
    /// See [`preprocess`] for an example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        super::execute::undo_records(&self.records, map)
    }
}

/// The preprocessing Sec. 2.6 assumes: every interior vertex of valence 6 or more is split
/// along a pair of opposite edges (a 6 becomes two regular vertices and two v5s at the far
/// ends; a 7 a 4 and a 5), and every interior valence-2 vertex is removed (its two quads
/// merge), until none is left. Pairs whose far ends have valence 4 or less are preferred so
/// no new valence-6 vertex appears. All or nothing: on a refusal everything is undone.
///
/// ```
/// use zipmesh::{gen, ops::quad, Dart};
/// use zipmesh::qzip::preprocess;
/// let mut map = gen::torus_grid(8, 8).map;
/// quad::collapse_quad(&mut map, Dart::new(0)).unwrap(); // makes a valence 6
/// let before = map.clone();
/// let p = preprocess(&mut map).unwrap();
/// assert!(map.vertices().all(|v| (3..=5).contains(&map.valence(v))));
/// assert_eq!(p.records().len(), 1);
/// p.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn preprocess(map: &mut Map) -> Result<Preprocessed, Refusal> {
    let mut out = Preprocessed::default();
    // Each step lowers the sum of (valence - 5) over high vertices or removes a vertex, so
    // this bound is never reached on a valid map; it keeps a corrupt one from looping.
    let bound = 4 * map.dart_slots() + 16;
    for _ in 0..bound {
        let next = map
            .vertices()
            .find(|&v| !map.is_boundary_vertex(v) && (map.valence(v) >= 6 || map.valence(v) == 2));
        let Some(v) = next else {
            return Ok(out);
        };
        let step = if map.valence(v) == 2 {
            remove_valence2(map, map.vertex_dart(v)).map(QuadRecord::from)
        } else {
            let k = map.valence(v);
            let far = |d: Dart| {
                let mut o = d;
                for _ in 0..k / 2 {
                    o = map.rotate_cw(o);
                }
                [map.dest(d), map.dest(o)]
            };
            let low = |x: Vert| map.valence(x) <= 4;
            let first = map
                .vertex_darts(v)
                .find(|&d| far(d).iter().all(|&x| low(x)))
                .unwrap_or_else(|| map.vertex_dart(v));
            split_high_valence(map, v, first).map(QuadRecord::from)
        };
        match step {
            Ok(r) => out.records.push(r),
            Err(e) => {
                let _ = out.undo(map);
                return Err(e);
            }
        }
    }
    let _ = out.undo(map);
    Err(Refusal::BadArguments)
}
