//! Removing the temporary files of `-o` and of `grade`'s report when the program is
//! interrupted while writing them.

use legacy_rt::image_output::file::Temporary;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporary files that exist or are being created (several at once: `grade` writes
/// a report's images on every core), how many are being created, and whether an
/// interrupt came.
struct Partial {
    files: Vec<PathBuf>,
    creating: usize,
    interrupted: bool,
}

static PARTIAL: Mutex<Partial> = Mutex::new(Partial {
    files: Vec::new(),
    creating: 0,
    interrupted: false,
});

/// Hears what becomes of a temporary file. Once an interrupt came, a file about to be
/// created is not: its thread waits for the exit.
pub fn partial_file(path: &Path, what: Temporary) {
    let Ok(mut partial) = PARTIAL.lock() else {
        return;
    };
    match what {
        Temporary::Creating if partial.interrupted => {
            drop(partial);
            loop {
                std::thread::park();
            }
        }
        Temporary::Creating => {
            partial.files.push(path.to_path_buf());
            partial.creating += 1;
        }
        Temporary::Created => partial.creating -= 1,
        Temporary::Gone => partial.files.retain(|p| p != path),
    }
}

/// On SIGINT, SIGTERM or SIGHUP: once no temporary file is half-way created, remove them
/// all, then exit with 128 plus the signal's number, as the default action's status reads
/// in a shell.
#[cfg(unix)]
pub fn remove_partial_file_on_interrupt() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        let Some(signal) = signals.forever().next() else {
            return;
        };
        loop {
            if let Ok(mut partial) = PARTIAL.lock() {
                partial.interrupted = true;
                if partial.creating == 0 {
                    for path in partial.files.drain(..) {
                        let _ = std::fs::remove_file(path);
                    }
                    // Held to the exit: no file is registered after the list is emptied.
                    std::process::exit(128 + signal);
                }
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
    });
}

/// Without Unix signals, an interrupt ends the program as it always does.
#[cfg(not(unix))]
pub fn remove_partial_file_on_interrupt() {}
