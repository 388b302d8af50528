//! diffuse_blend and specular_blend: C_out = sat(C_in + Σ_i f_i · k_i · Lc_i) (paper §4.2),
//! with f = fd for the diffuse unit and f = fs for the specular unit. The sum is exact
//! (serial hardware accumulates one term per clock, parallel hardware adds all at once: with
//! no intermediate rounding both give the same bits); one rounding to stage-colour units
//! (`colour_bits` plus `colour_guard_bits` fraction bits) and one saturating add close it.

use crate::config::PipelineConfig;
use crate::fixed::shift_round;

/// Align a factor in `u1.from_frac` to the common blend-factor format.
#[inline]
pub fn align_factor(cfg: &PipelineConfig, f: i64, from_frac: u32) -> i64 {
    f << (cfg.factor_frac() - from_frac)
}

/// One light's exact term f·k·Lc, in [`PipelineConfig::term_fmt`].
#[inline]
pub fn term(f: i64, k: i64, lc: u32) -> i64 {
    f * k * lc as i64
}

/// The rounding shift that takes an exact blend sum (`acc_fmt`) to stage-colour units.
#[inline]
pub fn sum_shift(cfg: &PipelineConfig) -> u32 {
    cfg.factor_frac() + cfg.k_frac_bits - cfg.colour_guard_bits
}

/// The blend: `factors` already aligned ([`align_factor`]), one per light slot; `c_in` and
/// the result are stage colours ([`PipelineConfig::stage_colour_fmt`]).
#[inline]
pub fn blend(cfg: &PipelineConfig, c_in: [u32; 3], factors: &[i64], k: &[i64], lc: &[[u32; 3]]) -> [u32; 3] {
    let shift = sum_shift(cfg);
    let max = cfg.stage_colour_max();
    let mut out = [0u32; 3];
    for ch in 0..3 {
        let mut acc: i64 = 0;
        for i in 0..factors.len() {
            acc += term(factors[i], k[i], lc[i][ch]);
        }
        let add = shift_round(acc as i128, shift, cfg.rounding) as i64;
        out[ch] = (c_in[ch] as i64 + add).min(max) as u32;
    }
    out
}
