//! power_unit: fs = (B·H)^n read from the power table, a memory loaded like a colour LUT
//! (paper §4.2): the paper's plain lookup, or one of the interpolating designs of
//! `model::power_unit` (`power_unit = "lerp" | "segmented"`) reading the same memory, or no
//! memory at all: `power_unit = "squaring"` squares and multiplies up to the shininess it is
//! built for (the Cg Tutorial's specular power, §8.3).

use super::{p, Dir, Lanes, Memories, Memory, Port, Unit};
use crate::config::{PipelineConfig, PowerUnitKind};
use crate::model::power_table::powi_exact;

/// The name of the memory the power unit reads: its load port's prefix and its init file's stem.
pub const POWER_TABLE: &str = "power_table";

pub struct PowerUnit;

/// The power table's memory: its load port is on every top, whether a table is behind it or
/// not (a configuration without the specular path, or with a squaring unit, leaves it unused).
pub fn table_memory(cfg: &PipelineConfig) -> Memory {
    Memory {
        prefix: POWER_TABLE,
        init_param: "INIT_FILE",
        init_stem: POWER_TABLE,
        depth: cfg.power_depth(),
        addr_bits: cfg.power_addr_bits(),
        data_bits: cfg.power_frac_bits + 1,
        data_frac: cfg.power_frac_bits,
        data_lanes: 1,
        doc: if cfg.power_rom {
            "power table entries, u1.P (a ROM: the shininess is the configuration's, its load port unused)"
        } else {
            "power table entries, u1.P (the shininess is whatever was loaded)"
        },
    }
}

/// What `fs` is, for the configuration's kind of power unit (x read as a real in [0, 1];
/// the README's "power units" gives each in codes): one text for every kind had described the
/// rounded table lookup whatever the unit did.
fn fs_doc(cfg: &PipelineConfig) -> &'static str {
    match (cfg.power_unit, cfg.power_index) {
        (PowerUnitKind::Table, crate::config::PowerIndex::Nearest) => "table[round(x (N-1))]",
        (PowerUnitKind::Table, crate::config::PowerIndex::Truncate) => "table[floor(x (N-1))]",
        (PowerUnitKind::Lerp, _) => "linear between the two of the N uniform knots around x",
        (PowerUnitKind::Segmented, _) => "linear between the two knots around x of its segment (segments halve towards x = 1)",
        (PowerUnitKind::Squaring, _) => "x^e by successive squarings, e = 2^round(log2 n); no table",
    }
}

