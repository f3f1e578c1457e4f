//! Every map up to a bound, built by `Map::from_permutation`, against the oracle.
//!
//! Enumeration: for `n` edges the darts are `0..2n` with twin `d ^ 1`; `next` runs over all
//! `(2n)!` permutations and the boundary marks over all `2^c` markings constant on each of
//! the `c` cycles of `next`, so there are `(2n + 1)!` candidates for `n` edges (the sum of
//! `2^cycles` over a symmetric group). Every valid map on `2n` darts is among them.
//!
//! Bound: `MAX_EDGES` = 4 edges (8 darts), 368 047 candidates in all (1 + 6 + 120 + 5040 +
//! 362 880, asserted). Each candidate's acceptance is decided by the oracle; the test prints
//! the tallies (`-- --nocapture`), which were: 103 981 accepted (1, 4, 56, 1776 and 102 144
//! for 0 to 4 edges), 218 218 rejected as `FacelessEdge` and 45 848 as `PinchedBoundary`.
//! Against published enumerations it asserts the rooted maps by genus (OEIS A238396), the
//! sensed planar maps (A006384: 2, 4, 14, 57) and the reflexible maps by genus, which checks
//! the enumeration, the genus, `mirror` and the canonical code at once.

use crate::choice::{Choice, Exhaustive, Random};
use crate::oracle::{permutations, Expected, RawMap};
use std::collections::{BTreeMap, HashMap};
use zipmesh_kernel::invariants::canonical::CanonicalCode;
use zipmesh_kernel::invariants::{gauss_bonnet, Counts, Histograms, MeshKind};
use zipmesh_kernel::rng::Rng;
use zipmesh_kernel::{is_isomorphic, is_isomorphic_mirror, Dart, Map, RawError, Vert};

/// The exhaustive bound on edges (darts = 2 * edges).
pub const MAX_EDGES: usize = 4;

/// What one run of the map property saw, for the checks across all maps.
pub struct Seen {
    pub raw: RawMap,
    pub result: Result<Facts, RawError>,
}

/// Facts about an accepted map.
pub struct Facts {
    pub code: CanonicalCode,
    pub counts: Counts,
    /// The raw data of `mirror()`.
    pub mirror: RawMap,
    /// `is_isomorphic(m, m.mirror())`.
    pub self_mirror: bool,
    /// Whether the polygon round trip applied.
    pub round_trip: bool,
}

/// Property: any map with at most `max_edges` edges satisfies every property below.
pub fn any_map(c: &mut impl Choice, max_edges: usize) -> Seen {
    let n = c.any(max_edges + 1);
    let raw = RawMap::any(c, n);
    let result = map_properties(c, &raw);
    Seen { raw, result }
}

