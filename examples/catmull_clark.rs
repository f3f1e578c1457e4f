//! Catmull-Clark steps of a mesh file: `cargo run --release --example catmull_clark -- IN
//! OUT [STEPS]` (one step by default). Makes the optimizer's robustness meshes
//! (`scripts/robust_meshes.py`, docs/benchmarks.md) from triangle meshes.

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(input), Some(output)) = (args.first(), args.get(1)) else {
        eprintln!("usage: catmull_clark IN OUT [STEPS]");
        return ExitCode::from(2);
    };
    let steps: usize = match args.get(2).map(|s| s.parse()) {
        None => 1,
        Some(Ok(n)) => n,
        Some(Err(e)) => {
            eprintln!("STEPS: {e}");
            return ExitCode::from(2);
        }
    };
    let mut mesh = match zipmesh::io::read_mesh(input) {
        Ok((m, _)) => m,
        Err(e) => {
            eprintln!("{input}: {e}");
            return ExitCode::from(2);
        }
    };
    for _ in 0..steps {
        mesh = zipmesh::gen::catmull_clark(&mesh);
    }
    if let Err(e) = zipmesh::io::write_mesh(output, &mesh) {
        eprintln!("{output}: {e}");
        return ExitCode::from(2);
    }
    println!("{output}: {} faces", mesh.map.num_faces());
    ExitCode::SUCCESS
}
