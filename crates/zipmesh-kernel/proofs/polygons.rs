//! Every small polygon list fed to `Map::from_polygons`, against an oracle.
//!
//! Enumeration: `n_vertices` in `0..=4`, up to 3 triangles, each corner any index in
//! `0..=n_vertices` (the value `n_vertices` is out of range): 2 256 210 lists in all. Every
//! accepted map then goes through the full map property of `maps.rs`. Pinched vertices need a
//! fifth vertex: every list of up to 3 triangles with distinct corners on 5 vertices
//! (219 661 lists) covers them. A last enumeration
//! feeds `Map::from_flat_polygons` every small corner list with every small offset list,
//! valid or not.

use crate::choice::{Choice, Exhaustive};
use crate::maps::{is_rotation, map_properties};
use crate::oracle::RawMap;
use std::collections::{BTreeMap, HashMap};
use std::panic::{catch_unwind, AssertUnwindSafe};
use zipmesh_kernel::invariants::canonical::CanonicalCode;
use zipmesh_kernel::invariants::Counts;
use zipmesh_kernel::{BuildError, Map, Vert};

pub const MAX_VERTICES: usize = 4;
pub const MAX_FACES: usize = 3;

/// Any list of at most `MAX_FACES` triangles on `n_vertices <= MAX_VERTICES`.
pub fn any_triangles(c: &mut impl Choice) -> (usize, Vec<[u32; 3]>) {
    let nv = c.any(MAX_VERTICES + 1);
    let nf = c.any(MAX_FACES + 1);
    let faces = (0..nf)
        .map(|_| [0; 3].map(|_: u32| c.any(nv + 1) as u32))
        .collect();
    (nv, faces)
}

/// The defects a polygon list has, computed directly.
enum Oracle {
    /// The first face with a bad corner fails with exactly this error.
    Exact(BuildError),
    /// Undirected edges used three or more times, and directed half-edges used twice by
    /// faces whose edge is used exactly twice (orientation conflicts).
    Edges {
        non_manifold: Vec<(u32, u32)>,
        same_direction: Vec<(u32, u32)>,
    },
    /// Vertices whose faces form more than one fan.
    Vertices(Vec<u32>),
    Ok,
}

fn oracle(nv: usize, faces: &[impl AsRef<[u32]>]) -> Oracle {
    for (f, poly) in faces.iter().enumerate() {
        let poly = poly.as_ref();
        if poly.len() < 3 {
            return Oracle::Exact(BuildError::FaceTooSmall {
                face: f,
                corners: poly.len(),
            });
        }
        if let Some(&v) = poly.iter().find(|&&v| v as usize >= nv) {
            return Oracle::Exact(BuildError::IndexOutOfRange {
                face: f,
                vertex: v,
                n_vertices: nv,
            });
        }
        if let Some(i) = (1..poly.len()).find(|&i| poly[..i].contains(&poly[i])) {
            return Oracle::Exact(BuildError::RepeatedCorner {
                face: f,
                vertex: poly[i],
            });
        }
    }
    let mut uses: BTreeMap<(u32, u32), Vec<(u32, u32)>> = BTreeMap::new();
    for poly in faces {
        let poly = poly.as_ref();
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            uses.entry((a.min(b), a.max(b))).or_default().push((a, b));
        }
    }
    let non_manifold: Vec<_> = uses
        .iter()
        .filter(|(_, u)| u.len() >= 3)
        .map(|(&e, _)| e)
        .collect();
    let same_direction: Vec<_> = uses
        .values()
        .filter(|u| u.len() == 2 && u[0] == u[1])
        .map(|u| u[0])
        .collect();
    if !non_manifold.is_empty() || !same_direction.is_empty() {
        return Oracle::Edges {
            non_manifold,
            same_direction,
        };
    }
    // Fans: faces at v joined when they share an edge at v (union-find over face numbers).
    let mut bad = Vec::new();
    for v in 0..nv as u32 {
        let at: Vec<usize> = (0..faces.len())
            .filter(|&f| faces[f].as_ref().contains(&v))
            .collect();
        let mut parent: HashMap<usize, usize> = at.iter().map(|&f| (f, f)).collect();
        fn find(p: &mut HashMap<usize, usize>, mut x: usize) -> usize {
            while p[&x] != x {
                x = p[&x];
            }
            x
        }
        for &f in &at {
            for &g in &at {
                let shares = |x: usize| {
                    let p = faces[x].as_ref();
                    let i = p.iter().position(|&c| c == v).unwrap_or(0);
                    [p[(i + 1) % p.len()], p[(i + p.len() - 1) % p.len()]]
                };
                if f < g && shares(f).iter().any(|w| shares(g).contains(w)) {
                    let (rf, rg) = (find(&mut parent, f), find(&mut parent, g));
                    parent.insert(rf, rg);
                }
            }
        }
        let roots = at.iter().filter(|&&f| find(&mut parent, f) == f).count();
        if roots > 1 {
            bad.push(v);
        }
    }
    if bad.is_empty() {
        Oracle::Ok
    } else {
        Oracle::Vertices(bad)
    }
}