/// Builds `raw` and checks it against the oracle; panics on any violation.
pub fn map_properties(c: &mut impl Choice, raw: &RawMap) -> Result<Facts, RawError> {
    let built = Map::from_permutation(&raw.next, &raw.boundary);
    let m = match (raw.expected(), built) {
        (Expected::Ok, Ok(m)) => m,
        (Expected::OneOf(allowed), Err(e)) => {
            assert!(allowed.contains(&e), "{raw:?}: {e:?} not in {allowed:?}");
            return Err(e);
        }
        (want, got) => panic!("{raw:?}: expected {want:?}, got {got:?}"),
    };
    assert_eq!(m.check(), Ok(()), "{raw:?}");
    structure(raw, &m);
    let counts = counts(raw, &m);
    histograms_and_gauss_bonnet(raw, &m, counts.euler_characteristic);

    // compact() on a map without dead slots renumbers nothing.
    let mut compacted = m.clone();
    let cp = compacted.compact();
    assert_eq!(compacted, m);
    assert!(cp
        .darts
        .iter()
        .enumerate()
        .all(|(i, d)| *d == Some(Dart::new(i as u32))));
    assert!(cp
        .vertices
        .iter()
        .enumerate()
        .all(|(i, v)| *v == Some(Vert::new(i as u32))));
    assert_eq!(cp.faces.len(), m.num_faces());
    let code = CanonicalCode::of(&m);
    assert_eq!(CanonicalCode::of(&compacted), code);

    // A relabelling of edges and of each edge's two darts keeps the canonical code.
    let n = raw.darts() / 2;
    let perm = c.sample_permutation(n);
    let swap: Vec<bool> = (0..n).map(|_| c.sample(2) == 1).collect();
    let relabelled = Map::from_permutation(
        &raw.relabel(&perm, &swap).next,
        &raw.relabel(&perm, &swap).boundary,
    )
    .expect("a relabelled valid map is valid");
    assert_eq!(
        CanonicalCode::of(&relabelled),
        code,
        "{raw:?} under {perm:?} {swap:?}"
    );
    assert!(is_isomorphic(&m, &relabelled));

    // The mirror is valid, has the same counts, and mirrors back.
    let mirror = m.mirror();
    assert_eq!(mirror.check(), Ok(()), "mirror of {raw:?}");
    assert_eq!(Counts::of(&mirror), counts);
    assert_eq!(Histograms::of(&mirror), Histograms::of(&m));
    assert!(
        is_isomorphic(&mirror.mirror(), &m),
        "mirror twice of {raw:?}"
    );
    assert!(is_isomorphic_mirror(&m, &mirror));
    let self_mirror = is_isomorphic(&m, &mirror);

    let round_trip = polygon_round_trip(&m);
    Ok(Facts {
        code,
        counts,
        mirror: RawMap::of(&mirror),
        self_mirror,
        round_trip,
    })
}

/// Accessors agree with the raw permutations; vertices and faces are the oracle's orbits.
fn structure(raw: &RawMap, m: &Map) {
    let nd = raw.darts();
    assert_eq!((m.num_darts(), m.dart_slots()), (nd, nd));
    let (vo, nv) = raw.vertex_orbits();
    let (fo, _) = raw.face_cycles();
    let mut vert_of_orbit = vec![None; nv];
    let mut face_of_cycle = HashMap::new();
    for d in 0..nd {
        let x = Dart::new(d as u32);
        assert!(m.is_live_dart(x));
        assert_eq!(m.next(x).index(), raw.next[d] as usize);
        assert_eq!(m.is_boundary_dart(x), raw.boundary[d]);
        assert_eq!(m.face(x).is_none(), raw.boundary[d]);
        assert_eq!(m.next(m.prev(x)), x);
        assert_eq!(m.prev(m.next(x)), x);
        assert_eq!(m.rotate_cw(x), m.next(x.twin()));
        assert_eq!(m.rotate_ccw(m.rotate_cw(x)), x);
        assert_eq!(m.dest(x), m.origin(x.twin()));
        // Origins and faces name the oracle's orbits one-to-one.
        let v = *vert_of_orbit[vo[d]].get_or_insert(m.origin(x));
        assert_eq!(m.origin(x), v);
        if let Some(f) = m.face(x) {
            assert_eq!(*face_of_cycle.entry(fo[d]).or_insert(f), f);
        }
    }
    let mut names: Vec<Vert> = vert_of_orbit.into_iter().flatten().collect();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), nv, "two vertex orbits share a vertex");
    let mut fnames: Vec<_> = face_of_cycle.values().copied().collect();
    fnames.sort();
    fnames.dedup();
    assert_eq!(
        fnames.len(),
        face_of_cycle.len(),
        "two face cycles share a face"
    );
    for v in m.vertices() {
        let ds: Vec<Dart> = m.vertex_darts(v).collect();
        assert_eq!(ds.len(), m.valence(v));
        assert!(ds.iter().all(|&d| m.origin(d) == v));
        let boundary = ds.iter().filter(|&&d| m.is_boundary_dart(d)).count();
        assert!(boundary <= 1);
        assert_eq!(m.is_boundary_vertex(v), boundary == 1);
    }
    for f in m.faces() {
        assert_eq!(m.face_darts(f).count(), m.degree(f));
        assert!(m.face_darts(f).all(|d| m.face(d) == Some(f)));
    }
}

