//! Icarus Verilog: `iverilog -g2005` compiles the testbench and RTL to a vvp image; `vvp`
//! runs it (with `-fst` when waves are asked for).

use super::{build_dir, outcome, require, run_cmd, Outcome, Sim};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Compile `tb` (top module `top`) with `rtl` sources; cached in `root`.
pub fn build(root: &Path, top: &str, tb: &str, rtl: &[PathBuf]) -> Result<PathBuf> {
    require(Sim::Icarus)?;
    let mut parts = vec![tb.to_string(), top.to_string()];
    for f in rtl {
        parts.push(std::fs::read_to_string(f).map_err(|e| Error::io(f, e))?);
    }
    let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
    let dir = build_dir(root, &format!("icarus_{top}"), &refs);
    let exe = dir.join(format!("{top}.vvp"));
    if exe.exists() {
        return Ok(exe);
    }
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    let tb_path = dir.join(format!("{top}.v"));
    std::fs::write(&tb_path, tb).map_err(|e| Error::io(&tb_path, e))?;
    let tmp = dir.join(format!("{top}.vvp.tmp"));
    let mut cmd = Command::new("iverilog");
    cmd.args(["-g2005", "-Wall", "-s", top, "-o"]).arg(&tmp).arg(&tb_path).args(rtl);
    let (ok, log, _) = run_cmd(&mut cmd, "iverilog")?;
    if !ok {
        return Err(Error::Other(format!(
            "iverilog failed to compile {top}:\n{}",
            super::tail(&log, 20)
        )));
    }
    std::fs::rename(&tmp, &exe).map_err(|e| Error::io(&exe, e))?;
    Ok(exe)
}

/// Run a compiled image with plusargs; `waves` writes an FST.
pub fn run(exe: &Path, plusargs: &[String], waves: Option<&Path>, cwd: &Path, what: &str) -> Result<Outcome> {
    let mut cmd = Command::new("vvp");
    cmd.arg("-n").arg(exe);
    if waves.is_some() {
        cmd.arg("-fst");
    }
    cmd.args(plusargs);
    if let Some(w) = waves {
        cmd.arg(format!("+waves={}", w.display()));
    }
    cmd.current_dir(cwd);
    let (ok, log, secs) = run_cmd(&mut cmd, what)?;
    outcome(ok, log, secs, what)
}
