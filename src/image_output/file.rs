//! Writing an image to a named file without destroying what the name stood for.
//!
//! `-o FILE` must either leave a complete image at FILE or leave FILE as it was. How that
//! is done depends on what FILE is, so [`OutputFile::check`] looks before the render and
//! [`OutputFile::write`] writes after it:
//!
//! * a new name, or an existing regular file with no other hard link: the image is written
//!   to a temporary file beside it and renamed over it, so a failure or an interrupt
//!   never leaves half an image; an existing file keeps its permissions and owner;
//! * a symbolic link: the same, at the file the link points to (the link stays);
//! * a regular file with other hard links: rewritten in place, so the links stay links
//!   (as the shell's `>` does);
//! * a device, a FIFO or a socket (`/dev/null`, `/dev/stdout`, a named pipe): opened and
//!   written in place, never replaced by a regular file;
//! * a read-only file or a folder: an error, and nothing is touched.
//!
//! The format comes from the name: PNG for `.png`, binary PPM for `.ppm`, `.pnm` or no
//! extension (and for devices and pipes); any other extension is an error rather than a
//! PPM under a misleading name.

use super::Format;
use std::fs::{self, File, Metadata, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};

/// Where an image will go, decided before rendering.
#[derive(Debug)]
pub struct OutputFile {
    /// The name as the user gave it, for messages.
    pub shown: String,
    /// The format the name asks for.
    pub format: Format,
    how: How,
}

#[derive(Debug)]
enum How {
    /// Open the existing path and write into it (devices, pipes, hard-linked files).
    InPlace(PathBuf),
    /// Write a temporary file in the same folder and rename it to `path`, copying the
    /// permissions of `existing` if there was a file.
    Replace {
        path: PathBuf,
        existing: Option<Metadata>,
    },
}

/// Why `-o FILE` cannot be used, found before anything is rendered or written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// An extension that names neither format.
    #[error(
        "cannot tell the image format from the name `{0}`: the output is PNG for a name \
         ending in .png and binary PPM for .ppm, .pnm or no extension"
    )]
    Extension(String),
    /// A folder where a file was expected.
    #[error("`{0}` is a folder; give a file name")]
    Folder(String),
    /// A file without write permission: replacing it would defeat the permission.
    #[error("`{0}` is read-only; this program does not replace it")]
    ReadOnly(String),
    /// Anything the system refused.
    #[error("cannot write `{0}`: {1}")]
    Io(String, io::Error),
}

impl OutputFile {
    /// Looks at `path` and decides how to write to it.
    pub fn check(path: &Path) -> Result<OutputFile, OutputError> {
        let shown = path.display().to_string();
        let io_error = |error| OutputError::Io(shown.clone(), error);
        // Through symbolic links: the link's target is what the user means.
        let existing = match fs::metadata(path) {
            Ok(metadata) => Some(metadata),
            Err(error) if error.kind() == io::ErrorKind::NotFound => None,
            Err(error) => return Err(io_error(error)),
        };
        let special = existing
            .as_ref()
            .is_some_and(|m| !m.is_file() && !m.is_dir());
        let format = match path.extension() {
            Some(ext) if ext.eq_ignore_ascii_case("png") => Format::Png,
            Some(ext) if ext.eq_ignore_ascii_case("ppm") || ext.eq_ignore_ascii_case("pnm") => {
                Format::Ppm
            }
            None => Format::Ppm,
            Some(_) if special => Format::Ppm,
            Some(_) => return Err(OutputError::Extension(shown)),
        };
        let how = match existing {
            Some(m) if m.is_dir() => return Err(OutputError::Folder(shown)),
            Some(_) if special => How::InPlace(path.to_path_buf()),
            Some(m) if m.permissions().readonly() => return Err(OutputError::ReadOnly(shown)),
            Some(m) if links(&m) > 1 => How::InPlace(path.to_path_buf()),
            Some(m) => How::Replace {
                path: fs::canonicalize(path).map_err(io_error)?,
                existing: Some(m),
            },
            // A dangling symbolic link: writing through it creates its target.
            None if fs::symlink_metadata(path).is_ok() => How::InPlace(path.to_path_buf()),
            None => How::Replace {
                path: path.to_path_buf(),
                existing: None,
            },
        };
        Ok(OutputFile { shown, format, how })
    }

