//! `zipmesh render`: the SVG's balls match the library's scene, PNG output has the asked
//! size, paths from `zip --json` / `optimize --json`-shaped reports are drawn, and bad input
//! (sizes, views, names, path entries) exits 2 with no OUT (an existing OUT unchanged).

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use common::shared;
use common::svg::{assert_xmlish, circles, elements};
use run::{s, stderr, stdout, temp_dir, zipmesh};
use serde_json::{json, Value};
use std::fs;
use std::path::{Path, PathBuf};
use zipmesh::render::{Options, Scene, View};
use zipmesh::{gen, io};

fn spot() -> PathBuf {
    shared("quad/spot_quadrangulated.obj")
}

/// Runs `render` and expects success.
fn render_ok(args: &[&str]) -> String {
    let o = zipmesh(&[&["render"], args].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    stdout(&o)
}

/// Runs `render`, expects exit 2 with a message containing `says`, and no `out`.
fn render_fails(args: &[&str], out: &Path, says: &str) {
    let o = zipmesh(&[&["render"], args].concat());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains(says), "{}", stderr(&o));
    assert!(!out.exists(), "{} was written", out.display());
}

#[test]
fn svg_balls_match_the_library_scene() {
    let dir = temp_dir("render-svg");
    let out = dir.join("spot.svg");
    let spot = spot();
    for view in [None, Some("-30,20"), Some("120,-10")] {
        let mut args = vec![s(&spot), "-o", s(&out)];
        if let Some(v) = view {
            args.extend(["--view", v]);
        }
        let text = render_ok(&args);
        assert!(text.contains("interior singularities seen"), "{text}");
        let svg = fs::read_to_string(&out).unwrap();
        assert_xmlish(&svg);
        let (mesh, _) = io::read_mesh(&spot).unwrap();
        let view = view.map(|v| {
            let (a, e) = v.split_once(',').unwrap();
            View::new(a.parse().unwrap(), e.parse().unwrap()).unwrap()
        });
        let scene = Scene::new(
            &mesh,
            &Options {
                view,
                ..Options::default()
            },
        )
        .unwrap();
        let got: Vec<(usize, String)> = circles(&svg)
            .into_iter()
            .map(|c| (c.vertex, c.class))
            .collect();
        let want: Vec<(usize, String)> = scene
            .balls()
            .iter()
            .filter(|b| b.visible)
            .map(|b| (b.vertex.index(), format!("v{}", mesh.map.valence(b.vertex))))
            .collect();
        assert_eq!(got, want);
        assert!(!got.is_empty() && got.len() < scene.balls().len());
    }
}

#[test]
fn png_has_the_asked_size() {
    let dir = temp_dir("render-png");
    let out = dir.join("spot.PNG");
    render_ok(&[s(&spot()), "-o", s(&out), "--size", "321,123"]);
    let png = fs::read(&out).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&png[12..16], b"IHDR");
    assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 321);
    assert_eq!(u32::from_be_bytes(png[20..24].try_into().unwrap()), 123);
}

#[test]
fn bad_sizes_views_and_names_exit_2_without_output() {
    let dir = temp_dir("render-bad");
    let svg = dir.join("out.svg");
    let png = dir.join("out.png");
    let spot = spot();
    let spot = s(&spot);
    render_fails(&[spot, "-o", s(&svg), "--size", "20000,10"], &svg, "16384");
    render_fails(
        &[spot, "-o", s(&svg), "--size", "0,10"],
        &svg,
        "from 1 to 16384",
    );
    render_fails(
        &[spot, "-o", s(&svg), "--size", "99999999999,10"],
        &svg,
        "16384",
    );
    render_fails(&[spot, "-o", s(&svg), "--size", "800"], &svg, "comma");
    render_fails(
        &[spot, "-o", s(&png), "--size", "16384,16384"],
        &png,
        "at most",
    );
    render_fails(&[spot, "-o", s(&svg), "--view", "10,95"], &svg, "elevation");
    render_fails(
        &[spot, "-o", s(&svg), "--view", "x,5"],
        &svg,
        "not a number",
    );
    let jpg = dir.join("out.jpg");
    render_fails(&[spot, "-o", s(&jpg)], &jpg, ".svg or .png");
    let missing = dir.join("missing.obj");
    render_fails(&[s(&missing), "-o", s(&svg)], &svg, "missing.obj");
}

