//! Harmony (paper §3.5, Evans & Sutherland): the per-vertex coordinate systems (−P_v × N,
//! −N × P_u, P_u × P_v: Blinn's own axes) are interpolated over the triangle and the bump
//! normal placed in the interpolated frame; each light's direction and half vector are
//! interpolated from the vertices. Assumptions: the interpolated frame is not
//! re-orthonormalised (the text interpolates the axes and says no more), the perturbed normal
//! and the interpolated L and H are normalised before the dot products, and each light's k
//! and spot factor is interpolated from the vertices.
//!
//! The bit-accurate path: the rasteriser sends the interpolated frame (`in_frame`) and each
//! light's L and H in eye space per fragment; the `frame_transform` unit places the fetched
//! normal in the frame, `normalise_b` scales it to unit length, the `normalise` units scale
//! L and H, and the rest is the Gouraud bump pipeline's. It differs from this model where
//! the text leaves the hardware open: C_src is interpolated from the vertices (a Gouraud
//! rasteriser's) rather than evaluated at the pixel, and there is no self-shadowing gate
//! (the pipeline's reads L_z in bump space; this model's reads the geometric normal).

use super::common::{bump_normal, corners, finish, mix, Base};
use super::{Cost, Ctx, Engine, PerFragment};
use crate::config::Interpolate;
use crate::model::power_table::powi_exact;
use crate::raster::{Hit, PixelGeom};
use crate::reference::perpixel::light_factors;
use crate::scene::lighting::{half_vector, light_dir, spot_factor};
use glam::DVec3;

pub const HARMONY: Engine = Engine {
    name: "harmony",
    source: "paper §3.5 (Harmony, E&S): interpolated per-vertex frames, interpolated L and H per light",
    per_triangle: "a frame per vertex (27 words) and L and H per light per vertex (18 words a light)",
    per_fragment: "the frame (9 words), L and H per light (6 words a light), three normalisations",
    cost: Cost {
        triangle: 27,
        triangle_per_light: 18,
        fragment: 9,
        fragment_per_light: 6,
    },
    shade,
    scene_blend: false,
    fixed: Some(FRAME_PATH),
};

/// Harmony's per-fragment choices, which every engine that places the bump normal in a frame
/// per fragment shares (TexRam's and VISA+'s paths add where the frame comes from): L, H
/// and k interpolated, L, H and the placed normal renormalised, and where the scene
/// self-shadows (as the engines' f64 models do there) the gate on N·L with the frame's N.
pub const FRAME_PATH: PerFragment = PerFragment {
    interpolate: Interpolate::Hl,
    renormalise: true,
    interpolate_k: true,
    renormalise_bump: true,
    frame_transform: true,
    self_shadow: true,
    ..PerFragment::PER_TRIANGLE
};

fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let p = c.p;
    let so = &p.scene.objects[hit.obj as usize];
    let v = corners(p, hit);
    let nb = bump_normal(p, hit, g);
    let n = g.n.try_normalize().unwrap_or(DVec3::Z);
    let np = (g.t * nb.x + g.b * nb.y + g.n * nb.z).try_normalize().unwrap_or(n);
    let (mut diff, mut spec) = (DVec3::ZERO, DVec3::ZERO);
    for l in p.scene.bump_lights() {
        let ld = |i: usize| light_dir(l, v[i].p, v[i].n);
        let li = mix(hit, ld).try_normalize().unwrap_or(n);
        let hi = mix(hit, |i| half_vector(ld(i), p.camera.to_viewer)).try_normalize().unwrap_or(n);
        let k = mix(hit, |i| DVec3::splat(l.k * spot_factor(l, v[i].p))).x;
        let (fd, fs) = light_factors(np, n, li, hi, p.scene.self_shadowing);
        let lc = DVec3::from_array(l.colour) * k;
        diff += lc * fd;
        spec += lc * powi_exact(fs, so.shininess);
    }
    finish(p, hit, g, Base::PerPixel, diff, spec)
}
