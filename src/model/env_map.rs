//! Direct3D 6 environment-mapped bump mapping (paper §3.3), bit for bit: `env_coords` turns
//! the fetched normal's (b_x, b_y) = (du, dv), the interpolated sphere-map coordinates st and
//! the triangle's 2×2 matrix M into a texel and bilinear weights, and `env_fetch` reads the
//! four texels of a map. The blends then filter them (the light slots are the texels).
//!
//! Arithmetic (G = (lh_bits − 2) + (normal_bits − 1) fraction bits, n = 2^E texels a side):
//! - s = st + M·b exactly: S_x = st_x·2^(nb−1) + m_0 b_x + m_2 b_y, S_y = st_y·2^(nb−1) +
//!   m_1 b_x + m_3 b_y (M's columns are ds/db_x and ds/db_y);
//! - texel coordinate X = (s + 1)·n/2 − 1/2 (texel i's centre at s = (i + 1/2)·2/n − 1),
//!   exact, clamped to [0, n − 1];
//! - x0 = min(⌊X⌋, n − 2), and the sub-texel fraction fx = ⌊(X − x0)·16⌋ in 0..=16 (16 only
//!   at the last texel's centre), the one truncation;
//! - weights, exact in u1.8: w_0 = (16 − fx)(16 − fy), w_1 = fx(16 − fy), w_2 = (16 − fx)fy,
//!   w_3 = fx·fy, for the texels (x0, y0), (x0 + 1, y0), (x0, y0 + 1), (x0 + 1, y0 + 1).

use crate::config::PipelineConfig;

/// Sub-texel bits per axis of the bilinear weights (so each weight is exact in u1.8).
pub const SUBTEXEL_BITS: u32 = 4;
/// Fraction bits of a bilinear weight.
pub const WEIGHT_FRAC_BITS: u32 = 2 * SUBTEXEL_BITS;

/// EMBM's per-fragment state: the interpolated sphere-map coordinates and the triangle's 2×2
/// matrix, raw `s1.(lh-2)` codes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnvState {
    /// (s, t): where the unperturbed normal reads the map.
    pub st: [i64; 2],
    /// (m_0, m_1) = ds/db_x, (m_2, m_3) = ds/db_y.
    pub m: [i64; 4],
}

/// What `env_coords` gives: the texel (x0, y0) and the four bilinear weights (u1.8).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnvSample {
    pub x0: i64,
    pub y0: i64,
    pub w: [i64; 4],
}

/// The RAM word layout of an environment map, as `gbump rom` writes it and the top's
/// `env_<which>_wdata` port takes it (`rtlgen::rom::env_map_rom`), for messages.
pub fn word_layout(cfg: &PipelineConfig) -> String {
    let (cb, n) = (cfg.colour_bits, cfg.env_map_side());
    format!(
        "{} words of {} bits, texel (x, y) at word y*{n} + x, {{B, G, R}} of {cb} bits each, R lowest",
        n * n,
        3 * cb
    )
}

/// One texel from its RAM word (R in the lowest `colour_bits`), or an error when the word is
/// wider than the three channels; `what` names the word in it.
pub fn texel_of_word(cfg: &PipelineConfig, w: u64, what: &str) -> crate::error::Result<[u32; 3]> {
    let cb = cfg.colour_bits;
    if w >> (3 * cb) != 0 {
        return Err(crate::error::Error::Other(format!(
            "{what} is {w:#x}, wider than a texel's {} bits\n  fix: {}",
            3 * cb,
            word_layout(cfg)
        )));
    }
    let mask = (1u64 << cb) - 1;
    Ok([0, 1, 2].map(|c| ((w >> (c * cb)) & mask) as u32))
}

/// Refuse `count` words for one environment map other than its n².
pub fn check_word_count(cfg: &PipelineConfig, count: i64, what: &str) -> crate::error::Result<()> {
    let n = cfg.env_map_side() as i64;
    if count != n * n {
        return Err(crate::error::Error::Other(format!(
            "{what}: {count} words, not the {n}x{n} map's {}\n  fix: give the whole map: {} (env_map_bits = {})",
            n * n,
            word_layout(cfg),
            cfg.env_map_bits
        )));
    }
    Ok(())
}

/// The texels of one environment map from its RAM words ([`word_layout`]): exactly n² words,
/// none wider than a texel. `what` names the words' source in an error.
pub fn texels_of_words(cfg: &PipelineConfig, words: &[u64], what: &str) -> crate::error::Result<Vec<[u32; 3]>> {
    check_word_count(cfg, words.len() as i64, what)?;
    words
        .iter()
        .enumerate()
        .map(|(i, &w)| texel_of_word(cfg, w, &format!("{what}: word {i}")))
        .collect()
}

/// The two environment maps, texel (x, y) at `y·n + x`: colour codes R, G, B.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EnvMaps {
    pub bits: u32,
    pub diffuse: Vec<[u32; 3]>,
    pub specular: Vec<[u32; 3]>,
}

impl EnvMaps {
    /// The map called `which`: "specular", else the diffuse one.
    pub fn named(&self, which: &str) -> &Vec<[u32; 3]> {
        if which == "specular" {
            &self.specular
        } else {
            &self.diffuse
        }
    }

    /// [`named`](Self::named), to change.
    pub fn named_mut(&mut self, which: &str) -> &mut Vec<[u32; 3]> {
        if which == "specular" {
            &mut self.specular
        } else {
            &mut self.diffuse
        }
    }
}

/// Fraction bits of the exact map coordinate S.
pub fn coord_frac(cfg: &PipelineConfig) -> u32 {
    (cfg.lh_bits - 2) + (cfg.normal_bits - 1)
}

