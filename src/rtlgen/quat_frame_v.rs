//! The `quat_frame` unit's Verilog (`model::quat_frame`): the quaternion's ten products
//! exact, each frame entry their signed sum (doubled off the diagonal), one rounding to
//! `s1.(lh-2)` and a clamp, with the register cut of `units::timing::QUAT_FRAME` the depth
//! puts in place.

use super::booth::{sum_of_products, Factor, Form};
use super::fixed_ops::requant_to;
use super::units_v::{module_name, postamble, preamble};
use super::writer::VWriter;
use crate::config::PipelineConfig;
use crate::model::quat_frame::{entry_exact_fmt, length2_fmt, scaled_exact_fmt};
use crate::units::timing::{cut, cuts_in_place, latency, QUAT_FRAME};

/// The ten products, by name: the four squares and the six cross terms (lane indices into
/// q = (w, x, y, z)).
pub const PRODUCTS: [(&str, usize, usize); 10] = [
    ("ww", 0, 0),
    ("xx", 1, 1),
    ("yy", 2, 2),
    ("zz", 3, 3),
    ("xy", 1, 2),
    ("xz", 1, 3),
    ("yz", 2, 3),
    ("wx", 0, 1),
    ("wy", 0, 2),
    ("wz", 0, 3),
];

/// T's and B's entries `[axis][component]` as (doubled, terms with their signs), the
/// homogeneous rotation of `model::quat_frame::homogeneous`.
const ENTRIES: [[(bool, &[(char, &str)]); 3]; 2] = [
    [
        (false, &[('+', "ww"), ('+', "xx"), ('-', "yy"), ('-', "zz")]),
        (true, &[('+', "xy"), ('+', "wz")]),
        (true, &[('+', "xz"), ('-', "wy")]),
    ],
    [
        (true, &[('+', "xy"), ('-', "wz")]),
        (false, &[('+', "ww"), ('-', "xx"), ('+', "yy"), ('-', "zz")]),
        (true, &[('+', "yz"), ('+', "wx")]),
    ],
];

pub fn quat_frame(cfg: &PipelineConfig) -> String {
    let lh = cfg.lh_bits;
    let lf = cfg.lh_fmt();
    let ex = entry_exact_fmt(cfg);
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// quat_frame (paper sec. 3.2 [5], VISA+ with quaternions): T and B of the rotation of q = (w, x, y, z) in the homogeneous form, |q|^2 R(q/|q|), each entry exact in {} ({} bits), one rounding ({:?}) to {}, clamped; N = round(round(|q|^2) N_i).",
        ex.name(),
        ex.width,
        cfg.rounding,
        lf.name()
    ));
    w.line(format!(
        "// Latency {}: pipeline_depth {} puts {} of its register cuts in place. frame: vector v (T, B, N), component c at lane 3v + c.",
        latency(cfg, QUAT_FRAME),
        cfg.pipeline_depth,
        cuts_in_place(cfg, QUAT_FRAME)
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] q,\n    input  wire [{}:0] n_i,\n    output reg  [{}:0] frame\n);",
        module_name(cfg, "quat_frame"),
        4 * lh - 1,
        3 * lh - 1,
        9 * lh - 1
    ));
    let lane = |i: usize| Factor::signed(format!("q[{}:{}]", i as u32 * lh + lh - 1, i as u32 * lh), lh);
    let pw = 2 * lh;
    for (name, a, b) in PRODUCTS {
        let e = sum_of_products(&mut w, Form::of(cfg), &format!("{name}m"), &[(lane(a), lane(b))], 0, pw);
        w.stage(cut(cfg, QUAT_FRAME, 0), &format!("signed [{}:0]", pw - 1), name, &e);
    }
    w.stage(cut(cfg, QUAT_FRAME, 0), &format!("[{}:0]", 3 * lh - 1), "nq", "n_i");
    let ext = |p: &str| format!("{{{{{}{{{p}[{}]}}}}, {p}}}", ex.width - pw, pw - 1);
    let mut outs = Vec::new();
    for (v, row) in ENTRIES.iter().enumerate() {
        for (c, (doubled, terms)) in row.iter().enumerate() {
            let sum = terms
                .iter()
                .enumerate()
                .map(|(i, (sign, p))| {
                    let t = format!("$signed({})", ext(p));
                    match (i, sign) {
                        (0, '+') => t,
                        (0, _) => format!("-{t}"),
                        (_, s) => format!(" {s} {t}"),
                    }
                })
                .collect::<String>();
            let name = format!("e{v}{c}");
            let body = if *doubled { format!("({sum}) <<< 1") } else { sum };
            w.line(format!("wire signed [{}:0] {name}_s = {body};", ex.width - 1));
            requant_to(&mut w, &name, &format!("{name}_s"), ex, lf, cfg.rounding);
            outs.push(name);
        }
    }
    // N: |q|² rounded, times each component of N_i, rounded and clamped.
    let (l2, sc) = (length2_fmt(cfg), scaled_exact_fmt(cfg));
    w.line(format!(
        "wire signed [{}:0] s_s = {};",
        ex.width - 1,
        ["ww", "xx", "yy", "zz"].map(|p| format!("$signed({})", ext(p))).join(" + ")
    ));
    requant_to(&mut w, "s", "s_s", ex, l2, cfg.rounding);
    for c in 0..3u32 {
        let e = sum_of_products(
            &mut w,
            Form::of(cfg),
            &format!("n{c}m"),
            &[(
                Factor::signed("s", l2.width),
                Factor::signed(format!("nq[{}:{}]", c * lh + lh - 1, c * lh), lh),
            )],
            0,
            sc.width,
        );
        w.line(format!("wire signed [{}:0] n{c}_p = {e};", sc.width - 1));
        requant_to(&mut w, &format!("e2{c}"), &format!("n{c}_p"), sc, lf, cfg.rounding);
        outs.push(format!("e2{c}"));
    }
    outs.reverse();
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line(format!("frame <= {{{}}};", outs.join(", ")));
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}