/// Outcome name, for the tallies.
pub fn polygon_properties(
    c: &mut impl Choice,
    nv: usize,
    faces: &[impl AsRef<[u32]> + std::fmt::Debug],
) -> &'static str {
    let got = catch_unwind(AssertUnwindSafe(|| {
        Map::from_polygons_with_report(nv, faces)
    }))
    .unwrap_or_else(|_| panic!("from_polygons panicked on {nv} {faces:?}"));
    let uses_face = |f: usize, a: u32, b: u32| {
        let p = faces[f].as_ref();
        (0..p.len()).any(|i| {
            let (x, y) = (p[i], p[(i + 1) % p.len()]);
            (x, y) == (a, b) || (y, x) == (a, b)
        })
    };
    let runs = |f: usize, a: u32, b: u32| {
        let p = faces[f].as_ref();
        (0..p.len()).any(|i| (p[i], p[(i + 1) % p.len()]) == (a, b))
    };
    let ctx = || format!("{nv} {faces:?}: got {got:?}");
    match (oracle(nv, faces), &got) {
        (Oracle::Exact(want), Err(e)) => assert_eq!(e, &want, "{}", ctx()),
        (
            Oracle::Edges { non_manifold, .. },
            Err(BuildError::NonManifoldEdge { a, b, faces: fs }),
        ) => {
            assert!(a < b && non_manifold.contains(&(*a, *b)), "{}", ctx());
            assert!(fs[0] < fs[1] && fs[1] < fs[2], "{}", ctx());
            assert!(fs.iter().all(|&f| uses_face(f, *a, *b)), "{}", ctx());
        }
        (
            Oracle::Edges { same_direction, .. },
            Err(BuildError::InconsistentOrientation { a, b, faces: fs }),
        ) => {
            assert!(same_direction.contains(&(*a, *b)), "{}", ctx());
            assert!(
                fs[0] < fs[1] && runs(fs[0], *a, *b) && runs(fs[1], *a, *b),
                "{}",
                ctx()
            );
        }
        (Oracle::Vertices(bad), Err(BuildError::NonManifoldVertex { vertex, face })) => {
            assert!(bad.contains(vertex), "{}", ctx());
            assert!(faces[*face].as_ref().contains(vertex), "{}", ctx());
        }
        (Oracle::Ok, Ok((m, report))) => accepted(c, nv, faces, m, &report.unreferenced),
        _ => panic!("wrong answer for {}", ctx()),
    }
    match &got {
        Ok(_) => "Ok",
        Err(e) => {
            assert!(e.face().is_none_or(|f| f < faces.len()), "{}", ctx());
            assert!(!e.to_string().is_empty());
            match e {
                BuildError::FaceTooSmall { .. } => "FaceTooSmall",
                BuildError::RepeatedCorner { .. } => "RepeatedCorner",
                BuildError::IndexOutOfRange { .. } => "IndexOutOfRange",
                BuildError::NonManifoldEdge { .. } => "NonManifoldEdge",
                BuildError::InconsistentOrientation { .. } => "InconsistentOrientation",
                BuildError::NonManifoldVertex { .. } => "NonManifoldVertex",
                BuildError::TooLarge { .. } => "TooLarge",
            }
        }
    }
}

/// An accepted polygon list: numbering kept, counts right, and the full map property holds.
fn accepted(
    c: &mut impl Choice,
    nv: usize,
    faces: &[impl AsRef<[u32]>],
    m: &Map,
    unreferenced: &[Vert],
) {
    assert_eq!(m.check(), Ok(()));
    let used: Vec<bool> = (0..nv as u32)
        .map(|v| faces.iter().any(|p| p.as_ref().contains(&v)))
        .collect();
    let want_unref: Vec<Vert> = (0..nv)
        .filter(|&v| !used[v])
        .map(|v| Vert::new(v as u32))
        .collect();
    assert_eq!(unreferenced, want_unref.as_slice());
    assert_eq!(m.vertex_slots(), nv);
    for (v, &u) in used.iter().enumerate() {
        assert_eq!(m.is_live_vertex(Vert::new(v as u32)), u);
    }
    assert_eq!(m.num_faces(), faces.len());
    for (f, poly) in m.faces().zip(faces) {
        let got: Vec<u32> = m
            .face_darts(f)
            .map(|d| m.origin(d).index() as u32)
            .collect();
        assert!(is_rotation(&got, poly.as_ref()), "face {f:?}: {got:?}");
    }
    let mut edges: Vec<(u32, u32)> = faces
        .iter()
        .flat_map(|p| {
            let p = p.as_ref();
            (0..p.len()).map(move |i| {
                (
                    p[i].min(p[(i + 1) % p.len()]),
                    p[i].max(p[(i + 1) % p.len()]),
                )
            })
        })
        .collect();
    let corners = edges.len();
    edges.sort();
    edges.dedup();
    assert_eq!(m.num_edges(), edges.len());
    // Half-edges without a partner are exactly the boundary darts.
    assert_eq!(
        m.darts().filter(|&d| m.is_boundary_dart(d)).count(),
        2 * edges.len() - corners
    );
    assert_eq!(Map::from_polygons(nv, faces).as_ref(), Ok(m));
    // The compacted map, rebuilt from its permutations, passes every map property.
    let mut compact = m.clone();
    compact.compact();
    let facts = map_properties(c, &RawMap::of(&compact)).expect("a built map is valid");
    assert_eq!(Counts::of(m), facts.counts);
    assert_eq!(
        CanonicalCode::of(m),
        facts.code,
        "code must ignore dead slots"
    );
}

