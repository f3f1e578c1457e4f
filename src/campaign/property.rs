//! Properties: a name and a check of one [`Case`]; the built-in kernel and operator ones.

use super::case::Case;
use crate::invariants::canonical::CanonicalCode;
use crate::invariants::{euler_characteristic, gauss_bonnet, Counts, MeshKind};
use crate::map::{Dart, Map, Vert};
use crate::ops::{quad, tri, Refusal, Undo};
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

/// Every built-in property: [`kernel`], [`operators`], then the Q-zip properties
/// ([`qzip_properties`](super::qzip_properties) with the default [`PairChoice`](super::PairChoice)).
///
/// ```
/// let names: Vec<String> = zipmesh::campaign::builtin().iter().map(|p| p.name().to_string()).collect();
/// assert!(names.contains(&"gauss-bonnet".to_string()));
/// assert!(names.contains(&"tri-flip".to_string()));
/// ```
pub fn builtin() -> Vec<Property> {
    let mut all = kernel();
    all.extend(operators());
    all.extend(super::qzip_properties(super::PairChoice::default()));
    all
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
                Ok(record) => settle(before, work, Ok(()), Ok(record), |_| Ok(())),
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
    let code = CanonicalCode::of(map);
    if CanonicalCode::of(&relabelled) != code {
        return Outcome::fail("the canonical code changed under renumbering", None);
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
// Operator properties: one harness, one expectation per operator.

/// One site's check: `(before, working copy, site, rng) -> applied?` or the failure.
type Attempt<'a> = dyn FnMut(&Map, &mut Map, Dart, &mut Rng) -> Result<bool, String> + 'a;

/// Sites tried per case by each operator property.
const SITES: usize = 16;

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

fn at_darts(
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
/// an application gives a valid map meeting `expect`, and its undo restores `before`.
fn settle<R: Undo>(
    before: &Map,
    work: &mut Map,
    can: Result<(), Refusal>,
    result: Result<R, Refusal>,
    expect: impl FnOnce(&Map) -> Result<(), String>,
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
            expect(work)?;
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

/// `(V, E, F)` of `map`.
fn vef(map: &Map) -> [i64; 3] {
    [
        map.num_vertices() as i64,
        map.num_edges() as i64,
        map.num_faces() as i64,
    ]
}

fn deltas(before: [i64; 3], after: &Map, want: [i64; 3]) -> Result<(), String> {
    let now = vef(after);
    let got = [now[0] - before[0], now[1] - before[1], now[2] - before[2]];
    if got == want {
        Ok(())
    } else {
        Err(format!("(V, E, F) changed by {got:?}, documented {want:?}"))
    }
}

fn valence_is(map: &Map, v: Vert, want: usize, what: &str) -> Result<(), String> {
    let got = map.valence(v);
    if got == want {
        Ok(())
    } else {
        Err(format!(
            "{what} (vertex {}) has valence {got}, documented {want}",
            v.index()
        ))
    }
}

/// The dart `k` steps clockwise from `d` around its origin.
fn cw(map: &Map, d: Dart, k: usize) -> Dart {
    (0..k).fold(d, |x, _| map.rotate_cw(x))
}

fn collapse_quad(case: &Case) -> Outcome {
    at_sites(case, 1, 4, |before, work, d, _| {
        let (a, b) = (before.origin(d), before.dest(d));
        let h2 = before.next(before.next(d));
        let (c, dd) = (before.origin(h2), before.dest(h2));
        let (va, vb, vc, vd) = (
            before.valence(a),
            before.valence(b),
            before.valence(c),
            before.valence(dd),
        );
        let counts = vef(before);
        let can = quad::can_collapse_quad(work, d);
        let res = quad::collapse_quad(work, d);
        settle(before, work, can, res, |m| {
            deltas(counts, m, [-1, -2, -1])?;
            valence_is(m, a, (va + vc).saturating_sub(2), "the merged vertex")?;
            valence_is(m, b, vb.saturating_sub(1), "corner b")?;
            valence_is(m, dd, vd.saturating_sub(1), "corner d")
        })
    })
}

fn quad_vertex_split(case: &Case) -> Outcome {
    at_sites(case, 2, 4, |before, work, s1, rng| {
        let w = before.origin(s1);
        let val = before.valence(w);
        if val < 2 {
            return Ok(false);
        }
        let k = 1 + rng.below(val - 1);
        let s2 = cw(before, s1, k);
        let (a, b) = (before.dest(s1), before.dest(s2));
        let (va, vb) = (before.valence(a), before.valence(b));
        let counts = vef(before);
        let can = quad::can_split_vertex(work, s1, s2);
        let res = quad::split_vertex(work, s1, s2);
        settle(before, work, can, res, |m| {
            deltas(counts, m, [1, 2, 1])?;
            valence_is(m, w, k + 1, "the split vertex")?;
            if a != b {
                valence_is(m, a, va + 1, "end a")?;
                valence_is(m, b, vb + 1, "end b")?;
            }
            Ok(())
        })
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
        let v = before.origin(first);
        let k = before.valence(v);
        let other = cw(before, first, k / 2);
        let (a, b) = (before.dest(first), before.dest(other));
        let (va, vb) = (before.valence(a), before.valence(b));
        let counts = vef(before);
        let can = quad::can_split_high_valence(work, v, first);
        let res = quad::split_high_valence(work, v, first);
        settle(before, work, can, res, |m| {
            deltas(counts, m, [1, 2, 1])?;
            valence_is(m, v, k / 2 + 1, "the split vertex")?;
            if a != b {
                valence_is(m, a, va + 1, "end a")?;
                valence_is(m, b, vb + 1, "end b")?;
            }
            Ok(())
        })
    })
}

fn quad_doublet(case: &Case) -> Outcome {
    // The code of the case's map, computed at the first application only.
    let mut code_before: Option<CanonicalCode> = None;
    at_sites(case, 4, 4, |before, work, d, _| {
        let p = before.origin(d);
        let q = before.origin(before.next(before.next(d)));
        let (vp, vq) = (before.valence(p), before.valence(q));
        let counts = vef(before);
        let can = quad::can_insert_doublet(work, d);
        let res = quad::insert_doublet(work, d);
        let created = res.as_ref().ok().map(|r| r.vertex());
        settle(before, work, can, res, |m| {
            deltas(counts, m, [1, 2, 1])?;
            valence_is(m, p, vp + 1, "diagonal end p")?;
            valence_is(m, q, vq + 1, "diagonal end q")?;
            let v = created.ok_or("no new vertex")?;
            valence_is(m, v, 2, "the new vertex")?;
            // The removal of the new vertex is the inverse, up to handles: check it on a copy.
            let mut removed = m.clone();
            let x = removed.vertex_dart(v);
            let rec = quad::remove_valence2(&mut removed, x)
                .map_err(|r| format!("removing the new valence-2 vertex is refused: {r}"))?;
            removed
                .check()
                .map_err(|e| format!("after the removal, check() fails: {e:?}"))?;
            deltas(counts, &removed, [0, 0, 0])?;
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
        })
    })
}

fn quad_rotate(case: &Case) -> Outcome {
    at_sites(case, 5, 4, |before, work, h, rng| {
        let dir = if rng.below(2) == 0 {
            quad::Rotation::Clockwise
        } else {
            quad::Rotation::CounterClockwise
        };
        let (u, v) = (before.origin(h), before.dest(h));
        let (vu, vv) = (before.valence(u), before.valence(v));
        let counts = vef(before);
        let can = quad::can_rotate_edge(work, h, dir);
        let res = quad::rotate_edge(work, h, dir);
        settle(before, work, can, res, |m| {
            deltas(counts, m, [0, 0, 0])?;
            valence_is(m, u, vu.saturating_sub(1), "old end u")?;
            valence_is(m, v, vv.saturating_sub(1), "old end v")?;
            let (x, y) = (m.origin(h), m.dest(h));
            valence_is(m, x, before.valence(x) + 1, "new end")?;
            valence_is(m, y, before.valence(y) + 1, "new end")
        })
    })
}

fn tri_flip(case: &Case) -> Outcome {
    at_sites(case, 6, 3, |before, work, h, _| {
        let (a, b) = (before.origin(h), before.dest(h));
        let c = before.origin(before.next(before.next(h)));
        let t = h.twin();
        let d = before.origin(before.next(before.next(t)));
        let vals: Vec<usize> = [a, b, c, d].iter().map(|&x| before.valence(x)).collect();
        let counts = vef(before);
        let can = tri::can_flip_edge(work, h);
        let res = tri::flip_edge(work, h);
        settle(before, work, can, res, |m| {
            deltas(counts, m, [0, 0, 0])?;
            valence_is(m, a, vals[0].saturating_sub(1), "end a")?;
            valence_is(m, b, vals[1].saturating_sub(1), "end b")?;
            valence_is(m, c, vals[2] + 1, "apex c")?;
            valence_is(m, d, vals[3] + 1, "apex d")
        })
    })
}

fn tri_collapse(case: &Case) -> Outcome {
    at_sites(case, 7, 3, |before, work, h, _| {
        let (v, u) = (before.origin(h), before.dest(h));
        let t = h.twin();
        let apex = |x: Dart| {
            before
                .face(x)
                .map(|_| before.origin(before.next(before.next(x))))
        };
        let (c, d) = (apex(h), apex(t));
        let interior = c.is_some() && d.is_some();
        let (vu, vv) = (before.valence(u), before.valence(v));
        let vc = c.map(|x| before.valence(x));
        let vd = d.map(|x| before.valence(x));
        let counts = vef(before);
        let can = tri::can_collapse_edge(work, h);
        let res = tri::collapse_edge(work, h);
        settle(before, work, can, res, |m| {
            if interior {
                deltas(counts, m, [-1, -3, -2])?;
                valence_is(m, u, (vu + vv).saturating_sub(4), "the kept vertex u")?;
            } else {
                deltas(counts, m, [-1, -2, -1])?;
                valence_is(m, u, (vu + vv).saturating_sub(3), "the kept vertex u")?;
            }
            if let (Some(c), Some(vc)) = (c, vc) {
                valence_is(m, c, vc.saturating_sub(1), "apex c")?;
            }
            if let (Some(d), Some(vd)) = (d, vd) {
                valence_is(m, d, vd.saturating_sub(1), "apex d")?;
            }
            Ok(())
        })
    })
}

fn tri_vertex_split(case: &Case) -> Outcome {
    at_sites(case, 8, 3, |before, work, d1, rng| {
        let w = before.origin(d1);
        let val = before.valence(w);
        if val < 2 {
            return Ok(false);
        }
        let k = 1 + rng.below(val - 1);
        let d2 = cw(before, d1, k);
        let (a, b) = (before.dest(d1), before.dest(d2));
        let (va, vb) = (before.valence(a), before.valence(b));
        let counts = vef(before);
        let can = tri::can_split_vertex(work, d1, d2);
        let res = tri::split_vertex(work, d1, d2);
        settle(before, work, can, res, |m| {
            deltas(counts, m, [1, 3, 2])?;
            // k_w: the darts strictly between d1 and d2 clockwise stay at w.
            valence_is(m, w, (k - 1) + 3, "the split vertex w")?;
            valence_is(m, a, va + 1, "end a")?;
            valence_is(m, b, vb + 1, "end b")
        })
    })
}

fn tri_edge_split(case: &Case) -> Outcome {
    at_sites(case, 9, 3, |before, work, h, _| {
        let (a, b) = (before.origin(h), before.dest(h));
        let t = h.twin();
        let apex = |x: Dart| {
            before
                .face(x)
                .map(|_| before.origin(before.next(before.next(x))))
        };
        let apexes: Vec<(Vert, usize)> = [apex(h), apex(t)]
            .into_iter()
            .flatten()
            .map(|x| (x, before.valence(x)))
            .collect();
        let (va, vb) = (before.valence(a), before.valence(b));
        let counts = vef(before);
        let can = tri::can_split_edge(work, h);
        let res = tri::split_edge(work, h);
        settle(before, work, can, res, |m| {
            if apexes.len() == 2 {
                deltas(counts, m, [1, 3, 2])?;
            } else {
                deltas(counts, m, [1, 2, 1])?;
            }
            valence_is(m, a, va, "end a")?;
            valence_is(m, b, vb, "end b")?;
            for &(x, vx) in &apexes {
                valence_is(m, x, vx + 1, "apex")?;
            }
            Ok(())
        })
    })
}
