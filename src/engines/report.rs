//! `gbump engines`: every engine on the same scenes, measured against the Blinn reference:
//! PSNR, largest and mean error, share of pixels more than 1 LSB off, and the seam error (how
//! much more an engine's colour jumps across a shared triangle edge than the reference's
//! does); a contact sheet (engines as columns, scenes as rows, each image over its difference
//! from the reference); and the Markdown table.

use super::{Ctx, Engine, Maps, ENGINES};
use crate::error::Result;
use crate::raster::fragment::pixel_geom;
use crate::raster::rasterise::rasterise;
use crate::raster::Prepared;
use crate::scene::Scene;
use rayon::prelude::*;

/// One engine's image of one scene, [0, 1] per channel, background where nothing is drawn.
pub struct EngineImage {
    pub w: u32,
    pub h: u32,
    pub rgb: Vec<[f64; 3]>,
    /// (object, triangle) drawn at each pixel: the scene's, shared by every engine's image.
    pub owner: std::sync::Arc<Vec<Option<(u32, u32)>>>,
}

/// Render `engines` over `scene` at `w`×`h`.
pub fn render(scene: &Scene, engines: &[&Engine], w: u32, h: u32, maps: Maps) -> Result<Vec<EngineImage>> {
    // The scene's own configuration: the Gouraud engine reads its blend order and skip_flat.
    let cfg = scene.derive_config()?;
    let p = Prepared::new(scene, &cfg, w, h)?;
    let ctx = Ctx::new(&p, maps);
    let gb = rasterise(&p)?;
    let owner: std::sync::Arc<Vec<Option<(u32, u32)>>> = std::sync::Arc::new(gb.hits.iter().map(|h| h.map(|h| (h.obj, h.tri))).collect());
    let bg = scene.camera.background;
    Ok(engines
        .iter()
        .map(|e| EngineImage {
            w,
            h,
            rgb: gb
                .hits
                .par_iter()
                .map(|hit| match hit {
                    None => bg,
                    Some(hit) => {
                        let g = pixel_geom(&p, hit);
                        (e.shade)(&ctx, hit, &g).clamp(glam::DVec3::ZERO, glam::DVec3::ONE).to_array()
                    }
                })
                .collect(),
            owner: owner.clone(),
        })
        .collect())
}

/// One engine against the reference on one scene, errors in 8-bit LSBs.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct EngineError {
    pub psnr_db: f64,
    pub max_lsb: f64,
    pub mean_lsb: f64,
    pub over_1lsb: f64,
    /// Over pixel pairs side by side on different triangles of one object: the largest and the
    /// mean of |engine's jump − reference's jump|, per channel.
    pub seam_max_lsb: f64,
    pub seam_mean_lsb: f64,
}

const LSB: f64 = 255.0;

/// `img` against `reference` over the drawn pixels.
pub fn compare(img: &EngineImage, reference: &EngineImage) -> EngineError {
    let diffs = img
        .rgb
        .iter()
        .zip(&reference.rgb)
        .zip(img.owner.iter())
        .filter(|(_, o)| o.is_some())
        .map(|((a, b), _)| [0, 1, 2].map(|i| (a[i] - b[i]) * LSB));
    let e = crate::measure::image_metrics::stats(diffs, LSB);
    let (mut seam_max, mut seam_sum, mut pairs) = (0.0f64, 0.0f64, 0usize);
    let (w, h) = (img.w as usize, img.h as usize);
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            for j in [(x + 1 < w).then_some(i + 1), (y + 1 < h).then_some(i + w)].into_iter().flatten() {
                let (Some(a), Some(b)) = (img.owner[i], img.owner[j]) else {
                    continue;
                };
                if a.0 != b.0 || a.1 == b.1 {
                    continue;
                }
                for c in 0..3 {
                    let jump = img.rgb[i][c] - img.rgb[j][c];
                    let ref_jump = reference.rgb[i][c] - reference.rgb[j][c];
                    let d = ((jump - ref_jump) * LSB).abs();
                    seam_max = seam_max.max(d);
                    seam_sum += d;
                }
                pairs += 1;
            }
        }
    }
    EngineError {
        psnr_db: e.psnr_db,
        max_lsb: e.max_lsb,
        mean_lsb: e.mean_lsb,
        over_1lsb: e.over_1lsb,
        seam_max_lsb: seam_max,
        seam_mean_lsb: seam_sum / (3 * pairs).max(1) as f64,
    }
}

