//! Every unit's counted registers (`Unit::resources`, the area model's input) are the
//! register bits of the Verilog it emits, over the fuzzer's corner configurations: the
//! counts mirror the emitters, and this is what holds them together when an emitter changes.

use gbump::config::PipelineConfig;
use std::collections::HashMap;

/// A range bound: a number, or `R*w-1` of a unit with read ports (alone, R = 1).
fn bound(s: &str) -> i64 {
    let s = s.trim();
    if let Ok(v) = s.parse() {
        return v;
    }
    let (prod, sub) = s.split_once('-').unwrap_or_else(|| panic!("bound {s}"));
    let (_, w) = prod.split_once('*').expect("R*w");
    w.trim().parse::<i64>().expect("w") - sub.trim().parse::<i64>().expect("1")
}

/// Register bits of `module` in `mods`, its instances of other modules in `mods` included:
/// every declared `reg` (not an array) that a nonblocking assignment drives.
fn register_bits(module: &str, mods: &HashMap<String, String>) -> u32 {
    let text = &mods[module];
    let mut widths: HashMap<String, u32> = HashMap::new();
    let mut bits = 0;
    for line in text.lines().map(str::trim) {
        let decl = line.trim_start_matches("output").trim_start();
        if let Some(rest) = decl.strip_prefix("reg ") {
            let rest = rest.trim_start().trim_start_matches("signed").trim_start();
            let (w, rest) = match rest.strip_prefix('[') {
                Some(r) => {
                    let (range, after) = r.split_once(']').expect("a range closes");
                    let (h, l) = range.split_once(':').expect("h:l");
                    (bound(h) - bound(l) + 1, after.trim_start())
                }
                None => (1, rest),
            };
            let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
            if !rest[name.len()..].trim_start().starts_with('[') {
                widths.insert(name, w as u32);
            }
        }
        let first = line.split(|c: char| !c.is_ascii_alphanumeric() && c != '_').next().unwrap_or("");
        if mods.contains_key(first) && !line.starts_with("module") {
            bits += register_bits(first, mods);
        }
    }
    let driven: std::collections::HashSet<String> = text
        .lines()
        .filter_map(|l| l.split_once("<=").map(|(lhs, _)| lhs))
        .filter_map(|lhs| {
            let lhs = lhs.trim_end();
            // A part select may hold spaces (`fs[r*9 +: 9]`): drop it before the name.
            let lhs = if lhs.ends_with(']') { &lhs[..lhs.rfind('[')?] } else { lhs };
            let name: String = lhs
                .rsplit([' ', ')'])
                .next()?
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            Some(name)
        })
        .collect();
    bits + widths.iter().filter(|(n, _)| driven.contains(*n)).map(|(_, w)| w).sum::<u32>()
}

#[test]
fn every_units_register_count_is_its_verilogs() {
    let mut cfgs: Vec<PipelineConfig> = gbump::sim::fuzz::corner_configs().into_iter().map(|c| c.1).collect();
    cfgs.push(PipelineConfig::default());
    cfgs.extend(gbump::sim::fuzz::normalise_configs());
    use gbump::config::PowerUnitKind::{Lerp, Segmented, Squaring};
    // A squaring unit's cuts at every depth, for exponents of no product (x^1), one, and many.
    for (power_unit, shininess) in [(Lerp, 16), (Segmented, 16), (Squaring, 1), (Squaring, 2), (Squaring, 64)] {
        for pipeline_depth in 1..=4 {
            for light_mode in [gbump::config::LightMode::Serial, gbump::config::LightMode::Parallel] {
                cfgs.push(PipelineConfig {
                    power_unit,
                    shininess,
                    pipeline_depth,
                    light_mode,
                    lights: 2,
                    ..Default::default()
                });
            }
        }
    }
    let mut checked = 0;
    for cfg in &cfgs {
        for u in gbump::units::included(cfg) {
            let mods: HashMap<String, String> = u
                .verilog(cfg)
                .into_iter()
                // The RAM is a black box in the area (its bits stand apart).
                .filter(|(n, _)| *n != gbump::rtlgen::ram::RAM)
                .map(|(n, t)| (gbump::rtlgen::units_v::module_name(cfg, n), t))
                .collect();
            let own = gbump::rtlgen::units_v::module_name(cfg, u.verilog(cfg)[0].0);
            let text_bits = register_bits(&own, &mods);
            let counted = u.resources(cfg).ff;
            assert_eq!(
                counted,
                text_bits as f64,
                "{} under {}: counted {counted}, Verilog {text_bits}",
                u.name(),
                cfg.to_toml()
            );
            checked += 1;
        }
    }
    assert!(checked > 50, "{checked} units checked");
}
