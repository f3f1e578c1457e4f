//! Stage 4 of Q-zip, execution: the serial operations, the v2/v6 clean-up and the report.
//!
//! [`execute`] walks a prepared [`Surgery`] from its first vertex. At each vertex `P` with
//! next vertex `N` (see `docs/qzip.md`):
//!
//! * **no-op**: nothing; `P` becomes the guide of the next operation.
//! * **LC / RC**: the quad on the right (LC) or left (RC) of the edge `P -> N` is collapsed,
//!   merging `N` (which keeps its handle) with that quad's corner next to `P`; the quad's
//!   corner next to `N` (the transient v3) becomes the guide.
//! * **LS / RS**: `P` is split along its edges to the guide and to `N`; the copy on the left
//!   of the path (LS) or on its right (RS) continues the path and becomes the guide.
//!
//! After the whole chain, vertices the chain made valence 2 are removed (two v3s come back)
//! and vertices it made valence 6 are split into two regular ones (two v5s appear): the
//! post-processing of Sec. 2.7, done once at the end because a v5 start with a collapse makes
//! a transient v6 that the next operation resolves.
//!
//! ```
//! use zipmesh::{gen, Vert};
//! use zipmesh::qzip::{Qzip, Tag};
//! let mut map = gen::subdivided_icosahedron(2).map;
//! let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
//! let before = map.clone();
//! let r = Qzip::new().zip(&mut map, v3, v5, Tag::LS).unwrap();
//! assert_eq!(map.check(), Ok(()));
//! assert_eq!((map.valence(r.moved_from()), map.valence(r.moved_to())), (3, 5));
//! r.undo(&mut map).unwrap();
//! assert_eq!(map, before);
//! ```

use alloc::vec::Vec;
use core::fmt;

use super::compass::Tag;
use super::prepare::{EndRule, StartRule, Surgery};
use super::quad::bounds_one_quad;
use crate::invariants::canonical::least_start;
use crate::invariants::{is_regular_interior, regular_valence, MeshKind};
use crate::ops::quad::{
    collapse_quad, remove_valence2, split_high_valence, split_vertex, QuadRecord,
};
use crate::ops::Refusal;
use crate::{Dart, Edge, Face, Map, Vert};

/// What an executed Q-zip did: the moved singularities, counts, footprint and scar, and the
/// records for an exact undo.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{Qzip, Tag};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let v0 = map.num_vertices();
/// let r = Qzip::new().zip(&mut map, v5, v3, Tag::LC).unwrap();
/// assert_eq!(map.num_vertices() as isize, v0 as isize + r.vertex_delta());
/// assert_eq!(r.footprint_faces().len(), r.collapses());
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ZipReport {
    surgery: Surgery,
    records: Vec<QuadRecord>,
    splits: usize,
    collapses: usize,
    v2_removals: usize,
    v6_splits: usize,
    moved_from: Vert,
    moved_to: Vert,
    footprint_faces: Vec<Face>,
    scar_faces: Vec<Face>,
    scar_edges: Vec<Edge>,
}

impl ZipReport {
    /// The surgery that was executed (the adjusted path and its operations).
    ///
    /// See [`execute`] for an example.
    pub fn surgery(&self) -> &Surgery {
        &self.surgery
    }

    /// The number of vertex splits of the chain (clean-up splits not included).
    ///
    /// See [`ZipReport`] for an example.
    pub fn splits(&self) -> usize {
        self.splits
    }

    /// The number of quad collapses of the chain.
    ///
    /// See [`ZipReport`] for an example.
    pub fn collapses(&self) -> usize {
        self.collapses
    }

    /// The change of the vertex count: splits minus collapses, plus the clean-up's valence-6
    /// splits minus its valence-2 removals.
    ///
    /// See [`ZipReport`] for an example.
    pub fn vertex_delta(&self) -> isize {
        (self.splits + self.v6_splits) as isize - (self.collapses + self.v2_removals) as isize
    }

    /// The number of valence-2 removals and of valence-6 splits done by the clean-up.
    ///
    /// See [`execute`] for an example.
    pub fn cleanup_counts(&self) -> (usize, usize) {
        (self.v2_removals, self.v6_splits)
    }

    /// Where the initial singularity went (a vertex of the edited map).
    ///
    /// See the module example.
    pub fn moved_from(&self) -> Vert {
        self.moved_from
    }

    /// Where the terminal singularity went (a vertex of the edited map).
    ///
    /// See the module example.
    pub fn moved_to(&self) -> Vert {
        self.moved_to
    }

    /// The footprint's faces: quads of the original map deleted by collapses (handles of the
    /// original map; a handle may be reused by the scar).
    ///
    /// See [`ZipReport`] for an example.
    pub fn footprint_faces(&self) -> &[Face] {
        &self.footprint_faces
    }

    /// The footprint's edges: edges of the original map split in two, in the order split.
    /// Read off the records on each call (each split's two split edges, unless an earlier
    /// split made them), so the edit itself tracks nothing for it.
    ///
    /// See [`execute`] for an example.
    pub fn footprint_edges(&self) -> Vec<Edge> {
        let chain = self
            .records
            .get(..self.splits + self.collapses)
            .unwrap_or(&[]);
        split_original_edges(chain)
    }

    /// The scar's faces: quads made by the chain's splits that are still there.
    ///
    /// See [`execute`] for an example.
    pub fn scar_faces(&self) -> &[Face] {
        &self.scar_faces
    }

    /// The scar's edges: edges into which collapses merged two edges, still there.
    ///
    /// See [`execute`] for an example.
    pub fn scar_edges(&self) -> &[Edge] {
        &self.scar_edges
    }

    /// The operator records in the order applied (chain, then clean-up).
    ///
    /// See [`execute`] for an example.
    pub fn records(&self) -> &[QuadRecord] {
        &self.records
    }

    /// Undoes the whole edit (records in reverse order): with the map as the edit left it,
    /// the result is `==` the map before.
    ///
    /// See the module example.
    pub fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        undo_records(&self.records, map)
    }
}

