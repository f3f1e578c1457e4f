//! `zipmesh tri-move`, `tri-generate`, `tri-type` and `tri-cancel`: JSON reports checked
//! on the written mesh, the printed undo restoring the input up to isomorphism
//! (`invariants::canonical`), untouched vertices keeping their positions bit for bit, and
//! exit 2 with no output file on bad input.

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use glam::DVec3;
use run::{s, stderr, temp_dir, zipmesh};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Output;
use zipmesh::gen::{cone_disk, geodesic_sphere, subdivided_bipyramid};
use zipmesh::invariants::canonical::is_isomorphic;
use zipmesh::tri_edit::{move_pair, Direction};
use zipmesh::{gen, io, Map, Mesh, Vert};

fn json(o: &Output) -> Value {
    assert!(o.status.success(), "{}", stderr(o));
    serde_json::from_slice(&o.stdout).expect("one JSON value")
}

/// Runs `zipmesh ARGS -o OUT` and returns its output.
fn zipmesh_to(args: &[&str], out: &Path) -> Output {
    let mut all = args.to_vec();
    all.extend(["-o", s(out)]);
    zipmesh(&all)
}

/// Runs `zipmesh ARGS -o OUT --json`, which must succeed, and returns its report; with
/// `--no-relax` unless ARGS choose a `--relax`, so that the placement rules can be compared
/// bit for bit.
fn report(args: &[&str], out: &Path) -> Value {
    let mut all = args.to_vec();
    if !all.contains(&"--relax") {
        all.push("--no-relax");
    }
    report_as_given(&all, out)
}

/// Runs `zipmesh ARGS -o OUT --json` as given, which must succeed, and returns its report.
fn report_as_given(args: &[&str], out: &Path) -> Value {
    let mut all = args.to_vec();
    all.push("--json");
    json(&zipmesh_to(&all, out))
}

/// Runs the `tri-generate` that a cancellation's printed undo (`at`, `toward`, `config`)
/// names, on `file` into `out`; it must succeed.
fn generate_from_undo(file: &Path, u: &Value, out: &Path) {
    let (at, toward) = (u["at"].to_string(), u["toward"].to_string());
    let config = u["config"].as_str().unwrap();
    let args = [
        "tri-generate",
        s(file),
        "--at",
        &at,
        "--toward",
        &toward,
        "--config",
        config,
    ];
    let o = zipmesh_to(&args, out);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Runs the `tri-move` that a report's `undo` (`pair`, `direction`, `steps`) names, on
/// `file` into `out`; it must succeed.
fn run_move_undo(file: &Path, undo: &Value, out: &Path) {
    let (pair, d, k) = (
        join(&numbers(&undo["pair"])),
        undo["direction"].to_string(),
        undo["steps"].to_string(),
    );
    let args = [
        "tri-move",
        s(file),
        "--pair",
        &pair,
        "--direction",
        &d,
        "--steps",
        &k,
    ];
    let o = zipmesh_to(&args, out);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Distinct, irregular positions, so that "unchanged" compares real bits.
fn with_positions(mut map: Map) -> Mesh {
    map.compact();
    let positions = (0..map.vertex_slots())
        .map(|i| {
            let t = i as f64;
            DVec3::new(
                (t * 0.731).sin() * 3.1,
                (t * 1.137).cos() + t / 7.0,
                t.sqrt() * 0.3,
            )
        })
        .collect();
    Mesh { map, positions }
}

fn write(dir: &Path, name: &str, map: Map) -> PathBuf {
    let p = dir.join(name);
    io::write_mesh(&p, &with_positions(map)).unwrap();
    p
}

/// A 14 x 14 triangulated torus with one diagonal flipped (two 5-7 pairs), one pair moved
/// three steps away from the other: a 5-7 pair in a regular neighbourhood. Returns the
/// file and the pair's numbers in it (v5, v7).
fn lone_pair_file(dir: &Path) -> (PathBuf, u32, u32) {
    let (mut map, (mut p, mut q)) = common::tri::flipped_torus(14);
    for _ in 0..3 {
        let m = move_pair(&mut map, p, q, Direction::SplitRight).unwrap();
        (p, q) = (m.p(), m.q());
    }
    let c = map.compact();
    let at = |v: Vert| c.vertices[v.index()].unwrap().index() as u32;
    let (p, q) = (at(p), at(q));
    let file = write(dir, "pair.obj", map);
    (file, p, q)
}

fn read(p: &Path) -> Mesh {
    io::read_mesh(p).unwrap().0
}

/// How many of `before`'s positions (as bits, with multiplicity) are missing from `after`.
fn positions_lost(before: &Mesh, after: &Mesh) -> usize {
    let bits = |m: &Mesh| {
        let mut v: Vec<[u64; 3]> = m
            .positions
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
            .collect();
        v.sort();
        v
    };
    let (a, b) = (bits(before), bits(after));
    let mut lost = 0;
    let mut j = 0;
    for x in &a {
        while j < b.len() && b[j] < *x {
            j += 1;
        }
        if j < b.len() && b[j] == *x {
            j += 1;
        } else {
            lost += 1;
        }
    }
    lost
}

fn numbers(v: &Value) -> Vec<u32> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap() as u32)
        .collect()
}

