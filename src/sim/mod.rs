//! Simulators behind one interface (`Simulator`, in `simulator.rs`), one file each (Icarus
//! Verilog, Verilator), driven as processes. Builds are cached by a hash of every source and
//! flag, so a configuration is compiled once; a run's verdict is the testbench's own
//! "N passed, N failed" line (`verdict.rs`).

pub mod fuzz;
pub mod icarus;
pub mod lint;
pub mod regress;
pub mod regress_cmd;
pub mod rtl_files;
pub mod rtl_image;
pub mod simulator;
pub mod stream;
pub mod summary;
pub mod verdict;
pub mod verilator;
pub mod verilator_runtime;

/// The testbenches are generated with the RTL; the simulators run them.
pub use crate::rtlgen::testbench;
pub use icarus::Icarus;
pub use simulator::{Simulator, Testbench};
pub use verdict::{outcome, parse_summary, simulator_warnings, Outcome};
pub use verilator::Verilator;

use crate::error::{Error, Result};
use std::path::Path;

/// The simulators gbump drives (the values of `--sim`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Sim {
    Icarus,
    Verilator,
}

impl Sim {
    /// Its implementation.
    pub fn simulator(self) -> &'static dyn Simulator {
        match self {
            Sim::Icarus => &Icarus,
            Sim::Verilator => &Verilator,
        }
    }
    pub fn name(self) -> &'static str {
        self.simulator().name()
    }
}

/// Error unless every program of `sim` is installed; the message says how to install it.
pub fn require(sim: Sim) -> Result<()> {
    sim.simulator().programs().iter().try_for_each(|p| crate::tool::require(p))?;
    if sim == Sim::Verilator {
        verilator_recent_enough(&crate::cache::tool_version("verilator"))?;
        // Verilator builds its model with make and the C++ compiler make calls: $CXX, else g++.
        let cxx = std::env::var("CXX")
            .ok()
            .filter(|c| !c.trim().is_empty())
            .unwrap_or_else(|| "g++".into());
        let prog = cxx.split_whitespace().next().unwrap_or("g++").to_string();
        crate::tool::require(&prog)?;
    }
    Ok(())
}

/// The oldest Verilator major release gbump's benches build under: 4.x has no `--timing`
/// or `--main`, and failed on them with an option error that did not name its version.
pub const MIN_VERILATOR_MAJOR: u32 = 5;

/// Refuse a Verilator whose `--version` line (`Verilator 4.038 2020-07-11 ...`) names a
/// release older than [`MIN_VERILATOR_MAJOR`]; a line that names none is let through.
pub fn verilator_recent_enough(version: &str) -> Result<()> {
    let major = version
        .split_whitespace()
        .nth(1)
        .and_then(|v| v.split('.').next())
        .and_then(|m| m.parse::<u32>().ok());
    match major {
        Some(m) if m < MIN_VERILATOR_MAJOR => Err(Error::Other(format!(
            "verilator ({}) is `{version}`: gbump's testbenches need Verilator {MIN_VERILATOR_MAJOR} or later (they build with --timing and --main; the suite runs Debian bookworm's 5.006)\n  fix: install Verilator {MIN_VERILATOR_MAJOR} or later (scripts/install-tools.sh on Debian bookworm; elsewhere a newer package or a build from source) and put it first on PATH",
            crate::tool::located("verilator")
        ))),
        _ => Ok(()),
    }
}

/// Refuse a folder or file the simulators would be handed that they cannot take whole:
/// Verilator's makefiles split paths at spaces, Verilog string literals end at quotes, and
/// plusargs end at whitespace. `flag` names the option in the message.
pub fn check_tool_path(p: &Path, flag: &str) -> Result<()> {
    refuse_chars(
        p,
        flag,
        |c| !c.is_ascii() || c.is_ascii_whitespace() || c.is_ascii_control() || "\"'\\$`;&|<>*?#%!{}()[]=:".contains(c),
        "make (a `:` is its rule separator), Verilator or a plusarg would split or misread\n  fix: use a folder whose absolute path has only letters, digits and - _ . / + , @ ~",
    )
}

/// Refuse an output folder whose files a filelist (`-F`, `-c`) or a plusarg will name when
/// its path holds white space or a quote, which those split or misread, before anything is
/// written. (Other characters, non-ASCII letters among them, go through; `regress` checks
/// the paths it hands to make with [`check_tool_path`].)
pub fn check_out_path(p: &Path) -> Result<()> {
    refuse_chars(
        p,
        "--out",
        |c| c.is_whitespace() || "\"'`".contains(c),
        "Verilator and Icarus filelists and plusargs split or misread\n  fix: give a folder whose path has no spaces or quotes",
    )?;
    // Characters a filelist takes but `gbump regress` and `cosim` refuse (make reads `:`
    // and `=`): written all the same, for the user's own flow, with a word on what follows.
    if let Err(e) = check_tool_path(p, "--out") {
        let why = e.to_string();
        crate::warn::warn(format!(
            "note: `gbump regress --vectors` and `gbump cosim --rtl` will refuse this folder: {}; your own filelists and testbench can take it",
            why.lines().next().unwrap_or_default()
        ));
    }
    Ok(())
}

/// Refuse `p` when its absolute path holds a character `bad` names; the message says which,
/// then `why` (the tools that would misread it, and the fix).
fn refuse_chars(p: &Path, flag: &str, bad: impl Fn(char) -> bool, why: &str) -> Result<()> {
    let abs = std::path::absolute(p).map_err(|e| Error::io(p, e))?;
    // Where the tools really work: a symbolic link on the way may lead to such a path too.
    let real = abs
        .ancestors()
        .find_map(|a| Some((a, std::fs::canonicalize(a).ok()?)))
        .map(|(a, c)| c.join(abs.strip_prefix(a).unwrap_or(Path::new(""))))
        .filter(|r| *r != abs);
    let linked = real.filter(|r| r.to_string_lossy().chars().any(&bad));
    let checked = linked.as_ref().unwrap_or(&abs).to_string_lossy().into_owned();
    let text = match &linked {
        Some(r) => format!("{} (through a link: {})", abs.display(), r.display()),
        None => checked.clone(),
    };
    let found: Vec<String> = checked.chars().filter(|&c| bad(c)).map(|c| format!("{c:?}")).collect();
    if found.is_empty() {
        return Ok(());
    }
    Err(Error::Other(format!(
        "{flag} {}: the path holds {} (in {text}), which {why}",
        p.display(),
        found.join(" ")
    )))
}
