//! A configuration's generated RTL as the simulators see it: Verilog sources, lint waivers
//! and the power table's init file, all by absolute path, so a simulation started from any
//! folder finds them.

use std::path::PathBuf;

#[derive(Clone, Debug)]
pub struct Rtl {
    pub dir: PathBuf,
    pub sources: Vec<PathBuf>,
    pub waivers: Vec<PathBuf>,
    /// The power table's power-up contents, for the top's `INIT_FILE` parameter.
    pub init_file: PathBuf,
    /// The other memories' power-up contents: (the top's parameter, the unit, the file).
    pub memory_inits: Vec<(String, String, PathBuf)>,
}
