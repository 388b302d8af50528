//! The integration kit beside the Verilog: filelists that work from any folder (one per tool
//! where a tool cannot resolve names against the list itself), a FuseSoC CAPI2 core with
//! Icarus and Verilator simulation targets running the generated top testbench, and a
//! SystemVerilog package of widths, formats, record structs and lane helpers.
//!
//! How each tool reads a list (checked by `tests/integration_kit.rs` from another folder):
//! - `verilator -F LIST.f` resolves the names in `LIST.f` against the list's folder;
//! - `iverilog -c LIST` resolves them against the working folder, so Icarus gets its own list
//!   whose names start with `$(GBUMP_RTL)` (Icarus substitutes environment variables in
//!   command files): `GBUMP_RTL=DIR iverilog -c DIR/..._icarus.f`;
//! - Yosys 0.23 has no filelist option, so it gets a Tcl script that reads every source
//!   relative to the script's own folder: `yosys -c DIR/..._yosys.tcl`, or
//!   `yosys -p "tcl DIR/..._yosys.tcl; synth -top TOP"`.

use super::header::header;
use super::top::latency;
use super::units_v::module_name;
use super::GenFile;
use crate::config::PipelineConfig;
use crate::vectors::layout::{Layout, Role};
use crate::vectors::targets::{top_layout, unit_layout};

/// The environment variable the Icarus command file takes the RTL folder from.
pub const ICARUS_DIR_VAR: &str = "GBUMP_RTL";

/// File name of the generated top testbench, its module's name and `.v`.
pub fn tb_file_name(cfg: &PipelineConfig) -> String {
    format!("{}.v", tb_module_name(cfg))
}

/// The generated top testbench's module, `tb_top_<hash8>` as every generated module is named,
/// so the kits of two configurations compile together.
pub fn tb_module_name(cfg: &PipelineConfig) -> String {
    module_name(cfg, "tb_top")
}

/// File name of the SystemVerilog package (package `gbump_pkg_<hash8>`).
pub fn package_file_name(cfg: &PipelineConfig) -> String {
    format!("{}.sv", package_name(cfg))
}

/// Name of the SystemVerilog package.
pub fn package_name(cfg: &PipelineConfig) -> String {
    module_name(cfg, "gbump_pkg")
}

/// File names of the three filelists: (Verilator and any tool reading relative to the list,
/// Icarus, Yosys).
pub fn filelist_names(cfg: &PipelineConfig) -> (String, String, String) {
    let top = module_name(cfg, "gbump_pipeline");
    (format!("{top}.f"), format!("{top}_icarus.f"), format!("{top}_yosys.tcl"))
}

/// The filelists of `sources` (file names in the RTL folder, in compile order).
pub fn filelists(cfg: &PipelineConfig, command: &str, sources: &[String]) -> Vec<GenFile> {
    let (f, fi, fy) = filelist_names(cfg);
    let top = module_name(cfg, "gbump_pipeline");
    let mut plain = header(
        cfg,
        command,
        &format!("Verilog sources of {top}, names relative to this list: verilator -F {f}"),
        "// ",
    );
    plain += &format!("// Lint: verilator --lint-only -Wall {top}.vlt -F {f} --top-module {top}\n");
    plain += &format!("// Icarus resolves names against its working folder: use {fi}; Yosys: {fy}\n");
    for s in sources {
        plain += &format!("{s}\n");
    }
    let mut icarus = header(
        cfg,
        command,
        &format!("Verilog sources of {top} for Icarus, which resolves command-file names against its working folder"),
        "// ",
    );
    icarus += &format!("// Set {ICARUS_DIR_VAR} to this folder: {ICARUS_DIR_VAR}=DIR iverilog -g2005 -s {top} -c DIR/{fi}\n");
    for s in sources {
        icarus += &format!("$({ICARUS_DIR_VAR})/{s}\n");
    }
    let mut tcl = header(
        cfg,
        command,
        &format!("Yosys reads the Verilog sources of {top}, relative to this script, from any folder"),
        "# ",
    );
    tcl += &format!("# yosys -c DIR/{fy}    or    yosys -p \"tcl DIR/{fy}; synth -top {top}\"\n");
    tcl += "set gbump_dir [file dirname [file normalize [info script]]]\n";
    tcl += &format!("foreach gbump_src {{{}}} {{\n", sources.join(" "));
    tcl += "    yosys read_verilog -defer [file join $gbump_dir $gbump_src]\n}\n";
    vec![(f, plain), (fi, icarus), (fy, tcl)]
}

