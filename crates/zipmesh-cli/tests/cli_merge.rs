//! Campaigns across machines, on the command line: `zipmesh check --shard i/n --json` on
//! each machine and `zipmesh check --merge A.json B.json ...` give the table, the JSON and
//! the exit status of one unsharded run; reports of different campaigns, duplicate and
//! missing shards are refused with exit status 2.

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use run::{s, stderr, stdout, temp_dir, zipmesh};
use serde_json::Value;
use std::fs;
use std::path::{Path, PathBuf};
use zipmesh::campaign::{self, Config, Outcome, Property, Shard};

const ARGS: [&str; 6] = ["--cases", "10", "--max-faces", "250", "--seed", "5"];

/// Runs `check ARGS extra`, returning the exit status and standard output.
fn check(extra: &[&str]) -> (Option<i32>, String) {
    let mut all = vec!["check"];
    all.extend_from_slice(&ARGS);
    all.extend_from_slice(extra);
    let out = zipmesh(&all);
    assert!(!stderr(&out).contains("panicked"), "{}", stderr(&out));
    (out.status.code(), stdout(&out))
}

/// Runs the four shards as JSON, each written to `dir/shardI.json`, with `extra` flags.
fn four_shards(dir: &Path, extra: &[&str]) -> Vec<PathBuf> {
    (0..4)
        .map(|i| {
            let shard = format!("{i}/4");
            let (code, json) = check(&[&["--json", "--shard", &shard], extra].concat());
            assert!(matches!(code, Some(0 | 3)), "shard {shard}: {code:?}");
            let path = dir.join(format!("shard{i}.json"));
            fs::write(&path, json).unwrap();
            path
        })
        .collect()
}

fn merge(reports: &[PathBuf], extra: &[&str]) -> std::process::Output {
    let mut all = vec!["check", "--merge"];
    all.extend(reports.iter().map(|p| s(p)));
    all.extend_from_slice(extra);
    zipmesh(&all)
}

/// The JSON without its times (`seconds`, the campaign's and each row's).
fn without_times(text: &str) -> Value {
    let mut v: Value = serde_json::from_str(text).expect("one JSON object");
    v.as_object_mut().unwrap().remove("seconds");
    for row in v["properties"].as_array_mut().unwrap() {
        row.as_object_mut().unwrap().remove("seconds");
    }
    v
}

