//! Random configurations: draw a valid `PipelineConfig`, generate its RTL, lint it with
//! Verilator, and simulate the level-2 corners and random vectors (top and units) on
//! Verilator; any lint warning or mismatch fails the run and keeps the config for replay.
//! `run_for` is `gbump fuzz`: that, for a time or a number of configurations.

use super::regress::{run_sets, write_rtl, RegressOptions};
use super::{Sim, Simulator, Verilator};
use crate::config::{limit, BlendOrder, BumpStateAt, LightMode, Multipliers, NormalRange, PipelineConfig, PowerIndex, PowerUnitKind};
use crate::error::{Error, Result};
use crate::fixed::Rounding;
use crate::vectors::rng::SplitMix64;
use crate::vectors::{dump, DumpOptions, Source};
use std::path::Path;

/// A random valid configuration, uniform over the valid space: every numeric field is drawn
/// over its whole range in [`LIMITS`] (`power_entries` over its powers of two), every choice
/// over all its values (palette mode among them), and draws that break a cross-field rule are
/// redrawn.
pub fn random_config(rng: &mut SplitMix64) -> PipelineConfig {
    loop {
        let (e_lo, e_hi) = limit("power_entries");
        let mut cfg = PipelineConfig {
            normal_bits: field(rng, "normal_bits"),
            normal_range: pick(rng, &[NormalRange::Binary, NormalRange::Symmetric]),
            lh_bits: field(rng, "lh_bits"),
            dot_frac_bits: field(rng, "dot_frac_bits"),
            power_entries: 1 << rng.range(e_lo.ilog2() as i64, e_hi.ilog2() as i64),
            power_frac_bits: field(rng, "power_frac_bits"),
            power_index: pick(rng, &[PowerIndex::Nearest, PowerIndex::Truncate]),
            power_unit: pick(rng, &[PowerUnitKind::Table, PowerUnitKind::Lerp, PowerUnitKind::Segmented]),
            power_segments: field(rng, "power_segments"),
            shininess: field(rng, "shininess"),
            colour_bits: field(rng, "colour_bits"),
            k_frac_bits: field(rng, "k_frac_bits"),
            lights: field(rng, "lights"),
            light_mode: pick(rng, &[LightMode::Serial, LightMode::Parallel]),
            blend_order: pick(rng, &[BlendOrder::DiffuseTextureSpecular, BlendOrder::TextureLast]),
            rounding: pick(rng, &[Rounding::Truncate, Rounding::HalfUp, Rounding::NearestEven]),
            palette: pick(rng, &[false, true]),
            diffuse: pick(rng, &[false, true]),
            specular: pick(rng, &[false, true]),
            skip_flat: pick(rng, &[false, true]),
            bump_state: pick(rng, &[BumpStateAt::Triangle, BumpStateAt::Fragment]),
            backpressure: pick(rng, &[false, true]),
            triangle_banks: field(rng, "triangle_banks"),
            pipeline_depth: field(rng, "pipeline_depth"),
            multipliers: pick(rng, &[Multipliers::Booth, Multipliers::Inferred]),
            // What the rasteriser interpolates changes no RTL by itself (renormalise, below,
            // draws it where it does), and a draw here would change every configuration a
            // seed gives.
            interpolate: crate::config::Interpolate::None,
            // Drawn last, so every draw before it is what it was before the field.
            colour_guard_bits: field(rng, "colour_guard_bits"),
            white_lights: pick(rng, &[false, true]),
            power_rom: pick(rng, &[false, true]),
            renormalise: false,
            // As interpolate: the rasteriser's choice, no RTL of its own.
            interpolate_k: false,
            renormalise_bump: false,
            cube_map_face: 0,
            self_shadow: false,
            frame_transform: false,
            frame_build: false,
            // As interpolate: the rasteriser's choice, no RTL of its own.
            triangle_frame: false,
            frame_quaternion: false,
            pixel_lh: false,
            env_map_bits: 0,
        };
        // Drawn only where it is valid (per-fragment state, parallel lights), so no draw is
        // rejected for it (its draws do shift every later configuration of a seed, as any
        // new field does); what it renormalises (H, or H and L) changes the RTL, so that is
        // drawn with it.
        if cfg.bump_state == BumpStateAt::Fragment && cfg.light_mode == LightMode::Parallel && pick(rng, &[false, true]) {
            cfg.renormalise = true;
            cfg.interpolate = pick(rng, &[crate::config::Interpolate::H, crate::config::Interpolate::Hl]);
        }
        // Drawn last, so every draw before it is what it was; valid without a palette, and
        // the normalise_b unit changes the RTL.
        cfg.renormalise_bump = !cfg.palette && pick(rng, &[false, true]);
        // Drawn after it, and only where there are normalise units to read a map.
        if cfg.renormalise && pick(rng, &[false, true]) {
            cfg.cube_map_face = 1 << rng.range(2, 7);
        }
        // Drawn last, where valid: self-shadowing reads the diffuse path's B·L; a squaring
        // power unit in place of the drawn one (no table to make a ROM of).
        cfg.self_shadow = cfg.diffuse && pick(rng, &[false, true]);
        if cfg.specular && pick(rng, &[false, false, false, true]) {
            cfg.power_unit = PowerUnitKind::Squaring;
            cfg.power_rom = false;
        }
        // Drawn last, where valid: a frame with per-fragment state (self-shadowing then gates
        // on N·L with the frame's normal).
        if cfg.bump_state == BumpStateAt::Fragment && pick(rng, &[false, true]) {
            cfg.frame_transform = true;
            // Drawn after it: the frame interpolated whole (Harmony), built per fragment
            // (TexRam) or formed from a quaternion (VISA+).
            match pick(rng, &[0, 1, 2]) {
                1 => cfg.frame_build = true,
                2 => cfg.frame_quaternion = true,
                _ => {}
            }
            // Drawn after it, where valid: L and H formed at the pixel (Blinn), the H
            // normalise fed the halved sum of the normalised L and V.
            cfg.pixel_lh = cfg.renormalise && cfg.interpolate == crate::config::Interpolate::Hl && pick(rng, &[false, true]);
        }
        // Drawn last, where valid: EMBM, whose four light slots are the bilinear texels (what
        // it has no use for is cleared; its weights need 8 fraction bits in each factor).
        let four_parallel = cfg.lights == 4 && cfg.light_mode == LightMode::Parallel && cfg.bump_state == BumpStateAt::Fragment;
        if four_parallel && !cfg.palette && cfg.dot_frac_bits >= 8 && cfg.power_frac_bits >= 8 && pick(rng, &[false, true]) {
            cfg.env_map_bits = rng.range(2, limit("env_map_bits").1 as i64) as u32;
            cfg.interpolate = crate::config::Interpolate::None;
            (cfg.renormalise, cfg.renormalise_bump, cfg.interpolate_k, cfg.cube_map_face) = (false, false, false, 0);
            (cfg.frame_transform, cfg.frame_build, cfg.frame_quaternion, cfg.pixel_lh) = (false, false, false, false);
            (cfg.self_shadow, cfg.white_lights, cfg.power_rom) = (false, false, false);
        }
        // A drawn value no unit reads (banks with per-fragment state, segments of a table)
        // goes back to its default: the draws stay the same, and the hash is the hardware's.
        let cfg = cfg.canonical();
        if cfg.validate("random").is_ok() {
            return cfg;
        }
    }
}

