//! The journal of a commit in progress (`commit::apply`): what a process killed between its
//! renames leaves for the next run to undo. Before the first rename, each folder the commit
//! renames into gets `.gbump-commit.<pid>`, naming each result and whether a replaced file
//! waits under its backup name; when every result is in place the journal is renamed to
//! `.gbump-commit.<pid>.done` and the backups go. A later run about to write into the folder
//! (`temp_files` makes each temporary name through [`recover`]) finds the journal of a
//! process that is gone and puts the folder back as it was before that commit, or, past
//! `.done`, finishes removing the backups; so the folder holds one run's files, never a mix.
//! Backups are not temporary names: only their journal removes them.

use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

const JOURNAL: &str = ".gbump-commit.";
const DONE: &str = ".done";

/// Whether process `pid` is running (this one is; without /proc nothing is known to be dead).
pub fn alive(pid: u32) -> bool {
    pid == std::process::id() || !Path::new("/proc/self").exists() || Path::new(&format!("/proc/{pid}")).exists()
}

/// The name a replaced result waits under while process `pid` commits.
fn backup_name(name: &str, pid: u32) -> String {
    format!(".{name}.gbump-old{pid}")
}

/// Where `path`'s replaced file waits during this process's commit.
pub fn backup_of(path: &Path) -> PathBuf {
    let name = path.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(backup_name(&name, std::process::id()))
}

fn journal_of(dir: &Path, pid: u32) -> PathBuf {
    dir.join(format!("{JOURNAL}{pid}"))
}

/// A commit's journals, one per folder it renames into.
pub struct Journal {
    files: Vec<PathBuf>,
}

impl Journal {
    /// Write the journals of a commit of `entries`: (result path, whether a file there will
    /// wait under its backup name). Synced, so a crash after the first rename finds them.
    pub fn write(entries: &[(&Path, bool)]) -> std::io::Result<Journal> {
        let mut by_dir: Vec<(PathBuf, Vec<u8>)> = Vec::new();
        for (path, replaced) in entries {
            let dir = path
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .to_path_buf();
            let name = path.file_name().unwrap_or_default();
            let at = match by_dir.iter().position(|(d, _)| *d == dir) {
                Some(i) => i,
                None => {
                    by_dir.push((dir, Vec::new()));
                    by_dir.len() - 1
                }
            };
            // NUL-separated: a file name may hold any other byte.
            let text = &mut by_dir[at].1;
            text.push(if *replaced { b'B' } else { b'N' });
            text.extend_from_slice(name.as_encoded_bytes());
            text.push(0);
        }
        let mut files = Vec::new();
        for (dir, text) in by_dir {
            let p = journal_of(&dir, std::process::id());
            let mut f = std::fs::File::create(&p)?;
            f.write_all(&text)?;
            f.sync_all()?;
            files.push(p);
        }
        Ok(Journal { files })
    }

    /// Every result is in place: from here a recovery removes the backups, never restores.
    pub fn done(&self) {
        for p in &self.files {
            let _ = std::fs::rename(p, done_name(p));
        }
    }

    /// The commit is over (its backups removed, or it was undone).
    pub fn close(self) {
        for p in &self.files {
            let _ = std::fs::remove_file(p);
            let _ = std::fs::remove_file(done_name(p));
        }
    }
}

fn done_name(p: &Path) -> PathBuf {
    let mut s = p.as_os_str().to_owned();
    s.push(DONE);
    PathBuf::from(s)
}

/// Undo or finish, in `dir`, the commits of processes that are gone (see the module); once
/// per folder per process.
pub fn recover(dir: &Path) {
    static SEEN: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);
    let key = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
    if !SEEN
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .get_or_insert_with(HashSet::new)
        .insert(key)
    {
        return;
    }
    recover_now(dir);
}

/// [`recover`], every time.
pub fn recover_now(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let Some(rest) = name.strip_prefix(JOURNAL) else {
            continue;
        };
        let (pid, done) = match rest.strip_suffix(DONE) {
            Some(p) => (p, true),
            None => (rest, false),
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        if alive(pid) {
            continue;
        }
        let Ok(text) = std::fs::read(e.path()) else {
            continue;
        };
        for entry in text.split(|&b| b == 0).filter(|x| !x.is_empty()) {
            // SAFETY of the encoding: written by `Journal::write` from an OsStr on this system.
            let name = unsafe { std::ffi::OsStr::from_encoded_bytes_unchecked(&entry[1..]) };
            let (path, backup) = (dir.join(name), dir.join(backup_name(&name.to_string_lossy(), pid)));
            match (done, entry[0]) {
                (true, _) => {
                    let _ = std::fs::remove_file(&backup);
                }
                (false, b'B') => {
                    // Not yet moved aside, or moved and maybe replaced: the old file goes back.
                    if backup.exists() {
                        let _ = std::fs::rename(&backup, &path);
                    }
                }
                // A result that had no file before the commit: gone again.
                (false, _) => {
                    if std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
                        let _ = std::fs::remove_file(&path);
                    }
                }
            }
        }
        let _ = std::fs::remove_file(e.path());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(p: &Path) -> String {
        std::fs::read_to_string(p).unwrap_or_else(|_| "(none)".into())
    }

    /// A commit killed after its first rename (pid 0 is never a running process): the file it
    /// replaced comes back from its backup, one it had not reached yet stays, one it created
    /// goes; the journal goes; files it did not name stay.
    #[test]
    fn a_killed_commit_is_undone() {
        let d = tempfile::tempdir().unwrap();
        let p = |n: &str| d.path().join(n);
        std::fs::write(p("a"), "new a").unwrap();
        std::fs::write(p(&backup_name("a", 0)), "old a").unwrap();
        std::fs::write(p("b"), "old b").unwrap();
        std::fs::write(p("c"), "new c").unwrap();
        std::fs::write(p("mine"), "user's").unwrap();
        std::fs::write(p(".gbump-commit.0"), b"Ba\0Bb\0Nc\0").unwrap();
        recover_now(d.path());
        assert_eq!(
            [read(&p("a")), read(&p("b")), read(&p("c")), read(&p("mine"))],
            ["old a", "old b", "(none)", "user's"]
        );
        let left: Vec<_> = std::fs::read_dir(d.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(left.len(), 3, "{left:?}");
    }

    /// Past `.done` every result is in: the backups go and the results stay.
    #[test]
    fn a_commit_killed_after_its_renames_is_finished() {
        let d = tempfile::tempdir().unwrap();
        let p = |n: &str| d.path().join(n);
        std::fs::write(p("a"), "new a").unwrap();
        std::fs::write(p(&backup_name("a", 0)), "old a").unwrap();
        std::fs::write(p(".gbump-commit.0.done"), b"Ba\0").unwrap();
        recover_now(d.path());
        assert_eq!(read(&p("a")), "new a");
        assert_eq!(std::fs::read_dir(d.path()).unwrap().count(), 1);
    }

    /// A running process's journal (this one's) is left alone.
    #[test]
    fn a_live_commit_is_left_alone() {
        let d = tempfile::tempdir().unwrap();
        let j = Journal::write(&[(&d.path().join("a"), false)]).unwrap();
        std::fs::write(d.path().join("a"), "new").unwrap();
        recover_now(d.path());
        assert_eq!(read(&d.path().join("a")), "new");
        j.close();
        assert_eq!(std::fs::read_dir(d.path()).unwrap().count(), 1);
    }
}
