//! All output of the tool: standard output is collected here and written once, so that a
//! closed pipe or a full disk is an error the tool handles instead of a panic in `println!`.
//!
//! A reader that closes the pipe early (`zipmesh stats | head -c0`) ends the tool quietly
//! with [`CLOSED_PIPE`], the status a shell reports for a Unix tool stopped by `SIGPIPE`;
//! any other failure to write (a full disk) is an error, exit 2.

use std::fmt;
use std::io::{self, Write};
use std::process::ExitCode;
use std::sync::Mutex;

/// The exit status on a closed standard output: 128 + SIGPIPE, as `cat` or `seq` give.
pub const CLOSED_PIPE: u8 = 141;

/// Text printed so far (standard output), whether writing it has already failed, and,
/// while a command runs for an embedder ([`capture`]), the text flushed so far.
struct Sink {
    text: String,
    closed: bool,
    captured: Option<String>,
}

static STDOUT: Mutex<Sink> = Mutex::new(Sink {
    text: String::new(),
    closed: false,
    captured: None,
});

/// Runs `f` with standard output collected instead of written; its result and the text.
/// The caller runs one command at a time (`run_captured` holds a lock).
pub fn capture<T>(f: impl FnOnce() -> T) -> (T, String) {
    let lock = || STDOUT.lock().unwrap_or_else(|p| p.into_inner());
    {
        let mut sink = lock();
        sink.text.clear();
        sink.captured = Some(String::new());
    }
    let result = f();
    let mut sink = lock();
    let mut text = sink.captured.take().unwrap_or_default();
    text.push_str(&std::mem::take(&mut sink.text));
    (result, text)
}

/// Whether standard output is being collected for an embedder (no progress bars then).
pub fn capturing() -> bool {
    STDOUT.lock().map(|s| s.captured.is_some()).unwrap_or(false)
}

/// Appends to standard output; [`flush`] writes it.
macro_rules! outln {
    () => { $crate::out::push(format_args!("\n")) };
    ($($t:tt)*) => { $crate::out::push(format_args!("{}\n", format_args!($($t)*))) };
}
pub(crate) use outln;

/// Appends formatted text to the pending standard output.
pub fn push(args: fmt::Arguments<'_>) {
    let mut sink = STDOUT.lock().unwrap_or_else(|p| p.into_inner());
    let text = escape(&args.to_string());
    sink.text.push_str(&text);
}

/// A failure to write standard output.
#[derive(Debug)]
pub struct OutputError(io::Error);

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write to standard output: {}", self.0)
    }
}

/// Writes the pending standard output and flushes it.
///
/// A command that commits a file calls this first, so that a failing exit status never
/// comes with a new file.
pub fn flush() -> Result<(), OutputError> {
    let mut sink = STDOUT.lock().unwrap_or_else(|p| p.into_inner());
    let text = std::mem::take(&mut sink.text);
    if let Some(captured) = &mut sink.captured {
        captured.push_str(&text);
        return Ok(());
    }
    let mut stdout = io::stdout().lock();
    let result = stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush());
    result.map_err(|e| {
        sink.closed |= e.kind() == io::ErrorKind::BrokenPipe;
        OutputError(e)
    })
}

/// Whether standard output was found closed by its reader.
pub fn closed() -> bool {
    STDOUT.lock().map(|s| s.closed).unwrap_or(true)
}

/// Prints `zipmesh: MESSAGE` on standard error. If even that fails there is nobody to tell,
/// so the error is dropped: the exit status still says what happened.
pub fn error(message: impl fmt::Display) {
    error_line(format_args!("zipmesh: {message}"));
}

/// Prints one line on standard error as it is (control characters escaped).
pub fn error_line(line: impl fmt::Display) {
    let _ = writeln!(io::stderr().lock(), "{}", escape(&line.to_string()));
}

/// The exit status of a run: `code` when standard output was written, otherwise that of the
/// failure (a closed pipe quietly, any other write error with a message).
pub fn finish(code: ExitCode) -> ExitCode {
    match flush() {
        Ok(()) => code,
        Err(e) => failure(&e),
    }
}

/// The exit status for a failure to write standard output.
pub fn failure(e: &OutputError) -> ExitCode {
    if e.0.kind() == io::ErrorKind::BrokenPipe {
        ExitCode::from(CLOSED_PIPE)
    } else {
        error(e);
        ExitCode::from(2)
    }
}

/// `text` with control characters (from file names, say) written as escapes, so that a
/// message cannot move the cursor or clear the terminal; newlines between lines are kept.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() && c != '\n' {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}
