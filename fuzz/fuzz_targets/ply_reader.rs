//! The PLY reader on any bytes (ASCII and binary): never a panic; every mesh it returns is
//! valid and survives a round trip through both writers (binary little-endian and ASCII),
//! except one with a face of more than 255 corners, which both writers refuse.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::io::ply;
use zipmesh_fuzz::assert_mesh_round_trip;

fuzz_target!(|data: &[u8]| {
    match ply::parse_bytes(data) {
        Ok((mesh, _)) => {
            if mesh.map.faces().any(|f| mesh.map.degree(f) > 255) {
                let e = ply::write(&mesh, &mut Vec::new()).unwrap_err();
                assert_eq!(e.kind(), std::io::ErrorKind::InvalidData);
                return;
            }
            let parse = |src: &[u8]| ply::parse_bytes(src).ok().map(|(m, _)| m);
            assert_mesh_round_trip(&mesh, |m, out| ply::write(m, out), parse);
            assert_mesh_round_trip(&mesh, |m, out| ply::write_ascii(m, out), parse);
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
});
