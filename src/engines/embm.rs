//! Direct3D 6 environment-mapped bump mapping (paper §3.3): the lighting lives in an
//! environment map, and the bump map's (du, dv), through a 2×2 matrix, perturbs the map
//! coordinates per pixel. Assumptions: the map is a sphere map of the normal in view space
//! (coordinates (N·right, N·up), texel centres on a square grid), `EMBM_MAP` texels a side,
//! read bilinearly; the bump map's (du, dv) are the map normal's tangent components as the
//! texture unit filters them (what moves a unit normal's sphere-map coordinates, so a plane
//! facing the viewer is exact; a filtered du/dv texture, as Direct3D 6 hardware reads it);
//! it holds the diffuse and the specular lighting of the object's material, each texel
//! clamped to [0, 1] as a texture of colours holds it, from the scene's bump lights taken as
//! distant (their direction and spot factor at the object's centre: the map's lights are
//! stationary); the map coordinates are interpolated
//! from the vertices, and the 2×2 matrix is held per triangle, the view-space right and up
//! components of the triangle's T and B. Moving one light regenerates both maps of every
//! object it lights: `2 · EMBM_MAP²` texels each. The geometry and the maps are
//! `reference::embm_f64`'s, which the bit-accurate path (`env_map_bits`, the golden model and
//! RTL) quantises: maps of 2^6 = `EMBM_MAP` texels a side whatever `--embm-map` asks of the
//! f64 engine.

use super::common::{finish, map_normal, Base};
use super::{Cost, Ctx, Engine, PerFragment};
use crate::raster::{Hit, PixelGeom};
use crate::reference::embm_f64;
use glam::DVec3;

/// Texels along the environment map's side by default (`gbump engines --embm-map` changes it).
pub const EMBM_MAP: u32 = 64;

pub const EMBM: Engine = Engine {
    name: "embm",
    source: "paper §3.3 (Direct3D 6): (du, dv) through a 2×2 matrix perturbs environment-map coordinates",
    per_triangle: "the 2×2 matrix (4 words); the maps per object (2 · 64² texels at the default size)",
    per_fragment: "the map coordinates (2 words) and uv; four texels of two maps",
    cost: Cost {
        triangle: 10,
        triangle_per_light: 0,
        fragment: 2,
        fragment_per_light: 0,
    },
    shade,
    scene_blend: false,
    fixed: Some(PerFragment {
        env_map_bits: EMBM_MAP.trailing_zeros(),
        ..PerFragment::PER_TRIANGLE
    }),
};

/// The EMBM colour with the context's `embm_map`×`embm_map` environment maps.
fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let (diff, spec) = embm_f64::maps_lighting(c.p, hit, map_normal(c, hit, g), c.embm_map);
    finish(c.p, hit, g, Base::Interpolated, diff, spec)
}