/// Counts against the oracle, with genus per component a non-negative whole number.
fn counts(raw: &RawMap, m: &Map) -> Counts {
    let nd = raw.darts();
    let (vo, nv) = raw.vertex_orbits();
    let (fo, nc) = raw.face_cycles();
    let (comp, ncomp) = raw.components();
    let mut loops = 0;
    let mut faces = 0;
    // Per component: V - E + F and boundary loops, each orbit counted at its smallest dart.
    let mut chi = vec![0i64; ncomp];
    let mut b = vec![0i64; ncomp];
    let mut first_v = vec![true; nv];
    let mut first_f = vec![true; nc];
    for d in 0..nd {
        let k = comp[d];
        if std::mem::take(&mut first_v[vo[d]]) {
            chi[k] += 1;
        }
        if d % 2 == 0 {
            chi[k] -= 1;
        }
        if std::mem::take(&mut first_f[fo[d]]) {
            if raw.boundary[d] {
                b[k] += 1;
                loops += 1;
            } else {
                chi[k] += 1;
                faces += 1;
            }
        }
    }
    let mut genus = 0;
    for k in 0..ncomp {
        let twice = 2 - chi[k] - b[k];
        assert!(
            twice >= 0 && twice % 2 == 0,
            "{raw:?}: component {k} has 2g = {twice}"
        );
        genus += twice / 2;
    }
    let c = Counts::of(m);
    assert_eq!(
        (c.vertices, c.edges, c.faces, c.boundary_loops, c.components),
        (nv, nd / 2, faces, loops, ncomp),
        "{raw:?}"
    );
    assert_eq!(c.euler_characteristic, chi.iter().sum::<i64>());
    assert_eq!(
        c.euler_characteristic,
        nv as i64 - (nd / 2) as i64 + faces as i64
    );
    assert_eq!(c.genus, genus, "{raw:?}");
    assert_eq!(m.boundary_loops().len(), loops);
    assert!(m.boundary_loops().iter().all(|&d| m.is_boundary_dart(d)));
    c
}

fn histograms_and_gauss_bonnet(raw: &RawMap, m: &Map, chi: i64) {
    let h = Histograms::of(m);
    let (inner, outer, faces) = raw.histograms();
    assert_eq!(
        (&h.interior_valences, &h.boundary_valences, &h.face_degrees),
        (&inner, &outer, &faces)
    );
    let sum = |x: &BTreeMap<usize, usize>| x.values().sum::<usize>();
    assert_eq!(
        sum(&h.interior_valences) + sum(&h.boundary_valences),
        m.num_vertices()
    );
    assert_eq!(sum(&h.face_degrees), m.num_faces());
    for (kind, reg_in, reg_b, reg_f, weight, scale) in [
        (MeshKind::Quad, 4, 3, 4, 1, 4),
        (MeshKind::Mixed, 4, 3, 4, 1, 4),
        (MeshKind::Triangle, 6, 4, 3, 2, 6),
    ] {
        let curv = |x: &BTreeMap<usize, usize>, r: i64| -> i64 {
            x.iter().map(|(&k, &n)| (r - k as i64) * n as i64).sum()
        };
        let gb = gauss_bonnet(m, kind);
        assert!(gb.holds(), "{raw:?} {kind:?}: {gb:?}");
        assert_eq!(gb.rhs, scale * chi);
        assert_eq!(gb.vertex_sum, curv(&inner, reg_in) + curv(&outer, reg_b));
        assert_eq!(gb.face_sum, weight * curv(&faces, reg_f));
    }
}

