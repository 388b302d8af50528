//! The top pipeline, `gbump_pipeline_<hash>`, as a list of unit instances and their
//! connections, scheduled by `schedule.rs` and written through `module.rs`: valid-in /
//! valid-out, synchronous reset of the valid bits, the load port of every unit memory, and the
//! latency the schedule returns.
//!
//! Parallel lights (one fragment per clock): the fetch, a dot_clamp per L_i and H_i (each
//! interpolated one after a `normalise` under `renormalise`), the power unit with n read ports, then the three colour stages in the configured order.
//! Serial lights (paper §4.2, n clocks per fragment): the fragment is held while a counter
//! walks the light slots through one dot_clamp pair, one power-table port and one
//! `light_accumulate` per blend; `blend_finish` closes each sum; `in_ready` is low meanwhile.
//! The bump state (L_i, H_i, Lc_i, k_i) is loaded once per triangle through the setup port
//! (`tri_valid/tri_ready`, `tri_*`) into `triangle_banks` register banks, and fragments carry a
//! bank tag (`bump_state = "triangle"`, the default); or it enters with every fragment on the
//! `in_*` ports (`bump_state = "fragment"`).

use super::module::ModuleBuilder;
use super::schedule::Scheduler;
use super::units_v::{module_name, rom_file_name};
use crate::config::{BlendOrder, LightMode, PipelineConfig};
use crate::fixed::Format;
use crate::units::{self, Dir, Unit};

/// Rising edges with `rst` high that bring the top to a known idle state from any power-up
/// state: every valid bit is cleared by `rst ? 0 : ...` at the first one. The testbenches hold
/// reset for exactly this many edges, so the number is proven by every regression.
pub const RESET_CYCLES: u32 = 1;

/// What a top port carries (the interface JSON's `kind`, in snake case).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PortKind {
    /// clk, rst, valid/ready.
    Control,
    /// A memory's load port.
    Load,
    /// A fragment field: a stimulus column of the vectors.
    Fragment,
    /// A triangle-setup field (per-triangle tops): a stimulus column of the vectors, driven
    /// through the setup port when the record starts a triangle.
    Triangle,
    /// The result: an expected column of the vectors.
    Result,
}

/// One port of the top.
#[derive(Clone, Debug, PartialEq)]
pub struct TopPort {
    pub name: String,
    pub dir: Dir,
    pub kind: PortKind,
    /// Lane format and lane count (a 1-bit control is u1 × 1).
    pub fmt: Format,
    pub lanes: u32,
    pub doc: String,
}

impl TopPort {
    pub fn width(&self) -> u32 {
        self.fmt.width * self.lanes
    }
}

/// The fetch unit of `cfg`: `palette_fetch` or `bump_fetch`.
pub fn fetch_unit(cfg: &PipelineConfig) -> &'static dyn Unit {
    units::unit(if cfg.palette { "palette_fetch" } else { "bump_fetch" }).expect("fetch unit")
}

/// The memories of the top, in port order: the power unit's power table (its load port is on
/// every top: a configuration without the specular path leaves it unused, so every top of one
/// light count has the same ports), then the other units' memories.
pub fn memories(cfg: &PipelineConfig) -> Vec<units::Memory> {
    let mut v = vec![units::table_memory(cfg)];
    v.extend(
        units::included(cfg)
            .iter()
            .filter(|u| u.name() != "power_unit")
            .filter_map(|u| u.memory(cfg)),
    );
    v
}

/// EMBM's environment maps among [`memories`]: one per blend the configuration has.
pub fn env_map_memories(cfg: &PipelineConfig) -> Vec<units::Memory> {
    memories(cfg).into_iter().filter(|m| m.prefix.starts_with("env_")).collect()
}

/// The names of [`env_map_memories`]: "diffuse", "specular" (those the top has a port for).
pub fn env_map_names(cfg: &PipelineConfig) -> Vec<&'static str> {
    env_map_memories(cfg).iter().map(|m| m.prefix.trim_start_matches("env_")).collect()
}

/// The memories other than the power table: (the top's init parameter, the unit that holds
/// the memory, the init file's name in the generated RTL).
pub fn memory_inits(cfg: &PipelineConfig) -> Vec<(String, String, String)> {
    units::included(cfg)
        .iter()
        .filter(|u| u.name() != "power_unit")
        .filter_map(|u| {
            u.memory(cfg).map(|m| {
                (
                    m.init_param.to_string(),
                    u.name().to_string(),
                    rom_file_name(cfg, m.init_stem, "hex"),
                )
            })
        })
        .collect()
}

/// Whether the top reads a power table (a RAM, or a ROM under `power_rom`): not under EMBM
/// or a squaring power unit, whose table port stays on the interface unused.
pub fn power_table_read(cfg: &PipelineConfig) -> bool {
    !cfg.embm() && cfg.power_unit != crate::config::PowerUnitKind::Squaring
}

/// The power-up file of memory `m` of the top (its `init_param`'s default).
pub fn memory_init_file(cfg: &PipelineConfig, m: &units::Memory) -> String {
    match m.init_param {
        "INIT_FILE" => rom_file_name(cfg, "power_table", "hex"),
        param => memory_inits(cfg)
            .into_iter()
            .find(|i| i.0 == param)
            .map(|i| i.2)
            .expect("every memory but the table has an init parameter"),
    }
}

/// The memories the top reads: [`memories`] less the power table where its port is unused
/// (EMBM, a squaring unit).
pub fn read_memories(cfg: &PipelineConfig) -> Vec<units::Memory> {
    memories(cfg)
        .into_iter()
        .filter(|m| m.prefix != "power_table" || power_table_read(cfg))
        .collect()
}

/// The memories a reset leaves as they are, as a sentence lists them: each memory the top
/// reads, with its power-up parameter and default file.
pub fn kept_memories(cfg: &PipelineConfig) -> Vec<String> {
    read_memories(cfg)
        .iter()
        .map(|m| {
            let what = match m.prefix {
                "power_table" if cfg.power_rom => "the power table (a ROM)".to_string(),
                p => format!("the {} memory", p.replace('_', " ")),
            };
            format!(
                "{what} (power-up contents from the `{}` parameter, default `{}`)",
                m.init_param,
                memory_init_file(cfg, m)
            )
        })
        .collect()
}

/// What the power unit's table is to a testbench: written through its load port, a ROM its
/// init file fills, or not read at all (why). Every text that says what to do with the load
/// port (the interface JSON's memories and units, the integration notes) asks here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableUse {
    Loaded,
    Rom,
    Unread(&'static str),
}

pub fn table_use(cfg: &PipelineConfig) -> TableUse {
    if !power_table_read(cfg) {
        let why = unused_load_docs(cfg).map_or("no power table", |u| u.0);
        TableUse::Unread(why.trim_start_matches("unused: "))
    } else if cfg.power_rom {
        TableUse::Rom
    } else {
        TableUse::Loaded
    }
}

/// The power table's load-port docs where the port is unused: (write enable, address and
/// data).
pub fn unused_load_docs(cfg: &PipelineConfig) -> Option<(&'static str, &'static str)> {
    if cfg.embm() {
        let doc = "unused: env_map_bits > 0 (EMBM: the specular light comes from its map, not a power table)";
        Some((doc, doc))
    } else if cfg.power_unit == crate::config::PowerUnitKind::Squaring {
        let doc = "unused: power_unit = \"squaring\" (no table: x^n is squared out)";
        Some((doc, doc))
    } else if cfg.power_rom {
        Some((
            "unused: power_rom = true (the table is a ROM holding its INIT_FILE; writes are ignored)",
            "unused: power_rom = true",
        ))
    } else {
        None
    }
}