fn join(v: &[u32]) -> String {
    v.iter().map(u32::to_string).collect::<Vec<_>>().join(",")
}

/// Every direction, 1 and 2 steps, both orders of the pair: the report's pair has a v5 and
/// a v7 in the given order, adjacent, in OUT; the counts add up to the steps; at most two
/// input positions change (a collapse moves one vertex and removes another); and the
/// printed undo, run on OUT, gives a mesh isomorphic to the input.
#[test]
fn tri_move_reports_and_undoes() {
    let dir = temp_dir("tri-move");
    let (file, p, q) = lone_pair_file(&dir);
    let input = read(&file);
    for d in 0..6u32 {
        for steps in 1..=2u32 {
            for (a, b, want) in [(p, q, (5, 7)), (q, p, (7, 5))] {
                let out = dir.join(format!("m{d}-{steps}-{a}.obj"));
                let args = [
                    "tri-move",
                    s(&file),
                    "--pair",
                    &format!("{a},{b}"),
                    "--direction",
                    &d.to_string(),
                    "--steps",
                    &steps.to_string(),
                ];
                let v = report(&args, &out);
                let moved = read(&out);
                moved.map.check().unwrap();
                let pair = numbers(&v["pair"]);
                let (x, y) = (Vert::new(pair[0]), Vert::new(pair[1]));
                assert_eq!((moved.map.valence(x), moved.map.valence(y)), want, "{v}");
                assert!(moved.map.dart_between(x, y).is_some());
                let ops = ["flips", "collapses", "splits"].map(|k| v[k].as_u64().unwrap());
                assert_eq!(ops.iter().sum::<u64>(), u64::from(steps));
                assert!(positions_lost(&input, &moved) <= 2 * steps as usize, "{v}");
                if ops[0] == u64::from(steps) {
                    assert_eq!(moved.positions, input.positions, "flips move nothing");
                }
                let undo = &v["undo"];
                assert_eq!(undo["direction"], (d + 3) % 6);
                let back = dir.join(format!("u{d}-{steps}-{a}.obj"));
                run_move_undo(&out, undo, &back);
                assert!(is_isomorphic(&read(&back).map, &input.map), "{d} x {steps}");
            }
        }
    }
}