/// The FuseSoC CAPI2 core: the RTL, the power-up file of every memory the top reads (copied
/// into the simulator's working folder, where each relative init parameter finds it), the
/// lint waivers and the top testbench.
pub fn core(cfg: &PipelineConfig, command: &str, sources: &[String]) -> String {
    let top = module_name(cfg, "gbump_pipeline");
    // Every memory the top reads, with its init parameter and file: a file the RTL reads at
    // power-up and the core did not copy left that memory X in every run (EMBM's maps).
    let inits: Vec<(&'static str, String, &'static str)> = super::top::read_memories(cfg)
        .iter()
        .map(|m| (m.init_param, super::top::memory_init_file(cfg, m), m.prefix))
        .collect();
    let params: Vec<&str> = inits.iter().map(|i| i.0).collect();
    let table = super::top::power_table_read(cfg);
    // The top's other memories (EMBM's maps) load from a file the same way, by their prefix.
    let others: Vec<&'static str> = super::testbench::other_memories(cfg).iter().map(|m| m.prefix).collect();
    let vlt = format!("{top}.vlt");
    let mut s = String::from("CAPI=2:\n");
    s += &header(cfg, command, "FuseSoC CAPI2 core of the pipeline and its top testbench", "# ");
    let loads: String = table
        .then(|| " [--table=SET_top_power_table.hex]".to_string())
        .into_iter()
        .chain(others.iter().map(|p| format!(" [--{p}=FILE]")))
        .collect();
    s += &format!(
        "# fusesoc --cores-root DIR run --target sim_icarus gbump:gbump:{top} --vectors=SET_top.hex [--count=N]{loads} [--bubbles=N]\n"
    );
    s += &format!("name: gbump:gbump:{top}:{}\n", env!("CARGO_PKG_VERSION"));
    s += &format!(
        "description: Gouraud bump-mapping pipeline (config {}), latency {} cycles, one fragment every {} cycle(s)\n\n",
        cfg.hash(),
        latency(cfg),
        cfg.initiation_interval()
    );
    s += "filesets:\n  rtl:\n    files:\n";
    for f in sources {
        s += &format!("      - {f}\n");
    }
    for (_, file, _) in &inits {
        s += &format!("      - {file}: {{file_type: user, copyto: {file}}}\n");
    }
    s += "    file_type: verilogSource\n";
    s += &format!("  waivers:\n    files:\n      - {vlt}\n    file_type: vlt\n");
    s += &format!(
        "  package:\n    files:\n      - {}\n    file_type: systemVerilogSource\n",
        package_file_name(cfg)
    );
    s += &format!("  tb:\n    files:\n      - {}\n    file_type: verilogSource\n\n", tb_file_name(cfg));
    s += "targets:\n";
    s += &format!(
        "  default:\n    filesets: [rtl]\n    toplevel: {top}\n    parameters: [{}]\n",
        params.join(", ")
    );
    s += &format!(
        "  lint:\n    default_tool: verilator\n    filesets: [rtl, waivers, package]\n    toplevel: {top}\n    tools:\n      verilator:\n        mode: lint-only\n        verilator_options: [-Wall]\n"
    );
    let tb = tb_module_name(cfg);
    // The testbench declares `INIT_FILE` alone and names the other memories' files itself: a
    // parameter it does not declare is an error to Verilator (`-G` of nothing).
    let plus: Vec<&str> = ["INIT_FILE", "vectors", "count"]
        .into_iter()
        .chain(table.then_some("table"))
        .chain(others.iter().copied())
        .chain(["bubbles", "max_errors"])
        .collect();
    let plus = format!("[{}]", plus.join(", "));
    s += &format!(
        "  sim_icarus:\n    default_tool: icarus\n    filesets: [rtl, tb]\n    toplevel: {tb}\n    parameters: {plus}\n    tools:\n      icarus:\n        iverilog_options: [-g2005, -Wall]\n"
    );
    s += &format!(
        "  sim_verilator:\n    default_tool: verilator\n    filesets: [rtl, waivers, tb]\n    toplevel: {tb}\n    parameters: {plus}\n    tools:\n      verilator:\n        mode: binary\n        verilator_options: [-Wno-lint, -Wno-style]\n\n"
    );
    s += "parameters:\n";
    if !table {
        // The testbench's own parameter, on a top that reads no table.
        s += &format!(
            "  INIT_FILE:\n    datatype: str\n    paramtype: vlogparam\n    default: {}\n    description: not read, as this top has no power table\n",
            super::top::memory_init_file(cfg, &crate::units::table_memory(cfg))
        );
    }
    for (param, file, prefix) in &inits {
        s += &format!(
            "  {param}:\n    datatype: str\n    paramtype: vlogparam\n    default: {file}\n    description: $readmemh file of the {prefix} memory's power-up contents, relative to the simulator's working folder\n"
        );
    }
    s += "  vectors:\n    datatype: file\n    paramtype: plusarg\n    description: top vector set in text form (gbump vectors --target top --format hex), one record per line\n";
    s += "  count:\n    datatype: int\n    paramtype: plusarg\n    description: records the vector file must hold (its manifest's count); without it a file cut at a line boundary runs as a shorter set\n";
    if table {
        s += "  table:\n    datatype: file\n    paramtype: plusarg\n    description: power table loaded through power_table_we/power_table_waddr/power_table_wdata before streaming (the set's _power_table.hex)\n";
    }
    for p in &others {
        s += &format!("  {p}:\n    datatype: file\n    paramtype: plusarg\n    description: contents loaded through {p}_we/{p}_waddr/{p}_wdata before streaming (the _{p}.hex a set's manifest names, where it names one); without it the power-up contents\n");
    }
    s += "  bubbles:\n    datatype: int\n    paramtype: plusarg\n    description: idle in_valid for 1-3 cycles before every Nth record\n";
    s += "  max_errors:\n    datatype: int\n    paramtype: plusarg\n    description: stop after this many mismatches (default 20)\n";
    s
}

