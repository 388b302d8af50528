//! The lockstep testbench (`testbench/tb_cosim.sv.tpl`) filled from an RTL folder's interface
//! JSON alone: the protocol ports by their documented names, every other input port driven
//! from the model's record column of the same name (offsets asked of libgbump at run time),
//! every other output port checked against the model's expected column of that name.

use crate::error::{Error, Result};
use crate::rtlgen::writer::verilog_string;
use serde_json::Value;
use std::path::Path;

const TB_COSIM: &str = include_str!("../../testbench/tb_cosim.sv.tpl");

/// Ports the template drives or reads by name.
const PROTOCOL: [&str; 8] = [
    "clk",
    "rst",
    "power_table_we",
    "power_table_waddr",
    "power_table_wdata",
    "in_valid",
    "in_ready",
    "out_valid",
];

/// The setup handshake of a per-triangle top, driven by name when the top has it.
const SETUP: [&str; 2] = ["tri_valid", "tri_ready"];

/// Back-pressure, when the top has it: held high, so every result comes at its latency.
const OUT_READY: &str = "out_ready";

/// One port of the interface JSON.
struct Port {
    name: String,
    output: bool,
    width: u64,
    /// A triangle-setup field: packed from what the top took at the setup's edge.
    triangle: bool,
}

fn field<'a>(j: &'a Value, path: &[&str], file: &Path) -> Result<&'a Value> {
    path.iter().try_fold(j, |v, k| v.get(k)).ok_or_else(|| {
        Error::Other(format!(
            "{}: no `{}`\n  fix: regenerate the folder with `gbump rtl --out DIR` (this gbump's interface format)",
            file.display(),
            path.join(".")
        ))
    })
}

fn num(j: &Value, path: &[&str], file: &Path) -> Result<u64> {
    field(j, path, file)?.as_u64().ok_or_else(|| {
        Error::Other(format!(
            "{}: `{}` is not a count\n  fix: regenerate the folder with `gbump rtl --out DIR`",
            file.display(),
            path.join(".")
        ))
    })
}

pub fn text<'a>(j: &'a Value, path: &[&str], file: &Path) -> Result<&'a str> {
    field(j, path, file)?.as_str().ok_or_else(|| {
        Error::Other(format!(
            "{}: `{}` is not a string\n  fix: regenerate the folder with `gbump rtl --out DIR`",
            file.display(),
            path.join(".")
        ))
    })
}

fn ports(j: &Value, file: &Path) -> Result<Vec<Port>> {
    let list = field(j, &["ports"], file)?.as_array().cloned().unwrap_or_default();
    let ps = list
        .iter()
        .map(|p| {
            Ok(Port {
                name: text(p, &["name"], file)?.to_string(),
                output: text(p, &["dir"], file)? == "output",
                width: num(p, &["width"], file)?,
                triangle: text(p, &["kind"], file)? == "triangle",
            })
        })
        .collect::<Result<Vec<_>>>()?;
    for want in PROTOCOL {
        if !ps.iter().any(|p| p.name == want) {
            return Err(Error::Other(format!(
                "{}: the top has no port `{want}`\n  fix: regenerate the folder with `gbump rtl --out DIR`",
                file.display()
            )));
        }
    }
    Ok(ps)
}

