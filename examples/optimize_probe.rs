//! Why a run stops: `cargo run --release --example optimize_probe -- NAME [BATCHES]`.
//!
//! Runs the optimizer (default options, `BATCHES` at most, default 40) on a mesh (`genus2`,
//! `genus3`, `genus4` for the generated Catmull-Clark meshes, or a path), then tries every
//! candidate the batches would try from *every* remaining singularity (its three closest
//! v3-like and v5-like targets, four movements each) and tells, with numbers, what stands in
//! the way: pairs with no path, movements refused, movements that cancel and which score
//! term makes them lose (whole-mesh score, the scar relaxed as the batches do).
use std::collections::VecDeque;
use zipmesh::optimize::{
    optimize, singularities, Constraints, Context, Count, Electric, FaceBudget, Isotropy,
    OptimizeOptions, ScoreTerm, Separatrix, SingularityCounts, Sizing,
};
use zipmesh::qzip::{Qzip, SketchOptions, Tag};
use zipmesh::{gen, io, Mesh, Vert};

fn load(name: &str) -> Mesh {
    match name {
        "genus2" | "genus3" | "genus4" => {
            let g = name[5..].parse().unwrap();
            gen::catmull_clark(&gen::random_triangle(300, g, 0, 1))
        }
        path => io::read_mesh(path).expect("a readable mesh").0,
    }
}

fn mean_area(mesh: &Mesh) -> f64 {
    let (mut s, mut n) = (0.0, 0);
    for f in mesh.map.faces() {
        let p: Vec<_> = mesh
            .map
            .face_darts(f)
            .map(|d| mesh.positions[mesh.map.origin(d).index()])
            .collect();
        if p.len() == 4 {
            s += 0.5 * (p[2] - p[0]).cross(p[3] - p[1]).length();
            n += 1;
        }
    }
    s / n.max(1) as f64
}

/// The weighted terms of the default options, each evaluated on the whole mesh.
struct Terms {
    terms: Vec<(f64, Box<dyn ScoreTerm>)>,
    area: f64,
    faces: usize,
}

impl Terms {
    fn parts(&mut self, mesh: &Mesh) -> Vec<f64> {
        let s = singularities(mesh);
        let ctx = Context {
            mesh,
            singularities: &s,
            features: &[],
            target_area: self.area,
            target_faces: self.faces,
            faces: None,
            walls: true,
        };
        self.terms
            .iter_mut()
            .map(|(w, t)| *w * t.score(&ctx))
            .collect()
    }
}

