//! `gbump regress` end to end: the given vector sets (manifests or folders of them) checked
//! before the work folder is taken, or the default suite generated in it; the RTL written;
//! every set run; the summary and the JUnit XML; an error when any run failed.

use super::regress::{check_sets, run_checked, suite, RegressOptions};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::work_lock::WorkLock;
use std::path::{Path, PathBuf};

/// The manifests `--vectors` names: JSON files, and every JSON file of a folder and of the
/// folders under it (sorted; a link to a folder is not followed), by absolute path.
pub fn given_manifests(vectors: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut given = Vec::new();
    for p in vectors {
        super::check_tool_path(p, "--vectors")?;
        if p.is_dir() {
            let p = &std::path::absolute(p).map_err(|e| Error::io(p, e))?;
            json_under(p, &mut given)?;
        } else {
            given.push(std::path::absolute(p).map_err(|e| Error::io(p, e))?);
        }
    }
    // A set named twice (directly, or in a folder named too) would run twice.
    let mut seen = std::collections::BTreeSet::new();
    if let Some(twice) = given
        .iter()
        .find(|p| !seen.insert(std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())))
    {
        return Err(Error::Other(format!(
            "--vectors: {} is given more than once\n  fix: name each set (or its folder) once",
            twice.display()
        )));
    }
    if !vectors.is_empty() && given.is_empty() {
        return Err(Error::Other(format!(
            "--vectors {}: no .json manifests there\n  fix: point at a folder or the .json manifests `gbump vectors --out DIR` wrote",
            vectors
                .iter()
                .map(|p| crate::shell::quoted(&p.display().to_string()))
                .collect::<Vec<_>>()
                .join(" ")
        )));
    }
    Ok(given)
}

/// Every `.json` file in `dir` and the folders under it, sorted, onto `out`: a set kept in
/// a subfolder runs too rather than being passed over.
fn json_under(dir: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    let mut entries: Vec<std::fs::DirEntry> = std::fs::read_dir(dir)
        .map_err(|e| Error::io(dir, e))?
        .collect::<std::io::Result<_>>()
        .map_err(|e| Error::io(dir, e))?;
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        let path = e.path();
        if e.file_type().map_err(|err| Error::io(&path, err))?.is_dir() {
            json_under(&path, out)?;
        } else if path.extension().is_some_and(|x| x == "json") {
            out.push(path);
        }
    }
    Ok(())
}

/// Regress `cfg` (selected by `pick_args`, for the RTL's header) on `vectors`, or on the
/// default suite when there are none. `lock` takes `o.work` once every given set is checked,
/// then `announce` writes or says what the caller held back until then; the table and totals
/// go to `say`, the XML to `junit`.
#[allow(clippy::too_many_arguments)]
pub fn regress(
    cfg: &PipelineConfig,
    pick_args: &str,
    vectors: &[PathBuf],
    o: &RegressOptions,
    junit: Option<&Path>,
    lock: impl FnOnce() -> Result<WorkLock>,
    announce: impl FnOnce(&mut dyn FnMut(&str) -> Result<()>) -> Result<()>,
    say: &mut dyn FnMut(&str) -> Result<()>,
) -> Result<()> {
    let r = (|| -> Result<()> {
        for s in &o.sims {
            super::require(*s)?;
        }
        let h = &cfg.hash()[..8];
        // Given sets are checked (paths, completeness, sha256, configuration) before the work
        // folder is taken, and before `announce` writes or says anything.
        let given: Vec<_> = given_manifests(vectors)?.into_iter().map(|m| (m, None)).collect();
        let given = check_sets(cfg, &given, o)?;
        // The given manifests are read now: --junit may not name one of them.
        if let Some(j) = junit {
            crate::render::output::check_writable(j)?;
        }
        let _lock = lock()?;
        announce(say)?;
        let sets = if vectors.is_empty() {
            let t0 = std::time::Instant::now();
            let s = suite(cfg, o, &o.work.join(format!("vectors_{h}")))?;
            say(&format!("generated {} vector sets in {:.1} s", s.len(), t0.elapsed().as_secs_f64()))?;
            check_sets(cfg, &s, o)?
        } else {
            given
        };
        let rtl = super::rtl_files::regression_rtl(cfg, pick_args, &o.work)?;
        let results = run_checked(cfg, &sets, &rtl, o)?;
        let t = super::summary::table(&results, say)?;
        if let Some(j) = junit {
            crate::render::output::write_atomic(j, super::summary::junit(cfg, &results).as_bytes())?;
        }
        super::summary::verdict(cfg, "", &t, say)
    })();
    report_failure(cfg, junit, &r);
    r
}

/// A run that fails before its table leaves no earlier run's verdict behind for CI to read:
/// the report becomes this failure. Only over nothing or a report gbump wrote, so a --junit
/// that names an input (refused with its own message) is never overwritten.
fn report_failure(cfg: &PipelineConfig, junit: Option<&Path>, r: &Result<()>) {
    if let (Err(e), Some(j)) = (&r, junit) {
        // Read only from a regular file, and only its head: a pipe or /dev/stdout would wait.
        let target = crate::render::output::link_target(j).unwrap_or_else(|_| j.to_path_buf());
        let ours = match std::fs::metadata(&target) {
            Err(e) => e.kind() == std::io::ErrorKind::NotFound,
            Ok(m) if m.is_file() => {
                use std::io::Read;
                let mut head = Vec::new();
                let read = std::fs::File::open(&target).and_then(|f| f.take(512).read_to_end(&mut head));
                read.is_ok() && super::summary::is_report(&head)
            }
            Ok(_) => false,
        };
        if ours {
            // The run's own error is what matters; a report that cannot be written adds nothing.
            let _ = crate::render::output::write_atomic(j, super::summary::junit_error(cfg, &e.to_string()).as_bytes());
        }
    }
}

#[cfg(test)]
mod manifest_tests {
    /// A folder's sets are its own `.json` files and those of the folders under it (a set kept
    /// in a subfolder is not passed over), sorted; other files and links to folders are not
    /// read.
    #[test]
    fn a_folder_gives_the_manifests_of_its_subfolders_too() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path();
        std::fs::create_dir_all(p.join("b/deeper")).unwrap();
        for f in ["z.json", "a.json", "b/m.json", "b/deeper/n.json", "b/notes.txt"] {
            std::fs::write(p.join(f), "{}").unwrap();
        }
        std::os::unix::fs::symlink(p.join("b"), p.join("link")).unwrap();
        let got = super::given_manifests(&[p.to_path_buf()]).unwrap();
        let rel: Vec<String> = got.iter().map(|g| g.strip_prefix(p).unwrap().display().to_string()).collect();
        assert_eq!(rel, ["a.json", "b/deeper/n.json", "b/m.json", "z.json"]);
    }
}