/// Why [`execute`] refused; the map is unchanged in every case.
///
/// ```
/// use zipmesh::qzip::ZipError;
/// use zipmesh::Vert;
/// let e = ZipError::StalePlan { index: 3 };
/// assert!(e.to_string().contains("3"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ZipError {
    /// The surgery does not fit the map: at position `index` a vertex is dead or the edge to
    /// the next vertex (or to the guide) is missing or not unique.
    StalePlan {
        /// Position in the surgery.
        index: usize,
    },
    /// A collapse would delete a vertex the surgery still has to visit.
    Lost {
        /// Position of the collapse in the surgery.
        index: usize,
        /// The vertex that would be deleted.
        vertex: Vert,
    },
    /// An operation was refused by the operator (not realizable here).
    Refused {
        /// Position in the surgery.
        index: usize,
        /// The vertex.
        vertex: Vert,
        /// The operation.
        tag: Tag,
        /// The operator's reason.
        refusal: Refusal,
    },
    /// The edit would change the irregular vertices other than by moving the pair (our
    /// reading of the rules does not cover this configuration): a guard, checked on every
    /// vertex the edit touched, so that grid preservation holds for every edit that is done.
    NotGridPreserving {
        /// Irregular vertices among the touched ones before.
        before: usize,
        /// And after.
        after: usize,
    },
    /// The irregular vertices were kept, but the two moved singularities cannot be told
    /// apart from others the edit touched (crowded configurations): refused rather than
    /// reported wrongly.
    Untracked,
    /// The edit would change a triangle of a quad-dominant map: a corner's valence, or which
    /// vertices are corners. Q-zip treats a triangle's edges as boundary edges (Sec. 3.2), so
    /// only the triangle moves change a triangle; refused, so that every triangle is kept by
    /// every edit that is done.
    TriangleChanged {
        /// The first touched vertex whose triangle corners changed.
        vertex: Vert,
    },
    /// A clean-up operation (valence-2 removal or valence-6 split) was refused.
    Cleanup {
        /// The vertex.
        vertex: Vert,
        /// The operator's reason.
        refusal: Refusal,
    },
}

impl fmt::Display for ZipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::StalePlan { index } => write!(
                f,
                "the surgery does not fit this map at position {index} (a vertex is gone, or an \
                 edge is missing or not unique)"
            ),
            Self::Lost { index, vertex } => write!(
                f,
                "the collapse at position {index} would delete vertex {}, which the surgery \
                 still has to visit",
                vertex.index()
            ),
            Self::Refused {
                index,
                vertex,
                tag,
                refusal,
            } => write!(
                f,
                "the {tag} operation at vertex {} (position {index}) is not realizable: {refusal}",
                vertex.index()
            ),
            Self::NotGridPreserving { before, after } => write!(
                f,
                "the edit would not preserve the grid here ({before} irregular vertices in the \
                 touched region before, a different set of {after} after); refused"
            ),
            Self::Untracked => f.write_str(
                "the edit kept the irregular vertices but the moved pair cannot be told apart \
                 from the other singularities it touched; refused",
            ),
            Self::TriangleChanged { vertex } => write!(
                f,
                "the edit would change a triangle at vertex {} (a corner's valence); a Q-zip \
                 treats triangles as boundary and keeps them; refused",
                vertex.index()
            ),
            Self::Cleanup { vertex, refusal } => write!(
                f,
                "the clean-up at vertex {} was refused: {refusal}",
                vertex.index()
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ZipError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Refused { refusal, .. } | Self::Cleanup { refusal, .. } => Some(refusal),
            _ => None,
        }
    }
}

/// The dart of the quad collapsed at edge `e: P -> N` that leaves `N` (collapsing at it
/// merges `N` with the corner next to `P`), and that quad's corner next to `N`.
fn strip_quad(map: &Map, e: Dart, tag: Tag) -> (Dart, Vert) {
    if tag == Tag::LC {
        let d = e.twin();
        (d, map.origin(map.prev(d)))
    } else {
        let d = map.next(e);
        (d, map.dest(d))
    }
}

/// A vertex the chain touched: its valence and boundary flag at the first touch (`None` if
/// the surgery made it), and whether its handle was (re)born during the surgery.
#[derive(Clone, Copy)]
struct Seen {
    v: Vert,
    before: Option<usize>,
    boundary: bool,
    born: bool,
    /// A corner of a triangle at the first touch (quad-dominant maps, Sec. 3.2).
    corner: bool,
}

/// Whether `v` is a corner of a triangle: a face of three darts round it (O(valence)).
fn triangle_corner(map: &Map, v: Vert) -> bool {
    map.vertex_darts(v)
        .any(|d| map.face(d).is_some() && map.next(map.next(map.next(d))) == d)
}

/// Whether `v` is a regular interior vertex of the quad grid: valence 4, not on the
/// boundary, and no triangle round it (a triangle's edges count as boundary, Sec. 3.2).
fn regular_quad_vertex(map: &Map, v: Vert) -> bool {
    is_regular_interior(map, MeshKind::Quad, v) && !triangle_corner(map, v)
}

/// The distinct vertices the chain touched, in order of first touch, with a small
/// open-addressing index so each touch costs O(1) and nothing is sorted (hand-written: a
/// `hashbrown` map measured 3 to 5 % slower on `zip_along`, `docs/benchmarks.md`, as it
/// allocates per chain where this table is inline for the usual few dozen vertices).
struct Touched {
    list: Vec<Seen>,
    /// Position in `list` plus one, 0 for empty, at most half full: inline for the usual
    /// few dozen vertices (no allocation per chain), `big` past that.
    small: [u32; SMALL_TABLE],
    big: Vec<u32>,
    /// How many entries the index in use takes before it grows (half its length).
    room: usize,
}

/// The inline index's size: chains of up to about 15 operations touch fewer than half.
const SMALL_TABLE: usize = 128;

