//! Verilog for the power-unit designs of `model::power_unit`, as standalone units with a
//! registered output (input `x`: u1.F, output `fs`: u1.P). Table-based designs read a
//! separate ROM module (`<name>_rom`, two combinational read ports, `$readmemh` contents),
//! so synthesis can count the datapath's gates apart from the storage, whose size is
//! reported in bits.

use super::booth::{sum_of_products, Factor, Form};
use super::writer::VWriter;
use crate::model::power_unit::{segment_of, PowerFormats, PowerUnitDesign};

/// Module name of a design.
pub fn name(d: &PowerUnitDesign, fm: PowerFormats) -> String {
    let tag = match *d {
        PowerUnitDesign::Table { entries, nearest } => format!("table{entries}{}", if nearest { "n" } else { "t" }),
        PowerUnitDesign::Lerp { knots } => format!("lerp{knots}"),
        PowerUnitDesign::Segmented {
            segments,
            per_segment,
            lerp,
        } => format!("seg{segments}x{per_segment}{}", if lerp { "l" } else { "" }),
        PowerUnitDesign::Squaring { guard } => format!("sq{guard}"),
    };
    format!("pu_{tag}_f{}p{}", fm.f, fm.p)
}

fn head(w: &mut VWriter) {
    w.line("`timescale 1ns / 1ps");
    w.line("`default_nettype none");
}

/// The ROM module: `depth` words, two read ports.
pub fn rom(module: &str, width: u32, depth: usize) -> String {
    let ab = addr_bits(depth);
    let mut w = VWriter::new();
    head(&mut w);
    w.line(format!("module {module}_rom #(parameter INIT_FILE = \"{module}.hex\") (input wire [{}:0] a0, input wire [{}:0] a1, output wire [{}:0] d0, output wire [{}:0] d1);", ab - 1, ab - 1, width - 1, width - 1));
    w.line(format!("reg [{}:0] mem [0:{}];", width - 1, depth - 1));
    w.line("initial $readmemh(INIT_FILE, mem);");
    w.line("assign d0 = mem[a0];");
    w.line("assign d1 = mem[a1];");
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}

/// Address bits of a memory of `depth` words (at least one).
pub fn addr_bits(depth: usize) -> u32 {
    (usize::BITS - (depth.max(2) - 1).leading_zeros()).max(1)
}

/// Entry-index bits (at least one) and segment-number bits of a segmented design.
pub fn segment_bits(segments: u32, per_segment: u32) -> (u32, u32) {
    (per_segment.trailing_zeros().max(1), (32 - (segments - 1).leading_zeros()).max(1))
}

/// An input inside segment `s` (the last segment holds 0): what the datapath asks
/// `segment_of` about that segment's base and width.
pub fn segment_probe(f: u32, segments: u32, s: u32) -> i64 {
    if s + 1 == segments {
        0
    } else {
        1i64 << (f - 1 - s)
    }
}

/// Address bits of a design's ROM.
pub fn rom_depth(d: &PowerUnitDesign, fm: PowerFormats) -> usize {
    (d.rom_bits(fm) / (fm.p as u64 + 1)) as usize
}

/// The datapath module (`n` only matters for squaring, where it is built in): registered,
/// reading its own ROM module.
pub fn unit(d: &PowerUnitDesign, fm: PowerFormats, n: u32) -> String {
    let (f, p) = (fm.f, fm.p);
    let m = name(d, fm);
    let mut w = VWriter::new();
    head(&mut w);
    w.line(format!(
        "// {}: x^n for x = x/2^{f} (u1.{f}) to u1.{p}, registered. See model::power_unit.",
        d.label()
    ));
    w.line(format!("module {m} (input wire clk, input wire [{f}:0] x, output reg [{p}:0] fs);"));
    let result = datapath(&mut w, d, fm, n, false, &|w: &mut VWriter| {
        w.line(format!("wire [{p}:0] k0;"));
        w.line(format!("wire [{p}:0] k1;"));
        w.line(format!("{m}_rom u_rom (.a0(a0), .a1(a1), .d0(k0), .d1(k1));"));
    });
    w.line(format!("always @(posedge clk) fs <= {result};"));
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}

