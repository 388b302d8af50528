//! colour_round: the last stage colour, which keeps `colour_guard_bits` fraction bits between
//! the colour stages, rounded once to the output colour code. Present only with guard bits:
//! without them every stage already ends at colour codes (the paper's units).

use super::{p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::texture_modulate::colour_round;

pub struct ColourRound;

impl Unit for ColourRound {
    fn name(&self) -> &'static str {
        "colour_round"
    }
    fn source(&self) -> &'static str {
        "guard bits between the colour stages of paper §5.1, rounded once at the end"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("colour_guard_bits", "1")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.colour_guard_bits > 0
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p(
                "c_in",
                Dir::In,
                cfg.stage_colour_fmt(),
                3,
                "the last stage's colour (colour_guard_bits fraction bits)",
            ),
            p(
                "c_out",
                Dir::Out,
                cfg.colour_fmt(),
                3,
                "c_in rounded to colour codes by the configured rule",
            ),
        ]
    }
    fn input_max(&self, cfg: &PipelineConfig) -> Vec<(&'static str, i64, &'static str)> {
        vec![("c_in", cfg.stage_colour_max(), "full scale: a stage colour saturates there")]
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        let c = [i[0][0] as u32, i[0][1] as u32, i[0][2] as u32];
        vec![colour_round(cfg, c).iter().map(|&x| x as i64).collect()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        let f = cfg.stage_colour_fmt();
        vec![i[0].iter().map(|&x| f.to_f64(x)).collect()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::Resources;
        let cs = cfg.stage_colour_fmt().width;
        let add = if cfg.rounding == crate::fixed::Rounding::Truncate {
            Resources::default()
        } else {
            Resources::adders(cs)
        };
        (add + Resources::regs(cfg.colour_bits)).scaled(3.0)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("colour_round", crate::rtlgen::units_v::colour_round(cfg))]
    }
    fn exhaustive_count(&self, cfg: &PipelineConfig) -> Option<u64> {
        Some(cfg.stage_colour_max() as u64 + 1)
    }
    fn exhaustive_input(&self, cfg: &PipelineConfig, i: u64) -> Lanes {
        let sm = cfg.stage_colour_max();
        let x = i as i64;
        vec![vec![x, sm - x, (x * 7) % (sm + 1)]]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let sm = cfg.stage_colour_max();
        let half = 1i64 << (cfg.colour_guard_bits - 1);
        vec![
            ("1.0 stays the largest code".into(), vec![vec![sm, 0, sm - 1]]),
            (
                "exact halves: the rounding rule (odd and even codes)".into(),
                vec![vec![half, 3 * half, sm - half]],
            ),
        ]
    }
}
