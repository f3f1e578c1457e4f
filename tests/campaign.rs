//! The campaign library: built-in properties pass, a deliberately broken operator is caught
//! and shrunk, and reports do not depend on the number of jobs or on sharding.
#![cfg(feature = "campaign")]

use std::collections::BTreeSet;
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use zipmesh::campaign::{self, Case, Config, Outcome, Property, Shard};
use zipmesh::ops::{quad, Refusal, Undo};
use zipmesh::{io, Dart, Map, Vert};

/// The record of a deliberately broken operator (test only, not shipped): a quad collapse
/// whose undo is silently skipped when the merged vertex reached valence 7 or more, a bug of
/// the kind an optimisation ("nothing to restore for big fans") could introduce.
struct BrokenCollapse(Option<quad::QuadCollapse>);

impl Undo for BrokenCollapse {
    fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        match &self.0 {
            Some(record) => record.undo(map),
            None => Ok(()), // the bug: claims success without undoing
        }
    }
}

fn broken_collapse(map: &mut Map, d: Dart) -> Result<BrokenCollapse, Refusal> {
    let record = quad::collapse_quad(map, d)?;
    // The merged vertex keeps the handle of `origin(d)`.
    if map.valence(map.origin(d)) >= 7 {
        Ok(BrokenCollapse(None))
    } else {
        Ok(BrokenCollapse(Some(record)))
    }
}

/// The broken operator registered as a property, as a user would register theirs.
fn broken_property() -> Property {
    campaign::undo_property("broken-collapse-undo", 4, broken_collapse)
}

fn out_dir(name: &str) -> std::path::PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("campaign-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn builtin_properties_pass_on_a_small_campaign() {
    let config = Config {
        cases: 40,
        max_faces: 600,
        seed: 11,
        ..Config::default()
    };
    let report = campaign::run(&config, &campaign::builtin());
    assert!(report.passed(), "{}", report.table(true));
    assert_eq!(report.run, 40);
    for row in &report.rows {
        assert_eq!(row.cases + row.skipped, 40, "{}", row.property);
        assert_eq!(row.passed, row.cases, "{}", row.property);
    }
    // Every operator property applied somewhere: skips are not the whole story.
    assert!(report.rows.iter().all(|r| r.cases > 0 && r.checks > 0));
}

#[test]
fn broken_operator_is_caught_and_shrunk_to_a_small_replayable_mesh() {
    let dir = out_dir("broken");
    let config = Config {
        cases: 30,
        max_faces: 800,
        seed: 3,
        out_dir: Some(dir.clone()),
        ..Config::default()
    };
    let broken = broken_property();
    let report = campaign::run(&config, std::slice::from_ref(&broken));
    assert!(!report.passed());
    let row = &report.rows[0];
    assert!(row.failed > 0);
    assert_eq!(row.passed + row.failed, row.cases);
    let failure = &report.failures[0];
    let shrunk = failure
        .shrunk
        .as_ref()
        .expect("shrinking finds a failing sub-mesh");
    let faces = shrunk.mesh.map.num_faces();
    eprintln!("shrunk to {faces} of {} faces", failure.original_faces);
    assert!(
        faces * 4 <= failure.original_faces,
        "shrunk to {faces} of {} faces",
        failure.original_faces
    );
    // Still fails, exactly as the replay builds it...
    assert!(broken.check(&shrunk.case(config.seed)).is_fail());
    // ...and from the OBJ file written atomically to the output directory.
    let path = failure.path.as_ref().expect("counterexample written");
    assert!(path.starts_with(&dir));
    let (mesh, _) = io::read_mesh(path).unwrap();
    assert_eq!(mesh.map, shrunk.mesh.map);
    let mut replay = Case::from_mesh(mesh, config.seed, 0, "file");
    replay.focus = shrunk.focus;
    assert!(broken.check(&replay).is_fail());
    assert!(failure.replay.contains(path.to_str().unwrap()));
    assert!(failure.replay.contains("--property broken-collapse-undo"));
    {
        // The JSON form parses and carries the same failure.
        let v: serde_json::Value = serde_json::from_str(&report.to_json(true)).unwrap();
        assert_eq!(v["passed"], false);
        let f = &v["failures"][0];
        assert_eq!(f["property"], "broken-collapse-undo");
        assert_eq!(f["case"], failure.case);
        assert_eq!(f["shrunk_faces"], faces);
        assert_eq!(f["original_faces"], failure.original_faces);
        assert_eq!(f["counterexample"], path.to_str().unwrap());
        assert_eq!(f["replay"], failure.replay.as_str());
        assert_eq!(v["properties"][0]["failed"], row.failed);
    }
    // The working operator passes on the same cases.
    let good = campaign::select(&campaign::builtin(), &["quad-collapse".into()]).unwrap();
    let config = Config {
        out_dir: None,
        ..config
    };
    assert!(campaign::run(&config, &good).passed());
}

