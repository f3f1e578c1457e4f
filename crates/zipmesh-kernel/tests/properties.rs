//! Property tests over generated meshes: the generators' contracts, canonical codes under
//! relabelling, mirror images and compaction, Catmull-Clark, and closed-form counts of the
//! regular generators.

use glam::DVec3;
use proptest::prelude::*;
use zipmesh_kernel::invariants::canonical::{CanonicalCode, CanonicalWorkspace};
use zipmesh_kernel::invariants::{gauss_bonnet, irregular_vertices, Counts, Histograms, MeshKind};
use zipmesh_kernel::rng::Rng;
use zipmesh_kernel::{gen, is_isomorphic, is_isomorphic_mirror, Face, Map, Mesh, Vert};

/// Which random generator.
#[derive(Clone, Copy, Debug)]
enum Kind {
    Quad,
    Triangle,
    Mixed,
}

fn generate(kind: Kind, faces: usize, genus: usize, holes: usize, seed: u64) -> Mesh {
    match kind {
        Kind::Quad => gen::random_quad(faces, genus, holes, seed),
        Kind::Triangle => gen::random_triangle(faces, genus, holes, seed),
        Kind::Mixed => gen::random_mixed(faces, genus, holes, seed),
    }
}

fn kind() -> impl Strategy<Value = Kind> {
    prop_oneof![Just(Kind::Quad), Just(Kind::Triangle), Just(Kind::Mixed)]
}

/// The size bound documented on the generators.
fn size_ok(kind: Kind, faces: usize, genus: usize, holes: usize, got: usize) -> bool {
    let t = 64 * (genus + holes) + 256;
    let (got, faces) = (got as i64, faces as i64);
    let t = t as i64;
    match kind {
        Kind::Triangle if faces >= 2 * t => (got - faces).abs() <= faces / 8 + 130,
        Kind::Triangle => got <= 2 * (t + t / 8 + 64),
        _ if faces >= t => (got - faces).abs() <= faces / 8 + 64,
        _ => got <= t + t / 8 + 64,
    }
}

/// The polygons of `map` as vertex-slot lists.
fn polygons(map: &Map) -> Vec<Vec<u32>> {
    map.faces()
        .map(|f| {
            map.face_darts(f)
                .map(|d| map.origin(d).index() as u32)
                .collect()
        })
        .collect()
}

/// A random renumbering of vertices into `0..n_out` (`n_out >= n`, so unused numbers
/// become dead slots), a random face order and a random rotation of every corner list.
fn relabel(polys: &[Vec<u32>], n: usize, n_out: usize, rng: &mut Rng) -> Vec<Vec<u32>> {
    let mut slots: Vec<u32> = (0..n_out as u32).collect();
    shuffle(&mut slots, rng);
    let mut out: Vec<Vec<u32>> = polys
        .iter()
        .map(|p| {
            let r = rng.below(p.len());
            (0..p.len())
                .map(|k| slots[p[(k + r) % p.len()] as usize % n])
                .collect()
        })
        .collect();
    shuffle(&mut out, rng);
    out
}

fn shuffle<T>(v: &mut [T], rng: &mut Rng) {
    for i in (1..v.len()).rev() {
        v.swap(i, rng.below(i + 1));
    }
}

