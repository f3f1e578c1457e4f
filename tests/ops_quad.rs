//! Property tests of the quad operators on large meshes: generated tori, cubes, grids and
//! random quad meshes of thousands of faces, and the quad meshes in `tests/data/quad/`.
//!
//! Each case runs a random sequence of operators at random places (half of them near the
//! previous edits, so that operators interact). Every step is either refused, with the same
//! reason as the `can_*` check and the mesh unchanged, or applied, with `check()` passing, its
//! documented effect (`QuadOp::effect`: the V/E/F deltas, the valence of every involved
//! vertex, every other valence unchanged) and every face still a quad. At the end the whole sequence is undone in
//! reverse order and the mesh (topology and positions) must equal the original.

use proptest::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::mesh::Edited;
use zipmesh::ops::quad::{self, QuadRecord, Rotation};
use zipmesh::rng::Rng;
use zipmesh::{gen, Dart, Map, Mesh};

use zipmesh::ops::quad::QuadOp as Op;

/// Checks an applied operator against its documented effect ([`Op::effect`], computed on
/// the map before).
fn check_applied(before: &Map, after: &Map, op: Op, rec: &QuadRecord) {
    if let Err(v) = after.check() {
        panic!("{op:?} left an invalid map: {v:?}");
    }
    let effect = op.effect(before).expect("an applied operator is allowed");
    if let Err(e) = effect.check(before, after, rec) {
        panic!("{op:?}: {e}");
    }
    assert!(after.faces().all(|f| after.degree(f) == 4), "{op:?}");
    assert_eq!(defects(after), defects(before), "{op:?}");
}

/// Loops plus surplus parallel edges: operators neither create nor remove any.
fn defects(m: &Map) -> usize {
    zipmesh::invariants::non_simple_edges(m)
}

fn random_dart(m: &Map, rng: &mut Rng, hot: &[Dart]) -> Dart {
    if !hot.is_empty() && rng.chance(1, 2) {
        let d = hot[rng.below(hot.len())];
        if m.is_live_dart(d) {
            return d;
        }
    }
    for _ in 0..64 {
        let d = Dart::new(rng.below(m.dart_slots()) as u32);
        if m.is_live_dart(d) {
            return d;
        }
    }
    m.darts().next().expect("a non-empty map")
}

fn random_op(m: &Map, rng: &mut Rng, hot: &[Dart]) -> Op {
    let d = random_dart(m, rng, hot);
    match rng.below(9) {
        0 | 1 => Op::Collapse(d),
        2 | 3 => {
            // Mostly a second dart around the same vertex, sometimes any dart.
            let s2 = if rng.chance(1, 8) {
                random_dart(m, rng, &[])
            } else {
                let k = rng.below(m.valence(m.origin(d)).max(1));
                (0..k).fold(d, |x, _| m.rotate_cw(x))
            };
            Op::Split(d, s2)
        }
        4 => Op::HighValence(d),
        5 => Op::RemoveValence2(d),
        6 => Op::InsertDoublet(d),
        7 => Op::Rotate(d, Rotation::Clockwise),
        _ => Op::Rotate(d, Rotation::CounterClockwise),
    }
}

/// Tallies of what a run did, to check that runs exercise the operators.
#[derive(Default, Debug)]
struct Stats {
    applied: usize,
    refused: usize,
}

/// Runs `steps` random operators on `mesh`, checking each, then undoes them all.
fn run_sequence(original: &Mesh, seed: u64, steps: usize) -> Stats {
    let mut rng = Rng::new(seed);
    let mut mesh = original.clone();
    let mut edits: Vec<Edited<QuadRecord>> = Vec::new();
    let mut hot: Vec<Dart> = Vec::new();
    let mut stats = Stats::default();
    for _ in 0..steps {
        let op = random_op(&mesh.map, &mut rng, &hot);
        let before = mesh.clone();
        let can = op.can(&mesh.map);
        match op.apply(&mut mesh) {
            Err(r) => {
                assert_eq!(can, Err(r), "{op:?}");
                assert!(
                    mesh == before,
                    "{op:?} refused ({r:?}) but changed the mesh"
                );
                stats.refused += 1;
            }
            Ok(edit) => {
                assert_eq!(can, Ok(()), "{op:?}");
                check_applied(&before.map, &mesh.map, op, edit.record());
                assert!(mesh.positions.len() >= mesh.map.vertex_slots());
                // Work near this edit next: darts around the touched vertices.
                let d = match op {
                    Op::Collapse(d)
                    | Op::Split(d, _)
                    | Op::HighValence(d)
                    | Op::InsertDoublet(d)
                    | Op::Rotate(d, _) => d,
                    Op::RemoveValence2(d) => before.map.next(d),
                };
                if mesh.map.is_live_dart(d) {
                    hot = mesh.map.vertex_darts(mesh.map.origin(d)).collect();
                    hot.extend(mesh.map.face_cycle(d));
                }
                edits.push(edit);
                stats.applied += 1;
            }
        }
    }
    while let Some(e) = edits.pop() {
        e.undo(&mut mesh).expect("undo in reverse order");
    }
    assert!(
        mesh == *original,
        "undoing the sequence did not restore the mesh"
    );
    stats
}

fn data(rel: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    assert!(
        dir.join("SOURCES.md").is_file(),
        "the test meshes are missing: expected {}",
        dir.display()
    );
    dir.join(rel)
}

const SHARED: [&str; 6] = [
    "quad/blub_quadrangulated.obj",
    "quad/cubespikes.obj",
    "quad/osd_catmark_helmet.obj",
    "quad/osd_catmark_toroidal_tet.obj",
    "quad/osd_catmark_torus.obj",
    "quad/spot_quadrangulated.obj",
];