/// Bad input: exit 2, a message, and no OUT.
#[test]
fn tri_commands_refuse_bad_input() {
    let dir = temp_dir("tri-bad");
    let (file, p, q) = lone_pair_file(&dir);
    let quad = dir.join("quad.obj");
    io::write_mesh(&quad, &gen::torus_grid(4, 4)).unwrap();
    let pq = format!("{p},{q}");
    let far = format!("{p},{}", q + 40);
    let (f, q4) = (s(&file), s(&quad));
    let cases: Vec<Vec<String>> = [
        format!("tri-move {q4} --pair 0,1 --direction 0"),
        format!("tri-move {f} --pair {far} --direction 0"),
        format!("tri-move {f} --pair 1,2 --direction 0"),
        format!("tri-move {f} --pair 0,99999 --direction 0"),
        format!("tri-move {f} --pair {pq} --direction 6"),
        format!("tri-move {f} --pair {pq} --direction 1 --steps 0"),
        // Back toward the other pair (the file moved it 3 steps in direction 5): the fourth
        // step needs a vertex of that pair regular and refuses.
        format!("tri-move {f} --pair {pq} --direction 2 --steps 5"),
        format!("tri-generate {f} --at {p} --config collapse-flip"),
        format!("tri-type {f} --split 0"),
        format!("tri-type {f} --aggregate 0,1"),
        format!("tri-cancel {f} --quadruple 0,1,2"),
        format!("tri-cancel {f} --quadruple 0,1,2,3"),
        format!("tri-cancel {f} --triple 0,1"),
        format!("tri-cancel {f} --triple {p},{q},0"),
        format!("tri-cancel {f}"),
        format!("tri-generate {f} --at {q} --config collapse"),
        format!("tri-generate {f} --at 0 --config collapse"),
        // Pairs apart: not from a v5, not the chain, not without a direction, not too far.
        format!("tri-generate {f} --at {p} --apart 2 --direction 0"),
        format!("tri-generate {f} --at 0 --config collapse-flip --apart 2 --direction 0"),
        format!("tri-generate {f} --at 0 --apart 2"),
        format!("tri-generate {f} --at 0 --apart 4000000000 --direction 0"),
    ]
    .iter()
    .map(|c| c.split_whitespace().map(String::from).collect())
    .collect();
    for (i, case) in cases.iter().enumerate() {
        let out = dir.join(format!("bad{i}.obj"));
        let mut args: Vec<&str> = case.iter().map(String::as_str).collect();
        args.extend(["-o", s(&out)]);
        let o = zipmesh(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).is_empty());
        assert!(!out.exists(), "{args:?} wrote OUT");
    }
}

/// `tri-generate` in the two configurations inside two triangles, every neighbour: the
/// four are two v5 and two v7 in OUT, and the printed `tri-cancel` undoes it; the chain
/// configuration reports no undo.
#[test]
fn tri_generate_and_cancel() {
    let dir = temp_dir("tri-generate");
    let file = write(&dir, "sphere.obj", geodesic_sphere(3));
    let input = read(&file);
    let at = 100u32;
    let neighbours: Vec<u32> = input
        .map
        .vertex_darts(Vert::new(at))
        .map(|d| input.map.dest(d).index() as u32)
        .collect();
    for config in ["flip", "split", "collapse-flip"] {
        let mut applied = 0;
        for &w in &neighbours {
            let out = dir.join(format!("g-{config}-{w}.obj"));
            let (at, w) = (at.to_string(), w.to_string());
            let args = [
                "tri-generate",
                s(&file),
                "--at",
                &at,
                "--toward",
                &w,
                "--config",
                config,
            ];
            let o = zipmesh_to(&[&args[..], &["--json", "--no-relax"]].concat(), &out);
            // Toward the sphere's v5 the edit needs an irregular vertex regular: refused.
            if o.status.code() == Some(2) {
                assert!(stderr(&o).contains("not regular"), "{}", stderr(&o));
                assert!(!out.exists());
                continue;
            }
            applied += 1;
            let v = json(&o);
            let g = read(&out);
            let mut vals: Vec<usize> = numbers(&v["four"])
                .iter()
                .map(|&x| g.map.valence(Vert::new(x)))
                .collect();
            vals.sort();
            assert_eq!(vals, [5, 5, 7, 7]);
            for x in numbers(&v["v5"]) {
                assert_eq!(g.map.valence(Vert::new(x)), 5);
            }
            assert!(positions_lost(&input, &g) <= 2);
            if config == "collapse-flip" {
                assert_eq!(v["in_two_triangles"], false);
                assert!(v["undo"].is_null());
                continue;
            }
            let four = join(&numbers(&v["undo"]["quadruple"]));
            let back = dir.join(format!("c-{config}-{w}.obj"));
            let c = report(&["tri-cancel", s(&out), "--quadruple", &four], &back);
            let cancelled = read(&back);
            assert!(is_isomorphic(&cancelled.map, &input.map), "{config} {w}");
            // And the cancel's own undo generates the quadruple again.
            let u = &c["undo"];
            let again = dir.join(format!("a-{config}-{w}.obj"));
            generate_from_undo(&back, u, &again);
            assert!(
                is_isomorphic(&read(&again).map, &g.map),
                "{config} {w}: {u}"
            );
        }
        assert!(applied >= 3, "{config}: {applied} of {}", neighbours.len());
    }
}

