//! Scenes: camera, lights and objects, read from TOML (the built-ins ship as such files in
//! `scenes/`). A scene says what it needs; [`Scene::derive_config`] turns that into the
//! smallest pipeline that renders it ("model only what the scene requires").

pub mod builtin;
pub mod camera;
mod fingerprint;
pub mod lighting;
pub mod mesh;
pub mod needs;
pub mod sphere_map;
pub mod teapot;
pub(crate) mod validate;

use crate::bumpmap::{Filter, HeightSource, NormalMethod};
use crate::config::PipelineConfig;
use crate::error::{toml_error, Error, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub use camera::Camera;

/// A whole scene file.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub name: String,
    #[serde(default)]
    pub description: String,
    /// Default image size [w, h].
    #[serde(default = "default_size")]
    pub size: [u32; 2],
    pub camera: CameraDesc,
    /// Ambient light, added to the Gouraud colour of every vertex.
    #[serde(default)]
    pub ambient: [f64; 3],
    /// Overrides of the derived pipeline configuration (any `PipelineConfig` field).
    #[serde(default)]
    pub pipeline: Option<toml::Table>,
    #[serde(default)]
    pub lights: Vec<Light>,
    /// The per-pixel reference applies the Cg Tutorial's geometric self-shadowing (§8.5.3):
    /// no light reaches a point whose geometric normal faces away from it, whatever its bump
    /// normal says. The pipeline has no such test, so this measures what omitting it costs.
    #[serde(default)]
    pub self_shadowing: bool,
    pub objects: Vec<Object>,
    /// Folder that relative paths (PNG height maps) are resolved against.
    #[serde(skip)]
    pub base: PathBuf,
    /// Where the scene came from, for error messages.
    #[serde(skip)]
    pub file: String,
    /// `LINE:COL` of each `[pipeline]` key (and of the table, under ""), for error messages;
    /// a renamed field's under its new name.
    #[serde(skip)]
    pub pipeline_lines: std::collections::BTreeMap<String, String>,
    /// Renamed fields written under their old names: new name to old.
    #[serde(skip)]
    pub pipeline_old_names: std::collections::BTreeMap<String, String>,
}

fn default_size() -> [u32; 2] {
    [256, 256]
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Where the viewer stands: the near plane, so only what lies in front of it (towards
    /// `target`) is drawn.
    pub eye: [f64; 3],
    pub target: [f64; 3],
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    /// Height of the orthographic view in world units (the paper's parallel viewer).
    pub height: f64,
    #[serde(default)]
    pub background: [f64; 3],
}

fn default_up() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LightKind {
    /// Parallel light; `direction` points towards the light.
    Directional,
    /// Light at `position`; the pipeline treats it as parallel per triangle (paper §4).
    Point,
    /// Spotlight at `position` shining along `direction`.
    Spot,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    pub kind: LightKind,
    #[serde(default)]
    pub direction: [f64; 3],
    #[serde(default)]
    pub position: [f64; 3],
    pub colour: [f64; 3],
    /// Acts on the bump map (a light slot of the pipeline); otherwise it is carried by the
    /// Gouraud colour (paper §5.4.1, Fig. 6's spotlights).
    #[serde(default = "yes")]
    pub bump: bool,
    /// Constant modulation k_i in [0, 1].
    #[serde(default = "one")]
    pub k: f64,
    #[serde(default = "default_cutoff")]
    pub cutoff_deg: f64,
    #[serde(default)]
    pub exponent: f64,
}

fn yes() -> bool {
    true
}
fn one() -> f64 {
    1.0
}
fn default_cutoff() -> f64 {
    30.0
}

/// A parametric or patch shape.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
    /// A w×h rectangle in the xy plane, normal +z.
    Plane {
        size: [f64; 2],
    },
    Sphere {
        radius: f64,
    },
    /// Open cylinder along z; `sides` > 0 makes it a faceted prism (paper Figs. 5/8).
    Cylinder {
        radius: f64,
        height: f64,
        #[serde(default)]
        sides: u32,
    },
    Torus {
        major: f64,
        minor: f64,
    },
    /// Newell's teapot, about 3 units tall. (An empty struct variant, not a unit one: serde
    /// lets a unit variant of a tagged enum take any other key, which must be refused.)
    Teapot {},
}

