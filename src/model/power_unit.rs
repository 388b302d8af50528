//! The design space of the power unit fs = x^n (issue: the paper's 256-entry table loses
//! accuracy as n grows). Each design is evaluated bit-exactly on the clamped dot product
//! x = fd / 2^F (u1.F) and produces u1.P from the power table (`model::power_table`):
//!
//! - `Table`: the paper's table, N entries at x_i = i/(N-1), nearest or truncating index;
//! - `Lerp`: N uniform knots with linear interpolation (one multiplier);
//! - `Segmented`: S segments halving towards x = 1 (where x^n changes fastest), M entries
//!   each holding the minimax constant of its interval, optionally interpolated;
//! - `Squaring`: square-and-multiply on u1.(P+G) (the Cg tutorial's x^8 is three squarings);
//!   no table, but up to 2·log2(n) multipliers and n fixed when the hardware is built.

use crate::config::{PipelineConfig, PowerUnitKind};
use crate::fixed::{shift_round, Rounding};
use crate::model::power_table::{powi_exact, PowerTable};
use serde::Serialize;

/// The exponent successive squarings reach nearest `n`: 2^round(log2 n) (n for n <= 1), the
/// Cg Tutorial's specular power (§8.3 squares three times for 8).
pub fn squarings_exponent(n: u32) -> u32 {
    if n <= 1 {
        return n;
    }
    1 << (n as f64).log2().round() as u32
}

/// The power unit of the pipeline (`cfg.power_unit` selects its design): fs for the clamped
/// dot product `x` (`u1.F`), read from the power table `table`.
#[inline]
pub fn power_unit(cfg: &PipelineConfig, table: &PowerTable, x: i64) -> i64 {
    match cfg.power_unit {
        PowerUnitKind::Table => table.entries[PowerTable::index(cfg, x)],
        // A squaring unit reads no table (its entries are the unused load port's) and raises
        // to the power of two its squarings reach.
        _ => cfg
            .power_unit_design()
            .eval(cfg.power_formats(), &table.entries, cfg.power_exponent(table.n), x),
    }
}

/// One design of the power unit, with its parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum PowerUnitDesign {
    Table { entries: u32, nearest: bool },
    Lerp { knots: u32 },
    Segmented { segments: u32, per_segment: u32, lerp: bool },
    Squaring { guard: u32 },
}

/// Input and output fraction bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PowerFormats {
    pub f: u32,
    pub p: u32,
}

fn q(v: f64, p: u32) -> i64 {
    (v * (1u64 << p) as f64 + 0.5).floor() as i64
}

/// The segment of y = 2^F - fd, as hardware finds it with a leading-zero count: segment 0
/// covers y in [2^(F-1), 2^F] (y = 2^F is its last knot), segment s < S-1 covers
/// [2^(F-1-s), 2^(F-s)), the last segment [0, 2^(F-S+1)). Returns (s, lo, log2 of width).
pub fn segment_of(f: u32, segments: u32, y: i64) -> (u32, i64, u32) {
    let lz = if y <= 0 { f } else { f - 1 - (63 - y.leading_zeros()).min(f - 1) };
    let s = if y >= 1 << f { 0 } else { lz.min(segments - 1) };
    if s + 1 == segments {
        (s, 0, f + 1 - segments)
    } else {
        (s, 1i64 << (f - 1 - s), f - 1 - s)
    }
}

/// Entry index within the segment and the remainder below it, in codes; with more entries
/// than codes (`m > lw`) entries sit between codes and the remainder is always 0.
fn entry_of(y: i64, lo: i64, lw: u32, m: u32) -> (i64, i64, u32) {
    if lw >= m {
        let sh = lw - m;
        ((y - lo) >> sh, (y - lo) & ((1 << sh) - 1), sh)
    } else {
        ((y - lo) << (m - lw), 0, 0)
    }
}

impl PowerUnitDesign {
    /// A short label.
    pub fn label(&self) -> String {
        match self {
            PowerUnitDesign::Table { entries, nearest } => format!("table {entries} {}", if *nearest { "nearest" } else { "truncate" }),
            PowerUnitDesign::Lerp { knots } => format!("lerp {knots} knots"),
            PowerUnitDesign::Segmented {
                segments,
                per_segment,
                lerp,
            } => format!("segmented {segments}x{per_segment}{}", if *lerp { " lerp" } else { "" }),
            PowerUnitDesign::Squaring { guard } => format!("squaring, {guard} guard bits"),
        }
    }

