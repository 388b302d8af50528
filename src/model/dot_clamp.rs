//! dot_clamp: fd = max(0, B·V) for V = L_i or H_i (paper §4.2), requantised to `u1.F`.
//! The three products are summed exactly (no intermediate rounding: the adder tree is
//! cheap next to the multipliers), then one rounding to F fraction bits and a clamp to
//! [0, 1]. Negative results clamp to 0: a surface facing away gets no light, which is also
//! the Cg tutorial's geometric self-shadowing at the bump level.

use crate::config::PipelineConfig;
use crate::fixed::{requant, Overflow};

/// Exact B·V in [`PipelineConfig::dot_exact_fmt`].
#[inline]
pub fn dot_exact(b: [i64; 3], v: [i64; 3]) -> i64 {
    b[0] * v[0] + b[1] * v[1] + b[2] * v[2]
}

/// max(0, B·V), rounded to `u1.F` and clamped at 1.0.
#[inline]
pub fn dot_clamp(cfg: &PipelineConfig, b: [i64; 3], v: [i64; 3]) -> i64 {
    let exact = dot_exact(b, v);
    let from = cfg.dot_exact_fmt();
    let q = requant(exact, from, cfg.dot_fmt(), cfg.rounding, Overflow::Saturate);
    q.min(1 << cfg.dot_frac_bits)
}

/// Exact ties of the dot product's rounding, half an output LSB above an even and above an
/// odd code, where truncate, half_up and nearest_even all differ: b_x·v_x = (2k+1)·2^(E-F-1)
/// with E the exact product's fraction bits and F the output's, b_x a power of two within
/// the normal's range and v_x the rest within L/H's. As (the multiple of a half LSB, 1 or 3;
/// B raw; V raw); none when E <= F (the exact sum has no bits below fd's LSB, so no tie
/// exists). The unit's corners and the top's both hold them.
pub fn rounding_ties(cfg: &PipelineConfig) -> Option<[(i64, [i64; 3], [i64; 3]); 2]> {
    let e = cfg.dot_exact_fmt().frac;
    (e > cfg.dot_frac_bits).then(|| {
        let z = e - cfg.dot_frac_bits - 1;
        let bz = z.min(cfg.normal_bits - 2);
        [1i64, 3].map(|odd| (odd, [1i64 << bz, 0, 0], [odd << (z - bz), 0, 0]))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extremes() {
        let cfg = PipelineConfig::default();
        let one = 1i64 << (cfg.lh_bits - 2);
        let flat = cfg.flat_normal();
        // B·L = 127/128 for the flat normal under a light straight above.
        assert_eq!(dot_clamp(&cfg, flat, [0, 0, one]), 254); // 127/128 * 256 = 254
                                                             // A normal pointing away: negative, clamps to 0.
        assert_eq!(dot_clamp(&cfg, flat, [0, 0, -one]), 0);
        // Exactly perpendicular.
        assert_eq!(dot_clamp(&cfg, flat, [one, 0, 0]), 0);
        // Largest possible sum (all components -128 · -1.0) clamps to exactly 1.0.
        assert_eq!(dot_clamp(&cfg, [-128, -128, -128], [-one, -one, -one]), 256);
        // Smallest: below any threshold.
        assert_eq!(dot_clamp(&cfg, [-128, -128, -128], [one, one, one]), 0);
    }
}
