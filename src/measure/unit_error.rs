//! Error of the fixed-point model against exact arithmetic of the same equations, per unit
//! and for the whole pipeline, in output LSBs: maximum, mean, the worst input, and a
//! histogram. Inputs are the unit's own quantised inputs, so this is the error each
//! narrowing adds; the rows of [`input_errors`] add what quantising the inputs costs (stored
//! normals, sent L and H), and the image error is the whole scene's.

use crate::config::{BlendOrder, PipelineConfig};
use crate::model::blend::blend;
use crate::model::dot_clamp::dot_clamp;
use crate::model::power_table::powi_exact;
use crate::model::texture_modulate::texture_modulate;
use crate::model::{shade, BumpTexel, Palette, PowerTable};
use crate::vectors::rng::SplitMix64;
use crate::vectors::sources::{corners, random_stim};
use crate::vectors::targets::TopStim;
use serde::Serialize;

/// Histogram bin upper edges, in LSBs.
pub const BINS: [f64; 7] = [0.0, 0.5, 1.0, 2.0, 4.0, 8.0, f64::INFINITY];

#[derive(Clone, Debug, Serialize)]
pub struct ErrorStats {
    pub unit: String,
    pub source: String,
    pub samples: u64,
    pub max_lsb: f64,
    pub mean_lsb: f64,
    pub worst_input: String,
    /// Counts per bin of `BINS` (error ≤ edge, above the previous edge).
    pub histogram: Vec<u64>,
}

impl ErrorStats {
    pub(crate) fn new(unit: &str, source: &str) -> ErrorStats {
        ErrorStats {
            unit: unit.into(),
            source: source.into(),
            samples: 0,
            max_lsb: 0.0,
            mean_lsb: 0.0,
            worst_input: String::new(),
            histogram: vec![0; BINS.len()],
        }
    }
    pub(crate) fn add(&mut self, err: f64, input: impl FnOnce() -> String) {
        let e = err.abs();
        self.samples += 1;
        self.mean_lsb += (e - self.mean_lsb) / self.samples as f64;
        if e > self.max_lsb || self.worst_input.is_empty() {
            self.max_lsb = self.max_lsb.max(e);
            self.worst_input = input();
        }
        let bin = BINS.iter().position(|edge| e <= *edge + 1e-12).unwrap_or(BINS.len() - 1);
        self.histogram[bin] += 1;
    }
}

/// The stored normal codes of a bump texel: its own, or the power-up palette's entry (the
/// palette the stimuli of `sources` assume).
fn stored_codes(palette: &Palette, bump: BumpTexel) -> [u32; 3] {
    match bump {
        BumpTexel::Rgb(t) => t,
        BumpTexel::Index(i) => palette.0[i as usize],
    }
}

