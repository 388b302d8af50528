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

/// A process as journals name it: its pid and its start time (`interrupt::started`; 0 where
/// the process table cannot be read), so a later process that got the same pid (a container
/// whose entrypoint is always pid 7) is not taken for the one that wrote the journal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Tag {
    pid: u32,
    start: u64,
}

impl Tag {
    fn own() -> Tag {
        static OWN: std::sync::OnceLock<Tag> = std::sync::OnceLock::new();
        *OWN.get_or_init(|| {
            let pid = std::process::id();
            Tag {
                pid,
                start: crate::interrupt::started(pid).unwrap_or(0),
            }
        })
    }

    fn parse(s: &str) -> Option<Tag> {
        let (pid, start) = s.split_once('-')?;
        Some(Tag {
            pid: pid.parse().ok()?,
            start: start.parse().ok()?,
        })
    }

    /// Whether the process that wrote a journal with this tag still runs.
    fn alive(self) -> bool {
        if self == Tag::own() {
            return true;
        }
        if self.start == 0 {
            return self.pid != std::process::id() && alive(self.pid);
        }
        crate::interrupt::running(self.pid, Some(self.start))
    }
}

impl std::fmt::Display for Tag {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}-{}", self.pid, self.start)
    }
}

/// The name a replaced result waits under while the process of `tag` commits.
fn backup_name(name: &str, tag: Tag) -> String {
    format!(".{name}.gbump-old{tag}")
}

/// Where `path`'s replaced file waits during this process's commit.
pub fn backup_of(path: &Path) -> PathBuf {
    let name = path.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(backup_name(&name, Tag::own()))
}

fn journal_of(dir: &Path, tag: Tag) -> PathBuf {
    dir.join(format!("{JOURNAL}{tag}"))
}

/// A commit's journals, one per folder it renames into.
pub struct Journal {
    files: Vec<PathBuf>,
}

