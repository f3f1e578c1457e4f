//! `zipmesh optimize`: the JSON counts equal a recount of OUT and its rows add up (kept
//! chains included), the same seed writes the same file, and bad input exits 2 without OUT.

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use common::shared;
use run::{assert_quality_matches, s, stderr, temp_dir, zipmesh};
use serde_json::Value;
use std::fs;
use zipmesh::optimize::SingularityCounts;
use zipmesh::quality::{Bounds, Reference, Summary};
use zipmesh::{gen, io, Mesh};

fn counts_json(c: &SingularityCounts) -> Value {
    serde_json::json!({
        "faces": c.faces, "triangles": c.triangles, "vertices": c.vertices, "v2": c.v2, "v3": c.v3, "v5": c.v5,
        "v6plus": c.v6plus, "boundary_defects": c.boundary_defects,
    })
}

/// The report's `quality` is the library's summary of IN and of OUT as written, both
/// against IN's surface, and its `bounds` are the library's verdict on the two.
fn assert_quality_reported(v: &Value, before: &Mesh, after: &Mesh) {
    let reference = Reference::new(before);
    let q = [before, after].map(|m| Summary::against(m, &reference));
    assert_quality_matches(&v["quality"]["input"], &q[0]);
    assert_quality_matches(&v["quality"]["output"], &q[1]);
    let failed: Vec<Value> = Bounds::default()
        .failures(&q[0], &q[1])
        .into_iter()
        .map(|b| Value::from(b.name()))
        .collect();
    assert_eq!(v["bounds"]["failed"], Value::Array(failed.clone()));
    assert_eq!(v["bounds"]["hold"], failed.is_empty());
}

fn input(dir: &std::path::Path) -> std::path::PathBuf {
    let mesh = gen::catmull_clark(&gen::random_triangle(120, 2, 1, 5));
    let path = dir.join("in.obj");
    io::write_mesh(&path, &mesh).unwrap();
    path
}

