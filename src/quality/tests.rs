//! Each measure on hand-made elements, degenerate input, and invariance under rigid motions
//! and uniform scaling.

use alloc::vec;
use alloc::vec::Vec;

use glam::{DQuat, DVec3};
use proptest::prelude::*;

use super::*;
use crate::map::Face;
use crate::{gen, Mesh};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

const SQUARE: [DVec3; 4] = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];

#[test]
fn a_square_is_perfect() {
    assert_eq!(scaled_jacobian(&SQUARE), 1.0);
    assert!(!diagonal_fold(&SQUARE) && !corner_fold(&SQUARE));
    assert_eq!(
        angles(&SQUARE),
        Angles {
            min: 90.0,
            max: 90.0
        }
    );
    assert_eq!(edge_ratio(&SQUARE), 1.0);
    let q = FaceQuality::of_corners(&SQUARE, DVec3::Z);
    assert!(!q.folds.any() && !q.degenerate && !q.flipped);
    // Its mirror image reads the same: the measures do not depend on the orientation.
    let mirror = SQUARE.map(|p| v(p.x, p.y, -p.z) * -1.0);
    assert_eq!(scaled_jacobian(&mirror), 1.0);
}

#[test]
fn a_parallelogram_reads_the_sine_of_its_angle() {
    // Sides 1 and 2 at 60 degrees.
    let (c, s) = (0.5, 0.75f64.sqrt());
    let p = [
        DVec3::ZERO,
        DVec3::X,
        v(1.0 + 2.0 * c, 2.0 * s, 0.0),
        v(2.0 * c, 2.0 * s, 0.0),
    ];
    assert!((scaled_jacobian(&p) - s).abs() < 1e-15);
    let a = angles(&p);
    assert!((a.min - 60.0).abs() < 1e-12 && (a.max - 120.0).abs() < 1e-12);
    assert!((edge_ratio(&p) - 2.0).abs() < 1e-15);
}

/// Edges p1 p2 and p3 p0 cross; the lobes differ in area, so the quad has a normal.
#[test]
fn a_bow_tie_is_folded_by_the_diagonal_and_corner_tests() {
    let bow = [
        DVec3::ZERO,
        v(2.0, 0.0, 0.0),
        v(0.0, 2.0, 0.0),
        v(1.0, 2.0, 0.0),
    ];
    assert!(diagonal_fold(&bow) && corner_fold(&bow));
    assert!(scaled_jacobian(&bow) < 0.0);
    assert!(crate::optimize::is_folded(&one_face(&bow), Face::new(0)));
}

/// A reflex corner: the quad is a dart, its corner 2 inverted.
#[test]
fn an_inverted_corner_has_a_negative_jacobian() {
    let dart = [DVec3::ZERO, DVec3::X, v(0.25, 0.25, 0.0), DVec3::Y];
    // Corner 2: c2 = (-0.25, 0.75) x (0.75, -0.25) = -0.5 z; n = z; sides sqrt(10)/4 each.
    assert!((scaled_jacobian(&dart) - (-0.5 / (10.0 / 16.0))).abs() < 1e-15);
    assert!(corner_fold(&dart) && diagonal_fold(&dart));
}

/// A square folded along its diagonal p1 p3 by 120 degrees: the two triangles of that split
/// point apart (c0 . c2 < 0), but every corner normal still has a positive part along n.
/// The fold that the diagonal test sees and the scaled Jacobian does not.
#[test]
fn a_taco_fold_is_seen_by_the_diagonal_test_only() {
    let t = 120f64.to_radians();
    let r = 0.5f64.sqrt();
    let u = v(1.0, 1.0, 0.0) / 2f64.sqrt();
    let p2 = v(0.5, 0.5, 0.0) + u * (r * t.cos()) + DVec3::Z * (r * t.sin());
    let taco = [DVec3::ZERO, DVec3::X, p2, DVec3::Y];
    assert!(diagonal_fold(&taco));
    assert!(!corner_fold(&taco));
    assert!(scaled_jacobian(&taco) > 0.0);
}