/// Every engine of `engines` on every scene of `scenes`: the images and their errors.
pub struct Table {
    pub engines: Vec<&'static Engine>,
    pub scenes: Vec<String>,
    /// Each scene's bump lights.
    pub lights: Vec<u32>,
    /// `errors[scene][engine]`.
    pub errors: Vec<Vec<EngineError>>,
    /// `images[scene][engine]`.
    pub images: Vec<Vec<EngineImage>>,
    /// `fixed[scene][engine]`: the engine's bit-accurate path, where it has one.
    pub fixed: Vec<Vec<Option<Fixed>>>,
    pub maps: Maps,
}

/// An engine's bit-accurate path on one scene: the golden model's image against the
/// reference, and the generated top's size as the area model counts it.
#[derive(Clone, Debug)]
pub struct Fixed {
    pub config_hash: String,
    pub error: EngineError,
    pub area_ge: f64,
    pub flip_flops: u64,
    pub memory_bits: u64,
    pub latency: u32,
}

/// The golden model's image of `scene` under `cfg` (what the generated RTL computes) as an
/// engine image the size of `reference`, sharing its drawn pixels, so `compare` measures it
/// against the reference.
pub fn golden_image(scene: &Scene, cfg: &crate::config::PipelineConfig, reference: &EngineImage) -> Result<EngineImage> {
    let (w, h) = (reference.w, reference.h);
    let (codes, _) = crate::render::golden(scene, cfg, w, h)?;
    let m = cfg.colour_max() as f64;
    Ok(EngineImage {
        w,
        h,
        rgb: codes.iter().map(|c| c.map(|x| x as f64 / m)).collect(),
        owner: reference.owner.clone(),
    })
}

/// The bit-accurate path of `e` on `scene` at `reference`'s size against it, when it has one.
fn fixed(scene: &Scene, e: &Engine, reference: &EngineImage) -> Result<Option<Fixed>> {
    let Some(cfg) = e.fixed_config(scene)? else {
        return Ok(None);
    };
    cfg.validate(&format!("{} (engine {})", scene.file, e.name))?;
    let img = golden_image(scene, &cfg, reference)?;
    let area = crate::measure::area_model::model_area(&cfg);
    Ok(Some(Fixed {
        config_hash: cfg.hash()[..8].to_string(),
        error: compare(&img, reference),
        area_ge: area.top_ge,
        flip_flops: area.flip_flops,
        memory_bits: area.memory_bits,
        latency: crate::rtlgen::top::latency(&cfg),
    }))
}