/// Exact evaluation of the pipeline's equations on a stimulus's quantised inputs: real dot
/// products clamped to [0,1], exact powers, unrounded blends with saturation, exact c·t/max.
pub fn exact_pipeline(cfg: &PipelineConfig, n: u32, palette: &Palette, s: &TopStim) -> [f64; 3] {
    let nf = cfg.normal_fmt();
    let lf = cfg.lh_fmt();
    let max = cfg.colour_max() as f64;
    let t = stored_codes(palette, s.frag.bump);
    let codes = t.map(|c| crate::model::bump_fetch::expand(cfg, c));
    // Under `frame_transform` B is placed in the fragment's frame exactly, clamped to the
    // normal's range as the unit saturates.
    let placed: [f64; 3] = if let Some(fe) = crate::model::frame_build::fragment_frame_exact(cfg, &s.state.frame) {
        // A frame a unit forms (TexRam's, VISA+'s quaternion) formed exactly from the same
        // lanes, then B placed in it.
        let unit = (1u64 << (cfg.lh_bits - 2)) as f64;
        let (lo, hi) = (nf.to_f64(nf.min_raw()), nf.to_f64(nf.max_raw()));
        std::array::from_fn(|c| ((0..3).map(|i| nf.to_f64(codes[i]) * fe[i][c]).sum::<f64>() / unit).clamp(lo, hi))
    } else if cfg.frame_transform {
        crate::model::frame_transform::frame_transform_exact(cfg, codes, &s.state.frame).map(|x| x / (1u64 << nf.frac) as f64)
    } else {
        codes.map(|c| nf.to_f64(c))
    };
    // Renormalised, B enters the dot products at exactly its unit length, as normalise_b's
    // equation says; otherwise as it is.
    let b: Vec<f64> = if cfg.renormalise_bump {
        // Clamped to the format, as the unit saturates: under binary normals +1.0 is one code
        // beyond it, which is the format's, not the arithmetic's, error.
        let shape = crate::model::normalise::Shape::bump(cfg);
        let (f, one) = (shape.fmt(), (1u64 << shape.frac) as f64);
        let len = placed.iter().map(|x| x * x).sum::<f64>().sqrt();
        placed
            .iter()
            .map(|x| match len {
                0.0 => 0.0,
                _ => (x * shape.scale() / len).clamp(f.min_raw() as f64 / one, f.max_raw() as f64 / one),
            })
            .collect()
    } else {
        placed.to_vec()
    };
    let flat = codes == cfg.flat_normal();
    let bypass = cfg.skip_flat && flat;
    let d_on = cfg.diffuse && s.frag.diffuse_en && !bypass;
    let s_on = cfg.specular && s.frag.specular_en && !bypass;
    let (mut dif, mut spe) = ([0.0; 3], [0.0; 3]);
    // A renormalised vector enters the dot product at exactly its unit length (times the
    // normals' scale), as the normalise unit's equation says; the others as their codes.
    let (norm_l, norm_h) = crate::model::normalise::renormalised(cfg);
    let real = |v: [i64; 3], norm: bool| -> [f64; 3] {
        if norm {
            crate::model::normalise::normalise_exact(cfg, v).map(|x| x / (1u64 << lf.frac) as f64)
        } else {
            v.map(|x| lf.to_f64(x))
        }
    };
    for ls in s.state.lights.iter().take(cfg.lights as usize) {
        let dot = |v: [f64; 3]| (0..3).map(|i| b[i] * v[i]).sum::<f64>().clamp(0.0, 1.0);
        let k = cfg.k_fmt().to_f64(ls.k);
        let lc = cfg.light_colour(ls.lc);
        let (l, h) = (real(ls.l, norm_l), real(ls.h, norm_h));
        for ch in 0..3 {
            if d_on {
                dif[ch] += dot(l) * k * lc[ch] as f64;
            }
            if s_on {
                spe[ch] += powi_exact(dot(h), cfg.power_exponent(n)) * k * lc[ch] as f64;
            }
        }
    }
    let mut out = [0.0; 3];
    for ch in 0..3 {
        let c = s.frag.c_src[ch] as f64;
        let tex = s.frag.tex[ch] as f64 / max;
        let c0 = (c + dif[ch]).min(max);
        out[ch] = match cfg.blend_order {
            BlendOrder::DiffuseTextureSpecular => (c0 * tex + spe[ch]).min(max),
            BlendOrder::TextureLast => (c0 + spe[ch]).min(max) * tex,
        };
    }
    out
}

