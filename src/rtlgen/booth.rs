//! Exact sums of products as radix-4 Booth partial-product rows, for every multiplier the
//! units emit. Yosys 0.23 maps a Verilog `*` to an AND array (one row per multiplier bit);
//! Booth recoding halves the rows. Measured with `gbump area` (Yosys 0.23), `*` against
//! Booth: `dot_clamp` (8 x 16 signed) 5,891 against 4,634 NAND2 equivalents and 1,145
//! against 769 iCE40 LUTs; the serial light accumulator (unsigned) 1,465 against 1,184 LUTs;
//! the default serial top 10,211 against 9,010 iCE40 logic cells; the 1-light top 33,551
//! against 31,364 NAND2 equivalents. Unsigned 8 x 8 alone loses a little in NAND2
//! equivalents (texture_modulate 2,673 against 2,890) and gains on iCE40; one rule for
//! every product keeps one structure to verify. The value is the same product to the bit:
//! the regressions check it against the model, the unit test below checks the recoding on
//! every small input, and `tests/booth.rs` checks the emitted Verilog against `*` under
//! Icarus.
//!
//! Row j of a x b adds d_j a 4^j, with the digit d_j = -2 b_{2j+1} + b_{2j} + b_{2j-1} in
//! {-2..2}. A row is (|d_j| a) XOR neg_j, whose two's-complement value is d_j a - neg_j, so
//! neg_j is added back at bit 2j; its sign bit s is written as (1 - s) with the constant
//! -2^(m-1) 4^j folded into one constant (the usual sign-extension trick), so no row is
//! sign-extended bit by bit.

use super::writer::VWriter;

/// One factor of a product: a Verilog expression of `width` bits, two's complement when
/// `signed`.
#[derive(Clone, Debug)]
pub struct Factor {
    pub expr: String,
    pub width: u32,
    pub signed: bool,
}

impl Factor {
    pub fn signed(expr: impl Into<String>, width: u32) -> Factor {
        Factor {
            expr: expr.into(),
            width,
            signed: true,
        }
    }
    pub fn unsigned(expr: impl Into<String>, width: u32) -> Factor {
        Factor {
            expr: expr.into(),
            width,
            signed: false,
        }
    }
    /// Booth digits (rows) this factor makes as the recoded operand.
    fn digits(&self) -> u32 {
        (self.width + u32::from(!self.signed)).div_ceil(2)
    }
}

/// How the rows are written. The logic Yosys makes of either is within 1 % (measured on the
/// units); event-driven simulation differs. Icarus evaluates row wires as compiled vector
/// operations, twenty times faster than a function's loop (measured: texture_modulate, 2^18
/// inputs), but a chain of products in wires re-evaluates every product downstream once per
/// row of the one before: forty times slower than a function on the squaring power unit
/// (square-and-multiply, up to fourteen products in a chain for exponents below 256).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// A wire per row, summed in one expression: for a product or two in a row.
    Wires,
    /// One Verilog function per product, the rows in a loop: for long chains of products.
    Function,
    /// No rows: a Verilog `*` per product, for synthesis to map (to a DSP block where the
    /// FPGA has one; `multipliers = "inferred"`).
    Inferred,
}

impl Form {
    /// The form of the units' products in `cfg` (rows as wires for Booth).
    pub fn of(cfg: &crate::config::PipelineConfig) -> Form {
        match cfg.multipliers {
            crate::config::Multipliers::Booth => Form::Wires,
            crate::config::Multipliers::Inferred => Form::Inferred,
        }
    }
}

