//! Stimulus and vector sets from the library's sources: the seeded random stream (record `k`
//! is record `k` of `gbump vectors --source random:N --seed SEED`), and whole sets of
//! `random:N`, `corners`, `scene:NAME` and `exhaustive:UNIT` with the model's responses, the
//! records `gbump vectors` writes.

use crate::arrays::{check_batch, records_out};
use gbump::capi::{GbumpConfig, GbumpStim};
use gbump::units::MemoryContents;
use gbump::vectors::sources::{corners, exhaustive, exhaustive_count, random_chunk, scene_groups, RANDOM_CHUNK};
use gbump::vectors::targets::{eval_top, eval_unit, top_record, unit_layout, unit_record, TopStim};
use gbump::vectors::Source;
use gbump::PipelineConfig;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;

/// A seeded random stimulus stream of top records (expected columns zero: `Config.eval`
/// fills them). Made by `Config.stimulus(seed)`.
#[pyclass(module = "gbump", name = "Stimulus")]
pub struct Stimulus {
    s: GbumpStim,
}

impl Stimulus {
    pub fn new(h: &GbumpConfig, seed: u64) -> Stimulus {
        Stimulus {
            s: GbumpStim::new(h, seed),
        }
    }
}

#[pymethods]
impl Stimulus {
    /// The next `n` records, uint32 shape (n, words).
    #[pyo3(signature = (n = crate::Int(1)), text_signature = "(self, n=1)")]
    fn next<'py>(&mut self, py: Python<'py>, n: crate::Int) -> PyResult<Bound<'py, PyAny>> {
        let n = crate::arg("Stimulus.next: n", n.0, 0, gbump::limits::MAX_BATCH_RECORDS, "MAX_BATCH_RECORDS")?;
        let w = self.s.layout.words32();
        gbump::capi::plan_memory(&format!("Stimulus.next: {n} records"), n * w as u64 * 4).map_err(crate::err)?;
        let mut out = Vec::with_capacity(n as usize * w);
        for _ in 0..n {
            out.extend(self.s.next_record().to_words32(w));
        }
        records_out(py, out, w, false)
    }

    /// Index of the record `next` gives next.
    #[getter]
    fn index(&self) -> u64 {
        self.s.index
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.s.seed
    }
}

/// Top records of `stims` evaluated with the power table of shininess `n`, as words.
fn top_words(cfg: &PipelineConfig, stims: &[TopStim], n: u32, env: Option<&gbump::model::env_map::EnvMaps>) -> Vec<u32> {
    let mem = MemoryContents::new(cfg, n).with_env(env);
    let l = gbump::vectors::targets::top_layout(cfg);
    let w = l.words32();
    stims
        .par_iter()
        .flat_map_iter(|s| top_record(cfg, &l, s, &eval_top(cfg, &mem.view(), s)).to_words32(w))
        .collect()
}

/// One set: {name, target, shininess, records, reasons}.
fn set<'py>(
    py: Python<'py>,
    name: &str,
    target: &str,
    n: u32,
    words: Vec<u32>,
    per: usize,
    reasons: Option<Vec<String>>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", name)?;
    d.set_item("target", target)?;
    d.set_item("shininess", n)?;
    d.set_item("records", records_out(py, words, per, false)?)?;
    d.set_item("reasons", reasons)?;
    Ok(d)
}

