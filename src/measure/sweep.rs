//! `gbump sweep`: a grid of configurations, each measured on both sides of the trade —
//! area (Yosys, whole top and the two blend units), throughput (fragments per clock) and
//! latency, against error (pipeline vs exact arithmetic, image PSNR vs the per-pixel
//! reference). Results are cached per configuration hash, so an interrupted sweep resumes
//! where it stopped; the table goes to CSV and JSON and the trade to an SVG with the Pareto
//! front marked.

use crate::config::PipelineConfig;
use crate::error::{toml_error, Error, Result};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A sweep space: a base configuration and a grid of values per field.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Space {
    #[serde(default)]
    pub base: toml::Table,
    pub grid: toml::Table,
    /// Scene whose image error is measured (default torus_caps): a built-in name, or a .toml
    /// file relative to the space file's folder.
    #[serde(default = "default_scene")]
    pub scene: String,
    /// An FPGA to measure each point on as well (`"ice40"`: LUTs and Fmax after place and
    /// route on an HX8K; `"ecp5"`, `"xilinx"`: LUTs). None by default: the sweep stays cheap.
    #[serde(default)]
    pub target: Option<super::fpga::Target>,
}

fn default_scene() -> String {
    "torus_caps".into()
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Point {
    pub config_hash: String,
    pub label: String,
    pub config: PipelineConfig,
    pub top_ge: f64,
    pub blend_ge: f64,
    pub flip_flops: u64,
    /// Bits of the top's RAMs (apart from `top_ge`).
    #[serde(alias = "rom_bits")]
    pub memory_bits: u64,
    pub fragments_per_clock: f64,
    pub latency: u32,
    pub max_error_lsb: f64,
    pub mean_error_lsb: f64,
    pub psnr_vs_reference_db: f64,
    pub pareto: bool,
    /// LUTs of the top on the space's `target` (none without one).
    #[serde(default)]
    pub fpga_luts: Option<u64>,
    /// The top's Fmax on the target (iCE40 only; none when it does not fit).
    #[serde(default)]
    pub fmax_mhz: Option<f64>,
    /// Where the area figures come from: "model" (`measure::area_model`) or "yosys".
    #[serde(default = "by_yosys")]
    pub area_by: String,
}

fn by_yosys() -> String {
    "yosys".into()
}

impl Space {
    /// Read and check a space: every field name and value type (at its own line), the grid's
    /// size and the scene, so a sweep never fails after its first Yosys run.
    pub fn load(path: &Path) -> Result<Space> {
        let text = crate::limits::read_text(path)?;
        let file = path.display().to_string();
        let mut s: Space = toml::from_str(&text).map_err(|e| {
            toml_error(
                &file,
                &text,
                &e,
                "a sweep space has scene, an optional target (ice40, ecp5 or xilinx: FPGA figures beside the gate equivalents every sweep measures), an optional [base] and a [grid] with arrays of values",
            )
        })?;
        // A scene file named by a relative path is found beside the space file, as a scene's
        // images are found beside the scene.
        if s.scene.ends_with(".toml") && Path::new(&s.scene).is_relative() {
            if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
                s.scene = dir.join(&s.scene).display().to_string();
            }
        }
        // Gate equivalents are what every sweep measures: `target = "cmos"` asks for nothing more.
        if s.target == Some(super::fpga::Target::Cmos) {
            s.target = None;
        }
        let spans: Spans = toml::from_str(&text).map_err(|e| toml_error(&file, &text, &e, "check the sweep space"))?;
        let at = |span: std::ops::Range<usize>| format!("{file}:{}", crate::error::line_col(&text, span.start).0);
        if s.grid.is_empty() {
            return Err(Error::field(
                &file,
                "grid",
                "empty",
                "give at least one field with an array of values",
            ));
        }
        for (k, v) in &spans.base {
            check_value(&text, &file, &format!("base.{k}"), k, v.get_ref(), v.span())?;
        }
        let mut points: u64 = 1;
        for (k, v) in &spans.grid {
            let field = format!("grid.{k}");
            let vals = v
                .get_ref()
                .as_array()
                .ok_or_else(|| Error::field(&at(v.span()), &field, "not an array", format!("write {k} = [value, value, ...]")))?;
            if vals.is_empty() {
                return Err(Error::field(&at(v.span()), &field, "empty array", "give at least one value"));
            }
            for x in vals {
                check_value(&text, &file, &field, k, x, v.span())?;
            }
            points = points.saturating_mul(vals.len() as u64);
        }
        if let Some(k) = s.base.keys().find(|k| s.grid.contains_key(*k)) {
            return Err(Error::field(
                &spans.base.get(k).map_or(file.clone(), |v| at(v.span())),
                &format!("base.{k}"),
                format!("`{k}` is in both [base] and [grid], and the grid's values would replace the base's"),
                format!("keep `{k}` in one of them"),
            ));
        }
        // A renamed field under its old name is said at its own line, then read under its new
        // one: the points' composed TOML has no lines of this file.
        for &(old, new) in crate::config::RENAMED_FIELDS {
            let Some(v) = spans.base.get(old).or_else(|| spans.grid.get(old)) else {
                continue;
            };
            let old_at = at(v.span());
            if [&s.base, &s.grid].iter().any(|t| t.contains_key(new)) {
                return Err(crate::config::renamed_twice(&old_at, old, new));
            }
            crate::warn::warn(crate::config::renamed_warning(&old_at, old, new));
            for t in [&mut s.base, &mut s.grid] {
                if let Some(v) = t.remove(old) {
                    t.insert(new.to_string(), v);
                }
            }
        }
        let max = crate::limits::MAX_SWEEP_POINTS;
        if points > max {
            return Err(Error::field(
                &file,
                "grid",
                format!("{points} combinations, more than MAX_SWEEP_POINTS = {max}"),
                "give fewer values per field, or split the sweep into several spaces",
            ));
        }
        let scene_at = spans.scene.as_ref().map_or(file.clone(), |sp| at(sp.span()));
        match crate::scene::Scene::load(&s.scene) {
            Err(Error::UnknownScene { name }) => {
                return Err(Error::field(
                    &scene_at,
                    "scene",
                    format!("unknown scene `{name}`"),
                    "run `gbump scenes` for the built-in names, or give a path to a .toml scene file",
                ))
            }
            Err(e) => return Err(e),
            Ok(_) => {}
        }
        // Refused here if no point is valid; the notes on skipped points wait for the sweep.
        s.expand(&file)?;
        if let Some(t) = s.target {
            super::fpga::require(t)?;
        }
        Ok(s)
    }

    /// Every valid configuration of the grid, with a label naming the varied fields; notes on
    /// the points skipped or merged go to stderr.
    pub fn configs(&self, file: &str) -> Result<Vec<(String, PipelineConfig)>> {
        let (out, notes) = self.expand(file)?;
        for n in notes {
            eprintln!("{n}");
        }
        Ok(out)
    }

    /// [`Space::configs`] with its notes returned rather than printed.
    fn expand(&self, file: &str) -> Result<(Vec<(String, PipelineConfig)>, Vec<String>)> {
        let mut combos: Vec<(Vec<String>, toml::Table)> = vec![(Vec::new(), self.base.clone())];
        // Values a grid list gives more than once, said apart from the designs that coincide.
        let mut repeated = Vec::new();
        for (k, v) in &self.grid {
            let vals = v.as_array().ok_or_else(|| {
                Error::field(
                    file,
                    &format!("grid.{k}"),
                    "not an array",
                    format!("write {k} = [value, value, ...]"),
                )
            })?;
            if vals.is_empty() {
                return Err(Error::field(file, &format!("grid.{k}"), "empty array", "give at least one value"));
            }
            for (i, x) in vals.iter().enumerate() {
                if vals[..i].contains(x) && !repeated.iter().any(|r: &String| r.starts_with(&format!("{k} = {x} "))) {
                    repeated.push(format!("{k} = {x} ({} times)", vals.iter().filter(|y| *y == x).count()));
                }
            }
            combos = combos
                .into_iter()
                .flat_map(|(lab, t)| {
                    vals.iter().map(move |x| {
                        let mut t = t.clone();
                        t.insert(k.clone(), x.clone());
                        let mut lab = lab.clone();
                        lab.push(format!("{k}={}", x.to_string().trim_matches('"')));
                        (lab, t)
                    })
                })
                .collect();
        }
        let mut out = Vec::new();
        let total = combos.len();
        let mut skipped: Vec<(String, String)> = Vec::new();
        // Points that differ only in a field their other values make inert are one design:
        // it is measured once, under the first point's label.
        let mut seen = std::collections::HashSet::new();
        let mut merged = 0;
        for (lab, t) in combos {
            let text = toml::to_string(&t).expect("table");
            match PipelineConfig::from_toml_canonical(file, &text) {
                Ok(c) if !seen.insert(c.hash()) => merged += 1,
                Ok(c) => out.push((lab.join(" "), c)),
                // An invalid combination (a rule across fields) is skipped, and counted.
                Err(Error::Field { field, msg, .. }) => skipped.push((lab.join(" "), format!("{field}: {msg}"))),
                Err(e) => return Err(e),
            }
        }
        let mut notes = Vec::new();
        if let Some((lab, why)) = skipped.first() {
            notes.push(format!(
                "note: {file}: {} of {total} grid points are invalid combinations and skipped (the first, {lab}: {why})",
                skipped.len()
            ));
        }
        if merged > 0 {
            let why = if repeated.is_empty() {
                "a field their other values leave unused".to_string()
            } else {
                format!("the grid lists {}", repeated.join(", "))
            };
            notes.push(format!(
                "note: {file}: {merged} of {total} grid points repeat another's design ({why}) and are measured once"
            ));
        }
        if out.is_empty() {
            let first = skipped
                .first()
                .map(|(lab, why)| format!(": every point is an invalid combination (the first, {lab}: {why})"))
                .unwrap_or_default();
            return Err(Error::Other(format!(
                "{file}: no valid configuration in the grid{first}\n  fix: change the grid or [base] so the fields named agree"
            )));
        }
        let (out, note) = fitting(out, &self.scene, file)?;
        notes.extend(note);
        Ok((out, notes))
    }
}

