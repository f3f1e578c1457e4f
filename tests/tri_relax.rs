//! Relaxation of triangle meshes (Sec. 8, `tri_edit::relax_local` / `relax_global`): on
//! generated edited meshes (an equilateral lattice, flat or bumpy, with an edge flipped near
//! the centre and one of its 5-7 pairs moved a few steps), the relaxed vertices stay on the
//! input surface, everything outside the region keeps its bits, the connectivity is the
//! same, Eq. 5 never increases under global relaxation, a lattice at rest does not move, and
//! the worst triangle near the edit gets better on average. Bad input is refused with the
//! mesh unchanged.

mod common;

use common::tri::{lattice, to_surface};
use glam::DVec3;
use proptest::prelude::*;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::ops::tri;
use zipmesh::optimize::Surface;
use zipmesh::rng::Rng;
use zipmesh::tri_edit::{
    mean_edge_length, move_pair, relax_energy, relax_global, relax_local, relax_region,
    touched_vertices, Direction, RelaxError, Relaxed,
};
use zipmesh::{Map, Mesh, Vert};

const N: usize = 14;

/// The centre vertex of the lattice.
fn centre() -> Vert {
    Vert::new(((N / 2) * N + N / 2) as u32)
}

/// A generated edit: a lattice (flat or bumpy by the seed), a spoke of the centre flipped,
/// then the centre (now a v5) and a v7 next to it moved up to 3 steps in one direction
/// (positions by the operators' rules). Returns the input and the edited mesh.
fn edited(seed: u64) -> (Mesh, Mesh) {
    let mut rng = Rng::new(seed);
    let input = lattice(N, [0.0, 0.4, 1.0][rng.below(3)]);
    let mut mesh = input.clone();
    let c = centre();
    let spokes: Vec<_> = mesh.map.vertex_darts(c).collect();
    tri::flip_edge(&mut mesh.map, spokes[rng.below(spokes.len())]).expect("a regular spoke");
    let map = &mesh.map;
    let q = map
        .vertex_darts(c)
        .map(|d| map.dest(d))
        .find(|&w| map.valence(w) == 7);
    let (mut p, mut q) = (c, q.expect("the flip leaves a v7 next to the centre"));
    let dir = Direction::ALL[rng.below(6)];
    for _ in 0..rng.below(4) {
        match move_pair(&mut mesh, p, q, dir) {
            Ok(e) => (p, q) = (e.record().p(), e.record().q()),
            Err(_) => break,
        }
    }
    (input, mesh)
}

/// The smallest angle (radians) of the triangles with a corner in `region`.
fn worst_angle(mesh: &Mesh, region: &[Vert]) -> f64 {
    let angle = |a: DVec3, b: DVec3, c: DVec3| (b - a).angle_between(c - a);
    mesh.polygons()
        .iter()
        .filter(|f| f.iter().any(|&v| region.contains(&Vert::new(v))))
        .map(|f| {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[f[k] as usize]);
            angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b))
        })
        .fold(f64::INFINITY, f64::min)
}

fn relax(mesh: &mut Mesh, s: &Surface, region: &[Vert], global: bool) -> Relaxed {
    if global {
        relax_global(mesh, s, region, 8).unwrap()
    } else {
        relax_local(mesh, s, region, 8).unwrap()
    }
}

/// The region of the edit from `input` to `mesh`: what it touched and `rings` rings.
fn region_of(input: &Mesh, mesh: &Mesh, rings: usize) -> Vec<Vert> {
    relax_region(&mesh.map, &touched_vertices(&input.map, &mesh.map), rings)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Every relaxation keeps the contract: the map and its canonical code are the same,
    /// vertices outside the region keep their bits, the region's vertices lie on the input
    /// surface, the report's energies are Eq. 5's, and global relaxation never raises it.
    #[test]
    fn relaxation_keeps_its_contract(seed in any::<u64>(), global in any::<bool>(), rings in 0usize..4) {
        let (input, mut mesh) = edited(seed);
        let region = region_of(&input, &mesh, rings);
        prop_assert!(!region.is_empty());
        let before = mesh.clone();
        let s = Surface::new(&input);
        let r = relax(&mut mesh, &s, &region, global);
        prop_assert_eq!(&mesh.map, &before.map);
        prop_assert_eq!(CanonicalCode::of(&mesh.map), CanonicalCode::of(&before.map));
        for (i, (a, b)) in mesh.positions.iter().zip(&before.positions).enumerate() {
            if !region.contains(&Vert::new(i as u32)) {
                prop_assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits));
            }
        }
        for &v in &region {
            let p = mesh.positions[v.index()];
            if p != before.positions[v.index()] {
                let dist = to_surface(&input, p);
                prop_assert!(dist < 1e-9, "vertex {} is {dist} off the input", v.index());
            }
        }
        prop_assert_eq!(r.edge_length, mean_edge_length(&before));
        prop_assert_eq!(r.energy_before, relax_energy(&before, &region, r.edge_length));
        prop_assert_eq!(r.energy_after, relax_energy(&mesh, &region, r.edge_length));
        if global {
            prop_assert!(r.energy_after <= r.energy_before);
        }
        prop_assert!(r.moved <= r.movable && r.movable <= region.len());
    }
}

