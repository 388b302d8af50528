//! Per-triangle bump state: the triangle's tangent frame (the average of its vertex frames,
//! re-orthonormalised), and each bump light's L_i and H_i in that frame (in eye space under
//! `frame_transform`, whose frame enters per fragment), in f64 and quantised to the
//! pipeline's L/H words. Parallel viewer and per-triangle parallel lights
//! are the paper's simplifications (§5.4, items 2 and 3).

use crate::config::{Interpolate, PipelineConfig};
use crate::error::{Error, Result};
use crate::fixed::{from_f64, Overflow, Rounding};
use crate::model::{BumpState, LightSlot, MAX_LIGHTS};
use crate::scene::lighting::{half_vector, light_dir, spot_factor};
use crate::scene::mesh::{frame, triangle_frame, Mesh};
use crate::scene::{Camera, Scene};
use glam::DVec3;

#[derive(Clone, Copy, Debug)]
pub struct TriState {
    /// Light and half vectors (bump space, or eye space under `frame_transform`), light
    /// colour and k, per slot (f64).
    pub l: [DVec3; MAX_LIGHTS],
    pub h: [DVec3; MAX_LIGHTS],
    pub k: [f64; MAX_LIGHTS],
    /// The same, quantised.
    pub fixed: BumpState,
}

/// One component of L or H as the setup sends it: times the normal codes' scale
/// (`normal_range`), so B·L is the same product on the codes, rounded to the L/H word. None
/// when not finite.
pub fn send_lh(cfg: &PipelineConfig, x: f64) -> Option<i64> {
    from_f64(x * cfg.normal_scale(), cfg.lh_fmt(), Rounding::HalfUp, Overflow::Saturate)
}

/// A light's k (intensity times spot factor) as the setup sends it, rounded to u1.K.
pub fn send_k(cfg: &PipelineConfig, x: f64) -> i64 {
    from_f64(x, cfg.k_fmt(), Rounding::HalfUp, Overflow::Saturate).expect("finite k")
}

/// The triangle's matrix as the setup sends it (`m`, `s1.(lh-2)`): (m_0, m_1) its T's and
/// (m_2, m_3) its B's (right, up) components, times the normal codes' scale as L and H are,
/// so M times the fetched codes is M times the normal.
pub fn send_matrix(cfg: &PipelineConfig, cam: &Camera, v: &[crate::scene::mesh::Vertex; 3]) -> [i64; 4] {
    let [t, b] = crate::scene::sphere_map::triangle_matrix(cam, v);
    // Unit T and B give components within [-1, 1]: finite, and inside the L/H format.
    [t.x, t.y, b.x, b.y].map(|c| send_lh(cfg, c).expect("a unit frame's components are finite"))
}

pub fn tri_states(scene: &Scene, cfg: &PipelineConfig, cam: &Camera, mesh: &Mesh) -> Result<Vec<TriState>> {
    let lights: Vec<_> = scene.bump_lights().collect();
    scene.check_config(cfg, &crate::config::origin())?;
    scene.warn_config(cfg, &crate::config::origin());
    let q = |x: f64| send_lh(cfg, x).ok_or_else(|| Error::Other("non-finite light vector".into()));
    let max = cfg.colour_max() as f64;
    let mut out = Vec::with_capacity(mesh.tris.len());
    for t in &mesh.tris {
        let v = t.map(|i| mesh.verts[i as usize]);
        let centroid = (v[0].p + v[1].p + v[2].p) / 3.0;
        let (n, tg, bn) = triangle_frame(&v);
        // Under `frame_transform` the pipeline places the bump normal in the fragment's
        // frame, so L and H stay in eye space.
        let to_bump = |w: DVec3| match cfg.frame_transform {
            true => w,
            false => DVec3::new(w.dot(tg), w.dot(bn), w.dot(n)),
        };
        let mut st = TriState {
            l: [DVec3::ZERO; MAX_LIGHTS],
            h: [DVec3::ZERO; MAX_LIGHTS],
            k: [0.0; MAX_LIGHTS],
            fixed: BumpState::default(),
        };
        if cfg.embm() {
            // EMBM's lights are in its maps: the setup sends the triangle's 2×2 matrix alone.
            st.fixed.env.m = send_matrix(cfg, cam, &v);
            out.push(st);
            continue;
        }
        for (i, light) in lights.iter().enumerate() {
            let ld = light_dir(light, centroid, n);
            let hd = half_vector(ld, cam.to_viewer);
            st.l[i] = to_bump(ld);
            st.h[i] = to_bump(hd);
            st.k[i] = light.k * spot_factor(light, centroid);
            let l = st.l[i];
            let h = st.h[i];
            st.fixed.lights[i] = LightSlot {
                l: [q(l.x)?, q(l.y)?, q(l.z)?],
                h: [q(h.x)?, q(h.y)?, q(h.z)?],
                lc: light.colour.map(|c| (c * max).round() as u32),
                k: send_k(cfg, st.k[i]),
            };
        }
        out.push(st);
    }
    Ok(out)
}