/// The exact S = st + M·b of one axis, in [`coord_frac`] fraction bits.
#[inline]
pub fn coordinate(cfg: &PipelineConfig, st: i64, m_x: i64, m_y: i64, b: [i64; 2]) -> i64 {
    (st << (cfg.normal_bits - 1)) + m_x * b[0] + m_y * b[1]
}

/// One axis: the texel index and the sub-texel fraction (0..=16) of exact coordinate `s`.
#[inline]
pub fn texel_axis(cfg: &PipelineConfig, s: i64) -> (i64, i64) {
    let g = coord_frac(cfg);
    let e = cfg.env_map_bits;
    let n = 1i64 << e;
    let x = (((s + (1i64 << g)) << e) >> 1) - (1i64 << (g - 1));
    let x = x.clamp(0, (n - 1) << g);
    let x0 = (x >> g).min(n - 2);
    let f = (x - (x0 << g)) >> (g - SUBTEXEL_BITS);
    (x0, f)
}

/// The four bilinear weights of sub-texel fractions (fx, fy), u1.8.
#[inline]
pub fn weights(fx: i64, fy: i64) -> [i64; 4] {
    let one = 1i64 << SUBTEXEL_BITS;
    [(one - fx) * (one - fy), fx * (one - fy), (one - fx) * fy, fx * fy]
}

/// The `env_coords` unit: texel and weights for normal (b_x, b_y), st and M.
pub fn env_coords(cfg: &PipelineConfig, b: [i64; 2], st: [i64; 2], m: [i64; 4]) -> EnvSample {
    let (x0, fx) = texel_axis(cfg, coordinate(cfg, st[0], m[0], m[2], b));
    let (y0, fy) = texel_axis(cfg, coordinate(cfg, st[1], m[1], m[3], b));
    EnvSample {
        x0,
        y0,
        w: weights(fx, fy),
    }
}

/// The `env_fetch` unit: the four texels of the 2×2 block at (x0, y0) of a map with `bits`.
pub fn env_fetch(bits: u32, map: &[[u32; 3]], x0: i64, y0: i64) -> [[u32; 3]; 4] {
    let n = 1usize << bits;
    let at = |dx: usize, dy: usize| map[(y0 as usize + dy) * n + x0 as usize + dx];
    [at(0, 0), at(1, 0), at(0, 1), at(1, 1)]
}

/// The maps a top with EMBM powers up with: a white directional light up and to the right
/// of the viewer, L = (1, 1, 2)/√6, lighting the sphere map's normals (texel centres; the
/// rim beyond the disc takes the rim's normal): diffuse max(0, N·L), specular max(0, N·H)^n
/// at the configuration's shininess, rounded to colour codes. A top without EMBM has none.
pub fn default_maps(cfg: &PipelineConfig) -> EnvMaps {
    if !cfg.embm() {
        return EnvMaps::default();
    }
    let n = cfg.env_map_side() as usize;
    let cmax = cfg.colour_max() as f64;
    let l = glam::DVec3::new(1.0, 1.0, 2.0).normalize();
    let h = (l + glam::DVec3::Z).normalize();
    let (mut diffuse, mut specular) = (Vec::with_capacity(n * n), Vec::with_capacity(n * n));
    for y in 0..n {
        for x in 0..n {
            let c = |i: usize| (i as f64 + 0.5) / n as f64 * 2.0 - 1.0;
            let (mut sx, mut sy) = (c(x), c(y));
            let r = (sx * sx + sy * sy).sqrt();
            if r > 1.0 {
                (sx, sy) = (sx / r, sy / r);
            }
            let nz = (1.0 - sx * sx - sy * sy).max(0.0).sqrt();
            let nv = glam::DVec3::new(sx, sy, nz).normalize();
            let code = |v: f64| (v.clamp(0.0, 1.0) * cmax).round() as u32;
            diffuse.push([code(nv.dot(l).max(0.0)); 3]);
            specular.push([code(crate::model::power_table::powi_exact(nv.dot(h).max(0.0), cfg.shininess)); 3]);
        }
    }
    EnvMaps {
        bits: cfg.env_map_bits,
        diffuse,
        specular,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cfg(bits: u32) -> PipelineConfig {
        PipelineConfig {
            env_map_bits: bits,
            lights: 4,
            light_mode: crate::config::LightMode::Parallel,
            bump_state: crate::config::BumpStateAt::Fragment,
            ..Default::default()
        }
    }

    /// Texel i's centre reads texel i alone; the edges clamp; the weights sum to one.
    #[test]
    fn texel_centres_edges_and_weights() {
        let c = cfg(3);
        let g = coord_frac(&c);
        let one = 1i64 << g;
        for i in 0..8i64 {
            // s = (i + 1/2)·2/8 − 1 exactly.
            let s = ((2 * i + 1) * one) / 8 - one;
            let (x0, f) = texel_axis(&c, s);
            assert_eq!((x0 + f / 16, f % 16), (i, 0), "texel {i}");
        }
        assert_eq!(texel_axis(&c, -3 * one), (0, 0), "below the map: the first texel");
        assert_eq!(texel_axis(&c, 3 * one), (6, 16), "above: the last texel, from the one before");
        for (fx, fy) in [(0, 0), (3, 11), (16, 16), (16, 0)] {
            assert_eq!(weights(fx, fy).iter().sum::<i64>(), 256);
        }
        c.validate("t").unwrap();
    }

    #[test]
    fn the_power_up_maps_are_lit_from_the_light() {
        let c = cfg(4);
        let m = default_maps(&c);
        assert_eq!(m.diffuse.len(), 256);
        // The texel nearest the light's direction is the brightest.
        let brightest = (0..256).max_by_key(|&i| m.diffuse[i][0]).unwrap();
        let (x, y) = (brightest % 16, brightest / 16);
        assert!(x > 8 && y > 8, "{x} {y}");
    }
}
