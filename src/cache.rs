//! Caches: a result is found under a key made of everything that changes it (inputs, flags,
//! gbump's version, the versions of the tools that made it), is built under a temporary name,
//! is marked complete last with the sha256 of every file it holds, and is verified on use.
//! A half-written or tampered entry is rebuilt, never trusted for existing.

use crate::error::{Error, Result};
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

const COMPLETE: &str = ".complete";

/// A cache key under construction: gbump's version is always part of it.
pub struct Key(Sha256);

impl Key {
    pub fn new(kind: &str) -> Key {
        let mut k = Key(Sha256::new());
        k.add(crate::TOOL.as_bytes()).add(kind.as_bytes());
        k
    }
    /// One more input (length-prefixed, so inputs cannot run into each other).
    pub fn add(&mut self, part: &[u8]) -> &mut Key {
        self.0.update((part.len() as u64).to_le_bytes());
        self.0.update(part);
        self
    }
    pub fn add_file(&mut self, path: &Path) -> Result<&mut Key> {
        let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
        Ok(self.add(path.file_name().map_or(&[][..], |n| n.as_encoded_bytes())).add(&bytes))
    }
    /// The version a tool prints of itself.
    pub fn add_tool(&mut self, prog: &str) -> &mut Key {
        let v = tool_version(prog);
        self.add(prog.as_bytes()).add(v.as_bytes())
    }
    /// 16 hex digits.
    pub fn finish(self) -> String {
        self.0.finalize().iter().take(8).map(|b| format!("{b:02x}")).collect()
    }
}

/// Where results shared between runs and work folders are kept (today Verilator's runtime
/// objects, `sim::verilator_runtime`): `GBUMP_CACHE`, else `$XDG_CACHE_HOME/gbump`, else
/// `$HOME/.cache/gbump`. None when `GBUMP_CACHE` is set empty, no home is known or the folder
/// cannot be made: nothing is shared then, and every build compiles all it needs.
pub fn shared_root() -> Option<PathBuf> {
    let env = |k: &str| std::env::var_os(k).filter(|v| !v.is_empty()).map(PathBuf::from);
    let root = match std::env::var_os("GBUMP_CACHE") {
        Some(v) if v.is_empty() => return None,
        Some(v) => PathBuf::from(v),
        None => env("XDG_CACHE_HOME")
            .or_else(|| env("HOME").map(|h| h.join(".cache")))?
            .join("gbump"),
    };
    if let Err(e) = std::fs::create_dir_all(&root) {
        // Nothing is shared then; said once, since every build is slower for it.
        static SAID: OnceLock<()> = OnceLock::new();
        let why = match std::fs::metadata(&root) {
            Ok(m) if !m.is_dir() => "it is a file, not a folder".to_string(),
            _ => e.to_string(),
        };
        SAID.get_or_init(|| {
            crate::warn::warn(format!(
                "gbump: warning: the shared cache {} cannot be used ({why}): every build compiles all it needs\n  fix: point GBUMP_CACHE at a folder (or set it empty to share nothing, silently)",
                root.display()
            ))
        });
        return None;
    }
    // Entries half-built by a process that was killed are cleared once per run.
    static CLEANED: OnceLock<()> = OnceLock::new();
    CLEANED.get_or_init(|| {
        crate::temp_files::clean_stale(&root, 0);
    });
    Some(root)
}

/// The first line a tool prints for `--version` (or `-V`), once per process.
pub fn tool_version(prog: &str) -> String {
    static SEEN: OnceLock<Mutex<HashMap<String, String>>> = OnceLock::new();
    let seen = SEEN.get_or_init(Default::default);
    if let Some(v) = seen.lock().expect("lock").get(prog) {
        return v.clone();
    }
    let v = ["--version", "-V"]
        .iter()
        .find_map(|flag| {
            let out = crate::tool::output(std::process::Command::new(prog).arg(flag)).ok()?;
            let text = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
            let line = text.lines().find(|l| !l.trim().is_empty())?.trim().to_string();
            Some(line)
        })
        .unwrap_or_else(|| "not installed".into());
    seen.lock().expect("lock").insert(prog.to_string(), v.clone());
    v
}

fn sha256_file(path: &Path) -> Option<String> {
    use std::io::Read;
    let mut f = std::fs::File::open(path).ok()?;
    let mut h = Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    loop {
        let n = f.read(&mut buf).ok()?;
        if n == 0 {
            break;
        }
        h.update(&buf[..n]);
    }
    Some(h.finalize().iter().map(|b| format!("{b:02x}")).collect())
}

