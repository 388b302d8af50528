//! The `frame_build` unit's Verilog (TexRam, paper §3.1; `model::frame_build`): N from N_i
//! and B from N × m by two instances of the normalise arithmetic at the frame's plain unit
//! length (`frame_normalise`), each cross product exact, one rounding to `s1.(lh-2)` and a
//! clamp, registered; m and N wait in delay registers for the normaliser they skip.

use super::booth::{sum_of_products, Factor, Form};
use super::fixed_ops::requant_to;
use super::units_v::{module_name, postamble, preamble};
use super::writer::VWriter;
use crate::config::PipelineConfig;
use crate::model::frame_build::cross_exact_fmt;

/// The helper module both normalisations instantiate.
pub const NORMALISE: &str = "frame_normalise";

pub fn frame_build(cfg: &PipelineConfig) -> String {
    let lh = cfg.lh_bits;
    let lf = cfg.lh_fmt();
    let ex = cross_exact_fmt(cfg);
    let ln = crate::units::timing::latency(cfg, crate::units::timing::NORMALISE);
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// frame_build (paper sec. 3.1, TexRam): N = N_i/|N_i|, B = N x m/|N x m|, T = B x N (the paper's e2, and e1 = -B); each cross product exact in {} ({} bits), one rounding ({:?}) to {}, clamped.",
        ex.name(),
        ex.width,
        cfg.rounding,
        lf.name()
    ));
    w.line(format!(
        "// Latency {}: two {NORMALISE} instances of latency {ln} and a registered cross product after each. frame: vector v (T, B, N), component c at lane 3v + c.",
        2 * ln + 2
    ));
    let v3 = format!("[{}:0]", 3 * lh - 1);
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire {v3} m,\n    input  wire {v3} n_i,\n    output reg  [{}:0] frame\n);",
        module_name(cfg, "frame_build"),
        9 * lh - 1
    ));
    let norm = module_name(cfg, NORMALISE);
    // Register copies of `x` delayed 1..=k cycles; returns the last one's name.
    let delay = |w: &mut VWriter, x: &str, k: u32| -> String {
        let mut prev = x.to_string();
        for d in 1..=k {
            let name = format!("{x}_d{d}");
            w.stage(true, &v3, &name, &prev);
            prev = name;
        }
        prev
    };
    // Component c of a × b, rounded and clamped, as wire `{name}{c}`.
    let cross = |w: &mut VWriter, name: &str, a: &str, b: &str| {
        let lane = |v: &str, i: usize| Factor::signed(format!("{v}[{}:{}]", i as u32 * lh + lh - 1, i as u32 * lh), lh);
        for c in 0..3 {
            let (i, j) = ((c + 1) % 3, (c + 2) % 3);
            let pos = sum_of_products(w, Form::of(cfg), &format!("{name}{c}p"), &[(lane(a, i), lane(b, j))], 0, ex.width);
            let neg = sum_of_products(w, Form::of(cfg), &format!("{name}{c}n"), &[(lane(a, j), lane(b, i))], 0, ex.width);
            w.line(format!("wire signed [{}:0] {name}{c}_p = {pos};", ex.width - 1));
            w.line(format!("wire signed [{}:0] {name}{c}_n = {neg};", ex.width - 1));
            w.line(format!("wire signed [{}:0] {name}{c}_d = {name}{c}_p - {name}{c}_n;", ex.width - 1));
            requant_to(w, &format!("{name}{c}"), &format!("{name}{c}_d"), ex, lf, cfg.rounding);
        }
    };
    w.line(format!("wire {v3} n;"));
    w.line(format!("{norm} u_n (.clk(clk), .v(n_i), .n(n));"));
    let m_late = delay(&mut w, "m", ln);
    cross(&mut w, "c", "n", &m_late);
    w.stage(true, &v3, "c_r", "{c2, c1, c0}");
    w.stage(true, &v3, "n_r", "n");
    w.line(format!("wire {v3} b;"));
    w.line(format!("{norm} u_b (.clk(clk), .v(c_r), .n(b));"));
    let n_late = delay(&mut w, "n_r", ln);
    cross(&mut w, "t", "b", &n_late);
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line(format!("frame <= {{{n_late}, b, t2, t1, t0}};"));
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}
