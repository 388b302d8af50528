//! The regression's sets and runs: the default vector suite of a configuration, every set
//! checked before anything is built, each bench built once per simulator (cached) and every
//! set run. `regress_cmd.rs` is the command around it, `summary.rs` its report.
//! Top sets run through the C++ harness on Verilator (binary records) and through the
//! Verilog testbench on Icarus (text); unit sets through the all-units testbench on both.

pub use super::rtl_files::{write_rtl, Rtl};
use super::testbench::{harness_top, tb_top, tb_units};
use super::{Outcome, Sim, Simulator, Testbench, Verilator};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::rtlgen::units_v::module_name;
use crate::vectors::manifest::EnvMapFiles;
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

/// A regression's stream, as every command that regresses runs it: `in_valid` idle for 1-3
/// cycles before every [`BUBBLES`]th record, `out_ready` low for 1-3 edges every [`STALL`]th
/// edge (primes, so the two patterns drift against each other and against the interval).
pub const BUBBLES: u32 = 29;
pub const STALL: u32 = 13;
/// Mismatches a bench reports before it stops (`--max-errors`' default).
pub const MAX_ERRORS: u32 = 20;

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
    /// Scene files (not built in) whose fragments join the suite too: the scene a
    /// configuration was derived from (`--scene FILE`), which the built-in scenes may not
    /// exercise (white lights, say).
    pub own_scenes: Vec<String>,
    /// Image size for scene fragments.
    pub scene_size: Option<(u32, u32)>,
    pub work: PathBuf,
    pub waves: bool,
    pub max_errors: u32,
    pub command: String,
    /// Idle in_valid for 1-3 cycles before every Nth top record (0: never).
    pub bubbles: u32,
    /// Tops with out_ready: hold it low for 1-3 edges every Nth edge (0: never).
    pub stall: u32,
    /// Also run one top set on the power table's power-up contents.
    pub power_up: bool,
    /// What the default suite checks: `all`, `top` or unit names, as `gbump vectors
    /// --target` takes them (resolved against the configuration by `targets::resolve`).
    pub targets: Vec<String>,
}

/// Refuse, before anything runs, a scene file of `own` (`--scene FILE`) whose top sets would
/// have names no regression reads (`vectors::check_scene_names`).
pub fn check_own_scenes(cfg: &PipelineConfig, own: &[String], targets: &[String]) -> Result<()> {
    // Only the top's sets carry them.
    if !crate::vectors::targets::resolve(cfg, targets)?.iter().any(|t| t == "top") {
        return Ok(());
    }
    for file in own {
        let s = crate::scene::Scene::load(file)?;
        crate::vectors::check_scene_names(cfg, &format!("--scene {file}"), file, &s, &["top".to_string()])?;
    }
    Ok(())
}