/// Case counts keep the whole file well under a minute in the test profile.
fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: n,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(cases(1024))]

    /// Every random mesh is valid, connected, of the requested genus and number of loops,
    /// satisfies Gauss-Bonnet in its own frame, has the promised face degrees and size.
    #[test]
    fn random_meshes_keep_their_contract(
        kind in kind(),
        faces in 0usize..2200,
        genus in 0usize..=3,
        holes in 0usize..=2,
        seed in any::<u64>(),
    ) {
        let m = generate(kind, faces, genus, holes, seed);
        prop_assert_eq!(m.map.check(), Ok(()));
        let c = Counts::of(&m.map);
        prop_assert_eq!(c.genus, genus as i64);
        prop_assert_eq!(c.boundary_loops, holes);
        prop_assert_eq!(c.components, 1);
        prop_assert_eq!(c.euler_characteristic, 2 - 2 * genus as i64 - holes as i64);
        prop_assert!(size_ok(kind, faces, genus, holes, c.faces), "{} faces", c.faces);
        prop_assert_eq!(m.positions.len(), m.map.vertex_slots());
        prop_assert!(m.positions.iter().all(|p| p.is_finite()));
        let h = Histograms::of(&m.map);
        let frame = match kind {
            Kind::Quad => {
                prop_assert!(h.face_degrees.keys().all(|&d| d == 4));
                MeshKind::Quad
            }
            Kind::Triangle => {
                prop_assert!(h.face_degrees.keys().all(|&d| d == 3));
                MeshKind::Triangle
            }
            Kind::Mixed => {
                prop_assert!(h.face_degrees.keys().all(|&d| (3..=5).contains(&d)));
                prop_assert!(h.face_degrees.contains_key(&3));
                let quads = h.face_degrees.get(&4).copied().unwrap_or(0);
                prop_assert!(2 * quads > c.faces, "not quad-dominant: {:?}", h.face_degrees);
                MeshKind::Mixed
            }
        };
        prop_assert!(gauss_bonnet(&m.map, frame).holds());
        // Genus 0 (box corners) and genus >= 2 (gluings) always have singularities.
        if genus != 1 {
            prop_assert!(!irregular_vertices(&m.map, frame).is_empty());
        }
        // Determinism.
        prop_assert_eq!(&generate(kind, faces, genus, holes, seed), &m);
    }
}

/// Two copies of `map` side by side: two components.
fn side_by_side(map: &Map) -> Map {
    let n = map.vertex_slots();
    let mut polys = polygons(map);
    let shifted: Vec<Vec<u32>> = (polys.iter())
        .map(|p| p.iter().map(|&v| v + n as u32).collect())
        .collect();
    polys.extend(shifted);
    Map::from_polygons(2 * n, &polys).unwrap()
}

proptest! {
    #![proptest_config(cases(128))]

    /// A workspace kept from map to map (growing and shrinking; regular tori among them,
    /// whose automorphisms take label arrays and give them back; one or two components)
    /// codes each map as a fresh call does.
    #[test]
    fn a_kept_workspace_codes_as_a_fresh_call(
        maps in prop::collection::vec(
            (
                kind(),
                0usize..400,
                0usize..=2,
                0usize..=2,
                any::<u64>(),
                prop::option::of((3usize..14, 3usize..14)),
                any::<bool>(),
            ),
            1..6,
        )
    ) {
        let mut ws = CanonicalWorkspace::new();
        for (kind, faces, genus, holes, seed, torus, twice) in maps {
            let m = match torus {
                Some((a, b)) => gen::torus_grid(a, b),
                None => generate(kind, faces, genus, holes, seed),
            };
            let map = if twice { side_by_side(&m.map) } else { m.map };
            prop_assert_eq!(ws.code(&map), &CanonicalCode::of(&map));
        }
    }
}

proptest! {
    #![proptest_config(cases(512))]

    /// Renumbering vertices (with unused numbers as dead slots), reordering faces and
    /// rotating corner lists keeps the canonical code.
    #[test]
    fn relabelling_keeps_the_canonical_code(
        kind in kind(),
        faces in 0usize..1500,
        genus in 0usize..=3,
        holes in 0usize..=2,
        seed in any::<u64>(),
        extra in 0usize..50,
    ) {
        let m = generate(kind, faces, genus, holes, seed);
        let n = m.map.vertex_slots();
        let polys = polygons(&m.map);
        let mut rng = Rng::new(seed ^ 0xABCD);
        let code = CanonicalCode::of(&m.map);

        let same = Map::from_polygons(n, &relabel(&polys, n, n, &mut rng)).unwrap();
        prop_assert_eq!(CanonicalCode::of(&same), code.clone());
        prop_assert!(is_isomorphic(&m.map, &same));

        let (sparse, report) =
            Map::from_polygons_with_report(n + extra, &relabel(&polys, n, n + extra, &mut rng))
                .unwrap();
        prop_assert_eq!(report.unreferenced.len(), extra);
        prop_assert_eq!(CanonicalCode::of(&sparse), code.clone());
        prop_assert!(is_isomorphic(&sparse, &m.map));

        // compact() keeps the code and validity.
        let mut compacted = sparse.clone();
        compacted.compact();
        prop_assert_eq!(compacted.check(), Ok(()));
        prop_assert_eq!(compacted.vertex_slots(), compacted.num_vertices());
        prop_assert_eq!(CanonicalCode::of(&compacted), code);
    }
}

