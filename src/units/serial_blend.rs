//! The blend units in their serial form (paper §4.2: "one light per clock"): the serial top
//! runs each fragment's light slots through one `light_accumulate` per blend, which adds one
//! exact term f·k·Lc per clock, then closes each sum with `blend_finish`, the same rounding
//! and saturating add the parallel `diffuse_blend`/`specular_blend` end with. Sums are exact,
//! so both forms give the same bits.

use super::{p, Dir, Lanes, Memories, Port, Unit};
use crate::config::{LightMode, PipelineConfig};
use crate::fixed::{shift_round, Format};
use crate::rtlgen::units_v::module_name;
use crate::rtlgen::writer::{zext, VWriter};

pub struct LightAccumulate;
pub struct BlendFinish;

fn serial_blend(cfg: &PipelineConfig) -> bool {
    cfg.light_mode == LightMode::Serial && (cfg.diffuse || cfg.specular)
}

/// `(first ? 0 : acc_in) + f k lc` per channel, modulo the accumulator width (the hardware's
/// adder; an exact sum of at most `lights` terms never reaches it).
pub fn accumulate(cfg: &PipelineConfig, acc_in: &[i64], first: bool, f: i64, k: i64, lc: &[i64]) -> [i64; 3] {
    let aw = cfg.acc_fmt().width;
    let mask = (1i128 << aw) - 1;
    [0, 1, 2].map(|ch| {
        let base = if first { 0 } else { acc_in[ch] as i128 };
        ((base + (f * k * lc[ch]) as i128) & mask) as i64
    })
}

/// `sat(c_in + round(acc))` per channel, in stage colours.
pub fn finish(cfg: &PipelineConfig, c_in: &[i64], acc: &[i64]) -> [i64; 3] {
    let shift = crate::model::blend::sum_shift(cfg);
    let max = cfg.stage_colour_max();
    [0, 1, 2].map(|ch| (c_in[ch] + shift_round(acc[ch] as i128, shift, cfg.rounding) as i64).min(max))
}