/// The default suite: corners, random, every compatible built-in scene, exhaustive sweeps.
pub fn suite(cfg: &PipelineConfig, o: &RegressOptions, dir: &Path) -> Result<Vec<(PathBuf, Option<Sim>)>> {
    let all = crate::vectors::targets::resolve(cfg, &o.targets)?;
    let has = |t: &str| all.iter().any(|a| a == t);
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
        for s in dump(cfg, &Source::Random(n), &all, &sub, &dopt(o.seed))? {
            sets.push((s.manifest, Some(sim)));
        }
    }
    // Scene sets of a configuration with memories loaded per object are refused by dump.
    let scene_sets = crate::vectors::sources::scene_sets_made(cfg, "the built-in scene sets are skipped");
    if let (true, Err(e)) = (o.scenes, &scene_sets) {
        eprintln!("regress: {e}\n  (random, corner and unit sets still run)");
    }
    if o.scenes && scene_sets.is_ok() && has("top") {
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
    // The user's own scene (`--scene FILE`) runs even with --no-scenes, which skips the
    // built-in ones; it must fit, and a palette configuration's scene sets are refused by the
    // dump with the reason: a misfit is an error, not a silent skip.
    for file in o.own_scenes.iter().filter(|_| has("top")) {
        crate::scene::Scene::load(file)?.check_config(cfg, &crate::config::origin())?;
        for s in dump(
            cfg,
            &Source::Scene(file.clone()),
            &["top".to_string()],
            &dir.join("own_scenes"),
            &dopt(o.seed),
        )? {
            sets.push((s.manifest, None));
        }
    }
    // Every unit small enough to sweep in the suite's budget (2^18 inputs: texture pairs up to
    // w = 9; beyond, the random sets and the identity's proof in fixed.rs stand in); the power
    // unit is swept per shininess below.
    for u in crate::units::included(cfg) {
        if !has(u.name()) || u.name() == "power_unit" || u.exhaustive_count(cfg).is_none_or(|c| c > 1 << 18) {
            continue;
        }
        let unit = u.name().to_string();
        for s in dump(cfg, &Source::Exhaustive(unit.clone()), &[unit], dir, &dopt(o.seed))? {
            sets.push((s.manifest, None));
        }
    }
    // The power unit exhaustively for its reset shininess and for the extremes, each set
    // loading its own table through the load port.
    if cfg.specular && has("power_unit") {
        let mut ns = vec![cfg.shininess, 0, 1, 2, 254, 255, 1024];
        if cfg.power_unit == crate::config::PowerUnitKind::Squaring {
            // Its exponent is built in: no table to load for another.
            ns.truncate(1);
        }
        ns.dedup();
        for n in ns {
            let sub = dir.join(format!("power_n{n}"));
            let opts = DumpOptions {
                shininess: Some(n),
                ..dopt(o.seed)
            };
            for s in dump(
                cfg,
                &Source::Exhaustive("power_unit".into()),
                &["power_unit".to_string()],
                &sub,
                &opts,
            )? {
                sets.push((s.manifest, None));
            }
        }
    }
    Ok(sets)
}

/// How one set runs on one simulator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Bench {
    /// The Verilog top testbench on text records (Icarus, or Verilator `--binary`).
    TopTb,
    /// The Verilator C++ harness on binary records.
    Harness,
    /// The all-units Verilog testbench on text records.
    Units,
}

/// The command that wrote set `set` (its manifest's path), into the set's own folder, with
/// `--format both` in place of its own.
fn again(m: &crate::vectors::manifest::Manifest, set: &str) -> String {
    let dir = Path::new(set)
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    use crate::vectors::manifest::{quoted_words, regenerate_words, relative_note};
    let words = regenerate_words(&crate::vectors::manifest::recorded_command(m), dir);
    let mut out: Vec<String> = Vec::new();
    let mut skip = false;
    for w in &words {
        if std::mem::take(&mut skip) {
            continue;
        }
        if w == "--format" {
            skip = true;
        } else if !w.starts_with("--format=") {
            out.push(w.clone());
        }
    }
    out.extend(["--format".to_string(), "both".to_string()]);
    quoted_words(&out) + &relative_note(&words)
}

/// The bench a set runs on, or why it cannot run on `sim` (checked before anything is built).
fn bench_for(sim: Sim, m: &crate::vectors::manifest::Manifest, set: &str, waves: bool) -> Result<Bench> {
    let top = m.target == "top";
    match (sim, top) {
        (Sim::Verilator, true) if m.bin.is_some() && !waves => Ok(Bench::Harness),
        _ if m.hex.is_some() => Ok(if top { Bench::TopTb } else { Bench::Units }),
        (Sim::Verilator, true) => Err(Error::Other(format!(
            "{set}: --waves needs text records (the Verilog testbench), and this set has only binary ones\n  fix: dump it again with: {}; or run without --waves",
            again(m, set)
        ))),
        _ => Err(Error::Other(format!(
            "{set}: the {} testbench reads text records, and this set has only binary ones\n  fix: dump it again with: {}{}",
            sim.name(),
            again(m, set),
            if top { "; or run it with --sim verilator (its C++ harness reads binary records)" } else { "" }
        ))),
    }
}