/// The keys of a space with their spans, so errors point at the line of the value.
#[derive(Deserialize)]
struct Spans {
    #[serde(default)]
    base: std::collections::BTreeMap<String, toml::Spanned<toml::Value>>,
    #[serde(default)]
    grid: std::collections::BTreeMap<String, toml::Spanned<toml::Value>>,
    #[serde(default)]
    scene: Option<toml::Spanned<String>>,
}

/// Refuse an unknown field, a value of the wrong type or a number outside its field's own
/// range at its own line; a value that fails only beside another field's value is left to the
/// grid (that combination is skipped, and counted).
fn check_value(text: &str, file: &str, field: &str, key: &str, v: &toml::Value, span: std::ops::Range<usize>) -> Result<()> {
    // A renamed field is checked under its new name (`Space::load` says the old one, at its line).
    let key = crate::config::RENAMED_FIELDS.iter().find(|r| r.0 == key).map_or(key, |r| r.1);
    if let (Some(&(_, lo, hi, why)), Some(x)) = (crate::config::LIMITS.iter().find(|l| l.0 == key), v.as_integer()) {
        if x < lo as i64 || x > hi as i64 {
            let (line, col) = crate::error::line_col(text, span.start);
            return Err(Error::Input {
                file: file.to_string(),
                line,
                col,
                msg: format!("`{field}`: {x} is out of range ({why})"),
                fix: format!("use values in {lo}..={hi}"),
            });
        }
    }
    let mut t = toml::Table::new();
    t.insert(key.to_string(), v.clone());
    match PipelineConfig::from_toml(file, &toml::to_string(&t).expect("table")) {
        Err(Error::Input { msg, fix, .. }) => {
            let (line, col) = crate::error::line_col(text, span.start);
            Err(Error::Input {
                file: file.to_string(),
                line,
                col,
                msg: format!("`{field}`: {msg}"),
                fix,
            })
        }
        _ => Ok(()),
    }
}

