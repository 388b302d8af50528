//! A register shell around the top, `gbump_fpga_shell_<hash>`, so the core places on an FPGA
//! whose package has fewer pins than the top's ports (the default four-light top has about
//! 640; an iCE40 HX8K in its largest package bonds 206). Used only for place and route
//! (`gbump area --target ice40`); it is not part of the simulated RTL.
//!
//! Seven pins, each registered where it enters or leaves the FPGA:
//! - `si`, `shift_in`: every input of the top except `clk` and `rst` comes from one serial-in
//!   shift chain (`in_valid` included), shifted one bit per clock while `shift_in` is high;
//! - `capture`, `shift_out`, `so`: every output of the top is loaded in parallel into a
//!   shift-out register when `capture` is high and shifted towards `so` while `shift_out` is;
//! - `rst` reaches the core through a register.
//!
//! So every path that starts or ends at a core port starts or ends at a flip-flop, and the
//! Fmax nextpnr reports for `clk` is the core's own clock rate (the shell adds only
//! flip-flop-to-flip-flop hops and one 2:1 multiplexer per output bit).

use super::top::top_ports;
use super::units_v::module_name;
use super::writer::{range, VWriter};
use crate::config::PipelineConfig;

/// Pins of the shell, in order.
pub const PINS: [&str; 7] = ["clk", "rst", "si", "shift_in", "capture", "shift_out", "so"];

/// The shell's module name.
pub fn name(cfg: &PipelineConfig) -> String {
    module_name(cfg, "gbump_fpga_shell")
}

/// (input chain bits, output register bits) of the shell of `cfg`.
pub fn widths(cfg: &PipelineConfig) -> (u32, u32) {
    let ps = top_ports(cfg);
    let sum = |dir: &str| -> u32 {
        ps.iter()
            .filter(|(n, d, _)| *d == dir && *n != "clk" && *n != "rst")
            .map(|p| p.2)
            .sum()
    };
    (sum("input"), sum("output"))
}

/// The shell's Verilog.
pub fn shell(cfg: &PipelineConfig) -> String {
    let (win, wout) = widths(cfg);
    let mut w = VWriter::new();
    w.line("`timescale 1ns / 1ps");
    w.line("`default_nettype none");
    w.line("");
    w.line(format!(
        "// FPGA register shell of {}: {win} input bits through a serial-in chain, {wout} output",
        module_name(cfg, "gbump_pipeline")
    ));
    w.line("// bits through a parallel-load shift-out register, a register on every pin. For place and");
    w.line("// route only (the core's ports outnumber any iCE40 package's pins).");
    w.line(format!(
        "module {} #(\n    parameter INIT_FILE = \"{}\"\n) (",
        name(cfg),
        super::units_v::rom_file_name(cfg, "power_table", "hex")
    ));
    w.lines([
        "    input  wire clk,",
        "    input  wire rst,",
        "    input  wire si,",
        "    input  wire shift_in,",
        "    input  wire capture,",
        "    input  wire shift_out,",
        "    output wire so",
        ");",
    ]);
    w.line("reg rst_r, si_r, shift_in_r, capture_r, shift_out_r, so_r;");
    w.line(format!("reg {}chain;", range(win)));
    w.line(format!("reg {}outs;", range(wout)));
    w.line(format!("wire {}core_out;", range(wout)));
    let shifted = |reg: &str, width: u32, fill: &str| {
        if width == 1 {
            fill.to_string()
        } else {
            format!("{{{reg}[{}:0], {fill}}}", width - 2)
        }
    };
    w.block("always @(posedge clk) begin", "end", |w| {
        w.lines([
            "rst_r <= rst;",
            "si_r <= si;",
            "shift_in_r <= shift_in;",
            "capture_r <= capture;",
            "shift_out_r <= shift_out;",
        ]);
        w.line(format!("if (shift_in_r) chain <= {};", shifted("chain", win, "si_r")));
        w.line("if (capture_r) outs <= core_out;");
        w.line(format!("else if (shift_out_r) outs <= {};", shifted("outs", wout, "1'b0")));
        w.line(format!(
            "so_r <= outs{};",
            if wout > 1 { format!("[{}]", wout - 1) } else { String::new() }
        ));
    });
    w.line("assign so = so_r;");
    // Inputs take consecutive slices of the chain (the first port at the low end); outputs
    // fill core_out the same way.
    let mut conns = vec![".clk(clk)".to_string(), ".rst(rst_r)".to_string()];
    let (mut at_in, mut at_out) = (0u32, 0u32);
    for (port, dir, width) in top_ports(cfg) {
        if port == "clk" || port == "rst" {
            continue;
        }
        let (sig, at) = if dir == "input" {
            ("chain", &mut at_in)
        } else {
            ("core_out", &mut at_out)
        };
        let total = if dir == "input" { win } else { wout };
        let slice = if total == 1 {
            sig.to_string()
        } else if width == 1 {
            format!("{sig}[{at}]")
        } else {
            format!("{sig}[{}:{at}]", *at + width - 1)
        };
        *at += width;
        conns.push(format!(".{port}({slice})"));
    }
    w.line(format!(
        "{} #(.INIT_FILE(INIT_FILE)) u_core (\n    {}\n);",
        module_name(cfg, "gbump_pipeline"),
        conns.join(",\n    ")
    ));
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_top_port_is_connected_once_to_its_own_slice() {
        let cfg = PipelineConfig::default();
        let (win, wout) = widths(&cfg);
        let v = shell(&cfg);
        assert!(win > 600, "the default top has about 640 pins");
        // out_c, out_valid, in_ready and the setup port's tri_ready.
        assert_eq!(wout, 3 * cfg.colour_bits + 3);
        for (p, dir, _) in top_ports(&cfg) {
            assert_eq!(v.matches(&format!(".{p}(")).count(), 1, "{p} ({dir})\n{v}");
        }
        // The last input ends at the top of the chain, the last output at the top of core_out.
        let (name, _, w) = top_ports(&cfg).into_iter().rfind(|p| p.1 == "input").unwrap();
        let slice = if w == 1 {
            format!("chain[{}]", win - 1)
        } else {
            format!("chain[{}:{}]", win - 1, win - w)
        };
        assert!(v.contains(&format!(".{name}({slice})")), "{v}");
        assert!(v.contains(&format!("core_out[{}:", wout - 1)));
        assert!(v.contains(&format!("reg [{}:0] chain;", win - 1)));
        for pin in PINS {
            assert!(v.contains(&format!("wire {pin}")), "{pin}");
        }
    }
}
