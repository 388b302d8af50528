//! Run-time-width fixed-point arithmetic: the number system of the golden model.
//!
//! A [`Format`] is a width, a count of fraction bits and a signedness; a value is a raw
//! two's-complement integer read as `raw / 2^frac`. Hardware never rounds or overflows
//! implicitly, so neither does this module: every narrowing step names its [`Rounding`] and
//! its [`Overflow`]. Exact operations (add, multiply) return wider formats, as a Verilog
//! expression sized to its full result would. Raw values live in `i64`; intermediate
//! alignment uses `i128` so that no step can overflow silently. The Verilog emitter
//! (`rtlgen::fixed_ops`) turns the same [`requant`] description into RTL.

use serde::{Deserialize, Serialize};
use std::fmt;

/// How a value loses fraction bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Rounding {
    /// Drop the low bits: floor for two's complement, the cheapest in hardware.
    Truncate,
    /// Add half an LSB, then truncate: ties go towards +infinity.
    HalfUp,
    /// Ties go to the even neighbour: unbiased, one more gate level than `HalfUp`.
    NearestEven,
}

/// What happens when a value does not fit the destination width.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Overflow {
    /// Keep the low bits (plain Verilog assignment).
    Wrap,
    /// Clamp to the nearest representable value.
    Saturate,
}

/// A fixed-point format: `width` bits in all, `frac` of them after the binary point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Format {
    pub width: u32,
    pub frac: u32,
    pub signed: bool,
}

/// The widest raw value the model carries; wider intermediate sums would need `i128` raws.
pub const MAX_WIDTH: u32 = 62;

impl Format {
    /// A format; `None` when the width is 0, above [`MAX_WIDTH`], or (signed) 1 bit of sign only.
    #[inline]
    pub fn new(width: u32, frac: u32, signed: bool) -> Option<Format> {
        if width == 0 || width > MAX_WIDTH || (signed && width < 2) {
            return None;
        }
        Some(Format { width, frac, signed })
    }

    /// Signed format; panics on an impossible width (a programming error, not user input).
    #[inline]
    pub fn s(width: u32, frac: u32) -> Format {
        Format::new(width, frac, true).unwrap_or_else(|| panic!("bad signed format {width}.{frac}"))
    }

    /// Unsigned format; panics on an impossible width.
    #[inline]
    pub fn u(width: u32, frac: u32) -> Format {
        Format::new(width, frac, false).unwrap_or_else(|| panic!("bad unsigned format {width}.{frac}"))
    }

    /// Smallest raw value.
    #[inline]
    pub fn min_raw(self) -> i64 {
        if self.signed {
            -(1i64 << (self.width - 1))
        } else {
            0
        }
    }

    /// Largest raw value.
    #[inline]
    pub fn max_raw(self) -> i64 {
        if self.signed {
            (1i64 << (self.width - 1)) - 1
        } else {
            (1i64 << self.width) - 1
        }
    }

    /// Whether `raw` is representable.
    pub fn contains(self, raw: i64) -> bool {
        raw >= self.min_raw() && raw <= self.max_raw()
    }

    /// The real value of `raw` in this format.
    pub fn to_f64(self, raw: i64) -> f64 {
        raw as f64 / (self.frac as f64).exp2()
    }

    /// Number of distinct codes (for exhaustive sweeps).
    pub fn codes(self) -> u64 {
        1u64 << self.width
    }

    /// The format of an exact product `self * other`.
    #[inline]
    pub fn product(self, other: Format) -> Format {
        let signed = self.signed || other.signed;
        // An unsigned operand gains a sign bit when it meets a signed one.
        let wa = self.width + u32::from(signed && !self.signed);
        let wb = other.width + u32::from(signed && !other.signed);
        Format::new(wa + wb, self.frac + other.frac, signed).expect("product wider than MAX_WIDTH")
    }

    /// The format of an exact sum of `terms` values of this format.
    #[inline]
    pub fn sum(self, terms: u32) -> Format {
        let grow = 32 - (terms.max(1) - 1).leading_zeros();
        Format::new(self.width + grow, self.frac, self.signed).expect("sum wider than MAX_WIDTH")
    }

    /// `u1.F`-style short name used in headers and manifests: `s1.14` / `u1.8` (integer.fraction bits).
    pub fn name(self) -> String {
        let int = self.width as i64 - self.frac as i64 - i64::from(self.signed);
        format!("{}{}.{}", if self.signed { 's' } else { 'u' }, int, self.frac)
    }
}

