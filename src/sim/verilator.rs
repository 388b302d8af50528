//! Verilator: `--binary` builds the Verilog testbenches; `--cc --exe --build` builds the C++
//! harness that streams binary vectors. Both compile with two jobs (the machine has two cores).

use super::{build_dir, outcome, require, run_cmd, Outcome, Sim};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

fn sources(rtl: &[PathBuf], extra: &[String]) -> Result<Vec<String>> {
    let mut parts = extra.to_vec();
    for f in rtl {
        parts.push(std::fs::read_to_string(f).map_err(|e| Error::io(f, e))?);
    }
    Ok(parts)
}

fn verilator_build(dir: &Path, args: Vec<String>, exe: &Path, what: &str) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let mut cmd = Command::new("verilator");
    cmd.args(&args).current_dir(dir);
    let (ok, log, _) = run_cmd(&mut cmd, "verilator")?;
    if !ok || !exe.exists() {
        return Err(Error::Other(format!(
            "verilator failed to build {what}:\n{}",
            super::tail(&log, 25)
        )));
    }
    Ok(())
}

/// Build a Verilog testbench with `--binary`. `vlt` holds lint waivers for the RTL.
pub fn build_tb(root: &Path, top: &str, tb: &str, rtl: &[PathBuf], vlt: &[PathBuf], waves: bool, x_unique: bool) -> Result<PathBuf> {
    require(Sim::Verilator)?;
    let flags = format!("binary waves={waves} x_unique={x_unique}");
    let parts = sources(rtl, &[tb.to_string(), top.to_string(), flags])?;
    let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
    let dir = build_dir(root, &format!("verilator_{top}"), &refs);
    let exe = dir.join(top);
    if exe.exists() {
        return Ok(exe);
    }
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    let tb_path = dir.join(format!("{top}.v"));
    std::fs::write(&tb_path, tb).map_err(|e| Error::io(&tb_path, e))?;
    let mut args: Vec<String> = [
        "--binary",
        "-j",
        "2",
        "-Wno-fatal",
        "-Wno-lint",
        "-Wno-style",
        "--top-module",
        top,
        "-Mdir",
        "obj",
        "-o",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.push(format!("../{top}"));
    if waves {
        args.push("--trace-fst".into());
    }
    if x_unique {
        args.extend(["--x-assign", "unique", "--x-initial", "unique"].map(String::from));
    }
    args.extend(vlt.iter().map(|p| p.display().to_string()));
    args.push(tb_path.display().to_string());
    args.extend(rtl.iter().map(|p| p.display().to_string()));
    verilator_build(&dir, args, &exe, top)?;
    Ok(exe)
}

/// Build the C++ harness around the top module `top`.
pub fn build_harness(root: &Path, top: &str, cpp: &str, rtl: &[PathBuf], vlt: &[PathBuf]) -> Result<PathBuf> {
    require(Sim::Verilator)?;
    let parts = sources(rtl, &[cpp.to_string(), top.to_string(), "harness".into()])?;
    let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
    let dir = build_dir(root, &format!("verilator_harness_{top}"), &refs);
    let exe = dir.join("harness");
    if exe.exists() {
        return Ok(exe);
    }
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    let cpp_path = dir.join("harness.cpp");
    std::fs::write(&cpp_path, cpp).map_err(|e| Error::io(&cpp_path, e))?;
    let mut args: Vec<String> = [
        "--cc",
        "--exe",
        "--build",
        "-j",
        "2",
        "-O3",
        "--x-assign",
        "fast",
        "--x-initial",
        "fast",
        "-Wno-fatal",
        "--top-module",
        top,
        "-Mdir",
        "obj",
        "-o",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.push("../harness".into());
    args.extend(vlt.iter().map(|p| p.display().to_string()));
    args.push(cpp_path.display().to_string());
    args.extend(rtl.iter().map(|p| p.display().to_string()));
    verilator_build(&dir, args, &exe, "the C++ harness")?;
    Ok(exe)
}

/// Run a built executable (testbench with plusargs, or harness with options).
pub fn run(exe: &Path, args: &[String], cwd: &Path, what: &str) -> Result<Outcome> {
    let mut cmd = Command::new(exe);
    cmd.args(args).current_dir(cwd);
    let (ok, log, secs) = run_cmd(&mut cmd, what)?;
    outcome(ok, log, secs, what)
}
