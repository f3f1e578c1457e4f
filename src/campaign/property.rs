//! Properties: a name and a check of one [`Case`]; the built-in kernel and operator ones.

use super::case::Case;
use crate::invariants::canonical::CanonicalCode;
use crate::invariants::{euler_characteristic, gauss_bonnet, Counts, MeshKind};
use crate::map::{Dart, Map, Vert};
use crate::ops::quad::{self, QuadOp};
use crate::ops::tri::TriOp;
use crate::ops::{Effect, Refusal, Undo, VertexChanges};
use crate::rng::Rng;
use alloc::format;
use alloc::string::{String, ToString};
use alloc::sync::Arc;
use alloc::vec::Vec;
use core::fmt;

/// The result of checking one property on one case.
///
/// ```
/// use zipmesh::campaign::Outcome;
/// assert!(Outcome::Pass { checks: 3 }.is_pass());
/// assert!(Outcome::fail("broken", None).is_fail());
/// assert!(!Outcome::Skip.is_pass() && !Outcome::Skip.is_fail());
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The property holds; `checks` counts the assertions made (for an operator property,
    /// the applications checked), reported in the table.
    Pass {
        /// How many assertions were made.
        checks: u64,
    },
    /// The property does not apply to this case (for example a triangle operator on a mesh
    /// without triangles). Skipped cases are not counted in the property's `cases`.
    Skip,
    /// The property fails.
    Fail {
        /// What went wrong, for the report.
        message: String,
        /// The vertex where it went wrong, if there is one: shrinking keeps the faces near
        /// it, and replays try it first (see [`Case::focus`]).
        focus: Option<Vert>,
    },
}

impl Outcome {
    /// A failure with a message and an optional focus vertex.
    ///
    /// ```
    /// use zipmesh::{campaign::Outcome, Vert};
    /// let o = Outcome::fail("valence 1 left", Some(Vert::new(4)));
    /// assert!(matches!(o, Outcome::Fail { focus: Some(v), .. } if v == Vert::new(4)));
    /// ```
    pub fn fail(message: impl Into<String>, focus: Option<Vert>) -> Outcome {
        Outcome::Fail {
            message: message.into(),
            focus,
        }
    }

    /// Whether this is [`Outcome::Pass`].
    ///
    /// ```
    /// assert!(zipmesh::campaign::Outcome::Pass { checks: 0 }.is_pass());
    /// ```
    pub fn is_pass(&self) -> bool {
        matches!(self, Outcome::Pass { .. })
    }

    /// Whether this is [`Outcome::Fail`].
    ///
    /// ```
    /// assert!(zipmesh::campaign::Outcome::fail("x", None).is_fail());
    /// ```
    pub fn is_fail(&self) -> bool {
        matches!(self, Outcome::Fail { .. })
    }
}

/// The check function of a [`Property`]: any thread-safe closure from a case to an outcome.
///
/// ```
/// use std::sync::Arc;
/// use zipmesh::campaign::{CheckFn, Outcome};
/// let f: Arc<CheckFn> = Arc::new(|case| Outcome::Pass { checks: case.mesh.map.num_faces() as u64 });
/// assert!(f(&zipmesh::campaign::Case::generate(0, 0, 100)).is_pass());
/// ```
pub type CheckFn = dyn Fn(&Case) -> Outcome + Send + Sync;

/// A named property checked on every case of a campaign: the built-in ones come from
/// [`builtin`]; your own are made with [`Property::new`] and run by the same campaign.
///
/// ```
/// use zipmesh::campaign::{self, Config, Outcome, Property};
/// // Every vertex of a generated mesh has valence at least 2.
/// let p = Property::new("min-valence", "every vertex has valence >= 2", |case| {
///     let map = &case.mesh.map;
///     match map.vertices().find(|&v| map.valence(v) < 2) {
///         Some(v) => Outcome::fail("valence below 2", Some(v)),
///         None => Outcome::Pass { checks: map.num_vertices() as u64 },
///     }
/// });
/// let report = campaign::run(&Config { cases: 8, max_faces: 200, ..Config::default() }, &[p]);
/// assert_eq!(report.rows[0].passed, 8);
/// ```
#[derive(Clone)]
pub struct Property {
    name: String,
    about: String,
    check: Arc<CheckFn>,
}

impl fmt::Debug for Property {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Property")
            .field("name", &self.name)
            .field("about", &self.about)
            .finish_non_exhaustive()
    }
}