/// For maps without loops or multi-edges whose faces have at least three distinct corners,
/// the polygons rebuild an isomorphic map with the same vertex numbers. Returns whether the
/// round trip applied.
fn polygon_round_trip(m: &Map) -> bool {
    let mut pairs = Vec::new();
    for d in m.darts().filter(|d| d.index() % 2 == 0) {
        let (a, b) = (m.origin(d), m.dest(d));
        if a == b {
            return false;
        }
        pairs.push((a.min(b), a.max(b)));
    }
    pairs.sort();
    if pairs.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    let polys: Vec<Vec<u32>> = m
        .faces()
        .map(|f| {
            m.face_darts(f)
                .map(|d| m.origin(d).index() as u32)
                .collect()
        })
        .collect();
    for p in &polys {
        let mut q = p.clone();
        q.sort();
        q.dedup();
        if p.len() < 3 || q.len() != p.len() {
            return false;
        }
    }
    let p = Map::from_polygons(m.vertex_slots(), &polys).expect("polygons of a valid map");
    assert_eq!(p.check(), Ok(()));
    assert!(is_isomorphic(&p, m), "round trip of {polys:?}");
    assert_eq!(Counts::of(&p), Counts::of(m));
    for (f, poly) in p.faces().zip(&polys) {
        let got: Vec<u32> = p
            .face_darts(f)
            .map(|d| p.origin(d).index() as u32)
            .collect();
        assert!(is_rotation(&got, poly), "face {f:?}: {got:?} vs {poly:?}");
    }
    true
}

/// Whether `a` is a cyclic rotation of `b`.
pub fn is_rotation(a: &[u32], b: &[u32]) -> bool {
    a.len() == b.len()
        && (a.is_empty() || (0..a.len()).any(|k| a.iter().cycle().skip(k).take(a.len()).eq(b)))
}

/// Rooted maps with n edges on the orientable surface of genus g (OEIS A238396, rows 0..=4).
const ROOTED_BY_GENUS: [&[u64]; 5] = [&[1], &[2], &[9, 1], &[54, 20], &[378, 307, 21]];

/// Sensed planar maps with n edges (OEIS A006384), n = 0..=4.
const SENSED_PLANAR: [u64; 5] = [1, 2, 4, 14, 57];

/// Reflexible closed maps with n edges by genus (Krasko's table of reflexible maps), n = 0..=4.
const REFLEXIBLE_BY_GENUS: [&[u64]; 5] = [&[1], &[2], &[4, 1], &[14, 6], &[47, 34, 4]];

#[derive(Default)]
struct Tally {
    candidates: u64,
    accepted: u64,
    rejected: BTreeMap<String, u64>,
    round_trips: u64,
    /// Labelled closed connected maps by genus.
    closed_connected: BTreeMap<i64, u64>,
    /// Isomorphism classes (brute-force form) of closed connected maps by genus, and how
    /// many of them are reflexible (isomorphic to their mirror).
    classes: HashMap<u64, (bool, i64)>,
}

