//! Campaigns across machines, in the library: the shards `0/n` … `(n-1)/n` merged
//! (`campaign::merge`) give the report of one unsharded run, cell by cell, failures and
//! their shrunk counterexamples included; shards of different campaigns, duplicate and
//! missing shards are refused.
#![cfg(feature = "campaign")]

use std::path::{Path, PathBuf};
use std::time::Duration;
use zipmesh::campaign::{self, Case, Config, MergeError, Outcome, Property, Report, Shard};
use zipmesh::gen;

/// Fails on every mesh with a boundary, naming a boundary vertex (so it shrinks).
fn no_boundary() -> Property {
    Property::new("no-boundary", "the mesh is closed", |c| {
        let m = &c.mesh.map;
        match m.vertices().find(|&v| m.is_boundary_vertex(v)) {
            Some(v) => Outcome::fail("a boundary vertex", Some(v)),
            None => Outcome::Pass { checks: 1 },
        }
    })
}

/// Fails on triangle meshes of more than 40 faces only: its first failure is at a position
/// of its own, and a shrunk counterexample keeps more than 40 faces.
fn small_triangle_meshes() -> Property {
    Property::new("small-triangle-meshes", "", |c| {
        let m = &c.mesh.map;
        let triangles = m.faces().all(|f| m.degree(f) == 3);
        if !triangles {
            Outcome::Skip
        } else if m.num_faces() > 40 {
            Outcome::fail("more than 40 triangles", m.vertices().next())
        } else {
            Outcome::Pass { checks: 1 }
        }
    })
}

fn properties() -> Vec<Property> {
    let mut all = campaign::kernel();
    all.push(no_boundary());
    all.push(small_triangle_meshes());
    all
}

fn dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("merge-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn config(shard: Shard, out: &Path) -> Config {
    Config {
        seed: 11,
        cases: 14,
        max_faces: 160,
        shard,
        jobs: Some(1),
        out_dir: Some(out.to_path_buf()),
        ..Config::default()
    }
}

/// The shards `0/n` … `(n-1)/n`, each with its own output directory (its own machine).
fn shards(n: u64, base: &Path, make: impl Fn(Config) -> Report) -> Vec<Report> {
    (0..n)
        .map(|index| {
            let out = base.join(format!("shard{index}"));
            make(config(Shard { index, count: n }, &out))
        })
        .collect()
}

/// Every field but the times, compared one by one so that a difference names its cell.
fn assert_same_report(merged: &Report, one: &Report) {
    assert_eq!(merged.seed, one.seed);
    assert_eq!(merged.shard, one.shard);
    assert_eq!(
        (merged.planned, merged.run, merged.timed_out),
        (one.planned, one.run, one.timed_out)
    );
    assert_eq!(merged.campaign, one.campaign);
    assert_eq!(merged.rows.len(), one.rows.len());
    for (m, o) in merged.rows.iter().zip(&one.rows) {
        let cells = |r: &campaign::Row| {
            [
                r.cases,
                r.passed,
                r.failed,
                r.skipped,
                r.checks,
                r.cut,
                r.unchecked,
            ]
        };
        assert_eq!(m.property, o.property);
        assert_eq!(cells(m), cells(o), "row {}", o.property);
    }
    assert_eq!(merged.failures.len(), one.failures.len());
    for (m, o) in merged.failures.iter().zip(&one.failures) {
        assert_eq!(
            (&m.property, m.case, m.position, &m.description, &m.message),
            (&o.property, o.case, o.position, &o.description, &o.message)
        );
        assert_eq!(m.original_faces, o.original_faces);
        assert_eq!(
            (&m.path, &m.replay, &m.case_replay),
            (&o.path, &o.replay, &o.case_replay)
        );
        match (&m.shrunk, &o.shrunk) {
            (Some(a), Some(b)) => {
                assert_eq!(a.mesh.map, b.mesh.map, "{}", o.property);
                assert_eq!((a.focus, &a.message), (b.focus, &b.message));
            }
            (None, None) => {}
            _ => panic!("{}: shrunk in one report only", o.property),
        }
    }
    assert_eq!(merged.table(false), one.table(false));
    assert_eq!(merged.to_json(false), one.to_json(false));
}

#[test]
fn four_shards_merged_equal_one_run_cell_by_cell() {
    let base = dir("four");
    let all = properties();
    let one = campaign::run(&config(Shard::ALL, &base.join("one")), &all);
    // The campaign is not trivial: both planted properties fail, at positions in different
    // shards, and a counterexample was shrunk and written.
    assert_eq!(one.failures.len(), 2, "{}", one.table(false));
    let shard_of = |k: usize| one.failures[k].position % 4;
    assert_ne!(shard_of(0), shard_of(1));
    assert!(one.failures.iter().any(|f| f.path.is_some()));
    let parts = shards(4, &base, |c| campaign::run(&c, &all));
    assert!(parts.iter().all(|p| p.planned < one.planned));
    // The shards' counterexamples name their own directories ...
    let mut merged = campaign::merge(&parts).unwrap();
    assert!(merged
        .failures
        .iter()
        .any(|f| f.replay.contains(&format!("shard{}", f.position % 4))));
    // ... and written again where the one run wrote them, the reports are equal.
    let written: Vec<Vec<u8>> = one
        .failures
        .iter()
        .filter_map(|f| f.path.as_ref())
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    merged.write_counterexamples(&base.join("one"));
    assert_same_report(&merged, &one);
    let again: Vec<Vec<u8>> = merged
        .failures
        .iter()
        .filter_map(|f| f.path.as_ref())
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    assert_eq!(again, written);
    // Row times are the shards' sums; the wall time is the longest shard's.
    let sum: Duration = parts.iter().map(|p| p.rows[0].time).sum();
    assert_eq!(merged.rows[0].time, sum);
    assert_eq!(
        merged.elapsed,
        parts.iter().map(|p| p.elapsed).max().unwrap()
    );
}

