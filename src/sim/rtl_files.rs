//! Writing a configuration's RTL where the simulators will read it (see `rtlgen::rtl_set`).

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
pub use crate::rtlgen::rtl_set::Rtl;
pub use crate::rtlgen::writer::verilog_string;
use std::path::Path;

/// The RTL a regression of `cfg` (selected by `pick_args`) runs, in `work/rtl_HASH`, its header
/// naming the `gbump rtl` command that writes the same files.
pub fn regression_rtl(cfg: &PipelineConfig, pick_args: &str, work: &Path) -> Result<Rtl> {
    let dir = work.join(format!("rtl_{}", &cfg.hash()[..8]));
    let command = format!("gbump rtl {pick_args} --out {}", crate::shell::quoted(&dir.display().to_string()));
    write_rtl(cfg, &dir, &command)
}

/// Write the RTL of `cfg` into `dir`.
pub fn write_rtl(cfg: &PipelineConfig, dir: &Path, command: &str) -> Result<Rtl> {
    let dir = std::path::absolute(dir).map_err(|e| Error::io(dir, e))?;
    let files = crate::rtlgen::generate(cfg, command);
    crate::render::output::write_files(&dir, &files)?;
    Ok(Rtl {
        sources: crate::rtlgen::sources(&files).iter().map(|f| dir.join(f)).collect(),
        waivers: files.iter().filter(|f| f.0.ends_with(".vlt")).map(|f| dir.join(&f.0)).collect(),
        init_file: dir.join(crate::rtlgen::units_v::rom_file_name(cfg, "power_table", "hex")),
        memory_inits: crate::rtlgen::top::memory_inits(cfg)
            .into_iter()
            .map(|(param, unit, file)| (param, unit, dir.join(file)))
            .collect(),
        dir,
    })
}