/// Measure `engines` (the reference added first when missing) on `scenes` at `size` (or each
/// scene's own size halved, to keep the sheet small).
pub fn measure(scenes: &[String], engines: &[&'static Engine], size: Option<(u32, u32)>, maps: Maps) -> Result<Table> {
    let mut list: Vec<&'static Engine> = vec![&ENGINES[0]];
    list.extend(engines.iter().filter(|e| e.name != ENGINES[0].name));
    let (mut errors, mut images, mut lights, mut fixeds) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for name in scenes {
        let s = Scene::load(name)?;
        lights.push(s.bump_lights().count() as u32);
        let (w, h) = size.unwrap_or((s.size[0] / 2, s.size[1] / 2));
        crate::limits::check_render(crate::limits::PixelUse::Engines, &s.file, w, h, s.triangles())?;
        let imgs = render(&s, &list, w.max(1), h.max(1), maps)?;
        errors.push(imgs.iter().map(|i| compare(i, &imgs[0])).collect());
        fixeds.push(list.iter().map(|e| fixed(&s, e, &imgs[0])).collect::<Result<Vec<_>>>()?);
        images.push(imgs);
    }
    Ok(Table {
        engines: list,
        scenes: scenes.to_vec(),
        lights,
        errors,
        images,
        fixed: fixeds,
        maps,
    })
}

impl Table {
    /// The Markdown section: one row per engine and scene, then what each engine holds.
    pub fn markdown(&self) -> String {
        let mut s = String::from(
            "| scene | engine | PSNR (dB) | max (LSB) | mean (LSB) | pixels > 1 LSB | seam max (LSB) | seam mean (LSB) | bytes per triangle | words per fragment |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
        );
        for (si, scene) in self.scenes.iter().enumerate() {
            for (ei, e) in self.engines.iter().enumerate() {
                let r = &self.errors[si][ei];
                let psnr = if r.psnr_db.is_infinite() {
                    // Only the reference is the reference; another engine can equal it exactly.
                    if e.name == super::blinn::BLINN.name {
                        "∞ (reference)"
                    } else {
                        "∞ (identical)"
                    }
                    .to_string()
                } else {
                    format!("{:.2}", r.psnr_db)
                };
                let n = self.lights[si];
                s += &format!(
                    "| {scene} | {} | {psnr} | {:.2} | {:.3} | {:.1} % | {:.2} | {:.3} | {} | {} |\n",
                    e.name,
                    r.max_lsb,
                    r.mean_lsb,
                    100.0 * r.over_1lsb,
                    r.seam_max_lsb,
                    r.seam_mean_lsb,
                    e.cost.triangle_bytes(n),
                    e.cost.fragment_words(n)
                );
            }
        }
        s += &self.fixed_markdown();
        s += "\n| engine | source | per triangle | per fragment |\n|---|---|---|---|\n";
        for e in &self.engines {
            s += &format!("| {} | {} | {} | {} |\n", e.name, e.source, e.per_triangle, e.per_fragment);
        }
        // The map sizes of the engines in the table, and only those.
        let has = |name: &str| self.engines.iter().any(|e| e.name == name);
        let mut maps = String::new();
        if has(super::embm::EMBM.name) {
            let n = self.maps.embm_map;
            maps += &format!(
                " EMBM's environment maps have {n}×{n} texels; moving one light regenerates 2 · {n}² = {} texels per object.",
                2 * n * n
            );
        }
        if has(super::cg::CG.name) {
            maps += &format!(
                " The Cg engine's normalisation cube map has {0}×{0} texels a face.",
                self.maps.cg_cube
            );
        }
        s += &format!(
            "\nErrors are in 8-bit LSBs against `blinn` over the drawn pixels, every engine in f64 (no arithmetic rounding: each engine's own approximations only). The seam error compares the colour jump between two side-by-side pixels on different triangles of one object with the reference's jump there. Bytes per triangle (16-bit words, two bytes each) and words per fragment count what goes beyond what a textured Gouraud triangle already carries (screen positions, colours, uv), at the scene's number of bump lights: what the engine sends to the rasteriser, and what its interpolators produce per fragment.{maps} The contact sheet's columns are the engines in this table's order; under each scene's row of images is their difference from `blinn` (full scale 16 LSB).\n",
        );
        if self.maps.renormalise_map {
            s += "\nWhat-if (`--renormalise-map`): SGI and Cg renormalise the map's filtered normal before lighting with it, which neither text does; their f64 rows above show it, no other engine's changes, and the bit-accurate paths do not (in hardware that is `renormalise_bump = true`, a `normalise_b` unit after the fetch: `gbump claim map-filter`).\n";
        }
        s
    }

    /// The bit-accurate paths: each engine that has one, on each scene.
    fn fixed_markdown(&self) -> String {
        let mut s = String::from(
            "\nBit-accurate paths (the golden model's image, what the generated RTL computes, against `blinn`; the top's logic by the area model, `gbump area` synthesises it with Yosys):\n\n| scene | engine | config | PSNR (dB) | max (LSB) | mean (LSB) | pixels > 1 LSB | seam max (LSB) | seam mean (LSB) | logic (GE, model) | flip-flops | memory bits | latency (cycles) |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
        );
        let mut none = Vec::new();
        for (si, scene) in self.scenes.iter().enumerate() {
            for (ei, e) in self.engines.iter().enumerate() {
                let Some(f) = &self.fixed[si][ei] else {
                    if si == 0 {
                        none.push(format!("`{}`", e.name));
                    }
                    continue;
                };
                let r = &f.error;
                s += &format!(
                    "| {scene} | {} | `{}` | {:.2} | {:.2} | {:.3} | {:.1} % | {:.2} | {:.3} | {:.0} | {} | {} | {} |\n",
                    e.name,
                    f.config_hash,
                    r.psnr_db,
                    r.max_lsb,
                    r.mean_lsb,
                    100.0 * r.over_1lsb,
                    r.seam_max_lsb,
                    r.seam_mean_lsb,
                    f.area_ge,
                    f.flip_flops,
                    f.memory_bits,
                    f.latency
                );
            }
        }
        if !none.is_empty() {
            s += &format!("\nNo bit-accurate path or RTL yet (f64 only): {}.\n", none.join(", "));
        }
        s
    }

    /// CSV of the error table.
    pub fn csv(&self) -> String {
        let mut s =
            String::from("scene,engine,psnr_db,max_lsb,mean_lsb,over_1lsb,seam_max_lsb,seam_mean_lsb,triangle_bytes,fragment_words,fixed_config,fixed_psnr_db,fixed_max_lsb,fixed_mean_lsb,fixed_over_1lsb,fixed_seam_max_lsb,fixed_seam_mean_lsb,fixed_logic_ge,fixed_flip_flops,fixed_memory_bits,fixed_latency\n");
        for (si, scene) in self.scenes.iter().enumerate() {
            for (ei, e) in self.engines.iter().enumerate() {
                let r = &self.errors[si][ei];
                let fx = self.fixed[si][ei].as_ref().map_or(",,,,,,,,,,".to_string(), |f| {
                    let r = &f.error;
                    format!(
                        "{},{},{},{},{},{},{},{},{},{},{}",
                        f.config_hash,
                        r.psnr_db,
                        r.max_lsb,
                        r.mean_lsb,
                        r.over_1lsb,
                        r.seam_max_lsb,
                        r.seam_mean_lsb,
                        f.area_ge,
                        f.flip_flops,
                        f.memory_bits,
                        f.latency
                    )
                });
                s += &format!(
                    "{scene},{},{},{},{},{},{},{},{},{},{fx}\n",
                    e.name,
                    r.psnr_db,
                    r.max_lsb,
                    r.mean_lsb,
                    r.over_1lsb,
                    r.seam_max_lsb,
                    r.seam_mean_lsb,
                    e.cost.triangle_bytes(self.lights[si]),
                    e.cost.fragment_words(self.lights[si])
                );
            }
        }
        s
    }

    /// The contact sheet: a column per engine under its name, and per scene its name, then
    /// its images, then their differences from the reference as heat maps (full scale at
    /// 16 LSB), a 2-pixel gutter. A column is as wide as its widest image and the longest
    /// engine name, so no name is cut at a small `--size`; images are centred in it.
    pub fn contact_sheet(&self) -> (u32, u32, Vec<[u8; 3]>) {
        use crate::render::label::{draw, CHAR_W, LINE_H};
        const GAP: u32 = 2;
        const INK: [u8; 3] = [230, 230, 230];
        let band = LINE_H + GAP;
        let iw = self.images.iter().flat_map(|r| r.iter().map(|i| i.w)).max().unwrap_or(1);
        let name_w = self
            .engines
            .iter()
            .map(|e| e.name.chars().count() as u32 * CHAR_W)
            .max()
            .unwrap_or(0);
        let cw = iw.max(name_w);
        let ch = self.images.iter().flat_map(|r| r.iter().map(|i| i.h)).max().unwrap_or(1);
        let cols = self.engines.len() as u32;
        let scene_h = band + 2 * (ch + GAP);
        let (w, h) = (cols * (cw + GAP) + GAP, GAP + band + self.scenes.len() as u32 * scene_h);
        let mut px = vec![[40u8; 3]; (w * h) as usize];
        let col_x = |col: u32| GAP + col * (cw + GAP);
        for (ei, e) in self.engines.iter().enumerate() {
            draw(&mut px, w, col_x(ei as u32), GAP, e.name, cw, INK);
        }
        let put = |px: &mut [[u8; 3]], col: u32, y0: u32, iw: u32, pixels: &[[u8; 3]]| {
            let x0 = col_x(col) + (cw - iw) / 2;
            for (k, c) in pixels.iter().enumerate() {
                let (x, y) = (x0 + k as u32 % iw, y0 + k as u32 / iw);
                px[(y * w + x) as usize] = *c;
            }
        };
        for (si, row) in self.images.iter().enumerate() {
            let top = GAP + band + si as u32 * scene_h;
            for (ei, img) in row.iter().enumerate() {
                put(&mut px, ei as u32, top + band, img.w, &crate::render::output::f64_to_u8(&img.rgb));
                let err: Vec<f64> = img
                    .rgb
                    .iter()
                    .zip(&row[0].rgb)
                    .map(|(a, b)| (0..3).map(|c| ((a[c] - b[c]) * LSB).abs()).fold(0.0, f64::max))
                    .collect();
                put(
                    &mut px,
                    ei as u32,
                    top + band + ch + GAP,
                    img.w,
                    &crate::render::output::heat_map(&err, 16.0),
                );
            }
            let name = std::path::Path::new(&self.scenes[si])
                .file_stem()
                .map_or(self.scenes[si].clone(), |s| s.to_string_lossy().into());
            let label = format!("{name}: images, then |difference from blinn| (16 LSB full scale)");
            draw(&mut px, w, GAP, top, &label, w - 2 * GAP, INK);
        }
        (w, h, px)
    }
}

/// The fourth claim's text: Gouraud bump mapping's whole top against the first per-pixel
/// building block gbump generates (the `normalise` unit), both from the bit-accurate table.
pub fn cost_claim(t: &Table) -> String {
    // The smallest and largest top of the engines `pick` names, over every scene.
    let range = |pick: &dyn Fn(&super::Engine) -> bool| {
        let ge: Vec<f64> = t
            .engines
            .iter()
            .enumerate()
            .filter(|(_, e)| e.fixed.is_some() && pick(e))
            .flat_map(|(ei, _)| t.fixed.iter().filter_map(move |row| row[ei].as_ref().map(|f| f.area_ge)))
            .collect();
        ge.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)))
    };
    let (lo, hi) = range(&|e| e.fixed.is_some_and(|v| !v.renormalise && v.env_map_bits == 0));
    let (elo, ehi) = range(&|e| e.name == "embm");
    let (nlo, nhi) = range(&|e| ["gouraud_hn", "gouraud_hln"].contains(&e.name));
    let (hlo, hhi) = range(&|e| e.name == "harmony");
    let (tlo, thi) = range(&|e| e.name == "texram");
    let (qlo, qhi) = range(&|e| e.name == "visa_quaternion");
    let (clo, chi) = range(&|e| e.name == "cg");
    let (blo, bhi) = range(&|e| e.name == "blinn");
    // One normalise unit at the default widths, by the same area model.
    let cfg = crate::config::PipelineConfig {
        bump_state: crate::config::BumpStateAt::Fragment,
        interpolate: crate::config::Interpolate::H,
        renormalise: true,
        light_mode: crate::config::LightMode::Parallel,
        ..Default::default()
    };
    let unit = crate::measure::area_model::unit_features(&cfg, "normalise")
        .expect("normalise is a unit")
        .ge(&crate::measure::area_model::COEFFICIENTS);
    let compared = if unit > hi {
        "That one step alone costs more than the whole Gouraud bump top of any scene, which is the paper's argument".to_string()
    } else {
        format!(
            "That one step alone costs {:.0} % of the largest Gouraud bump top",
            100.0 * unit / hi
        )
    };
    format!(
        "\n### Gouraud bump mapping's added units against the per-pixel engines' cost\n\nHalf measured. Gouraud bump mapping's side is in the bit-accurate table above: each scene's own configuration, the whole generated top (every unit the paper adds to a textured Gouraud pipeline, bank registers and output buffer included), {lo:.0} to {hi:.0} GE of logic by the area model (held within 10 % mean, 20 % max of Yosys, section \"Area model against Yosys\"), the power table and banks in memory bits apart. The per-pixel side has its first building block: the `normalise` unit that every per-pixel engine needs to scale an interpolated vector back to unit length (a reciprocal-square-root table and a Newton step) is {unit:.0} GE by the area model at the default 16-bit L and H (the model is calibrated on the Gouraud units and has not been fitted to this one; `gbump area --config tests/configs/renormalise_hl.toml` synthesises it), one per vector, so the renormalising variants `gouraud_hn` (one a light) and `gouraud_hln` (two a light) take {nlo:.0} to {nhi:.0} GE for the whole top (parallel lights: the normalise units sit before the parallel dot products). {compared}. Seven per-pixel engines are generated whole: Harmony's path (the `frame_transform` unit's 3×3 transform into the interpolated frame, `normalise_b` on the placed normal and a `normalise` per interpolated vector) takes {hlo:.0} to {hhi:.0} GE, and VISA+'s with its per-triangle matrix is the same top fed the triangle's T and B; VISA+'s with quaternions (the same with the `quat_frame` unit: the rotation's T and B from ten products, no division) {qlo:.0} to {qhi:.0} GE; TexRam's (the same with the `frame_build` unit forming the frame per fragment: two more normalisations and two cross products) {tlo:.0} to {thi:.0} GE; Blinn's (TexRam's top lighting at the pixel: each light's H normalised from its normalised L and the viewer direction, the same units) {blo:.0} to {bhi:.0} GE; and the Cg Tutorial's (a `normalise_cube` map read per vector, the squaring power unit) {clo:.0} to {chi:.0} GE; and EMBM's (`env_coords` forming the texel and bilinear weights, two `env_fetch` units reading four texels of each map, the blends as the filter; no dot product or power unit) {elo:.0} to {ehi:.0} GE of logic, its two maps (four copies each, one per texel of the 2×2 block) in memory bits apart.\n"
    )
}

