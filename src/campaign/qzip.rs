//! The Q-zip properties: grid preservation, reversal, homotopy invariance and the four
//! movements, checked on the singularity pairs of quad cases.

use std::borrow::Cow;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use super::{Case, Outcome, Property};
use crate::invariants::canonical::CanonicalCode;
use crate::invariants::{is_regular_interior, MeshKind};
use crate::qzip::{
    find_reverse, one_quad_sweeps, sketch, start_turn, verify_edit, Path, Qzip, ReverseWay,
    SketchOptions, Tag,
};
use crate::{quad_dominant, Map, Vert};

/// How a Q-zip property picks its pairs.
///
/// ```
/// use zipmesh::campaign::PairChoice;
/// let p = PairChoice::default();
/// assert_eq!((p.max_distance, p.per_case), (12, Some(4)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PairChoice {
    /// Pairs whose shortest path is longer than this are not tried.
    pub max_distance: usize,
    /// `Some(n)`: n pairs drawn from the case's random stream, each a random singularity and
    /// a random partner among those within `max_distance` edges of it (generated campaigns,
    /// `zipmesh check FILE --pairs n`); `None`: every ordered pair within `max_distance`
    /// (`zipmesh check FILE`).
    pub per_case: Option<usize>,
}

impl Default for PairChoice {
    fn default() -> Self {
        PairChoice {
            max_distance: 12,
            per_case: Some(4),
        }
    }
}

/// The interior irregular vertices of a pure-quad map, or `None` if it is not pure quad.
fn singularities(map: &Map) -> Option<Vec<Vert>> {
    if map.num_faces() == 0 || map.faces().any(|f| map.degree(f) != 4) {
        return None;
    }
    Some(
        map.vertices()
            .filter(|&v| !map.is_boundary_vertex(v) && map.valence(v) != 4)
            .collect(),
    )
}

/// What a Q-zip property runs on: a map, its singularities (the path ends to draw from) and
/// the sketch options; on a quad-dominant subject ([`super::qzip_quad_dominant`]) also the vertices
/// within one edge of a triangle, which no path may visit.
pub(super) struct Subject<'c> {
    pub map: Cow<'c, Map>,
    pub sing: Vec<Vert>,
    pub opts: SketchOptions<'static>,
    pub near: Option<Vec<Vert>>,
}

