//! The hardware units. A unit is one value (a [`Unit`]) that carries everything about it:
//! its ports and their formats under a configuration, latency and initiation interval,
//! whether the configuration includes it, its memory (if it has one), the bit-accurate model,
//! the exact f64 version of the same equation, its Verilog, its exhaustive input domain and
//! its corner cases with their reasons. The model pipeline's per-unit checks, the top
//! emitter, the interface JSON, the vector layouts, the testbenches, the error meter and the
//! README tables all read it; nothing else restates a port, a width or a latency.
//!
//! A new unit is one file here and one line in [`UNITS`]; the pipeline description
//! (`rtlgen::pipeline`) says where it sits.

mod blend;
mod bump_fetch;
mod colour_round;
mod dot_clamp;
mod env_coords;
mod env_fetch;
mod frame_build;
mod frame_transform;
mod normalise;
mod normalise_cube;
mod palette_fetch;
mod power_unit;
mod quat_frame;
pub mod resources;
mod serial_blend;
mod texture_modulate;
pub mod timing;

use crate::config::PipelineConfig;
use crate::fixed::Format;
use crate::model::env_map::EnvMaps;
use crate::model::{Palette, PowerTable};

pub use blend::{DIFFUSE_BLEND, SPECULAR_BLEND};
pub use palette_fetch::PALETTE_ENTRIES;
pub use power_unit::{table_memory, POWER_TABLE};
pub use serial_blend::{accumulate, finish};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dir {
    In,
    Out,
}

/// One port of a unit: `lanes` values of format `fmt` (e.g. 3 for a vector, 3·n for colours of n lights).
#[derive(Clone, Debug, PartialEq)]
pub struct Port {
    pub name: &'static str,
    pub dir: Dir,
    pub fmt: Format,
    pub lanes: u32,
    pub doc: &'static str,
    /// An input sampled this many rising edges after the edge that samples its record's other
    /// inputs (0 for nearly every port): `light_accumulate`'s `acc_in`, the running sum fed
    /// back into its last stage, enters `latency - 1` edges late. A unit's vectors name it
    /// per column (`enters`), so a testbench that streams records one per edge skews it.
    pub enters: u32,
}

impl Port {
    pub fn bits(&self) -> u32 {
        self.fmt.width * self.lanes
    }

    /// This port sampled `edges` edges after its record's other inputs.
    pub fn entering(self, edges: u32) -> Port {
        Port { enters: edges, ..self }
    }
}

pub(crate) fn p(name: &'static str, dir: Dir, fmt: Format, lanes: u32, doc: &'static str) -> Port {
    Port {
        name,
        dir,
        fmt,
        lanes,
        doc,
        enters: 0,
    }
}

/// A loadable memory inside a unit: written through `<prefix>_we/_waddr/_wdata` on the top
/// (`we/waddr/wdata` on the unit), powered up from the `$readmemh` file its `init` parameter
/// names.
#[derive(Clone, Debug, PartialEq)]
pub struct Memory {
    /// Prefix of the top's load ports (`pt`, `pal`).
    pub prefix: &'static str,
    /// Name of the top's parameter holding the init file.
    pub init_param: &'static str,
    /// Stem of the init file's name (`rom_file_name(cfg, stem, "hex")`).
    pub init_stem: &'static str,
    pub depth: u32,
    pub addr_bits: u32,
    pub data_bits: u32,
    /// Fraction bits of a word (the power table's entries are u1.P; colours are integers).
    pub data_frac: u32,
    /// Fields of a word, each `data_bits / data_lanes` wide, the first in the low bits (a
    /// palette entry's x, y, z; a map texel's R, G, B): the load port's data lanes.
    pub data_lanes: u32,
    pub doc: &'static str,
}

/// The contents of every memory a unit may read, for the model.
#[derive(Clone, Copy)]
pub struct Memories<'a> {
    pub table: &'a PowerTable,
    pub palette: &'a Palette,
    /// EMBM's two environment maps (empty without EMBM).
    pub env: &'a EnvMaps,
}

