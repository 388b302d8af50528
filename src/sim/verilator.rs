//! Verilator: `--binary` builds the Verilog testbenches; `--cc --exe --build` builds the C++
//! harness that streams binary vectors. Both compile with two jobs (the machine has two cores).

use super::{build_dir, outcome, require, run_cmd, Outcome, Sim};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Build `exe_name` from the generated `source` (written as `source_name`) and the RTL with
/// `flags`, in a folder keyed by the hash of everything that goes in; a finished build is
/// reused.
#[allow(clippy::too_many_arguments)]
fn cached_build(
    root: &Path,
    kind: &str,
    exe_name: &str,
    source_name: &str,
    source: &str,
    flags: &[String],
    rtl: &[PathBuf],
    vlt: &[PathBuf],
) -> Result<PathBuf> {
    require(Sim::Verilator)?;
    let mut parts = vec![source.to_string(), flags.join(" ")];
    for f in rtl {
        parts.push(std::fs::read_to_string(f).map_err(|e| Error::io(f, e))?);
    }
    let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
    let dir = build_dir(root, kind, &refs);
    let exe = dir.join(exe_name);
    if exe.exists() {
        return Ok(exe);
    }
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    let src = dir.join(source_name);
    std::fs::write(&src, source).map_err(|e| Error::io(&src, e))?;
    let mut cmd = Command::new("verilator");
    cmd.args(["-j", "2", "-Wno-fatal", "-Mdir", "obj", "-o"])
        .arg(format!("../{exe_name}"))
        .args(flags)
        .args(vlt)
        .arg(&src)
        .args(rtl)
        .current_dir(&dir);
    let (ok, log, _) = run_cmd(&mut cmd, "verilator")?;
    if !ok || !exe.exists() {
        return Err(Error::Other(format!(
            "verilator failed to build {exe_name}:\n{}",
            super::tail(&log, 25)
        )));
    }
    Ok(exe)
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// Build a Verilog testbench with `--binary`. `vlt` holds lint waivers for the RTL.
pub fn build_tb(root: &Path, top: &str, tb: &str, rtl: &[PathBuf], vlt: &[PathBuf], waves: bool, x_unique: bool) -> Result<PathBuf> {
    let mut flags = strings(&["--binary", "-Wno-lint", "-Wno-style", "--top-module", top]);
    if waves {
        flags.push("--trace-fst".into());
    }
    if x_unique {
        flags.extend(strings(&["--x-assign", "unique", "--x-initial", "unique"]));
    }
    cached_build(root, &format!("verilator_{top}"), top, &format!("{top}.v"), tb, &flags, rtl, vlt)
}

/// Build the C++ harness around the top module `top`.
pub fn build_harness(root: &Path, top: &str, cpp: &str, rtl: &[PathBuf], vlt: &[PathBuf]) -> Result<PathBuf> {
    let flags = strings(&[
        "--cc",
        "--exe",
        "--build",
        "-O3",
        "--x-assign",
        "fast",
        "--x-initial",
        "fast",
        "--top-module",
        top,
    ]);
    cached_build(
        root,
        &format!("verilator_harness_{top}"),
        "harness",
        "harness.cpp",
        cpp,
        &flags,
        rtl,
        vlt,
    )
}

/// Run a built executable (testbench with plusargs, or harness with options).
pub fn run(exe: &Path, args: &[String], cwd: &Path, what: &str) -> Result<Outcome> {
    let mut cmd = Command::new(exe);
    cmd.args(args).current_dir(cwd);
    let (ok, log, secs) = run_cmd(&mut cmd, what)?;
    outcome(ok, log, secs, what)
}
