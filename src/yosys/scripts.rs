//! Every Yosys script gbump runs. Their text is also part of cache keys (sweep points, FPGA
//! synthesis) and of reports, so a change here shows up as rebuilt entries and new headers.

use super::target::Target;
use std::path::Path;

/// The lint's synthesis check: elaborate, fail on latches (`proc` infers them), undriven nets,
/// multiple drivers or combinational loops (`check -assert`, run again after memory inference,
/// `memory -nomap`, so it sees the inferred memories). Synthesis's other word-level passes (`opt`, `wreduce`, `alumacc`,
/// `share`, `fsm`) and gate mapping rewrite a netlist these checks already passed and add
/// none of those defects; they took two thirds of the lint (the renormalising top: 20 s
/// against 6.5 s), and `gbump area` and the FPGA flows run them.
pub fn check(files: &[String], top: &str) -> String {
    let mut s = String::new();
    for f in files {
        s += &format!("read_verilog -defer {f}\n");
    }
    s += &format!("hierarchy -check -top {top}\nproc\nflatten\nopt_clean\ncheck -assert\nselect -assert-none t:$dlatch t:$adlatch t:$dlatchsr\nmemory -nomap\nopt_clean\ncheck -assert\n");
    // Evidence that the script ran to its end on this design: a Yosys that exits 0 without
    // reading it leaves no such file.
    s += &format!("tee -q -o {CHECK_DONE} stat\n");
    s
}

/// The file [`check`]'s last step writes: the elaborated design's statistics, which name
/// its top.
pub const CHECK_DONE: &str = "lint_yosys_stat.txt";

/// Gate-level area of one module: the bits of its RAMs (`rtlgen::ram`) counted first into
/// `memory.json`, then every RAM made a black box, so the logic's NAND/NOR/NOT cells (`abc -g
/// cmos2`, flip-flops unmapped) hold no storage: `stat -json -tech cmos` into `area.json` and
/// `ltp -noff` into `area.ltp`. Any other Verilog array (the top's triangle banks and output
/// buffer) is synthesised as flip-flops and counted there, so no bit is counted twice.
pub fn cmos_area(files: &[String], top: &str) -> String {
    format!(
        "read_verilog -defer {}\nhierarchy -top {top}\ndesign -save elaborated\nproc\nmemory_map {} %n\nflatten\ntee -q -o memory.json stat -json\ndesign -load elaborated\nblackbox {}\nsynth -flatten -top {top}\ndffunmap\nabc -g cmos2\ntee -q -o area.json stat -json -tech cmos\ntee -q -o area.ltp ltp -noff\n",
        files.join(" "),
        ram_modules(),
        ram_modules()
    )
}

/// `stat -json` of the elaborated hierarchy below `top`, flattened, into `file`: its
/// `num_memory_bits` is the storage of every memory, copies included. The hierarchy is saved
/// and restored around it (`stat -top` would mix its text listing into the JSON).
fn memory_stat(_top: &str, file: &str) -> String {
    format!("design -save elaborated\nflatten\ntee -q -o {file} stat -json\ndesign -load elaborated\n")
}

/// A selection of every RAM module of the generated RTL, as elaborated with its parameters.
fn ram_modules() -> String {
    format!("=*{}_*", crate::rtlgen::ram::RAM)
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

/// One module for an FPGA target: its memories' bits into `out/memory.json`, then `stat
/// -json` of the mapped design into `out/stat.json` and, with `netlist`, the JSON netlist into
/// `out/netlist.json` (outputs by absolute path, so it can run in the RTL folder, where the
/// power table's init file loads).
pub fn fpga(target: Target, sources: &[String], top: &str, out: &Path, netlist: bool) -> String {
    let mut s = format!(
        "read_verilog -defer {}\nhierarchy -top {top}\n{}{}",
        sources.join(" "),
        memory_stat(top, &out.join("memory.json").display().to_string()),
        target.synth(top)
    );
    if netlist {
        s += &format!("\nwrite_json {}", out.join("netlist.json").display());
    }
    s + &format!("\ntee -q -o {} stat -json\n", out.join("stat.json").display())
}

/// `fpga` as the report shows it.
pub fn fpga_summary(target: Target) -> String {
    format!(
        "read_verilog -defer <files>; hierarchy -top <module>; stat -json -top <module> (memory bits); {}; stat -json",
        target.synth("<module>")
    )
}
