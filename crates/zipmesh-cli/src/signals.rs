//! `SIGINT` and `SIGTERM`: remove the temporary files of atomic writes, then end by the
//! signal (exit status 130 or 143 in a shell), so an interrupted write leaves nothing.

/// Starts the thread that waits for the signals; without it the default action runs.
#[cfg(unix)]
pub fn install() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            zipmesh::io::remove_temporaries();
            let _ = signal_hook::low_level::emulate_default_handler(signal);
            std::process::exit(128 + signal);
        }
    });
}

/// Elsewhere the default action runs.
#[cfg(not(unix))]
pub fn install() {}
