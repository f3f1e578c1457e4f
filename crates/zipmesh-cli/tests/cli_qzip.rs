//! `zipmesh moves` and `zipmesh zip`: JSON reports checked against the library, the printed
//! undo restoring the input, and exit 2 with no output file on bad input.

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use run::{temp_dir, zipmesh};
use serde_json::Value;
use std::process::Output;
use zipmesh::qzip::{moves, sketch, SketchOptions, Tag};
use zipmesh::{io, is_isomorphic, Vert};

fn spot() -> String {
    let p = run::root().join("tests/data/quad/spot_quadrangulated.obj");
    p.to_str().unwrap().to_string()
}

fn json(o: &Output) -> Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).expect("one JSON value")
}

/// Spot's v5 15 and v3 2, 16 edges apart (see `moves` below).
/// The library's default sketch between two vertices, as `moves` and `zip` find it.
fn default_path(map: &zipmesh::Map, from: u32, to: u32) -> zipmesh::qzip::Path {
    sketch(
        map,
        Vert::new(from),
        Vert::new(to),
        &SketchOptions::default(),
    )
    .unwrap()
}

/// `zip` on Spot from FROM to TO with the given move and output, then `extra`.
fn zip_spot(tag: &str, out: &str, extra: &[&str]) -> Output {
    let spot = spot();
    let mut args = vec![
        "zip", &spot, "--from", FROM, "--to", TO, "--move", tag, "-o", out,
    ];
    args.extend_from_slice(extra);
    zipmesh(&args)
}

const FROM: &str = "15";
const TO: &str = "2";

#[test]
fn moves_json_matches_the_library() {
    let v = json(&zipmesh(&[
        "moves",
        &spot(),
        "--from",
        FROM,
        "--to",
        TO,
        "--json",
    ]));
    let rows = v.as_array().expect("a list");
    let (mesh, _) = io::read_mesh(spot()).unwrap();
    let path = default_path(&mesh.map, 15, 2);
    let lib = moves(&mesh.map, &path);
    assert_eq!(rows.len(), 4);
    for (row, m) in rows.iter().zip(lib.iter()) {
        assert_eq!(row["move"], m.tag.to_string());
        assert_eq!(row["realizable"], m.outcome.is_ok());
        match &m.outcome {
            Ok((_, r)) => {
                assert_eq!(row["splits"], r.splits());
                assert_eq!(row["collapses"], r.collapses());
                assert!(row["moved"]["from"].is_u64() && row["moved"]["to"].is_u64());
            }
            Err(e) => assert_eq!(row["reason"], e.to_string()),
        }
    }
}