#[test]
fn every_map_up_to_the_bound() {
    let mut tallies: Vec<Tally> = (0..=MAX_EDGES).map(|_| Tally::default()).collect();
    // Brute-force form <-> canonical code must be a bijection: isomorphic maps (equal
    // forms) get equal codes and non-isomorphic maps different codes.
    let mut code_of_form: HashMap<u64, CanonicalCode> = HashMap::new();
    let mut form_of_code: HashMap<CanonicalCode, u64> = HashMap::new();
    let paths = Exhaustive::run(
        |c| any_map(c, MAX_EDGES),
        |seen| {
            let n = seen.raw.darts() / 2;
            let t = &mut tallies[n];
            t.candidates += 1;
            let facts = match seen.result {
                Ok(f) => f,
                Err(e) => {
                    *t.rejected.entry(format!("{e:?}")).or_default() += 1;
                    return;
                }
            };
            t.accepted += 1;
            t.round_trips += u64::from(facts.round_trip);
            let form = seen.raw.brute_form();
            let mirror_form = facts.mirror.brute_form();
            assert_eq!(facts.self_mirror, form == mirror_form, "{:?}", seen.raw);
            let code = code_of_form
                .entry(form)
                .or_insert_with(|| facts.code.clone());
            assert_eq!(
                *code, facts.code,
                "isomorphic maps, different codes: {:?}",
                seen.raw
            );
            let f = *form_of_code.entry(facts.code).or_insert(form);
            assert_eq!(f, form, "non-isomorphic maps, same code: {:?}", seen.raw);
            let cn = facts.counts;
            if cn.boundary_loops == 0 && cn.components == 1 {
                *t.closed_connected.entry(cn.genus).or_default() += 1;
                t.classes.insert(form, (facts.self_mirror, cn.genus));
            }
        },
    );
    let mut total = 0;
    for (n, t) in tallies.iter().enumerate() {
        // (2n + 1)! candidates: the enumeration is complete and has no duplicates.
        assert_eq!(t.candidates, (1..=2 * n as u64 + 1).product::<u64>());
        total += t.candidates;
        // Labelled closed connected maps = rooted maps * (n-1)! 2^(n-1) labellings per root.
        if n > 0 {
            let per_root: u64 = (1..n as u64).product::<u64>() << (n - 1);
            let want: Vec<u64> = ROOTED_BY_GENUS[n].iter().map(|r| r * per_root).collect();
            let got: Vec<u64> = t.closed_connected.values().copied().collect();
            assert_eq!(got, want, "closed connected maps with {n} edges by genus");
        }
        let mut sensed: BTreeMap<i64, (u64, u64)> = BTreeMap::new();
        for &(reflexible, g) in t.classes.values() {
            let e = sensed.entry(g).or_default();
            e.0 += 1;
            e.1 += u64::from(reflexible);
        }
        if n > 0 {
            // Classes up to orientation-preserving isomorphism ("sensed") and those
            // isomorphic to their mirror ("reflexible"), against the published numbers.
            let got: Vec<(i64, (u64, u64))> = sensed.iter().map(|(&g, &x)| (g, x)).collect();
            eprintln!("{n} edges: closed connected classes by genus (sensed, reflexible): {got:?}");
            assert_eq!(
                sensed[&0].0, SENSED_PLANAR[n],
                "sensed planar maps with {n} edges"
            );
            let reflexible: Vec<u64> = sensed.values().map(|x| x.1).collect();
            assert_eq!(
                reflexible, REFLEXIBLE_BY_GENUS[n],
                "reflexible maps with {n} edges"
            );
        }
        eprintln!(
            "{n} edges ({} darts): {} candidates, {} accepted, rejected {:?}, {} polygon round trips",
            2 * n,
            t.candidates,
            t.accepted,
            t.rejected,
            t.round_trips
        );
    }
    assert_eq!(paths, total);
    eprintln!(
        "{} isomorphism classes of valid maps with up to {MAX_EDGES} edges",
        code_of_form.len()
    );
}

/// The same property on random maps past the exhaustive bound (10 to 16 darts).
#[test]
fn random_maps_past_the_bound() {
    let mut c = Random(Rng::new(2024));
    let mut accepted = 0;
    for n in MAX_EDGES + 1..=8 {
        for _ in 0..2000 {
            let raw = RawMap::any(&mut c, n);
            accepted += usize::from(map_properties(&mut c, &raw).is_ok());
        }
    }
    assert!(accepted > 500, "too few valid random maps: {accepted}");
}

/// The brute-force oracle itself: relabelling never changes the form.
#[test]
fn brute_form_is_invariant() {
    let mut c = Random(Rng::new(7));
    for _ in 0..200 {
        let n = 1 + c.any(MAX_EDGES);
        let raw = RawMap::any(&mut c, n);
        let perm = &permutations(n)[c.any((1..=n).product())];
        let swap: Vec<bool> = (0..n).map(|_| c.any_bool()).collect();
        assert_eq!(raw.relabel(perm, &swap).brute_form(), raw.brute_form());
    }
}
