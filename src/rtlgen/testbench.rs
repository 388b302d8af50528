//! Testbenches from the templates in `testbench/`: the template holds the protocol (reset,
//! table load, streaming, checking, the "N passed, N failed" line); this module fills in the
//! configuration's ports and record slices from the same layouts the vector writer uses.

use super::rtl_set::Rtl;
use super::top::latency;
use super::units_v::module_name;
use super::writer::verilog_string;
use crate::config::PipelineConfig;
use crate::vectors::layout::{Layout, Role};
use crate::vectors::targets::{top_layout, unit_layout};

const TB_TOP: &str = include_str!("../../testbench/tb_top.v.tpl");
const TB_UNITS: &str = include_str!("../../testbench/tb_units.v.tpl");
const HARNESS_TOP: &str = include_str!("../../testbench/harness_top.cpp.tpl");

fn fill(mut t: String, subs: &[(&str, String)]) -> String {
    for (k, v) in subs {
        t = t.replace(&format!("{{{{{k}}}}}"), v);
    }
    assert!(!t.contains("{{"), "unfilled template field");
    t
}

/// The last line of a failed testbench run (its `$fatal` message, exit code 1), which the
/// verdict reads past: the lines before it say what failed.
pub const EXIT_MARK: &str = "gbump testbench: exit code 1, see the lines above";

fn pt(cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
    vec![
        ("EXIT_MARK", EXIT_MARK.to_string()),
        ("RESET_CYCLES", crate::rtlgen::top::RESET_CYCLES.to_string()),
        ("POWER_TABLE_WORDS", cfg.power_depth().to_string()),
        ("POWER_TABLE_ADDR_BITS", cfg.power_addr_bits().to_string()),
        ("POWER_TABLE_DATA_BITS", (cfg.power_frac_bits + 1).to_string()),
    ]
}

fn init_literal(rtl: &Rtl) -> String {
    verilog_string(&rtl.init_file.display().to_string())
}

fn slice(rec: &str, lsb: u32, width: u32) -> String {
    format!("{rec}[{}:{lsb}]", lsb + width - 1)
}

/// The top's memories other than the power table (a palette, EMBM's maps): each loadable
/// from a file by the testbench (`+PREFIX=FILE`) and the harness ([`harness_flag`]).
pub fn other_memories(cfg: &PipelineConfig) -> Vec<crate::units::Memory> {
    crate::rtlgen::top::memories(cfg)
        .into_iter()
        .filter(|m| m.prefix != crate::units::POWER_TABLE)
        .collect()
}

/// The C++ harness's option that loads the memory of load-port prefix `prefix`
/// (`env_diffuse` is `--env-diffuse`).
pub fn harness_flag(prefix: &str) -> String {
    format!("--{}", prefix.replace('_', "-"))
}

/// The top testbench (Icarus and Verilator --binary); the pipeline powers up with `rtl`'s
/// init file.
pub fn tb_top(cfg: &PipelineConfig, rtl: &Rtl) -> String {
    let extra: Vec<(String, String)> = rtl
        .memory_inits
        .iter()
        .map(|(p, _, f)| (p.clone(), verilog_string(&f.display().to_string())))
        .collect();
    tb_top_init(cfg, &init_literal(rtl), &extra)
}

