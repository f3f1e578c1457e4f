//! Running the `zipmesh` binary from the command-line tests.
#![allow(dead_code)]

use serde_json::Value;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use zipmesh::quality::Summary;

/// Runs the binary with `args`.
pub fn zipmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_zipmesh"))
        .args(args)
        .output()
        .expect("the zipmesh binary runs")
}

/// `zip IN --from 15 --to 2 --move LC`: the LC movement on Spot's quad mesh that several
/// tests run (add `-o` and the options).
#[allow(dead_code)] // not every test file that includes this module zips
pub fn spot_zip(input: &str) -> Vec<&str> {
    vec!["zip", input, "--from", "15", "--to", "2", "--move", "LC"]
}

/// Runs the binary with the words of `line` as arguments (for arguments without spaces).
pub fn zipmesh_words(line: &str) -> Output {
    zipmesh(&line.split_whitespace().collect::<Vec<_>>())
}

/// A fresh directory for one test's files.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// A path as `&str`.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

/// The repository's root, where the tests' meshes (`tests/data/`) and docs are.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Whether a JSON number is `x` (serde_json's default parsing may miss by an ulp).
fn same_number(v: &Value, x: Option<f64>) -> bool {
    match (v.as_f64(), x) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-12 * b.abs().max(1.0),
        (a, b) => a.is_none() && b.is_none() && v.is_null(),
    }
}

/// Compares a `"quality"` object (of `stats --json`, or an input or output of an edit's or
/// `optimize`'s report) with the library's summary.
pub fn assert_quality_matches(q: &Value, s: &Summary) {
    assert_eq!(q["faces"], s.faces);
    assert_eq!(q["quads"], s.quads);
    assert_eq!(q["triangles"], s.triangles);
    assert_eq!(q["folded_quads"], s.folded_quads);
    assert_eq!(q["folded_by"]["diagonal"], s.folded_by.diagonal);
    assert_eq!(q["folded_by"]["corner"], s.folded_by.corner);
    assert_eq!(q["folded_by"]["neighbours"], s.folded_by.neighbours);
    assert_eq!(q["negative_scaled_jacobian"], s.negative_jacobian);
    let j = &q["scaled_jacobian"];
    match s.jacobian {
        Some(p) => {
            let pairs = [
                ("min", p.min),
                ("p1", p.p1),
                ("p5", p.p5),
                ("median", p.median),
            ];
            for (key, x) in pairs {
                assert!(
                    same_number(&j[key], Some(x)),
                    "{key}: {} against {x}",
                    j[key]
                );
            }
        }
        None => assert!(j.is_null()),
    }
    assert!(same_number(&q["min_angle_degrees"], s.min_angle), "{q}");
    assert_eq!(q["thin_triangles"], s.thin_triangles);
    assert_eq!(q["flipped_triangles"], s.flipped_triangles);
    assert!(same_number(&q["max_edge_ratio"], s.max_edge_ratio), "{q}");
    assert_eq!(q["degenerate_faces"], s.degenerate_faces);
    match s.distance {
        Some(d) => {
            let got = &q["distance"];
            for (key, x) in [("mean", d.mean), ("p99", d.p99), ("max", d.max)] {
                assert!(same_number(&got[key], Some(x)), "{key}: {got}");
            }
            assert_eq!(got["vertices"], d.vertices);
        }
        None => assert!(q["distance"].is_null()),
    }
}