/// Every port of the top, in order.
pub fn port_list(cfg: &PipelineConfig) -> Vec<TopPort> {
    let n = cfg.lights;
    let bit = Format::u(1, 0);
    let tp = |name: &str, dir, kind, fmt, lanes, doc: &str| TopPort {
        name: name.into(),
        dir,
        kind,
        fmt,
        lanes,
        doc: doc.into(),
    };
    let mut v = vec![
        tp("clk", Dir::In, PortKind::Control, bit, 1, "clock, rising edge"),
        tp(
            "rst",
            Dir::In,
            PortKind::Control,
            bit,
            1,
            "synchronous reset, active high: clears the valid bits",
        ),
    ];
    for m in memories(cfg) {
        // (the write enable's doc, the address's and data's) where the load port is unused.
        let unused = (m.prefix == "power_table").then(|| unused_load_docs(cfg)).flatten();
        v.push(tp(
            &format!("{}_we", m.prefix),
            Dir::In,
            PortKind::Load,
            bit,
            1,
            unused.map_or("write enable of the load port", |u| u.0),
        ));
        v.push(tp(
            &format!("{}_waddr", m.prefix),
            Dir::In,
            PortKind::Load,
            Format::u(m.addr_bits, 0),
            1,
            unused.map_or("write address", |u| u.1),
        ));
        v.push(tp(
            &format!("{}_wdata", m.prefix),
            Dir::In,
            PortKind::Load,
            Format::u(m.data_bits / m.data_lanes, m.data_frac),
            m.data_lanes,
            unused.map_or(m.doc, |u| u.1),
        ));
    }
    let fetch_in = units::inputs(fetch_unit(cfg), cfg).remove(0);
    let bump_doc = if cfg.palette {
        "8-bit index into the bump palette"
    } else {
        "x, y, z of the stored bump normal, offset binary (lane 0 = x)"
    };
    let col = cfg.colour_fmt();
    v.extend([
        tp("in_valid", Dir::In, PortKind::Control, bit, 1, "a fragment is offered"),
        tp(
            "in_ready",
            Dir::Out,
            PortKind::Control,
            bit,
            1,
            "the fragment is accepted at this edge if in_valid",
        ),
        tp("in_bump", Dir::In, PortKind::Fragment, fetch_in.fmt, fetch_in.lanes, bump_doc),
        tp(
            "in_c_src",
            Dir::In,
            PortKind::Fragment,
            col,
            3,
            "R, G, B of the Gouraud colour C_src (lane 0 = R)",
        ),
        tp(
            "in_tex",
            Dir::In,
            PortKind::Fragment,
            col,
            3,
            "R, G, B of the texture colour T (lane 0 = R)",
        ),
        tp("in_diffuse_en", Dir::In, PortKind::Fragment, bit, 1, "diffuse blend enable"),
        tp("in_specular_en", Dir::In, PortKind::Fragment, bit, 1, "specular blend enable"),
    ]);
    if cfg.per_triangle() {
        v.extend([
            tp("tri_valid", Dir::In, PortKind::Control, bit, 1, "a triangle's bump state is offered on tri_*"),
            tp(
                "tri_ready",
                Dir::Out,
                PortKind::Control,
                bit,
                1,
                "the setup is accepted at this edge if tri_valid: low while the bank it would load is still read by an earlier triangle's fragment, and during reset",
            ),
        ]);
    }
    let (pre, kind) = if cfg.per_triangle() {
        ("tri", PortKind::Triangle)
    } else {
        ("in", PortKind::Fragment)
    };
    // Under `normal_range = "symmetric"` L and H carry the normal codes' scale.
    let scaled = match cfg.normal_range {
        crate::config::NormalRange::Binary => String::new(),
        crate::config::NormalRange::Symmetric => {
            let half = 1u64 << (cfg.normal_bits - 1);
            format!(
                ", times {half}/{} (normal_range = \"symmetric\": a bump normal code b means b/{}, the hardware multiplies by b/{half})",
                half - 1,
                half - 1
            )
        }
    };
    // Under `frame_transform` L and H are in the frame's space, where the bump normal is placed.
    let space = if cfg.frame_transform {
        "the frame's space (in_frame)"
    } else {
        "bump space"
    };
    // What the L and H lanes carry: under `pixel_lh` the vector to the light (normalised by
    // the top) and the viewer direction V (not normalised: the half sum needs it unit).
    let (l_is, h_is) = if cfg.pixel_lh {
        (
            "the vector from the surface to light j, any length up to unit (the top normalises it)",
            "the viewer direction V, at unit length (the top does not normalise it; H_j = normalise((normalise(L_j) + V)/2))",
        )
    } else {
        ("L_j", "H_j")
    };
    if cfg.embm() {
        v.extend([
            tp(
                "in_st",
                Dir::In,
                kind,
                cfg.lh_fmt(),
                2,
                "EMBM: the interpolated sphere-map coordinates (s, t) of the unperturbed normal (lane 0 = s); texel i's centre is at (i + 1/2) 2/n - 1",
            ),
            tp(
                "in_m",
                Dir::In,
                kind,
                cfg.lh_fmt(),
                4,
                "EMBM: the triangle's 2x2 matrix, lanes 0, 1 = ds/ddu (s, t), lanes 2, 3 = ds/ddv: s = st + M (b_x, b_y)",
            ),
        ]);
    } else {
        v.extend([
            tp(
                &format!("{pre}_l"),
                Dir::In,
                kind,
                cfg.lh_fmt(),
                3 * n,
                &format!("light j, component c (x, y, z) at lane 3j + c: {l_is} in {space}{scaled}"),
            ),
            tp(
                &format!("{pre}_h"),
                Dir::In,
                kind,
                cfg.lh_fmt(),
                3 * n,
                &format!("light j, component c (x, y, z) at lane 3j + c: {h_is} in {space}{scaled}"),
            ),
            tp(
                &format!("{pre}_lc"),
                Dir::In,
                kind,
                col,
                3 * n,
                if cfg.white_lights {
                    "unused: white_lights = true (every Lc_j is 1, 1, 1; drive anything)"
                } else {
                    "light j, channel c (R, G, B) at lane 3j + c: light colour Lc_j"
                },
            ),
            tp(
                &format!("{pre}_k"),
                Dir::In,
                kind,
                cfg.k_fmt(),
                n,
                "light j at lane j: the light's weight k_j",
            ),
        ]);
    }
    if cfg.frame_transform {
        v.push(tp(
            "in_frame",
            Dir::In,
            PortKind::Fragment,
            cfg.lh_fmt(),
            9,
            if cfg.frame_quaternion {
                "lanes 0 to 3: the interpolated vertex quaternion q = (w, x, y, z), any length; lanes 6 to 8: the interpolated normal N_i (lanes 4 and 5 are not read); in the space L and H are given in; quat_frame forms the frame from them (T and B the rotation's of q/|q|, N = N_i, all times |q|^2) and the bump normal is placed in it (frame_transform)"
            } else if cfg.frame_build {
                "vector v (T, B, N), component c at lane 3v + c: the main direction m in the T lanes (under 2 long: N x m is clamped per component) and the interpolated normal N_i in the N lanes (any length; the B lanes are not read), in the space L and H are given in; frame_build forms the frame from them (N = N_i/|N_i|, B = N x m/|N x m|, T = B x N) and the bump normal is placed in it (frame_transform)"
            } else {
                "vector v (T, B, N), component c at lane 3v + c: the fragment's frame, in the space L and H are given in; the bump normal is placed in it (frame_transform)"
            },
        ));
    }
    v.extend([tp("out_valid", Dir::Out, PortKind::Control, bit, 1, "out_c holds a result")]);
    if cfg.backpressure {
        v.push(tp(
            "out_ready",
            Dir::In,
            PortKind::Control,
            bit,
            1,
            "the result on out_c is taken at this edge if out_valid; low holds it (and the ones behind it) in the output buffer",
        ));
    }
    v.extend([tp("out_c", Dir::Out, PortKind::Result, col, 3, "R, G, B of C_new")]);
    v
}

/// Ports of the top, in order: (name, direction, width).
pub fn top_ports(cfg: &PipelineConfig) -> Vec<(String, &'static str, u32)> {
    port_list(cfg)
        .into_iter()
        .map(|p| (p.name.clone(), if p.dir == Dir::In { "input" } else { "output" }, p.width()))
        .collect()
}

