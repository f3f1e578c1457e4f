//! The fuzz regressions (`fuzz/regressions/TARGET/`), replayed in `cargo test`: the inputs
//! of the Q-zip targets are decoded by the targets' own decoder
//! (`fuzz/fuzz_targets/common/qzip_case.rs`) and checked with the `qzip` target's oracle
//! for every tag; the `qzip_four_moves` inputs also keep what made them crash. `.ci/run`
//! replays every regression through the fuzz binaries themselves.

#[path = "../fuzz/fuzz_targets/common/qzip_case.rs"]
mod qzip_case;

use std::fs;
use std::path::{Path, PathBuf};
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::qzip::{sketch, verify_edit, Qzip, SketchOptions, Tag};

const QZIP_TARGETS: [&str; 4] = ["qzip", "qzip_four_moves", "qzip_homotopy", "qzip_reverse"];

/// The regression files of `target` (none when it has no directory).
fn regressions(target: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/regressions")
        .join(target);
    let mut files: Vec<PathBuf> = fs::read_dir(dir)
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    files.sort();
    files
}

/// The bytes of the regression `name` of `target`.
fn regression(target: &str, name: &str) -> Vec<u8> {
    let files = regressions(target);
    let file = files.iter().find(|f| f.ends_with(name));
    fs::read(file.unwrap_or_else(|| panic!("no regression {target}/{name}"))).unwrap()
}

#[test]
fn every_fuzz_target_directory_of_regressions_names_a_target() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let manifest = fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let mut seen = 0;
    for entry in fs::read_dir(root.join("regressions")).unwrap().flatten() {
        if entry.path().is_dir() {
            let name = entry.file_name().into_string().unwrap();
            assert!(
                manifest.contains(&format!("name = \"{name}\"")),
                "fuzz/regressions/{name} is not a fuzz target"
            );
            seen += regressions(&name).len();
        }
    }
    assert!(seen >= 1, "no regression input at all");
}

#[test]
fn qzip_regressions_keep_the_qzip_targets_oracle() {
    let mut replayed = 0;
    for target in QZIP_TARGETS {
        for file in regressions(target) {
            let data = fs::read(&file).unwrap();
            let c = qzip_case::case(&data)
                .unwrap_or_else(|| panic!("{} decodes to no case", file.display()));
            for tag in Tag::CCW {
                let mut map = c.original.clone();
                match Qzip::new().zip_along(&mut map, &c.path, tag) {
                    Ok(report) => {
                        if let Err(b) = verify_edit(&c.original, &map, &c.path, &report) {
                            panic!("{} {tag}: {b}", file.display());
                        }
                    }
                    Err(_) => assert!(map == c.original, "{} {tag}", file.display()),
                }
            }
            replayed += 1;
        }
    }
    assert!(replayed >= 1);
}

/// The seeds cut from the real meshes (`fuzz/corpus/TARGET/patch-*`, written by
/// `cargo run --example fuzz_patches`) decode to a patch and a path between two interior
/// singularities, and keep the `qzip` target's oracle for every tag.
#[test]
fn real_mesh_patch_seeds_decode_and_keep_the_oracle() {
    use zipmesh::invariants::{is_irregular, MeshKind};
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/qzip");
    let (mut seeds, mut done) = (0, 0);
    for entry in fs::read_dir(dir).unwrap().flatten() {
        if !entry.file_name().to_string_lossy().starts_with("patch-") {
            continue;
        }
        let data = fs::read(entry.path()).unwrap();
        assert_eq!(data[0], qzip_case::PATCH);
        let c = qzip_case::case(&data).expect("a patch seed decodes");
        let m = &c.original;
        for v in [c.path.start(), c.path.end()] {
            assert!(is_irregular(m, MeshKind::Quad, v) && !m.is_boundary_vertex(v));
        }
        for tag in Tag::CCW {
            let mut map = c.original.clone();
            match Qzip::new().zip_along(&mut map, &c.path, tag) {
                Ok(report) => {
                    let edit = verify_edit(&c.original, &map, &c.path, &report);
                    assert!(edit.is_ok(), "{}: {:?}", entry.path().display(), edit);
                    done += 1;
                }
                Err(_) => assert!(map == c.original),
            }
        }
        seeds += 1;
    }
    assert!(seeds >= 20, "{seeds} patch seeds");
    assert!(done >= seeds, "{done} movements done on {seeds} seeds");
}