/// Uniform over the valid range of numeric field `name`.
fn field(rng: &mut SplitMix64, name: &str) -> u32 {
    let (lo, hi) = limit(name);
    rng.range(lo as i64, hi as i64) as u32
}

/// Uniform over `options`.
fn pick<T: Copy>(rng: &mut SplitMix64, options: &[T]) -> T {
    options[rng.range(0, options.len() as i64 - 1) as usize]
}

/// Fixed configurations at the edges of the space, which uniform draws reach only now and
/// then: every light slot (serial with self-shadowing, and parallel on a palettised map with
/// the squaring power unit), the widest dot product
/// and table, the widest segmented unit, and every width at its top and at its bottom;
/// `normalise_b` on two of them (the widest normals with the flat bypass, the narrowest
/// normals in its table-alone regime with inferred multipliers), the largest
/// normalisation cube map (`normalise_cube`) at the widest L and H with a frame built per
/// fragment (`frame_build`), and a frame from a quaternion per fragment (`quat_frame`) on
/// the serial top.
pub fn corner_configs() -> Vec<(&'static str, PipelineConfig)> {
    let (lo, hi) = (|n| limit(n).0, |n| limit(n).1);
    let d = PipelineConfig::default();
    let widest_dot = PipelineConfig {
        dot_frac_bits: hi("dot_frac_bits"),
        power_entries: hi("power_entries"),
        power_frac_bits: hi("power_frac_bits"),
        shininess: hi("shininess"),
        ..d.clone()
    };
    let embm = PipelineConfig {
        lights: 4,
        light_mode: LightMode::Parallel,
        bump_state: BumpStateAt::Fragment,
        ..d.clone()
    };
    vec![
        (
            "EMBM, the largest maps, every width at its top, the deepest pipeline",
            PipelineConfig {
                env_map_bits: hi("env_map_bits"),
                normal_bits: hi("normal_bits"),
                normal_range: NormalRange::Symmetric,
                lh_bits: hi("lh_bits"),
                colour_bits: hi("colour_bits"),
                colour_guard_bits: hi("colour_guard_bits"),
                k_frac_bits: hi("k_frac_bits"),
                dot_frac_bits: hi("dot_frac_bits"),
                power_frac_bits: hi("power_frac_bits"),
                pipeline_depth: hi("pipeline_depth"),
                rounding: Rounding::NearestEven,
                skip_flat: true,
                blend_order: BlendOrder::TextureLast,
                ..embm.clone()
            },
        ),
        (
            "EMBM, the smallest maps, the narrowest normals and L/H words (4 coordinate fraction bits), diffuse only",
            PipelineConfig {
                env_map_bits: 2,
                normal_bits: lo("normal_bits"),
                lh_bits: lo("lh_bits"),
                colour_bits: lo("colour_bits"),
                k_frac_bits: lo("k_frac_bits"),
                specular: false,
                pipeline_depth: lo("pipeline_depth"),
                ..embm
            },
        ),
        (
            "all light slots, serial, self-shadowing",
            PipelineConfig {
                lights: hi("lights"),
                light_mode: LightMode::Serial,
                self_shadow: true,
                ..d.clone()
            },
        ),
        (
            "all light slots, parallel, palette, squaring power unit",
            PipelineConfig {
                lights: hi("lights"),
                light_mode: LightMode::Parallel,
                palette: true,
                power_unit: PowerUnitKind::Squaring,
                ..d.clone()
            },
        ),
        ("widest dot product and table", widest_dot.clone()),
        (
            "widest segmented unit, serial, a frame from a quaternion per fragment, self-shadowing",
            PipelineConfig {
                power_unit: PowerUnitKind::Segmented,
                power_segments: hi("power_segments"),
                power_entries: 16,
                bump_state: BumpStateAt::Fragment,
                frame_transform: true,
                frame_quaternion: true,
                self_shadow: true,
                ..widest_dot.clone()
            },
        ),
        (
            "every width at its top",
            PipelineConfig {
                normal_bits: hi("normal_bits"),
                normal_range: NormalRange::Symmetric,
                lh_bits: hi("lh_bits"),
                colour_bits: hi("colour_bits"),
                colour_guard_bits: hi("colour_guard_bits"),
                k_frac_bits: hi("k_frac_bits"),
                lights: hi("lights"),
                light_mode: LightMode::Parallel,
                rounding: Rounding::NearestEven,
                triangle_banks: hi("triangle_banks"),
                pipeline_depth: hi("pipeline_depth"),
                renormalise_bump: true,
                skip_flat: true,
                ..widest_dot
            },
        ),
        (
            "every width at its bottom",
            PipelineConfig {
                normal_bits: lo("normal_bits"),
                normal_range: NormalRange::Symmetric,
                lh_bits: lo("lh_bits"),
                dot_frac_bits: lo("dot_frac_bits"),
                power_entries: lo("power_entries"),
                power_frac_bits: lo("power_frac_bits"),
                shininess: lo("shininess"),
                colour_bits: lo("colour_bits"),
                k_frac_bits: lo("k_frac_bits"),
                lights: lo("lights"),
                rounding: Rounding::Truncate,
                triangle_banks: lo("triangle_banks"),
                pipeline_depth: lo("pipeline_depth"),
                // normalise_b's table-alone regime at the narrowest normals, multipliers
                // left to synthesis.
                renormalise_bump: true,
                multipliers: Multipliers::Inferred,
                ..d.clone()
            },
        ),
        (
            "the largest normalisation cube map, widest L and H, a frame built per fragment",
            PipelineConfig {
                lh_bits: hi("lh_bits"),
                normal_bits: hi("normal_bits"),
                normal_range: NormalRange::Symmetric,
                bump_state: BumpStateAt::Fragment,
                frame_transform: true,
                frame_build: true,
                interpolate: crate::config::Interpolate::Hl,
                renormalise: true,
                cube_map_face: hi("cube_map_face"),
                light_mode: LightMode::Parallel,
                lights: 1,
                pipeline_depth: hi("pipeline_depth"),
                ..d
            },
        ),
    ]
}

