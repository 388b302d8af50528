//! Lockstep co-simulation: the generated top under Verilator against the golden model
//! itself, called through DPI-C (libgbump, `src/capi`), with no vector file. The testbench
//! draws fragments from the model's random stream, the model evaluates each one as the top
//! accepts it, and every output is compared when its `out_valid` arrives.

pub mod tb;

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::sim::rtl_files::Rtl;
use crate::sim::Outcome;
use std::path::{Path, PathBuf};

#[derive(Clone, Debug)]
pub struct CosimOptions {
    /// Work folder (absolute): generated RTL, the configuration file, the cached build.
    pub work: PathBuf,
    /// An existing RTL folder (`gbump rtl --out DIR`) to check instead of generating one.
    pub rtl: Option<PathBuf>,
    /// libgbump (default: `libgbump.so` beside the running gbump executable).
    pub lib: Option<PathBuf>,
    pub count: u64,
    pub seed: u64,
    /// Idle `in_valid` for 1-3 cycles before every Nth fragment (0: never).
    pub bubbles: u32,
    pub max_errors: u32,
    /// The command line, for the generated RTL's headers.
    pub command: String,
}

/// The C library cargo builds with the gbump executable `exe`: `libgbump.so` beside it
/// (`cargo build`), or in `deps/` beside it (`cargo test` builds it there without copying it
/// up). The one built from the running gbump's sources wins (a build of only an example or a
/// test rewrites `deps/` alone); failing that the newer, which [`check_library`] refuses.
pub fn library_beside(exe: &Path) -> Option<PathBuf> {
    let name = format!("{}gbump{}", std::env::consts::DLL_PREFIX, std::env::consts::DLL_SUFFIX);
    let dir = exe.parent()?;
    let found: Vec<PathBuf> = [dir.join(&name), dir.join("deps").join(&name)]
        .into_iter()
        .filter(|p| p.is_file())
        .collect();
    if let Some(p) = found.iter().find(|p| built_from_these_sources(p)) {
        return Some(p.clone());
    }
    found
        .into_iter()
        .filter_map(|p| Some((std::fs::metadata(&p).ok()?.modified().ok()?, p)))
        .max()
        .map(|(_, p)| p)
}

/// Whether `lib` carries the running gbump's source hash (`gbump_source()` returns it, so it
/// is in the file as a NUL-terminated string): the model it holds is this gbump's.
pub fn built_from_these_sources(lib: &Path) -> bool {
    std::fs::read(lib).is_ok_and(|b| holds_cstr(&b, crate::SOURCE_HASH))
}

/// Whether `image` holds `s` as a NUL-terminated string (a symbol name, a string constant).
fn holds_cstr(image: &[u8], s: &str) -> bool {
    image.windows(s.len() + 1).any(|w| &w[..s.len()] == s.as_bytes() && w[s.len()] == 0)
}

/// A 64-bit little-endian ELF image's header fields, each None past the end of the file.
struct Elf<'a>(&'a [u8]);

impl Elf<'_> {
    /// The image, when it is 64-bit little-endian ELF.
    fn of(b: &[u8]) -> Option<Elf<'_>> {
        (b.get(..4) == Some(b"\x7fELF") && b.get(4) == Some(&2) && b.get(5) == Some(&1)).then_some(Elf(b))
    }
    fn field<const N: usize>(&self, at: usize) -> Option<[u8; N]> {
        self.0.get(at..at.checked_add(N)?)?.try_into().ok()
    }
    fn u16(&self, at: usize) -> Option<usize> {
        self.field(at).map(|x| u16::from_le_bytes(x) as usize)
    }
    fn u32(&self, at: usize) -> Option<u32> {
        self.field(at).map(u32::from_le_bytes)
    }
    fn u64(&self, at: usize) -> Option<usize> {
        self.field(at).map(|x| u64::from_le_bytes(x) as usize)
    }
    /// Where each program header starts (the header's own count and size, however corrupt).
    fn program_headers(&self) -> impl Iterator<Item = usize> + '_ {
        let (off, size, n) = (
            self.u64(0x20).unwrap_or(0),
            self.u16(0x36).unwrap_or(0),
            self.u16(0x38).unwrap_or(0),
        );
        (0..n).map(move |i| off.saturating_add(i.saturating_mul(size)))
    }
}