impl Touched {
    /// Room for `n` vertices without growing.
    fn with_capacity(n: usize) -> Self {
        let size = (2 * n).next_power_of_two().max(SMALL_TABLE);
        Touched {
            list: Vec::with_capacity(n),
            small: [0; SMALL_TABLE],
            big: if size > SMALL_TABLE {
                alloc::vec![0; size]
            } else {
                Vec::new()
            },
            room: size / 2,
        }
    }

    /// The index in use (a power of two in length).
    fn table(&self) -> &[u32] {
        if self.big.is_empty() {
            &self.small
        } else {
            &self.big
        }
    }

    /// Where `v` is in `table`, or the empty place where it would go.
    fn slot(table: &[u32], list: &[Seen], v: Vert) -> usize {
        let mask = table.len() - 1;
        let mut h = (v.index() as u32).wrapping_mul(0x9e37_79b1) as usize & mask;
        // One lap at most: the table is never full, and a bug that filled it would give a
        // wrong entry, which the tests see, rather than a loop without end.
        for _ in 0..table.len() {
            match table.get(h) {
                Some(&k) if k != 0 && list[k as usize - 1].v != v => h = (h + 1) & mask,
                _ => break,
            }
        }
        debug_assert!(
            table
                .get(h)
                .is_some_and(|&k| k == 0 || list[k as usize - 1].v == v),
            "the touch index is full"
        );
        h
    }

    fn find(&self, v: Vert) -> Option<&Seen> {
        let table = self.table();
        match table[Self::slot(table, &self.list, v)] {
            0 => None,
            k => self.list.get(k as usize - 1),
        }
    }

    /// The entry of `v`, made with `make` at its first touch.
    fn entry(&mut self, v: Vert, make: impl FnOnce() -> Seen) -> &mut Seen {
        if self.list.len() + 1 > self.room {
            let size = (4 * (self.list.len() + 1)).next_power_of_two();
            self.big = alloc::vec![0; size];
            self.room = size / 2;
            for i in 0..self.list.len() {
                let h = Self::slot(&self.big, &self.list, self.list[i].v);
                self.big[h] = i as u32 + 1;
            }
        }
        let table = self.table();
        let h = Self::slot(table, &self.list, v);
        let k = match table[h] {
            0 => {
                self.list.push(make());
                let k = self.list.len() as u32;
                if self.big.is_empty() {
                    self.small[h] = k;
                } else {
                    self.big[h] = k;
                }
                k
            }
            k => k,
        };
        &mut self.list[k as usize - 1]
    }

    fn touch(&mut self, map: &Map, v: Vert) {
        self.entry(v, || Seen {
            v,
            before: Some(map.valence(v)),
            boundary: map.is_boundary_vertex(v),
            born: false,
            corner: triangle_corner(map, v),
        });
    }

    fn born(&mut self, v: Vert) {
        self.entry(v, || Seen {
            v,
            before: None,
            boundary: false,
            born: true,
            corner: false,
        })
        .born = true;
    }

    /// Whether the touched vertices carry the same multiset of irregular (valence,
    /// boundary) pairs before the surgery and now; else the two counts. Counted in a fixed
    /// table (valences below 32; higher ones in a list, which is then the only allocation).
    fn irregulars_kept(&self, map: &Map) -> Result<(), (usize, usize)> {
        let irregular = |k: usize, b: bool| k != regular_valence(MeshKind::Quad, b);
        let mut table = [0i32; 64];
        let mut high: Vec<(usize, bool, i32)> = Vec::new();
        let (mut n_before, mut n_after) = (0, 0);
        let mut add = |k: usize, b: bool, x: i32| {
            if k < 32 {
                table[2 * k + usize::from(b)] += x;
            } else {
                high.push((k, b, x));
            }
        };
        for s in &self.list {
            if let Some(k) = s.before {
                if irregular(k, s.boundary) {
                    add(k, s.boundary, 1);
                    n_before += 1;
                }
            }
            if map.is_live_vertex(s.v) {
                let (k, b) = (map.valence(s.v), map.is_boundary_vertex(s.v));
                if irregular(k, b) {
                    add(k, b, -1);
                    n_after += 1;
                }
            }
        }
        high.sort_unstable_by_key(|&(k, b, _)| (k, b));
        let high_kept = high
            .chunk_by(|x, y| (x.0, x.1) == (y.0, y.1))
            .all(|c| c.iter().map(|x| x.2).sum::<i32>() == 0);
        if table.iter().all(|&x| x == 0) && high_kept {
            Ok(())
        } else {
            Err((n_before, n_after))
        }
    }

    /// Whether every triangle corner the surgery touched is still the same vertex with the
    /// same valence, and no other touched vertex became one; else the first that is not.
    /// Q-zip treats a triangle's edges as boundary edges (Sec. 3.2): only the triangle
    /// moves (`quad_dominant`) change its corners.
    fn triangles_kept(&self, map: &Map) -> Result<(), Vert> {
        for s in &self.list {
            let live = map.is_live_vertex(s.v);
            let now = live && triangle_corner(map, s.v);
            if !(s.corner || now) {
                continue;
            }
            let kept = live && !s.born && s.corner && now && s.before == Some(map.valence(s.v));
            if !kept {
                return Err(s.v);
            }
        }
        Ok(())
    }

    /// Vertices the surgery left at valence 2 or 6 that were not so before, in order of
    /// first touch.
    fn to_clean(&self, map: &Map) -> Vec<Vert> {
        let mut out: Vec<Vert> = Vec::new();
        for s in &self.list {
            if !map.is_live_vertex(s.v) || map.is_boundary_vertex(s.v) {
                continue;
            }
            let k = map.valence(s.v);
            // A handle freed and reused is a new vertex.
            let before = if s.born { None } else { s.before };
            if (k == 2 || k == 6) && before != Some(k) {
                out.push(s.v);
            }
        }
        out
    }

