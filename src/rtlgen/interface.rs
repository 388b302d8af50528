//! The machine-readable interface of the generated top: ports, widths, the fixed-point
//! format of every field, latency, initiation interval and ROM files, as JSON.

use super::top::latency;
use super::units_v::{module_name, rom_file_name};
use crate::config::PipelineConfig;
use serde_json::json;

pub fn interface_json(cfg: &PipelineConfig, command: &str) -> String {
    let ports: Vec<_> = super::top::port_list(cfg)
        .iter()
        .map(|p| {
            let dir = if p.dir == crate::units::Dir::In { "input" } else { "output" };
            let field = if p.kind == super::top::PortKind::Control {
                json!(null)
            } else {
                json!({"format": p.fmt.name(), "lane_bits": p.fmt.width, "lanes": p.lanes, "doc": p.doc})
            };
            json!({"name": p.name, "dir": dir, "kind": p.kind, "width": p.width(), "field": field})
        })
        .collect();
    let mut params = serde_json::Map::new();
    let mut memories = serde_json::Map::new();
    let read: Vec<&str> = super::top::read_memories(cfg).iter().map(|m| m.prefix).collect();
    for m in super::top::memories(cfg) {
        let init = rom_file_name(cfg, m.init_stem, "hex");
        // A memory whose port stays on the top with nothing behind it (EMBM's or a squaring
        // unit's power table) says so in every text a testbench may read, not only in its
        // load port: one written from `doc` alone had loaded a table the top never reads.
        let (is_read, doc, param_doc) = if read.contains(&m.prefix) {
            (
                true,
                m.doc.to_string(),
                format!("$readmemh file with the power-up contents of the {} memory; relative paths resolve against the simulator's working folder", m.prefix),
            )
        } else {
            let why = match super::top::table_use(cfg) {
                super::top::TableUse::Unread(why) => why,
                _ => "nothing reads it",
            };
            (false, format!("not read: {why}"), format!("not read: {why}"))
        };
        params.insert(m.init_param.into(), json!({"default": init, "doc": param_doc}));
        memories.insert(m.prefix.into(), json!({"read": is_read, "init_file": init, "words": m.depth, "addr_bits": m.addr_bits, "data_bits": m.data_bits, "doc": doc, "load_port": load_port(cfg, m.prefix)}));
    }
    let v = json!({
        "generator": crate::TOOL,
        "regenerate": command,
        "config_hash": cfg.hash(),
        "config": cfg,
        "top": module_name(cfg, "gbump_pipeline"),
        "clock": clock_doc(cfg),
        "reset_cycles": super::top::RESET_CYCLES,
        "latency_cycles": latency(cfg),
        "initiation_interval": cfg.initiation_interval(),
        "handshake": if cfg.backpressure {
            "a fragment is accepted at a rising edge at which in_valid && in_ready are high; results leave in order; its C_new is on out_c, with out_valid high, when sampled at the rising edge exactly latency_cycles later if every earlier result was taken when offered (out_ready high); otherwise it is offered from the edge after the previous result is taken, never before latency_cycles"
        } else {
            "a fragment is accepted at a rising edge at which in_valid && in_ready are high; its C_new is on out_c, with out_valid high, when sampled at the rising edge exactly latency_cycles later; results leave in order"
        },
        "nullable": "output_buffer_results is null without back-pressure (backpressure = false); under bump_state, banks, bank_hold_cycles and setup_edges are present only with at = triangle; every other key is always present (memories lists every memory's load port the top has; memories.NAME.read is false where nothing behind the port is read, as the power table's under EMBM or a squaring power unit)",
        "bump_state": if cfg.per_triangle() {
            json!({"at": "triangle", "banks": cfg.triangle_banks, "bank_hold_cycles": super::top::bank_hold(cfg), "setup_edges": super::top::setup_edges(cfg), "setup_edges_definition": "the fewest rising edges a setup spans, from the first edge at which tri_valid offers it to the edge that accepts it, both counted, whether its bank is free yet or not (the serial top writes one light slot per edge into its bank RAM): a setup is accepted at the later of first offer + setup_edges - 1 and last use of its bank + bank_hold_cycles, where tri_ready is high; when setup_edges > 1, tri_ready depends on tri_valid and is high only at the accepting edge (low while no setup is offered, whatever the banks), so raise tri_valid without waiting for tri_ready; hold tri_* while tri_valid && !tri_ready, as valid/ready requires", "bank_hold_definition": "rising edges from the edge that accepts the last fragment using a bank to the first edge at which a setup may load that bank again; setup m after reset loads bank m mod banks", "setup": "a triangle's bump state (ports of kind `triangle`) is accepted at a rising edge at which tri_valid && tri_ready are high; every fragment accepted after that edge, up to the next setup, uses it; a fragment accepted at the same edge belongs to the previous triangle; no fragment may come before the first setup after reset", "vectors": "a record whose tri_start column is 1 starts a triangle: offer a setup from its tri_* columns only after the previous record's fragment has been accepted, and offer its own fragment only after the setup is taken (gbump's testbenches hold in_valid low meanwhile); a fragment accepted at the same edge as the setup belongs to the previous triangle, but one still waiting for in_ready when the setup is taken becomes the new triangle's"})
        } else {
            // Every state port the top has (in_frame too, under frame_transform).
            let ports: Vec<String> = super::top::port_list(cfg)
                .into_iter()
                .filter(|p| p.kind == super::top::PortKind::Fragment)
                .map(|p| p.name)
                .filter(|n| ["l", "h", "lc", "k"].iter().any(|f| *n == crate::vectors::targets::state_column(cfg, f)) || [crate::vectors::targets::FRAME, "in_st", "in_m"].contains(&n.as_str()))
                .collect();
            json!({"at": "fragment", "setup": format!("none: the bump state enters with every fragment on the {} ports", ports.join(", "))})
        },
        "output_buffer_results": super::top::output_depth(cfg),
        "backpressure": if cfg.backpressure { "out_ready: a result on out_c is taken at a rising edge at which out_valid && out_ready are high; it is offered from latency_cycles edges after its accept on and stays offered until taken; in_ready is low while output_buffer_results accepted results are untaken (and as the interval says); no pipeline register stalls" } else { "none: every result is taken when offered; the top has no out_ready" },
        "latency_definition": if cfg.backpressure {
            "rising edges from the edge that accepts a fragment to the edge at which its out_valid is first sampled high, when every earlier result was taken as it was offered; a result held up behind an untaken one is offered from the edge after that one is taken, never earlier than the latency (see backpressure)"
        } else {
            "rising edges from the edge that accepts a fragment to the edge at which its out_valid is sampled high"
        },
        "initiation_interval_definition": "rising edges between two accepts while in_valid stays high: in_ready is low for the initiation_interval - 1 edges after an accept and high at the next",
        "parameters": params,
        "memories": memories,
        "units": units_json(cfg),
        "power_table": {"present": super::top::power_table_read(cfg), "init_file": rom_file_name(cfg, "power_table", "hex"), "power_unit": cfg.power_unit_design().label(), "words": cfg.power_depth(), "entry_format": cfg.power_fmt().name(), "shininess": cfg.shininess, "rom": cfg.power_rom, "load_port": load_port(cfg, "power_table")},
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
    // Every generated file is ASCII: a unit's port text (`B·H`) is escaped, as JSON allows.
    ascii_json(&serde_json::to_string_pretty(&v).expect("json")) + "\n"
}

/// `json` with every character beyond ASCII written as its `\\uXXXX` escape (a surrogate pair
/// beyond the first plane), which any JSON reader decodes back.
fn ascii_json(json: &str) -> String {
    let mut out = String::with_capacity(json.len());
    for c in json.chars() {
        if c.is_ascii() {
            out.push(c);
        } else {
            let mut units = [0u16; 2];
            for u in c.encode_utf16(&mut units) {
                out += &format!("\\u{u:04x}");
            }
        }
    }
    out
}

/// Every unit the top includes, as a testbench of one unit drives it (`gbump vectors --target
/// UNIT` sets): its module, latency, ports (the clock, a memory's load port, then the record's
/// columns in the manifests' order, each with its format and when it enters) and parameters.
/// The top's description alone had left a unit-level testbench to the Markdown table.
fn units_json(cfg: &PipelineConfig) -> serde_json::Value {
    use crate::units::Dir;
    let mut units = serde_json::Map::new();
    for u in crate::units::included(cfg) {
        let mut ports = vec![
            json!({"name": "clk", "dir": "in", "width": 1, "role": "clock", "doc": "rising edge; no reset and no valid: a record's stimulus every edge"}),
        ];
        let mut params = serde_json::Map::new();
        // Every power unit's module has the table's load port and parameters, a squaring one's
        // unused, so that every power unit instantiates alike.
        let memory = match u.name() {
            "power_unit" => Some(crate::units::table_memory(cfg)),
            _ => u.memory(cfg),
        };
        if let Some(m) = memory {
            let load = |name: &str, width: u32, doc: String| json!({"name": name, "dir": "in", "width": width, "role": "load", "doc": doc});
            let we = match (m.prefix == crate::units::POWER_TABLE, super::top::table_use(cfg)) {
                (true, super::top::TableUse::Loaded) => {
                    "write enable of the power table: its sets load the set's _power_table.hex through we, waddr and wdata before the records".to_string()
                }
                (true, super::top::TableUse::Rom) => {
                    "unused: power_rom = true (the table is a ROM its INIT_FILE fills, which its sets assume); hold it low".to_string()
                }
                (true, super::top::TableUse::Unread(why)) => format!("unused: this power unit reads no table ({why}); hold it low"),
                (false, _) => format!("write enable of its {} memory: its sets assume the power-up contents (INIT_FILE), so hold it low", m.prefix),
            };
            ports.push(load("we", 1, we));
            ports.push(load("waddr", m.addr_bits, format!("{} word address", m.prefix)));
            ports.push(load("wdata", m.data_bits, m.doc.to_string()));
            params.insert("INIT_FILE".into(), json!({"default": super::top::memory_init_file(cfg, &m), "doc": format!("$readmemh file of the {} memory's power-up contents (the top passes its {})", m.prefix, m.init_param)}));
            if u.name() == "power_unit" {
                params.insert(
                    "R".into(),
                    json!({"default": 1, "doc": "read ports: x and fs hold R lanes of the widths below (the vectors hold one)"}),
                );
            }
        }
        for p in u.ports(cfg) {
            ports.push(json!({
                "name": p.name,
                "dir": if p.dir == Dir::In { "in" } else { "out" },
                "width": p.fmt.width * p.lanes,
                "lanes": p.lanes,
                "format": p.fmt.name(),
                "signed": p.fmt.signed,
                "enters": p.enters,
                "role": if p.dir == Dir::In { "stimulus" } else { "expected" },
                "doc": p.doc,
            }));
        }
        units.insert(
            u.name().into(),
            json!({"module": module_name(cfg, u.name()), "latency_cycles": u.latency(cfg), "initiation_interval": 1, "ports": ports, "parameters": params}),
        );
    }
    serde_json::Value::Object(units)
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

/// How a memory is loaded: its load port, or (a ROM power table) not at all.
fn load_port(cfg: &PipelineConfig, prefix: &str) -> String {
    if cfg.embm() && prefix == "power_table" {
        "none: env_map_bits > 0 (EMBM: the specular light comes from its map), the top has no power table; power_table_we, power_table_waddr, power_table_wdata are unused and INIT_FILE is not read"
            .into()
    } else if cfg.power_unit == crate::config::PowerUnitKind::Squaring && prefix == "power_table" {
        "none: power_unit = \"squaring\" reads no table (x^e by successive squarings, e = 2^round(log2 shininess), the power of two nearest on a log scale); power_table_we, power_table_waddr, power_table_wdata are unused"
            .into()
    } else if cfg.power_rom && prefix == "power_table" {
        "none: power_rom = true, the table is a ROM holding its init_file; power_table_we, power_table_waddr, power_table_wdata are unused"
            .into()
    } else {
        format!("{prefix}_we, {prefix}_waddr, {prefix}_wdata; write when idle")
    }
}

/// The `clock` key: the reset, and the memories it leaves as they are.
fn clock_doc(cfg: &PipelineConfig) -> String {
    let kept: Vec<String> = super::top::read_memories(cfg).iter().map(|m| m.prefix.replace('_', " ")).collect();
    format!(
        "clk, rising edge; rst synchronous, active high: reset_cycles rising edge(s) with rst high clear the valid bits{}",
        match kept.len() {
            0 => String::new(),
            _ => format!(" (and leave every memory as it is: {})", kept.join(", ")),
        }
    )
}
