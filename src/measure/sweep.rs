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
    /// Scene whose image error is measured (default torus_caps).
    #[serde(default = "default_scene")]
    pub scene: String,
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
    pub rom_bits: u64,
    pub fragments_per_clock: f64,
    pub latency: u32,
    pub max_error_lsb: f64,
    pub mean_error_lsb: f64,
    pub psnr_vs_reference_db: f64,
    pub pareto: bool,
}

impl Space {
    pub fn load(path: &Path) -> Result<Space> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let file = path.display().to_string();
        let s: Space = toml::from_str(&text).map_err(|e| {
            toml_error(
                &file,
                &text,
                &e,
                "a sweep space has [base] (optional) and [grid] with arrays of values",
            )
        })?;
        if s.grid.is_empty() {
            return Err(Error::field(
                &file,
                "grid",
                "empty",
                "give at least one field with an array of values",
            ));
        }
        Ok(s)
    }

    /// Every valid configuration of the grid, with a label naming the varied fields.
    pub fn configs(&self, file: &str) -> Result<Vec<(String, PipelineConfig)>> {
        let mut combos: Vec<(Vec<String>, toml::Table)> = vec![(Vec::new(), self.base.clone())];
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
        for (lab, t) in combos {
            let text = toml::to_string(&t).expect("table");
            match PipelineConfig::from_toml(file, &text) {
                Ok(c) => out.push((lab.join(" "), c)),
                Err(Error::Field { .. }) => continue, // an invalid combination is skipped
                Err(e) => return Err(e),
            }
        }
        if out.is_empty() {
            return Err(Error::Other(format!(
                "{file}: no valid configuration in the grid\n  fix: check the ranges with `gbump config`"
            )));
        }
        Ok(out)
    }
}

