//! Standard input and output, and the files the command line reads: the scene text in,
//! the image or the text out, and files that students uploaded.

use super::Failure;
use std::fs::File;
use std::io::{IsTerminal, Read};
use std::path::Path;

/// The largest scene text accepted on standard input, and the largest text file read.
pub const MAX_INPUT: u64 = 256 << 20;

/// The scene text from standard input, at most `MAX_INPUT` bytes.
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
    let mut text = Vec::with_capacity(stdin_file_size().min(MAX_INPUT + 1) as usize);
    if let Err(error) = stdin.take(MAX_INPUT + 1).read_to_end(&mut text) {
        return Err(Failure(
            format!("error: cannot read standard input: {error}"),
            2,
        ));
    }
    if text.len() as u64 > MAX_INPUT {
        let mib = MAX_INPUT >> 20;
        return Err(super::scene_failure(format!(
            "the scene is larger than {mib} MiB, the most this program reads"
        )));
    }
    Ok(text_of(text))
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

/// Bytes as text: valid UTF-8 (nearly every scene) becomes the String without a copy.
pub fn text_of(bytes: Vec<u8>) -> String {
    String::from_utf8(bytes)
        .unwrap_or_else(|invalid| String::from_utf8_lossy(invalid.as_bytes()).into_owned())
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
        Err(error) => Err(Failure(
            format!("error: cannot write to standard output: {error}"),
            2,
        )),
    }
}

/// A file a user named, opened for reading only if it is a regular file: a FIFO, a
/// socket or a device would block the open or the read, or never end. Opened without
/// blocking, then asked what it is, so that even a FIFO with no writer is an error at
/// once. `shown` names it in messages.
pub fn open_regular(path: &Path) -> Result<File, Failure> {
    let shown = legacy_rt::error::escaped(&path.display().to_string());
    let cannot = |error: std::io::Error| Failure(format!("error: cannot read {shown}: {error}"), 2);
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(cannot)?;
    let kind = file.metadata().map_err(cannot)?.file_type();
    if kind.is_dir() {
        return Err(Failure(
            format!("error: {shown} is a folder, not a file"),
            2,
        ));
    }
    if !kind.is_file() {
        return Err(Failure(
            format!(
                "error: {shown} is not a regular file (a pipe, socket or device), and only \
                 files are read"
            ),
            2,
        ));
    }
    Ok(file)
}

/// The rest of an open file's bytes, at most `limit`; `path` names it in messages.
pub fn read_all(file: File, path: &Path, limit: u64) -> Result<Vec<u8>, Failure> {
    let shown = legacy_rt::error::escaped(&path.display().to_string());
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|error| Failure(format!("error: cannot read {shown}: {error}"), 2))?;
    if bytes.len() as u64 > limit {
        let mib = limit >> 20;
        return Err(Failure(
            format!("error: {shown} is larger than {mib} MiB"),
            2,
        ));
    }
    Ok(bytes)
}

/// Whether two names are one file: the same device and inode, so that a hard link, a
/// symbolic link or another spelling of the path counts. A name that does not exist is
/// no file.
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        #[cfg(unix)]
        (Ok(a), Ok(b)) => {
            use std::os::unix::fs::MetadataExt;
            (a.dev(), a.ino()) == (b.dev(), b.ino())
        }
        #[cfg(not(unix))]
        (Ok(_), Ok(_)) => match (a.canonicalize(), b.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        },
        _ => false,
    }
}