/// The byte just past the furthest data ELF image `b`'s headers place in the file (its
/// section header table, each segment's file contents), for a file cut short; None for an
/// image that is not 64-bit little-endian ELF.
pub fn elf_end(b: &[u8]) -> Option<usize> {
    let e = Elf::of(b)?;
    let (phoff, shoff) = (e.u64(0x20)?, e.u64(0x28)?);
    let (phentsize, phnum, shentsize, shnum) = (e.u16(0x36)?, e.u16(0x38)?, e.u16(0x3A)?, e.u16(0x3C)?);
    let tables = shoff
        .saturating_add(shentsize.saturating_mul(shnum))
        .max(phoff.saturating_add(phentsize.saturating_mul(phnum)));
    // Each segment's file offset and size (p_offset, p_filesz), where its header is present.
    let segments = e.program_headers().filter_map(|h| {
        let field = |o: usize| h.checked_add(o).and_then(|at| e.u64(at));
        Some(field(8)?.saturating_add(field(32)?))
    });
    Some(segments.fold(tables, usize::max))
}

/// Whether ELF image `b` is a program rather than a shared library: of type EXEC, or with a
/// PT_INTERP program header (a position-independent executable is of type DYN, as a library
/// is, but names its loader). 64-bit little-endian images only; anything else is left to
/// the checks after this one.
pub fn elf_executable(b: &[u8]) -> bool {
    let Some(e) = Elf::of(b) else {
        return false;
    };
    e.u16(16) == Some(2) || e.program_headers().any(|h| e.u32(h) == Some(3))
}

/// The C library of the running gbump (see [`library_beside`]).
pub fn default_library() -> Result<PathBuf> {
    let exe = std::env::current_exe().map_err(|e| Error::Other(format!("cannot find the running executable: {e}")))?;
    library_beside(&exe).ok_or_else(|| {
        Error::Other(format!(
            "no libgbump beside {}\n  fix: cargo build --release -j 1 (it builds target/release/libgbump.so with the gbump executable), or pass --lib FILE",
            exe.display()
        ))
    })
}

/// Refuse `lib` unless it is a file with an ELF header: anything else would fail at the
/// link, after a whole Verilator build, in the linker's words. Checked before the work folder
/// is touched.
pub fn check_library(lib: &Path) -> Result<()> {
    if !lib.is_file() {
        let what = match std::fs::metadata(lib) {
            Err(_) => "the gbump C library is not there",
            Ok(m) if m.is_dir() => "a folder, not the gbump C library",
            Ok(_) => "not a regular file (a device or a pipe), so not the gbump C library",
        };
        return Err(Error::Other(format!(
            "{}: {what}\n  fix: cargo build --release -j 1 (it builds libgbump.so beside the gbump executable), or pass --lib FILE",
            lib.display()
        )));
    }
    let mut magic = [0u8; 4];
    let is_elf = std::fs::File::open(lib)
        .and_then(|mut f| std::io::Read::read_exact(&mut f, &mut magic))
        .is_ok()
        && magic == *b"\x7fELF";
    if !is_elf {
        return Err(Error::Other(format!(
            "{}: not a shared library (no ELF header), so not the gbump C library\n  fix: pass the libgbump.so that cargo build --release writes beside the gbump executable",
            lib.display()
        )));
    }
    let image = std::fs::read(lib).map_err(|e| Error::io(lib, e))?;
    if let Some(end) = elf_end(&image).filter(|&end| end > image.len()) {
        return Err(Error::Other(format!(
            "{}: cut short ({} bytes, where its ELF headers place data up to byte {end}): a copy or a build that did not finish\n  fix: cargo build --release -j 1 (it rebuilds libgbump.so beside the gbump executable), or pass --lib with a whole copy",
            lib.display(),
            image.len()
        )));
    }
    if elf_executable(&image) {
        return Err(Error::Other(format!(
            "{}: an executable (it names a program interpreter), not the gbump C library\n  fix: pass the libgbump.so that cargo build --release writes beside the gbump executable",
            lib.display()
        )));
    }
    if !holds_cstr(&image, "gbump_abi_version") {
        return Err(Error::Other(format!(
            "{}: a shared library, but not the gbump C library (it defines no gbump_abi_version)\n  fix: pass the libgbump.so that cargo build --release writes beside the gbump executable",
            lib.display()
        )));
    }
    if !holds_cstr(&image, crate::SOURCE_HASH) {
        return Err(Error::Other(format!(
            "{}: built from other sources than this gbump (source {}, `gbump --version`), so its model is not the one this gbump generates RTL for\n  fix: cargo build --release -j 1 (it rebuilds the library with the gbump executable), or pass --lib with the library of this build",
            lib.display(),
            crate::SOURCE_HASH
        )));
    }
    Ok(())
}

