//! texture_modulate: C·T for a stage colour C and a texture colour T, rounded to nearest:
//! exact `round(c·t / (2^w-1))` in C's units, so a white texture colour passes the colour
//! through unchanged and a black one gives black. Without guard bits the hardware divides
//! by `fixed::unorm_mul`'s add-and-shift identity, with them by
//! [`UnormDiv`](crate::fixed::UnormDiv)'s constant reciprocal; both are proven equal to the
//! division.

use crate::config::PipelineConfig;
use crate::fixed::{unorm_div_round, UnormDiv};

#[inline]
pub fn texture_modulate(cfg: &PipelineConfig, c: [u32; 3], tex: [u32; 3]) -> [u32; 3] {
    [0, 1, 2].map(|i| unorm_div_round(c[i] as u64 * tex[i] as u64, cfg.colour_bits) as u32)
}

/// The divider the hardware with guard bits (and the fast model at every width) uses: exact
/// for every product of a stage colour and a texture colour.
pub fn divider(cfg: &PipelineConfig) -> UnormDiv {
    UnormDiv::new(cfg.colour_bits, cfg.stage_colour_max() as u64 * cfg.colour_max() as u64)
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
