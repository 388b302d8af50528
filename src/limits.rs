//! Every bound on a size or a count that gbump checks before it allocates, in one place, so
//! that a hostile or mistyped input is refused with the limit's name instead of exhausting
//! memory. The README's "Limits" table is generated from [`ALL`] (`gbump limits`).

use crate::error::{Error, Result};
use std::io::Read;
use std::path::Path;

/// Pixels per side of a rendered image (`--size`, a scene's `size`).
pub const MAX_IMAGE_SIDE: u32 = 8192;
/// Triangles of a whole scene after tessellation (about 1.2 KB each while rendering).
pub const MAX_TRIANGLES: u64 = 4_000_000;
/// Tessellation segments per direction of an object.
pub const MAX_SEGMENTS: u32 = 1024;
/// Sides of a faceted cylinder (they replace its u segments).
pub const MAX_CYLINDER_SIDES: u32 = 4096;
/// Texels per side of a bump map, generated or read from a PNG (checked from the PNG header).
pub const MAX_BUMP_SIDE: u32 = 4096;
/// Bytes of a scene, configuration or sweep-space file (read with this cap, so a device or a
/// huge file is refused at once).
pub const MAX_INPUT_BYTES: u64 = 1 << 20;
/// Memory a command that rasterises a scene may plan to use; less if `/proc/meminfo` says
/// less is available.
pub const MAX_MEMORY_BYTES: u64 = 8 << 30;
/// Planned bytes per pixel of `gbump render` (three images, hits, fragments with their
/// per-unit traces, heat map, PNG buffers). Each per-pixel figure is the peak resident memory
/// a fully covered scene was measured to take, with a margin; `tests/memory_plan.rs` runs each
/// command and fails when its peak exceeds its plan.
pub const RENDER_BYTES_PER_PIXEL: u64 = 1500;
/// Planned bytes per pixel of a scene's error (`gbump error --scene`).
pub const ERROR_BYTES_PER_PIXEL: u64 = 1800;
/// Planned bytes per pixel of a scene's vector sets (`gbump vectors --source scene:NAME`).
pub const SCENE_VECTOR_BYTES_PER_PIXEL: u64 = 2000;
/// Planned bytes per pixel of `gbump engines` (every engine's image of the scene at once).
pub const ENGINES_BYTES_PER_PIXEL: u64 = 2500;
/// Planned bytes per triangle (mesh, tangent frames, fixed-point bump state).
pub const RENDER_BYTES_PER_TRIANGLE: u64 = 1200;
/// Configurations in a sweep grid (the product of its array lengths).
pub const MAX_SWEEP_POINTS: u64 = 4096;
/// Random vectors of one set (`random:N`, `--random` of regress and fuzz); they stream to disk.
pub const MAX_RANDOM_VECTORS: u64 = 1_000_000_000;
/// Records of one streamed regression (`gbump regress --stream random:N`): nothing is held or
/// written per record, so the bound is time (about a day at 10^5 records a second per core).
pub const MAX_STREAM_VECTORS: u64 = 10_000_000_000;
/// Random stimuli of `gbump error` (held in memory, about 600 bytes each).
pub const MAX_ERROR_STIMULI: u64 = 2_000_000;
/// Vectors of an exhaustive sweep (held in memory before writing).
pub const MAX_EXHAUSTIVE_VECTORS: u64 = 1 << 20;
/// Records the Python module builds in one array (`Config.vectors`, `Stimulus.next`, `pack`).
pub const MAX_BATCH_RECORDS: u64 = 1 << 24;
/// Shininess n of a power table.
pub const MAX_SHININESS: u32 = 1024;
/// Texels per side of a normalisation cube-map face.
pub const MAX_CUBE_SIDE: u32 = 1024;
/// Texels per side of EMBM's environment maps (`gbump engines --embm-map`).
pub const MAX_ENV_MAP_SIDE: u32 = 4096;
/// Register stages per unit (`pipeline_depth`): the deepest unit, the parallel blend, has
/// three cuts (`units::timing`), so a fifth stage would cut nothing.
pub const MAX_PIPELINE_DEPTH: u32 = 4;
/// Characters of a name that becomes part of a file name (see `names.rs`).
pub const MAX_NAME_CHARS: u64 = 64;
/// Seconds of the tool time limit (`--tool-timeout`, `GBUMP_TOOL_TIMEOUT`): a year.
pub const MAX_TOOL_TIMEOUT_SECONDS: u64 = 365 * 86400;
/// Seconds a tool may take to answer `--version` (whether it is installed).
pub const TOOL_PROBE_SECONDS: u64 = 10;
/// Mismatches a bench reports before it stops (`--max-errors`): the Verilog benches count in
/// a 32-bit signed `integer`, so a larger value wrapped and Icarus stopped at the first.
pub const MAX_ERRORS_REPORTED: u64 = i32::MAX as u64;

