//! The attribute layer (`zipmesh::mesh`): per-vertex data kept in step with every edit.
//!
//! For random operator sequences on generated meshes, with two layers travelling together
//! (positions and a mark per vertex): an edit writes at most the one vertex its rule places,
//! leaves every other value bit for bit, places by its stated rule, and its undo restores
//! map and layers `==`; a refusal changes neither.

use glam::DVec3;
use proptest::prelude::*;
use zipmesh::mesh::{Blend, Edited, Journal, Rule, VertexAttributes};
use zipmesh::ops::quad::{QuadOp, QuadRecord, Rotation};
use zipmesh::ops::tri::{TriOp, TriRecord};
use zipmesh::ops::{Refusal, Undo};
use zipmesh::rng::Rng;
use zipmesh::{gen, Dart, Map, Mesh, Vert};

type Layers = (Vec<DVec3>, Vec<bool>);

/// An operator family as the harness drives it.
trait Op: Copy + std::fmt::Debug {
    type Record: Undo + std::fmt::Debug;
    fn random(m: &Map, rng: &mut Rng) -> Self;
    fn apply(self, m: &mut Map, l: &mut Layers) -> Result<Edited<Self::Record, Layers>, Refusal>;
    /// The vertex the applied operator places, if any.
    fn placed(r: &Self::Record) -> Option<Vert>;
}

fn random_dart(m: &Map, rng: &mut Rng) -> Dart {
    Dart::new(rng.below(m.dart_slots().max(1)) as u32)
}

impl Op for QuadOp {
    type Record = QuadRecord;
    fn random(m: &Map, rng: &mut Rng) -> Self {
        let d = random_dart(m, rng);
        let around = |k: usize| (0..k).fold(d, |x, _| m.rotate_cw(x));
        match rng.below(7) {
            0 | 1 => QuadOp::Collapse(d),
            2 => QuadOp::Split(d, around(1 + rng.below(4))),
            3 => QuadOp::HighValence(d),
            4 => QuadOp::RemoveValence2(d),
            5 => QuadOp::InsertDoublet(d),
            _ => QuadOp::Rotate(d, Rotation::Clockwise),
        }
    }
    fn apply(self, m: &mut Map, l: &mut Layers) -> Result<Edited<QuadRecord, Layers>, Refusal> {
        self.apply(&mut (&mut *m, &mut *l))
    }
    fn placed(r: &QuadRecord) -> Option<Vert> {
        match r {
            QuadRecord::Collapse(c) => Some(c.kept()),
            QuadRecord::Split(s) => Some(s.created()),
            QuadRecord::InsertDoublet(i) => Some(i.vertex()),
            QuadRecord::RemoveValence2(_) | QuadRecord::Rotate(_) => None,
        }
    }
}

impl Op for TriOp {
    type Record = TriRecord;
    fn random(m: &Map, rng: &mut Rng) -> Self {
        let d = random_dart(m, rng);
        match rng.below(4) {
            0 => TriOp::Flip(d),
            1 => TriOp::Collapse(d),
            2 => TriOp::SplitVertex(d, (0..2 + rng.below(3)).fold(d, |x, _| m.rotate_cw(x))),
            _ => TriOp::SplitEdge(d),
        }
    }
    fn apply(self, m: &mut Map, l: &mut Layers) -> Result<Edited<TriRecord, Layers>, Refusal> {
        self.apply(&mut (&mut *m, &mut *l))
    }
    fn placed(r: &TriRecord) -> Option<Vert> {
        match r {
            TriRecord::Flip(_) => None,
            TriRecord::Collapse(c) => Some(c.kept()),
            TriRecord::SplitVertex(s) => Some(s.created()),
            TriRecord::SplitEdge(s) => Some(s.created()),
        }
    }
}

/// Old slots whose values differ between `before` and `after`.
fn changed(before: &Layers, after: &Layers) -> Vec<Vert> {
    (0..before.0.len().max(before.1.len()))
        .map(|i| Vert::new(i as u32))
        .filter(|&v| before.value(v) != after.value(v))
        .collect()
}