/// The three closest v3-like and v5-like singularities of `s`, with their distances.
fn targets(mesh: &Mesh, s: Vert, defect: &[i64]) -> Vec<(Vert, u32)> {
    let map = &mesh.map;
    let mut dist = vec![u32::MAX; map.vertex_slots()];
    let (mut minus, mut plus) = (Vec::new(), Vec::new());
    let mut q = VecDeque::from([s]);
    dist[s.index()] = 0;
    while let Some(v) = q.pop_front() {
        let d = dist[v.index()];
        if d > 0 {
            match defect[v.index()] {
                x if x < 0 && minus.len() < 3 => minus.push((v, d)),
                x if x > 0 && plus.len() < 3 => plus.push((v, d)),
                _ => {}
            }
        }
        if (minus.len() >= 3 && plus.len() >= 3) || d >= 64 {
            continue;
        }
        for x in map.vertex_darts(v) {
            let u = map.dest(x);
            if dist[u.index()] == u32::MAX {
                dist[u.index()] = d + 1;
                q.push_back(u);
            }
        }
    }
    minus.extend(plus);
    minus
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map(String::as_str).unwrap_or("genus3");
    let batches = args.get(1).and_then(|b| b.parse().ok()).unwrap_or(40);
    let mut mesh = load(name);
    let input_faces = mesh.map.num_faces();
    let opts = OptimizeOptions::default().batches(batches);
    let weights: Vec<f64> = opts.terms().iter().map(|(w, _)| *w).collect();
    let out = optimize(&mut mesh, Constraints::default(), opts, |_| {}).unwrap();
    let c = out.final_counts;
    println!(
        "{name}: {} batches, v3/v5/v6+ {}/{}/{}, faces {}",
        out.batches.len(),
        c.v3,
        c.v5,
        c.v6plus,
        c.faces
    );
    let mut terms = Terms {
        terms: vec![
            (weights[0], Box::new(Count)),
            (weights[1], Box::new(Electric::default())),
            (weights[2], Box::new(Isotropy)),
            (weights[3], Box::new(Sizing)),
            (weights[4], Box::new(Separatrix::default())),
            (weights[5], Box::new(FaceBudget::default())),
        ],
        area: mean_area(&mesh),
        faces: input_faces,
    };
    let names: Vec<String> = terms
        .terms
        .iter()
        .map(|(_, t)| t.name().to_string())
        .collect();
    let sing = singularities(&mesh);
    let mut defect = vec![0i64; mesh.map.vertex_slots()];
    for s in &sing {
        defect[s.vertex.index()] = s.defect;
    }
    let mut qzip = Qzip::with_options(SketchOptions::default()).allow_cancellation(true);
    let base = terms.parts(&mesh);
    let (mut no_path, mut refused, mut ok, mut cancel, mut cancel_wins) = (0, 0, 0, 0, 0);
    let mut blocker = [0usize; 6];
    let mut lowering = 0;
    let mut best: Option<(f64, Vec<f64>)> = None;
    let mut opposite_dist = Vec::new();
    for s in &sing {
        let ts = targets(&mesh, s.vertex, &defect);
        if let Some(d) = ts
            .iter()
            .filter(|(t, _)| defect[t.index()].signum() != s.defect.signum())
            .map(|x| x.1)
            .min()
        {
            opposite_dist.push(d);
        }
        for (t, _) in ts {
            let Ok(path) = qzip.sketch(&mesh.map, s.vertex, t) else {
                no_path += 1;
                continue;
            };
            for tag in Tag::CCW {
                let Ok(z) = qzip.zip_along(&mut mesh, &path, tag) else {
                    refused += 1;
                    continue;
                };
                ok += 1;
                let p = terms.parts(&mesh);
                let d: Vec<f64> = p.iter().zip(&base).map(|(a, b)| a - b).collect();
                let total: f64 = d.iter().sum();
                lowering += usize::from(total < 0.0);
                if best.as_ref().is_none_or(|(t, _)| total < *t) {
                    best = Some((total, d));
                }
                let after = SingularityCounts::of(&mesh).singularities();
                if after < c.singularities() {
                    cancel += 1;
                    let p = terms.parts(&mesh);
                    let d: Vec<f64> = p.iter().zip(&base).map(|(a, b)| a - b).collect();
                    if d.iter().sum::<f64>() < 0.0 {
                        cancel_wins += 1;
                    } else {
                        let worst = (1..6).max_by(|&i, &j| d[i].total_cmp(&d[j])).unwrap_or(0);
                        blocker[worst] += 1;
                    }
                }
                z.undo(&mut mesh).unwrap();
            }
        }
    }
    opposite_dist.sort_unstable();
    println!(
        "{} singularities; closest opposite-kind target (edges): min {:?} median {:?} max {:?}",
        sing.len(),
        opposite_dist.first(),
        opposite_dist.get(opposite_dist.len() / 2),
        opposite_dist.last()
    );
    println!(
        "candidates: {no_path} pairs without a path, {refused} movements refused, {ok} applied, \
         {cancel} cancel, {cancel_wins} of them lower the score (no relaxation)"
    );
    println!("{lowering} applied movements lower the whole-mesh score (before relaxation)");
    if let Some((t, d)) = best {
        let parts: Vec<String> = names
            .iter()
            .zip(&d)
            .map(|(n, x)| format!("{n} {x:+.4}"))
            .collect();
        println!("best movement: {t:+.4} = {}", parts.join(", "));
    }
    for (n, b) in names.iter().zip(blocker) {
        if b > 0 {
            println!("  cancelling movements lost mostly to {n}: {b}");
        }
    }
}