fn library(o: &CosimOptions) -> Result<PathBuf> {
    let lib = match &o.lib {
        Some(l) => l.clone(),
        None => default_library()?,
    };
    let lib = std::path::absolute(&lib).map_err(|e| Error::io(&lib, e))?;
    check_library(&lib)?;
    crate::sim::check_tool_path(&lib, "--lib")?;
    Ok(lib)
}

/// A build of the RTL in a folder of the user's (`--rtl DIR`) that failed: where its Verilog
/// is not what `gbump rtl` writes for `cfg`, the fix is the edit (or a damaged copy) and says
/// which files, not "a gbump bug"; otherwise the build's own error stands.
fn blame_edits(cfg: &PipelineConfig, dir: &Path, rtl: &Rtl, e: Error) -> Error {
    if crate::interrupt::interrupted() {
        return e;
    }
    // The header names the command that wrote a file; the rest is the design.
    let code = |t: &str| {
        t.lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let edited: Vec<String> = crate::rtlgen::generate(cfg, "")
        .into_iter()
        // The sources the build compiled, each against what `gbump rtl` writes under its name.
        .filter(|(name, _)| rtl.sources.iter().any(|p| p.file_name().is_some_and(|n| n == name.as_str())))
        .filter(|(name, text)| std::fs::read_to_string(dir.join(name)).map_or(true, |t| code(&t) != code(text)))
        .map(|(name, _)| name)
        .collect();
    if edited.is_empty() {
        return e;
    }
    let text = e.to_string();
    let what = text.split("\n  fix:").next().unwrap_or(&text);
    Error::Other(format!(
        "{what}\n  fix: the Verilog in --rtl {} is not what `gbump rtl` writes for this configuration ({} differ or are missing: an edit, or a damaged copy): correct the edit, or regenerate the folder with `gbump rtl --config FILE --out {0}`",
        dir.display(),
        edited.join(", ")
    ))
}

/// The interface JSON of the RTL folder `dir`: the one `gbump_pipeline_*.json` in it.
pub fn interface_file(dir: &Path) -> Result<PathBuf> {
    let entries = std::fs::read_dir(dir).map_err(|e| {
        Error::Other(format!(
            "--rtl {}: cannot read the folder ({e})\n  fix: give a folder written by `gbump rtl --out DIR`",
            dir.display()
        ))
    })?;
    let mut found: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let n = p.file_name().map_or(String::new(), |n| n.to_string_lossy().into_owned());
            n.starts_with("gbump_pipeline_") && n.ends_with(".json")
        })
        .collect();
    found.sort();
    match found.len() {
        1 => Ok(found.remove(0)),
        0 => Err(Error::Other(format!(
            "--rtl {}: no interface JSON (gbump_pipeline_*.json)\n  fix: give a folder written by `gbump rtl --out DIR`",
            dir.display()
        ))),
        _ => Err(Error::Other(format!(
            "--rtl {}: {} interface JSON files ({}), so which top to check is unclear\n  fix: give a folder holding one configuration's RTL",
            dir.display(),
            found.len(),
            found.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
        ))),
    }
}