/// The SystemVerilog package: formats, widths, timing, record structs and lane helpers.
pub fn package(cfg: &PipelineConfig, command: &str) -> String {
    let name = package_name(cfg);
    let mut s = header(
        cfg,
        command,
        "SystemVerilog package: widths, formats, record structs, lane helpers",
        "// ",
    );
    s += "`timescale 1ns / 1ps\n`default_nettype none\n";
    s += "// A package names every width whether or not a design reads it; the waiver covers only\n";
    s += "// this file.\n// verilator lint_off UNUSEDPARAM\n";
    s += &format!("package {name};\n");
    let p = |s: &mut String, n: &str, v: u64, doc: &str| *s += &format!("    localparam int {n} = {v}; // {doc}\n");
    s += "    // Formats: lane widths in bits (a lane is one component or one light's value).\n";
    p(
        &mut s,
        "COLOUR_BITS",
        cfg.colour_bits.into(),
        &format!("colour code {}, max = 1.0", cfg.colour_fmt().name()),
    );
    p(
        &mut s,
        "NORMAL_BITS",
        cfg.normal_bits.into(),
        "stored bump normal component (`in_bump` lane), offset binary",
    );
    p(
        &mut s,
        "LH_BITS",
        cfg.lh_bits.into(),
        &format!("L_i, H_i component {}", cfg.lh_fmt().name()),
    );
    p(&mut s, "K_BITS", cfg.k_fmt().width.into(), &format!("k_i {}", cfg.k_fmt().name()));
    p(
        &mut s,
        "DOT_BITS",
        cfg.dot_fmt().width.into(),
        &format!("clamped dot product {}", cfg.dot_fmt().name()),
    );
    p(
        &mut s,
        "POWER_BITS",
        cfg.power_fmt().width.into(),
        &format!("power-table entry {}", cfg.power_fmt().name()),
    );
    p(&mut s, "LIGHTS", cfg.lights.into(), "light slots");
    p(&mut s, "SHININESS", cfg.shininess.into(), "shininess of the power-up table");
    s += "    // Timing (rising edges, as the interface JSON defines them).\n";
    p(
        &mut s,
        "LATENCY",
        latency(cfg).into(),
        "latency_cycles: accepting edge to the edge out_valid is first sampled high",
    );
    p(
        &mut s,
        "INITIATION_INTERVAL",
        cfg.initiation_interval().into(),
        "edges between accepts",
    );
    // The rest of the handshake's numbers, each the interface JSON's key of the same name
    // (0 where the JSON has none or null).
    p(
        &mut s,
        "RESET_CYCLES",
        super::top::RESET_CYCLES.into(),
        "rising edges with rst high that reset the top",
    );
    p(
        &mut s,
        "OUTPUT_BUFFER_RESULTS",
        super::top::output_depth(cfg).unwrap_or(0).into(),
        "untaken results the output buffer holds before in_ready falls (0: no back-pressure)",
    );
    let tri = cfg.per_triangle();
    p(
        &mut s,
        "TRIANGLE_BANKS",
        if tri { cfg.triangle_banks.into() } else { 0 },
        "bump_state.banks (0: the state enters with every fragment)",
    );
    p(
        &mut s,
        "BANK_HOLD_CYCLES",
        super::top::bank_hold(cfg).unwrap_or(0).into(),
        "bump_state.bank_hold_cycles: last use of a bank to the first setup that may load it",
    );
    p(
        &mut s,
        "SETUP_EDGES",
        if tri { super::top::setup_edges(cfg).into() } else { 0 },
        "bump_state.setup_edges: the fewest edges a setup spans",
    );
    s += "    // Memories behind the load ports: words, address width and power-up file (the top's\n    // parameter of the same name; relative to the simulator's working folder).\n";
    for m in super::top::memories(cfg) {
        let up = m.prefix.to_uppercase();
        p(
            &mut s,
            &format!("{up}_WORDS"),
            m.depth.into(),
            &format!("words of the {} memory", m.prefix),
        );
        p(
            &mut s,
            &format!("{up}_ADDR_BITS"),
            m.addr_bits.into(),
            &format!("{}_waddr width", m.prefix),
        );
        let file = super::top::memory_init_file(cfg, &m);
        // The power table's port is on every top; where nothing reads it, its doc says so.
        let doc = match m.prefix {
            "power_table" if !super::top::power_table_read(cfg) => super::top::unused_load_docs(cfg).map_or(m.doc, |u| u.1),
            _ => m.doc,
        };
        s += &format!("    localparam {} = \"{file}\"; // {doc}\n", m.init_param);
    }
    s += "    // Top ports.\n";
    for (n, _, w) in super::top::top_ports(cfg) {
        p(&mut s, &format!("{}_BITS", n.to_uppercase()), w.into(), &format!("width of {n}"));
    }
    let mut layouts: Vec<(String, Layout)> = vec![("top".into(), top_layout(cfg))];
    for u in super::testbench::units_of(cfg) {
        layouts.push((u.to_string(), unit_layout(cfg, u)));
    }
    for (what, l) in &layouts {
        let up = what.to_uppercase();
        s += &format!("    // {what} vector record: a $readmemh'd word of {up}_RECORD_BITS bits assigned to a {what}_record_t.\n");
        p(
            &mut s,
            &format!("{up}_RECORD_BITS"),
            l.bits.into(),
            "bits of one record (LSB-first columns)",
        );
        s += "    typedef struct packed {\n";
        for c in l.columns.iter().rev() {
            let role = if c.role == Role::Stimulus { "stimulus" } else { "expected" };
            s += &format!(
                "        logic [{}:0] {}; // bits [{}:{}], {} x {} ({role})\n",
                c.width - 1,
                c.name,
                c.lsb + c.width - 1,
                c.lsb,
                c.lanes,
                c.format
            );
        }
        s += &format!("    }} {what}_record_t;\n");
    }
    s += "    // Lane helpers for the top's data ports: lane 0 in the low bits; per light x, y, z (or\n    // R, G, B), per frame vector x, y, z.\n";
    let st = |f: &str| crate::vectors::targets::state_column(cfg, f);
    let per_light = [st("l"), st("h"), st("lc")];
    for port in super::top::port_list(cfg) {
        use super::top::PortKind;
        let data = matches!(port.kind, PortKind::Fragment | PortKind::Triangle | PortKind::Result)
            || (port.kind == PortKind::Load && port.lanes > 1);
        if !data || port.fmt.width == 1 {
            continue;
        }
        let (args, idx) = if per_light.contains(&port.name) {
            ("input int light, input int axis", "3 * light + axis")
        } else if port.name == crate::vectors::targets::FRAME {
            ("input int vector, input int axis", "3 * vector + axis")
        } else {
            ("input int i", "i")
        };
        let (name, lb) = (&port.name, port.fmt.width);
        let w = format!("{}_BITS", name.to_uppercase());
        s += &format!(
            "    function automatic logic [{}:0] {name}_lane(input logic [{w}-1:0] v, {args}); // {} x {}\n        return v[({idx}) * {lb} +: {lb}];\n    endfunction\n",
            lb - 1,
            port.lanes,
            port.fmt.name()
        );
    }
    s += "endpackage\n// verilator lint_on UNUSEDPARAM\n`default_nettype wire\n";
    s
}
