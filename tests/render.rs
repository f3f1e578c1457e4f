//! `zipmesh::render`: the SVG's balls are exactly the seen interior singularities with their
//! recounted valences and colours; on convex meshes the near side is seen and the far side
//! is not; an occluding face hides a ball; PNG decodes at the asked size with ball colours
//! where the balls are; paths are checked and drawn where seen.
#![cfg(feature = "render")]

mod common;

use common::svg::{assert_xmlish, circles, elements};
use glam::DVec3;
use proptest::prelude::*;
use std::collections::BTreeSet;
use std::path::Path;
use zipmesh::invariants::{is_irregular, MeshKind};
use zipmesh::render::{Options, RenderError, Scene, View};
use zipmesh::{gen, io, Map, Mesh, Vert};

fn shared(rel: &str) -> Mesh {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(rel);
    io::read_mesh(&p)
        .unwrap_or_else(|e| panic!("shared mesh {rel}: {e}"))
        .0
}

fn at(view: Option<(f64, f64)>, width: u32, height: u32) -> Options {
    Options {
        view: view.map(|(a, e)| View::new(a, e).unwrap()),
        width,
        height,
        paths: Vec::new(),
        point_paths: Vec::new(),
        legend: true,
    }
}

/// The interior singularities of `map` by the invariants module's rule, independently of
/// `render::singularities`.
fn interior_irregular(map: &Map) -> BTreeSet<usize> {
    let kind = MeshKind::of(map);
    zipmesh::invariants::irregular_vertices(map, kind)
        .into_iter()
        .filter(|&v| !map.is_boundary_vertex(v))
        .map(|v| v.index())
        .collect()
}

/// The colour table, written out again (quad-dominant meshes use the quad colours).
fn colour(kind: MeshKind, valence: usize) -> &'static str {
    match (kind, valence) {
        (MeshKind::Triangle, 5) => "blue",
        (MeshKind::Triangle, 7) => "orange",
        (MeshKind::Triangle, _) => "red",
        (_, 3) => "blue",
        (_, 5) => "orange",
        (_, 2) => "green",
        _ => "red",
    }
}

/// Every circle is a seen interior singularity, once, with its recounted valence as class
/// and its kind's colour; every seen one has a circle; unseen ones have none.
fn check_circles(mesh: &Mesh, options: &Options) -> Scene {
    let scene = Scene::new(mesh, options).unwrap();
    let svg = scene.svg();
    assert_xmlish(&svg);
    let map = &mesh.map;
    let kind = MeshKind::of(map);
    let cs = circles(&svg);
    let drawn: BTreeSet<usize> = cs.iter().map(|c| c.vertex).collect();
    assert_eq!(drawn.len(), cs.len(), "a vertex with two circles");
    let singular = interior_irregular(map);
    for c in &cs {
        let v = Vert::new(c.vertex as u32);
        assert!(
            singular.contains(&c.vertex),
            "circle on a regular vertex {v}"
        );
        assert_eq!(c.class, format!("v{}", map.valence(v)));
        assert_eq!(
            c.fill,
            format!("url(#ball-{})", colour(kind, map.valence(v)))
        );
    }
    let all: BTreeSet<usize> = scene.balls().iter().map(|b| b.vertex.index()).collect();
    assert_eq!(
        all, singular,
        "the scene's balls are the interior singularities"
    );
    let seen: BTreeSet<usize> = scene
        .balls()
        .iter()
        .filter(|b| b.visible)
        .map(|b| b.vertex.index())
        .collect();
    assert_eq!(drawn, seen);
    scene
}

#[test]
fn circles_are_the_seen_interior_singularities() {
    let meshes = [
        ("spot quad", shared("quad/spot_quadrangulated.obj")),
        ("spot tri", shared("tri/spot_triangulated.obj")),
        ("blub", shared("quad/blub_quadrangulated.obj")),
        ("cubespikes", shared("quad/cubespikes.obj")),
        ("disk", shared("tri/circle_disk.obj")),
        ("cube", gen::cube(3)),
        ("mixed", gen::random_mixed(300, 1, 1, 5)),
    ];
    for (name, mesh) in &meshes {
        let mut partly_hidden = false;
        for view in [
            None,
            Some((0.0, 0.0)),
            Some((200.0, -35.0)),
            Some((75.0, 90.0)),
        ] {
            let scene = check_circles(mesh, &at(view, 640, 480));
            let seen = scene.balls().iter().filter(|b| b.visible).count();
            partly_hidden |= seen > 0 && seen < scene.balls().len();
        }
        let closed = mesh.map.boundary_loops().is_empty();
        assert!(
            !closed || partly_hidden,
            "{name}: never a hidden and a seen ball"
        );
    }
}

