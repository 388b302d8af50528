//! `gbump render`: a scene's golden, f64 Gouraud and per-pixel reference images, the heat map
//! of golden against reference and the metrics JSON, written together; with `rtl`, also the
//! image the Verilated pipeline renders, which must equal the golden one. The files are written
//! together once every image exists (an RTL build or simulation that fails leaves nothing),
//! then the lines for the user go to `say`.

use super::output::{codes_to_u8, encode_png, f64_to_u8, heat_map, quantise, write_files};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::measure::image_metrics::{compare, error_map};
use crate::scene::Scene;
use crate::work_lock::WorkLock;
use std::io::IsTerminal;
use std::path::Path;

/// What `gbump render` was asked for.
pub struct RenderRequest<'a> {
    /// Built-in scene name or scene file.
    pub scene: &'a str,
    pub out: &'a Path,
    /// `WxH` (default: the scene's).
    pub size: Option<&'a str>,
    /// Configuration file (default: derived from the scene).
    pub config: Option<&'a Path>,
    /// Also render through the RTL, in this work folder (`--work`, by default
    /// `sim::rtl_image::RENDER_WORK`).
    pub rtl: Option<&'a Path>,
}

/// Scene plus the configuration to render it with (a given file, or derived).
pub fn scene_and_config(scene: &str, config: Option<&Path>) -> Result<(Scene, PipelineConfig)> {
    let s = Scene::load(scene)?;
    let cfg = match config {
        Some(p) => {
            let c = PipelineConfig::load(p)?;
            s.check_config(&c, &p.display().to_string())?;
            crate::config::note_origin(&p.display().to_string());
            c
        }
        None => {
            let c = s.derive_config()?;
            crate::config::note_derived(scene);
            c
        }
    };
    Ok((s, cfg))
}

/// Refuse scene `s` at `w`x`h` where its name cannot name its files or the render would not
/// fit in memory (`use_` says what the command keeps per pixel), before anything is rendered.
pub fn renderable(s: &crate::scene::Scene, use_: crate::limits::PixelUse, w: u32, h: u32) -> Result<()> {
    crate::names::check(&s.file, "name", &s.name)?;
    crate::limits::check_render(use_, &s.file, w, h, s.triangles())
}