    /// Storage the design needs, in bits.
    pub fn rom_bits(&self, fm: PowerFormats) -> u64 {
        let w = (fm.p + 1) as u64;
        match *self {
            PowerUnitDesign::Table { entries, .. } => entries as u64 * w,
            PowerUnitDesign::Lerp { knots } => knots as u64 * w,
            PowerUnitDesign::Segmented {
                segments,
                per_segment,
                lerp,
            } => (segments * (per_segment + u32::from(lerp))) as u64 * w,
            PowerUnitDesign::Squaring { .. } => 0,
        }
    }

    /// Multipliers (and their operand widths) the design needs for exponents below 2^8.
    pub fn multipliers(&self, fm: PowerFormats) -> (u32, u32) {
        match *self {
            PowerUnitDesign::Table { .. } | PowerUnitDesign::Segmented { lerp: false, .. } => (0, 0),
            PowerUnitDesign::Lerp { .. } | PowerUnitDesign::Segmented { lerp: true, .. } => (1, fm.p + 1),
            PowerUnitDesign::Squaring { guard } => (14, fm.p + guard + 1),
        }
    }

    /// The stored table for exponent `n` (empty for squaring).
    pub fn table(&self, fm: PowerFormats, n: u32) -> Vec<i64> {
        match *self {
            PowerUnitDesign::Table { entries, .. } => (0..entries)
                .map(|i| q(powi_exact(i as f64 / (entries - 1) as f64, n), fm.p))
                .collect(),
            PowerUnitDesign::Lerp { knots } => (0..knots).map(|i| q(powi_exact(i as f64 / (knots - 1) as f64, n), fm.p)).collect(),
            PowerUnitDesign::Segmented {
                segments,
                per_segment,
                lerp,
            } => {
                let one = (1i64 << fm.f) as f64;
                let m = per_segment.trailing_zeros();
                let x_of = |y: f64| (1.0 - y / one).max(0.0);
                let mut t = Vec::new();
                for s in 0..segments {
                    // Representative y inside the segment gives its lo and width.
                    let probe = if s + 1 == segments { 0 } else { 1i64 << (fm.f - 1 - s) };
                    let (_, lo, lw) = segment_of(fm.f, segments, probe);
                    let step = (lw as f64 - m as f64).exp2();
                    if lerp {
                        // M + 1 knots at the entry boundaries.
                        for j in 0..=per_segment {
                            t.push(q(powi_exact(x_of(lo as f64 + j as f64 * step), n), fm.p));
                        }
                    } else {
                        // The minimax constant over the codes of each entry (segment 0's last
                        // entry also holds y = 2^F, x = 0).
                        for j in 0..per_segment {
                            let a = lo as f64 + j as f64 * step;
                            let mut b = (a + step - 1.0).max(a);
                            if s == 0 && j + 1 == per_segment {
                                b = one;
                            }
                            t.push(q((powi_exact(x_of(b), n) + powi_exact(x_of(a), n)) / 2.0, fm.p));
                        }
                    }
                }
                t
            }
            PowerUnitDesign::Squaring { .. } => Vec::new(),
        }
    }

    /// fs for input `fd` (u1.F) with the table of `table()` (or exponent `n` for squaring).
    pub fn eval(&self, fm: PowerFormats, table: &[i64], n: u32, fd: i64) -> i64 {
        let f = fm.f;
        match *self {
            PowerUnitDesign::Table { entries, nearest } => {
                let r = if nearest { Rounding::HalfUp } else { Rounding::Truncate };
                table[shift_round(fd as i128 * (entries as i128 - 1), f, r) as usize]
            }
            PowerUnitDesign::Lerp { knots } => {
                let s = fd * (knots as i64 - 1);
                let (i, fr) = ((s >> f) as usize, s & ((1 << f) - 1));
                if i + 1 >= table.len() {
                    return table[table.len() - 1];
                }
                table[i] + shift_round(((table[i + 1] - table[i]) * fr) as i128, f, Rounding::HalfUp) as i64
            }
            PowerUnitDesign::Segmented {
                segments,
                per_segment,
                lerp,
            } => {
                let y = (1i64 << f) - fd;
                let (s, lo, lw) = segment_of(f, segments, y);
                let m = per_segment.trailing_zeros();
                let (j, r, sh) = entry_of(y, lo, lw, m);
                if !lerp {
                    return table[(s * per_segment) as usize + (j as usize).min(per_segment as usize - 1)];
                }
                // Between the knots at the entry's boundaries; y = 2^F lands exactly on knot M.
                let base = (s * (per_segment + 1)) as usize + j as usize;
                if r == 0 {
                    return table[base];
                }
                let t_q = r << (f - sh);
                table[base] + shift_round(((table[base + 1] - table[base]) * t_q) as i128, f, Rounding::HalfUp) as i64
            }
            PowerUnitDesign::Squaring { guard } => {
                let w = fm.p + guard;
                let x = shift_round((fd as i128) << w, f, Rounding::HalfUp) as i64;
                let mut acc: i64 = 1 << w;
                for bit in (0..32).rev() {
                    acc = shift_round(acc as i128 * acc as i128, w, Rounding::HalfUp) as i64;
                    if (n >> bit) & 1 == 1 {
                        acc = shift_round(acc as i128 * x as i128, w, Rounding::HalfUp) as i64;
                    }
                }
                shift_round(acc as i128, guard, Rounding::HalfUp) as i64
            }
        }
    }

