//! The Gouraud bump equations in f64: the golden model's algorithm without its quantisation.

use crate::bumpmap::sample::Filter;
use crate::config::{BlendOrder, Interpolate, PerFragment};
use crate::model::power_table::powi_exact;
use crate::raster::{Hit, PixelGeom, Prepared};
use glam::{DVec2, DVec3};

/// Filtered normal without renormalisation: what a texture unit hands the pipeline.
pub fn filtered_normal(map: &crate::bumpmap::NormalMap, uv: DVec2, filter: Filter) -> DVec3 {
    match filter {
        Filter::Nearest => crate::bumpmap::sample::sample_normal(map, uv, Filter::Nearest),
        Filter::Bilinear => {
            let x = uv.x * map.w as f64 - 0.5;
            let y = uv.y * map.h as f64 - 0.5;
            let (x0, y0) = (x.floor(), y.floor());
            let (fx, fy) = (x - x0, y - y0);
            let (x0, y0) = (x0 as i64, y0 as i64);
            map.at(x0, y0) * ((1.0 - fx) * (1.0 - fy))
                + map.at(x0 + 1, y0) * (fx * (1.0 - fy))
                + map.at(x0, y0 + 1) * ((1.0 - fx) * fy)
                + map.at(x0 + 1, y0 + 1) * (fx * fy)
        }
    }
}

/// The equations with L, H and k as the configuration's per-fragment choices say (per
/// triangle unless it interpolates them).
pub fn shade(p: &Prepared, hit: &Hit, g: &PixelGeom) -> DVec3 {
    shade_interpolating(p, hit, g, p.cfg.per_fragment())
}

/// The equations with L, H and k per triangle or interpolated as `how` says (the engines ask
/// for each variant whatever the configuration); `how.renormalise` scales each interpolated
/// vector back to unit length (H, and L when it is interpolated), as the `normalise` unit does
/// (or to its cube-map texel's direction, as `normalise_cube` does).
pub fn shade_interpolating(p: &Prepared, hit: &Hit, g: &PixelGeom, how: PerFragment) -> DVec3 {
    use crate::raster::tri_state::{frame_at, k_at, lh_at, vertex_k, vertex_vectors_in};
    let o = &p.objects[hit.obj as usize];
    let ts = &o.tris[hit.tri as usize];
    let corners = o.mesh.corners(hit.tri);
    let vv = if how.interpolate.is_none() {
        Vec::new()
    } else {
        vertex_vectors_in(p.scene, &p.camera, &corners, how.frame_transform, how.pixel_lh)
    };
    let vk = if how.interpolate_k {
        vertex_k(p.scene, &corners)
    } else {
        Vec::new()
    };
    // With a frame, a per-triangle L and H are the triangle's in eye space only where the
    // scene was prepared for a frame.
    debug_assert!(how.interpolate == Interpolate::Hl || how.frame_transform == p.cfg.frame_transform);
    let frame = how.frame_transform.then(|| {
        let f = frame_at(&corners, hit.bary);
        if how.frame_build {
            built_frame(f[0], f[2])
        } else if how.frame_quaternion {
            // T and B of the rotation and the interpolated normal, all times |q|².
            let q = crate::raster::tri_state::quaternion_at(&corners, hit.bary);
            let h = crate::model::quat_frame::homogeneous([q.w, q.x, q.y, q.z]).map(DVec3::from_array);
            [h[0], h[1], f[2] * q.length_squared()]
        } else if how.triangle_frame {
            let (_, t, b) = crate::scene::mesh::plane_frame(&corners);
            [t, b, f[2]]
        } else {
            f
        }
    });
    shade_with(p, hit, g, how.renormalise_bump, frame, |i| {
        let (l, h) = lh_at(ts, &vv, hit.bary, how.interpolate, i);
        let k = k_at(ts, &vk, hit.bary, how.interpolate_k, i);
        // The cube map's texel direction where the configuration reads one.
        let unit = |v: DVec3| match how.cube_map_face {
            0 => v.normalize_or_zero(),
            face => super::cube_map::cube_normalise(v, face),
        };
        let (l, h) = match (how.renormalise, how.interpolate) {
            (false, _) | (_, Interpolate::None) => (l, h),
            (true, Interpolate::H) => (l, unit(h)),
            // Blinn's per-pixel vectors: the pixel's own L, and H from it and V (the H lanes).
            (true, Interpolate::Hl) if how.pixel_lh => (unit(l), unit(unit(l) + h)),
            (true, Interpolate::Hl) => (unit(l), unit(h)),
        };
        (l, h, k)
    })
}

