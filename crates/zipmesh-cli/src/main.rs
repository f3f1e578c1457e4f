//! The `zipmesh` binary: everything is in the crate's library (`zipmesh_cli`).

fn main() -> std::process::ExitCode {
    zipmesh_cli::main()
}