impl Property {
    /// A property from a name (used by `--property` and in reports), a one-line description
    /// and the check. The check must be deterministic given the case (take randomness from
    /// [`Case::rng`] or [`Case::sites`]) for campaigns to be reproducible.
    ///
    /// ```
    /// use zipmesh::campaign::{Case, Outcome, Property};
    /// let p = Property::new("has-faces", "at least one face", |c| {
    ///     if c.mesh.map.num_faces() > 0 { Outcome::Pass { checks: 1 } } else { Outcome::fail("empty", None) }
    /// });
    /// assert!(p.check(&Case::generate(0, 0, 100)).is_pass());
    /// ```
    pub fn new(
        name: impl Into<String>,
        about: impl Into<String>,
        check: impl Fn(&Case) -> Outcome + Send + Sync + 'static,
    ) -> Property {
        Property {
            name: name.into(),
            about: about.into(),
            check: Arc::new(check),
        }
    }

    /// The property's name.
    ///
    /// ```
    /// assert_eq!(zipmesh::campaign::builtin()[0].name(), "validity");
    /// ```
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The one-line description.
    ///
    /// ```
    /// assert!(!zipmesh::campaign::builtin()[0].about().is_empty());
    /// ```
    pub fn about(&self) -> &str {
        &self.about
    }

    /// Checks the property on one case.
    ///
    /// ```
    /// use zipmesh::campaign::{builtin, Case};
    /// let case = Case::generate(1, 0, 300);
    /// assert!(!builtin()[0].check(&case).is_fail());
    /// ```
    pub fn check(&self, case: &Case) -> Outcome {
        (self.check)(case)
    }
}

/// Every built-in property: [`kernel`], [`operators`], the Q-zip properties
/// ([`qzip_properties`](super::qzip_properties) with the default [`PairChoice`](super::PairChoice)),
/// then [`optimize_property`](super::optimize_property) and
/// [`optimize_triangles_property`](super::optimize_triangles_property).
///
/// ```
/// let names: Vec<String> = zipmesh::campaign::builtin().iter().map(|p| p.name().to_string()).collect();
/// assert!(names.contains(&"gauss-bonnet".to_string()));
/// assert!(names.contains(&"tri-flip".to_string()));
/// ```
pub fn builtin() -> Vec<Property> {
    builtin_with(super::PairChoice::default())
}

/// [`builtin`] with the Q-zip properties drawing their pairs by `choice` (what `zipmesh
/// check --max-distance` sets).
///
/// ```
/// use zipmesh::campaign::{builtin, builtin_with, PairChoice};
/// assert_eq!(builtin_with(PairChoice::default()).len(), builtin().len());
/// ```
pub fn builtin_with(choice: super::PairChoice) -> Vec<Property> {
    let mut all = kernel();
    all.extend(operators());
    all.extend(super::tri_edit_properties());
    all.extend(quad_dominant());
    all.extend(super::qzip_properties(choice));
    all.push(super::optimize_property());
    all.push(super::optimize_triangles_property());
    all
}

/// The quad-dominant properties (Q-zip paper, Sec. 3.2): `qd-walk`, sixteen random
/// triangle moves per case (on a mixed case its own triangles, on a quad case two inserted
/// triangle pairs, [`crate::gen::with_triangle_pairs`]): `can_move_triangle` and the move
/// agree, a refusal changes nothing, an application passes `check()` with its
/// [`crate::quad_dominant::Move::effect`], and undoing every move, last first, restores the map
/// exactly.
///
/// ```
/// assert_eq!(zipmesh::campaign::quad_dominant()[0].name(), "qd-walk");
/// ```
pub fn quad_dominant() -> Vec<Property> {
    alloc::vec![Property::new(
        "qd-walk",
        "triangle moves VE/EV/LE/RE: can_* agrees, documented effect, valid map; exact undo",
        qd_walk
    )]
}

/// The kernel's properties: `validity`, `euler`, `gauss-bonnet`, `canonical-relabel`.
///
/// ```
/// assert_eq!(zipmesh::campaign::kernel().len(), 4);
/// ```
pub fn kernel() -> Vec<Property> {
    alloc::vec![
        Property::new(
            "validity",
            "check() accepts the map, and a generated mesh has the face kind asked for",
            validity
        ),
        Property::new(
            "euler",
            "chi = V - E + F from counting elements; genus and boundary loops are those asked for",
            euler
        ),
        Property::new(
            "gauss-bonnet",
            "discrete Gauss-Bonnet holds in the quad and the triangle frame",
            gauss_bonnet_property
        ),
        Property::new(
            "canonical-relabel",
            "the canonical code is unchanged by a random renumbering and by compact()",
            canonical_relabel
        ),
    ]
}