/// TexRam's frame (paper §3.1) from the main direction `m` and the interpolated normal
/// `n_i`, exactly: N = N_i/|N_i|, B = N × m/|N × m| (−e1), T = B × N (e2); zero axes where
/// the unit's would be zero (`model::frame_build`).
pub fn built_frame(m: DVec3, n_i: DVec3) -> [DVec3; 3] {
    let n = n_i.normalize_or_zero();
    let b = n.cross(m).normalize_or_zero();
    [b.cross(n), b, n]
}

/// The Gouraud bump equations with light `i`'s bump-space L, H and k from `lhk(i)`: the
/// paper's per-triangle values, or (the §6 variants and SGI, `engines`) interpolated ones;
/// `frame` (T, B, N: `frame_transform`) places the filtered bump normal in it, L and H then
/// being in the frame's space; `renormalise_bump` scales the normal back to unit length
/// (`normalise_b`).
pub fn shade_with(
    p: &Prepared,
    hit: &Hit,
    g: &PixelGeom,
    renormalise_bump: bool,
    frame: Option<[DVec3; 3]>,
    lhk: impl Fn(usize) -> (DVec3, DVec3, f64),
) -> DVec3 {
    let cfg = p.cfg;
    let so = &p.scene.objects[hit.obj as usize];
    let o = &p.objects[hit.obj as usize];
    let bn = filtered_normal(&o.normals, g.uv, so.bump.filter);
    // The flat test reads the filtered normal, as the pipeline's bypass reads the fetched
    // codes; normalise_b then scales it back to unit length.
    let bypass = cfg.skip_flat && (bn - DVec3::Z).length() < 1e-9;
    let bn = match frame {
        Some([t, b, n]) => t * bn.x + b * bn.y + n * bn.z,
        None => bn,
    };
    // The surface normal in L's space: z in bump space, the frame's N in a frame.
    let surface = frame.map_or(DVec3::Z, |[_, _, n]| n);
    let bn = if renormalise_bump { bn.normalize_or_zero() } else { bn };
    let dif_on = cfg.diffuse && so.diffuse && !bypass;
    let spe_on = cfg.specular && so.specular && !bypass;
    let (mut diff, mut spec) = (DVec3::ZERO, DVec3::ZERO);
    for (i, l) in p.scene.bump_lights().enumerate() {
        let (lv, hv, k) = lhk(i);
        let lc = DVec3::from_array(l.colour) * k;
        // Self-shadowing (Cg §8.5.3): nothing from a light below the surface, no highlight
        // where the bump faces away from it.
        let (lit, faces) = (surface.dot(lv) > 0.0, bn.dot(lv) > 0.0);
        if cfg.self_shadow && !lit {
            continue;
        }
        if dif_on {
            diff += lc * bn.dot(lv).clamp(0.0, 1.0);
        }
        if spe_on && (faces || !cfg.self_shadow) {
            spec += lc * powi_exact(bn.dot(hv).clamp(0.0, 1.0), cfg.power_exponent(so.shininess));
        }
    }
    combine(cfg, so, g, diff, spec)
}

/// The pipeline's colour from diffuse and specular light `diff` and `spec`: the clamped
/// Gouraud colour, the texture and the blends in the configuration's order.
pub fn combine(cfg: &crate::config::PipelineConfig, so: &crate::scene::Object, g: &PixelGeom, diff: DVec3, spec: DVec3) -> DVec3 {
    let tex = crate::raster::assets::texture_at(so, g.uv);
    let c = (g.c_src).clamp(DVec3::ZERO, DVec3::ONE);
    let s0 = (c + diff).min(DVec3::ONE);
    match cfg.blend_order {
        BlendOrder::DiffuseTextureSpecular => (s0 * tex + spec).min(DVec3::ONE),
        BlendOrder::TextureLast => (s0 + spec).min(DVec3::ONE) * tex,
    }
}