/// `tri-type`: a v9 apex splits into three v7, a ring v4 into two v5; the printed
/// aggregation of each gives back a mesh isomorphic to the input.
#[test]
fn tri_type_split_and_aggregate() {
    let dir = temp_dir("tri-type");
    let file = write(&dir, "bipyramid.obj", subdivided_bipyramid(9, 2));
    let input = read(&file);
    let v9 = (0..input.map.vertex_slots() as u32)
        .find(|&v| input.map.valence(Vert::new(v)) == 9)
        .unwrap();
    let out = dir.join("v9.obj");
    let v = report(&["tri-type", s(&file), "--split", &v9.to_string()], &out);
    let split = read(&out);
    let sevens: Vec<usize> = numbers(&v["vertices"])
        .iter()
        .map(|&x| split.map.valence(Vert::new(x)))
        .collect();
    assert_eq!(sevens, [7, 7, 7]);
    assert!(positions_lost(&input, &split) <= 3);
    // The printed undo gathers the three v7 back into the v9.
    let sevens = numbers(&v["undo"]["aggregate"]);
    assert_eq!(sevens, numbers(&v["vertices"]));
    let back = dir.join("v9-back.obj");
    let a = report(&["tri-type", s(&out), "--aggregate", &join(&sevens)], &back);
    let agg = read(&back);
    assert_eq!(agg.map.valence(Vert::new(numbers(&a["vertices"])[0])), 9);
    assert!(is_isomorphic(&agg.map, &input.map));

    let v4 = (0..input.map.vertex_slots() as u32)
        .find(|&v| input.map.valence(Vert::new(v)) == 4)
        .unwrap();
    let out = dir.join("v4.obj");
    let v = report(&["tri-type", s(&file), "--split", &v4.to_string()], &out);
    let fives = numbers(&v["undo"]["aggregate"]);
    let split = read(&out);
    assert!(fives.iter().all(|&x| split.map.valence(Vert::new(x)) == 5));
    assert_eq!(fives.len(), 2);
    let back = dir.join("v4-back.obj");
    let a = report(&["tri-type", s(&out), "--aggregate", &join(&fives)], &back);
    let agg = read(&back);
    assert_eq!(agg.map.valence(Vert::new(numbers(&a["vertices"])[0])), 4);
    assert!(is_isomorphic(&agg.map, &input.map));
}