/// Every unit's error and the pipeline's, over corners, `random` random stimuli and
/// exhaustive sweeps where a unit is small enough.
pub fn unit_errors(cfg: &PipelineConfig, random: u64, seed: u64) -> Vec<ErrorStats> {
    if cfg.embm() {
        return super::embm_error::embm_errors(cfg, &stimuli(cfg, random, &mut SplitMix64(seed)));
    }
    let n = cfg.shininess;
    let table = PowerTable::build(cfg, n);
    let palette = crate::rtlgen::rom::default_palette(cfg);
    let mut rng = SplitMix64(seed);
    let stims = stimuli(cfg, random, &mut rng);
    let mut out = Vec::new();
    // dot_clamp over every L and H of every stimulus.
    let mut dot = ErrorStats::new("dot_clamp", "corners + random");
    let nf = cfg.normal_fmt();
    let lf = cfg.lh_fmt();
    let one = (1u64 << cfg.dot_frac_bits) as f64;
    // The normalise units over every vector they scale and their corners, against
    // v·unit/|v|: `normalise` on L and H, `normalise_b` on the fetched bump normal.
    use crate::model::normalise::Shape;
    let (lh_shape, b_shape) = (Shape::lh(cfg), Shape::bump(cfg));
    // Under `cube_map_face` the L and H unit is `normalise_cube`, measured against the
    // direction through the texel's centre (its rounding alone; the map's resolution is the
    // engines' comparison).
    let lh_unit = crate::model::normalise::lh_unit(cfg);
    let mut norm = ErrorStats::new(lh_unit, "corners + random");
    let mut norm_b = ErrorStats::new("normalise_b", "corners + random");
    let mut frame = ErrorStats::new("frame_transform", "corners + random");
    let mut build = ErrorStats::new(if cfg.frame_quaternion { "quat_frame" } else { "frame_build" }, "random");
    let (norm_l, norm_h) = crate::model::normalise::renormalised(cfg);
    let lh_error = |stats: &mut ErrorStats, v: [i64; 3]| {
        normalise_error(
            stats,
            &lh_shape,
            v,
            crate::model::normalise::normalise(cfg, v),
            crate::model::normalise::normalise_exact(cfg, v),
        )
    };
    let b_error = |stats: &mut ErrorStats, v: [i64; 3]| {
        use crate::model::normalise::{normalise_exact_shape, normalise_shape};
        normalise_error(stats, &b_shape, v, normalise_shape(&b_shape, v), normalise_exact_shape(&b_shape, v))
    };
    if let Some(u) = crate::units::unit(lh_unit).filter(|_| cfg.renormalise) {
        for (_, c) in u.corners(cfg) {
            lh_error(&mut norm, [c[0][0], c[0][1], c[0][2]]);
        }
    }
    if let Some(u) = crate::units::unit("normalise_b").filter(|_| cfg.renormalise_bump) {
        for (_, c) in u.corners(cfg) {
            b_error(&mut norm_b, [c[0][0], c[0][1], c[0][2]]);
        }
    }
    for (_, s) in &stims {
        let t = stored_codes(&palette, s.frag.bump);
        let fetched = t.map(|c| crate::model::bump_fetch::expand(cfg, c));
        // normalise_b and dot_clamp see B as the pipeline hands it on: placed in the
        // fragment's frame under `frame_transform`, then renormalised.
        let framed = if cfg.frame_transform {
            let f = &crate::model::frame_build::fragment_frame(cfg, &s.state.frame);
            if let Some(exact) = crate::model::frame_build::fragment_frame_exact(cfg, &s.state.frame) {
                let lanes = s.state.frame;
                for v in 0..3 {
                    for c in 0..3 {
                        build.add(f[v][c] as f64 - exact[v][c], || format!("in_frame={lanes:?}"));
                    }
                }
            }
            let got = crate::model::frame_transform::frame_transform(cfg, fetched, f);
            let exact = crate::model::frame_transform::frame_transform_exact(cfg, fetched, f);
            for c in 0..3 {
                frame.add(got[c] as f64 - exact[c], || format!("B={fetched:?} frame={f:?}"));
            }
            got
        } else {
            fetched
        };
        let b = if cfg.renormalise_bump {
            b_error(&mut norm_b, framed)
        } else {
            framed
        };
        for ls in s.state.lights.iter().take(cfg.lights as usize) {
            if norm_l {
                lh_error(&mut norm, ls.l);
            }
            if norm_h {
                lh_error(&mut norm, ls.h);
            }
            // dot_clamp sees the vectors as the pipeline hands them on.
            let (l, h) = crate::model::pipeline::dot_vectors(cfg, ls);
            for v in [l, h] {
                let exact = (0..3).map(|i| nf.to_f64(b[i]) * lf.to_f64(v[i])).sum::<f64>().clamp(0.0, 1.0) * one;
                dot.add(dot_clamp(cfg, b, v) as f64 - exact, || format!("B={b:?} V={v:?}"));
            }
        }
    }
    if cfg.frame_build || cfg.frame_quaternion {
        out.push(build);
    }
    if cfg.frame_transform {
        out.push(frame);
    }
    if cfg.renormalise_bump {
        out.push(norm_b);
    }
    if cfg.renormalise {
        out.push(norm);
    }
    out.push(dot);
    // power_unit exhaustively over its input.
    let mut pw = ErrorStats::new("power_unit", &format!("exhaustive, n = {n}"));
    let ps = (1u64 << cfg.power_frac_bits) as f64;
    for fd in 0..=(1i64 << cfg.dot_frac_bits) {
        let exact = powi_exact(fd as f64 / one, cfg.power_exponent(n)) * ps;
        pw.add(crate::model::power_unit::power_unit(cfg, &table, fd) as f64 - exact, || {
            format!("x = {fd}/2^{}", cfg.dot_frac_bits)
        });
    }
    out.push(pw);
    // Blends over random inputs in their own formats; every colour-stage error is in output
    // colour LSBs (a stage colour's LSB is 2^-colour_guard_bits of one), so the rows add up.
    let g = cfg.colour_guard_bits;
    let stage_lsb = (1u64 << g) as f64;
    let sm = cfg.stage_colour_max();
    for unit in ["diffuse_blend", "specular_blend"] {
        let mut st = ErrorStats::new(unit, "random");
        let ff = cfg.factor_frac();
        let max = cfg.colour_max() as u64;
        for _ in 0..random {
            let l = cfg.lights as usize;
            let c_in = [0; 3].map(|_| rng.range(0, sm) as u32);
            let f: Vec<i64> = (0..l).map(|_| rng.range(0, 1 << ff)).collect();
            let k: Vec<i64> = (0..l).map(|_| rng.range(0, 1 << cfg.k_frac_bits)).collect();
            let lc: Vec<[u32; 3]> = (0..l).map(|_| [0; 3].map(|_| rng.range(0, max as i64) as u32)).collect();
            let o = blend(cfg, c_in, &f, &k, &lc);
            for ch in 0..3 {
                let add: f64 = (0..l)
                    .map(|i| f[i] as f64 / (1u64 << ff) as f64 * k[i] as f64 / (1u64 << cfg.k_frac_bits) as f64 * lc[i][ch] as f64)
                    .sum();
                let exact = (c_in[ch] as f64 / stage_lsb + add).min(max as f64);
                st.add(o[ch] as f64 / stage_lsb - exact, || {
                    format!("c_in={c_in:?} f={f:?} k={k:?} lc={lc:?}")
                });
            }
        }
        out.push(st);
    }
    // texture_modulate exhaustively where that is at most 2^24 pairs, else at random.
    let max = cfg.colour_max();
    let pairs = (sm as u64 + 1) * (max as u64 + 1);
    let exhaustive = pairs <= 1 << 24;
    let mut tm = ErrorStats::new("texture_modulate", if exhaustive { "exhaustive" } else { "random 2^22" });
    let mut tex_pair = |c: u32, t: u32| {
        let o = texture_modulate(cfg, [c, 0, 0], [t, 0, 0])[0];
        tm.add((o as f64 - c as f64 * t as f64 / max as f64) / stage_lsb, || format!("c={c} t={t}"));
    };
    if exhaustive {
        for c in 0..=sm as u32 {
            for t in 0..=max {
                tex_pair(c, t);
            }
        }
    } else {
        for _ in 0..1u32 << 22 {
            tex_pair(rng.range(0, sm) as u32, rng.range(0, max as i64) as u32);
        }
    }
    out.push(tm);
    if g > 0 {
        let mut cr = ErrorStats::new("colour_round", "exhaustive");
        for c in 0..=sm as u32 {
            let o = crate::model::texture_modulate::colour_round(cfg, [c, 0, 0])[0];
            cr.add(o as f64 - c as f64 / stage_lsb, || format!("c={c}/2^{g}"));
        }
        out.push(cr);
    }
    out.extend(pipeline_rows(cfg, &table, &palette, &stims));
    out.extend(input_errors(cfg, random, seed));
    out
}