/// The top testbench with `init` (a Verilog string literal) as its `INIT_FILE` default and
/// `extra` (parameter, literal) for the top's other memories.
pub fn tb_top_init(cfg: &PipelineConfig, init: &str, extra: &[(String, String)]) -> String {
    let l = top_layout(cfg);
    let ports = port_names(cfg);
    let mut decls = Vec::new();
    let mut connect = Vec::new();
    let mut assign = Vec::new();
    let mut print = Vec::new();
    // The setup handshake: a fragment-state top has none, so its ready is tied high here.
    if cfg.per_triangle() {
        decls.push("    reg tri_valid = 1'b0;\n    wire tri_ready;".to_string());
        connect.push(".tri_valid(tri_valid), .tri_ready(tri_ready)".to_string());
    } else {
        decls.push("    reg tri_valid = 1'b0;\n    wire tri_ready = 1'b1;".to_string());
    }
    // out_ready follows the +stall pattern; a top without it takes every result offered.
    decls.push("    reg out_ready_r = 1'b1;".to_string());
    if cfg.backpressure {
        decls.push("    wire out_ready = out_ready_r;".to_string());
        connect.push(".out_ready(out_ready)".to_string());
    } else {
        decls.push("    wire out_ready = 1'b1;".to_string());
    }
    for c in &l.columns {
        let r = if c.width > 1 {
            format!("[{}:0] ", c.width - 1)
        } else {
            String::new()
        };
        if c.role == Role::Stimulus {
            decls.push(format!("    reg {r}{} = 0;", c.name));
            assign.push(format!("            {} = {};", c.name, slice("stim", c.lsb, c.width)));
            print.push(format!(
                "                    $display(\"  {:15} %h\", {});",
                c.name,
                slice("chk", c.lsb, c.width)
            ));
        } else {
            decls.push(format!("    wire {r}{};", c.name));
        }
        if ports.contains(&c.name) {
            connect.push(format!(".{0}({0})", c.name));
        }
    }
    // The other memories' load ports idle unless +PREFIX=FILE names contents to load (a set
    // with its own maps); otherwise the vectors assume their power-up contents.
    let mut mem_load = Vec::new();
    for m in other_memories(cfg) {
        for (sig, w) in [("we", 1), ("waddr", m.addr_bits), ("wdata", m.data_bits)] {
            let r = if w > 1 { format!("[{}:0] ", w - 1) } else { String::new() };
            decls.push(format!("    reg {r}{}_{sig} = 0;", m.prefix));
            connect.push(format!(".{0}_{sig}({0}_{sig})", m.prefix));
        }
        let p = m.prefix;
        decls.push(format!(
            "    reg [{}:0] {p}_mem [0:{}];\n    reg [8*512-1:0] {p}_file;\n    integer {p}_fd;",
            m.data_bits - 1,
            m.depth - 1
        ));
        // A file that is missing or short would load x words: refused by name instead.
        mem_load.push(format!(
            "        if ($value$plusargs(\"{p}=%s\", {p}_file)) begin\n            {p}_fd = $fopen({p}_file, \"r\");\n            if ({p}_fd == 0) begin $display(\"FATAL: cannot open %0s\", {p}_file); end_run(1); end\n            $fclose({p}_fd);\n            for (i = 0; i < {d}; i = i + 1) {p}_mem[i] = {{{w}{{1'bx}}}};\n            $readmemh({p}_file, {p}_mem);\n            if (^{p}_mem[{last}] === 1'bx) begin $display(\"FATAL: %0s: fewer than {d} words of {p}\", {p}_file); end_run(1); end\n            for (i = 0; i < {d}; i = i + 1) begin\n                {p}_we = 1'b1; {p}_waddr = i; {p}_wdata = {p}_mem[i];\n                @(negedge clk);\n            end\n            {p}_we = 1'b0;\n        end",
            d = m.depth,
            w = m.data_bits,
            last = m.depth - 1
        ));
    }
    let out = l.column("out_c");
    let mut s = pt(cfg);
    s.extend([
        ("RECORD_BITS", l.bits.to_string()),
        ("HEX_DIGITS", l.hex_digits().to_string()),
        ("LATENCY", latency(cfg).to_string()),
        ("II", cfg.initiation_interval().to_string()),
        ("INIT_FILE", init.to_string()),
        (
            "DUT_PARAMS",
            std::iter::once(".INIT_FILE(INIT_FILE)".to_string())
                .chain(extra.iter().map(|(p, v)| format!(".{p}({v})")))
                .collect::<Vec<_>>()
                .join(", "),
        ),
        ("TOP", module_name(cfg, "gbump_pipeline")),
        ("TB_MODULE", crate::rtlgen::kit::tb_module_name(cfg)),
        ("DECLS", decls.join("\n")),
        ("CONNECT", format!("        {}", connect.join(", "))),
        ("ASSIGN", assign.join("\n")),
        ("PRINT", print.join("\n")),
        ("OUT_HI", (out.lsb + out.width - 1).to_string()),
        ("OUT_LO", out.lsb.to_string()),
        ("TRI_START", tri_start_bit(&l).map_or("1'b0".into(), |b| format!("stim[{b}]"))),
        ("MEM_LOAD", mem_load.join("\n")),
    ]);
    s.extend(banks(cfg));
    s.push(("OUT_DEPTH", crate::rtlgen::top::output_depth(cfg).unwrap_or(0).to_string()));
    fill(TB_TOP.to_string(), &s)
}

/// The banks, the bank hold and the setup's edges a testbench checks every setup against (one bank that is never
/// loaded when the top has no setup port).
fn banks(cfg: &PipelineConfig) -> [(&'static str, String); 3] {
    let hold = crate::rtlgen::top::bank_hold(cfg);
    [
        ("TRI_BANKS", if hold.is_some() { cfg.triangle_banks } else { 1 }.to_string()),
        ("BANK_HOLD", hold.unwrap_or(0).to_string()),
        ("SETUP_EDGES", crate::rtlgen::top::setup_edges(cfg).to_string()),
    ]
}

/// The names of the top's ports (a vector column that is not one, `tri_start`, is not driven).
fn port_names(cfg: &PipelineConfig) -> Vec<String> {
    crate::rtlgen::top::port_list(cfg).into_iter().map(|p| p.name).collect()
}

/// The bit of a top record that marks a triangle's first fragment, when the top has setups.
fn tri_start_bit(l: &Layout) -> Option<u32> {
    l.columns
        .iter()
        .find(|c| c.name == crate::vectors::targets::TRI_START)
        .map(|c| c.lsb)
}

/// Units present in this configuration, in `UNITS` order.
pub fn units_of(cfg: &PipelineConfig) -> Vec<&'static str> {
    crate::units::included(cfg).iter().map(|u| u.name()).collect()
}

