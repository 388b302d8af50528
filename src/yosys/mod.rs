//! Yosys, in one place: every script gbump runs (`scripts.rs`), the one way it is run
//! (`run`), and every reader of what it writes (`stat.rs` for `stat -json`, `ltp.rs` for
//! `ltp -noff`, `target.rs` for the FPGA cell libraries). The lint's synthesis check and
//! every measurement (CMOS area, FPGA resources, the power units' datapaths) use it, so it
//! sits below both `sim` and `measure`.

pub mod ltp;
pub mod scripts;
pub mod stat;
pub mod target;

use crate::error::{Error, Result};
use std::path::Path;

/// Error unless Yosys is installed; the message says how to install it.
pub fn require() -> Result<()> {
    crate::tool::require("yosys")
}

/// The version line that goes into reports and cache keys.
pub fn version() -> String {
    crate::cache::tool_version("yosys")
}

/// Write `script` as `file` and run it with `yosys -q -s file` from `cwd` (a relative `file`
/// is relative to `cwd`): (success, log). Every file of `outputs` (relative to `cwd`) is
/// removed first, so a report an earlier run left there never stands in for this one.
pub fn run(script: &str, file: &Path, cwd: &Path, outputs: &[&str]) -> Result<(bool, String)> {
    crate::render::output::make_folder(cwd)?;
    let path = cwd.join(file);
    std::fs::write(&path, script).map_err(|e| Error::io(&path, e))?;
    for o in outputs {
        let _ = std::fs::remove_file(cwd.join(o));
    }
    let mut c = std::process::Command::new("yosys");
    c.arg("-q").arg("-s").arg(file).current_dir(cwd);
    let (ok, log, _) = crate::tool::run_cmd(&mut c, "yosys")?;
    Ok((ok, log))
}
