//! The regression: generate the RTL and a vector suite for a configuration, build each
//! simulator once (cached), run every set, summarise, and fail on any mismatch.
//! Top sets run through the C++ harness on Verilator (binary records) and through the
//! Verilog testbench on Icarus (text); unit sets through the all-units testbench on both.

use super::testbench::{harness_top, tb_top, tb_units};
use super::{icarus, verilator, Outcome, Sim};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::vectors::{dump, verify, DumpOptions, Source};
use std::path::{Path, PathBuf};

/// One run's line in the summary.
#[derive(Clone, Debug)]
pub struct RunResult {
    pub sim: Sim,
    pub set: String,
    pub target: String,
    pub outcome: std::result::Result<Outcome, String>,
}

/// What to regress.
#[derive(Clone, Debug)]
pub struct RegressOptions {
    pub sims: Vec<Sim>,
    /// Random top vectors for Verilator and for Icarus.
    pub random_verilator: u64,
    pub random_icarus: u64,
    pub seed: u64,
    /// Render every built-in scene whose lights fit and use its fragments.
    pub scenes: bool,
    /// Image size for scene fragments.
    pub scene_size: Option<(u32, u32)>,
    pub work: PathBuf,
    pub waves: bool,
    pub max_errors: u32,
    pub command: String,
}

/// RTL files written for `cfg` into `dir`: (verilog sources, lint waivers).
pub fn write_rtl(cfg: &PipelineConfig, dir: &Path, command: &str) -> Result<(Vec<PathBuf>, Vec<PathBuf>)> {
    let files = crate::rtlgen::generate(cfg, command);
    crate::cli::write_files(dir, &files)?;
    let v = files.iter().filter(|f| f.0.ends_with(".v")).map(|f| dir.join(&f.0)).collect();
    let vlt = files.iter().filter(|f| f.0.ends_with(".vlt")).map(|f| dir.join(&f.0)).collect();
    Ok((v, vlt))
}

/// The default suite: corners, random, every compatible built-in scene, exhaustive sweeps.
pub fn suite(cfg: &PipelineConfig, o: &RegressOptions, dir: &Path) -> Result<Vec<(PathBuf, Option<Sim>)>> {
    let all: Vec<String> = crate::vectors::targets::all_targets().iter().map(|s| s.to_string()).collect();
    let mut sets = Vec::new();
    let dopt = |seed| DumpOptions {
        text: true,
        binary: true,
        seed,
        size: o.scene_size,
        command: o.command.clone(),
        shininess: None,
    };
    for s in dump(cfg, &Source::Corners(2), &all, dir, &dopt(o.seed))? {
        sets.push((s.manifest, None));
    }
    // Random sets sized per simulator: Icarus is about a hundred times slower.
    let sizes: Vec<(Sim, u64)> = o
        .sims
        .iter()
        .map(|s| (*s, if *s == Sim::Icarus { o.random_icarus } else { o.random_verilator }))
        .collect();
    for (sim, n) in sizes {
        if n == 0 {
            continue;
        }
        let sub = dir.join(format!("random_{}", sim.name()));
        let targets: Vec<String> = all.clone();
        for s in dump(cfg, &Source::Random(n), &targets, &sub, &dopt(o.seed))? {
            sets.push((s.manifest, Some(sim)));
        }
    }
    if o.scenes {
        for (name, _) in crate::scene::builtin::ALL {
            let scene = crate::scene::Scene::load(name)?;
            if scene.check_config(cfg, "").is_err() {
                continue;
            }
            for s in dump(cfg, &Source::Scene(name.to_string()), &["top".to_string()], dir, &dopt(o.seed))? {
                sets.push((s.manifest, None));
            }
        }
    }
    for unit in ["texture_modulate", "bump_fetch"] {
        // 2^(2w) texture pairs: beyond w = 9 the random sets and the identity's proof
        // (exhaustive to w = 10 in fixed.rs, property-tested above) stand in for the sweep.
        if unit == "texture_modulate" && cfg.colour_bits > 9 {
            continue;
        }
        for s in dump(cfg, &Source::Exhaustive(unit.into()), &[unit.to_string()], dir, &dopt(o.seed))? {
            sets.push((s.manifest, None));
        }
    }
    // The power table exhaustively for its reset shininess and for the extremes, each set
    // loading its own table through the load port.
    if cfg.specular {
        let mut ns = vec![cfg.shininess, 0, 1, 2, 254, 255, 1024];
        ns.dedup();
        for n in ns {
            let sub = dir.join(format!("power_n{n}"));
            let opts = DumpOptions {
                shininess: Some(n),
                ..dopt(o.seed)
            };
            for s in dump(
                cfg,
                &Source::Exhaustive("power_table".into()),
                &["power_table".to_string()],
                &sub,
                &opts,
            )? {
                sets.push((s.manifest, None));
            }
        }
    }
    Ok(sets)
}