proptest! {
    #![proptest_config(cases(512))]

    /// The mirror of the mirror is the map; the mirror equals the map with every polygon
    /// reversed (an independent construction), and is mirror-isomorphic to the map.
    #[test]
    fn mirror_images(
        kind in kind(),
        faces in 0usize..1200,
        genus in 0usize..=3,
        holes in 0usize..=2,
        seed in any::<u64>(),
    ) {
        let m = generate(kind, faces, genus, holes, seed).map;
        let mirror = m.mirror();
        prop_assert_eq!(mirror.check(), Ok(()));
        prop_assert_eq!(Counts::of(&mirror), Counts::of(&m));
        prop_assert!(is_isomorphic(&mirror.mirror(), &m));
        let reversed: Vec<Vec<u32>> = polygons(&m)
            .into_iter()
            .map(|mut p| {
                p.reverse();
                p
            })
            .collect();
        let reversed = Map::from_polygons(m.vertex_slots(), &reversed).unwrap();
        prop_assert!(is_isomorphic(&mirror, &reversed));
        prop_assert!(is_isomorphic_mirror(&m, &reversed));
        prop_assert!(is_isomorphic_mirror(&reversed, &m));
        // Either both orientations are the same map or neither direction finds it.
        prop_assert_eq!(is_isomorphic(&m, &reversed), is_isomorphic(&reversed, &m));
    }
}

proptest! {
    #![proptest_config(cases(256))]

    /// Changing one face is detected: removing an interior face (same darts, one boundary
    /// loop more) and flipping one diagonal of a triangulation both change the code.
    #[test]
    fn a_change_changes_the_code(
        faces in 600usize..2000,
        genus in 0usize..=3,
        seed in any::<u64>(),
        pick in any::<u64>(),
    ) {
        let quad = gen::random_quad(faces, genus, 0, seed);
        let polys = polygons(&quad.map);
        let n = quad.map.vertex_slots();
        let code = CanonicalCode::of(&quad.map);

        let mut fewer = polys.clone();
        fewer.remove(pick as usize % polys.len());
        let fewer = Map::from_polygons(n, &fewer).unwrap();
        prop_assert_eq!(fewer.num_darts(), quad.map.num_darts());
        prop_assert_ne!(CanonicalCode::of(&fewer), code);

        // Triangulate with random diagonals, then again with one diagonal flipped. With at
        // least 400 quads an accidental isomorphism would need a symmetry of the diagonal
        // pattern, which has probability about 4 * 2000 / 2^400.
        let mut rng = Rng::new(seed);
        let diag: Vec<bool> = (0..polys.len()).map(|_| rng.chance(1, 2)).collect();
        let tri = |flip: Option<usize>| {
            let mut t = Vec::new();
            for (i, p) in polys.iter().enumerate() {
                let (a, b, c, d) = (p[0], p[1], p[2], p[3]);
                if diag[i] != (flip == Some(i)) {
                    t.extend([[a, b, c], [a, c, d]]);
                } else {
                    t.extend([[a, b, d], [b, c, d]]);
                }
            }
            Map::from_polygons(n, &t).unwrap()
        };
        let (t0, t1) = (tri(None), tri(Some(pick as usize % polys.len())));
        prop_assert_eq!(t1.check(), Ok(()));
        prop_assert_eq!(Counts::of(&t0), Counts::of(&t1));
        prop_assert_ne!(CanonicalCode::of(&t0), CanonicalCode::of(&t1));
        prop_assert!(!is_isomorphic(&t0, &t1));
    }
}

