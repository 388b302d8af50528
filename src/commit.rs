//! Several output files put in place as one. Inside [`together`], a writer that would rename
//! its finished temporary file over the result ([`write_atomic`], the vector writer) hands
//! the pair over instead ([`defer`]); when the work succeeds every file is renamed into place,
//! each file it replaces kept under a backup name until all are in, so a rename that fails
//! puts every earlier one back. When the work fails nothing is renamed and the temporaries go.
//! Either way the folder holds the old results or the new ones, never a mix: a run that fails
//! over the last good output leaves that output as it was.
//!
//! [`write_atomic`]: crate::render::output::write_atomic

use crate::error::{Error, Result};
use std::cell::RefCell;
use std::path::{Path, PathBuf};

thread_local! {
    /// (temporary, result) pairs of the scope open on this thread.
    static STAGED: RefCell<Option<Vec<(PathBuf, PathBuf)>>> = const { RefCell::new(None) };
}

/// Run `f`, whose results land together when it succeeds (see the module). A scope inside
/// another belongs to the outer one.
pub fn together<T>(f: impl FnOnce() -> Result<T>) -> Result<T> {
    if STAGED.with(|s| s.borrow().is_some()) {
        return f();
    }
    // A signal sets a flag the work checks; the renames themselves finish first.
    let _hold = crate::interrupt::cleanup();
    STAGED.with(|s| *s.borrow_mut() = Some(Vec::new()));
    let r = f();
    let staged = STAGED.with(|s| s.borrow_mut().take()).unwrap_or_default();
    match r {
        Ok(v) => apply(&staged).map(|_| v),
        Err(e) => {
            for (tmp, _) in &staged {
                let _ = std::fs::remove_file(tmp);
            }
            Err(e)
        }
    }
}

/// Leave `tmp` to be renamed to `path` when the open scope ends; false (rename it yourself)
/// when no scope is open on this thread.
pub fn defer(tmp: &Path, path: &Path) -> bool {
    STAGED.with(|s| match s.borrow_mut().as_mut() {
        Some(v) => {
            // The same result written twice reuses its temporary name: the last bytes win. A
            // result written after it was retired is written, not removed.
            v.retain(|(t, p)| !(t.as_os_str().is_empty() && p == path));
            if !v.iter().any(|(t, p)| t == tmp && p == path) {
                v.push((tmp.to_path_buf(), path.to_path_buf()));
            }
            true
        }
        None => false,
    })
}

/// Remove `path`, a result the new ones leave out (the other format of a vector set written
/// again), when the open scope's files land, so the folder never holds an old file beside a
/// new set; at once when no scope is open. Only a regular file is removed.
pub fn retire(path: &Path) -> Result<()> {
    let staged = STAGED.with(|s| match s.borrow_mut().as_mut() {
        Some(v) => {
            // An empty temporary marks a removal; a file this scope writes there instead stays
            // (one backup per path: a write and a removal of it would share one).
            if !v.iter().any(|(_, p)| p == path) {
                v.push((PathBuf::new(), path.to_path_buf()));
            }
            true
        }
        None => false,
    });
    if !staged && std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        std::fs::remove_file(path).map_err(|e| Error::io(path, e))?;
    }
    Ok(())
}

use crate::commit_journal::{backup_of, Journal};

/// Rename every pair into place, or none; a process killed in between leaves a journal the
/// next run in the folder undoes (`commit_journal`).
fn apply(staged: &[(PathBuf, PathBuf)]) -> Result<()> {
    let is_file = |p: &Path| std::fs::symlink_metadata(p).is_ok_and(|m| m.is_file());
    let entries: Vec<(&Path, bool)> = staged
        .iter()
        .filter(|(tmp, path)| !tmp.as_os_str().is_empty() || is_file(path))
        .map(|(_, path)| (path.as_path(), is_file(path)))
        .collect();
    let journal = match Journal::write(&entries) {
        Ok(j) => j,
        Err((at, e)) => {
            for (tmp, _) in staged {
                let _ = std::fs::remove_file(tmp);
            }
            return Err(Error::io(at, e));
        }
    };
    let r = apply_journalled(staged, &journal);
    journal.close();
    r
}

