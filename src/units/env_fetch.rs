//! env_fetch: the four texels of EMBM's bilinear block (paper §3.3) from one of its two
//! environment maps, the diffuse and the specular one (each a loadable memory of its own).

use super::{p, Dir, Lanes, Memories, Memory, Port, Unit};
use crate::config::PipelineConfig;
use crate::fixed::Format;
use crate::model::env_map::env_fetch;

/// One of the two map fetches.
pub struct EnvFetch {
    name: &'static str,
    specular: bool,
}

pub static ENV_FETCH_DIFFUSE: EnvFetch = EnvFetch {
    name: "env_fetch_diffuse",
    specular: false,
};

pub static ENV_FETCH_SPECULAR: EnvFetch = EnvFetch {
    name: "env_fetch_specular",
    specular: true,
};

impl EnvFetch {
    fn map<'m>(&self, m: &'m Memories) -> &'m [[u32; 3]] {
        if self.specular {
            &m.env.specular
        } else {
            &m.env.diffuse
        }
    }
    fn stem(&self) -> &'static str {
        if self.specular {
            "env_specular_default"
        } else {
            "env_diffuse_default"
        }
    }
}

impl Unit for EnvFetch {
    fn name(&self) -> &'static str {
        self.name
    }
    fn source(&self) -> &'static str {
        "paper §3.3 (Direct3D 6 EMBM): the lighting lives in an environment map, read bilinearly"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("env_map_bits", "6"), (if self.specular { "specular" } else { "diffuse" }, "true")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.embm() && if self.specular { cfg.specular } else { cfg.diffuse }
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        let e = Format::u(cfg.env_map_bits, 0);
        vec![
            p("x0", Dir::In, e, 1, "texel column of the block's first texel (at most n - 2)"),
            p("y0", Dir::In, e, 1, "texel row of the block's first texel (at most n - 2)"),
            p(
                "t",
                Dir::Out,
                cfg.colour_fmt(),
                12,
                "texel j, channel c (R, G, B) at lane 3j + c: (x0, y0), (x0+1, y0), (x0, y0+1), (x0+1, y0+1)",
            ),
        ]
    }
    fn memory(&self, cfg: &PipelineConfig) -> Option<Memory> {
        let e = cfg.env_map_bits;
        Some(Memory {
            prefix: if self.specular { "env_specular" } else { "env_diffuse" },
            init_param: if self.specular {
                "ENV_SPECULAR_INIT_FILE"
            } else {
                "ENV_DIFFUSE_INIT_FILE"
            },
            init_stem: self.stem(),
            depth: 1 << (2 * e),
            addr_bits: 2 * e,
            data_bits: 3 * cfg.colour_bits,
            data_frac: 0,
            data_lanes: 3,
            doc: if self.specular {
                "specular map texel (x, y) at address y n + x: {B, G, R}, R in the low bits"
            } else {
                "diffuse map texel (x, y) at address y n + x: {B, G, R}, R in the low bits"
            },
        })
    }
    fn input_max(&self, cfg: &PipelineConfig) -> Vec<(&'static str, i64, &'static str)> {
        let last = cfg.env_map_side() as i64 - 2;
        vec![
            ("x0", last, "n - 2: the block's second column is inside the map"),
            ("y0", last, "n - 2: the block's second row is inside the map"),
        ]
    }
    fn eval(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Lanes {
        let t = env_fetch(cfg.env_map_bits, self.map(m), i[0][0], i[1][0]);
        vec![t.iter().flat_map(|c| c.map(i64::from)).collect()]
    }
    fn exact(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        // A read is exact: the model is the equation.
        vec![self.eval(cfg, m, i)[0].iter().map(|&x| x as f64).collect()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        // Four RAM copies (their read registers included, counted as memory) and the two
        // increments x0 + 1, y0 + 1.
        crate::units::resources::Resources::adders(2 * cfg.env_map_bits)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![
            (self.name, crate::rtlgen::env_v::env_fetch(cfg, self.name, self.stem())),
            (crate::rtlgen::ram::RAM, crate::rtlgen::ram::ram(cfg)),
        ]
    }
    fn exhaustive_count(&self, cfg: &PipelineConfig) -> Option<u64> {
        let b = cfg.env_map_side() as u64 - 1;
        Some(b * b)
    }
    fn exhaustive_input(&self, cfg: &PipelineConfig, i: u64) -> Lanes {
        let b = cfg.env_map_side() as u64 - 1;
        vec![vec![(i % b) as i64], vec![(i / b) as i64]]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let last = cfg.env_map_side() as i64 - 2;
        vec![
            ("the first block: texels (0, 0) to (1, 1)".into(), vec![vec![0], vec![0]]),
            ("the last block: the map's far corner".into(), vec![vec![last], vec![last]]),
            ("last column, first row".into(), vec![vec![last], vec![0]]),
        ]
    }
}