/// (name, value, what it bounds) of every limit, for the README and `gbump limits`.
pub const ALL: &[(&str, u64, &str)] = &[
    (
        "MAX_IMAGE_SIDE",
        MAX_IMAGE_SIDE as u64,
        "pixels per side of a rendered image (`--size`, scene `size`)",
    ),
    ("MAX_TRIANGLES", MAX_TRIANGLES, "triangles of a scene after tessellation"),
    (
        "MAX_SEGMENTS",
        MAX_SEGMENTS as u64,
        "tessellation segments per direction of an object",
    ),
    ("MAX_CYLINDER_SIDES", MAX_CYLINDER_SIDES as u64, "sides of a faceted cylinder"),
    (
        "MAX_BUMP_SIDE",
        MAX_BUMP_SIDE as u64,
        "texels per side of a bump map (generated, or a PNG's header)",
    ),
    (
        "MAX_INPUT_BYTES",
        MAX_INPUT_BYTES,
        "bytes of a scene, configuration or sweep-space file",
    ),
    (
        "MAX_MEMORY_BYTES",
        MAX_MEMORY_BYTES,
        "planned memory of a command that rasterises a scene, or of a batch of the C library or Python module (or MemAvailable, or the room `ulimit -v` leaves, if lower)",
    ),
    (
        "RENDER_BYTES_PER_PIXEL",
        RENDER_BYTES_PER_PIXEL,
        "planned bytes per pixel of a render",
    ),
    (
        "ERROR_BYTES_PER_PIXEL",
        ERROR_BYTES_PER_PIXEL,
        "planned bytes per pixel of a scene's error",
    ),
    (
        "SCENE_VECTOR_BYTES_PER_PIXEL",
        SCENE_VECTOR_BYTES_PER_PIXEL,
        "planned bytes per pixel of a scene's vector sets",
    ),
    (
        "ENGINES_BYTES_PER_PIXEL",
        ENGINES_BYTES_PER_PIXEL,
        "planned bytes per pixel of `gbump engines`",
    ),
    (
        "RENDER_BYTES_PER_TRIANGLE",
        RENDER_BYTES_PER_TRIANGLE,
        "planned bytes per triangle of a render",
    ),
    ("MAX_SWEEP_POINTS", MAX_SWEEP_POINTS, "configurations in a sweep grid"),
    (
        "MAX_RANDOM_VECTORS",
        MAX_RANDOM_VECTORS,
        "random vectors of one set (`random:N`, `--random`)",
    ),
    (
        "MAX_STREAM_VECTORS",
        MAX_STREAM_VECTORS,
        "records of one streamed regression (`regress --stream random:N`)",
    ),
    ("MAX_ERROR_STIMULI", MAX_ERROR_STIMULI, "random stimuli of `gbump error --random`"),
    (
        "MAX_EXHAUSTIVE_VECTORS",
        MAX_EXHAUSTIVE_VECTORS,
        "vectors of an exhaustive sweep (`exhaustive:UNIT`)",
    ),
    (
        "MAX_BATCH_RECORDS",
        MAX_BATCH_RECORDS,
        "records of one array the Python module builds (`vectors`, `Stimulus.next`, `pack`) and of one C `gbump_eval_batch` call",
    ),
    ("MAX_SHININESS", MAX_SHININESS as u64, "shininess n of a power table"),
    (
        "MAX_CUBE_SIDE",
        MAX_CUBE_SIDE as u64,
        "texels per side of a cube-map face (`--cube-size`, `engines --cg-cube`)",
    ),
    (
        "MAX_ENV_MAP_SIDE",
        MAX_ENV_MAP_SIDE as u64,
        "texels per side of EMBM's environment maps (`engines --embm-map`)",
    ),
    (
        "MAX_PIPELINE_DEPTH",
        MAX_PIPELINE_DEPTH as u64,
        "register stages per unit (`pipeline_depth` of a configuration)",
    ),
    (
        "MAX_NAME_CHARS",
        MAX_NAME_CHARS,
        "characters of a name that becomes part of a file name",
    ),
    (
        "MAX_TOOL_TIMEOUT_SECONDS",
        MAX_TOOL_TIMEOUT_SECONDS,
        "seconds of the time limit of each simulator, build or synthesis run (`--tool-timeout`, `GBUMP_TOOL_TIMEOUT`; none by default)",
    ),
    (
        "TOOL_PROBE_SECONDS",
        TOOL_PROBE_SECONDS,
        "seconds a tool may take to answer `--version`, the check that it is installed; one that takes longer is named as hung",
    ),
    (
        "MAX_ERRORS_REPORTED",
        MAX_ERRORS_REPORTED,
        "mismatches a bench reports before it stops (`--max-errors` of `regress` and `cosim`; the Verilog benches count in a 32-bit `integer`)",
    ),
];