#[test]
fn a_quad_turned_over_whole_is_seen_by_the_neighbour_test_only() {
    let mut m = gen::grid(3, 3);
    // The middle quad's corners are the interior vertices 5, 6, 10, 9: swapping 5 and 10
    // reverses it, so each of its own tests reads it as sound.
    m.positions.swap(5, 10);
    let middle = FaceQuality::of(&m, Face::new(4)).unwrap();
    assert_eq!(
        middle.folds,
        Folds {
            diagonal: false,
            corner: false,
            neighbours: true
        }
    );
    assert_eq!(middle.scaled_jacobian, Some(1.0));
    // And the same through the summary's shared normals.
    let all = measure_faces(&m);
    assert_eq!(
        all.iter().find(|(f, _)| *f == Face::new(4)).unwrap().1,
        middle
    );
}

#[test]
fn a_flat_triangle_is_degenerate_not_flipped() {
    let flat = [DVec3::ZERO, DVec3::X, v(2.0, 0.0, 0.0)];
    assert_eq!(normal(&flat), None);
    let q = FaceQuality::of_corners(&flat, DVec3::Z);
    assert_eq!((q.angles.min, q.angles.max), (0.0, 180.0));
    assert_eq!(q.edge_ratio, 2.0);
    assert!(q.degenerate && !q.flipped);
    assert_eq!(q.scaled_jacobian, None);
}

