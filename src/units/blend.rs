//! diffuse_blend and specular_blend: C_out = sat(C_in + Σ_i f_i k_i Lc_i) (paper §4.2, §5.1),
//! one value of one type for both, with f = fd_i or fs_i: the parallel form, all light terms
//! summed in one cycle. The serial top uses the serial form (`serial_blend.rs`).

use super::{p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::blend::blend;

pub struct Blend {
    name: &'static str,
    source: &'static str,
    specular: bool,
}

pub static DIFFUSE_BLEND: Blend = Blend {
    name: "diffuse_blend",
    source: "paper §4.2, §5.1: C' = sat(C_src + sum fd_i k_i Lc_i)",
    specular: false,
};

pub static SPECULAR_BLEND: Blend = Blend {
    name: "specular_blend",
    source: "paper §4.2, §5.1: C_new = sat(C'' + sum fs_i k_i Lc_i)",
    specular: true,
};

fn rgb(v: &[i64]) -> [u32; 3] {
    [v[0] as u32, v[1] as u32, v[2] as u32]
}

/// Each light slot's colour: the `lc` input's, or white when the configuration has no `lc`.
fn light_colours(cfg: &PipelineConfig, i: &[Vec<i64>]) -> Vec<[u32; 3]> {
    (0..cfg.lights as usize)
        .map(|j| {
            if cfg.white_lights {
                [cfg.colour_max(); 3]
            } else {
                rgb(&i[3][3 * j..])
            }
        })
        .collect()
}

impl Unit for Blend {
    fn name(&self) -> &'static str {
        self.name
    }
    fn source(&self) -> &'static str {
        self.source
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![
            (if self.specular { "specular" } else { "diffuse" }, "true"),
            ("light_mode", "\"parallel\""),
        ]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.light_mode == crate::config::LightMode::Parallel && if self.specular { cfg.specular } else { cfg.diffuse }
    }
    fn ports(&self, c: &PipelineConfig) -> Vec<Port> {
        let mut v = vec![
            p(
                "c_in",
                Dir::In,
                c.stage_colour_fmt(),
                3,
                "colour in (R, G, B; colour_guard_bits fraction bits)",
            ),
            p("f", Dir::In, c.factor_fmt(), c.lights, "fd_i or fs_i per light, aligned"),
            p("k", Dir::In, c.k_fmt(), c.lights, "k_i per light"),
        ];
        // White lights: no light colour to multiply by.
        if !c.white_lights {
            v.push(p(
                "lc",
                Dir::In,
                c.colour_fmt(),
                3 * c.lights,
                "light colours Lc_i (R, G, B per light)",
            ));
        }
        v.push(p(
            "c_out",
            Dir::Out,
            c.stage_colour_fmt(),
            3,
            "sat(c_in + round(sum f_i k_i Lc_i)), rounded to c_in's fraction bits",
        ));
        v
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        super::timing::latency(cfg, super::timing::BLEND)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        let lc = light_colours(cfg, i);
        vec![blend(cfg, rgb(&i[0]), &i[1], &i[2], &lc).iter().map(|&x| x as i64).collect()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        let (ff, kf) = (cfg.factor_fmt(), cfg.k_fmt());
        let max = cfg.stage_colour_max() as f64;
        let one = (1u64 << cfg.colour_guard_bits) as f64;
        let lc = light_colours(cfg, i);
        let out = (0..3)
            .map(|ch| {
                let add: f64 = (0..cfg.lights as usize)
                    .map(|j| ff.to_f64(i[1][j]) * kf.to_f64(i[2][j]) * lc[j][ch] as f64)
                    .sum();
                (i[0][ch] as f64 + add * one).min(max)
            })
            .collect();
        vec![out]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{blend_finish, light_term, Resources};
        use crate::units::timing::{cut, BLEND};
        let (n, c, aw) = (cfg.lights, cfg.stage_colour_fmt().width, cfg.acc_fmt().width);
        let lt = crate::rtlgen::units_v::light_term_cuts(cfg);
        light_term(cfg).scaled(n as f64)
            + Resources::regs(lt * 3 * c)
            + Resources::adders(3 * (n - 1) * aw)
            + Resources::stage(cut(cfg, BLEND, 2), 3 * aw + 3 * c)
            + blend_finish(cfg)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        use crate::rtlgen::units_v as v;
        vec![
            (self.name, v::blend(cfg, self.name)),
            ("light_term", v::light_term(cfg)),
            ("blend_finish", v::blend_finish(cfg)),
        ]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let n = cfg.lights as usize;
        let (m, one_f, one_k) = (cfg.colour_max() as i64, 1i64 << cfg.factor_frac(), 1i64 << cfg.k_frac_bits);
        let sm = cfg.stage_colour_max();
        let white = cfg.white_lights;
        let all = |c: i64, f: i64, k: i64, lc: i64| {
            let mut v = vec![vec![c; 3], vec![f; n], vec![k; n]];
            if !white {
                v.push(vec![lc; 3 * n]);
            }
            v
        };
        vec![
            (
                "every light at full strength on white: the sum saturates".into(),
                all(sm, one_f, one_k, m),
            ),
            ("every term zero: c_in passes through".into(), all(sm / 2, 0, one_k, m)),
            ("k = 0 kills every light".into(), all(sm.min(7), one_f, 0, m)),
            ("one LSB terms: the rounding of the smallest sum".into(), all(0, 1, 1, 1)),
            ("half-way sums round by the configured rule".into(), all(0, one_f / 2, one_k, 1)),
            ("half a stage-colour LSB: the rounding at the guard bits' precision".into(), {
                let half = crate::model::blend::sum_shift(cfg) - 1;
                let k_exp = half.min(cfg.k_frac_bits);
                all(1, 1i64 << (half - k_exp), 1i64 << k_exp, 1)
            }),
        ]
    }
}
