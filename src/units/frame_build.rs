//! frame_build: TexRam's frame built per fragment (paper §3.1; `model::frame_build` holds
//! the arithmetic) from the main direction m and the interpolated normal N_i that enter on
//! `in_frame`'s T and N lanes. Present with `frame_build = true`, one instance before
//! `frame_transform`, beside the fetch.

use super::{lanes, p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::frame_build::{frame_build, frame_build_exact};
use crate::model::normalise::Shape;
use crate::units::timing::{latency, NORMALISE};

pub struct FrameBuild;

impl Unit for FrameBuild {
    fn name(&self) -> &'static str {
        "frame_build"
    }
    fn source(&self) -> &'static str {
        "paper §3.1 (TexRam): the frame built per pixel from the interpolated normal and a main direction, N = N_i/|N_i|, e1 = m×N/|m×N|, e2 = N×e1 (T = e2, B = −e1)"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("frame_build", "true"), ("frame_transform", "true"), ("bump_state", "\"fragment\"")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.frame_build
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p(
                "m",
                Dir::In,
                cfg.lh_fmt(),
                3,
                "the main direction m (in_frame's T lanes), under 2 long (N × m is clamped per component to the format)",
            ),
            p(
                "n_i",
                Dir::In,
                cfg.lh_fmt(),
                3,
                "the interpolated normal N_i (in_frame's N lanes), any length",
            ),
            p(
                "frame",
                Dir::Out,
                cfg.lh_fmt(),
                9,
                "T, B, N at unit length, vector v's component c at lane 3v + c (zero axes where m is along N)",
            ),
        ]
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        2 * latency(cfg, NORMALISE) + 2
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![frame_build(cfg, lanes(&i[0]), lanes(&i[1])).concat()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        vec![frame_build_exact(cfg, lanes(&i[0]), lanes(&i[1])).concat()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{requant_clamp, signed, sum_of_products, Resources};
        let lh = cfg.lh_bits;
        let ex = crate::model::frame_build::cross_exact_fmt(cfg);
        let ln = latency(cfg, NORMALISE);
        // As `rtlgen::frame_build_v` builds it: per cross product component two products,
        // their difference, the rounding and clamp.
        let one = sum_of_products(cfg.multipliers, &[(signed(lh), signed(lh))], false, ex.width).scaled(2.0)
            + Resources::adders(ex.width)
            + requant_clamp(ex, lh - 2, cfg.rounding, lh);
        super::normalise::resources(cfg, &Shape::frame(cfg)).scaled(2.0)
            + one.scaled(6.0)
            // m waits ln cycles, N 1 + ln; the first cross product's register; the output.
            + Resources::regs(3 * lh * (2 * ln + 1))
            + Resources::regs(3 * lh)
            + Resources::regs(9 * lh)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        use crate::rtlgen::frame_build_v::{frame_build, NORMALISE};
        vec![
            ("frame_build", frame_build(cfg)),
            (NORMALISE, crate::rtlgen::normalise_v::normalise(cfg, &Shape::frame(cfg), NORMALISE)),
        ]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let f = cfg.lh_fmt();
        let (lo, hi) = (f.min_raw(), f.max_raw());
        let one = 1i64 << (cfg.lh_bits - 2);
        let short = |x: i64| x * 7 / 10;
        vec![
            (
                "m along x, N along z, both shortened: the identity frame".into(),
                vec![vec![short(one), 0, 0], vec![0, 0, short(one)]],
            ),
            (
                "m leaning towards N: T is its part perpendicular to N".into(),
                vec![vec![one / 2, 0, one / 2], vec![0, 0, one]],
            ),
            (
                "a turned frame: m along z, N along x".into(),
                vec![vec![0, 0, one], vec![one, 0, 0]],
            ),
            ("m along N: zero T and B".into(), vec![vec![0, 0, one], vec![0, 0, hi]]),
            ("a zero N: a zero frame".into(), vec![vec![one, 0, 0], vec![0; 3]]),
            ("a zero m: zero T and B".into(), vec![vec![0; 3], vec![0, one, 0]]),
            (
                "the longest inputs: N × m beyond the format's range, clamped".into(),
                vec![vec![lo, hi, lo], vec![hi, lo, lo]],
            ),
            (
                "the shortest inputs: the normalisers' largest shifts".into(),
                vec![vec![1, 0, 0], vec![0, 0, -1]],
            ),
            (
                "the most negative codes on both: m along N again".into(),
                vec![vec![lo; 3], vec![lo; 3]],
            ),
        ]
    }
}
