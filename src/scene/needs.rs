//! What a scene needs of the pipeline, and why: the facts `derive_config` sizes the hardware
//! from and `gbump config --scene` prints above the configuration, so a designer sees which
//! part of the scene asks for which part of the hardware.

use super::{LightKind, Scene};
use crate::bumpmap::StoredMap;
use crate::config::PipelineConfig;
use crate::error::Result;
use std::collections::{BTreeSet, HashSet};

/// A scene's demands on the pipeline.
#[derive(Clone, Debug)]
pub struct SceneNeeds {
    /// Bump lights in slot order: (index in the scene's `lights`, what it is).
    pub bump_lights: Vec<(usize, String)>,
    /// Lights carried by the Gouraud colour (`bump = false`).
    pub gouraud_lights: usize,
    /// Objects (index) that take the diffuse and the specular blend.
    pub diffuse_objects: Vec<usize>,
    pub specular_objects: Vec<usize>,
    /// Shininess of every specular object.
    pub shininess: BTreeSet<u32>,
    /// Every bump light's k_i is 0 or 1 on every triangle: k = 0 or 1 and no spot cone that
    /// grades it (a spot's factor is cos^e inside the cut-off, so only e = 0 keeps it 0 or 1).
    pub k_on_off: bool,
    /// Bump lights whose k_i takes other values, and why.
    pub graded_k: Vec<(usize, String)>,
    /// Every bump light is white (Lc = 1, 1, 1).
    pub white_lights: bool,
}

/// Distinct stored normals of each object's bump map in `cfg`'s normal format (what a palette
/// must hold to be exact).
pub fn distinct_normals(scene: &Scene, cfg: &PipelineConfig) -> Result<Vec<usize>> {
    let plain = PipelineConfig {
        palette: false,
        ..cfg.clone()
    };
    let mut out = Vec::new();
    for i in 0..scene.objects.len() {
        let normals = scene.normal_map(i)?;
        out.push(match StoredMap::store(&plain, &normals) {
            StoredMap::Rgb { codes, .. } => codes.into_iter().collect::<HashSet<_>>().len(),
            StoredMap::Palettised { .. } => unreachable!("stored without a palette"),
        });
    }
    Ok(out)
}

impl SceneNeeds {
    /// The scene's needs.
    pub fn of(scene: &Scene) -> SceneNeeds {
        let bump: Vec<(usize, &super::Light)> = scene.lights.iter().enumerate().filter(|(_, l)| l.bump).collect();
        let graded_k: Vec<(usize, String)> = bump
            .iter()
            .filter_map(|(i, l)| {
                if l.k != 0.0 && l.k != 1.0 {
                    Some((*i, format!("k = {}", l.k)))
                } else if l.kind == LightKind::Spot && l.exponent != 0.0 && l.k != 0.0 {
                    Some((*i, format!("spot exponent {}", l.exponent)))
                } else {
                    None
                }
            })
            .collect();
        SceneNeeds {
            bump_lights: bump.iter().map(|(i, l)| (*i, format!("{:?}", l.kind).to_lowercase())).collect(),
            gouraud_lights: scene.lights.len() - bump.len(),
            diffuse_objects: (0..scene.objects.len()).filter(|&i| scene.objects[i].diffuse).collect(),
            specular_objects: (0..scene.objects.len()).filter(|&i| scene.objects[i].specular).collect(),
            shininess: scene.objects.iter().filter(|o| o.specular).map(|o| o.shininess).collect(),
            k_on_off: graded_k.is_empty(),
            graded_k,
            white_lights: bump.iter().all(|(_, l)| l.colour == [1.0, 1.0, 1.0]),
        }
    }

    /// The configuration these needs size (the scene's `[pipeline]` overrides come after).
    pub fn sized(&self) -> PipelineConfig {
        let d = PipelineConfig::default();
        PipelineConfig {
            lights: self.bump_lights.len().max(1) as u32,
            specular: !self.specular_objects.is_empty(),
            diffuse: !self.diffuse_objects.is_empty(),
            shininess: self.shininess.iter().next().copied().unwrap_or(d.shininess),
            // k_i of 0 or 1 is exact at 0 fraction bits: the blends lose their f·k multiplier
            // and the images do not change (f·k·Lc is exact before its one rounding).
            k_frac_bits: if self.k_on_off { 0 } else { d.k_frac_bits },
            // Lc = 1 on every channel of every bump light: the multiply by it is x1.
            white_lights: self.white_lights && !self.bump_lights.is_empty(),
            ..d
        }
    }

