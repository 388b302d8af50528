//! The RTL generator: Verilog-2005 for every unit of `units::UNITS` and the top pipeline,
//! ROM init files, and a machine-readable interface description, all from one
//! `PipelineConfig`. Output is deterministic: the same config gives the same bytes.

pub mod booth;
pub mod env_v;
pub mod fixed_ops;
pub mod fpga_shell;
pub mod frame_build_v;
pub mod frame_transform_v;
pub mod integration_doc;
pub mod interface;
pub mod kit;
pub mod module;
pub mod normalise_cube_v;
pub mod normalise_v;
pub mod power_units;
pub mod quat_frame_v;
pub mod ram;
pub mod rom;
pub mod rom_files;
pub mod rtl_set;
pub mod schedule;
pub mod testbench;
pub mod top;
pub mod units_v;
pub mod writer;

use crate::config::PipelineConfig;
use header::header;
use units_v::{module_name, rom_file_name};

pub mod header;

/// One generated file: name and contents.
pub type GenFile = (String, String);

/// Every file of the RTL for `cfg`; `command` is what regenerates them (for headers).
pub fn generate(cfg: &PipelineConfig, command: &str) -> Vec<GenFile> {
    let mut files: Vec<GenFile> = Vec::new();
    let mut v = |unit: &str, body: String| {
        let name = format!("{}.v", module_name(cfg, unit));
        files.push((
            name,
            format!("{}{body}", header(cfg, command, &format!("{unit}: Verilog-2005"), "// ")),
        ));
    };
    // Every included unit's modules; a helper two units share is written once.
    let mut seen = std::collections::BTreeSet::new();
    for u in crate::units::included(cfg) {
        for (name, body) in u.verilog(cfg) {
            if seen.insert(name) {
                v(name, body);
            }
        }
    }
    // The top's own RAMs (bank RAM, output buffer) need the module whatever units are in.
    if top::uses_ram_module(cfg) && seen.insert(ram::RAM) {
        v(ram::RAM, ram::ram(cfg));
    }
    v("gbump_pipeline", top::top(cfg));
    if cfg.palette {
        let pal = rom::palette_rom(cfg, &rom::default_palette(cfg), rom::DEFAULT_PALETTE);
        let hl = rom::rom_header(&pal, Some(cfg), command, "palette_fetch reset contents ($readmemh)");
        files.push((
            rom_file_name(cfg, "bump_palette_spiral", "hex"),
            rom::write(&pal, rom::RomFormat::Hex, &hl),
        ));
    }
    if cfg.embm() {
        let maps = crate::model::env_map::default_maps(cfg);
        for (which, map) in [("diffuse", &maps.diffuse), ("specular", &maps.specular)] {
            let on = if which == "diffuse" { cfg.diffuse } else { cfg.specular };
            if !on {
                continue;
            }
            let rom = rom::env_map_rom(cfg, map, which, rom::DEFAULT_ENV_MAPS);
            let hl = rom::rom_header(&rom, Some(cfg), command, &format!("env_fetch_{which} reset contents ($readmemh)"));
            files.push((
                rom_file_name(cfg, &format!("env_{which}_default"), "hex"),
                rom::write(&rom, rom::RomFormat::Hex, &hl),
            ));
        }
    }
    let table = rom::power_rom(cfg, cfg.shininess);
    let hl = rom::rom_header(&table, Some(cfg), command, "power_table reset contents ($readmemh)");
    files.push((
        rom_file_name(cfg, "power_table", "hex"),
        rom::write(&table, rom::RomFormat::Hex, &hl),
    ));
    files.push((
        format!("{}.json", module_name(cfg, "gbump_pipeline")),
        interface::interface_json(cfg, command),
    ));
    files.push((format!("{}.vlt", module_name(cfg, "gbump_pipeline")), waivers(cfg, command)));
    let srcs = sources(&files);
    files.extend(kit::filelists(cfg, command, &srcs));
    files.push((kit::package_file_name(cfg), kit::package(cfg, command)));
    // The top testbench, powering up from the init file in the simulator's working folder.
    let init = writer::verilog_string(&rom_file_name(cfg, "power_table", "hex"));
    let extra: Vec<(String, String)> = top::memory_inits(cfg)
        .into_iter()
        .map(|(p, _, f)| (p, writer::verilog_string(&f)))
        .collect();
    let tb = testbench::tb_top_init(cfg, &init, &extra);
    files.push((
        kit::tb_file_name(cfg),
        format!("{}{tb}", header(cfg, command, "tb_top: the top testbench (plusargs below)", "// ")),
    ));
    files.push((
        format!("{}.core", module_name(cfg, "gbump_pipeline")),
        kit::core(cfg, command, &srcs),
    ));
    files
}

/// Verilog source names of the RTL in `files`, in compile order (for simulator command lines
/// and filelists); the generated testbench is not one of them.
pub fn sources(files: &[GenFile]) -> Vec<String> {
    let tb = |n: &str| n.starts_with("tb_top_");
    files
        .iter()
        .filter(|f| f.0.ends_with(".v") && !tb(&f.0))
        .map(|f| f.0.clone())
        .collect()
}

