//! Verilator: `--main --exe --timing` (`--binary` less its build) makes the Verilog
//! testbenches; `--cc --exe` makes the C++ harness that streams binary vectors (Verilator
//! only, so an inherent method); `--lint-only -Wall` lints. Verilator only writes the C++;
//! make compiles it with two jobs (the machine has two cores), Verilator's own runtime
//! objects reused from the shared cache.

use super::rtl_files::Rtl;
use super::simulator::{build_key, Simulator, Testbench};
use super::verilator_runtime::{fetch, record, runtime_objects, store};
use crate::error::{Error, Result};
use crate::tool::run_cmd;
use std::path::{Path, PathBuf};
use std::process::Command;

pub struct Verilator;

/// Build `exe_name` from the generated `source` (written as `source_name`) and the RTL:
/// Verilator turns them into C++ with `flags` (never `--build`), then make compiles it with
/// `make_args` (the optimisation levels), Verilator's runtime objects taken from the shared
/// cache where it holds them (`verilator_runtime`). The folder is keyed by everything that goes
/// in (the C++ compiler included), built under a temporary name and verified on reuse.
#[allow(clippy::too_many_arguments)]
fn cached_build(
    root: &Path,
    kind: &str,
    exe_name: &str,
    source_name: &str,
    source: &str,
    flags: &[String],
    make_args: &str,
    rtl: &Rtl,
) -> Result<PathBuf> {
    super::require(super::Sim::Verilator)?;
    let make_args: Vec<String> = make_args.split_whitespace().map(str::to_string).collect();
    let key_flags: Vec<String> = flags.iter().chain(&make_args).cloned().collect();
    let key = build_key(kind, source, &key_flags, rtl, &["verilator", "c++"])?;
    let dir = crate::cache::build_dir(&root.join(format!("{kind}_{key}")), &[exe_name], |dir| {
        let src = dir.join(source_name);
        std::fs::write(&src, source).map_err(|e| Error::io(&src, e))?;
        let mut cmd = Command::new("verilator");
        cmd.args(["-Wno-fatal", "-Mdir", "obj", "-o"])
            .arg(format!("../{exe_name}"))
            .args(flags)
            .args(&rtl.waivers)
            .arg(&src)
            .args(&rtl.sources)
            .current_dir(dir);
        let (ok, log, _) = run_cmd(&mut cmd, "verilator")?;
        let obj = dir.join("obj");
        let Some(mk) = ok.then(|| makefile(&obj)).flatten() else {
            return Err(Error::Other(format!(
                "verilator failed to build {exe_name}:\n{}\n{}",
                crate::tool::log_tail("verilator", &log, 25),
                crate::tool::build_fix("verilator", &log)
            )));
        };
        let runtime = runtime_objects(&obj, &mk, &make_args)?;
        let mut missing = fetch(&runtime, &obj);
        let make = || {
            let mut make = Command::new("make");
            make.args(["-j", "2", "-f", &mk]).args(&make_args).current_dir(&obj);
            run_cmd(&mut make, "make (Verilator's C++)")
        };
        let (mut ok, mut make_log, _) = make()?;
        // A full disk, a file-size limit or an unwritable TMPDIR fails the link whatever the
        // cached objects hold: they are kept, not blamed.
        let machine = crate::tool::environment_fix("make", &make_log).is_some();
        if (!ok || !dir.join(exe_name).exists()) && missing.len() < runtime.len() && !machine {
            // A cached object that does not link (damaged in a way its digest cannot see, or
            // made by another compiler that prints the same version): compile them all here
            // once more, and replace their entries.
            for o in &runtime {
                o.forget(&obj);
            }
            missing = runtime.iter().collect();
            (ok, make_log, _) = make()?;
        }
        if !ok || !dir.join(exe_name).exists() {
            // Verilator's part is done here: a silent failure is make's (or the compiler's).
            if ok && make_log.trim().is_empty() {
                return Err(Error::Other(crate::tool::did_not_run("make", &format!("it links {exe_name}"), "")));
            }
            if make_log.trim().is_empty() {
                return Err(Error::Other(format!(
                    "make (the C++ build of Verilator's output) failed to build {exe_name}:\n(make printed nothing)\n{}",
                    crate::tool::silent_fix("make")
                )));
            }
            let log = log + &make_log;
            return Err(Error::Other(format!(
                "verilator failed to build {exe_name}:\n{}\n{}",
                crate::tool::log_tail("verilator", &log, 25),
                crate::tool::build_fix("verilator", &log)
            )));
        }
        store(&missing, &obj);
        record(dir, &runtime, &missing)?;
        // The object folder is only needed while linking.
        let _ = std::fs::remove_dir_all(&obj);
        Ok(())
    })?;
    Ok(dir.join(exe_name))
}

/// The makefile Verilator wrote in `obj` (`V<top>.mk`, beside its `_classes.mk`).
fn makefile(obj: &Path) -> Option<String> {
    std::fs::read_dir(obj).ok()?.flatten().find_map(|e| {
        let n = e.file_name().to_string_lossy().into_owned();
        (n.starts_with('V') && n.ends_with(".mk") && !n.ends_with("_classes.mk")).then_some(n)
    })
}

/// `--binary` without its `--build`: a testbench with its own `main`, timing on; make runs
/// apart so the runtime objects can come from the cache.
const BINARY: [&str; 3] = ["--main", "--exe", "--timing"];

