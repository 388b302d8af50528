//! The `frame_transform` unit's Verilog: per component c, `b_x T_c + b_y B_c + b_z N_c`
//! exact, one rounding to the normal's format and a clamp to its range
//! (`model::frame_transform`), with the register cuts of `units::timing::FRAME_TRANSFORM`
//! the depth puts in place.

use super::booth::{sum_of_products, Factor, Form};
use super::fixed_ops::requant_clamp;
use super::units_v::{module_name, postamble, preamble};
use super::writer::VWriter;
use crate::config::PipelineConfig;
use crate::units::timing::{cut, cuts_in_place, latency, FRAME_TRANSFORM};

pub fn frame_transform(cfg: &PipelineConfig) -> String {
    let (nb, lh) = (cfg.normal_bits, cfg.lh_bits);
    let ex = cfg.dot_exact_fmt();
    let nf = cfg.normal_fmt();
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// frame_transform (paper sec. 3.5, Harmony): v_c = b_x T_c + b_y B_c + b_z N_c exact in {} ({} bits), one rounding ({:?}) to {}, clamped to its range.",
        ex.name(),
        ex.width,
        cfg.rounding,
        nf.name()
    ));
    w.line(format!(
        "// Latency {}: pipeline_depth {} puts {} of its register cuts in place.",
        latency(cfg, FRAME_TRANSFORM),
        cfg.pipeline_depth,
        cuts_in_place(cfg, FRAME_TRANSFORM)
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] b,\n    input  wire [{}:0] frame,\n    output reg  [{}:0] v\n);",
        module_name(cfg, "frame_transform"),
        3 * nb - 1,
        9 * lh - 1,
        3 * nb - 1
    ));
    let decl = format!("signed [{}:0]", ex.width - 1);
    // b_i times component c of frame vector i (lane 3i + c).
    let product = |i: u32, c: u32| {
        let lane = 3 * i + c;
        (
            Factor::signed(format!("b[{}:{}]", i * nb + nb - 1, i * nb), nb),
            Factor::signed(format!("frame[{}:{}]", lane * lh + lh - 1, lane * lh), lh),
        )
    };
    for c in 0..3 {
        if cut(cfg, FRAME_TRANSFORM, 0) {
            for i in 0..3 {
                let e = sum_of_products(&mut w, Form::of(cfg), &format!("p{c}{i}m"), &[product(i, c)], 0, ex.width);
                w.stage(true, &decl, &format!("p{c}{i}"), &e);
            }
            w.stage(
                cut(cfg, FRAME_TRANSFORM, 1),
                &decl,
                &format!("s{c}"),
                &format!("p{c}0 + p{c}1 + p{c}2"),
            );
        } else {
            // No register between the products and their sum: one tree of all the rows.
            let e = sum_of_products(
                &mut w,
                Form::of(cfg),
                &format!("p{c}m"),
                &[product(0, c), product(1, c), product(2, c)],
                0,
                ex.width,
            );
            w.stage(cut(cfg, FRAME_TRANSFORM, 1), &decl, &format!("s{c}"), &e);
        }
        requant_clamp(
            &mut w,
            &format!("q{c}"),
            &format!("s{c}"),
            ex,
            nf.frac,
            cfg.rounding,
            nf.min_raw(),
            nf.max_raw(),
            nb,
        );
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line("v <= {q2, q1, q0};");
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}
