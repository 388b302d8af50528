//! The survey's bump engines (paper §2–3, §6; Cg Tutorial §8) as f64 models, each rendering
//! the same scenes through its own approximation of Blinn's perturbed-normal lighting, so
//! `gbump engines` can say which engine gives which image quality. Each engine keeps the
//! approximations that define it (what it interpolates, what it holds per triangle, what it
//! looks up in a map) and none of any arithmetic's rounding: those are the fixed-point
//! models' part.
//!
//! Assumptions the texts leave open, the same for every engine unless its file says
//! otherwise:
//! - the bump map is the object's f64 normal map (the stored map before quantisation),
//!   sampled with the object's filter; an engine that wants offsets (VISA+, EMBM) takes
//!   `(x/z, y/z)` of it, the height gradient Eq. 1 encodes; an engine that lights with the
//!   map's normal directly (SGI, Cg, and Gouraud's, whose variants all leave
//!   `renormalise_bump` off) takes it as the texture unit's filter leaves it, shortened
//!   between texels, since no text renormalises it (`common::map_normal`; the engines that
//!   place it in a frame renormalise the result, which undoes the shortening);
//! - lights are the scene's bump lights; the viewer is parallel (as in every renderer here);
//! - the colour is `min(min(C_src + D, 1) · T + S, 1)` with `C_src` the non-bump lighting, the
//!   combination `reference::perpixel` uses: engines with per-pixel normals evaluate `C_src`
//!   per pixel, engines on a Gouraud rasteriser interpolate it from the vertices.

pub mod blinn;
pub mod cg;
pub mod claims;
pub mod common;
pub mod embm;
pub mod gouraud;
pub mod harmony;
pub mod report;
pub mod sgi;
pub mod texram;
pub mod visa;

pub use crate::config::PerFragment;
use crate::raster::{Hit, PixelGeom, Prepared};
use glam::DVec3;

/// One engine: its name on the command line and in tables, where it comes from, and its
/// per-pixel colour in [0, 1].
pub struct Engine {
    pub name: &'static str,
    pub source: &'static str,
    /// What it holds or sends per triangle, and interpolates per fragment (the paper's
    /// argument is about both).
    pub per_triangle: &'static str,
    pub per_fragment: &'static str,
    pub cost: Cost,
    pub shade: fn(&Ctx, &Hit, &PixelGeom) -> DVec3,
    /// Whether the engine blends as the scene's configuration says (blend order, skip_flat:
    /// Gouraud bump mapping's engines) rather than as every other engine does,
    /// `min(min(C_src + D, 1) · T + S, 1)` with no flat bypass (`common::finish`).
    pub scene_blend: bool,
    /// The engine's bit-accurate path, where gbump generates it: the scene's own
    /// configuration (`gbump config --scene`) with these per-fragment choices, rendered by the
    /// golden model and generated as RTL like any configuration. None: the engine is f64 only
    /// so far.
    pub fixed: Option<PerFragment>,
}

impl Engine {
    /// The configuration of the engine's bit-accurate path on `scene` (None: the engine has
    /// none yet): the scene's own configuration (`Scene::derive_config`) with the engine's
    /// per-fragment choices.
    pub fn fixed_config(&self, scene: &crate::scene::Scene) -> crate::error::Result<Option<crate::config::PipelineConfig>> {
        use crate::config::{BumpStateAt, Interpolate, LightMode, PowerUnitKind};
        let Some(v) = self.fixed else {
            return Ok(None);
        };
        let mut cfg = scene.derive_config()?;
        if !self.scene_blend {
            cfg.blend_order = crate::config::BlendOrder::DiffuseTextureSpecular;
            cfg.skip_flat = false;
        }
        // Every per-fragment choice is the engine's, whatever the scene's configuration says.
        cfg.interpolate = v.interpolate;
        cfg.renormalise = v.renormalise;
        cfg.interpolate_k = v.interpolate_k;
        cfg.renormalise_bump = v.renormalise_bump;
        cfg.cube_map_face = v.cube_map_face;
        cfg.frame_transform = v.frame_transform;
        cfg.frame_build = v.frame_build;
        cfg.triangle_frame = v.triangle_frame;
        cfg.frame_quaternion = v.frame_quaternion;
        cfg.pixel_lh = v.pixel_lh;
        cfg.env_map_bits = v.env_map_bits;
        if v.env_map_bits > 0 {
            // EMBM (`validate_embm`): the four light slots are the bilinear filter's texels in
            // one parallel blend per map, the map coordinates enter per fragment, the stored
            // normal's x and y are (du, dv), and the lighting is in the maps.
            cfg.lights = 4;
            cfg.light_mode = LightMode::Parallel;
            cfg.bump_state = BumpStateAt::Fragment;
            cfg.palette = false;
            cfg.white_lights = false;
            cfg.power_rom = false;
            cfg.dot_frac_bits = cfg.dot_frac_bits.max(crate::model::env_map::WEIGHT_FRAC_BITS);
            cfg.power_frac_bits = cfg.power_frac_bits.max(crate::model::env_map::WEIGHT_FRAC_BITS);
        }
        if v.renormalise_bump {
            // The fetched normal is renormalised, which a palette (unfiltered, loaded as
            // given) refuses: the engine's path fetches the stored codes instead.
            cfg.palette = false;
        }
        if v.squaring {
            // Successive squarings: no table, so none to make a ROM of.
            cfg.power_unit = PowerUnitKind::Squaring;
            cfg.power_rom = false;
        }
        // Self-shadowing where the scene asks for it (its per-pixel reference applies it).
        cfg.self_shadow = v.self_shadow && scene.self_shadowing && cfg.diffuse;
        if v.interpolate != Interpolate::None || v.interpolate_k || v.frame_transform {
            // An interpolated vector, k or frame reaches the pipeline per fragment.
            cfg.bump_state = BumpStateAt::Fragment;
        }
        if v.interpolate_k && cfg.k_frac_bits == 0 {
            // A scene whose k are all 0 or 1 at the triangles still needs fractions between
            // its vertices.
            cfg.k_frac_bits = crate::config::PipelineConfig::default().k_frac_bits;
        }
        if v.renormalise {
            // The normalise units sit one per vector before the parallel dot products.
            cfg.light_mode = LightMode::Parallel;
        }
        // Per-fragment state has no triangle banks, whatever the scene's configuration held.
        Ok(Some(cfg.canonical()))
    }
}

