//! Temporary names. Everything gbump writes goes to `<name>.gbump.tmp<pid>` first and is renamed
//! into place, so a killed run leaves only such names behind; any run that later writes into
//! the same folder removes those whose process is gone.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Every temporary name this process has made ([`temp_path`], [`hidden_temp_path`]), so that a forced exit (a signal that cannot wait for the run's own
/// cleanup) removes what is left under them. A replaced result's backup (`commit`) is not
/// among them: removing it mid-commit would lose the old result.
static MADE: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

/// The temporary sibling of `path` for this process.
pub fn temp_path(path: &Path) -> PathBuf {
    named(path, "")
}

/// [`temp_path`] as a hidden file (`.NAME.tmpPID`): a result written beside the user's own
/// files (an output file, a wave file), out of a plain listing while it is written.
pub fn hidden_temp_path(path: &Path) -> PathBuf {
    named(path, ".")
}

/// What ends every temporary name gbump makes, before the process id: distinct enough that
/// no one else's file is taken for one (a plain `.tmp<digits>` was, and removed).
const MARK: &str = ".gbump.tmp";

fn named(path: &Path, prefix: &str) -> PathBuf {
    // A commit a killed run left half done in this folder is undone before anything new is
    // written into it.
    if let Some(dir) = path.parent() {
        crate::commit_journal::recover(if dir.as_os_str().is_empty() { Path::new(".") } else { dir });
    }
    let name = path.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let tmp = path.with_file_name(format!("{prefix}{name}{MARK}{}", std::process::id()));
    register(&tmp);
    tmp
}

/// Note `tmp`, a temporary name of this process, for [`remove_own`].
fn register(tmp: &Path) {
    let mut set = MADE.lock().unwrap_or_else(|e| e.into_inner());
    set.get_or_insert_with(HashSet::new)
        .insert(std::path::absolute(tmp).unwrap_or_else(|_| tmp.to_path_buf()));
}

/// Remove whatever is still under a temporary name this process made (those renamed into
/// place are gone from there already); returns how many were removed. For an exit that skips
/// the run's own cleanup: the next run in the folder would remove them anyway, but a dump's
/// are hundreds of megabytes.
pub fn remove_own() -> usize {
    remove_own_under(Path::new("/"))
}

/// [`remove_own`] from a path that may have interrupted this process's own use of the list
/// (an allocation that failed while a name was being added): a list that is held is left, for
/// the next run in the folder to clear, rather than waited for forever.
pub fn remove_own_unless_held() -> usize {
    match lock_unless_held(&MADE) {
        Some(g) => remove_listed(g.clone().unwrap_or_default(), Path::new("/")),
        None => 0,
    }
}

/// `m`'s guard, waiting a few milliseconds for it at most (poisoned or not): a thread that
/// holds it for a moment lets go, one stopped for good (out of memory while adding to it)
/// never does, and the caller goes on without it.
pub fn lock_unless_held<T>(m: &Mutex<T>) -> Option<std::sync::MutexGuard<'_, T>> {
    for _ in 0..50 {
        match m.try_lock() {
            Ok(g) => return Some(g),
            Err(std::sync::TryLockError::Poisoned(p)) => return Some(p.into_inner()),
            Err(std::sync::TryLockError::WouldBlock) => std::thread::sleep(std::time::Duration::from_millis(1)),
        }
    }
    None
}

/// [`remove_own`] for the names under `dir` alone.
pub fn remove_own_under(dir: &Path) -> usize {
    let set = MADE.lock().unwrap_or_else(|e| e.into_inner()).clone().unwrap_or_default();
    remove_listed(set, dir)
}

