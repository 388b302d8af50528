//! One Verilog module per unit of `units::UNITS`, each emitted from the same formats the
//! model uses. Every unit has a registered output, and the register cuts of `units::timing`
//! that the configuration's `pipeline_depth` puts in place; `bump_fetch` can also be
//! emitted combinationally for the serial top, where the fetched normal must be ready in the
//! same cycle as the first light.

use super::booth::{sum_of_products, Factor, Form};
use super::fixed_ops::requant_clamp;
use super::writer::VWriter;
use crate::config::PipelineConfig;

/// Module name: unit name plus the first 8 hex digits of the config hash, so that modules of
/// several configurations can live in one simulation.
pub fn module_name(cfg: &PipelineConfig, unit: &str) -> String {
    format!("{unit}_{}", &cfg.hash()[..8])
}

pub(super) fn preamble(w: &mut VWriter) {
    w.line("`timescale 1ns / 1ps");
    w.line("`default_nettype none");
    w.line("");
}

pub(super) fn postamble(w: &mut VWriter) {
    w.line("`default_nettype wire");
}

/// bump_fetch: the stored offset-binary bump normal `bump` → signed normal (MSB inversion). `registered` adds the
/// output register; otherwise the module is combinational (and has no clock).
pub fn bump_fetch(cfg: &PipelineConfig, registered: bool) -> String {
    let nb = cfg.normal_bits;
    let name = if registered {
        module_name(cfg, "bump_fetch")
    } else {
        module_name(cfg, "bump_fetch_comb")
    };
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line("// bump_fetch (paper §4.1; Cg §8.1.2 range expansion): stored code c → b = c - 2^(w-1),");
    w.line("// which for offset binary is an inversion of each component's MSB.");
    let clk = if registered { "input  wire clk,\n    " } else { "" };
    let out_kind = if registered { "reg " } else { "wire" };
    w.line(format!(
        "module {name} (\n    {clk}input  wire [{}:0] bump,\n    output {out_kind} [{}:0] b\n);",
        3 * nb - 1,
        3 * nb - 1
    ));
    let flip = |i: u32| format!("{{~bump[{}], bump[{}:{}]}}", i * nb + nb - 1, i * nb + nb - 2, i * nb);
    let expr = format!("{{{}, {}, {}}}", flip(2), flip(1), flip(0));
    if registered {
        w.block("always @(posedge clk) begin", "end", |w| {
            w.line(format!("b <= {expr};"));
        });
    } else {
        w.line(format!("assign b = {expr};"));
    }
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// dot_clamp: f = clamp(round(B·V), 0, 1) in u1.F, registered; the cuts of
/// `timing::DOT_CLAMP` in place at the configuration's depth.
pub fn dot_clamp(cfg: &PipelineConfig) -> String {
    use crate::units::timing::{cut, DOT_CLAMP};
    let (nb, lh, f) = (cfg.normal_bits, cfg.lh_bits, cfg.dot_frac_bits);
    let ex = cfg.dot_exact_fmt();
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// dot_clamp (paper §4.2): exact B·V in {} ({} bits), one rounding ({:?}) to {}, clamped to [0, 1].",
        ex.name(),
        ex.width,
        cfg.rounding,
        cfg.dot_fmt().name()
    ));
    w.line(format!(
        "// Latency {}: pipeline_depth {} puts {} of its register cuts in place.",
        crate::units::timing::latency(cfg, DOT_CLAMP),
        cfg.pipeline_depth,
        crate::units::timing::cuts_in_place(cfg, DOT_CLAMP)
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] b,\n    input  wire [{}:0] v,\n    output reg  [{}:0] f\n);",
        module_name(cfg, "dot_clamp"),
        3 * nb - 1,
        3 * lh - 1,
        f
    ));
    let decl = format!("signed [{}:0]", ex.width - 1);
    let product = |i: u32| {
        (
            Factor::signed(format!("b[{}:{}]", i * nb + nb - 1, i * nb), nb),
            Factor::signed(format!("v[{}:{}]", i * lh + lh - 1, i * lh), lh),
        )
    };
    if cut(cfg, DOT_CLAMP, 0) {
        for i in 0..3 {
            let e = sum_of_products(&mut w, Form::of(cfg), &format!("p{i}m"), &[product(i)], 0, ex.width);
            w.stage(true, &decl, &format!("p{i}"), &e);
        }
        w.stage(cut(cfg, DOT_CLAMP, 1), &decl, "dot", "p0 + p1 + p2");
    } else {
        // No register between the products and their sum: one tree of all twelve rows.
        let e = sum_of_products(&mut w, Form::of(cfg), "pm", &[product(0), product(1), product(2)], 0, ex.width);
        w.stage(cut(cfg, DOT_CLAMP, 1), &decl, "dot", &e);
    }
    requant_clamp(&mut w, "fq", "dot", ex, f, cfg.rounding, 0, 1 << f, f + 1);
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line("f <= fq;");
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// power_unit: `R` read ports into the reloadable power table, one RAM copy per read port (all
/// written by the load port); index = round(x (N-1) / 2^F) for the paper's table, whose RAM
/// read register is the output register (latency 1), or the `power_unit_core` datapath of an
/// interpolated/segmented unit around its two knot reads (latency 2).
pub fn power_unit(cfg: &PipelineConfig) -> String {
    match cfg.power_unit {
        crate::config::PowerUnitKind::Table => {}
        crate::config::PowerUnitKind::Squaring => return power_unit_squaring(cfg),
        _ => return power_unit_with_core(cfg),
    }
    let (f, p, n) = (cfg.dot_frac_bits, cfg.power_frac_bits, cfg.power_entries);
    let ib = cfg.power_index_bits();
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// power_unit (paper §4.2): fs = (B·H)^n from a {n}-entry power table of {}-bit u1.{p} entries, loaded",
        p + 1
    ));
    w.line("// like a colour LUT through the write port; INIT_FILE holds the reset contents. One RAM");
    w.line("// copy per read port; its read register is the unit's output register.");
    w.line(format!(
        "// Index = {:?}(x * {}) >> {f}: a subtract instead of a multiplier.",
        cfg.power_index,
        n - 1
    ));
    power_unit_shell(&mut w, cfg);
    w.block("generate for (r = 0; r < R; r = r + 1) begin : port", "end endgenerate", |w| {
        let sw = f + 1 + ib + 1;
        w.line(format!("wire [{}:0] xr = x[r*{} +: {}];", f, f + 1, f + 1));
        w.line(format!(
            "wire [{}:0] scaled = ({{{}'d0, xr}} << {ib}) - {{{}'d0, xr}};",
            sw - 1,
            ib + 1,
            ib + 1
        ));
        let half = match cfg.power_index {
            crate::config::PowerIndex::Nearest => 1u64 << (f - 1),
            crate::config::PowerIndex::Truncate => 0,
        };
        w.line(format!("wire [{}:0] rounded = scaled + {sw}'d{half};", sw - 1));
        w.line(format!("wire [{}:0] idx = rounded[{}:{f}];", ib.max(1) - 1, f + ib.max(1) - 1));
        w.line(super::ram::instance(
            cfg,
            "u_ram",
            p + 1,
            cfg.power_depth(),
            cfg.power_addr_bits(),
            "idx",
            &format!("fs[r*{} +: {}]", p + 1, p + 1),
        ));
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// The power unit's module header: the same for every kind of power unit.
fn power_unit_shell(w: &mut VWriter, cfg: &PipelineConfig) {
    let (f, p) = (cfg.dot_frac_bits, cfg.power_frac_bits);
    let out = if cfg.power_unit == crate::config::PowerUnitKind::Table {
        "wire"
    } else {
        "reg "
    };
    w.line(format!(
        "module {} #(\n    parameter R = 1,\n    parameter INIT_FILE = \"{}\"\n) (\n    input  wire clk,\n    input  wire we,\n    input  wire [{}:0] waddr,\n    input  wire [{p}:0] wdata,\n    input  wire [R*{}-1:0] x,\n    output {out} [R*{}-1:0] fs\n);",
        module_name(cfg, "power_unit"),
        rom_file_name(cfg, "power_table", "hex"),
        cfg.power_addr_bits() - 1,
        f + 1,
        p + 1
    ));
    w.line("genvar r;");
}

/// No table: each read port squares and multiplies x up to the shininess the unit is built
/// for (the Cg Tutorial's specular power), registered. The load port stays (every top of a
/// light count has the same ports) and is ignored.
fn power_unit_squaring(cfg: &PipelineConfig) -> String {
    use super::booth::Form;
    let (f, p) = (cfg.dot_frac_bits, cfg.power_frac_bits);
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// power_unit (Cg Tutorial sec. 8.3): fs = x^{} by successive squarings (shininess {}), no table; {} guard bits.",
        cfg.power_exponent(cfg.shininess),
        cfg.shininess,
        crate::config::SQUARING_GUARD_BITS
    ));
    w.line("// The load port and INIT_FILE are kept for the top's interface and ignored.");
    power_unit_shell(&mut w, cfg);
    w.line("wire unused_load = ^{1'b0, we, waddr, wdata};");
    // A chain of products: Booth rows in functions (see `booth::Form`), or `*`.
    let form = match Form::of(cfg) {
        Form::Wires => Form::Function,
        other => other,
    };
    w.block("generate for (r = 0; r < R; r = r + 1) begin : port", "end endgenerate", |w| {
        w.line(format!("wire [{f}:0] xr = x[r*{} +: {}];", f + 1, f + 1));
        let y = super::power_units::squaring(
            w,
            cfg.power_formats(),
            crate::config::SQUARING_GUARD_BITS,
            cfg.power_exponent(cfg.shininess),
            "xr",
            form,
            crate::units::timing::cuts_in_place(cfg, crate::units::timing::SQUARING),
        );
        w.line(format!("always @(posedge clk) fs[r*{} +: {}] <= {y};", p + 1, p + 1));
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// A loadable table of `power_depth()` words read through two RAM copies per lookup (the
/// knots on both sides) by the `power_unit_core` datapath: one core instance computes the
/// addresses from x, the RAMs register the knots, and a second instance interpolates from
/// x one cycle later (synthesis keeps only the half of each that is used).
fn power_unit_with_core(cfg: &PipelineConfig) -> String {
    let (f, p) = (cfg.dot_frac_bits, cfg.power_frac_bits);
    let (depth, ab) = (cfg.power_depth(), cfg.power_addr_bits());
    let core = module_name(cfg, "power_unit_core");
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// power_unit (paper sec. 4.2, improved): {}, {depth} words of u1.{p} loaded like a colour LUT;",
        cfg.power_unit_design().label()
    ));
    w.line("// INIT_FILE holds the reset contents. Each read port reads two knots from two RAM copies");
    w.line("// (their read registers are the first stage), then interpolates (the output register).");
    power_unit_shell(&mut w, cfg);
    w.block("generate for (r = 0; r < R; r = r + 1) begin : port", "end endgenerate", |w| {
        w.line(format!("wire [{f}:0] xr = x[r*{} +: {}];", f + 1, f + 1));
        w.line(format!("wire [{}:0] a0;", ab - 1));
        w.line(format!("wire [{}:0] a1;", ab - 1));
        w.line(format!("wire [{p}:0] unused_y;"));
        w.line(format!(
            "{core} u_addr (.x(xr), .a0(a0), .a1(a1), .k0({}'d0), .k1({}'d0), .fs_out(unused_y));",
            p + 1,
            p + 1
        ));
        w.line(format!("wire [{p}:0] k0;"));
        w.line(format!("wire [{p}:0] k1;"));
        w.line(super::ram::instance(cfg, "u_ram0", p + 1, depth, ab, "a0", "k0"));
        w.line(super::ram::instance(cfg, "u_ram1", p + 1, depth, ab, "a1", "k1"));
        w.line(format!("reg [{f}:0] xd;"));
        w.line("always @(posedge clk) xd <= xr;");
        w.line(format!("wire [{}:0] unused_a0;", ab - 1));
        w.line(format!("wire [{}:0] unused_a1;", ab - 1));
        w.line(format!("wire [{p}:0] y;"));
        w.line(format!(
            "{core} u_core (.x(xd), .a0(unused_a0), .a1(unused_a1), .k0(k0), .k1(k1), .fs_out(y));"
        ));
        w.line(format!("always @(posedge clk) fs[r*{} +: {}] <= y;", p + 1, p + 1));
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// Name of a ROM init file of this configuration.
pub fn rom_file_name(cfg: &PipelineConfig, what: &str, ext: &str) -> String {
    format!("{what}_{}.{ext}", &cfg.hash()[..8])
}

/// Register cuts inside `light_term`: the first two cuts of the blends, which are also the
/// cuts of `light_accumulate` (the same f k, then Lc).
pub fn light_term_cuts(cfg: &PipelineConfig) -> u32 {
    crate::units::timing::cuts_in_place(cfg, crate::units::timing::ACCUMULATE)
}

/// light_term: one light's exact f·k·Lc per channel: combinational at depth 1, with a
/// register after f·k and then after ·Lc as the depth adds them (a clock port only then).
pub fn light_term(cfg: &PipelineConfig) -> String {
    let (ff, k, c) = (cfg.factor_frac(), cfg.k_frac_bits, cfg.colour_bits);
    let tw = cfg.term_fmt().width;
    let cuts = light_term_cuts(cfg);
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// light_term: exact f·k·Lc per channel, {} ({tw} bits); no rounding before the sum. {cuts} register stage(s).",
        cfg.term_fmt().name()
    ));
    let clk = if cuts > 0 { "input  wire clk,\n    " } else { "" };
    let lc_port = light_colour_port(cfg, 3 * c);
    w.line(format!(
        "module {} (\n    {clk}input  wire [{ff}:0] f,\n    input  wire [{k}:0] k,\n    {lc_port}output wire [{}:0] term\n);",
        module_name(cfg, "light_term"),
        3 * tw - 1
    ));
    let fkw = ff + k + 2;
    let e = sum_of_products(
        &mut w,
        Form::of(cfg),
        "fkm",
        &[(Factor::unsigned("f", ff + 1), Factor::unsigned("k", k + 1))],
        0,
        fkw,
    );
    w.stage(cuts >= 1, &format!("[{}:0]", fkw - 1), "fk", &e);
    if cfg.white_lights {
        // Lc = 2^c - 1 on every channel: f k Lc = (f k << c) - f k, one term for all three.
        w.line(format!(
            "wire [{}:0] tw0 = {{fk, {c}'d0}} - {};",
            tw - 1,
            super::writer::zext("fk", tw - fkw)
        ));
        w.stage(cuts >= 2, &format!("[{}:0]", tw - 1), "t0", "tw0");
        w.line("assign term = {t0, t0, t0};");
        w.line("endmodule");
        postamble(&mut w);
        return w.finish();
    }
    w.stage(cuts >= 1, &format!("[{}:0]", 3 * c - 1), "lc1", "lc");
    for ch in 0..3 {
        let e = sum_of_products(
            &mut w,
            Form::of(cfg),
            &format!("t{ch}m"),
            &[(
                Factor::unsigned("fk", fkw),
                Factor::unsigned(format!("lc1[{}:{}]", ch * c + c - 1, ch * c), c),
            )],
            0,
            tw,
        );
        w.stage(cuts >= 2, &format!("[{}:0]", tw - 1), &format!("t{ch}"), &e);
    }
    w.line("assign term = {t2, t1, t0};");
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// The light-colour input of a module's port list, `width` bits (none with white lights).
pub fn light_colour_port(cfg: &PipelineConfig, width: u32) -> String {
    if cfg.white_lights {
        String::new()
    } else {
        format!("input  wire [{}:0] lc,\n    ", width - 1)
    }
}

/// The light-colour connection of a `light_term` instance (none with white lights).
pub fn light_colour_conn(cfg: &PipelineConfig, lc: &str) -> String {
    if cfg.white_lights {
        String::new()
    } else {
        format!(", .lc({lc})")
    }
}

/// The clock connection of a `light_term` instance (none at depth 1).
pub fn light_term_clk(cfg: &PipelineConfig) -> &'static str {
    if light_term_cuts(cfg) > 0 {
        ".clk(clk), "
    } else {
        ""
    }
}

/// blend_finish: c_out = sat(c_in + round(acc)) per channel, registered; colours are stage
/// colours (`colour_guard_bits` fraction bits), so the sum rounds to that precision.
pub fn blend_finish(cfg: &PipelineConfig) -> String {
    let c = cfg.stage_colour_fmt().width;
    let g = cfg.colour_guard_bits;
    let acc = cfg.acc_fmt();
    let shift = crate::model::blend::sum_shift(cfg);
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// blend_finish: c_out = sat(c_in + round_{:?}(acc >> {shift})), acc in {} ({} bits), colours {}.",
        cfg.rounding,
        acc.name(),
        acc.width,
        cfg.stage_colour_fmt().name()
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] c_in,\n    input  wire [{}:0] acc,\n    output reg  [{}:0] c_out\n);",
        module_name(cfg, "blend_finish"),
        3 * c - 1,
        3 * acc.width - 1,
        3 * c - 1
    ));
    let max = cfg.stage_colour_max();
    for ch in 0..3 {
        w.line(format!(
            "wire [{}:0] a{ch} = acc[{}:{}];",
            acc.width - 1,
            ch * acc.width + acc.width - 1,
            ch * acc.width
        ));
        // The rounded sum never exceeds the accumulator's integer range; clamp it at max
        // already, since c_in + anything ≥ max saturates anyway.
        requant_clamp(&mut w, &format!("add{ch}"), &format!("a{ch}"), acc, g, cfg.rounding, 0, max, c);
        w.line(format!(
            "wire [{c}:0] s{ch} = {{1'b0, c_in[{}:{}]}} + {{1'b0, add{ch}}};",
            ch * c + c - 1,
            ch * c
        ));
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        for ch in 0..3 {
            // The saturated sum: the carry, or (with guard bits) anything above 1.0.
            let over = if g == 0 {
                format!("s{ch}[{c}]")
            } else {
                format!("(s{ch} > {}'d{max})", c + 1)
            };
            w.line(format!(
                "c_out[{}:{}] <= {over} ? {c}'d{max} : s{ch}[{}:0];",
                ch * c + c - 1,
                ch * c,
                c - 1
            ));
        }
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// diffuse_blend / specular_blend (parallel form): light terms of every slot, their exact
/// sum, and the finish, with the cuts of `timing::BLEND` in place at the depth.
pub fn blend(cfg: &PipelineConfig, unit: &str) -> String {
    use crate::units::timing::{cut, BLEND};
    let (ff, k, c, n) = (cfg.factor_frac(), cfg.k_frac_bits, cfg.colour_bits, cfg.lights);
    let cs = cfg.stage_colour_fmt().width;
    let tw = cfg.term_fmt().width;
    let aw = cfg.acc_fmt().width;
    let lt = light_term_cuts(cfg);
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// {unit} (paper §4.2): c_out = sat(c_in + sum_i f_i k_i Lc_i) over {n} light slot(s), exact sum."
    ));
    w.line(format!(
        "// Latency {}: the light terms take {lt} stage(s), the sum {}, the finish 1.",
        crate::units::timing::latency(cfg, BLEND),
        u32::from(cut(cfg, BLEND, 2))
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] c_in,\n    input  wire [{}:0] f,\n    input  wire [{}:0] k,\n    {}output wire [{}:0] c_out\n);",
        module_name(cfg, unit),
        3 * cs - 1,
        n * (ff + 1) - 1,
        n * (k + 1) - 1,
        light_colour_port(cfg, 3 * n * c),
        3 * cs - 1
    ));
    for i in 0..n {
        w.line(format!("wire [{}:0] t{i};", 3 * tw - 1));
        w.line(format!(
            "{} lt{i} ({}.f(f[{}:{}]), .k(k[{}:{}]){}, .term(t{i}));",
            module_name(cfg, "light_term"),
            light_term_clk(cfg),
            i * (ff + 1) + ff,
            i * (ff + 1),
            i * (k + 1) + k,
            i * (k + 1),
            light_colour_conn(cfg, &format!("lc[{}:{}]", 3 * c * (i + 1) - 1, 3 * c * i))
        ));
    }
    // c_in waits beside the light terms.
    let cw = format!("[{}:0]", 3 * cs - 1);
    let mut cin = "c_in".to_string();
    for s in 1..=lt {
        w.stage(true, &cw, &format!("c_in_d{s}"), &cin);
        cin = format!("c_in_d{s}");
    }
    let sums: Vec<String> = (0..3)
        .rev()
        .map(|ch| {
            (0..n)
                .map(|i| super::writer::zext(&format!("t{i}[{}:{}]", ch * tw + tw - 1, ch * tw), aw - tw))
                .collect::<Vec<_>>()
                .join(" + ")
        })
        .collect();
    // A concatenation of sums would be sized by its operands, so each channel is its own wire.
    for (ch, e) in (0..3).rev().zip(&sums) {
        w.line(format!("wire [{}:0] sum{ch} = {e};", aw - 1));
    }
    let summed = cut(cfg, BLEND, 2);
    w.stage(summed, &format!("[{}:0]", 3 * aw - 1), "acc", "{sum2, sum1, sum0}");
    w.stage(summed, &cw, "c_fin", &cin);
    w.line(format!(
        "{} fin (.clk(clk), .c_in(c_fin), .acc(acc), .c_out(c_out));",
        module_name(cfg, "blend_finish")
    ));
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// texture_modulate: round(c_in tex / (2^w - 1)), registered; a register after the product
/// when the depth puts `timing::TEXTURE`'s cut in place. Without guard bits the division is
/// the add-and-shift identity (`fixed::unorm_mul`); with them it is `fixed::UnormDiv`'s
/// constant reciprocal as shifted adds. Both are proven equal to the division in `fixed`.
pub fn texture_modulate(cfg: &PipelineConfig) -> String {
    use crate::units::timing::{cut, TEXTURE};
    let c = cfg.colour_bits;
    let cs = cfg.stage_colour_fmt().width;
    let g = cfg.colour_guard_bits;
    let mut w = VWriter::new();
    preamble(&mut w);
    let div = crate::model::texture_modulate::divider(cfg);
    if g == 0 {
        w.line("// texture_modulate (paper §5.1): exact round(c_in·tex / (2^w - 1)) as ((p + h) + ((p + h) >> w)) >> w, h = 2^(w-1).");
    } else {
        w.line(format!(
            "// texture_modulate (paper §5.1): exact round(c_in·tex / (2^w - 1)) for c_in in {} as ((p + {}) * {}) >> {}, the constant as shifted adds.",
            cfg.stage_colour_fmt().name(),
            div.half,
            div.m,
            div.s
        ));
    }
    w.line(format!("// Latency {}.", crate::units::timing::latency(cfg, TEXTURE)));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] c_in,\n    input  wire [{}:0] tex,\n    output reg  [{}:0] c_out\n);",
        module_name(cfg, "texture_modulate"),
        3 * cs - 1,
        3 * c - 1,
        3 * cs - 1
    ));
    let yw = if g == 0 { 2 * c + 1 } else { div.y_bits };
    let bits = div.m_bits();
    let qw = yw + bits.last().copied().unwrap_or(0) + 1;
    for ch in 0..3 {
        let lane = |v: &str, width: u32| Factor::unsigned(format!("{v}[{}:{}]", ch * width + width - 1, ch * width), width);
        let e = sum_of_products(
            &mut w,
            Form::of(cfg),
            &format!("p{ch}m"),
            &[(lane("c_in", cs), lane("tex", c))],
            if g == 0 { 1u128 << (c - 1) } else { div.half as u128 },
            yw,
        );
        if g == 0 {
            w.stage(cut(cfg, TEXTURE, 0), &format!("[{}:0]", 2 * c), &format!("p{ch}"), &e);
            w.line(format!("wire [{}:0] q{ch} = p{ch} + (p{ch} >> {c});", 2 * c));
        } else {
            w.stage(cut(cfg, TEXTURE, 0), &format!("[{}:0]", yw - 1), &format!("p{ch}"), &e);
            let sum: Vec<String> = bits
                .iter()
                .map(|&b| format!("({} << {b})", super::writer::zext(&format!("p{ch}"), qw - yw)))
                .collect();
            w.line(format!("wire [{}:0] q{ch} = {};", qw - 1, sum.join(" + ")));
        }
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        for ch in 0..3 {
            let (hi, lo) = if g == 0 { (2 * c - 1, c) } else { (div.s + cs - 1, div.s) };
            w.line(format!("c_out[{}:{}] <= q{ch}[{hi}:{lo}];", ch * cs + cs - 1, ch * cs));
        }
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// colour_round: a stage colour to the output colour, rounded by the configured rule,
/// registered. The stage colour is at most 1.0, so the rounded value never passes the
/// largest code and needs no clamp.
pub fn colour_round(cfg: &PipelineConfig) -> String {
    let c = cfg.colour_bits;
    let cs = cfg.stage_colour_fmt().width;
    let g = cfg.colour_guard_bits;
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// colour_round: c_out = round_{:?}(c_in / 2^{g}), c_in in {}, c_out in {}; latency 1.",
        cfg.rounding,
        cfg.stage_colour_fmt().name(),
        cfg.colour_fmt().name()
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] c_in,\n    output reg  [{}:0] c_out\n);",
        module_name(cfg, "colour_round"),
        3 * cs - 1,
        3 * c - 1
    ));
    for ch in 0..3 {
        let x = format!("c_in[{}:{}]", ch * cs + cs - 1, ch * cs);
        let inc = match cfg.rounding {
            crate::fixed::Rounding::Truncate => format!("{cs}'d0"),
            crate::fixed::Rounding::HalfUp => format!("{cs}'d{}", 1u64 << (g - 1)),
            crate::fixed::Rounding::NearestEven => {
                format!("{cs}'d{} + {{{}'d0, c_in[{}]}}", (1u64 << (g - 1)) - 1, cs - 1, ch * cs + g)
            }
        };
        // At most (2^c - 1) 2^g + 2^(g-1): no carry out of cs bits.
        w.line(format!("wire [{}:0] r{ch} = {x} + {inc};", cs - 1));
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        for ch in 0..3 {
            w.line(format!("c_out[{}:{}] <= r{ch}[{}:{g}];", ch * c + c - 1, ch * c, cs - 1));
        }
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}