/// A set whose files matched its manifest when it was checked.
#[derive(Clone, Debug)]
pub struct CheckedSet {
    pub manifest: PathBuf,
    /// The only simulator to run it on (None: every one of the regression).
    pub only: Option<Sim>,
    m: crate::vectors::manifest::Manifest,
    dir: PathBuf,
    /// What its testbench's digest of the records it checked must be.
    digest: crate::vectors::digest::Digest,
}

/// Check every set against `cfg` and the simulators before anything is built: its files
/// against the manifest (read once here; the runs use what was checked), its configuration,
/// and a bench on every simulator that will run it.
pub fn check_sets(cfg: &PipelineConfig, sets: &[(PathBuf, Option<Sim>)], o: &RegressOptions) -> Result<Vec<CheckedSet>> {
    let mut out = Vec::new();
    for (manifest, only) in sets {
        let (m, dir) = verify(manifest)?;
        if m.config_hash != cfg.hash() {
            return Err(Error::Other(format!(
                "{}: vectors are for config {} but the RTL is config {}\n  fix: sets of different configurations run in separate invocations: run each as `gbump regress --vectors MANIFEST` alone (without --config or --scene its manifest's configuration is used), pass the --config/--scene the set was made with, or regenerate the vectors for this configuration",
                manifest.display(),
                m.config_hash,
                cfg.hash()
            )));
        }
        // A ROM power table holds one shininess: a top set for another cannot load its table.
        if let Some(fixed) = cfg.fixed_shininess_of(&m.target).filter(|_| m.shininess != cfg.shininess) {
            return Err(Error::Other(format!(
                "{}: vectors for shininess {} but the configuration's {}\n  fix: regenerate the vectors at shininess {} (a scene's specular objects must all have it), or set {}",
                manifest.display(),
                m.shininess,
                fixed.what,
                cfg.shininess,
                fixed.release
            )));
        }
        // Its expected values are the model's, or the RTL would be judged by others.
        let regen = crate::vectors::manifest::regenerate_into(&crate::vectors::manifest::recorded_command(&m), &dir);
        let digest = crate::vectors::model_check::check_expected(&m, &dir, &regen)?;
        for &sim in o.sims.iter().filter(|s| only.is_none_or(|x| x == **s)) {
            bench_for(sim, &m, &manifest.display().to_string(), o.waves)?;
        }
        out.push(CheckedSet {
            manifest: manifest.clone(),
            only: *only,
            m,
            dir,
            digest,
        });
    }
    Ok(out)
}

/// Run the sets in `sets` on each simulator of `o`. Top sets run with the power table loaded
/// through the load port; with `o.power_up`, the first top set made for the reset shininess
/// runs once more on the table's power-up contents (INIT_FILE), nothing loaded.
pub fn run_sets(cfg: &PipelineConfig, sets: &[(PathBuf, Option<Sim>)], rtl: &Rtl, o: &RegressOptions) -> Result<Vec<RunResult>> {
    run_checked(cfg, &check_sets(cfg, sets, o)?, rtl, o)
}

