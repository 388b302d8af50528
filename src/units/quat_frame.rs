//! quat_frame: VISA+'s frame from an interpolated vertex quaternion (paper §3.2 and its [5];
//! `model::quat_frame` holds the arithmetic), which enters on `in_frame`'s lanes 0 to 3.
//! Present with `frame_quaternion = true`, one instance before `frame_transform`, beside the
//! fetch.

use super::{lanes, p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::quat_frame::{entry_exact_fmt, quat_frame, quat_frame_exact};
use crate::units::timing::{cut, latency, QUAT_FRAME};

pub struct QuatFrame;

impl Unit for QuatFrame {
    fn name(&self) -> &'static str {
        "quat_frame"
    }
    fn source(&self) -> &'static str {
        "paper §3.2 and its [5] (VISA+ with quaternions): the frame as the rotation of an interpolated vertex quaternion, in the homogeneous form |q|² R(q/|q|)"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![
            ("frame_quaternion", "true"),
            ("frame_transform", "true"),
            ("bump_state", "\"fragment\""),
        ]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.frame_quaternion
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p(
                "q",
                Dir::In,
                cfg.lh_fmt(),
                4,
                "the quaternion w, x, y, z (in_frame's lanes 0 to 3), any length",
            ),
            p(
                "n_i",
                Dir::In,
                cfg.lh_fmt(),
                3,
                "the interpolated normal N_i (in_frame's lanes 6 to 8)",
            ),
            p(
                "frame",
                Dir::Out,
                cfg.lh_fmt(),
                9,
                "T and B of the rotation and N_i, each times |q|², vector v's component c at lane 3v + c",
            ),
        ]
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        latency(cfg, QUAT_FRAME)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![quat_frame(cfg, lanes(&i[0]), lanes(&i[1])).concat()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        vec![quat_frame_exact(cfg, lanes(&i[0]), lanes(&i[1])).concat()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::model::quat_frame::{length2_fmt, scaled_exact_fmt};
        use crate::units::resources::{requant_clamp, signed, sum_of_products, Resources};
        let lh = cfg.lh_bits;
        let (ex, l2) = (entry_exact_fmt(cfg), length2_fmt(cfg));
        // As `rtlgen::quat_frame_v` builds it: ten products and N_i (registered at the cut);
        // T's and B's diagonal entries three additions each, the others one, each entry
        // rounded and clamped; |q|² three additions and a rounding, its three products with
        // N_i each rounded and clamped; the output register.
        sum_of_products(cfg.multipliers, &[(signed(lh), signed(lh))], false, 2 * lh).scaled(10.0)
            + Resources::stage(cut(cfg, QUAT_FRAME, 0), 10 * 2 * lh + 3 * lh)
            + Resources::adders(ex.width).scaled(2.0 * 3.0 + 4.0 + 3.0)
            + requant_clamp(ex, lh - 2, cfg.rounding, lh).scaled(6.0)
            + requant_clamp(ex, l2.frac, cfg.rounding, l2.width)
            + (sum_of_products(
                cfg.multipliers,
                &[(signed(l2.width), signed(lh))],
                false,
                scaled_exact_fmt(cfg).width,
            ) + requant_clamp(scaled_exact_fmt(cfg), lh - 2, cfg.rounding, lh))
            .scaled(3.0)
            + Resources::regs(9 * lh)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("quat_frame", crate::rtlgen::quat_frame_v::quat_frame(cfg))]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let f = cfg.lh_fmt();
        let (lo, hi) = (f.min_raw(), f.max_raw());
        let one = 1i64 << (cfg.lh_bits - 2);
        let h = (one as f64 * 0.7 / 2f64.sqrt()).round() as i64;
        let z = vec![0, 0, one];
        vec![
            (
                "the identity quaternion: the identity frame".into(),
                vec![vec![one, 0, 0, 0], z.clone()],
            ),
            ("its negation: the same rotation".into(), vec![vec![-one, 0, 0, 0], z.clone()]),
            ("180 degrees about x: B turned over".into(), vec![vec![0, one, 0, 0], z.clone()]),
            (
                "90 degrees about z at 70 % length: T = y, B = -x, N, times 0.49".into(),
                vec![vec![h, 0, 0, h], z.clone()],
            ),
            ("a zero quaternion: a zero frame".into(), vec![vec![0; 4], z]),
            (
                "the most negative codes: every sum at its largest, |q|^2 = 16, clamped".into(),
                vec![vec![lo; 4], vec![lo; 3]],
            ),
            (
                "mixed extremes: the largest differences".into(),
                vec![vec![hi, lo, hi, lo], vec![hi, lo, hi]],
            ),
        ]
    }
}
