//! The `zipmesh` binary: JSON stats against the library, hashes, `iso` exit codes, and
//! errors for bad files and bad usage.

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use common::shared;
use glam::DVec3;
use run::{assert_quality_matches, s, stderr, stdout, temp_dir, zipmesh, zipmesh_words};
use serde_json::Value;
use std::fs;
use std::path::Path;
use std::process::Command;
use zipmesh::invariants::canonical::canonical_hash;
use zipmesh::invariants::{gauss_bonnet, irregular_vertices, Counts, Histograms, MeshKind};
use zipmesh::quality::{Reference, Summary};
use zipmesh::{gen, io, Mesh};

/// Compares `stats --json` output with the library's own numbers for `mesh`.
fn assert_stats_match(json: &Value, mesh: &Mesh, unreferenced: usize) {
    let map = &mesh.map;
    let c = Counts::of(map);
    let h = Histograms::of(map);
    let kind = MeshKind::of(map);
    let gb = gauss_bonnet(map, kind);
    let hist = |m: &std::collections::BTreeMap<usize, usize>| -> Value {
        m.iter()
            .map(|(k, v)| (k.to_string(), Value::from(*v)))
            .collect::<serde_json::Map<_, _>>()
            .into()
    };
    assert_eq!(json["vertices"], c.vertices);
    assert_eq!(json["edges"], c.edges);
    assert_eq!(json["faces"], c.faces);
    assert_eq!(json["boundary_loops"], c.boundary_loops);
    assert_eq!(json["components"], c.components);
    assert_eq!(json["euler_characteristic"], c.euler_characteristic);
    assert_eq!(json["genus"], c.genus);
    assert_eq!(json["face_degrees"], hist(&h.face_degrees));
    assert_eq!(json["interior_valences"], hist(&h.interior_valences));
    assert_eq!(json["boundary_valences"], hist(&h.boundary_valences));
    assert_eq!(json["unreferenced_vertices"], unreferenced);
    assert_eq!(
        json["irregular_vertices"],
        irregular_vertices(map, kind).len()
    );
    assert_eq!(json["gauss_bonnet"]["vertex_sum"], gb.vertex_sum);
    assert_eq!(json["gauss_bonnet"]["face_sum"], gb.face_sum);
    assert_eq!(json["gauss_bonnet"]["rhs"], gb.rhs);
    assert_eq!(json["gauss_bonnet"]["holds"], true);
    assert_eq!(
        json["canonical_hash"],
        format!("{:032x}", canonical_hash(map))
    );
    assert_quality_matches(&json["quality"], &Summary::of(mesh));
}