/// Declares, under `prefix`, the partial-product rows of `addend + Σ a_i b_i` and returns
/// the sum expression, exact modulo 2^`out_width`: with `out_width` at least the width of
/// the widest product (plus carries of the sum), it is the exact value, two's complement.
/// Each product recodes its factor with fewer digits.
pub fn sum_of_products(w: &mut VWriter, form: Form, prefix: &str, products: &[(Factor, Factor)], addend: u128, out_width: u32) -> String {
    assert!((2..=120).contains(&out_width), "sum of products {prefix}: {out_width} bits");
    let modulus = 1u128 << out_width;
    let mut terms = Vec::new();
    let mut constant = addend % modulus;
    for (i, (x, y)) in products.iter().enumerate() {
        let p = format!("{prefix}_{i}");
        let (a, b) = if y.digits() <= x.digits() { (x, y) } else { (y, x) };
        // A one-bit unsigned factor is an enable: the product is a gated copy of the other
        // (k_i with no fraction bits). Booth rows would be twice as wide as the product.
        if !b.signed && b.width == 1 {
            terms.push(gated(w, &p, a, &b.expr, out_width));
            continue;
        }
        let c = match form {
            Form::Wires => rows_as_wires(w, &p, a, b, out_width, &mut terms),
            Form::Function => rows_in_function(w, &p, a, b, out_width, &mut terms),
            Form::Inferred => {
                // Both factors signed at out_width bits: the product modulo 2^out_width.
                let op = |f: &Factor| {
                    if f.signed {
                        format!("$signed({})", f.expr)
                    } else {
                        format!("$signed({{1'b0, {}}})", f.expr)
                    }
                };
                w.line(format!("wire signed [{}:0] {p} = {} * {};", out_width - 1, op(x), op(y)));
                terms.push(p.clone());
                0
            }
        };
        constant = (constant + c) % modulus;
    }
    if constant != 0 {
        terms.push(format!("{out_width}'d{constant}"));
    }
    if terms.is_empty() {
        terms.push(format!("{out_width}'d0"));
    }
    terms.join(" + ")
}

/// `a` times the one-bit `bit`, extended to `out_width` bits (sign-extended when `a` is signed)
/// and cut there, as a wire named `p`.
fn gated(w: &mut VWriter, p: &str, a: &Factor, bit: &str, out_width: u32) -> String {
    let wa = a.width;
    w.line(format!("wire [{}:0] {p}_a = {};", wa - 1, a.expr));
    let kept = wa.min(out_width);
    let ext = out_width - kept;
    let fill = if ext == 0 {
        String::new()
    } else if a.signed {
        format!("{{{ext}{{{p}_a[{}] & {bit}}}}}, ", wa - 1)
    } else {
        format!("{ext}'d0, ")
    };
    w.line(format!(
        "wire [{}:0] {p} = {{{fill}{p}_a[{}:0] & {{{kept}{{{bit}}}}}}};",
        out_width - 1,
        kept - 1
    ));
    p.to_string()
}

/// Bits of a row: they hold 2a in two's complement.
fn row_width(a: &Factor) -> u32 {
    a.width + if a.signed { 1 } else { 2 }
}

/// The rows of b (recoded) that start below `out_width`.
fn rows(b: &Factor, out_width: u32) -> u32 {
    b.digits().min(out_width.div_ceil(2))
}

/// a and 2a at [`row_width`] bits, from the bits of a named `x`.
fn multiples(a: &Factor, x: &str) -> (String, String) {
    if a.signed {
        (format!("{{{x}[{}], {x}}}", a.width - 1), format!("{{{x}, 1'b0}}"))
    } else {
        (format!("{{2'b00, {x}}}"), format!("{{1'b0, {x}, 1'b0}}"))
    }
}

/// The constant `rows` rows of `m` bits need, modulo 2^out_width: -2^(m-1) 4^j for each
/// (each row's sign bit s is written as 1 - s).
fn sign_constant(m: u32, rows: u32, out_width: u32) -> u128 {
    let modulus = 1u128 << out_width;
    (0..rows).fold(0, |c, j| (c + modulus - ((1u128 << (m - 1 + 2 * j)) % modulus)) % modulus)
}