/// Every realizable movement: the report's moved vertices carry the pair's valences in OUT,
/// and the printed undo, passed back to `zip`, gives a mesh isomorphic to the input.
#[test]
fn zip_then_its_undo_restores_the_input() {
    let dir = temp_dir("qzip-undo");
    let (input, _) = io::read_mesh(spot()).unwrap();
    let mut done = 0;
    for tag in Tag::CCW {
        let out = dir.join(format!("{tag}.obj"));
        let o = zip_spot(&tag.to_string(), out.to_str().unwrap(), &["--json"]);
        if !o.status.success() {
            assert_eq!(o.status.code(), Some(2));
            assert!(!out.exists());
            continue;
        }
        let r = json(&o);
        for k in ["splits", "collapses", "moved", "path", "undo"] {
            assert!(r.get(k).is_some(), "missing {k}");
        }
        let (edited, _) = io::read_mesh(&out).unwrap();
        let at = |k: &str| Vert::new(r["moved"][k].as_u64().unwrap() as u32);
        assert_eq!(edited.map.valence(at("from")), 5);
        assert_eq!(edited.map.valence(at("to")), 3);
        assert_eq!(
            edited.map.num_vertices() as u64,
            input.map.num_vertices() as u64 + r["splits"].as_u64().unwrap()
                - r["collapses"].as_u64().unwrap()
        );
        let u = &r["undo"];
        let path: Vec<String> = u["path"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_u64().unwrap().to_string())
            .collect();
        let back = dir.join(format!("{tag}-back.obj"));
        let o = zipmesh(&[
            "zip",
            out.to_str().unwrap(),
            "--from",
            &u["from"].to_string(),
            "--to",
            &u["to"].to_string(),
            "--move",
            u["move"].as_str().unwrap(),
            "--path",
            &path.join(","),
            "-o",
            back.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let (restored, _) = io::read_mesh(&back).unwrap();
        assert!(is_isomorphic(&restored.map, &input.map));
        done += 1;
    }
    assert!(done >= 2);
}

/// Bad input: exit 2, a message naming the problem, and no output file.
#[test]
fn bad_input_exits_2_without_output() {
    let dir = temp_dir("qzip-bad");
    let out = dir.join("out.obj");
    let o = out.to_str().unwrap();
    let torus = run::root().join("tests/data/tri/torus.obj");
    let helmet = run::root().join("tests/data/quad/osd_catmark_helmet.obj");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["--from".into(), FROM.into(), "--to".into(), "16".into()],
            "not irregular",
        ),
        (
            vec!["--from".into(), FROM.into(), "--to".into(), "99999".into()],
            "no such vertex",
        ),
        (
            vec![
                "--from".into(),
                FROM.into(),
                "--to".into(),
                TO.into(),
                "--path".into(),
                "15,2".into(),
            ],
            "no surgery path",
        ),
    ];
    for (extra, msg) in cases {
        let mut args: Vec<String> = vec![
            "zip".into(),
            spot(),
            "--move".into(),
            "LC".into(),
            "-o".into(),
            o.into(),
        ];
        args.extend(extra);
        let a: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let r = zipmesh(&a);
        assert_eq!(r.status.code(), Some(2));
        assert!(
            String::from_utf8_lossy(&r.stderr).contains(msg),
            "{}",
            String::from_utf8_lossy(&r.stderr)
        );
        assert!(!out.exists());
    }
    let refused = |file: &std::path::Path, from: &str, to: &str, msg: &str| {
        let file = file.to_str().unwrap();
        let r = zipmesh(&[
            "zip", file, "--from", from, "--to", to, "--move", "LC", "-o", o,
        ]);
        assert_eq!(r.status.code(), Some(2), "{file}");
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(err.contains(msg), "{file}: {err}");
        assert!(!out.exists(), "{file}");
    };
    refused(&torus, "0", "1", "not a quad or quad-dominant mesh");
    // Helmet: vertex 0 is a boundary corner (valence 2); Sec. 2.6 does not cover it.
    refused(&helmet, "0", "54", "not realizable");
    let r = zip_spot("XX", o, &[]);
    assert_eq!(r.status.code(), Some(2));
    assert!(!out.exists());
}

/// A movement with no reverse Q-zip: on the toroidal tetrahedron after `--preprocess` (every
/// vertex of valence 6 split into v5 pairs one edge apart), LS from 0 to 1 is done but no
/// reverse run restores the preprocessed input. `--json` gives `"undo": null` and the text
/// says so; the exit status is 0 and OUT is written (the edit itself is fine).
#[test]
fn zip_without_a_reverse_run_gives_undo_null() {
    let file = run::root()
        .join("tests/data/quad/osd_catmark_toroidal_tet.obj")
        .to_str()
        .unwrap()
        .to_string();
    // The premise, from the library: the movement is done and find_reverse finds nothing.
    let (mut mesh, _) = io::read_mesh(&file).unwrap();
    zipmesh::qzip::preprocess(&mut mesh).unwrap();
    let path = default_path(&mesh.map, 0, 1);
    let mut edited = mesh.map.clone();
    let r = zipmesh::qzip::Qzip::new()
        .zip_along(&mut edited, &path, Tag::LS)
        .unwrap();
    assert!(zipmesh::qzip::find_reverse(&edited, &r, &mesh.map).is_none());

    let dir = temp_dir("qzip-no-undo");
    let out = dir.join("out.obj");
    let args = |json: bool| {
        let mut a = vec![
            "zip",
            &file,
            "--preprocess",
            "--from",
            "0",
            "--to",
            "1",
            "--move",
            "LS",
            "-o",
            out.to_str().unwrap(),
        ];
        if json {
            a.push("--json");
        }
        zipmesh(&a)
    };
    let v = json(&args(true));
    assert!(v.get("undo").is_some_and(Value::is_null), "{v}");
    assert!(v["moved"]["from"].is_u64() && v["splits"].is_u64());
    assert!(out.exists());
    std::fs::remove_file(&out).unwrap();
    let o = args(false);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("undo: no reverse Q-zip restores the input here"),
        "{text}"
    );
    assert!(out.exists());
}