fn shared(i: usize) -> &'static Mesh {
    static MESHES: OnceLock<Vec<Mesh>> = OnceLock::new();
    &MESHES.get_or_init(|| {
        SHARED
            .iter()
            .map(|f| {
                let (m, _) = zipmesh::io::read_mesh(data(f)).expect("shared quad mesh");
                m
            })
            .collect()
    })[i]
}

fn generated(kind: usize, a: usize, b: usize, seed: u64) -> Mesh {
    match kind {
        0 => gen::torus_grid(3 + a % 40, 3 + b % 40),
        1 => gen::cube(1 + a % 14),
        2 => gen::grid(1 + a % 45, 1 + b % 45),
        _ => gen::random_quad(200 + 60 * a, b % 4, (b / 4) % 3, seed),
    }
}

fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: n,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(cases(256))]

    /// Random operator sequences on generated meshes (random quad meshes up to about 3,200
    /// faces of genus 0 to 3 with 0 to 2 holes, tori up to 42 x 42, cubes, grids).
    #[test]
    fn random_sequences_on_generated_meshes(
        kind in 0usize..4, a in 0usize..50, b in 0usize..50, seed in any::<u64>()
    ) {
        let mesh = generated(kind, a, b, seed);
        prop_assume!(mesh.map.num_faces() > 0);
        let s = run_sequence(&mesh, seed ^ 0x9e37, 80);
        prop_assert!(s.applied > 0, "{s:?}");
    }
}

proptest! {
    #![proptest_config(cases(96))]

    /// Random operator sequences on the real quad meshes of `tests/data/quad/`.
    #[test]
    fn random_sequences_on_shared_meshes(which in 0usize..6, seed in any::<u64>()) {
        let s = run_sequence(shared(which), seed, 80);
        prop_assert!(s.applied > 0, "{s:?}");
    }
}

proptest! {
    #![proptest_config(cases(64))]

    /// A vertex split followed by the quad collapse of the new quad (both as ordinary
    /// operators) gives back the canonical code, and so does a collapse followed by the split
    /// of the merged vertex along its two merged edges.
    #[test]
    fn split_and_collapse_invert_each_other(
        faces in 200usize..1200, genus in 0usize..3, holes in 0usize..3, seed in any::<u64>()
    ) {
        let mesh = gen::random_quad(faces, genus, holes, seed);
        let m = &mesh.map;
        let code = CanonicalCode::of(m);
        let mut rng = Rng::new(seed);
        let mut splits = 0;
        let mut collapses = 0;
        for _ in 0..40 {
            let d = random_dart(m, &mut rng, &[]);
            let k = rng.below(m.valence(m.origin(d)));
            let s2 = (0..k).fold(d, |x, _| m.rotate_cw(x));
            if quad::can_split_vertex(m, d, s2).is_ok() {
                let mut x = m.clone();
                quad::split_vertex(&mut x, d, s2).unwrap();
                quad::collapse_quad(&mut x, d).unwrap();
                prop_assert_eq!(&CanonicalCode::of(&x), &code);
                splits += 1;
            }
            if quad::can_collapse_quad(m, d).is_ok() {
                let mut x = m.clone();
                let r = quad::collapse_quad(&mut x, d).unwrap();
                let [to_b, to_d] = r.merged_edges();
                quad::split_vertex(&mut x, to_b, to_d).unwrap();
                prop_assert_eq!(x.check(), Ok(()));
                prop_assert_eq!(&CanonicalCode::of(&x), &code);
                collapses += 1;
            }
        }
        prop_assert!(splits > 0 && collapses > 0);
    }
}

/// Each shared mesh gets a long sequence too, and every operator is applied somewhere.
#[test]
fn long_sequences_on_every_shared_mesh() {
    let mut total = Stats::default();
    for (i, name) in SHARED.iter().enumerate() {
        let s = run_sequence(shared(i), 1000 + i as u64, 400);
        assert!(s.applied > 20, "{name}: {s:?}");
        total.applied += s.applied;
        total.refused += s.refused;
    }
    assert!(total.refused > 0);
}

/// Every operator is applied on a quad mesh somewhere in a fixed run (a test that the random
/// sequences above do not only ever refuse one kind of operator).
#[test]
fn every_operator_applies_on_generated_meshes() {
    let mut applied: HashMap<&str, usize> = HashMap::new();
    let mesh = gen::random_quad(1500, 1, 1, 5);
    let mut m = mesh.clone();
    let mut rng = Rng::new(17);
    let mut hot = Vec::new();
    for _ in 0..3000 {
        let op = random_op(&m.map, &mut rng, &hot);
        if op.apply(&mut m).is_ok() {
            let name = match op {
                Op::Collapse(_) => "collapse",
                Op::Split(..) => "split",
                Op::HighValence(_) => "high",
                Op::RemoveValence2(_) => "remove2",
                Op::InsertDoublet(_) => "insert",
                Op::Rotate(..) => "rotate",
            };
            *applied.entry(name).or_default() += 1;
            if let Op::InsertDoublet(d) | Op::Collapse(d) = op {
                if m.map.is_live_dart(d) {
                    hot = m.map.vertex_darts(m.map.origin(d)).collect();
                    hot.extend(m.map.face_cycle(d));
                }
            }
        }
    }
    assert_eq!(m.map.check(), Ok(()));
    for name in ["collapse", "split", "high", "remove2", "insert", "rotate"] {
        assert!(
            applied.get(name).copied().unwrap_or(0) > 0,
            "{name}: {applied:?}"
        );
    }
}