    /// Why each derived field has its value, as TOML comment lines; `cfg` is the configuration
    /// the normals are counted in.
    pub fn explain(&self, scene: &Scene, cfg: &PipelineConfig) -> Result<String> {
        let list = |v: &[usize]| v.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(", ");
        let mut s = format!("# What scene `{}` ({}) needs:\n", scene.name, scene.file);
        let slots: Vec<String> = self.bump_lights.iter().map(|(i, k)| format!("light {i} ({k})")).collect();
        s += &format!(
            "# lights = {}: {} bump light(s){}{}\n",
            self.bump_lights.len().max(1),
            self.bump_lights.len(),
            if slots.is_empty() {
                String::new()
            } else {
                format!(": {}", slots.join(", "))
            },
            if self.gouraud_lights > 0 {
                format!("; {} more carried by the Gouraud colour (bump = false)", self.gouraud_lights)
            } else {
                String::new()
            }
        );
        s += &format!(
            "# diffuse = {}: objects [{}] use the diffuse blend\n",
            !self.diffuse_objects.is_empty(),
            list(&self.diffuse_objects)
        );
        s += &format!(
            "# specular = {}: objects [{}] use the specular blend\n",
            !self.specular_objects.is_empty(),
            list(&self.specular_objects)
        );
        if !self.shininess.is_empty() {
            let set: Vec<String> = self.shininess.iter().map(|n| n.to_string()).collect();
            s += &format!(
                "# shininess = {}: the set {{{}}}{}\n",
                self.shininess.iter().next().unwrap(),
                set.join(", "),
                if self.shininess.len() == 1 {
                    "; one shininess, so the table need never be reloaded (power_rom = true makes it a ROM; `gbump fit` chooses that)"
                } else {
                    "; the power table is reloaded between objects"
                }
            );
        }
        if self.k_on_off {
            s += "# k_frac_bits = 0: every bump light's k_i is 0 or 1 on every triangle, exact without fraction bits (no f·k multiplier; the paper's sample implementation)\n";
        } else {
            let why: Vec<String> = self.graded_k.iter().map(|(i, w)| format!("light {i}: {w}")).collect();
            s += &format!(
                "# k_frac_bits = {}: k_i takes values between 0 and 1 ({})\n",
                PipelineConfig::default().k_frac_bits,
                why.join("; ")
            );
        }
        s += if self.white_lights && !self.bump_lights.is_empty() {
            "# white_lights = true: every bump light is white (Lc = 1, 1, 1): no Lc multiply in the blends, no Lc in the banks\n"
        } else if self.bump_lights.is_empty() {
            "# white_lights = false: no bump light\n"
        } else {
            "# white_lights = false: coloured bump lights (the blends multiply by Lc)\n"
        };
        for (i, n) in distinct_normals(scene, cfg)?.iter().enumerate() {
            s += &format!(
                "# object {i}: {n} distinct stored normals at normal_bits = {}{}\n",
                cfg.normal_bits,
                if *n <= 256 {
                    "; palette = true holds them exactly (8-bit indices, paper §6)"
                } else {
                    "; palette = true would approximate them by 256"
                }
            );
        }
        let filtered: Vec<String> = scene
            .objects
            .iter()
            .enumerate()
            .filter(|(_, o)| o.bump.filter == crate::bumpmap::sample::Filter::Bilinear)
            .map(|(i, _)| i.to_string())
            .collect();
        if !filtered.is_empty() && !cfg.renormalise_bump {
            s += &format!(
                "# renormalise_bump = false: objects [{}] filter their maps bilinearly, which shortens the normal between texels that disagree; renormalise_bump = true renormalises it in the pipeline (a normalise_b unit; `gbump claim map-filter` measures what it buys)\n",
                filtered.join(", ")
            );
        }
        Ok(s)
    }
}
