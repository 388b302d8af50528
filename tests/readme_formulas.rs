//! The README's bit-level formulas computed as the README writes them, independently of the
//! model's code, and compared with the model for every input code (power units) or for
//! corners and random vectors at every width (the normalise unit): a client that implements
//! the README gets the model's bits, or this fails naming the formula.

use gbump::config::{NormalRange, PowerUnitKind};
use gbump::model::normalise::{normalise, normalise_bump};
use gbump::model::power_unit::power_unit;
use gbump::model::PowerTable;
use gbump::vectors::rng::SplitMix64;
use gbump::PipelineConfig;

/// floor(a / b) for b > 0.
fn floor_div(a: i128, b: i128) -> i128 {
    a.div_euclid(b)
}

/// r(a / b) = floor(a / b + 1/2), b > 0: the README's r(v).
fn r_div(a: i128, b: i128) -> i128 {
    floor_div(2 * a + b, 2 * b)
}

/// r(v) of a real.
fn r(v: f64) -> i128 {
    (v + 0.5).floor() as i128
}

/// "Power units": fs for x in u1.F as the README's bullet for `cfg.power_unit` writes it.
fn readme_fs(cfg: &PipelineConfig, n: u32, x: i64) -> i64 {
    let (f, p) = (cfg.dot_frac_bits, cfg.power_frac_bits);
    let x = x as i128;
    let one = 1i128 << f;
    let pw = |v: f64| if n == 0 { 1.0 } else { v.powi(n as i32) };
    let fs = match cfg.power_unit {
        PowerUnitKind::Table => {
            // entry i = r((i/(N-1))^n 2^P); fs = entry[r(x (N-1) / 2^F)].
            let big_n = cfg.power_entries as i128;
            let i = r_div(x * (big_n - 1), one);
            r(pw(i as f64 / (big_n - 1) as f64) * (1u64 << p) as f64)
        }
        PowerUnitKind::Lerp => {
            // K knots t_i = r((i/(K-1))^n 2^P); (i, q) = divmod(x (K-1), 2^F);
            // fs = t_i + r((t_(i+1) - t_i) q / 2^F).
            let k = cfg.power_entries as i128;
            let t = |i: i128| r(pw(i as f64 / (k - 1) as f64) * (1u64 << p) as f64);
            let (i, q) = (floor_div(x * (k - 1), one), (x * (k - 1)).rem_euclid(one));
            if q == 0 {
                t(i)
            } else {
                t(i) + r_div((t(i + 1) - t(i)) * q, one)
            }
        }
        PowerUnitKind::Segmented => {
            // y = 2^F - x; segment s < S-1: y in [2^(F-1-s), 2^(F-s)), segment 0 also y = 2^F;
            // the last [0, 2^(F-S+1)). M + 1 knots at y_j = lo + j w / M, t_j = r((1 -
            // y_j/2^F)^n 2^P); (j, q) = divmod((y - lo) M, w); fs = t_j + r((t_(j+1) - t_j) q / w).
            let (segs, m) = (cfg.power_segments as i128, cfg.power_entries as i128);
            let y = one - x;
            let (lo, w) = (0..segs - 1)
                .map(|s| (1i128 << (f as i128 - 1 - s), 1i128 << (f as i128 - 1 - s)))
                .find(|&(lo, w)| y >= lo && (y < lo + w || (lo == one / 2 && y == one)))
                .unwrap_or((0, 1i128 << (f as i128 - segs + 1)));
            let t = |j: i128| {
                let yj = lo as f64 + (j * w) as f64 / m as f64;
                r(pw(1.0 - yj / one as f64) * (1u64 << p) as f64)
            };
            let (j, q) = (floor_div((y - lo) * m, w), ((y - lo) * m).rem_euclid(w));
            if q == 0 {
                t(j)
            } else {
                t(j) + r_div((t(j + 1) - t(j)) * q, w)
            }
        }
        PowerUnitKind::Squaring => {
            // e = 2^round(log2 n); x rounded half up to W = P + 4 bits; over e's bits from
            // the top: acc = r(acc^2 / 2^W), then acc = r(acc x / 2^W) where the bit is set,
            // from acc = 1; fs = r(acc / 2^4). n = 0: fs = 1.
            if n == 0 {
                return 1 << p;
            }
            let w = p + 4;
            let e = if n == 1 { 1 } else { 1u32 << (n as f64).log2().round() as u32 };
            let xw = if w >= f { x << (w - f) } else { r_div(x, 1 << (f - w)) };
            let mut acc: i128 = 1 << w;
            for bit in (0..32 - e.leading_zeros()).rev() {
                acc = r_div(acc * acc, 1 << w);
                if e >> bit & 1 == 1 {
                    acc = r_div(acc * xw, 1 << w);
                }
            }
            r_div(acc, 16)
        }
    };
    fs as i64
}