/// A scene made ready for the engines: the prepared scene, and what an engine computes once
/// per object rather than per pixel.
pub struct Ctx<'a> {
    pub p: &'a Prepared<'a>,
    /// Texels along EMBM's environment-map side.
    pub embm_map: u32,
    /// Texels along a face edge of the Cg engine's normalisation cube map.
    pub cg_cube: u32,
    /// Engines that light with the map's normal as the texture unit filters it (SGI, Cg)
    /// renormalise it first: a what-if that `gbump claim map-filter` measures.
    pub renormalise_map: bool,
}

impl<'a> Ctx<'a> {
    pub fn new(p: &'a Prepared<'a>, maps: Maps) -> Ctx<'a> {
        Ctx {
            p,
            embm_map: maps.embm_map,
            cg_cube: maps.cg_cube,
            renormalise_map: maps.renormalise_map,
        }
    }
}

/// The sizes of the maps that engines look their lighting or normalisation up in, and how
/// the bump map's filtered normal reaches the engines that light with it directly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Maps {
    pub embm_map: u32,
    pub cg_cube: u32,
    /// See [`Ctx::renormalise_map`]; false is each engine's own text.
    pub renormalise_map: bool,
}

impl Default for Maps {
    fn default() -> Maps {
        Maps {
            embm_map: embm::EMBM_MAP,
            cg_cube: cg::CUBE_FACE,
            renormalise_map: false,
        }
    }
}

/// What an engine sends and interpolates, in 16-bit words, beyond what a textured Gouraud
/// triangle already carries (screen positions, colours, uv): per triangle to the rasteriser,
/// and per fragment out of its interpolators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cost {
    pub triangle: u32,
    pub triangle_per_light: u32,
    pub fragment: u32,
    pub fragment_per_light: u32,
}

impl Cost {
    /// Bytes sent per triangle with `lights` bump lights.
    pub fn triangle_bytes(&self, lights: u32) -> u32 {
        2 * (self.triangle + lights * self.triangle_per_light)
    }
    /// Words interpolated per fragment with `lights` bump lights.
    pub fn fragment_words(&self, lights: u32) -> u32 {
        self.fragment + lights * self.fragment_per_light
    }
}

/// Every engine, the reference first.
pub const ENGINES: &[Engine] = &[
    blinn::BLINN,
    texram::TEXRAM,
    visa::VISA,
    visa::VISA_QUATERNION,
    embm::EMBM,
    sgi::SGI,
    harmony::HARMONY,
    gouraud::GOURAUD,
    gouraud::GOURAUD_H,
    gouraud::GOURAUD_HL,
    gouraud::GOURAUD_HN,
    gouraud::GOURAUD_HLN,
    cg::CG,
];

/// The engine called `name` when it has a bit-accurate path; otherwise an error naming the
/// engines that have one.
pub fn fixed_engine(name: &str) -> crate::error::Result<&'static Engine> {
    let with: Vec<&str> = ENGINES.iter().filter(|e| e.fixed.is_some()).map(|e| e.name).collect();
    match engine(name) {
        Some(e) if e.fixed.is_some() => Ok(e),
        found => Err(crate::error::Error::Other(format!(
            "--engine {name}: {}\n  fix: use one of {}",
            if found.is_some() {
                "this engine is f64 only so far (no bit-accurate path, no RTL)"
            } else {
                "no such engine"
            },
            with.join(", ")
        ))),
    }
}

/// The engine called `name`.
pub fn engine(name: &str) -> Option<&'static Engine> {
    ENGINES.iter().find(|e| e.name == name)
}
