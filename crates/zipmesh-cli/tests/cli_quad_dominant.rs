//! `zipmesh qd-walk`: the JSON report checked against the library, the printed undo
//! restoring the input up to isomorphism, and exit 2 with no output file on bad input.

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use run::{s, stderr, temp_dir, zipmesh};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Output;
use zipmesh::invariants::canonical::canonical_hash;
use zipmesh::quad_dominant::{self, compass, Move};
use zipmesh::{gen, io, is_isomorphic, Dart, Face, Mesh, Vert};

fn json(o: &Output) -> Value {
    assert!(o.status.success(), "{}", stderr(o));
    serde_json::from_slice(&o.stdout).expect("one JSON value")
}

/// A torus grid with two triangle pairs, written to `dir/in.obj` and read back (so face
/// and vertex numbers are the file's).
fn input(dir: &Path, seed: u64) -> (PathBuf, Mesh) {
    let (mesh, _) = gen::quad_dominant(10, 10, 2, seed);
    let p = dir.join("in.obj");
    io::write_mesh(&p, &mesh).unwrap();
    let (read, _) = io::read_mesh(&p).unwrap();
    (p, read)
}

/// The tip dart of face `f` (the corner of highest valence).
fn tip(mesh: &Mesh, f: u32) -> Dart {
    quad_dominant::default_tip(&mesh.map, Face::new(f)).unwrap()
}

fn num(v: &Value) -> String {
    v.as_u64().map(|x| x.to_string()).unwrap_or_default()
}