/// Rising edges from the one that accepts a fragment (`in_valid && in_ready` high) to the
/// one at which its `out_valid` is first sampled high: the schedule's result. Every
/// testbench checks it per vector.
pub fn latency(cfg: &PipelineConfig) -> u32 {
    build(cfg).latency
}

/// Per-triangle tops: rising edges from the edge that accepts a bank's last fragment to the
/// first edge at which a setup may load that bank again (before it, `tri_ready` is low while a
/// setup for that bank is offered; from it on, high once the setup has been offered for
/// [`setup_edges`]). The schedule's result: the last stage that reads a bank, plus the serial
/// top's n slot cycles and the setup's slot writes. Every testbench checks it per setup.
pub fn bank_hold(cfg: &PipelineConfig) -> Option<u32> {
    build(cfg).bank_hold
}

/// Whether the top keeps its triangle banks in a RAM (`rtlgen::ram`): the serial per-triangle
/// top does.
pub fn banks_in_ram(cfg: &PipelineConfig) -> bool {
    cfg.per_triangle() && cfg.light_mode == LightMode::Serial
}

/// Per-triangle tops: the fewest rising edges a setup spans, from the first edge at which it
/// is offered (`tri_valid` high, its bank free) to the edge that accepts it, both counted. The
/// serial top writes one light slot per edge into its bank RAM, so n; register banks take a
/// setup at one edge. Every testbench checks it per setup, with the bank hold.
pub fn setup_edges(cfg: &PipelineConfig) -> u32 {
    match cfg.light_mode {
        LightMode::Serial => cfg.lights,
        LightMode::Parallel => 1,
    }
}

/// Tops with `out_ready`: results the output buffer holds, enough for every fragment that can
/// be in flight when `in_ready` allows an accept (`ceil(latency / interval) + 1`), so an accept
/// never waits for `out_ready` while it stays high. `in_ready` is low while this many accepted
/// results have not been taken.
pub fn output_depth(cfg: &PipelineConfig) -> Option<u32> {
    cfg.backpressure.then(|| latency(cfg).div_ceil(cfg.initiation_interval()) + 1)
}

/// Whether the top instantiates the RAM module itself (the serial top's bank RAM, the output
/// buffer), so the RTL set needs it whatever units are in.
pub fn uses_ram_module(cfg: &PipelineConfig) -> bool {
    banks_in_ram(cfg) || cfg.backpressure
}

/// Bits of the top's own RAMs (instances of the RAM module, black boxes in `gbump area`):
/// the serial top's bank RAM and the output buffer.
pub fn ram_bits(cfg: &PipelineConfig) -> u32 {
    let banks = if banks_in_ram(cfg) {
        // The RAM's words: a power of two of slots per bank, one slot of the stored fields each.
        let slot: u32 = bank_ram_ports(cfg).iter().map(|p| p.width() / cfg.lights).sum();
        (cfg.triangle_banks << slot_bits(cfg)) * slot
    } else {
        0
    };
    banks + output_depth(cfg).unwrap_or(0) * 3 * cfg.colour_bits
}

/// Bits of the top's own arrays, which Yosys counts as memories beside the units' RAMs: its
/// RAMs ([`ram_bits`]) and the parallel top's register banks (flip-flops in `gbump area`).
pub fn array_bits(cfg: &PipelineConfig) -> u32 {
    let register_banks = if cfg.per_triangle() && !banks_in_ram(cfg) {
        let tri: u32 = banked_ports(cfg).iter().map(|p| p.width()).sum();
        cfg.triangle_banks * tri
    } else {
        0
    };
    register_banks + ram_bits(cfg)
}

/// The whole top module.
pub fn top(cfg: &PipelineConfig) -> String {
    build(cfg).text
}

/// What the top is built of: its own logic and its unit instances (the area model's input).
pub fn tally(cfg: &PipelineConfig) -> super::module::Tally {
    build_with(cfg, ModuleBuilder::counting("gbump_pipeline")).tally
}

/// A generated top and the figures its schedule gives.
struct Built {
    tally: super::module::Tally,
    text: String,
    latency: u32,
    bank_hold: Option<u32>,
}

/// What a light-mode body returns: latency, output colour and valid signals, bank hold.
type Body = (u32, String, String, Option<u32>);

fn lane(i: u32, w: u32) -> String {
    format!("[{}:{}]", i * w + w - 1, i * w)
}

/// Under `pixel_lh`, the input of light `i`'s H `normalise`: its normalised L (`nl<i>`, from
/// `u_norm_l<i>`, instantiated here when the diffuse path has not) and the viewer direction on
/// its H lanes, added one bit wider and halved (`model::pipeline::half_sum`). The template
/// of the three halved lanes.
fn half_sum(s: &mut Scheduler, cfg: &PipelineConfig, norm: &dyn units::Unit, pre: &str, i: u32) -> String {
    let lh = cfg.lh_bits;
    let nl = format!("nl{i}");
    if !s.m.has(&nl) {
        let l = format!("{{{pre}_l}}{}", lane(i, 3 * lh));
        s.unit(cfg, norm, &format!("u_norm_l{i}"), &[("v", &l)], &[("n", &nl)], &[]);
    }
    let mut halves = Vec::new();
    for c in (0..3).rev() {
        let (lo, hi) = (c * lh, c * lh + lh - 1);
        let (vlo, vhi) = (i * 3 * lh + lo, i * 3 * lh + hi);
        let sum = format!("hs{i}_{c}");
        s.comb(
            &sum,
            lh + 1,
            &format!("{{{{{nl}}}[{hi}], {{{nl}}}[{hi}:{lo}]}} + {{{{{pre}_h}}[{vhi}], {{{pre}_h}}[{vhi}:{vlo}]}}"),
        );
        halves.push(format!("{{{sum}}}[{lh}:1]"));
    }
    let h = format!("hh{i}");
    s.comb(&h, 3 * lh, &format!("{{{}}}", halves.join(", ")));
    format!("{{{h}}}")
}

/// Whether a light direction whose z lane is `z` (a template of `lh_bits` bits) is above the
/// surface, z > 0: self-shadowing's test (`model::pipeline::self_shadow_lit`).
fn above_z(cfg: &PipelineConfig, z: &str) -> String {
    let lh = cfg.lh_bits;
    format!("!{z}[{}] && ({z} != {lh}'d0)", lh - 1)
}

/// A light's blend enable `en`, under `self_shadow` also gated by `lit` (the light is above
/// the surface) and, for a highlight (`fd`: its B·L), by B·L above 0.
fn shadowed(cfg: &PipelineConfig, en: &str, lit: &str, fd: Option<&str>) -> String {
    if !cfg.self_shadow {
        return en.to_string();
    }
    match fd {
        Some(fd) => format!("{en} & {lit} & ({fd} != 0)"),
        None => format!("{en} & {lit}"),
    }
}

/// The aligned, enable-gated blend factor of a dot product or power (`src_frac` fraction bits).
fn factor(cfg: &PipelineConfig, src: &str, src_frac: u32, en: &str) -> String {
    let pad = cfg.factor_frac() - src_frac;
    let aligned = if pad > 0 { format!("{{{src}, {pad}'d0}}") } else { src.to_string() };
    format!("({en} ? {aligned} : {}'d0)", cfg.factor_frac() + 1)
}

/// The enables of §4.2, with the §5.4.2 bypass of the unperturbed normal when configured.
fn enable(cfg: &PipelineConfig, present: bool, en: &str) -> String {
    if !present {
        return "1'b0".into();
    }
    if cfg.skip_flat {
        let nb = cfg.normal_bits;
        format!("{{{en}}} & ~({{b}} == {{{nb}'d{}, {nb}'d0, {nb}'d0}})", (1u64 << (nb - 1)) - 1)
    } else {
        format!("{{{en}}}")
    }
}

fn build(cfg: &PipelineConfig) -> Built {
    build_with(cfg, ModuleBuilder::new(module_name(cfg, "gbump_pipeline")))
}