/// The README's "Limits" table.
pub fn markdown() -> String {
    let mut s = String::from("| limit | value | bounds |\n|---|---:|---|\n");
    for (name, v, what) in ALL {
        s += &format!("| `{name}` | {v} | {what} |\n");
    }
    s
}

/// `what` = `v` must lie in `lo..=hi`, where `hi` is the limit named `limit` (none if empty);
/// the error names the limit and how to stay inside it.
pub fn check_count(what: &str, v: u64, lo: u64, hi: u64, limit: &str) -> Result<()> {
    if v >= lo && v <= hi {
        return Ok(());
    }
    if v > hi {
        return Err(above_limit(what, v, lo, hi, limit));
    }
    let fix = if limit.is_empty() {
        format!("use {lo} or more")
    } else {
        format!("use {lo}..={hi} ({limit}, README: Limits)")
    };
    Err(Error::Other(format!("{what}: {v} is below {lo}\n  fix: {fix}")))
}

/// `--max-errors` of `regress` and `cosim`: at least 1 (stopping after no mismatch would
/// report nothing about a failing run), at most [`MAX_ERRORS_REPORTED`].
pub fn check_max_errors(n: u32) -> Result<()> {
    check_count("--max-errors", n.into(), 1, MAX_ERRORS_REPORTED, "MAX_ERRORS_REPORTED")
}

/// `what` = `shown` (a number, or digits past any integer type) is above the limit `limit` = `hi`.
fn above_limit(what: &str, shown: impl std::fmt::Display, lo: u64, hi: u64, limit: &str) -> Error {
    Error::Other(format!(
        "{what}: {shown} exceeds {limit} = {hi}\n  fix: use {lo}..={hi} ({limit}, README: Limits)"
    ))
}

/// Parse the record count `n` of a source (`what`: the flag and its value, for messages):
/// decimal digits, `_` between them allowed, within `lo..=hi` (`limit` names the bound).
pub fn parse_count(what: &str, n: &str, lo: u64, hi: u64, limit: &str) -> Result<u64> {
    let digits = n.replace('_', "");
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) || n.starts_with('_') {
        return Err(Error::Other(format!(
            "{what}: `{n}` is not a count of records: N is written in decimal digits alone (no sign, point or exponent; `_` may group them)\n  fix: use {lo}..={hi}, e.g. 1000000 or 1_000_000"
        )));
    }
    let Ok(v) = digits.parse::<u64>() else {
        // More digits than a u64 holds is above any limit; the message quotes them as given.
        return Err(above_limit(what, n, lo, hi, limit));
    };
    check_count(what, v, lo, hi, limit)?;
    Ok(v)
}