impl Memories<'_> {
    /// Shade one fragment of `cfg` with these memories (the pipeline model, EMBM's included).
    pub fn shade(&self, cfg: &PipelineConfig, state: &crate::model::BumpState, frag: &crate::model::FragmentIn) -> crate::model::Shaded {
        if cfg.embm() {
            crate::model::pipeline::shade_embm(cfg, self.env, state, frag)
        } else {
            crate::model::shade(cfg, self.table, Some(self.palette), state, frag)
        }
    }
}

/// Owned memory contents: the power table for one shininess, the palette and the
/// environment maps the top powers up with (the default spiral; the default maps).
pub struct MemoryContents {
    pub table: PowerTable,
    pub palette: Palette,
    pub env: EnvMaps,
}

impl MemoryContents {
    pub fn new(cfg: &PipelineConfig, shininess: u32) -> MemoryContents {
        MemoryContents {
            table: PowerTable::build(cfg, shininess),
            palette: crate::rtlgen::rom::default_palette(cfg),
            env: crate::model::env_map::default_maps(cfg),
        }
    }

    /// These contents with `env` in place of the power-up maps, where a set has its own (an
    /// EMBM scene object's).
    pub fn with_env(mut self, env: Option<&crate::model::env_map::EnvMaps>) -> MemoryContents {
        if let Some(e) = env {
            self.env = e.clone();
        }
        self
    }

    pub fn view(&self) -> Memories<'_> {
        Memories {
            table: &self.table,
            palette: &self.palette,
            env: &self.env,
        }
    }
}

/// Every input port's lanes (raw codes), in port order.
pub type Lanes = Vec<Vec<i64>>;

/// The first `N` lanes of one port, as an array (a vector's components, a quaternion's).
pub(crate) fn lanes<const N: usize>(port: &[i64]) -> [i64; N] {
    std::array::from_fn(|k| port[k])
}

/// A hardware unit.
pub trait Unit: Sync {
    fn name(&self) -> &'static str;
    /// Where the paper (or the Cg tutorial) defines it.
    fn source(&self) -> &'static str;
    /// The configuration settings (field, value) that include the unit; all must hold.
    fn requires(&self, _cfg: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        Vec::new()
    }
    fn included(&self, _cfg: &PipelineConfig) -> bool {
        true
    }
    /// Data ports (the clock and a memory's load port are implied).
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port>;
    /// Rising edges from the input to the registered output.
    fn latency(&self, _cfg: &PipelineConfig) -> u32 {
        1
    }
    /// Clock cycles between two inputs.
    fn interval(&self, _cfg: &PipelineConfig) -> u32 {
        1
    }
    fn memory(&self, _cfg: &PipelineConfig) -> Option<Memory> {
        None
    }
    /// Input ports whose values the unit's domain bounds below their format's largest code,
    /// as (port, largest raw value, what it is): a clamped dot product is at most 1.0, a stage
    /// colour at most full scale, a texel block starts at most at n − 2. Every stimulus the
    /// pipeline makes is inside; [`check_domain`] refuses one from outside (a hand-made
    /// record) instead of evaluating it.
    fn input_max(&self, _cfg: &PipelineConfig) -> Vec<(&'static str, i64, &'static str)> {
        Vec::new()
    }
    /// Bit-accurate model: output lanes (raw codes) for input lanes, in port order.
    fn eval(&self, cfg: &PipelineConfig, mem: &Memories, inputs: &[Vec<i64>]) -> Lanes;
    /// The same equation in f64, without the unit's roundings, in the output formats' LSBs.
    fn exact(&self, cfg: &PipelineConfig, mem: &Memories, inputs: &[Vec<i64>]) -> Vec<Vec<f64>>;
    /// The Verilog modules (base name, text without the generated-file header): the unit's
    /// own module first, then the helpers it instantiates (two units may share a helper).
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)>;
    /// What the unit's own module is built of under `cfg` (one read port of a unit with
    /// several), counted from its widths as its Verilog emitter builds it.
    fn resources(&self, cfg: &PipelineConfig) -> resources::Resources;
    /// How many inputs `exhaustive:<unit>` sweeps, or None when the domain is too large.
    fn exhaustive_count(&self, _cfg: &PipelineConfig) -> Option<u64> {
        None
    }
    /// When the unit has an exhaustive sweep, for a unit whose domain is too large under some
    /// configurations (the refusal names it, with the fix).
    fn exhaustive_when(&self) -> Option<&'static str> {
        None
    }
    /// The `i`-th input of the exhaustive sweep (`i < exhaustive_count`).
    fn exhaustive_input(&self, _cfg: &PipelineConfig, _i: u64) -> Lanes {
        unreachable!("{} has no exhaustive domain", self.name())
    }
    /// Inputs at the unit's own edges, each with the reason it is there.
    fn corners(&self, _cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        Vec::new()
    }
}