#[test]
fn a_failed_render_leaves_an_existing_output_unchanged() {
    let dir = temp_dir("render-keep");
    let out = dir.join("keep.svg");
    fs::write(&out, "old").unwrap();
    let o = zipmesh(&["render", s(&spot()), "-o", s(&out), "--size", "0,0"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(fs::read_to_string(&out).unwrap(), "old");
    let leftovers: Vec<_> = fs::read_dir(&dir).unwrap().collect();
    assert_eq!(leftovers.len(), 1, "no temporary file left");
}

/// A cube of 3 x 3 quads a side, written to OBJ, and the vertex numbers of its edge
/// x = 1, z = 1 (toward the eye at view 30,20), bottom to top.
fn cube_and_front_edge(dir: &Path) -> (PathBuf, Vec<u64>) {
    let cube = gen::cube(3);
    let file = dir.join("cube.obj");
    io::write_mesh(&file, &cube).unwrap();
    let mut edge: Vec<(f64, u64)> = (0..cube.positions.len())
        .filter(|&i| cube.positions[i].x == 1.0 && cube.positions[i].z == 1.0)
        .map(|i| (cube.positions[i].y, i as u64))
        .collect();
    edge.sort_by(|a, b| a.0.total_cmp(&b.0));
    (file, edge.into_iter().map(|(_, i)| i).collect())
}

fn polylines(svg: &Path) -> Vec<usize> {
    let svg = fs::read_to_string(svg).unwrap();
    elements(&svg, "polyline")
        .iter()
        .map(|el| common::svg::attr(el, "points").unwrap().split(' ').count())
        .collect()
}

#[test]
fn paths_from_reports_are_drawn() {
    let dir = temp_dir("render-paths");
    let (cube, edge) = cube_and_front_edge(&dir);
    let out = dir.join("cube.svg");
    let report = dir.join("report.json");
    let half = edge[..2].to_vec();
    let mesh = io::read_mesh(&cube).unwrap().0;
    let points: Vec<[f64; 3]> = edge
        .iter()
        .map(|&v| mesh.positions[v as usize].to_array())
        .collect();
    let shapes = [
        (json!({"path": edge}), vec![edge.len()]),
        (
            json!({"batches": [{"paths": [edge, half]}, {"paths": []}], "final": {}}),
            vec![edge.len(), 2],
        ),
        (
            json!({"undo": null, "x": [{"deep": {"path": half}}]}),
            vec![2],
        ),
        (json!({"path": null}), vec![]),
        // Points, as `optimize --paths` writes them: the cube's front edge again.
        (json!({"batches": [{"paths": [points]}]}), vec![edge.len()]),
        // A zip report: its undo path numbers OUT's vertices, so it is not drawn on IN.
        (
            json!({"path": edge, "undo": {"path": [0, 1, 2, 3, 4, 5, 6, 7]}}),
            vec![edge.len()],
        ),
    ];
    for (value, want) in shapes {
        fs::write(&report, value.to_string()).unwrap();
        render_ok(&[
            s(&cube),
            "-o",
            s(&out),
            "--view",
            "30,20",
            "--paths",
            s(&report),
        ]);
        assert_eq!(polylines(&out), want, "{value}");
    }
    render_ok(&[s(&cube), "-o", s(&out), "--view", "30,20"]);
    assert!(polylines(&out).is_empty());
}

#[test]
fn the_path_zip_reports_is_drawn_on_its_input() {
    let dir = temp_dir("render-zip-path");
    let zipped = dir.join("zipped.obj");
    let input = spot();
    let mut args = run::spot_zip(s(&input));
    args.extend(["-o", s(&zipped), "--json"]);
    let o = zipmesh(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: Value = serde_json::from_slice(&o.stdout).unwrap();
    let path: Vec<u64> = report["path"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    let file = dir.join("path.json");
    fs::write(&file, json!({"path": path}).to_string()).unwrap();
    let (mesh, _) = io::read_mesh(spot()).unwrap();
    // The first of eight side views from which some of the path is seen.
    let (az, want) = (0..8)
        .map(|k| {
            let options = Options {
                view: Some(View::new(f64::from(k * 45), 10.0).unwrap()),
                paths: vec![path.clone()],
                ..Options::default()
            };
            let scene = Scene::new(&mesh, &options).unwrap();
            (
                k * 45,
                scene.polylines().iter().map(Vec::len).collect::<Vec<_>>(),
            )
        })
        .find(|(_, lines)| !lines.is_empty())
        .expect("the path is seen from some side");
    let out = dir.join("spot.svg");
    let view = format!("{az},10");
    render_ok(&[
        s(&spot()),
        "-o",
        s(&out),
        "--paths",
        s(&file),
        "--view",
        &view,
    ]);
    assert_eq!(polylines(&out), want);
}

#[test]
fn bad_path_entries_exit_2_without_output() {
    let dir = temp_dir("render-bad-paths");
    let (cube, edge) = cube_and_front_edge(&dir);
    let out = dir.join("cube.svg");
    let report = dir.join("report.json");
    let cases = [
        (
            json!({"path": [edge[0], 98]}),
            "path 0, entry 1: 98 is not a vertex",
        ),
        (
            json!({"paths": [[0, 1], [2, -1]]}),
            "path 1, entry 1: -1 is not a vertex number",
        ),
        (json!({"paths": [[0, 1], 7]}), "not an array"),
        (json!({"path": "0,1"}), "not an array"),
        (json!({"path": [1.5]}), "not a vertex number"),
        (
            json!({"path": [[0.0, 1.0, 2.0], [0.0, 1.0]]}),
            "path 0, entry 1: [0.0,1.0] is not a point",
        ),
        (json!({"path": [[0.0, 0.0, 0.0], 3]}), "is not a point"),
    ];
    for (value, says) in cases {
        fs::write(&report, value.to_string()).unwrap();
        render_fails(
            &[s(&cube), "-o", s(&out), "--paths", s(&report)],
            &out,
            says,
        );
    }
    fs::write(&report, "{").unwrap();
    render_fails(
        &[s(&cube), "-o", s(&out), "--paths", s(&report)],
        &out,
        "not JSON",
    );
    let missing = dir.join("none.json");
    render_fails(
        &[s(&cube), "-o", s(&out), "--paths", s(&missing)],
        &out,
        "none.json",
    );
}
