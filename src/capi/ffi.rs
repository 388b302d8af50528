//! The `extern "C"` functions (cbindgen writes `include/gbump.h` from this file; the DPI-C
//! package is generated from that header). Their conventions (handles, status codes, error
//! messages, string ownership, records, threads) are [`super::CONVENTIONS`], which the header
//! opens with.

use super::guard::{guard, handle, handle_mut, last_error, name_arg, str_arg, words, words_mut};
use super::handle::{GbumpConfig, GbumpStim};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::vectors::layout::Role;
use std::ffi::c_char;

/// The ABI version (`ABI_VERSION`): compare with the header's `GBUMP_ABI_VERSION`.
#[no_mangle]
pub extern "C" fn gbump_abi_version() -> i32 {
    super::ABI_VERSION
}

/// The library's name and version, as stamped into generated files (`gbump 0.1.0`).
/// A static string: never freed.
#[no_mangle]
pub extern "C" fn gbump_version() -> *const c_char {
    concat!("gbump ", env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// The hash of the sources the library was built from, as `gbump --version` prints it: a
/// library built from other sources than the gbump beside it differs here (the version
/// numbers are the same). A static string: never freed.
#[no_mangle]
pub extern "C" fn gbump_source() -> *const c_char {
    concat!(env!("GBUMP_SOURCE_HASH"), "\0").as_ptr().cast()
}

/// Why the last failing call on this thread failed (empty before any failure).
#[no_mangle]
pub extern "C" fn gbump_last_error() -> *const c_char {
    last_error()
}

fn boxed(r: Result<GbumpConfig>) -> Result<*mut GbumpConfig> {
    r.map(|h| Box::into_raw(Box::new(h)))
}

/// A handle for the built-in default configuration; NULL on failure.
#[no_mangle]
pub extern "C" fn gbump_config_default() -> *mut GbumpConfig {
    guard("gbump_config_default", std::ptr::null_mut(), || {
        boxed(GbumpConfig::new(PipelineConfig::default()))
    })
}

/// A handle for a configuration given as TOML text; `name` names it in error messages.
/// NULL on failure (a parse or range error names the line and the fix).
///
/// # Safety
/// `text` and `name` are NUL-terminated strings.
#[no_mangle]
pub unsafe extern "C" fn gbump_config_from_toml(text: *const c_char, name: *const c_char) -> *mut GbumpConfig {
    guard("gbump_config_from_toml", std::ptr::null_mut(), || {
        let text = str_arg(text, "text")?;
        let name = crate::error::one_line(str_arg(name, "name")?);
        boxed(GbumpConfig::read(|| PipelineConfig::from_toml(&name, text)))
    })
}

/// A handle for a configuration TOML file; NULL on failure.
///
/// # Safety
/// `path` is a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn gbump_config_from_file(path: *const c_char) -> *mut GbumpConfig {
    guard("gbump_config_from_file", std::ptr::null_mut(), || {
        let path = super::guard::one_line_arg(str_arg(path, "path")?, "path", "give the file a name without one")?;
        boxed(GbumpConfig::read(|| PipelineConfig::load(std::path::Path::new(path))))
    })
}

/// Release a configuration handle (NULL is ignored). Streams made from it stay valid.
///
/// # Safety
/// `h` is NULL or a handle from `gbump_config_*` not yet freed.
#[no_mangle]
pub unsafe extern "C" fn gbump_config_free(h: *mut GbumpConfig) {
    if !h.is_null() {
        drop(Box::from_raw(h));
    }
}

/// The warnings reading the handle's configuration gave, one per line (a renamed field read
/// under its old name, with the fix); "" when there were none. The library never writes to
/// stdout or stderr: this is where its warnings go.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_config_warnings(h: *const GbumpConfig) -> *const c_char {
    with("gbump_config_warnings", h, std::ptr::null(), |h| Ok(h.warnings.as_ptr()))
}

/// Evaluation targets of the configuration: `top` (index 0), then each unit it has, in
/// data-flow order (the names `gbump_eval`, `gbump_record_words` and `gbump_column` take).
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_target_count(h: *const GbumpConfig) -> i32 {
    with("gbump_target_count", h, -1, |h| Ok(h.targets.len() as i32))
}

/// Name of target `i` (0..gbump_target_count); NULL when out of range.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_target_name(h: *const GbumpConfig, i: i32) -> *const c_char {
    with("gbump_target_name", h, std::ptr::null(), |h| {
        let t = h.targets.get(usize::try_from(i).unwrap_or(usize::MAX)).ok_or_else(|| {
            Error::Other(format!(
                "target {i}: out of range\n  fix: use 0..{} (gbump_target_count)",
                h.targets.len()
            ))
        })?;
        Ok(t.c_name.as_ptr())
    })
}

