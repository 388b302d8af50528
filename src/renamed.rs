//! Every user-facing name that was renamed, old and new: the README's upgrade table is written
//! from this list (and from the configuration's own `RENAMED_FIELDS`, which the parser still
//! reads), and the tests below prove each old name is gone from what gbump generates and each
//! new one is there, so the table cannot claim a rename that did not happen.

use crate::config::RENAMED_FIELDS;

/// Where a renamed name appears.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Where {
    /// A port of the top and the top's vector column of the same name.
    TopPort,
    /// A port of one unit: the unit's module port and its per-unit vector column.
    UnitPort(&'static str),
    /// A unit: its name (`--target`, `exhaustive:<unit>`, the C ABI's and Python's targets,
    /// per-unit vector sets `<set>_<unit>.*`), its module `<unit>_<hash8>` and instance `u_<unit>`.
    Unit,
    /// A Verilog module of its own, `<name>_<hash8>`.
    Module,
    /// A parameter of the SystemVerilog package.
    PackageParam,
    /// A key of the interface JSON (`section.key`).
    InterfaceKey,
    /// The generated top testbench's module (FuseSoC's `toplevel`, `-P NAME.INIT_FILE`, the
    /// scope of its waves), written with its hash as `<hash8>`.
    Testbench,
}

impl Where {
    fn describe(self) -> String {
        match self {
            Where::TopPort => "top port (and the top vector column of a fragment or triangle port)".into(),
            Where::UnitPort(u) => format!("`{u}` port: module port and per-unit vector column"),
            Where::Unit => "unit: `--target`, `exhaustive:UNIT`, C ABI / Python target, per-unit vector sets `<set>_UNIT.*`, module `UNIT_<hash8>`, instance `u_UNIT`".into(),
            Where::Module => "Verilog module `NAME_<hash8>`".into(),
            Where::PackageParam => "SystemVerilog package parameter".into(),
            Where::InterfaceKey => "interface JSON key".into(),
            Where::Testbench => "module of the top testbench `tb_top_<hash8>.v` (FuseSoC `toplevel`, `-P NAME.INIT_FILE`, wave scope)".into(),
        }
    }
}

/// One rename.
#[derive(Clone, Copy, Debug)]
pub struct Renamed {
    pub at: Where,
    pub old: &'static str,
    pub new: &'static str,
}

const fn r(at: Where, old: &'static str, new: &'static str) -> Renamed {
    Renamed { at, old, new }
}

/// Renames of this release ("names mean one thing": `bump` is the bump map's texel or palette
/// index, `tex` the texture colour T; the power unit reads the power table).
pub const RENAMED: &[Renamed] = &[
    r(Where::TopPort, "in_texel", "in_bump"),
    r(Where::TopPort, "in_t", "in_tex"),
    r(Where::TopPort, "pt_we", "power_table_we"),
    r(Where::TopPort, "pt_waddr", "power_table_waddr"),
    r(Where::TopPort, "pt_wdata", "power_table_wdata"),
    r(Where::TopPort, "pal_we", "palette_we"),
    r(Where::TopPort, "pal_waddr", "palette_waddr"),
    r(Where::TopPort, "pal_wdata", "palette_wdata"),
    r(Where::UnitPort("bump_fetch"), "texel", "bump"),
    r(Where::UnitPort("palette_fetch"), "index", "bump"),
    r(Where::UnitPort("texture_modulate"), "t", "tex"),
    r(Where::Unit, "power_table", "power_unit"),
    r(Where::Module, "power_core", "power_unit_core"),
    r(Where::PackageParam, "PT_WORDS", "POWER_TABLE_WORDS"),
    r(Where::PackageParam, "PT_ADDR_BITS", "POWER_TABLE_ADDR_BITS"),
    r(Where::InterfaceKey, "power_table.unit", "power_table.power_unit"),
    r(Where::InterfaceKey, "memories.pt", "memories.power_table"),
    r(Where::InterfaceKey, "memories.pal", "memories.palette"),
    r(Where::Testbench, "tb_top", "tb_top_<hash8>"),
];

/// The fix line for a unit name that is not known: its new name if it was renamed, else `usual`.
pub fn unit_fix(name: &str, usual: String) -> String {
    match RENAMED.iter().find(|x| x.at == Where::Unit && x.old == name) {
        Some(x) => format!(
            "`{}` was renamed `{}`: use {} (README, \"Upgrading: renamed names\")",
            x.old, x.new, x.new
        ),
        None => usual,
    }
}