/// The operators' properties: for random sites, `can_*` and the operator agree, an applied
/// operator leaves a valid map with its documented changes in V, E, F and valences, and
/// undo restores the map exactly (`==`). Quad: `quad-collapse`, `quad-vertex-split`,
/// `quad-high-valence-split`, `quad-doublet` (insertion and valence-2 removal),
/// `quad-rotate`; triangle: `tri-flip`, `tri-collapse`, `tri-vertex-split`,
/// `tri-edge-split`.
///
/// ```
/// assert_eq!(zipmesh::campaign::operators().len(), 9);
/// ```
pub fn operators() -> Vec<Property> {
    alloc::vec![
        Property::new(
            "quad-collapse",
            "quad collapse: V-1 E-2 F-1, merged valence val(a)+val(c)-2, b and d -1; exact undo",
            collapse_quad
        ),
        Property::new(
            "quad-vertex-split",
            "vertex split: V+1 E+2 F+1, val(w) = |arc1|+2, a and b +1; exact undo",
            quad_vertex_split
        ),
        Property::new(
            "quad-high-valence-split",
            "split of a valence k >= 6: V+1 E+2 F+1, val(v) = floor(k/2)+1; exact undo",
            quad_high_valence_split
        ),
        Property::new(
            "quad-doublet",
            "doublet insertion V+1 E+2 F+1 (new valence 2), its removal gives an isomorphic map; exact undos",
            quad_doublet
        ),
        Property::new(
            "quad-rotate",
            "edge rotation: counts unchanged, old ends -1, new ends +1; exact undo",
            quad_rotate
        ),
        Property::new(
            "tri-flip",
            "triangle flip: counts unchanged, ends -1, apexes +1; exact undo",
            tri_flip
        ),
        Property::new(
            "tri-collapse",
            "edge collapse: V-1 E-3 F-2 inside (E-2 F-1 on the boundary), documented valences; exact undo",
            tri_collapse
        ),
        Property::new(
            "tri-vertex-split",
            "triangle vertex split: V+1 E+3 F+2, val(w) = k_w+3, a and b +1; exact undo",
            tri_vertex_split
        ),
        Property::new(
            "tri-edge-split",
            "edge split: V+1 E+3 F+2 inside (E+2 F+1 on the boundary), apexes +1; exact undo",
            tri_edge_split
        ),
    ]
}

/// A property for an editing operator of your own: at 16 sites per case (the darts of
/// [`Case::sites`]), `apply(map, dart)` either refuses and leaves the map `==` to before, or
/// returns a record after which the map passes [`Map::check`] and whose
/// [`Undo::undo`] restores the map exactly (`==`, free lists included). `degree`: the face
/// degree the operator works on (cases without such a face are skipped), or 0 for any.
/// A failure's focus is the origin of the site's dart, so shrinking keeps the faces there.
///
/// ```
/// use zipmesh::campaign::{self, undo_property, Config};
/// use zipmesh::ops::tri;
/// // The kernel's own triangle flip passes; plug in your operator the same way.
/// let p = undo_property("my-flip", 3, |map, d| tri::flip_edge(map, d));
/// let report = campaign::run(&Config { cases: 10, max_faces: 300, ..Config::default() }, &[p]);
/// assert!(report.passed());
/// assert!(report.rows[0].checks > 0);
/// ```
pub fn undo_property<R, E, F>(name: impl Into<String>, degree: usize, apply: F) -> Property
where
    R: Undo + 'static,
    F: Fn(&mut Map, Dart) -> Result<R, E> + Send + Sync + 'static,
{
    let name = name.into();
    let about = format!(
        "{name}: a refusal changes nothing; an application passes check() and undo restores the map exactly"
    );
    Property::new(name, about, move |case| {
        at_sites(
            case,
            0x7573_6572,
            degree,
            |before, work, d, _| match apply(work, d) {
                Err(_) if work == before => Ok(false),
                Err(_) => Err("refused but changed the map".to_string()),
                Ok(record) => settle::<_, Refusal>(before, work, Ok(()), Ok(record), |_, _| Ok(())),
            },
        )
    })
}