/// The iCE40 a sweep with `target = "ice40"` places and routes on.
pub const FPGA_DEVICE: &str = super::fpga::DEFAULT_DEVICE;

/// Image size and random stimuli per point: part of every point's cache key.
const IMAGE: (u32, u32) = (128, 96);
const ERROR_SAMPLES: u64 = 20_000;

/// The cache key of one point: everything its numbers depend on.
fn point_key(cfg: &PipelineConfig, scene: &crate::scene::Scene, target: Option<super::fpga::Target>, yosys: bool) -> Result<String> {
    let mut k = crate::cache::Key::new("sweep point");
    k.add(cfg.hash().as_bytes())
        .add(cfg.to_toml().as_bytes())
        .add(scene.fingerprint()?.as_bytes())
        .add(&IMAGE.0.to_le_bytes())
        .add(&IMAGE.1.to_le_bytes())
        .add(&ERROR_SAMPLES.to_le_bytes());
    if yosys {
        k.add(crate::yosys::scripts::cmos_area(&[], "").as_bytes()).add_tool("yosys");
    } else {
        // The model's weights: a recalibration invalidates the points it sized.
        k.add(format!("area model {:?}", super::area_model::COEFFICIENTS).as_bytes());
    }
    // Only a space with a target adds to the key, so plain sweeps keep their caches.
    if let Some(t) = target {
        k.add(t.name().as_bytes())
            .add(FPGA_DEVICE.as_bytes())
            .add(crate::yosys::scripts::fpga_summary(t).as_bytes());
        if t == super::fpga::Target::Ice40 {
            k.add_tool("nextpnr-ice40");
        }
    }
    Ok(k.finish())
}