/// Render, write the files and report; `lock` takes the RTL's work folder (only with `rtl`,
/// after the golden images are rendered, before any file is written). An RTL image that differs is an error.
pub fn render(r: &RenderRequest, lock: impl FnOnce() -> Result<WorkLock>, say: &mut dyn FnMut(&str) -> Result<()>) -> Result<()> {
    let (s, cfg) = scene_and_config(r.scene, r.config)?;
    let (w, h) = match r.size {
        Some(sz) => crate::limits::parse_size("--size", sz)?,
        None => (s.size[0], s.size[1]),
    };
    let use_ = if r.rtl.is_some() {
        crate::limits::PixelUse::RenderRtl
    } else {
        crate::limits::PixelUse::Render
    };
    renderable(&s, use_, w, h)?;
    if let Some(work) = r.rtl {
        // Scene fragments reach the RTL as a scene vector set: refused where one is.
        let from = r
            .config
            .map_or_else(|| format!("{} (its derived configuration)", s.file), |p| p.display().to_string());
        crate::vectors::sources::scene_sets_made(&cfg, &format!("{from}: render --rtl"))?;
        crate::sim::require(crate::sim::Sim::Verilator)?;
        // A work folder the simulators cannot take is refused before anything is rendered
        // or written.
        crate::sim::check_tool_path(work, "--work")?;
    }
    let t0 = std::time::Instant::now();
    let img = super::render(&s, &cfg, w, h, std::io::stderr().is_terminal())?;
    let secs = t0.elapsed().as_secs_f64();
    let max = img.colour_max;
    let vs_ref = compare(&img.golden, &img.reference, &img.covered, max);
    let vs_gou = compare(&img.golden, &img.gouraud, &img.covered, max);
    let alg = compare(&quantise(&img.gouraud, max), &img.reference, &img.covered, max);
    let emap = error_map(&img.golden, &img.reference, &img.covered, max);
    let name = &s.name;
    let files = [
        (format!("{name}_golden.png"), codes_to_u8(&img.golden, max)),
        (format!("{name}_gouraud_f64.png"), f64_to_u8(&img.gouraud)),
        (format!("{name}_reference.png"), f64_to_u8(&img.reference)),
        (format!("{name}_diff.png"), heat_map(&emap, vs_ref.max_lsb.max(4.0))),
    ];
    let mut blobs: Vec<(String, Vec<u8>)> = Vec::new();
    for (f, px) in &files {
        blobs.push((f.clone(), encode_png(w, h, px)?));
    }
    let report = serde_json::json!({
        "scene": name, "size": [w, h], "config_hash": cfg.hash(), "fragments": vs_ref.pixels,
        "golden_vs_reference": vs_ref, "golden_vs_gouraud_f64": vs_gou, "gouraud_f64_vs_reference": alg,
        "seconds": secs,
    });
    blobs.push((
        format!("{name}_metrics.json"),
        serde_json::to_string_pretty(&report).expect("json").into_bytes(),
    ));
    // The RTL image first: a build or simulation that fails leaves nothing in the output
    // folder; one that differs writes every image, its own among them, as the evidence.
    let mut rtl = None;
    if let Some(work) = r.rtl {
        let t0 = std::time::Instant::now();
        let _lock = lock()?;
        let img_rtl = crate::sim::rtl_image::rtl_image(r.scene, &cfg, w, h, work)?;
        blobs.push((format!("{name}_rtl.png"), encode_png(w, h, &codes_to_u8(&img_rtl, max))?));
        let differ = img_rtl.iter().zip(&img.golden).filter(|(a, b)| a != b).count();
        rtl = Some((differ, t0.elapsed().as_secs_f64()));
    }
    // A run without --rtl removes an earlier run's RTL image with the files it replaces: it
    // was of another size or configuration, and read beside these as if of this run.
    let stale_rtl = r.out.join(format!("{name}_rtl.png"));
    let retired = rtl.is_none() && std::fs::symlink_metadata(&stale_rtl).is_ok_and(|m| m.is_file());
    crate::commit::together(|| {
        if retired {
            crate::commit::retire(&stale_rtl)?;
        }
        write_files(r.out, &blobs)
    })?;
    if retired {
        say(&format!(
            "  removed {name}_rtl.png, an earlier run's RTL image (add --rtl to make this run's)"
        ))?;
    }
    say(&format!(
        "scene {name} {w}x{h}, config {}, {} fragments, {:.2} s",
        cfg.hash(),
        vs_ref.pixels,
        secs
    ))?;
    say(&format!(
        "  golden vs per-pixel reference: PSNR {:6.2} dB, max {:5.1} LSB, mean {:.3} LSB, {:5.2}% of pixels off by >1 LSB",
        vs_ref.psnr_db,
        vs_ref.max_lsb,
        vs_ref.mean_lsb,
        100.0 * vs_ref.over_1lsb
    ))?;
    say(&format!(
        "  golden vs {}: PSNR {:6.2} dB, max {:5.1} LSB, mean {:.3} LSB, {:5.2}% of pixels off by >1 LSB",
        // The configuration's own equations in f64: EMBM's maps, or Gouraud bump's lights.
        if cfg.embm() { "f64 EMBM equations " } else { "f64 Gouraud bump   " },
        vs_gou.psnr_db,
        vs_gou.max_lsb,
        vs_gou.mean_lsb,
        100.0 * vs_gou.over_1lsb
    ))?;
    say(&format!(
        "  wrote {} and {name}_metrics.json in {}",
        files.iter().map(|f| f.0.as_str()).collect::<Vec<_>>().join(", "),
        r.out.display()
    ))?;
    if let Some((differ, secs)) = rtl {
        say(&format!(
            "  RTL (Verilator) image: {name}_rtl.png, {secs:.1} s, {differ} pixel(s) differ from the golden image"
        ))?;
        if differ > 0 {
            return Err(Error::Other(format!(
                "the RTL image differs from the golden image in {differ} pixels"
            )));
        }
    }
    Ok(())
}
