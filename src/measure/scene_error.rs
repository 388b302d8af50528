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

/// Image error of every built-in scene that fits `cfg`'s light slots.
pub fn scene_errors(cfg: &PipelineConfig, w: u32, h: u32) -> Result<Vec<SceneError>> {
    let mut out = Vec::new();
    for (name, _) in builtin::ALL {
        let s = Scene::load(name)?;
        if s.check_config(cfg, "").is_err() {
            continue;
        }
        // The scene's own per-object choices stay; the hardware is `cfg`.
        let img = crate::render::render(&s, cfg, w, h, false)?;
        let g = compare(&img.golden, &img.gouraud, &img.covered, img.colour_max);
        let r = compare(&img.golden, &img.reference, &img.covered, img.colour_max);
        out.push((name.to_string(), g, r));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_size_argument_is_the_size() {
        let (w, h) = super::IMAGE_SIZE;
        assert_eq!(super::IMAGE_SIZE_ARG, format!("{w}x{h}"));
    }
}
