//! One `gbump fit`: the scenes' common needs as the base, the search, and what it writes (the
//! chosen configuration as TOML, the front as CSV and SVG).

use super::budget::Budget;
use super::evaluate::Evaluator;
use super::search::{pareto, Candidate, Search, Space};
use crate::config::PipelineConfig;
use crate::error::Result;
use crate::scene::Scene;

/// The outcome of a search.
pub struct Fit {
    pub budget: Budget,
    pub scenes: Vec<String>,
    pub chosen: Candidate,
    /// Every candidate measured (unsized), and the sized winners no other winner beats.
    pub seen: Vec<Candidate>,
    pub front: Vec<Candidate>,
    pub evaluations: usize,
    pub seconds: f64,
    /// The base configuration the search started from (what the scenes need).
    pub base: PipelineConfig,
}

/// What every scene needs at once: the most bump lights, any blend any scene uses, k fraction
/// bits unless every scene's k_i are on/off, white lights only when every scene's are, the
/// first scene's shininess (the table is loadable; a ROM when every specular object of every
/// scene shares one), the rest of the first scene's configuration.
pub fn common_base(scenes: &[Scene]) -> Result<PipelineConfig> {
    let mut base = scenes[0].derive_config()?;
    for s in &scenes[1..] {
        let c = s.derive_config()?;
        base.lights = base.lights.max(c.lights);
        base.diffuse |= c.diffuse;
        base.specular |= c.specular;
        base.k_frac_bits = base.k_frac_bits.max(c.k_frac_bits);
        base.white_lights &= c.white_lights;
    }
    // One shininess over every specular object of every scene: the table is never reloaded,
    // so it is a ROM (the same logic; a ROM macro instead of a RAM, no load port to drive).
    let shininess: std::collections::BTreeSet<u32> = scenes
        .iter()
        .flat_map(|s| s.objects.iter().filter(|o| o.specular).map(|o| o.shininess))
        .collect();
    if base.specular && shininess.len() == 1 {
        base.shininess = *shininess.iter().next().expect("one");
        base.power_rom = true;
    }
    Ok(base)
}

/// Refuse, before a search whose choice is then regressed on the scene files, a scene file
/// whose name no vector set can carry (it would fail only after the search).
pub fn check_regressable(scene_names: &[String]) -> Result<()> {
    let scenes: Vec<Scene> = scene_names.iter().map(|n| Scene::load(n)).collect::<Result<_>>()?;
    let own = crate::scene::builtin::files_among(scene_names);
    crate::sim::regress::check_own_scenes(&common_base(&scenes)?, &own, &["all".to_string()])
}

/// Search for the smallest configuration (by `area`) that renders `scenes` within `budget` with
/// at least `min_throughput` fragments per clock.
pub fn fit(scene_names: &[String], budget: Budget, min_throughput: f64, area: &dyn Fn(&PipelineConfig) -> Result<f64>) -> Result<Fit> {
    let t0 = std::time::Instant::now();
    let scenes: Vec<Scene> = scene_names.iter().map(|n| Scene::load(n)).collect::<Result<_>>()?;
    let base = common_base(&scenes)?;
    // Warnings name where the configurations come from: the scene's, not the default.
    if let [one] = scene_names {
        crate::config::note_derived(one);
    }
    // A palette is offered when every map fits one exactly at the base's normal width.
    let mut palette_exact = true;
    for s in &scenes {
        palette_exact &= crate::scene::needs::distinct_normals(s, &base)?.iter().all(|&n| n <= 256);
    }
    // A field a scene's [pipeline] sets is the scene's to choose, not the search's.
    let set: std::collections::BTreeSet<String> = scenes
        .iter()
        .flat_map(|s| s.pipeline.iter().flat_map(|t| t.keys().cloned()))
        .collect();
    let space = Space::full(palette_exact).pin(&base, &set);
    let mut eval = Evaluator::new(scenes, &base, budget)?;
    let mut search = Search {
        eval: &mut eval,
        area,
        seen: Vec::new(),
    };
    let (chosen, sized) = search.run(&base, &space, min_throughput)?;
    let seen = std::mem::take(&mut search.seen);
    let evaluations = eval.evaluations;
    let Some(chosen) = chosen else {
        let best = seen.iter().map(|c| budget.error(&c.measured)).fold(f64::INFINITY, f64::min);
        let best = if matches!(budget, Budget::Psnr(_)) { -best } else { best };
        let (kept, fix) = match space.kept.is_empty() {
            true => (String::new(), ""),
            false => (
                format!(" keeping {} as the scene's [pipeline] sets", space.kept.join(", ")),
                ", or drop those fields from [pipeline] to let the search choose them",
            ),
        };
        return Err(crate::error::Error::Other(format!(
            "no configuration renders {} within {budget}{}{kept}: the best measured {best:.2}\n  fix: loosen the budget{fix}",
            scene_names.join(", "),
            if min_throughput > 0.0 {
                format!(" at {min_throughput} fragments per clock")
            } else {
                String::new()
            },
        )));
    };
    let front = pareto(&sized, |m| budget.error(m)).into_iter().cloned().collect();
    Ok(Fit {
        budget,
        scenes: scene_names.to_vec(),
        chosen,
        seen,
        front,
        evaluations,
        seconds: t0.elapsed().as_secs_f64(),
        base,
    })
}

