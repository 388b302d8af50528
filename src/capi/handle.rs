//! The two objects behind the C handles: a configuration with its power table and record
//! layouts, and a random stimulus stream. Their methods are plain Rust (tested as such); the
//! `extern "C"` wrappers in `ffi.rs` only check pointers and catch panics.

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::model::PowerTable;
use crate::vectors::layout::{Layout, Record};
use crate::vectors::sources::{chunk_rng, RandomTriangles, RANDOM_CHUNK};
use crate::vectors::targets::{eval_top, top_layout, top_record, top_stim, unit_layout, unit_stim};
use crate::vectors::writer::unit_present;
use std::ffi::CString;

/// Bytes a batch may hold without being planned against the machine's memory.
pub const PLAN_FREE_BYTES: u64 = 64 << 20;

/// Refuse a batch that would hold `bytes` and not fit in memory (`limits::check_memory`): a
/// failed allocation aborts the caller's whole process. A batch under [`PLAN_FREE_BYTES`] is
/// not planned (the per-record calls of a scoreboard would each read /proc).
pub fn plan_memory(what: &str, bytes: u64) -> Result<()> {
    if bytes < PLAN_FREE_BYTES {
        return Ok(());
    }
    crate::limits::check_memory(what, bytes, "pass fewer records per call (split the batch), or free memory")
}

/// One evaluation target: `top` or a unit the configuration has.
pub struct Target {
    pub name: &'static str,
    /// The name, kept alive for `gbump_target_name`.
    pub c_name: CString,
    pub layout: Layout,
    /// Column names, kept alive for `gbump_column_name`.
    pub column_names: Vec<CString>,
}

/// A configuration handle (`GbumpConfig *` in C, `chandle` in SystemVerilog).
pub struct GbumpConfig {
    pub cfg: PipelineConfig,
    /// The power table (for the current shininess) and the palette the top powers up with.
    pub mem: crate::units::MemoryContents,
    /// The fast model of `cfg` and `mem` (rebuilt with the table), for batches of top records.
    pub fast: crate::model::FastModel,
    pub targets: Vec<Target>,
    pub hash: CString,
    pub module: CString,
    pub toml: CString,
    /// The top's ports: name, width, whether an output.
    pub ports: Vec<(CString, u32, bool)>,
    /// The warnings reading the configuration gave (a renamed field under its old name), one
    /// per line; empty when there were none. The library never prints them.
    pub warnings: CString,
}

fn cstring(s: String) -> CString {
    CString::new(s).expect("generated names hold no NUL")
}

impl GbumpConfig {
    /// A handle for `cfg` (already validated), its power table at the configured shininess.
    pub fn new(cfg: PipelineConfig) -> Result<GbumpConfig> {
        if cfg.palette {
            return Err(Error::Other(
                "the C library does not take palette configurations yet (its records and stimulus stream assume stored normals)\n  fix: run palette configurations with `gbump regress`, or set palette = false".into(),
            ));
        }
        let mut targets = vec![target("top", top_layout(&cfg))];
        for u in crate::units::UNITS.iter().filter(|u| unit_present(&cfg, u.name())) {
            targets.push(target(u.name(), unit_layout(&cfg, u.name())));
        }
        // The DPI-C package's record vectors are MAX_RECORD_BITS wide: a wider record would
        // overrun a SystemVerilog caller's buffer.
        if let Some(t) = targets.iter().find(|t| t.layout.bits > super::MAX_RECORD_BITS) {
            return Err(Error::Other(format!(
                "the {} record is {} bits, wider than the DPI-C package's {} (MAX_RECORD_BITS)\n  fix: raise MAX_RECORD_BITS in src/capi/mod.rs and regenerate the package",
                t.name,
                t.layout.bits,
                super::MAX_RECORD_BITS
            )));
        }
        let mem = crate::units::MemoryContents::new(&cfg, cfg.shininess);
        Ok(GbumpConfig {
            fast: crate::model::FastModel::of(&cfg, &mem.view()),
            mem,
            targets,
            hash: cstring(cfg.hash()),
            module: cstring(crate::rtlgen::units_v::module_name(&cfg, "gbump_pipeline")),
            toml: cstring(cfg.to_toml()),
            ports: crate::rtlgen::top::top_ports(&cfg)
                .into_iter()
                .map(|(n, d, w)| (cstring(n), w, d == "output"))
                .collect(),
            cfg,
            warnings: CString::default(),
        })
    }