// ------------------------------------------------------------------------------------
// Kernel properties.

fn validity(case: &Case) -> Outcome {
    let map = &case.mesh.map;
    if let Err(v) = map.check() {
        return Outcome::fail(format!("check() fails: {v:?}"), None);
    }
    let degrees = |d: usize| map.faces().filter(|&f| map.degree(f) == d).count();
    let faces = map.num_faces();
    let kind_ok = match case.kind() {
        Some(super::Kind::Quad) => degrees(4) == faces,
        Some(super::Kind::Triangle) => degrees(3) == faces,
        Some(super::Kind::Mixed) => degrees(3) > 0 && degrees(4) > 0,
        None => true,
    };
    if !kind_ok {
        return Outcome::fail(
            format!("a generated mesh does not have the face kind asked for ({faces} faces)"),
            None,
        );
    }
    Outcome::Pass { checks: 2 }
}

fn euler(case: &Case) -> Outcome {
    let map = &case.mesh.map;
    let v = map.vertices().count() as i64;
    let e = (map.darts().count() / 2) as i64;
    let f = map.faces().count() as i64;
    let chi = v - e + f;
    let c = Counts::of(map);
    if c.euler_characteristic != chi || euler_characteristic(map) != chi {
        return Outcome::fail(
            format!(
                "chi from counting is {chi}, Counts says {}, euler_characteristic says {}",
                c.euler_characteristic,
                euler_characteristic(map)
            ),
            None,
        );
    }
    // Summed over components, (2 - chi_c - b_c) / 2 gives 2 C - chi - B = 2 genus.
    let twice = 2 * c.components as i64 - chi - c.boundary_loops as i64;
    if twice != 2 * c.genus || twice < 0 {
        return Outcome::fail(
            format!(
                "2 C - chi - B = {twice} but the genus is {} (C = {}, B = {})",
                c.genus, c.components, c.boundary_loops
            ),
            None,
        );
    }
    if let Some((genus, holes)) = case.intended_topology() {
        if (c.genus, c.boundary_loops, c.components) != (genus as i64, holes, 1) {
            return Outcome::fail(
                format!(
                    "asked for genus {genus} with {holes} boundary loops in one piece, got genus {} with {} loops in {} components",
                    c.genus, c.boundary_loops, c.components
                ),
                None,
            );
        }
        return Outcome::Pass { checks: 3 };
    }
    Outcome::Pass { checks: 2 }
}

fn gauss_bonnet_property(case: &Case) -> Outcome {
    let map = &case.mesh.map;
    let own = MeshKind::of(map);
    for kind in [own, MeshKind::Quad, MeshKind::Triangle] {
        let gb = gauss_bonnet(map, kind);
        if !gb.holds() {
            return Outcome::fail(
                format!(
                    "{kind:?} frame: {} + {} != {}",
                    gb.vertex_sum, gb.face_sum, gb.rhs
                ),
                None,
            );
        }
        if kind == own && own != MeshKind::Mixed && gb.face_sum != 0 {
            return Outcome::fail(
                format!("pure {own:?} mesh with face term {}", gb.face_sum),
                None,
            );
        }
    }
    Outcome::Pass { checks: 3 }
}

fn canonical_relabel(case: &Case) -> Outcome {
    let map = &case.mesh.map;
    let mut rng = case.rng(0x6361_6e6f);
    let n = map.vertex_slots();
    // Extra numbers become dead vertex slots: the code must not see them.
    let n_out = n + rng.below(4);
    let mut slots: Vec<u32> = (0..n_out as u32).collect();
    shuffle(&mut slots, &mut rng);
    let mut polys: Vec<Vec<u32>> = map
        .faces()
        .map(|f| {
            let p: Vec<u32> = map
                .face_darts(f)
                .map(|d| slots[map.origin(d).index()])
                .collect();
            let r = rng.below(p.len());
            (0..p.len()).map(|k| p[(k + r) % p.len().max(1)]).collect()
        })
        .collect();
    shuffle(&mut polys, &mut rng);
    let mut relabelled = match Map::from_polygons(n_out, &polys) {
        Ok(m) => m,
        Err(e) => return Outcome::fail(format!("the renumbered polygons do not build: {e}"), None),
    };
    // Each code of a case of millions of faces takes a second or more: the deadline is
    // read between them.
    if case.out_of_time() {
        return Outcome::Pass { checks: 0 };
    }
    let code = CanonicalCode::of(map);
    if case.out_of_time() {
        return Outcome::Pass { checks: 0 };
    }
    if CanonicalCode::of(&relabelled) != code {
        return Outcome::fail("the canonical code changed under renumbering", None);
    }
    if case.out_of_time() {
        return Outcome::Pass { checks: 1 };
    }
    relabelled.compact();
    if relabelled.check().is_err() || relabelled.vertex_slots() != relabelled.num_vertices() {
        return Outcome::fail("compact() left an invalid map or dead slots", None);
    }
    if CanonicalCode::of(&relabelled) != code {
        return Outcome::fail("the canonical code changed under compact()", None);
    }
    Outcome::Pass { checks: 3 }
}