/// Run `f` on the handle; `fail` (NULL or -1) when the handle is NULL or `f` fails.
unsafe fn with<T>(what: &str, h: *const GbumpConfig, fail: T, f: impl FnOnce(&GbumpConfig) -> Result<T>) -> T {
    guard(what, fail, || f(handle(h, "config handle")?))
}

/// The configuration's 16-hex-digit hash (as in every generated file's header).
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_config_hash(h: *const GbumpConfig) -> *const c_char {
    with("gbump_config_hash", h, std::ptr::null(), |h| Ok(h.hash.as_ptr()))
}

/// The configuration as canonical TOML (the input of the hash): every field, except that
/// the fields added after the first release (interpolate, colour_guard_bits, white_lights,
/// power_rom, renormalise, interpolate_k, renormalise_bump, cube_map_face, self_shadow,
/// frame_transform, frame_build, triangle_frame, frame_quaternion, pixel_lh, env_map_bits)
/// are left out at their defaults ("none", 0 or false), so hashes made before they existed
/// stay.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_config_toml(h: *const GbumpConfig) -> *const c_char {
    with("gbump_config_toml", h, std::ptr::null(), |h| Ok(h.toml.as_ptr()))
}

/// The generated top module's name (`gbump_pipeline_<hash8>`).
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_module_name(h: *const GbumpConfig) -> *const c_char {
    with("gbump_module_name", h, std::ptr::null(), |h| Ok(h.module.as_ptr()))
}

/// Light slots in hardware.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_lights(h: *const GbumpConfig) -> i32 {
    with("gbump_lights", h, -1, |h| Ok(h.cfg.lights as i32))
}

/// Rising edges from a fragment's accept to its `out_valid` (the interface JSON's
/// `latency_cycles`).
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_latency(h: *const GbumpConfig) -> i32 {
    with("gbump_latency", h, -1, |h| Ok(crate::rtlgen::top::latency(&h.cfg) as i32))
}

/// Rising edges between two accepts of fragments offered back to back.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_initiation_interval(h: *const GbumpConfig) -> i32 {
    with("gbump_initiation_interval", h, -1, |h| Ok(h.cfg.initiation_interval() as i32))
}

/// Rising edges with `rst` high that bring the top to idle.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_reset_cycles(h: *const GbumpConfig) -> i32 {
    with("gbump_reset_cycles", h, -1, |_| Ok(crate::rtlgen::top::RESET_CYCLES as i32))
}

/// Clock cycles from input to output of unit `unit` (a unit name; -1 for `"top"`, whose
/// latency is `gbump_latency`).
///
/// # Safety
/// `h` is a live handle, `unit` a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn gbump_unit_latency(h: *const GbumpConfig, unit: *const c_char) -> i32 {
    with("gbump_unit_latency", h, -1, |h| {
        let t = h.target(name_arg(unit, "unit")?)?;
        let u = crate::units::unit(t.name).ok_or_else(|| Error::Other("`top`: use gbump_latency\n  fix: pass a unit name".into()))?;
        Ok(u.latency(&h.cfg) as i32)
    })
}

/// Ports of the generated top, in declaration order.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_port_count(h: *const GbumpConfig) -> i32 {
    with("gbump_port_count", h, -1, |h| Ok(h.ports.len() as i32))
}

fn port(h: &GbumpConfig, i: i32) -> Result<&(std::ffi::CString, u32, bool)> {
    h.ports.get(usize::try_from(i).unwrap_or(usize::MAX)).ok_or_else(|| {
        Error::Other(format!(
            "port {i}: out of range\n  fix: use 0..{} (gbump_port_count)",
            h.ports.len()
        ))
    })
}

/// Name of port `i` of the top.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_port_name(h: *const GbumpConfig, i: i32) -> *const c_char {
    with("gbump_port_name", h, std::ptr::null(), |h| Ok(port(h, i)?.0.as_ptr()))
}

/// Width in bits of port `i` of the top.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_port_width(h: *const GbumpConfig, i: i32) -> i32 {
    with("gbump_port_width", h, -1, |h| Ok(port(h, i)?.1 as i32))
}

/// 1 when port `i` of the top is an output, 0 when an input.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_port_is_output(h: *const GbumpConfig, i: i32) -> i32 {
    with("gbump_port_is_output", h, -1, |h| Ok(port(h, i)?.2 as i32))
}