    /// A handle for the configuration `read` returns, the warnings it gave kept in the
    /// handle rather than printed.
    pub fn read(read: impl FnOnce() -> Result<PipelineConfig>) -> Result<GbumpConfig> {
        let (cfg, warnings) = crate::warn::capture(read);
        let mut h = GbumpConfig::new(cfg?)?;
        h.warnings = cstring(warnings.join("\n").replace('\0', " "));
        Ok(h)
    }

    /// The target called `name`, or an error listing the ones there are.
    pub fn target(&self, name: &str) -> Result<&Target> {
        // Quoted in the message below: a control character would break its line.
        super::guard::one_line_arg(name, "target", "pass the name alone, as gbump_target_name gives it")?;
        self.targets.iter().find(|t| t.name == name).ok_or_else(|| {
            let names: Vec<&str> = self.targets.iter().map(|t| t.name).collect();
            Error::Other(format!(
                "target `{name}`: not in this configuration\n  fix: one of {}",
                names.join(", ")
            ))
        })
    }

    /// Reload the power table for shininess `n` (what the top's load port is given).
    pub fn set_shininess(&mut self, n: i64) -> Result<()> {
        let max = crate::limits::MAX_SHININESS as i64;
        if !(0..=max).contains(&n) {
            return Err(Error::Other(format!(
                "shininess {n}: out of range\n  fix: use 0..={max} (MAX_SHININESS)"
            )));
        }
        // The top's table is a ROM: its load port is tied off, so no other table can be loaded.
        if let Some(fixed) = self.cfg.fixed_shininess().filter(|_| n != self.cfg.shininess as i64) {
            return Err(Error::Other(format!(
                "shininess {n}: the configuration's {}\n  fix: keep shininess {}, or use a configuration with {}",
                fixed.what, self.cfg.shininess, fixed.release
            )));
        }
        self.mem.table = PowerTable::build(&self.cfg, n as u32);
        self.fast = crate::model::FastModel::of(&self.cfg, &self.mem.view());
        Ok(())
    }

    /// [`plan_memory`] for `count` records of `t` that hold `per_record` bytes each while
    /// the call runs.
    pub fn plan_batch(&self, t: &Target, count: u64, per_record: u64, what: &str) -> Result<()> {
        plan_memory(&format!("{what}: {count} `{}` records", t.name), count.saturating_mul(per_record))
    }

    /// Load environment map `which` ("diffuse" or "specular") from its RAM words, as the top's
    /// `env_<which>_we`/`_wdata` port would (`model::env_map::word_layout`): an EMBM scene
    /// set's objects each light with their own maps (its manifest's `env_maps`, the Python
    /// module's `env_diffuse`/`env_specular`), the power-up maps being the random and corner
    /// sets'. Refused, the map unchanged, where the configuration has none or a word does not
    /// fit.
    pub fn set_env_map(&mut self, which: &str, words: &[u64]) -> Result<()> {
        self.env_map_named(which)?;
        let texels = crate::model::env_map::texels_of_words(&self.cfg, words, &format!("env map `{which}`"))?;
        for (i, t) in texels.iter().enumerate() {
            self.fast.set_env_texel(which, i, *t);
        }
        *self.mem.env.named_mut(which) = texels;
        Ok(())
    }

    /// Write texel `index` of environment map `which`, as one write of the top's
    /// `env_<which>_we`/`_waddr`/`_wdata` port: `word` is the texel's RAM word.
    pub fn set_env_texel(&mut self, which: &str, index: i64, word: u64) -> Result<()> {
        self.env_map_named(which)?;
        let n = self.mem.env.named(which).len();
        let i = usize::try_from(index).ok().filter(|&i| i < n).ok_or_else(|| {
            Error::Other(format!(
                "env map `{which}`: texel {index} is outside the map's 0..={}\n  fix: pass an index in 0..={} (texel (x, y) at y*{} + x)",
                n - 1,
                n - 1,
                self.cfg.env_map_side()
            ))
        })?;
        let texel = crate::model::env_map::texel_of_word(&self.cfg, word, &format!("env map `{which}`: texel {index}'s word"))?;
        self.mem.env.named_mut(which)[i] = texel;
        self.fast.set_env_texel(which, i, texel);
        Ok(())
    }

