//! Runs every command of `docs/guide.md` as written and checks the output the guide shows.
//!
//! In the guide, each line of a ```` ```sh ```` block is one `zipmesh` command (arguments
//! without spaces or quotes); a trailing `# exit N` says the status it must end with (0
//! otherwise). A ```` ```text ```` block right after a command block is the output of its
//! last command: every line of it must appear in that command's standard output or error,
//! except `...`, which stands for lines the guide leaves out (timings, say). The commands
//! run in order in one fresh folder where `tests/` is the repository's, so the guide's paths
//! (`tests/data/...`) work and its outputs land in the folder.
#![cfg(unix)]

mod run;

use std::path::{Path, PathBuf};
use std::process::Command;

/// One command of the guide, with the status it must end with and the output it must show.
struct Step {
    line: usize,
    args: Vec<String>,
    status: i32,
    shows: Vec<String>,
}

/// The guide's commands, in order.
fn steps(guide: &str) -> Vec<Step> {
    let mut steps: Vec<Step> = Vec::new();
    let mut block: Option<&str> = None;
    let mut last_block_was_sh = false;
    for (i, raw) in guide.lines().enumerate() {
        let line = raw.trim_end();
        if let Some(kind) = block {
            if line == "```" {
                last_block_was_sh = kind == "sh";
                block = None;
            } else if kind == "sh" && !line.trim().is_empty() {
                steps.push(command(i + 1, line));
            } else if kind == "text" {
                let last = steps.last_mut().expect("a text block follows a command");
                last.shows.push(line.trim().to_string());
            }
            continue;
        }
        if let Some(kind) = line.strip_prefix("```") {
            if kind == "text" {
                assert!(
                    last_block_was_sh,
                    "guide line {}: an output block must follow a command block",
                    i + 1
                );
            }
            block = Some(if kind == "sh" || kind == "text" {
                kind
            } else {
                "other"
            });
        } else if !line.is_empty() {
            last_block_was_sh = false;
        }
    }
    assert!(block.is_none(), "the guide ends inside a code block");
    steps
}

/// A command line of the guide: `zipmesh ARGS... [# exit N]`.
fn command(line: usize, text: &str) -> Step {
    let (cmd, comment) = match text.split_once(" # ") {
        Some((c, k)) => (c, Some(k.trim())),
        None => (text, None),
    };
    let status = match comment.and_then(|k| k.strip_prefix("exit ")) {
        Some(n) => n.parse().expect("`# exit N` takes a number"),
        None => 0,
    };
    let mut words = cmd.split_whitespace();
    assert_eq!(
        words.next(),
        Some("zipmesh"),
        "guide line {line}: every command runs zipmesh"
    );
    Step {
        line,
        args: words.map(str::to_string).collect(),
        status,
        shows: Vec::new(),
    }
}

/// A fresh folder whose `tests` is the repository's.
fn workdir() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("guide");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let tests = run::root().join("tests");
    std::os::unix::fs::symlink(tests, dir.join("tests")).unwrap();
    dir
}

/// Whether the printed `line` is the guide's `shown` line, spaces aside; a shown line ending
/// in ` ...` stands for every line that begins with the rest.
fn shows(line: &str, shown: &str) -> bool {
    let words = |t: &str| t.split_whitespace().collect::<Vec<_>>().join(" ");
    match shown.strip_suffix(" ...") {
        Some(prefix) => words(line).starts_with(&words(prefix)),
        None => words(line) == words(shown),
    }
}

#[test]
fn every_command_of_the_guide_runs_as_written() {
    let path = run::root().join("docs/guide.md");
    let guide = std::fs::read_to_string(&path).expect("docs/guide.md");
    let steps = steps(&guide);
    assert!(steps.len() >= 10, "the guide has {} commands", steps.len());
    let dir = workdir();
    for step in &steps {
        let out = Command::new(env!("CARGO_BIN_EXE_zipmesh"))
            .args(&step.args)
            .current_dir(&dir)
            .output()
            .expect("the zipmesh binary runs");
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(
            out.status.code(),
            Some(step.status),
            "guide line {}: `zipmesh {}` printed\n{text}",
            step.line,
            step.args.join(" ")
        );
        for shown in step.shows.iter().filter(|s| *s != "..." && !s.is_empty()) {
            assert!(
                text.lines().any(|l| shows(l, shown)),
                "guide line {}: `zipmesh {}` does not print the line\n  {shown}\nit printed\n{text}",
                step.line,
                step.args.join(" ")
            );
        }
    }
}

#[test]
fn the_reader_of_the_guide_finds_commands_and_outputs() {
    let guide = "Text\n\n```sh\nzipmesh stats a.obj\nzipmesh hash a.obj  # exit 2\n```\n\n```text\nV 3\n...\n```\n\n```rust\nlet x = 1;\n```\n";
    let s = steps(guide);
    assert_eq!(s.len(), 2);
    assert_eq!(s[0].args, ["stats", "a.obj"]);
    assert_eq!(
        (s[1].status, s[1].shows.clone()),
        (2, vec!["V 3".to_string(), "...".to_string()])
    );
    assert!(shows("  12   5  interior", "12 5 interior"));
    assert!(shows("after 9 batches, 1.5 s", "after 9 batches, ..."));
    assert!(!shows("after 9 batches, 1.5 s", "after 8 batches, ..."));
    assert!(!shows("12 5 interior", "12 5"));
}
