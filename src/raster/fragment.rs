//! Fragment records: what the pipeline receives for one covered pixel (Gouraud colour,
//! texture colour, bump texel, enables, and which triangle's bump state applies), and the
//! interpolated surface geometry the f64 renderers need.

use super::assets::texture_at;
use super::{Hit, Prepared};
use crate::bumpmap::sample::sample_bump;
use crate::model::{BumpState, FragmentIn};
use crate::scene::lighting::gouraud_colour;
use glam::{DVec2, DVec3};

/// One fragment as the pipeline sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FragmentRecord {
    pub x: u32,
    pub y: u32,
    pub obj: u32,
    pub tri: u32,
    pub frag: FragmentIn,
    /// The bump state it is shaded with: its triangle's, or under `interpolate` its own.
    pub state: BumpState,
}

/// Interpolated geometry at a pixel.
#[derive(Clone, Copy, Debug)]
pub struct PixelGeom {
    pub p: DVec3,
    pub n: DVec3,
    pub t: DVec3,
    pub b: DVec3,
    pub uv: DVec2,
    /// Gouraud colour interpolated from the vertices (unclamped f64).
    pub c_src: DVec3,
}

/// Interpolate a hit's vertex attributes (vectors are not renormalised here).
pub fn pixel_geom(p: &Prepared, hit: &Hit) -> PixelGeom {
    let v = p.objects[hit.obj as usize].mesh.corners(hit.tri);
    let w = hit.bary;
    let mix3 = |f: &dyn Fn(usize) -> DVec3| f(0) * w[0] + f(1) * w[1] + f(2) * w[2];
    let c = |i: usize| gouraud_colour(p.scene, v[i].p, v[i].n);
    PixelGeom {
        p: mix3(&|i| v[i].p),
        n: mix3(&|i| v[i].n),
        t: mix3(&|i| v[i].t),
        b: mix3(&|i| v[i].b),
        uv: v[0].uv * w[0] + v[1].uv * w[1] + v[2].uv * w[2],
        c_src: mix3(&c),
    }
}

pub use crate::fixed::colour_codes;

/// The pipeline inputs for a hit.
pub fn fragment_in(p: &Prepared, hit: &Hit, g: &PixelGeom) -> FragmentIn {
    let so = &p.scene.objects[hit.obj as usize];
    let o = &p.objects[hit.obj as usize];
    let max = p.cfg.colour_max();
    // Colour textures are procedural (constant or checker), point-sampled at the fragment's uv.
    let tex = colour_codes(texture_at(so, g.uv), max);
    FragmentIn {
        bump: sample_bump(&o.stored, g.uv, so.bump.filter),
        c_src: colour_codes(g.c_src, max),
        tex,
        diffuse_en: so.diffuse,
        specular_en: so.specular,
    }
}

/// The bump state of the fragment at `hit` (`tri_state::fragment_state`).
pub fn state_at(p: &Prepared, hit: &Hit) -> BumpState {
    let o = &p.objects[hit.obj as usize];
    let ts = &o.tris[hit.tri as usize];
    if p.cfg.embm() {
        let mut st = ts.fixed;
        st.env = super::env_setup::fragment_env(p.cfg, &p.camera, &o.mesh.corners(hit.tri), ts.fixed.env.m, hit.bary);
        return st;
    }
    if p.cfg.interpolate.is_none() && !p.cfg.interpolate_k && !p.cfg.frame_transform {
        return ts.fixed;
    }
    let corners = o.mesh.corners(hit.tri);
    let vv = super::tri_state::vertex_vectors_in(p.scene, &p.camera, &corners, p.cfg.frame_transform, p.cfg.pixel_lh);
    let vk = super::tri_state::vertex_k(p.scene, &corners);
    // Interpolated unit vectors stay within the unit ball, so every component is finite.
    let mut st = super::tri_state::fragment_state(p.cfg, ts, &vv, &vk, hit.bary).expect("finite interpolated vectors");
    if p.cfg.frame_transform {
        let mut f = super::tri_state::frame_at(&corners, hit.bary);
        if p.cfg.frame_build {
            // TexRam sends the main direction (T lanes) and the normal (N lanes) alone.
            f[1] = glam::DVec3::ZERO;
        }
        if p.cfg.frame_quaternion {
            // VISA+ with quaternions: (w, x, y, z) in lanes 0 to 3, the interpolated normal in
            // lanes 6 to 8, the rest zero.
            let q = super::tri_state::quaternion_at(&corners, hit.bary);
            f = [glam::DVec3::new(q.w, q.x, q.y), glam::DVec3::new(q.z, 0.0, 0.0), f[2]];
        }
        if p.cfg.triangle_frame {
            // VISA+: the triangle's alignment matrix with the interpolated normal.
            let (_, t, b) = crate::scene::mesh::plane_frame(&corners);
            (f[0], f[1]) = (t, b);
        }
        st.frame = super::tri_state::send_frame(p.cfg, f).expect("finite interpolated frame");
    }
    st
}

/// Every covered pixel's fragment record, triangle by triangle (pixel order within one).
pub fn fragments(p: &Prepared, gb: &super::GBuffer) -> Vec<FragmentRecord> {
    use rayon::prelude::*;
    let mut v: Vec<FragmentRecord> = gb
        .hits
        .par_iter()
        .enumerate()
        .filter_map(|(i, h)| {
            let hit = h.as_ref()?;
            let g = pixel_geom(p, hit);
            Some(FragmentRecord {
                x: i as u32 % gb.w,
                y: i as u32 / gb.w,
                obj: hit.obj,
                tri: hit.tri,
                frag: fragment_in(p, hit, &g),
                state: state_at(p, hit),
            })
        })
        .collect();
    // A rasteriser walks one triangle at a time: each triangle's visible fragments together,
    // in pixel order, so a per-triangle top sees one setup per triangle.
    v.sort_by_key(|f| (f.obj, f.tri));
    v
}
