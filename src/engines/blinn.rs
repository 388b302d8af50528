//! Blinn 1978 (paper §2): N' = N + D, D = (F_u (N × P_v) + F_v (P_u × N)) / ‖N‖, lit per pixel
//! with per-pixel light and half vectors and exact powers. With the interpolated frame
//! re-orthonormalised per pixel and the stored normal map as Eq. 2's normalised (−F_u, −F_v,
//! 1), this is `reference::perpixel`, the yardstick every other engine is measured against.
//!
//! The bit-accurate path: the re-orthonormalised frame is what the `frame_build` unit forms
//! from the interpolated normal and tangent (N = N_i/|N_i|, B = N × P_u/|N × P_u|,
//! T = B × N: the reference's Gram–Schmidt frame, exactly, in real arithmetic), so the frame
//! is TexRam's top; what makes it Blinn's is lighting at the pixel (`pixel_lh`): each
//! light's vector to the light is interpolated unnormalised (exact, being linear over the
//! triangle), a `normalise` unit makes it the pixel's L, and a second forms H from that L
//! and the viewer direction. It differs from this model where the pipeline has no unit for
//! it: each light's k (its spot factor) is interpolated from the vertices rather than taken
//! at the pixel, the non-bump colour C_src is interpolated by the rasteriser, the specular
//! power is the scene's power table, and a mirrored uv mapping is refused (the unit's
//! frame is right-handed).

use super::{Cost, Ctx, Engine, PerFragment};
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
    fixed: Some(PerFragment {
        frame_build: true,
        pixel_lh: true,
        ..super::harmony::FRAME_PATH
    }),
};

fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::perpixel::shade(c.p, hit, g)
}