impl<'c> Subject<'c> {
    /// A pure-quad case as it is.
    fn quad(case: &'c Case) -> Option<Subject<'c>> {
        let map = &case.mesh.map;
        Some(Subject {
            sing: singularities(map)?,
            map: Cow::Borrowed(map),
            opts: SketchOptions::default(),
            near: None,
        })
    }

    /// Whether a path keeps away from the triangles (always on a pure-quad subject).
    pub(super) fn allows(&self, p: &Path) -> bool {
        self.near
            .as_ref()
            .is_none_or(|n| p.vertices().iter().all(|v| n.binary_search(v).is_err()))
    }
}

/// The pairs to try on a subject, each with its shortest path.
fn pairs(case: &Case, s: &Subject<'_>, choice: PairChoice, salt: u64) -> Option<Vec<Path>> {
    let (map, sing) = (&*s.map, &s.sing);
    if sing.len() < 2 {
        return None;
    }
    let fits = |a: Vert, b: Vert| {
        sketch(map, a, b, &s.opts)
            .ok()
            .filter(|p| p.len() <= choice.max_distance)
    };
    let mut out = Vec::new();
    match choice.per_case {
        None => {
            for &a in sing.iter().take_while(|_| !case.out_of_time()) {
                for &b in sing {
                    if a != b {
                        out.extend(fits(a, b));
                    }
                }
            }
        }
        Some(n) => {
            let mut rng = case.rng(salt);
            // A focused replay tries pairs from the focus first.
            let first = case.focus.filter(|v| sing.contains(v));
            for k in 0..4 * n {
                if out.len() >= n {
                    break;
                }
                let a = match first {
                    Some(f) if k < n => f,
                    _ => sing[rng.below(sing.len())],
                };
                let near = within(map, sing, a, choice.max_distance);
                let b = match near.len() {
                    0 => sing[rng.below(sing.len())],
                    len => near[rng.below(len)],
                };
                if a != b {
                    out.extend(fits(a, b));
                }
            }
        }
    }
    (!out.is_empty()).then_some(out)
}

/// The singularities other than `a` within `radius` edges of it (breadth-first over the
/// edges, so a superset of those whose sketch fits): drawing the partner among them keeps a
/// sample's pairs within reach on a large mesh, where two random singularities are rarely
/// `radius` edges apart. `sing` is in vertex order.
fn within(map: &Map, sing: &[Vert], a: Vert, radius: usize) -> Vec<Vert> {
    let mut out = super::near(map, a, radius, |w| sing.binary_search(&w).is_ok());
    out.sort_unstable();
    out
}

/// One movement checked for grid preservation and exact undo: `Ok(Some(edited))` if done,
/// `Ok(None)` if refused cleanly, `Err` if a promise is broken.
pub(super) fn checked_zip(
    s: &Subject<'_>,
    path: &Path,
    tag: Tag,
) -> Result<Option<(Map, crate::qzip::ZipReport)>, String> {
    let map = &*s.map;
    let mut m = map.clone();
    let r = match Qzip::new().zip_along(&mut m, path, tag) {
        Ok(r) => r.into_record(),
        Err(_) if &m == map => return Ok(None),
        Err(e) => return Err(format!("{tag} refused ({e}) but changed the map")),
    };
    if let Err(b) = verify_edit(map, &m, path, &r) {
        return Err(format!(
            "{tag} from {} to {}: {b}",
            path.start().index(),
            path.end().index()
        ));
    }
    if s.near.is_some() {
        triangles_kept(map, &m).map_err(|e| format!("{tag}: {e}"))?;
    }
    Ok(Some((m, r)))
}

fn grid(case: &Case, choice: PairChoice) -> Outcome {
    Subject::quad(case).map_or(Outcome::Skip, |s| grid_on(case, &s, choice))
}

pub(super) fn grid_on(case: &Case, s: &Subject<'_>, choice: PairChoice) -> Outcome {
    let Some(paths) = pairs(case, s, choice, 0x717a_6772) else {
        return Outcome::Skip;
    };
    let mut checks = 0;
    for path in paths.iter().take_while(|_| !case.out_of_time()) {
        for tag in Tag::CCW {
            match checked_zip(s, path, tag) {
                Ok(_) => checks += 1,
                Err(e) => return Outcome::fail(e, Some(path.start())),
            }
        }
    }
    Outcome::Pass { checks }
}

fn reversal(case: &Case, choice: PairChoice) -> Outcome {
    Subject::quad(case).map_or(Outcome::Skip, |s| reversal_on(case, &s, choice))
}

pub(super) fn reversal_on(case: &Case, s: &Subject<'_>, choice: PairChoice) -> Outcome {
    let Some(paths) = pairs(case, s, choice, 0x717a_7276) else {
        return Outcome::Skip;
    };
    let map = &*s.map;
    let code = CanonicalCode::of(map);
    let (mut checks, mut missed) = (0, 0);
    for path in paths.iter().take_while(|_| !case.out_of_time()) {
        for tag in Tag::CCW {
            let edited = match checked_zip(s, path, tag) {
                Ok(Some(x)) => x,
                Ok(None) => continue,
                Err(e) => return Outcome::fail(e, Some(path.start())),
            };
            let (m, r) = edited;
            // A run found is re-executed independently. A movement with no restoring run
            // is reported as unchecked, not failed: the search is known to miss some
            // (docs/qzip.md), and some edits have no single restoring Q-zip at all.
            let Some(back) = find_reverse(&m, &r, map) else {
                missed += 1;
                case.note_unchecked(1);
                continue;
            };
            let mut again = m.clone();
            let ok = Qzip::new()
                .zip_along(&mut again, &back.path, back.tag)
                .is_ok()
                && CanonicalCode::of(&again) == code;
            if !ok {
                return Outcome::fail(
                    format!("the reverse run {} of {tag} does not restore", back.tag),
                    Some(path.start()),
                );
            }
            if back.way == ReverseWay::Searched {
                case.note_searched(1);
            }
            checks += 1;
        }
    }
    // A case whose movements all missed applied (its misses are in the row), checking none.
    if missed > 0 {
        Outcome::Pass { checks }
    } else {
        tally(checks)
    }
}

/// Pass with the number of checks made, or Skip if the property found nothing to check.
fn tally(checks: u64) -> Outcome {
    if checks == 0 {
        Outcome::Skip
    } else {
        Outcome::Pass { checks }
    }
}

fn outcomes(map: &Map, p: &Path) -> [Option<CanonicalCode>; 4] {
    Tag::CCW.map(|t| {
        let mut m = map.clone();
        Qzip::new()
            .zip_along(&mut m, p, t)
            .ok()
            .map(|_| CanonicalCode::of(&m))
    })
}

fn homotopy(case: &Case, choice: PairChoice) -> Outcome {
    Subject::quad(case).map_or(Outcome::Skip, |s| homotopy_on(case, &s, choice))
}

pub(super) fn homotopy_on(case: &Case, s: &Subject<'_>, choice: PairChoice) -> Outcome {
    let choice = PairChoice {
        max_distance: choice.max_distance.min(8),
        ..choice
    };
    let Some(paths) = pairs(case, s, choice, 0x717a_686f) else {
        return Outcome::Skip;
    };
    let map = &*s.map;
    let mut checks = 0;
    for p in paths.iter().take_while(|_| !case.out_of_time()) {
        let h0 = outcomes(map, p);
        for (_, q) in one_quad_sweeps(map, p).into_iter().take(4) {
            // A sweep next to a triangle leaves the region the sketch keeps to (counted).
            if !s.allows(&q) {
                case.note_unchecked(1);
                continue;
            }
            let Some(k) = start_turn(map, p, &q) else {
                return Outcome::fail("the swept path does not share the start", None);
            };
            let h1 = outcomes(map, &q);
            for (j, tag) in Tag::CCW.into_iter().enumerate() {
                let jq = Tag::CCW
                    .iter()
                    .position(|&u| u == tag.turned(k))
                    .unwrap_or(j);
                if let (Some(x), Some(y)) = (&h0[j], &h1[jq]) {
                    if x != y {
                        return Outcome::fail(
                            format!(
                                "movement {tag} differs along two homotopic paths from {} to {}",
                                p.start().index(),
                                p.end().index()
                            ),
                            Some(p.start()),
                        );
                    }
                    checks += 1;
                }
            }
        }
    }
    tally(checks)
}

/// Whether the pair sits in a regular region: at least three edges apart, and every vertex
/// within two edges of the path regular, the two ends excepted.
fn in_regular_region(map: &Map, p: &Path) -> bool {
    let ok =
        |y: Vert| y == p.start() || y == p.end() || is_regular_interior(map, MeshKind::Quad, y);
    p.len() >= 3
        && p.vertices().iter().all(|&x| {
            map.vertex_darts(x).all(|d| {
                let y = map.dest(d);
                ok(y) && map.vertex_darts(y).all(|e| ok(map.dest(e)))
            })
        })
}

fn four_moves(case: &Case, choice: PairChoice) -> Outcome {
    let Some(s) = Subject::quad(case) else {
        return Outcome::Skip;
    };
    let Some(paths) = pairs(case, &s, choice, 0x717a_666d) else {
        return Outcome::Skip;
    };
    let map = &*s.map;
    let mut checks = 0;
    for p in paths
        .iter()
        .filter(|p| !case.out_of_time() && in_regular_region(map, p))
    {
        let codes = outcomes(map, p);
        let done: Vec<&CanonicalCode> = codes.iter().flatten().collect();
        for i in 0..done.len() {
            for j in 0..i {
                if done[i] == done[j] {
                    return Outcome::fail(
                        format!(
                            "two movements of the pair {}-{} give isomorphic maps",
                            p.start().index(),
                            p.end().index()
                        ),
                        Some(p.start()),
                    );
                }
            }
        }
        checks += 1;
    }
    tally(checks)
}

/// A property of a Q-zip check: its name, what it states, and the check with a pair choice.
pub(super) type PairCheck = (&'static str, &'static str, fn(&Case, PairChoice) -> Outcome);

/// The properties of `table`, each checking with `choice`.
pub(super) fn with_choice(table: &[PairCheck], choice: PairChoice) -> Vec<Property> {
    let property = |&(name, about, check): &PairCheck| {
        Property::new(name, about.to_string(), move |c| check(c, choice))
    };
    table.iter().map(property).collect()
}

/// The Q-zip properties of quad cases (`qzip-grid` to `qzip-four-moves`), in order.
#[rustfmt::skip]
pub(super) fn quad_properties(choice: PairChoice) -> Vec<Property> {
    with_choice(&[
        ("qzip-grid", "a Q-zip done keeps the grid (valid, pure quad, chi, boundary, irregular valences) and undoes exactly; a refusal changes nothing", grid),
        ("qzip-reversal", "the reverse Q-zip found from the moved terminal back to the moved initial singularity restores the original up to isomorphism", reversal),
        ("qzip-homotopy", "along paths one swept regular quad apart, each movement gives the same map (labels matched by the turn at the start)", homotopy),
        ("qzip-four-moves", "for a pair in a regular region, the movements done give pairwise non-isomorphic maps", four_moves),
    ], choice)
}

/// The triangles of `map`, each with its sorted corner valences.
fn corner_valences(map: &Map) -> Vec<(crate::Face, [usize; 3])> {
    quad_dominant::triangles(map)
        .into_iter()
        .map(|f| {
            let mut v = [0; 3];
            for (x, d) in v.iter_mut().zip(map.face_darts(f)) {
                *x = map.valence(map.origin(d));
            }
            v.sort_unstable();
            (f, v)
        })
        .collect()
}

/// Whether every triangle of `before` is still a triangle of `after` (same face handle)
/// with the same corner valences, and there are no others.
pub(super) fn triangles_kept(before: &Map, after: &Map) -> Result<(), String> {
    let (b, a) = (corner_valences(before), corner_valences(after));
    if a == b {
        return Ok(());
    }
    // Only the triangles that differ: a real mesh has dozens that do not.
    let changed: Vec<String> = b
        .iter()
        .filter(|t| !a.contains(t))
        .map(|&(f, v)| match a.iter().find(|&&(g, _)| g == f) {
            Some((_, w)) => format!("{f:?} {v:?} -> {w:?}"),
            None => format!("{f:?} {v:?} -> gone"),
        })
        .chain(
            a.iter()
                .filter(|&&(f, _)| !b.iter().any(|&(g, _)| g == f))
                .map(|(f, w)| format!("{f:?} new {w:?}")),
        )
        .collect();
    Err(format!(
        "the triangles changed (corner valences): {}",
        changed.join(", ")
    ))
}