/// `tri-generate --apart K --direction D` on a regular lattice: the four in polygon order
/// are v5, v7, v5, v7 in OUT, opposite sides equal, not in two triangles; the printed walk
/// back brings the moving pair next to the staying one.
#[test]
fn tri_generate_pairs_apart() {
    let dir = temp_dir("tri-apart");
    let (file, _, _) = lone_pair_file(&dir);
    let input = read(&file);
    // A regular vertex far from the file's pair: the lattice's middle row, a third across.
    let at = (0..input.map.vertex_slots() as u32)
        .filter(|&v| input.map.valence(Vert::new(v)) == 6)
        .nth(input.map.vertex_slots() / 2)
        .unwrap();
    let mut applied = 0;
    for (config, d) in [("flip", 0), ("flip", 2), ("split", 4), ("split", 5)] {
        let out = dir.join(format!("apart-{config}-{d}.obj"));
        let args = [
            "tri-generate",
            s(&file),
            "--at",
            &at.to_string(),
            "--config",
            config,
        ];
        let more = ["--apart", "3", "--direction", &d.to_string(), "--json"];
        let o = zipmesh_to(&[&args[..], &more[..]].concat(), &out);
        if o.status.code() == Some(2) {
            assert!(!out.exists());
            continue;
        }
        let v = json(&o);
        let m = read(&out);
        let four = numbers(&v["four"]);
        let vals: Vec<usize> = four.iter().map(|&x| m.map.valence(Vert::new(x))).collect();
        assert_eq!(vals, [5, 7, 5, 7], "{config} {d}");
        assert_eq!(v["in_two_triangles"], false);
        let sides = &v["sides"];
        assert_eq!(sides[0], sides[2]);
        assert_eq!(sides[1], sides[3], "{config} {d}: {sides}");
        let w = &v["walk_back"];
        assert_eq!(numbers(&w["pair"]), four[2..]);
        let back = dir.join(format!("back-{config}-{d}.obj"));
        let pair = join(&numbers(&w["pair"]));
        let (dd, st) = (w["direction"].to_string(), w["steps"].to_string());
        let b = report(
            &[
                "tri-move",
                s(&out),
                "--pair",
                &pair,
                "--direction",
                &dd,
                "--steps",
                &st,
            ],
            &back,
        );
        let walked = read(&back);
        let moved = numbers(&b["pair"]);
        // The moving pair is back next to a v5 and a v7 of the staying pair.
        let near: Vec<usize> = walked
            .map
            .vertex_darts(Vert::new(moved[0]))
            .map(|h| walked.map.valence(walked.map.dest(h)))
            .filter(|&k| k == 7)
            .collect();
        assert!(near.len() >= 2, "{config} {d}");
        applied += 1;
    }
    assert!(applied >= 2, "{applied}");
}

/// Sec. 7.3 then 7.2 from the command line: `tri-generate` at a v5 (the geodesic sphere)
/// or a v7 (a lattice cone) makes a triple whose printed `tri-cancel --triple` gives back
/// a mesh isomorphic to the input, and that cancellation's own printed undo generates the
/// triple again (up to isomorphism).
#[test]
fn tri_generate_triples_and_cancel_them() {
    let dir = temp_dir("tri-triple");
    let cases = [
        (
            write(&dir, "sphere.obj", geodesic_sphere(2)),
            0u32,
            vec!["flip", "collapse", "split"],
            5,
        ),
        (
            write(&dir, "cone.obj", cone_disk(7, 5)),
            0u32,
            vec!["flip", "split"],
            7,
        ),
    ];
    for (file, at, configs, k) in cases {
        let input = read(&file);
        assert_eq!(input.map.valence(Vert::new(at)), k);
        for config in configs {
            let out = dir.join(format!("t{k}-{config}.obj"));
            let v = report(
                &[
                    "tri-generate",
                    s(&file),
                    "--at",
                    &at.to_string(),
                    "--config",
                    config,
                ],
                &out,
            );
            let g = read(&out);
            let three = numbers(&v["three"]);
            let vals: Vec<usize> = three.iter().map(|&x| g.map.valence(Vert::new(x))).collect();
            let want = if k == 5 { [5, 5, 7] } else { [7, 5, 7] };
            assert_eq!(vals, want, "{config}: {v}");
            assert!(positions_lost(&input, &g) <= 2);
            let back = dir.join(format!("c{k}-{config}.obj"));
            let c = report(
                &[
                    "tri-cancel",
                    s(&out),
                    "--triple",
                    &join(&numbers(&v["undo"]["triple"])),
                ],
                &back,
            );
            let cancelled = read(&back);
            assert!(is_isomorphic(&cancelled.map, &input.map), "{k} {config}");
            let left = c["remaining"].as_u64().unwrap() as u32;
            assert_eq!(cancelled.map.valence(Vert::new(left)), k);
            let u = &c["undo"];
            let again = dir.join(format!("a{k}-{config}.obj"));
            generate_from_undo(&back, u, &again);
            assert!(
                is_isomorphic(&read(&again).map, &g.map),
                "{k} {config}: {u}"
            );
        }
    }
}