/// The RTL a simulator reads, from the interface JSON's file names (the filelist and the
/// waivers), all by absolute path.
fn rtl_of(dir: &Path, j: &serde_json::Value, file: &Path) -> Result<Rtl> {
    // Every name is a file of the folder: none may lead out of it (`../x`, `/etc/x`).
    let name = |path: &[&str]| -> Result<PathBuf> {
        let n = tb::text(j, path, file)?;
        crate::names::check(&file.display().to_string(), &path.join("."), n)?;
        Ok(dir.join(n))
    };
    let list = name(&["files", "filelist"])?;
    let fix = "regenerate the folder with `gbump rtl --out DIR`";
    let text = crate::limits::read_text_as(&list, "a filelist", fix)?;
    let mut sources = Vec::new();
    for (i, l) in text.lines().enumerate().map(|(i, l)| (i, l.trim())) {
        if l.is_empty() || l.starts_with("//") {
            continue;
        }
        crate::names::check(&format!("{}:{}", list.display(), i + 1), "source", l)?;
        sources.push(dir.join(l));
    }
    let waivers = vec![name(&["files", "waivers"])?];
    for f in sources.iter().chain(&waivers) {
        if !f.is_file() {
            return Err(Error::Other(format!(
                "{}: listed in {} but missing\n  fix: regenerate the folder with `gbump rtl --out DIR`",
                f.display(),
                list.display()
            )));
        }
    }
    Ok(Rtl {
        init_file: name(&["power_table", "init_file"])?,
        dir: dir.to_path_buf(),
        sources,
        waivers,
        // The lockstep bench instantiates the top with INIT_FILE only: palette tops are not
        // co-simulated yet (their palette would not load from the work folder).
        memory_inits: Vec::new(),
    })
}

/// The interface JSON of the RTL folder `dir` (read with the input cap), which must be the
/// RTL of `cfg`: RTL of another configuration would only show after a whole build.
fn interface_of(cfg: &PipelineConfig, dir: &Path) -> Result<(PathBuf, serde_json::Value)> {
    crate::sim::check_tool_path(dir, "--rtl")?;
    let jf = interface_file(dir)?;
    let fix = "regenerate the folder with `gbump rtl --out DIR`";
    let jtext = crate::limits::read_text_as(&jf, "an interface JSON", fix)?;
    let j: serde_json::Value =
        serde_json::from_str(&jtext).map_err(|e| Error::Other(format!("{}: not JSON ({e})\n  fix: {fix}", jf.display())))?;
    let hash = j.get("config_hash").and_then(|h| h.as_str()).unwrap_or_default();
    if hash != cfg.hash() {
        return Err(Error::Other(format!(
            "--rtl {}: the RTL of another configuration ({hash:?}), not of the one picked ({})\n  fix: pick its configuration (the interface JSON's `config`), or generate this one's RTL with `gbump rtl`",
            dir.display(),
            cfg.hash()
        )));
    }
    // The module the testbench instantiates: the configuration's, as the hash says.
    let top = crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline");
    let named = tb::text(&j, &["top"], &jf)?;
    if named != top {
        return Err(Error::Other(format!(
            "{}: `top` is {named:?}, but the top of configuration {} is {top:?}: the interface JSON was edited or belongs to other RTL\n  fix: {fix}",
            jf.display(),
            cfg.hash()
        )));
    }
    // The testbench is made from this file (latency, ports, lanes): an edit that kept the hash
    // would be blamed on the RTL as mismatches or a timeout.
    let mut want: serde_json::Value =
        serde_json::from_str(&crate::rtlgen::interface::interface_json(cfg, "")).expect("the interface is JSON");
    let mut got = j.clone();
    // A folder another gbump wrote differs in its notes as well: that is what to say.
    if let (Some(g), Some(w)) = (got.get("generator"), want.get("generator")) {
        if g != w {
            return Err(Error::Other(format!(
                "{}: written by {g}, and this is {w}: its testbench and notes are another gbump's\n  fix: {fix}",
                jf.display()
            )));
        }
    }
    for v in [&mut want, &mut got] {
        if let Some(o) = v.as_object_mut() {
            o.remove("regenerate");
        }
    }
    if let Some((at, g, w)) = first_difference(&got, &want, String::new()) {
        return Err(Error::Other(format!(
            "{}: `{at}` is {g}, but configuration {}'s interface has {w}: the interface JSON was edited after `gbump rtl` wrote it\n  fix: {fix}",
            jf.display(),
            &cfg.hash()[..8]
        )));
    }
    Ok((jf, j))
}

