//! Q-zip on the real quad meshes of `tests/data/quad/`: every pair of irregular vertices
//! within 12 edges, every movement; grid preservation, exact undo and the moved valences
//! hold for every movement done, refusals leave the mesh untouched, and the reverse run
//! restores the original.

mod common;

use common::{check_zip, pairs_within};
use std::collections::BTreeMap;
use std::path::Path;
use zipmesh::invariants::canonical::CanonicalCode;
use zipmesh::qzip::{find_reverse, Qzip, QzipError, Tag};
use zipmesh::{io, Map};

const MAX_DISTANCE: usize = 12;

#[derive(Default, Debug)]
struct Tally {
    pairs: usize,
    moved: usize,
    refused: BTreeMap<String, usize>,
    reversed: usize,
    reverse_checked: usize,
}

/// The refusal's kind, without vertex numbers.
fn kind(e: &QzipError) -> String {
    let s = format!("{e:?}");
    s.split(['{', '(', ' '])
        .take(2)
        .collect::<Vec<_>>()
        .join(" ")
}

fn campaign(map: &Map, reverse_every: usize) -> Tally {
    let mut t = Tally::default();
    let code = CanonicalCode::of(map);
    for path in pairs_within(map, MAX_DISTANCE) {
        t.pairs += 1;
        for tag in Tag::CCW {
            match check_zip(map, &path, tag) {
                Ok((edited, r)) => {
                    t.moved += 1;
                    if t.moved % reverse_every == 0 {
                        t.reverse_checked += 1;
                        if let Some(back) = find_reverse(&edited, &r, map) {
                            let mut m = edited.clone();
                            Qzip::new().zip_along(&mut m, &back.path, back.tag).unwrap();
                            assert_eq!(CanonicalCode::of(&m), code);
                            t.reversed += 1;
                        }
                    }
                }
                Err(e) => *t.refused.entry(kind(&e)).or_default() += 1,
            }
        }
    }
    t
}

fn mesh(name: &str) -> Map {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/quad")
        .join(name);
    io::read_mesh(p).expect("shared mesh").0.map
}

#[test]
fn cubespikes() {
    let t = campaign(&mesh("cubespikes.obj"), 1);
    eprintln!("cubespikes: {t:?}");
    assert!(t.moved > 100, "{t:?}");
    assert_eq!(t.reversed, t.reverse_checked, "{t:?}");
}

#[test]
fn spot() {
    let t = campaign(&mesh("spot_quadrangulated.obj"), 1);
    eprintln!("spot: {t:?}");
    assert!(t.moved > 100, "{t:?}");
    assert_eq!(t.reversed, t.reverse_checked, "{t:?}");
}

#[test]
fn blub() {
    let t = campaign(&mesh("blub_quadrangulated.obj"), 1);
    eprintln!("blub: {t:?}");
    assert!(t.moved > 20, "{t:?}");
    assert_eq!(t.reversed, t.reverse_checked, "{t:?}");
}

/// The helmet has a boundary (its irregular boundary corners are refused by name) and four
/// interior v3s; the OpenSubdiv tori have no pair to move (regular, or all valence 6).
#[test]
fn small_meshes() {
    let t = campaign(&mesh("osd_catmark_helmet.obj"), 1);
    eprintln!("helmet: {t:?}");
    assert!(t.pairs > 0);
    assert_eq!(t.reversed, t.reverse_checked, "{t:?}");
    for name in ["osd_catmark_torus.obj", "osd_catmark_toroidal_tet.obj"] {
        let t = campaign(&mesh(name), 1);
        eprintln!("{name}: {t:?}");
        assert_eq!(t.moved, 0);
    }
}

/// With the preprocessing (valence-6+ vertices split), the pairs that ran through or ended
/// at a valence-6 or 7 vertex of Spot and Blub move too.
#[test]
fn preprocessed_spot_and_blub() {
    for name in ["spot_quadrangulated.obj", "blub_quadrangulated.obj"] {
        let mut map = mesh(name);
        let before = map.clone();
        let p = zipmesh::qzip::preprocess(&mut map).expect("preprocessing");
        assert!(map
            .vertices()
            .all(|v| map.is_boundary_vertex(v) || (3..=5).contains(&map.valence(v))));
        let t = campaign(&map, 8);
        eprintln!("{name} preprocessed: {t:?}");
        assert!(!t.refused.contains_key("Plan Valence"), "{t:?}");
        assert!(t.moved > 100, "{t:?}");
        // Measured on every movement: 5,317 of 5,340 on Spot, 487 of 529 on Blub (every 8th
        // here: 667 of 667 and 59 of 66); each miss has a third singularity on its path or
        // next to one of its ends. The canonical clean-up split costs some (5,322 of 5,336
        // and 510 of 526 when the split followed the touch order, which broke homotopy
        // invariance): docs/qzip.md.
        assert!(t.reversed * 100 >= t.reverse_checked * 85, "{t:?}");
        p.undo(&mut map).unwrap();
        assert_eq!(map, before);
    }
}
