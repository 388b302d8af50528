//! `gbump.Config`: one pipeline configuration with its model (the C ABI's handle, so Python,
//! C and DPI-C evaluate through the same object): queries, record layouts, evaluation of
//! packed and per-field records, ROM contents and the interface description.

use crate::arrays::{records_in, records_out};
use gbump::capi::GbumpConfig;
use gbump::PipelineConfig;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;

/// A pipeline configuration and its bit-accurate model.
///
/// `Config()` is the built-in default; `Config(toml_text, name)` parses TOML text (`name`
/// labels it in errors); `Config.load(path)` reads a TOML file. Palette configurations are
/// refused, as by the C library.
#[pyclass(module = "gbump", name = "Config")]
pub struct Config {
    pub h: GbumpConfig,
}

impl Config {
    pub fn cfg(&self) -> &PipelineConfig {
        &self.h.cfg
    }
}

/// The handle of the configuration `f` reads; its warnings (an old field name) are raised as
/// Python `DeprecationWarning`s, which the caller's warning filters govern, not printed.
fn read(py: Python<'_>, f: impl FnOnce() -> gbump::Result<PipelineConfig>) -> PyResult<Config> {
    let h = GbumpConfig::read(f).map_err(crate::err)?;
    let text = h.warnings.to_str().unwrap_or_default();
    if !text.is_empty() {
        let category = py.get_type::<pyo3::exceptions::PyDeprecationWarning>();
        PyErr::warn(py, &category, &h.warnings, 1)?;
    }
    Ok(Config { h })
}

/// A JSON text as Python objects (dicts, lists, numbers, strings).
fn json_to_py<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// `slf` for a change of its model (a table or map load), or a `GbumpError` when another
/// thread's call holds it: Python's own `RuntimeError: Already borrowed` names neither.
fn exclusive<'py>(slf: &Bound<'py, Config>, what: &str) -> PyResult<PyRefMut<'py, Config>> {
    slf.try_borrow_mut().map_err(|_| {
        crate::fail(format!(
            "{what}: this Config is in use by another thread (an eval, vectors or other call on it is running)\n  fix: change it when no call on it runs, or give each thread a Config of its own"
        ))
    })
}

#[pymethods]
impl Config {
    #[new]
    #[pyo3(signature = (toml = None, name = "<toml text>"))]
    fn new(py: Python<'_>, toml: Option<&str>, name: &str) -> PyResult<Self> {
        read(py, || match toml {
            None => Ok(PipelineConfig::default()),
            // Quoted in messages: a line break in it would start a line of its own.
            Some(t) => PipelineConfig::from_toml(&gbump::error::one_line(name), t),
        })
    }