fn build_with(cfg: &PipelineConfig, mut m: ModuleBuilder) -> Built {
    for mem in memories(cfg) {
        m.param(mem.init_param, || format!("\"{}\"", rom_file_name(cfg, mem.init_stem, "hex")));
    }
    for p in port_list(cfg) {
        m.port(&p.name, p.dir, p.width());
    }
    let (lat, out_c, out_v, bank_hold) = {
        let mut s = Scheduler::new(&mut m);
        match cfg.light_mode {
            LightMode::Parallel => parallel(&mut s, cfg),
            LightMode::Serial => serial(&mut s, cfg),
        }
    };
    let (out_c, out_v) = if cfg.backpressure {
        output_buffer(&mut m, cfg, lat, &out_c, &out_v)
    } else {
        (out_c, out_v)
    };
    m.comment("The colour is forced to 0 while not valid, so no X ever leaves the pipeline after reset.");
    m.assign("out_valid", &out_v);
    m.assign("out_c", &format!("{out_v} ? {out_c} : {}'d0", 3 * cfg.colour_bits));
    let mut text = format!(
        "`timescale 1ns / 1ps\n`default_nettype none\n\n// gbump_pipeline: {:?} lights ({} slot(s)), blend order {:?}, latency {lat} cycles, one fragment every {} cycle(s).\n// INIT_FILE: the power table's contents at power-up (rst does not restore them); a path\n// relative to the simulator's working folder, so pass an absolute one from elsewhere.\n",
        cfg.light_mode,
        cfg.lights,
        cfg.blend_order,
        cfg.initiation_interval()
    );
    let (body, tally) = m.finish();
    text += &body;
    text += "`default_nettype wire\n";
    Built {
        text,
        latency: lat,
        bank_hold,
        tally,
    }
}

/// The output buffer of a top with `out_ready`: a fall-through FIFO of `output_depth` results
/// (a result the pipeline delivers while the buffer is empty and `out_ready` is high passes
/// straight through, so the latency is unchanged) and the credit that gates `in_ready`: the
/// count of accepted results not yet taken. No pipeline register stalls, so `out_ready` fans
/// out to the buffer alone. The entries sit in the RAM module (a memory, counted with the RAM
/// bits, block RAM on an FPGA), which reads at every edge the entry that is the head after it
/// (a look-ahead address), so the head is in the read register when `out_ready` takes it. The
/// RAM's read of an entry written at the same edge may return the old word (`no_rw_check`),
/// so an entry that becomes the head at the edge that writes it is shown from `obuf_byp`.
/// Returns the colour and valid the top's outputs show.
fn output_buffer(m: &mut ModuleBuilder, cfg: &PipelineConfig, lat: u32, pipe_c: &str, pipe_v: &str) -> (String, String) {
    let d = lat.div_ceil(cfg.initiation_interval()) + 1;
    let cw = 3 * cfg.colour_bits;
    let bits = |n: u32| (32 - n.leading_zeros()).max(1);
    let (ab, cb) = (bits(d - 1), bits(d));
    m.comment(format!(
        "Output buffer: {d} results (every fragment that can be in flight) in a RAM read one entry ahead, fall-through when empty; in_ready is low while {d} accepted results are untaken."
    ));
    m.reg_decl("obuf_rd", ab);
    m.reg_decl("obuf_wr", ab);
    m.reg_decl("obuf_n", cb);
    m.reg_decl("occupancy", cb);
    m.wire("obuf_empty", 1, Some(&format!("obuf_n == {cb}'d0")));
    m.wire("obuf_push", 1, Some(&format!("{pipe_v} && !(obuf_empty && out_ready)")));
    m.wire("obuf_pop", 1, Some("!obuf_empty && out_ready"));
    m.wire("taken", 1, Some(&format!("(!obuf_empty || {pipe_v}) && out_ready")));
    let wrap = |r: &str| format!("({r} == {ab}'d{}) ? {ab}'d0 : {r} + {ab}'d1", d - 1);
    m.wire("obuf_head", ab, Some(&format!("obuf_pop ? ({}) : obuf_rd", wrap("obuf_rd"))));
    m.wire("obuf_q", cw, None);
    m.raw(format!(
        "{} #(.WIDTH({cw}), .DEPTH({d}), .ABITS({ab}), .INIT_FILE(\"\")) u_obuf (.clk(clk), .we(obuf_push), .waddr(obuf_wr), .wdata({pipe_c}), .raddr(obuf_head), .rdata(obuf_q));",
        module_name(cfg, super::ram::RAM)
    ));
    m.reg_decl("obuf_byp", cw);
    m.reg_decl("obuf_use_byp", 1);
    m.raw(format!(
        "always @(posedge clk) begin\n    obuf_byp <= {pipe_c};\n    obuf_use_byp <= obuf_push && obuf_wr == obuf_head;\nend"
    ));
    m.raw(format!(
        "always @(posedge clk) begin\n    if (rst) begin\n        obuf_rd <= {ab}'d0;\n        obuf_wr <= {ab}'d0;\n        obuf_n <= {cb}'d0;\n        occupancy <= {cb}'d0;\n    end\n    else begin\n        if (obuf_push) obuf_wr <= {};\n        obuf_rd <= obuf_head;\n        obuf_n <= obuf_n + {{{{({cb}-1){{1'b0}}}}, obuf_push}} - {{{{({cb}-1){{1'b0}}}}, obuf_pop}};\n        occupancy <= occupancy + {{{{({cb}-1){{1'b0}}}}, accept}} - {{{{({cb}-1){{1'b0}}}}, taken}};\n    end\nend",
        wrap("obuf_wr"),
    ));
    m.raw(format!("assign credit = occupancy < {cb}'d{d};"));
    (
        format!("(obuf_empty ? {pipe_c} : (obuf_use_byp ? obuf_byp : obuf_q))"),
        format!("(!obuf_empty || {pipe_v})"),
    )
}

/// The memory parameter of an instance of `unit`: its INIT_FILE is the top's parameter.
fn mem_params(cfg: &PipelineConfig, unit: &dyn Unit) -> Vec<(&'static str, String)> {
    unit.memory(cfg)
        .map(|m| ("INIT_FILE", m.init_param.to_string()))
        .into_iter()
        .collect()
}

/// The power unit with `r` read ports on `{xh}`, its output `fs` (the unit's ports describe one
/// read port, so the instance is written as a helper with its `R` parameter).
fn power_unit(s: &mut Scheduler, cfg: &PipelineConfig, r: u32) {
    let pu = units::unit("power_unit").expect("unit");
    let mem = units::table_memory(cfg);
    s.m.wire("fs", r * (cfg.power_frac_bits + 1), None);
    let st = s.stage_of(&["{xh}"]);
    let x = s.fill("{xh}", st);
    s.m.count_instances(pu.name(), r);
    s.m.inst_helper(
        cfg,
        "power_unit",
        &format!("#(.R({r}), .INIT_FILE(INIT_FILE)) u_power_unit"),
        &[
            ("clk", "clk".into()),
            // A ROM (power_rom): the write port tied off, the contents its INIT_FILE; a squaring
            // unit has no table to write.
            (
                "we",
                if cfg.power_table_unused().is_some() {
                    "1'b0".into()
                } else {
                    "power_table_we".into()
                },
            ),
            ("waddr", rom_tie(cfg, "power_table_waddr", mem.addr_bits)),
            ("wdata", rom_tie(cfg, "power_table_wdata", mem.data_bits)),
            ("x", x),
            ("fs", "fs".into()),
        ],
    );
    s.source("fs", st + pu.latency(cfg));
}

/// A load-port input of the power table: the top's port, or zeros when the table is a ROM
/// or there is none.
fn rom_tie(cfg: &PipelineConfig, port: &str, width: u32) -> String {
    if cfg.power_table_unused().is_some() {
        format!("{width}'d0")
    } else {
        port.to_string()
    }
}