    /// Refuse `which` unless it names a map the top has a port for.
    pub fn env_map_named(&self, which: &str) -> Result<()> {
        if !self.cfg.embm() {
            return Err(Error::Other(
                "env map: this configuration has none (env_map_bits = 0: it is not EMBM)\n  fix: load maps into an EMBM configuration (env_map_bits > 0)".into(),
            ));
        }
        super::guard::one_line_arg(which, "env map", "\"diffuse\" or \"specular\"")?;
        // The maps the top has a port for: one per blend the configuration has.
        let has = crate::rtlgen::top::env_map_names(&self.cfg);
        if !has.contains(&which) {
            let names: Vec<String> = has.iter().map(|h| format!("\"{h}\"")).collect();
            return Err(Error::Other(format!(
                "env map `{which}`: this configuration has no such map\n  fix: {} (a map per blend the configuration has)",
                names.join(" or ")
            )));
        }
        Ok(())
    }

    /// Evaluate one record of `t`: the stimulus columns of `input` are read, and the whole
    /// record (stimulus and the model's expected columns) is returned, exactly as the vector
    /// files hold it.
    pub fn eval(&self, t: &Target, input: &Record) -> Result<Record> {
        if t.name == "top" {
            let s = top_stim(&self.cfg, &t.layout, input);
            Ok(top_record(&self.cfg, &t.layout, &s, &eval_top(&self.cfg, &self.mem.view(), &s)))
        } else {
            let s = unit_stim(&t.layout, t.name, input);
            crate::vectors::targets::checked_unit_record(&self.cfg, &self.mem.view(), &t.layout, &s)
        }
    }
}

impl GbumpConfig {
    /// Evaluate back-to-back records of `t` (`t.layout.words32()` words each) from `input`
    /// into `out` (the same length), on the library's thread pool when there are many.
    pub fn eval_words(&self, t: &Target, input: &[u32], out: &mut [u32]) -> Result<()> {
        let n = t.layout.words32();
        if input.len() != out.len() || !input.len().is_multiple_of(n) {
            return Err(Error::Other(format!(
                "{} and {} words given for {} records of {n} words\n  fix: pass whole records, as many out as in",
                input.len(),
                out.len(),
                t.name
            )));
        }
        if t.name == "top" {
            return self.eval_top_words(t, input, out);
        }
        // A call of one record (`gbump_eval`) is not told which record failed.
        let many = input.len() > n;
        let eval = |(k, (i, o)): (usize, (&[u32], &mut [u32]))| -> Result<()> {
            let r = self.eval(t, &Record::from_words32(i)).map_err(|e| match many {
                true => Error::Other(format!("record {k}: {e}")),
                false => e,
            })?;
            o.copy_from_slice(&r.to_words32(n));
            Ok(())
        };
        each_chunk(input, out, n, input.len() / n >= super::PARALLEL_RECORDS, eval)
    }
}

/// `f` over `input` and `out` a chunk of `words` at a time (numbered from 0), on every core
/// when `parallel`; on failure the error of the lowest chunk that fails, whichever thread
/// met one first, so a batch names the same record every run (what `out` holds then is
/// unspecified).
fn each_chunk<F>(input: &[u32], out: &mut [u32], words: usize, parallel: bool, f: F) -> Result<()>
where
    F: Fn((usize, (&[u32], &mut [u32]))) -> Result<()> + Sync,
{
    use rayon::prelude::*;
    let failed = if parallel {
        crate::thread_pool::install(|| {
            input
                .par_chunks(words)
                .zip(out.par_chunks_mut(words))
                .enumerate()
                .filter_map(|(k, io)| f((k, io)).err().map(|e| (k, e)))
                .min_by_key(|(k, _)| *k)
        })
    } else {
        input
            .chunks(words)
            .zip(out.chunks_mut(words))
            .enumerate()
            .find_map(|(k, io)| f((k, io)).err().map(|e| (k, e)))
    };
    failed.map_or(Ok(()), |(_, e)| Err(e))
}

impl GbumpConfig {
    /// [`eval_words`](Self::eval_words) of the top: the fast model, a batch at a time, under
    /// the readable model's check (`vectors::top_records`, record indices counted from the
    /// start of this call).
    fn eval_top_words(&self, t: &Target, input: &[u32], out: &mut [u32]) -> Result<()> {
        use crate::vectors::targets::TopEncoder;
        use crate::vectors::top_records::{TopRecords, BATCH};
        let n = t.layout.words32();
        let maker = TopRecords::with(&self.cfg, self.mem.view(), std::borrow::Cow::Borrowed(&self.fast));
        let run = |(b, (i, o)): (usize, (&[u32], &mut [u32]))| -> Result<()> {
            let stims: Vec<_> = i
                .chunks(n)
                .map(|w| top_stim(&self.cfg, &t.layout, &Record::from_words32(w)))
                .collect();
            let mut colours = vec![[0u32; 3]; stims.len()];
            maker.colours((b * BATCH) as u64, &stims, &mut colours)?;
            let enc = TopEncoder::new(&self.cfg, &t.layout);
            let mut r = Record::new(&t.layout);
            for ((s, c), o) in stims.iter().zip(&colours).zip(o.chunks_mut(n)) {
                enc.fill_colour(s, *c, &mut r);
                o.copy_from_slice(&r.to_words32(n));
            }
            Ok(())
        };
        each_chunk(input, out, n * BATCH, input.len() / n >= super::PARALLEL_RECORDS, run)
    }
}

