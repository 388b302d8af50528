//! Simulators behind one interface, one file each (Icarus Verilog, Verilator), driven as
//! processes. Builds are cached by a hash of every source and flag, so a configuration is
//! compiled once; a run's verdict is the testbench's own "N passed, N failed" line.

pub mod fuzz;
pub mod icarus;
pub mod lint;
pub mod regress;
pub mod rtl_files;
pub mod rtl_image;
pub mod verilator;

/// The testbenches are generated with the RTL; the simulators run them.
pub use crate::rtlgen::testbench;

use crate::error::{Error, Result};
use std::path::Path;
use std::process::Command;

/// The simulators gbump drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Sim {
    Icarus,
    Verilator,
}

impl Sim {
    pub fn name(self) -> &'static str {
        match self {
            Sim::Icarus => "icarus",
            Sim::Verilator => "verilator",
        }
    }
    /// Executables this simulator needs.
    pub fn programs(self) -> &'static [&'static str] {
        match self {
            Sim::Icarus => &["iverilog", "vvp"],
            Sim::Verilator => &["verilator"],
        }
    }
}

/// Whether `prog` runs.
pub fn have(prog: &str) -> bool {
    Command::new(prog).arg("--version").output().is_ok() || Command::new(prog).arg("-V").output().is_ok()
}

/// Error unless every program of `sim` is installed; the message says how to install it.
pub fn require(sim: Sim) -> Result<()> {
    for p in sim.programs() {
        if !have(p) {
            return Err(missing(p));
        }
    }
    Ok(())
}

pub fn missing(prog: &str) -> Error {
    let pkg = match prog {
        "vvp" | "iverilog" => "iverilog",
        p => p,
    };
    Error::Other(format!(
        "{prog} is not installed (or not on PATH)\n  fix: run scripts/install-tools.sh, or apt-get update && apt-get install -y {pkg}"
    ))
}

/// Refuse a folder or file the simulators would be handed that they cannot take whole:
/// Verilator's makefiles split paths at spaces, Verilog string literals end at quotes, and
/// plusargs end at whitespace. `flag` names the option in the message.
pub fn check_tool_path(p: &Path, flag: &str) -> Result<()> {
    let abs = std::path::absolute(p).map_err(|e| Error::io(p, e))?;
    let text = abs.to_string_lossy();
    let bad: Vec<char> = text
        .chars()
        .filter(|c| !c.is_ascii() || c.is_ascii_whitespace() || c.is_ascii_control() || "\"'\\$`;&|<>*?#%!{}()[]=".contains(*c))
        .collect();
    if bad.is_empty() {
        return Ok(());
    }
    Err(Error::Other(format!(
        "{flag} {}: the path holds {} (in {}), which make, Verilator or a plusarg would split or misread\n  fix: use a folder whose absolute path has only letters, digits and - _ . / + , : @ ~",
        p.display(),
        bad.iter().map(|c| format!("{c:?}")).collect::<Vec<_>>().join(" "),
        text
    )))
}

/// Verdict of one simulation run.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub passed: u64,
    pub failed: u64,
    pub seconds: f64,
    pub log: String,
}

/// Parse the testbench's summary line.
pub fn parse_summary(log: &str) -> Option<(u64, u64)> {
    log.lines().rev().find_map(|l| {
        let l = l.trim();
        let (p, rest) = l.split_once(" passed, ")?;
        let f = rest.strip_suffix(" failed")?;
        Some((p.parse().ok()?, f.parse().ok()?))
    })
}

/// Run a command, capturing stdout and stderr together; `what` names it in errors.
pub fn run_cmd(cmd: &mut Command, what: &str) -> Result<(bool, String, f64)> {
    crate::interrupt::check()?;
    let t0 = std::time::Instant::now();
    let out = cmd.output().map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            missing(&cmd.get_program().to_string_lossy())
        } else {
            Error::Other(format!("{what}: cannot start {}: {e}", cmd.get_program().to_string_lossy()))
        }
    })?;
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

/// The cache key of a simulator build: the testbench, every RTL file and waiver, the flags
/// and the versions of the tools involved.
pub fn build_key(kind: &str, source: &str, flags: &[String], rtl: &rtl_files::Rtl, tools: &[&str]) -> Result<String> {
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

/// Lines of a simulation log in which the simulator warned or erred: a memory file that did
/// not load (`$readmemh`), a file that did not open. Any of them fails the run, because the
/// simulation went on with contents nobody meant (X, or an old table).
pub fn simulator_warnings(log: &str) -> Vec<&str> {
    log.lines()
        .filter(|l| {
            let t = l.trim_start();
            let low = t.to_ascii_lowercase();
            t.starts_with("WARNING")
                || t.starts_with("ERROR")
                || t.starts_with("%Warning")
                || t.starts_with("%Error")
                || low.contains("$readmem")
                || low.contains("unable to open")
        })
        .collect()
}

/// Turn a finished run into an outcome, or an error when the testbench did not report, gave
/// up (a FATAL line), or the simulator warned.
pub fn outcome(ok: bool, log: String, secs: f64, what: &str) -> Result<Outcome> {
    let warned = simulator_warnings(&log);
    if !warned.is_empty() {
        return Err(Error::Other(format!(
            "{what}: the simulator warned, so the run does not count (a warning means it went on with contents nobody meant):\n{}\n  fix: {}",
            warned.iter().take(10).copied().collect::<Vec<_>>().join("\n"),
            if warned.iter().any(|l| l.to_ascii_lowercase().contains("readmem")) {
                "a memory init file did not load: check the path given to INIT_FILE (absolute, or relative to the folder the simulator runs in)"
            } else {
                "read the lines above; rerun with --waves to see the signals"
            }
        )));
    }
    if parse_summary(&log) == Some((0, 0)) {
        return Err(Error::Other(format!(
            "{what}: the testbench checked no vectors\n{}",
            tail(&log, 10)
        )));
    }
    if let Some(fatal) = log.lines().find(|l| l.trim_start().starts_with("FATAL")) {
        return Err(Error::Other(format!("{what}: the testbench gave up: {}", fatal.trim())));
    }
    match parse_summary(&log) {
        Some((passed, failed)) => {
            if passed + failed == 0 {
                return Err(Error::Other(format!("{what}: the testbench checked no vectors\n{}", tail(&log, 10))));
            }
            Ok(Outcome { passed, failed, seconds: secs, log })
        }
        None => Err(Error::Other(format!(
            "{what}: the simulation ended without a \"N passed, N failed\" line (exit {}): it crashed or was cut short\n--- last lines ---\n{}",
            if ok { "ok" } else { "non-zero" },
            tail(&log, 15)
        ))),
    }
}