fn shuffle<T>(v: &mut [T], rng: &mut Rng) {
    for i in (1..v.len()).rev() {
        v.swap(i, rng.below(i + 1));
    }
}

// ------------------------------------------------------------------------------------
// Operator properties: one harness; the expectation is each operator's `effect`.

/// One site's check: `(before, working copy, site, rng) -> applied?` or the failure.
type Attempt<'a> = dyn FnMut(&Map, &mut Map, Dart, &mut Rng) -> Result<bool, String> + 'a;

/// Sites tried per case by each operator property.
pub(super) const SITES: usize = 16;

/// Runs `attempt` at the case's sites on a working copy that must equal the case's map
/// again after every site. `degree`: the face degree the operator works on; a mesh without
/// such a face is skipped (0: never skipped).
fn at_sites(
    case: &Case,
    salt: u64,
    degree: usize,
    mut attempt: impl FnMut(&Map, &mut Map, Dart, &mut Rng) -> Result<bool, String>,
) -> Outcome {
    at_darts(
        case,
        salt,
        degree,
        case.sites_salted(SITES, salt),
        &mut attempt,
    )
}

pub(super) fn at_darts(
    case: &Case,
    salt: u64,
    degree: usize,
    sites: Vec<Dart>,
    attempt: &mut Attempt<'_>,
) -> Outcome {
    let before = &case.mesh.map;
    if degree != 0 && !before.faces().any(|f| before.degree(f) == degree) {
        return Outcome::Skip;
    }
    let mut work = before.clone();
    let mut rng = case.rng(salt ^ 0x6172_6773);
    let mut checks = 0;
    for d in sites.into_iter().take_while(|_| !case.out_of_time()) {
        match attempt(before, &mut work, d, &mut rng) {
            Ok(applied) => checks += u64::from(applied),
            Err(msg) => {
                return Outcome::fail(
                    format!(
                        "at dart {} (vertex {}): {msg}",
                        d.index(),
                        before.origin(d).index()
                    ),
                    Some(before.origin(d)),
                )
            }
        }
    }
    Outcome::Pass { checks }
}

/// The common contract: `can` and the operator agree; a refusal leaves the map as it was;
/// an application gives a valid map meeting `expect` (given the map after and the record),
/// and its undo restores `before`.
pub(super) fn settle<R: Undo, E: PartialEq + fmt::Display>(
    before: &Map,
    work: &mut Map,
    can: Result<(), E>,
    result: Result<R, E>,
    expect: impl FnOnce(&Map, &R) -> Result<(), String>,
) -> Result<bool, String> {
    match (can, result) {
        (Err(a), Err(b)) if a == b => {
            if work == before {
                Ok(false)
            } else {
                Err(format!("refused ({a}) but changed the map"))
            }
        }
        (Err(a), Err(b)) => Err(format!(
            "can_* refuses with \"{a}\", the operator with \"{b}\""
        )),
        (Err(a), Ok(_)) => Err(format!("can_* refuses (\"{a}\") but the operator applied")),
        (Ok(()), Err(b)) => Err(format!("can_* accepts but the operator refuses (\"{b}\")")),
        (Ok(()), Ok(record)) => {
            work.check()
                .map_err(|v| format!("the result fails check(): {v:?}"))?;
            expect(work, &record)?;
            record
                .undo(work)
                .map_err(|r| format!("undo refused: {r}"))?;
            if work != before {
                return Err("undo did not restore the map exactly".to_string());
            }
            Ok(true)
        }
    }
}