#[test]
fn report_is_identical_for_one_and_two_jobs() {
    let mut properties = campaign::builtin();
    properties.push(broken_property());
    let base = Config {
        cases: 24,
        max_faces: 500,
        seed: 99,
        ..Config::default()
    };
    let one = campaign::run(
        &Config {
            jobs: Some(1),
            ..base.clone()
        },
        &properties,
    );
    let two = campaign::run(
        &Config {
            jobs: Some(2),
            ..base
        },
        &properties,
    );
    assert_eq!(one.table(false), two.table(false));
    assert_eq!(one.to_json(false), two.to_json(false));
    assert_eq!(one.failures.len(), 1);
    let (a, b) = (&one.failures[0], &two.failures[0]);
    assert_eq!(a.case, b.case);
    let (sa, sb) = (a.shrunk.as_ref().unwrap(), b.shrunk.as_ref().unwrap());
    assert_eq!(sa.mesh.map, sb.mesh.map);
}

#[test]
fn shards_partition_the_cases() {
    let seen: Arc<Mutex<Vec<(u64, usize)>>> = Arc::default();
    let record = {
        let seen = Arc::clone(&seen);
        Property::new("record", "records the case", move |case: &Case| {
            seen.lock()
                .unwrap()
                .push((case.index, case.mesh.map.num_faces()));
            Outcome::Pass { checks: 1 }
        })
    };
    let mut properties = campaign::kernel();
    properties.push(record);
    let base = Config {
        cases: 21,
        max_faces: 300,
        seed: 5,
        ..Config::default()
    };
    let full = campaign::run(&base, &properties);
    let full_seen: BTreeSet<(u64, usize)> = seen.lock().unwrap().drain(..).collect();
    let mut parts = Vec::new();
    let mut union = BTreeSet::new();
    for index in 0..2 {
        let shard = Shard { index, count: 2 };
        let r = campaign::run(
            &Config {
                shard,
                ..base.clone()
            },
            &properties,
        );
        let got: Vec<(u64, usize)> = seen.lock().unwrap().drain(..).collect();
        assert!(got.iter().all(|&(i, _)| i % 2 == index));
        for x in got {
            assert!(union.insert(x), "case {x:?} in two shards");
        }
        parts.push(r);
    }
    assert_eq!(union, full_seen);
    assert_eq!(full_seen.len(), 21);
    assert_eq!(parts[0].planned + parts[1].planned, full.planned);
    for (k, row) in full.rows.iter().enumerate() {
        let (a, b) = (&parts[0].rows[k], &parts[1].rows[k]);
        assert_eq!(a.cases + b.cases, row.cases);
        assert_eq!(a.passed + b.passed, row.passed);
        assert_eq!(a.checks + b.checks, row.checks);
    }
}

#[test]
fn a_panicking_property_is_a_failure_not_a_crash() {
    let p = Property::new("panics", "", |case: &Case| {
        if case.index == 2 {
            panic!("boom in user code");
        }
        Outcome::Pass { checks: 1 }
    });
    let config = Config {
        cases: 4,
        max_faces: 100,
        shrink: false,
        ..Config::default()
    };
    let r = campaign::run(&config, &[p]);
    assert_eq!((r.rows[0].passed, r.rows[0].failed), (3, 1));
    assert_eq!(r.failures[0].case, 2);
    assert!(r.failures[0].message.contains("boom in user code"));
    assert!(r.failures[0].replay.contains("--case 2"));
}