#[test]
fn every_small_triangle_list() {
    let mut tally: BTreeMap<&str, u64> = BTreeMap::new();
    let paths = Exhaustive::run(
        |c| {
            let (nv, faces) = any_triangles(c);
            polygon_properties(c, nv, &faces)
        },
        |o| *tally.entry(o).or_default() += 1,
    );
    // Per n_vertices v: sum over k <= 3 faces of ((v + 1)^3)^k lists.
    let want: u64 = (0..=MAX_VERTICES as u64)
        .map(|v| {
            (0..=MAX_FACES as u32)
                .map(|k| ((v + 1).pow(3)).pow(k))
                .sum::<u64>()
        })
        .sum();
    assert_eq!(paths, want);
    eprintln!(
        "{paths} triangle lists (<= {MAX_FACES} faces, <= {MAX_VERTICES} vertices): {tally:?}"
    );
    for kind in [
        "Ok",
        "RepeatedCorner",
        "IndexOutOfRange",
        "NonManifoldEdge",
        "InconsistentOrientation",
    ] {
        assert!(tally.contains_key(kind), "no case reached {kind}");
    }
}

/// Any list of at most `MAX_FACES` triangles with distinct in-range corners on 5 vertices:
/// enough room for a pinched ("bow-tie") vertex, which 4 vertices cannot hold.
pub fn any_proper_triangles(c: &mut impl Choice) -> (usize, Vec<[u32; 3]>) {
    let nf = c.any(MAX_FACES + 1);
    let faces = (0..nf)
        .map(|_| {
            let mut pool: Vec<u32> = (0..5).collect();
            [0; 3].map(|_: u32| pool.remove(c.any(pool.len())))
        })
        .collect();
    (5, faces)
}

#[test]
fn every_proper_triangle_list_on_five_vertices() {
    let mut tally: BTreeMap<&str, u64> = BTreeMap::new();
    let paths = Exhaustive::run(
        |c| {
            let (nv, faces) = any_proper_triangles(c);
            polygon_properties(c, nv, &faces)
        },
        |o| *tally.entry(o).or_default() += 1,
    );
    assert_eq!(paths, 1 + 60 + 60 * 60 + 60 * 60 * 60);
    eprintln!("{paths} proper triangle lists on 5 vertices (<= {MAX_FACES} faces): {tally:?}");
    for kind in [
        "Ok",
        "NonManifoldEdge",
        "InconsistentOrientation",
        "NonManifoldVertex",
    ] {
        assert!(tally.contains_key(kind), "no case reached {kind}");
    }
}

/// `from_flat_polygons` with every corner list of length <= 4 on 3 vertices and every offset
/// list of length <= 3 with entries <= 5: valid offsets give the answer of `from_polygons` on
/// the slices, invalid offsets an error, and nothing panics.
#[test]
fn every_small_flat_polygon_list() {
    let mut ok = 0;
    let paths = Exhaustive::run(
        |c| {
            let corners: Vec<u32> = (0..c.any(5)).map(|_| c.any(3) as u32).collect();
            let offsets: Vec<u32> = (0..c.any(4)).map(|_| c.any(6) as u32).collect();
            let got = catch_unwind(|| Map::from_flat_polygons(3, &corners, &offsets))
                .unwrap_or_else(|_| panic!("panicked on {corners:?} {offsets:?}"));
            let valid = (offsets.is_empty() && corners.is_empty())
                || (offsets.first() == Some(&0)
                    && offsets.windows(2).all(|w| w[0] <= w[1])
                    && offsets.last() == Some(&(corners.len() as u32)));
            if valid {
                let slices: Vec<&[u32]> = offsets
                    .windows(2)
                    .map(|w| &corners[w[0] as usize..w[1] as usize])
                    .collect();
                assert_eq!(
                    got,
                    Map::from_polygons_with_report(3, &slices),
                    "{corners:?} {offsets:?}"
                );
            } else {
                assert!(got.is_err(), "{corners:?} {offsets:?}");
            }
            if let Ok((m, _)) = &got {
                assert_eq!(m.check(), Ok(()));
            }
            got.is_ok()
        },
        |o| ok += u64::from(o),
    );
    assert_eq!(paths, 121 * 259);
    assert!(ok > 0);
}