fn target(name: &'static str, layout: Layout) -> Target {
    Target {
        name,
        c_name: cstring(name.to_string()),
        column_names: layout.columns.iter().map(|c| cstring(c.name.clone())).collect(),
        layout,
    }
}

/// The random stimulus stream of `gbump vectors --source random:N --seed S`, record by record
/// (`GbumpStim *` in C, `chandle` in SystemVerilog).
pub struct GbumpStim {
    pub cfg: PipelineConfig,
    pub layout: Layout,
    pub seed: u64,
    /// Index of the next record.
    pub index: u64,
    tris: RandomTriangles,
}

impl GbumpStim {
    pub fn new(h: &GbumpConfig, seed: u64) -> GbumpStim {
        GbumpStim {
            cfg: h.cfg.clone(),
            layout: top_layout(&h.cfg),
            seed,
            index: 0,
            tris: RandomTriangles::new(&h.cfg, chunk_rng(seed, 0)),
        }
    }

    /// The next record's stimulus (expected columns zero): record `index` of `random:N`.
    pub fn next_record(&mut self) -> Record {
        if self.index > 0 && self.index.is_multiple_of(RANDOM_CHUNK) {
            self.tris = RandomTriangles::new(&self.cfg, chunk_rng(self.seed, self.index / RANDOM_CHUNK));
        }
        self.index += 1;
        let s = self.tris.next(&self.cfg);
        // A default trace has colour 0: the expected column stays zero.
        top_record(&self.cfg, &self.layout, &s, &Default::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{LightMode, PowerUnitKind};

    /// A batch with several records outside the unit's domain names the lowest of them, on
    /// the parallel path as on the serial one, every time.
    #[test]
    fn a_failing_batch_names_its_lowest_bad_record() {
        let h = GbumpConfig::new(PipelineConfig::default()).unwrap();
        let t = h.target("power_unit").unwrap();
        let n = t.layout.words32();
        let x = t.layout.column("x");
        for count in [300usize, 1 << 16] {
            let bad = [100, count / 2, count - 10];
            let mut input = vec![0u32; count * n];
            for &k in &bad {
                let mut r = Record::new(&t.layout);
                r.set_lane(x, 0, (1 << PipelineConfig::default().dot_frac_bits) + 1);
                input[k * n..(k + 1) * n].copy_from_slice(&r.to_words32(n));
            }
            for _ in 0..3 {
                let mut out = vec![0u32; count * n];
                let e = h.eval_words(t, &input, &mut out).unwrap_err().to_string();
                assert!(e.starts_with("record 100:"), "{count} records: {e}");
            }
        }
    }

    /// The widest configurations the limits allow fit the DPI-C package's records.
    #[test]
    fn every_valid_configuration_fits_the_package_records() {
        let (_, lights) = crate::config::limit("lights");
        for mode in [LightMode::Serial, LightMode::Parallel] {
            let cfg = PipelineConfig {
                normal_bits: crate::config::limit("normal_bits").1,
                lh_bits: crate::config::limit("lh_bits").1,
                dot_frac_bits: crate::config::limit("dot_frac_bits").1,
                power_frac_bits: crate::config::limit("power_frac_bits").1,
                colour_bits: crate::config::limit("colour_bits").1,
                colour_guard_bits: crate::config::limit("colour_guard_bits").1,
                k_frac_bits: crate::config::limit("k_frac_bits").1,
                power_unit: PowerUnitKind::Table,
                lights,
                light_mode: mode,
                ..Default::default()
            };
            cfg.validate("widest").unwrap();
            let h = GbumpConfig::new(cfg).unwrap();
            let widest = h.targets.iter().map(|t| t.layout.bits).max().unwrap();
            assert!(widest > super::super::MAX_RECORD_BITS / 2, "{widest}: MAX_RECORD_BITS could halve");
        }
    }
}