/// Configurations at the normalise units' edges: every regime of its table and Newton steps
/// (table alone, one step, two steps) at the narrowest and widest words, both normal ranges
/// (symmetric ones at the widest normals: the longest S), every rounding and every depth, and
/// `normalise_b` (the bump normal's) on serial tops at narrow and default normals. The
/// unit-level tests read them; the simulated corners above leave them out, since synthesis of
/// the two-step unit is slow.
pub fn normalise_configs() -> Vec<PipelineConfig> {
    // Two parallel lights whose L and H are interpolated and renormalised: the base of each.
    let renormalising = |lh: u32, range: NormalRange, depth: u32| PipelineConfig {
        lh_bits: lh,
        normal_range: range,
        bump_state: BumpStateAt::Fragment,
        interpolate: crate::config::Interpolate::Hl,
        renormalise: true,
        light_mode: LightMode::Parallel,
        lights: 2,
        pipeline_depth: depth,
        ..PipelineConfig::default()
    };
    let mut out = Vec::new();
    for (lh, range, nb) in [
        (4, NormalRange::Binary, 8),
        (7, NormalRange::Symmetric, 3),
        (16, NormalRange::Binary, 8),
        (18, NormalRange::Symmetric, 8),
        (24, NormalRange::Symmetric, 16),
    ] {
        for depth in 1..=crate::limits::MAX_PIPELINE_DEPTH {
            let rounding = [Rounding::Truncate, Rounding::HalfUp, Rounding::NearestEven][depth as usize % 3];
            out.push(PipelineConfig {
                normal_bits: nb,
                rounding,
                multipliers: if depth == 2 { Multipliers::Inferred } else { Multipliers::Booth },
                // The bump normal's unit beside them on every other depth.
                renormalise_bump: depth % 2 == 0,
                ..renormalising(lh, range, depth)
            });
        }
    }
    // L and H formed at the pixel (`pixel_lh`): H's normalise fed the half sum of L's output
    // and V, in a frame (interpolated whole, or built), at the narrowest symmetric, the
    // default and the widest words, at the shallowest and the deepest pipeline.
    for (lh, range) in [(7, NormalRange::Symmetric), (16, NormalRange::Binary), (24, NormalRange::Symmetric)] {
        for depth in [1, crate::limits::MAX_PIPELINE_DEPTH] {
            out.push(PipelineConfig {
                frame_transform: true,
                frame_build: depth == 1,
                pixel_lh: true,
                self_shadow: lh == 16,
                ..renormalising(lh, range, depth)
            });
        }
    }
    // normalise_cube in place of normalise: the smallest map at the narrowest words (its
    // exhaustive regime), the Cg Tutorial's 32 texels at the default words, the largest map at
    // the widest symmetric words, at every depth.
    for (lh, range, face) in [
        (6, NormalRange::Binary, 4),
        (16, NormalRange::Binary, 32),
        (24, NormalRange::Symmetric, 128),
    ] {
        for depth in 1..=crate::limits::MAX_PIPELINE_DEPTH {
            out.push(PipelineConfig {
                cube_map_face: face,
                ..renormalising(lh, range, depth)
            });
        }
    }
    // normalise_b alone on serial tops: its table-alone regime (5-bit normals, both ranges)
    // and the default normals, at every depth.
    for (nb, range) in [
        (5, NormalRange::Symmetric),
        (5, NormalRange::Binary),
        (8, NormalRange::Binary),
        (12, NormalRange::Symmetric),
    ] {
        for depth in 1..=crate::limits::MAX_PIPELINE_DEPTH {
            out.push(PipelineConfig {
                normal_bits: nb,
                normal_range: range,
                renormalise_bump: true,
                pipeline_depth: depth,
                skip_flat: depth % 2 == 1,
                ..PipelineConfig::default()
            });
        }
    }
    out
}

