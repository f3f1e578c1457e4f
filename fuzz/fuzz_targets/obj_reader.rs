//! The OBJ reader on any text: never a panic; every mesh it returns is valid and survives a
//! write-read round trip.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::io::obj;
use zipmesh_fuzz::assert_mesh_round_trip;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    match obj::parse(&text) {
        Ok((mesh, _)) => assert_mesh_round_trip(
            &mesh,
            |m, out| obj::write(m, out),
            |src| obj::parse_bytes(src).ok().map(|(m, _)| m),
        ),
        Err(e) => assert!(!e.to_string().is_empty()),
    }
    // Raw bytes (UTF-16, binary): an error, or a valid mesh.
    if let Ok((mesh, _)) = obj::parse_bytes(data) {
        assert!(mesh.map.check().is_ok());
    }
    // The byte reader agrees with the text reader on valid UTF-8.
    if let Ok(s) = std::str::from_utf8(data) {
        assert_eq!(
            obj::parse(s).map(|(m, r)| (m.map, r)).ok(),
            obj::parse_bytes(data).map(|(m, r)| (m.map, r)).ok()
        );
    }
});
