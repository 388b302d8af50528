//! The one reader of Yosys `stat -json` output (gate-level area, FPGA cell counts and the
//! power-unit datapaths all use it): the cell counts of the whole design and, with
//! `-tech cmos`, its estimated transistor count.

use serde_json::Value;
use std::collections::BTreeMap;

/// What `stat -json` says of the whole design.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stat {
    /// Cell type (as Yosys names it, `$_DFF_P_`, `SB_LUT4`, `LUT6`, ...) to count.
    pub cells: BTreeMap<String, u64>,
    /// `estimated_num_transistors` (present with `-tech cmos`).
    pub transistors: Option<u64>,
    /// Yosys marks the estimate with a trailing `+` when some cells had no transistor count.
    pub transistors_lower_bound: bool,
    /// Bits of every memory (`num_memory_bits`), counted before synthesis maps them.
    pub memory_bits: u64,
}

impl Stat {
    /// Sum of the counts of the cell types `pick` accepts.
    pub fn count(&self, pick: impl Fn(&str) -> bool) -> u64 {
        self.cells.iter().filter(|(k, _)| pick(k)).map(|(_, v)| v).sum()
    }
}

/// Parse the text a `tee -o FILE stat -json` wrote. The `design` totals are used (the whole
/// hierarchy below the top); a file with one module and no totals falls back to that module.
/// `None` when the text is not `stat -json` output.
pub fn parse(text: &str) -> Option<Stat> {
    // `tee -o` may put the command's log lines before the JSON object.
    let start = text.find('{')?;
    let v: Value = serde_json::from_str(text[start..].trim_end()).ok()?;
    let section = match v.get("design") {
        Some(d) => d,
        None => {
            let mods = v.get("modules")?.as_object()?;
            if mods.len() != 1 {
                return None;
            }
            mods.values().next()?
        }
    };
    let cells = section
        .get("num_cells_by_type")?
        .as_object()?
        .iter()
        .map(|(k, n)| Some((k.clone(), n.as_u64()?)))
        .collect::<Option<BTreeMap<_, _>>>()?;
    let (transistors, transistors_lower_bound) = match section.get("estimated_num_transistors") {
        None => (None, false),
        Some(t) => {
            // A string in Yosys 0.23 ("11010", or "11010+"); a number in some versions.
            let s = t.as_str().map(str::to_string).unwrap_or_else(|| t.to_string());
            let plus = s.ends_with('+');
            (Some(s.trim_end_matches('+').trim().parse().ok()?), plus)
        }
    };
    let memory_bits = section.get("num_memory_bits").and_then(Value::as_u64).unwrap_or(0);
    Some(Stat {
        cells,
        transistors,
        transistors_lower_bound,
        memory_bits,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Captured from Yosys 0.23: `stat -json -tech cmos` after `abc -g cmos2`.
    const CMOS: &str = r#"
5. Printing statistics.
{
   "creator": "Yosys 0.23 (git sha1 7ce5011c24b)",
   "invocation": "stat -json -tech cmos ",
   "modules": {
      "\\texture_modulate_cff673d6": {
         "num_wires":         4204,
         "num_cells":         2855,
         "num_cells_by_type": {
            "$_DFF_P_": 24,
            "$_NAND_": 1353,
            "$_NOR_": 1129,
            "$_NOT_": 349
         },
         "estimated_num_transistors": "11010"
      }
   },
      "design": {
         "num_wires":         4204,
         "num_cells":         2855,
         "num_cells_by_type": {
            "$_DFF_P_": 24,
            "$_NAND_": 1353,
            "$_NOR_": 1129,
            "$_NOT_": 349
         },
         "estimated_num_transistors": "11010"
      }
}
"#;

    /// Captured from Yosys 0.23: `stat -json` after `synth_ice40` (one-light parallel top).
    const ICE40: &str = r#"{
   "creator": "Yosys 0.23 (git sha1 7ce5011c24b)",
   "invocation": "stat -json ",
   "modules": {
      "\\gbump_pipeline_cff673d6": {
         "num_cells":         6496,
         "num_cells_by_type": {
            "SB_CARRY": 558,
            "SB_DFF": 529,
            "SB_DFFSR": 33,
            "SB_DFFSS": 48,
            "SB_LUT4": 5327,
            "SB_RAM40_4K": 1
         }
      }
   },
      "design": {
         "num_cells":         6496,
         "num_cells_by_type": {
            "SB_CARRY": 558,
            "SB_DFF": 529,
            "SB_DFFSR": 33,
            "SB_DFFSS": 48,
            "SB_LUT4": 5327,
            "SB_RAM40_4K": 1
         }
      }
}
"#;

    #[test]
    fn reads_cells_and_transistors_of_the_design() {
        let s = parse(CMOS).unwrap();
        assert_eq!(s.transistors, Some(11010));
        assert!(!s.transistors_lower_bound);
        assert_eq!(s.cells["$_NAND_"], 1353);
        assert_eq!(s.count(|c| c.starts_with("$_DFF")), 24);
        let f = parse(ICE40).unwrap();
        assert_eq!(f.transistors, None);
        assert_eq!(f.count(|c| c.starts_with("SB_DFF")), 529 + 33 + 48);
        assert_eq!(f.cells["SB_LUT4"], 5327);
    }

    #[test]
    fn a_lower_bound_estimate_and_broken_text() {
        let s = parse(&CMOS.replace("\"11010\"", "\"11010+\"")).unwrap();
        assert_eq!(s.transistors, Some(11010));
        assert!(s.transistors_lower_bound);
        assert_eq!(parse("   Number of cells: 12\n"), None);
        assert_eq!(parse(&ICE40[..ICE40.len() / 2]), None, "a truncated file");
        assert_eq!(parse(&CMOS.replace("\"11010\"", "\"lots\"")), None);
    }
}