/// Every unit, in data-flow order.
pub static UNITS: &[&dyn Unit] = &[
    &bump_fetch::BumpFetch,
    &palette_fetch::PaletteFetch,
    &normalise::NORMALISE,
    &normalise_cube::NormaliseCube,
    &frame_build::FrameBuild,
    &quat_frame::QuatFrame,
    &frame_transform::FrameTransform,
    &normalise::NORMALISE_B,
    &env_coords::EnvCoords,
    &env_fetch::ENV_FETCH_DIFFUSE,
    &env_fetch::ENV_FETCH_SPECULAR,
    &dot_clamp::DotClamp,
    &power_unit::PowerUnit,
    &DIFFUSE_BLEND,
    &serial_blend::LightAccumulate,
    &serial_blend::BlendFinish,
    &texture_modulate::TextureModulate,
    &SPECULAR_BLEND,
    &colour_round::ColourRound,
];

/// Look a unit up by name.
pub fn unit(name: &str) -> Option<&'static dyn Unit> {
    UNITS.iter().copied().find(|u| u.name() == name)
}

/// Units `cfg` includes, in data-flow order.
pub fn included(cfg: &PipelineConfig) -> Vec<&'static dyn Unit> {
    UNITS.iter().copied().filter(|u| u.included(cfg)).collect()
}

/// Why `cfg` has no `u`, and the fix, for refusals that name a unit: each unmet setting with
/// the configuration's value and the one the unit needs.
pub fn absence(u: &dyn Unit, cfg: &PipelineConfig) -> String {
    let toml = cfg.to_toml();
    let current = |field: &str| cfg.field_text(&toml, field);
    // (what the configuration has, what the unit needs) for every unmet setting.
    let (has, want): (Vec<String>, Vec<String>) = u
        .requires(cfg)
        .into_iter()
        .filter_map(|(field, want)| {
            let now = current(field);
            (now != want).then(|| (format!("{field} = {now}"), format!("{field} = {want}")))
        })
        .unzip();
    if has.is_empty() {
        return format!("the configuration has no {}\n  fix: enable diffuse or specular", u.name());
    }
    format!(
        "the configuration has no {} ({})\n  fix: drop it, or set {} in the configuration",
        u.name(),
        has.join(", "),
        want.join(" and ")
    )
}

/// Refuse inputs of `u` outside its domain ([`Unit::input_max`]), naming the port, the lane,
/// the value and the bound: the ports whose model indexes a table or map by its value.
pub fn check_domain(u: &dyn Unit, cfg: &PipelineConfig, inputs: &[Vec<i64>]) -> crate::error::Result<()> {
    let ports = self::inputs(u, cfg);
    for (name, max, what) in u.input_max(cfg) {
        let i = ports.iter().position(|p| p.name == name).expect("input_max names an input");
        if let Some((lane, v)) = inputs[i].iter().enumerate().find(|(_, v)| **v > max) {
            return Err(crate::error::Error::Other(format!(
                "{}: input `{name}` lane {lane} is {v}, above {max} ({what}): outside the unit's domain, which the pipeline never feeds it\n  fix: give `{name}` at most {max}",
                u.name()
            )));
        }
    }
    Ok(())
}