/// The stimuli of the error measures, each named by its source: the level-2 corners, then
/// `random` random ones drawn from `rng`.
fn stimuli(cfg: &PipelineConfig, random: u64, rng: &mut SplitMix64) -> Vec<(String, TopStim)> {
    let mut stims: Vec<(String, TopStim)> = corners(cfg, 2).into_iter().map(|(_, s)| ("corners".to_string(), s)).collect();
    stims.extend((0..random).map(|_| ("random".to_string(), random_stim(cfg, rng))));
    stims
}

/// The whole pipeline against exact arithmetic, a row per source of `stims`.
fn pipeline_rows(cfg: &PipelineConfig, table: &PowerTable, palette: &Palette, stims: &[(String, TopStim)]) -> Vec<ErrorStats> {
    ["corners", "random"]
        .into_iter()
        .map(|src| {
            let mut st = ErrorStats::new("gbump_pipeline", src);
            for (_, s) in stims.iter().filter(|(k, _)| k == src) {
                let got = shade(cfg, table, Some(palette), &s.state, &s.frag).colour();
                let exact = exact_pipeline(cfg, cfg.shininess, palette, s);
                for ch in 0..3 {
                    st.add(got[ch] as f64 - exact[ch], || format!("{:?}", s.frag));
                }
            }
            st
        })
        .collect()
}