proptest! {
    #![proptest_config(cases(512))]

    /// Catmull-Clark on random meshes: the documented counts, numbering and invariance.
    #[test]
    fn catmull_clark_counts(
        kind in kind(),
        faces in 0usize..800,
        genus in 0usize..=3,
        holes in 0usize..=2,
        seed in any::<u64>(),
    ) {
        let m = generate(kind, faces, genus, holes, seed);
        let s = gen::catmull_clark(&m);
        check_subdivision(&m.map, &s.map)?;
        prop_assert_eq!(s.positions.len(), s.map.vertex_slots());
        // Simple input: the polygon numbering, which keeps old vertices' valences.
        let (vs, es) = (m.map.vertex_slots(), m.map.dart_slots() / 2);
        for v in m.map.vertices() {
            prop_assert_eq!(s.map.valence(v), m.map.valence(v));
        }
        for d in m.map.darts().filter(|d| d.index() % 2 == 0) {
            let sides = usize::from(m.map.face(d).is_some()) + usize::from(m.map.face(d.twin()).is_some());
            prop_assert_eq!(s.map.valence(Vert::new((vs + d.edge().index()) as u32)), 2 + sides);
        }
        for f in m.map.faces() {
            let c = Vert::new((vs + es + f.index()) as u32);
            prop_assert_eq!(s.map.valence(c), m.map.degree(f));
        }
        // Subdividing commutes with relabelling and with mirroring.
        let n = m.map.vertex_slots();
        let mut rng = Rng::new(seed);
        let relabelled = Map::from_polygons(n, &relabel(&polygons(&m.map), n, n, &mut rng)).unwrap();
        let s2 = gen::catmull_clark(&Mesh { map: relabelled, positions: m.positions.clone() });
        prop_assert!(is_isomorphic(&s.map, &s2.map));
        let sm = gen::catmull_clark(&Mesh { map: m.map.mirror(), positions: vec![] });
        prop_assert!(is_isomorphic(&sm.map, &s.map.mirror()));
    }
}

proptest! {
    #![proptest_config(cases(4096))]

    /// Catmull-Clark on arbitrary small maps (loops, parallel edges, faces of degree 1 and
    /// 2, faces along both sides of an edge): the same counts, through the dart path.
    #[test]
    fn catmull_clark_on_raw_maps(edges in 1usize..8, seed in any::<u64>()) {
        let nd = 2 * edges;
        let mut rng = Rng::new(seed);
        let mut next: Vec<u32> = (0..nd as u32).collect();
        shuffle(&mut next, &mut rng);
        let mut boundary = vec![false; nd];
        let mut seen = vec![false; nd];
        for d0 in 0..nd {
            if !seen[d0] {
                let mark = rng.chance(1, 3);
                let mut d = d0;
                while !seen[d] {
                    seen[d] = true;
                    boundary[d] = mark;
                    d = next[d] as usize;
                }
            }
        }
        let Ok(map) = Map::from_permutation(&next, &boundary) else {
            return Ok(());
        };
        let s = gen::catmull_clark(&Mesh { map: map.clone(), positions: vec![DVec3::ONE] });
        check_subdivision(&map, &s.map)?;
        prop_assert!(s.positions.iter().all(|p| p.is_finite()));
    }
}

/// `sub` is one Catmull-Clark step of `map`, judged by counts.
fn check_subdivision(map: &Map, sub: &Map) -> Result<(), TestCaseError> {
    prop_assert_eq!(sub.check(), Ok(()));
    let (c, cs) = (Counts::of(map), Counts::of(sub));
    let degrees: usize = map.faces().map(|f: Face| map.degree(f)).sum();
    prop_assert_eq!(cs.vertices, c.vertices + c.edges + c.faces);
    prop_assert_eq!(cs.edges, 2 * c.edges + degrees);
    prop_assert_eq!(cs.faces, degrees);
    prop_assert!(sub.faces().all(|f| sub.degree(f) == 4));
    prop_assert_eq!(cs.euler_characteristic, c.euler_characteristic);
    prop_assert_eq!(cs.genus, c.genus);
    prop_assert_eq!(cs.boundary_loops, c.boundary_loops);
    prop_assert_eq!(cs.components, c.components);
    Ok(())
}