/// The fetch: `b` from `bump` (a template).
fn fetch(s: &mut Scheduler, cfg: &PipelineConfig, bump: &str, combinational: bool) {
    let u = fetch_unit(cfg);
    let nb3 = 3 * cfg.normal_bits;
    if combinational && !cfg.palette {
        let st = s.stage_of(&[bump]);
        let t = s.fill(bump, st);
        s.m.wire("b", nb3, None);
        s.m.inst_helper(cfg, "bump_fetch_comb", "u_bump_fetch", &[("bump", t), ("b", "b".into())]);
        s.source("b", st);
    } else {
        let port = units::inputs(u, cfg).remove(0).name;
        s.unit(
            cfg,
            u,
            &format!("u_{}", u.name()),
            &[(port, bump)],
            &[("b", "b")],
            &mem_params(cfg, u),
        );
    }
}

/// The bump normal the dot products read: the fetch's `b`, under `frame_transform` placed in
/// the fragment's frame (`{pre}_frame`) by the `frame_transform` unit (`bf`), and under
/// `renormalise_bump` the `normalise_b` unit's `bn` after that (the flat bypass keeps
/// comparing `b`).
fn dot_normal(s: &mut Scheduler, cfg: &PipelineConfig, pre: &str) -> String {
    let mut b = "{b}".to_string();
    if cfg.frame_transform {
        let u = units::unit("frame_transform").expect("unit");
        let mut frame = format!("{{{pre}_frame}}");
        // A unit that forms the frame reads its source from the port's first lanes (m: the T
        // lanes, or q: lanes 0 to 3) and N_i from the N lanes; the lanes between are unread.
        let former = match (cfg.frame_build, cfg.frame_quaternion) {
            (true, _) => Some(("frame_build", "m", 3)),
            (_, true) => Some(("quat_frame", "q", 4)),
            _ => None,
        };
        if let Some((name, source, lanes)) = former {
            let lh = cfg.lh_bits;
            let u = units::unit(name).expect("unit");
            let src = format!("{{{pre}_frame}}[{}:0]", lanes * lh - 1);
            let n_i = format!("{{{pre}_frame}}[{}:{}]", 9 * lh - 1, 6 * lh);
            s.unit(
                cfg,
                u,
                &format!("u_{name}"),
                &[(source, &src), ("n_i", &n_i)],
                &[("frame", "fb")],
                &[],
            );
            frame = "{fb}".into();
        }
        s.unit(cfg, u, "u_frame", &[("b", &b), ("frame", &frame)], &[("v", "bf")], &[]);
        if cfg.self_shadow {
            // The self-shadow gate's surface normal (`model::pipeline::surface_normal`): the
            // unperturbed normal placed in the same frame, its constant products folding away.
            let nb = cfg.normal_bits;
            let flat = format!("{{{nb}'d{}, {nb}'d0, {nb}'d0}}", cfg.normal_fmt().max_raw());
            s.unit(cfg, u, "u_frame_n", &[("b", &flat), ("frame", &frame)], &[("v", "nf")], &[]);
        }
        b = "{bf}".into();
    }
    if cfg.renormalise_bump {
        let u = units::unit("normalise_b").expect("unit");
        s.unit(cfg, u, "u_norm_b", &[("v", &b)], &[("n", "bn")], &[]);
        b = "{bn}".into();
    }
    b
}

/// Which blend a colour stage runs.
#[derive(Clone, Copy, PartialEq)]
enum Stage {
    Diffuse,
    Texture,
    Specular,
}

fn order(cfg: &PipelineConfig) -> [Stage; 3] {
    match cfg.blend_order {
        BlendOrder::DiffuseTextureSpecular => [Stage::Diffuse, Stage::Texture, Stage::Specular],
        BlendOrder::TextureLast => [Stage::Diffuse, Stage::Specular, Stage::Texture],
    }
}

/// The three colour stages in the configured order (paper §5.1, Figs. 2 and 3), by unit name.
pub fn stage_order(cfg: &PipelineConfig) -> [&'static str; 3] {
    order(cfg).map(|s| match s {
        Stage::Diffuse => "diffuse_blend",
        Stage::Texture => "texture_modulate",
        Stage::Specular => "specular_blend",
    })
}

/// The three colour stages from `c_in` (texture colour `tex`) in the configured order;
/// `blend(stage, c)` emits a blend stage and returns its output signal. Returns the final
/// colour signal.
fn colour_stages(
    s: &mut Scheduler,
    cfg: &PipelineConfig,
    c_in: &str,
    tex: &str,
    mut blend: impl FnMut(&mut Scheduler, Stage, &str) -> Option<String>,
) -> String {
    let mut c = c_in.to_string();
    let g = cfg.colour_guard_bits;
    if g > 0 {
        // Stage colours carry the guard bits: C_src enters with g zero fraction bits.
        let (cb, cs) = (cfg.colour_bits, cfg.stage_colour_fmt().width);
        let parts: Vec<String> = (0..3)
            .rev()
            .map(|ch| format!("{{{c_in}}}[{}:{}], {g}'d0", ch * cb + cb - 1, ch * cb))
            .collect();
        s.comb("c_src_g", 3 * cs, &format!("{{{}}}", parts.join(", ")));
        c = "c_src_g".into();
    }
    for st in order(cfg) {
        if st == Stage::Texture {
            let u = units::unit("texture_modulate").expect("unit");
            s.unit(
                cfg,
                u,
                "u_texture_modulate",
                &[("c_in", &format!("{{{c}}}")), ("tex", tex)],
                &[("c_out", "c_tex")],
                &[],
            );
            c = "c_tex".into();
        } else if let Some(out) = blend(s, st, &c) {
            c = out;
        }
    }
    if g > 0 {
        let u = units::unit("colour_round").expect("unit");
        s.unit(
            cfg,
            u,
            "u_colour_round",
            &[("c_in", &format!("{{{c}}}"))],
            &[("c_out", "c_rnd")],
            &[],
        );
        c = "c_rnd".into();
    }
    c
}

/// The bump state's signal names: `{pre}_l`, `{pre}_h`, `{pre}_lc`, `{pre}_k` templates.
/// A per-triangle top reads them from its banks (late signals `st_*`, see [`banks`]); a
/// per-fragment top from the fragment (`held`: the serial top's captured `fr_*`, else `in_*`).
fn state_pre(cfg: &PipelineConfig, held: bool) -> &'static str {
    match (cfg.per_triangle(), held) {
        (true, _) => "st",
        (false, true) => "fr",
        (false, false) => "in",
    }
}

/// The setup ports a register bank stores: every one but `tri_lc` with white lights (it stays
/// on the interface, unused).
fn banked_ports(cfg: &PipelineConfig) -> Vec<TopPort> {
    port_list(cfg)
        .into_iter()
        .filter(|p| p.kind == PortKind::Triangle && (p.name != "tri_lc" || !cfg.white_lights))
        .collect()
}

/// The triangle-setup port's register banks (per-triangle tops). A setup is written into the
/// bank after the current one and makes it current; a fragment is tagged with the current
/// bank when it is accepted (`tag` at stage 0) and reads its state there through late
/// signals `st_*`, at the stage that uses each field. Returns nothing: [`bank_ready`] closes
/// the handshake once every read is placed.
fn banks(s: &mut Scheduler, cfg: &PipelineConfig, tag: &str) {
    let k = cfg.triangle_banks;
    s.m.comment(format!(
        "Triangle setup: {k} register banks. A setup loads the bank after the current one and makes it current; fragments carry the bank's tag."
    ));
    bank_pointer(s, cfg);
    let tri = banked_ports(cfg);
    for p in &tri {
        let f = &p.name[4..];
        s.m.array(&format!("bank_{f}"), p.width(), k);
    }
    let writes: Vec<String> = tri
        .iter()
        .map(|p| format!("        bank_{0}[tri_next] <= {1};", &p.name[4..], p.name))
        .collect();
    s.m.raw(format!(
        "always @(posedge clk) begin\n    if (tri_accept) begin\n{}\n    end\nend",
        writes.join("\n")
    ));
    s.source(tag, 0);
    for p in &tri {
        let f = &p.name[4..];
        s.late(&format!("st_{f}"), p.width(), &format!("bank_{f}[{{{tag}}}]"));
    }
}