/// The rows of a x b (b recoded) as `out_width`-bit wires pushed on `terms`; returns the
/// constant they need, modulo 2^out_width.
fn rows_as_wires(w: &mut VWriter, p: &str, a: &Factor, b: &Factor, out_width: u32, terms: &mut Vec<String>) -> u128 {
    let m = row_width(a);
    w.line(format!("wire [{}:0] {p}_a = {};", a.width - 1, a.expr));
    w.line(format!("wire [{}:0] {p}_b = {};", b.width - 1, b.expr));
    let (a1, a2) = multiples(a, &format!("{p}_a"));
    w.line(format!("wire [{}:0] {p}_a1 = {a1};", m - 1));
    w.line(format!("wire [{}:0] {p}_a2 = {a2};", m - 1));
    let bit = |i: i64| -> String {
        if i < 0 {
            "1'b0".into()
        } else if (i as u32) < b.width {
            format!("{p}_b[{i}]")
        } else if b.signed {
            format!("{p}_b[{}]", b.width - 1)
        } else {
            "1'b0".into()
        }
    };
    let mut negs = Vec::new();
    for j in 0..rows(b, out_width) {
        let shift = 2 * j;
        let (hi, mid, lo) = (bit(2 * j as i64 + 1), bit(2 * j as i64), bit(2 * j as i64 - 1));
        let r = format!("{p}_r{j}");
        w.line(format!("wire {r}_one = {mid} ^ {lo};"));
        w.line(format!("wire {r}_two = ({hi} & ~{mid} & ~{lo}) | (~{hi} & {mid} & {lo});"));
        w.line(format!("wire {r}_neg = {hi};"));
        // A row cut off at out_width keeps only the bits below it.
        let kept = m.min(out_width - shift);
        w.line(format!(
            "wire [{h}:0] {r}_pp = (({{{kept}{{{r}_one}}}} & {p}_a1[{h}:0]) | ({{{kept}{{{r}_two}}}} & {p}_a2[{h}:0])) ^ {{{kept}{{{r}_neg}}}};",
            h = kept - 1
        ));
        let row = placed(&format!("{r}_pp"), m, shift, out_width);
        w.line(format!("wire [{}:0] {r} = {row};", out_width - 1));
        terms.push(r.clone());
        negs.push((shift, format!("{r}_neg")));
    }
    // The +neg_j bits, one row: bit 2j of it is neg_j.
    let top = negs.last().map_or(0, |n| n.0);
    let bits: Vec<String> = (0..=top)
        .rev()
        .map(|i| negs.iter().find(|n| n.0 == i).map_or("1'b0".to_string(), |n| n.1.clone()))
        .collect();
    // Rows start below out_width, so bit `top` is inside it.
    let pad = out_width - 1 - top;
    let bits = if pad > 0 {
        format!("{pad}'d0, {}", bits.join(", "))
    } else {
        bits.join(", ")
    };
    w.line(format!("wire [{}:0] {p}_neg = {{{bits}}};", out_width - 1));
    terms.push(format!("{p}_neg"));
    sign_constant(m, rows(b, out_width), out_width)
}

/// Bits `[out_width-1:0]` of the row {~pp[m-1], pp[m-2:0]} shifted left by `shift`, as one
/// concatenation of exactly `out_width` bits (a lint-clean width, no implicit extension).
fn placed(pp: &str, m: u32, shift: u32, out_width: u32) -> String {
    let mut parts = Vec::new();
    let kept = m.min(out_width - shift);
    if shift + m < out_width {
        parts.push(format!("{}'d0", out_width - shift - m));
    }
    if kept == m {
        parts.push(format!("~{pp}[{}]", m - 1));
        if m > 1 {
            parts.push(format!("{pp}[{}:0]", m - 2));
        }
    } else {
        parts.push(format!("{pp}[{}:0]", kept - 1));
    }
    if shift > 0 {
        parts.push(format!("{shift}'d0"));
    }
    format!("{{{}}}", parts.join(", "))
}

