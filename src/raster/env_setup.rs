//! EMBM's setup (paper §3.3), in the pipeline's words: each object's two environment maps
//! quantised to colour codes, the triangle's 2×2 matrix and the fragment's interpolated map
//! coordinates as the rasteriser sends them (`scene::sphere_map` is their geometry).

use crate::config::PipelineConfig;
use crate::fixed::{from_f64, Overflow, Rounding};
use crate::model::env_map::{EnvMaps, EnvState};
use crate::scene::mesh::Vertex;
use crate::scene::sphere_map::{coords_at, texel, texel_centre};
use crate::scene::{Camera, Scene};
use glam::DVec3;

/// Object `obj`'s maps at the configuration's size, its lights evaluated at `at` (its centre): each texel's lighting clamped to [0, 1]
/// and rounded to colour codes, as a stored colour is (a sum of lights above full scale
/// saturates in the map, not in the blend).
pub fn object_maps(cfg: &PipelineConfig, scene: &Scene, cam: &Camera, obj: usize, at: DVec3) -> EnvMaps {
    let side = cfg.env_map_side();
    let max = cfg.colour_max();
    let (mut diffuse, mut specular) = (Vec::new(), Vec::new());
    for y in 0..side {
        for x in 0..side {
            let (sx, sy) = texel_centre(side, x, y);
            let (d, s) = texel(scene, cam, obj, at, sx, sy);
            diffuse.push(crate::fixed::colour_codes(d, max));
            specular.push(crate::fixed::colour_codes(s, max));
        }
    }
    EnvMaps {
        bits: cfg.env_map_bits,
        diffuse,
        specular,
    }
}

/// The fragment's EMBM state: its triangle's matrix and its map coordinates interpolated at
/// barycentric weights `w`, rounded to the L/H word (coordinates, so unscaled).
pub fn fragment_env(cfg: &PipelineConfig, cam: &Camera, v: &[Vertex; 3], m: [i64; 4], w: [f64; 3]) -> EnvState {
    let st = coords_at(cam, v, w);
    let q = |x: f64| from_f64(x, cfg.lh_fmt(), Rounding::HalfUp, Overflow::Saturate).expect("unit coordinates are finite");
    EnvState { st: [q(st.x), q(st.y)], m }
}