#[test]
fn json_counts_match_a_recount_of_out() {
    let dir = temp_dir("optimize-json");
    let (inp, out) = (input(&dir), dir.join("out.obj"));
    let o = zipmesh(&[
        "optimize",
        s(&inp),
        "-o",
        s(&out),
        "--json",
        "--batches",
        "4",
        "--paths",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let (before, _) = io::read_mesh(&inp).unwrap();
    let (after, _) = io::read_mesh(&out).unwrap();
    assert_eq!(v["input"], counts_json(&SingularityCounts::of(&before)));
    assert_eq!(v["final"], counts_json(&SingularityCounts::of(&after)));
    assert_quality_reported(&v, &before, &after);
    let batches = v["batches"].as_array().unwrap();
    assert!(!batches.is_empty() && batches.len() <= 4);
    let last = batches.last().unwrap();
    for k in [
        "faces",
        "triangles",
        "vertices",
        "v2",
        "v3",
        "v5",
        "v6plus",
        "boundary_defects",
    ] {
        assert_eq!(last[k], v["final"][k], "{k}");
    }
    rows_add_up(batches);
    assert!(v["seconds"].as_f64().unwrap() >= 0.0);
}

/// Each JSON batch row's numbers add up: one path per Q-zip, the chain stage's share within
/// the batch's, and the face change from the previous row's count to this one's.
fn rows_add_up(batches: &[Value]) {
    for (i, b) in batches.iter().enumerate() {
        assert_eq!(b["batch"], i + 1);
        let paths = b["paths"].as_array().unwrap();
        assert_eq!(paths.len() as u64, b["qzips"].as_u64().unwrap());
        let c = &b["chains"];
        assert!(c["kept"].as_u64() <= c["cancelled"].as_u64());
        assert!(c["cancelled"].as_u64() <= c["tried"].as_u64());
        assert!(c["qzips"].as_u64() <= b["qzips"].as_u64());
        if i > 0 {
            // The executed Q-zips' face change, the chains' included, is the batch's
            // (smoothing changes no face).
            let faces = |x: &Value| x["faces"].as_i64().unwrap();
            let change = faces(b) - faces(&batches[i - 1]);
            assert_eq!(b["face_change"].as_i64(), Some(change), "batch {}", i + 1);
        }
    }
}

/// On cubespikes the batches stall after about 25 batches and the chain stage keeps chains
/// (`docs/results.md`): the JSON reports them, and the rows still add up.
#[test]
fn kept_chains_are_reported_and_add_up() {
    let dir = temp_dir("optimize-chains");
    let inp = run::root().join("tests/data/quad/cubespikes.obj");
    let out = dir.join("out.obj");
    let args = ["optimize", s(&inp), "-o", s(&out), "--json", "--paths"];
    let o = zipmesh(&[&args[..], &["--batches", "40"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let batches = v["batches"].as_array().unwrap();
    rows_add_up(batches);
    let kept: u64 = batches
        .iter()
        .map(|b| b["chains"]["kept"].as_u64().unwrap())
        .sum();
    assert!(kept > 0, "no chain kept in {} batches", batches.len());
    let o = zipmesh(&[&args[..], &["--batches", "24", "--no-chains"]].concat());
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = v["batches"].as_array().unwrap();
    assert!(rows.iter().all(|b| b["chains"]["tried"] == 0));
}

#[test]
fn same_seed_same_file() {
    let dir = temp_dir("optimize-seed");
    let inp = input(&dir);
    let (a, b) = (dir.join("a.obj"), dir.join("b.obj"));
    for out in [&a, &b] {
        let o = zipmesh(&[
            "optimize",
            s(&inp),
            "-o",
            s(out),
            "--batches",
            "3",
            "--seed",
            "9",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert_eq!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
}

#[test]
fn bad_input_exits_2_without_out() {
    let dir = temp_dir("optimize-bad");
    let inp = input(&dir);
    let tri = dir.join("tri.obj");
    io::write_mesh(&tri, &gen::random_triangle(40, 0, 0, 1)).unwrap();
    let bad_faces = dir.join("faces.txt");
    fs::write(&bad_faces, "0\n99999\n").unwrap();
    let bad_edges = dir.join("edges.txt");
    fs::write(&bad_edges, "0 1 2\n").unwrap();
    let cases: Vec<Vec<String>> = vec![
        // All triangles is accepted, but the quad-only options are refused, not ignored.
        vec![s(&tri).into(), "--protect".into(), s(&bad_faces).into()],
        vec![s(&tri).into(), "--weight".into(), "count=1".into()],
        vec![s(&tri).into(), "--fold-guard".into()],
        vec![s(&tri).into(), "--no-chains".into()],
        // And the triangle-only option on a quad mesh.
        vec![s(&inp).into(), "--no-lookahead".into()],
        vec![s(&inp).into(), "--protect".into(), s(&bad_faces).into()],
        vec![s(&inp).into(), "--features".into(), s(&bad_edges).into()],
        vec![s(&inp).into(), "--sharp-angle".into(), "400".into()],
        vec![s(&inp).into(), "--weight".into(), "nope=1".into()],
        vec![s(&dir.join("missing.obj")).into()],
    ];
    for (i, c) in cases.iter().enumerate() {
        let out = dir.join(format!("out{i}.obj"));
        let mut args = vec!["optimize"];
        args.extend(c.iter().map(String::as_str));
        args.extend(["-o", s(&out)]);
        let o = zipmesh(&args);
        assert_eq!(o.status.code(), Some(2), "{c:?}: {}", stderr(&o));
        assert!(!out.exists(), "{c:?} left OUT");
        assert!(!stderr(&o).is_empty());
    }
    // An unknown term's message names every term the library has.
    let o = zipmesh(&["optimize", s(&inp), "--weight", "nope=1", "-o", "x.obj"]);
    let defaults = zipmesh::optimize::OptimizeOptions::default();
    for (_, t) in defaults.terms() {
        assert!(
            stderr(&o).contains(t.name()),
            "{}: {}",
            t.name(),
            stderr(&o)
        );
    }
}

/// `-o` into a missing directory is refused before the input is read (a broken input is
/// not what the message is about), naming the directory; so are a directory as OUT, a
/// directory that is a file, and a name without a mesh format.
#[test]
fn an_output_that_cannot_be_written_is_refused_before_any_work() {
    let dir = temp_dir("optimize-target");
    let inp = input(&dir);
    let missing = dir.join("no").join("such");
    let target = missing.join("x.obj");
    let broken = shared("invalid/osd_catmark_fan.obj");
    for file in [&inp, &broken] {
        let o = zipmesh(&["optimize", s(file), "-o", s(&target)]);
        assert_eq!(o.status.code(), Some(2));
        assert_eq!(
            stderr(&o),
            format!(
                "zipmesh: cannot write {}: the directory {} does not exist\n",
                target.display(),
                missing.display()
            )
        );
    }
    assert!(!dir.join("no").exists());
    let under_a_file = inp.join("x.obj");
    for (target, message) in [
        (dir.clone(), "is a directory".to_string()),
        (
            under_a_file,
            format!("{} is not a directory", inp.display()),
        ),
        (dir.join("x.txt"), "unknown mesh format".to_string()),
    ] {
        let o = zipmesh(&["optimize", s(&broken), "-o", s(&target)]);
        assert_eq!(o.status.code(), Some(2));
        let err = stderr(&o);
        let expected = format!("zipmesh: cannot write {}: {message}", target.display());
        assert!(err.starts_with(&expected), "{err}");
    }
    assert_eq!(fs::read_dir(&dir).unwrap().count(), 1, "only the input");
}

#[test]
fn protected_faces_from_a_file_hold() {
    let dir = temp_dir("optimize-protect");
    let inp = input(&dir);
    let (mesh, _) = io::read_mesh(&inp).unwrap();
    let faces = dir.join("faces.txt");
    fs::write(&faces, "0\n5\n17\n").unwrap();
    let out = dir.join("out.obj");
    let o = zipmesh(&[
        "optimize",
        s(&inp),
        "-o",
        s(&out),
        "--protect",
        s(&faces),
        "--batches",
        "3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (after, _) = io::read_mesh(&out).unwrap();
    let key = |m: &zipmesh::Mesh, f: &[u32]| -> Vec<[u64; 3]> {
        f.iter()
            .map(|&v| m.positions[v as usize].to_array().map(f64::to_bits))
            .collect()
    };
    let polys = mesh.polygons();
    let out_faces: Vec<Vec<[u64; 3]>> = after.polygons().iter().map(|f| key(&after, f)).collect();
    for i in [0usize, 5, 17] {
        let want = key(&mesh, &polys[i]);
        let found = out_faces
            .iter()
            .any(|f| (0..4).any(|k| f.iter().cycle().skip(k).take(4).eq(want.iter())));
        assert!(found, "protected face {i} changed");
    }
}

/// A quad-dominant input (a random genus-1 quad mesh with two triangle pairs): `optimize` accepts it,
/// the JSON counts (triangles included) equal a recount of IN and OUT, the triangle stage
/// accounts for the triangles that went, and the same seed writes the same file.
#[test]
fn quad_dominant_input_through_the_cli() {
    let dir = temp_dir("optimize-qdom");
    let base = gen::random_quad(400, 1, 0, 3);
    let (mesh, tips) = gen::with_triangle_pairs(base, 2, 10, 4);
    assert_eq!(tips.len(), 4);
    let inp = dir.join("qdom.obj");
    io::write_mesh(&inp, &mesh).unwrap();
    let (a, b) = (dir.join("a.obj"), dir.join("b.obj"));
    let mut reports = Vec::new();
    for out in [&a, &b] {
        let o = zipmesh(&[
            "optimize",
            s(&inp),
            "-o",
            s(out),
            "--json",
            "--batches",
            "3",
            "--seed",
            "5",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        reports.push(serde_json::from_slice::<Value>(&o.stdout).unwrap());
    }
    assert_eq!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
    let v = &reports[0];
    let (before, _) = io::read_mesh(&inp).unwrap();
    let (after, _) = io::read_mesh(&a).unwrap();
    assert_eq!(v["input"], counts_json(&SingularityCounts::of(&before)));
    assert_eq!(v["final"], counts_json(&SingularityCounts::of(&after)));
    assert_eq!(v["input"]["triangles"], 4);
    let stage = &v["triangle_stage"];
    assert_eq!(stage["input"], 4);
    let merged = stage["merged_pairs"].as_u64().unwrap();
    assert_eq!(v["final"]["triangles"].as_u64(), Some(4 - 2 * merged));
    assert!(after
        .map
        .faces()
        .all(|f| matches!(after.map.degree(f), 3 | 4)));
}

/// An all-triangle input: the JSON counts equal a recount of IN and OUT (interior valences),
/// the batches never raise the irregular count (nor the score while it stays), and OUT keeps the genus and the boundary.
#[test]
fn triangle_input_json_counts_match_a_recount() {
    let dir = temp_dir("optimize-tri");
    let (inp, out) = (dir.join("in.obj"), dir.join("out.obj"));
    let mesh = gen::random_triangle(600, 1, 1, 8);
    io::write_mesh(&inp, &mesh).unwrap();
    let o = zipmesh(&["optimize", s(&inp), "-o", s(&out), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let recount = |m: &zipmesh::Mesh| {
        let c = zipmesh::optimize::TriCounts::of(&m.map);
        serde_json::json!({
            "faces": c.faces, "vertices": c.vertices, "v3": c.v3, "v4": c.v4, "v5": c.v5,
            "v7": c.v7, "v8plus": c.v8plus, "irregular": c.irregular(),
        })
    };
    let (result, _) = io::read_mesh(&out).unwrap();
    assert_eq!(v["kind"], "triangle");
    assert_eq!(v["input"], recount(&mesh));
    assert_eq!(v["final"], recount(&result));
    let (read, _) = io::read_mesh(&inp).unwrap();
    assert_quality_reported(&v, &read, &result);
    // Count first, then score: the look-ahead may raise the score to lower the count.
    let ranks: Vec<(u64, u64)> = v["batches"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| {
            (
                b["irregular"].as_u64().unwrap(),
                b["score"].as_u64().unwrap(),
            )
        })
        .collect();
    assert!(ranks.windows(2).all(|w| w[1] <= w[0]), "{ranks:?}");
    let before = zipmesh::invariants::Counts::of(&mesh.map);
    let after = zipmesh::invariants::Counts::of(&result.map);
    assert_eq!(
        (before.genus, before.boundary_loops),
        (after.genus, after.boundary_loops)
    );
    assert!(v["final"]["irregular"].as_u64() < v["input"]["irregular"].as_u64());
}

/// `--time-limit`: Blub stops inside the limit (with room for reading, the surface and
/// writing in a debug build: the whole run takes minutes there), the JSON says so, OUT is a
/// valid mesh; a limit that is not a positive number of seconds exits 2 without OUT.
#[test]
fn the_time_limit_stops_the_run() {
    let dir = temp_dir("optimize-limit");
    let inp = shared("quad/blub_quadrangulated.obj");
    let out = dir.join("out.obj");
    let o = zipmesh(&[
        "optimize",
        s(&inp),
        "-o",
        s(&out),
        "--json",
        "--time-limit",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["time_limit_reached"], true, "{v}");
    let seconds = v["seconds"].as_f64().unwrap();
    assert!(seconds < 30.0, "{seconds} s");
    let (result, _) = io::read_mesh(&out).unwrap();
    assert_eq!(result.map.check(), Ok(()));
    for bad in ["0", "-1", "nan", "inf", "1e300", "soon"] {
        let target = dir.join(format!("bad-{bad}.obj"));
        let o = zipmesh(&["optimize", s(&inp), "-o", s(&target), "--time-limit", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}: {}", stderr(&o));
        assert!(!target.exists());
    }
}

/// `--progress-json` prints each batch's row as one JSON line as the batch ends, the same
/// object as the report's `batches` entry, then the report: on a quad and a triangle mesh.
#[test]
fn progress_json_streams_the_batch_rows() {
    let dir = temp_dir("optimize-progress-json");
    let out = dir.join("out.obj");
    for file in ["quad/amo_quad.obj", "tri/circle_disk.obj"] {
        let input = shared(file);
        let o = zipmesh(&[
            "optimize",
            s(&input),
            "-o",
            s(&out),
            "--json",
            "--progress-json",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let lines: Vec<Value> = String::from_utf8(o.stdout)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        let (report, rows) = lines.split_last().unwrap();
        let batches = report["batches"].as_array().unwrap();
        assert!(!batches.is_empty(), "{file}");
        assert_eq!(rows, batches.as_slice(), "{file}");
        for (i, row) in rows.iter().enumerate() {
            assert_eq!(row["batch"].as_u64(), Some(i as u64 + 1), "{file}");
        }
    }
}

/// A quad-dominant input whose first run folds quads (case 1501 of the default campaign, a
/// torus of 105 faces, 36 of them triangles) is optimized again with each triangle merge
/// guarded: the report says so, its `batches` are the second run's (numbered from 1, the
/// last rows `--progress-json` streamed), the text line says so too, and OUT adds no
/// folded quad.
#[test]
fn a_guarded_second_run_reports_its_own_batches() {
    let dir = temp_dir("optimize-guarded");
    let (inp, out) = (dir.join("in.obj"), dir.join("out.obj"));
    let case = zipmesh::campaign::Case::generate(0, 1501, 1000);
    io::write_mesh(&inp, &case.mesh).unwrap();
    let args = ["optimize", s(&inp), "-o", s(&out), "--batches", "8"];
    let o = zipmesh(&[&args[..], &["--seed", "1501", "--json", "--progress-json"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let lines: Vec<Value> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let (report, rows) = lines.split_last().unwrap();
    assert_eq!(report["triangle_stage"]["guarded"], true);
    let batches = report["batches"].as_array().unwrap();
    assert!(rows.len() > batches.len(), "both runs stream their rows");
    assert_eq!(&rows[rows.len() - batches.len()..], batches.as_slice());
    assert_eq!(batches[0]["batch"], 1);
    let (before, after) = (case.mesh.clone(), io::read_mesh(&out).unwrap().0);
    let reference = Reference::new(&before);
    let [q0, q1] = [&before, &after].map(|m| Summary::against(m, &reference));
    assert!(q1.folded_quads <= q0.folded_quads, "{q0:?} -> {q1:?}");
    let text = zipmesh(&[&args[..], &["--seed", "1501"]].concat());
    assert!(String::from_utf8_lossy(&text.stdout).contains("each triangle merge guarded"));
}