#[test]
fn a_triangle_moved_across_its_neighbour_is_flipped() {
    let positions = vec![DVec3::ZERO, DVec3::X, v(1.0, 1.0, 0.0), DVec3::Y];
    let (mut m, _) = Mesh::from_polygons(positions, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    assert_eq!(Summary::of(&m).flipped_triangles, 0);
    m.positions[1] = v(0.2, 0.8, 0.0); // past the diagonal 0 2
    let s = Summary::of(&m);
    assert_eq!(
        (s.triangles, s.flipped_triangles),
        (2, 2),
        "each against the other"
    );
    assert!(FaceQuality::of(&m, Face::new(0)).unwrap().flipped);
}

#[test]
fn thin_triangles_are_counted_below_ten_degrees() {
    let needle = |h: f64| [DVec3::ZERO, DVec3::X, v(0.5, h, 0.0)];
    let mesh = |h| {
        Mesh::from_polygons(needle(h).to_vec(), &[[0u32, 1, 2]])
            .unwrap()
            .0
    };
    // tan(10 degrees) = 0.176: half-width 0.5 at height 0.08 is 9.1 degrees, 0.1 is 11.3.
    assert_eq!(Summary::of(&mesh(0.08)).thin_triangles, 1);
    assert_eq!(Summary::of(&mesh(0.1)).thin_triangles, 0);
}

/// Zero-length sides, NaN and infinite corners, and positions missing altogether: no
/// measure panics, each reads as documented, and the face is flagged degenerate.
#[test]
fn degenerate_geometry_reads_as_documented() {
    let nan = DVec3::splat(f64::NAN);
    let inf = DVec3::splat(f64::INFINITY);
    for p in [
        [DVec3::ZERO, DVec3::ZERO, DVec3::X, DVec3::Y],
        [DVec3::ZERO, DVec3::X, nan, DVec3::Y],
        [DVec3::ZERO, DVec3::X, inf, DVec3::Y],
        [DVec3::ZERO; 4],
        [
            v(1e300, 0.0, 0.0),
            v(-1e300, 0.0, 0.0),
            v(0.0, 1e300, 0.0),
            DVec3::ZERO,
        ],
    ] {
        let q = FaceQuality::of_corners(&p, DVec3::Z);
        let sj = q.scaled_jacobian.unwrap();
        assert!(sj.is_finite() && (-1.0..=1.0).contains(&sj), "{p:?}: {sj}");
        assert!(
            q.angles.min.is_finite() && q.angles.max.is_finite(),
            "{p:?}"
        );
        assert!(!q.edge_ratio.is_nan(), "{p:?}");
        if !p.iter().all(|c| c.is_finite()) || p[0] == p[1] {
            assert!(q.degenerate && sj == 0.0 && !q.folds.any(), "{p:?}: {q:?}");
            assert_eq!(q.edge_ratio, f64::INFINITY);
        }
    }
    for k in 0..3 {
        let short = vec![DVec3::X; k];
        let q = FaceQuality::of_corners(&short, DVec3::Z);
        assert!(q.degenerate && q.angles == Angles { min: 0.0, max: 0.0 });
    }
    // A mesh with a NaN vertex and one missing position: the summary and the reference
    // leave them out where they cannot be read.
    let mut m = gen::grid(3, 3);
    m.positions[5] = nan;
    m.positions.truncate(15);
    let r = Reference::new(&m);
    let s = Summary::against(&m, &r);
    assert!(s.degenerate_faces >= 4 && s.max_edge_ratio.unwrap().is_finite());
    let d = s.distance.unwrap();
    assert_eq!(d.vertices, 14); // 16 vertices, one NaN, one without a position (dropped)
    assert!(d.max.is_finite());
    assert_eq!(
        Reference::new(&Mesh::default()).distance(DVec3::ZERO),
        f64::INFINITY
    );
    assert_eq!(
        Summary::against(&m, &Reference::new(&Mesh::default())).distance,
        None
    );
}

#[test]
fn nearest_rank_percentiles() {
    let x: Vec<f64> = (1..=200).map(f64::from).collect();
    assert_eq!(nearest_rank(&x, 1.0), Some(2.0));
    assert_eq!(nearest_rank(&x, 5.0), Some(10.0));
    assert_eq!(nearest_rank(&x, 50.0), Some(100.0));
    assert_eq!(nearest_rank(&x, 99.0), Some(198.0));
    assert_eq!(nearest_rank(&x, 0.0), Some(1.0));
    assert_eq!(nearest_rank(&x[..1], 1.0), Some(1.0));
    assert_eq!(nearest_rank(&[], 50.0), None);
}

/// The reference's distances are those of `optimize::Surface` (parry's with the `parry`
/// feature, so the two closest-point searches check each other).
#[test]
fn reference_distances_are_those_of_the_surface() {
    let mesh = gen::subdivided_icosahedron(2);
    let (r, s) = (Reference::new(&mesh), crate::geometry::Surface::new(&mesh));
    let mut rng = crate::rng::Rng::new(3);
    let mut u = || rng.below(2_000_001) as f64 / 1_000_000.0 - 1.0;
    for _ in 0..2_000 {
        let p = v(u(), u(), u()) * 1.5;
        let (a, b) = (r.distance(p), s.closest(p).distance(p));
        assert!((a - b).abs() <= 1e-12, "{p}: {a} against {b}");
    }
}

#[test]
fn the_diagonal_test_is_the_optimizers() {
    let mut m = gen::torus_grid(8, 6);
    let mut rng = crate::rng::Rng::new(11);
    for p in &mut m.positions {
        *p += v(1.0, 1.0, 1.0) * (rng.below(1001) as f64 / 1000.0 - 0.5);
    }
    let s = Summary::of(&m);
    assert!(s.folded_by.diagonal > 0, "the jitter folds some quads");
    assert_eq!(s.folded_by.diagonal, crate::optimize::folded_quads(&m));
    assert_eq!(s.folded_by.corner, s.negative_jacobian);
}

fn one_face(p: &[DVec3; 4]) -> Mesh {
    Mesh::from_polygons(p.to_vec(), &[[0u32, 1, 2, 3]])
        .unwrap()
        .0
}

/// A random quad-dominant mesh (quads, triangles and pentagons) with its vertices moved by
/// up to `jitter` in each coordinate, so that some quads fold and some triangles flip.
fn jittered(seed: u64, jitter: f64) -> Mesh {
    let mut m = gen::random_mixed(300, 1, 1, seed);
    let mut rng = crate::rng::Rng::new(seed ^ 0xfeed);
    for p in &mut m.positions {
        let mut u = || (rng.below(2_000_001) as f64 / 1_000_000.0 - 1.0) * jitter;
        *p += v(u(), u(), u());
    }
    m
}

/// Equal up to rounding: coordinates shifted by up to 20 mesh sizes round at ~1e-14 of the
/// mesh, and a thin element's angle or edge ratio (a side 1/200 of another) amplifies
/// that a few hundred times.
fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

fn same_face(a: &FaceQuality, b: &FaceQuality) -> bool {
    a.degree == b.degree
        && a.folds == b.folds
        && a.flipped == b.flipped
        && a.degenerate == b.degenerate
        && close(a.angles.min, b.angles.min)
        && close(a.angles.max, b.angles.max)
        && close(a.edge_ratio, b.edge_ratio)
        && match (a.scaled_jacobian, b.scaled_jacobian) {
            (Some(x), Some(y)) => close(x, y),
            (x, y) => x == y,
        }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// A rotation, a translation and a uniform scaling change no measure: every face's, the
    /// summary's counts, and the distances to a reference moved with the mesh.
    #[test]
    fn rigid_motions_and_scaling_change_no_measure(
        seed in 0u64..1_000,
        jitter in 0.0f64..0.6,
        axis in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
        angle in 0.0f64..6.3,
        shift in (-20.0f64..20.0, -20.0f64..20.0, -20.0f64..20.0),
        log_scale in -3.0f64..3.0,
    ) {
        let reference = gen::random_mixed(300, 1, 1, seed);
        let mesh = jittered(seed, jitter);
        let axis = v(axis.0, axis.1, axis.2).try_normalize().unwrap_or(DVec3::Z);
        let (turn, shift, scale) =
            (DQuat::from_axis_angle(axis, angle), v(shift.0, shift.1, shift.2), 10f64.powf(log_scale));
        let moved = |m: &Mesh| Mesh {
            map: m.map.clone(),
            positions: m.positions.iter().map(|&p| (turn * p + shift) * scale).collect(),
        };
        let (before, after) = (measure_faces(&mesh), measure_faces(&moved(&mesh)));
        for ((f, a), (g, b)) in before.iter().zip(&after) {
            prop_assert_eq!(f, g);
            prop_assert!(same_face(a, b), "{:?}: {:?} against {:?}", f, a, b);
        }
        let a = Summary::against(&mesh, &Reference::new(&reference));
        let b = Summary::against(&moved(&mesh), &Reference::new(&moved(&reference)));
        prop_assert_eq!(
            (a.folded_quads, a.folded_by, a.negative_jacobian, a.thin_triangles),
            (b.folded_quads, b.folded_by, b.negative_jacobian, b.thin_triangles)
        );
        prop_assert_eq!((a.flipped_triangles, a.degenerate_faces), (b.flipped_triangles, b.degenerate_faces));
        let (da, db) = (a.distance.unwrap(), b.distance.unwrap());
        // The box is axis-aligned: a rotation changes its diagonal, the unit of the
        // distances, and not the distances themselves.
        let unit = |r: &Mesh, s: f64| Reference::new(r).diagonal() / s;
        let (ua, ub) = (unit(&reference, 1.0), unit(&moved(&reference), scale));
        for (x, y) in [(da.mean, db.mean), (da.p99, db.p99), (da.max, db.max)] {
            prop_assert!((x * ua - y * ub).abs() <= 1e-9 * ua, "{} against {}", x * ua, y * ub);
        }
        // Without the rotation, the relative distances are the same too.
        let shifted = |m: &Mesh| Mesh {
            map: m.map.clone(),
            positions: m.positions.iter().map(|&p| (p + shift) * scale).collect(),
        };
        let c = Summary::against(&shifted(&mesh), &Reference::new(&shifted(&reference)));
        let dc = c.distance.unwrap();
        for (x, y) in [(da.mean, dc.mean), (da.p99, dc.p99), (da.max, dc.max)] {
            prop_assert!((x - y).abs() <= 1e-9, "{} against {}", x, y);
        }
    }
}
