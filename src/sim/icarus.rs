//! Icarus Verilog: `iverilog -g2005` compiles the testbench and RTL to a vvp image; `vvp`
//! runs it (with `-fst` when waves are asked for).

use super::rtl_files::Rtl;
use super::{build_key, outcome, require, run_cmd, Outcome, Sim};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Compile `tb` (top module `top`) with the RTL; cached in `root` under a key of everything
/// that goes in, built under a temporary name and verified on reuse.
pub fn build(root: &Path, top: &str, tb: &str, rtl: &Rtl) -> Result<PathBuf> {
    require(Sim::Icarus)?;
    let flags: Vec<String> = ["-g2005", "-Wall", "-s", top].iter().map(|s| s.to_string()).collect();
    let key = build_key("icarus", tb, &flags, rtl, &["iverilog"])?;
    let exe_name = format!("{top}.vvp");
    let dir = crate::cache::build_dir(&root.join(format!("icarus_{top}_{key}")), &[&exe_name], |dir| {
        let tb_path = dir.join(format!("{top}.v"));
        std::fs::write(&tb_path, tb).map_err(|e| Error::io(&tb_path, e))?;
        let mut cmd = Command::new("iverilog");
        cmd.args(&flags).arg("-o").arg(dir.join(&exe_name)).arg(&tb_path).args(&rtl.sources);
        let (ok, log, _) = run_cmd(&mut cmd, "iverilog")?;
        if !ok {
            return Err(Error::Other(format!(
                "iverilog failed to compile {top}:\n{}",
                super::tail(&log, 20)
            )));
        }
        Ok(())
    })?;
    Ok(dir.join(exe_name))
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
