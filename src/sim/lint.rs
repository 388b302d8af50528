//! `gbump lint`: the three tools' opinions of the generated RTL. Verilator `--lint-only -Wall`
//! (with the checked-in waivers) on every module as top and `iverilog -Wall` (both through
//! `Simulator::lint`); Yosys elaborates the pipeline and fails on latches, undriven nets,
//! multiple drivers or combinational loops (`yosys::scripts::check`).

use super::{Icarus, Simulator, Verilator};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::rtlgen::units_v::module_name;
use crate::tool::tail;
use std::path::Path;

/// Error unless every linter is installed (the message says how to install it).
pub fn require_tools() -> Result<()> {
    ["verilator", "iverilog", "yosys"].iter().try_for_each(|p| crate::tool::require(p))
}

/// Lint `cfg`'s RTL (written under `work`; `pick_args` selects it in the files' headers); the
/// verdict line goes to `say`, the problems into the error.
pub fn lint(cfg: &PipelineConfig, work: &Path, pick_args: &str, say: &mut dyn FnMut(&str) -> Result<()>) -> Result<()> {
    require_tools()?;
    let dir = work.join(format!("rtl_{}", &cfg.hash()[..8]));
    let super::rtl_files::Rtl {
        sources: v, waivers: vlt, ..
    } = super::rtl_files::write_rtl(
        cfg,
        &dir,
        &format!("gbump rtl {pick_args} --out {}", crate::shell::quoted(&dir.display().to_string())),
    )?;
    let files: Vec<String> = v.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    let waivers: Vec<String> = vlt.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    let mut problems = Vec::new();
    let progress = crate::progress::Progress::new("lint", files.len() as u64 + 2);
    for f in &files {
        let top = f.trim_end_matches(".v");
        progress.start(&format!("verilator -Wall --top-module {top}"));
        if let Some(log) = Verilator.lint(&dir, &files, &waivers, Some(top))? {
            problems.push(format!("verilator --lint-only -Wall --top-module {top}:\n{}", tail(&log, 20)));
        }
        progress.done(&format!("verilator --top-module {top}"));
    }
    progress.start("iverilog -Wall");
    if let Some(log) = Icarus.lint(&dir, &files, &[], None)? {
        problems.push(format!("iverilog -g2005 -Wall:\n{}", tail(&log, 20)));
    }
    progress.done("iverilog -Wall");
    progress.start("yosys synthesis check");
    let top = module_name(cfg, "gbump_pipeline");
    let sp = dir.join("lint.ys");
    let done = dir.join(crate::yosys::scripts::CHECK_DONE);
    let _ = std::fs::remove_file(&done);
    let (ok, log) = crate::yosys::run(&crate::yosys::scripts::check(&files, &top), Path::new("lint.ys"), &dir, &[])?;
    if !ok {
        problems.push(format!("yosys synthesis check ({}):\n{}", sp.display(), tail(&log, 20)));
    } else if !std::fs::read_to_string(&done).is_ok_and(|t| t.contains(&top)) {
        problems.push(crate::tool::did_not_run(
            "yosys",
            &format!("its script's last step writes {}", done.display()),
            &log,
        ));
    }
    progress.done("yosys synthesis check");
    drop(progress);
    say(&format!(
        "lint config {}: verilator ({} tops), iverilog, yosys: {}",
        cfg.hash(),
        files.len(),
        if problems.is_empty() { "clean" } else { "PROBLEMS" }
    ))?;
    if problems.is_empty() {
        Ok(())
    } else {
        Err(Error::Other(problems.join("\n\n")))
    }
}