/// Verilator waivers, each with its reason.
fn waivers(cfg: &PipelineConfig, command: &str) -> String {
    let h = &cfg.hash()[..8];
    let mut s = String::from("`verilator_config\n");
    s += &header(
        cfg,
        command,
        "Lint waivers (a comment may not begin with the tool name: it would be a metacomment)",
        "// ",
    );
    s += "// A rounding shift keeps the high bits of its sum and drops the low ones by design; the\n";
    s += "// top bits are zero by construction (the index never exceeds N-1, the product never 2^(2w)).\n";
    s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*power_unit_{h}.v\" -match \"Bits of signal are not used: 'rounded'*\"\n");
    s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*texture_modulate_{h}.v\" -match \"Bits of signal are not used: 'q*\"\n");
    if cfg.colour_guard_bits > 0 {
        s += "// colour_round keeps the integer bits of the rounded stage colour and drops its guard bits.\n";
        s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*colour_round_{h}.v\" -match \"Bits of signal are not used: 'r*\"\n");
    }
    for (on, unit) in [
        (cfg.renormalise && cfg.cube_map_face == 0, "normalise"),
        (cfg.renormalise_bump, "normalise_b"),
        (cfg.frame_build, crate::rtlgen::frame_build_v::NORMALISE),
    ] {
        if on {
            s += &format!("// {unit} reads the top bits of the shifted squared length (the table index, m) and keeps\n");
            s += "// the high bits of each Newton product, truncating the rest by design.\n";
            for sig in ["sn", "rr*_p", "mq*_p", "re*_p"] {
                s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*{unit}_{h}.v\" -match \"Bits of signal are not used: '{sig}'*\"\n");
            }
        }
    }
    if cfg.embm() {
        s += "// env_coords keeps the texel index and four sub-texel bits of the clamped coordinate and\n";
        s += "// truncates the rest by design; the top reads the fetched normal's x and y, not its z.\n";
        for sig in ["cx", "cy"] {
            s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*env_coords_{h}.v\" -match \"Bits of signal are not used: '{sig}'*\"\n");
        }
        s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*gbump_pipeline_{h}.v\" -match \"Bits of signal are not used: 'b'*\"\n");
        s += "// EMBM has no power unit: the top's INIT_FILE (the power table's) stays a parameter, unread.\n";
        s += &format!("lint_off -rule UNUSEDPARAM -file \"*gbump_pipeline_{h}.v\" -match \"Parameter is not used: 'INIT_FILE'\"\n");
    }
    if cfg.pixel_lh {
        s += "// pixel_lh halves the sum of the normalised L and V: each component's low bit is dropped by design.\n";
        s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*gbump_pipeline_{h}.v\" -match \"Bits of signal are not used: 'hs*\"\n");
    }
    if cfg.frame_build || cfg.frame_quaternion {
        s += "// frame_build reads in_frame's T and N lanes (m and N_i), quat_frame its lanes 0 to 3 (q) and 6 to 8 (N_i); the others stay on the port, unread.\n";
        // The serial top registers the fragment port first (fr_frame).
        for sig in ["in_frame", "fr_frame"] {
            s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*gbump_pipeline_{h}.v\" -match \"Bits of signal are not used: '{sig}'*\"\n");
        }
    }
    if !matches!(
        cfg.power_unit,
        crate::config::PowerUnitKind::Table | crate::config::PowerUnitKind::Squaring
    ) {
        s += "// The power unit's core keeps the high bits of its rounded interpolation step and of the scaled\n";
        s += "// index and drops the rest by design; an entry index never reaches its top bits.\n";
        for sig in ["step", "scaled", "j", "off", "prod"] {
            s +=
                &format!("lint_off -rule UNUSEDSIGNAL -file \"*power_unit_core_{h}.v\" -match \"Bits of signal are not used: '{sig}'*\"\n");
        }
    }
    if cfg.power_unit == crate::config::PowerUnitKind::Squaring {
        s += "// The squaring power unit keeps the high bits of each rounded product and reads no table.\n";
        for sig in ["xw_r", "sq*_r", "mu*_r", "fin"] {
            s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*power_unit_{h}.v\" -match \"Bits of signal are not used: '{sig}'*\"\n");
        }
        s += &format!("lint_off -rule UNUSEDPARAM -file \"*power_unit_{h}.v\" -match \"Parameter is not used: 'INIT_FILE'\"\n");
    }
    if let Some(why) = cfg.power_table_unused() {
        s += &format!("// {why}: the power table's load port stays on the interface, unused.\n");
        for sig in ["power_table_we", "power_table_waddr", "power_table_wdata"] {
            s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*gbump_pipeline_{h}.v\" -match \"Signal is not used: '{sig}'\"\n");
        }
    }
    if cfg.white_lights {
        s += "// White lights: the light-colour port stays on the interface, unused (every Lc is 1).\n";
        for sig in ["in_lc", "tri_lc"] {
            s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*gbump_pipeline_{h}.v\" -match \"Signal is not used: '{sig}'\"\n");
        }
    }
    // Every configuration has the same top ports; the enable of a blend unit this
    // configuration leaves out is accepted and ignored.
    for (present, en) in [(cfg.diffuse, "de"), (cfg.specular, "se")] {
        if !present {
            s += "// This configuration has no ";
            s += if en == "de" { "diffuse blend" } else { "specular path" };
            s += ": its enable, light vectors (and power-table port) stay on the interface, unused.\n";
            let sigs: &[&str] = if en == "de" {
                &["in_diffuse_en", "in_l", "fr_diffuse_en", "fr_l", "bank_l", "tri_l"]
            } else {
                &[
                    "in_specular_en",
                    "in_h",
                    "power_table_we",
                    "power_table_waddr",
                    "power_table_wdata",
                    "fr_specular_en",
                    "fr_h",
                    "bank_h",
                    "tri_h",
                ]
            };
            for sig in sigs {
                s += &format!("lint_off -rule UNUSEDSIGNAL -file \"*gbump_pipeline_{h}.v\" -match \"Signal is not used: '{sig}'\"\n");
            }
            if en == "se" {
                s += &format!("lint_off -rule UNUSEDPARAM -file \"*gbump_pipeline_{h}.v\" -match \"Parameter is not used: 'INIT_FILE'\"\n");
            }
        }
    }
    s
}
