//! texture_modulate: C·T for normalised colour codes, rounded to nearest
//! (`fixed::unorm_mul`: exact `round(c·t / (2^w-1))` with one adder instead of a divider),
//! so a white texture colour passes the colour through unchanged and a black one gives black.

use crate::config::PipelineConfig;
use crate::fixed::unorm_mul;

#[inline]
pub fn texture_modulate(cfg: &PipelineConfig, c: [u32; 3], tex: [u32; 3]) -> [u32; 3] {
    [0, 1, 2].map(|i| unorm_mul(c[i] as u64, tex[i] as u64, cfg.colour_bits) as u32)
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