/// The input found with the shortest-path condition removed: along its bent path two of
/// the four movements are isomorphic, and a shorter path joins the ends, so the target
/// (which requires a shortest path) skips it.
#[test]
fn the_bent_path_regression_is_bent_and_makes_two_movements_isomorphic() {
    let data = regression("qzip_four_moves", "bent-path-rs-equals-lc");
    let c = qzip_case::case(&data).unwrap();
    let shortest = sketch(
        &c.original,
        c.path.start(),
        c.path.end(),
        &SketchOptions::default(),
    )
    .unwrap();
    assert!(shortest.len() < c.path.len(), "{} vs {}", shortest, c.path);
    let codes: Vec<(Tag, CanonicalCode)> = Tag::CCW
        .iter()
        .filter_map(|&t| {
            let mut m = c.original.clone();
            Qzip::new()
                .zip_along(&mut m, &c.path, t)
                .ok()
                .map(|_| (t, CanonicalCode::of(&m)))
        })
        .collect();
    let same = codes
        .iter()
        .enumerate()
        .any(|(i, (_, a))| codes[..i].iter().any(|(_, b)| a == b));
    assert!(same, "movements along {} now pairwise distinct", c.path);
}

/// The input found before `qzip::wraps`: on a 4 x 3 torus with one vertex split, the path
/// from the v3 11 to the v5 7 goes round the short loop and ends next to its start, so it
/// wraps and lists no sweep (`tests/qzip_homotopy.rs` shows that its sweep changes the map).
#[test]
fn the_torus_loop_regression_wraps() {
    use zipmesh::qzip::{one_quad_sweeps, wraps};
    let data = regression("qzip_homotopy", "path-round-a-short-torus-loop");
    let c = qzip_case::case(&data).unwrap();
    assert_eq!(c.path.to_string(), "11 -> 8 -> 9 -> 10 -> 12 -> 7");
    assert!(wraps(&c.original, &c.path), "{}", c.path);
    assert!(one_quad_sweeps(&c.original, &c.path).is_empty());
}

/// Every movement done along the path of a `qzip_homotopy` regression and along each of its
/// one-quad sweeps (labels matched by `start_turn`) gives the same map; returns how many
/// were done on both sides.
fn sweeps_agree(c: &qzip_case::Case<'_>) -> usize {
    use zipmesh::qzip::{one_quad_sweeps, start_turn};
    let run = |p, t| {
        let mut m = c.original.clone();
        Qzip::new()
            .zip_along(&mut m, p, t)
            .ok()
            .map(|_| CanonicalCode::of(&m))
    };
    let mut compared = 0;
    for (_, swept) in &one_quad_sweeps(&c.original, &c.path) {
        let k = start_turn(&c.original, &c.path, swept).unwrap();
        for t in Tag::CCW {
            if let (Some(a), Some(b)) = (run(&c.path, t), run(swept, t.turned(k))) {
                assert!(
                    a == b,
                    "{t} along {} and {} along {swept}",
                    c.path,
                    t.turned(k)
                );
                compared += 1;
            }
        }
    }
    compared
}

/// The input found by a 12-minute `qzip_homotopy` run: on an 8 x 10 grid with
/// two vertex splits, `LC` along `37 -> 28 -> 29 -> 38 -> 47 -> 56 -> 55 -> 46` (which ends
/// round the quad `47 56 55 46`, shortened by the end rule) and along its sweep across the
/// regular quad `47 48 57 56` differed: the end rule shortened the first path only. Now the
/// sweep is straightened before the end rule, and every movement done along the path and
/// along each of its sweeps gives the same map (labels matched by `start_turn`). Since the
/// compass is carried along a v3 start's reroute (`46 -> 100 -> 28`, into the v5 28), `LC`
/// reaches the v5 end 46 with a split and returns to 46, where the reroute starts: refused
/// on both paths alike (`PrepareError::NotSimple`).
#[test]
fn the_sweep_before_the_end_turn_regression_gives_one_map() {
    use zipmesh::qzip::one_quad_sweeps;
    let data = regression("qzip_homotopy", "sweep-before-the-end-turn");
    let c = qzip_case::case(&data).unwrap();
    assert_eq!(
        c.path.to_string(),
        "37 -> 28 -> 29 -> 38 -> 47 -> 56 -> 55 -> 46"
    );
    // The failing pair (LC along the sweep across 47 48 57 56) is among them.
    assert!(one_quad_sweeps(&c.original, &c.path)
        .iter()
        .any(|(_, s)| s.to_string().contains("47 -> 48 -> 57 -> 56")));
    sweeps_agree(&c);
}

