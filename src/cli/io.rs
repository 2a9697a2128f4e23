//! Standard input and output: the scene text in, the image or the text out (the files a
//! user names are read through `legacy_rt::files`).

use super::Failure;
use std::io::{IsTerminal, Read};

/// The scene text from standard input, at most `legacy_rt::files::MAX_INPUT` bytes.
pub fn read_scene() -> Result<String, Failure> {
    let stdin = std::io::stdin();
    if stdin.is_terminal() {
        super::say(
            "legacy-rt: reading the scene from the terminal; end it with Ctrl-D, \
             or run: legacy-rt < scene.txt > image.ppm",
        );
    }
    // A file's own size, so that its bytes are read into one buffer of that size rather
    // than a buffer doubled past it (a 52 MB scene took 64 MiB).
    let mut text =
        Vec::with_capacity(stdin_file_size().min(legacy_rt::files::MAX_INPUT + 1) as usize);
    if let Err(error) = stdin
        .take(legacy_rt::files::MAX_INPUT + 1)
        .read_to_end(&mut text)
    {
        return Err(Failure::other(format!(
            "cannot read standard input: {error}"
        )));
    }
    if text.len() as u64 > legacy_rt::files::MAX_INPUT {
        let mib = legacy_rt::files::MAX_INPUT >> 20;
        return Err(Failure::scene(format!(
            "the scene is larger than {mib} MiB, the most this program reads"
        )));
    }
    Ok(legacy_rt::files::text_of(text))
}

/// The size of the regular file on standard input, 0 for anything else (a pipe, a
/// terminal) or where it cannot be told.
fn stdin_file_size() -> u64 {
    #[cfg(target_os = "linux")]
    {
        // The descriptor's own metadata, through /proc (no unsafe fstat needed).
        match std::fs::metadata("/proc/self/fd/0") {
            Ok(own) if own.is_file() => own.len(),
            _ => 0,
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        0
    }
}

/// The file standard input reads, as the reports' commands name it: relative to the
/// current folder where it is inside it; `None` for a pipe or a terminal, or where the
/// system does not say.
pub fn stdin_name() -> Option<String> {
    #[cfg(target_os = "linux")]
    {
        let path = std::fs::read_link("/proc/self/fd/0").ok()?;
        if !std::fs::metadata(&path).ok()?.is_file() {
            return None;
        }
        let here = std::env::current_dir().ok()?;
        let shown = path.strip_prefix(&here).unwrap_or(&path);
        Some(shown.display().to_string())
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}

/// Writes `bytes` to standard output. A standard output closed at start is /dev/null
/// (Rust's runtime opens it there) and takes the bytes as `> /dev/null` does; one that
/// fails a write is an error that says so.
pub fn emit_to_stdout(bytes: &[u8]) -> Result<(), Failure> {
    emit_pieces_to_stdout(&[bytes])
}

/// Writes `pieces` to standard output one after the other, as [`emit_to_stdout`].
pub fn emit_pieces_to_stdout(pieces: &[&[u8]]) -> Result<(), Failure> {
    match legacy_rt::image_output::write(&mut std::io::stdout().lock(), pieces) {
        Ok(()) => Ok(()),
        // The reader went away (`| head`): end quietly.
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(error) => Err(Failure::other(format!(
            "cannot write to standard output: {error}"
        ))),
    }
}
