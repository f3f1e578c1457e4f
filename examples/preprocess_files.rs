//! Writes preprocessed copies of quad meshes, for `zipmesh check` on them:
//! `cargo run --release --example preprocess_files -- DIR FILE...`.
//!
//! Each FILE is read, `qzip::preprocess`ed (no interior valence 2 or 6+ left), compacted
//! and written to `DIR/<its name>`; the number of operations goes to stderr. For example
//! `docs/VERIFICATION.md` counts the reversal misses of `check DIR/*.obj` this way.

use std::path::Path;
use zipmesh::{io, qzip};

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(dir) = args.next() else {
        eprintln!("usage: preprocess_files DIR FILE...");
        std::process::exit(2);
    };
    for file in args {
        let (mut mesh, _) = io::read_mesh(&file).unwrap_or_else(|e| panic!("{e}"));
        let p = qzip::preprocess(&mut mesh).unwrap_or_else(|e| panic!("{file}: {e}"));
        mesh.compact();
        let name = Path::new(&file).file_name().expect("a file name");
        let out = Path::new(&dir).join(name);
        io::write_mesh(&out, &mesh).unwrap_or_else(|e| panic!("{e}"));
        eprintln!(
            "{}: {} operations",
            out.display(),
            p.record().records().len()
        );
    }
}