    /// Whether the edit left `v` with valence `k` and it carries `k` because of the edit:
    /// born here, or changed to `k`.
    /// Whether `v` was a regular vertex of the quad grid before the surgery, or the surgery
    /// made it (its valence mid-chain is transient).
    fn was_regular(&self, map: &Map, v: Vert) -> bool {
        match self.find(v) {
            Some(s) if s.born => true,
            Some(s) => {
                s.before == Some(regular_valence(MeshKind::Quad, false)) && !s.boundary && !s.corner
            }
            None => regular_quad_vertex(map, v),
        }
    }

    fn changed_to(&self, map: &Map, v: Vert, k: usize) -> bool {
        map.is_live_vertex(v)
            && map.valence(v) == k
            && self.find(v).is_some_and(|s| s.born || s.before != Some(k))
    }
}

/// Surgeries of at most this many vertices look path vertices up by a scan.
const SCAN_LIMIT: usize = 24;

/// The records a chain has applied so far, in order (undone in reverse on an error).
type Records = Vec<QuadRecord>;

/// What one step of the chain gives: done, or why the chain stops.
type Step = Result<(), ZipError>;

/// Undoes records made in order on `map`, last first; stops at the first refusal.
pub(crate) fn undo_records(records: &[QuadRecord], map: &mut Map) -> Result<(), Refusal> {
    for r in records.iter().rev() {
        r.undo(map)?;
    }
    Ok(())
}

fn undo_all(map: &mut Map, records: &[QuadRecord]) {
    // The records were made in order on this map, so undoing in reverse cannot be stale;
    // should it be, nothing better than stopping is possible, and the error is reported anyway.
    let _ = undo_records(records, map);
}

/// The dart of the valence-6 vertex `v` to split along (with its opposite), among the pairs
/// of opposite edges whose far ends are both regular vertices of the quad grid (they become
/// the two v5s; a triangle corner is not one, its edges counting as boundary, Sec. 3.2): the
/// one whose breadth-first reading of the map is smallest (the canonical code's numbering
/// started there).
///
/// The choice must depend on the map, not on the path's history: a homotopic path swept
/// round a quad elsewhere gives an isomorphic map before the clean-up but touches (and
/// names) the vertices round `v` in another order. Choosing by touch order broke homotopy
/// invariance on the Catmull-Clark-subdivided Spot and Blub cages.
fn v6_first_dart(map: &Map, v: Vert) -> Dart {
    let regular = |x: Vert| regular_quad_vertex(map, x);
    let opposite = |d: Dart| map.rotate_cw(map.rotate_cw(map.rotate_cw(d)));
    let good: Vec<Dart> = map
        .vertex_darts(v)
        .filter(|&d| regular(map.dest(d)) && regular(map.dest(opposite(d))))
        .collect();
    least_start(map, &good).unwrap_or_else(|| map.vertex_dart(v))
}

/// Executes a prepared surgery: the serial operations, then the v2/v6 clean-up.
///
/// All or nothing: on any refusal every operation already applied is undone and the map is
/// left `==` to what it was ([`ZipError`] says where and why).
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{execute, plan, prepare, sketch, SketchOptions, Tag};
/// let mut map = gen::subdivided_icosahedron(2).map;
/// let (v5, v3) = (Vert::new(0), Vert::new(42)); // four edges apart
/// let before = map.clone();
/// let path = sketch(&map, v5, v3, &SketchOptions::default()).unwrap();
/// let s = prepare(&map, &plan(&map, &path, Tag::RS).unwrap()).unwrap();
/// let r = execute(&mut map, &s).unwrap();
/// assert_eq!(r.surgery(), &s);
/// assert_eq!(r.splits() + r.collapses(), s.operations());
/// assert_eq!(r.records().len(), s.operations() + r.cleanup_counts().0 + r.cleanup_counts().1);
/// assert!(r.footprint_edges().len() <= 2 * r.splits());
/// assert_eq!(r.scar_faces().len() + r.scar_edges().len() > 0, true);
/// r.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
pub fn execute(map: &mut Map, surgery: &Surgery) -> Result<ZipReport, ZipError> {
    execute_owned(map, surgery.clone(), Guard::GridPreserving)
}

/// Whether execution refuses an edit that changes the irregular valences of the vertices it
/// touched (the guard of [`ZipError::NotGridPreserving`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Guard {
    /// Refuse: the Q-zip only moves singularities (the default, [`execute`]).
    GridPreserving,
    /// Accept: a moved singularity may cancel against, or merge with, another one (the
    /// optimizer's use, [`crate::qzip::Qzip::allow_cancellation`]).
    AllowCancellation,
}

/// [`execute`] taking the surgery by value (it goes into the report without a copy).
pub(crate) fn execute_owned(
    map: &mut Map,
    surgery: Surgery,
    guard: Guard,
) -> Result<ZipReport, ZipError> {
    let mut records: Vec<QuadRecord> = Vec::with_capacity(surgery.steps().len() + 2);
    match run(map, surgery, &mut records, guard) {
        Ok(r) => Ok(r),
        Err(e) => {
            undo_all(map, &records);
            Err(e)
        }
    }
}

/// Where an edge of the path is looked up: the dart the surgery carries when it still joins
/// `from` and `to`, else (the chain's edits merged or re-homed it, or the map changed) the
/// dart found again in the map.
fn joining_dart(map: &Map, carried: Option<Dart>, from: Vert, to: Vert) -> Option<Dart> {
    carried
        .filter(|&d| map.is_live_dart(d) && map.origin(d) == from && map.dest(d) == to)
        .or_else(|| map.dart_between(from, to))
}

/// The error of an operation at position `index` (vertex `vertex`, operation `tag`) that the
/// operator refused.
fn refused(index: usize, vertex: Vert, tag: Tag) -> impl FnOnce(Refusal) -> ZipError {
    move |refusal| ZipError::Refused {
        index,
        vertex,
        tag,
        refusal,
    }
}