fn apply_journalled(staged: &[(PathBuf, PathBuf)], journal: &Journal) -> Result<()> {
    let mut done: Vec<(&Path, Option<PathBuf>)> = Vec::new();
    let undo = |done: &[(&Path, Option<PathBuf>)], from: usize| {
        for (path, backup) in done.iter().rev() {
            match backup {
                Some(b) => {
                    let _ = std::fs::rename(b, path);
                }
                None => {
                    let _ = std::fs::remove_file(path);
                }
            }
        }
        for (tmp, _) in &staged[from..] {
            let _ = std::fs::remove_file(tmp);
        }
    };
    for (i, (tmp, path)) in staged.iter().enumerate() {
        let retired = tmp.as_os_str().is_empty();
        if retired && !std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
            continue;
        }
        let backup = match std::fs::symlink_metadata(path) {
            Ok(m) if m.is_file() => {
                let b = backup_of(path);
                if let Err(e) = std::fs::rename(path, &b) {
                    undo(&done, i);
                    return Err(Error::io(path, e));
                }
                Some(b)
            }
            _ => None,
        };
        if retired {
            // Moved aside with the replaced files: gone when all land, back if one fails.
            done.push((path, backup));
            continue;
        }
        if let Err(e) = std::fs::rename(tmp, path) {
            if let Some(b) = &backup {
                let _ = std::fs::rename(b, path);
            }
            undo(&done, i);
            return Err(Error::io(path, e));
        }
        done.push((path, backup));
    }
    journal.done();
    for (_, b) in done {
        if let Some(b) = b {
            let _ = std::fs::remove_file(b);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::output::write_atomic;

    fn read(p: &Path) -> String {
        std::fs::read_to_string(p).unwrap()
    }

    /// A scope that fails leaves the old files; one that succeeds replaces them all; a rename
    /// that fails midway puts back every file already replaced.
    #[test]
    fn results_land_together_or_not_at_all() {
        let d = tempfile::tempdir().unwrap();
        let (a, b, c) = (d.path().join("a"), d.path().join("b"), d.path().join("c"));
        for p in [&a, &b, &c] {
            std::fs::write(p, "old").unwrap();
        }
        let r: Result<()> = together(|| {
            write_atomic(&a, b"new")?;
            write_atomic(&b, b"new")?;
            Err(Error::Other("the work failed".into()))
        });
        assert!(r.is_err());
        assert_eq!([read(&a), read(&b), read(&c)], ["old", "old", "old"]);
        together(|| {
            write_atomic(&a, b"new")?;
            write_atomic(&b, b"new")
        })
        .unwrap();
        assert_eq!([read(&a), read(&b), read(&c)], ["new", "new", "old"]);
        // A folder in the way of the last result: the first two go back to what they were.
        let x = d.path().join("x");
        std::fs::create_dir(&x).unwrap();
        std::fs::create_dir(x.join("inside")).unwrap();
        let r = together(|| {
            write_atomic(&a, b"newer")?;
            write_atomic(&c, b"newer")?;
            // Staged by hand: write_atomic itself refuses a folder before the scope ends.
            let t = d.path().join(".x.gbump.tmp1");
            std::fs::write(&t, "newer").unwrap();
            assert!(defer(&t, &x));
            Ok(())
        });
        assert!(r.is_err());
        assert_eq!([read(&a), read(&b), read(&c)], ["new", "new", "old"]);
        let left: Vec<String> = std::fs::read_dir(d.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(".tmp"))
            .collect();
        assert!(left.is_empty(), "temporaries left: {left:?}");
        // A retired file goes when the scope's files land, and stays when the work fails.
        let r: Result<()> = together(|| {
            write_atomic(&a, b"newest")?;
            retire(&c)?;
            Err(Error::Other("the work failed".into()))
        });
        assert!(r.is_err());
        assert_eq!([read(&a), read(&c)], ["new", "old"]);
        together(|| {
            write_atomic(&a, b"newest")?;
            retire(&c)
        })
        .unwrap();
        assert_eq!(read(&a), "newest");
        assert!(!c.exists());
    }
}