/// Measure one configuration on `scene` (cached in `work/points/<key>.json`, the key made of
/// the configuration, the scene and its files, the sizes, gbump's and Yosys's versions).
pub fn measure(
    label: &str,
    cfg: &PipelineConfig,
    scene: &str,
    target: Option<super::fpga::Target>,
    yosys: bool,
    work: &Path,
) -> Result<Point> {
    let s = crate::scene::Scene::load(scene)?;
    let cache = work.join("points").join(format!("{}.json", point_key(cfg, &s, target, yosys)?));
    if let Ok(text) = std::fs::read_to_string(&cache) {
        if let Ok(p) = serde_json::from_str::<Point>(&text) {
            if cached_point_fits(&p, cfg, yosys) {
                return Ok(Point {
                    label: label.to_string(),
                    ..p
                });
            }
        }
    }
    // The top alone on the FPGA (its synthesis and place and route are cached by themselves).
    let fpga = match target {
        Some(t) if t != super::fpga::Target::Cmos => Some(super::fpga::fpga_area(cfg, t, FPGA_DEVICE, false, work, "gbump sweep")?),
        _ => None,
    };
    let area = if yosys {
        let area = super::area::cached_area(cfg, work)?;
        let ge = |name: &str| {
            area.units
                .iter()
                .filter(|u| u.unit.starts_with(name))
                .map(|u| u.gate_equivalents)
                .sum::<f64>()
        };
        let top = area.top();
        super::area_model::ModelArea {
            top_ge: top.gate_equivalents,
            // The blend hardware as instantiated: one parallel blend per enabled blend, or in
            // the serial form one accumulator and one finish per enabled blend.
            blend_ge: ge("diffuse_blend")
                + ge("specular_blend")
                + (cfg.diffuse as u32 + cfg.specular as u32) as f64 * (ge("light_accumulate") + ge("blend_finish")),
            flip_flops: top.flip_flops,
            memory_bits: top.memory_bits,
        }
    } else {
        super::area_model::model_area(cfg)
    };
    let errs = super::unit_error::unit_errors(cfg, ERROR_SAMPLES, 1);
    let pipe = errs
        .iter()
        .find(|e| e.unit == "gbump_pipeline" && e.source == "random")
        .expect("pipeline error");
    let img = crate::render::render(&s, cfg, IMAGE.0, IMAGE.1, false)?;
    let psnr = super::image_metrics::compare(&img.golden, &img.reference, &img.covered, img.colour_max).psnr_db;
    let p = Point {
        config_hash: cfg.hash(),
        label: label.to_string(),
        config: cfg.clone(),
        top_ge: area.top_ge,
        blend_ge: area.blend_ge,
        flip_flops: area.flip_flops,
        memory_bits: area.memory_bits,
        fragments_per_clock: 1.0 / cfg.initiation_interval() as f64,
        latency: crate::rtlgen::top::latency(cfg),
        max_error_lsb: pipe.max_lsb,
        mean_error_lsb: pipe.mean_lsb,
        psnr_vs_reference_db: psnr,
        pareto: false,
        fpga_luts: fpga.as_ref().map(|r| r.top().luts),
        fmax_mhz: fpga.as_ref().and_then(|r| r.place_route.as_ref()).and_then(|p| p.fmax_mhz),
        area_by: if yosys { "yosys" } else { "model" }.into(),
    };
    std::fs::create_dir_all(cache.parent().expect("dir")).map_err(|e| Error::io(&cache, e))?;
    crate::render::output::write_atomic(&cache, serde_json::to_string_pretty(&p).expect("json").as_bytes())?;
    Ok(p)
}

