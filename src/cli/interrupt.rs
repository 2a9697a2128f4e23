//! Removing the temporary file of `-o` when the program is interrupted while writing it.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporary file being written, if any.
static PARTIAL: Mutex<Option<PathBuf>> = Mutex::new(None);

/// Records the temporary file being written (`None` once it is renamed or removed).
pub fn partial_file(path: Option<&Path>) {
    if let Ok(mut partial) = PARTIAL.lock() {
        *partial = path.map(Path::to_path_buf);
    }
}

/// On SIGINT, SIGTERM or SIGHUP: remove the temporary file, then exit with 128 plus
/// the signal's number, as the default action's status reads in a shell.
#[cfg(unix)]
pub fn remove_partial_file_on_interrupt() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            if let Ok(mut partial) = PARTIAL.lock()
                && let Some(path) = partial.take()
            {
                let _ = std::fs::remove_file(path);
            }
            std::process::exit(128 + signal);
        }
    });
}

/// Without Unix signals, an interrupt ends the program as it always does.
#[cfg(not(unix))]
pub fn remove_partial_file_on_interrupt() {}
