//! texture_modulate: C·T for a stage colour C and a texture colour T, rounded to nearest:
//! exact `round(c·t / (2^w-1))` in C's units, so a white texture colour passes the colour
//! through unchanged and a black one gives black. Without guard bits the hardware divides
//! by `fixed::unorm_mul`'s add-and-shift identity, with them by
//! [`UnormDiv`](crate::fixed::UnormDiv)'s constant reciprocal; both are proven equal to the
//! division.

use crate::config::PipelineConfig;
use crate::fixed::{unorm_div_round, unorm_mul};

#[inline]
pub fn texture_modulate(cfg: &PipelineConfig, c: [u32; 3], tex: [u32; 3]) -> [u32; 3] {
    let w = cfg.colour_bits;
    if cfg.colour_guard_bits == 0 {
        return [0, 1, 2].map(|i| unorm_mul(c[i] as u64, tex[i] as u64, w) as u32);
    }
    [0, 1, 2].map(|i| unorm_div_round(c[i] as u64 * tex[i] as u64, w) as u32)
}

/// colour_round: a stage colour with `colour_guard_bits` fraction bits to the output colour,
/// by the configured rounding (never above the largest code: the stage colour is at most
/// 1.0).
#[inline]
pub fn colour_round(cfg: &PipelineConfig, c: [u32; 3]) -> [u32; 3] {
    let g = cfg.colour_guard_bits;
    c.map(|x| crate::fixed::shift_round(x as i128, g, cfg.rounding) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_is_identity_black_is_zero() {
        let cfg = PipelineConfig::default();
        for c in 0..=255 {
            assert_eq!(texture_modulate(&cfg, [c; 3], [255; 3]), [c; 3]);
            assert_eq!(texture_modulate(&cfg, [c; 3], [0; 3]), [0; 3]);
        }
    }
}
