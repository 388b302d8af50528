//! TexRam (paper §3.1, Schilling et al.): the frame is rebuilt per pixel from the
//! interpolated normal N_i and a main direction m, e1 = m × N / ‖m × N‖, e2 = N × e1, and the
//! bump normal is placed in it; lighting per pixel. Assumption: m is the interpolated vertex
//! tangent (the u direction), "homogeneously interpolated over the triangle"; e1 then lies
//! along −B, so the map's (x, y, z) land on (e2, −e1, N), with B's handedness kept. The
//! unnormalised, widened variant (everything times ‖N_i‖) is the same vector up to its length,
//! so it differs only in fixed point.
//!
//! The bit-accurate path builds the normalised frame (the paper's first formulae; the
//! shared `normalise` arithmetic makes the widened variant's norm no cheaper): the
//! rasteriser sends the interpolated tangent as m and the interpolated normal as N_i on
//! `in_frame` (six words), the `frame_build` unit forms N, B = N × m/|N × m| (−e1) and
//! T = B × N (e2), and the rest is Harmony's path (`frame_transform`, `normalise_b`, a
//! `normalise` unit per interpolated L and H). It differs from this model where the text
//! leaves the hardware open, as Harmony's does: each light's L, H and k are interpolated from
//! the vertices rather than formed at the pixel, C_src is interpolated, and there is no
//! self-shadowing gate; and a mirrored uv mapping is refused (the unit's frame is
//! right-handed, where this model takes B's side from the mesh).

use super::common::{bump_normal, finish, per_pixel_lights, Base};
use super::{Cost, Ctx, Engine, PerFragment};
use crate::raster::{Hit, PixelGeom};
use glam::DVec3;

pub const TEXRAM: Engine = Engine {
    name: "texram",
    source: "paper §3.1 (TexRam): e1 = m×N/‖m×N‖, e2 = N×e1 per pixel",
    per_triangle: "nothing beyond the vertices",
    per_fragment: "P, N_i, m; e1 and e2 formed at the pixel (a normalisation); L and H per light",
    cost: Cost {
        triangle: 27,
        triangle_per_light: 0,
        fragment: 9,
        fragment_per_light: 0,
    },
    shade,
    scene_blend: false,
    fixed: Some(PerFragment {
        frame_build: true,
        ..super::harmony::FRAME_PATH
    }),
};

fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let p = c.p;
    let n = g.n.try_normalize().unwrap_or(DVec3::Z);
    let m = g.t;
    let e1 = m.cross(n).try_normalize().unwrap_or_else(|| n.any_orthonormal_vector());
    let e2 = n.cross(e1);
    // e1 points along −B for a right-handed (T, B, N); a mirrored map flips it back.
    let v = if (-e1).dot(g.b) >= 0.0 { -e1 } else { e1 };
    let nb = bump_normal(p, hit, g);
    let np = (e2 * nb.x + v * nb.y + n * nb.z).try_normalize().unwrap_or(n);
    let (d, s) = per_pixel_lights(p, hit, g, np, n);
    finish(p, hit, g, Base::PerPixel, d, s)
}
