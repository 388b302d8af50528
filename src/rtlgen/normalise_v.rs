//! The `normalise` and `normalise_b` units' Verilog, one emitter for every `Shape`: the steps of `model::normalise` (squared length, even
//! leading-zero shift, reciprocal-square-root table, Newton steps, scaled products, one
//! rounding), with the register cuts of `units::timing::NORMALISE` the depth puts in place.

use super::booth::{sum_of_products, Factor, Form};
use super::fixed_ops::requant_clamp;
use super::units_v::module_name;
use super::writer::VWriter;
use crate::config::PipelineConfig;
use crate::fixed::Format;
use crate::model::normalise::{params_of, table_word, Shape};
use crate::units::timing::{cut, cuts_in_place, latency, NORMALISE};

/// Width of the scaled product x·r·(2^post - 1)·2^(z/2) before its rounding.
pub fn scaled_width(shape: &Shape) -> u32 {
    let p = params_of(shape);
    shape.width + p.word_bits() + 1 + p.post_bits + p.window / 2
}

/// The module `base` (`normalise` for L and H, `normalise_b` for the bump normal) for vectors
/// of `shape`.
pub fn normalise(cfg: &PipelineConfig, shape: &Shape, base: &str) -> String {
    let p = params_of(shape);
    let lh = shape.width;
    let (l, t, y, mb) = (p.window, p.table_bits, p.r_frac, p.m_bits);
    let rw = p.word_bits();
    let zw = p.shift_bits();
    let mut w = VWriter::new();
    w.line("`timescale 1ns / 1ps");
    w.line("`default_nettype none");
    w.line("");
    w.line(format!(
        "// {base}: n = v scale / |v| in s{}.{} (scale {:.6}), a zero vector stays zero. S = sum of squares{};",
        lh - 1 - shape.frac,
        shape.frac,
        shape.scale(),
        if p.pre_bits > 0 {
            format!(" times (2^{} - 1)^2", p.pre_bits)
        } else {
            String::new()
        }
    ));
    w.line(format!(
        "// its leading one shifted into the top two of {l} bits by an even z; r = 1/sqrt(m) from a {}-word table (index: the top {t} bits),",
        p.entries()
    ));
    w.line(format!(
        "// {} Newton step(s) r = r (3 - m r^2) / 2 in u2.{y} (m cut to {mb} bits); n = round(x r{} 2^(z/2) / 2^{}) ({:?}), saturated.",
        p.steps,
        if p.post_bits > 0 {
            format!(" (2^{} - 1)", p.post_bits)
        } else {
            String::new()
        },
        y + 2 + p.post_bits,
        crate::model::normalise::ROUNDING
    ));
    w.line(format!(
        "// Latency {}: pipeline_depth {} puts {} of its register cuts in place.",
        latency(cfg, NORMALISE),
        cfg.pipeline_depth,
        cuts_in_place(cfg, NORMALISE)
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] v,\n    output reg  [{}:0] n\n);",
        module_name(cfg, base),
        3 * lh - 1,
        3 * lh - 1
    ));
    // The reciprocal-square-root table: a constant, so a case in logic.
    w.block(format!("function [{}:0] rsqrt;", rw - 1), "endfunction", |w| {
        w.line(format!("input [{}:0] i;", t - 1));
        w.block("case (i)", "endcase", |w| {
            for k in 0..p.entries() {
                w.line(format!("{t}'d{}: rsqrt = {rw}'d{};", p.first_index() + k, table_word(&p, k)));
            }
            w.line(format!("default: rsqrt = {rw}'d0;"));
        });
    });
    // The even shift that puts S's leading one into its top two bits (0 for S = 0, whose
    // products are zero whatever r is).
    w.block(format!("function [{}:0] lead2;", zw - 1), "endfunction", |w| {
        w.line(format!("input [{}:0] lead2_s;", l - 1));
        w.block("begin", "end", |w| {
            for k in 0..l / 2 {
                let hi = l - 1 - 2 * k;
                let kw = if k == 0 { "if" } else { "else if" };
                w.line(format!("{kw} (lead2_s[{hi}:{}] != 2'b00) lead2 = {zw}'d{};", hi - 1, 2 * k));
            }
            w.line(format!("else lead2 = {zw}'d0;"));
        });
    });
    let vw = format!("[{}:0]", 3 * lh - 1);
    let x = |v: &str, i: u32| format!("{v}[{}:{}]", i * lh + lh - 1, i * lh);
    // Stage 1: the squared length, scaled for symmetric normals.
    let sq = sum_of_products(
        &mut w,
        Form::of(cfg),
        "sq",
        &[0, 1, 2].map(|i| (Factor::signed(x("v", i), lh), Factor::signed(x("v", i), lh))),
        0,
        2 * lh,
    );
    // Exact modulo 2^(2 lh), and 3 (2^(lh-1))^2 < 2^(2 lh).
    w.line(format!("wire [{}:0] s = {sq};", 2 * lh - 1));
    let big_s = if p.pre_bits == 0 {
        // A bump normal's window is two bits wider than its squared length (F + 2 = width + 1).
        if l > 2 * lh {
            format!("{{{}'d0, s}}", l - 2 * lh)
        } else {
            "s".to_string()
        }
    } else {
        let a = p.pre_bits;
        format!("{{s, {}'d0}} - {{{}'d0, s, {}'d0}} + {{{}'d0, s}}", 2 * a, a - 1, a + 1, 2 * a)
    };
    w.line(format!("wire [{}:0] s_w = {big_s};", l - 1));
    let c0 = cut(cfg, NORMALISE, 0);
    w.stage(c0, &format!("[{}:0]", l - 1), "s1", "s_w");
    w.stage(c0, &vw, "v1", "v");
    // Stage 2: shift, table, Newton steps.
    w.line(format!("wire [{}:0] z1 = lead2(s1);", zw - 1));
    w.line(format!("wire [{}:0] sn = s1 << z1;", l - 1));
    if p.steps > 0 {
        w.line(format!("wire [{}:0] m = sn[{}:{}];", mb - 1, l - 1, l - mb));
    }
    w.line(format!("wire [{}:0] r0 = rsqrt(sn[{}:{}]);", rw - 1, l - 1, l - t));
    let mut r = "r0".to_string();
    // The steps chain up to six products: as Booth rows in functions, which Icarus evaluates
    // once per input change instead of once per row of every product upstream.
    let chain = match Form::of(cfg) {
        Form::Wires => Form::Function,
        f => f,
    };
    for k in 1..=p.steps {
        let rr = sum_of_products(
            &mut w,
            chain,
            &format!("rr{k}"),
            &[(Factor::unsigned(&r, rw), Factor::unsigned(&r, rw))],
            0,
            2 * rw,
        );
        w.line(format!("wire [{}:0] rr{k}_p = {rr};", 2 * rw - 1));
        let qw = rw + 2;
        w.line(format!("wire [{}:0] nq{k} = rr{k}_p[{}:{}];", qw - 1, 2 * rw - 1, y));
        let mq = sum_of_products(
            &mut w,
            chain,
            &format!("mq{k}"),
            &[(Factor::unsigned("m", mb), Factor::unsigned(format!("nq{k}"), qw))],
            0,
            mb + qw,
        );
        w.line(format!("wire [{}:0] mq{k}_p = {mq};", mb + qw - 1));
        // 0 < 3 - m r^2 < 4 for every table word and m of its interval (the unit's tests), so
        // m r^2 and 3 - m r^2 fit u2.Y.
        w.line(format!("wire [{}:0] u{k} = mq{k}_p[{}:{}];", rw - 1, mb + rw - 1, mb));
        w.line(format!("wire [{}:0] e{k} = {}'d{} - u{k};", rw - 1, rw, 3u64 << y));
        let re = sum_of_products(
            &mut w,
            chain,
            &format!("re{k}"),
            &[(Factor::unsigned(&r, rw), Factor::unsigned(format!("e{k}"), rw))],
            0,
            2 * rw,
        );
        w.line(format!("wire [{}:0] re{k}_p = {re};", 2 * rw - 1));
        w.line(format!("wire [{}:0] nr{k} = re{k}_p[{}:{}];", rw - 1, y + rw, y + 1));
        r = format!("nr{k}");
    }
    let c1 = cut(cfg, NORMALISE, 1);
    w.stage(c1, &format!("[{}:0]", rw - 1), "r_s2", &r);
    w.stage(c1, &format!("[{}:0]", zw - 1), "h2", "z1 >> 1");
    w.stage(c1, &vw, "v2", "v1");
    // Stage 3: the products x r (times 2^post - 1: a shift and a subtraction), then the shift
    // by z/2 and one rounding.
    let xw = lh + rw + 1;
    let pw = xw + p.post_bits;
    let c2 = cut(cfg, NORMALISE, 2);
    for i in 0..3 {
        let e = sum_of_products(
            &mut w,
            Form::of(cfg),
            &format!("xr{i}"),
            &[(Factor::signed(x("v2", i), lh), Factor::unsigned("r_s2", rw))],
            0,
            xw,
        );
        let e = if p.post_bits > 0 {
            w.line(format!("wire signed [{}:0] xr{i}_p = {e};", xw - 1));
            let ext = format!("$signed({{{{{}{{xr{i}_p[{}]}}}}, xr{i}_p}})", p.post_bits, xw - 1);
            format!("($signed({{xr{i}_p, {}'d0}}) - {ext})", p.post_bits)
        } else {
            e
        };
        w.stage(c2, &format!("signed [{}:0]", pw - 1), &format!("p{i}"), &e);
    }
    w.stage(c2, &format!("[{}:0]", zw - 1), "h3", "h2");
    let sw = scaled_width(shape);
    // Wider than the model's i64 formats at the widest words: only its shape is read here.
    let fmt = Format {
        width: sw,
        frac: y + 2 + p.post_bits,
        signed: true,
    };
    let lo = shape.fmt().min_raw();
    let hi = shape.fmt().max_raw();
    for i in 0..3 {
        w.line(format!(
            "wire signed [{}:0] sc{i} = $signed({{{{{}{{p{i}[{}]}}}}, p{i}}}) <<< h3;",
            sw - 1,
            sw - pw,
            pw - 1
        ));
        requant_clamp(
            &mut w,
            &format!("n{i}"),
            &format!("sc{i}"),
            fmt,
            0,
            crate::model::normalise::ROUNDING,
            lo,
            hi,
            lh,
        );
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line("n <= {n2, n1, n0};");
    });
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}