/// An operator at one site, checked against its documented effect ([`quad::QuadOp::effect`],
/// [`tri::TriOp::effect`], computed on `before`): `effect` is also the `can_*` answer (it is
/// the check's refusal where the operator does not apply); `more` checks what else the
/// property promises.
fn documented<R: Undo + VertexChanges>(
    before: &Map,
    work: &mut Map,
    effect: Result<Effect, Refusal>,
    apply: impl FnOnce(&mut Map) -> Result<R, Refusal>,
    more: impl FnOnce(&Map, &R) -> Result<(), String>,
) -> Result<bool, String> {
    let can = effect.as_ref().map(|_| ()).map_err(|r| *r);
    let result = apply(work);
    settle(before, work, can, result, |after, record| {
        let effect = effect.map_err(|r| r.to_string())?;
        effect
            .check(before, after, record)
            .map_err(|e| e.to_string())?;
        more(after, record)
    })
}

/// A quad operator at one site, with nothing to check beyond its effect.
fn quad_op(before: &Map, work: &mut Map, op: QuadOp) -> Result<bool, String> {
    documented(before, work, op.effect(work), |m| op.apply(m), nothing)
}

/// A triangle operator at one site, with nothing to check beyond its effect.
fn tri_op(before: &Map, work: &mut Map, op: TriOp) -> Result<bool, String> {
    documented(before, work, op.effect(work), |m| op.apply(m), nothing)
}

fn nothing<R>(_: &Map, _: &R) -> Result<(), String> {
    Ok(())
}

/// A random dart around the origin of `d` other than `d`, the second separator of a vertex
/// split; `None` below valence 2.
fn other_dart(map: &Map, d: Dart, rng: &mut Rng) -> Option<Dart> {
    let val = map.valence(map.origin(d));
    (val >= 2).then(|| cw(map, d, 1 + rng.below(val - 1)))
}

/// The dart `k` steps clockwise from `d` around its origin.
fn cw(map: &Map, d: Dart, k: usize) -> Dart {
    (0..k).fold(d, |x, _| map.rotate_cw(x))
}

fn collapse_quad(case: &Case) -> Outcome {
    at_sites(case, 1, 4, |before, work, d, _| {
        quad_op(before, work, QuadOp::Collapse(d))
    })
}

fn quad_vertex_split(case: &Case) -> Outcome {
    at_sites(case, 2, 4, |before, work, s1, rng| {
        match other_dart(before, s1, rng) {
            Some(s2) => quad_op(before, work, QuadOp::Split(s1, s2)),
            None => Ok(false),
        }
    })
}

fn quad_high_valence_split(case: &Case) -> Outcome {
    let map = &case.mesh.map;
    // Random darts rarely leave a vertex of valence 6 or more: pick those vertices directly.
    let high: Vec<Vert> = map
        .vertices()
        .filter(|&v| map.valence(v) >= quad::MIN_HIGH_VALENCE)
        .collect();
    if high.is_empty() && case.focus.is_none() {
        return Outcome::Skip;
    }
    let mut rng = case.rng(3);
    let mut sites = case.sites_salted(if case.focus.is_some() { SITES / 2 } else { 0 }, 3);
    sites.retain(|&d| map.origin(d) == case.focus.unwrap_or(Vert::new(u32::MAX)));
    for _ in (0..SITES / 2).take_while(|_| !case.out_of_time()) {
        if high.is_empty() {
            break;
        }
        let v = high[rng.below(high.len())];
        let k = rng.below(map.valence(v));
        sites.push(cw(map, map.vertex_dart(v), k));
    }
    at_darts(case, 3, 4, sites, &mut |before, work, first, _| {
        quad_op(before, work, QuadOp::HighValence(first))
    })
}

fn quad_doublet(case: &Case) -> Outcome {
    // The code of the case's map, computed at the first application only.
    let mut code_before: Option<CanonicalCode> = None;
    at_sites(case, 4, 4, |before, work, d, _| {
        let op = QuadOp::InsertDoublet(d);
        documented(
            before,
            work,
            op.effect(work),
            |m| op.apply(m),
            |m, record| {
                let v = record.created_vertex().ok_or("no new vertex")?;
                // The removal of the new vertex is the inverse, up to handles: check it on a copy.
                let refused =
                    |r: Refusal| format!("removing the new valence-2 vertex is refused: {r}");
                let remove = QuadOp::RemoveValence2(m.vertex_dart(v));
                let effect = remove.effect(m).map_err(refused)?;
                let mut removed = m.clone();
                let rec = remove.apply(&mut removed).map_err(refused)?;
                removed
                    .check()
                    .map_err(|e| format!("after the removal, check() fails: {e:?}"))?;
                effect
                    .check(m, &removed, &rec)
                    .map_err(|e| format!("the removal: {e}"))?;
                let code = code_before.get_or_insert_with(|| CanonicalCode::of(before));
                if CanonicalCode::of(&removed) != *code {
                    return Err("removing the doublet does not give back an isomorphic map".into());
                }
                rec.undo(&mut removed)
                    .map_err(|r| format!("undo of the removal refused: {r}"))?;
                if removed != *m {
                    return Err("undo of the removal did not restore the map exactly".into());
                }
                Ok(())
            },
        )
    })
}