/// The whole pipeline's largest error against exact arithmetic over the level-2 corners and
/// `random` random stimuli (`gbump error`'s pipeline rows, in colour LSB).
pub fn pipeline_exact_max(cfg: &PipelineConfig, random: u64, seed: u64) -> f64 {
    if cfg.embm() {
        let rows = super::embm_error::embm_errors(cfg, &stimuli(cfg, random, &mut SplitMix64(seed)));
        return rows
            .iter()
            .filter(|r| r.unit == "gbump_pipeline")
            .map(|r| r.max_lsb)
            .fold(0.0, f64::max);
    }
    let table = PowerTable::build(cfg, cfg.shininess);
    let palette = crate::rtlgen::rom::default_palette(cfg);
    pipeline_rows(cfg, &table, &palette, &stimuli(cfg, random, &mut SplitMix64(seed)))
        .iter()
        .map(|r| r.max_lsb)
        .fold(0.0, f64::max)
}

/// A unit vector from `rng`, in the upper half space when `upper` (bump normals face out).
fn unit_vector(rng: &mut SplitMix64, upper: bool) -> glam::DVec3 {
    loop {
        let v = glam::DVec3::new(rng.unit() * 2.0 - 1.0, rng.unit() * 2.0 - 1.0, rng.unit() * 2.0 - 1.0);
        let l = v.length();
        if (0.05..=1.0).contains(&l) && (!upper || v.z >= 0.0) {
            return v / l;
        }
    }
}

/// One normalise unit's error on `v` (of `shape`) against `v·unit/|v|`, clamped to the format
/// as the unit saturates, added to `stats`; the unit's result.
/// One normalise unit's result `got` for `v` against its exact `want`, clamped to the format
/// as the unit saturates.
fn normalise_error(stats: &mut ErrorStats, shape: &crate::model::normalise::Shape, v: [i64; 3], got: [i64; 3], want: [f64; 3]) -> [i64; 3] {
    let f = shape.fmt();
    for i in 0..3 {
        stats.add(got[i] as f64 - want[i].clamp(f.min_raw() as f64, f.max_raw() as f64), || {
            format!("v={v:?}")
        });
    }
    got
}

/// The error of quantising the inputs, apart from the arithmetic: unit bump normals stored as
/// codes (`encode_normal`) and unit L and H as the setup sends them (times
/// `normal_scale`), evaluated exactly, against the same equations on the true vectors. The
/// flat normal under a light straight above is always one sample: under `normal_range =
/// "binary"` its B·L is 127/128 and its highlight (127/128)^n; `"symmetric"` stores +1.0.
pub fn input_errors(cfg: &PipelineConfig, random: u64, seed: u64) -> Vec<ErrorStats> {
    let mut rng = SplitMix64(seed ^ 0x1a9u64);
    let (nf, lf) = (cfg.normal_fmt(), cfg.lh_fmt());
    let one = (1u64 << cfg.dot_frac_bits) as f64;
    let ps = (1u64 << cfg.power_frac_bits) as f64;
    let n = cfg.shininess;
    let source = "input quantisation: unit B, L, H as stored and sent, exact arithmetic, against the true vectors";
    let mut dot = ErrorStats::new("dot_clamp", source);
    let mut pw = ErrorStats::new("power_unit", &format!("{source}, (B·H)^{n}"));
    let samples = std::iter::once((glam::DVec3::Z, glam::DVec3::Z))
        .chain((0..random).map(|_| (unit_vector(&mut rng, true), unit_vector(&mut rng, false))));
    for (bn, v) in samples {
        // As the dot products see it: the stored codes, through normalise_b when it is there.
        let codes = crate::bumpmap::storage::encode_normal(cfg, bn).map(|c| crate::model::bump_fetch::expand(cfg, c));
        let codes = if cfg.renormalise_bump {
            crate::model::normalise::normalise_bump(cfg, codes)
        } else {
            codes
        };
        let b = codes.map(|c| nf.to_f64(c));
        let q = [v.x, v.y, v.z].map(|x| lf.to_f64(crate::raster::tri_state::send_lh(cfg, x).expect("finite")));
        let stored = (0..3).map(|i| b[i] * q[i]).sum::<f64>().clamp(0.0, 1.0);
        let truth = bn.dot(v).clamp(0.0, 1.0);
        let input = || format!("B={bn:?} V={v:?}");
        dot.add((stored - truth) * one, input);
        pw.add((powi_exact(stored, n) - powi_exact(truth, n)) * ps, input);
    }
    vec![dot, pw]
}

