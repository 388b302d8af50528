//! Icarus Verilog: `iverilog -g2005` compiles the testbench and RTL to a vvp image; `vvp`
//! runs it (with `-fst` when waves are asked for); `iverilog -Wall -o /dev/null` lints.

use super::rtl_files::Rtl;
use super::simulator::{build_key, Simulator, Testbench};
use crate::error::{Error, Result};
use crate::tool::run_cmd;
use std::path::{Path, PathBuf};
use std::process::Command;

pub struct Icarus;

impl Simulator for Icarus {
    fn name(&self) -> &'static str {
        "icarus"
    }

    fn programs(&self) -> &'static [&'static str] {
        &["iverilog", "vvp"]
    }

    /// `waves` needs nothing at build time and Icarus has no unique-X mode, so both are ignored.
    fn build(&self, root: &Path, tb: &Testbench, rtl: &Rtl) -> Result<PathBuf> {
        super::require(super::Sim::Icarus)?;
        let top = tb.top;
        let flags: Vec<String> = ["-g2005", "-Wall", "-s", top].iter().map(|s| s.to_string()).collect();
        let key = build_key("icarus", tb.source, &flags, rtl, &["iverilog"])?;
        let exe_name = format!("{top}.vvp");
        let dir = crate::cache::build_dir(&root.join(format!("icarus_{top}_{key}")), &[&exe_name], |dir| {
            let tb_path = dir.join(format!("{top}.v"));
            std::fs::write(&tb_path, tb.source).map_err(|e| Error::io(&tb_path, e))?;
            let mut cmd = Command::new("iverilog");
            cmd.args(&flags).arg("-o").arg(dir.join(&exe_name)).arg(&tb_path).args(&rtl.sources);
            let (ok, log, _) = run_cmd(&mut cmd, "iverilog")?;
            if !ok {
                return Err(Error::Other(format!(
                    "iverilog failed to compile {top}:\n{}\n{}",
                    crate::tool::log_tail("iverilog", &log, 20),
                    crate::tool::build_fix("iverilog", &log)
                )));
            }
            if !dir.join(&exe_name).is_file() {
                return Err(Error::Other(crate::tool::did_not_run(
                    "iverilog",
                    &format!("it compiles {exe_name}"),
                    &log,
                )));
            }
            Ok(())
        })?;
        Ok(dir.join(exe_name))
    }

    fn run_log(&self, exe: &Path, plusargs: &[String], waves: Option<&Path>, cwd: &Path, what: &str) -> Result<(bool, String, f64)> {
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
        run_cmd(&mut cmd, what)
    }

    /// Icarus has no waiver files; anything it prints is a problem.
    /// Its compiled image is the evidence that it read the design: an `iverilog` that exits
    /// 0 without compiling leaves none, and a lint that looked at nothing is not clean.
    fn lint(&self, cwd: &Path, files: &[String], _waivers: &[String], top: Option<&str>) -> Result<Option<String>> {
        // Absolute, since iverilog runs in `cwd`.
        let image = std::path::absolute(cwd.join("lint_icarus.vvp")).map_err(|e| Error::io(cwd, e))?;
        let _ = std::fs::remove_file(&image);
        let mut c = Command::new("iverilog");
        c.args(["-g2005", "-Wall", "-o"]).arg(&image);
        if let Some(t) = top {
            c.args(["-s", t]);
        }
        c.args(files).current_dir(cwd);
        let (ok, log, _) = run_cmd(&mut c, "iverilog -Wall")?;
        let read = std::fs::read_to_string(&image).is_ok_and(|t| top.is_none_or(|t2| t.contains(t2)));
        let _ = std::fs::remove_file(&image);
        if ok && log.trim().is_empty() && !read {
            return Ok(Some(crate::tool::did_not_run(
                "iverilog",
                &format!("it compiles {} with the design's top", image.display()),
                &log,
            )));
        }
        Ok((!ok || !log.trim().is_empty()).then_some(log))
    }
}