/// The all-units testbench.
pub fn tb_units(cfg: &PipelineConfig, rtl: &Rtl) -> String {
    let mut decls = Vec::new();
    let mut lats = Vec::new();
    let mut drive = Vec::new();
    let mut check = Vec::new();
    let mut max_rb = 1;
    let mut max_lat = 1;
    for (i, u) in units_of(cfg).iter().enumerate() {
        let l: Layout = unit_layout(cfg, u);
        max_rb = max_rb.max(l.bits);
        let mut conns = vec![".clk(clk)".to_string()];
        if *u == "power_unit" {
            conns.extend([
                ".we(power_table_we)".into(),
                ".waddr(power_table_waddr)".into(),
                ".wdata(power_table_wdata)".into(),
            ]);
        } else if crate::units::unit(u).and_then(|x| x.memory(cfg)).is_some() {
            // Other memories run on their power-up contents, which the unit vectors assume.
            conns.extend([".we(1'b0)".into(), ".waddr(0)".into(), ".wdata(0)".into()]);
        }
        let kw = if i == 0 { "if" } else { "else if" };
        let mut d = vec![format!("            {kw} (unit == \"{u}\") begin")];
        let unit = crate::units::unit(u).expect("unit");
        let lat = unit.latency(cfg);
        // Every unit registers its outputs: a record is checked at least one edge after it enters.
        assert!(lat >= 1, "unit {u}: latency 0");
        max_lat = max_lat.max(lat);
        lats.push(format!("        {kw} (unit == \"{u}\") lat = {lat};"));
        let mut k = vec![format!("                {kw} (unit == \"{u}\") begin")];
        for c in &l.columns {
            let sig = format!("{u}_{}", c.name);
            let r = if c.width > 1 {
                format!("[{}:0] ", c.width - 1)
            } else {
                String::new()
            };
            if c.role == Role::Stimulus {
                assert!(c.enters < lat, "unit {u}: {} enters after the output is sampled", c.name);
                decls.push(format!("    reg {r}{sig} = 0;"));
                d.push(format!(
                    "                {sig} = {};",
                    slice(&format!("hist[{}]", c.enters), c.lsb, c.width)
                ));
            } else {
                decls.push(format!("    wire {r}{sig};"));
                k.push(format!("                    if ({sig} !== {}) begin", slice("chk", c.lsb, c.width)));
                k.push("                        ok = 1'b0;".into());
                k.push("                        if (failed < max_errors) begin".into());
                k.push(format!(
                    "                            $display(\"MISMATCH unit {u} vector %0d:\", m);"
                ));
                for ci in l.columns.iter().filter(|x| x.role == Role::Stimulus) {
                    k.push(format!(
                        "                            $display(\"  {:10} %h\", {});",
                        ci.name,
                        slice("chk", ci.lsb, ci.width)
                    ));
                }
                k.push(format!(
                    "                            $display(\"  {} expected %h got %h\", {}, {sig});",
                    c.name,
                    slice("chk", c.lsb, c.width)
                ));
                k.push("                        end".into());
                k.push("                    end".into());
            }
            conns.push(format!(".{}({sig})", c.name));
        }
        d.push("            end".into());
        k.push("                end".into());
        drive.extend(d);
        check.extend(k);
        let params = if *u == "power_unit" {
            format!(" #(.R(1), .INIT_FILE({}))", init_literal(rtl))
        } else if let Some((_, _, f)) = rtl.memory_inits.iter().find(|m| m.1 == *u) {
            format!(" #(.INIT_FILE({}))", verilog_string(&f.display().to_string()))
        } else {
            String::new()
        };
        decls.push(format!("    {}{params} u_{u} ({});", module_name(cfg, u), conns.join(", ")));
    }
    lats.push("        else begin $display(\"FATAL: unknown unit %0s\", unit); end_run(1); end".into());
    let mut s = pt(cfg);
    s.extend([
        ("DECLS", decls.join("\n")),
        ("LAT", lats.join("\n")),
        ("DRIVE", drive.join("\n")),
        ("CHECK", check.join("\n")),
        ("MAX_RB", max_rb.to_string()),
        ("MAX_LAT", max_lat.to_string()),
    ]);
    fill(TB_UNITS.to_string(), &s)
}

