//! Random configurations: draw a valid `PipelineConfig`, generate its RTL, lint it with
//! Verilator, and simulate the level-2 corners and random vectors (top and units) on
//! Verilator; any lint warning or mismatch fails the run and keeps the config for replay.

use super::regress::{run_sets, write_rtl, RegressOptions};
use super::Sim;
use crate::config::{BlendOrder, LightMode, PipelineConfig, PowerIndex, PowerUnitKind};
use crate::error::{Error, Result};
use crate::fixed::Rounding;
use crate::vectors::rng::SplitMix64;
use crate::vectors::{dump, DumpOptions, Source};
use std::path::Path;
use std::process::Command;

/// A random valid configuration. Widths span their whole legal range; the light count is
/// kept to 1–4 so a Verilator build stays within seconds.
pub fn random_config(rng: &mut SplitMix64) -> PipelineConfig {
    loop {
        let dot_bits = rng.range(2, 14) as u32;
        let cfg = PipelineConfig {
            normal_bits: rng.range(3, 16) as u32,
            lh_bits: rng.range(4, 24) as u32,
            dot_bits,
            power_entries: 1 << rng.range(1, dot_bits.min(11) as i64),
            power_bits: rng.range(2, 16) as u32,
            power_index: if rng.chance(0.5) {
                PowerIndex::Nearest
            } else {
                PowerIndex::Truncate
            },
            power_unit: [PowerUnitKind::Table, PowerUnitKind::Lerp, PowerUnitKind::Segmented][rng.range(0, 2) as usize],
            power_segments: rng.range(2, 8) as u32,
            shininess: [0, 1, 2, 8, 32, 255, 1024][rng.range(0, 6) as usize],
            colour_bits: rng.range(2, 12) as u32,
            k_bits: rng.range(1, 12) as u32,
            lights: rng.range(1, 4) as u32,
            light_mode: if rng.chance(0.5) { LightMode::Serial } else { LightMode::Parallel },
            blend_order: if rng.chance(0.5) {
                BlendOrder::DiffuseTextureSpecular
            } else {
                BlendOrder::TextureLast
            },
            rounding: [Rounding::Truncate, Rounding::HalfUp, Rounding::NearestEven][rng.range(0, 2) as usize],
            palette: false,
            diffuse: rng.chance(0.9),
            specular: rng.chance(0.9),
            skip_flat: rng.chance(0.3),
        };
        if cfg.validate("random").is_ok() {
            return cfg;
        }
    }
}

/// Generate, lint and simulate one configuration; returns the number of vectors checked.
pub fn check_config(cfg: &PipelineConfig, work: &Path, random: u64, seed: u64) -> Result<u64> {
    let h = &cfg.hash()[..8];
    let dir = work.join(format!("cfg_{h}"));
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    std::fs::write(dir.join("config.toml"), cfg.to_toml()).map_err(|e| Error::io(&dir, e))?;
    let rtl = write_rtl(cfg, &dir.join("rtl"), "gbump fuzz")?;
    let mut lint = Command::new("verilator");
    lint.args(["--lint-only", "-Wall", "--top-module", &format!("gbump_pipeline_{h}")])
        .args(&rtl.waivers)
        .args(&rtl.sources);
    let (ok, log, _) = super::run_cmd(&mut lint, "verilator --lint-only")?;
    if !ok || log.contains("%Warning") {
        return Err(Error::Other(format!(
            "config {h} ({}): lint:\n{}",
            dir.join("config.toml").display(),
            super::tail(&log, 20)
        )));
    }
    let all: Vec<String> = crate::vectors::targets::all_targets().iter().map(|s| s.to_string()).collect();
    let o = DumpOptions {
        text: true,
        binary: true,
        seed,
        size: None,
        command: "gbump fuzz".into(),
        shininess: None,
    };
    let mut sets = Vec::new();
    for src in [Source::Corners(2), Source::Random(random)] {
        for s in dump(cfg, &src, &all, &dir.join("vectors"), &o)? {
            sets.push((s.manifest, None));
        }
    }
    let opts = RegressOptions {
        sims: vec![Sim::Verilator],
        random_verilator: 0,
        random_icarus: 0,
        seed,
        scenes: false,
        scene_size: None,
        work: dir.clone(),
        waves: false,
        max_errors: 10,
        command: "gbump fuzz".into(),
        bubbles: 29,
        power_up: true,
    };
    let mut checked = 0;
    for r in run_sets(cfg, &sets, &rtl, &opts)? {
        match r.outcome {
            Ok(out) if out.failed == 0 => checked += out.passed,
            Ok(out) => {
                return Err(Error::Other(format!(
                    "config {h} ({}): {} failed {} vectors:\n{}",
                    dir.join("config.toml").display(),
                    r.set,
                    out.failed,
                    super::tail(&out.log, 30)
                )))
            }
            Err(e) => return Err(Error::Other(format!("config {h}: {}: {e}", r.set))),
        }
    }
    Ok(checked)
}
