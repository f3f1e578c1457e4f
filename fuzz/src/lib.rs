//! Checks shared by the fuzz targets: what every map the library hands out must satisfy.

use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::Hash;
use zipmesh::invariants::{gauss_bonnet, Counts, Histograms, MeshKind};
use zipmesh::{is_isomorphic, Map, Mesh};

/// The most meshes a target's cache keeps; it is emptied when full.
const CACHED: usize = 256;

/// The mesh `key` names: a copy from `cache`, or `make(key)`, kept there. Generators are
/// deterministic, and libFuzzer's mutations mostly keep an input's first bytes (the mesh)
/// and change the rest, so most runs copy a mesh instead of building it.
pub fn cached<K: Eq + Hash + Copy>(
    cache: &RefCell<HashMap<K, Mesh>>,
    key: K,
    make: impl FnOnce(K) -> Mesh,
) -> Mesh {
    if let Some(m) = cache.borrow().get(&key) {
        return m.clone();
    }
    let m = make(key);
    let mut cache = cache.borrow_mut();
    if cache.len() >= CACHED {
        cache.clear();
    }
    cache.insert(key, m.clone());
    m
}

/// Asserts the axioms and the identities that hold on every valid map.
pub fn assert_valid(map: &Map) {
    assert_eq!(map.check(), Ok(()));
    let c = Counts::of(map);
    assert_eq!(
        (c.vertices, c.edges, c.faces),
        (map.num_vertices(), map.num_edges(), map.num_faces())
    );
    let chi = c.vertices as i64 - c.edges as i64 + c.faces as i64;
    assert_eq!(c.euler_characteristic, chi);
    assert_eq!(c.boundary_loops, map.boundary_loops().len());
    // Summed over components, 2g = 2 - chi - b; a half-integer genus anywhere breaks this.
    assert!(c.genus >= 0);
    assert_eq!(
        2 * c.genus,
        2 * c.components as i64 - chi - c.boundary_loops as i64
    );
    let h = Histograms::of(map);
    let vertices: usize =
        h.interior_valences.values().sum::<usize>() + h.boundary_valences.values().sum::<usize>();
    assert_eq!(vertices, c.vertices);
    assert_eq!(h.face_degrees.values().sum::<usize>(), c.faces);
    for (kind, scale) in [(MeshKind::Quad, 4), (MeshKind::Triangle, 6)] {
        let gb = gauss_bonnet(map, kind);
        assert!(gb.holds(), "{kind:?}: {gb:?}");
        assert_eq!(gb.rhs, scale * chi);
    }
    let mirror = map.mirror();
    assert_eq!(mirror.check(), Ok(()));
    assert_eq!(Counts::of(&mirror), c);
    assert!(is_isomorphic(&mirror.mirror(), map));
}

/// A parsed mesh: a valid map, one position per vertex slot, and a write-read round trip
/// through `write` and `parse` that keeps the map up to isomorphism.
pub fn assert_mesh_round_trip(
    mesh: &Mesh,
    write: fn(&Mesh, &mut Vec<u8>) -> std::io::Result<()>,
    parse: fn(&[u8]) -> Option<Mesh>,
) {
    assert_valid(&mesh.map);
    assert_eq!(mesh.positions.len(), mesh.map.vertex_slots());
    let mut out = Vec::new();
    write(mesh, &mut out).expect("writing to memory");
    let again = parse(&out).unwrap_or_else(|| {
        panic!(
            "the writer's output does not parse:\n{}",
            String::from_utf8_lossy(&out)
        )
    });
    assert!(is_isomorphic(&again.map, &mesh.map));
    assert_eq!(Counts::of(&again.map), Counts::of(&mesh.map));
    // Live vertices are written in slot order, and every coordinate reads back exactly.
    let live: Vec<_> = mesh.map.vertices().collect();
    assert_eq!(again.positions.len(), live.len());
    for (k, v) in live.iter().enumerate() {
        let (a, b) = (mesh.positions[v.index()], again.positions[k]);
        for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
            assert!(
                x == y || (x.is_nan() && y.is_nan()),
                "{a} written, {b} read back"
            );
        }
    }
}