impl Format {
    /// The format a [`name`](Format::name) names (`s1.14`, `u8.0`; an integer part may be
    /// negative, `u-2.10`), None for anything else.
    pub fn from_name(name: &str) -> Option<Format> {
        let signed = match name.as_bytes().first()? {
            b's' => true,
            b'u' => false,
            _ => return None,
        };
        let (int, frac) = name[1..].split_once('.')?;
        let (int, frac): (i64, u32) = (int.parse().ok()?, frac.parse().ok()?);
        let width = u32::try_from(int.checked_add(frac as i64)?.checked_add(i64::from(signed))?).ok()?;
        let f = Format::new(width, frac, signed)?;
        (f.name() == name).then_some(f)
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({} bits)", self.name(), self.width)
    }
}

/// `x / 2^shift` rounded as `rnd` says.
#[inline]
pub fn shift_round(x: i128, shift: u32, rnd: Rounding) -> i128 {
    if shift == 0 {
        return x;
    }
    let floor = x >> shift;
    let rem = x - (floor << shift);
    let half = 1i128 << (shift - 1);
    match rnd {
        Rounding::Truncate => floor,
        Rounding::HalfUp => floor + i128::from(rem >= half),
        Rounding::NearestEven => {
            if rem > half || (rem == half && floor & 1 == 1) {
                floor + 1
            } else {
                floor
            }
        }
    }
}

/// Fit an integer into `fmt`'s width.
#[inline]
pub fn fit(x: i128, fmt: Format, ovf: Overflow) -> i64 {
    match ovf {
        Overflow::Saturate => x.clamp(fmt.min_raw() as i128, fmt.max_raw() as i128) as i64,
        Overflow::Wrap => {
            let m = x & ((1i128 << fmt.width) - 1);
            if fmt.signed && m >> (fmt.width - 1) == 1 {
                (m - (1i128 << fmt.width)) as i64
            } else {
                m as i64
            }
        }
    }
}

/// Convert `raw` in `from` to `to`: align the binary point (rounding as `rnd` says when bits
/// are dropped), then fit the width (as `ovf` says).
#[inline]
pub fn requant(raw: i64, from: Format, to: Format, rnd: Rounding, ovf: Overflow) -> i64 {
    let x = raw as i128;
    let aligned = if to.frac >= from.frac {
        x << (to.frac - from.frac)
    } else {
        shift_round(x, from.frac - to.frac, rnd)
    };
    fit(aligned, to, ovf)
}

/// Quantise a real number; `None` for NaN or infinity (callers turn that into a user error).
pub fn from_f64(v: f64, to: Format, rnd: Rounding, ovf: Overflow) -> Option<i64> {
    if !v.is_finite() {
        return None;
    }
    let scaled = v * (to.frac as f64).exp2();
    let r = match rnd {
        Rounding::Truncate => scaled.floor(),
        Rounding::HalfUp => (scaled + 0.5).floor(),
        Rounding::NearestEven => {
            let f = scaled.floor();
            let d = scaled - f;
            if d > 0.5 || (d == 0.5 && (f as i128) & 1 == 1) {
                f + 1.0
            } else {
                f
            }
        }
    };
    let clamped = r.clamp(-(2f64.powi(100)), 2f64.powi(100));
    Some(fit(clamped as i128, to, ovf))
}

/// Exact `round(a * b / (2^w - 1))` for unsigned `w`-bit normalised codes, by the
/// add-and-shift identity (Blinn, "Three wrongs make a right"): one adder, no divider.
/// `fixed` tests prove it equal to the division for every pair at w ≤ 10 and at random above.
pub fn unorm_mul(a: u64, b: u64, w: u32) -> u64 {
    let t = a * b + (1u64 << (w - 1));
    (t + (t >> w)) >> w
}

/// Exact `round(x / (2^w - 1))` (half up; the divisor is odd, so there are no ties).
#[inline]
pub fn unorm_div_round(x: u64, w: u32) -> u64 {
    let d = (1u64 << w) - 1;
    (x + d / 2) / d
}

/// `round(x / (2^w - 1))` for `x <= x_max` as hardware computes it without a divider:
/// `floor((x + (d-1)/2) · m / 2^s)` with `m = ceil(2^s / d)` a constant whose set bits are
/// shifted adds. It is exact when `y_max · (m·d − 2^s) < 2^s` for `y_max = x_max + (d-1)/2`
/// (the error term `y·e/(d·2^s)` then stays below `1/d`); `s` is the smallest such.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnormDiv {
    pub w: u32,
    /// The rounding offset `(d-1)/2`.
    pub half: u64,
    pub m: u64,
    pub s: u32,
    /// Bits of `y = x + half` at `x_max`.
    pub y_bits: u32,
}