fn quad_rotate(case: &Case) -> Outcome {
    at_sites(case, 5, 4, |before, work, h, rng| {
        let dir = if rng.below(2) == 0 {
            quad::Rotation::Clockwise
        } else {
            quad::Rotation::CounterClockwise
        };
        quad_op(before, work, QuadOp::Rotate(h, dir))
    })
}

fn tri_flip(case: &Case) -> Outcome {
    at_sites(case, 6, 3, |before, work, h, _| {
        tri_op(before, work, TriOp::Flip(h))
    })
}

fn tri_collapse(case: &Case) -> Outcome {
    at_sites(case, 7, 3, |before, work, h, _| {
        tri_op(before, work, TriOp::Collapse(h))
    })
}

fn tri_vertex_split(case: &Case) -> Outcome {
    at_sites(case, 8, 3, |before, work, d1, rng| {
        match other_dart(before, d1, rng) {
            Some(d2) => tri_op(before, work, TriOp::SplitVertex(d1, d2)),
            None => Ok(false),
        }
    })
}

fn tri_edge_split(case: &Case) -> Outcome {
    at_sites(case, 9, 3, |before, work, h, _| {
        tri_op(before, work, TriOp::SplitEdge(h))
    })
}

// ------------------------------------------------------------------------------------
// Quad-dominant properties.

fn qd_walk(case: &Case) -> Outcome {
    use crate::quad_dominant::{self, Move};
    let m0 = &case.mesh.map;
    if !m0.faces().any(|f| m0.degree(f) == 4) {
        return Outcome::Skip;
    }
    let mut rng = Rng::new(case.seed ^ case.index.rotate_left(17) ^ 0x7472_6977);
    let mut map = if quad_dominant::triangles(m0).is_empty() {
        crate::gen::with_triangle_pairs(case.mesh.clone(), 2, 4, rng.next_u64())
            .0
            .map
    } else {
        m0.clone()
    };
    let mut tips: Vec<Dart> = quad_dominant::triangles(&map)
        .into_iter()
        .map(|f| quad_dominant::default_tip(&map, f).unwrap_or(map.face_dart(f)))
        .collect();
    if tips.is_empty() {
        return Outcome::Skip;
    }
    let start = map.clone();
    let mut done = Vec::new();
    let mut checks = 0;
    for _ in 0..16 {
        let (i, mv) = (rng.below(tips.len()), Move::ALL[rng.below(4)]);
        let t = tips[i];
        let before = map.clone();
        let can = quad_dominant::can_move_triangle(&map, t, mv);
        let effect = mv.effect(&map, t);
        let focus = Some(map.origin(t));
        match quad_dominant::move_triangle(&mut map, t, mv) {
            Err(r) if can == Err(r) && map == before => {}
            Err(r) => {
                return Outcome::fail(
                    format!("{mv} refused ({r}) against can {can:?}, or changed the map"),
                    focus,
                )
            }
            Ok(rec) => {
                if let Err(v) = map.check() {
                    return Outcome::fail(format!("{mv} left an invalid map: {v:?}"), focus);
                }
                match effect.map(|e| e.check(&before, &map, &rec)) {
                    Ok(Ok(())) => {}
                    other => {
                        return Outcome::fail(
                            format!("{mv}: not its documented effect: {other:?}"),
                            focus,
                        )
                    }
                }
                for x in &mut tips {
                    *x = rec.follow(*x);
                }
                tips[i] = rec.tip();
                done.push(rec);
                checks += 1;
            }
        }
    }
    for rec in done.iter().rev() {
        if rec.undo(&mut map).is_err() {
            return Outcome::fail("an undo in reverse order was refused", None);
        }
    }
    if map != start {
        return Outcome::fail("undoing every move did not restore the map exactly", None);
    }
    Outcome::Pass { checks }
}