/// Measure one configuration (cached in `work/points/<hash>.json`).
pub fn measure(label: &str, cfg: &PipelineConfig, scene: &str, work: &Path) -> Result<Point> {
    let cache = work.join("points").join(format!("{}.json", cfg.hash()));
    if let Ok(text) = std::fs::read_to_string(&cache) {
        if let Ok(p) = serde_json::from_str::<Point>(&text) {
            if p.config == *cfg {
                return Ok(Point {
                    label: label.to_string(),
                    ..p
                });
            }
        }
    }
    let area = super::area::area(cfg, &work.join("area"), "gbump sweep")?;
    let ge = |name: &str| {
        area.units
            .iter()
            .filter(|u| u.unit.starts_with(name))
            .map(|u| u.gate_equivalents)
            .sum::<f64>()
    };
    let top = area.units.iter().find(|u| u.unit.starts_with("gbump_pipeline")).expect("top");
    let errs = super::unit_error::unit_errors(cfg, 20_000, 1);
    let pipe = errs
        .iter()
        .find(|e| e.unit == "gbump_pipeline" && e.source == "random")
        .expect("pipeline error");
    let s = crate::scene::Scene::load(scene)?;
    let mut scfg = cfg.clone();
    scfg.lights = scfg.lights.max(s.bump_lights().count() as u32);
    let img = crate::render::render(&s, &scfg, 128, 96, false)?;
    let psnr = super::image_metrics::compare(&img.golden, &img.reference, &img.covered, img.colour_max).psnr_db;
    let p = Point {
        config_hash: cfg.hash(),
        label: label.to_string(),
        config: cfg.clone(),
        top_ge: top.gate_equivalents,
        blend_ge: ge("diffuse_blend") + ge("specular_blend"),
        flip_flops: top.flip_flops,
        rom_bits: top.rom_bits,
        fragments_per_clock: 1.0 / cfg.initiation_interval() as f64,
        latency: crate::rtlgen::top::latency(cfg),
        max_error_lsb: pipe.max_lsb,
        mean_error_lsb: pipe.mean_lsb,
        psnr_vs_reference_db: psnr,
        pareto: false,
    };
    std::fs::create_dir_all(cache.parent().expect("dir")).map_err(|e| Error::io(&cache, e))?;
    crate::render::output::write_atomic(&cache, serde_json::to_string_pretty(&p).expect("json").as_bytes())?;
    Ok(p)
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
pub fn sweep(space: &Space, file: &str, work: &Path, progress: bool) -> Result<Vec<Point>> {
    let configs = space.configs(file)?;
    let bar = progress.then(|| crate::progress::Progress::new("sweep", configs.len() as u64));
    let mut points = configs
        .par_iter()
        .map(|(label, cfg)| {
            let p = measure(label, cfg, &space.scene, work);
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

pub fn csv(points: &[Point]) -> String {
    let mut s = String::from("config_hash,label,top_ge,blend_ge,flip_flops,rom_bits,fragments_per_clock,latency,max_error_lsb,mean_error_lsb,psnr_vs_reference_db,pareto\n");
    for p in points {
        s += &format!(
            "{},\"{}\",{:.0},{:.0},{},{},{:.4},{},{:.3},{:.4},{:.2},{}\n",
            p.config_hash,
            p.label,
            p.top_ge,
            p.blend_ge,
            p.flip_flops,
            p.rom_bits,
            p.fragments_per_clock,
            p.latency,
            p.max_error_lsb,
            p.mean_error_lsb,
            p.psnr_vs_reference_db,
            p.pareto
        );
    }
    s
}

/// Error against area as SVG: every configuration a dot, the Pareto front joined and ringed.
pub fn svg(points: &[Point], title: &str) -> String {
    let (w, h, m) = (720.0, 440.0, 70.0);
    let xs: Vec<f64> = points.iter().map(|p| p.top_ge).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.mean_error_lsb).collect();
    let (x0, x1) = (0.0, xs.iter().cloned().fold(1.0, f64::max) * 1.08);
    let (y0, y1) = (0.0, ys.iter().cloned().fold(0.01, f64::max) * 1.15);
    let px = |x: f64| m + (x - x0) / (x1 - x0) * (w - 1.5 * m);
    let py = |y: f64| h - m - (y - y0) / (y1 - y0) * (h - 1.8 * m);
    let mut s = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"22\" font-size=\"14\" text-anchor=\"middle\">{}</text>\n", w / 2.0, esc(title));
    s += &format!("<line x1=\"{m}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"black\"/>\n<line x1=\"{m}\" y1=\"{}\" x2=\"{m}\" y2=\"{}\" stroke=\"black\"/>\n", h - m, w - 0.5 * m, h - m, h - m, 0.8 * m);
    for i in 0..=5 {
        let xv = x0 + (x1 - x0) * i as f64 / 5.0;
        let yv = y0 + (y1 - y0) * i as f64 / 5.0;
        s += &format!(
            "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\">{:.0}</text>\n",
            px(xv),
            h - m + 16.0,
            xv
        );
        s += &format!(
            "<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{:.3}</text>\n",
            m - 6.0,
            py(yv) + 4.0,
            yv
        );
    }
    s += &format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">top area, NAND2 gate equivalents (Yosys)</text>\n",
        w / 2.0,
        h - 22.0
    );
    s += &format!(
        "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">mean error vs exact arithmetic, LSB</text>\n",
        h / 2.0,
        h / 2.0
    );
    // The paper's 10,000–25,000 GE estimate for the blend units, as a band.
    s += &format!(
        "<rect x=\"{:.1}\" y=\"{}\" width=\"{:.1}\" height=\"{}\" fill=\"#2a7\" opacity=\"0.08\"/>\n",
        px(10_000.0),
        0.8 * m,
        (px(25_000.0) - px(10_000.0)).max(0.0),
        h - 1.8 * m
    );
    s += &format!(
        "<text x=\"{:.1}\" y=\"{}\" fill=\"#2a7\">paper: 10k-25k GE</text>\n",
        px(10_000.0) + 4.0,
        0.8 * m + 12.0
    );
    let mut front: Vec<&Point> = points.iter().filter(|p| p.pareto).collect();
    front.sort_by(|a, b| a.top_ge.total_cmp(&b.top_ge));
    let path: Vec<String> = front
        .iter()
        .map(|p| format!("{:.1},{:.1}", px(p.top_ge), py(p.mean_error_lsb)))
        .collect();
    s += &format!(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#c33\" stroke-width=\"1.5\"/>\n",
        path.join(" ")
    );
    for p in points {
        let (cx, cy) = (px(p.top_ge), py(p.mean_error_lsb));
        s += &format!(
            "<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"3.5\" fill=\"#246\"><title>{}</title></circle>\n",
            esc(&p.label)
        );
        if p.pareto {
            s += &format!("<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"7\" fill=\"none\" stroke=\"#c33\"/>\n<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"9\">{}</text>\n", cx + 8.0, cy - 6.0, esc(&p.label));
        }
    }
    s + "</svg>\n"
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
