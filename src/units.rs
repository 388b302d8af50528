//! The one table of hardware units. Each unit exists three times — a model function
//! (`model::`), a Verilog emitter (`rtlgen::`) and a column group of the vector format
//! (`vectors::`) — under the same name; all of them, and the README's interface table, read
//! their ports, formats and latency from here, so they cannot drift apart.

use crate::config::PipelineConfig;
use crate::fixed::Format;

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
}

impl Port {
    pub fn bits(&self) -> u32 {
        self.fmt.width * self.lanes
    }
}

/// A hardware unit of the pipeline.
pub struct Unit {
    pub name: &'static str,
    /// Where the paper (or the Cg tutorial) defines it.
    pub source: &'static str,
    pub ports: fn(&PipelineConfig) -> Vec<Port>,
    /// Clock cycles from input to output.
    pub latency: fn(&PipelineConfig) -> u32,
}

fn p(name: &'static str, dir: Dir, fmt: Format, lanes: u32, doc: &'static str) -> Port {
    Port {
        name,
        dir,
        fmt,
        lanes,
        doc,
    }
}

fn blend_ports(c: &PipelineConfig) -> Vec<Port> {
    vec![
        p("c_in", Dir::In, c.colour_fmt(), 3, "colour in (R, G, B)"),
        p("f", Dir::In, c.factor_fmt(), c.lights, "fd_i or fs_i per light, aligned"),
        p("k", Dir::In, c.k_fmt(), c.lights, "k_i per light"),
        p(
            "lc",
            Dir::In,
            c.colour_fmt(),
            3 * c.lights,
            "light colours Lc_i (R, G, B per light)",
        ),
        p("c_out", Dir::Out, c.colour_fmt(), 3, "sat(c_in + round(sum f_i k_i Lc_i))"),
    ]
}

/// The blend units are emitted in their parallel form (all light terms summed in one cycle);
/// a serial top accumulates one `light_term` per clock and closes with `blend_finish` instead.
fn blend_latency(_: &PipelineConfig) -> u32 {
    1
}

/// Every unit, in data-flow order.
pub const UNITS: &[Unit] = &[
    Unit {
        name: "bump_fetch",
        source: "paper §4.1, §6 (palette); Cg §8.1.2 (range expansion)",
        ports: |c| {
            vec![
                if c.palette {
                    p("texel", Dir::In, Format::u(8, 0), 1, "palette index")
                } else {
                    p(
                        "texel",
                        Dir::In,
                        Format::u(c.normal_bits, 0),
                        3,
                        "range-compressed normal (offset binary)",
                    )
                },
                p("b", Dir::Out, c.normal_fmt(), 3, "bump normal B"),
            ]
        },
        latency: |_| 1,
    },
    Unit {
        name: "dot_clamp",
        source: "paper §4.2: fd_i = B·L_i, and B·H_i",
        ports: |c| {
            vec![
                p("b", Dir::In, c.normal_fmt(), 3, "bump normal B"),
                p("v", Dir::In, c.lh_fmt(), 3, "L_i or H_i in bump space"),
                p("f", Dir::Out, c.dot_fmt(), 1, "max(0, B·V) rounded, clamped to 1"),
            ]
        },
        latency: |_| 1,
    },
    Unit {
        name: "power_table",
        source: "paper §4.2: fs_i = (B·H_i)^n, a reloadable table for one shininess",
        ports: |c| {
            vec![
                p("x", Dir::In, c.dot_fmt(), 1, "clamped B·H"),
                p("fs", Dir::Out, c.power_fmt(), 1, "table[round(x (N-1))]"),
            ]
        },
        latency: |_| 1,
    },
    Unit {
        name: "diffuse_blend",
        source: "paper §4.2, §5.1: C' = sat(C_src + sum fd_i k_i Lc_i)",
        ports: blend_ports,
        latency: blend_latency,
    },
    Unit {
        name: "texture_modulate",
        source: "paper §5.1: the texture stage between the blends",
        ports: |c| {
            vec![
                p("c_in", Dir::In, c.colour_fmt(), 3, "colour in"),
                p("t", Dir::In, c.colour_fmt(), 3, "texel T"),
                p("c_out", Dir::Out, c.colour_fmt(), 3, "round(c t / max)"),
            ]
        },
        latency: |_| 1,
    },
    Unit {
        name: "specular_blend",
        source: "paper §4.2, §5.1: C_new = sat(C'' + sum fs_i k_i Lc_i)",
        ports: blend_ports,
        latency: blend_latency,
    },
];

/// Look a unit up by name.
pub fn unit(name: &str) -> Option<&'static Unit> {
    UNITS.iter().find(|u| u.name == name)
}

/// Markdown table of every unit's ports under `cfg` (the README's interface table).
pub fn markdown_table(cfg: &PipelineConfig) -> String {
    let mut s = String::from("| unit | port | dir | format | lanes | bits | meaning |\n|---|---|---|---|---|---|---|\n");
    for u in UNITS {
        for (i, port) in (u.ports)(cfg).iter().enumerate() {
            let name = if i == 0 {
                format!("`{}` (latency {})", u.name, (u.latency)(cfg))
            } else {
                String::new()
            };
            let dir = if port.dir == Dir::In { "in" } else { "out" };
            s += &format!(
                "| {name} | `{}` | {dir} | {} | {} | {} | {} |\n",
                port.name,
                port.fmt.name(),
                port.lanes,
                port.bits(),
                port.doc
            );
        }
    }
    s
}

/// The three colour stages in the configured order (paper §5.1).
pub fn stage_order(cfg: &PipelineConfig) -> [&'static str; 3] {
    match cfg.blend_order {
        crate::config::BlendOrder::DiffuseTextureSpecular => ["diffuse_blend", "texture_modulate", "specular_blend"],
        crate::config::BlendOrder::TextureLast => ["diffuse_blend", "specular_blend", "texture_modulate"],
    }
}