/// Newell normal of a face.
fn normal(mesh: &Mesh, f: zipmesh::Face) -> DVec3 {
    let c: Vec<DVec3> = mesh
        .map
        .face_darts(f)
        .map(|d| mesh.positions[mesh.map.origin(d).index()])
        .collect();
    let mut n = DVec3::ZERO;
    for i in 0..c.len() {
        n += c[i].cross(c[(i + 1) % c.len()]);
    }
    n.normalize()
}

/// The signed volume of a closed mesh (positive: faces oriented outward).
fn volume(mesh: &Mesh) -> f64 {
    let mut v = 0.0;
    for f in mesh.map.faces() {
        let c: Vec<DVec3> = mesh
            .map
            .face_darts(f)
            .map(|d| mesh.positions[mesh.map.origin(d).index()])
            .collect();
        for i in 1..c.len() - 1 {
            v += c[0].dot(c[i].cross(c[i + 1])) / 6.0;
        }
    }
    v
}

/// On a convex closed mesh, a vertex is seen iff one of its faces faces the eye. Expected
/// from the face normals alone (with a margin of 0.2 in the cosine either way), compared
/// with the drawn circles.
#[test]
fn convex_meshes_show_the_near_side_and_hide_the_far_side() {
    let meshes = [
        ("cube", gen::cube(3)),
        ("icosahedron", gen::icosahedron()),
        ("cc icosahedron", gen::subdivided_icosahedron(2)),
        (
            "cc cube",
            gen::catmull_clark(&gen::catmull_clark(&gen::cube(1))),
        ),
    ];
    for (name, mesh) in &meshes {
        assert!(volume(mesh) > 0.0, "{name} is oriented outward");
        let (mut near, mut far) = (0, 0);
        for az in (0..360).step_by(40) {
            for el in [-70.0, -30.0, 0.0, 25.0, 60.0] {
                let view = View::new(az as f64, el).unwrap();
                let eye = view.toward_eye();
                let scene = check_circles(mesh, &at(Some((view.azimuth, el)), 600, 500));
                let drawn: BTreeSet<usize> =
                    circles(&scene.svg()).iter().map(|c| c.vertex).collect();
                for b in scene.balls() {
                    let map = &mesh.map;
                    let facing = map
                        .vertex_darts(b.vertex)
                        .filter_map(|d| map.face(d))
                        .map(|f| normal(mesh, f).dot(eye))
                        .fold(f64::NEG_INFINITY, f64::max);
                    let shown = drawn.contains(&b.vertex.index());
                    if facing > 0.2 {
                        near += 1;
                        assert!(shown, "{name} at {view:?}: near vertex {} hidden", b.vertex);
                    } else if facing < -0.2 {
                        far += 1;
                        assert!(!shown, "{name} at {view:?}: far vertex {} drawn", b.vertex);
                    }
                }
            }
        }
        // A cube's corner is far only when all three of its faces turn away: one a view.
        assert!(near > 100 && far > 10, "{name}: {near} near, {far} far");
    }
}

/// The cube's corner nearest the eye, and the cube plus one extra quad (its own component,
/// boundary corners only, so no ball of its own) placed by `quad(corner, eye, right, up)`.
fn cube_with(quad: impl Fn(DVec3, DVec3, DVec3, DVec3) -> [DVec3; 4]) -> (Mesh, Mesh, Vert) {
    let cube = gen::cube(2);
    let view = View::new(30.0, 20.0).unwrap();
    let eye = view.toward_eye();
    let corner = (0..cube.positions.len())
        .max_by(|&a, &b| {
            cube.positions[a]
                .dot(eye)
                .total_cmp(&cube.positions[b].dot(eye))
        })
        .unwrap();
    assert_eq!(cube.positions[corner], DVec3::ONE);
    let right = DVec3::Y.cross(eye).normalize();
    let up = eye.cross(right);
    let mut positions = cube.positions.clone();
    let base = positions.len() as u32;
    positions.extend(quad(DVec3::ONE, eye, right, up));
    let mut polys = cube.polygons();
    polys.push((base..base + 4).collect());
    let (with, _) = Mesh::from_polygons(positions, &polys).unwrap();
    (cube, with, Vert::new(corner as u32))
}