/// The mean change of the worst angle at the region (2 rings) over the edits of `seeds`.
fn mean_gain(seeds: impl Iterator<Item = u64>, global: bool) -> f64 {
    let (mut gain, mut n) = (0.0, 0);
    for seed in seeds {
        let (input, mut mesh) = edited(seed);
        let region = region_of(&input, &mesh, 2);
        let w0 = worst_angle(&mesh, &region);
        relax(&mut mesh, &Surface::new(&input), &region, global);
        gain += worst_angle(&mesh, &region) - w0;
        n += 1;
    }
    gain / n as f64
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Over any 8 consecutive seeds' edits, relaxation of either kind raises the worst angle
    /// at the region on average.
    #[test]
    fn relaxation_improves_quality_on_average(base in any::<u64>(), global in any::<bool>()) {
        let gain = mean_gain((0..8).map(|k| base.wrapping_add(k)), global);
        prop_assert!(gain > 0.0, "mean worst-angle change {gain} rad");
    }
}

/// Over 40 generated edits, relaxation (each kind, 2 rings) raises the worst angle of the
/// triangles at the region on average, and global relaxation lowers Eq. 5 on each edit.
#[test]
fn relaxation_improves_the_worst_triangle_on_average() {
    for global in [false, true] {
        let (mut gain, mut better, mut lower) = (0.0, 0, 0);
        let cases = 40;
        for seed in 0..cases {
            let (input, mut mesh) = edited(seed);
            let region = region_of(&input, &mesh, 2);
            let s = Surface::new(&input);
            let w0 = worst_angle(&mesh, &region);
            let r = relax(&mut mesh, &s, &region, global);
            let w1 = worst_angle(&mesh, &region);
            gain += w1 - w0;
            better += usize::from(w1 > w0);
            lower += usize::from(r.energy_after < r.energy_before);
        }
        let kind = if global { "global" } else { "local" };
        let mean = (gain / cases as f64).to_degrees();
        println!("{kind}: worst angle +{mean:.2} deg on average, better in {better}/{cases}, Eq. 5 lower in {lower}/{cases}");
        assert!(
            mean > 0.0,
            "{kind}: the worst angle got worse on average ({mean} deg)"
        );
        if global {
            assert_eq!(
                lower, cases as usize,
                "global relaxation left Eq. 5 as it was"
            );
        }
    }
}

/// On a flat equilateral lattice every vertex is at rest: Eq. 5 is zero around the centre
/// and neither relaxation moves anything by more than rounding.
#[test]
fn lattice_at_rest_does_not_move() {
    let mesh = lattice(N, 0.0);
    let region = relax_region(&mesh.map, &[centre()], 3);
    assert_eq!(region.len(), 37); // 1 + 6 + 12 + 18
    let d = mean_edge_length(&mesh);
    assert!((d - 1.0).abs() < 1e-12);
    assert!(relax_energy(&mesh, &region, d) < 1e-20);
    let s = Surface::new(&mesh);
    for global in [false, true] {
        let mut m = mesh.clone();
        relax(&mut m, &s, &region, global);
        let worst = m
            .positions
            .iter()
            .zip(&mesh.positions)
            .map(|(a, b)| a.distance(*b))
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "global {global}: moved by {worst}");
    }
}

/// A vertex off its place in a flat lattice goes back to it, under either relaxation.
#[test]
fn a_displaced_vertex_goes_back() {
    let rest = lattice(N, 0.0);
    let mut mesh = rest.clone();
    let c = centre();
    mesh.positions[c.index()] += DVec3::new(0.31, -0.22, 0.0);
    let s = Surface::new(&rest);
    for global in [false, true] {
        let mut m = mesh.clone();
        let r = relax(&mut m, &s, &[c], global);
        let off = m.positions[c.index()].distance(rest.positions[c.index()]);
        assert!(off < 1e-6, "global {global}: still {off} off");
        assert!(r.energy_after < r.energy_before && r.moved == 1);
    }
}

/// A change that makes a mesh bad input.
type Spoil = fn(&mut Mesh);

