//! The runs of docs/results.md: `cargo run --release --example optimize_results`.
//! Each row: mesh, counts before and after, batches, Q-zips, seconds, face count change.
//! `ZIPMESH_WEIGHTS=name=w,...` changes weights; `ZIPMESH_TRACE=1` prints each batch's stats;
//! `ZIPMESH_CHAINS=0` turns the chain stage off, `ZIPMESH_FOLD_GUARD=0` the fold guard.
use std::time::Instant;
use zipmesh::optimize::{folded_quads, optimize, Constraints, OptimizeOptions, SingularityCounts};
use zipmesh::{gen, io, Mesh};

/// The options: 40 batches (or `ZIPMESH_BATCHES`), seed 0 (or `ZIPMESH_SEED`), with the weights of `ZIPMESH_WEIGHTS` (`name=w,name=w`) if set.
fn options() -> OptimizeOptions {
    let batches = std::env::var("ZIPMESH_BATCHES")
        .ok()
        .and_then(|b| b.parse().ok())
        .unwrap_or(40);
    let seed = std::env::var("ZIPMESH_SEED")
        .ok()
        .and_then(|b| b.parse().ok())
        .unwrap_or(0);
    let on = |name: &str| std::env::var(name).map_or(true, |c| c != "0");
    let mut o = OptimizeOptions::default()
        .batches(batches)
        .seed(seed)
        .chains(on("ZIPMESH_CHAINS"))
        .fold_guard(on("ZIPMESH_FOLD_GUARD"))
        .smoothing(on("ZIPMESH_SMOOTH"));
    if let Ok(w) = std::env::var("ZIPMESH_WEIGHTS") {
        for pair in w.split(',').filter(|p| !p.is_empty()) {
            if let Some((n, x)) = pair.split_once('=') {
                o = o.weight(n, x.parse().unwrap_or(0.0));
            }
        }
    }
    o
}

fn row(name: &str, mesh: Mesh) {
    row_with(name, mesh, |_| Constraints::default());
}

fn row_with(name: &str, mut mesh: Mesh, constraints: impl Fn(&Mesh) -> Constraints) {
    let before = SingularityCounts::of(&mesh);
    let folds_before = folded_quads(&mesh);
    let c = constraints(&mesh);
    let check = c.clone();
    let t = Instant::now();
    let trace = std::env::var_os("ZIPMESH_TRACE").is_some();
    let out = optimize(&mut mesh, c, options(), |b| {
        if trace {
            let c = b.counts;
            eprintln!(
                "{name} batch {}: {} Q-zips, v3/v5/v6+ {}/{}/{}, faces {}, {:?}, {:?}",
                b.batch, b.qzips, c.v3, c.v5, c.v6plus, c.faces, b.stats, b.chains
            );
        }
    });
    assert!(check.holds(&mesh), "{name}: a constraint broke");
    let secs = t.elapsed().as_secs_f64();
    let Ok(out) = out else {
        println!("| {name} | refused | | | | | | |");
        return;
    };
    let a = out.final_counts;
    let q: usize = out.batches.iter().map(|b| b.qzips + b.chains.qzips).sum();
    let nb = out.batches.len().max(1);
    println!(
        "| {name} | {}/{}/{}/{} ({}) bd {} | {}/{}/{}/{} ({}) bd {} | {} | {q} | {secs:.1} ({:.2}/batch) | {} -> {} ({:+.1} %) | {folds_before} -> {} |",
        before.v2, before.v3, before.v5, before.v6plus, before.singularities(), before.boundary_defects,
        a.v2, a.v3, a.v5, a.v6plus, a.singularities(), a.boundary_defects, out.batches.len(), secs / nb as f64,
        before.faces, a.faces,
        100.0 * (a.faces as f64 - before.faces as f64) / before.faces.max(1) as f64,
        folded_quads(&mesh)
    );
}

/// A row: its short name, its label, how to make its mesh.
type Input = (String, String, Box<dyn Fn() -> Option<Mesh>>);

/// The rows by name.
fn inputs() -> Vec<Input> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");
    let file = move |f: &str| io::read_mesh(format!("{dir}/{f}")).ok().map(|m| m.0);
    let mut rows: Vec<Input> = Vec::new();
    for g in [2, 3, 4] {
        rows.push((
            format!("genus{g}"),
            format!("CC of random triangle mesh, genus {g}, ~300 tris"),
            Box::new(move || Some(gen::catmull_clark(&gen::random_triangle(300, g, 0, 1)))),
        ));
    }
    for (short, f) in [
        ("spot", "quad/spot_quadrangulated.obj"),
        ("blub", "quad/blub_quadrangulated.obj"),
        ("cubespikes", "quad/cubespikes.obj"),
        ("torus", "quad/osd_catmark_torus.obj"),
        ("tet", "quad/osd_catmark_toroidal_tet.obj"),
        ("helmet", "quad/osd_catmark_helmet.obj"),
    ] {
        rows.push((short.into(), f.into(), Box::new(move || file(f))));
    }
    for (short, f) in [
        ("tritorus", "tri/torus.obj"),
        ("disk", "tri/circle_disk.obj"),
        ("spottri", "tri/spot_triangulated.obj"),
    ] {
        rows.push((
            short.into(),
            format!("CC of {f}"),
            Box::new(move || file(f).map(|m| gen::catmull_clark(&m))),
        ));
    }
    rows
}

/// No argument: every row but the 17,568-quad Spot; a row's short name (or several, or
/// `constraints`, or `all`): those rows.
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    println!("| mesh | before v2/v3/v5/v6+ (total) boundary defects | after | batches | Q-zips | seconds (per batch) | faces | folded quads |");
    println!("|---|---|---|---|---|---|---|---|");
    for (short, label, make) in inputs() {
        let wanted = if args.is_empty() {
            short != "spottri"
        } else {
            args.iter().any(|a| *a == short || a == "all")
        };
        if wanted {
            match make() {
                Some(m) => row(&label, m),
                None => println!("| {label} | unreadable | | | | | | |"),
            }
        }
    }
    if args.iter().any(|a| a == "constraints" || a == "all") || args.is_empty() {
        constraint_rows();
    }
}

/// Protected faces and sharp features: the constraints hold, singularities elsewhere go.
fn constraint_rows() {
    let genus2 = gen::catmull_clark(&gen::random_triangle(300, 2, 0, 1));
    row_with("CC genus 2, faces 0..200 protected", genus2, |m| {
        let mut c = Constraints::default();
        for f in m.map.faces().take(200) {
            c.protect_face(m, f).unwrap();
        }
        c
    });
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");
    let spikes = io::read_mesh(format!("{dir}/quad/cubespikes.obj"))
        .unwrap()
        .0;
    row_with("quad/cubespikes.obj, --sharp-angle 40", spikes, |m| {
        let mut c = Constraints::default();
        let n = c.add_sharp_edges(m, 40.0);
        eprintln!("cubespikes: {n} sharp edges");
        c
    });
}
