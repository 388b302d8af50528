//! External programs (simulators, Yosys, nextpnr): whether one is installed, the message that
//! says how to install it, and running one with its log. Every spawn of a tool goes through
//! `run_cmd`, so Ctrl-C, a missing program and a child killed by a signal read the same
//! everywhere.

use crate::error::{Error, Result};
use std::process::Command;

/// Whether `prog` runs.
pub fn have(prog: &str) -> bool {
    Command::new(prog).arg("--version").output().is_ok() || Command::new(prog).arg("-V").output().is_ok()
}

/// Error unless `prog` is installed.
pub fn require(prog: &str) -> Result<()> {
    if have(prog) {
        Ok(())
    } else {
        Err(missing(prog))
    }
}

/// The error for a program that is not installed; it says how to install it.
pub fn missing(prog: &str) -> Error {
    let pkg = match prog {
        "vvp" | "iverilog" => "iverilog",
        p => p,
    };
    Error::Other(format!(
        "{prog} is not installed (or not on PATH)\n  fix: run scripts/install-tools.sh from gbump's repository, or apt-get update && apt-get install -y {pkg}"
    ))
}

/// Run a command, capturing stdout and stderr together; `what` names it in errors.
pub fn run_cmd(cmd: &mut Command, what: &str) -> Result<(bool, String, f64)> {
    crate::interrupt::check()?;
    let t0 = std::time::Instant::now();
    let prog = cmd.get_program().to_string_lossy().into_owned();
    let start_err = |e: std::io::Error| {
        if e.kind() == std::io::ErrorKind::NotFound {
            missing(&prog)
        } else {
            Error::Other(format!("{what}: cannot start {prog}: {e}"))
        }
    };
    let child = cmd
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(start_err)?;
    // A signal that ends gbump ends the tool too, rather than leaving it writing on its own.
    let _child = crate::interrupt::child(child.id());
    let out = child.wait_with_output().map_err(|e| Error::Other(format!("{what}: {e}")))?;
    let mut log = String::from_utf8_lossy(&out.stdout).into_owned();
    log += &String::from_utf8_lossy(&out.stderr);
    // A child killed by a signal (a crash, or Ctrl-C reaching the whole process group).
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(sig) = out.status.signal() {
            log += &format!("\n{what}: killed by signal {sig}");
        }
    }
    crate::interrupt::check()?;
    Ok((out.status.success(), log, t0.elapsed().as_secs_f64()))
}

/// The last `n` lines of a log, for error messages.
pub fn tail(log: &str, n: usize) -> String {
    let lines: Vec<&str> = log.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

/// The fix line of a build by `tool` that failed with `log`: a tool that crashed is reinstalled;
/// one that refused the sources names what it refused in the log above the line.
pub fn build_fix(tool: &str, log: &str) -> String {
    // Killed itself, or a compiler it ran (gcc's "Killed signal terminated program cc1plus"
    // when memory ran out).
    if ["killed by signal", "Killed signal", "fatal error: Killed", "out of memory"]
        .iter()
        .any(|k| log.contains(k))
    {
        format!("  fix: {tool} or a compiler it ran was killed (a crash, or memory ran out): check free memory, reinstall it if it happens again (scripts/install-tools.sh), and run again")
    } else {
        format!("  fix: {tool} refused the sources for the reasons above; gbump's own RTL and testbenches compile on the versions scripts/install-tools.sh installs, so an error in them is a gbump bug: report it with the configuration")
    }
}