impl Shape {
    /// The shape as a person names it (its `kind`; a cylinder with `sides = 0` is smooth).
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Plane { .. } => "plane",
            Shape::Sphere { .. } => "sphere",
            Shape::Cylinder { sides: 0, .. } => "smooth cylinder",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Torus { .. } => "torus",
            Shape::Teapot {} => "teapot",
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    pub shape: Shape,
    /// Tessellation [u, v] (per patch for the teapot), at least `mesh::min_segments` of the
    /// shape: 3 around a sphere, torus or smooth cylinder, 2 along a sphere, 3 along a torus.
    #[serde(default = "default_segments")]
    pub segments: [u32; 2],
    #[serde(default)]
    pub translate: [f64; 3],
    #[serde(default)]
    pub rotate_deg: [f64; 3],
    #[serde(default = "one")]
    pub scale: f64,
    /// Repeats of the bump map and texture over the surface's [0,1]² parameter square (a
    /// prism's u is per facet: its `uv_scale[0]` must be 1).
    #[serde(default = "default_uv_scale")]
    pub uv_scale: [f64; 2],
    #[serde(default)]
    pub shininess: u32,
    #[serde(default = "yes")]
    pub diffuse: bool,
    #[serde(default = "yes")]
    pub specular: bool,
    #[serde(default)]
    pub texture: Texture,
    pub bump: BumpDesc,
}