fn drawn(mesh: &Mesh) -> BTreeSet<usize> {
    let scene = check_circles(mesh, &at(Some((30.0, 20.0)), 600, 500));
    circles(&scene.svg()).iter().map(|c| c.vertex).collect()
}

#[test]
fn an_occluding_face_hides_a_ball() {
    // A small square between the eye and the corner, facing the eye.
    let (cube, with, corner) = cube_with(|c, eye, r, u| {
        let m = c + 0.8 * eye;
        [
            m - 0.2 * r - 0.2 * u,
            m + 0.2 * r - 0.2 * u,
            m + 0.2 * r + 0.2 * u,
            m - 0.2 * r + 0.2 * u,
        ]
    });
    let before = drawn(&cube);
    let after = drawn(&with);
    assert_eq!(before.len(), 7);
    assert!(before.contains(&corner.index()) && !after.contains(&corner.index()));
    let mut rest = before.clone();
    rest.remove(&corner.index());
    assert_eq!(after, rest, "only the covered corner disappears");
}

/// A long slanted quad: in front of the corner where it covers it, but its centre (and so
/// its place in a far-to-near painting order) far behind the cube. Visibility comes from the
/// depth at the ball, not from the order faces are painted in.
#[test]
fn a_slanted_face_behind_on_average_still_hides_the_ball() {
    let (cube, with, corner) = cube_with(|c, eye, r, u| {
        let near = c + 0.3 * eye;
        let far = c - 6.0 * eye;
        [
            near - 0.1 * r - 0.1 * u,
            near + 0.1 * r - 0.1 * u,
            far + 0.1 * r + 3.0 * u,
            far - 0.1 * r + 3.0 * u,
        ]
    });
    let scene = Scene::new(&with, &at(Some((30.0, 20.0)), 600, 500)).unwrap();
    let slanted = scene
        .faces()
        .iter()
        .find(|f| f.face.index() == cube.map.num_faces());
    let corner_depth = scene
        .balls()
        .iter()
        .find(|b| b.vertex == corner)
        .unwrap()
        .centre
        .z;
    assert!(
        slanted.is_some_and(|f| f.depth > corner_depth),
        "drawn, centre behind"
    );
    assert!(drawn(&cube).contains(&corner.index()));
    assert!(!drawn(&with).contains(&corner.index()));
}

/// The PNG's pixels: (r, g, b) at `(x, y)`, after checking the signature and the IHDR size.
fn decode(png: &[u8], width: u32, height: u32) -> impl Fn(f64, f64) -> [u8; 3] {
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&png[12..16], b"IHDR");
    assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), width);
    assert_eq!(u32::from_be_bytes(png[20..24].try_into().unwrap()), height);
    let mut reader = png::Decoder::new(png).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (width, height));
    let channels = info.color_type.samples();
    move |x: f64, y: f64| {
        let i = (y as usize * width as usize + x as usize) * channels;
        [buf[i], buf[i + 1], buf[i + 2]]
    }
}

#[test]
fn png_has_the_size_and_ball_colours_where_the_balls_are() {
    for (mesh, (w, h)) in [
        (gen::cube(3), (320, 240)),
        (gen::icosahedron(), (200, 300)),
        (shared("quad/spot_quadrangulated.obj"), (900, 700)),
    ] {
        let scene = Scene::new(&mesh, &at(None, w, h)).unwrap();
        let pixel = decode(&scene.png().unwrap(), w, h);
        assert_eq!(pixel(1.0, 1.0), [255, 255, 255], "background");
        let mut checked = 0;
        for b in scene.balls().iter().filter(|b| b.visible) {
            // Balls drawn later may cover this one: check only balls with none near.
            let alone = scene.balls().iter().filter(|o| o.visible).all(|o| {
                o.vertex == b.vertex
                    || (o.centre.truncate() - b.centre.truncate()).length() > 2.5 * scene.radius()
            });
            if !alone {
                continue;
            }
            let [r, g, bl] = pixel(b.centre.x, b.centre.y).map(i32::from);
            let ok = match (MeshKind::of(&mesh.map), b.valence) {
                (MeshKind::Quad, 3) | (MeshKind::Triangle, 5) => bl > r + 40 && bl > g + 20,
                (MeshKind::Quad, 5) => r > bl + 60 && g > bl,
                _ => r > g + 40 && r > bl + 40,
            };
            assert!(ok, "ball at {} has colour {r},{g},{bl}", b.vertex);
            checked += 1;
        }
        assert!(checked >= 5, "only {checked} balls checked");
    }
}

