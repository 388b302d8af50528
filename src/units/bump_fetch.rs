//! bump_fetch: stored offset-binary bump normal `bump` → signed bump normal B (paper §4.1; Cg §8.1.2's
//! range expansion), an inversion of each component's MSB.

use super::{p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::fixed::Format;
use crate::model::bump_fetch::bump_fetch_rgb;

pub struct BumpFetch;

fn rgb(v: &[i64]) -> [u32; 3] {
    [v[0] as u32, v[1] as u32, v[2] as u32]
}

impl Unit for BumpFetch {
    fn name(&self) -> &'static str {
        "bump_fetch"
    }
    fn source(&self) -> &'static str {
        "paper §4.1; Cg §8.1.2 (range expansion)"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("palette", "false")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        !cfg.palette
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p(
                "bump",
                Dir::In,
                Format::u(cfg.normal_bits, 0),
                3,
                "range-compressed normal (offset binary)",
            ),
            p("b", Dir::Out, cfg.normal_fmt(), 3, "bump normal B"),
        ]
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![bump_fetch_rgb(cfg, rgb(&i[0])).to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        // The expansion is exact: the model is the equation.
        vec![self.eval(cfg, m, i)[0].iter().map(|&x| x as f64).collect()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        // An inversion of each MSB: the output register only.
        crate::units::resources::Resources::regs(3 * cfg.normal_bits)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![
            ("bump_fetch", crate::rtlgen::units_v::bump_fetch(cfg, true)),
            // The serial top reads the held fragment's normal in the cycle of its first light.
            ("bump_fetch_comb", crate::rtlgen::units_v::bump_fetch(cfg, false)),
        ]
    }
    fn exhaustive_count(&self, cfg: &PipelineConfig) -> Option<u64> {
        Some(1u64 << cfg.normal_bits)
    }
    fn exhaustive_input(&self, cfg: &PipelineConfig, i: u64) -> Lanes {
        // Every code on every lane, each lane a different permutation of the codes.
        let nm = (1i64 << cfg.normal_bits) - 1;
        let x = i as i64;
        vec![vec![x, nm - x, x ^ (nm >> 1)]]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let nm = (1i64 << cfg.normal_bits) - 1;
        let half = 1i64 << (cfg.normal_bits - 1);
        vec![
            ("smallest code: -1.0 on every axis".into(), vec![vec![0, 0, 0]]),
            ("largest code: +1 - 2^-(w-1) on every axis".into(), vec![vec![nm; 3]]),
            ("the unperturbed normal".into(), vec![vec![half, half, nm]]),
            ("codes either side of zero".into(), vec![vec![half - 1, half, half + 1]]),
        ]
    }
}