/// The same datapath as a combinational core that reads an external memory through
/// (a0 -> k0, a1 -> k1): the pipeline's power unit wraps it around its loadable table.
pub fn core(d: &PowerUnitDesign, fm: PowerFormats, module: &str) -> String {
    let (f, p) = (fm.f, fm.p);
    let depth = rom_depth(d, fm);
    let ab = addr_bits(depth);
    let mut w = VWriter::new();
    head(&mut w);
    w.line(format!(
        "// {}: combinational core of the power unit; the table is outside.",
        d.label()
    ));
    w.line(format!(
        "module {module} (input wire [{f}:0] x, output wire [{}:0] a0, output wire [{}:0] a1, input wire [{p}:0] k0, input wire [{p}:0] k1, output wire [{p}:0] fs_out);",
        ab - 1,
        ab - 1
    ));
    let result = datapath(&mut w, d, fm, 0, true, &|_: &mut VWriter| {});
    w.line(format!("assign fs_out = {result};"));
    w.line("endmodule");
    w.line("`default_nettype wire");
    w.finish()
}

/// Emit the datapath of `d`: address logic driving `a0`/`a1`, then `mem` (which must make
/// `k0`/`k1` available), then the result; returns the expression of the result.
fn datapath(w: &mut VWriter, d: &PowerUnitDesign, fm: PowerFormats, n: u32, ports: bool, mem: &dyn Fn(&mut VWriter)) -> String {
    let (f, p) = (fm.f, fm.p);
    let depth = rom_depth(d, fm);
    let ab = addr_bits(depth);
    // Rounded signed interpolation k0 + round((k1 - k0) * t / 2^F) in P+2+F+1 bits.
    let interp = |w: &mut VWriter, t: &str, tw: u32| {
        let pw = p + 2 + tw + 1;
        w.line(format!(
            "wire signed [{}:0] diff = $signed({{2'b00, k1}}) - $signed({{2'b00, k0}});",
            p + 2
        ));
        let e = sum_of_products(
            w,
            Form::Wires,
            "prodm",
            &[(Factor::signed("diff", p + 3), Factor::unsigned(t, tw))],
            0,
            pw,
        );
        w.line(format!("wire signed [{}:0] prod = {e};", pw - 1));
        w.line(format!(
            "wire signed [{}:0] step = (prod + {pw}'sd{}) >>> {f};",
            pw - 1,
            1u64 << (f - 1)
        ));
        w.line(format!("wire [{p}:0] y_out = k0 + step[{p}:0];"));
    };
    // a0/a1 are wires of the standalone unit and output ports of the core.
    let addr = |w: &mut VWriter, name: &str, e: &str| {
        if ports {
            w.line(format!("assign {name} = {e};"));
        } else {
            w.line(format!("wire [{}:0] {name} = {e};", ab - 1));
        }
    };
    match *d {
        PowerUnitDesign::Table { entries, nearest } => {
            let ib = entries.trailing_zeros();
            let sw = f + 1 + ib + 1;
            w.line(format!(
                "wire [{}:0] scaled = ({{{}'d0, x}} << {ib}) - {{{}'d0, x}};",
                sw - 1,
                ib + 1,
                ib + 1
            ));
            w.line(format!(
                "wire [{}:0] rounded = scaled + {sw}'d{};",
                sw - 1,
                if nearest { 1u64 << (f - 1) } else { 0 }
            ));
            addr(w, "a0", &format!("rounded[{}:{f}]", f + ab - 1));
            addr(w, "a1", "a0");
            mem(w);
            "k0".into()
        }
        PowerUnitDesign::Lerp { knots } => {
            // x * (N - 1) by a constant multiply: N - 1 is not a power of two.
            let sw = f + 1 + ab + 1;
            w.line(format!("wire [{}:0] scaled = {{{}'d0, x}} * {sw}'d{};", sw - 1, ab + 1, knots - 1));
            w.line(format!("wire [{}:0] i = scaled[{}:{f}];", ab - 1, f + ab - 1));
            w.line(format!("wire [{}:0] fr = scaled[{}:0];", f - 1, f - 1));
            w.line(format!("wire last = (i >= {ab}'d{});", knots - 1));
            addr(w, "a0", &format!("last ? {ab}'d{} : i", knots - 1));
            addr(w, "a1", &format!("last ? {ab}'d{} : i + {ab}'d1", knots - 1));
            mem(w);
            interp(w, "fr", f);
            "(last ? k0 : y_out)".into()
        }
        PowerUnitDesign::Segmented {
            segments,
            per_segment,
            lerp,
        } => {
            let (mb, sb) = segment_bits(segments, per_segment);
            w.line(format!("wire [{f}:0] y = {{1'b1, {f}'d0}} - x;"));
            w.line("// Segment: the leading one of y (segment 0 also holds y = 2^F).");
            w.line(format!("reg [{}:0] s;", sb - 1));
            w.line("integer i;");
            w.block("always @* begin", "end", |w| {
                w.line(format!("s = {sb}'d{};", segments - 1));
                w.line(format!(
                    "for (i = {}; i >= 0; i = i - 1) if (y[{} - i]) s = i[{}:0];",
                    segments as i32 - 2,
                    f - 1,
                    sb - 1
                ));
                w.line(format!("if (y[{f}]) s = {sb}'d0;"));
            });
            w.line(format!("reg [{f}:0] off;"));
            w.line(format!("reg [{}:0] j;", f + mb));
            w.line(format!("reg [{}:0] t;", f - 1));
            w.block("always @*", "", |w| {
                w.block("case (s)", "endcase", |w| {
                    for s in 0..segments {
                        let probe = segment_probe(f, segments, s);
                        let (_, lo, lw) = segment_of(f, segments, probe);
                        let body = if lw >= mb {
                            let sh = lw - mb;
                            let tpart = if sh == 0 {
                                format!("{f}'d0")
                            } else {
                                format!("{{off[{}:0], {}'d0}}", sh - 1, f - sh)
                            };
                            format!("begin off = y - {}'d{lo}; j = {{{mb}'d0, off}} >> {sh}; t = {tpart}; end", f + 1)
                        } else {
                            format!(
                                "begin off = y - {}'d{lo}; j = {{{mb}'d0, off}} << {}; t = {f}'d0; end",
                                f + 1,
                                mb - lw
                            )
                        };
                        let label = if s + 1 == segments {
                            "default".to_string()
                        } else {
                            format!("{sb}'d{s}")
                        };
                        w.line(format!("{label}: {body}"));
                    }
                });
            });
            let per = if lerp { per_segment + 1 } else { per_segment };
            w.line(format!(
                "wire [{}:0] jc = (j > {}) ? {}'d{} : j[{}:0];",
                ab - 1,
                per - 1,
                ab,
                per - 1,
                ab - 1
            ));
            addr(w, "a0", &format!("s * {ab}'d{per} + jc"));
            addr(w, "a1", &format!("(t == {f}'d0) ? a0 : a0 + {ab}'d1"));
            mem(w);
            if lerp {
                interp(w, "t", f);
                format!("((t == {f}'d0) ? k0 : y_out)")
            } else {
                "k0".into()
            }
        }
        PowerUnitDesign::Squaring { guard } => squaring(w, fm, guard, n, "x", Form::Function, 0),
    }
}