/// Whether `dir` holds a complete entry: its marker lists `outputs` and every file still has
/// the recorded size and digest.
pub fn is_complete(dir: &Path, outputs: &[&str]) -> bool {
    let Ok(marker) = std::fs::read_to_string(dir.join(COMPLETE)) else {
        return false;
    };
    let recorded: HashMap<&str, &str> = marker.lines().filter_map(|l| l.split_once("  ").map(|(d, n)| (n, d))).collect();
    outputs.iter().all(|o| {
        recorded
            .get(o)
            .is_some_and(|d| sha256_file(&dir.join(o)).is_some_and(|real| real == *d))
    })
}

/// The folder `dir`, built by `build` into a temporary folder when it is not a complete entry
/// holding `outputs`, then marked and renamed into place.
pub fn build_dir(dir: &Path, outputs: &[&str], build: impl FnOnce(&Path) -> Result<()>) -> Result<PathBuf> {
    if is_complete(dir, outputs) {
        return Ok(dir.to_path_buf());
    }
    let tmp = crate::temp_files::temp_path(dir);
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).map_err(|e| Error::io(&tmp, e))?;
    let made = build(&tmp).and_then(|_| {
        let mut marker = String::new();
        for o in outputs {
            let p = tmp.join(o);
            let d = sha256_file(&p)
                .filter(|_| p.metadata().is_ok_and(|m| m.len() > 0))
                .ok_or_else(|| {
                    // Named by the entry it was for: the temporary folder is gone by the time
                    // the message is read.
                    Error::Other(format!(
                        "{}: the build exited 0 but did not produce {o}\n  fix: a tool it ran is not working (`which` it and check `--version` answers); reinstall it (scripts/install-tools.sh) or put a working one first on PATH",
                        dir.display()
                    ))
                })?;
            marker += &format!("{d}  {o}\n");
        }
        let m = tmp.join(COMPLETE);
        std::fs::write(&m, marker).map_err(|e| Error::io(&m, e))
    });
    if let Err(e) = made {
        let _ = std::fs::remove_dir_all(&tmp);
        return Err(e);
    }
    // A stale or half-built entry is replaced; if another process finished the same entry
    // first, its copy is as good as ours.
    if dir.exists() {
        let _ = std::fs::remove_dir_all(dir);
    }
    if let Err(e) = std::fs::rename(&tmp, dir) {
        let _ = std::fs::remove_dir_all(&tmp);
        if !is_complete(dir, outputs) {
            return Err(Error::io(dir, e));
        }
    }
    Ok(dir.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_entry_is_trusted_only_when_complete_and_intact() {
        let d = tempfile::tempdir().unwrap();
        let dir = d.path().join("e");
        let runs = std::cell::Cell::new(0);
        let b = |t: &Path| {
            runs.set(runs.get() + 1);
            std::fs::write(t.join("exe"), b"program").map_err(|e| Error::io(t, e))
        };
        build_dir(&dir, &["exe"], b).unwrap();
        build_dir(&dir, &["exe"], b).unwrap();
        assert_eq!(runs.get(), 1);
        // A truncated output (a kill during linking) is rebuilt.
        std::fs::write(dir.join("exe"), b"").unwrap();
        build_dir(&dir, &["exe"], b).unwrap();
        assert_eq!(runs.get(), 2);
        // A folder without the marker (killed before it was written) is rebuilt.
        std::fs::remove_file(dir.join(COMPLETE)).unwrap();
        build_dir(&dir, &["exe"], b).unwrap();
        assert_eq!(runs.get(), 3);
        assert_eq!(std::fs::read(dir.join("exe")).unwrap(), b"program");
        // A build that fails leaves nothing under the entry's name or a temporary one.
        let other = d.path().join("f");
        assert!(build_dir(&other, &["exe"], |_| Ok(())).is_err());
        assert!(!other.exists());
        assert_eq!(std::fs::read_dir(d.path()).unwrap().count(), 1);
    }

    #[test]
    fn keys_separate_inputs_and_include_the_version() {
        let k = |parts: &[&str]| {
            let mut k = Key::new("t");
            for p in parts {
                k.add(p.as_bytes());
            }
            k.finish()
        };
        assert_ne!(k(&["ab", "c"]), k(&["a", "bc"]));
        assert_eq!(k(&["x"]), k(&["x"]));
        let mut other = Key::new("u");
        other.add(b"x");
        assert_ne!(other.finish(), k(&["x"]));
    }
}
