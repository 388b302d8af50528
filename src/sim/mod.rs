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

/// Refuse a folder or file the simulators would be handed that they cannot take whole:
/// Verilator's makefiles split paths at spaces, Verilog string literals end at quotes, and
/// plusargs end at whitespace. `flag` names the option in the message.
pub fn check_tool_path(p: &Path, flag: &str) -> Result<()> {
    let abs = std::path::absolute(p).map_err(|e| Error::io(p, e))?;
    let text = abs.to_string_lossy();
    let bad: Vec<char> = text
        .chars()
        .filter(|c| !c.is_ascii() || c.is_ascii_whitespace() || c.is_ascii_control() || "\"'\\$`;&|<>*?#%!{}()[]=:".contains(*c))
        .collect();
    if bad.is_empty() {
        return Ok(());
    }
    Err(Error::Other(format!(
        "{flag} {}: the path holds {} (in {}), which make (a `:` is its rule separator), Verilator or a plusarg would split or misread\n  fix: use a folder whose absolute path has only letters, digits and - _ . / + , @ ~",
        p.display(),
        bad.iter().map(|c| format!("{c:?}")).collect::<Vec<_>>().join(" "),
        text
    )))
}
