//! Image error of the built-in scenes under one configuration: the golden image against the
//! f64 Gouraud-equation image and against the per-pixel reference (`gbump error`, the report).

use crate::config::PipelineConfig;
use crate::error::Result;
use crate::measure::image_metrics::compare;
use crate::scene::{builtin, Scene};

/// Rows of `scene_errors` as a Markdown table.
pub fn scene_error_table(rows: &[SceneError]) -> String {
    let mut s = String::from("| scene | vs f64 Gouraud: PSNR dB | max | >1 LSB | vs per-pixel reference: PSNR dB | max | >1 LSB |\n|---|---:|---:|---:|---:|---:|---:|\n");
    for (name, g, r) in rows {
        s += &format!(
            "| {name} | {:.2} | {:.1} | {:.1}% | {:.2} | {:.1} | {:.1}% |\n",
            g.psnr_db,
            g.max_lsb,
            100.0 * g.over_1lsb,
            r.psnr_db,
            r.max_lsb,
            100.0 * r.over_1lsb
        );
    }
    s
}

/// A scene's name and its golden image's error against the f64 Gouraud image and the reference.
pub type SceneError = (
    String,
    crate::measure::image_metrics::ImageError,
    crate::measure::image_metrics::ImageError,
);

/// Refuse a size at which some built-in scene cannot be rendered, before any is.
pub fn check_builtin_renders(use_: crate::limits::PixelUse, w: u32, h: u32) -> Result<()> {
    for (name, _) in builtin::ALL {
        let s = Scene::load(name)?;
        crate::limits::check_render(use_, &s.file, w, h, s.triangles())?;
    }
    Ok(())
}

/// The per-scene table's image size: `gbump error`'s default and the report's.
pub const IMAGE_SIZE: (u32, u32) = (192, 144);
/// [`IMAGE_SIZE`] as `--size` takes it.
pub const IMAGE_SIZE_ARG: &str = "192x144";

/// Image error of every built-in scene that fits `cfg`, and the ones that do not with why
/// (the first line of the refusal `gbump render --config` would give).
pub fn scene_errors(cfg: &PipelineConfig, w: u32, h: u32) -> Result<(Vec<SceneError>, Vec<(String, String)>)> {
    let (mut out, mut left_out) = (Vec::new(), Vec::new());
    for (name, _) in builtin::ALL {
        let s = Scene::load(name)?;
        if let Err(e) = s.check_config_fields(cfg, "the configuration") {
            left_out.push((name.to_string(), e.to_string().lines().next().unwrap_or_default().to_string()));
            continue;
        }
        out.push(scene_error(&s, cfg, w, h)?);
    }
    Ok((out, left_out))
}

/// Image error of scene `s` rendered under `cfg` at `w`x`h`; its per-object choices stay.
pub fn scene_error(s: &Scene, cfg: &PipelineConfig, w: u32, h: u32) -> Result<SceneError> {
    let img = crate::render::render(s, cfg, w, h, false)?;
    let g = compare(&img.golden, &img.gouraud, &img.covered, img.colour_max);
    let r = compare(&img.golden, &img.reference, &img.covered, img.colour_max);
    Ok((s.name.clone(), g, r))
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_size_argument_is_the_size() {
        let (w, h) = super::IMAGE_SIZE;
        assert_eq!(super::IMAGE_SIZE_ARG, format!("{w}x{h}"));
    }
}