/// Each bump light's L and H at each vertex of a triangle, each in that vertex's own frame
/// (what paper §6's interpolating variants send per vertex): `[light][vertex] = (L, H)`.
pub fn vertex_vectors(scene: &Scene, cam: &Camera, v: &[crate::scene::mesh::Vertex; 3]) -> Vec<[(DVec3, DVec3); 3]> {
    vertex_vectors_in(scene, cam, v, false, false)
}

/// [`vertex_vectors`], or with `eye` in eye space (Harmony's, `frame_transform`: the bump
/// normal is placed in the interpolated frame instead); with `pixel` (`pixel_lh`, eye space)
/// what Blinn's per-pixel lighting interpolates instead: each light's vector from the vertex
/// to the light, unnormalised (so it interpolates to the pixel's own, exactly) and scaled by
/// one factor per triangle that makes the longest unit (a directional light's direction), and
/// the viewer direction V in place of H.
pub fn vertex_vectors_in(
    scene: &Scene,
    cam: &Camera,
    v: &[crate::scene::mesh::Vertex; 3],
    eye: bool,
    pixel: bool,
) -> Vec<[(DVec3, DVec3); 3]> {
    if pixel {
        return scene
            .bump_lights()
            .map(|l| {
                let to = |j: usize| match l.kind {
                    crate::scene::LightKind::Directional => DVec3::from_array(l.direction).normalize(),
                    _ => DVec3::from_array(l.position) - v[j].p,
                };
                let longest = (0..3).map(|j| to(j).length()).fold(0.0, f64::max);
                let scale = if longest > 0.0 { 1.0 / longest } else { 0.0 };
                std::array::from_fn(|j| (to(j) * scale, cam.to_viewer))
            })
            .collect();
    }
    scene
        .bump_lights()
        .map(|l| {
            std::array::from_fn(|j| {
                let (n, t, b) = frame(v[j].n, v[j].t, v[j].b);
                let to_bump = |w: DVec3| if eye { w } else { DVec3::new(w.dot(t), w.dot(b), w.dot(n)) };
                let ld = light_dir(l, v[j].p, n);
                (to_bump(ld), to_bump(half_vector(ld, cam.to_viewer)))
            })
        })
        .collect()
}

/// The vertex frames (T, B, N) interpolated at barycentric weights `w`, not
/// re-orthonormalised: Harmony's per-fragment frame (`frame_transform`).
pub fn frame_at(v: &[crate::scene::mesh::Vertex; 3], w: [f64; 3]) -> [DVec3; 3] {
    let mix = |f: &dyn Fn(&crate::scene::mesh::Vertex) -> DVec3| f(&v[0]) * w[0] + f(&v[1]) * w[1] + f(&v[2]) * w[2];
    [mix(&|x| x.t), mix(&|x| x.b), mix(&|x| x.n)]
}