/// `tri-cancel --triple` on a triple that is not adjacent (Sec. 7.2): the pair walks back
/// and the triple cancels into one v5; the report counts the pair moves and has no undo.
#[test]
fn tri_cancel_far_triple() {
    use zipmesh::tri_edit::{generate_pair, Moved, Via};
    let dir = temp_dir("tri-far");
    let mut map = geodesic_sphere(3);
    let d = map.vertex_dart(Vert::new(0));
    let g = generate_pair(&mut map, d, Via::Flip, Moved::First).unwrap();
    let (mut p, mut q) = g.pair().unwrap();
    for _ in 0..2 {
        let m = move_pair(&mut map, p, q, Direction::CollapseLeft).unwrap();
        (p, q) = (m.p(), m.q());
    }
    assert!(map.dart_between(q, g.moved()).is_none());
    let c = map.compact();
    let at = |v: Vert| c.vertices[v.index()].unwrap().index() as u32;
    let three = [at(g.moved()), at(p), at(q)];
    let file = write(&dir, "far.obj", map);
    let input = read(&file);
    let out = dir.join("cancelled.obj");
    let v = report(&["tri-cancel", s(&file), "--triple", &join(&three)], &out);
    let done = read(&out);
    done.map.check().unwrap();
    let left = v["remaining"].as_u64().unwrap() as u32;
    assert_eq!(done.map.valence(Vert::new(left)), 5);
    let walked = v["pair_moves"].as_u64().unwrap();
    assert!(walked >= 1);
    assert!(v["undo"].is_null());
    let fives = |m: &Mesh| m.map.vertices().filter(|&x| m.map.valence(x) == 5).count();
    assert_eq!((fives(&input), fives(&done)), (13, 12));
    assert!(positions_lost(&input, &done) <= 2 * (walked as usize + 1));
}

/// The sorted valences of the irregular interior vertices.
fn irregular_multiset(m: &Mesh) -> Vec<usize> {
    let mut v: Vec<usize> = common::tri::irregular(&m.map)
        .into_iter()
        .map(|(_, k)| k)
        .collect();
    v.sort();
    v
}