/// The README's upgrade table: every rename, then the configuration fields.
pub fn markdown() -> String {
    let mut s = String::from("| where | old | new |\n|---|---|---|\n");
    for x in RENAMED {
        s += &format!("| {} | `{}` | `{}` |\n", x.at.describe(), x.old, x.new);
    }
    for (old, new) in RENAMED_FIELDS {
        s += &format!("| configuration field (the old name is still read, with a warning) | `{old}` | `{new}` |\n");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{BumpStateAt, LightMode, PipelineConfig, PowerUnitKind};
    use crate::rtlgen::top::{port_list, top};
    use crate::units::{self, UNITS};
    use crate::vectors::targets::{top_layout, unit_layout};

    /// Configurations that between them hold every port, unit and module.
    fn configs() -> Vec<PipelineConfig> {
        vec![
            PipelineConfig::default(),
            PipelineConfig {
                palette: true,
                light_mode: LightMode::Parallel,
                lights: 1,
                power_unit: PowerUnitKind::Lerp,
                ..Default::default()
            },
            PipelineConfig {
                bump_state: BumpStateAt::Fragment,
                ..Default::default()
            },
        ]
    }

    /// Whether `name` is a whole identifier in `text`.
    fn has_word(text: &str, name: &str) -> bool {
        text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).any(|w| w == name)
    }

    /// Every name a configuration's generated outputs use for `at`.
    fn names(cfg: &PipelineConfig, at: Where) -> Vec<String> {
        match at {
            Where::TopPort => {
                let mut v: Vec<String> = port_list(cfg).into_iter().map(|p| p.name).collect();
                v.extend(top_layout(cfg).columns.into_iter().map(|c| c.name));
                v
            }
            Where::UnitPort(u) => {
                let Some(unit) = units::unit(u).filter(|x| x.included(cfg)) else {
                    return Vec::new();
                };
                let mut v: Vec<String> = unit.ports(cfg).into_iter().map(|p| p.name.to_string()).collect();
                v.extend(unit_layout(cfg, u).columns.into_iter().map(|c| c.name));
                v
            }
            Where::Unit => {
                let mut v: Vec<String> = UNITS.iter().map(|u| u.name().to_string()).collect();
                // The top's instances, `u_<name>`, by their name.
                let t = top(cfg);
                v.extend(
                    t.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                        .filter_map(|w| w.strip_prefix("u_"))
                        .map(String::from),
                );
                v
            }
            Where::Module => units::included(cfg)
                .iter()
                .flat_map(|u| u.verilog(cfg))
                .map(|(name, _)| name.to_string())
                .collect(),
            Where::PackageParam => {
                let p = crate::rtlgen::kit::package(cfg, "test");
                p.lines()
                    .filter_map(|l| l.trim().strip_prefix("localparam "))
                    .filter_map(|l| l.split('=').next())
                    .filter_map(|l| l.split_whitespace().last())
                    .map(String::from)
                    .collect()
            }
            Where::Testbench => {
                let tb = crate::rtlgen::testbench::tb_top_init(cfg, "\"init.hex\"", &[]);
                tb.lines()
                    .filter_map(|l| l.strip_prefix("module ")?.strip_suffix(';'))
                    .map(|m| m.replace(&cfg.hash()[..8], "<hash8>"))
                    .collect()
            }
            Where::InterfaceKey => {
                let j: serde_json::Value = serde_json::from_str(&crate::rtlgen::interface::interface_json(cfg, "test")).unwrap();
                let mut v = Vec::new();
                for (section, body) in j.as_object().unwrap() {
                    if let Some(o) = body.as_object() {
                        v.extend(o.keys().map(|k| format!("{section}.{k}")));
                    }
                }
                v
            }
        }
    }

    #[test]
    fn every_old_name_is_gone_and_every_new_one_is_used() {
        let cfgs = configs();
        for x in RENAMED {
            let all: Vec<String> = cfgs.iter().flat_map(|c| names(c, x.at)).collect();
            assert!(!all.iter().any(|n| n == x.old), "{:?} `{}` is still generated", x.at, x.old);
            assert!(
                all.iter().any(|n| n == x.new),
                "{:?} `{}` is generated nowhere: {all:?}",
                x.at,
                x.new
            );
        }
    }

    #[test]
    fn the_top_verilog_holds_no_old_port_or_instance() {
        for cfg in configs() {
            let t = top(&cfg);
            for x in RENAMED.iter().filter(|x| matches!(x.at, Where::TopPort | Where::Unit)) {
                let old = if x.at == Where::Unit {
                    format!("u_{}", x.old)
                } else {
                    x.old.to_string()
                };
                assert!(!has_word(&t, &old), "`{old}` in the top of {}", cfg.hash());
            }
        }
    }

    #[test]
    fn the_table_lists_every_rename_and_config_field() {
        let md = markdown();
        assert_eq!(md.lines().count(), 2 + RENAMED.len() + RENAMED_FIELDS.len());
        for x in RENAMED {
            assert!(md.contains(&format!("| `{}` | `{}` |", x.old, x.new)), "{x:?}");
        }
    }
}
