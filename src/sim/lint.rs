//! `gbump lint`: the three tools' opinions of the generated RTL. Verilator `--lint-only -Wall`
//! (with the checked-in waivers) and `iverilog -Wall` on every module as top; Yosys
//! synthesises the pipeline and fails on latches, undriven nets or combinational loops.

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::rtlgen::units_v::module_name;
use crate::sim::{run_cmd, tail};
use std::path::Path;
use std::process::Command;

/// Yosys script of the synthesis check.
pub fn yosys_check_script(files: &[String], top: &str) -> String {
    let mut s = String::new();
    for f in files {
        s += &format!("read_verilog -defer {f}\n");
    }
    s += &format!("hierarchy -check -top {top}\nproc\nflatten\nopt\ncheck -assert\nselect -assert-none t:$dlatch t:$adlatch t:$dlatchsr\nsynth -top {top}\nselect -assert-none t:$_DLATCH_*\ncheck -assert\n");
    s
}

pub fn lint(cfg: &PipelineConfig, work: &Path, pick_args: &str) -> Result<()> {
    for p in ["verilator", "iverilog", "yosys"] {
        if !crate::sim::have(p) {
            return Err(crate::sim::missing(p));
        }
    }
    let dir = work.join(format!("rtl_{}", &cfg.hash()[..8]));
    let crate::sim::rtl_files::Rtl {
        sources: v, waivers: vlt, ..
    } = crate::sim::regress::write_rtl(cfg, &dir, &format!("gbump rtl {pick_args} --out {}", dir.display()))?;
    let files: Vec<String> = v.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    let waivers: Vec<String> = vlt.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    let mut problems = Vec::new();
    let progress = crate::progress::Progress::new("lint", files.len() as u64 + 2);
    for f in &files {
        let top = f.trim_end_matches(".v");
        progress.start(&format!("verilator -Wall --top-module {top}"));
        let mut c = Command::new("verilator");
        c.args(["--lint-only", "-Wall", "--top-module", top])
            .args(&waivers)
            .args(&files)
            .current_dir(&dir);
        let (ok, log, _) = run_cmd(&mut c, "verilator --lint-only")?;
        if !ok || log.contains("%Warning") {
            problems.push(format!("verilator --lint-only -Wall --top-module {top}:\n{}", tail(&log, 20)));
        }
        progress.done(&format!("verilator --top-module {top}"));
    }
    progress.start("iverilog -Wall");
    let mut c = Command::new("iverilog");
    c.args(["-g2005", "-Wall", "-o", "/dev/null"]).args(&files).current_dir(&dir);
    let (ok, log, _) = run_cmd(&mut c, "iverilog -Wall")?;
    if !ok || !log.trim().is_empty() {
        problems.push(format!("iverilog -g2005 -Wall:\n{}", tail(&log, 20)));
    }
    progress.done("iverilog -Wall");
    progress.start("yosys synthesis check");
    let top = module_name(cfg, "gbump_pipeline");
    let script = yosys_check_script(&files, &top);
    let sp = dir.join("lint.ys");
    std::fs::write(&sp, &script).map_err(|e| Error::io(&sp, e))?;
    let mut c = Command::new("yosys");
    c.args(["-q", "-s", "lint.ys"]).current_dir(&dir);
    let (ok, log, _) = run_cmd(&mut c, "yosys")?;
    if !ok {
        problems.push(format!("yosys synthesis check ({}):\n{}", sp.display(), tail(&log, 20)));
    }
    progress.done("yosys synthesis check");
    drop(progress);
    println!(
        "lint config {}: verilator ({} tops), iverilog, yosys: {}",
        cfg.hash(),
        files.len(),
        if problems.is_empty() { "clean" } else { "PROBLEMS" }
    );
    if problems.is_empty() {
        Ok(())
    } else {
        Err(Error::Other(problems.join("\n\n")))
    }
}