/// `tri-move` of pairs that are not adjacent (Sec. 7.1): a 5-7 pair at distance 2 (both
/// orders) and a 5-5 pair of a geodesic sphere, every direction: the report's pair has the
/// given valences in OUT, the 5-7 pair keeps its distance, the irregular multiset is the
/// input's, the counts add up to the graph operations the positions account for, and the
/// printed undo (when one is found) gives back the input up to isomorphism.
#[test]
fn tri_move_composite_pairs() {
    use common::tri::{distance, far_five_seven};
    let dir = temp_dir("tri-move-far");
    let (map, p, q) = far_five_seven();
    let five_seven = {
        let mut map = map;
        let c = map.compact();
        let at = |v: Vert| c.vertices[v.index()].unwrap().index() as u32;
        let (p, q) = (at(p), at(q));
        (write(&dir, "far57.obj", map), p, q)
    };
    let sphere = geodesic_sphere(2);
    let fives: Vec<u32> = (0..sphere.vertex_slots() as u32)
        .filter(|&v| sphere.valence(Vert::new(v)) == 5)
        .collect();
    let near = *fives[1..]
        .iter()
        .min_by_key(|&&w| distance(&sphere, Vert::new(fives[0]), Vert::new(w)))
        .unwrap();
    let five_five = (write(&dir, "s55.obj", sphere), fives[0], near);
    let (mut undone, mut tried) = (0, 0);
    for (file, a, b) in [
        five_seven.clone(),
        (five_seven.0, five_seven.2, five_seven.1),
        five_five,
    ] {
        let input = read(&file);
        let want = [a, b].map(|x| input.map.valence(Vert::new(x)));
        let d0 = distance(&input.map, Vert::new(a), Vert::new(b));
        for d in 0..6u32 {
            tried += 1;
            let out = dir.join(format!("f{a}-{d}.obj"));
            let (pair, dd) = (format!("{a},{b}"), d.to_string());
            let v = report(
                &["tri-move", s(&file), "--pair", &pair, "--direction", &dd],
                &out,
            );
            let moved = read(&out);
            moved.map.check().unwrap();
            let np = numbers(&v["pair"]);
            let (x, y) = (Vert::new(np[0]), Vert::new(np[1]));
            assert_eq!([moved.map.valence(x), moved.map.valence(y)], want, "{v}");
            if want[0] != want[1] {
                assert_eq!(distance(&moved.map, x, y), d0, "a 5-7 move translates");
            }
            assert_eq!(irregular_multiset(&moved), irregular_multiset(&input));
            let ops: u64 = ["flips", "collapses", "splits"]
                .map(|k| v[k].as_u64().unwrap())
                .iter()
                .sum();
            assert!(ops >= 2, "a generation and a removal at least: {v}");
            assert!(positions_lost(&input, &moved) <= 2 * ops as usize, "{v}");
            let undo = &v["undo"];
            if undo.is_null() {
                continue;
            }
            let back = dir.join(format!("fu{a}-{d}.obj"));
            run_move_undo(&out, undo, &back);
            assert!(is_isomorphic(&read(&back).map, &input.map), "{a} {d}");
            undone += 1;
        }
    }
    eprintln!("composite tri-move: {undone} of {tried} found an undo");
    assert_eq!(
        undone, tried,
        "every composite move has an undo among the six directions"
    );
}

/// A bumpy equilateral lattice with a spoke of its centre flipped: a file and the 5-7 pair
/// (the centre, a v5, and a v7 next to it).
fn bumpy_pair_file(dir: &Path) -> (PathBuf, u32, u32) {
    let n = 12;
    let mut mesh = common::tri::lattice(n, 0.8);
    let c = Vert::new(((n / 2) * n + n / 2) as u32);
    let d = mesh.map.vertex_darts(c).next().unwrap();
    zipmesh::ops::tri::flip_edge(&mut mesh.map, d).unwrap();
    let map = &mesh.map;
    let mut ring = map.vertex_darts(c).map(|d| map.dest(d));
    let q = ring.find(|&w| map.valence(w) == 7).unwrap();
    let file = dir.join("bumpy.obj");
    io::write_mesh(&file, &mesh).unwrap();
    (file, c.index() as u32, q.index() as u32)
}