#[test]
fn shards_of_given_cases_merge_by_position() {
    // Given cases all have index 0: the failure kept must be the one of smallest position.
    let cases = vec![
        Case::from_mesh(gen::cube(2), 11, 0, "cube"),
        Case::from_mesh(gen::torus_grid(4, 4), 11, 0, "torus"),
        Case::from_mesh(gen::grid(3, 3), 11, 0, "grid"),
        Case::from_mesh(gen::grid(4, 2), 11, 0, "strip"),
        Case::from_mesh(gen::grid(2, 2), 11, 0, "square"),
    ];
    let base = dir("given");
    let all = properties();
    let run = |c: Config| campaign::run_cases(&c, &cases, &all, &|| {});
    let one = run(config(Shard::ALL, &base.join("one")));
    let failure = &one.failures[0]; // the kernel holds: only no-boundary fails
    assert_eq!(
        (failure.property.as_str(), failure.position),
        ("no-boundary", 2)
    );
    for n in [2, 3, 5] {
        let mut merged = campaign::merge(&shards(n, &base, run)).unwrap();
        merged.write_counterexamples(&base.join("one"));
        assert_same_report(&merged, &one);
    }
}

#[test]
fn shards_cut_by_a_time_limit_merge_to_a_cut_run() {
    let base = dir("cut");
    let limited = |mut c: Config| {
        c.time_limit = Some(Duration::ZERO);
        campaign::run(&c, &campaign::kernel())
    };
    let one = limited(config(Shard::ALL, &base));
    let merged = campaign::merge(&shards(3, &base, limited)).unwrap();
    assert!(merged.timed_out && merged.run == 0 && merged.planned == 14);
    assert_same_report(&merged, &one);
}

#[test]
fn merging_refuses_shards_of_different_campaigns() {
    let base = dir("refuse");
    let kernel = campaign::kernel();
    let good = shards(2, &base, |c| campaign::run(&c, &kernel));
    let other = |change: &dyn Fn(&mut Config), properties: &[Property]| {
        let mut c = config(Shard { index: 1, count: 2 }, &base);
        change(&mut c);
        campaign::run(&c, properties)
    };
    let differs = |part: Report| match campaign::merge(&[good[0].clone(), part]).unwrap_err() {
        MergeError::Differs { what, report, .. } => {
            assert_eq!(report, 1);
            what
        }
        e => panic!("{e}"),
    };
    assert_eq!(differs(other(&|c| c.seed = 12, &kernel)), "seed");
    assert_eq!(differs(other(&|c| c.cases = 15, &kernel)), "cases");
    assert_eq!(differs(other(&|c| c.max_faces = 161, &kernel)), "max-faces");
    let setting = |c: &mut Config| {
        c.settings.insert("max-distance".into(), "6".into());
    };
    assert_eq!(differs(other(&setting, &kernel)), "settings");
    assert_eq!(differs(other(&|_| {}, &kernel[..3])), "properties");
    let wider = |c: &mut Config| c.shard = Shard { index: 1, count: 3 };
    assert_eq!(differs(other(&wider, &kernel)), "shard count");
    let given = [Case::from_mesh(gen::cube(2), 11, 0, "cube")];
    let c = config(Shard { index: 1, count: 2 }, &base);
    let files = campaign::run_cases(&c, &given, &kernel, &|| {});
    assert!(matches!(
        campaign::merge(&[good[0].clone(), files]).unwrap_err(),
        MergeError::Differs { .. }
    ));

    // Duplicate, missing, none, and a report that contradicts itself.
    let e = campaign::merge(&[good[0].clone(), good[0].clone()]).unwrap_err();
    assert_eq!(
        e,
        MergeError::Duplicate {
            shard: Shard { index: 0, count: 2 },
            first: 0,
            second: 1
        }
    );
    let e = campaign::merge(&good[1..]).unwrap_err();
    assert_eq!(
        e,
        MergeError::Missing {
            count: 2,
            missing: vec![0],
            total: 1
        }
    );
    assert!(e.to_string().contains("0/2"), "{e}");
    assert_eq!(campaign::merge(&[]).unwrap_err(), MergeError::Empty);
    let mut edited = good[1].clone();
    edited.rows[0].passed += 1;
    assert!(matches!(
        campaign::merge(&[good[0].clone(), edited]).unwrap_err(),
        MergeError::Inconsistent { report: 1, .. }
    ));
    assert!(campaign::merge(&good).is_ok());
}