/// The filled testbench for the RTL described by interface JSON `j` (read from `file`, in
/// folder `dir`, whose power-table init file the top is given by absolute path).
pub fn fill(j: &Value, file: &Path, dir: &Path) -> Result<String> {
    let ps = ports(j, file)?;
    let width = |n: &str| ps.iter().find(|p| p.name == n).map_or(1, |p| p.width);
    let data: Vec<&Port> = ps
        .iter()
        .filter(|p| !PROTOCOL.contains(&p.name.as_str()) && !SETUP.contains(&p.name.as_str()) && p.name != OUT_READY)
        .collect();
    let setup = ps.iter().any(|p| p.name == SETUP[0]);
    let mut lines: std::collections::BTreeMap<&str, Vec<String>> = Default::default();
    let mut push = |k: &'static str, s: String| lines.entry(k).or_default().push(s);
    for p in &data {
        let (n, w) = (&p.name, p.width);
        let slice = format!("acc[lsb_{n} +: {w}]");
        push("LSB_DECLS", format!("    int lsb_{n};"));
        push("COLUMNS", format!("        column(\"{n}\", {w}, lsb_{n});"));
        push("CONNECT", format!(".{n}({n})"));
        if p.output {
            push("DECLS", format!("    wire [{}:0] {n};", w - 1));
            push("OUT_XCHECK", format!(", {n}"));
            // The integration notes promise every data output 0 while out_valid is low.
            push(
                "OUT_GATE",
                format!("            if ({n} !== '0) gate_report($sformatf(\"{n} is not 0 while out_valid is low at %0t: {n}=%h\", $time, {n}));"),
            );
            push("OUT_EQUAL", format!("{n} === {slice}"));
            push(
                "PRINT_OUT",
                format!("                        $display(\"  {n} expected %h got %h\", {slice}, {n});"),
            );
        } else {
            push("DECLS", format!("    logic [{}:0] {n} = '0;", w - 1));
            push("ASSIGN", format!("            {n} = stim[lsb_{n} +: {w}];"));
            if p.triangle {
                // The state the top loaded at the setup's edge, not what the port shows now.
                push("TRI_CAPTURE", format!("            tri_state[lsb_{n} +: {w}] = {n};"));
                push("PACK", format!("            {slice} = tri_state[lsb_{n} +: {w}];"));
            } else {
                push("PACK", format!("            {slice} = {n};"));
            }
            push("PRINT", format!("                        $display(\"  {n:15} %h\", {slice});"));
        }
    }
    if ps.iter().any(|p| p.name == OUT_READY) {
        push("DECLS", "    logic out_ready = 1'b1;".into());
        push("CONNECT", ".out_ready(out_ready)".into());
    }
    if setup {
        push("LSB_DECLS", "    int lsb_tri_start;".into());
        push("COLUMNS", "        column(\"tri_start\", 1, lsb_tri_start);".into());
        push("CONNECT", ".tri_valid(tri_valid), .tri_ready(tri_ready)".into());
    }
    if !lines.contains_key("OUT_EQUAL") || !lines.contains_key("PACK") {
        return Err(Error::Other(format!(
            "{}: the top has no data inputs or no data outputs besides the protocol ports\n  fix: regenerate the folder with `gbump rtl --out DIR`",
            file.display()
        )));
    }
    let get = |k: &str, sep: &str| lines.get(k).map_or(String::new(), |v| v.join(sep));
    let init = dir.join(text(j, &["power_table", "init_file"], file)?);
    let print = format!("{}\n{}", get("PRINT", "\n"), get("PRINT_OUT", "\n"));
    let subs: Vec<(&str, String)> = vec![
        ("INIT_FILE", verilog_string(&init.display().to_string())),
        ("EXIT_MARK", crate::rtlgen::testbench::EXIT_MARK.to_string()),
        ("LATENCY", num(j, &["latency_cycles"], file)?.to_string()),
        ("II", num(j, &["initiation_interval"], file)?.to_string()),
        ("POWER_TABLE_WORDS", num(j, &["power_table", "words"], file)?.to_string()),
        ("POWER_TABLE_ADDR_BITS", width("power_table_waddr").to_string()),
        ("POWER_TABLE_DATA_BITS", width("power_table_wdata").to_string()),
        ("TOP", text(j, &["top"], file)?.to_string()),
        ("HASH", text(j, &["config_hash"], file)?.to_string()),
        ("DECLS", get("DECLS", "\n")),
        ("CONNECT", format!("        {}", get("CONNECT", ", "))),
        ("LSB_DECLS", get("LSB_DECLS", "\n")),
        ("COLUMNS", get("COLUMNS", "\n")),
        ("ASSIGN", get("ASSIGN", "\n")),
        ("PACK", get("PACK", "\n")),
        ("TRI_CAPTURE", get("TRI_CAPTURE", "\n")),
        (
            "TRI_DECLS",
            if setup {
                "    logic tri_valid = 1'b0;\n    wire tri_ready;"
            } else {
                "    logic tri_valid = 1'b0;\n    wire tri_ready = 1'b1;"
            }
            .into(),
        ),
        ("TRI_START", if setup { "stim[lsb_tri_start]" } else { "1'b0" }.into()),
        ("OUT_XCHECK", get("OUT_XCHECK", "")),
        ("OUT_GATE", get("OUT_GATE", "\n")),
        ("OUT_EQUAL", get("OUT_EQUAL", " && ")),
        ("PRINT", print),
    ];
    let mut t = TB_COSIM.to_string();
    for (k, v) in subs {
        t = t.replace(&format!("{{{{{k}}}}}"), &v);
    }
    assert!(!t.contains("{{"), "unfilled field in testbench/tb_cosim.sv.tpl");
    Ok(t)
}
