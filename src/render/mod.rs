//! Rendering a scene three ways: through the golden model (bit-accurate), through the f64
//! Gouraud bump equations, and through the per-pixel f64 reference.

pub mod label;
pub mod output;
pub mod report;

use crate::config::PipelineConfig;
use crate::error::Result;
use crate::model::shade;
use crate::raster::fragment::{colour_codes, fragments, pixel_geom};
use crate::raster::rasterise::rasterise;
use crate::raster::{FragmentRecord, Prepared};
use crate::reference::perpixel;
use crate::scene::Scene;
use glam::DVec3;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

/// The three images of one scene, row-major; colours are codes (golden) or [0, 1] (f64).
pub struct Images {
    pub w: u32,
    pub h: u32,
    pub colour_max: u32,
    pub golden: Vec<[u32; 3]>,
    pub gouraud: Vec<[f64; 3]>,
    pub reference: Vec<[f64; 3]>,
    /// Pixels covered by a fragment (metrics are taken over these).
    pub covered: Vec<bool>,
}

/// The golden image of `frags`, background elsewhere.
pub fn golden_image(p: &Prepared, frags: &[FragmentRecord], bar: &ProgressBar) -> Vec<[u32; 3]> {
    let (w, h) = (p.camera.width, p.camera.height);
    let bg = colour_codes(DVec3::from_array(p.scene.camera.background), p.cfg.colour_max());
    let mut img = vec![bg; (w * h) as usize];
    let colours: Vec<[u32; 3]> = frags
        .par_chunks(4096)
        .flat_map_iter(|chunk| {
            bar.inc(chunk.len() as u64);
            chunk.iter().map(|f| {
                let o = &p.objects[f.obj as usize];
                if p.cfg.embm() {
                    return crate::model::pipeline::shade_embm(p.cfg, &o.env, &f.state, &f.frag).colour();
                }
                let table = &p.tables[&p.scene.objects[f.obj as usize].shininess];
                shade(p.cfg, table, o.stored.palette(), &f.state, &f.frag).colour()
            })
        })
        .collect();
    for (f, c) in frags.iter().zip(colours) {
        img[(f.y * w + f.x) as usize] = c;
    }
    img
}

/// The golden image alone and the covered pixels: what a search over configurations renders
/// many times against one f64 image (the f64 images do not depend on widths).
pub fn golden(scene: &Scene, cfg: &PipelineConfig, w: u32, h: u32) -> Result<(Vec<[u32; 3]>, Vec<bool>)> {
    let p = Prepared::new(scene, cfg, w, h)?;
    let gb = rasterise(&p)?;
    let frags = fragments(&p, &gb);
    let img = golden_image(&p, &frags, &ProgressBar::hidden());
    Ok((img, gb.hits.iter().map(Option::is_some).collect()))
}

/// Render all three images. `progress` shows a bar on stderr.
pub fn render(scene: &Scene, cfg: &PipelineConfig, w: u32, h: u32, progress: bool) -> Result<Images> {
    let p = Prepared::new(scene, cfg, w, h)?;
    let gb = rasterise(&p)?;
    let frags = fragments(&p, &gb);
    let bar = if progress {
        ProgressBar::new(frags.len() as u64 * 2)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} fragments")
            .expect("template")
            .progress_chars("=> "),
    );
    bar.set_message(format!("render {}", scene.name));
    let golden = golden_image(&p, &frags, &bar);
    let bg = scene.camera.background;
    let pairs: Vec<([f64; 3], [f64; 3])> = gb
        .hits
        .par_iter()
        .map(|hit| match hit {
            None => (bg, bg),
            Some(hit) => {
                let g = pixel_geom(&p, hit);
                (
                    crate::reference::equations(&p, hit, &g).to_array(),
                    perpixel::shade(&p, hit, &g).to_array(),
                )
            }
        })
        .collect();
    bar.inc(frags.len() as u64);
    bar.finish_and_clear();
    let (gouraud, reference) = pairs.into_iter().unzip();
    Ok(Images {
        w,
        h,
        colour_max: cfg.colour_max(),
        golden,
        gouraud,
        reference,
        covered: gb.hits.iter().map(Option::is_some).collect(),
    })
}