impl Unit for LightAccumulate {
    fn name(&self) -> &'static str {
        "light_accumulate"
    }
    fn source(&self) -> &'static str {
        "paper §4.2: one light per clock; the exact running sum of f_i k_i Lc_i"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("light_mode", "\"serial\"")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        serial_blend(cfg)
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        super::timing::latency(cfg, super::timing::ACCUMULATE)
    }
    fn ports(&self, c: &PipelineConfig) -> Vec<Port> {
        vec![
            p(
                "acc_in",
                Dir::In,
                c.acc_fmt(),
                3,
                "the running sum (the top feeds acc back); added at the last stage",
            )
            .entering(self.latency(c) - 1),
            p("first", Dir::In, Format::u(1, 0), 1, "first light slot: start from 0"),
            p("f", Dir::In, c.factor_fmt(), 1, "fd_j or fs_j of this slot, aligned"),
            p("k", Dir::In, c.k_fmt(), 1, "k_j of this slot"),
        ]
        .into_iter()
        // White lights: no light colour to multiply by.
        .chain((!c.white_lights).then(|| p("lc", Dir::In, c.colour_fmt(), 3, "Lc_j of this slot")))
        .chain([p("acc", Dir::Out, c.acc_fmt(), 3, "(first ? 0 : acc_in) + f k Lc")])
        .collect()
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        let white = [cfg.colour_max() as i64; 3];
        let lc = if cfg.white_lights { &white[..] } else { &i[4][..] };
        vec![accumulate(cfg, &i[0], i[1][0] == 1, i[2][0], i[3][0], lc).to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        // The sum is exact: the model is the equation.
        vec![self.eval(cfg, m, i)[0].iter().map(|&x| x as f64).collect()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{light_term, Resources};
        let aw = cfg.acc_fmt().width;
        // The term, `first` beside it, and per channel (first ? 0 : acc_in) + term, registered.
        light_term(cfg)
            + Resources::regs(crate::rtlgen::units_v::light_term_cuts(cfg))
            + (Resources::muxes(aw) + Resources::adders(aw) + Resources::regs(aw)).scaled(3.0)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        let (ff, k, c) = (cfg.factor_frac(), cfg.k_frac_bits, cfg.colour_bits);
        let (tw, aw) = (cfg.term_fmt().width, cfg.acc_fmt().width);
        let mut w = VWriter::new();
        w.line("`timescale 1ns / 1ps");
        w.line("`default_nettype none");
        w.line("");
        w.line("// light_accumulate (paper sec. 4.2, one light per clock): acc = (first ? 0 : acc_in) + f k Lc,");
        w.line(format!(
            "// exact in {} ({aw} bits per channel), registered; latency {} (acc_in is added at the last stage).",
            cfg.acc_fmt().name(),
            self.latency(cfg)
        ));
        let lc_port = crate::rtlgen::units_v::light_colour_port(cfg, 3 * c);
        w.line(format!(
            "module {} (\n    input  wire clk,\n    input  wire [{}:0] acc_in,\n    input  wire first,\n    input  wire [{ff}:0] f,\n    input  wire [{k}:0] k,\n    {lc_port}output reg  [{}:0] acc\n);",
            module_name(cfg, "light_accumulate"),
            3 * aw - 1,
            3 * aw - 1
        ));
        w.line(format!("wire [{}:0] term;", 3 * tw - 1));
        w.line(format!(
            "{} lt ({}.f(f), .k(k){}, .term(term));",
            module_name(cfg, "light_term"),
            crate::rtlgen::units_v::light_term_clk(cfg),
            crate::rtlgen::units_v::light_colour_conn(cfg, "lc")
        ));
        // `first` waits beside the term; acc_in is added at the last stage, so the running
        // sum feeds back in one cycle at any depth.
        let mut first = "first".to_string();
        for s in 1..=crate::rtlgen::units_v::light_term_cuts(cfg) {
            w.stage(true, "", &format!("first_d{s}"), &first);
            first = format!("first_d{s}");
        }
        w.block("always @(posedge clk) begin", "end", |w| {
            for ch in 0..3 {
                let (hi, lo) = (ch * aw + aw - 1, ch * aw);
                w.line(format!(
                    "acc[{hi}:{lo}] <= ({first} ? {aw}'d0 : acc_in[{hi}:{lo}]) + {};",
                    zext(&format!("term[{}:{}]", ch * tw + tw - 1, ch * tw), aw - tw)
                ));
            }
        });
        w.line("endmodule");
        w.line("`default_nettype wire");
        vec![
            ("light_accumulate", w.finish()),
            ("light_term", crate::rtlgen::units_v::light_term(cfg)),
        ]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let (m, one_f, one_k) = (cfg.colour_max() as i64, 1i64 << cfg.factor_frac(), 1i64 << cfg.k_frac_bits);
        let big = ((cfg.lights as i64 - 1).max(0)) * one_f * one_k * m;
        let some = cfg.acc_fmt().max_raw() / 3;
        vec![
            (
                "first slot ignores acc_in".into(),
                vec![vec![some; 3], vec![1], vec![one_f], vec![one_k], vec![m; 3]],
            ),
            (
                "last slot of all-full lights: the largest sum".into(),
                vec![vec![big; 3], vec![0], vec![one_f], vec![one_k], vec![m; 3]],
            ),
            (
                "zero term keeps the sum".into(),
                vec![vec![some; 3], vec![0], vec![0], vec![one_k], vec![m; 3]],
            ),
            ("one LSB term".into(), vec![vec![0; 3], vec![1], vec![1], vec![1], vec![1; 3]]),
        ]
        .into_iter()
        .map(|(why, mut lanes)| {
            // White lights: the unit has no light-colour input.
            if cfg.white_lights {
                lanes.pop();
            }
            (why, lanes)
        })
        .collect()
    }
}

impl Unit for BlendFinish {
    fn name(&self) -> &'static str {
        "blend_finish"
    }
    fn source(&self) -> &'static str {
        "paper §4.2, §5.1: C_out = sat(C_in + round(sum)), closing a serial blend"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("light_mode", "\"serial\"")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        serial_blend(cfg)
    }
    fn ports(&self, c: &PipelineConfig) -> Vec<Port> {
        vec![
            p(
                "c_in",
                Dir::In,
                c.stage_colour_fmt(),
                3,
                "colour in (colour_guard_bits fraction bits)",
            ),
            p("acc", Dir::In, c.acc_fmt(), 3, "exact sum of f_i k_i Lc_i"),
            p(
                "c_out",
                Dir::Out,
                c.stage_colour_fmt(),
                3,
                "sat(c_in + round(acc)), rounded to c_in's fraction bits",
            ),
        ]
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![finish(cfg, &i[0], &i[1]).to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        let af = cfg.acc_fmt();
        let max = cfg.stage_colour_max() as f64;
        let one = (1u64 << cfg.colour_guard_bits) as f64;
        vec![(0..3).map(|ch| (i[0][ch] as f64 + af.to_f64(i[1][ch]) * one).min(max)).collect()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        crate::units::resources::blend_finish(cfg)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("blend_finish", crate::rtlgen::units_v::blend_finish(cfg))]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let m = cfg.stage_colour_max();
        let af = cfg.acc_fmt();
        let half = 1i64 << (crate::model::blend::sum_shift(cfg) - 1);
        vec![
            ("largest sum on white: saturates".into(), vec![vec![m; 3], vec![af.max_raw(); 3]]),
            ("zero sum passes c_in".into(), vec![vec![0, m / 2, m], vec![0; 3]]),
            (
                "half an LSB: the rounding rule".into(),
                vec![vec![0; 3], vec![half, half - 1, half + 1]],
            ),
        ]
    }
}
