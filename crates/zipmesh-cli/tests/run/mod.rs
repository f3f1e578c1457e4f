//! Running the `zipmesh` binary from the command-line tests.
#![allow(dead_code)]

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the binary with `args`.
pub fn zipmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_zipmesh"))
        .args(args)
        .output()
        .expect("the zipmesh binary runs")
}

/// `zip IN --from 15 --to 2 --move LC`: the LC movement on Spot's quad mesh that several
/// tests run (add `-o` and the options).
#[allow(dead_code)] // not every test file that includes this module zips
pub fn spot_zip(input: &str) -> Vec<&str> {
    vec!["zip", input, "--from", "15", "--to", "2", "--move", "LC"]
}

/// Runs the binary with the words of `line` as arguments (for arguments without spaces).
pub fn zipmesh_words(line: &str) -> Output {
    zipmesh(&line.split_whitespace().collect::<Vec<_>>())
}

/// A fresh directory for one test's files.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// A path as `&str`.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

/// The repository's root, where the tests' meshes (`tests/data/`) and docs are.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}