#[test]
fn a_zero_time_limit_runs_nothing_and_says_so() {
    let config = Config {
        cases: 10,
        time_limit: Some(Duration::ZERO),
        ..Config::default()
    };
    let r = campaign::run(&config, &campaign::kernel());
    assert!(r.timed_out);
    assert_eq!((r.planned, r.run), (10, 0));
    assert!(r.rows.iter().all(|row| row.cases == 0));
}

#[test]
fn a_huge_campaign_is_not_sized_by_its_case_count() {
    // 10^15 cases: sizing anything by the count would abort; the limit ends it.
    let config = Config {
        cases: 1_000_000_000_000_000,
        max_faces: 60,
        jobs: Some(2),
        time_limit: Some(Duration::from_millis(300)),
        ..Config::default()
    };
    let r = campaign::run(&config, &campaign::kernel());
    assert!(r.timed_out && r.passed());
    assert_eq!(r.planned, 1_000_000_000_000_000);
    assert!(r.run > 0 && r.run < r.planned);
}

#[test]
fn a_property_polling_the_deadline_is_cut_short_and_counted() {
    // Polls forever: only the deadline ends it.
    let endless = Property::new("endless", "", |case: &Case| {
        let mut checks = 0;
        while !case.out_of_time() {
            checks += 1;
        }
        Outcome::Pass { checks }
    });
    let counter = campaign::CheckCounter::default();
    let config = Config {
        cases: 3,
        max_faces: 60,
        jobs: Some(1),
        time_limit: Some(Duration::from_millis(200)),
        checks: counter.clone(),
        ..Config::default()
    };
    let all = [campaign::kernel()[0].clone(), endless];
    let r = campaign::run(&config, &all);
    assert!(r.timed_out && r.passed());
    assert_eq!(r.run, 1, "the first case takes the whole budget");
    assert_eq!((r.rows[0].cut, r.rows[1].cut), (0, 1));
    assert!(r.rows[1].checks > 0 && counter.get() >= r.rows[1].checks);
    assert!(r.to_json(false).contains("\"cut\":1"));
    // Without a time limit nothing is cut, and polling outside a campaign is false.
    let r = campaign::run(
        &Config {
            cases: 3,
            max_faces: 60,
            ..Config::default()
        },
        &campaign::kernel(),
    );
    assert!(!r.timed_out && r.rows.iter().all(|row| row.cut == 0));
    assert!(!Case::generate(0, 0, 60).out_of_time());
}

#[test]
fn generated_cases_depend_only_on_seed_and_index() {
    for i in [0u64, 1, 17, 1000] {
        let a = Case::generate(8, i, 700);
        let b = Case::generate(8, i, 700);
        assert_eq!(a.mesh.map, b.mesh.map);
        assert_eq!(a.origin, b.origin);
    }
    // Different seeds give different case sequences.
    let differ =
        (0..10).any(|i| Case::generate(1, i, 700).mesh.map != Case::generate(2, i, 700).mesh.map);
    assert!(differ);
}

mod generated {
    use super::*;
    use proptest::prelude::*;
    use zipmesh::campaign::{Kind, Origin};
    use zipmesh::invariants::Counts;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Every generated case is valid, has the face kind and topology it was asked for,
        /// and regular cases respect the face budget.
        #[test]
        fn generated_cases_keep_their_contract(seed in any::<u64>(), index in 0u64..1_000_000, max in 6usize..1500) {
            let case = Case::generate(seed, index, max);
            let map = &case.mesh.map;
            prop_assert_eq!(map.check(), Ok(()));
            let Origin::Generated { shape, kind, genus, holes, .. } = case.origin.clone() else {
                return Err(TestCaseError::fail("a generated case says it was given"));
            };
            let c = Counts::of(map);
            prop_assert_eq!((c.genus, c.boundary_loops, c.components), (genus as i64, holes, 1));
            let degrees: Vec<usize> = map.faces().map(|f| map.degree(f)).collect();
            match kind {
                Kind::Quad => prop_assert!(degrees.iter().all(|&d| d == 4)),
                Kind::Triangle => prop_assert!(degrees.iter().all(|&d| d == 3)),
                Kind::Mixed => prop_assert!(degrees.contains(&3) && degrees.contains(&4)),
            }
            if shape != "random" {
                // The smallest regular case is a cube: 6 quads, 12 triangles.
                prop_assert!(degrees.len() <= max.max(12), "{} faces for budget {max}", degrees.len());
            }
        }