/// The Verilator C++ harness for binary top vectors.
pub fn harness_top(cfg: &PipelineConfig) -> String {
    let l = top_layout(cfg);
    let ports = port_names(cfg);
    let mut assign = Vec::new();
    let mut print = Vec::new();
    for c in l.columns.iter().filter(|c| c.role == Role::Stimulus) {
        // tri_start is read by the harness, not driven.
        if ports.contains(&c.name) {
            assign.push(if c.width <= 64 {
                format!("            top.{} = get_bits(rin, {}, {});", c.name, c.lsb, c.width)
            } else {
                let words = c.width.div_ceil(32);
                format!(
                    "            for (unsigned w = 0; w < {words}; ++w) top.{}[w] = (uint32_t)get_bits(rin, {} + 32 * w, w + 1 < {words} ? 32 : {});",
                    c.name,
                    c.lsb,
                    c.width - 32 * (words - 1)
                )
            });
        }
        let words = c.width.div_ceil(32);
        let mut p = format!("                    printf(\"  {:15} \");", c.name);
        p += &format!(
            " for (int w = {}; w >= 0; --w) printf(\"%08llx\", (unsigned long long)get_bits(rec, {} + 32 * w, w + 1 < {words} ? 32 : {}));",
            words - 1,
            c.lsb,
            c.width - 32 * (words - 1)
        );
        p += " printf(\"\\n\");";
        print.push(p);
    }
    let (mut vars, mut args, mut read, mut load) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for m in other_memories(cfg) {
        let p = m.prefix;
        assign.push(format!("            top.{p}_we = 0;"));
        // Verilator gives a port of up to 64 bits a plain integer; wider would be a VlWide.
        assert!(m.data_bits <= 64, "{p}: a load port wider than 64 bits");
        vars.push(format!("    const char* {p}_path = nullptr;\n    std::vector<uint64_t> {p}_words;"));
        args.push(format!(
            "        else if (!strcmp(argv[i], \"{}\") && i + 1 < argc) {p}_path = argv[++i];",
            harness_flag(p)
        ));
        read.push(format!(
            "    if ({p}_path && !read_words({p}_path, {p}_words, {d})) {{ fprintf(stderr, \"FATAL: %s: expected %d words of {p}\\n\", {p}_path, {d}); return 2; }}",
            d = m.depth
        ));
        load.push(format!(
            "    if ({p}_path)\n        for (int i = 0; i < {d}; ++i) {{ top.{p}_we = 1; top.{p}_waddr = i; top.{p}_wdata = {p}_words[i]; tick(); }}\n    top.{p}_we = 0;",
            d = m.depth
        ));
    }
    let out = l.column("out_c");
    let mut s = pt(cfg);
    s.extend([
        ("TOP", module_name(cfg, "gbump_pipeline")),
        ("RECORD_BYTES", l.bytes().to_string()),
        ("LATENCY", latency(cfg).to_string()),
        ("ASSIGN", assign.join("\n")),
        ("PRINT", print.join("\n")),
        ("OUT_LSB", out.lsb.to_string()),
        ("OUT_W", out.width.to_string()),
        ("II", cfg.initiation_interval().to_string()),
        ("MEM_VARS", vars.join("\n")),
        ("MEM_ARGS", args.join("\n")),
        ("MEM_READ", read.join("\n")),
        ("MEM_LOAD", load.join("\n")),
        (
            "TRI_START",
            tri_start_bit(&l).map_or("false".into(), |b| format!("(get_bits(rin, {b}, 1) != 0)")),
        ),
    ]);
    s.extend(banks(cfg));
    s.push(("OUT_DEPTH", crate::rtlgen::top::output_depth(cfg).unwrap_or(0).to_string()));
    let bp = cfg.backpressure;
    s.push(("OUT_READY_1", if bp { "top.out_ready = 1;" } else { "" }.to_string()));
    s.push((
        "OUT_READY_SET",
        if bp { "top.out_ready = out_ready;" } else { "out_ready = true;" }.to_string(),
    ));
    let tri = cfg.per_triangle();
    s.extend([
        ("TRI_VALID_0", if tri { "top.tri_valid = 0;" } else { "" }.to_string()),
        ("TRI_VALID_1", if tri { "top.tri_valid = 1;" } else { "" }.to_string()),
        (
            "TRI_ACCEPT",
            if tri { "top.tri_valid && top.tri_ready" } else { "false" }.to_string(),
        ),
        (
            "RAW_SETUP",
            if tri {
                "top.tri_valid = 1; top.clk = 0; top.eval(); while (!top.tri_ready) tick(); tick(); top.tri_valid = 0;"
            } else {
                ""
            }
            .to_string(),
        ),
    ]);
    fill(HARNESS_TOP.to_string(), &s)
}