/// The current bank `tri_cur` and the one a setup loads, `tri_next`; a setup accepted at an
/// edge makes `tri_next` current.
fn bank_pointer(s: &mut Scheduler, cfg: &PipelineConfig) {
    let (k, bb) = (cfg.triangle_banks, cfg.bank_bits());
    s.m.reg_decl("tri_cur", bb);
    s.m.wire(
        "tri_next",
        bb,
        Some(&format!("(tri_cur == {bb}'d{}) ? {bb}'d0 : tri_cur + {bb}'d1", k - 1)),
    );
    s.m.wire("tri_accept", 1, Some("tri_valid && tri_ready"));
    s.m.raw(format!(
        "always @(posedge clk) begin\n    if (rst) tri_cur <= {bb}'d0;\n    else if (tri_accept) tri_cur <= tri_next;\nend"
    ));
}

/// `bank_free`: no fragment tagged with the next bank is at a stage `first..last`, where
/// `last` is the first stage at which every read of a bank is done (a combinational read at
/// that stage happens before the edge that would write, so it is not waited for).
fn bank_free(s: &mut Scheduler, tag: &str, valid: &str, first: u32, last: u32) {
    let mut busy = Vec::new();
    for st in first..last {
        let (v, t) = (s.at(valid, st), s.at(tag, st));
        busy.push(format!("({v} && {t} == tri_next)"));
    }
    s.m.comment(format!(
        "A bank is read up to stage {last}: a setup waits while the next bank has a fragment before that stage."
    ));
    let busy = if busy.is_empty() { "1'b0".to_string() } else { busy.join(" || ") };
    s.m.wire("bank_free", 1, Some(&format!("!({busy})")));
}

/// `tri_ready` of register banks: low during reset and while the next bank is not free.
/// Returns the last stage that reads a bank.
fn bank_ready(s: &mut Scheduler, tag: &str, valid: &str, first: u32) -> u32 {
    let last = s.late_max().expect("a per-triangle top reads its banks");
    bank_free(s, tag, valid, first, last);
    s.m.raw("assign tri_ready = !rst && bank_free;");
    last
}

/// The serial top's triangle banks as one RAM (`rtlgen::ram`, block RAM on an FPGA): word
/// {bank, slot} holds one light slot's state, in place of banks × lights × fields
/// flip-flops and their read multiplexers (the default four-light top did not fit an iCE40
/// HX8K with them). A RAM has one write port, so a setup writes its n slots one per edge
/// while the next bank is free, holding `tri_ready` low until the last (the setup's data is
/// held meanwhile, as valid/ready requires); fragment slot j is read at the edge that ends its
/// slot-j cycle at stage 0, so the fields are ready at stage 1 as `st_*`, one slot wide.
/// Returns the last stage that reads a bank in the sense of [`bank_free`].
/// The setup ports the serial top's bank RAM stores, lowest word bits first: only the
/// fields a blend reads (L for diffuse, H for specular).
fn bank_ram_ports(cfg: &PipelineConfig) -> Vec<TopPort> {
    port_list(cfg)
        .into_iter()
        .filter(|p| p.kind == PortKind::Triangle && state_field_used(cfg, &p.name[4..]))
        .collect()
}

/// Whether a blend reads bump-state field `f` (`l`, `h`, `lc`, `k`): L for diffuse, H for
/// specular, Lc unless every light is white.
fn state_field_used(cfg: &PipelineConfig, f: &str) -> bool {
    match f {
        "l" => cfg.diffuse,
        "h" => cfg.specular,
        "lc" => !cfg.white_lights && (cfg.diffuse || cfg.specular),
        _ => cfg.diffuse || cfg.specular,
    }
}

fn bank_ram(s: &mut Scheduler, cfg: &PipelineConfig, jb: u32) -> u32 {
    let (k, bb, n) = (cfg.triangle_banks, cfg.bank_bits(), cfg.lights);
    s.m.comment(format!(
        "Triangle setup: {k} banks of {n} light slot(s) in one RAM, word {{bank, slot}}. A setup writes the bank after the current one, a slot per edge, and makes it current at its last."
    ));
    bank_pointer(s, cfg);
    s.source("fr_tag", 0);
    let tri = bank_ram_ports(cfg);
    s.m.reg_decl("tri_slot", jb);
    let word: u32 = tri.iter().map(|p| p.width() / n).sum();
    let parts: Vec<String> = tri
        .iter()
        .rev()
        .map(|p| super::writer::lane(&p.name, n, "tri_slot", p.width() / n))
        .collect();
    s.m.wire("tri_word", word, Some(&format!("{{{}}}", parts.join(", "))));
    s.m.wire("bank_rd", word, None);
    s.m.raw(format!(
        "{} #(.WIDTH({word}), .DEPTH({}), .ABITS({}), .INIT_FILE(\"\")) u_banks (.clk(clk), .we(tri_we), .waddr({{tri_next, tri_slot}}), .wdata(tri_word), .raddr({{fr_tag, j}}), .rdata(bank_rd));",
        module_name(cfg, super::ram::RAM),
        k << jb,
        bb + jb
    ));
    s.source("bank_rd", 1);
    let mut off = 0;
    for p in &tri {
        let ws = p.width() / n;
        s.comb(&format!("st_{}", &p.name[4..]), ws, &format!("{{bank_rd}}[{}:{off}]", off + ws - 1));
        off += ws;
    }
    // The RAM reads at the edge ending stage 0: a write to the bank must wait for stage 0.
    bank_free(s, "fr_tag", "busy", 0, 1);
    s.m.wire("tri_we", 1, Some("tri_valid && bank_free && !rst"));
    s.m.raw(format!("assign tri_ready = !rst && bank_free && tri_slot == {jb}'d{};", n - 1));
    s.m.raw(format!(
        "always @(posedge clk) begin\n    if (rst || !tri_we || tri_ready) tri_slot <= {jb}'d0;\n    else tri_slot <= tri_slot + {jb}'d1;\nend"
    ));
    1
}

fn parallel(s: &mut Scheduler, cfg: &PipelineConfig) -> Body {
    if cfg.backpressure {
        s.m.wire("credit", 1, None);
        s.m.raw("assign in_ready = credit;");
    } else {
        s.m.raw("assign in_ready = 1'b1;");
    }
    s.m.wire("accept", 1, Some("in_valid && in_ready"));
    for p in port_list(cfg).iter().filter(|p| p.kind == PortKind::Fragment) {
        s.source(&p.name, 0);
    }
    s.source("accept", 0);
    s.valid_bit("accept");
    if cfg.per_triangle() {
        banks(s, cfg, "tri_cur");
    }
    let pre = state_pre(cfg, false);
    s.m.comment("The fetch; the rest of the fragment waits beside it.");
    fetch(s, cfg, "{in_bump}", false);
    let bn = &dot_normal(s, cfg, pre);
    if cfg.embm() {
        embm_factors(s, cfg, bn);
    } else {
        light_factors(s, cfg, pre, bn);
    }
    s.m.comment("The colour stages in the configured order.");
    let out = colour_stages(s, cfg, "in_c_src", "{in_tex}", |s, st, c| {
        let (u, f, name, frac) = match st {
            Stage::Diffuse if cfg.diffuse => (&units::DIFFUSE_BLEND, "{dfac}", "c_dif", cfg.dot_frac_bits),
            Stage::Specular if cfg.specular => (&units::SPECULAR_BLEND, "{sfac}", "c_spe", cfg.power_frac_bits),
            _ => return None,
        };
        let c_in = format!("{{{c}}}");
        // EMBM's light slots are the texels: k is one and the colours are the map's.
        let (k, lc) = if cfg.embm() {
            let kw = cfg.k_frac_bits + 1;
            let one = format!("{kw}'d{}", 1u64 << cfg.k_frac_bits);
            (
                format!("{{{one}, {one}, {one}, {one}}}"),
                if st == Stage::Diffuse { "{td}" } else { "{ts}" }.to_string(),
            )
        } else {
            (format!("{{{pre}_k}}"), format!("{{{pre}_lc}}"))
        };
        let mut ins = vec![("c_in", c_in.as_str()), ("f", f), ("k", k.as_str())];
        if !cfg.white_lights {
            ins.push(("lc", lc.as_str()));
        }
        s.unit(cfg, u, &format!("u_{}", u.name()), &ins, &[("c_out", name)], &[]);
        s.m.factor_frac(frac);
        Some(name.to_string())
    });
    let lat = s.ready(&out);
    let v = s.at("accept", lat);
    // Stage 0 is the accepting cycle: that fragment is tagged with the current bank, which a
    // setup never writes; stage s ends s edges after the accept.
    let hold = cfg.per_triangle().then(|| bank_ready(s, "tri_cur", "accept", 1));
    (lat, out, v, hold)
}