/// Whether a cached point is this configuration's, whole: every field that follows from the
/// configuration alone agrees with it (its hash, rate, latency, and the area model's figures
/// where the model sized it), and every measured figure is a possible one. Anything else is
/// measured again, so a cache entry edited or left by another version is never served.
fn cached_point_fits(p: &Point, cfg: &PipelineConfig, yosys: bool) -> bool {
    let by = if yosys { "yosys" } else { "model" };
    let sane = |v: f64| v.is_finite() && v >= 0.0;
    let derived = p.config == *cfg
        && p.config_hash == cfg.hash()
        && p.area_by == by
        && p.fragments_per_clock == 1.0 / cfg.initiation_interval() as f64
        && p.latency == crate::rtlgen::top::latency(cfg);
    let area = if yosys {
        p.top_ge > 0.0 && sane(p.top_ge) && sane(p.blend_ge) && p.blend_ge <= p.top_ge
    } else {
        let m = super::area_model::model_area(cfg);
        p.top_ge == m.top_ge && p.blend_ge == m.blend_ge && p.flip_flops == m.flip_flops && p.memory_bits == m.memory_bits
    };
    let errors = sane(p.max_error_lsb)
        && sane(p.mean_error_lsb)
        && p.mean_error_lsb <= p.max_error_lsb
        && !p.psnr_vs_reference_db.is_nan()
        && p.psnr_vs_reference_db > 0.0;
    derived && area && errors && !p.pareto
}

/// Mark the points no other point beats on both area and mean error.
pub fn mark_pareto(points: &mut [Point]) {
    let snapshot: Vec<(f64, f64)> = points.iter().map(|p| (p.top_ge, p.mean_error_lsb)).collect();
    for (i, p) in points.iter_mut().enumerate() {
        let (a, e) = snapshot[i];
        p.pareto = !snapshot
            .iter()
            .enumerate()
            .any(|(j, &(a2, e2))| j != i && a2 <= a && e2 <= e && (a2 < a || e2 < e));
    }
}

/// Run a sweep (parallel; with `progress`, a bar on a terminal or a line per configuration).
/// Every point of `space`; areas by Yosys when `yosys`, else by the area model.
pub fn sweep(space: &Space, file: &str, work: &Path, progress: bool, yosys: bool) -> Result<Vec<Point>> {
    let configs = space.configs(file)?;
    let bar = progress.then(|| crate::progress::Progress::new("sweep", configs.len() as u64));
    let mut points = configs
        .par_iter()
        .map(|(label, cfg)| {
            let p = measure(label, cfg, &space.scene, space.target, yosys, work);
            if let Some(b) = &bar {
                b.done(&format!("{label} ({})", &cfg.hash()[..8]));
            }
            p
        })
        .collect::<Result<Vec<_>>>()?;
    drop(bar);
    mark_pareto(&mut points);
    Ok(points)
}