/// Each set's name in the summary, the JUnit report and its waveform's file name: its file
/// stem, with its folder's name in front where two given sets share a stem (sets of the same
/// source from two folders), so that no two runs read alike.
fn set_names(sets: &[CheckedSet]) -> Vec<String> {
    let stem = |p: &Path| p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let folder = |p: &Path| {
        p.parent()
            .and_then(|d| d.file_name())
            .map(|d| d.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    let mut names: Vec<String> = sets.iter().map(|s| stem(&s.manifest)).collect();
    let shared = |names: &[String], i: usize| names.iter().filter(|n| **n == names[i]).count() > 1;
    let clash: Vec<bool> = (0..names.len()).map(|i| shared(&names, i)).collect();
    for (i, s) in sets.iter().enumerate() {
        if clash[i] {
            // A folder with no name of its own (`..`): the whole path below.
            names[i] = match folder(&s.manifest) {
                f if f.is_empty() => f,
                f => format!("{f}/{}", names[i]),
            };
        }
    }
    // Folders of the same name too: the whole path.
    let clash: Vec<bool> = (0..names.len()).map(|i| names[i].is_empty() || shared(&names, i)).collect();
    for (i, s) in sets.iter().enumerate() {
        if clash[i] {
            names[i] = s.manifest.with_extension("").display().to_string();
        }
    }
    names
}

/// `run_sets` on sets `check_sets` has already checked.
pub fn run_checked(cfg: &PipelineConfig, sets: &[CheckedSet], rtl: &Rtl, o: &RegressOptions) -> Result<Vec<RunResult>> {
    let build_root = o.work.join("build");
    let names = set_names(sets);
    let mut results = Vec::new();
    for &sim in &o.sims {
        super::require(sim)?;
        let simulator = sim.simulator();
        let mut exes: Vec<(Bench, PathBuf)> = Vec::new();
        let mut power_up_done = !o.power_up;
        for (
            CheckedSet {
                manifest,
                only,
                m,
                dir,
                digest,
            },
            set,
        ) in sets.iter().zip(&names)
        {
            if only.is_some_and(|s| s != sim) {
                continue;
            }
            let bench = bench_for(sim, m, &manifest.display().to_string(), o.waves)?;
            let exe = match exes.iter().find(|e| e.0 == bench) {
                Some(e) => e.1.clone(),
                None => {
                    let (top, source) = match bench {
                        Bench::Harness => (module_name(cfg, "gbump_pipeline"), harness_top(cfg)),
                        Bench::TopTb => (crate::rtlgen::kit::tb_module_name(cfg), tb_top(cfg, rtl)),
                        Bench::Units => ("tb_units".to_string(), tb_units(cfg, rtl)),
                    };
                    let exe = match bench {
                        Bench::Harness => Verilator.build_harness(&build_root, &top, &source, rtl)?,
                        _ => {
                            let tb = Testbench {
                                waves: o.waves,
                                ..Testbench::new(&top, &source)
                            };
                            simulator.build(&build_root, &tb, rtl)?
                        }
                    };
                    exes.push((bench, exe.clone()));
                    exe
                }
            };
            let mut loads = vec![true];
            // A set with its own maps means nothing on the power-up ones.
            if bench != Bench::Units && !power_up_done && m.shininess == cfg.shininess && m.env_maps.is_none() {
                loads.push(false);
                power_up_done = true;
            }
            for load in loads {
                let name = if load { set.clone() } else { format!("{set}+power-up") };
                let what = format!("{} {name}", sim.name());
                let waves = o
                    .waves
                    .then(|| o.work.join(format!("{}_{}.fst", name.replace('/', "__"), sim.name())));
                let table = load.then(|| dir.join(&m.power_table.name).display().to_string());
                let file = |f: &Option<crate::vectors::manifest::FileEntry>| {
                    f.as_ref().map(|f| dir.join(&f.name).display().to_string()).unwrap_or_default()
                };
                let outcome = match bench {
                    Bench::Harness => {
                        let mut args = vec!["--vectors".into(), file(&m.bin), "--max-errors".into(), o.max_errors.to_string()];
                        if let Some(t) = &table {
                            args.extend(["--table".into(), t.clone()]);
                        }
                        args.extend(harness_memory_args(m.env_maps.as_ref(), dir));
                        if o.bubbles > 0 {
                            args.extend(["--bubbles".into(), o.bubbles.to_string()]);
                        }
                        if o.stall > 0 {
                            args.extend(["--stall".into(), o.stall.to_string()]);
                        }
                        Verilator.run(&exe, &args, None, &o.work, &what)
                    }
                    _ => {
                        let mut plus = vec![
                            format!("+vectors={}", file(&m.hex)),
                            format!("+max_errors={}", o.max_errors),
                            format!("+count={}", m.count),
                        ];
                        if let Some(t) = &table {
                            plus.push(format!("+table={t}"));
                        }
                        if bench != Bench::Units {
                            plus.extend(env_files(m.env_maps.as_ref(), dir).into_iter().map(|(p, f)| format!("+{p}={f}")));
                        }
                        if bench == Bench::Units {
                            plus.push(format!("+unit={}", m.target));
                        } else {
                            if o.bubbles > 0 {
                                plus.push(format!("+bubbles={}", o.bubbles));
                            }
                            if o.stall > 0 {
                                plus.push(format!("+stall={}", o.stall));
                            }
                        }
                        simulator.run(&exe, &plus, waves.as_deref(), &o.work, &what)
                    }
                };
                let outcome = outcome.and_then(|out| every_record(out, m.count, *digest, &what));
                results.push(RunResult {
                    sim,
                    set: name,
                    target: m.target.clone(),
                    outcome: outcome.map_err(|e| e.to_string()),
                });
            }
        }
    }
    Ok(results)
}

/// A clean run must have checked every record of its set, and those records: a testbench that
/// stops early, skips records, prints a summary of its own or read another file of the same
/// length is a failing run, not a pass. (A run with mismatches may stop at --max-errors; it
/// fails anyway.)
pub fn every_record(out: super::verdict::Outcome, count: u64, digest: Digest, what: &str) -> Result<super::verdict::Outcome> {
    if out.failed != 0 {
        return Ok(out);
    }
    if out.passed != count {
        return Err(Error::Other(format!(
            "{what}: the testbench reports {} vectors checked, and the set holds {count}\n  fix: a run must check every record; look at the simulator's log below for where it stopped\n{}",
            out.passed,
            crate::tool::tail(&out.log, 15)
        )));
    }
    match Digest::of_log(&out.log) {
        Some(d) if d == digest => Ok(out),
        Some(d) => Err(Error::Other(format!(
            "{what}: the testbench's digest of the records it checked is {:016x}, the set's is {:016x}: it read other records than the set's (another file of the same length, or its records altered on the way)\n  fix: run the set's own files (regenerate them with the command in its manifest); look at the log below for the file it opened\n{}",
            d.0,
            digest.0,
            crate::tool::tail(&out.log, 15)
        ))),
        None => Err(Error::Other(format!(
            "{what}: the testbench printed no digest of the records it checked (a `{}` line beside its summary), so nothing shows it read the set\n  fix: run gbump's own testbench (`gbump rtl` writes it; a testbench of your own prints the digest as the kit's does, README \"Integrating the RTL\"), not a wrapper or another program in the simulator's place\n{}",
            crate::vectors::digest::PREFIX.trim(),
            crate::tool::tail(&out.log, 15)
        ))),
    }
}

use crate::vectors::digest::Digest;

/// A set's environment maps in `dir` as (load-port prefix, path): `env_diffuse` is
/// `+env_diffuse=` for the testbench; none for a set on the power-up maps.
pub fn env_files(e: Option<&EnvMapFiles>, dir: &Path) -> Vec<(&'static str, String)> {
    e.map_or_else(Vec::new, |e| {
        e.each()
            .into_iter()
            .map(|(prefix, _, f)| (prefix, dir.join(&f.name).display().to_string()))
            .collect()
    })
}

/// [`env_files`] as the C++ harness's options (`--env-diffuse PATH`).
pub fn harness_memory_args(e: Option<&EnvMapFiles>, dir: &Path) -> Vec<String> {
    env_files(e, dir)
        .into_iter()
        .flat_map(|(p, f)| [crate::rtlgen::testbench::harness_flag(p), f])
        .collect()
}