/// Runs `steps` random operators of family `O` with both layers; returns how many applied.
fn run<O: Op>(mesh: &Mesh, seed: u64, steps: usize) -> usize {
    let mut rng = Rng::new(seed);
    let mut map = mesh.map.clone();
    let marks = (0..map.vertex_slots()).map(|_| rng.chance(1, 3)).collect();
    let mut layers: Layers = (mesh.positions.clone(), marks);
    let mut applied = 0;
    for _ in 0..steps {
        let op = O::random(&map, &mut rng);
        let before = (map.clone(), layers.clone());
        match op.apply(&mut map, &mut layers) {
            Err(r) => assert_eq!((&map, &layers), (&before.0, &before.1), "{op:?}: {r}"),
            Ok(edit) => {
                applied += 1;
                let diff = changed(&before.1, &layers);
                let target = O::placed(edit.record());
                assert!(
                    diff.iter().all(|&v| Some(v) == target),
                    "{op:?} changed {diff:?}, placed {target:?}"
                );
                // A placed vertex that existed before (a kept or reused slot) is saved once.
                let reused = target.is_some_and(|v| v.index() < before.1 .0.len());
                assert_eq!(edit.journal().overwritten(), usize::from(reused), "{op:?}");
                if let Some(v) = target {
                    assert!(layers.0.len() > v.index() && layers.1.len() > v.index());
                }
                // Every edit undoes exactly on its own; redo it to go on.
                edit.undo(&mut (&mut map, &mut layers)).unwrap();
                assert_eq!((&map, &layers), (&before.0, &before.1), "{op:?} undo");
                op.apply(&mut map, &mut layers).unwrap();
            }
        }
    }
    applied
}

fn generated(kind: usize, a: usize, seed: u64) -> Mesh {
    match kind {
        0 => gen::torus_grid(3 + a % 12, 4 + a % 9),
        1 => gen::cube(1 + a % 6),
        2 => gen::grid(1 + a % 10, 2 + a % 7),
        _ => gen::random_quad(100 + 20 * a, a % 3, a % 2, seed),
    }
}

fn generated_tri(a: usize, seed: u64) -> Mesh {
    gen::random_triangle(60 + 25 * a, a % 3, a % 2, seed)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn quad_edits_keep_both_layers_in_step(kind in 0usize..4, a in 0usize..40, seed in any::<u64>()) {
        let mesh = generated(kind, a, seed);
        run::<QuadOp>(&mesh, seed, 60);
    }

    #[test]
    fn tri_edits_keep_both_layers_in_step(a in 0usize..40, seed in any::<u64>()) {
        run::<TriOp>(&generated_tri(a, seed), seed, 60);
    }
}

#[test]
fn sequences_apply_often_enough_to_mean_something() {
    let quad: usize = (0..8)
        .map(|s| run::<QuadOp>(&gen::random_quad(300, 1, 1, s), s, 80))
        .sum();
    let tri: usize = (0..8)
        .map(|s| run::<TriOp>(&generated_tri(8, s), s, 80))
        .sum();
    // Random darts refuse often (wrong valence, boundary); a quarter applying is plenty.
    for (family, applied) in [("quad", quad), ("tri", tri)] {
        assert!(
            applied > 8 * 80 / 4,
            "{family}: {applied} of 640 edits applied"
        );
    }
}

#[test]
fn rules_place_where_they_say() {
    let mesh = gen::grid(2, 2);
    let at = |v: u32| mesh.positions[v as usize];
    let value = |v: Vert| mesh.positions[v.index()];
    let (a, b, centre) = (Vert::new(0), Vert::new(1), Vert::new(4));
    assert_eq!(
        Rule::Midpoint(a, b).evaluate(&mesh.map, value),
        Some((at(0) + at(1)) / 2.0)
    );
    // The mean of the neighbours of `of`, leaving out `skip`.
    let ring = |of: Vert, skip: Option<Vert>| {
        let values: Vec<DVec3> = mesh
            .map
            .vertex_darts(of)
            .map(|d| mesh.map.dest(d))
            .filter(|&n| Some(n) != skip)
            .map(value)
            .collect();
        DVec3::mean(&values).unwrap()
    };
    let mean = ring(centre, None);
    assert_eq!(
        Rule::NeighbourMean(centre).evaluate(&mesh.map, value),
        Some(mean)
    );
    for (from, skip_from) in [(a, false), (b, true)] {
        let rule = Rule::TowardNeighbours {
            from,
            of: centre,
            skip_from,
        };
        let pull = ring(centre, skip_from.then_some(from));
        let want = (value(from) + pull) / 2.0;
        assert_eq!(rule.evaluate(&mesh.map, value), Some(want), "{rule:?}");
    }
    // Leaving `from` out changes the pull when `from` is a neighbour of `of`.
    assert_ne!(ring(centre, Some(b)), mean);
}

