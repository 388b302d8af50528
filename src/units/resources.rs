//! What a unit is built of, counted from its widths without writing its Verilog: register
//! bits, Booth partial-product bits, inferred multiplier bit-products, adder bits, comparator
//! bits and multiplexer bits. Each unit's `resources` mirrors its emitter step by step with
//! the helpers below, which mirror the emitter's own helpers (`rtlgen::booth`,
//! `rtlgen::fixed_ops`); `measure::area_model` weighs the counts into gate equivalents, and
//! a test holds every unit's register count to the register bits of its generated Verilog.

use crate::config::{Multipliers, PipelineConfig};
use crate::fixed::{Format, Rounding};

/// Counts of one piece of logic, in bits (fractional after scaling by a probability-free
/// factor, e.g. a constant operand that halves an adder).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Resources {
    /// Register bits.
    pub ff: f64,
    /// Booth partial-product bits after each product's first row: a full adder each in the
    /// tree (every row bit's select and negate count as `mux`).
    pub pp: f64,
    /// Adder cells of unsigned multiplier arrays left to synthesis (`multipliers =
    /// "inferred"`): a x (b - 1) for an a x b product, whose a x b AND gates count as `mux`.
    pub mul: f64,
    /// The same for signed multipliers (sign extension makes them dearer per cell).
    pub smul: f64,
    /// Adder and subtractor bits (an n-operand sum counts n - 1 adders).
    pub add: f64,
    /// Magnitude-comparator bits.
    pub cmp: f64,
    /// Two-way multiplexer and AND-gating bits (an inferred array's AND gates among them).
    pub mux: f64,
    /// Register-array bits times the reads of the array: the write enables and the
    /// bank-wide read selects of the top's triangle banks.
    pub array: f64,
}

/// The number of counts, in [`Resources::row`] order.
pub const KINDS: usize = 8;

impl Resources {
    pub fn row(&self) -> [f64; KINDS] {
        [self.ff, self.pp, self.mul, self.smul, self.add, self.cmp, self.mux, self.array]
    }
    /// The counts of a [`Resources::row`].
    pub fn from_row(r: [f64; KINDS]) -> Resources {
        let [ff, pp, mul, smul, add, cmp, mux, array] = r;
        Resources {
            ff,
            pp,
            mul,
            smul,
            add,
            cmp,
            mux,
            array,
        }
    }
    pub fn scaled(&self, k: f64) -> Resources {
        Resources::from_row(self.row().map(|x| x * k))
    }
    pub fn regs(w: u32) -> Resources {
        Resources {
            ff: w as f64,
            ..Default::default()
        }
    }
    pub fn adders(w: u32) -> Resources {
        Resources {
            add: w as f64,
            ..Default::default()
        }
    }
    pub fn muxes(w: u32) -> Resources {
        Resources {
            mux: w as f64,
            ..Default::default()
        }
    }
    pub fn compares(w: u32) -> Resources {
        Resources {
            cmp: w as f64,
            ..Default::default()
        }
    }
    /// A stage of `w` bits: registers when `registered`, nothing otherwise (a wire).
    pub fn stage(registered: bool, w: u32) -> Resources {
        if registered {
            Resources::regs(w)
        } else {
            Resources::default()
        }
    }
}

impl std::ops::Add for Resources {
    type Output = Resources;
    fn add(self, o: Resources) -> Resources {
        let (a, b) = (self.row(), o.row());
        Resources::from_row(std::array::from_fn(|i| a[i] + b[i]))
    }
}

impl std::ops::Sub for Resources {
    type Output = Resources;
    fn sub(self, o: Resources) -> Resources {
        let (a, b) = (self.row(), o.row());
        Resources::from_row(std::array::from_fn(|i| a[i] - b[i]))
    }
}

impl std::ops::AddAssign for Resources {
    fn add_assign(&mut self, o: Resources) {
        *self = *self + o;
    }
}

impl std::iter::Sum for Resources {
    fn sum<I: Iterator<Item = Resources>>(it: I) -> Resources {
        it.fold(Resources::default(), |a, b| a + b)
    }
}

/// One factor of a product: its width and signedness (as `rtlgen::booth::Factor`).
#[derive(Clone, Copy, Debug)]
pub struct Operand {
    pub width: u32,
    pub signed: bool,
}

pub fn signed(width: u32) -> Operand {
    Operand { width, signed: true }
}

pub fn unsigned(width: u32) -> Operand {
    Operand { width, signed: false }
}

impl Operand {
    fn digits(&self) -> u32 {
        (self.width + u32::from(!self.signed)).div_ceil(2)
    }
}