fn remove_listed(set: HashSet<PathBuf>, dir: &Path) -> usize {
    set.iter()
        .filter(|p| p.starts_with(dir))
        .filter(|p| {
            // Renamed aside first: a thread renaming the name into place at this moment wins
            // or loses that race whole, and a finished result is never emptied.
            // Itself a temporary name of this process, so a removal that fails now (a tool
            // still writing into the folder) is cleared by the next run in the folder.
            let aside = p.with_file_name(format!(
                "{}.del{MARK}{}",
                p.file_name().unwrap_or_default().to_string_lossy(),
                std::process::id()
            ));
            if std::fs::rename(p, &aside).is_err() {
                return false;
            }
            match std::fs::symlink_metadata(&aside) {
                Ok(m) if m.is_dir() => std::fs::remove_dir_all(&aside).is_ok(),
                Ok(_) => std::fs::remove_file(&aside).is_ok(),
                Err(_) => false,
            }
        })
        .count()
}

/// The process id a temporary name belongs to, if `name` is one gbump made.
fn owner(name: &str) -> Option<u32> {
    let (_, pid) = name.rsplit_once(MARK)?;
    if pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    pid.parse().ok()
}

use crate::commit_journal::alive;

/// Remove the temporary files and folders of dead processes in `dir`, and in its subfolders
/// down to `depth` levels, after undoing their half-done commits. Returns how many were
/// removed.
pub fn clean_stale(dir: &Path, depth: u32) -> usize {
    crate::commit_journal::recover(dir);
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let mut removed = 0;
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let is_dir = e.file_type().is_ok_and(|t| t.is_dir());
        match owner(&name) {
            Some(pid) if !alive(pid) => {
                let gone = if is_dir {
                    std::fs::remove_dir_all(e.path())
                } else {
                    std::fs::remove_file(e.path())
                };
                removed += gone.is_ok() as usize;
            }
            Some(_) => {}
            None if is_dir && depth > 0 => removed += clean_stale(&e.path(), depth - 1),
            None => {}
        }
    }
    removed
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What is still under a handed-out temporary name goes; what was renamed into place,
    /// and files this process did not name, stay.
    #[test]
    fn a_forced_exit_removes_this_processs_temporary_files() {
        let dir = tempfile::tempdir().unwrap();
        let (left, kept, other) = (
            dir.path().join("left.bin"),
            dir.path().join("kept.bin"),
            dir.path().join("other.gbump.tmp1"),
        );
        let t = temp_path(&left);
        std::fs::write(&t, b"partial").unwrap();
        let folder = temp_path(&dir.path().join("sets"));
        std::fs::create_dir_all(folder.join("inner")).unwrap();
        let k = temp_path(&kept);
        std::fs::write(&k, b"done").unwrap();
        std::fs::rename(&k, &kept).unwrap();
        std::fs::write(&other, b"not ours").unwrap();
        assert_eq!(remove_own_under(dir.path()), 2);
        assert!(!t.exists() && !folder.exists(), "a temporary file or folder was left");
        assert!(kept.exists() && other.exists(), "a finished file or another's was removed");
    }

    #[test]
    fn only_names_of_dead_processes_are_removed() {
        let d = tempfile::tempdir().unwrap();
        let mine = temp_path(&d.path().join("a.bin"));
        std::fs::write(&mine, b"x").unwrap();
        // pid 0 is never a user process: its temporary files are stale.
        std::fs::write(d.path().join("b.bin.gbump.tmp0"), b"x").unwrap();
        std::fs::create_dir_all(d.path().join("sub/build_1.gbump.tmp0/obj")).unwrap();
        std::fs::write(d.path().join("keep.tmpfile"), b"x").unwrap();
        // A user's own names that merely end in `.tmp<digits>` are not gbump's.
        std::fs::create_dir_all(d.path().join("thesis.tmp999999")).unwrap();
        std::fs::write(d.path().join("thesis.tmp999999/chapter1.tex"), b"x").unwrap();
        std::fs::write(d.path().join("draft.tmp0"), b"x").unwrap();
        assert_eq!(clean_stale(d.path(), 2), 2);
        assert!(mine.exists());
        assert!(d.path().join("keep.tmpfile").exists());
        assert!(!d.path().join("sub/build_1.gbump.tmp0").exists());
        assert!(d.path().join("thesis.tmp999999/chapter1.tex").exists() && d.path().join("draft.tmp0").exists());
    }
}