/// Closed-form counts of the regular generators, and their singularities.
#[test]
fn regular_generators_match_closed_forms() {
    for nx in 1..9usize {
        for ny in 1..9usize {
            let g = gen::grid(nx, ny).map;
            g.check().unwrap();
            let c = Counts::of(&g);
            let e = nx * (ny + 1) + ny * (nx + 1);
            assert_eq!(
                (c.vertices, c.edges, c.faces),
                ((nx + 1) * (ny + 1), e, nx * ny)
            );
            assert_eq!(
                (c.euler_characteristic, c.genus, c.boundary_loops),
                (1, 0, 1)
            );
            let h = Histograms::of(&g);
            assert_eq!(h.boundary_valences.get(&2), Some(&4));
            let side = 2 * (nx - 1) + 2 * (ny - 1);
            assert_eq!(h.boundary_valences.get(&3).copied().unwrap_or(0), side);
            let inner = (nx - 1) * (ny - 1);
            assert_eq!(h.interior_valences.get(&4).copied().unwrap_or(0), inner);
            let irr = irregular_vertices(&g, MeshKind::Quad);
            assert_eq!(irr.len(), 4);
            assert!(irr.iter().all(|&v| g.valence(v) == 2));
            assert!(gauss_bonnet(&g, MeshKind::Quad).holds());

            let t = gen::torus_grid(nx, ny).map;
            t.check().unwrap();
            let (mx, my) = (nx.max(3), ny.max(3));
            let c = Counts::of(&t);
            assert_eq!(
                (c.vertices, c.edges, c.faces),
                (mx * my, 2 * mx * my, mx * my)
            );
            assert_eq!(
                (c.euler_characteristic, c.genus, c.boundary_loops),
                (0, 1, 0)
            );
            assert!(irregular_vertices(&t, MeshKind::Quad).is_empty());
        }
    }
    for n in 1..10usize {
        let cube = gen::cube(n).map;
        cube.check().unwrap();
        let c = Counts::of(&cube);
        assert_eq!(
            (c.vertices, c.edges, c.faces),
            (6 * n * n + 2, 12 * n * n, 6 * n * n)
        );
        assert_eq!(
            (c.euler_characteristic, c.genus, c.boundary_loops),
            (2, 0, 0)
        );
        let irr = irregular_vertices(&cube, MeshKind::Quad);
        assert_eq!(irr.len(), 8);
        assert!(irr.iter().all(|&v| cube.valence(v) == 3));
        assert!(gauss_bonnet(&cube, MeshKind::Quad).holds());
    }
}

/// Catmull-Clark of the cube, by hand: 8 corners keep valence 3, every other vertex has
/// valence 4, and the edge points of a closed mesh have valence 4.
#[test]
fn catmull_clark_of_a_cube() {
    let s = gen::catmull_clark(&gen::cube(1));
    let c = Counts::of(&s.map);
    assert_eq!((c.vertices, c.edges, c.faces), (26, 48, 24));
    let irr = irregular_vertices(&s.map, MeshKind::Quad);
    assert_eq!(irr, (0..8).map(Vert::new).collect::<Vec<_>>());
    // Corner (0,0,0), valence 3: its face points average to (1/3,1/3,1/3) and its edge
    // midpoints to (1/6,1/6,1/6), so (Q + 2R + 0 P) / 3 = (2/9, 2/9, 2/9).
    let p = s.positions[0];
    assert!((p - DVec3::splat(2.0 / 9.0)).length() < 1e-12, "{p}");
}