/// Parse an image size `WxH` (`--size`, `--scene-size`), each side in 1..=[`MAX_IMAGE_SIDE`].
pub fn parse_size(flag: &str, s: &str) -> Result<(u32, u32)> {
    let max = MAX_IMAGE_SIDE;
    let bad = || {
        Error::Other(format!(
            "{flag} {s}: expected WxH with 1..={max} pixels per side (MAX_IMAGE_SIDE)\n  fix: give a size such as 512x384"
        ))
    };
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?);
    if w == 0 || h == 0 || w > max || h > max {
        return Err(bad());
    }
    Ok((w, h))
}

/// Bytes of memory a plan may use: [`MAX_MEMORY_BYTES`], or less if the machine has less free
/// or the process may map less (`ulimit -v`: an allocation past it fails, and a failed
/// allocation aborts the process rather than returning an error).
pub fn memory_budget() -> u64 {
    let kb_field = |file: &str, field: &str| {
        std::fs::read_to_string(file).ok().and_then(|t| {
            t.lines()
                .find(|l| l.starts_with(field))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
    };
    let avail = kb_field("/proc/meminfo", "MemAvailable:").map(|kb| kb * 1024);
    let room = address_space_limit().map(|max| max.saturating_sub(kb_field("/proc/self/status", "VmSize:").unwrap_or(0) * 1024));
    [Some(MAX_MEMORY_BYTES), avail, room]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(MAX_MEMORY_BYTES)
}

/// The process's address-space limit (`ulimit -v`), when it has one.
pub fn address_space_limit() -> Option<u64> {
    #[cfg(unix)]
    {
        let mut r = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        // SAFETY: `r` is a valid rlimit for getrlimit to fill.
        if unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut r) } == 0 && r.rlim_cur != libc::RLIM_INFINITY {
            return Some(r.rlim_cur as u64);
        }
    }
    None
}

/// Refuse a plan of `bytes` that will not fit in [`memory_budget`].
pub fn check_memory(what: &str, bytes: u64, fix: &str) -> Result<()> {
    let budget = memory_budget();
    if bytes > budget {
        // As many decimals as tell the two apart (8.01 against 8.00, not 8.0 against 8.0).
        let gib = |b: u64| b as f64 / (1u64 << 30) as f64;
        let places = (1..=6)
            .find(|&p| format!("{:.p$}", gib(bytes)) != format!("{:.p$}", gib(budget)))
            .unwrap_or(6);
        return Err(Error::Other(format!(
            "{what} would need about {:.places$} GiB of memory, more than the {:.places$} GiB allowed (the lowest of MAX_MEMORY_BYTES, MemAvailable and the room `ulimit -v` leaves)\n  fix: {fix}",
            gib(bytes),
            gib(budget)
        )));
    }
    Ok(())
}

/// What a command keeps per pixel of a scene it rasterises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelUse {
    Render,
    Error,
    SceneVectors,
    Engines,
    /// `render --rtl`: the render, then its scene set through the RTL.
    RenderRtl,
}

impl PixelUse {
    /// Planned bytes per pixel.
    pub fn bytes(self) -> u64 {
        match self {
            PixelUse::Render => RENDER_BYTES_PER_PIXEL,
            PixelUse::Error => ERROR_BYTES_PER_PIXEL,
            PixelUse::SceneVectors => SCENE_VECTOR_BYTES_PER_PIXEL,
            PixelUse::Engines => ENGINES_BYTES_PER_PIXEL,
            // The images stay while the scene's set is dumped and simulated.
            PixelUse::RenderRtl => RENDER_BYTES_PER_PIXEL + SCENE_VECTOR_BYTES_PER_PIXEL,
        }
    }
}

/// Planned memory of `use_` of `triangles` at `w`×`h`.
pub fn render_bytes(use_: PixelUse, w: u32, h: u32, triangles: u64) -> u64 {
    w as u64 * h as u64 * use_.bytes() + triangles * RENDER_BYTES_PER_TRIANGLE
}