impl Unit for PowerUnit {
    fn name(&self) -> &'static str {
        "power_unit"
    }
    fn source(&self) -> &'static str {
        "paper §4.2: fs_i = (B·H_i)^n, a reloadable table for one shininess"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("specular", "true"), ("env_map_bits", "0")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.specular && !cfg.embm()
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        vec![
            p("x", Dir::In, cfg.dot_fmt(), 1, "clamped B·H"),
            p("fs", Dir::Out, cfg.power_fmt(), 1, fs_doc(cfg)),
        ]
    }
    fn input_max(&self, cfg: &PipelineConfig) -> Vec<(&'static str, i64, &'static str)> {
        vec![("x", 1 << cfg.dot_frac_bits, "1.0: a clamped dot product")]
    }
    /// The table's read register is its output register; an interpolating unit adds the
    /// interpolation after it; a squaring unit's chain of products is cut by
    /// `pipeline_depth` ([`crate::units::timing::SQUARING`]).
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        match cfg.power_unit {
            PowerUnitKind::Table => 1,
            PowerUnitKind::Squaring => crate::units::timing::latency(cfg, crate::units::timing::SQUARING),
            _ => 2,
        }
    }
    /// The table a squaring unit does without (its load port stays on the top: [`table_memory`]).
    fn memory(&self, cfg: &PipelineConfig) -> Option<Memory> {
        (cfg.power_unit != PowerUnitKind::Squaring).then(|| table_memory(cfg))
    }
    fn eval(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![vec![crate::model::power_unit::power_unit(cfg, m.table, i[0][0])]]
    }
    fn exact(&self, cfg: &PipelineConfig, m: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        let x = i[0][0] as f64 / (1u64 << cfg.dot_frac_bits) as f64;
        vec![vec![
            powi_exact(x, cfg.power_exponent(m.table.n)) * (1u64 << cfg.power_frac_bits) as f64,
        ]]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{power_datapath, sum_of_products, unsigned, Resources};
        if cfg.power_unit == PowerUnitKind::Squaring {
            // As `rtlgen::power_units::squaring` emits it: x widened, a rounded product per
            // squaring and per set bit of n, the running power (and x while a multiply
            // remains) at each cut, the guard bits rounded off, the output register.
            use crate::rtlgen::power_units::{squaring_cut_positions, squaring_products};
            let (f, p, g) = (cfg.dot_frac_bits, cfg.power_frac_bits, crate::config::SQUARING_GUARD_BITS);
            let wd = p + g;
            let steps = squaring_products(cfg.power_exponent(cfg.shininess));
            let cuts = crate::units::timing::cuts_in_place(cfg, crate::units::timing::SQUARING);
            let stages: u32 = squaring_cut_positions(steps.len(), cuts)
                .into_iter()
                .map(|at| if steps[at..].contains(&true) { 2 * (wd + 1) } else { wd + 1 })
                .sum();
            let product = sum_of_products(cfg.multipliers, &[(unsigned(wd + 1), unsigned(wd + 1))], false, 2 * wd + 2)
                + Resources::adders(2 * wd + 2);
            let fin = if g > 0 { Resources::adders(wd + 2) } else { Resources::default() };
            return Resources::adders(f + wd + 1) + product.scaled(steps.len() as f64) + fin + Resources::regs(stages + p + 1);
        }
        let core = power_datapath(&cfg.power_unit_design(), cfg.power_formats());
        if cfg.power_unit == PowerUnitKind::Table {
            // The RAM's read register is the output register.
            core
        } else {
            // x waits for the knots beside the RAMs; the interpolation is registered.
            core + Resources::regs(cfg.dot_frac_bits + 1 + cfg.power_frac_bits + 1)
        }
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        let mut v = vec![
            ("power_unit", crate::rtlgen::units_v::power_unit(cfg)),
            (crate::rtlgen::ram::RAM, crate::rtlgen::ram::ram(cfg)),
        ];
        if !matches!(cfg.power_unit, PowerUnitKind::Table | PowerUnitKind::Squaring) {
            let name = crate::rtlgen::units_v::module_name(cfg, "power_unit_core");
            v.push((
                "power_unit_core",
                crate::rtlgen::power_units::core(&cfg.power_unit_design(), cfg.power_formats(), &name),
            ));
        }
        v
    }
    fn exhaustive_count(&self, cfg: &PipelineConfig) -> Option<u64> {
        Some((1u64 << cfg.dot_frac_bits) + 1)
    }
    fn exhaustive_input(&self, _: &PipelineConfig, i: u64) -> Lanes {
        vec![vec![i as i64]]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let one = 1i64 << cfg.dot_frac_bits;
        vec![
            ("x = 0: entry 0 (0^n)".into(), vec![vec![0]]),
            ("x = 1 LSB: the first index step".into(), vec![vec![1]]),
            ("x one LSB below 1: the steepest part of x^n".into(), vec![vec![one - 1]]),
            ("x = 1: the last entry, exactly 1.0".into(), vec![vec![one]]),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::PowerIndex;

    /// `fs`'s port text names what each kind of unit computes: five kinds, five texts.
    #[test]
    fn the_fs_port_says_what_each_kind_computes() {
        let kinds = [
            (PowerUnitKind::Table, PowerIndex::Nearest, "round("),
            (PowerUnitKind::Table, PowerIndex::Truncate, "floor("),
            (PowerUnitKind::Lerp, PowerIndex::Nearest, "uniform knots"),
            (PowerUnitKind::Segmented, PowerIndex::Nearest, "segment"),
            (PowerUnitKind::Squaring, PowerIndex::Nearest, "squarings"),
        ];
        let mut seen = std::collections::BTreeSet::new();
        for (power_unit, power_index, word) in kinds {
            let cfg = PipelineConfig {
                power_unit,
                power_index,
                ..PipelineConfig::default()
            };
            let fs = PowerUnit.ports(&cfg).into_iter().find(|p| p.name == "fs").expect("an fs port");
            assert!(fs.doc.contains(word), "{power_unit:?}/{power_index:?}: {}", fs.doc);
            seen.insert(fs.doc);
        }
        assert_eq!(seen.len(), kinds.len());
    }
}
