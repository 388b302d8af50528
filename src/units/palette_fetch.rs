//! palette_fetch: the paper's §6 palettised bump map ("up to 256 surface orientations"): an
//! 8-bit index (`bump`, the bump map's texel) reads a loadable 256-entry normal palette, and
//! the entry is range-expanded like `bump_fetch`. The palette is a synchronous-read memory (the read register is the
//! unit's output register), so synthesis maps it to block RAM.

use super::{p, Dir, Lanes, Memories, Memory, Port, Unit};
use crate::config::PipelineConfig;
use crate::fixed::Format;
use crate::model::bump_fetch::bump_fetch_index;
use crate::rtlgen::units_v::{module_name, rom_file_name};
use crate::rtlgen::writer::VWriter;

pub struct PaletteFetch;

/// Entries of the palette (the index is 8 bits).
pub const PALETTE_ENTRIES: u32 = 256;

impl Unit for PaletteFetch {
    fn name(&self) -> &'static str {
        "palette_fetch"
    }
    fn source(&self) -> &'static str {
        "paper §6: a palette of up to 256 surface orientations; Cg §8.1.2 (range expansion)"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("palette", "true")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.palette
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p("bump", Dir::In, Format::u(8, 0), 1, "palette index"),
            p("b", Dir::Out, cfg.normal_fmt(), 3, "bump normal B of the entry"),
        ]
    }
    fn memory(&self, cfg: &PipelineConfig) -> Option<Memory> {
        Some(Memory {
            prefix: "palette",
            init_param: "PALETTE_INIT_FILE",
            init_stem: "bump_palette_spiral",
            depth: PALETTE_ENTRIES,
            addr_bits: 8,
            data_bits: 3 * cfg.normal_bits,
            data_frac: 0,
            data_lanes: 3,
            doc: "palette entries {z, y, x}, offset-binary components, x in the low bits",
        })
    }
    fn eval(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![bump_fetch_index(cfg, m.palette, i[0][0] as u8).to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        vec![self.eval(cfg, m, i)[0].iter().map(|&x| x as f64).collect()]
    }
    fn resources(&self, _cfg: &PipelineConfig) -> crate::units::resources::Resources {
        // The RAM (its read register included) and an inversion: no logic outside the RAM.
        crate::units::resources::Resources::default()
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        let nb = cfg.normal_bits;
        let w = 3 * nb;
        let mut v = VWriter::new();
        v.line("`timescale 1ns / 1ps");
        v.line("`default_nettype none");
        v.line("");
        v.line("// palette_fetch (paper §6): b = expand(palette[bump]). The palette is a RAM with a");
        v.line("// registered read (block RAM on FPGAs), loaded like a colour LUT through the write port;");
        v.line("// INIT_FILE holds its power-up contents. Expansion (an MSB inversion) follows the read.");
        v.line(format!(
            "module {} #(\n    parameter INIT_FILE = \"{}\"\n) (\n    input  wire clk,\n    input  wire we,\n    input  wire [7:0] waddr,\n    input  wire [{}:0] wdata,\n    input  wire [7:0] bump,\n    output wire [{}:0] b\n);",
            module_name(cfg, "palette_fetch"),
            rom_file_name(cfg, "bump_palette_spiral", "hex"),
            w - 1,
            w - 1
        ));
        v.line(format!("wire [{}:0] rd;", w - 1));
        v.line(crate::rtlgen::ram::instance(cfg, "u_ram", w, PALETTE_ENTRIES, 8, "bump", "rd"));
        let flip = |i: u32| format!("~rd[{}], rd[{}:{}]", i * nb + nb - 1, i * nb + nb - 2, i * nb);
        v.line(format!("assign b = {{{}, {}, {}}};", flip(2), flip(1), flip(0)));
        v.line("endmodule");
        v.line("`default_nettype wire");
        vec![
            ("palette_fetch", v.finish()),
            (crate::rtlgen::ram::RAM, crate::rtlgen::ram::ram(cfg)),
        ]
    }
    fn exhaustive_count(&self, _: &PipelineConfig) -> Option<u64> {
        Some(PALETTE_ENTRIES as u64)
    }
    fn exhaustive_input(&self, _: &PipelineConfig, i: u64) -> Lanes {
        vec![vec![i as i64]]
    }
    fn corners(&self, _: &PipelineConfig) -> Vec<(String, Lanes)> {
        vec![
            ("palette index 0: the first entry".into(), vec![vec![0]]),
            ("palette index 255: the last entry".into(), vec![vec![255]]),
        ]
    }
}