/// A function computing the rows of a x b (b recoded) and their +neg bits, modulo
/// 2^out_width; pushes its call on `terms` and returns the constant the rows need (modulo
/// 2^out_width).
fn rows_in_function(w: &mut VWriter, p: &str, a: &Factor, b: &Factor, out_width: u32, terms: &mut Vec<String>) -> u128 {
    let m = row_width(a);
    let digits = rows(b, out_width);
    let ow = out_width;
    // bx holds b_{-1} = 0, b, and b's extension up to bit 2 digits - 1 (index shifted by one).
    let bxw = 2 * b.digits() + 1;
    let ext = bxw - 1 - b.width;
    let bx = match (ext, b.signed) {
        (0, _) => "{booth_y, 1'b0}".to_string(),
        (e, true) => format!("{{{{{e}{{booth_y[{}]}}}}, booth_y, 1'b0}}", b.width - 1),
        (e, false) => format!("{{{e}'d0, booth_y, 1'b0}}"),
    };
    let (a1, a2) = multiples(a, "booth_x");
    // The unshifted row at `ow` bits; the loop shifts it.
    let row = placed("booth_pp", m, 0, ow);
    let f = format!("{p}_booth");
    w.block(format!("function [{}:0] {f};", ow - 1), "endfunction", |w| {
        w.line(format!("input [{}:0] booth_x;", a.width - 1));
        w.line(format!("input [{}:0] booth_y;", b.width - 1));
        w.line(format!("reg [{}:0] booth_a1, booth_a2, booth_pp;", m - 1));
        w.line(format!("reg [{}:0] booth_bx;", bxw - 1));
        w.line(format!("reg [{}:0] booth_row, booth_negw;", ow - 1));
        w.line("reg booth_one, booth_two, booth_neg;");
        w.line("integer booth_j;");
        w.block("begin", "end", |w| {
            w.line(format!("booth_a1 = {a1};"));
            w.line(format!("booth_a2 = {a2};"));
            w.line(format!("booth_bx = {bx};"));
            w.line(format!("{f} = {ow}'d0;"));
            w.line(format!("booth_negw = {ow}'d0;"));
            w.block(format!("for (booth_j = 0; booth_j < {digits}; booth_j = booth_j + 1) begin"), "end", |w| {
                w.line("booth_one = booth_bx[2*booth_j+1] ^ booth_bx[2*booth_j];");
                w.line("booth_two = (booth_bx[2*booth_j+2] & ~booth_bx[2*booth_j+1] & ~booth_bx[2*booth_j]) | (~booth_bx[2*booth_j+2] & booth_bx[2*booth_j+1] & booth_bx[2*booth_j]);");
                w.line("booth_neg = booth_bx[2*booth_j+2];");
                w.line(format!("booth_pp = (({{{m}{{booth_one}}}} & booth_a1) | ({{{m}{{booth_two}}}} & booth_a2)) ^ {{{m}{{booth_neg}}}};"));
                w.line(format!("booth_row = {row};"));
                w.line(format!("booth_negw = booth_negw | ({{{}'d0, booth_neg}} << (2*booth_j));", ow - 1));
                w.line(format!("{f} = {f} + (booth_row << (2*booth_j));"));
            });
            // The +neg bits sit in one row, added once: a full adder per row spent on a
            // single bit would cost more than the whole row.
            w.line(format!("{f} = {f} + booth_negw;"));
        });
    });
    terms.push(format!("{f}({}, {})", a.expr, b.expr));
    sign_constant(m, digits, out_width)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rows' arithmetic in Rust, from the same recoding rule, over every small input: a
    /// wrong digit rule or constant fails here before any simulator runs.
    fn booth_value(a: i128, b_bits: u32, b_signed: bool, b: i128, m: u32) -> i128 {
        let bit = |i: i64| -> i128 {
            if i < 0 {
                0
            } else if (i as u32) < b_bits {
                (b >> i) & 1
            } else if b_signed {
                (b >> (b_bits - 1)) & 1
            } else {
                0
            }
        };
        let digits = (b_bits + u32::from(!b_signed)).div_ceil(2);
        let mut sum = 0i128;
        for j in 0..digits as i64 {
            let (hi, mid, lo) = (bit(2 * j + 1), bit(2 * j), bit(2 * j - 1));
            let one = mid ^ lo;
            let two = (hi & (1 - mid) & (1 - lo)) | ((1 - hi) & mid & lo);
            let mag = one * a + two * 2 * a;
            // m-bit XOR with neg, read back as signed, plus neg.
            let mask = (1i128 << m) - 1;
            let pp = if hi == 1 { !mag & mask } else { mag & mask };
            let pp_signed = if pp >> (m - 1) == 1 { pp - (1 << m) } else { pp };
            sum += (pp_signed + hi) << (2 * j);
        }
        sum
    }

    #[test]
    fn recoded_rows_sum_to_the_product_on_every_small_input() {
        for (aw, a_signed, bw, b_signed) in [
            (5, true, 4, true),
            (4, false, 5, false),
            (6, true, 3, false),
            (3, false, 6, true),
            (1, false, 1, false),
            (7, false, 7, true),
        ] {
            let m = aw + if a_signed { 1 } else { 2 };
            let range = |w: u32, s: bool| {
                if s {
                    -(1i128 << (w - 1))..(1i128 << (w - 1))
                } else {
                    0..(1i128 << w)
                }
            };
            for a in range(aw, a_signed) {
                for b in range(bw, b_signed) {
                    let braw = b & ((1 << bw) - 1);
                    assert_eq!(
                        booth_value(a, bw, b_signed, braw, m),
                        a * b,
                        "{aw}{a_signed} x {bw}{b_signed}: {a} * {b}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_narrower_factor_is_recoded_and_the_constant_is_folded() {
        let mut w = VWriter::new();
        let e = sum_of_products(
            &mut w,
            Form::Function,
            "p",
            &[(Factor::signed("v", 16), Factor::signed("b", 8))],
            0,
            24,
        );
        let text = w.finish();
        assert!(text.contains("input [7:0] booth_y;") && e.starts_with("p_0_booth(v, b)"), "{text}");
        assert!(text.contains("booth_j < 4;"), "8-bit signed: four rows: {text}");
        // -2^16 (1 + 4 + 16 + 64) mod 2^24.
        assert!(e.ends_with(" + 24'd11206656"), "{e}");
    }
}
