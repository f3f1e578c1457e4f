//! 5-5-7-7 generation with the two pairs apart (`generate_quadruple_apart`, irregular-vertex
//! paper Sec. 7.3): the four vertices form a polygon whose opposite sides are equal; the
//! pairs walk back and the quadruple is removed, back to the regular start; refusals leave
//! the map unchanged.

mod common;

use common::tri::irregular;
use zipmesh::gen;
use zipmesh::tri_edit::{
    can_generate_quadruple_apart, generate_quadruple_apart, move_pair, quadruple_sides,
    remove_quadruple, Direction, Quadruple, TriEditError,
};
use zipmesh::{is_isomorphic, ops::Refusal, Dart, Map, Vert};

/// An `n x n` triangulated torus: every vertex regular.
fn regular_torus(n: usize) -> Map {
    let tris: Vec<[u32; 3]> = gen::torus_quads(n, n)
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    Map::from_polygons(n * n, &tris).unwrap()
}

const HOWS: [Quadruple; 2] = [Quadruple::Flip, Quadruple::Split];

/// One generation: a refusal equal to `can_*`'s with the map `==`, or `[5, 7, 5, 7]` in
/// polygon order, exactly four irregular vertices more, `check()`, exact undo. Returns the
/// four vertices on the edited copy.
fn generate(
    map: &Map,
    d: Dart,
    how: Quadruple,
    dir: Direction,
    k: usize,
) -> Option<(Map, [Vert; 4])> {
    let mut m = map.clone();
    let can = can_generate_quadruple_apart(&m, d, how, dir, k);
    let g = match generate_quadruple_apart(&mut m, d, how, dir, k) {
        Ok(g) => g,
        Err(e) => {
            assert_eq!(can, Err(e));
            assert_eq!(&m, map);
            return None;
        }
    };
    assert_eq!(can, Ok(()));
    m.check().unwrap();
    let four: [Vert; 4] = g.vertices().try_into().unwrap();
    assert_eq!(four.map(|v| m.valence(v)), [5, 7, 5, 7]);
    assert_eq!(irregular(&m).len(), irregular(map).len() + 4);
    assert!(k > 0 || g.in_two_triangles(&m));
    let mut back = m.clone();
    g.undo(&mut back).unwrap();
    assert_eq!(&back, map);
    Some((m, four))
}

#[test]
fn opposite_sides_are_equal() {
    let map = regular_torus(24);
    let d = map.vertex_dart(Vert::new(300));
    let (mut applied, mut far, mut unequal_control) = (0, 0, 0);
    for how in HOWS {
        for dir in Direction::ALL {
            for k in 0..=6 {
                let Some((m, four)) = generate(&map, d, how, dir, k) else {
                    continue;
                };
                applied += 1;
                let s = quadruple_sides(&m, four, 40).expect("sides on a regular torus");
                // The pairs stay adjacent; opposite sides equal.
                assert_eq!((s[0], s[2]), ((1, 0), (1, 0)), "{how:?} {dir:?} {k}");
                assert_eq!(s[1], s[3], "{how:?} {dir:?} {k}: {s:?}");
                far += usize::from(s[1].0 + s[1].1 >= 3);
                // Control: the other order of the moving pair is not a parallelogram.
                let c = quadruple_sides(&m, [four[0], four[1], four[3], four[2]], 40).unwrap();
                unequal_control += usize::from(c[1] != c[3]);
            }
        }
    }
    println!("{applied} generations, {far} with the pairs 3+ edges apart, {unequal_control} controls unequal");
    assert!(applied >= 60, "{applied}");
    assert!(far >= 20, "{far}");
    assert!(unequal_control >= applied / 2, "{unequal_control}");
}