/// The state of the chain while a surgery runs: the position on the path, the guide, the
/// touched vertices, the counts, the candidates for where the pair goes, and the footprint and
/// scar found so far.
struct Chain<'s> {
    surgery: &'s Surgery,
    touched: Touched,
    splits: usize,
    collapses: usize,
    /// The vertex the next split splits towards (with the next path vertex).
    guide: Option<Vert>,
    /// The position on the path, and the handle of the vertex there: a merge can fold the path
    /// onto itself, and then the position jumps ahead while the handle stays the merged vertex.
    index: usize,
    current: Vert,
    /// Valences of the pair before the edit.
    from_valence: usize,
    to_valence: usize,
    /// Where the pair went: the vertices of the first and of the last operation, the one the
    /// start/end rule predicts first; the first of them left with the singularity's valence
    /// wins (at a turn right after a start the defect can land on the other copy). Fixed size:
    /// no allocation per operation.
    from_candidates: Option<[Vert; 3]>,
    to_candidates: [Vert; 4],
    footprint_faces: Vec<Face>,
    /// The faces made by the chain's splits and still there (a collapse of one shrinks the
    /// scar; faces die only by the chain's collapses, so no slot is listed twice): every
    /// other face the chain collapses is one of the map before, in the footprint.
    scar_faces: Vec<Face>,
    scar_edges: Vec<Edge>,
    /// Path vertices sorted, with their positions, for long surgeries (short ones scan).
    positions: Vec<(Vert, usize)>,
}

impl<'s> Chain<'s> {
    fn new(map: &Map, surgery: &'s Surgery) -> Self {
        let steps = surgery.steps();
        // Sized for the usual counts (a few touches and merged edges per operation) so nothing
        // regrows mid-chain.
        let expected = 4 * steps.len() + 8;
        let mut positions: Vec<(Vert, usize)> = Vec::new();
        if steps.len() > SCAN_LIMIT {
            positions = steps
                .iter()
                .enumerate()
                .map(|(i, x)| (x.vertex, i))
                .collect();
            positions.sort_unstable();
        }
        Chain {
            surgery,
            touched: Touched::with_capacity(expected),
            splits: 0,
            collapses: 0,
            guide: None,
            index: 0,
            current: steps[0].vertex,
            from_valence: map.valence(surgery.from()),
            to_valence: map.valence(surgery.to()),
            from_candidates: None,
            to_candidates: [Vert::new(u32::MAX); 4],
            // At most one face and two edges per operation: sized once, so no vector
            // regrows mid-chain (regrowth was a tenth of a Q-zip's time on Spot).
            footprint_faces: Vec::with_capacity(steps.len()),
            scar_faces: Vec::with_capacity(steps.len()),
            scar_edges: Vec::with_capacity(2 * steps.len()),
            positions,
        }
    }

    fn vertex_at(&self, i: usize) -> Vert {
        self.surgery.steps()[i].vertex
    }

    /// Moves on to position `i`, whose vertex has the handle `handle`.
    fn advance(&mut self, i: usize, handle: Vert) {
        self.index = i;
        self.current = handle;
    }

    /// Runs every operation of the surgery, in order.
    fn run(&mut self, map: &mut Map, records: &mut Vec<QuadRecord>) -> Result<(), ZipError> {
        let last = self.surgery.steps().len() - 1;
        while self.index < last {
            let index = self.index;
            let (p, n) = (self.current, self.vertex_at(index + 1));
            let Some(tag) = self.surgery.steps()[index].op else {
                self.guide = Some(p);
                self.advance(index + 1, n);
                continue;
            };
            let carried = self.surgery.darts().get(index).copied();
            let edge = joining_dart(map, carried, p, n).ok_or(ZipError::StalePlan { index })?;
            if tag.is_split() {
                self.split_step(map, tag, edge, records)?;
            } else {
                self.collapse_step(map, tag, edge, records)?;
            }
            // Every step moves on; one that did not would loop for ever.
            if self.index <= index {
                return Err(ZipError::StalePlan { index });
            }
        }
        if matches!(
            self.surgery.end_rule(),
            EndRule::V5Collapse | EndRule::V5Split
        ) {
            self.to_candidates[0] = self.current;
        }
        Ok(())
    }

    /// LS / RS at `p = origin(edge)`: split `p` along its edges to the guide and to the next
    /// vertex; the copy on the hand's side continues the path and becomes the guide.
    fn split_step(&mut self, map: &mut Map, tag: Tag, edge: Dart, out: &mut Records) -> Step {
        let index = self.index;
        let (p, n) = (map.origin(edge), map.dest(edge));
        let guide = self.guide.ok_or(ZipError::StalePlan { index })?;
        // After a no-op the guide is the previous path vertex, whose carried dart may still
        // join them; after an operation the guide is a vertex the edit made or moved, found in
        // the map.
        let carried_back = index
            .checked_sub(1)
            .and_then(|i| self.surgery.darts().get(i))
            .map(|d| d.twin());
        let to_guide =
            joining_dart(map, carried_back, p, guide).ok_or(ZipError::StalePlan { index })?;
        for x in [p, guide, n] {
            self.touched.touch(map, x);
        }
        let r = split_vertex(map, to_guide, edge).map_err(refused(index, p, tag))?;
        self.splits += 1;
        let (left, right) = (r.kept(), r.created());
        self.touched.born(right);
        let (cont, other) = if tag == Tag::LS {
            (left, right)
        } else {
            (right, left)
        };
        if self.from_candidates.is_none() {
            self.from_candidates = Some(match self.surgery.start_rule() {
                StartRule::V5Split => [self.vertex_at(0), other, cont],
                _ => [other, cont, guide],
            });
        }
        self.to_candidates = [cont, cont, other, n];
        self.guide = Some(cont);
        self.scar_faces.push(r.face());
        out.push(r.into());
        self.advance(index + 1, self.vertex_at(index + 1));
        Ok(())
    }

