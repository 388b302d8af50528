//! The `normalise_cube` unit's Verilog: the steps of `model::cube_normalise` (magnitudes and
//! the major axis, two restoring divisions for the texel indices, the quarter-face map as a
//! constant case, signs and axis order), with the register cuts of
//! `units::timing::NORMALISE_CUBE` the depth puts in place.

use super::units_v::module_name;
use super::writer::VWriter;
use crate::config::PipelineConfig;
use crate::model::cube_normalise::{component_bits, word, words};
use crate::model::normalise::Shape;
use crate::units::timing::{cut, cuts_in_place, latency, NORMALISE_CUBE};

/// Bits of a texel index along a face edge of `face` texels.
pub fn index_bits(face: u32) -> u32 {
    face.trailing_zeros()
}

/// Widths the division works in for vectors of `lh` bits: the dividend `(p + m) · face/2`.
pub fn dividend_bits(lh: u32, face: u32) -> u32 {
    lh + index_bits(face)
}

pub fn normalise_cube(cfg: &PipelineConfig) -> String {
    let shape = Shape::lh(cfg);
    let face = cfg.cube_map_face;
    let lh = shape.width;
    let c = index_bits(face);
    let qb = c - 1;
    let cw = component_bits(&shape);
    let dw = dividend_bits(lh, face);
    let mut w = VWriter::new();
    w.line("`timescale 1ns / 1ps");
    w.line("`default_nettype none");
    w.line("");
    w.line(format!(
        "// normalise_cube: n = the unit vector through the centre of the texel v pierces in a {face}x{face}-texel-a-face normalisation cube map,"
    ));
    w.line(format!(
        "// in s1.{} (scale {:.6}); a zero vector stays zero. Major axis: x if |x| >= |y|, |z|, else y if |y| >= |z|, else z.",
        shape.frac,
        shape.scale()
    ));
    w.line(format!(
        "// Texel i = min(floor((p + m) {} / m), {}) for each minor p (a {}-bit restoring division); the map is a quarter face",
        face / 2,
        face - 1,
        c + 1
    ));
    w.line(format!(
        "// of {} words (i >= {h}: i - {h}, else {} - i and the component negated), each component rounded half up.",
        words(face),
        face / 2 - 1,
        h = face / 2
    ));
    w.line(format!(
        "// Latency {}: pipeline_depth {} puts {} of its register cuts in place.",
        latency(cfg, NORMALISE_CUBE),
        cfg.pipeline_depth,
        cuts_in_place(cfg, NORMALISE_CUBE)
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] v,\n    output reg  [{}:0] n\n);",
        module_name(cfg, "normalise_cube"),
        3 * lh - 1,
        3 * lh - 1
    ));
    // The quarter face: a constant, so a case in logic. Word = {major, minor 2, minor 1}.
    let ww = 3 * cw;
    w.block(format!("function [{}:0] map;", ww - 1), "endfunction", |w| {
        w.line(format!("input [{}:0] ab;", 2 * qb - 1));
        w.block("case (ab)", "endcase", |w| {
            for a in 0..face / 2 {
                for b in 0..face / 2 {
                    let x = word(&shape, face, a, b);
                    w.line(format!(
                        "{}'d{}: map = {{{cw}'d{}, {cw}'d{}, {cw}'d{}}};",
                        2 * qb,
                        (b << qb) | a,
                        x[2],
                        x[1],
                        x[0]
                    ));
                }
            }
            w.line(format!("default: map = {ww}'d0;"));
        });
    });
    let x = |i: u32| format!("v[{}:{}]", i * lh + lh - 1, i * lh);
    // Stage 1: magnitudes, the major axis, the minors.
    for i in 0..3 {
        w.line(format!("wire [{}:0] a{i} = v[{}] ? -{} : {};", lh - 1, i * lh + lh - 1, x(i), x(i)));
    }
    w.line("wire [1:0] major = (a0 >= a1 && a0 >= a2) ? 2'd0 : (a1 >= a2) ? 2'd1 : 2'd2;");
    let c0 = cut(cfg, NORMALISE_CUBE, 0);
    w.stage(c0, "[1:0]", "major1", "major");
    w.stage(c0, &format!("[{}:0]", lh - 1), "m1", "major == 2'd0 ? a0 : major == 2'd1 ? a1 : a2");
    w.stage(
        c0,
        &format!("signed [{}:0]", lh - 1),
        "p1",
        &format!("major == 2'd0 ? {} : {}", x(1), x(0)),
    );
    w.stage(
        c0,
        &format!("signed [{}:0]", lh - 1),
        "q1",
        &format!("major == 2'd2 ? {} : {}", x(1), x(2)),
    );
    w.stage(
        c0,
        "",
        "neg1",
        &format!(
            "major == 2'd0 ? v[{}] : major == 2'd1 ? v[{}] : v[{}]",
            lh - 1,
            2 * lh - 1,
            3 * lh - 1
        ),
    );
    // Stage 2: the divisions, quotient bit k from the top: subtract m << k where it fits.
    for (t, p) in [("i", "p1"), ("j", "q1")] {
        w.line(format!(
            "wire [{}:0] {t}_r{} = {{{}'d0, $unsigned($signed({{{p}[{}], {p}}}) + $signed({{1'b0, m1}}))}} << {};",
            dw - 1,
            c + 1,
            dw - lh - 1,
            lh - 1,
            c - 1
        ));
        for k in (0..=c).rev() {
            let d = format!("({{{}'d0, m1}} << {k})", dw - lh);
            w.line(format!("wire {t}_b{k} = {t}_r{} >= {d};", k + 1));
            if k == 0 {
                // The last remainder is the division's, not the texel's.
                break;
            }
            w.line(format!(
                "wire [{}:0] {t}_r{k} = {t}_b{k} ? {t}_r{} - {d} : {t}_r{};",
                dw - 1,
                k + 1,
                k + 1
            ));
        }
        let bits: Vec<String> = (0..=c).rev().map(|k| format!("{t}_b{k}")).collect();
        // The quotient reaches `face` only for p = m: the last texel.
        w.line(format!(
            "wire [{c}:0] {t}_q = {{{}}};\nwire [{}:0] {t}_t = {t}_q[{c}] ? {c}'d{} : {t}_q[{}:0];",
            bits.join(", "),
            c - 1,
            face - 1,
            c - 1
        ));
    }
    let c1 = cut(cfg, NORMALISE_CUBE, 1);
    w.stage(c1, &format!("[{}:0]", c - 1), "i2", "i_t");
    w.stage(c1, &format!("[{}:0]", c - 1), "j2", "j_t");
    w.stage(c1, "[1:0]", "major2", "major1");
    w.stage(c1, "", "neg2", "neg1");
    w.stage(c1, "", "zero2", "m1 == 0");
    // Output: the word, its signs, the axes in order.
    // Faces of at least 4 texels (the configuration's rule): a quarter index of qb >= 1 bits.
    let quarter = |t: &str| format!("({t}2[{}] ? {t}2[{}:0] : ~{t}2[{}:0])", c - 1, qb - 1, qb - 1);
    w.line(format!("wire [{}:0] wd = map({{{}, {}}});", ww - 1, quarter("j"), quarter("i")));
    let signed = |name: &str, lo: u32, neg: &str| {
        format!(
            "wire signed [{}:0] {name} = {neg} ? -$signed({{1'b0, wd[{}:{lo}]}}) : $signed({{1'b0, wd[{}:{lo}]}});",
            lh - 1,
            lo + cw - 1,
            lo + cw - 1
        )
    };
    w.line(signed("s1", 0, &format!("!i2[{}]", c - 1)));
    w.line(signed("s2", cw, &format!("!j2[{}]", c - 1)));
    w.line(signed("s3", 2 * cw, "neg2"));
    w.line(format!("wire signed [{}:0] nx = major2 == 2'd0 ? s3 : s1;", lh - 1));
    w.line(format!(
        "wire signed [{}:0] ny = major2 == 2'd0 ? s1 : major2 == 2'd1 ? s3 : s2;",
        lh - 1
    ));
    w.line(format!("wire signed [{}:0] nz = major2 == 2'd2 ? s3 : s2;", lh - 1));
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line(format!("n <= zero2 ? {}'d0 : {{nz, ny, nx}};", 3 * lh));
    });
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}