/// The grid points that can render `scene` (`gbump render` refuses the others: too few light
/// slots for its bump lights, say), and a note naming the first skipped and why; refused when
/// none is left, so no point's image is of another design than its area.
fn fitting(configs: Vec<(String, PipelineConfig)>, scene: &str, file: &str) -> Result<(Vec<(String, PipelineConfig)>, Option<String>)> {
    let s = crate::scene::Scene::load(scene)?;
    let total = configs.len();
    let mut why = None;
    let out: Vec<_> = configs
        .into_iter()
        .filter(|(label, cfg)| match s.check_config(cfg, file) {
            Ok(()) => true,
            Err(e) => {
                why.get_or_insert_with(|| (label.clone(), e.to_string()));
                false
            }
        })
        .collect();
    let Some((label, e)) = why else {
        return Ok((out, None));
    };
    let first = e.lines().next().unwrap_or_default().to_string();
    if out.is_empty() {
        return Err(Error::Other(format!(
            "{file}: no grid point can render the scene {scene} (the first, {label}: {first})\n  fix: change the grid or [base] so its points fit the scene (the reason names the field), or sweep another scene"
        )));
    }
    let note = format!(
        "note: {file}: {} of the {total} designs in the grid cannot render the scene {scene} and are skipped (the first, {label}: {first})",
        total - out.len()
    );
    Ok((out, Some(note)))
}

/// Whether any point was measured on an FPGA (the CSV and the report then add its columns).
pub fn has_fpga(points: &[Point]) -> bool {
    points.iter().any(|p| p.fpga_luts.is_some())
}

pub fn csv(points: &[Point]) -> String {
    let fpga = has_fpga(points);
    let mut s = String::from("config_hash,label,top_ge,blend_ge,flip_flops,memory_bits,fragments_per_clock,latency,max_error_lsb,mean_error_lsb,psnr_vs_reference_db,pareto");
    s += if fpga { ",fpga_luts,fmax_mhz\n" } else { "\n" };
    for p in points {
        s += &format!(
            "{},\"{}\",{:.0},{:.0},{},{},{:.4},{},{:.3},{:.4},{:.2},{}",
            p.config_hash,
            p.label,
            p.top_ge,
            p.blend_ge,
            p.flip_flops,
            p.memory_bits,
            p.fragments_per_clock,
            p.latency,
            p.max_error_lsb,
            p.mean_error_lsb,
            p.psnr_vs_reference_db,
            p.pareto
        );
        if fpga {
            let opt = |v: Option<String>| v.unwrap_or_default();
            s += &format!(
                ",{},{}",
                opt(p.fpga_luts.map(|v| v.to_string())),
                opt(p.fmax_mhz.map(|v| format!("{v:.2}")))
            );
        }
        s += "\n";
    }
    s
}

/// Error against area as SVG: every configuration a dot, the Pareto front joined and ringed.
pub fn svg(points: &[Point], title: &str) -> String {
    let pts: Vec<super::plot::Dot> = points
        .iter()
        .map(|p| super::plot::Dot {
            x: p.top_ge,
            y: p.mean_error_lsb,
            label: p.label.clone(),
            front: p.pareto,
            chosen: false,
        })
        .collect();
    let by = if points.iter().all(|p| p.area_by == "model") {
        "area model"
    } else {
        "Yosys"
    };
    super::plot::scatter(
        &pts,
        title,
        &format!("top area, NAND2 gate equivalents ({by})"),
        "mean error vs exact arithmetic, LSB",
    )
}

#[cfg(test)]
mod tests {
    /// A value a grid list gives twice is named as such in the note, not blamed on a field
    /// left unused.
    #[test]
    fn a_value_listed_twice_is_named_in_the_note() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("sp.toml");
        std::fs::write(&p, "scene = \"cg_wall_front\"\n[grid]\nlights = [2, 2, 3]\n").unwrap();
        let (cfgs, notes) = super::Space::load(&p).unwrap().expand("sp.toml").unwrap();
        assert_eq!(cfgs.len(), 2);
        assert!(
            notes
                .iter()
                .any(|n| n.contains("1 of 3 grid points repeat") && n.contains("the grid lists lights = 2 (2 times)")),
            "{notes:?}"
        );
    }
}
