//! The files a user names: read only if they are regular files, up to a size, each
//! failure a [`FileError`] that names the file as the user gave it.
//!
//! The command line reads scenes, images and `grade`'s files through here, and `grade`
//! ([`crate::grade`]) reads a class's folders the same way.

use crate::compare::read::{ImageFileError, image_named};
use crate::error::escaped;
use crate::render::Image;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;
use thiserror::Error;

/// The largest scene text accepted on standard input, and the largest text file read.
pub const MAX_INPUT: u64 = 256 << 20;

/// Why a file a user named cannot be read. Each message names the file as the user gave
/// it, escaped ([`escaped`]); none starts with `error: `, which the command line adds.
#[derive(Debug, Error)]
pub enum FileError {
    /// The system refused to open or read it.
    #[error("cannot read {shown}: {error}")]
    Cannot {
        /// The file's name, escaped.
        shown: String,
        /// What the system said.
        error: std::io::Error,
    },
    /// It is a folder.
    #[error("{shown} is a folder, not a file")]
    Folder {
        /// The folder's name, escaped.
        shown: String,
    },
    /// It is a pipe, a socket or a device.
    #[error("{shown} is not a regular file (a pipe, socket or device), and only files are read")]
    NotRegular {
        /// The name, escaped.
        shown: String,
    },
    /// It holds more bytes than the reader takes.
    #[error("{shown} is larger than {mib} MiB")]
    TooLarge {
        /// The file's name, escaped.
        shown: String,
        /// The limit, in MiB.
        mib: u64,
    },
    /// It is no image this program reads.
    #[error(transparent)]
    Image(#[from] ImageFileError),
}

/// A path as messages show it.
pub fn shown(path: &Path) -> String {
    escaped(&path.display().to_string())
}

/// A file a user named, opened for reading only if it is a regular file: a FIFO, a
/// socket or a device would block the open or the read, or never end. Opened without
/// blocking, then asked what it is, so that even a FIFO with no writer is an error at
/// once.
pub fn open_regular(path: &Path) -> Result<File, FileError> {
    let cannot = |error: std::io::Error| FileError::Cannot {
        shown: shown(path),
        error,
    };
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
        return Err(FileError::Folder { shown: shown(path) });
    }
    if !kind.is_file() {
        return Err(FileError::NotRegular { shown: shown(path) });
    }
    Ok(file)
}

/// The rest of an open file's bytes, at most `limit`; `path` names it in messages.
pub fn read_all(file: File, path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|error| FileError::Cannot {
            shown: shown(path),
            error,
        })?;
    if bytes.len() as u64 > limit {
        return Err(FileError::TooLarge {
            shown: shown(path),
            mib: limit >> 20,
        });
    }
    Ok(bytes)
}

/// The bytes of the regular file at `path`, at most `limit`.
pub fn read_file(path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    read_all(open_regular(path)?, path, limit)
}

/// Bytes as text: valid UTF-8 (nearly every scene) becomes the String without a copy.
pub fn text_of(bytes: Vec<u8>) -> String {
    String::from_utf8(bytes)
        .unwrap_or_else(|invalid| String::from_utf8_lossy(invalid.as_bytes()).into_owned())
}

/// An image file (a regular file, decoded from the disk as it is read) of at most
/// `max_pixels`; `role` says what it is in messages ("student's image").
pub fn read_image(path: &Path, role: &str, max_pixels: u64) -> Result<Image, FileError> {
    let file = open_regular(path)?;
    Ok(image_named(
        BufReader::new(file),
        max_pixels,
        &shown(path),
        role,
    )?)
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
