//! `Map::from_polygons` on any polygon list: never a panic; every map it returns is valid,
//! keeps every face's corners, and reports exactly the unreferenced vertices.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::arbitrary::PolygonSoup;
use zipmesh::{Map, Vert};
use zipmesh_fuzz::assert_valid;

fuzz_target!(|soup: PolygonSoup| {
    let nv = usize::from(soup.n_vertices);
    let faces = soup.faces();
    let Ok((map, report)) = Map::from_polygons_with_report(nv, &faces) else {
        return;
    };
    assert_valid(&map);
    assert_eq!(map.num_faces(), faces.len());
    for (f, poly) in map.faces().zip(&faces) {
        let got: Vec<u32> = map
            .face_darts(f)
            .map(|d| map.origin(d).index() as u32)
            .collect();
        let k = poly.iter().position(|&v| v == got[0]).expect("corner kept");
        assert!(got
            .iter()
            .enumerate()
            .all(|(i, &v)| poly[(k + i) % poly.len()] == v));
    }
    let unreferenced: Vec<Vert> = (0..nv as u32)
        .filter(|v| !faces.iter().any(|p| p.contains(v)))
        .map(Vert::new)
        .collect();
    assert_eq!(report.unreferenced, unreferenced);
});
