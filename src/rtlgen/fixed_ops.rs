//! Verilog for the fixed-point steps of `fixed`: the same rounding shift and clamp that
//! `fixed::requant` performs, as explicitly sized, explicitly signed wires. Everything is
//! computed in a signed domain two bits wider than the operand, so neither sign extension
//! of unsigned values nor the rounding increment can overflow.

use super::writer::{range, VWriter};
use crate::fixed::{Format, Rounding};

/// Signed Verilog literal of width `w`.
pub fn slit(w: u32, v: i64) -> String {
    if v < 0 {
        format!("-{w}'sd{}", -v)
    } else {
        format!("{w}'sd{v}")
    }
}

/// [`requant_clamp`] to format `to`: its fraction bits, clamped to its range, its width.
pub fn requant_to(w: &mut VWriter, name: &str, x: &str, from: Format, to: Format, rnd: Rounding) {
    requant_clamp(w, name, x, from, to.frac, rnd, to.min_raw(), to.max_raw(), to.width);
}

/// Declare `name`: `x` (a wire of format `from`) requantised to `to_frac` fraction bits with
/// `rnd`, then clamped to `[lo, hi]` and truncated to `out_w` bits (unsigned output when
/// `lo >= 0`, else its two's-complement bits). Mirrors `fixed::requant(.., Overflow::Saturate)` followed by a clamp.
// The arguments are the operation's own parameters (source, destination, rounding, bounds).
#[allow(clippy::too_many_arguments)]
pub fn requant_clamp(w: &mut VWriter, name: &str, x: &str, from: Format, to_frac: u32, rnd: Rounding, lo: i64, hi: i64, out_w: u32) {
    let ww = from.width + 2;
    let ext = if from.signed {
        format!("$signed({{{{2{{{x}[{}]}}}}, {x}}})", from.width - 1)
    } else {
        format!("$signed({{2'b00, {x}}})")
    };
    w.line(format!("wire signed [{}:0] {name}_x = {ext};", ww - 1));
    let (rw, expr) = if from.frac > to_frac {
        let s = from.frac - to_frac;
        let inc = match rnd {
            Rounding::Truncate => "0".to_string(),
            Rounding::HalfUp => format!("{}'d{}", ww - 1, 1u64 << (s - 1)),
            Rounding::NearestEven => format!("{}'d{} + {{{}'d0, {name}_x[{s}]}}", ww - 1, (1u64 << (s - 1)) - 1, ww - 2),
        };
        w.line(format!("wire [{}:0] {name}_inc = {inc};", ww - 2));
        (ww, format!("({name}_x + $signed({{1'b0, {name}_inc}})) >>> {s}"))
    } else {
        let s = to_frac - from.frac;
        if s == 0 {
            (ww, format!("{name}_x"))
        } else {
            // Appending zero bits widens exactly, where `<<<` would be sized by its operand.
            (ww + s, format!("$signed({{{name}_x, {s}'d0}})"))
        }
    };
    w.line(format!("wire signed [{}:0] {name}_r = {expr};", rw - 1));
    w.line(format!(
        "wire {}{name} = ({name}_r < {}) ? {out_w}'d{} : ({name}_r > {}) ? {out_w}'d{} : {name}_r[{}:0];",
        range(out_w),
        slit(rw, lo),
        (lo as i128).rem_euclid(1i128 << out_w),
        slit(rw, hi),
        hi,
        out_w - 1
    ));
}