/// Refuse rasterising `what` (a scene file) at `w`×`h` with `triangles` for `use_` before
/// anything is allocated.
pub fn check_render(use_: PixelUse, what: &str, w: u32, h: u32, triangles: u64) -> Result<()> {
    let side = u64::from(MAX_IMAGE_SIDE);
    check_count(&format!("{what}: image width"), w.into(), 1, side, "MAX_IMAGE_SIDE")?;
    check_count(&format!("{what}: image height"), h.into(), 1, side, "MAX_IMAGE_SIDE")?;
    check_count(&format!("{what}: triangles"), triangles, 1, MAX_TRIANGLES, "MAX_TRIANGLES")?;
    check_memory(
        &format!("rendering {what} at {w}x{h} ({triangles} triangles)"),
        render_bytes(use_, w, h, triangles),
        "render a smaller --size, or lower the scene's `segments`",
    )
}

/// Read a text input with a byte cap, so `/dev/urandom` or a huge file fails at once.
pub fn read_text(path: &Path) -> Result<String> {
    read_text_as(path, "a scene, configuration or sweep space", "give the .toml file itself")
}

/// Refuse a named pipe or a socket as an input file: opening one waits for a writer, so the
/// run would hang rather than fail. (Devices such as /dev/zero are read, and capped.)
pub fn check_not_pipe(path: &Path, fix: &str) -> Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if let Ok(m) = std::fs::metadata(path) {
            let t = m.file_type();
            if t.is_fifo() || t.is_socket() {
                return Err(Error::Other(format!(
                    "{}: a named pipe or socket, not a file (reading it would wait for a writer)\n  fix: {fix}",
                    path.display()
                )));
            }
        }
    }
    Ok(())
}

/// The regular files this run has read as inputs (canonical paths): a result written over one
/// of them would destroy the input it came from (`--json` naming the `--config`, say). Kept
/// only by a command-line run ([`record_inputs`]): a library or Python process reads and
/// writes as its caller says.
static INPUTS: std::sync::Mutex<Option<std::collections::HashSet<std::path::PathBuf>>> = std::sync::Mutex::new(None);

/// Start keeping this process's inputs (the command line does).
pub fn record_inputs() {
    INPUTS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .get_or_insert_with(Default::default);
}

/// Record `path` as an input of this run (a regular file: a device is read and written in
/// place, never replaced).
pub fn note_input(path: &Path) {
    let mut inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    if let (Some(set), Ok(p)) = (inputs.as_mut(), std::fs::canonicalize(path)) {
        if p.is_file() {
            set.insert(p);
        }
    }
}

/// Refuse to write a result at `path` when it is an input this run has read.
pub fn check_not_input(path: &Path) -> Result<()> {
    let Ok(p) = std::fs::canonicalize(path) else {
        return Ok(());
    };
    if INPUTS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .as_ref()
        .is_some_and(|s| s.contains(&p))
    {
        return Err(Error::Other(format!(
            "{}: an input of this run; writing a result there would replace it\n  fix: give the output another path",
            path.display()
        )));
    }
    Ok(())
}

/// [`read_text`] for an input that is `what`, with `fix` when it is not text or too large.
pub fn read_text_as(path: &Path, what: &str, fix: &str) -> Result<String> {
    check_not_pipe(path, fix)?;
    let f = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    note_input(path);
    let mut buf = Vec::new();
    f.take(MAX_INPUT_BYTES + 1).read_to_end(&mut buf).map_err(|e| Error::io(path, e))?;
    if buf.len() as u64 > MAX_INPUT_BYTES {
        return Err(Error::Other(format!(
            "{}: larger than MAX_INPUT_BYTES = {MAX_INPUT_BYTES} bytes; not {what}\n  fix: {fix}",
            path.display()
        )));
    }
    String::from_utf8(buf).map_err(|_| Error::Other(format!("{}: not UTF-8 text, so not {what}\n  fix: {fix}", path.display())))
}

/// Bytes an unprivileged writer may still put on the file system holding `dir` (None when
/// the system cannot say).
pub fn free_bytes(dir: &Path) -> Option<u64> {
    use std::os::unix::ffi::OsStrExt;
    let c = std::ffi::CString::new(dir.as_os_str().as_bytes()).ok()?;
    // SAFETY: statvfs(3) fills the zeroed struct from a NUL-terminated path.
    unsafe {
        let mut st: libc::statvfs = std::mem::zeroed();
        (libc::statvfs(c.as_ptr(), &mut st) == 0).then(|| st.f_bavail as u64 * st.f_frsize as u64)
    }
}