/// Bits of one record of `target` (`"top"` or a unit name).
///
/// # Safety
/// `h` is a live handle, `target` a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn gbump_record_bits(h: *const GbumpConfig, target: *const c_char) -> i32 {
    with("gbump_record_bits", h, -1, |h| {
        Ok(h.target(name_arg(target, "target")?)?.layout.bits as i32)
    })
}

/// 32-bit words of one record of `target`: the size of every record buffer.
///
/// # Safety
/// `h` is a live handle, `target` a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn gbump_record_words(h: *const GbumpConfig, target: *const c_char) -> i32 {
    with("gbump_record_words", h, -1, |h| {
        Ok(h.target(name_arg(target, "target")?)?.layout.words32() as i32)
    })
}

/// Columns of a record of `target` (stimulus first, then expected).
///
/// # Safety
/// `h` is a live handle, `target` a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn gbump_column_count(h: *const GbumpConfig, target: *const c_char) -> i32 {
    with("gbump_column_count", h, -1, |h| {
        Ok(h.target(name_arg(target, "target")?)?.layout.columns.len() as i32)
    })
}

/// Name of column `i` of `target`.
///
/// # Safety
/// `h` is a live handle, `target` a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn gbump_column_name(h: *const GbumpConfig, target: *const c_char, i: i32) -> *const c_char {
    with("gbump_column_name", h, std::ptr::null(), |h| {
        let t = h.target(name_arg(target, "target")?)?;
        let n = t.column_names.len();
        t.column_names
            .get(usize::try_from(i).unwrap_or(usize::MAX))
            .map(|c| c.as_ptr())
            .ok_or_else(|| {
                Error::Other(format!(
                    "column {i} of {}: out of range\n  fix: use 0..{n} (gbump_column_count)",
                    t.name
                ))
            })
    })
}

/// Where column `column` of `target` lies in a record: its lowest bit, its width (every
/// lane's bits together: lane i is bits lsb + i·width/lanes up, width/lanes wide), its lane
/// count, and whether the model fills it (1: expected output, 0: stimulus). -1 when there
/// is no such column.
///
/// # Safety
/// `h` is a live handle, the strings NUL-terminated, the four pointers writable.
#[no_mangle]
pub unsafe extern "C" fn gbump_column(
    h: *const GbumpConfig,
    target: *const c_char,
    column: *const c_char,
    lsb: *mut i32,
    width: *mut i32,
    lanes: *mut i32,
    expected: *mut i32,
) -> i32 {
    with("gbump_column", h, -1, |h| {
        let c = column_of(h, target, column)?;
        for (p, v, arg) in [
            (lsb, c.lsb as i32, "lsb"),
            (width, c.width as i32, "width"),
            (lanes, c.lanes as i32, "lanes"),
            (expected, (c.role == Role::Expected) as i32, "expected"),
        ] {
            *p.as_mut()
                .ok_or_else(|| Error::Other(format!("{arg} is NULL\n  fix: pass a writable int")))? = v;
        }
        Ok(0)
    })
}

/// Column `column` of `target` (`target` and `column` C strings).
unsafe fn column_of(h: &GbumpConfig, target: *const c_char, column: *const c_char) -> Result<&crate::vectors::layout::Column> {
    let t = h.target(name_arg(target, "target")?)?;
    let name = name_arg(column, "column")?;
    t.layout.columns.iter().find(|c| c.name == name).ok_or_else(|| {
        let names: Vec<&str> = t.layout.columns.iter().map(|c| c.name.as_str()).collect();
        Error::Other(format!(
            "column `{name}` of {}: no such column\n  fix: one of {}",
            t.name,
            names.join(", ")
        ))
    })
}

/// Rising edges after the rest of its record at which column `column` of `target` enters
/// the unit, in a stream of one record per edge: 0 for nearly every column;
/// `light_accumulate`'s `acc_in`, the running sum fed back into its last stage, enters
/// `latency - 1` edges late (the vector manifests' `enters`). -1 when there is no such
/// column.
///
/// # Safety
/// `h` is a live handle, the strings NUL-terminated.
#[no_mangle]
pub unsafe extern "C" fn gbump_column_enters(h: *const GbumpConfig, target: *const c_char, column: *const c_char) -> i32 {
    with("gbump_column_enters", h, -1, |h| Ok(column_of(h, target, column)?.enters as i32))
}

/// Evaluate one record of `target`: read the stimulus columns of `rec_in` and write the whole
/// record, stimulus and the model's expected columns, to `rec_out` (may equal `rec_in`):
/// the record a vector file holds for that stimulus.
///
/// # Safety
/// `h` is a live handle, `target` a NUL-terminated string, `rec_in` and `rec_out`
/// `gbump_record_words(h, target)` words each.
#[no_mangle]
pub unsafe extern "C" fn gbump_eval(h: *const GbumpConfig, target: *const c_char, rec_in: *const u32, rec_out: *mut u32) -> i32 {
    eval_batch("gbump_eval", h, target, rec_in, rec_out, 1)
}