#[test]
fn a_journal_saves_each_vertex_once_and_rewinds_in_order() {
    let mut marks = vec![false, true, false];
    let mut j = Journal::start(&marks);
    j.set(&mut marks, Vert::new(0), true);
    j.set(&mut marks, Vert::new(0), false); // a second write keeps the first saved value
    j.set(&mut marks, Vert::new(5), true); // beyond the layer: grows, nothing to save
    assert_eq!(j.overwritten(), 1);
    assert_eq!(marks.len(), 6);
    j.rewind(&mut marks);
    assert_eq!(marks, vec![false, true, false]);
}

/// Past the short scan (many overwritten vertices in one edit) repeats are still saved once,
/// and the rewind still restores every first value.
#[test]
fn a_long_journal_saves_each_vertex_once() {
    let before: Vec<f64> = (0..200).map(f64::from).collect();
    let mut layer = before.clone();
    let mut j = Journal::start(&layer);
    for round in 1..=3 {
        for v in (0..200).rev() {
            j.set(&mut layer, Vert::new(v), f64::from(1000 * round + v));
        }
    }
    assert_eq!(j.overwritten(), 200);
    assert_eq!(layer[7], 3007.0);
    j.rewind(&mut layer);
    assert_eq!(layer, before);
}

/// Vertices that a Q-zip's splits created (their slots may be reused ones).
fn created_by(records: &[QuadRecord]) -> Vec<Vert> {
    records
        .iter()
        .filter_map(|r| match r {
            QuadRecord::Split(s) => Some(s.created()),
            _ => None,
        })
        .collect()
}

#[test]
fn qzip_keeps_both_layers_in_step() {
    use zipmesh::invariants::{irregular_vertices, MeshKind};
    use zipmesh::qzip::{sketch, Qzip, SketchOptions, Tag};
    let mut mesh = gen::subdivided_icosahedron(2);
    let mut rng = Rng::new(7);
    let marks = (0..mesh.map.vertex_slots())
        .map(|_| rng.chance(1, 2))
        .collect();
    let mut layers: Layers = (mesh.positions.clone(), marks);
    let sing = irregular_vertices(&mesh.map, MeshKind::Quad);
    let (mut zipped, mut reused) = (0, 0);
    for (i, &a) in sing.iter().enumerate().take(8) {
        let b = sing[(i * 7 + 13) % sing.len()];
        let Ok(path) = sketch(&mesh.map, a, b, &SketchOptions::default()) else {
            continue;
        };
        for tag in Tag::CCW {
            let before = (mesh.map.clone(), layers.clone());
            let Ok(z) = Qzip::new().zip_along(&mut (&mut mesh.map, &mut layers), &path, tag) else {
                assert_eq!((&mesh.map, &layers), (&before.0, &before.1));
                continue;
            };
            zipped += 1;
            let created = created_by(z.record().records());
            let diff = changed(&before.1, &layers);
            assert!(
                diff.iter().all(|v| created.contains(v)),
                "{diff:?} not created"
            );
            reused += z.journal().overwritten();
            assert!(layers.0.len() >= mesh.map.vertex_slots());
            z.undo(&mut (&mut mesh.map, &mut layers)).unwrap();
            assert_eq!((&mesh.map, &layers), (&before.0, &before.1), "{tag:?} undo");
        }
    }
    assert!(zipped >= 8, "only {zipped} Q-zips applied");
    // Zips free slots (collapses) and reuse them (splits): the journal must have saved some.
    assert!(
        reused > 0,
        "no Q-zip reused a slot: the journal was not exercised"
    );
}

/// The preprocessing's undo restores positions too, also those of reused slots (before the
/// attribute layer it dropped them).
#[test]
fn preprocessing_undo_restores_positions() {
    use zipmesh::ops::quad;
    use zipmesh::qzip::preprocess;
    let mut found = 0;
    for seed in 0..40u64 {
        let mut mesh = gen::torus_grid(8, 8);
        let mut rng = Rng::new(seed);
        // A collapse frees a slot and makes a v6; a doublet takes the slot as a v2.
        for _ in 0..3 {
            let d = Dart::new(rng.below(mesh.map.dart_slots()) as u32);
            let _ = quad::QuadOp::Collapse(d).apply(&mut mesh);
            let d = Dart::new(rng.below(mesh.map.dart_slots()) as u32);
            let _ = quad::QuadOp::InsertDoublet(d).apply(&mut mesh);
        }
        let before = mesh.clone();
        let Ok(p) = preprocess(&mut mesh) else {
            assert_eq!(mesh, before);
            continue;
        };
        found += usize::from(p.journal().overwritten() > 0);
        p.undo(&mut mesh).unwrap();
        assert_eq!(mesh, before, "seed {seed}");
    }
    assert!(
        found > 0,
        "no preprocessing overwrote a position: the case is not exercised"
    );
}
