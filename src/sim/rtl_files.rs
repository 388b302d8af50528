//! The generated RTL of one configuration as the simulators see it: Verilog sources, lint
//! waivers and the power table's init file, all by absolute path, so a simulation started from
//! any folder finds them.

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

#[derive(Clone, Debug)]
pub struct Rtl {
    pub dir: PathBuf,
    pub sources: Vec<PathBuf>,
    pub waivers: Vec<PathBuf>,
    /// The power table's power-up contents, for the top's `INIT_FILE` parameter.
    pub init_file: PathBuf,
}

/// Write the RTL of `cfg` into `dir`.
pub fn write_rtl(cfg: &PipelineConfig, dir: &Path, command: &str) -> Result<Rtl> {
    let dir = std::path::absolute(dir).map_err(|e| Error::io(dir, e))?;
    let files = crate::rtlgen::generate(cfg, command);
    crate::cli::write_files(&dir, &files)?;
    let with = |ext: &str| files.iter().filter(|f| f.0.ends_with(ext)).map(|f| dir.join(&f.0)).collect();
    Ok(Rtl {
        sources: crate::rtlgen::sources(&files).iter().map(|f| dir.join(f)).collect(),
        waivers: with(".vlt"),
        init_file: dir.join(crate::rtlgen::units_v::rom_file_name(cfg, "power_table", "hex")),
        dir,
    })
}

/// `s` as a Verilog string literal.
pub fn verilog_string(s: &str) -> String {
    format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
}