    /// Writes `pieces` one after the other, whole or not at all where the target allows
    /// it. `temporary` is told of the temporary file ([`Temporary`]), so that an
    /// interrupt handler can remove it.
    pub fn write(
        &self,
        pieces: &[&[u8]],
        temporary: impl Fn(&Path, Temporary),
    ) -> Result<(), OutputError> {
        let io_error = |error| OutputError::Io(self.shown.clone(), error);
        match &self.how {
            How::InPlace(path) => write_in_place(path, pieces).map_err(io_error),
            How::Replace { path, existing } => {
                let partial = match create_beside(path, &temporary) {
                    Ok(partial) => partial,
                    // A folder we may not create in, holding a file we may write: write it
                    // as the shell would.
                    Err(error)
                        if error.kind() == io::ErrorKind::PermissionDenied
                            && existing.is_some() =>
                    {
                        return write_in_place(path, pieces).map_err(io_error);
                    }
                    Err(error) => return Err(io_error(error)),
                };
                let temporary_path = partial.1.clone();
                let result = fill_and_rename(partial, path, pieces, existing.as_ref());
                temporary(&temporary_path, Temporary::Gone);
                result.map_err(io_error)
            }
        }
    }
}

/// Replaces (or creates) the file at `path` with `bytes`, whole or not at all: written
/// to a new file beside it, then renamed over it. Whatever `path` was (a symbolic or hard
/// link, a file of other permissions) is replaced, never written through: what `grade`
/// needs for the files of its report folder. `temporary` is told of the temporary file
/// as [`OutputFile::write`] tells it.
pub fn replace(path: &Path, bytes: &[u8], temporary: impl Fn(&Path, Temporary)) -> io::Result<()> {
    let partial = create_beside(path, &temporary)?;
    let temporary_path = partial.1.clone();
    let result = fill_and_rename(partial, path, &[bytes], None);
    temporary(&temporary_path, Temporary::Gone);
    result
}

/// What becomes of a temporary file, as an interrupt handler needs to hear it: told
/// before the file is created and after, an interrupt that comes in between is not
/// missed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Temporary {
    /// It is about to be created (a handler may hold this off while it cleans up).
    Creating,
    /// The attempt to create it is over (it exists, or it could not be created).
    Created,
    /// It is renamed over its target, removed, or was never created.
    Gone,
}

/// Fills the new file `partial` and renames it to `path`; removed if that fails.
fn fill_and_rename(
    (file, partial): (File, PathBuf),
    path: &Path,
    pieces: &[&[u8]],
    existing: Option<&Metadata>,
) -> io::Result<()> {
    let result = fill(file, pieces, existing).and_then(|()| fs::rename(&partial, path));
    if result.is_err() {
        let _ = fs::remove_file(&partial);
    }
    result
}

/// The number of hard links to a file (1 where the system does not say).
fn links(metadata: &Metadata) -> u64 {
    #[cfg(unix)]
    {
        std::os::unix::fs::MetadataExt::nlink(metadata)
    }
    #[cfg(not(unix))]
    {
        let _ = metadata;
        1
    }
}

fn write_in_place(path: &Path, pieces: &[&[u8]]) -> io::Result<()> {
    let mut file = OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .open(path)?;
    super::write(&mut file, pieces)
}

/// A new, empty file in the folder of `path`, named after it and this process, that
/// did not exist before (so that no other file is ever overwritten by it); `temporary` is
/// told of each name tried.
fn create_beside(
    path: &Path,
    temporary: &impl Fn(&Path, Temporary),
) -> io::Result<(File, PathBuf)> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut attempt = 0;
    loop {
        let partial = folder.join(format!(".{name}.{}-{attempt}.partial", std::process::id()));
        temporary(&partial, Temporary::Creating);
        let created = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&partial);
        temporary(&partial, Temporary::Created);
        match created {
            Ok(file) => return Ok((file, partial)),
            Err(error) => {
                temporary(&partial, Temporary::Gone);
                match error.kind() == io::ErrorKind::AlreadyExists && attempt < 100 {
                    true => attempt += 1,
                    false => return Err(error),
                }
            }
        }
    }
}

/// Writes the pieces, gives the file the permissions and owner of the file it replaces,
/// and makes sure the bytes are on disk before the rename makes them visible.
fn fill(mut file: File, pieces: &[&[u8]], existing: Option<&Metadata>) -> io::Result<()> {
    super::write(&mut file, pieces)?;
    if let Some(existing) = existing {
        file.set_permissions(existing.permissions())?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            // Only root can give a file away; anyone else keeps their own files' owner.
            let _ = std::os::unix::fs::fchown(&file, Some(existing.uid()), Some(existing.gid()));
        }
    }
    file.sync_all()
}