/// The 127/128 loss in colour LSBs: the highlight (B·H)^n of the flat normal under H straight
/// above, with B as stored and H as sent, exact arithmetic, against 1 (full colour).
/// `normal_range = "binary"` stores +1.0 as 127/128 (at 8 bits); `"symmetric"` as +1.0.
pub fn flat_highlight_loss(cfg: &PipelineConfig) -> f64 {
    let b = crate::bumpmap::storage::encode_normal(cfg, glam::DVec3::Z)
        .map(|c| cfg.normal_fmt().to_f64(crate::model::bump_fetch::expand(cfg, c)));
    let h = cfg.lh_fmt().to_f64(crate::raster::tri_state::send_lh(cfg, 1.0).expect("finite"));
    (1.0 - powi_exact((b[2] * h).clamp(0.0, 1.0), cfg.shininess)) * cfg.colour_max() as f64
}

/// Markdown table of unit errors.
pub fn markdown(cfg: &PipelineConfig, stats: &[ErrorStats]) -> String {
    let mut s = format!("Error against exact arithmetic, config `{}` (LSBs of each unit's output format; the colour stages in LSBs of the output colour; samples are outputs compared, one per channel and light of each random stimulus)\n\n| unit | source | samples | max | mean | 0 | ≤½ | ≤1 | ≤2 | ≤4 | ≤8 | >8 |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n", cfg.hash());
    for e in stats {
        let h: Vec<String> = e.histogram.iter().map(|x| x.to_string()).collect();
        s += &format!(
            "| {} | {} | {} | {:.3} | {:.4} | {} |\n",
            e.unit,
            e.source,
            e.samples,
            e.max_lsb,
            e.mean_lsb,
            h.join(" | ")
        );
    }
    s += "\nWorst inputs:\n\n";
    for e in stats {
        s += &format!("- {} ({}): {:.3} LSB at {}\n", e.unit, e.source, e.max_lsb, e.worst_input);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The README's bound: with g guard bits each colour stage errs by at most 2^-(g+1) of an
    /// output LSB when it rounds to nearest (2^-g when the blends truncate; the texture always
    /// rounds to nearest), and colour_round by at most half an LSB (1 - 2^-g truncating), for
    /// every g the configuration allows, every rounding and both blend orders.
    #[test]
    fn each_colour_stage_errs_by_at_most_half_a_stage_lsb() {
        use crate::fixed::Rounding;
        let (_, hi) = crate::config::limit("colour_guard_bits");
        for g in 0..=hi {
            for rounding in [Rounding::HalfUp, Rounding::NearestEven, Rounding::Truncate] {
                for blend_order in [BlendOrder::DiffuseTextureSpecular, BlendOrder::TextureLast] {
                    let cfg = PipelineConfig {
                        colour_guard_bits: g,
                        colour_bits: 6,
                        rounding,
                        blend_order,
                        ..Default::default()
                    };
                    let lsb = 1.0 / (1u64 << g) as f64;
                    let truncating = rounding == Rounding::Truncate;
                    let bound = |unit: &str| match unit {
                        "colour_round" if truncating => 1.0 - lsb,
                        "colour_round" => 0.5,
                        "texture_modulate" => lsb / 2.0,
                        _ if truncating => lsb,
                        _ => lsb / 2.0,
                    };
                    let rows = unit_errors(&cfg, 1000, 3);
                    let mut seen = 0;
                    for r in rows.iter().filter(|r| {
                        ["diffuse_blend", "specular_blend", "texture_modulate", "colour_round"].contains(&r.unit.as_str())
                            && !r.source.starts_with("input")
                    }) {
                        seen += 1;
                        assert!(
                            r.max_lsb <= bound(&r.unit) + 1e-9,
                            "g={g} {rounding:?}: {} errs {} > {}",
                            r.unit,
                            r.max_lsb,
                            bound(&r.unit)
                        );
                    }
                    assert_eq!(seen, if g == 0 { 3 } else { 4 }, "g={g}: the colour rows");
                }
            }
        }
    }
}