/// The C++ optimisation of every build but the lockstep one. Verilator's makefile compiles at
/// -Os, which ran the one-light top at half the speed of -O2. -O1 against -O2 (the harness's
/// `--raw` cycles per second, and `gbump bench` in docs/REPORT.md): the one-light and TexRam
/// tops as fast or faster, the default four-light serial top 10-25 % slower; the file
/// harness's own share of the time grows (file / raw per CPU second 77 % on the one-light
/// top, from 110 %, the issue-13 target is 75 %). A deep top builds in less than half the
/// time (TexRam's harness: 24 CPU seconds against 57), and the suite's regressions are
/// mostly builds, so -O1 it is; -O2 is the lever if a long stream on the default top matters.
const CXX_OPT: &str = "OPT_FAST=-O1 OPT_SLOW=-O1 OPT_GLOBAL=-O1";

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

impl Verilator {
    /// Build the C++ harness `cpp` around the top module `top`; its power table powers up
    /// with the RTL's init file. Run it with `run` (its options in place of plusargs).
    pub fn build_harness(&self, root: &Path, top: &str, cpp: &str, rtl: &Rtl) -> Result<PathBuf> {
        let mut flags = strings(&[
            "--cc",
            "--exe",
            "-O3",
            "--x-assign",
            "fast",
            "--x-initial",
            "fast",
            "--top-module",
            top,
        ]);
        flags.push(format!(
            "-GINIT_FILE={}",
            super::rtl_files::verilog_string(&rtl.init_file.display().to_string())
        ));
        for (param, _, file) in &rtl.memory_inits {
            flags.push(format!(
                "-G{param}={}",
                super::rtl_files::verilog_string(&file.display().to_string())
            ));
        }
        cached_build(
            root,
            &format!("verilator_harness_{top}"),
            "harness",
            "harness.cpp",
            cpp,
            &flags,
            CXX_OPT,
            rtl,
        )
    }
}

impl Simulator for Verilator {
    fn name(&self) -> &'static str {
        "verilator"
    }

    fn programs(&self) -> &'static [&'static str] {
        &["verilator", "make"]
    }

    /// A binary of its own (`--binary`'s options); the RTL's `.vlt` waivers go in with it.
    fn build(&self, root: &Path, tb: &Testbench, rtl: &Rtl) -> Result<PathBuf> {
        let top = tb.top;
        let mut flags = strings(&BINARY);
        flags.extend(strings(&["-Wno-lint", "-Wno-style", "--top-module", top]));
        if tb.waves {
            flags.push("--trace-fst".into());
        }
        if tb.x_unique {
            flags.extend(strings(&["--x-assign", "unique", "--x-initial", "unique"]));
        }
        cached_build(
            root,
            &format!("verilator_{top}"),
            top,
            &format!("{top}.v"),
            tb.source,
            &flags,
            CXX_OPT,
            rtl,
        )
    }

    /// The executable takes its arguments as given; `waves` goes last as `+waves=`.
    fn run_log(&self, exe: &Path, plusargs: &[String], waves: Option<&Path>, cwd: &Path, what: &str) -> Result<(bool, String, f64)> {
        let mut cmd = Command::new(exe);
        cmd.args(plusargs);
        if let Some(w) = waves {
            cmd.arg(format!("+waves={}", w.display()));
        }
        cmd.current_dir(cwd);
        run_cmd(&mut cmd, what)
    }

    /// A `%Warning` fails it even when Verilator exits 0.
    /// Its statistics file (`--stats`) is the evidence that it read the design: a
    /// `verilator` that exits 0 without linting writes none.
    fn lint(&self, cwd: &Path, files: &[String], waivers: &[String], top: Option<&str>) -> Result<Option<String>> {
        // Absolute, since Verilator runs in `cwd`; made here, since --lint-only makes none.
        let mdir = std::path::absolute(cwd.join(format!("lint_verilator_{}", top.unwrap_or("all")))).map_err(|e| Error::io(cwd, e))?;
        let _ = std::fs::remove_dir_all(&mdir);
        std::fs::create_dir_all(&mdir).map_err(|e| Error::io(&mdir, e))?;
        let mut c = Command::new("verilator");
        c.args(["--lint-only", "-Wall", "--stats", "--Mdir"]).arg(&mdir);
        if let Some(t) = top {
            c.args(["--top-module", t]);
        }
        c.args(waivers).args(files).current_dir(cwd);
        let (ok, log, _) = run_cmd(&mut c, "verilator --lint-only")?;
        let stats = std::fs::read_dir(&mdir)
            .into_iter()
            .flatten()
            .flatten()
            .any(|e| e.file_name().to_string_lossy().ends_with("__stats.txt") && e.metadata().is_ok_and(|m| m.len() > 0));
        let _ = std::fs::remove_dir_all(&mdir);
        if ok && !log.contains("%Warning") && !stats {
            return Ok(Some(crate::tool::did_not_run(
                "verilator",
                &format!("--stats writes its statistics under {}", mdir.display()),
                &log,
            )));
        }
        Ok((!ok || log.contains("%Warning")).then_some(log))
    }
}

/// Build the lockstep co-simulation testbench (`tb_cosim`): `source` holds the DPI-C package
/// and the testbench; the executable links libgbump at `lib` (absolute, so it needs no
/// library path at run time).
pub fn build_cosim(root: &Path, source: &str, rtl: &Rtl, lib: &Path) -> Result<PathBuf> {
    // Unoptimised C++ halves the build (8 s instead of 16 s for the one-light top) and still
    // checks 25 000 fragments a second on the default top: a lockstep run is dominated by its build.
    let mut flags = strings(&BINARY);
    flags.extend(strings(&["-Wno-lint", "-Wno-style", "--top-module", "tb_cosim", "-LDFLAGS"]));
    flags.push(lib.display().to_string());
    cached_build(
        root,
        "verilator_cosim",
        "tb_cosim",
        "tb_cosim.sv",
        source,
        &flags,
        "OPT_FAST=-O0 OPT_SLOW=-O0 OPT_GLOBAL=-O0",
        rtl,
    )
}