/// EMBM's blend factors and texels (paper §3.3): `env_coords` on the fetched normal's x and
/// y, the two maps' `env_fetch`, and the bilinear weights as `dfac` and `sfac` (each aligned
/// from u1.8, gated by its enable).
fn embm_factors(s: &mut Scheduler, cfg: &PipelineConfig, bn: &str) {
    use crate::model::env_map::WEIGHT_FRAC_BITS;
    use crate::rtlgen::env_v::WEIGHT_BITS;
    let nb = cfg.normal_bits;
    let ff1 = cfg.factor_frac() + 1;
    let coords = units::unit("env_coords").expect("unit");
    s.m.comment("EMBM: the map coordinates, then the four texels of each map.");
    s.unit(
        cfg,
        coords,
        "u_env_coords",
        &[("b", &format!("{bn}[{}:0]", 2 * nb - 1)), ("st", "{in_st}"), ("m", "{in_m}")],
        &[("x0", "ex0"), ("y0", "ey0"), ("w", "ew")],
        &[],
    );
    for (on, name, out, fac, en, frac) in [
        (
            cfg.diffuse,
            "env_fetch_diffuse",
            "td",
            "dfac",
            ("de", "in_diffuse_en"),
            cfg.dot_frac_bits,
        ),
        (
            cfg.specular,
            "env_fetch_specular",
            "ts",
            "sfac",
            ("se", "in_specular_en"),
            cfg.power_frac_bits,
        ),
    ] {
        if !on {
            continue;
        }
        let u = units::unit(name).expect("unit");
        s.unit(
            cfg,
            u,
            &format!("u_{name}"),
            &[("x0", "{ex0}"), ("y0", "{ey0}")],
            &[("t", out)],
            &mem_params(cfg, u),
        );
        s.comb(en.0, 1, &enable(cfg, true, en.1));
        let parts: Vec<String> = (0..4)
            .rev()
            .map(|i| {
                // The weight in the factor's format: u1.8 widened to u1.frac, then aligned.
                let lane = format!("{{ew}}[{}:{}]", i * WEIGHT_BITS + WEIGHT_BITS - 1, i * WEIGHT_BITS);
                let pad = frac - WEIGHT_FRAC_BITS;
                let wgt = if pad > 0 { format!("{{{lane}, {pad}'d0}}") } else { lane };
                factor(cfg, &wgt, frac, &format!("{{{}}}", en.0))
            })
            .collect();
        s.comb(fac, 4 * ff1, &format!("{{{}}}", parts.join(", ")));
    }
}

/// The light slots' blend factors (paper §4.2): one `dot_clamp` per light for B·L_i into
/// `dfac`, and B·H_i through the power unit into `sfac`, with the renormalise units, the
/// self-shadow gates and the enables.
fn light_factors(s: &mut Scheduler, cfg: &PipelineConfig, pre: &str, bn: &str) {
    let n = cfg.lights;
    let (lh3, f1, p1, ff1) = (
        3 * cfg.lh_bits,
        cfg.dot_frac_bits + 1,
        cfg.power_frac_bits + 1,
        cfg.factor_frac() + 1,
    );
    let dot = units::unit("dot_clamp").expect("unit");
    let norm = units::unit(crate::model::normalise::lh_unit(cfg)).expect("unit");
    // Which vectors are renormalised before their dot products: H, and L when interpolated.
    let (norm_l, norm_h) = crate::model::normalise::renormalised(cfg);
    let renormalised = |v: &str| if v == "l" { norm_l } else { norm_h };
    // One dot_clamp per light slot: B·L_i into fd<i>, or B·H_i into xh<i>.
    let dots = |s: &mut Scheduler, v: &str, out: &str| {
        for i in 0..n {
            let mut lanes = format!("{{{pre}_{v}}}{}", lane(i, lh3));
            if v == "h" && cfg.pixel_lh {
                lanes = half_sum(s, cfg, norm, pre, i);
            }
            if renormalised(v) {
                let nv = format!("n{v}{i}");
                s.unit(cfg, norm, &format!("u_norm_{v}{i}"), &[("v", &lanes)], &[("n", &nv)], &[]);
                lanes = format!("{{{nv}}}");
            }
            s.unit(
                cfg,
                dot,
                &format!("u_dot_{v}{i}"),
                &[("b", bn), ("v", &lanes)],
                &[("f", &format!("{out}{i}"))],
                &[],
            );
        }
    };
    if cfg.diffuse {
        s.comb("de", 1, &enable(cfg, true, "in_diffuse_en"));
        dots(s, "l", "fd");
        if cfg.self_shadow {
            // Light i is above the surface where its L, as its dot product sees it, has z > 0
            // in bump space, or makes N·L > 0 with the frame's surface normal.
            let lh = cfg.lh_bits;
            for i in 0..n {
                let l = if norm_l {
                    format!("{{nl{i}}}")
                } else {
                    format!("{{{pre}_l}}{}", lane(i, lh3))
                };
                if cfg.frame_transform {
                    s.unit(
                        cfg,
                        dot,
                        &format!("u_dot_n{i}"),
                        &[("b", "{nf}"), ("v", &l)],
                        &[("f", &format!("ln{i}"))],
                        &[],
                    );
                    s.comb(&format!("lit{i}"), 1, &format!("{{ln{i}}} != 0"));
                } else {
                    // L's z lane alone: the top lh bits of the light's three.
                    let z = if norm_l {
                        format!("{{nl{i}}}[{}:{}]", 3 * lh - 1, 2 * lh)
                    } else {
                        format!("{{{pre}_l}}[{}:{}]", i * lh3 + 3 * lh - 1, i * lh3 + 2 * lh)
                    };
                    s.comb(&format!("lz{i}"), lh, &z);
                    s.comb(&format!("lit{i}"), 1, &above_z(cfg, &format!("{{lz{i}}}")));
                }
            }
        }
        let parts: Vec<String> = (0..n)
            .rev()
            .map(|i| {
                factor(
                    cfg,
                    &format!("{{fd{i}}}"),
                    cfg.dot_frac_bits,
                    &shadowed(cfg, "{de}", &format!("{{lit{i}}}"), None),
                )
            })
            .collect();
        s.comb("dfac", n * ff1, &format!("{{{}}}", parts.join(", ")));
    }
    if cfg.specular {
        s.comb("se", 1, &enable(cfg, true, "in_specular_en"));
        dots(s, "h", "xh");
        let xs: Vec<String> = (0..n).rev().map(|i| format!("{{xh{i}}}")).collect();
        s.comb("xh", n * f1, &format!("{{{}}}", xs.join(", ")));
        s.m.comment(format!("The power unit with {n} read port(s)."));
        power_unit(s, cfg, n);
        let parts: Vec<String> = (0..n)
            .rev()
            .map(|i| {
                let fd = format!("{{fd{i}}}");
                factor(
                    cfg,
                    &format!("{{fs}}{}", lane(i, p1)),
                    cfg.power_frac_bits,
                    &shadowed(cfg, "{se}", &format!("{{lit{i}}}"), Some(&fd)),
                )
            })
            .collect();
        s.comb("sfac", n * ff1, &format!("{{{}}}", parts.join(", ")));
    }
}

/// Bits of the serial top's light slot index `j`.
fn slot_bits(cfg: &PipelineConfig) -> u32 {
    (32 - (cfg.lights.max(2) - 1).leading_zeros()).max(1)
}