/// `addend + Σ a_i b_i` to `out_width` bits, as `rtlgen::booth::sum_of_products` writes it
/// under `multipliers` (Booth rows or `*`): the rows or products, and the adders of the sum
/// of all terms. A one-bit unsigned factor is an AND gate per bit of the other.
pub fn sum_of_products(multipliers: Multipliers, products: &[(Operand, Operand)], addend: bool, out_width: u32) -> Resources {
    let mut r = Resources::default();
    let mut terms = u32::from(addend);
    for (x, y) in products {
        let (a, b) = if y.digits() <= x.digits() { (x, y) } else { (y, x) };
        if !b.signed && b.width == 1 {
            r.mux += a.width.min(out_width) as f64;
            terms += 1;
            continue;
        }
        match multipliers {
            Multipliers::Booth => {
                let m = a.width + if a.signed { 1 } else { 2 };
                let rows = b.digits().min(out_width.div_ceil(2));
                // Each row keeps the bits below out_width. Every row bit is a select and a
                // negate; synthesis sums the rows in one carry-save tree, a full adder per bit
                // of every row after the first (a two-row product is one adder row), then one
                // carry-propagate adder.
                let bits: Vec<u32> = (0..rows).map(|j| m.min(out_width - 2 * j)).collect();
                r.mux += bits.iter().sum::<u32>() as f64;
                r.pp += bits.iter().skip(1).sum::<u32>() as f64;
                terms += 2;
            }
            Multipliers::Inferred => {
                // Yosys builds the array only below the result's width; a signed factor is
                // sign-extended up to it, so signed products count apart.
                // An a x b array is a x b AND gates and a x (b - 1) adder cells: a two-bit factor
                // costs one adder row, not two rows of the average array's cost.
                let (wa, wb) = (a.width.min(out_width), b.width.min(out_width));
                let cells = (wa * (wb - 1)) as f64;
                if a.signed || b.signed {
                    r.smul += cells;
                } else {
                    r.mul += cells;
                }
                r.mux += (wa * wb) as f64;
                terms += 1;
            }
        }
    }
    r.add += (terms.max(1) - 1) as f64 * out_width as f64;
    r
}

/// `rtlgen::fixed_ops::requant_clamp`: the rounding add (when bits are dropped and the
/// rounding adds), two comparisons against the bounds and the two-way clamp select.
pub fn requant_clamp(from: Format, to_frac: u32, rounding: Rounding, out_w: u32) -> Resources {
    let ww = from.width + 2;
    let mut r = Resources::default();
    let rw = if from.frac > to_frac {
        if rounding != Rounding::Truncate {
            r.add += ww as f64;
        }
        ww - (from.frac - to_frac)
    } else {
        ww + (to_frac - from.frac)
    };
    r.cmp += 2.0 * rw as f64;
    r.mux += 2.0 * out_w as f64;
    r
}

/// The form the configuration's products take.
pub fn form(cfg: &PipelineConfig) -> Multipliers {
    cfg.multipliers
}

/// `rtlgen::units_v::light_term`: f·k, then ·Lc per channel, with the cuts in place.
pub fn light_term(cfg: &PipelineConfig) -> Resources {
    let (ff, k, c) = (cfg.factor_frac(), cfg.k_frac_bits, cfg.colour_bits);
    let tw = cfg.term_fmt().width;
    let cuts = crate::rtlgen::units_v::light_term_cuts(cfg);
    let fkw = ff + k + 2;
    let mut r = sum_of_products(form(cfg), &[(unsigned(ff + 1), unsigned(k + 1))], false, fkw);
    if cfg.white_lights {
        // (f k << c) - f k, one term for every channel.
        return r + Resources::stage(cuts >= 1, fkw) + Resources::adders(tw) + Resources::stage(cuts >= 2, tw);
    }
    r += Resources::stage(cuts >= 1, fkw + 3 * c);
    let channel = sum_of_products(form(cfg), &[(unsigned(fkw), unsigned(c))], false, tw) + Resources::stage(cuts >= 2, tw);
    r + channel.scaled(3.0)
}

/// `rtlgen::units_v::blend_finish`: per channel the rounded, clamped sum and the saturating
/// add to c_in, registered.
pub fn blend_finish(cfg: &PipelineConfig) -> Resources {
    let (c, g) = (cfg.stage_colour_fmt().width, cfg.colour_guard_bits);
    // With guard bits the saturation compares the sum against 1.0; without, it is the carry.
    let over = if g > 0 { Resources::compares(c + 1) } else { Resources::default() };
    let channel =
        requant_clamp(cfg.acc_fmt(), g, cfg.rounding, c) + Resources::adders(c + 1) + over + Resources::muxes(c) + Resources::regs(c);
    channel.scaled(3.0)
}