        /// Shards i/n for every i partition the positions, for any n.
        #[test]
        fn shards_partition_positions(n in 1u64..9, positions in 0u64..200) {
            for p in 0..positions {
                let owners = (0..n).filter(|&i| Shard { index: i, count: n }.contains(p)).count();
                prop_assert_eq!(owners, 1);
            }
        }
    }
}

#[test]
fn replay_of_an_unshrunk_given_case_names_the_file_seed_and_focus() {
    let mut case = Case::from_mesh(zipmesh::gen::cube(2), 12, 0, "meshes/cube.obj");
    case.focus = Some(Vert::new(3));
    let p = Property::new("no-cubes", "", |_: &Case| Outcome::fail("a cube", None));
    let config = Config {
        shrink: false,
        ..Config::default()
    };
    let r = campaign::run_cases(&config, &[case], &[p], &|| {});
    assert_eq!(r.failures.len(), 1);
    assert_eq!(
        r.failures[0].replay,
        "zipmesh check meshes/cube.obj --seed 12 --property no-cubes --focus 3"
    );
}

/// `qzip-reversal` counts the movements with no reverse run found as `unchecked` (table and
/// JSON) instead of skipping them silently: on the preprocessed toroidal tetrahedron most of
/// its movements miss. Other properties report 0, and the property still passes.
#[test]
fn reversal_misses_are_counted_as_unchecked() {
    let file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/quad/osd_catmark_toroidal_tet.obj");
    let (mut mesh, _) = io::read_mesh(&file).unwrap();
    zipmesh::qzip::preprocess(&mut mesh).unwrap();
    let cases = [Case::from_mesh(mesh, 0, 0, "toroidal tet, preprocessed")];
    let choice = campaign::PairChoice {
        max_distance: 2,
        per_case: None,
    };
    let mut props = campaign::select(
        &campaign::qzip_properties(choice),
        &["qzip-grid".into(), "qzip-reversal".into()],
    )
    .unwrap();
    props.push(campaign::kernel()[0].clone());
    let r = campaign::run_cases(&Config::default(), &cases, &props, &|| {});
    assert!(r.passed(), "{}", r.table(false));
    let (grid, rev, validity) = (&r.rows[0], &r.rows[1], &r.rows[2]);
    assert!(rev.unchecked > 0 && rev.checks > 0, "{}", r.table(false));
    assert_eq!(rev.passed, 1);
    // Every movement done is reversed or unchecked; grid also counts the refusals.
    assert!(
        rev.checks + rev.unchecked <= grid.checks,
        "{}",
        r.table(false)
    );
    assert_eq!((grid.unchecked, validity.unchecked), (0, 0));
    // Some reverse runs are derived, some searched: the searched ones are counted apart.
    assert!(
        rev.searched > 0 && rev.searched < rev.checks,
        "{}",
        r.table(false)
    );
    assert_eq!(grid.searched, 0);
    let json = r.to_json(false);
    assert!(
        json.contains(&format!("\"searched\":{}", rev.searched)),
        "{json}"
    );
    assert!(
        json.contains(&format!("\"unchecked\":{}", rev.unchecked)),
        "{json}"
    );
    let table = r.table(false);
    assert!(
        table.lines().next().unwrap().ends_with("unchecked"),
        "{table}"
    );
    let line = table
        .lines()
        .find(|l| l.starts_with("qzip-reversal"))
        .unwrap();
    assert!(line.ends_with(&format!(" {}", rev.unchecked)), "{table}");
}

/// `Case::note_unchecked` does nothing outside a campaign; inside, a case with only
/// unchecked items and a pass counts as passed, with the items in the row.
#[test]
fn note_unchecked_outside_a_campaign_does_nothing() {
    let case = Case::generate(0, 0, 60);
    case.note_unchecked(3);
    let p = Property::new("misses-only", "", |c: &Case| {
        c.note_unchecked(2);
        Outcome::Pass { checks: 0 }
    });
    let r = campaign::run_cases(&Config::default(), &[case], &[p], &|| {});
    assert_eq!((r.rows[0].unchecked, r.rows[0].passed), (2, 1));
}
