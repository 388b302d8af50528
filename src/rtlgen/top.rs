//! The top pipeline, `gbump_pipeline_<hash>`: valid-in/valid-out, synchronous reset of the
//! valid bits, the power table's load port, and the fixed latency of `latency()`.
//!
//! Parallel lights (one fragment per clock): bump_fetch → dot_clamp ×2n → power_table (n read
//! ports) → three blend/texture stages in the configured order; latency 6.
//! Serial lights (paper §4.2, n clocks per fragment): the fragment is held while a counter
//! walks the light slots through one dot_clamp pair, one power-table port and two
//! accumulators; `in_ready` is low while it does; latency n + 6.
//! The bump state (L_i, H_i, Lc_i, k_i) enters with each fragment, so vectors are
//! self-contained; a production design would hold it in per-triangle registers.

use super::units_v::module_name;
use super::writer::{zext, VWriter};
use crate::config::{BlendOrder, LightMode, PipelineConfig};

/// Rising edges with `rst` high that bring the top to a known idle state from any power-up
/// state: every valid bit is cleared by `rst ? 0 : ...` at the first one. The testbenches hold
/// reset for exactly this many edges, so the number is proven by every regression.
pub const RESET_CYCLES: u32 = 1;

/// Register stages of the three colour units (two blends and the texture modulation).
const COLOUR_STAGES: u32 = 3;

/// Rising edges from the one that accepts a fragment (`in_valid && in_ready` high) to the
/// one at which its `out_valid` is first sampled high. Every testbench checks it per vector.
pub fn latency(cfg: &PipelineConfig) -> u32 {
    match cfg.light_mode {
        // bump_fetch, dot_clamp, power_table, then the colour stages.
        LightMode::Parallel => 3 + COLOUR_STAGES,
        // The accepting edge captures the fragment; one edge per light slot through
        // dot_clamp; the power table; the accumulator; then the colour stages.
        LightMode::Serial => 1 + cfg.lights + 1 + 1 + COLOUR_STAGES,
    }
}

/// Width of the texel input.
pub fn texel_bits(cfg: &PipelineConfig) -> u32 {
    3 * cfg.normal_bits
}

fn lane(sig: &str, i: u32, w: u32) -> String {
    format!("{sig}[{}:{}]", i * w + w - 1, i * w)
}

/// Ports of the top, in order: (name, direction, width).
pub fn top_ports(cfg: &PipelineConfig) -> Vec<(&'static str, &'static str, u32)> {
    let (n, c, lh, k) = (cfg.lights, cfg.colour_bits, cfg.lh_bits, cfg.k_bits);
    vec![
        ("clk", "input", 1),
        ("rst", "input", 1),
        ("pt_we", "input", 1),
        ("pt_waddr", "input", cfg.power_addr_bits()),
        ("pt_wdata", "input", cfg.power_bits + 1),
        ("in_valid", "input", 1),
        ("in_ready", "output", 1),
        ("in_texel", "input", texel_bits(cfg)),
        ("in_c_src", "input", 3 * c),
        ("in_t", "input", 3 * c),
        ("in_diffuse_en", "input", 1),
        ("in_specular_en", "input", 1),
        ("in_l", "input", 3 * n * lh),
        ("in_h", "input", 3 * n * lh),
        ("in_lc", "input", 3 * n * c),
        ("in_k", "input", n * (k + 1)),
        ("out_valid", "output", 1),
        ("out_c", "output", 3 * c),
    ]
}