#[test]
fn the_pair_walks_back_and_the_quadruple_goes() {
    let map = regular_torus(20);
    let d = map.vertex_dart(Vert::new(210));
    let mut checked = 0;
    for how in HOWS {
        for dir in Direction::ALL {
            let k = 4;
            let Some((mut m, four)) = generate(&map, d, how, dir, k) else {
                continue;
            };
            // Removal needs the two pairs in two triangles: refused now.
            assert_eq!(
                remove_quadruple(&mut m.clone(), &four).unwrap_err(),
                TriEditError::NotAPair
            );
            let (mut p, mut q) = (four[2], four[3]);
            for _ in 0..k {
                let step = move_pair(&mut m, p, q, dir.opposite()).unwrap();
                (p, q) = (step.p(), step.q());
            }
            remove_quadruple(&mut m, &[four[0], four[1], p, q]).unwrap();
            assert!(irregular(&m).is_empty());
            assert!(is_isomorphic(&m, &map), "{how:?} {dir:?}");
            checked += 1;
        }
    }
    println!("{checked} walked back and removed");
    assert!(checked >= 8, "{checked}");
}

#[test]
fn refusals_leave_the_map() {
    let map = regular_torus(12);
    let d = map.vertex_dart(Vert::new(50));
    let mut m = map.clone();
    let r = generate_quadruple_apart(&mut m, d, Quadruple::CollapseFlip, Direction::FlipLeft, 1);
    assert_eq!(r.unwrap_err(), TriEditError::WrongValence);
    let too_many = map.vertex_slots() + 1;
    let r = generate_quadruple_apart(&mut m, d, Quadruple::Flip, Direction::FlipLeft, too_many);
    assert_eq!(r.unwrap_err(), TriEditError::Refused(Refusal::BadArguments));
    // As many steps as vertex slots is not too many: the walk itself decides.
    let (how, dir) = (Quadruple::Split, Direction::SplitLeft);
    let r = generate_quadruple_apart(&mut m, d, how, dir, map.vertex_slots());
    assert_ne!(r.unwrap_err(), TriEditError::Refused(Refusal::BadArguments));
    assert_eq!(m, map);
    // On a 12 x 12 torus a straight walk comes round and meets the staying pair.
    let errs: Vec<_> = HOWS
        .iter()
        .flat_map(|&how| {
            Direction::ALL
                .map(|dir| generate_quadruple_apart(&mut map.clone(), d, how, dir, 12).err())
        })
        .collect();
    assert!(errs.contains(&Some(TriEditError::Irregular)));
    assert_eq!(m, map);
    // A v5 of the icosahedron cannot be the start.
    let ico = gen::geodesic_sphere(0);
    let mut i = ico.clone();
    let r = generate_quadruple_apart(
        &mut i,
        ico.vertex_dart(Vert::new(0)),
        Quadruple::Flip,
        Direction::FlipLeft,
        1,
    );
    assert_eq!(r.unwrap_err(), TriEditError::WrongValence);
    assert_eq!(i, ico);
}

#[test]
fn other_meshes_refuse_or_apply() {
    let (mut applied, mut refused, mut sides_found, mut equal) = (0, 0, 0, 0);
    let meshes = (0..4)
        .map(|seed| gen::random_triangle(400, seed as usize % 3, 0, seed).map)
        .chain([gen::geodesic_sphere(3), gen::geodesic_sphere(4)]);
    for map in meshes {
        for (i, d) in map.darts().enumerate().step_by(7) {
            let how = HOWS[i % 2];
            let dir = Direction::ALL[i % 6];
            match generate(&map, d, how, dir, i % 4) {
                Some((m, four)) => {
                    applied += 1;
                    // Sides need straight lines through regular vertices: often blocked here.
                    if let Some(s) = quadruple_sides(&m, four, 12) {
                        sides_found += 1;
                        assert_eq!((s[0], s[2]), ((1, 0), (1, 0)));
                        // Opposite sides are equal on the regular lattice (the test above);
                        // here other irregular vertices may lie inside the polygon.
                        equal += usize::from(s[1] == s[3]);
                    }
                }
                None => refused += 1,
            }
        }
    }
    println!(
        "{applied} applied, {refused} refused, sides measured on {sides_found} (skipped on {}: \
         a side with no straight path through regular vertices), opposite sides equal on {equal}",
        applied - sides_found
    );
    assert!(applied >= 20 && refused >= 20, "{applied} {refused}");
}
