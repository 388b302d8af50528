//! The one RAM of the generated RTL: a write port and a registered read port, powered up from
//! `INIT_FILE`, written in the form Yosys infers as block RAM for iCE40 (SB_RAM40_4K), ECP5
//! (DP16KD) and Xilinx (RAMB18E1). The power table and the palette instantiate it, one copy
//! per read port, all copies written by the one load port; the serial top keeps its triangle
//! banks in one (written by the setup port, one light slot per edge).
//!
//! `ram_style = "block"`: without it Yosys puts a table this small into Xilinx LUT RAM.
//! `no_rw_check`: a read of the entry written at the same edge may return either word (as a
//! block RAM does); without it Yosys adds bypass flip-flops to emulate read-first. The
//! protocol never reads an entry while it is loaded: tables are loaded between fragments,
//! as a colour LUT is.

use super::units_v::module_name;
use super::writer::VWriter;
use crate::config::PipelineConfig;

/// Base name of the RAM module (`module_name(cfg, RAM)`).
pub const RAM: &str = "sync_ram";

/// The RAM module's Verilog (without the generated-file header).
pub fn ram(cfg: &PipelineConfig) -> String {
    let mut w = VWriter::new();
    w.line("`timescale 1ns / 1ps");
    w.line("`default_nettype none");
    w.line("");
    w.line("// sync_ram: DEPTH words of WIDTH bits, one write port, one read port with its read");
    w.line("// register (block RAM on FPGAs, a RAM macro in a standard-cell flow); INIT_FILE holds");
    w.line("// the power-up contents (none when empty), and rst does not restore them.");
    w.line(format!(
        "module {} #(\n    parameter WIDTH = 8,\n    parameter DEPTH = 256,\n    parameter ABITS = 8,\n    parameter INIT_FILE = \"\"\n) (\n    input  wire clk,\n    input  wire we,\n    input  wire [ABITS-1:0] waddr,\n    input  wire [WIDTH-1:0] wdata,\n    input  wire [ABITS-1:0] raddr,\n    output reg  [WIDTH-1:0] rdata\n);",
        module_name(cfg, RAM)
    ));
    w.line("(* ram_style = \"block\", no_rw_check *)");
    w.line("reg [WIDTH-1:0] mem [0:DEPTH-1];");
    // A RAM with no INIT_FILE (the serial top's triangle banks) powers up undefined.
    w.line("generate if (INIT_FILE != \"\") begin : load");
    w.line("    initial $readmemh(INIT_FILE, mem);");
    w.line("end endgenerate");
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line("if (we) mem[waddr] <= wdata;");
        w.line("rdata <= mem[raddr];");
    });
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}

/// An instance of the RAM: `inst` with the memory's geometry, reading `raddr` into `rdata`,
/// written through the unit's own `we/waddr/wdata`.
pub fn instance(cfg: &PipelineConfig, inst: &str, width: u32, depth: u32, abits: u32, raddr: &str, rdata: &str) -> String {
    format!(
        "{} #(.WIDTH({width}), .DEPTH({depth}), .ABITS({abits}), .INIT_FILE(INIT_FILE)) {inst} (.clk(clk), .we(we), .waddr(waddr), .wdata(wdata), .raddr({raddr}), .rdata({rdata}));",
        module_name(cfg, RAM)
    )
}
