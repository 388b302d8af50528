//! Bump-map storage as the hardware's texture memory holds it: range-compressed RGB codes
//! of `normal_bits` per component, or 8-bit indices into a 256-normal palette (paper §6).

use super::normals::NormalMap;
use super::palette::build_palette;
use crate::config::PipelineConfig;
use crate::fixed::{from_f64, Overflow, Rounding};
use crate::model::bump_fetch::{compress, Palette};
use glam::DVec3;

/// A stored bump map.
#[derive(Clone, Debug)]
pub enum StoredMap {
    Rgb {
        w: usize,
        h: usize,
        codes: Vec<[u32; 3]>,
        clamp_u: bool,
    },
    Palettised {
        w: usize,
        h: usize,
        indices: Vec<u8>,
        palette: Palette,
        /// As an RGB map's: a baked-cylinder map clamps in u, indices as codes.
        clamp_u: bool,
    },
}

/// Range-compress one unit normal to stored codes (round to nearest, saturate). Under
/// `normal_range = "binary"` +1.0 becomes the largest code, 2^(w-1)-1 over 2^(w-1); under
/// `"symmetric"` the component is divided by [`PipelineConfig::normal_scale`] first, so +1.0
/// is the largest code exactly.
pub fn encode_normal(cfg: &PipelineConfig, n: DVec3) -> [u32; 3] {
    let (f, scale) = (cfg.normal_fmt(), cfg.normal_scale());
    [n.x, n.y, n.z].map(|c| {
        compress(
            cfg,
            from_f64(c / scale, f, Rounding::HalfUp, Overflow::Saturate).expect("finite normal"),
        )
    })
}

impl StoredMap {
    /// Store `map` in the configured format.
    pub fn store(cfg: &PipelineConfig, map: &NormalMap) -> StoredMap {
        let codes: Vec<[u32; 3]> = map.data.iter().map(|n| encode_normal(cfg, *n)).collect();
        if cfg.palette {
            let (palette, indices) = build_palette(cfg, &codes);
            StoredMap::Palettised {
                w: map.w,
                h: map.h,
                indices,
                palette,
                clamp_u: map.clamp_u,
            }
        } else {
            StoredMap::Rgb {
                w: map.w,
                h: map.h,
                codes,
                clamp_u: map.clamp_u,
            }
        }
    }

    pub fn size(&self) -> (usize, usize) {
        match self {
            StoredMap::Rgb { w, h, .. } | StoredMap::Palettised { w, h, .. } => (*w, *h),
        }
    }

    pub fn palette(&self) -> Option<&Palette> {
        match self {
            StoredMap::Palettised { palette, .. } => Some(palette),
            StoredMap::Rgb { .. } => None,
        }
    }
}
