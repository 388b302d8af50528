//! Every Yosys script gbump runs. Their text is also part of cache keys (sweep points, FPGA
//! synthesis) and of reports, so a change here shows up as rebuilt entries and new headers.

use super::target::Target;
use std::path::Path;

/// The lint's synthesis check: elaborate, fail on latches, undriven nets or combinational
/// loops, before and after `synth`.
pub fn check(files: &[String], top: &str) -> String {
    let mut s = String::new();
    for f in files {
        s += &format!("read_verilog -defer {f}\n");
    }
    s += &format!("hierarchy -check -top {top}\nproc\nflatten\nopt\ncheck -assert\nselect -assert-none t:$dlatch t:$adlatch t:$dlatchsr\nsynth -top {top}\nselect -assert-none t:$_DLATCH_*\ncheck -assert\n");
    s
}

/// Gate-level area of one module: NAND/NOR/NOT cells (`abc -g cmos2`), flip-flops unmapped,
/// `stat -json -tech cmos` into `area.json` and `ltp -noff` into `area.ltp`.
pub fn cmos_area(files: &[String], top: &str) -> String {
    format!(
        "read_verilog -defer {}\nsynth -flatten -top {top}\ndffunmap\nabc -g cmos2\ntee -q -o area.json stat -json -tech cmos\ntee -q -o area.ltp ltp -noff\n",
        files.join(" ")
    )
}

/// A power unit's datapath, its ROM module (`<top>_rom`, when `rom`) a black box: the same
/// gate-level mapping as `cmos_area`, `stat -json -tech cmos` into `area.json`.
pub fn power_datapath(files: &[String], top: &str, rom: bool) -> String {
    let bb = if rom { format!("blackbox {top}_rom\n") } else { String::new() };
    format!(
        "read_verilog -defer {}\nhierarchy -top {top}\n{bb}synth -flatten -top {top}\ndffunmap\nabc -g cmos2\ntee -q -o area.json stat -json -tech cmos\n",
        files.join(" ")
    )
}

/// One module for an FPGA target, `stat -json` into `out/stat.json` and, with `netlist`, the
/// JSON netlist into `out/netlist.json` (outputs by absolute path, so it can run in the RTL
/// folder, where the power table's init file loads).
pub fn fpga(target: Target, sources: &[String], top: &str, out: &Path, netlist: bool) -> String {
    let mut s = format!("read_verilog -defer {}\n{}", sources.join(" "), target.synth(top));
    if netlist {
        s += &format!("\nwrite_json {}", out.join("netlist.json").display());
    }
    s + &format!("\ntee -q -o {} stat -json\n", out.join("stat.json").display())
}

/// `fpga` as the report shows it.
pub fn fpga_summary(target: Target) -> String {
    format!("read_verilog -defer <files>; {}; stat -json", target.synth("<module>"))
}