    /// Largest error in output LSBs over every input code and every exponent in `ns`, with
    /// the exponent and input where it occurs, and the mean.
    pub fn worst_error(&self, fm: PowerFormats, ns: impl Iterator<Item = u32>) -> (f64, u32, i64, f64) {
        let (mut worst, mut wn, mut wx, mut sum, mut cnt) = (0.0f64, 0, 0, 0.0, 0u64);
        let one = (1i64 << fm.f) as f64;
        let ps = (1u64 << fm.p) as f64;
        for n in ns {
            let t = self.table(fm, n);
            for fd in 0..=(1i64 << fm.f) {
                let e = (self.eval(fm, &t, n, fd) as f64 - powi_exact(fd as f64 / one, n) * ps).abs();
                sum += e;
                cnt += 1;
                if e > worst {
                    (worst, wn, wx) = (e, n, fd);
                }
            }
        }
        (worst, wn, wx, sum / cnt.max(1) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plain_table_matches_the_pipeline_unit() {
        let cfg = crate::config::PipelineConfig::default();
        let fm = PowerFormats {
            f: cfg.dot_frac_bits,
            p: cfg.power_frac_bits,
        };
        let d = PowerUnitDesign::Table {
            entries: 256,
            nearest: true,
        };
        for n in [0, 1, 16, 255] {
            let t = crate::model::PowerTable::build(&cfg, n);
            assert_eq!(d.table(fm, n), t.entries);
            for fd in 0..=256 {
                assert_eq!(d.eval(fm, &t.entries, n, fd), power_unit(&cfg, &t, fd));
            }
        }
    }

    #[test]
    fn a_table_with_an_entry_per_input_code_is_exactly_rounded() {
        let fm = PowerFormats { f: 8, p: 8 };
        let (worst, ..) = PowerUnitDesign::Table {
            entries: 257,
            nearest: true,
        }
        .worst_error(fm, 1..=255);
        assert!(worst <= 0.5 + 1e-9, "{worst}");
    }

    #[test]
    fn squaring_rounds_x_exactly_and_x_squared_within_a_double_rounding() {
        let fm = PowerFormats { f: 8, p: 8 };
        let d = PowerUnitDesign::Squaring { guard: 4 };
        let (w1, ..) = d.worst_error(fm, 1..=1);
        let (w2, ..) = d.worst_error(fm, 2..=2);
        // x^2 is rounded to P+G bits, then to P: at most 1/2 + 2^-G LSB.
        assert!(w1 <= 0.5 + 1e-9 && w2 <= 0.5 + 1.0 / 16.0 + 1e-9, "{w1} {w2}");
    }

    /// The pipeline's squaring unit (`SQUARING_GUARD_BITS`) at the default formats: within
    /// an LSB of x^e for every power-of-two exponent it can be built for, printed.
    #[test]
    fn the_pipelines_squaring_unit_stays_within_an_lsb() {
        let fm = PowerFormats { f: 8, p: 8 };
        let d = PowerUnitDesign::Squaring {
            guard: crate::config::SQUARING_GUARD_BITS,
        };
        let (worst, n, x, mean) = d.worst_error(fm, (0..=10).map(|k| 1u32 << k));
        println!(
            "squaring, {} guard bits: worst {worst:.3} LSB at n = {n}, x = {x}; mean {mean:.4}",
            crate::config::SQUARING_GUARD_BITS
        );
        assert!(worst <= 1.0, "{worst} at n = {n}, x = {x}");
    }
}
