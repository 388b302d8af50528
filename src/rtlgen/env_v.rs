//! Verilog of EMBM's two units (paper §3.3; `model::env_map` has the arithmetic):
//! `env_coords` (s = st + M·b, the texel and the bilinear weights) and `env_fetch` (the four
//! texels of a 2×2 block of an environment map).

use super::booth::{sum_of_products, Factor, Form};
use super::units_v::{module_name, postamble, preamble, rom_file_name};
use super::writer::VWriter;
use crate::config::PipelineConfig;
use crate::model::env_map::{coord_frac, SUBTEXEL_BITS, WEIGHT_FRAC_BITS};
use crate::units::timing::{cut, cuts_in_place, latency, ENV_COORDS};

/// Bits of the exact map coordinate S = st·2^(nb−1) + m b_x + m b_y.
pub fn coord_width(cfg: &PipelineConfig) -> u32 {
    cfg.lh_bits + cfg.normal_bits + 1
}

/// RAM copies of each environment map: one per texel of the bilinear block.
pub const FETCH_COPIES: u32 = 4;

/// Bits of a bilinear weight (u1.8: 0..=256).
pub const WEIGHT_BITS: u32 = WEIGHT_FRAC_BITS + 1;

pub fn env_coords(cfg: &PipelineConfig) -> String {
    let (nb, lh, e) = (cfg.normal_bits, cfg.lh_bits, cfg.env_map_bits);
    let g = coord_frac(cfg);
    let sw = coord_width(cfg);
    // X = (S + 2^G)·2^(E−1) − 2^(G−1): E − 1 more integer bits.
    let xw = sw + e;
    let fb = SUBTEXEL_BITS + 1;
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line("// env_coords (paper §3.3, Direct3D 6 EMBM): s = st + M (b_x, b_y) exactly, the texel");
    w.line(format!(
        "// coordinate X = (s + 1) n/2 - 1/2 (n = {}) clamped to [0, n - 1], x0 = min(floor X, n - 2), the",
        1u32 << e
    ));
    w.line(format!(
        "// sub-texel fraction truncated to {SUBTEXEL_BITS} bits (0..16) and the four bilinear weights, exact in u1.{WEIGHT_FRAC_BITS}."
    ));
    w.line(format!(
        "// Latency {}: pipeline_depth {} puts {} of its register cuts in place.",
        latency(cfg, ENV_COORDS),
        cfg.pipeline_depth,
        cuts_in_place(cfg, ENV_COORDS)
    ));
    w.line(format!(
        "module {} (\n    input  wire clk,\n    input  wire [{}:0] b,\n    input  wire [{}:0] st,\n    input  wire [{}:0] m,\n    output reg  [{}:0] x0,\n    output reg  [{}:0] y0,\n    output reg  [{}:0] w\n);",
        module_name(cfg, "env_coords"),
        2 * nb - 1,
        2 * lh - 1,
        4 * lh - 1,
        e - 1,
        e - 1,
        4 * WEIGHT_BITS - 1
    ));
    let bl = |i: u32| Factor::signed(format!("b[{}:{}]", i * nb + nb - 1, i * nb), nb);
    let ml = |i: u32| Factor::signed(format!("m[{}:{}]", i * lh + lh - 1, i * lh), lh);
    for (i, (axis, (mx, my))) in [("x", (0, 2)), ("y", (1, 3))].into_iter().enumerate() {
        let i = i as u32;
        let prod = sum_of_products(
            &mut w,
            Form::of(cfg),
            &format!("s{axis}m"),
            &[(ml(mx), bl(0)), (ml(my), bl(1))],
            0,
            sw,
        );
        w.line(format!("wire [{}:0] st{axis}_raw = st[{}:{}];", lh - 1, i * lh + lh - 1, i * lh));
        w.line(format!(
            "wire signed [{}:0] st{axis} = $signed({{{{{}{{st{axis}_raw[{}]}}}}, st{axis}_raw}});",
            sw - 1,
            sw - lh,
            lh - 1
        ));
        w.stage(
            cut(cfg, ENV_COORDS, 0),
            &format!("signed [{}:0]", sw - 1),
            &format!("s{axis}"),
            &format!("$signed({prod}) + (st{axis} <<< {})", nb - 1),
        );
        w.line(format!(
            "wire signed [{}:0] u{axis} = ($signed({{{{{}{{s{axis}[{}]}}}}, s{axis}}}) + {xw}'sd{}) <<< {};",
            xw - 1,
            xw - sw,
            sw - 1,
            1u64 << g,
            e - 1
        ));
        w.line(format!(
            "wire signed [{}:0] v{axis} = u{axis} - {xw}'sd{};",
            xw - 1,
            1u64 << (g - 1)
        ));
        // Clamped to [0, (n - 1) 2^G]: G + E bits hold it.
        let top = ((1u64 << e) - 1) << g;
        let cw = g + e;
        w.line(format!(
            "wire [{}:0] c{axis} = v{axis} < 0 ? {cw}'d0 : v{axis} > {xw}'sd{top} ? {cw}'d{top} : v{axis}[{}:0];",
            cw - 1,
            cw - 1
        ));
        // X at the last texel's centre, exactly: the block before it, at its far side.
        w.line(format!("wire l{axis} = c{axis}[{}:{g}] == {e}'d{};", g + e - 1, (1u64 << e) - 1));
        w.stage(
            cut(cfg, ENV_COORDS, 1),
            &format!("[{}:0]", e - 1),
            &format!("i{axis}"),
            &format!("l{axis} ? {e}'d{} : c{axis}[{}:{g}]", (1u64 << e) - 2, g + e - 1),
        );
        w.stage(
            cut(cfg, ENV_COORDS, 1),
            &format!("[{}:0]", fb - 1),
            &format!("f{axis}"),
            &format!(
                "l{axis} ? {fb}'d{} : {{1'b0, c{axis}[{}:{}]}}",
                1 << SUBTEXEL_BITS,
                g - 1,
                g - SUBTEXEL_BITS
            ),
        );
        w.line(format!("wire [{}:0] g{axis} = {fb}'d{} - f{axis};", fb - 1, 1 << SUBTEXEL_BITS));
    }
    let uf = |s: &str| Factor::unsigned(s, fb);
    for (i, (a, b)) in [("gx", "gy"), ("fx", "gy"), ("gx", "fy"), ("fx", "fy")].iter().enumerate() {
        // At most 16 x 16 = 256: exact in the weight's 9 bits.
        let e = sum_of_products(&mut w, Form::of(cfg), &format!("w{i}m"), &[(uf(a), uf(b))], 0, WEIGHT_BITS);
        w.line(format!("wire [{}:0] wp{i} = {e};", WEIGHT_BITS - 1));
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line("x0 <= ix;");
        w.line("y0 <= iy;");
        w.line(format!(
            "w <= {{{}}};",
            (0..4)
                .rev()
                .map(|i| format!("wp{i}[{}:0]", WEIGHT_BITS - 1))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    });
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}

/// `env_fetch_<which>`: four copies of the map, one per texel of the 2×2 block, all written
/// by the load port (texel (x, y) at address y·n + x); each read register is the output.
pub fn env_fetch(cfg: &PipelineConfig, unit: &str, init_stem: &str) -> String {
    let (e, cb) = (cfg.env_map_bits, cfg.colour_bits);
    let mut w = VWriter::new();
    preamble(&mut w);
    w.line(format!(
        "// {unit} (paper §3.3): the texels (x0, y0), (x0 + 1, y0), (x0, y0 + 1), (x0 + 1, y0 + 1) of a"
    ));
    w.line(format!(
        "// {n}x{n} environment map, one RAM copy per texel (block RAM on FPGAs), all loaded through the",
        n = 1u32 << e
    ));
    w.line("// write port (texel (x, y) at address y n + x, {B, G, R} with R in the low bits); INIT_FILE");
    w.line("// holds the power-up map. Each copy's read register is the unit's output register.");
    w.line(format!(
        "module {} #(\n    parameter INIT_FILE = \"{}\"\n) (\n    input  wire clk,\n    input  wire we,\n    input  wire [{}:0] waddr,\n    input  wire [{}:0] wdata,\n    input  wire [{}:0] x0,\n    input  wire [{}:0] y0,\n    output wire [{}:0] t\n);",
        module_name(cfg, unit),
        rom_file_name(cfg, init_stem, "hex"),
        2 * e - 1,
        3 * cb - 1,
        e - 1,
        e - 1,
        12 * cb - 1
    ));
    w.line(format!("wire [{}:0] x1 = x0 + {e}'d1;", e - 1));
    w.line(format!("wire [{}:0] y1 = y0 + {e}'d1;", e - 1));
    for (i, (x, y)) in [("x0", "y0"), ("x1", "y0"), ("x0", "y1"), ("x1", "y1")].iter().enumerate() {
        w.line(format!("wire [{}:0] rd{i};", 3 * cb - 1));
        w.line(super::ram::instance(
            cfg,
            &format!("u_ram{i}"),
            3 * cb,
            1 << (2 * e),
            2 * e,
            &format!("{{{y}, {x}}}"),
            &format!("rd{i}"),
        ));
    }
    w.line("assign t = {rd3, rd2, rd1, rd0};");
    w.line("endmodule");
    postamble(&mut w);
    w.finish()
}