/// Random vectors to simulate for `cfg` when `random` are asked for: fewer for big
/// configurations, whose table load (one word a cycle) and serial light slots (one a cycle)
/// make every vector slower, so a huge config costs about what a default one does.
pub fn vectors_for(cfg: &PipelineConfig, random: u64) -> u64 {
    let table_cost = (cfg.power_entries as u64 / 1024).max(1);
    let light_cost = match cfg.light_mode {
        LightMode::Serial => cfg.lights.div_ceil(4) as u64,
        LightMode::Parallel => 1,
    };
    (random / (table_cost * light_cost)).max(random.min(100))
}

/// Generate, lint and simulate one configuration; returns the number of vectors checked.
pub fn check_config(cfg: &PipelineConfig, work: &Path, random: u64, seed: u64) -> Result<u64> {
    let h = &cfg.hash()[..8];
    let dir = work.join(format!("cfg_{h}"));
    crate::render::output::make_folder(&dir)?;
    std::fs::write(dir.join("config.toml"), cfg.to_toml()).map_err(|e| Error::io(&dir, e))?;
    let progress = crate::progress::Progress::new(&format!("fuzz config {h}"), 3);
    progress.start("generate and lint");
    let rtl = write_rtl(cfg, &dir.join("rtl"), "gbump fuzz")?;
    let paths = |v: &[std::path::PathBuf]| v.iter().map(|p| p.display().to_string()).collect::<Vec<_>>();
    let top = format!("gbump_pipeline_{h}");
    if let Some(log) = Verilator.lint(&rtl.dir, &paths(&rtl.sources), &paths(&rtl.waivers), Some(&top))? {
        return Err(Error::Other(format!(
            "config {h} ({}): lint:\n{}",
            dir.join("config.toml").display(),
            crate::tool::tail(&log, 20)
        )));
    }
    progress.done("verilator --lint-only -Wall clean");
    progress.start("vectors from the model");
    let all: Vec<String> = crate::vectors::targets::all_targets().iter().map(|s| s.to_string()).collect();
    let o = DumpOptions {
        seed,
        ..DumpOptions::formats("gbump fuzz", true, true)
    };
    let mut sets = Vec::new();
    for src in [Source::Corners(2), Source::Random(vectors_for(cfg, random))] {
        for s in dump(cfg, &src, &all, &dir.join("vectors"), &o)? {
            sets.push((s.manifest, None));
        }
    }
    progress.done(&format!("{} vector sets", sets.len()));
    progress.start("build and simulate on Verilator");
    let opts = RegressOptions {
        sims: vec![Sim::Verilator],
        random_verilator: 0,
        random_icarus: 0,
        seed,
        scenes: false,
        own_scenes: Vec::new(),
        scene_size: None,
        work: dir.clone(),
        waves: false,
        max_errors: 10,
        command: "gbump fuzz".into(),
        bubbles: crate::sim::regress::BUBBLES,
        stall: crate::sim::regress::STALL,
        power_up: true,
        targets: vec!["all".into()],
    };
    let mut checked = 0;
    for r in run_sets(cfg, &sets, &rtl, &opts)? {
        match r.outcome {
            Ok(out) if out.failed == 0 => checked += out.passed,
            Ok(out) => {
                return Err(Error::Other(format!(
                    "config {h} ({}): {} failed {} check(s) (results, timing or X reports):\n{}",
                    dir.join("config.toml").display(),
                    r.set,
                    out.failed,
                    crate::tool::tail(&out.log, 30)
                )))
            }
            Err(e) => return Err(Error::Other(format!("config {h}: {}: {e}", r.set))),
        }
    }
    progress.done(&format!("{checked} vectors match the model"));
    Ok(checked)
}