/// The input found by a 20-minute run of `qzip_homotopy`: on a torus grid with
/// vertex splits, `LC` from the v3 29 along `29 -> 22 -> 21 -> 14 -> 7 -> 13 -> 12 -> 58` and
/// along its sweep across the regular quad `7 0 6 13` differed. The v3 start's reroute
/// `36 -> 56 -> 22` enters the v3 22 from 56, where the path entered from 29; the compass
/// from 22 on was carried along the planned first edge (`RC`, a right turn counted on the
/// right), not along the reroute (`LC`, a left turn counted on the left), and the chain's
/// transient v3 then ran along the path. Now the compass is carried along the reroute: `LC`
/// along both paths would cancel the crowded start's singularities (the guard refuses both),
/// and every movement done on both sides gives one map.
#[test]
fn the_crowded_v3_start_regression_gives_one_map() {
    use zipmesh::qzip::{plan, prepare};
    let data = regression("qzip_homotopy", "sweep-four-edges-after-a-crowded-start");
    let c = qzip_case::case(&data).unwrap();
    assert_eq!(
        c.path.to_string(),
        "29 -> 22 -> 21 -> 14 -> 7 -> 13 -> 12 -> 58"
    );
    sweeps_agree(&c);
    let s = prepare(&c.original, &plan(&c.original, &c.path, Tag::LC).unwrap()).unwrap();
    let first: Vec<(usize, Option<Tag>)> = s.steps()[..3]
        .iter()
        .map(|x| (x.vertex.index(), x.op))
        .collect();
    assert_eq!(
        first,
        [
            (36, Some(Tag::LC)),
            (56, Some(Tag::RC)),
            (22, Some(Tag::LC))
        ]
    );
}

/// The input found by a 30-minute `qzip_homotopy` run: on a grid with vertex splits, the
/// path `47 -> 40 -> 48 -> 56 -> 0 -> 1 -> 57 -> 58 -> ..` goes round three sides of the
/// quad `56 0 1 57` (the v3 0 and the v5 1 among its corners). Along its sweep across
/// `40 41 49 48`, `LC` at 49 collapses `48 49 57 56` and merges 48 with the later path vertex
/// 57, closing the loop `48 -> 56 -> 0 -> 1 -> 48` round that quad; the chain cut the loop
/// and so skipped the two singularities, and `LS` gave another map than along the path.
/// Now a loop is cut only when its corners were regular before the edit, as in the
/// preparation; this one is refused (`Lost`), and every movement done on both sides gives
/// one map.
#[test]
fn the_loop_round_two_singularities_is_not_cut() {
    use zipmesh::qzip::{one_quad_sweeps, ZipError};
    let data = regression("qzip_homotopy", "loop-round-two-singularities");
    let c = qzip_case::case(&data).unwrap();
    assert_eq!(
        c.path.to_string(),
        "47 -> 40 -> 48 -> 56 -> 0 -> 1 -> 57 -> 58 -> 2 -> 10 -> 9 -> 66"
    );
    let sweeps = one_quad_sweeps(&c.original, &c.path);
    let swept = &sweeps
        .iter()
        .find(|(_, s)| {
            s.to_string()
                .starts_with("47 -> 40 -> 41 -> 49 -> 48 -> 56")
        })
        .expect("the sweep across 40 41 49 48")
        .1;
    let mut m = c.original.clone();
    let e = Qzip::new().zip_along(&mut m, swept, Tag::LS).unwrap_err();
    assert!(m == c.original);
    assert!(
        matches!(e, zipmesh::qzip::QzipError::Execute(ZipError::Lost { .. })),
        "{e}"
    );
    // Along the path itself the same movement is done.
    let mut m = c.original.clone();
    Qzip::new().zip_along(&mut m, &c.path, Tag::LS).unwrap();
    assert!(sweeps_agree(&c) >= 1);
}

/// The input found by a `qzip_homotopy` run on the fixed loop cut (793 thousand runs): the
/// path `.. 12 -> 68 -> 196 -> 96 -> 11` ends round the quad `68 196 96 11` (a U-turn into
/// the v5 11, which the preparation shortens to `68 -> 11`); its sweep across the quad
/// `96 203 113 11` ends `.. 96 -> 203 -> 113 -> 11`, a U-turn shortened to `96 -> 11`, which
/// is the first U-turn again. It was shortened once only, so `RS` gave another map along the
/// sweep. Now the preparation shortens (and straightens) until neither applies, and every
/// movement done on both sides gives one map.
#[test]
fn a_u_turn_left_by_shortening_is_shortened_again() {
    use zipmesh::qzip::{plan, prepare};
    let data = regression("qzip_homotopy", "sweep-at-a-u-turn-end");
    let c = qzip_case::case(&data).unwrap();
    assert!(
        c.path.to_string().ends_with("12 -> 68 -> 196 -> 96 -> 11"),
        "{}",
        c.path
    );
    assert!(sweeps_agree(&c) >= 1);
    // Along the path, RS ends round the quad at the end as the end rule gives it.
    let s = prepare(&c.original, &plan(&c.original, &c.path, Tag::RS).unwrap()).unwrap();
    let tail: Vec<usize> = s.steps()[s.steps().len() - 3..]
        .iter()
        .map(|x| x.vertex.index())
        .collect();
    assert_eq!(tail, [68, 196, 96]);
}