/// Every power unit the README gives a formula for, at every input code, over widths,
/// entry counts, segment counts and shininesses (n = 0 and 1 among them).
#[test]
fn every_power_unit_is_its_readme_formula() {
    for kind in [
        PowerUnitKind::Table,
        PowerUnitKind::Lerp,
        PowerUnitKind::Segmented,
        PowerUnitKind::Squaring,
    ] {
        let mut checked = 0;
        for (f, p) in [(8, 8), (6, 10), (10, 6), (12, 12)] {
            // (entries, segments): a segmented unit's knots per segment, else the table's
            // or the knots' count (at most 2^F, a power of two).
            let shapes: Vec<(u32, u32)> = match kind {
                PowerUnitKind::Segmented => [2, 4, 8, 16].into_iter().flat_map(|m| [2, 4, f - 1].map(|s| (m, s))).collect(),
                PowerUnitKind::Squaring => vec![(PipelineConfig::default().power_entries.min(1 << f), 6)],
                _ => [2, 16, 64, 1 << f].map(|e| (e, 6)).to_vec(),
            };
            for (entries, segs) in shapes {
                let cfg = PipelineConfig {
                    power_unit: kind,
                    dot_frac_bits: f,
                    power_frac_bits: p,
                    power_entries: entries,
                    power_segments: segs,
                    ..PipelineConfig::default()
                };
                if let Err(e) = cfg.validate("readme_formulas") {
                    panic!("{kind:?} F={f} P={p} entries={entries} segments={segs} is meant to be valid: {e}");
                }
                for n in [0, 1, 2, 5, 16, 23, 40, 128] {
                    let table = PowerTable::build(&cfg, n);
                    for x in 0..=1i64 << f {
                        let (want, got) = (readme_fs(&cfg, n, x), power_unit(&cfg, &table, x));
                        assert_eq!(
                            got, want,
                            "{kind:?} F={f} P={p} entries={entries} segments={segs} n={n} x={x}: the model gives {got}, the README's formula {want}"
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 10_000, "{kind:?}: {checked} codes checked");
    }
}

/// Table bits and Newton steps for F fraction bits, as "Bit for bit" gives them.
fn steps(f: u32) -> (u32, u32) {
    if f + 2 <= 6 {
        ((f + 2).max(4), 0)
    } else if (f + 3).div_ceil(2) <= 9 {
        ((f + 3).div_ceil(2), 1)
    } else {
        ((f + 4).div_ceil(4).max(4), 2)
    }
}

/// The `normalise` unit as the README's "Bit for bit" paragraph writes it, for components
/// of F fraction bits clamped to [lo, hi]; with symmetric normals (h = 2^(nb-1)), `pre` (L
/// and H: S times (h-1)², W wider by 2(nb-1)) or `post` (`normalise_b`: x r times h - 1, then
/// divided by h more) is nb - 1.
fn readme_normalise(f: u32, v: [i64; 3], lo: i64, hi: i64, pre: u32, post: u32) -> [i64; 3] {
    let (y, m) = (f + 4, f + 6);
    let w = 2 * (f + 2) + 2 * pre;
    let (t, k) = steps(f);
    let s: i128 = v.iter().map(|&c| (c as i128) * (c as i128)).sum();
    if s == 0 {
        return [0; 3];
    }
    // (h-1)² and h - 1, where the range is symmetric; 1 where it is not.
    let sym = |b: u32| if b == 0 { 1 } else { (1i128 << b) - 1 };
    let s = s * sym(pre).pow(2);
    let bitlen = 128 - s.leading_zeros();
    let z = (w - bitlen) & !1;
    let s2 = s << z;
    let i = s2 >> (w - t);
    assert!((1 << (t - 2)..1 << t).contains(&i), "index {i} outside [2^(T-2), 2^T)");
    let mut r = r(2f64.powi(y as i32) / ((i as f64 + 0.5) / 2f64.powi(t as i32)).sqrt());
    let mm = s2 >> (w - m);
    for _ in 0..k {
        let q = r * r >> y;
        let e = (3 << y) - (mm * q >> m);
        r = floor_div(r * e, 1 << (y + 1));
    }
    let h1 = sym(post);
    v.map(|x| (r_div((x as i128) * r * h1 << (z / 2), 1 << (y + 2 + post)) as i64).clamp(lo, hi))
}

/// Corner vectors of a format (every axis and diagonal at the extremes, ±1 codes, the
/// smallest nonzero) and random ones over the whole format.
fn vectors(lo: i64, hi: i64, rng: &mut SplitMix64) -> Vec<[i64; 3]> {
    let vals = [lo, lo + 1, -1, 0, 1, hi - 1, hi, hi / 2, lo / 3];
    let mut out = Vec::new();
    for &a in &vals {
        for &b in &vals {
            for &c in &vals {
                out.push([a, b, c]);
            }
        }
    }
    for _ in 0..3000 {
        out.push(std::array::from_fn(|_| rng.range(lo, hi)));
        // Short vectors too, whose shift is large.
        out.push(std::array::from_fn(|_| rng.range(-3, 3)));
    }
    out
}

/// The L/H `normalise` unit (s1.F, F = lh_bits - 2) at every `lh_bits`, and `normalise_b`
/// (s0.F, F = normal_bits - 1) at every `normal_bits`, in both normal ranges.
#[test]
fn the_normalise_unit_is_its_readme_formula() {
    let mut rng = SplitMix64(0x5EED);
    for range in [NormalRange::Binary, NormalRange::Symmetric] {
        for lh in 4..=24 {
            let cfg = PipelineConfig {
                lh_bits: lh,
                normal_range: range,
                ..PipelineConfig::default()
            };
            let pre = if range == NormalRange::Symmetric { cfg.normal_bits - 1 } else { 0 };
            let f = lh - 2;
            let (lo, hi) = (-(1i64 << (f + 1)), (1i64 << (f + 1)) - 1);
            for v in vectors(lo, hi, &mut rng) {
                let (want, got) = (readme_normalise(f, v, lo, hi, pre, 0), normalise(&cfg, v));
                assert_eq!(
                    got, want,
                    "normalise, {range:?} lh_bits {lh}, {v:?}: the model gives {got:?}, the README's formula {want:?}"
                );
            }
        }
        for nb in 3..=16 {
            let cfg = PipelineConfig {
                normal_bits: nb,
                normal_range: range,
                renormalise_bump: true,
                ..PipelineConfig::default()
            };
            let post = if range == NormalRange::Symmetric { nb - 1 } else { 0 };
            let f = nb - 1;
            let (lo, hi) = (-(1i64 << f), (1i64 << f) - 1);
            for v in vectors(lo, hi, &mut rng) {
                let (want, got) = (readme_normalise(f, v, lo, hi, 0, post), normalise_bump(&cfg, v));
                assert_eq!(
                    got, want,
                    "normalise_b, {range:?} normal_bits {nb}, {v:?}: the model gives {got:?}, the README's formula {want:?}"
                );
            }
        }
    }
}

/// "Dropping d bits of x": the three roundings as the README defines them on signed values
/// (floor, floor of x + 1/2, ties to even), its example (-2.5 LSB) among them.
#[test]
fn roundings_of_signed_values_are_the_readmes() {
    use gbump::fixed::{shift_round, Rounding};
    assert_eq!(shift_round(-5, 1, Rounding::HalfUp), -2, "-2.5 LSB half up");
    assert_eq!(shift_round(-5, 1, Rounding::Truncate), -3, "-2.5 LSB truncated");
    for d in 1..6u32 {
        let one = 1i128 << d;
        for x in -200i128..200 {
            let floor = floor_div(x, one);
            let half_up = floor_div(2 * x + one, 2 * one);
            let rem2 = 2 * (x - floor * one);
            let even = if rem2 == one { floor + (floor & 1) } else { half_up };
            assert_eq!(shift_round(x, d, Rounding::Truncate), floor, "truncate {x} / 2^{d}");
            assert_eq!(shift_round(x, d, Rounding::HalfUp), half_up, "half_up {x} / 2^{d}");
            assert_eq!(shift_round(x, d, Rounding::NearestEven), even, "nearest_even {x} / 2^{d}");
        }
    }
}