/// Evaluate `count` records of `target` back to back (`gbump_record_words(h, target)` words
/// each), in parallel on the library's thread pool; 0 on success, -1 on failure. `count` is
/// 0..=MAX_BATCH_RECORDS (2^24); with 0 nothing is read or written (the buffers may be NULL).
/// A batch with a record the model refuses fails as a whole: `gbump_last_error()` names the
/// lowest such record (the same one every run, however the work was split), and what
/// `rec_out` holds is then unspecified.
///
/// # Safety
/// As `gbump_eval`, with `count` records in each buffer.
#[no_mangle]
pub unsafe extern "C" fn gbump_eval_batch(
    h: *const GbumpConfig,
    target: *const c_char,
    rec_in: *const u32,
    rec_out: *mut u32,
    count: i64,
) -> i32 {
    eval_batch("gbump_eval_batch", h, target, rec_in, rec_out, count)
}

/// `gbump_eval_batch`, its errors named after the function the caller called (`what`).
unsafe fn eval_batch(what: &str, h: *const GbumpConfig, target: *const c_char, rec_in: *const u32, rec_out: *mut u32, count: i64) -> i32 {
    with(what, h, -1, |h| {
        let t = h.target(name_arg(target, "target")?)?;
        let n = t.layout.words32();
        let count =
            u64::try_from(count).map_err(|_| Error::Other(format!("count {count}: negative\n  fix: pass the number of records")))?;
        crate::limits::check_count("count", count, 0, crate::limits::MAX_BATCH_RECORDS, "MAX_BATCH_RECORDS")?;
        if count == 0 {
            return Ok(0);
        }
        // What the call holds beside the caller's buffers: the input's copy.
        h.plan_batch(t, count, 4 * n as u64, "batch")?;
        let total = n * count as usize;
        // Copied first, so `rec_out` may alias `rec_in`.
        let input = words(rec_in, total, "rec_in")?.to_vec();
        h.eval_words(t, &input, words_mut(rec_out, total, "rec_out")?)?;
        Ok(0)
    })
}

/// Load the power table for shininess `n` (0..=MAX_SHININESS, 1024) into the model, as the
/// top's load port would. The configuration stays as it was (`gbump_config_toml` and
/// `gbump_config_hash` are unchanged; `gbump_shininess` gives the table's): the table is a
/// memory's contents, not the hardware. Refused (-1) where the hardware has no loadable
/// table (`power_rom = true`, `power_unit = "squaring"`) for any n but the configuration's.
///
/// # Safety
/// `h` is a live handle, not in use by another thread.
#[no_mangle]
pub unsafe extern "C" fn gbump_set_shininess(h: *mut GbumpConfig, n: i32) -> i32 {
    guard("gbump_set_shininess", -1, || {
        handle_mut(h, "config handle")?.set_shininess(n.into())?;
        Ok(0)
    })
}

/// Load environment map `which` ("diffuse" or "specular") of an EMBM configuration into the
/// model, as the top's `env_<which>_we`/`_wdata` port would: `count` words, the map's n x n
/// texels (n = 2^env_map_bits), texel (x, y) at word y*n + x, {B, G, R} of colour_bits each, R
/// lowest; what `gbump rom` and an EMBM scene set's map files hold (its manifest's
/// `env_maps`). A scene's objects each light with their own maps: load a set's before
/// evaluating its records. The handle powers up with the maps random and corner sets use.
/// Refused (-1) for a configuration without maps, another count, or a word wider than a
/// texel; the map is then unchanged.
///
/// # Safety
/// `h` is a live handle, not in use by another thread; `words` points to `count` words.
#[no_mangle]
pub unsafe extern "C" fn gbump_set_env_map(h: *mut GbumpConfig, which: *const c_char, words: *const u64, count: i64) -> i32 {
    guard("gbump_set_env_map", -1, || {
        let h = handle_mut(h, "config handle")?;
        let which = str_arg(which, "which")?;
        h.env_map_named(which)?;
        // The count is checked before a word is read: a byte count would read past the map.
        crate::model::env_map::check_word_count(&h.cfg, count, &format!("env map `{which}`"))?;
        h.set_env_map(which, super::guard::words(words, count as usize, "words")?)?;
        Ok(0)
    })
}