fn port_list(cfg: &PipelineConfig) -> String {
    let ps = top_ports(cfg);
    ps.iter()
        .enumerate()
        .map(|(i, (name, dir, w))| {
            let r = if *w > 1 { format!("[{}:0] ", w - 1) } else { String::new() };
            format!("    {dir:6} wire {r}{name}{}", if i + 1 < ps.len() { "," } else { "" })
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Aligned and gated blend factor of one light.
fn factor(cfg: &PipelineConfig, src: &str, src_frac: u32, en: &str) -> String {
    let pad = cfg.factor_frac() - src_frac;
    let ff = cfg.factor_frac();
    let aligned = if pad > 0 { format!("{{{src}, {pad}'d0}}") } else { src.to_string() };
    format!("({en} ? {aligned} : {}'d0)", ff + 1)
}

/// Registers `name <= expr` for a list, inside an always block.
fn regs(w: &mut VWriter, decls: &[(&str, u32, String)]) {
    for (name, width, _) in decls {
        w.line(format!(
            "reg {}{name};",
            if *width > 1 { format!("[{}:0] ", width - 1) } else { String::new() }
        ));
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        for (name, _, e) in decls {
            w.line(format!("{name} <= {e};"));
        }
    });
}

/// The three colour stages (blend / texture / blend in the configured order), from stage
/// `s0` colour `c_in` with factors, k and lc at that stage; emits `c_out` and `v_out`.
// One argument per signal bundle that travels with the colour.
#[allow(clippy::too_many_arguments)]
fn colour_stages(
    w: &mut VWriter,
    cfg: &PipelineConfig,
    s: u32,
    v_in: &str,
    c_in: &str,
    t: &str,
    dfac: &str,
    sfac: &str,
    k: &str,
    lc: &str,
) {
    let n = cfg.lights;
    let c = cfg.colour_bits;
    let fw = n * (cfg.factor_frac() + 1);
    let kw = n * (cfg.k_bits + 1);
    let lw = 3 * n * c;
    let order: [&str; 3] = match cfg.blend_order {
        BlendOrder::DiffuseTextureSpecular => ["diffuse_blend", "texture_modulate", "specular_blend"],
        BlendOrder::TextureLast => ["diffuse_blend", "specular_blend", "texture_modulate"],
    };
    // Side signals travel with the colour; each stage takes what it needs at its own cycle.
    let mut cur = (
        v_in.to_string(),
        c_in.to_string(),
        t.to_string(),
        dfac.to_string(),
        sfac.to_string(),
        k.to_string(),
        lc.to_string(),
    );
    for (i, unit) in order.iter().enumerate() {
        let st = s + i as u32 + 1;
        let (v, cc, tt, df, sf, kk, ll) = cur.clone();
        let out = format!("c{st}");
        w.line(format!("wire [{}:0] {out};", 3 * c - 1));
        let present = match *unit {
            "diffuse_blend" => cfg.diffuse,
            "specular_blend" => cfg.specular,
            _ => true,
        };
        if !present {
            w.line(format!("// {unit} is not in this configuration: the stage is a register."));
            w.line(format!("reg [{}:0] {out}_r;", 3 * c - 1));
            w.line(format!("always @(posedge clk) {out}_r <= {cc};"));
            w.line(format!("assign {out} = {out}_r;"));
        } else if *unit == "texture_modulate" {
            w.line(format!(
                "{} u_{unit} (.clk(clk), .c_in({cc}), .t({tt}), .c_out({out}));",
                module_name(cfg, unit)
            ));
        } else {
            let f = if *unit == "diffuse_blend" { &df } else { &sf };
            w.line(format!(
                "{} u_{unit} (.clk(clk), .c_in({cc}), .f({f}), .k({kk}), .lc({ll}), .c_out({out}));",
                module_name(cfg, unit)
            ));
        }
        let mut side = vec![(format!("v{st}"), 1, format!("rst ? 1'b0 : {v}"))];
        // Side signals travel only as far as a later stage uses them.
        let rest = &order[i + 1..];
        if rest.contains(&"texture_modulate") {
            side.push((format!("t{st}"), 3 * c, tt.clone()));
        }
        if rest.contains(&"specular_blend") && cfg.specular {
            side.extend([
                (format!("sf{st}"), fw, sf.clone()),
                (format!("k{st}"), kw, kk.clone()),
                (format!("lc{st}"), lw, ll.clone()),
            ]);
        }
        let side_ref: Vec<(&str, u32, String)> = side.iter().map(|(a, b, c)| (a.as_str(), *b, c.clone())).collect();
        regs(w, &side_ref);
        cur = (
            format!("v{st}"),
            out,
            format!("t{st}"),
            String::new(),
            format!("sf{st}"),
            format!("k{st}"),
            format!("lc{st}"),
        );
    }
    w.line(format!("assign out_valid = {};", cur.0));
    w.line("// The colour is forced to 0 while not valid, so no X ever leaves the pipeline after reset.");
    w.line(format!("assign out_c = {} ? {} : {}'d0;", cur.0, cur.1, 3 * c));
}

fn flat_code(cfg: &PipelineConfig) -> String {
    let nb = cfg.normal_bits;
    format!("{{{nb}'d{}, {nb}'d0, {nb}'d0}}", (1u64 << (nb - 1)) - 1)
}

/// The whole top module.
pub fn top(cfg: &PipelineConfig) -> String {
    let mut w = VWriter::new();
    w.line("`timescale 1ns / 1ps");
    w.line("`default_nettype none");
    w.line("");
    w.line(format!(
        "// gbump_pipeline: {:?} lights ({} slot(s)), blend order {:?}, latency {} cycles, one fragment every {} cycle(s).",
        cfg.light_mode,
        cfg.lights,
        cfg.blend_order,
        latency(cfg),
        cfg.initiation_interval()
    ));
    w.line("// INIT_FILE: the power table's contents at power-up (rst does not restore them); a path");
    w.line("// relative to the simulator's working folder, so pass an absolute one from elsewhere.");
    w.line(format!(
        "module {} #(\n    parameter INIT_FILE = \"{}\"\n) (\n{}\n);",
        module_name(cfg, "gbump_pipeline"),
        super::units_v::rom_file_name(cfg, "power_table", "hex"),
        port_list(cfg)
    ));
    match cfg.light_mode {
        LightMode::Parallel => parallel_body(&mut w, cfg),
        LightMode::Serial => serial_body(&mut w, cfg),
    }
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}

fn enables(cfg: &PipelineConfig, de: &str, se: &str, b: &str) -> (String, String) {
    let bypass = if cfg.skip_flat {
        format!(" & ~({b} == {})", flat_code(cfg))
    } else {
        String::new()
    };
    let d = if cfg.diffuse { format!("{de}{bypass}") } else { "1'b0".into() };
    let s = if cfg.specular { format!("{se}{bypass}") } else { "1'b0".into() };
    (d, s)
}

/// (lights, colour, L/H, k, normal, dot and power-entry bits) of a configuration.
fn widths(cfg: &PipelineConfig) -> (u32, u32, u32, u32, u32, u32, u32) {
    (
        cfg.lights,
        cfg.colour_bits,
        cfg.lh_bits,
        cfg.k_bits,
        cfg.normal_bits,
        cfg.dot_bits,
        cfg.power_bits,
    )
}

fn parallel_body(w: &mut VWriter, cfg: &PipelineConfig) {
    let (n, c, lh, k, nb, f, p) = widths(cfg);
    let ff = cfg.factor_frac();
    w.line("assign in_ready = 1'b1;");
    w.line("// Stage 1: bump_fetch; the rest of the fragment waits beside it.");
    w.line(format!("wire [{}:0] b1;", 3 * nb - 1));
    w.line(format!(
        "{} u_bump_fetch (.clk(clk), .texel(in_texel), .b(b1));",
        module_name(cfg, "bump_fetch")
    ));
    // A configuration without a blend unit leaves out its whole path (dot products, power
    // table, factors); its enable and light vectors stay on the interface, waived in the .vlt.
    let (d, sp) = (cfg.diffuse, cfg.specular);
    let keep = |v: Vec<(&'static str, u32, String, bool)>| -> Vec<(&'static str, u32, String)> {
        v.into_iter().filter(|x| x.3).map(|x| (x.0, x.1, x.2)).collect()
    };
    regs(
        w,
        &keep(vec![
            ("v1", 1, "rst ? 1'b0 : in_valid".into(), true),
            ("c1", 3 * c, "in_c_src".into(), true),
            ("t1", 3 * c, "in_t".into(), true),
            ("de1", 1, "in_diffuse_en".into(), d),
            ("se1", 1, "in_specular_en".into(), sp),
            ("l1", 3 * n * lh, "in_l".into(), d),
            ("h1", 3 * n * lh, "in_h".into(), sp),
            ("lc1", 3 * n * c, "in_lc".into(), true),
            ("k1", n * (k + 1), "in_k".into(), true),
        ]),
    );
    let (den, sen) = enables(cfg, "de1", "se1", "b1");
    w.line("// Stage 2: dot_clamp for every L_i and H_i.");
    if d {
        w.line(format!("wire [{}:0] fd2;", n * (f + 1) - 1));
    }
    if sp {
        w.line(format!("wire [{}:0] xh2;", n * (f + 1) - 1));
    }
    for i in 0..n {
        if d {
            w.line(format!(
                "{} u_dot_l{i} (.clk(clk), .b(b1), .v({}), .f({}));",
                module_name(cfg, "dot_clamp"),
                lane("l1", i, 3 * lh),
                lane("fd2", i, f + 1)
            ));
        }
        if sp {
            w.line(format!(
                "{} u_dot_h{i} (.clk(clk), .b(b1), .v({}), .f({}));",
                module_name(cfg, "dot_clamp"),
                lane("h1", i, 3 * lh),
                lane("xh2", i, f + 1)
            ));
        }
    }
    regs(
        w,
        &keep(vec![
            ("v2", 1, "rst ? 1'b0 : v1".into(), true),
            ("c2", 3 * c, "c1".into(), true),
            ("t2", 3 * c, "t1".into(), true),
            ("de2", 1, den, d),
            ("se2", 1, sen, sp),
            ("lc2", 3 * n * c, "lc1".into(), true),
            ("k2", n * (k + 1), "k1".into(), true),
        ]),
    );
    if sp {
        w.line(format!("// Stage 3: power_table with {n} read port(s)."));
        w.line(format!("wire [{}:0] fs3;", n * (p + 1) - 1));
        w.line(format!(
            "{} #(.R({n}), .INIT_FILE(INIT_FILE)) u_power_table (.clk(clk), .we(pt_we), .waddr(pt_waddr), .wdata(pt_wdata), .x(xh2), .fs(fs3));",
            module_name(cfg, "power_table")
        ));
    }
    regs(
        w,
        &keep(vec![
            ("v3", 1, "rst ? 1'b0 : v2".into(), true),
            ("c3", 3 * c, "c2".into(), true),
            ("t3", 3 * c, "t2".into(), true),
            ("de3", 1, "de2".into(), d),
            ("se3", 1, "se2".into(), sp),
            ("lc3", 3 * n * c, "lc2".into(), true),
            ("k3", n * (k + 1), "k2".into(), true),
            ("fd3", n * (f + 1), "fd2".into(), d),
        ]),
    );
    if d {
        w.line(format!("wire [{}:0] dfac3;", n * (ff + 1) - 1));
    }
    if sp {
        w.line(format!("wire [{}:0] sfac3;", n * (ff + 1) - 1));
    }
    for i in 0..n {
        if d {
            w.line(format!(
                "assign {} = {};",
                lane("dfac3", i, ff + 1),
                factor(cfg, &lane("fd3", i, f + 1), f, "de3")
            ));
        }
        if sp {
            w.line(format!(
                "assign {} = {};",
                lane("sfac3", i, ff + 1),
                factor(cfg, &lane("fs3", i, p + 1), p, "se3")
            ));
        }
    }
    w.line("// Stages 4-6: blends and texture in the configured order.");
    colour_stages(w, cfg, 3, "v3", "c3", "t3", "dfac3", "sfac3", "k3", "lc3");
}

fn serial_body(w: &mut VWriter, cfg: &PipelineConfig) {
    let (n, c, lh, k, nb, f, p) = widths(cfg);
    let tw = cfg.term_fmt().width;
    let aw = cfg.acc_fmt().width;
    let jb = (32 - (n.max(2) - 1).leading_zeros()).max(1);
    w.line("// Light sequencer: a fragment is held for n cycles, light slot j in cycle j.");
    w.line("reg busy;");
    w.line(format!("reg [{}:0] j;", jb - 1));
    w.line(format!("wire last_j = (j == {jb}'d{});", n - 1));
    w.line("assign in_ready = !busy || last_j;");
    w.line("wire accept = in_valid && in_ready;");
    w.block("always @(posedge clk) begin", "end", |w| {
        w.block("if (rst) begin", "end", |w| {
            w.line("busy <= 1'b0;");
            w.line(format!("j <= {jb}'d0;"));
        });
        w.block("else if (accept) begin", "end", |w| {
            w.line("busy <= 1'b1;");
            w.line(format!("j <= {jb}'d0;"));
        });
        w.block("else if (busy) begin", "end", |w| {
            w.line("busy <= !last_j;");
            w.line(format!("j <= last_j ? {jb}'d0 : j + {jb}'d1;"));
        });
    });
    let fr = [
        ("fr_texel", texel_bits(cfg), "in_texel"),
        ("fr_c", 3 * c, "in_c_src"),
        ("fr_t", 3 * c, "in_t"),
        ("fr_de", 1, "in_diffuse_en"),
        ("fr_se", 1, "in_specular_en"),
        ("fr_l", 3 * n * lh, "in_l"),
        ("fr_h", 3 * n * lh, "in_h"),
        ("fr_lc", 3 * n * c, "in_lc"),
        ("fr_k", n * (k + 1), "in_k"),
    ];
    for (name, wd, _) in fr {
        w.line(format!(
            "reg {}{name};",
            if wd > 1 { format!("[{}:0] ", wd - 1) } else { String::new() }
        ));
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        w.block("if (accept) begin", "end", |w| {
            for (name, _, src) in fr {
                w.line(format!("{name} <= {src};"));
            }
        });
    });
    w.line(format!("wire [{}:0] b0;", 3 * nb - 1));
    w.line(format!(
        "{} u_bump_fetch (.texel(fr_texel), .b(b0));",
        module_name(cfg, "bump_fetch_comb")
    ));
    let (den, sen) = enables(cfg, "fr_de", "fr_se", "b0");
    w.line(format!("wire [{}:0] l_sel = fr_l[j*{} +: {}];", 3 * lh - 1, 3 * lh, 3 * lh));
    w.line(format!("wire [{}:0] h_sel = fr_h[j*{} +: {}];", 3 * lh - 1, 3 * lh, 3 * lh));
    w.line(format!("wire [{}:0] fd1;", f));
    w.line(format!("wire [{}:0] xh1;", f));
    w.line(format!(
        "{} u_dot_l (.clk(clk), .b(b0), .v(l_sel), .f(fd1));",
        module_name(cfg, "dot_clamp")
    ));
    w.line(format!(
        "{} u_dot_h (.clk(clk), .b(b0), .v(h_sel), .f(xh1));",
        module_name(cfg, "dot_clamp")
    ));
    regs(
        w,
        &[
            ("v1", 1, "rst ? 1'b0 : busy".into()),
            ("first1", 1, format!("j == {jb}'d0")),
            ("last1", 1, "last_j".into()),
            ("lc1", 3 * c, format!("fr_lc[j*{} +: {}]", 3 * c, 3 * c)),
            ("k1", k + 1, format!("fr_k[j*{} +: {}]", k + 1, k + 1)),
            ("de1", 1, den),
            ("se1", 1, sen),
            ("c1", 3 * c, "fr_c".into()),
            ("t1", 3 * c, "fr_t".into()),
        ],
    );
    w.line(format!("wire [{p}:0] fs2;"));
    w.line(format!(
        "{} #(.R(1), .INIT_FILE(INIT_FILE)) u_power_table (.clk(clk), .we(pt_we), .waddr(pt_waddr), .wdata(pt_wdata), .x(xh1), .fs(fs2));",
        module_name(cfg, "power_table")
    ));
    regs(
        w,
        &[
            ("v2", 1, "rst ? 1'b0 : v1".into()),
            ("first2", 1, "first1".into()),
            ("last2", 1, "last1".into()),
            ("lc2", 3 * c, "lc1".into()),
            ("k2", k + 1, "k1".into()),
            ("de2", 1, "de1".into()),
            ("se2", 1, "se1".into()),
            ("c2", 3 * c, "c1".into()),
            ("t2", 3 * c, "t1".into()),
            ("fd2", f + 1, "fd1".into()),
        ],
    );
    w.line("// Accumulate one light's terms per cycle; the sum is exact, as in the parallel form.");
    w.line(format!("wire [{}:0] dterm;", 3 * tw - 1));
    w.line(format!("wire [{}:0] sterm;", 3 * tw - 1));
    w.line(format!(
        "{} u_dterm (.f({}), .k(k2), .lc(lc2), .term(dterm));",
        module_name(cfg, "light_term"),
        factor(cfg, "fd2", f, "de2")
    ));
    w.line(format!(
        "{} u_sterm (.f({}), .k(k2), .lc(lc2), .term(sterm));",
        module_name(cfg, "light_term"),
        factor(cfg, "fs2", p, "se2")
    ));
    w.line(format!("reg [{}:0] dacc;", 3 * aw - 1));
    w.line(format!("reg [{}:0] sacc;", 3 * aw - 1));
    w.line(format!("wire [{}:0] dacc_next;", 3 * aw - 1));
    w.line(format!("wire [{}:0] sacc_next;", 3 * aw - 1));
    for ch in 0..3 {
        for (acc, term) in [("dacc", "dterm"), ("sacc", "sterm")] {
            w.line(format!(
                "assign {} = (first2 ? {aw}'d0 : {}) + {};",
                lane(&format!("{acc}_next"), ch, aw),
                lane(acc, ch, aw),
                zext(&lane(term, ch, tw), aw - tw)
            ));
        }
    }
    w.block("always @(posedge clk) begin", "end", |w| {
        w.line("if (v2) dacc <= dacc_next;");
        w.line("if (v2) sacc <= sacc_next;");
    });
    regs(
        w,
        &[
            ("v3", 1, "rst ? 1'b0 : (v2 && last2)".into()),
            ("c3", 3 * c, "c2".into()),
            ("t3", 3 * c, "t2".into()),
            ("da3", 3 * aw, "dacc_next".into()),
            ("sa3", 3 * aw, "sacc_next".into()),
        ],
    );
    // The finish stages reuse blend_finish on the accumulated sums.
    let order: [&str; 3] = match cfg.blend_order {
        BlendOrder::DiffuseTextureSpecular => ["diffuse", "texture", "specular"],
        BlendOrder::TextureLast => ["diffuse", "specular", "texture"],
    };
    // The diffuse finish is always the first stage, so its sum is da3 and never travels.
    let mut cur = ("v3".to_string(), "c3".to_string(), "t3".to_string(), "sa3".to_string());
    for (i, what) in order.iter().enumerate() {
        let st = 4 + i as u32;
        let (v, cc, tt, sa) = cur.clone();
        let out = format!("c{st}");
        w.line(format!("wire [{}:0] {out};", 3 * c - 1));
        match *what {
            "texture" => w.line(format!(
                "{} u_texture_modulate (.clk(clk), .c_in({cc}), .t({tt}), .c_out({out}));",
                module_name(cfg, "texture_modulate")
            )),
            "diffuse" => w.line(format!(
                "{} u_diffuse_finish (.clk(clk), .c_in({cc}), .acc(da3), .c_out({out}));",
                module_name(cfg, "blend_finish")
            )),
            _ => w.line(format!(
                "{} u_specular_finish (.clk(clk), .c_in({cc}), .acc({sa}), .c_out({out}));",
                module_name(cfg, "blend_finish")
            )),
        };
        let rest = &order[i + 1..];
        let mut side = vec![(format!("v{st}"), 1, format!("rst ? 1'b0 : {v}"))];
        if rest.contains(&"texture") {
            side.push((format!("t{st}"), 3 * c, tt.clone()));
        }
        if rest.contains(&"specular") {
            side.push((format!("sa{st}"), 3 * aw, sa.clone()));
        }
        let side_ref: Vec<(&str, u32, String)> = side.iter().map(|(a, b, c)| (a.as_str(), *b, c.clone())).collect();
        regs(w, &side_ref);
        cur = (format!("v{st}"), out, format!("t{st}"), format!("sa{st}"));
    }
    w.line(format!("assign out_valid = {};", cur.0));
    w.line("// The colour is forced to 0 while not valid, so no X ever leaves the pipeline after reset.");
    w.line(format!("assign out_c = {} ? {} : {}'d0;", cur.0, cur.1, 3 * c));
}