impl UnormDiv {
    pub fn new(w: u32, x_max: u64) -> UnormDiv {
        let d = (1u64 << w) - 1;
        let half = d / 2;
        let y_max = (x_max + half) as u128;
        let s = (w..100)
            .find(|&s| {
                let p = 1u128 << s;
                let m = p.div_ceil(d as u128);
                y_max * (m * d as u128 - p) < p
            })
            .expect("a shift exists");
        UnormDiv {
            w,
            half,
            m: (1u128 << s).div_ceil(d as u128) as u64,
            s,
            y_bits: 128 - y_max.leading_zeros(),
        }
    }
    #[inline]
    pub fn apply(&self, x: u64) -> u64 {
        (((x + self.half) as u128 * self.m as u128) >> self.s) as u64
    }
    /// The set bits of `m`: the shifts whose sum is the constant product.
    pub fn m_bits(&self) -> Vec<u32> {
        (0..64).filter(|b| self.m >> b & 1 == 1).collect()
    }
}

/// Quantise a [0,1] colour to codes (clamped; NaN cannot occur, inputs are validated).
pub fn colour_codes(c: glam::DVec3, max: u32) -> [u32; 3] {
    c.to_array().map(|x| (x.clamp(0.0, 1.0) * max as f64).round() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A format's name reads back as that format; other text is no format.
    #[test]
    fn a_format_name_reads_back() {
        for f in [
            Format::s(16, 14),
            Format::u(9, 8),
            Format::u(8, 0),
            Format::u(10, 12),
            Format::s(2, 0),
            Format::u(62, 3),
        ] {
            assert_eq!(Format::from_name(&f.name()), Some(f), "{}", f.name());
        }
        for bad in [
            "",
            "s",
            "x1.2",
            "s1",
            "s1.x",
            "u0.0",
            "s-1.0",
            "u1.2.3",
            "s+1.14",
            "s01.14",
            "u99.0",
            "u9223372036854775807.1",
        ] {
            assert_eq!(Format::from_name(bad), None, "{bad}");
        }
    }

    /// The constant-reciprocal division against the division, for every product a stage
    /// colour of up to 4 guard bits and a texture colour can make, at every colour width up
    /// to 10 (and up to 12 at random); the fast model divides by it at every width, the RTL
    /// with guard bits. Its constant product stays inside 63 bits (the fast model's i64).
    #[test]
    fn unorm_div_is_the_rounded_division_for_every_guarded_product() {
        for w in 2..=10u32 {
            let d = (1u64 << w) - 1;
            for g in 0..=4u32 {
                let x_max = (d << g) * d;
                let u = UnormDiv::new(w, x_max);
                for x in 0..=x_max {
                    assert_eq!(u.apply(x), unorm_div_round(x, w), "w={w} g={g} x={x}");
                }
                assert_eq!(u.apply(x_max), d << g, "white on full colour");
                assert!(u.y_bits + 64 - u.m.leading_zeros() <= 63, "w={w} g={g}: {u:?}");
            }
        }
        let mut r = 0x9E37_79B9_7F4A_7C15u64;
        for w in 11..=12u32 {
            let d = (1u64 << w) - 1;
            for g in 0..=4u32 {
                let x_max = (d << g) * d;
                let u = UnormDiv::new(w, x_max);
                for x in (0..1_000_000u64)
                    .map(|_| {
                        r ^= r << 13;
                        r ^= r >> 7;
                        r ^= r << 17;
                        r % (x_max + 1)
                    })
                    .chain([x_max, x_max - 1, 0, 1])
                {
                    assert_eq!(u.apply(x), unorm_div_round(x, w), "w={w} g={g} x={x}");
                }
            }
        }
    }

    #[test]
    fn unorm_div_round_is_unorm_mul_where_both_apply() {
        for w in 1..=8u32 {
            let m = (1u64 << w) - 1;
            for a in 0..=m {
                for b in 0..=m {
                    assert_eq!(unorm_div_round(a * b, w), unorm_mul(a, b, w));
                }
            }
        }
    }

    /// Oracle: exact rational rounding via i128 floor division.
    fn oracle_div(x: i128, d: i128, rnd: Rounding) -> i128 {
        let q = x.div_euclid(d);
        let r = x.rem_euclid(d);
        match rnd {
            Rounding::Truncate => q,
            Rounding::HalfUp => q + i128::from(2 * r >= d),
            Rounding::NearestEven => q + i128::from(2 * r > d || (2 * r == d && q & 1 == 1)),
        }
    }

    const RNDS: [Rounding; 3] = [Rounding::Truncate, Rounding::HalfUp, Rounding::NearestEven];

    #[test]
    fn requant_exhaustive_small_formats() {
        for w_from in 2..=7u32 {
            for signed_from in [false, true] {
                let from = Format::new(w_from, w_from / 2, signed_from).unwrap();
                for w_to in 2..=6u32 {
                    for frac_to in 0..=w_to {
                        for signed_to in [false, true] {
                            let to = Format::new(w_to, frac_to, signed_to).unwrap();
                            for raw in from.min_raw()..=from.max_raw() {
                                for rnd in RNDS {
                                    let exact = if frac_to >= from.frac {
                                        (raw as i128) << (frac_to - from.frac)
                                    } else {
                                        oracle_div(raw as i128, 1 << (from.frac - frac_to), rnd)
                                    };
                                    let sat = requant(raw, from, to, rnd, Overflow::Saturate);
                                    let want_sat = exact.clamp(to.min_raw() as i128, to.max_raw() as i128);
                                    assert_eq!(sat as i128, want_sat, "{from} -> {to} raw {raw} {rnd:?}");
                                    let wrap = requant(raw, from, to, rnd, Overflow::Wrap);
                                    assert!(to.contains(wrap));
                                    assert_eq!((wrap as i128 - exact).rem_euclid(1 << w_to), 0);
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn unorm_mul_equals_rounded_division_exhaustively() {
        for w in 1..=10u32 {
            let m = (1u64 << w) - 1;
            for a in 0..=m {
                for b in 0..=m {
                    let want = oracle_div((a * b) as i128, m as i128, Rounding::HalfUp) as u64;
                    assert_eq!(unorm_mul(a, b, w), want, "w={w} a={a} b={b}");
                }
            }
        }
    }

    #[test]
    fn from_f64_refuses_nan_and_infinity() {
        let f = Format::s(16, 14);
        assert_eq!(from_f64(f64::NAN, f, Rounding::HalfUp, Overflow::Saturate), None);
        assert_eq!(from_f64(f64::INFINITY, f, Rounding::HalfUp, Overflow::Saturate), None);
        assert_eq!(from_f64(1.0, f, Rounding::HalfUp, Overflow::Saturate), Some(1 << 14));
        assert_eq!(from_f64(-3.0, f, Rounding::HalfUp, Overflow::Saturate), Some(f.min_raw()));
        assert_eq!(from_f64(2.5, Format::s(8, 0), Rounding::NearestEven, Overflow::Wrap), Some(2));
        assert_eq!(from_f64(3.5, Format::s(8, 0), Rounding::NearestEven, Overflow::Wrap), Some(4));
        assert_eq!(from_f64(-2.5, Format::s(8, 0), Rounding::HalfUp, Overflow::Wrap), Some(-2));
    }

    #[test]
    fn formats_of_exact_results() {
        assert_eq!(Format::s(8, 7).product(Format::s(16, 14)), Format::s(24, 21));
        assert_eq!(Format::u(9, 8).product(Format::s(16, 14)), Format::s(26, 22));
        assert_eq!(Format::s(24, 21).sum(3), Format::s(26, 21));
        assert_eq!(Format::s(24, 21).sum(1), Format::s(24, 21));
        assert_eq!(Format::s(16, 14).name(), "s1.14");
        assert_eq!(Format::u(9, 8).name(), "u1.8");
    }

    mod props {
        use super::*;
        use proptest::prelude::*;

        fn fmt_strategy() -> impl Strategy<Value = Format> {
            (2u32..=40, 0u32..=30, any::<bool>()).prop_map(|(w, f, s)| Format::new(w, f.min(w), s).unwrap())
        }

        proptest! {
            #[test]
            fn requant_matches_i128_oracle(from in fmt_strategy(), to in fmt_strategy(), seed in any::<u64>(), r in 0usize..3) {
                let span = (from.max_raw() as i128 - from.min_raw() as i128 + 1) as u128;
                let raw = (from.min_raw() as i128 + (seed as u128 % span) as i128) as i64;
                let rnd = RNDS[r];
                let exact = if to.frac >= from.frac {
                    (raw as i128) << (to.frac - from.frac)
                } else {
                    oracle_div(raw as i128, 1i128 << (from.frac - to.frac), rnd)
                };
                let got = requant(raw, from, to, rnd, Overflow::Saturate) as i128;
                prop_assert_eq!(got, exact.clamp(to.min_raw() as i128, to.max_raw() as i128));
            }

            #[test]
            fn unorm_mul_wide(w in 11u32..=16, a in any::<u64>(), b in any::<u64>()) {
                let m = (1u64 << w) - 1;
                let (a, b) = (a % (m + 1), b % (m + 1));
                prop_assert_eq!(unorm_mul(a, b, w) as i128, oracle_div((a * b) as i128, m as i128, Rounding::HalfUp));
            }
        }
    }
}
