//! Blinn 1978 (paper §2): N' = N + D, D = (F_u (N × P_v) + F_v (P_u × N)) / ‖N‖, lit per pixel
//! with per-pixel light and half vectors and exact powers. With the interpolated frame
//! re-orthonormalised per pixel and the stored normal map as Eq. 2's normalised (−F_u, −F_v,
//! 1), this is `reference::perpixel`, the yardstick every other engine is measured against.

use super::{Cost, Ctx, Engine};
use crate::raster::{Hit, PixelGeom};
use glam::DVec3;

pub const BLINN: Engine = Engine {
    name: "blinn",
    source: "paper §2 (Blinn 1978): N' = N + D per pixel, per-pixel L and H",
    per_triangle: "nothing beyond the vertices",
    per_fragment: "P, N, T, B, uv; L and H per light formed at the pixel",
    cost: Cost {
        triangle: 36,
        triangle_per_light: 0,
        fragment: 12,
        fragment_per_light: 0,
    },
    shade,
    scene_blend: false,
    fixed: None,
};

fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::perpixel::shade(c.p, hit, g)
}