/// `gbump fuzz`: check random configurations (`check_config`) until `minutes` have passed or
/// `configs` are done, one line per configuration to `say`; the first failure stops it (its
/// config is kept under `work` for replay). `lock` takes `work` once the arguments are checked.
pub fn run_for(
    minutes: f64,
    configs: Option<u64>,
    seed: u64,
    random: u64,
    work: &Path,
    lock: impl FnOnce() -> Result<crate::work_lock::WorkLock>,
    say: &mut dyn FnMut(&str) -> Result<()>,
) -> Result<()> {
    use crate::limits::{check_count, MAX_RANDOM_VECTORS};
    if !(minutes > 0.0 && minutes.is_finite()) {
        return Err(Error::Other(format!(
            "--minutes {minutes}: must be a positive number\n  fix: e.g. --minutes 10"
        )));
    }
    if let Some(c) = configs {
        check_count("--configs", c, 1, u64::MAX, "")?;
    }
    // A testbench over zero vectors proves nothing (and fails).
    check_count("--random", random, 1, MAX_RANDOM_VECTORS, "MAX_RANDOM_VECTORS")?;
    super::require(Sim::Verilator)?;
    let _lock = lock()?;
    let work = std::path::absolute(work).map_err(|e| Error::io(work, e))?;
    let mut rng = SplitMix64(seed);
    let t0 = std::time::Instant::now();
    let (mut n, mut vectors) = (0u64, 0u64);
    while t0.elapsed().as_secs_f64() < minutes * 60.0 && configs.is_none_or(|c| n < c) {
        let cfg = random_config(&mut rng);
        let v = check_config(&cfg, &work, random, seed.wrapping_add(n))?;
        n += 1;
        vectors += v;
        say(&format!(
            "config {} ok: {v} vectors ({:?} lights x{}, normal {} lh {} dot {}, power {} of {}-bit words, colour {} k {}, {:?}, {:?})",
            cfg.hash(),
            cfg.light_mode,
            cfg.lights,
            cfg.normal_bits,
            cfg.lh_bits,
            cfg.dot_frac_bits,
            cfg.power_unit_design().label(),
            cfg.power_frac_bits + 1,
            cfg.colour_bits,
            cfg.k_frac_bits,
            cfg.rounding,
            cfg.blend_order
        ))?;
    }
    say(&format!(
        "fuzz: {n} configurations, {vectors} vectors, 0 failures in {:.0} s",
        t0.elapsed().as_secs_f64()
    ))?;
    if n == 0 {
        return Err(Error::Other(
            "fuzz: no configuration was checked\n  fix: give more --minutes".into(),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::LIMITS;

    #[test]
    fn normalise_configs_are_valid_and_form_h_at_the_pixel() {
        let cs = normalise_configs();
        for c in &cs {
            c.validate("normalise_configs").unwrap();
        }
        assert!(cs.iter().any(|c| c.pixel_lh && c.frame_build) && cs.iter().any(|c| c.pixel_lh && !c.frame_build));
    }

    #[test]
    fn corner_configs_are_valid_and_reach_every_limit() {
        let cs = corner_configs();
        for (name, c) in &cs {
            c.validate(name).unwrap();
        }
        for &(f, lo, hi, _) in LIMITS {
            let seen: Vec<u32> = cs.iter().map(|c| c.1.get(f)).collect();
            assert!(seen.contains(&hi), "no corner config has {f} = {hi}");
            assert!(f == "power_segments" || seen.contains(&lo), "no corner config has {f} = {lo}");
        }
    }

    /// Uniform draws reach both ends of every range and every value of every choice.
    #[test]
    fn random_configs_span_every_field() {
        let mut rng = SplitMix64(1);
        let cfgs: Vec<PipelineConfig> = (0..4000).map(|_| random_config(&mut rng)).collect();
        let draws: Vec<toml::Table> = cfgs.iter().map(|c| toml::Table::try_from(c).unwrap()).collect();
        for &(f, lo, hi, _) in LIMITS {
            // A field the TOML leaves out at its default is read from the configuration.
            let vals: Vec<u32> = cfgs.iter().map(|c| c.get(f)).collect();
            assert!(
                vals.contains(&lo) && vals.contains(&hi),
                "{f}: draws span {:?}..{:?}, limits {lo}..{hi}",
                vals.iter().min(),
                vals.iter().max()
            );
        }
        for f in [
            "power_index",
            "power_unit",
            "light_mode",
            "blend_order",
            "rounding",
            "diffuse",
            "specular",
            "skip_flat",
            "white_lights",
            "power_rom",
            "renormalise",
            "renormalise_bump",
            "self_shadow",
            "frame_transform",
            "frame_build",
            "frame_quaternion",
        ] {
            // A choice left out of the TOML at its default (white_lights = false) reads as that.
            let distinct: std::collections::BTreeSet<String> = draws
                .iter()
                .map(|t| t.get(f).map_or("false".to_string(), |v| v.to_string()))
                .collect();
            let want = match f {
                "power_unit" => 4,
                "rounding" => 3,
                _ => 2,
            };
            assert_eq!(distinct.len(), want, "{f}: {distinct:?}");
        }
    }
}