/// The vertex frames as rotations (quaternions of (T, N × T, N); `Prepared::new` refuses a
/// mirrored mapping under `frame_quaternion`, whose B this would turn over) interpolated at barycentric weights `w`, each sign aligned to the first
/// vertex's, not normalised: VISA+'s quaternion variant (`frame_quaternion`).
pub fn quaternion_at(v: &[crate::scene::mesh::Vertex; 3], w: [f64; 3]) -> glam::DQuat {
    let q: Vec<glam::DQuat> = v
        .iter()
        .map(|x| {
            let (n, t, _) = crate::scene::mesh::frame(x.n, x.t, x.b);
            glam::DQuat::from_mat3(&glam::DMat3::from_cols(t, n.cross(t), n))
        })
        .collect();
    let mut sum = glam::DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    for (i, qi) in q.iter().enumerate() {
        let qi = if qi.dot(q[0]) < 0.0 { -*qi } else { *qi };
        sum = sum + qi * w[i];
    }
    sum
}

/// A frame as the rasteriser sends it (`in_frame`): each component rounded to the L/H word
/// (a rotation: no normal-range scale). None when not finite.
pub fn send_frame(cfg: &PipelineConfig, f: [DVec3; 3]) -> Option<crate::model::frame_transform::Frame> {
    let q = |x: f64| from_f64(x, cfg.lh_fmt(), Rounding::HalfUp, Overflow::Saturate);
    Some([
        [q(f[0].x)?, q(f[0].y)?, q(f[0].z)?],
        [q(f[1].x)?, q(f[1].y)?, q(f[1].z)?],
        [q(f[2].x)?, q(f[2].y)?, q(f[2].z)?],
    ])
}

/// Each bump light's k (intensity times spot factor) at each vertex of a triangle:
/// `[light][vertex]` (what `interpolate_k` interpolates; the triangle holds it at its centroid).
pub fn vertex_k(scene: &Scene, v: &[crate::scene::mesh::Vertex; 3]) -> Vec<[f64; 3]> {
    scene
        .bump_lights()
        .map(|l| std::array::from_fn(|j| l.k * spot_factor(l, v[j].p)))
        .collect()
}

/// Light `i`'s k at barycentric weights `w`: the triangle's own, or interpolated from `vk`
/// ([`vertex_k`]) under `interpolate_k`.
pub fn k_at(ts: &TriState, vk: &[[f64; 3]], w: [f64; 3], interpolate_k: bool, i: usize) -> f64 {
    if interpolate_k {
        vk[i][0] * w[0] + vk[i][1] * w[1] + vk[i][2] * w[2]
    } else {
        ts.k[i]
    }
}

/// Light `i`'s bump-space L and H at barycentric weights `w` under `interpolate`: the
/// triangle's own, or interpolated from `vv` ([`vertex_vectors`]).
pub fn lh_at(ts: &TriState, vv: &[[(DVec3, DVec3); 3]], w: [f64; 3], interpolate: Interpolate, i: usize) -> (DVec3, DVec3) {
    let mix = |f: &dyn Fn(&(DVec3, DVec3)) -> DVec3| f(&vv[i][0]) * w[0] + f(&vv[i][1]) * w[1] + f(&vv[i][2]) * w[2];
    match interpolate {
        Interpolate::None => (ts.l[i], ts.h[i]),
        Interpolate::H => (ts.l[i], mix(&|x| x.1)),
        Interpolate::Hl => (mix(&|x| x.0), mix(&|x| x.1)),
    }
}

/// The bump state one fragment carries under `cfg.interpolate` and `cfg.interpolate_k`: the
/// triangle's, with each light's interpolated vectors and k quantised as the setup quantises
/// its own.
pub fn fragment_state(cfg: &PipelineConfig, ts: &TriState, vv: &[[(DVec3, DVec3); 3]], vk: &[[f64; 3]], w: [f64; 3]) -> Result<BumpState> {
    let mut st = ts.fixed;
    let q = |x: f64| send_lh(cfg, x).ok_or_else(|| Error::Other("non-finite interpolated light vector".into()));
    for i in 0..vv.len() {
        let (l, h) = lh_at(ts, vv, w, cfg.interpolate, i);
        st.lights[i].l = [q(l.x)?, q(l.y)?, q(l.z)?];
        st.lights[i].h = [q(h.x)?, q(h.y)?, q(h.z)?];
        if cfg.interpolate_k {
            st.lights[i].k = send_k(cfg, k_at(ts, vk, w, true, i));
        }
    }
    Ok(st)
}