    /// The configuration in TOML file `path`.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        read(py, || PipelineConfig::load(&path))
    }

    /// The configuration scene `name` (built-in or a path) derives, as `--scene` picks it.
    #[staticmethod]
    fn from_scene(name: &str) -> PyResult<Self> {
        let cfg = gbump::scene::pick_config(None, Some(name)).map_err(crate::err)?;
        Ok(Config {
            h: GbumpConfig::new(cfg).map_err(crate::err)?,
        })
    }

    /// The configuration of the RTL whose interface JSON (`<top>.json`, written by `gbump
    /// rtl`) is at `path`; refused when its stated hash is not this library's hash of its
    /// fields (RTL of another gbump version).
    #[staticmethod]
    fn from_interface(path: PathBuf) -> PyResult<Self> {
        let p = path.display();
        let text =
            gbump::limits::read_text_as(&path, "an interface JSON", "pass the <top>.json that gbump rtl writes").map_err(crate::err)?;
        let v: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| crate::fail(format!("{p}: not JSON ({e})\n  fix: pass the <top>.json that gbump rtl writes")))?;
        let (Some(c), Some(hash)) = (v.get("config"), v.get("config_hash").and_then(|h| h.as_str())) else {
            return Err(crate::fail(format!(
                "{p}: no `config` and `config_hash`\n  fix: pass the <top>.json that gbump rtl writes"
            )));
        };
        let cfg: PipelineConfig = serde_json::from_value(c.clone()).map_err(|e| {
            crate::fail(format!(
                "{p}: field `config`: {e}\n  fix: regenerate it with this gbump (gbump rtl)"
            ))
        })?;
        cfg.validate(&p.to_string()).map_err(crate::err)?;
        if cfg.hash() != hash {
            return Err(crate::fail(format!(
                "{p}: config_hash {hash}, but this module hashes its config to {}\n  fix: regenerate the RTL with the gbump this module was built from (gbump rtl)",
                cfg.hash()
            )));
        }
        Ok(Config {
            h: GbumpConfig::new(cfg).map_err(crate::err)?,
        })
    }

    /// The 16-hex-digit configuration hash every generated file states.
    #[getter]
    fn hash(&self) -> String {
        self.cfg().hash()
    }

    /// Canonical TOML of the configuration (the input of the hash): every field, except that
    /// a field added after the first release is left out at its default ("none", 0 or
    /// false), so hashes made before it existed stay (`gbump config` prints those fields
    /// commented out, and the C header's `gbump_config_toml` names them).
    #[getter]
    fn toml(&self) -> String {
        self.cfg().to_toml()
    }

    /// The fields of `toml`, as a dict (the fields left out at their defaults are left out here
    /// too).
    fn as_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &serde_json::to_string(self.cfg()).expect("config serialises"))
    }

    /// The generated top module's name (`gbump_pipeline_<hash8>`).
    #[getter]
    fn top(&self) -> String {
        self.h.module.to_string_lossy().into_owned()
    }

    #[getter]
    fn lights(&self) -> u32 {
        self.cfg().lights
    }

    /// Rising edges from a fragment's accepting edge to the edge its out_valid is sampled high.
    #[getter]
    fn latency(&self) -> u32 {
        gbump::rtlgen::top::latency(self.cfg())
    }

    /// Rising edges between two accepts of fragments offered back to back.
    #[getter]
    fn initiation_interval(&self) -> u32 {
        self.cfg().initiation_interval()
    }

    /// Rising edges with rst high that bring the top to idle.
    #[getter]
    fn reset_cycles(&self) -> u32 {
        gbump::rtlgen::top::RESET_CYCLES
    }

    /// Clock cycles from input to output of unit `unit`.
    fn unit_latency(&self, unit: &str) -> PyResult<u32> {
        let t = self.h.target(unit).map_err(crate::err)?;
        let u = gbump::units::unit(t.name).ok_or_else(|| crate::fail("`top`: use Config.latency\n  fix: pass a unit name".into()))?;
        Ok(u.latency(self.cfg()))
    }

    /// The derived fixed-point formats: name -> {format, width, frac, signed}.
    #[getter]
    fn formats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, f) in self.cfg().formats() {
            let e = PyDict::new(py);
            e.set_item("format", f.name())?;
            e.set_item("width", f.width)?;
            e.set_item("frac", f.frac)?;
            e.set_item("signed", f.signed)?;
            d.set_item(name, e)?;
        }
        Ok(d)
    }

    /// Shininess of the model's power table now; setting it reloads the table, as the top's
    /// load port would (`eval` uses it). The configuration's own shininess, which `vectors`
    /// and `rom` default to as the command line does, stays as it was.
    #[getter]
    fn shininess(&self) -> u32 {
        self.h.mem.table.n
    }

    #[setter]
    fn set_shininess(slf: &Bound<'_, Self>, n: crate::Int) -> PyResult<()> {
        let n = i64::try_from(n.0).map_err(|_| {
            crate::fail(format!(
                "shininess {}: does not fit 64 bits\n  fix: use 0..={}",
                n.0,
                gbump::limits::MAX_SHININESS
            ))
        })?;
        exclusive(slf, "shininess")?.h.set_shininess(n).map_err(crate::err)
    }

    /// Load environment map `which` ("diffuse" or "specular") of an EMBM configuration from
    /// its RAM words (ints), as the top's `env_<which>_we`/`_wdata` port would; `eval` then
    /// lights with it. An EMBM scene set's objects each light with their own maps, which
    /// `vectors` gives as the set's `env_diffuse` and `env_specular`: load both before
    /// evaluating that set's records. The model powers up with the maps random and corner
    /// sets use. The words are the map's n x n texels (n = 2^env_map_bits), texel (x, y) at
    /// word y*n + x, {B, G, R} of colour_bits each, R lowest; another count, a word wider than
    /// a texel or a configuration without maps is refused, and the map is then unchanged.
    fn set_env_map(slf: &Bound<'_, Self>, which: &str, words: Vec<crate::Int>) -> PyResult<()> {
        let words = words
            .iter()
            .enumerate()
            .map(|(i, w)| crate::arg(&format!("set_env_map: word {i}"), w.0, 0, u64::MAX, ""))
            .collect::<PyResult<Vec<u64>>>()?;
        exclusive(slf, "set_env_map")?.h.set_env_map(which, &words).map_err(crate::err)
    }

    /// Words of the power-table memory (what its load port addresses).
    #[getter]
    fn power_words(&self) -> usize {
        self.h.mem.table.entries.len()
    }

    /// The model's power table now (words of the ROM file for the current shininess).
    fn power_table<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let v: Vec<u64> = self.h.mem.table.entries.iter().map(|&e| e as u64).collect();
        numpy::PyArray1::from_vec(py, v).into_any()
    }

    /// ROM `name` ("power_table" where the top reads one, "bump_palette", "cube_map", and
    /// under EMBM "env_diffuse" and "env_specular" where the top has them, the power-up maps)
    /// as {name, width, words, layout, params}: the words of the file `gbump rom` writes. `shininess` defaults to the
    /// configuration's own (its TOML field, as `gbump rom` does; not the `shininess`
    /// property, the model's current table), `cube_size` to the configuration's
    /// `cube_map_face`, else gbump rom's 32. A shininess a ROM table or squaring unit does not
    /// hold, or a cube size other than the configuration's map, is refused, as `gbump rom`
    /// refuses it.
    #[pyo3(signature = (name, shininess = None, cube_size = None))]
    fn rom<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        shininess: Option<crate::Int>,
        cube_size: Option<crate::Int>,
    ) -> PyResult<Bound<'py, PyDict>> {
        use gbump::limits::{MAX_CUBE_SIDE, MAX_SHININESS};
        use gbump::rtlgen::rom;
        let cfg = self.cfg();
        // Bounded here first, so a value past 32 bits is named rather than cut.
        let shininess = shininess
            .map(|n| crate::arg("shininess", n.0, 0, MAX_SHININESS.into(), "MAX_SHININESS").map(|n| n as u32))
            .transpose()?;
        let cube_size = cube_size
            .map(|c| crate::arg("cube_size", c.0, 1, MAX_CUBE_SIDE.into(), "MAX_CUBE_SIDE").map(|c| c as usize))
            .transpose()?;
        let (n, cube_size) =
            gbump::rtlgen::rom_files::rom_choices(cfg, shininess, cube_size, ["shininess=", "cube_size="]).map_err(crate::err)?;
        // The ROMs `gbump rom` writes for this configuration, by the names this takes.
        let envs: Vec<String> = gbump::rtlgen::top::env_map_names(cfg).iter().map(|w| format!("env_{w}")).collect();
        let table = gbump::rtlgen::top::power_table_read(cfg);
        let r = match name {
            "power_table" if table => rom::power_rom(cfg, n),
            "bump_palette" => rom::palette_rom(cfg, &rom::default_palette(cfg), rom::DEFAULT_PALETTE),
            "cube_map" => rom::cube_map_rom(cube_size),
            _ if envs.iter().any(|e| e == name) => {
                let which = name.trim_start_matches("env_");
                rom::env_map_rom(
                    cfg,
                    gbump::model::env_map::default_maps(cfg).named(which),
                    which,
                    rom::DEFAULT_ENV_MAPS,
                )
            }
            _ => {
                let names: Vec<&str> = ["power_table"]
                    .into_iter()
                    .filter(|_| table)
                    .chain(["bump_palette", "cube_map"])
                    .chain(envs.iter().map(String::as_str))
                    .collect();
                let why = match (name, cfg.power_table_unused()) {
                    ("power_table", Some(why)) => format!("the top reads no power table ({why})"),
                    _ => "not a ROM of this configuration".to_string(),
                };
                return Err(crate::fail(format!(
                    "rom `{}`: {why}\n  fix: one of {}",
                    gbump::error::one_line(name),
                    names.join(", ")
                )));
            }
        };
        let d = PyDict::new(py);
        d.set_item("name", &r.name)?;
        d.set_item("width", r.width)?;
        d.set_item("layout", &r.layout)?;
        d.set_item("params", r.params.clone())?;
        d.set_item("words", numpy::PyArray1::from_vec(py, r.words))?;
        Ok(d)
    }

    /// The interface JSON `gbump rtl` writes beside the top (`<top>.json`), as text;
    /// `regenerate` is its command field.
    #[pyo3(signature = (regenerate = "gbump rtl --out rtl"))]
    fn interface_json(&self, regenerate: &str) -> String {
        gbump::rtlgen::interface::interface_json(self.cfg(), regenerate)
    }

    /// The interface JSON as Python objects.
    #[pyo3(signature = (regenerate = "gbump rtl --out rtl"))]
    fn interface<'py>(&self, py: Python<'py>, regenerate: &str) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &self.interface_json(regenerate))
    }

    /// Targets this configuration has: "top", then its units.
    #[getter]
    fn targets(&self) -> Vec<&'static str> {
        self.h.targets.iter().map(|t| t.name).collect()
    }

    /// The columns of a `target` record: [{name, role, lsb, width, lanes, lane_bits, format,
    /// enters, signed}], stimulus first, as the vector manifests list them (`enters`: edges
    /// after the rest of its record at which a column enters a unit streamed one record per
    /// edge).
    fn columns<'py>(&self, py: Python<'py>, target: &str) -> PyResult<Bound<'py, PyList>> {
        let t = self.h.target(target).map_err(crate::err)?;
        let l = PyList::empty(py);
        for c in &t.layout.columns {
            let d = PyDict::new(py);
            d.set_item("name", &c.name)?;
            d.set_item(
                "role",
                if c.role == gbump::vectors::layout::Role::Stimulus {
                    "stimulus"
                } else {
                    "expected"
                },
            )?;
            d.set_item("lsb", c.lsb)?;
            d.set_item("width", c.width)?;
            d.set_item("lanes", c.lanes)?;
            d.set_item("lane_bits", c.width / c.lanes)?;
            d.set_item("format", &c.format)?;
            d.set_item("enters", c.enters)?;
            d.set_item("signed", c.signed())?;
            l.append(d)?;
        }
        Ok(l)
    }

    /// Bits of one `target` record.
    fn record_bits(&self, target: &str) -> PyResult<u32> {
        Ok(self.h.target(target).map_err(crate::err)?.layout.bits)
    }

    /// 32-bit words of one `target` record (the row length of record arrays).
    fn record_words(&self, target: &str) -> PyResult<usize> {
        Ok(self.h.target(target).map_err(crate::err)?.layout.words32())
    }

    /// Evaluate `target` records (uint32, shape (N, words) or (words,)): the stimulus columns
    /// are read and whole records returned, the model's expected columns filled in, exactly
    /// as a vector file holds them. Runs without the GIL, on all cores for large batches.
    fn eval<'py>(&self, py: Python<'py>, target: &str, records: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let t = self.h.target(target).map_err(crate::err)?;
        let n = t.layout.words32();
        // The input's copy and the output.
        let r = records_in(records, &self.h, t, 2 * crate::arrays::words_bytes(t))?;
        let mut out = crate::arrays::zeros(r.words.len(), "eval")?;
        crate::detach(py, || self.h.eval_words(t, &r.words, &mut out)).map_err(crate::err)?;
        records_out(py, out, n, r.single)
    }

    /// Per-field records -> packed records (uint32, shape (N, words)). `fields` maps every
    /// stimulus column (and optionally expected ones) to integer codes of shape (N, lanes),
    /// or (N,) for a one-lane column; each value is checked against its column's format.
    fn pack<'py>(&self, py: Python<'py>, target: &str, fields: &Bound<'py, PyDict>) -> PyResult<Bound<'py, PyAny>> {
        let t = self.h.target(target).map_err(crate::err)?;
        let (_, words) = crate::fields::pack(&self.h, t, fields)?;
        records_out(py, words, t.layout.words32(), false)
    }

    /// Packed records -> {column: int64 array (N, lanes)} for every column, signed columns
    /// sign-extended.
    fn unpack<'py>(&self, py: Python<'py>, target: &str, records: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
        let t = self.h.target(target).map_err(crate::err)?;
        let per = crate::arrays::words_bytes(t) + crate::arrays::fields_bytes(t);
        let r = records_in(records, &self.h, t, per)?;
        crate::fields::unpack(py, t, &r.words, r.count)
    }

    /// `eval` in the per-field form: stimulus fields in, every column out (`unpack` of the
    /// evaluated records).
    fn eval_fields<'py>(&self, py: Python<'py>, target: &str, fields: &Bound<'py, PyDict>) -> PyResult<Bound<'py, PyDict>> {
        let t = self.h.target(target).map_err(crate::err)?;
        let (count, words) = crate::fields::pack(&self.h, t, fields)?;
        // The packed input, the output and its per-field form, beside the fields given.
        let per = 2 * crate::arrays::words_bytes(t) + crate::arrays::fields_bytes(t);
        crate::arrays::plan(&self.h, t, "eval_fields", count as u64, per)?;
        let mut out = crate::arrays::zeros(words.len(), "eval_fields")?;
        crate::detach(py, || self.h.eval_words(t, &words, &mut out)).map_err(crate::err)?;
        crate::fields::unpack(py, t, &out, count)
    }

    /// The seeded random stimulus stream of `gbump vectors --source random:N --seed SEED`
    /// (the same default seed, 1).
    #[pyo3(signature = (seed = crate::Int(1)), text_signature = "(self, seed=1)")]
    fn stimulus(&self, seed: crate::Int) -> PyResult<crate::vectors::Stimulus> {
        let seed = crate::arg("seed", seed.0, 0, u64::MAX, "")?;
        Ok(crate::vectors::Stimulus::new(&self.h, seed))
    }

    /// Vector sets of `source` ("random:N", "corners", "scene:NAME", "exhaustive:UNIT"), the
    /// top's set as `gbump vectors --target top` writes it (an exhaustive source: its unit's
    /// set), with the same default seed, 1: a list of {name, target, shininess, records,
    /// reasons} (one per power table; `reasons` lists why each corner is there, else None);
    /// a scene's sets also have `pixels`, each record's pixel (uint32 (N, 2), x then y, row 0
    /// at the top), as the dump's `_pixels.txt` gives it, and `image_size` [width, height];
    /// an EMBM scene's sets `env_diffuse` and `env_specular`, their object's maps
    /// (`set_env_map` loads them for `eval`).
    /// Random, corner and exhaustive sets use `shininess`, by default the configuration's own
    /// (its TOML field, what `gbump vectors` uses; not the model's current table, which the
    /// `shininess` property reads and sets); scenes their objects'. `size` is a scene's image
    /// size as a (width, height) tuple in pixels (by default the scene's own).
    /// A choice the source ignores (`seed` but for random sources, `shininess` for a scene,
    /// `size` but for a scene) or that the hardware cannot serve (another `shininess` than a
    /// ROM table's or a squaring unit's, any under EMBM) is refused, as `gbump vectors` refuses it.
    #[pyo3(signature = (source, seed = None, shininess = None, size = None))]
    fn vectors<'py>(
        &self,
        py: Python<'py>,
        source: &str,
        seed: Option<crate::Int>,
        shininess: Option<crate::Int>,
        size: Option<(crate::Int, crate::Int)>,
    ) -> PyResult<Bound<'py, PyList>> {
        use gbump::limits::{MAX_IMAGE_SIDE, MAX_SHININESS};
        let (seed, shininess, size) = (seed.map(|s| s.0), shininess.map(|n| n.0), size.map(|(w, h)| (w.0, h.0)));
        let seed = seed.map(|s| crate::arg("seed", s, 0, u64::MAX, "")).transpose()?;
        let shininess = match shininess {
            Some(n) => Some(crate::arg("shininess", n, 0, MAX_SHININESS.into(), "MAX_SHININESS")? as u32),
            None => None,
        };
        let size = match size {
            Some((w, h)) => Some((
                crate::arg("size[0]", w, 1, MAX_IMAGE_SIDE.into(), "MAX_IMAGE_SIDE")? as u32,
                crate::arg("size[1]", h, 1, MAX_IMAGE_SIDE.into(), "MAX_IMAGE_SIDE")? as u32,
            )),
            None => None,
        };
        crate::vectors::vectors(py, &self.h, source, seed, shininess, size)
    }

    fn __repr__(&self) -> String {
        format!("gbump.Config(hash={}, top={})", self.hash(), self.top())
    }
}
