//! Measuring a candidate configuration against the budget: golden images of the scenes against
//! their f64 Gouraud images (rendered once, since they do not depend on the widths), and the
//! pipeline against exact arithmetic on random stored inputs.

use super::budget::{Budget, Measured};
use crate::config::PipelineConfig;
use crate::error::Result;
use crate::measure::image_metrics::compare;
use crate::scene::Scene;
use std::collections::HashMap;

/// Random stimuli of the `exact<=` measure (and the corners of level 2).
pub const EXACT_SAMPLES: u64 = 20_000;

struct SceneRef {
    scene: Scene,
    w: u32,
    h: u32,
    gouraud: Vec<[f64; 3]>,
}

/// Measures candidates, each configuration once.
pub struct Evaluator {
    budget: Budget,
    scenes: Vec<SceneRef>,
    seen: HashMap<String, Measured>,
    /// Configurations measured (not served from `seen`).
    pub evaluations: usize,
}

impl Evaluator {
    /// Renders each scene's f64 Gouraud image at its own size under `base` (the algorithmic
    /// choices a search keeps: blend order, flat bypass, blends present).
    pub fn new(scenes: Vec<Scene>, base: &PipelineConfig, budget: Budget) -> Result<Evaluator> {
        let mut out = Vec::new();
        for scene in scenes {
            let [w, h] = scene.size;
            let gouraud = if budget.needs_images() {
                crate::render::render(&scene, base, w, h, false)?.gouraud
            } else {
                Vec::new()
            };
            out.push(SceneRef { scene, w, h, gouraud });
        }
        Ok(Evaluator {
            budget,
            scenes: out,
            seen: HashMap::new(),
            evaluations: 0,
        })
    }

    /// `cfg`'s measures: the budget's own, and the image measures whenever images are rendered.
    pub fn measure(&mut self, cfg: &PipelineConfig) -> Result<Measured> {
        let key = cfg.hash();
        if let Some(m) = self.seen.get(&key) {
            return Ok(*m);
        }
        self.evaluations += 1;
        let mut m = Measured {
            max_lsb: f64::NAN,
            psnr_db: f64::NAN,
            exact_lsb: f64::NAN,
        };
        if self.budget.needs_images() {
            let (mut worst, mut psnr) = (0.0f64, f64::INFINITY);
            for s in &self.scenes {
                let (golden, covered) = crate::render::golden(&s.scene, cfg, s.w, s.h)?;
                let e = compare(&golden, &s.gouraud, &covered, cfg.colour_max());
                worst = worst.max(e.max_lsb);
                psnr = psnr.min(e.psnr_db);
            }
            m.max_lsb = worst;
            m.psnr_db = psnr;
        } else {
            m.exact_lsb = crate::measure::unit_error::pipeline_exact_max(cfg, EXACT_SAMPLES, 1);
        }
        self.seen.insert(key, m);
        Ok(m)
    }

    pub fn budget(&self) -> Budget {
        self.budget
    }

    pub fn met(&mut self, cfg: &PipelineConfig) -> Result<bool> {
        let m = self.measure(cfg)?;
        Ok(self.budget.met(&m))
    }
}
