//! dot_clamp: f = max(0, B·V) rounded to u1.F and clamped to 1 (paper §4.2: fd_i = B·L_i,
//! and B·H_i, the power unit's input).

use super::{lanes, p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::dot_clamp::dot_clamp;

pub struct DotClamp;

impl Unit for DotClamp {
    fn name(&self) -> &'static str {
        "dot_clamp"
    }
    fn source(&self) -> &'static str {
        "paper §4.2: fd_i = B·L_i, and B·H_i"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("env_map_bits", "0")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        // EMBM's blend factors are the bilinear weights: no dot product.
        !cfg.embm()
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p("b", Dir::In, cfg.normal_fmt(), 3, "bump normal B"),
            p(
                "v",
                Dir::In,
                cfg.lh_fmt(),
                3,
                "L_i or H_i in bump space (the frame's space under frame_transform)",
            ),
            p("f", Dir::Out, cfg.dot_fmt(), 1, "max(0, B·V) rounded, clamped to 1"),
        ]
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        super::timing::latency(cfg, super::timing::DOT_CLAMP)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![vec![dot_clamp(cfg, lanes(&i[0]), lanes(&i[1]))]]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        let (nf, lf) = (cfg.normal_fmt(), cfg.lh_fmt());
        let dot: f64 = (0..3).map(|k| nf.to_f64(i[0][k]) * lf.to_f64(i[1][k])).sum();
        vec![vec![dot.clamp(0.0, 1.0) * (1u64 << cfg.dot_frac_bits) as f64]]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{normal_dot_sum, requant_clamp, Resources};
        use crate::units::timing::{cut, DOT_CLAMP};
        let ex = cfg.dot_exact_fmt();
        normal_dot_sum(cfg, cut(cfg, DOT_CLAMP, 0), cut(cfg, DOT_CLAMP, 1))
            + requant_clamp(ex, cfg.dot_frac_bits, cfg.rounding, cfg.dot_frac_bits + 1)
            + Resources::regs(cfg.dot_frac_bits + 1)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("dot_clamp", crate::rtlgen::units_v::dot_clamp(cfg))]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let (nf, lf) = (cfg.normal_fmt(), cfg.lh_fmt());
        let one = 1i64 << (cfg.lh_bits - 2);
        let flat = cfg.flat_normal().to_vec();
        let ties = crate::model::dot_clamp::rounding_ties(cfg).map(|t| {
            t.map(|(odd, b, v)| {
                let below = if odd == 1 { "even" } else { "odd" };
                (
                    format!("B·V exactly {odd}/2 output LSB: a rounding tie above an {below} code"),
                    vec![b.to_vec(), v.to_vec()],
                )
            })
        });
        let mut v = vec![
            (
                "flat normal, V straight up: the largest dot of a unit normal".into(),
                vec![flat.clone(), vec![0, 0, one]],
            ),
            ("V in the surface plane: exactly 0".into(), vec![flat.clone(), vec![one, 0, 0]]),
            ("V below the horizon: negative, clamps to 0".into(), vec![flat, vec![0, 0, -one]]),
            (
                "most negative codes on both: the largest sum, clamps to 1".into(),
                vec![vec![nf.min_raw(); 3], vec![lf.min_raw(); 3]],
            ),
            (
                "largest codes on both: |V| ≈ 3.46, clamps to 1".into(),
                vec![vec![nf.max_raw(); 3], vec![lf.max_raw(); 3]],
            ),
            (
                "opposite extremes: the most negative sum, clamps to 0".into(),
                vec![vec![nf.min_raw(); 3], vec![lf.max_raw(); 3]],
            ),
        ];
        v.extend(ties.into_iter().flatten());
        v
    }
}
