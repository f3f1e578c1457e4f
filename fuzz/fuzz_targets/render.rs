//! `render` on small generated quad, triangle and quad-dominant meshes whose positions the
//! fuzzer moves (onto each other, far away, to tiny or huge coordinates), from a
//! fuzzer-chosen view at a fuzzer-chosen size, with a fuzzer-chosen path. The library must
//! never panic; the oracle: the SVG has exactly one circle per seen interior singularity,
//! each with its recounted valence as class.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::collections::BTreeSet;
use zipmesh::invariants::{is_irregular, MeshKind};
use zipmesh::render::{Options, Scene, View};
use zipmesh::{gen, Vert};

/// Reads the input a byte at a time; zeros once it runs out, so every input is usable.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
}

fn coordinate(bytes: &mut Bytes) -> f64 {
    let (k, e) = (bytes.u8(), bytes.u8());
    let mantissa = f64::from(bytes.u16()) / 65535.0 - 0.5;
    match k % 4 {
        0 => mantissa,
        1 => 0.0,
        // Anything from subnormal to the largest finite magnitudes (and past them: infinite
        // or NaN, which must be refused).
        _ => mantissa * 2f64.powi(i32::from(e) * 8 - 1016),
    }
}

fuzz_target!(|data: &[u8]| {
    let mut bytes = Bytes(data);
    let (family, faces, seed) = (bytes.u8(), bytes.u8(), bytes.u16());
    let (genus, holes) = (usize::from(bytes.u8() % 3), usize::from(bytes.u8() % 2));
    let faces = 16 + usize::from(faces);
    let mut mesh = match family % 3 {
        0 => gen::random_quad(faces, genus, holes, u64::from(seed)),
        1 => gen::random_triangle(faces, genus, holes, u64::from(seed)),
        _ => gen::random_mixed(faces, genus, holes, u64::from(seed)),
    };
    let slots = mesh.positions.len().max(1);
    for _ in 0..bytes.u8() % 16 {
        let v = usize::from(bytes.u16()) % slots;
        let p = [
            coordinate(&mut bytes),
            coordinate(&mut bytes),
            coordinate(&mut bytes),
        ];
        if let Some(q) = mesh.positions.get_mut(v) {
            *q = glam::DVec3::from_array(p);
        }
    }
    let view = View::new(
        f64::from(bytes.u16()) - 32768.0,
        f64::from(bytes.u8() % 181) - 90.0,
    );
    let path: Vec<u64> = (0..bytes.u8() % 8)
        .map(|_| u64::from(bytes.u16()) % slots as u64)
        .collect();
    let options = Options {
        view: view.ok(),
        width: 1 + u32::from(bytes.u16() % 600),
        height: 1 + u32::from(bytes.u16() % 600),
        paths: vec![path],
        point_paths: vec![(0..bytes.u8() % 4)
            .map(|_| [0, 1, 2].map(|_| f64::from(bytes.u16() as i16) / 100.0))
            .collect()],
    };
    let Ok(scene) = Scene::new(&mesh, &options) else {
        return;
    };
    let svg = scene.svg();
    let map = &mesh.map;
    let kind = MeshKind::of(map);
    let mut drawn = BTreeSet::new();
    for el in svg.split("<circle ").skip(1) {
        let attr = |name: &str| {
            let key = format!("{name}=\"");
            let start = el.find(&key).expect("attribute") + key.len();
            el[start..start + el[start..].find('"').expect("quote")].to_string()
        };
        let v: u32 = attr("data-vertex").parse().expect("a vertex number");
        let vert = Vert::new(v);
        assert!(!map.is_boundary_vertex(vert) && is_irregular(map, kind, vert));
        assert_eq!(attr("class"), format!("v{}", map.valence(vert)));
        assert!(drawn.insert(v), "two circles on vertex {v}");
    }
    let seen: BTreeSet<u32> = scene
        .balls()
        .iter()
        .filter(|b| b.visible)
        .map(|b| b.vertex.index() as u32)
        .collect();
    assert_eq!(drawn, seen);
});