    /// The position of `v` in the surgery, if it is a path vertex.
    fn position_of(&self, v: Vert) -> Option<usize> {
        if self.surgery.steps().len() > SCAN_LIMIT {
            let k = self.positions.binary_search_by_key(&v, |x| x.0).ok()?;
            Some(self.positions[k].1)
        } else {
            self.surgery.steps().iter().position(|x| x.vertex == v)
        }
    }

    /// LC / RC along `edge: P -> N`: collapse the quad on the hand's side, merging `N` with
    /// that quad's corner next to `P`; the corner next to `N` becomes the guide.
    fn collapse_step(&mut self, map: &mut Map, tag: Tag, edge: Dart, out: &mut Records) -> Step {
        let index = self.index;
        let (p, n) = (map.origin(edge), map.dest(edge));
        let (at, far) = strip_quad(map, edge, tag);
        let removed = map.origin(map.next(map.next(at)));
        let lost = ZipError::Lost {
            index,
            vertex: removed,
        };
        // Merging `n` with a later path vertex folds the path: n -> x -> removed comes back to
        // the merged vertex, and that pair of edges cancels (like a fold of the preparation,
        // with the compass unchanged). Merging with the path vertex four steps ahead makes a
        // loop n -> .. -> n: cancelled like the loops of the preparation when it goes round
        // one quad (checked after the collapse, which is undone with the rest if not).
        // Anything else would lose the vertex.
        let mut next = index + 1;
        let mut round = None;
        if let Some(j) = self.position_of(removed).filter(|&j| j >= index + 2) {
            if j == index + 5 {
                round = Some(j);
            } else if j != index + 3 {
                return Err(lost);
            }
            next = j;
        }
        for x in [p, n, far, removed] {
            self.touched.touch(map, x);
        }
        let r = collapse_quad(map, at).map_err(refused(index, p, tag))?;
        self.collapses += 1;
        if self.from_candidates.is_none() {
            self.from_candidates = Some(match self.surgery.start_rule() {
                StartRule::V5Collapse => [n, p, far],
                _ => [p, n, far],
            });
        }
        self.to_candidates = [far, far, n, p];
        self.guide = Some(far);
        self.track_collapsed(r.face(), r.merged_edges());
        out.push(r.into());
        if let Some(j) = round {
            let ring = [
                n,
                self.vertex_at(j - 3),
                self.vertex_at(j - 2),
                self.vertex_at(j - 1),
            ];
            // Valences mid-chain are transient, so the quad is read with `regular` off; but
            // cutting the loop is a homotopy across that quad only if its other corners were
            // regular before the edit (as in the preparation's cut): a singularity on the loop
            // would be skipped instead of passed by the counting rule.
            let ends = [self.surgery.from(), self.surgery.to()];
            if !bounds_one_quad(map, ring, ends, false)
                || !ring[1..].iter().all(|&w| self.touched.was_regular(map, w))
            {
                return Err(lost);
            }
        }
        self.advance(next, n);
        Ok(())
    }

    /// Footprint and scar after collapsing `face` (merging the two edge pairs of `merged`): a
    /// quad a split made leaves the scar, an original one joins the footprint.
    fn track_collapsed(&mut self, face: Face, merged: [Dart; 2]) {
        // A face the chain did not make (not in the scar) is one of the map before.
        if let Some(k) = self.scar_faces.iter().rposition(|&b| b == face) {
            self.scar_faces.remove(k);
        } else {
            self.footprint_faces.push(face);
        }
        self.scar_edges.extend(merged.map(Dart::edge));
    }

    /// The post-processing of Sec. 2.7: each vertex the chain made valence 2 is removed, each
    /// it made valence 6 is split (see [`v6_first_dart`]); returns the two counts.
    fn clean_up(
        &mut self,
        map: &mut Map,
        records: &mut Vec<QuadRecord>,
    ) -> Result<(usize, usize), ZipError> {
        let (mut v2_removals, mut v6_splits) = (0, 0);
        for v in self.touched.to_clean(map) {
            for d in map.vertex_darts(v) {
                self.touched.touch(map, map.dest(d));
            }
            let cleanup = |refusal| ZipError::Cleanup { vertex: v, refusal };
            if map.valence(v) == 2 {
                let r = remove_valence2(map, map.vertex_dart(v)).map_err(cleanup)?;
                v2_removals += 1;
                records.push(r.into());
            } else {
                let first = v6_first_dart(map, v);
                let r = split_high_valence(map, v, first).map_err(cleanup)?;
                v6_splits += 1;
                records.push(r.into());
            }
        }
        Ok((v2_removals, v6_splits))
    }

    /// The last touched vertex still live (every edit leaves one: the map is not empty).
    fn last_live_touched(&self, map: &Map) -> Option<Vert> {
        self.touched
            .list
            .iter()
            .rev()
            .map(|s| s.v)
            .find(|&v| map.is_live_vertex(v))
    }

    /// Where the pair went: among the candidates, the first the edit left with the
    /// singularity's valence, else the first such touched vertex (in touch order for the
    /// initial singularity, in reverse for the terminal one).
    fn locate_moved_pair(&self, map: &Map) -> Result<(Vert, Vert), ZipError> {
        let touched = &self.touched;
        let pick = |candidates: &[Vert], k: usize, forward: bool| {
            let changed = |v: &Vert| touched.changed_to(map, *v, k);
            candidates.iter().copied().find(changed).or_else(|| {
                let mut order = touched.list.iter().map(|s| s.v);
                if forward {
                    order.find(changed)
                } else {
                    order.rev().find(changed)
                }
            })
        };
        let from_candidates = self.from_candidates.unwrap_or([self.current; 3]);
        let (Some(moved_from), Some(moved_to)) = (
            pick(&from_candidates, self.from_valence, true),
            pick(&self.to_candidates, self.to_valence, false),
        ) else {
            return Err(ZipError::Untracked);
        };
        if moved_from == moved_to {
            return Err(ZipError::Untracked);
        }
        Ok((moved_from, moved_to))
    }
}

