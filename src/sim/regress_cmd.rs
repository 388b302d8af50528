//! `gbump regress` end to end: the given vector sets (manifests or folders of them) checked
//! before the work folder is taken, or the default suite generated in it; the RTL written;
//! every set run; the summary and the JUnit XML; an error when any run failed.

use super::regress::{check_sets, run_checked, suite, RegressOptions};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::work_lock::WorkLock;
use std::path::{Path, PathBuf};

/// The manifests `--vectors` names: JSON files, and every JSON file of a folder (sorted), by
/// absolute path. A folder's subfolders are not read (a work folder, an RTL kit's interface
/// JSON or a render's metrics may sit there), but sets in them are named in a warning, so
/// none is passed over without a word.
pub fn given_manifests(vectors: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut given = Vec::new();
    for p in vectors {
        super::check_tool_path(p, "--vectors")?;
        if p.is_dir() {
            let p = &std::path::absolute(p).map_err(|e| Error::io(p, e))?;
            let mut found: Vec<PathBuf> = std::fs::read_dir(p)
                .map_err(|e| Error::io(p, e))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect();
            found.sort();
            given.extend(found);
            warn_sets_below(p);
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

/// Warn of vector sets in the folders just under `dir` (manifests: `.json` files beside a
/// `.hex` or `.bin` of the same stem), which `--vectors DIR` does not run.
fn warn_sets_below(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut below: Vec<PathBuf> = entries
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .filter_map(|e| std::fs::read_dir(e.path()).ok())
        .flat_map(|d| d.flatten().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json") && ["hex", "bin"].iter().any(|x| p.with_extension(x).is_file()))
        .collect();
    if below.is_empty() {
        return;
    }
    below.sort();
    crate::warn::warn(format!(
        "warning: --vectors {}: {} set(s) in its subfolders are not run (first: {}); name a subfolder, or its manifests, to run them",
        dir.display(),
        below.len(),
        below[0].display()
    ));
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
    reporting(cfg, junit, |reported| {
        for s in &o.sims {
            super::require(*s)?;
        }
        let h = &cfg.hash()[..8];
        // Given sets are checked (paths, completeness, sha256, configuration) before the work
        // folder is taken, and before `announce` writes or says anything.
        let given: Vec<_> = given_manifests(vectors)?.into_iter().map(|m| (m, None)).collect();
        let given = check_sets(cfg, &given, o)?;
        if vectors.is_empty() {
            super::regress::check_own_scenes(cfg, &o.own_scenes, &o.targets)?;
        }
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
            *reported = true;
        }
        super::summary::verdict(cfg, "", &t, say)
    })
}

/// `run`, and its failure as the `junit` report unless `run` set its flag: it sets it once
/// its own table is written, so a failing verdict after that keeps the per-run report.
pub(super) fn reporting(cfg: &PipelineConfig, junit: Option<&Path>, run: impl FnOnce(&mut bool) -> Result<()>) -> Result<()> {
    let mut reported = false;
    let r = run(&mut reported);
    if !reported {
        report_failure(cfg, junit, &r);
    }
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
    /// A folder's sets are its own `.json` files, sorted; those of its subfolders are not run
    /// (unrelated JSON lives there too), and other files are not read.
    #[test]
    fn a_folder_gives_its_own_manifests() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path();
        std::fs::create_dir_all(p.join("b")).unwrap();
        for f in ["z.json", "a.json", "b/m.json", "b/m.hex", "b/notes.txt"] {
            std::fs::write(p.join(f), "{}").unwrap();
        }
        let (got, warned) = crate::warn::capture(|| super::given_manifests(&[p.to_path_buf()]).unwrap());
        let rel: Vec<String> = got.iter().map(|g| g.strip_prefix(p).unwrap().display().to_string()).collect();
        assert_eq!(rel, ["a.json", "z.json"]);
        assert!(
            warned.len() == 1 && warned[0].contains("1 set(s) in its subfolders are not run") && warned[0].contains("b/m.json"),
            "{warned:?}"
        );
    }
}