/// The text without its times: the table's last column and the wall time after the seed.
fn text_without_times(text: &str, rows: usize) -> String {
    text.lines()
        .enumerate()
        .map(|(k, line)| {
            if k <= rows {
                line[..line.len() - 10].to_string() // " {:>9}" time column
            } else if line.contains(" cases run") {
                line[..line.rfind(", ").unwrap()].to_string()
            } else {
                line.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn four_shards_merged_equal_one_run_table_json_and_exit_status() {
    let dir = temp_dir("merge-four");
    let reports = four_shards(&dir, &[]);
    let (code, one_json) = check(&["--json"]);
    let out = merge(&reports, &["--json"]);
    assert_eq!(out.status.code(), code, "{}", stderr(&out));
    let (one, merged) = (without_times(&one_json), without_times(&stdout(&out)));
    assert_eq!(merged, one);
    // Cell by cell (the comparison above, said row by row for a readable failure).
    let shard: Vec<Value> = reports
        .iter()
        .map(|p| without_times(&fs::read_to_string(p).unwrap()))
        .collect();
    for (k, row) in one["properties"].as_array().unwrap().iter().enumerate() {
        for key in [
            "cases",
            "passed",
            "failed",
            "skipped",
            "checks",
            "cut",
            "unchecked",
        ] {
            let sum: u64 = shard
                .iter()
                .map(|v| v["properties"][k][key].as_u64().unwrap())
                .sum();
            assert_eq!(sum, row[key].as_u64().unwrap(), "{key} of {}", row["name"]);
            assert_eq!(merged["properties"][k][key], row[key]);
        }
    }
    // The text: the same table and lines, times apart.
    let rows = one["properties"].as_array().unwrap().len();
    let (code, one_text) = check(&[]);
    let out = merge(&reports, &[]);
    assert_eq!(out.status.code(), code);
    assert_eq!(
        text_without_times(&stdout(&out), rows),
        text_without_times(&one_text, rows)
    );
    assert!(stdout(&out).contains("10 of 10 cases run, seed 5"));
}

#[test]
fn shards_cut_by_the_time_limit_merge_to_exit_3() {
    let dir = temp_dir("merge-cut");
    let reports = four_shards(&dir, &["--time-limit", "0"]);
    let (code, one) = check(&["--json", "--time-limit", "0"]);
    assert_eq!(code, Some(3));
    let out = merge(&reports, &["--json"]);
    assert_eq!(out.status.code(), Some(3));
    assert_eq!(without_times(&stdout(&out)), without_times(&one));
}

/// Shard reports of a library campaign with a property that fails (the command line's own
/// properties all hold): written as JSON, merged by the command line.
#[test]
fn failing_shards_merge_with_their_counterexamples_written_here() {
    let dir = temp_dir("merge-fail");
    let props = [Property::new("closed", "no boundary", |c| {
        let m = &c.mesh.map;
        match m.vertices().find(|&v| m.is_boundary_vertex(v)) {
            Some(v) => Outcome::fail("a boundary vertex", Some(v)),
            None => Outcome::Pass { checks: 1 },
        }
    })];
    let config = |shard, out: PathBuf| Config {
        seed: 3,
        cases: 12,
        max_faces: 200,
        shard,
        out_dir: Some(out),
        ..Config::default()
    };
    let here = dir.join("here");
    let one = campaign::run(&config(Shard::ALL, here.clone()), &props);
    let failure = &one.failures[0];
    let written = fs::read(failure.path.as_ref().unwrap()).unwrap();
    fs::remove_dir_all(&here).unwrap();
    let reports: Vec<PathBuf> = (0..3)
        .map(|index| {
            let elsewhere = dir.join(format!("machine{index}"));
            let r = campaign::run(&config(Shard { index, count: 3 }, elsewhere), &props);
            let path = dir.join(format!("s{index}.json"));
            fs::write(&path, r.to_json(true)).unwrap();
            path
        })
        .collect();
    let out = merge(&reports, &["--json", "--out", s(&here)]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert_eq!(
        without_times(&stdout(&out)),
        without_times(&one.to_json(true))
    );
    // The counterexample is written again here, byte for byte, and the replay names it.
    assert_eq!(fs::read(failure.path.as_ref().unwrap()).unwrap(), written);
    let out = merge(&reports, &["--out", s(&here)]);
    assert_eq!(out.status.code(), Some(1));
    let text = stdout(&out);
    assert!(
        text.contains(&format!("replay: {}", failure.replay)),
        "{text}"
    );
    assert!(text.contains("FAILED closed on case"), "{text}");
    // The replay on the original case needs no file: it runs on any machine.
    assert!(failure
        .case_replay
        .starts_with("zipmesh check --seed 3 --max-faces 200 --case"));
}

#[test]
fn merging_refuses_reports_of_other_campaigns_and_incomplete_sets() {
    let dir = temp_dir("merge-refuse");
    let reports = four_shards(&dir, &[]);
    let other = |name: &str, extra: &[&str]| {
        let mut args = vec!["check", "--json", "--shard", "3/4"];
        args.extend_from_slice(extra);
        if !extra.contains(&"--seed") {
            args.extend_from_slice(&ARGS);
        } else {
            args.extend_from_slice(&ARGS[..4]);
        }
        let out = zipmesh(&args);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {}", stderr(&out));
        let json = stdout(&out);
        let path = dir.join(name);
        fs::write(&path, json).unwrap();
        path
    };
    let cases = [
        (other("seed.json", &["--seed", "6"]), "seed 6, not 5"),
        (other("distance.json", &["--max-distance", "6"]), "settings"),
        (other("props.json", &["--property", "euler"]), "properties"),
    ];
    for (odd, says) in &cases {
        let set = [&reports[..3], std::slice::from_ref(odd)].concat();
        let out = merge(&set, &[]);
        assert_eq!(out.status.code(), Some(2), "{says}");
        let err = stderr(&out);
        assert!(err.contains(says) && err.contains(s(odd)), "{err}");
        assert!(stdout(&out).is_empty());
    }
    let (_, json) = check(&["--json", "--shard", "1/3"]);
    let thirds = dir.join("thirds.json");
    fs::write(&thirds, json).unwrap();
    let broken = dir.join("broken.json");
    fs::write(&broken, "{\"seed\": 5").unwrap();
    for (set, says) in [
        (vec![reports[0].clone(), thirds], "shard count 3, not 4"),
        (reports[..3].to_vec(), "1 of 4 shards missing: 3/4"),
        (
            vec![reports[0].clone(), reports[1].clone(), reports[1].clone()],
            "are both shard 1/4",
        ),
        (vec![broken], "not a report of check --json"),
        (vec![dir.join("absent.json")], "absent.json"),
        (vec![], "--merge needs"),
    ] {
        let out = merge(&set, &[]);
        assert_eq!(out.status.code(), Some(2), "{says}");
        assert!(stderr(&out).contains(says), "{says}: {}", stderr(&out));
    }
    // Flags that choose a campaign make no sense with --merge.
    let out = merge(&reports, &["--seed", "5"]);
    assert_eq!(out.status.code(), Some(2));
}