#[test]
fn sizes_out_of_range_are_refused() {
    let cube = gen::cube(1);
    for (w, h) in [(0, 10), (10, 0), (16385, 10), (10, u32::MAX)] {
        let e = Scene::new(&cube, &at(None, w, h)).unwrap_err();
        assert_eq!(
            e,
            RenderError::Size {
                width: w,
                height: h
            }
        );
    }
    check_circles(&cube, &at(None, 16384, 3));
    check_circles(&cube, &at(None, 1, 16384));
    let big = Scene::new(&cube, &at(None, 9000, 8000)).unwrap();
    assert!(matches!(big.png(), Err(RenderError::PngSize { .. })));
}

#[test]
fn views_out_of_range_and_bad_positions_are_refused() {
    assert!(View::new(0.0, 90.5).is_err() && View::new(f64::INFINITY, 0.0).is_err());
    assert!(View::new(-720.0, -90.0).is_ok());
    let mut cube = gen::cube(1);
    cube.positions[3].y = f64::NAN;
    let e = Scene::new(&cube, &Options::default()).unwrap_err();
    assert_eq!(e, RenderError::Position { vertex: 3 });
    cube.positions.truncate(2);
    assert!(matches!(
        Scene::new(&cube, &Options::default()),
        Err(RenderError::Position { .. })
    ));
}

#[test]
fn bad_path_entries_are_refused() {
    // Vertex 1 is unreferenced: a dead slot.
    let p = vec![DVec3::ZERO, DVec3::ONE, DVec3::X, DVec3::Y];
    let (mesh, _) = Mesh::from_polygons(p, &[[0u32, 2, 3]]).unwrap();
    for (paths, entry, vertex) in [
        (vec![vec![0, 2], vec![3, 4]], (1, 1), 4),
        (vec![vec![0, 1]], (0, 1), 1),
        (vec![vec![u64::MAX]], (0, 0), u64::MAX),
    ] {
        let o = Options {
            paths,
            ..Options::default()
        };
        let e = Scene::new(&mesh, &o).unwrap_err();
        assert_eq!(
            e,
            RenderError::PathVertex {
                path: entry.0,
                entry: entry.1,
                vertex,
                slots: 4
            }
        );
    }
}