/// `--reference` adds the vertices' distances to another mesh's surface: 0 for the input
/// itself, the library's numbers for a mesh with moved vertices; the table shows them in
/// one row, and the quality rows name what they count.
#[test]
fn stats_measures_quality_and_the_distance_to_a_reference() {
    let dir = temp_dir("reference");
    let input = shared("quad/spot_quadrangulated.obj");
    let (mesh, _) = io::read_mesh(&input).unwrap();
    let mut moved = mesh.clone();
    for (i, p) in moved.positions.iter_mut().enumerate().step_by(7) {
        *p += DVec3::new(0.0, 0.01 * (i % 5) as f64, 0.02);
    }
    let moved_path = dir.join("moved.obj");
    io::write_mesh(&moved_path, &moved).unwrap();
    let (moved, _) = io::read_mesh(&moved_path).unwrap(); // as written, digits and all
    let reference = Reference::new(&mesh);
    for (path, m) in [(&input, &mesh), (&moved_path, &moved)] {
        let out = zipmesh(&["stats", "--json", s(path), "--reference", s(&input)]);
        assert!(out.status.success(), "{}", stderr(&out));
        let json: Value = serde_json::from_str(&stdout(&out)).unwrap();
        assert_quality_matches(&json["quality"], &Summary::against(m, &reference));
    }
    let d = Summary::against(&moved, &reference).distance.unwrap();
    assert!(d.max > 0.001 && d.mean > 0.0);

    let out = zipmesh(&["stats", s(&moved_path), "--reference", s(&input)]);
    assert!(out.status.success(), "{}", stderr(&out));
    let table = stdout(&out);
    for label in [
        "folded quads",
        "scaled jacobian < 0",
        "scaled jacobian 1st %",
        "min angle",
        "triangles < 10 deg",
        "flipped triangles",
        "max edge ratio",
        "degenerate faces",
        "distance to reference",
    ] {
        assert!(
            table.lines().any(|l| l.starts_with(label)),
            "no {label} row in {table}"
        );
    }
    let row = format!("mean {:.6}, 99th % {:.6}, max {:.6}", d.mean, d.p99, d.max);
    assert!(table.contains(&row), "{row} in {table}");
    // A reference that cannot be read is an error (exit 2), as the mesh itself would be.
    let out = zipmesh(&["stats", s(&input), "--reference", s(&dir.join("none.obj"))]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}

#[test]
fn stats_json_equals_the_library() {
    for rel in [
        "tri/circle_disk.obj",
        "quad/osd_catmark_helmet.obj",
        "poly/blub_control_mesh.obj",
    ] {
        let path = shared(rel);
        let out = zipmesh(&["stats", s(&path), "--json"]);
        assert!(out.status.success(), "{}", stderr(&out));
        let json: Value = serde_json::from_str(&stdout(&out)).unwrap();
        let (mesh, report) = io::read_mesh(&path).unwrap();
        assert_stats_match(&json, &mesh, report.unreferenced.len());
    }
    let kinds = [
        ("tri/torus.obj", "triangle"),
        ("quad/osd_catmark_torus.obj", "quad"),
        ("poly/spot_control_mesh.obj", "mixed"),
    ];
    for (rel, kind) in kinds {
        let out = zipmesh(&["stats", "--json", s(&shared(rel))]);
        let json: Value = serde_json::from_str(&stdout(&out)).unwrap();
        assert_eq!(json["kind"], kind, "{rel}");
    }
}

#[test]
fn stats_counts_unreferenced_vertices_in_an_off_file() {
    let dir = temp_dir("unreferenced");
    let path = dir.join("extra.off");
    fs::write(
        &path,
        "OFF\n5 1 0\n0 0 0\n1 0 0\n9 9 9\n1 1 0\n0 1 0\n4 0 1 3 4\n",
    )
    .unwrap();
    let out = zipmesh(&["stats", "--json", s(&path)]);
    assert!(out.status.success(), "{}", stderr(&out));
    let json: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let (mesh, _) = io::read_mesh(&path).unwrap();
    assert_stats_match(&json, &mesh, 1);
    assert_eq!(json["vertices"], 4);
}

#[test]
fn stats_without_a_file_reads_the_shipped_mesh_from_any_directory() {
    let dir = temp_dir("cwd");
    let out = Command::new(env!("CARGO_BIN_EXE_zipmesh"))
        .args(["stats", "--json"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let json: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let shipped = run::root().join("crates/zipmesh-cli/data/spot_control_mesh.obj");
    let (mesh, _) = io::read_mesh(shipped).unwrap();
    assert_stats_match(&json, &mesh, 0);

    // The table names every quantity and the built-in file.
    let out = zipmesh(&["stats"]);
    assert!(out.status.success());
    let table = stdout(&out);
    assert!(table.contains("spot_control_mesh.obj"), "{table}");
    for (label, value) in [
        ("vertices", mesh.map.num_vertices()),
        ("edges", mesh.map.num_edges()),
        ("faces", mesh.map.num_faces()),
    ] {
        let row = table
            .lines()
            .find(|l| l.split_whitespace().next() == Some(label))
            .unwrap_or_else(|| panic!("no {label} row in {table}"));
        assert!(row.ends_with(&format!(" {value}")), "{row}");
    }
}

/// The same connectivity under another numbering: vertices reversed, faces reversed in
/// order and each face's corners rotated by one.
fn relabelled(mesh: &Mesh) -> Mesh {
    let n = mesh.positions.len() as u32;
    let positions: Vec<DVec3> = mesh.positions.iter().rev().copied().collect();
    let faces: Vec<Vec<u32>> = mesh
        .polygons()
        .into_iter()
        .rev()
        .map(|p| {
            let mut q: Vec<u32> = p.iter().map(|&v| n - 1 - v).collect();
            q.rotate_left(1);
            q
        })
        .collect();
    Mesh::from_polygons(positions, &faces).unwrap().0
}

/// The mirror image: every face's corners reversed.
fn mirrored(mesh: &Mesh) -> Mesh {
    let faces: Vec<Vec<u32>> = mesh
        .polygons()
        .into_iter()
        .map(|mut p| {
            p.reverse();
            p
        })
        .collect();
    Mesh::from_polygons(mesh.positions.clone(), &faces)
        .unwrap()
        .0
}

#[test]
fn hash_is_independent_of_numbering() {
    let dir = temp_dir("hash");
    let mesh = gen::torus_grid(5, 3);
    let (a, b, c) = (dir.join("a.obj"), dir.join("b.off"), dir.join("c.obj"));
    io::write_mesh(&a, &mesh).unwrap();
    io::write_mesh(&b, &relabelled(&mesh)).unwrap();
    io::write_mesh(&c, &gen::torus_grid(5, 4)).unwrap();
    assert_ne!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
    let hash = |p: &Path| {
        let out = zipmesh(&["hash", s(p)]);
        assert!(out.status.success(), "{}", stderr(&out));
        stdout(&out).trim().to_string()
    };
    let ha = hash(&a);
    assert_eq!(ha.len(), 32);
    assert!(ha.bytes().all(|b| b.is_ascii_hexdigit()));
    assert_eq!(ha, format!("{:032x}", canonical_hash(&mesh.map)));
    assert_eq!(hash(&b), ha);
    assert_ne!(hash(&c), ha);
}

/// A torus grid with a few quads cut into triangles, chosen (deterministically) so that
/// the map is not isomorphic to its mirror image.
fn chiral_mesh() -> Mesh {
    let torus = gen::torus_grid(6, 5);
    for seed in 0..200 {
        let mut rng = zipmesh::rng::Rng::new(seed);
        let mut faces: Vec<Vec<u32>> = Vec::new();
        for q in torus.polygons() {
            if rng.chance(1, 5) {
                let k = rng.below(2);
                faces.push(vec![q[k], q[k + 1], q[(k + 2) % 4]]);
                faces.push(vec![q[(k + 2) % 4], q[(k + 3) % 4], q[k]]);
            } else {
                faces.push(q);
            }
        }
        let (mesh, _) = Mesh::from_polygons(torus.positions.clone(), &faces).unwrap();
        if !zipmesh::is_isomorphic(&mesh.map, &mesh.map.mirror()) {
            return mesh;
        }
    }
    panic!("no chiral cut torus found");
}

#[test]
fn iso_exit_codes() {
    let dir = temp_dir("iso");
    let chiral = chiral_mesh();
    let (a, b, m, other) = (
        dir.join("a.obj"),
        dir.join("b.obj"),
        dir.join("m.off"),
        dir.join("other.obj"),
    );
    io::write_mesh(&a, &chiral).unwrap();
    io::write_mesh(&b, &relabelled(&chiral)).unwrap();
    io::write_mesh(&m, &mirrored(&relabelled(&chiral))).unwrap();
    io::write_mesh(&other, &gen::cube(3)).unwrap();

    let code = |args: &[&str]| zipmesh(args).status.code();
    assert_eq!(code(&["iso", s(&a), s(&b)]), Some(0));
    assert_eq!(code(&["iso", s(&a), s(&other)]), Some(1));
    assert_eq!(code(&["iso", s(&a), s(&m), "--mirror"]), Some(0));
    assert_eq!(code(&["iso", "--mirror", s(&a), s(&other)]), Some(1));
    // Without --mirror the verdict on the mirror image is the library's.
    let (ma, _) = io::read_mesh(&a).unwrap();
    let (mm, _) = io::read_mesh(&m).unwrap();
    let expect = if zipmesh::is_isomorphic(&ma.map, &mm.map) {
        0
    } else {
        1
    };
    assert_eq!(code(&["iso", s(&a), s(&m)]), Some(expect));

    let out = zipmesh(&["iso", s(&a), s(&b)]);
    let verdict = stdout(&out);
    assert_eq!(verdict.lines().count(), 1);
    assert!(verdict.starts_with("isomorphic"), "{verdict}");
    let out = zipmesh(&["iso", s(&a), s(&other)]);
    assert!(stdout(&out).starts_with("not isomorphic"));

    let missing = dir.join("missing.obj");
    let out = zipmesh(&["iso", s(&a), s(&missing)]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("missing.obj"), "{}", stderr(&out));
}

#[test]
fn bad_files_exit_2_naming_file_line_and_defect() {
    let dir = temp_dir("bad");
    let bad = dir.join("bowtie.obj");
    fs::write(
        &bad,
        "# two triangles sharing one edge three times\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 2 0\n\
f 1 2 3\nf 2 1 4\nf 1 2 5\n",
    )
    .unwrap();
    for args in [
        vec!["stats", s(&bad)],
        vec!["stats", "--json", s(&bad)],
        vec!["hash", s(&bad)],
        vec!["iso", s(&bad), s(&bad)],
    ] {
        let out = zipmesh(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains("bowtie.obj:9:"), "{err}");
        assert!(err.contains("non-manifold edge"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(out.stdout.is_empty());
    }
    let bad_off = dir.join("short.off");
    fs::write(&bad_off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n").unwrap();
    let out = zipmesh(&["hash", s(&bad_off)]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("short.off:5:"), "{}", stderr(&out));
    let out = zipmesh(&["stats", s(&dir.join("notes.txt"))]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("notes.txt"));
}

/// A directory given as input is said to be one, whatever its name.
#[test]
fn a_directory_as_input_is_a_directory() {
    let dir = temp_dir("input-dir");
    let named = dir.join("looks.obj");
    fs::create_dir(&named).unwrap();
    for path in [&dir, &named] {
        for args in [vec!["stats", s(path)], vec!["check", s(path)]] {
            let out = zipmesh(&args);
            assert_eq!(out.status.code(), Some(2), "{args:?}");
            let err = stderr(&out);
            assert!(
                err.ends_with(&format!("{}: is a directory\n", path.display())),
                "{err}"
            );
        }
    }
    let out = zipmesh(&["iso", s(&spot_quads()), s(&named)]);
    assert!(
        stderr(&out).contains("looks.obj: is a directory"),
        "{}",
        stderr(&out)
    );
}

/// Every command that writes refuses an output into a missing directory before it reads
/// its input (the input here is broken: the message is about the output).
#[test]
fn every_writing_command_checks_its_output_first() {
    let dir = temp_dir("targets-first");
    let bad = shared("invalid/osd_catmark_fan.obj");
    let gone = dir.join("gone");
    let (obj, svg) = (gone.join("o.obj"), gone.join("o.svg"));
    let (bad, obj, svg) = (s(&bad), s(&obj), s(&svg));
    for args in [
        vec![
            "zip", bad, "--from", "1", "--to", "2", "--move", "LS", "-o", obj,
        ],
        vec![
            "tri-move",
            bad,
            "--pair",
            "1,2",
            "--direction",
            "0",
            "-o",
            obj,
        ],
        vec!["tri-generate", bad, "--at", "1", "-o", obj],
        vec!["tri-type", bad, "--split", "1", "-o", obj],
        vec!["tri-cancel", bad, "--triple", "1,2,3", "-o", obj],
        vec!["qd-walk", bad, "--triangle", "0", "--to", "1", "-o", obj],
        vec!["optimize", bad, "-o", obj],
        vec!["render", bad, "-o", svg],
    ] {
        let out = zipmesh(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        let expected = format!("the directory {} does not exist\n", gone.display());
        assert!(err.starts_with("zipmesh: cannot write "), "{args:?}: {err}");
        assert!(err.ends_with(&expected), "{args:?}: {err}");
    }
    assert!(!gone.exists());
    // `check` makes its --out folder when it writes a shrunk counterexample there, so a
    // missing one is no error, but a file or a path under one is.
    let file = dir.join("file");
    fs::write(&file, "").unwrap();
    for out_dir in [file.clone(), file.join("sub")] {
        let out = zipmesh(&["check", "--cases", "1", "--out", s(&out_dir)]);
        assert_eq!(out.status.code(), Some(2));
        let expected = format!("{} is not a directory", file.display());
        assert!(stderr(&out).contains(&expected), "{}", stderr(&out));
    }
}

/// Messages number vertices from 0, as `--from`, `--path` and `--tip` take them, with an OBJ
/// file's own 1-based numbers quoted beside; lines stay 1-based; the help says so.
#[test]
fn messages_number_vertices_from_0_as_the_arguments_do() {
    let expect = |args: &[&str], message: &str| {
        let out = zipmesh(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains(message), "{args:?}: {err}");
    };
    // Lines 57, 60 and 64 of the fan all hold the file's `8` and `9`: vertices 7 and 8.
    let fan = shared("invalid/osd_catmark_fan.obj");
    expect(
        &["stats", s(&fan)],
        "osd_catmark_fan.obj:64: edge 7-8 (0-based; `8`-`9` in the file) is used by three \
         or more faces (lines 57, 60 and 64): non-manifold edge",
    );
    // Line 131 of the pole is `f 4 3 5 5`: the file's `5` is vertex 4.
    let pole = shared("invalid/osd_catmark_nonman_quadpole64.obj");
    expect(
        &["hash", s(&pole)],
        "osd_catmark_nonman_quadpole64.obj:131: face uses vertex 4 (0-based; `5` in the \
         file) twice: repeated corner",
    );
    let dir = temp_dir("numbers");
    let (obj, off) = (dir.join("far.obj"), dir.join("far.off"));
    fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
    fs::write(&off, "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 2\n").unwrap();
    expect(
        &["stats", s(&obj)],
        "far.obj:4: vertex 8 (0-based; `9` in the file) is out of range for 3 vertices \
         (0 to 2): index out of range",
    );
    // OFF numbers from 0 itself: no note.
    expect(
        &["stats", s(&off)],
        "far.off:7: face uses vertex 2 twice: repeated corner\n",
    );
    let help = stdout(&zipmesh(&["--help"]));
    assert!(
        help.contains(
            "Vertices and faces are numbered from 0 in file order, in arguments and in every \
             message"
        ),
        "{help}"
    );
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        vec![],
        vec!["frobnicate"],
        vec!["hash"],
        vec!["iso", "only-one.obj"],
        vec!["stats", "--yaml"],
    ] {
        let out = zipmesh(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!stderr(&out).is_empty());
    }
    assert_eq!(zipmesh(&["--help"]).status.code(), Some(0));
}

// ---------------------------------------------------------------------------------------
// `zipmesh check`

fn check_json(args: &[&str]) -> Value {
    let mut all = vec!["check", "--json"];
    all.extend_from_slice(args);
    let out = zipmesh(&all);
    assert_eq!(out.status.code(), Some(0), "{all:?}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("check --json prints one JSON object")
}

/// The property rows without their (non-deterministic) times.
fn rows_without_time(v: &Value) -> Vec<Value> {
    v["properties"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let mut r = r.clone();
            r.as_object_mut().unwrap().remove("seconds");
            r
        })
        .collect()
}

#[test]
fn check_json_passes_every_builtin_property() {
    let v = check_json(&["--cases", "12", "--max-faces", "400", "--seed", "4"]);
    assert_eq!(v["run"], 12);
    assert_eq!(v["passed"], true);
    assert!(v["failures"].as_array().unwrap().is_empty());
    let rows = v["properties"].as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["name"].as_str().unwrap()).collect();
    for expected in [
        "validity",
        "euler",
        "gauss-bonnet",
        "canonical-relabel",
        "quad-collapse",
        "tri-flip",
    ] {
        assert!(
            names.contains(&expected),
            "{expected} missing from {names:?}"
        );
    }
    for r in rows {
        assert_eq!(r["passed"], r["cases"], "{r}");
        assert_eq!(r["failed"], 0, "{r}");
        let total = r["cases"].as_u64().unwrap() + r["skipped"].as_u64().unwrap();
        assert_eq!(total, 12, "{r}");
    }
}

#[test]
fn check_table_is_the_same_for_one_and_two_jobs_and_shards_partition_it() {
    let args = ["--cases", "10", "--max-faces", "300", "--seed", "21"];
    let one = check_json(&[&args[..], &["--jobs", "1"]].concat());
    let two = check_json(&[&args[..], &["--jobs", "2"]].concat());
    assert_eq!(rows_without_time(&one), rows_without_time(&two));
    let a = check_json(&[&args[..], &["--shard", "0/2"]].concat());
    let b = check_json(&[&args[..], &["--shard", "1/2"]].concat());
    assert_eq!(a["run"].as_u64().unwrap() + b["run"].as_u64().unwrap(), 10);
    for (k, row) in rows_without_time(&one).iter().enumerate() {
        for key in ["cases", "passed", "skipped", "checks"] {
            let sum = a["properties"][k][key].as_u64().unwrap()
                + b["properties"][k][key].as_u64().unwrap();
            assert_eq!(sum, row[key].as_u64().unwrap(), "{key} of {}", row["name"]);
        }
    }
}

#[test]
fn check_selects_properties_and_replays_one_case() {
    let v = check_json(&[
        "--cases",
        "5",
        "--property",
        "euler",
        "--property",
        "validity",
    ]);
    let names: Vec<&str> = v["properties"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["euler", "validity"]);
    let v = check_json(&["--case", "3", "--seed", "8", "--property", "tri-flip"]);
    assert_eq!(
        (v["planned"].as_u64(), v["run"].as_u64()),
        (Some(1), Some(1))
    );
    // A zero time limit runs nothing, says so, and is not a failure: exit 3, not 0.
    let out = zipmesh(&["check", "--json", "--cases", "5", "--time-limit", "0"]);
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(
        (
            v["run"].as_u64(),
            v["timed_out"].as_bool(),
            v["passed"].as_bool()
        ),
        (Some(0), Some(true), Some(true))
    );
    // Not a terminal: no progress bar, nothing on stderr.
    let out = zipmesh(&["check", "--cases", "3", "--max-faces", "100"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(out.stderr.is_empty(), "{}", stderr(&out));
    assert!(
        stdout(&out).contains("3 of 3 cases run"),
        "{}",
        stdout(&out)
    );
    let out = zipmesh(&["check", "--list"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(stdout(&out).contains("gauss-bonnet"));
}

#[test]
fn check_files_runs_the_properties_on_each_mesh() {
    let files = [
        shared("quad/osd_catmark_torus.obj"),
        shared("tri/torus.obj"),
    ];
    let v = check_json(&[s(&files[0]), s(&files[1]), "--max-distance", "6"]);
    assert_eq!(v["planned"], 2);
    assert_eq!(v["passed"], true);
    let rows = v["properties"].as_array().unwrap();
    let row = |name: &str| rows.iter().find(|r| r["name"] == name).unwrap().clone();
    // One quad mesh and one triangle mesh: each operator family applies to one of them.
    assert_eq!(row("validity")["cases"], 2);
    assert_eq!(row("quad-collapse")["cases"], 1);
    assert_eq!(row("tri-collapse")["cases"], 1);
    // The text form ends with the verdict.
    let out = zipmesh(&["check", s(&files[0])]);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        stdout(&out).contains("all properties hold"),
        "{}",
        stdout(&out)
    );
}

#[test]
fn check_usage_and_input_errors_exit_2() {
    let missing = temp_dir("check-missing").join("absent.obj");
    for args in [
        vec!["check", "--property", "nope"],
        vec!["check", "--shard", "2/2"],
        vec!["check", "--shard", "one/two"],
        vec!["check", "--jobs", "0"],
        vec!["check", "--time-limit", "-1"],
        vec!["check", "--cases", "many"],
        vec!["check", "--frobnicate"],
        vec!["check", "--case", "1", "x.obj"],
        vec!["check", s(&missing)],
    ] {
        let out = zipmesh(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!stderr(&out).is_empty(), "{args:?}");
        assert!(!stderr(&out).contains("panicked"), "{args:?}");
    }
    let out = zipmesh(&["check", "--property", "nope"]);
    let err = stderr(&out);
    assert!(
        err.contains("nope") && err.contains("validity") && err.contains("tri-edge-split"),
        "{err}"
    );
}

// ---------------------------------------------------------------------------------------
// Output that cannot be written, and signals during a write

fn spot_quads() -> std::path::PathBuf {
    shared("quad/spot_quadrangulated.obj")
}

/// One invocation of every subcommand that prints to standard output.
/// The command left no file (no OUT, no temporary) in `dir`.
fn assert_nothing_written(dir: &Path, args: &[String]) {
    let left: Vec<_> = fs::read_dir(dir).unwrap().collect();
    assert!(left.is_empty(), "{args:?}: left {left:?}");
}

fn every_printing_command(dir: &Path) -> Vec<Vec<String>> {
    let spot = spot_quads().to_str().unwrap().to_string();
    let out = dir.join("zipped.obj").to_str().unwrap().to_string();
    let pair = ["--from", "15", "--to", "2"].map(String::from);
    let mut zip: Vec<String> = ["zip", &spot, "--move", "LS", "-o", &out]
        .map(String::from)
        .to_vec();
    zip.extend(pair.clone());
    let mut moves = vec!["moves".to_string(), spot.clone()];
    moves.extend(pair);
    let v = |a: &[&str]| a.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let page = dir.join("spot.html").to_str().unwrap().to_string();
    let amo = shared("quad/amo_quad.obj").to_str().unwrap().to_string();
    let fewer = dir.join("fewer.obj").to_str().unwrap().to_string();
    vec![
        v(&["view", &spot, "-o", &page]),
        // Its first write is a batch's line, while the run goes on.
        v(&[
            "optimize",
            &amo,
            "-o",
            &fewer,
            "--batches",
            "2",
            "--progress-json",
        ]),
        v(&["stats"]),
        v(&["stats", "--json"]),
        v(&["hash", &spot]),
        v(&["iso", &spot, &spot]),
        v(&["check", "--cases", "2", "--property", "validity"]),
        v(&["check", "--list"]),
        v(&["--help"]),
        moves,
        zip,
    ]
}

/// Runs the binary with standard output on a pipe whose reader is already closed, so the
/// first write fails with `EPIPE` whatever the timing.
#[allow(clippy::incompatible_msrv)] // std::io::pipe (1.87): the tests run on a newer toolchain
fn run_into_closed_pipe(args: &[String]) -> std::process::Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    Command::new(env!("CARGO_BIN_EXE_zipmesh"))
        .args(args)
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .output()
        .unwrap()
}

#[test]
fn a_closed_pipe_ends_every_command_quietly_with_141_and_zip_writes_nothing() {
    let dir = temp_dir("closed-pipe");
    for args in every_printing_command(&dir) {
        let out = run_into_closed_pipe(&args);
        assert_eq!(out.status.code(), Some(141), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).is_empty(),
            "{args:?}: quietly: {}",
            stderr(&out)
        );
        assert_nothing_written(&dir, &args);
    }
}

/// Runs the binary with its standard output (`stdout`) or standard error on `/dev/full`.
#[cfg(target_os = "linux")]
fn run_on_dev_full<S: AsRef<std::ffi::OsStr>>(args: &[S], stdout: bool) -> std::process::Output {
    let full = fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_zipmesh"));
    cmd.args(args);
    if stdout {
        cmd.stdout(full);
    } else {
        cmd.stderr(full);
    }
    cmd.output().unwrap()
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_is_an_error_exit_2_and_zip_writes_nothing() {
    let dir = temp_dir("full-disk");
    for args in every_printing_command(&dir) {
        let out = run_on_dev_full(&args, true);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(
            err.contains("cannot write to standard output"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_nothing_written(&dir, &args);
    }
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_standard_error_keeps_the_exit_status() {
    let dir = temp_dir("full-stderr");
    let missing = dir.join("absent.obj");
    for (args, code) in [
        (vec!["stats", s(&missing)], 2),
        (vec!["check", "--property", "nope"], 2),
        (vec!["frobnicate"], 2),
        (vec!["hash", s(&spot_quads())], 0),
    ] {
        let out = run_on_dev_full(&args, false);
        assert_eq!(out.status.code(), Some(code), "{args:?}");
    }
}

#[test]
fn file_names_with_control_characters_are_escaped_in_messages() {
    let dir = temp_dir("control-name");
    let name = dir.join("evil\u{1b}[2J\rname.obj");
    let out = zipmesh(&["hash", s(&name)]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(!err.contains('\u{1b}') && !err.contains('\r'), "{err:?}");
    assert!(err.contains(r"evil\u{1b}[2J\rname.obj"), "{err}");
}

/// A quad mesh large enough that writing it takes a while: Spot subdivided three times.
#[cfg(target_os = "linux")]
fn large_quad_mesh(dir: &Path) -> std::path::PathBuf {
    let (mut mesh, _) = io::read_mesh(spot_quads()).unwrap();
    for _ in 0..3 {
        mesh = gen::catmull_clark(&mesh);
    }
    let path = dir.join("large.obj");
    io::write_mesh(&path, &mesh).unwrap();
    path
}

/// Starts `zip` on `input` writing into `out_dir`, and waits until it has a file open there
/// (the temporary of the write, named or not). Returns the child, still running or not.
#[cfg(target_os = "linux")]
fn zip_caught_writing(input: &Path, out_dir: &Path) -> std::process::Child {
    let out = out_dir.join("out.obj");
    let mut child = Command::new(env!("CARGO_BIN_EXE_zipmesh"))
        .args(["zip", s(input), "--from", "15", "--to", "2", "--move", "LS"])
        .args(["-o", s(&out)])
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let fds = format!("/proc/{}/fd", child.id());
    // Generous: the outcome is asserted, not the time.
    for _ in 0..600_000 {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        let writing = fs::read_dir(&fds)
            .into_iter()
            .flatten()
            .flatten()
            .any(|e| fs::read_link(e.path()).is_ok_and(|t| t.starts_with(out_dir)));
        if writing {
            break;
        }
        std::thread::sleep(std::time::Duration::from_micros(200));
    }
    child
}

#[cfg(target_os = "linux")]
#[test]
fn sigint_or_sigterm_during_a_large_write_leaves_nothing() {
    use std::os::unix::process::ExitStatusExt;
    let dir = temp_dir("signals");
    let input = large_quad_mesh(&dir);
    for (signal, number) in [("-INT", 2), ("-TERM", 15)] {
        let out_dir = dir.join(&signal[1..]);
        fs::create_dir_all(&out_dir).unwrap();
        let mut child = zip_caught_writing(&input, &out_dir);
        let pid = child.id().to_string();
        let _ = Command::new("kill").args([signal, &pid]).status();
        let status = child.wait().unwrap();
        let left: Vec<_> = fs::read_dir(&out_dir).unwrap().flatten().collect();
        if status.success() {
            // The signal came after the commit: only the complete OUT.
            assert_eq!(left.len(), 1, "{signal}");
            assert!(io::read_mesh(out_dir.join("out.obj")).is_ok());
        } else {
            assert_eq!(status.signal(), Some(number), "{signal}: {status:?}");
            assert!(left.is_empty(), "{signal}: left {left:?}");
        }
    }
}

#[cfg(target_os = "linux")]
#[test]
fn after_sigkill_the_target_is_never_partial_and_the_next_write_cleans_up() {
    let dir = temp_dir("sigkill");
    let input = large_quad_mesh(&dir);
    let out_dir = dir.join("out");
    fs::create_dir_all(&out_dir).unwrap();
    let target = out_dir.join("out.obj");
    let mut child = zip_caught_writing(&input, &out_dir);
    let _ = child.kill();
    let _ = child.wait();
    if target.exists() {
        assert!(io::read_mesh(&target).is_ok(), "complete if present");
    }
    // A write killed where temporaries have names leaves this one; the next removes it.
    fs::write(io::temporary_path(&target), "v 0 0 0\n").unwrap();
    let status = zip_caught_writing(&input, &out_dir).wait().unwrap();
    assert!(status.success());
    let left: Vec<_> = fs::read_dir(&out_dir).unwrap().flatten().collect();
    assert_eq!(left.len(), 1, "{left:?}");
    assert!(io::read_mesh(&target).is_ok());
}

// ---------------------------------------------------------------------------------------
// `check` limits: memory and time do not follow `--cases`, the time limit cuts inside a case

#[test]
fn check_with_a_billion_cases_and_a_time_limit_ends_cut_with_exit_3() {
    // Before: 8 GiB allocated up front, an abort. Now: what ran, then exit 3.
    let out = zipmesh_words("check --cases 1000000000 --time-limit 1 --property validity --json");
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["planned"].as_u64(), Some(1_000_000_000));
    assert_eq!(v["timed_out"].as_bool(), Some(true));
    assert!(v["run"].as_u64().unwrap() < 1_000_000_000);
    // Sharded: planned is computed, not counted (counting 2^64 would take centuries).
    let out = zipmesh_words("check --cases 18446744073709551615 --shard 1/3 --time-limit 0 --json");
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["planned"].as_u64(), Some((u64::MAX - 2) / 3 + 1));
}

/// A generated case of about three million faces under `--time-limit 1`: no property
/// starts after the deadline and `canonical-relabel` reads it between its codes, so the run
/// ends within seconds of the limit (it took 42 s when each property's set-up ignored the
/// deadline: generation and the canonical codes alone are seconds at this size). The bound
/// is loose on purpose, a limit kept, not a speed measured.
#[test]
fn the_time_limit_holds_on_a_case_of_millions_of_faces() {
    let start = std::time::Instant::now();
    let out = zipmesh_words("check --max-faces 3000000 --cases 1 --time-limit 1 --jobs 1 --json");
    let took = start.elapsed();
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["timed_out"].as_bool(), Some(true));
    assert!(took.as_secs_f64() < 15.0, "{took:?}");
}

#[test]
fn the_time_limit_cuts_a_long_case_and_the_report_says_which_property() {
    // Every pair of Spot's singularities at any distance: minutes without the limit.
    let spot = spot_quads();
    let out = zipmesh(&[
        "check",
        s(&spot),
        "--property",
        "qzip-grid",
        "--property",
        "validity",
        "--max-distance",
        "1000000",
        "--time-limit",
        "0.5",
    ]);
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("qzip-grid cut short on 1 cases"), "{text}");
    // Validity comes after it and does not start past the deadline.
    assert!(
        text.contains("validity cut short on 1 cases (0 checks ran in all)"),
        "{text}"
    );
    assert!(text.contains("cut by the time limit"), "{text}");
    assert!(!text.contains("all properties hold\n"), "{text}");
    // Without a limit, a small campaign holds on everything: exit 0.
    let out = zipmesh(&["check", "--cases", "2", "--property", "validity"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(stdout(&out).contains("all properties hold\n"));
}

/// `singularities --json` lists exactly the library's irregular vertices, each with its
/// valence, place, defect and the file's position, in the numbering the file has.
#[test]
fn singularities_lists_every_irregular_vertex() {
    for (rel, kind) in [
        ("quad/spot_quadrangulated.obj", MeshKind::Quad),
        ("tri/spot_triangulated.obj", MeshKind::Triangle),
    ] {
        let path = shared(rel);
        let out = zipmesh(&["singularities", "--json", s(&path)]);
        assert!(out.status.success(), "{}", stderr(&out));
        let json: Value = serde_json::from_str(&stdout(&out)).unwrap();
        let (mesh, _) = io::read_mesh(&path).unwrap();
        let listed: Vec<u64> = json["singularities"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e["vertex"].as_u64().unwrap())
            .collect();
        let want: Vec<u64> = irregular_vertices(&mesh.map, kind)
            .into_iter()
            .map(|v| v.index() as u64)
            .collect();
        assert_eq!(listed, want, "{rel}");
        let regular = if kind == MeshKind::Quad { 4 } else { 6 };
        for e in json["singularities"].as_array().unwrap() {
            let v = zipmesh::Vert::new(e["vertex"].as_u64().unwrap() as u32);
            let valence = mesh.map.valence(v);
            assert_eq!(e["valence"], valence, "{rel}");
            assert_eq!(e["defect"], valence as i64 - regular, "{rel}");
            assert_eq!(e["boundary"], false, "{rel}");
            let p = mesh.positions[v.index()];
            assert_eq!(e["position"], serde_json::json!([p.x, p.y, p.z]), "{rel}");
        }
        // The table says the same count in its first line.
        let text = stdout(&zipmesh(&["singularities", s(&path)]));
        let first = text.lines().next().unwrap();
        assert!(
            first.contains(&format!(": {} singularities", want.len())),
            "{first}"
        );
        assert_eq!(text.lines().count(), want.len() + 2, "{rel}");
    }
}

/// `check FILE --pairs N` samples N Q-zip pairs within reach on a large mesh (every movement
/// of each, so 4N grid checks), names the sample and refuses to sample generated cases.
#[test]
fn check_samples_pairs_of_a_given_file() {
    let spot = shared("quad/spot_quadrangulated.obj");
    let run = |seed: &str| -> (u64, Value) {
        let out = zipmesh(&[
            "check",
            s(&spot),
            "--property",
            "qzip-grid",
            "--pairs",
            "20",
            "--seed",
            seed,
            "--json",
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let json: Value = serde_json::from_str(&stdout(&out)).unwrap();
        assert_eq!(json["settings"]["pairs"], "20", "{json}");
        let row = &json["properties"][0];
        (row["checks"].as_u64().unwrap(), json)
    };
    let (checks, _) = run("0");
    // Spot's singularities are spread over the cow: random pairs would rarely be 12 edges
    // apart, the sample's partners are.
    assert_eq!(checks, 4 * 20);
    let text = stdout(&zipmesh(&[
        "check",
        s(&spot),
        "--property",
        "qzip-grid",
        "--pairs",
        "20",
    ]));
    assert!(
        text.contains("Q-zip pairs: a sample of 20 per file, drawn by seed 0"),
        "{text}"
    );
    let out = zipmesh(&["check", "--pairs", "3", "--cases", "1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("--pairs samples the pairs of given files"),
        "{}",
        stderr(&out)
    );
}

/// Every command reads and writes PLY as OBJ: `hash` of a PLY copy equals the OBJ's, `zip`
/// writes `.ply`, and a truncated binary file is refused naming the byte, exit 2.
#[test]
fn ply_files_are_read_and_written_by_the_commands() {
    let dir = temp_dir("ply");
    let obj = shared("quad/spot_quadrangulated.obj");
    let (mesh, _) = io::read_mesh(&obj).unwrap();
    let ply = dir.join("spot.ply");
    io::write_mesh(&ply, &mesh).unwrap();
    let (a, b) = (zipmesh(&["hash", s(&obj)]), zipmesh(&["hash", s(&ply)]));
    assert!(a.status.success() && b.status.success(), "{}", stderr(&b));
    assert_eq!(stdout(&a), stdout(&b).replace(s(&ply), s(&obj)));
    let out = dir.join("moved.ply");
    let mut args = run::spot_zip(s(&ply));
    args.extend(["-o", s(&out)]);
    let z = zipmesh(&args);
    assert!(z.status.success(), "{}", stderr(&z));
    assert!(fs::read(&out)
        .unwrap()
        .starts_with(b"ply\nformat binary_little_endian 1.0\n"));
    let bytes = fs::read(&ply).unwrap();
    let cut = dir.join("cut.ply");
    fs::write(&cut, &bytes[..bytes.len() - 3]).unwrap();
    let e = zipmesh(&["stats", s(&cut)]);
    assert_eq!(e.status.code(), Some(2));
    assert!(
        stderr(&e).contains(": byte ") && stderr(&e).contains(": truncated"),
        "{}",
        stderr(&e)
    );
}

/// The help says what the tool is for (editing, not only counting), what the four Q-zip
/// movements are, and every way a command can be used.
#[test]
fn help_explains_editing_the_movements_and_both_cancellations() {
    let top = stdout(&zipmesh(&["--help"]));
    assert!(
        top.lines()
            .next()
            .unwrap()
            .starts_with("Edit the singularities"),
        "{top}"
    );
    assert!(top.lines().next().unwrap().contains("PLY"), "{top}");
    let zip = stdout(&zipmesh(&["zip", "--help"]));
    for word in [
        "LS or RS split it",
        "LC or RC collapse",
        "derived from the edit",
    ] {
        assert!(zip.contains(word), "{word}: {zip}");
    }
    let cancel = stdout(&zipmesh(&["tri-cancel", "--help"]));
    assert!(
        cancel.lines().next().unwrap().contains("--triple"),
        "{cancel}"
    );
    let optimize = stdout(&zipmesh(&["optimize", "--help"]));
    assert!(
        optimize.contains("quad, quad-dominant or triangle mesh"),
        "{optimize}"
    );
}