/// The report's section on the engines: every engine on every built-in scene (each at half
/// its size) and each of the paper's claims with its figure; the files it links (the
/// contact sheet and the claims' SVGs) beside it.
pub fn section() -> Result<(String, Vec<(String, Vec<u8>)>)> {
    let scenes: Vec<String> = crate::scene::builtin::ALL.iter().map(|(n, _)| n.to_string()).collect();
    let all: Vec<&'static Engine> = ENGINES.iter().collect();
    let t = measure(&scenes, &all, None, Maps::default())?;
    let (w, h, px) = t.contact_sheet();
    let mut md = String::from("`gbump engines` (every built-in scene at half its size); ![engines as columns, scenes as rows, each over its difference from Blinn](engines.png)\n\n");
    md += &t.markdown();
    let mut files = vec![("engines.png".to_string(), crate::render::output::encode_png(w, h, &px)?)];
    for (name, what) in super::claims::CLAIMS {
        let c = super::claims::claim(name)?;
        md += &format!(
            "\n### {what}\n\n`gbump claim {name}`; ![{name}](claim-{name}.svg)\n\n{}",
            c.markdown
        );
        files.push((format!("claim-{name}.svg"), c.svg.into_bytes()));
    }
    md += &cost_claim(&t);
    Ok((md, files))
}