/// `zip --help` says when `undo` is null.
#[test]
fn zip_help_documents_a_null_undo() {
    let o = zipmesh(&["zip", "--help"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("\"undo\": null"), "{text}");
}

/// `moves --partners` lists the nearest interior singularities, fewest edges first, each
/// with the movements the library realizes along a shortest path to it.
#[test]
fn moves_lists_the_nearest_partners_with_their_movements() {
    use zipmesh::qzip::{moves, sketch, SketchOptions};
    let file = common::shared("quad/spot_quadrangulated.obj");
    let o = run::zipmesh(&[
        "moves",
        file.to_str().unwrap(),
        "--from",
        "15",
        "--partners",
        "4",
        "--json",
    ]);
    assert!(o.status.success(), "{}", run::stderr(&o));
    let rows: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 4);
    let (mesh, _) = zipmesh::io::read_mesh(&file).unwrap();
    let map = &mesh.map;
    let from = zipmesh::Vert::new(15);
    let mut last = 0;
    for r in rows {
        let v = zipmesh::Vert::new(r["to"].as_u64().unwrap() as u32);
        assert!(map.valence(v) != 4 && !map.is_boundary_vertex(v));
        let path = sketch(map, from, v, &SketchOptions::default()).unwrap();
        let d = r["distance"].as_u64().unwrap() as usize;
        assert!(d >= last && d <= path.len(), "{r}");
        last = d;
        let want: Vec<String> = moves(map, &path)
            .iter()
            .filter(|m| m.outcome.is_ok())
            .map(|m| m.tag.to_string())
            .collect();
        let got: Vec<String> = r["realizable"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t.as_str().unwrap().to_string())
            .collect();
        assert_eq!(got, want, "{r}");
    }
    // Without --to and --partners nothing is moved.
    let o = run::zipmesh(&["moves", file.to_str().unwrap(), "--from", "15"]);
    assert_eq!(o.status.code(), Some(2));
}

/// `zipmesh zip` relaxes by default and reports the quality of input and output; with
/// `--no-relax` the raw placement (on Spot, 15 to 2 by LC: 2 folded quads, 8e-4 of the
/// diagonal off the surface; relaxed: none, and on the surface).
#[test]
fn zip_relaxes_by_default_and_reports_quality() {
    use run::{s, stdout, temp_dir, zipmesh};
    let dir = temp_dir("zip-geometry");
    let input = common::shared("quad/spot_quadrangulated.obj");
    let run = |extra: &[&str]| {
        let out = dir.join("moved.obj");
        let mut args = run::spot_zip(s(&input));
        args.extend(["-o", s(&out), "--json"]);
        args.extend(extra);
        let o = zipmesh(&args);
        assert!(o.status.success(), "{o:?}");
        serde_json::from_str::<serde_json::Value>(&stdout(&o)).unwrap()
    };
    let relaxed = run(&[]);
    let q = &relaxed["quality"];
    assert!(relaxed["relax"]["moves"].as_u64().unwrap() > 0);
    assert_eq!(q["input"]["folded_quads"], 0);
    assert_eq!(q["output"]["folded_quads"], 0);
    assert_eq!(q["output"]["negative_scaled_jacobian"], 0);
    assert!(q["output"]["distance"]["max"].as_f64().unwrap() < common::RELAXED_DISTANCE);
    let raw = run(&["--no-relax"]);
    let q = &raw["quality"];
    assert!(raw["relax"].is_null());
    assert_eq!(q["output"]["folded_quads"], 2);
    let far = q["output"]["distance"]["max"].as_f64().unwrap();
    assert!(
        far > common::RELAXED_DISTANCE && far < common::RAW_DISTANCE,
        "{far}"
    );
}