fn serial(s: &mut Scheduler, cfg: &PipelineConfig) -> Body {
    let n = cfg.lights;
    let (c3, lh3) = (3 * cfg.colour_bits, 3 * cfg.lh_bits);
    let jb = slot_bits(cfg);
    s.m.comment("Light sequencer: a fragment is held for n cycles, light slot j in cycle j.");
    s.m.reg_decl("busy", 1);
    s.m.reg_decl("j", jb);
    s.m.wire("last", 1, Some(&format!("(j == {jb}'d{})", n - 1)));
    s.m.wire("first", 1, Some(&format!("(j == {jb}'d0)")));
    if cfg.backpressure {
        s.m.wire("credit", 1, None);
        s.m.raw("assign in_ready = (!busy || last) && credit;");
    } else {
        s.m.raw("assign in_ready = !busy || last;");
    }
    s.m.wire("accept", 1, Some("in_valid && in_ready"));
    s.m.raw(format!(
        "always @(posedge clk) begin\n    if (rst) begin\n        busy <= 1'b0;\n        j <= {jb}'d0;\n    end\n    else if (accept) begin\n        busy <= 1'b1;\n        j <= {jb}'d0;\n    end\n    else if (busy) begin\n        busy <= !last;\n        j <= last ? {jb}'d0 : j + {jb}'d1;\n    end\nend"
    ));
    // The accepting edge captures the fragment: slot 0 runs in the next cycle, stage 0.
    for p in port_list(cfg)
        .iter()
        .filter(|p| p.kind == PortKind::Fragment && (p.name != "in_lc" || !cfg.white_lights))
    {
        let fr = format!("fr_{}", &p.name[3..]);
        s.m.reg_decl(&fr, p.width());
        s.m.raw(format!("always @(posedge clk) if (accept) {fr} <= {};", p.name));
        s.source(&fr, 0);
    }
    for sig in ["busy", "j", "first", "last"] {
        s.source(sig, 0);
    }
    s.valid_bit("busy");
    let read_done = cfg.per_triangle().then(|| {
        s.m.reg_decl("fr_tag", cfg.bank_bits());
        s.m.raw("always @(posedge clk) if (accept) fr_tag <= tri_cur;");
        bank_ram(s, cfg, jb)
    });
    let pre = state_pre(cfg, true);
    fetch(s, cfg, "{fr_bump}", true);
    let bn = &dot_normal(s, cfg, pre);
    let k1 = cfg.k_frac_bits + 1;
    // The held fragment's state is every slot, indexed by j; a bank RAM word is one slot.
    let slot = |f: &str, w: u32| {
        if cfg.per_triangle() {
            format!("{{st_{f}}}")
        } else {
            super::writer::lane(&format!("{{{pre}_{f}}}"), cfg.lights, "{j}", w)
        }
    };
    if !cfg.white_lights {
        s.comb("lc_sel", c3, &slot("lc", c3));
    }
    s.comb("k_sel", k1, &slot("k", k1));
    let dot = units::unit("dot_clamp").expect("unit");
    let acc = units::unit("light_accumulate").expect("unit");
    let aw3 = 3 * cfg.acc_fmt().width;
    let accumulate = |s: &mut Scheduler, name: &str, f: &str, frac: u32| {
        // The accumulator feeds itself back: slot j adds to the sum of slots 0..j-1.
        let lc_sel = if cfg.white_lights { "" } else { "{lc_sel}" };
        let st = s.stage_of(&[f, "{k_sel}", lc_sel, "{first}"]);
        let (ff, k, lc, first) = (s.fill(f, st), s.fill("{k_sel}", st), s.fill(lc_sel, st), s.fill("{first}", st));
        s.m.wire(name, aw3, None);
        let mut conns = vec![("acc_in", name.to_string()), ("first", first), ("f", ff), ("k", k)];
        if !cfg.white_lights {
            conns.push(("lc", lc));
        }
        conns.push(("acc", name.to_string()));
        s.m.inst(cfg, acc, &format!("u_{name}"), &conns, &[]);
        s.m.factor_frac(frac);
        s.source(name, st + acc.latency(cfg));
        // The sum is complete after the last slot: from here on a fragment is valid once.
        if !s.m.has("done") {
            let (last, v) = (s.fill("{last}", st), s.fill("{busy}", st));
            s.m.reg("done", 1, &format!("{v} && {last}"), true);
            s.source("done", st + 1);
            s.valid_bit("done");
        }
    };
    if cfg.diffuse {
        s.comb("de", 1, &enable(cfg, true, "fr_diffuse_en"));
        s.comb("l_sel", lh3, &slot("l", lh3));
        s.unit(cfg, dot, "u_dot_l", &[("b", bn), ("v", "{l_sel}")], &[("f", "fd")], &[]);
        if cfg.self_shadow {
            let lh = cfg.lh_bits;
            if cfg.frame_transform {
                s.unit(cfg, dot, "u_dot_n", &[("b", "{nf}"), ("v", "{l_sel}")], &[("f", "ln")], &[]);
                s.comb("lit", 1, "{ln} != 0");
            } else {
                s.comb("lit", 1, &above_z(cfg, &format!("{{l_sel}}[{}:{}]", 3 * lh - 1, 2 * lh)));
            }
        }
        let de = shadowed(cfg, "{de}", "{lit}", None);
        s.comb("dfac", cfg.factor_frac() + 1, &factor(cfg, "{fd}", cfg.dot_frac_bits, &de));
        accumulate(s, "dacc", "{dfac}", cfg.dot_frac_bits);
    }
    if cfg.specular {
        s.comb("se", 1, &enable(cfg, true, "fr_specular_en"));
        s.comb("h_sel", lh3, &slot("h", lh3));
        s.unit(cfg, dot, "u_dot_h", &[("b", bn), ("v", "{h_sel}")], &[("f", "xh")], &[]);
        power_unit(s, cfg, 1);
        let se = shadowed(cfg, "{se}", "{lit}", Some("{fd}"));
        s.comb("sfac", cfg.factor_frac() + 1, &factor(cfg, "{fs}", cfg.power_frac_bits, &se));
        accumulate(s, "sacc", "{sfac}", cfg.power_frac_bits);
    }
    if !s.m.has("done") {
        // Neither blend: the fragment leaves after its last slot.
        s.m.reg("done", 1, "busy && last", true);
        s.source("done", 1);
        s.valid_bit("done");
    }
    let finish = units::unit("blend_finish").expect("unit");
    let out = colour_stages(s, cfg, "fr_c_src", "{fr_tex}", |s, st, c| {
        let (acc, name, inst) = match st {
            Stage::Diffuse if cfg.diffuse => ("{dacc}", "c_dif", "u_diffuse_finish"),
            Stage::Specular if cfg.specular => ("{sacc}", "c_spe", "u_specular_finish"),
            _ => return None,
        };
        // The finish waits for the complete sum (`done`), not for its first slot.
        let at = s.stage_of(&[acc, &format!("{{{c}}}"), "{done}"]);
        let (cc, a) = (s.fill(&format!("{{{c}}}"), at), s.fill(acc, at));
        s.m.wire(name, 3 * cfg.stage_colour_fmt().width, None);
        s.m.inst(cfg, finish, inst, &[("c_in", cc), ("acc", a), ("c_out", name.to_string())], &[]);
        s.m.factor_frac(if inst == "u_diffuse_finish" {
            cfg.dot_frac_bits
        } else {
            cfg.power_frac_bits
        });
        s.source(name, at + finish.latency(cfg));
        Some(name.to_string())
    });
    let lat_out = s.stage_of(&[&format!("{{{out}}}"), "{done}"]);
    let c = s.fill(&format!("{{{out}}}"), lat_out);
    let v = s.fill("{done}", lat_out);
    // Stage 0 holds the fragment (in fr_*) for its n slot cycles, reading its bank; the last
    // slot's stage s ends n + s edges after the accept, and the setup's n slot writes end
    // n - 1 edges after the first.
    let hold = read_done.map(|last| cfg.lights + last + setup_edges(cfg) - 1);
    // Stages count from the cycle of a fragment's slot; its last slot runs n - 1 cycles after
    // the cycle following the accepting edge.
    (cfg.lights + lat_out, c, v, hold)
}
