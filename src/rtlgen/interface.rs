//! The machine-readable interface of the generated top: ports, widths, the fixed-point
//! format of every field, latency, initiation interval and ROM files, as JSON.

use super::top::{latency, top_ports};
use super::units_v::{module_name, rom_file_name};
use crate::config::PipelineConfig;
use serde_json::json;

pub fn interface_json(cfg: &PipelineConfig, command: &str) -> String {
    let fmt = |p: &str| -> serde_json::Value {
        let (f, lanes, doc) = match p {
            "in_texel" => (
                crate::fixed::Format::u(cfg.normal_bits, 0),
                3,
                "stored bump texel, offset binary, x in the low bits",
            ),
            "in_c_src" => (cfg.colour_fmt(), 3, "Gouraud colour C_src, R in the low bits"),
            "in_t" => (cfg.colour_fmt(), 3, "texel colour T"),
            "in_l" => (cfg.lh_fmt(), 3 * cfg.lights, "L_i in bump space, light 0 x in the low bits"),
            "in_h" => (cfg.lh_fmt(), 3 * cfg.lights, "H_i in bump space"),
            "in_lc" => (cfg.colour_fmt(), 3 * cfg.lights, "light colours Lc_i"),
            "in_k" => (cfg.k_fmt(), cfg.lights, "k_i"),
            "out_c" => (cfg.colour_fmt(), 3, "C_new"),
            "pt_wdata" => (cfg.power_fmt(), 1, "power-table entry"),
            _ => return json!(null),
        };
        json!({"format": f.name(), "lane_bits": f.width, "lanes": lanes, "doc": doc})
    };
    let ports: Vec<_> = top_ports(cfg)
        .iter()
        .map(|(n, d, w)| json!({"name": n, "dir": d, "width": w, "field": fmt(n)}))
        .collect();
    let v = json!({
        "generator": crate::TOOL,
        "regenerate": command,
        "config_hash": cfg.hash(),
        "config": cfg,
        "top": module_name(cfg, "gbump_pipeline"),
        "clock": "clk, rising edge; rst synchronous, active high, clears the valid bits",
        "latency_cycles": latency(cfg),
        "initiation_interval": cfg.initiation_interval(),
        "handshake": "a fragment is accepted at a rising edge at which in_valid && in_ready are high; its C_new is on out_c, with out_valid high, when sampled at the rising edge exactly latency_cycles later; results leave in order",
        "latency_definition": "rising edges from the edge that accepts a fragment to the edge at which its out_valid is first sampled high",
        "initiation_interval_definition": "rising edges between two accepts while in_valid stays high: in_ready is low for the initiation_interval - 1 edges after an accept and high at the next",
        "parameters": {"INIT_FILE": {"default": rom_file_name(cfg, "power_table", "hex"), "doc": "$readmemh file with the power table's power-up contents; relative paths resolve against the simulator's working folder"}},
        "power_table": {"init_file": rom_file_name(cfg, "power_table", "hex"), "unit": cfg.power_design().label(), "words": cfg.power_depth(), "entry_format": cfg.power_fmt().name(), "shininess": cfg.shininess, "load_port": "pt_we, pt_waddr, pt_wdata; write when idle"},
        "files": {
            "filelist": super::kit::filelist_names(cfg).0,
            "filelist_icarus": super::kit::filelist_names(cfg).1,
            "yosys_script": super::kit::filelist_names(cfg).2,
            "waivers": format!("{}.vlt", module_name(cfg, "gbump_pipeline")),
            "fusesoc_core": format!("{}.core", module_name(cfg, "gbump_pipeline")),
            "sv_package": super::kit::package_file_name(cfg),
            "testbench": super::kit::tb_file_name(cfg),
        },
        "ports": ports,
    });
    serde_json::to_string_pretty(&v).expect("json") + "\n"
}

/// The README's interface section: top ports, then every unit's ports.
pub fn interface_markdown(cfg: &PipelineConfig) -> String {
    let mut s = format!(
        "Top `{}` (config `{}`): latency {} cycles, one fragment every {} cycle(s).\n\n| port | dir | bits |\n|---|---|---|\n",
        crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline"),
        cfg.hash(),
        crate::rtlgen::top::latency(cfg),
        cfg.initiation_interval()
    );
    for (n, d, w) in crate::rtlgen::top::top_ports(cfg) {
        s += &format!("| `{n}` | {d} | {w} |\n");
    }
    s + "\n" + &crate::units::markdown_table(cfg)
}