/// The chain, the clean-up, the guard and the report; on an error the caller undoes
/// `records`.
fn run(
    map: &mut Map,
    surgery: Surgery,
    records: &mut Vec<QuadRecord>,
    guard: Guard,
) -> Result<ZipReport, ZipError> {
    let mut chain = Chain::new(map, &surgery);
    chain.run(map, records)?;
    let (v2_removals, v6_splits) = chain.clean_up(map, records)?;
    chain
        .touched
        .triangles_kept(map)
        .map_err(|vertex| ZipError::TriangleChanged { vertex })?;
    let kept = chain.touched.irregulars_kept(map);
    let (moved_from, moved_to) = match (kept, guard) {
        (Err((before, after)), Guard::GridPreserving) => {
            return Err(ZipError::NotGridPreserving { before, after })
        }
        (Ok(()), _) => chain.locate_moved_pair(map)?,
        // A cancelled singularity has no place to go: name the last live vertex touched.
        (Err(_), Guard::AllowCancellation) => chain.locate_moved_pair(map).or_else(|_| {
            chain
                .last_live_touched(map)
                .map(|v| (v, v))
                .ok_or(ZipError::Untracked)
        })?,
    };
    let Chain {
        splits,
        collapses,
        footprint_faces,
        mut scar_faces,
        mut scar_edges,
        ..
    } = chain;
    scar_edges.retain(|&e| map.is_live_edge(e));
    scar_faces.retain(|&f| map.is_live_face(f));
    Ok(ZipReport {
        surgery,
        records: core::mem::take(records),
        splits,
        collapses,
        v2_removals,
        v6_splits,
        moved_from,
        moved_to,
        footprint_faces,
        scar_faces,
        scar_edges,
    })
}