/// Run the sets in `sets` on each simulator of `o`.
pub fn run_sets(
    cfg: &PipelineConfig,
    sets: &[(PathBuf, Option<Sim>)],
    rtl: &(Vec<PathBuf>, Vec<PathBuf>),
    o: &RegressOptions,
) -> Result<Vec<RunResult>> {
    let build_root = o.work.join("build");
    let mut results = Vec::new();
    for &sim in &o.sims {
        super::require(sim)?;
        let mut top_exe: Option<PathBuf> = None;
        let mut units_exe: Option<PathBuf> = None;
        for (manifest, only) in sets {
            if only.is_some_and(|s| s != sim) {
                continue;
            }
            let (m, dir) = verify(manifest)?;
            if m.config_hash != cfg.hash() {
                return Err(Error::Other(format!(
                    "{}: vectors are for config {} but the RTL is config {}\n  fix: regenerate the vectors for this configuration, or pass its config",
                    manifest.display(), m.config_hash, cfg.hash()
                )));
            }
            let set = manifest.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
            let table = dir.join(&m.power_table.name).display().to_string();
            let what = format!("{} {set}", sim.name());
            let max = o.max_errors.to_string();
            let waves = o.waves.then(|| o.work.join(format!("{set}_{}.fst", sim.name())));
            let run = |exe: &Path, is_top: bool| -> Result<Outcome> {
                let hex = m.hex.as_ref().map(|f| dir.join(&f.name).display().to_string());
                let mut plus = vec![format!("+table={table}"), format!("+max_errors={max}")];
                if let Some(h) = &hex {
                    plus.push(format!("+vectors={h}"));
                }
                if !is_top {
                    plus.push(format!("+unit={}", m.target));
                }
                match sim {
                    Sim::Icarus => icarus::run(exe, &plus, waves.as_deref(), &o.work, &what),
                    Sim::Verilator if is_top && !o.waves => {
                        let bin = m
                            .bin
                            .as_ref()
                            .ok_or_else(|| Error::Other(format!("{set}: no binary records for the Verilator harness")))?;
                        verilator::run(
                            exe,
                            &[
                                "--vectors".into(),
                                dir.join(&bin.name).display().to_string(),
                                "--table".into(),
                                table.clone(),
                                "--max-errors".into(),
                                max.clone(),
                            ],
                            &o.work,
                            &what,
                        )
                    }
                    Sim::Verilator => {
                        if let Some(w) = &waves {
                            plus.push(format!("+waves={}", w.display()));
                        }
                        verilator::run(exe, &plus, &o.work, &what)
                    }
                }
            };
            let is_top = m.target == "top";
            let exe = if is_top {
                if top_exe.is_none() {
                    top_exe = Some(match sim {
                        Sim::Icarus => icarus::build(&build_root, "tb_top", &tb_top(cfg), &rtl.0)?,
                        Sim::Verilator if !o.waves => verilator::build_harness(
                            &build_root,
                            &crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline"),
                            &harness_top(cfg),
                            &rtl.0,
                            &rtl.1,
                        )?,
                        Sim::Verilator => verilator::build_tb(&build_root, "tb_top", &tb_top(cfg), &rtl.0, &rtl.1, true, false)?,
                    });
                }
                top_exe.clone().expect("built")
            } else {
                if units_exe.is_none() {
                    units_exe = Some(match sim {
                        Sim::Icarus => icarus::build(&build_root, "tb_units", &tb_units(cfg), &rtl.0)?,
                        Sim::Verilator => verilator::build_tb(&build_root, "tb_units", &tb_units(cfg), &rtl.0, &rtl.1, o.waves, false)?,
                    });
                }
                units_exe.clone().expect("built")
            };
            let outcome = run(&exe, is_top).map_err(|e| e.to_string());
            results.push(RunResult {
                sim,
                set,
                target: m.target.clone(),
                outcome,
            });
        }
    }
    Ok(results)
}

/// JUnit XML of a regression.
pub fn junit(cfg: &PipelineConfig, results: &[RunResult]) -> String {
    let esc = |s: &str| {
        s.replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
            .replace('"', "&quot;")
    };
    let failures = results.iter().filter(|r| !matches!(&r.outcome, Ok(o) if o.failed == 0)).count();
    let mut s = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"gbump regress {}\" tests=\"{}\" failures=\"{failures}\">\n",
        cfg.hash(),
        results.len()
    );
    for r in results {
        let name = format!("{}.{}", r.sim.name(), r.set);
        match &r.outcome {
            Ok(o) if o.failed == 0 => s += &format!("  <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"/>\n", r.target, esc(&name), o.seconds),
            Ok(o) => s += &format!("  <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"><failure message=\"{} passed, {} failed\">{}</failure></testcase>\n", r.target, esc(&name), o.seconds, o.passed, o.failed, esc(&super::tail(&o.log, 60))),
            Err(e) => s += &format!("  <testcase classname=\"{}\" name=\"{}\"><error message=\"simulation error\">{}</error></testcase>\n", r.target, esc(&name), esc(e)),
        }
    }
    s + "</testsuite>\n"
}
