//! The interface every simulator implements (`icarus.rs`, `verilator.rs`, one file each):
//! build a filled Verilog testbench and the RTL into a cached executable, run it with
//! plusargs, lint Verilog files. Regress, lint, fuzz, bench, the RTL image and the power-unit
//! check all go through it, so a simulator's flags, cache key and messages live in one file.

use super::rtl_files::Rtl;
use super::verdict::{outcome, Outcome};
use crate::error::Result;
use std::path::{Path, PathBuf};

/// A filled Verilog testbench and how to build it.
#[derive(Clone, Copy, Debug)]
pub struct Testbench<'a> {
    /// Its top module (also the executable's name).
    pub top: &'a str,
    /// The filled template (`rtlgen::testbench`).
    pub source: &'a str,
    /// Build for waveform dumps (Verilator compiles tracing in; Icarus decides at run time).
    pub waves: bool,
    /// X as unique random values (Verilator only: Icarus keeps X as X, which is stricter).
    pub x_unique: bool,
}

impl<'a> Testbench<'a> {
    /// A plain build: no waves, X as the simulator's default.
    pub fn new(top: &'a str, source: &'a str) -> Testbench<'a> {
        Testbench {
            top,
            source,
            waves: false,
            x_unique: false,
        }
    }
}

pub trait Simulator: Sync {
    /// Its name in `--sim`, summaries and cache folders.
    fn name(&self) -> &'static str;

    /// The programs it runs; each must be installed (`sim::require`).
    fn programs(&self) -> &'static [&'static str];

    /// Build `tb` with the RTL into an executable, cached under `root` in a folder keyed by
    /// everything that goes in (`build_key`), built under a temporary name and verified on reuse.
    fn build(&self, root: &Path, tb: &Testbench, rtl: &Rtl) -> Result<PathBuf>;

    /// Run an executable `build` made, from `cwd`, with `plusargs`; `waves` names the FST to
    /// write. (exit ok, log, seconds), unjudged.
    fn run_log(&self, exe: &Path, plusargs: &[String], waves: Option<&Path>, cwd: &Path, what: &str) -> Result<(bool, String, f64)>;

    /// `run_log` judged by the testbench's summary line; any simulator warning fails it. Waves
    /// are written under a temporary name and put in place after the run (through a symbolic
    /// link, as every result is), a failing one's too, unless the disk under them has less
    /// than [`WAVES_FREE_MARGIN`] free after the run: a simulator cut short by a full disk
    /// closes its FST early without a word, and a cut wave file would pass for a whole one, so
    /// a nearly full disk fails the run whatever the waves hold.
    fn run(&self, exe: &Path, plusargs: &[String], waves: Option<&Path>, cwd: &Path, what: &str) -> Result<Outcome> {
        let Some(w) = waves else {
            let (ok, log, secs) = self.run_log(exe, plusargs, None, cwd, what)?;
            return outcome(ok, log, secs, what);
        };
        let w = crate::render::output::link_target(w)?;
        let tmp = crate::temp_files::hidden_temp_path(&w);
        let (ok, log, secs) = self.run_log(exe, plusargs, Some(&tmp), cwd, what).inspect_err(|_| {
            let _ = std::fs::remove_file(&tmp);
        })?;
        let dir = w.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        if let Some(free) = crate::limits::free_bytes(dir).filter(|&b| b < WAVES_FREE_MARGIN) {
            let _ = std::fs::remove_file(&tmp);
            let verdict = super::verdict::parse_summary(&log).map_or("no summary".to_string(), |(p, f)| format!("{p} passed, {f} failed"));
            return Err(crate::error::Error::Other(format!(
                "{what} ({verdict}): the disk holding {} has {free} bytes free after the run: the simulator may have cut the waves short without a word, so they are not kept\n  fix: free space on that disk, or give --work a folder on another",
                w.display()
            )));
        }
        if tmp.exists() {
            std::fs::rename(&tmp, &w).map_err(|e| crate::error::Error::io(&w, e))?;
        }
        outcome(ok, log, secs, what)
    }

    /// Lint `files` (names as given, resolved from `cwd`) with every warning on, `top` as the
    /// only root (None: every module not instantiated); `waivers` are Verilator's `.vlt` files.
    /// The tool's log when it objects, None when clean.
    fn lint(&self, cwd: &Path, files: &[String], waivers: &[String], top: Option<&str>) -> Result<Option<String>>;
}

/// The cache key of a simulator build: the testbench, every RTL file and waiver, the flags
/// and the versions of the tools involved.
pub fn build_key(kind: &str, source: &str, flags: &[String], rtl: &Rtl, tools: &[&str]) -> Result<String> {
    let mut k = crate::cache::Key::new(kind);
    k.add(source.as_bytes());
    for f in flags {
        k.add(f.as_bytes());
    }
    for f in rtl.sources.iter().chain(&rtl.waivers) {
        k.add_file(f)?;
    }
    for t in tools {
        k.add_tool(t);
    }
    Ok(k.finish())
}

/// Free bytes below which a disk that took a wave file is taken to have filled while writing
/// it (a simulator does not report the short write).
pub const WAVES_FREE_MARGIN: u64 = 1 << 20;