impl Journal {
    /// Write the journals of a commit of `entries`: (result path, whether a file there will
    /// wait under its backup name). Synced, so a crash after the first rename finds them. On
    /// failure the journals already written are removed, and the error names the one that
    /// failed.
    pub fn write(entries: &[(&Path, bool)]) -> std::result::Result<Journal, (PathBuf, std::io::Error)> {
        let mut by_dir: Vec<(PathBuf, Vec<u8>)> = Vec::new();
        for (path, replaced) in entries {
            let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
            // One folder however it is spelled (`out`, `./out`, `/abs/out`): two journals of
            // one name would have the second overwrite the first.
            let dir = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
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
        let mut journal = Journal { files: Vec::new() };
        for (dir, text) in by_dir {
            let p = journal_of(&dir, Tag::own());
            let written = std::fs::File::create(&p).and_then(|mut f| {
                f.write_all(&text)?;
                f.sync_all()
            });
            if let Err(e) = written {
                let _ = std::fs::remove_file(&p);
                journal.close();
                return Err((p, e));
            }
            journal.files.push(p);
        }
        Ok(journal)
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

/// Whether the journal file `meta` describes may be acted on: a regular file of this user's
/// (a journal another user left in a shared folder names files this one must not touch).
fn ours(meta: &std::fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        // SAFETY: geteuid has no preconditions.
        meta.is_file() && meta.uid() == unsafe { libc::geteuid() }
    }
    #[cfg(not(unix))]
    meta.is_file()
}

/// A journal entry's file name: one plain component of the folder (never `..`, `/x` or
/// `a/b`, which a damaged or planted journal could hold).
fn entry_name(bytes: &[u8]) -> Option<&std::ffi::OsStr> {
    // SAFETY of the encoding: written by `Journal::write` from an OsStr on this system; a
    // name that is not one plain component is refused below whatever its bytes.
    let name = unsafe { std::ffi::OsStr::from_encoded_bytes_unchecked(bytes) };
    let mut parts = Path::new(name).components();
    match (parts.next(), parts.next()) {
        (Some(std::path::Component::Normal(n)), None) if n == name => Some(name),
        _ => None,
    }
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
        let (tag, done) = match rest.strip_suffix(DONE) {
            Some(p) => (p, true),
            None => (rest, false),
        };
        let Some(tag) = Tag::parse(tag) else {
            continue;
        };
        if tag.alive() || !std::fs::symlink_metadata(e.path()).is_ok_and(|m| ours(&m)) {
            continue;
        }
        let Ok(text) = std::fs::read(e.path()) else {
            continue;
        };
        for entry in text.split(|&b| b == 0).filter(|x| !x.is_empty()) {
            // A malformed entry ends the journal: what follows it is not trusted either.
            let (Some(kind @ (b'B' | b'N')), Some(name)) = (entry.first().copied(), entry_name(&entry[1..])) else {
                break;
            };
            let (path, backup) = (dir.join(name), dir.join(backup_name(&name.to_string_lossy(), tag)));
            match (done, kind) {
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

    /// A process that is gone: pid 0 is never one, and no process started at tick 1.
    const DEAD: Tag = Tag { pid: 0, start: 1 };

    fn read(p: &Path) -> String {
        std::fs::read_to_string(p).unwrap_or_else(|_| "(none)".into())
    }

    /// A commit killed after its first rename: the file it
    /// replaced comes back from its backup, one it had not reached yet stays, one it created
    /// goes; the journal goes; files it did not name stay.
    #[test]
    fn a_killed_commit_is_undone() {
        let d = tempfile::tempdir().unwrap();
        let p = |n: &str| d.path().join(n);
        std::fs::write(p("a"), "new a").unwrap();
        std::fs::write(p(&backup_name("a", DEAD)), "old a").unwrap();
        std::fs::write(p("b"), "old b").unwrap();
        std::fs::write(p("c"), "new c").unwrap();
        std::fs::write(p("mine"), "user's").unwrap();
        std::fs::write(p(&format!(".gbump-commit.{DEAD}")), b"Ba\0Bb\0Nc\0").unwrap();
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
        std::fs::write(p(&backup_name("a", DEAD)), "old a").unwrap();
        std::fs::write(p(&format!(".gbump-commit.{DEAD}.done")), b"Ba\0").unwrap();
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

    /// A journal names files of its own folder only: an entry that climbs out (`../x`, `/x`,
    /// `a/b`) ends the journal, and nothing outside the folder, nor any later entry, is touched.
    #[test]
    fn a_journal_cannot_reach_outside_its_folder() {
        let d = tempfile::tempdir().unwrap();
        let out = d.path().join("out");
        std::fs::create_dir(&out).unwrap();
        std::fs::write(d.path().join("victim"), "keep").unwrap();
        std::fs::write(out.join("later"), "keep too").unwrap();
        std::fs::write(out.join(format!(".gbump-commit.{DEAD}")), b"N../victim\0Nlater\0").unwrap();
        recover_now(&out);
        assert_eq!(read(&d.path().join("victim")), "keep");
        assert_eq!(read(&out.join("later")), "keep too");
        for bad in ["/etc/passwd", "a/b", "..", "."] {
            assert!(entry_name(bad.as_bytes()).is_none(), "{bad}");
        }
        assert!(entry_name(b"random10_top.bin").is_some());
    }

    /// A journal of a process that had this one's pid but started at another time (a reused
    /// pid) is a dead process's, and is undone; this process's own is left alone.
    #[test]
    fn a_reused_pid_is_not_taken_for_the_journals_writer() {
        let own = Tag::own();
        assert!(own.alive());
        let earlier = Tag {
            pid: own.pid,
            start: own.start.wrapping_sub(1).max(1),
        };
        if own.start > 1 {
            assert!(!earlier.alive(), "{earlier} is not this process, started at {}", own.start);
        }
        assert_eq!(Tag::parse(&own.to_string()), Some(own));
        assert_eq!(Tag::parse("12"), None, "a journal of the old form (pid alone) is not read");
    }

    /// A journal that cannot be written leaves none behind, and names the folder that failed.
    #[test]
    fn a_failed_journal_leaves_none_behind() {
        let d = tempfile::tempdir().unwrap();
        let missing = d.path().join("gone").join("a");
        let ok = d.path().join("b");
        let Err((at, _)) = Journal::write(&[(&ok, false), (&missing, false)]) else {
            panic!("a journal in a folder that does not exist was written");
        };
        assert!(at.starts_with(d.path().join("gone")), "{}", at.display());
        assert_eq!(std::fs::read_dir(d.path()).unwrap().count(), 0, "a journal was left");
    }
}