/// Refuse outputs of `u` that do not fit their ports (`outs` as `eval` gives them): inputs
/// every lane of which fits its format can still take a sum beyond the output's (an
/// accumulator fed its format's largest value and a full term). The pipeline never does.
pub fn check_outputs(u: &dyn Unit, cfg: &PipelineConfig, outs: &[Vec<i64>]) -> crate::error::Result<()> {
    for (port, lanes) in outputs(u, cfg).iter().zip(outs) {
        let f = port.fmt;
        if let Some((lane, v)) = lanes.iter().enumerate().find(|(_, v)| **v < f.min_raw() || **v > f.max_raw()) {
            return Err(crate::error::Error::Other(format!(
                "{}: these inputs take output `{}` lane {lane} to {v}, beyond its {} format ({}..={}): outside the unit's domain, which the pipeline never feeds it\n  fix: give inputs whose result fits (a smaller sum or term)",
                u.name(),
                port.name,
                f.name(),
                f.min_raw(),
                f.max_raw()
            )));
        }
    }
    Ok(())
}

/// Input ports of a unit, in order.
pub fn inputs(u: &dyn Unit, cfg: &PipelineConfig) -> Vec<Port> {
    u.ports(cfg).into_iter().filter(|p| p.dir == Dir::In).collect()
}

/// Output ports of a unit, in order.
pub fn outputs(u: &dyn Unit, cfg: &PipelineConfig) -> Vec<Port> {
    u.ports(cfg).into_iter().filter(|p| p.dir == Dir::Out).collect()
}