#[test]
fn a_seen_path_is_a_polyline_and_a_hidden_one_is_not() {
    let cube = gen::cube(3);
    let eye = View::new(30.0, 20.0).unwrap().toward_eye();
    // The edge x = 1, z = 1 (facing the eye), bottom to top; and the hidden x = 0, z = 0.
    let along = |x: f64, z: f64| -> Vec<u64> {
        let mut vs: Vec<(f64, u64)> = (0..cube.positions.len())
            .filter(|&i| {
                let p = cube.positions[i];
                p.x == x && p.z == z
            })
            .map(|i| (cube.positions[i].y, i as u64))
            .collect();
        vs.sort_by(|a, b| a.0.total_cmp(&b.0));
        vs.into_iter().map(|(_, i)| i).collect()
    };
    let (seen, hidden) = (along(1.0, 1.0), along(0.0, 0.0));
    assert!(DVec3::new(1.0, 0.5, 1.0).dot(eye) > DVec3::new(0.0, 0.5, 0.0).dot(eye));
    let o = |paths| Options {
        view: Some(View::new(30.0, 20.0).unwrap()),
        paths,
        ..Options::default()
    };
    let plain = Scene::new(&cube, &o(vec![])).unwrap().svg();
    assert_eq!(elements(&plain, "polyline").len(), 0);
    let svg = Scene::new(&cube, &o(vec![seen.clone()])).unwrap().svg();
    let lines = elements(&svg, "polyline");
    assert_eq!(lines.len(), 1);
    let points = common::svg::attr(lines[0], "points").unwrap();
    assert_eq!(points.split(' ').count(), seen.len());
    let svg = Scene::new(&cube, &o(vec![hidden.clone()])).unwrap().svg();
    assert_eq!(elements(&svg, "polyline").len(), 0);
    // The same paths given as points (as `optimize --paths` writes them) draw the same.
    let as_points = |vs: &[u64]| -> Vec<[f64; 3]> {
        vs.iter()
            .map(|&v| cube.positions[v as usize].to_array())
            .collect()
    };
    let p = |point_paths| Options {
        view: Some(View::new(30.0, 20.0).unwrap()),
        point_paths,
        ..Options::default()
    };
    let by_points = Scene::new(&cube, &p(vec![as_points(&seen)])).unwrap().svg();
    assert_eq!(elements(&by_points, "polyline"), lines);
    let svg = Scene::new(&cube, &p(vec![as_points(&hidden)]))
        .unwrap()
        .svg();
    assert_eq!(elements(&svg, "polyline").len(), 0);
    let bad = p(vec![vec![[0.0, f64::NAN, 0.0]]]);
    assert!(matches!(
        Scene::new(&cube, &bad),
        Err(zipmesh::render::RenderError::PathPoint { path: 0, entry: 0 })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random quad, triangle and quad-dominant meshes, random views and sizes: a picture is
    /// always made, and its circles are the seen singularities with their valences.
    #[test]
    fn random_meshes_render_with_matching_circles(
        family in 0..3u8,
        faces in 16usize..400,
        genus in 0usize..3,
        holes in 0usize..2,
        seed in any::<u64>(),
        az in -360.0f64..360.0,
        el in -90.0f64..=90.0,
        w in 1u32..500,
        h in 1u32..500,
    ) {
        let mesh = match family {
            0 => gen::random_quad(faces, genus, holes, seed),
            1 => gen::random_triangle(faces, genus, holes, seed),
            _ => gen::random_mixed(faces, genus, holes, seed),
        };
        let scene = check_circles(&mesh, &at(Some((az, el)), w, h));
        for b in scene.balls() {
            prop_assert!(is_irregular(&mesh.map, MeshKind::of(&mesh.map), b.vertex));
        }
    }
}

/// A pillow: two quads glued along all four edges, a sphere whose four vertices have
/// valence 2 (green balls); flat, so both quads lie on every ball.
#[test]
fn valence_two_vertices_are_green() {
    let p = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
    ];
    let (mesh, _) = Mesh::from_polygons(p, &[[0u32, 1, 2, 3], [0, 3, 2, 1]]).unwrap();
    let scene = check_circles(&mesh, &at(Some((10.0, 10.0)), 300, 300));
    let cs = circles(&scene.svg());
    assert_eq!(cs.len(), 4);
    assert!(cs
        .iter()
        .all(|c| c.class == "v2" && c.fill == "url(#ball-green)"));
}

/// The legend has one row per valence of the interior singularities, seen or not, with its
/// colour and count (Spot: 56 v3, 40 v5, 4 v6 among its 100), and `legend: false` drops it.
#[test]
fn the_legend_counts_each_valence() {
    let (mesh, _) = zipmesh::io::read_mesh(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/quad/spot_quadrangulated.obj"
    ))
    .unwrap();
    let svg = Scene::new(&mesh, &Options::default()).unwrap().svg();
    let mut want: std::collections::BTreeMap<usize, usize> = Default::default();
    for (_, valence) in zipmesh::render::singularities(&mesh.map) {
        *want.entry(valence).or_default() += 1;
    }
    let labels: Vec<String> = want.iter().map(|(k, n)| format!("v{k}: {n}")).collect();
    assert_eq!(labels, ["v3: 56", "v5: 40", "v6: 4"]);
    for (label, (valence, _)) in labels.iter().zip(&want) {
        assert!(svg.contains(&format!("data-label=\"{label}\"")), "{label}");
        let colour = zipmesh::render::ball_colour(MeshKind::Quad, *valence).unwrap();
        assert!(svg.contains(&format!("fill=\"url(#ball-{})\"", colour.name())));
    }
    assert_eq!(svg.matches("class=\"legend\"").count(), 3);
    let bare = Options {
        legend: false,
        ..Options::default()
    };
    let svg = Scene::new(&mesh, &bare).unwrap().svg();
    assert!(!svg.contains("id=\"legend\""));
}
