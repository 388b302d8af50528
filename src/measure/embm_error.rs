//! `gbump error` for an EMBM configuration (`env_map_bits` > 0): `env_coords`' weights against
//! the exact sub-texel fractions, and the whole pipeline against exact arithmetic on the same
//! quantised inputs and maps: s = st + M·b exactly, the texel coordinate clamped to the map as
//! the hardware clamps it but not truncated to a sixteenth, exact bilinear weights, unrounded
//! blend sums with saturation, exact c·t/max.

use super::unit_error::ErrorStats;
use crate::config::{BlendOrder, PipelineConfig};
use crate::model::env_map::{env_coords, EnvMaps};
use crate::vectors::targets::TopStim;

/// The exact texel block and bilinear weights of stimulus `s` (fetched normal `b`).
fn exact_weights(cfg: &PipelineConfig, b: [i64; 3], s: &TopStim) -> (i64, i64, [f64; 4]) {
    let (lf, nf) = (cfg.lh_fmt(), cfg.normal_fmt());
    let n = cfg.env_map_side() as f64;
    let m = s.state.env.m.map(|v| lf.to_f64(v));
    let bx = [nf.to_f64(b[0]), nf.to_f64(b[1])];
    let block = env_coords(cfg, [b[0], b[1]], s.state.env.st, s.state.env.m);
    let axis = |st: i64, mx: f64, my: f64, x0: i64| {
        let sv = lf.to_f64(st) + mx * bx[0] + my * bx[1];
        ((sv + 1.0) * n / 2.0 - 0.5).clamp(0.0, n - 1.0) - x0 as f64
    };
    let fx = axis(s.state.env.st[0], m[0], m[2], block.x0);
    let fy = axis(s.state.env.st[1], m[1], m[3], block.y0);
    (
        block.x0,
        block.y0,
        [(1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy],
    )
}

/// The exact colour of stimulus `s` with maps `maps`, in colour codes.
pub fn exact_embm(cfg: &PipelineConfig, maps: &EnvMaps, s: &TopStim) -> [f64; 3] {
    let codes = match s.frag.bump {
        crate::model::BumpTexel::Rgb(t) => t,
        crate::model::BumpTexel::Index(_) => unreachable!("EMBM has no palette"),
    };
    let b = codes.map(|c| crate::model::bump_fetch::expand(cfg, c));
    let max = cfg.colour_max() as f64;
    let bypass = cfg.skip_flat && b == cfg.flat_normal();
    let (x0, y0, w) = exact_weights(cfg, b, s);
    let filter = |map: &[[u32; 3]], on: bool| -> [f64; 3] {
        let t = crate::model::env_map::env_fetch(cfg.env_map_bits, map, x0, y0);
        std::array::from_fn(|ch| if on { (0..4).map(|i| w[i] * t[i][ch] as f64).sum() } else { 0.0 })
    };
    let dif = filter(&maps.diffuse, cfg.diffuse && s.frag.diffuse_en && !bypass);
    let spe = filter(&maps.specular, cfg.specular && s.frag.specular_en && !bypass);
    std::array::from_fn(|ch| {
        let c0 = (s.frag.c_src[ch] as f64 + dif[ch]).min(max);
        let tex = s.frag.tex[ch] as f64 / max;
        match cfg.blend_order {
            BlendOrder::DiffuseTextureSpecular => (c0 * tex + spe[ch]).min(max),
            BlendOrder::TextureLast => (c0 + spe[ch]).min(max) * tex,
        }
    })
}

/// `env_coords`' weights (in u1.8 LSBs) and the pipeline (in colour LSBs, a row per source of
/// `stims`) against exact arithmetic, on the power-up maps.
pub fn embm_errors(cfg: &PipelineConfig, stims: &[(String, TopStim)]) -> Vec<ErrorStats> {
    let mem = crate::units::MemoryContents::new(cfg, cfg.shininess);
    let mut coords = ErrorStats::new("env_coords", "corners + random");
    let mut rows: Vec<ErrorStats> = ["corners", "random"].iter().map(|s| ErrorStats::new("gbump_pipeline", s)).collect();
    for (src, s) in stims {
        let shaded = mem.view().shade(cfg, &s.state, &s.frag);
        let (_, _, w) = exact_weights(cfg, shaded.b, s);
        let one = (1u64 << crate::model::env_map::WEIGHT_FRAC_BITS) as f64;
        for i in 0..4 {
            coords.add(shaded.env.w[i] as f64 - w[i] * one, || format!("{:?}", s.state.env));
        }
        let exact = exact_embm(cfg, &mem.env, s);
        let row = &mut rows[usize::from(src != "corners")];
        for ch in 0..3 {
            row.add(shaded.out[ch] as f64 - exact[ch], || format!("{:?} {:?}", s.frag, s.state.env));
        }
    }
    let mut out = vec![coords];
    out.extend(rows);
    out
}