pub fn vectors<'py>(
    py: Python<'py>,
    h: &GbumpConfig,
    source: &str,
    seed: Option<u64>,
    shininess: Option<u32>,
    size: Option<(u32, u32)>,
) -> PyResult<Bound<'py, PyList>> {
    use gbump::vectors::choices::{refuse_ignored, refuse_unservable, Asked, Spelling};
    let cfg = &h.cfg;
    let spelling = Spelling::keywords(source);
    let src = Source::parse_as(source, &spelling.source).map_err(crate::err)?;
    let asked = Asked {
        seed: seed.is_some(),
        shininess,
        size: size.is_some(),
        level: false,
    };
    refuse_ignored(&src, &asked, &spelling).map_err(crate::err)?;
    let written = match &src {
        // The unit must exist before its shininess is judged (as `gbump vectors` does).
        Source::Exhaustive(u) => h.target(u).map_err(crate::err)?.name,
        _ => "top",
    };
    refuse_unservable(cfg, &[written], &asked, &spelling).map_err(crate::err)?;
    let seed = seed.unwrap_or(1);
    let n = shininess.unwrap_or(cfg.shininess);
    let top_w = gbump::vectors::targets::top_layout(cfg).words32();
    let out = PyList::empty(py);
    match &src {
        Source::Random(count) => {
            crate::arrays::check_records("random:N", *count, 1)?;
            let count = *count;
            let top = h.target("top").map_err(crate::err)?;
            // Each chunk's words, then all of them together.
            crate::arrays::plan(h, top, "vectors", count, 2 * crate::arrays::words_bytes(top))?;
            // A chunk's stimuli at a time: held all at once they took several times the records' memory.
            let words = crate::detach(py, || {
                let chunks: Vec<Vec<u32>> = (0..count.div_ceil(RANDOM_CHUNK))
                    .into_par_iter()
                    .map(|c| top_words(cfg, &random_chunk(cfg, seed, c, count), n, None))
                    .collect();
                chunks.concat()
            });
            out.append(set(py, &src.stem(), "top", n, words, top_w, None)?)?;
        }
        Source::Corners(level) => {
            let (reasons, stims): (Vec<String>, Vec<TopStim>) = corners(cfg, *level).into_iter().unzip();
            let words = crate::detach(py, || top_words(cfg, &stims, n, None));
            out.append(set(py, &src.stem(), "top", n, words, top_w, Some(reasons))?)?;
        }
        Source::Scene(name) => {
            let groups = crate::detach(py, || scene_groups(cfg, name, size)).map_err(crate::err)?;
            for g in groups {
                check_batch("scene fragments", g.stims.len() as u64)?;
                let words = crate::detach(py, || top_words(cfg, &g.stims, g.shininess, g.env.as_ref()));
                let d = set(py, &g.stem, "top", g.shininess, words, top_w, None)?;
                // Each record's pixel, as the dump's `_pixels.txt` gives it: uint32 (N, 2), x y.
                let px: Vec<u32> = g.pixels.iter().flat_map(|(px, _)| px).flatten().copied().collect();
                d.set_item("pixels", records_out(py, px, 2, false)?)?;
                d.set_item("image_size", g.pixels.as_ref().map(|p| p.1))?;
                if let Some(e) = &g.env {
                    // EMBM: the object's maps, as RAM words for the env_*_wdata ports.
                    for (which, map) in [("diffuse", &e.diffuse), ("specular", &e.specular)] {
                        let rom = gbump::rtlgen::rom::env_map_rom(cfg, map, which, "a scene object's lighting");
                        d.set_item(format!("env_{which}"), rom.words)?;
                    }
                }
                out.append(d)?;
            }
        }
        Source::Exhaustive(unit) => {
            // The target must exist in this configuration (the handle's error lists those that do).
            let t = h.target(unit).map_err(crate::err)?;
            exhaustive_count(cfg, unit).map_err(crate::err)?;
            let l = unit_layout(cfg, t.name);
            let w = l.words32();
            let words = crate::detach(py, || -> gbump::Result<Vec<u32>> {
                let mem = MemoryContents::new(cfg, n);
                Ok(exhaustive(cfg, unit)?
                    .iter()
                    .flat_map(|s| unit_record(&l, s, &eval_unit(cfg, &mem.view(), s)).to_words32(w))
                    .collect())
            });
            let name = if shininess.is_some() {
                format!("{}_n{n}", src.stem())
            } else {
                src.stem()
            };
            out.append(set(py, &name, t.name, n, words.map_err(crate::err)?, w, None)?)?;
        }
    }
    Ok(out)
}