/// The products square-and-multiply forms for x^n (n >= 1) once the top bit of n has made
/// the running power x (1·1 and 1·x are exact, so no product forms them), in order: a
/// squaring per lower bit of n, each followed by a multiply by x where the bit is set (true:
/// a multiply). None for n = 0 (x^0 = 1).
pub fn squaring_products(n: u32) -> Vec<bool> {
    let bits = 32 - n.leading_zeros();
    (0..bits.saturating_sub(1))
        .rev()
        .flat_map(|bit| std::iter::once(false).chain(((n >> bit) & 1 == 1).then_some(true)))
        .collect()
}

/// Where `cuts` registers split a chain of `products` into `cuts + 1` parts as equal as the
/// products allow: register j sits before product `ceil(products · j / (cuts + 1))` (at the
/// chain's end when that is `products`; two registers at one place follow each other).
pub fn squaring_cut_positions(products: usize, cuts: u32) -> Vec<usize> {
    let parts = cuts as usize + 1;
    (1..parts).map(|j| (products * j).div_ceil(parts)).collect()
}

/// Square-and-multiply for x^n (n built in) on u1.(P+guard), each product rounded half up,
/// its products written in `form` (a chain of up to fourteen products for n < 256: Booth rows in
/// functions, or `*`) from input `x` (u1.F), with `cuts` registers along the chain (on
/// `clk`, where [`squaring_cut_positions`] puts them); returns the expression of the u1.P
/// result. The pipeline's squaring power unit and `gbump power-space`'s standalone unit both
/// emit it here.
pub fn squaring(w: &mut VWriter, fm: PowerFormats, guard: u32, n: u32, x: &str, form: Form, cuts: u32) -> String {
    let (f, p) = (fm.f, fm.p);
    let wd = p + guard;
    w.line(format!(
        "// Built for n = {n}: square-and-multiply on u1.{wd}, each product rounded half-up."
    ));
    // x <= 1.0, so the rounded sum fits f + wd + 1 bits; its low f bits are the rounding.
    w.line(format!(
        "wire [{}:0] xw_r = {{{x}, {wd}'d0}} + {}'d{};",
        f + wd,
        f + wd + 1,
        1u64 << (f - 1)
    ));
    w.line(format!("wire [{wd}:0] xw = xw_r[{}:{f}];", f + wd));
    // name = round_half_up(a * b) on u1.wd.
    let product = |w: &mut VWriter, name: String, a: &str, b: &str| {
        let e = sum_of_products(
            w,
            form,
            &format!("{name}_m"),
            &[(Factor::unsigned(a, wd + 1), Factor::unsigned(b, wd + 1))],
            0,
            2 * wd + 2,
        );
        w.line(format!("wire [{}:0] {name}_p = {e};", 2 * wd + 1));
        // Both factors are at most 1.0: the rounded product stays below 2^(2wd+1).
        w.line(format!(
            "wire [{}:0] {name}_r = {name}_p + {}'d{};",
            2 * wd + 1,
            2 * wd + 2,
            1u64 << (wd - 1)
        ));
        w.line(format!("wire [{wd}:0] {name} = {name}_r[{}:{wd}];", 2 * wd));
        name
    };
    let steps = squaring_products(n);
    let at = squaring_cut_positions(steps.len(), cuts);
    let mut acc = match n {
        0 => format!("{}'d{}", wd + 1, 1u64 << wd),
        _ => "xw".to_string(),
    };
    let mut xc = "xw".to_string();
    let mut stage = 0;
    // Register the running power, and x while a multiply by it remains, at every cut before
    // product `i` (`i = steps.len()`: after the last).
    let mut registers = |w: &mut VWriter, i: usize, acc: &mut String, xc: &mut String| {
        for _ in at.iter().filter(|&&p| p == i) {
            w.line(format!("reg [{wd}:0] cut{stage}_acc;"));
            w.line(format!("always @(posedge clk) cut{stage}_acc <= {acc};"));
            *acc = format!("cut{stage}_acc");
            if steps[i..].contains(&true) {
                w.line(format!("reg [{wd}:0] cut{stage}_x;"));
                w.line(format!("always @(posedge clk) cut{stage}_x <= {xc};"));
                *xc = format!("cut{stage}_x");
            }
            stage += 1;
        }
    };
    // Products are named after their bit of n, counted from the top (sqK, then muK; the
    // top bit's, sq0 and mu0, are exact and not formed).
    let mut k = 1;
    for (i, &multiply) in steps.iter().enumerate() {
        registers(w, i, &mut acc, &mut xc);
        acc = if multiply {
            product(w, format!("mu{}", k - 1), &acc, &xc)
        } else {
            k += 1;
            product(w, format!("sq{}", k - 1), &acc, &acc)
        };
    }
    registers(w, steps.len(), &mut acc, &mut xc);
    if guard == 0 {
        acc
    } else {
        w.line(format!("wire [{}:0] fin = {acc} + {}'d{};", wd + 1, wd + 2, 1u64 << (guard - 1)));
        format!("fin[{}:{guard}]", wd)
    }
}