fn default_segments() -> [u32; 2] {
    [32, 16]
}
fn default_uv_scale() -> [f64; 2] {
    [1.0, 1.0]
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Texture {
    Constant { colour: [f64; 3] },
    Checker { cells: u32, a: [f64; 3], b: [f64; 3] },
}

impl Default for Texture {
    fn default() -> Self {
        Texture::Constant { colour: [1.0; 3] }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BumpDesc {
    pub source: HeightSource,
    /// Side of the generated map in texels (PNG maps keep their size).
    #[serde(default = "default_map_size")]
    pub size: u32,
    #[serde(default = "default_strength")]
    pub strength: f64,
    #[serde(default)]
    pub method: NormalMethod,
    #[serde(default)]
    pub filter: Filter,
    /// Bake the normals of a `sides`-sided cylinder into the map (paper §5.3).
    #[serde(default)]
    pub cylinder_sides: u32,
}

fn default_map_size() -> u32 {
    128
}
fn default_strength() -> f64 {
    4.0
}

/// The configuration a command works on: a TOML file, a scene's derived one, or the default
/// (`--config` / `--scene`, which the command line makes exclusive).
pub fn pick_config(config: Option<&Path>, scene: Option<&str>) -> Result<PipelineConfig> {
    match (config, scene) {
        (Some(p), _) => {
            let cfg = PipelineConfig::load(p)?;
            crate::config::note_origin(&p.display().to_string());
            Ok(cfg)
        }
        (None, Some(s)) => {
            let cfg = Scene::load(s)?.derive_config()?;
            crate::config::note_derived(s);
            Ok(cfg)
        }
        (None, None) => Ok(PipelineConfig::default()),
    }
}

impl Scene {
    /// Parse scene TOML; `file` names it in errors and `base` resolves relative paths.
    pub fn from_toml(file: &str, text: &str, base: &Path) -> Result<Scene> {
        let mut s: Scene = toml::from_str(text).map_err(|e| {
            let fix = crate::error::wrong_kind(text, "scene");
            toml_error(
                file,
                text,
                &e,
                fix.as_deref()
                    .unwrap_or("compare with a built-in scene: `gbump scenes --show NAME`"),
            )
        })?;
        s.base = base.to_path_buf();
        s.file = file.to_string();
        // Each override's place, however it is written (a `[pipeline]` table, dotted keys,
        // an inline table), from the parser's own spans.
        let place = |path: &str| crate::toml_line::place(text, path).map(|(l, c)| format!("{l}:{c}"));
        if let Some(over) = s.pipeline.as_ref() {
            if let Some(at) = place("pipeline") {
                s.pipeline_lines.insert(String::new(), at);
            }
            for k in over.keys() {
                if let Some(at) = place(&format!("pipeline.{k}")) {
                    s.pipeline_lines.insert(k.clone(), at);
                }
            }
        }
        // A renamed configuration field under its old name: read as the new one, with a
        // warning; under both names, refused.
        if let Some(over) = s.pipeline.as_mut() {
            for &(old, new) in crate::config::RENAMED_FIELDS {
                let Some(v) = over.remove(old) else { continue };
                let pos = s.pipeline_lines.remove(old);
                let at = pos.as_ref().map_or(file.to_string(), |p| format!("{file}:{p}"));
                if over.contains_key(new) {
                    return Err(crate::config::renamed_twice(&at, old, new));
                }
                crate::warn::warn(crate::config::renamed_warning(&at, old, new));
                over.insert(new.to_string(), v);
                if let Some(p) = pos {
                    s.pipeline_lines.insert(new.to_string(), p);
                }
                s.pipeline_old_names.insert(new.to_string(), old.to_string());
            }
        }
        validate::validate(&s, text)?;
        Ok(s)
    }

    /// A built-in name or a path to a `.toml` file.
    pub fn load(name_or_path: &str) -> Result<Scene> {
        if let Some(text) = builtin::get(name_or_path) {
            return Scene::from_toml(&format!("scenes/{name_or_path}.toml"), text, Path::new("scenes"));
        }
        let p = Path::new(name_or_path);
        if p.extension().is_some_and(|e| e == "toml") || p.exists() {
            let text = crate::limits::read_text(p)?;
            return Scene::from_toml(name_or_path, &text, p.parent().unwrap_or(Path::new(".")));
        }
        Err(Error::UnknownScene {
            name: name_or_path.to_string(),
        })
    }

    /// Triangles of the whole scene once tessellated.
    pub fn triangles(&self) -> u64 {
        self.objects.iter().map(mesh::triangle_count).sum()
    }

    /// Lights that act on the bump map, in slot order.
    pub fn bump_lights(&self) -> impl Iterator<Item = &Light> {
        self.lights.iter().filter(|l| l.bump)
    }

    /// The smallest configuration that renders this scene, then the scene's own overrides.
    pub fn derive_config(&self) -> Result<PipelineConfig> {
        let mut cfg = needs::SceneNeeds::of(self).sized();
        if let Some(over) = &self.pipeline {
            let mut base = toml::Table::try_from(&cfg).expect("config is a table");
            for (k, v) in over {
                base.insert(k.clone(), v.clone());
            }
            let text = toml::to_string(&base).expect("table serialises");
            cfg = PipelineConfig::from_toml(&self.file, &text).map_err(|e| self.at_pipeline_line(e))?;
            let at = self.pipeline_at("lights");
            self.check_config(&cfg, &at).map_err(|e| match e {
                Error::Field { file, field, msg, fix } => Error::Field {
                    file,
                    field: format!("pipeline.{field}"),
                    msg,
                    fix,
                },
                e => e,
            })?;
        }
        // Every configuration a tool builds goes through the same checks as one read from a
        // file: a scene the pipeline cannot take fails here, named, not deep in a run.
        cfg.validate(&format!("{} (the configuration it derives)", self.file))?;
        Ok(cfg)
    }

    /// `file:LINE:COL` of `key` in `[pipeline]` (of the table when the key is not there).
    fn pipeline_at(&self, key: &str) -> String {
        let line = self.pipeline_lines.get(key).or_else(|| self.pipeline_lines.get(""));
        line.map_or(self.file.clone(), |l| format!("{}:{l}", self.file))
    }

    /// `pipeline.FIELD` as the scene writes it (a renamed field under its old name), and
    /// whether the scene writes it at all.
    fn pipeline_field(&self, field: &str) -> (String, bool) {
        let written = self.pipeline.as_ref().is_some_and(|p| p.contains_key(field));
        let name = self.pipeline_old_names.get(field).map_or(field, String::as_str);
        (format!("pipeline.{name}"), written)
    }

    /// An override's error, which names a line of the merged table, moved to the scene's line.
    fn at_pipeline_line(&self, e: Error) -> Error {
        match e {
            Error::Input { msg, fix, .. } => {
                // The merged table's line says nothing here: find the override that fails alone.
                let alone = |k: &String, v: &toml::Value| {
                    let t = toml::Table::from_iter([(k.clone(), v.clone())]);
                    matches!(
                        PipelineConfig::from_toml("", &toml::to_string(&t).expect("table")),
                        Err(Error::Input { .. })
                    )
                };
                let key = self.pipeline.iter().flatten().find(|(k, v)| alone(k, v));
                let key = key.map_or(String::new(), |(k, _)| k.clone());
                Error::Field {
                    file: self.pipeline_at(&key),
                    field: if key.is_empty() {
                        "pipeline".into()
                    } else {
                        format!("pipeline.{key}")
                    },
                    msg,
                    fix,
                }
            }
            Error::Field { field, msg, fix, .. } => {
                let (name, written) = self.pipeline_field(&field);
                Error::Field {
                    file: self.pipeline_at(&field),
                    field: name,
                    // A field [pipeline] does not write has the value the scene derives; an
                    // override beside it is what conflicts.
                    msg: if written {
                        msg
                    } else {
                        format!("{msg} (`{field}` is not written in [pipeline]: its value is the one the scene derives, `gbump config --scene` prints it, and an override in [pipeline] conflicts with it)")
                    },
                    fix,
                }
            }
            e => e,
        }
    }

    /// Object `i`'s f64 normal map: its height field, differentiated, curved for a
    /// facet-baked cylinder.
    pub fn normal_map(&self, i: usize) -> Result<crate::bumpmap::NormalMap> {
        let o = &self.objects[i];
        // A height map that does not decode is named with the scene field that gave it.
        let hf = o.bump.source.generate(o.bump.size as usize, &self.base).map_err(|e| match e {
            Error::Image { path, msg } => Error::Image {
                path,
                msg: format!("{msg} (scene {}, field `objects[{i}].bump.source.path`)", self.file),
            },
            e => e,
        })?;
        let mut normals = crate::bumpmap::NormalMap::from_height(&hf, o.bump.method, o.bump.strength);
        if o.bump.cylinder_sides > 0 {
            normals.curve_for_cylinder(o.bump.cylinder_sides);
        }
        Ok(normals)
    }

    /// Check that `cfg` can render this scene.
    pub fn check_config(&self, cfg: &PipelineConfig, cfg_file: &str) -> Result<()> {
        // No file to edit when `cfg_file` names this run's default configuration or the one
        // another scene derives (`config::origin`), rather than a file.
        let no_file = cfg_file == crate::config::origin() && !crate::config::from_file();
        self.check_config_fields(cfg, cfg_file).map_err(|e| match no_file {
            true => {
                let text = e.to_string();
                let said: Vec<&str> = text.lines().filter(|l| !l.trim_start().starts_with("fix:")).collect();
                // The spelling `--scene` loads: a built-in scene's name, else its file.
                let me = crate::shell::quoted(if builtin::get(&self.name).is_some() { &self.name } else { &self.file });
                let both = if crate::config::from_scene() { "renders both scenes" } else { "renders it" };
                Error::Other(format!(
                    "{}\n  fix: give --scene {me} for this scene's own configuration, or --config a file that {both} (`gbump config --scene {me}` writes one to start from)",
                    said.join("\n"),
                ))
            }
            false => e,
        })
    }

    /// Say what `cfg` costs this scene without refusing it. Zero k fraction bits are a
    /// precision a sweep may well ask for: each k_i is then 0 or 1 on every triangle.
    pub fn warn_config(&self, cfg: &PipelineConfig, cfg_file: &str) {
        if cfg.k_frac_bits == 0 && !cfg.embm() {
            if let Some((i, why)) = needs::SceneNeeds::of(self).graded_k.first() {
                crate::warn::warn(format!(
                    "warning: {cfg_file}: k_frac_bits = 0 rounds each k_i to 0 or 1, but scene `{}` ({}) grades lights[{i}] ({why})\n  fix: set k_frac_bits = {} (the default) or more to keep the grades, or leave it at 0 to take the on/off error",
                    self.name,
                    self.file,
                    PipelineConfig::default().k_frac_bits
                ));
            }
        }
    }

    pub(crate) fn check_config_fields(&self, cfg: &PipelineConfig, cfg_file: &str) -> Result<()> {
        if cfg.embm() {
            // EMBM's lights, any number and colour, are in each object's maps, and it reads
            // no power table.
            return Ok(());
        }
        let n = self.bump_lights().count() as u32;
        if n > cfg.lights {
            return Err(Error::field(
                cfg_file,
                "lights",
                format!(
                    "scene `{}` ({}) has {n} bump lights but the pipeline has {} light slots",
                    self.name, self.file, cfg.lights
                ),
                format!("set lights = {n} or more"),
            ));
        }
        if let Some(fixed) = cfg.fixed_shininess() {
            if let Some(o) = self.objects.iter().find(|o| o.specular && o.shininess != cfg.shininess) {
                return Err(Error::field(
                    cfg_file,
                    fixed.field,
                    format!(
                        "scene `{}` ({}) has a specular object of shininess {} but the {}",
                        self.name, self.file, o.shininess, fixed.what
                    ),
                    format!(
                        "set shininess = {} (when every specular object shares it), or {}",
                        o.shininess, fixed.release
                    ),
                ));
            }
        }
        if cfg.white_lights {
            if let Some(l) = self.bump_lights().find(|l| l.colour != [1.0, 1.0, 1.0]) {
                return Err(Error::field(
                    cfg_file,
                    "white_lights",
                    format!(
                        "scene `{}` ({}) has a coloured bump light (colour {:?}) but white_lights = true drops the light-colour multiply",
                        self.name, self.file, l.colour
                    ),
                    "set white_lights = false (or make every bump light's colour [1, 1, 1])",
                ));
            }
        }
        Ok(())
    }
}