/// Runs qd-walk, checks the report against the library and the undo against the input.
fn walk_and_undo(name: &str, extra: &[&str], lib: impl Fn(&mut Mesh, Dart) -> Dart) {
    let dir = temp_dir(name);
    let (inp, mesh) = input(&dir, 3);
    let f = quad_dominant::triangles(&mesh.map)[0].index() as u32;
    let out = dir.join("out.obj");
    let mut args = vec!["qd-walk", s(&inp), "--triangle"];
    let fs = f.to_string();
    args.extend([fs.as_str(), "-o", s(&out), "--json"]);
    args.extend(extra);
    let r = json(&zipmesh(&args));
    let (edited, _) = io::read_mesh(&out).unwrap();
    // The library's result from the same start, up to isomorphism.
    let mut want = mesh.clone();
    let t = lib(&mut want, tip(&mesh, f));
    assert_eq!(
        canonical_hash(&edited.map),
        canonical_hash(&want.map),
        "{extra:?}"
    );
    // The reported triangle and tip are a triangle of OUT and one of its corners.
    let face = Face::new(r["triangle"].as_u64().unwrap() as u32);
    let tip_v = Vert::new(r["tip"].as_u64().unwrap() as u32);
    assert_eq!(edited.map.degree(face), 3);
    assert!(edited
        .map
        .face_darts(face)
        .any(|d| edited.map.origin(d) == tip_v));
    assert_eq!(
        edited.map.valence(tip_v),
        want.map.valence(want.map.origin(t))
    );
    // The undo, run on OUT, restores IN up to isomorphism.
    let u = &r["undo"];
    let back = dir.join("back.obj");
    let (uf, ut, um) = (
        num(&u["triangle"]),
        num(&u["tip"]),
        u["move"].as_str().unwrap(),
    );
    let o = zipmesh(&[
        "qd-walk",
        s(&out),
        "--triangle",
        &uf,
        "--tip",
        &ut,
        "--move",
        um,
        "-o",
        s(&back),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (restored, _) = io::read_mesh(&back).unwrap();
    assert!(
        is_isomorphic(&restored.map, &mesh.map),
        "{extra:?}: undo {u}"
    );
}

#[test]
fn each_move_and_its_undo() {
    for mv in Move::ALL {
        for steps in [1usize, 3] {
            let name = format!("qd-walk-{mv}-{steps}");
            let k = steps.to_string();
            walk_and_undo(&name, &["--move", mv.name(), "--steps", &k], |m, t| {
                (0..steps).fold(t, |t, _| mv.apply(m, t).unwrap().record().tip())
            });
        }
    }
}

#[test]
fn a_sequence_of_moves() {
    let seq = [Move::VE, Move::LE, Move::LE, Move::EV, Move::RE];
    walk_and_undo("qd-walk-seq", &["--move", "VE,LE,le,EV,RE"], |m, t| {
        seq.iter()
            .fold(t, |t, &mv| mv.apply(m, t).unwrap().record().tip())
    });
}

#[test]
fn compass_walk_to_a_vertex() {
    let dir = temp_dir("qd-walk-to-probe");
    let (_, mesh) = input(&dir, 3);
    let f = quad_dominant::triangles(&mesh.map)[0].index() as u32;
    let m = &mesh.map;
    // Four edges from the tip: VE direction, then a turn.
    let t = tip(&mesh, f);
    let straight = |d: Dart| m.rotate_cw(m.rotate_cw(d.twin()));
    let d = straight(straight(m.rotate_cw(m.rotate_cw(t))));
    let target = m.dest(m.rotate_cw(straight(d)));
    let ts = target.index().to_string();
    walk_and_undo("qd-walk-to", &["--to", &ts], |m, t| {
        compass::walk_to(m, t, target).unwrap().tip()
    });
}

/// `tri-walk`, the command's earlier name, runs `qd-walk`: the same report and OUT.
#[test]
fn the_earlier_name_runs_the_same_command() {
    let dir = temp_dir("qd-walk-alias");
    let (inp, mesh) = input(&dir, 3);
    let f = quad_dominant::triangles(&mesh.map)[0].index().to_string();
    let (a, b) = (dir.join("a.obj"), dir.join("b.obj"));
    let run = |cmd: &str, out: &Path| {
        json(&zipmesh(&[
            cmd,
            s(&inp),
            "--triangle",
            &f,
            "--move",
            "VE",
            "-o",
            s(out),
            "--json",
        ]))
    };
    let (ra, rb) = (run("qd-walk", &a), run("tri-walk", &b));
    assert_eq!(
        (ra["moves"].clone(), ra["undo"].clone()),
        (rb["moves"].clone(), rb["undo"].clone())
    );
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

/// Exit 2 and no OUT: a quad as the triangle, a tip that is not a corner, a refused move,
/// a missing target, an unknown move name.
#[test]
fn bad_input_exits_2_without_output() {
    let dir = temp_dir("qd-walk-bad");
    let (inp, mesh) = input(&dir, 3);
    let quad = mesh.map.faces().find(|&f| mesh.map.degree(f) == 4).unwrap();
    let tri = quad_dominant::triangles(&mesh.map)[0];
    let far = mesh
        .map
        .vertices()
        .find(|&v| !mesh.map.face_darts(tri).any(|d| mesh.map.origin(d) == v))
        .unwrap();
    // A split quad on a grid's corner: its tip is on the boundary, so VE is refused.
    let mut g = gen::grid(3, 3);
    let d0 = g
        .map
        .face_darts(Face::new(0))
        .find(|&d| g.map.origin(d) == Vert::new(0));
    quad_dominant::split_quad(&mut g.map, d0.unwrap()).unwrap();
    let gp = dir.join("grid.obj");
    io::write_mesh(&gp, &g).unwrap();
    let (q, t, fv) = (
        quad.index().to_string(),
        tri.index().to_string(),
        far.index().to_string(),
    );
    let out = dir.join("out.obj");
    let cases: Vec<Vec<&str>> = vec![
        vec![s(&inp), "--triangle", &q, "--move", "VE"],
        vec![s(&inp), "--triangle", &t, "--tip", &fv, "--move", "VE"],
        vec![s(&inp), "--triangle", "100000", "--move", "VE"],
        vec![s(&inp), "--triangle", &t, "--to", "100000"],
        vec![s(&inp), "--triangle", &t, "--move", "XY"],
        vec![s(&inp), "--triangle", &t],
        vec![s(&gp), "--triangle", "0", "--tip", "0", "--move", "VE"],
    ];
    for c in cases {
        let mut args = vec!["qd-walk"];
        args.extend(&c);
        args.extend(["-o", s(&out)]);
        let o = zipmesh(&args);
        assert_eq!(o.status.code(), Some(2), "{c:?}: {}", stderr(&o));
        assert!(!out.exists(), "{c:?} left an output file");
    }
}

/// `zip` and `moves` accept a quad-dominant mesh: the path winds around the triangles, the
/// result keeps them, and the printed undo restores the input.
#[test]
fn zip_and_moves_on_a_quad_dominant_mesh() {
    use zipmesh::invariants::{irregular_vertices, MeshKind};
    use zipmesh::qzip::{sketch, SketchOptions};
    let dir = temp_dir("zip-quad-dominant");
    let (mesh, _) = gen::with_triangle_pairs(gen::subdivided_icosahedron(2), 2, 8, 1);
    let inp = dir.join("in.obj");
    io::write_mesh(&inp, &mesh).unwrap();
    let (mesh, _) = io::read_mesh(&inp).unwrap();
    let m = &mesh.map;
    let opts = zipmesh::qzip::avoid_triangles(m, SketchOptions::default());
    let sing = irregular_vertices(m, MeshKind::Quad);
    let (a, b) = sing
        .iter()
        .flat_map(|&a| sing.iter().map(move |&b| (a, b)))
        .find(|&(a, b)| a != b && sketch(m, a, b, &opts).is_ok_and(|p| p.len() >= 4))
        .unwrap();
    let (fa, fb) = (a.index().to_string(), b.index().to_string());
    let rows = json(&zipmesh(&[
        "moves",
        s(&inp),
        "--from",
        &fa,
        "--to",
        &fb,
        "--json",
    ]));
    assert_eq!(rows.as_array().unwrap().len(), 4);
    let out = dir.join("out.obj");
    let r = json(&zipmesh(&[
        "zip",
        s(&inp),
        "--from",
        &fa,
        "--to",
        &fb,
        "--move",
        "LC",
        "-o",
        s(&out),
        "--json",
    ]));
    let (edited, _) = io::read_mesh(&out).unwrap();
    assert_eq!(
        quad_dominant::triangles(&edited.map).len(),
        quad_dominant::triangles(m).len()
    );
    let u = &r["undo"];
    let path: Vec<String> = u["path"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.to_string())
        .collect();
    let back = dir.join("back.obj");
    let o = zipmesh(&[
        "zip",
        s(&out),
        "--from",
        &num(&u["from"]),
        "--to",
        &num(&u["to"]),
        "--move",
        u["move"].as_str().unwrap(),
        "--path",
        &path.join(","),
        "-o",
        s(&back),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (restored, _) = io::read_mesh(&back).unwrap();
    assert!(is_isomorphic(&restored.map, m));
}

/// On the Spot cage (pentagons beside its four triangles) no corner of triangle 58 has the
/// highest valence alone: without `--tip` the walk starts from the first corner from
/// which it works, and says which; `--to` takes a move aside where no move brings the tip
/// nearer (the greedy walk failed from every corner to 0, 20, 100 and 150); where even
/// that fails the error names, for each corner, every move and why it does not help.
#[test]
fn the_spot_cage_picks_a_tip_and_walks_or_says_why_not() {
    let dir = temp_dir("qd-walk-spot-cage");
    let cage = common::shared("poly/spot_control_mesh.obj");
    let (mesh, _) = io::read_mesh(&cage).unwrap();
    let corners: Vec<u64> = mesh
        .map
        .face_darts(Face::new(58))
        .map(|d| mesh.map.origin(d).index() as u64)
        .collect();
    assert!(quad_dominant::default_tip(&mesh.map, Face::new(58)).is_none());
    let out = dir.join("out.obj");
    let o = zipmesh(&[
        "qd-walk",
        s(&cage),
        "--triangle",
        "58",
        "--move",
        "VE",
        "-o",
        s(&out),
        "--json",
    ]);
    let start = json(&o)["start_tip"].as_u64().unwrap();
    assert!(corners.contains(&start), "{start} {corners:?}");
    for to in [0u32, 20, 100, 150] {
        let o = zipmesh(&[
            "qd-walk",
            s(&cage),
            "--triangle",
            "58",
            "--to",
            &to.to_string(),
            "-o",
            s(&out),
            "--json",
        ]);
        let v = json(&o);
        let (walked, _) = io::read_mesh(&out).unwrap();
        assert_eq!(walked.map.check(), Ok(()));
        // The tip ends on the target (its number in the compacted output may differ, so
        // the position is compared).
        let tip = v["tip"].as_u64().unwrap() as usize;
        assert_eq!(
            walked.positions[tip], mesh.positions[to as usize],
            "--to {to}"
        );
    }
    std::fs::remove_file(&out).unwrap();
    let o = zipmesh(&[
        "qd-walk",
        s(&cage),
        "--triangle",
        "58",
        "--to",
        "5",
        "-o",
        s(&out),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    for c in &corners {
        assert!(e.contains(&format!("tip {c}: the walk to 5 failed")), "{e}");
    }
    for mv in ["VE", "EV", "LE", "RE"] {
        assert_eq!(
            e.matches(&format!("; {mv} ")).count() + e.matches(&format!(": {mv} ")).count(),
            3,
            "{mv}: {e}"
        );
    }
    assert!(!out.exists());
}