/// The edges of the map before that the chain's splits (in `chain`, its records in order)
/// split: each split's two split edges (`quad()[0]` and `[2]`) unless an earlier split made
/// them (its new sides, `quad()[1]` and `[3]`; a slot freed and reused is made again).
/// Quadratic in the splits, a few per chain.
fn split_original_edges(chain: &[QuadRecord]) -> Vec<Edge> {
    let splits = || {
        chain.iter().filter_map(|r| match r {
            QuadRecord::Split(s) => Some(s.quad()),
            _ => None,
        })
    };
    let mut out = Vec::new();
    for (i, q) in splits().enumerate() {
        for e in [q[0].edge(), q[2].edge()] {
            let made = splits()
                .take(i)
                .any(|p| p[1].edge() == e || p[3].edge() == e);
            if !made {
                out.push(e);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The touch index keeps first touches in order through its growth: every vertex once,
    /// its first valence kept, `born` sticking, lookups agreeing with a plain scan.
    #[test]
    fn touched_keeps_first_touches_in_order() {
        let map = crate::gen::torus_grid(40, 40).map;
        let mut t = Touched::with_capacity(0);
        let mut order: Vec<Vert> = Vec::new();
        let mut rng = crate::rng::Rng::new(7);
        for _ in 0..5000 {
            let v = Vert::new(rng.below(1600) as u32);
            if !order.contains(&v) {
                order.push(v);
            }
            if rng.chance(1, 10) {
                t.born(v);
            } else {
                t.touch(&map, v);
            }
        }
        let listed: Vec<Vert> = t.list.iter().map(|s| s.v).collect();
        assert_eq!(listed, order);
        for s in &t.list {
            assert_eq!(t.find(s.v).map(|x| x.v), Some(s.v));
            assert!(s.before.is_none() || s.before == Some(4));
        }
        assert!(t.list.iter().any(|s| s.born) && t.list.iter().any(|s| !s.born));
        let absent = (0..1600).map(Vert::new).find(|v| !order.contains(v));
        if let Some(v) = absent {
            assert!(t.find(v).is_none());
        }
    }

    /// A closed fan: `k` quads round vertex 0, each `(0, r_i, o_i, r_i+1)`, capped by one
    /// big face, so vertex 0 has valence `k`.
    fn fan(k: u32) -> Map {
        let mut faces: Vec<Vec<u32>> = (0..k)
            .map(|i| alloc::vec![0, 1 + i, 1 + k + i, 1 + (i + 1) % k])
            .collect();
        let mut cap: Vec<u32> = (0..k).flat_map(|i| [1 + i, 1 + k + i]).collect();
        cap.reverse();
        faces.push(cap);
        Map::from_polygons((1 + 2 * k) as usize, &faces).unwrap()
    }

    /// Each refusal says where and why, in its own words.
    #[test]
    fn zip_errors_read_as_documented() {
        use alloc::string::ToString;
        let v = Vert::new(7);
        assert_eq!(
            ZipError::Lost { index: 2, vertex: v }.to_string(),
            "the collapse at position 2 would delete vertex 7, which the surgery still has to visit"
        );
        assert!(ZipError::StalePlan { index: 4 }
            .to_string()
            .starts_with("the surgery does not fit this map at position 4"));
        assert!(ZipError::NotGridPreserving {
            before: 6,
            after: 2
        }
        .to_string()
        .contains(
            "(6 irregular vertices in the touched region before, a different set of 2 after)"
        ));
        assert!(ZipError::TriangleChanged { vertex: v }
            .to_string()
            .starts_with("the edit would change a triangle at vertex 7"));
        assert!(ZipError::Untracked.to_string().ends_with("; refused"));
    }

    /// `was_regular` reads a touched vertex as it was at its first touch (valence 4, interior,
    /// no triangle corner), an untouched one as it is now, and one the chain made as regular.
    #[test]
    fn was_regular_reads_a_vertex_as_it_was_at_its_first_touch() {
        let v = Vert::new;
        let grid = crate::gen::grid(4, 4).map;
        let (inner, five) = (v(6), fan(5));
        assert!(regular_quad_vertex(&grid, inner));
        // A 4 x 4 grid with the quad 6 7 12 11 cut into two triangles: 7 and 11 are interior
        // triangle corners of valence 4.
        let mut faces: Vec<Vec<u32>> = Vec::new();
        for j in 0..4u32 {
            for i in 0..4u32 {
                let a = 5 * j + i;
                if a == 6 {
                    faces.extend([alloc::vec![6, 7, 12], alloc::vec![6, 12, 11]]);
                } else {
                    faces.push(alloc::vec![a, a + 1, a + 6, a + 5]);
                }
            }
        }
        let tri = Map::from_polygons(25, &faces).unwrap();
        assert!(triangle_corner(&tri, v(7)) && tri.valence(v(7)) == 4);
        // Three quads round vertex 0 on the boundary: valence 4 there.
        let rim = Map::from_polygons(8, &[[0u32, 1, 2, 3], [0, 3, 4, 5], [0, 5, 6, 7]]).unwrap();
        assert!(rim.is_boundary_vertex(v(0)) && rim.valence(v(0)) == 4);
        let t = Touched::with_capacity(0);
        assert!(t.was_regular(&grid, inner));
        assert!(!t.was_regular(&five, v(0)));
        let mut t = Touched::with_capacity(0);
        t.touch(&grid, inner);
        t.touch(&five, v(0));
        t.touch(&tri, v(7));
        t.touch(&rim, v(0));
        // Read against another map: the first touch decides, not the valence now.
        assert!(t.was_regular(&five, inner));
        assert!(!t.was_regular(&grid, v(7)));
        let mut t = Touched::with_capacity(0);
        t.touch(&five, v(0));
        assert!(!t.was_regular(&grid, v(0)));
        let mut t = Touched::with_capacity(0);
        t.touch(&rim, v(0));
        assert!(!t.was_regular(&grid, v(0)));
        t.born(v(3));
        assert!(t.was_regular(&five, v(3)));
    }

    /// The guard's count compares valences of 32 and more too (kept outside the table).
    #[test]
    fn irregulars_kept_counts_high_valences() {
        let (a, b) = (fan(40), fan(41));
        assert_eq!((a.valence(Vert::new(0)), b.valence(Vert::new(0))), (40, 41));
        let mut t = Touched::with_capacity(0);
        t.touch(&a, Vert::new(0));
        assert_eq!(t.irregulars_kept(&a), Ok(()));
        assert_eq!(t.irregulars_kept(&b), Err((1, 1)));
        let mut u = Touched::with_capacity(0);
        u.touch(&fan(6), Vert::new(0));
        assert_eq!(u.irregulars_kept(&fan(6)), Ok(()));
        assert_eq!(u.irregulars_kept(&fan(7)), Err((1, 1)));
    }

    /// `verify_edit` refuses a report whose footprint or scar is tampered with, clause by
    /// clause (each tamper breaks one promise of `Broken::Footprint` and nothing else), and
    /// the untampered report passes: so the check can fail, and a weakened one would.
    #[test]
    fn verify_edit_catches_a_wrong_footprint_or_scar() {
        use crate::qzip::{sketch, verify_edit, Broken, Qzip, SketchOptions};
        use alloc::string::ToString;
        let before = crate::gen::subdivided_icosahedron(2).map;
        let o = SketchOptions::default();
        let path = sketch(&before, Vert::new(0), Vert::new(42), &o).unwrap();
        // A movement with collapses and splits: footprint faces and a scar to tamper with.
        let (after, r) = Tag::CCW
            .into_iter()
            .filter_map(|tag| {
                let mut m = before.clone();
                let r = Qzip::new()
                    .zip_along(&mut m, &path, tag)
                    .ok()?
                    .into_record();
                let full = !r.footprint_faces.is_empty() && !r.scar_faces.is_empty();
                (full && r.cleanup_counts() == (0, 0) && !r.scar_edges.is_empty()).then_some((m, r))
            })
            .next()
            .expect("a movement with a footprint and a scar");
        assert_eq!(verify_edit(&before, &after, &path, &r), Ok(()));
        let live_face = after.faces().find(|f| !r.scar_faces.contains(f)).unwrap();
        let dead_face = Face::new(after.face_slots() as u32 + 7);
        let dead_edge = Edge::new(after.edge_slots() as u32 + 7);
        let tampers: [&dyn Fn(&mut ZipReport); 5] = [
            &|r| r.footprint_faces.push(live_face),
            &|r| r.footprint_faces.push(dead_face),
            &|r| {
                r.footprint_faces.pop();
            },
            &|r| r.scar_faces.push(dead_face),
            &|r| r.scar_edges.push(dead_edge),
        ];
        for (i, tamper) in tampers.iter().enumerate() {
            let mut bad = r.clone();
            tamper(&mut bad);
            let got = verify_edit(&before, &after, &path, &bad);
            assert_eq!(got, Err(Broken::Footprint), "tamper {i}");
        }
        assert!(Broken::Footprint.to_string().contains("footprint or scar"));
        // With a valence-2 clean-up (which deletes a face of its own), a footprint face
        // dropped is still seen.
        let before = crate::gen::cube(2).map;
        let path = sketch(&before, Vert::new(8), Vert::new(17), &o).unwrap();
        let (after, r) = Tag::CCW
            .into_iter()
            .filter_map(|tag| {
                let mut m = before.clone();
                let r = Qzip::new()
                    .zip_along(&mut m, &path, tag)
                    .ok()?
                    .into_record();
                (r.cleanup_counts().0 > 0 && !r.footprint_faces.is_empty()).then_some((m, r))
            })
            .next()
            .expect("a movement with a valence-2 clean-up");
        assert_eq!(verify_edit(&before, &after, &path, &r), Ok(()));
        let mut bad = r.clone();
        bad.footprint_faces.pop();
        assert_eq!(
            verify_edit(&before, &after, &path, &bad),
            Err(Broken::Footprint)
        );
    }
}
