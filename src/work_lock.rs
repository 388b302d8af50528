//! One gbump run per work folder. Two runs sharing a folder would link, rename and delete
//! each other's half-built files; the second one waits, saying who holds the folder. The lock
//! is an OS file lock, so a killed holder releases it at once. The holder also clears what
//! killed runs left behind (temporary files, half-built caches).

use crate::error::{Error, Result};
use std::fs::{File, TryLockError};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

pub const LOCK_NAME: &str = ".gbump.lock";

/// Held for as long as the value lives.
pub struct WorkLock {
    _file: File,
    pub dir: PathBuf,
}

impl WorkLock {
    /// Lock `dir` (created if missing) for the command `what`; waits while another run holds it.
    pub fn acquire(dir: &Path, what: &str) -> Result<WorkLock> {
        let path = dir.join(LOCK_NAME);
        // A run that fails removes a work folder it made, lock file and all
        // (`output::remove_made_folders`): a lock then taken on the removed file is no lock,
        // so it is taken again on the file at the path.
        loop {
            let file = WorkLock::lock_file(dir, &path)?;
            if still_at(&file, &path) {
                return WorkLock::hold(file, dir, what);
            }
        }
    }

    /// `path` opened (created if missing, its folder too) and locked, waiting while another
    /// run holds it.
    fn lock_file(dir: &Path, path: &Path) -> Result<File> {
        crate::render::output::make_folder(dir)?;
        let mut file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(path)
            .map_err(|e| {
                // A folder, or a link to nowhere or to itself, in the lock's place: the user
                // never named that path, so the message must. Anything else (permissions, a
                // full disk) is said as it is.
                let dangling = e.kind() == std::io::ErrorKind::NotFound && path.symlink_metadata().is_ok();
                let in_place = e.kind() == std::io::ErrorKind::IsADirectory || e.raw_os_error() == Some(libc::ELOOP) || dangling;
                if in_place {
                    not_a_lock(dir, path, e)
                } else {
                    Error::io(path, e)
                }
            })?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let mut holder = String::new();
                let _ = file.read_to_string(&mut holder);
                let holder = holder.trim();
                eprintln!(
                    "waiting for {}: in use by {} (another gbump run; it is released when that run ends)",
                    dir.display(),
                    if holder.is_empty() { "another process" } else { holder }
                );
                file.lock().map_err(|e| Error::io(path, e))?;
            }
            Err(TryLockError::Error(e)) => return Err(Error::io(path, e)),
        }
        Ok(file)
    }

    /// The lock held: the holder written into it, what killed runs left cleared.
    fn hold(mut file: File, dir: &Path, what: &str) -> Result<WorkLock> {
        let me = format!("pid {}: {what}\n", std::process::id());
        let _ = file
            .set_len(0)
            .and_then(|_| file.rewind())
            .and_then(|_| file.write_all(me.as_bytes()));
        crate::temp_files::clean_stale(dir, 4);
        Ok(WorkLock {
            _file: file,
            dir: dir.to_path_buf(),
        })
    }
}

/// The error for a lock file at `path` that cannot be opened as one (a folder, a link to
/// nowhere, a file without permission): it names the work folder's lock, which the user
/// never gave, and says to remove it.
fn not_a_lock(dir: &Path, path: &Path, e: std::io::Error) -> Error {
    Error::Other(format!(
        "{}: the work folder's lock file ({LOCK_NAME}, which gbump keeps in its work folder {}) cannot be opened: {e}\n  fix: remove it (rm -rf {}) when no gbump run uses this work folder, or give another --work",
        path.display(),
        dir.display(),
        crate::shell::quoted(&path.display().to_string())
    ))
}

/// Whether `file` is still the file at `path` (not removed, nor replaced, since it was opened).
#[cfg(unix)]
fn still_at(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    let id = |m: std::fs::Metadata| (m.dev(), m.ino());
    matches!((file.metadata().map(id), std::fs::metadata(path).map(id)), (Ok(a), Ok(b)) if a == b)
}

#[cfg(not(unix))]
fn still_at(_file: &File, _path: &Path) -> bool {
    true
}