/// The regression the chosen configuration passes before `gbump fit` reports it: both
/// simulators, `gbump regress`'s protocol (bubbles, stalls, the power-up table), fewer random
/// vectors and the scenes at 64x48.
/// `scenes` are the fitted scenes: those that are files (not built in) are regressed too.
pub fn regress_options(work: &std::path::Path, command: String, scenes: &[String]) -> Result<crate::sim::regress::RegressOptions> {
    let own_scenes = crate::scene::builtin::files_among(scenes);
    Ok(crate::sim::regress::RegressOptions {
        sims: vec![crate::sim::Sim::Icarus, crate::sim::Sim::Verilator],
        random_verilator: 100_000,
        random_icarus: 5_000,
        seed: 1,
        scenes: true,
        own_scenes,
        scene_size: Some((64, 48)),
        work: std::path::absolute(work).map_err(|e| crate::error::Error::io(work, e))?,
        waves: false,
        max_errors: crate::sim::regress::MAX_ERRORS,
        command,
        bubbles: crate::sim::regress::BUBBLES,
        stall: crate::sim::regress::STALL,
        power_up: true,
        targets: vec!["all".into()],
    })
}

fn fmt_measure(x: f64) -> String {
    if x.is_nan() {
        String::new()
    } else {
        format!("{x:.3}")
    }
}

impl Fit {
    /// The front (and every other candidate) as CSV.
    pub fn csv(&self) -> String {
        let mut s = String::from("config_hash,power_unit,rounding,normal_range,palette,light_mode,pipeline_depth,normal_bits,lh_bits,dot_frac_bits,power_entries,power_segments,power_frac_bits,colour_guard_bits,area_ge,fragments_per_clock,max_lsb,psnr_db,exact_lsb,meets_budget,on_front\n");
        let rows = self.seen.iter().map(|c| (c, false)).chain(self.front.iter().map(|c| (c, true)));
        for (c, on_front) in rows {
            let g = &c.cfg;
            s += &format!(
                "{},{:?},{:?},{:?},{},{:?},{},{},{},{},{},{},{},{},{},{:.4},{},{},{},{},{}\n",
                g.hash(),
                g.power_unit,
                g.rounding,
                g.normal_range,
                g.palette,
                g.light_mode,
                g.pipeline_depth,
                g.normal_bits,
                g.lh_bits,
                g.dot_frac_bits,
                g.power_entries,
                g.power_segments,
                g.power_frac_bits,
                g.colour_guard_bits,
                format!("{:.0}", c.area_ge),
                c.throughput,
                fmt_measure(c.measured.max_lsb),
                fmt_measure(c.measured.psnr_db),
                fmt_measure(c.measured.exact_lsb),
                c.met,
                on_front
            );
        }
        s
    }