/// The first place (a dotted path, `[i]` for an array's element) where `got` differs from
/// `want`, with both values there as JSON (`absent` where one has no such key).
fn first_difference(got: &serde_json::Value, want: &serde_json::Value, at: String) -> Option<(String, String, String)> {
    use serde_json::Value as V;
    // A whole port list is not a message: long values are cut.
    let shown = |v: Option<&V>| {
        v.map_or("absent".to_string(), |v| {
            let t = v.to_string();
            match t.char_indices().nth(80) {
                Some((i, _)) => format!("{}...", &t[..i]),
                None => t,
            }
        })
    };
    let join = |k: &str| if at.is_empty() { k.to_string() } else { format!("{at}.{k}") };
    match (got, want) {
        (V::Object(g), V::Object(w)) => {
            let mut keys: Vec<&String> = w.keys().chain(g.keys().filter(|k| !w.contains_key(*k))).collect();
            keys.dedup();
            keys.into_iter().find_map(|k| match (g.get(k), w.get(k)) {
                (Some(a), Some(b)) => first_difference(a, b, join(k)),
                (a, b) => Some((join(k), shown(a), shown(b))),
            })
        }
        (V::Array(g), V::Array(w)) if g.len() == w.len() => g
            .iter()
            .zip(w)
            .enumerate()
            .find_map(|(i, (a, b))| first_difference(a, b, format!("{at}[{i}]"))),
        _ => (got != want).then(|| (at.clone(), shown(Some(got)), shown(Some(want)))),
    }
}

/// Everything `cosim` checks that needs no work folder (the simulator, the configuration,
/// the library, the RTL folder), so a command refuses before it takes one.
pub fn check_inputs(cfg: &PipelineConfig, o: &CosimOptions) -> Result<()> {
    crate::sim::require(crate::sim::Sim::Verilator)?;
    crate::capi::GbumpConfig::new(cfg.clone())?;
    // The user's own inputs first, then the library this gbump was built beside.
    if let Some(d) = &o.rtl {
        interface_of(cfg, &std::path::absolute(d).map_err(|e| Error::io(d, e))?)?;
    }
    library(o).map(|_| ())
}

/// Run `o.count` fragments of seed `o.seed` through the RTL (generated for `cfg`, or
/// `o.rtl`) against the model of `cfg`.
pub fn cosim(cfg: &PipelineConfig, o: &CosimOptions) -> Result<Outcome> {
    crate::sim::require(crate::sim::Sim::Verilator)?;
    // What the library would refuse at the testbench's start (palette mode, a record wider
    // than the DPI-C package's vectors) is refused before anything is built.
    crate::capi::GbumpConfig::new(cfg.clone())?;
    let lib = library(o)?;
    let hash = cfg.hash();
    let rtl_dir = match &o.rtl {
        Some(d) => std::path::absolute(d).map_err(|e| Error::io(d, e))?,
        None => crate::sim::rtl_files::write_rtl(cfg, &o.work.join(format!("cosim_rtl_{hash}")), &o.command)?.dir,
    };
    let (jf, j) = interface_of(cfg, &rtl_dir)?;
    let rtl = rtl_of(&rtl_dir, &j, &jf)?;
    let source = format!("{}\n{}", crate::capi::DPI_PACKAGE, tb::fill(&j, &jf, &rtl_dir)?);
    // The model reads the configuration from a file beside the build, whatever picked it.
    let cfg_file = o.work.join(format!("cosim_config_{hash}.toml"));
    // Written unless it holds this text already (it may be the --config the run read).
    if std::fs::read(&cfg_file).ok().as_deref() != Some(cfg.to_toml().as_bytes()) {
        crate::render::output::write_atomic(&cfg_file, cfg.to_toml().as_bytes())?;
    }
    let exe = crate::sim::verilator::build_cosim(&o.work.join("builds"), &source, &rtl, &lib).map_err(|e| match &o.rtl {
        Some(_) => blame_edits(cfg, &rtl_dir, &rtl, e),
        None => e,
    })?;
    let args = vec![
        format!("+config={}", cfg_file.display()),
        format!("+seed={:x}", o.seed),
        format!("+count={}", o.count),
        format!("+bubbles={}", o.bubbles),
        format!("+max_errors={}", o.max_errors),
    ];
    use crate::sim::Simulator;
    crate::sim::Verilator.run(&exe, &args, None, &o.work, "cosim (verilator)")
}

#[cfg(test)]
mod tests {
    /// The running test binary is a program; the library this crate builds (when there) is
    /// not.
    #[test]
    fn a_program_is_told_from_a_library() {
        let me = std::fs::read(std::env::current_exe().unwrap()).unwrap();
        assert!(super::elf_executable(&me));
        let lib = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/release/libgbump.so");
        if let Ok(b) = std::fs::read(&lib) {
            assert!(!super::elf_executable(&b), "{}", lib.display());
        }
        assert!(!super::elf_executable(b"\x7fELF"));
    }
}
