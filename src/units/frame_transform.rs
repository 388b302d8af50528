//! frame_transform: the fetched bump normal placed in the frame that enters with the
//! fragment (Harmony, paper §3.5; `model::frame_transform` holds the arithmetic). Present
//! with `frame_transform = true`, one instance between the fetch and `normalise_b` (or the
//! dot products).

use super::{p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::frame_transform::{frame_transform, frame_transform_exact, Frame};
use crate::units::timing::{cut, FRAME_TRANSFORM};

pub struct FrameTransform;

fn frame_of(lanes: &[i64]) -> Frame {
    std::array::from_fn(|i| std::array::from_fn(|c| lanes[3 * i + c]))
}

impl Unit for FrameTransform {
    fn name(&self) -> &'static str {
        "frame_transform"
    }
    fn source(&self) -> &'static str {
        "paper §3.5 (Harmony): the bump normal placed in the interpolated per-vertex frame, T b_x + B b_y + N b_z (a 3x3 transform)"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("frame_transform", "true"), ("bump_state", "\"fragment\"")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.frame_transform
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p("b", Dir::In, cfg.normal_fmt(), 3, "the fetched bump normal B"),
            p(
                "frame",
                Dir::In,
                cfg.lh_fmt(),
                9,
                "the fragment's frame: T, B, N, vector v's component c at lane 3v + c",
            ),
            p(
                "v",
                Dir::Out,
                cfg.normal_fmt(),
                3,
                "T b_x + B b_y + N b_z, rounded, clamped to the normal's range",
            ),
        ]
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        crate::units::timing::latency(cfg, FRAME_TRANSFORM)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![frame_transform(cfg, [i[0][0], i[0][1], i[0][2]], &frame_of(&i[1])).to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        vec![frame_transform_exact(cfg, [i[0][0], i[0][1], i[0][2]], &frame_of(&i[1])).to_vec()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{normal_dot_sum, requant_clamp, Resources};
        let ex = cfg.dot_exact_fmt();
        // As `rtlgen::frame_transform_v` builds it, per component: a dot_clamp's sum of
        // three products, the rounding and clamp, the output register.
        let one = normal_dot_sum(cfg, cut(cfg, FRAME_TRANSFORM, 0), cut(cfg, FRAME_TRANSFORM, 1))
            + requant_clamp(ex, cfg.normal_bits - 1, cfg.rounding, cfg.normal_bits)
            + Resources::regs(cfg.normal_bits);
        one.scaled(3.0)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("frame_transform", crate::rtlgen::frame_transform_v::frame_transform(cfg))]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let (nf, lf) = (cfg.normal_fmt(), cfg.lh_fmt());
        let one = 1i64 << (cfg.lh_bits - 2);
        let flat = cfg.flat_normal().to_vec();
        let id = vec![one, 0, 0, 0, one, 0, 0, 0, one];
        // A tilted normal in the format's own codes (every normal width).
        let hi = nf.max_raw();
        let tilted = vec![hi / 3, -(hi / 2), hi];
        vec![
            (
                "the identity frame: the normal unchanged".into(),
                vec![vec![nf.min_raw(), 1, nf.max_raw()], id.clone()],
            ),
            (
                "a flat normal in a turned frame: N itself".into(),
                vec![flat.clone(), vec![0, one, 0, 0, 0, one, one, 0, 0]],
            ),
            (
                "a mirrored frame (B = -y): the y component negated".into(),
                vec![tilted, vec![one, 0, 0, 0, -one, 0, 0, 0, one]],
            ),
            (
                "an interpolated frame at 70 % length: the normal shortened".into(),
                vec![flat.clone(), id.iter().map(|&x| x * 7 / 10).collect()],
            ),
            (
                "the most negative codes on both: the largest sum, clamps high".into(),
                vec![vec![nf.min_raw(); 3], vec![lf.min_raw(); 9]],
            ),
            (
                "opposite extremes: the most negative sum, clamps low".into(),
                vec![vec![nf.min_raw(); 3], vec![lf.max_raw(); 9]],
            ),
            ("a zero frame: zero".into(), vec![flat, vec![0; 9]]),
        ]
    }
}