/// `rtlgen::power_units::datapath` for the table, lerp and segmented designs (the parts that
/// drive the addresses and the interpolation; the memory is outside).
pub fn power_datapath(d: &crate::model::power_unit::PowerUnitDesign, fm: crate::model::power_unit::PowerFormats) -> Resources {
    use crate::model::power_unit::{segment_of, PowerUnitDesign};
    let (f, p) = (fm.f, fm.p);
    use crate::rtlgen::power_units::{addr_bits, rom_depth, segment_bits, segment_probe};
    let ab = addr_bits(rom_depth(d, fm));
    // k0 + round((k1 - k0) t / 2^F) and the select of k0 when t = 0 or at the last knot.
    let interp = |tw: u32| {
        let pw = p + 2 + tw + 1;
        Resources::adders(p + 3)
            + sum_of_products(Multipliers::Booth, &[(signed(p + 3), unsigned(tw))], false, pw)
            + Resources::adders(pw + p + 1)
            + Resources::muxes(p + 1)
    };
    // A constant multiply: synthesis keeps one shifted copy per set bit of the constant and
    // adds them, an adder row per set bit after the first.
    let times = |k: u32, w: u32| Resources::adders(k.count_ones().saturating_sub(1) * w);
    match *d {
        PowerUnitDesign::Table { entries, nearest } => {
            let sw = f + 1 + entries.trailing_zeros() + 1;
            Resources::adders(sw * (1 + u32::from(nearest)))
        }
        PowerUnitDesign::Lerp { knots } => {
            let sw = f + 1 + ab + 1;
            times(knots - 1, sw) + Resources::compares(ab) + Resources::muxes(2 * ab) + Resources::adders(ab) + interp(f)
        }
        PowerUnitDesign::Segmented {
            segments,
            per_segment,
            lerp,
        } => {
            let (mb, sb) = segment_bits(segments, per_segment);
            let per = per_segment + u32::from(lerp);
            // t is nonzero only in a segment with more codes than entries, and there only in its
            // top lw - mb bits (the rest are zeros synthesis drops from the interpolation).
            let t_live = (0..segments)
                .map(|s| segment_of(f, segments, segment_probe(f, segments, s)).2.saturating_sub(mb))
                .max()
                .unwrap_or(0);
            let t_used = t_live > 0;
            // Each segment's `off = y - lo` subtracts a power of two (or nothing, in the last):
            // only the bits from lo's up carry.
            let offsets: u32 = (0..segments)
                .map(|s| {
                    let (_, lo, _) = segment_of(f, segments, segment_probe(f, segments, s));
                    if lo > 0 {
                        f + 1 - lo.trailing_zeros()
                    } else {
                        0
                    }
                })
                .sum();
            let mut r = Resources::adders(f + 1)
                + Resources::muxes(segments * sb)
                + Resources::adders(offsets)
                + Resources::muxes(2 * (f + 1) + f).scaled(segments as f64)
                + Resources::compares(ab)
                + Resources::muxes(ab)
                + times(per, ab)
                + Resources::adders(ab);
            if t_used {
                r += Resources::compares(f) + Resources::adders(ab) + Resources::muxes(ab);
                if lerp {
                    r += interp(t_live);
                }
            }
            r
        }
        PowerUnitDesign::Squaring { .. } => unreachable!("the pipeline's power unit reads a table"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn booth_rows_halve_the_multiplier_bits() {
        // 8 x 16 signed: 4 rows of 17 bits (a select and a negate per bit), the 3 after the
        // first adding in the tree, then the carry-propagate adder.
        let r = sum_of_products(Multipliers::Booth, &[(signed(8), signed(16))], false, 26);
        assert_eq!((r.pp, r.mux), (51.0, 68.0));
        assert_eq!(r.add, 26.0);
        // Inferred: the array's 16 x 7 adder cells and its 16 x 8 AND gates.
        let i = sum_of_products(Multipliers::Inferred, &[(signed(8), signed(16))], false, 26);
        assert_eq!((i.mul, i.smul, i.mux), (0.0, 112.0, 128.0));
        assert_eq!(i.add, 0.0);
        // A one-bit enable is a gate per bit.
        let g = sum_of_products(Multipliers::Booth, &[(unsigned(9), unsigned(1))], false, 10);
        assert_eq!((g.pp, g.mux, g.add), (0.0, 9.0, 0.0));
    }
}

/// Three products of a normal component and an L/H component summed exactly into
/// `dot_exact_fmt` (`dot_clamp`'s B·V, and each component of `frame_transform`'s): each
/// product registered when `products_cut`, the sum when `sum_cut`.
pub fn normal_dot_sum(cfg: &PipelineConfig, products_cut: bool, sum_cut: bool) -> Resources {
    let ex = cfg.dot_exact_fmt();
    let product = (signed(cfg.normal_bits), signed(cfg.lh_bits));
    let sum = if products_cut {
        (sum_of_products(cfg.multipliers, &[product], false, ex.width) + Resources::regs(ex.width)).scaled(3.0)
            + Resources::adders(2 * ex.width)
    } else {
        sum_of_products(cfg.multipliers, &[product; 3], false, ex.width)
    };
    sum + Resources::stage(sum_cut, ex.width)
}