    /// Area against the budget's measure, the front joined, the chosen point in red.
    pub fn svg(&self) -> String {
        let measure = match self.budget {
            Budget::Max(_) => "max error vs f64 Gouraud, LSB",
            Budget::Psnr(_) => "minus PSNR vs f64 Gouraud, dB",
            Budget::Exact(_) => "max error vs exact arithmetic, LSB",
        };
        let mut dots: Vec<crate::measure::plot::Dot> = self
            .front
            .iter()
            .map(|c| crate::measure::plot::Dot {
                x: c.area_ge,
                y: self.budget.error(&c.measured),
                label: format!(
                    "{:?} {:?} n{} lh{} d{} g{}",
                    c.cfg.power_unit, c.cfg.rounding, c.cfg.normal_bits, c.cfg.lh_bits, c.cfg.dot_frac_bits, c.cfg.colour_guard_bits
                ),
                front: true,
                chosen: false,
            })
            .collect();
        dots.push(crate::measure::plot::Dot {
            x: self.chosen.area_ge,
            y: self.budget.error(&self.chosen.measured),
            label: "chosen".into(),
            front: false,
            chosen: true,
        });
        crate::measure::plot::scatter(
            &dots,
            &format!("gbump fit {} on {}", self.budget, self.scenes.join(", ")),
            "top logic, gate equivalents (area model)",
            measure,
        )
    }

    /// The chosen configuration as a TOML file, with how it was found.
    pub fn toml(&self) -> String {
        format!(
            "# gbump fit --budget {} on {}: the smallest configuration found ({:.0} GE by the area model, {} fragment(s) per clock; {})\n# config hash {}\n{}",
            self.budget,
            self.scenes.join(", "),
            self.chosen.area_ge,
            self.chosen.throughput,
            self.chosen.measured.describe(),
            self.chosen.cfg.hash(),
            self.chosen.cfg.to_toml()
        )
    }
}

/// `--min-fmax`: deepen the chosen configuration's pipeline (its arithmetic, so its error,
/// stays the same) until the top, placed and routed on the iCE40 `device` in its register
/// shell, reaches `min_mhz`. Returns the Fmax reached; an error names the best depth when none
/// does.
pub fn deepen_for_fmax(
    chosen: &mut Candidate,
    min_mhz: f64,
    device: &str,
    work: &std::path::Path,
    say: &mut dyn FnMut(&str),
) -> Result<f64> {
    use crate::measure::fpga::{fpga_area, Target};
    let mut best: Option<(u32, f64)> = None;
    for depth in chosen.cfg.pipeline_depth..=crate::limits::MAX_PIPELINE_DEPTH {
        let cfg = PipelineConfig {
            pipeline_depth: depth,
            ..chosen.cfg.clone()
        };
        let r = fpga_area(&cfg, Target::Ice40, device, false, work, "gbump fit --min-fmax")?;
        let pr = r.place_route.expect("iCE40 reports are placed and routed");
        let fmax = if pr.fits { pr.fmax_mhz.unwrap_or(0.0) } else { 0.0 };
        say(&format!(
            "pipeline_depth {depth}: {}",
            if pr.fits {
                format!("{fmax:.1} MHz on {device}")
            } else {
                format!("does not fit {device}")
            }
        ));
        if best.is_none_or(|b| fmax > b.1) {
            best = Some((depth, fmax));
        }
        if fmax >= min_mhz {
            chosen.cfg = cfg;
            chosen.area_ge = crate::measure::area_model::estimate(&chosen.cfg);
            return Ok(fmax);
        }
    }
    let (d, f) = best.expect("at least one depth");
    Err(crate::error::Error::Other(format!(
        "--min-fmax {min_mhz}: no pipeline_depth reaches it on the iCE40 {device}; the best is {f:.1} MHz at depth {d}\n  fix: lower --min-fmax to {f:.0} or less (a deeper pipeline stops helping once the critical path is outside the arithmetic units' register cuts)"
    )))
}