/// `--relax surface|local|global`: OUT has the connectivity and report of the same edit with
/// `--no-relax`; exactly the reported number of vertices move, each onto the input surface,
/// fewer with fewer `--rings`; global relaxation does not raise Eq. 5; the surface
/// relaxation (the default) adds no thin or flipped triangle. `--rings` or `--relax` with
/// `--no-relax` is refused.
#[test]
fn tri_move_relax() {
    let dir = temp_dir("tri-relax");
    let (file, p, q) = bumpy_pair_file(&dir);
    let input = read(&file);
    let pair = format!("{p},{q}");
    let plain_out = dir.join("plain.obj");
    // The first direction that moves the pair away from the flip's other pair.
    let dirs = ["0", "1", "2", "3", "4", "5"];
    let tries = dirs.map(|d| ["tri-move", s(&file), "--pair", &pair, "--direction", d]);
    let args = tries
        .iter()
        .find(|a| zipmesh_to(&a[..], &plain_out).status.success())
        .expect("some direction applies")
        .to_vec();
    let by_default = report_as_given(&args, &plain_out);
    assert_eq!(by_default["relax"]["mode"], "surface");
    let plain = report(&args, &plain_out);
    assert!(plain["relax"].is_null());
    let plain_mesh = read(&plain_out);
    let bits = |p: DVec3| p.to_array().map(f64::to_bits);
    for mode in ["surface", "local", "global"] {
        let mut moved_by_rings = Vec::new();
        for rings in ["0", "3"] {
            let out = dir.join(format!("{mode}-{rings}.obj"));
            let mut all = args.to_vec();
            all.extend(["--relax", mode, "--rings", rings]);
            let v = report(&all, &out);
            let relaxed = read(&out);
            assert_eq!(
                relaxed.map, plain_mesh.map,
                "{mode}: the connectivity changed"
            );
            assert_eq!(v["pair"], plain["pair"]);
            let r = &v["relax"];
            assert_eq!(
                (r["mode"].as_str(), r["rings"].to_string()),
                (Some(mode), rings.into())
            );
            let changed: Vec<usize> = (0..relaxed.positions.len())
                .filter(|&i| bits(relaxed.positions[i]) != bits(plain_mesh.positions[i]))
                .collect();
            assert_eq!(changed.len() as u64, r["moved"].as_u64().unwrap(), "{v}");
            assert!(
                !changed.is_empty(),
                "{mode} --rings {rings} moved nothing: {v}"
            );
            for &i in &changed {
                let d = common::tri::to_surface(&input, relaxed.positions[i]);
                assert!(d < 1e-9, "{mode}: vertex {i} is {d} off the input surface");
            }
            let (e0, e1) = (r["energy_before"].as_f64(), r["energy_after"].as_f64());
            if mode == "global" {
                assert!(e1.unwrap() <= e0.unwrap(), "{v}");
            }
            if mode == "surface" {
                let q = &v["quality"];
                for k in ["thin_triangles", "flipped_triangles"] {
                    assert!(q["output"][k].as_u64() <= q["input"][k].as_u64(), "{v}");
                }
            }
            moved_by_rings.push(changed.len());
        }
        assert!(
            moved_by_rings[0] < moved_by_rings[1],
            "{mode}: {moved_by_rings:?}"
        );
    }
    // tri-generate and tri-cancel relax through the same code: a quadruple at a regular
    // vertex far from the pair, relaxed, then cancelled and relaxed again.
    let (gen_plain, gen_relaxed) = (dir.join("gen-plain.obj"), dir.join("gen-relaxed.obj"));
    let g = ["tri-generate", s(&file), "--at", "40"];
    let plain = report(&g, &gen_plain);
    let v = report(&[&g[..], &["--relax", "local"]].concat(), &gen_relaxed);
    assert_eq!(v["four"], plain["four"]);
    assert_eq!(read(&gen_relaxed).map, read(&gen_plain).map);
    assert!(v["relax"]["moved"].as_u64().unwrap() > 0, "{v}");
    let four = join(&numbers(&v["four"]));
    let c = [
        "tri-cancel",
        s(&gen_relaxed),
        "--quadruple",
        &four,
        "--relax",
        "global",
    ];
    let v = report(&c, &dir.join("cancelled.obj"));
    let energy = |k: &str| v["relax"][k].as_f64().unwrap();
    assert!(energy("energy_after") <= energy("energy_before"), "{v}");
    let out = dir.join("rings-alone.obj");
    let mut all = args.to_vec();
    all.extend(["--rings", "1", "--no-relax"]);
    let o = zipmesh_to(&all, &out);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!out.exists());
    let o = zipmesh_to(
        &[&args[..], &["--no-relax", "--relax", "local"]].concat(),
        &out,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!out.exists());
    let o = zipmesh_to(
        &[
            "tri-type",
            s(&file),
            "--split",
            &p.to_string(),
            "--relax",
            "sideways",
        ],
        &out,
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists());
}