/// Write texel `index` (0..n*n-1, texel (x, y) at y*n + x) of environment map `which`
/// ("diffuse" or "specular") of an EMBM configuration: one write of the top's
/// `env_<which>_we`/`_waddr`/`_wdata` port, `word` its `{B, G, R}` data word (R lowest), as
/// `gbump_set_env_map` takes a whole map a word at a time (and the DPI-C package can call).
/// Refused (-1) for a configuration without maps, an index outside the map or a word wider
/// than a texel; the map is then unchanged.
///
/// # Safety
/// `h` is a live handle, not in use by another thread.
#[no_mangle]
pub unsafe extern "C" fn gbump_set_env_texel(h: *mut GbumpConfig, which: *const c_char, index: i32, word: u64) -> i32 {
    guard("gbump_set_env_texel", -1, || {
        let h = handle_mut(h, "config handle")?;
        h.set_env_texel(str_arg(which, "which")?, index.into(), word)?;
        Ok(0)
    })
}

/// The shininess of the model's power table (the configuration's until `gbump_set_shininess`).
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_shininess(h: *const GbumpConfig) -> i32 {
    with("gbump_shininess", h, -1, |h| Ok(h.mem.table.n as i32))
}

/// 1 when the top reads a power table (its `power_table_*` load port writes it, and
/// `gbump_set_shininess` changes what it holds), 0 when it has none (a squaring power unit
/// computes x^n, EMBM takes its specular light from the environment map): the interface
/// JSON's `power_table.present`. The table functions below still describe the table the
/// configuration would have.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_power_table_present(h: *const GbumpConfig) -> i32 {
    with("gbump_power_table_present", h, -1, |h| {
        Ok(crate::rtlgen::top::power_table_read(&h.cfg) as i32)
    })
}

/// Words of the power table memory (what the top's load port addresses).
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_power_words(h: *const GbumpConfig) -> i32 {
    with("gbump_power_words", h, -1, |h| Ok(h.mem.table.entries.len() as i32))
}

/// Bits of one power-table word (`power_table_wdata`'s width).
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_power_word_bits(h: *const GbumpConfig) -> i32 {
    with("gbump_power_word_bits", h, -1, |h| Ok(h.cfg.power_fmt().width as i32))
}

/// Word `i` of the power table (the ROM file's word `i`); -1 when out of range.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_power_word(h: *const GbumpConfig, i: i32) -> i64 {
    with("gbump_power_word", h, -1, |h| {
        let n = h.mem.table.entries.len();
        h.mem
            .table
            .entries
            .get(usize::try_from(i).unwrap_or(usize::MAX))
            .copied()
            .ok_or_else(|| Error::Other(format!("power word {i}: out of range\n  fix: use 0..{n} (gbump_power_words)")))
    })
}

/// A random stimulus stream: record `k` of it is record `k` of
/// `gbump vectors --source random:N --seed SEED` (any N > k), so a failing seed replays as a
/// vector file. NULL on failure.
///
/// # Safety
/// `h` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn gbump_stim_new(h: *const GbumpConfig, seed: u64) -> *mut GbumpStim {
    with("gbump_stim_new", h, std::ptr::null_mut(), |h| {
        Ok(Box::into_raw(Box::new(GbumpStim::new(h, seed))))
    })
}

/// Release a stream (NULL is ignored).
///
/// # Safety
/// `g` is NULL or a stream from `gbump_stim_new` not yet freed.
#[no_mangle]
pub unsafe extern "C" fn gbump_stim_free(g: *mut GbumpStim) {
    if !g.is_null() {
        drop(Box::from_raw(g));
    }
}

/// Write the stream's next top record (`gbump_record_words(h, "top")` words) to `rec_out`:
/// its stimulus, with the expected columns zero (`gbump_eval` fills them).
///
/// # Safety
/// `g` is a live stream, `rec_out` writable for a top record.
#[no_mangle]
pub unsafe extern "C" fn gbump_stim_next(g: *mut GbumpStim, rec_out: *mut u32) -> i32 {
    guard("gbump_stim_next", -1, || {
        let g = handle_mut(g, "stimulus stream")?;
        let n = g.layout.words32();
        let out = words_mut(rec_out, n, "rec_out")?;
        out.copy_from_slice(&g.next_record().to_words32(n));
        Ok(0)
    })
}

/// Index of the record `gbump_stim_next` writes next (0 for a new stream).
///
/// # Safety
/// `g` is a live stream.
#[no_mangle]
pub unsafe extern "C" fn gbump_stim_index(g: *const GbumpStim) -> i64 {
    guard("gbump_stim_index", -1, || Ok(handle(g, "stimulus stream")?.index as i64))
}