/// Markdown table of every unit's ports under `cfg` (the README's interface table).
pub fn markdown_table(cfg: &PipelineConfig) -> String {
    let mut s = String::from("| unit | port | dir | format | lanes | bits | meaning |\n|---|---|---|---|---|---|---|\n");
    for u in included(cfg) {
        for (i, port) in u.ports(cfg).iter().enumerate() {
            let name = if i == 0 {
                format!("`{}` (latency {})", u.name(), u.latency(cfg))
            } else {
                String::new()
            };
            let dir = if port.dir == Dir::In { "in" } else { "out" };
            let late = match port.enters {
                0 => String::new(),
                e => format!(" (sampled {e} edge(s) after the other inputs: `enters` = {e})"),
            };
            s += &format!(
                "| {name} | `{}` | {dir} | {} | {} | {} | {}{late} |\n",
                port.name,
                port.fmt.name(),
                port.lanes,
                port.bits(),
                port.doc
            );
        }
    }
    // The ports the table leaves out, which a unit's module declares all the same.
    let loaded: Vec<String> = included(cfg)
        .iter()
        .filter(|u| u.memory(cfg).is_some() || u.name() == "power_unit")
        .map(|u| format!("`{}`", u.name()))
        .collect();
    s += "\nEvery unit's module also has `clk` (rising edge; no reset and no valid)";
    if !loaded.is_empty() {
        s += &format!(
            ", and {} a memory's load port `we`, `waddr`, `wdata` and its parameter `INIT_FILE` (`power_unit` also `R`, its read ports)",
            loaded.join(", ")
        );
    }
    s + ": the interface JSON's `units` lists every port and parameter of each module.\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An output beyond its port's format is refused, naming the unit, the port and the
    /// value; one inside passes.
    #[test]
    fn an_output_beyond_its_format_is_refused() {
        let cfg = PipelineConfig::default();
        let u = unit("dot_clamp").unwrap();
        let top = 1i64 << cfg.dot_frac_bits;
        check_outputs(u, &cfg, &[vec![top]]).unwrap();
        let e = check_outputs(u, &cfg, &[vec![2 * top]]).unwrap_err().to_string();
        assert!(
            e.contains("dot_clamp") && e.contains("output `f` lane 0") && e.contains("fix:"),
            "{e}"
        );
    }

    /// Every unit's model output fits its output ports, over its corners and, where it has
    /// one, its exhaustive domain; and the exact version is never more than a few LSBs away.
    #[test]
    fn models_fit_their_ports_and_track_the_exact_equation() {
        // The fuzzer's corner configurations reach every width at its top and its bottom.
        let mut cfgs: Vec<PipelineConfig> = crate::sim::fuzz::corner_configs().into_iter().map(|c| c.1).collect();
        cfgs.push(PipelineConfig::default());
        cfgs.push(PipelineConfig {
            palette: true,
            lights: 2,
            ..Default::default()
        });
        cfgs.extend(crate::sim::fuzz::normalise_configs());
        // Each of them with a frame per fragment, where that is valid: the frame unit's
        // corners at every width.
        let framed: Vec<PipelineConfig> = cfgs
            .iter()
            .map(|c| PipelineConfig {
                bump_state: crate::config::BumpStateAt::Fragment,
                frame_transform: true,
                self_shadow: false,
                ..c.clone()
            })
            .filter(|c| c.validate("t").is_ok())
            .collect();
        assert!(framed.len() > 5, "{} framed configurations", framed.len());
        // And each of those with the frame built per fragment (TexRam), or from a quaternion.
        let built: Vec<PipelineConfig> = framed
            .iter()
            .flat_map(|c| {
                [
                    PipelineConfig {
                        frame_build: true,
                        ..c.clone()
                    },
                    PipelineConfig {
                        frame_quaternion: true,
                        ..c.clone()
                    },
                ]
            })
            .collect();
        cfgs.extend(framed);
        cfgs.extend(built);
        for cfg in cfgs {
            let table = PowerTable::build(&cfg, cfg.shininess);
            let palette = crate::rtlgen::rom::default_palette(&cfg);
            let env = crate::model::env_map::default_maps(&cfg);
            let mem = Memories {
                table: &table,
                palette: &palette,
                env: &env,
            };
            for u in included(&cfg) {
                let mut ins: Vec<Lanes> = u.corners(&cfg).into_iter().map(|c| c.1).collect();
                if let Some(n) = u.exhaustive_count(&cfg) {
                    ins.extend((0..n.min(5000)).map(|i| u.exhaustive_input(&cfg, i)));
                }
                assert!(!ins.is_empty(), "{} has no corners", u.name());
                for i in &ins {
                    for (port, lanes) in inputs(u, &cfg).iter().zip(i) {
                        assert_eq!(port.lanes as usize, lanes.len(), "{}.{}", u.name(), port.name);
                        for &v in lanes {
                            assert!(v >= port.fmt.min_raw() && v <= port.fmt.max_raw(), "{} input {v}", u.name());
                        }
                    }
                    // Its own edges are inside its domain: the C library evaluates them.
                    check_domain(u, &cfg, i).unwrap_or_else(|e| panic!("{}: {e}", u.name()));
                    let out = u.eval(&cfg, &mem, i);
                    let ex = u.exact(&cfg, &mem, i);
                    for ((port, lanes), exl) in outputs(u, &cfg).iter().zip(&out).zip(&ex) {
                        assert_eq!(port.lanes as usize, lanes.len());
                        for (&v, &e) in lanes.iter().zip(exl) {
                            assert!(v >= port.fmt.min_raw() && v <= port.fmt.max_raw(), "{} output {v}", u.name());
                            // Loose on purpose: a sanity bound; `gbump error` measures the real figure.
                            assert!((v as f64 - e).abs() <= 64.0, "{} exact {e} vs model {v} at {i:?}", u.name());
                        }
                    }
                }
            }
        }
    }
}
