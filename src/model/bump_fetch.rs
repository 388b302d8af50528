//! bump_fetch: turn a stored bump texel into a signed normal. Range-compressed storage is
//! offset binary (Cg tutorial §8.1.2's `2c - 1`, with 2^(w-1) standing for 0), so the
//! expansion is an inversion of each component's MSB; a palettised map (paper §6) first
//! looks its 8-bit index up in a 256-entry normal palette.

use crate::config::PipelineConfig;

/// The 256-entry normal palette: stored (offset-binary) codes per entry.
#[derive(Clone, Debug, PartialEq)]
pub struct Palette(pub Vec<[u32; 3]>);

/// Offset-binary storage code → signed component.
#[inline]
pub fn expand(cfg: &PipelineConfig, code: u32) -> i64 {
    code as i64 - (1i64 << (cfg.normal_bits - 1))
}

/// Signed component → offset-binary storage code.
#[inline]
pub fn compress(cfg: &PipelineConfig, b: i64) -> u32 {
    (b + (1i64 << (cfg.normal_bits - 1))) as u32
}

/// Stored bump texel (RGB codes) → expanded normal B.
#[inline]
pub fn bump_fetch_rgb(cfg: &PipelineConfig, rgb: [u32; 3]) -> [i64; 3] {
    rgb.map(|c| expand(cfg, c))
}

/// Palette index → expanded normal B.
#[inline]
pub fn bump_fetch_index(cfg: &PipelineConfig, palette: &Palette, index: u8) -> [i64; 3] {
    bump_fetch_rgb(cfg, palette.0[index as usize])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expansion_is_an_msb_flip() {
        let cfg = PipelineConfig::default();
        for c in 0..256u32 {
            let b = expand(&cfg, c);
            assert_eq!((b as u8) ^ 0x80, c as u8);
            assert_eq!(compress(&cfg, b), c);
        }
        assert_eq!(bump_fetch_rgb(&cfg, [128, 128, 255]), [0, 0, 127]);
    }
}