/// Dead vertices, non-finite or missing positions are refused with the mesh unchanged;
/// an empty region, boundary vertices and a collapsed (all-degenerate) mesh move nothing.
#[test]
fn bad_input_is_refused_and_degenerate_input_moves_nothing() {
    let (input, mesh) = edited(7);
    let s = Surface::new(&input);
    let region = region_of(&input, &mesh, 1);
    let cases: [(Spoil, RelaxError); 3] = [
        (
            |m| m.positions[centre().index()].y = f64::NAN,
            RelaxError::NonFinite(centre()),
        ),
        (
            |m| m.positions.truncate(centre().index()),
            RelaxError::NonFinite(centre()),
        ),
        (|_| (), RelaxError::DeadHandle(Vert::new(9999))),
    ];
    for (spoil, want) in cases {
        let mut bad = mesh.clone();
        spoil(&mut bad);
        let mut region = region.clone();
        region.insert(0, centre());
        if want == RelaxError::DeadHandle(Vert::new(9999)) {
            region.push(Vert::new(9999));
        }
        let copy = bad.clone();
        assert_eq!(relax_local(&mut bad, &s, &region, 3), Err(want));
        assert_eq!(format!("{bad:?}"), format!("{copy:?}"));
        assert_eq!(relax_global(&mut bad, &s, &region, 3), Err(want));
        assert_eq!(format!("{bad:?}"), format!("{copy:?}"));
    }
    let mut m = mesh.clone();
    let boundary: Vec<Vert> = m
        .map
        .vertices()
        .filter(|&v| m.map.is_boundary_vertex(v))
        .collect();
    for region in [&[][..], &boundary[..]] {
        let r = relax_global(&mut m, &s, region, 3).unwrap();
        assert_eq!((r.movable, r.moved, r.iterations), (0, 0, 0));
        assert_eq!(relax_local(&mut m, &s, region, 3).unwrap().moved, 0);
    }
    assert_eq!(m, mesh);
    let mut flat = mesh.clone();
    flat.positions.iter_mut().for_each(|p| *p = DVec3::ONE);
    let copy = flat.clone();
    let all: Vec<Vert> = flat.map.vertices().collect();
    assert_eq!(
        relax_local(&mut flat, &Surface::new(&copy), &all, 3)
            .unwrap()
            .moved,
        0
    );
    assert_eq!(
        relax_global(&mut flat, &Surface::new(&copy), &all, 3)
            .unwrap()
            .moved,
        0
    );
    assert_eq!(flat, copy);
}

/// A vertex without neighbours (unreferenced by any face) is not live: refused.
#[test]
fn an_isolated_vertex_is_a_dead_handle() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
    let (mut mesh, report) = Mesh::from_polygons(p, &[[0u32, 1, 2]]).unwrap();
    assert_eq!(report.unreferenced, vec![Vert::new(3)]);
    let s = Surface::new(&mesh);
    let r = relax_local(&mut mesh, &s, &[Vert::new(3)], 1);
    assert_eq!(r, Err(RelaxError::DeadHandle(Vert::new(3))));
}

/// The touched vertices of a flip are its four corners, and of no edit none.
#[test]
fn touched_vertices_of_a_flip() {
    let before = lattice(6, 0.0).map;
    let mut after: Map = before.clone();
    assert!(touched_vertices(&before, &after).is_empty());
    let d = after.vertex_darts(Vert::new(14)).next().unwrap();
    let corners = [
        after.origin(d),
        after.dest(d),
        after.dest(after.next(d)),
        after.dest(after.next(d.twin())),
    ];
    tri::flip_edge(&mut after, d).unwrap();
    let mut want = corners.to_vec();
    want.sort();
    assert_eq!(touched_vertices(&before, &after), want);
}

/// `Surface::closest` is the nearest point of the surface, on small surfaces (searched
/// whole, at most 64 triangles) and larger ones (searched by cells): its distance equals a
/// brute-force distance to every triangle, and it lies on the surface.
#[test]
fn closest_point_is_the_nearest_small_or_large() {
    let mut rng = Rng::new(11);
    for n in [4, 6, 12, 20] {
        let mesh = lattice(n, 0.8);
        let s = Surface::new(&mesh);
        for _ in 0..200 {
            let u = |r: &mut Rng, k: f64| (r.below(10_000) as f64 / 10_000.0) * k;
            let p = DVec3::new(
                u(&mut rng, n as f64 * 1.5) - 1.0,
                u(&mut rng, n as f64) - 1.0,
                u(&mut rng, 4.0) - 2.0,
            );
            let q = s.closest(p);
            assert!(
                (q.distance(p) - to_surface(&mesh, p)).abs() < 1e-9,
                "n {n}, {p}"
            );
            assert!(to_surface(&mesh, q) < 1e-9);
        }
    }
}
