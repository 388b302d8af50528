//! Texture filtering of bump maps and colour textures. The texture unit sits before the bump
//! pipeline, so filtering works on stored codes (as the paper's "full texture filtering
//! capability of bump maps", §5.3) and hands the pipeline one filtered texel. Palette
//! indices cannot be blended, so palettised maps are always sampled nearest.

use super::normals::NormalMap;
use super::storage::StoredMap;
use crate::model::BumpTexel;
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Filter {
    Nearest,
    #[default]
    Bilinear,
}

/// Texel coordinates and weights of a bilinear footprint (texel centres at +0.5; wraps).
fn footprint(uv: DVec2, w: usize, h: usize) -> [(i64, i64, f64); 4] {
    let x = uv.x * w as f64 - 0.5;
    let y = uv.y * h as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    [
        (x0, y0, (1.0 - fx) * (1.0 - fy)),
        (x0 + 1, y0, fx * (1.0 - fy)),
        (x0, y0 + 1, (1.0 - fx) * fy),
        (x0 + 1, y0 + 1, fx * fy),
    ]
}

fn wrap(i: i64, n: usize) -> usize {
    i.rem_euclid(n as i64) as usize
}

/// Texel column `i` of `n`: wrapped (tiling maps) or clamped to the edge.
pub fn address(i: i64, n: usize, clamp: bool) -> usize {
    if clamp {
        i.clamp(0, n as i64 - 1) as usize
    } else {
        wrap(i, n)
    }
}

fn nearest_index(uv: DVec2, w: usize, h: usize, clamp_u: bool) -> usize {
    let x = address((uv.x * w as f64).floor() as i64, w, clamp_u);
    let y = wrap((uv.y * h as f64).floor() as i64, h);
    y * w + x
}

/// Filter a grid of integer RGB codes.
pub fn sample_codes(codes: &[[u32; 3]], w: usize, h: usize, clamp_u: bool, uv: DVec2, filter: Filter) -> [u32; 3] {
    match filter {
        Filter::Nearest => codes[nearest_index(uv, w, h, clamp_u)],
        Filter::Bilinear => {
            let mut acc = [0f64; 3];
            for (x, y, wt) in footprint(uv, w, h) {
                let c = codes[wrap(y, h) * w + address(x, w, clamp_u)];
                for i in 0..3 {
                    acc[i] += wt * c[i] as f64;
                }
            }
            acc.map(|a| (a + 0.5).floor() as u32)
        }
    }
}

/// The bump texel the pipeline receives at `uv`.
pub fn sample_bump(map: &StoredMap, uv: DVec2, filter: Filter) -> BumpTexel {
    match map {
        StoredMap::Rgb { w, h, codes, clamp_u } => BumpTexel::Rgb(sample_codes(codes, *w, *h, *clamp_u, uv, filter)),
        StoredMap::Palettised {
            w, h, indices, clamp_u, ..
        } => BumpTexel::Index(indices[nearest_index(uv, *w, *h, *clamp_u)]),
    }
}

/// The unquantised normal at `uv`, renormalised after filtering (for the f64 images).
pub fn sample_normal(map: &NormalMap, uv: DVec2, filter: Filter) -> DVec3 {
    match filter {
        Filter::Nearest => map.data[nearest_index(uv, map.w, map.h, map.clamp_u)],
        Filter::Bilinear => {
            let mut acc = DVec3::ZERO;
            for (x, y, wt) in footprint(uv, map.w, map.h) {
                acc += wt * map.at(x, y);
            }
            acc.try_normalize().unwrap_or(DVec3::Z)
        }
    }
}
