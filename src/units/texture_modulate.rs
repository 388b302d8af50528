//! texture_modulate: round(C·T / (2^w - 1)) per channel (paper §5.1: the texture stage between
//! or after the blends).

use super::{p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::texture_modulate::texture_modulate;

pub struct TextureModulate;

fn rgb(v: &[i64]) -> [u32; 3] {
    [v[0] as u32, v[1] as u32, v[2] as u32]
}

impl Unit for TextureModulate {
    fn name(&self) -> &'static str {
        "texture_modulate"
    }
    fn source(&self) -> &'static str {
        "paper §5.1: the texture stage between the blends"
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p(
                "c_in",
                Dir::In,
                cfg.stage_colour_fmt(),
                3,
                "colour in (colour_guard_bits fraction bits)",
            ),
            p("tex", Dir::In, cfg.colour_fmt(), 3, "texture colour T"),
            p(
                "c_out",
                Dir::Out,
                cfg.stage_colour_fmt(),
                3,
                "round(c_in tex / max), in c_in's units",
            ),
        ]
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        super::timing::latency(cfg, super::timing::TEXTURE)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![texture_modulate(cfg, rgb(&i[0]), rgb(&i[1])).iter().map(|&x| x as i64).collect()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        let max = cfg.colour_max() as f64;
        vec![(0..3).map(|k| i[0][k] as f64 * i[1][k] as f64 / max).collect()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{sum_of_products, unsigned, Resources};
        use crate::units::timing::{cut, TEXTURE};
        let c = cfg.colour_bits;
        if cfg.colour_guard_bits == 0 {
            let w = 2 * c + 1;
            // Per channel: c·t + 2^(c-1), its register when cut, q = p + (p >> c), the output register.
            let channel = sum_of_products(cfg.multipliers, &[(unsigned(c), unsigned(c))], true, w)
                + Resources::stage(cut(cfg, TEXTURE, 0), w)
                + Resources::adders(w)
                + Resources::regs(c);
            return channel.scaled(3.0);
        }
        // Per channel: c·t + (d-1)/2, its register when cut, the constant reciprocal's shifted
        // adds (one per set bit after the first), the output register.
        let cs = cfg.stage_colour_fmt().width;
        let u = crate::model::texture_modulate::divider(cfg);
        let qw = u.y_bits + u.m_bits().last().copied().unwrap_or(0) + 1;
        let channel = sum_of_products(cfg.multipliers, &[(unsigned(cs), unsigned(c))], true, u.y_bits)
            + Resources::stage(cut(cfg, TEXTURE, 0), u.y_bits)
            + Resources::adders(qw * (u.m_bits().len() as u32 - 1))
            + Resources::regs(cs);
        channel.scaled(3.0)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("texture_modulate", crate::rtlgen::units_v::texture_modulate(cfg))]
    }
    fn exhaustive_count(&self, cfg: &PipelineConfig) -> Option<u64> {
        Some((cfg.stage_colour_max() as u64 + 1) * (cfg.colour_max() as u64 + 1))
    }
    fn exhaustive_input(&self, cfg: &PipelineConfig, i: u64) -> Lanes {
        // Every (c_in, tex) pair on lane 0; lanes 1 and 2 see the pair mirrored and swapped.
        let (sm, m) = (cfg.stage_colour_max(), cfg.colour_max() as i64);
        let (a, b) = ((i / (m as u64 + 1)) as i64, (i % (m as u64 + 1)) as i64);
        vec![vec![a, b, sm - a], vec![b, a % (m + 1), m - b]]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let (sm, m) = (cfg.stage_colour_max(), cfg.colour_max() as i64);
        vec![
            (
                "white texture colour T passes the colour through".into(),
                vec![vec![0, sm / 2, sm], vec![m; 3]],
            ),
            ("black texture colour T gives black".into(), vec![vec![0, sm / 2, sm], vec![0; 3]]),
            (
                "half-way products round to nearest".into(),
                vec![vec![m / 2, m / 2 + 1, 1], vec![m / 2 + 1, m / 2, m]],
            ),
            (
                "the largest product: full colour on white, the divider's widest input".into(),
                vec![vec![sm, sm - 1, sm / 2 + 1], vec![m, m, m]],
            ),
        ]
    }
}
