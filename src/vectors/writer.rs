//! Writing vector sets: records stream to temporary files (hex and binary) with running
//! sha256, then the files are renamed into place and the manifest written last, so an
//! interrupted or failed dump leaves no set that looks whole.

use super::layout::{Layout, Record};
use super::manifest::{columns, EnvMapFiles, FileEntry, Manifest};
use super::sources::{corners, exhaustive, exhaustive_count, SceneGroup, Source, RANDOM_CHUNK};
use super::staged_file::StagedFile;
use super::targets::{eval_top, eval_unit, top_layout, top_record, unit_layout, unit_record, unit_stims, TopStim, UnitStim};
use super::top_records::TopRecords;
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::model::env_map::EnvMaps;
use crate::units::{Memories, MemoryContents};
use rayon::prelude::*;
use sha2::{Digest, Sha256};
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Clone, Debug)]
pub struct DumpOptions {
    pub text: bool,
    pub binary: bool,
    pub seed: u64,
    /// Image size for scene sources (None: the scene's own).
    pub size: Option<(u32, u32)>,
    /// The command line, recorded in manifests.
    pub command: String,
    /// Power-table shininess for non-scene sources (default: the config's).
    pub shininess: Option<u32>,
}

impl DumpOptions {
    /// The files `text` (`.hex`) and `binary` (`.bin`) of seed 1, at a scene's own size and the
    /// configuration's shininess, recorded as made by `command`; set any other field apart.
    pub fn formats(command: impl Into<String>, text: bool, binary: bool) -> DumpOptions {
        DumpOptions {
            text,
            binary,
            seed: 1,
            size: None,
            command: command.into(),
            shininess: None,
        }
    }
}

/// A written set.
#[derive(Clone, Debug)]
pub struct VectorSet {
    pub target: String,
    pub manifest: PathBuf,
    pub count: u64,
}

struct Sink {
    /// The file's name in the set (its manifest entry), even where `path` is the end of a
    /// symbolic link of that name.
    name: String,
    path: PathBuf,
    tmp: PathBuf,
    /// Taken when the file is finished.
    w: Option<StagedFile>,
    sha: Sha256,
    bytes: u64,
}

/// Bytes of one write from which the hash runs beside the write (a thread each time).
const PARALLEL_HASH_BYTES: usize = 1 << 20;

impl Sink {
    fn new(path: PathBuf) -> Result<Sink> {
        let name = path.file_name().expect("a file name").to_string_lossy().into_owned();
        let path = crate::render::output::streamed_result_path(&path)?;
        let tmp = crate::temp_files::temp_path(&path);
        let f = StagedFile::create(&tmp).map_err(|e| Error::io(&tmp, e))?;
        Ok(Sink {
            name,
            path,
            tmp,
            w: Some(f),
            sha: Sha256::new(),
            bytes: 0,
        })
    }
    fn file(&mut self) -> &mut StagedFile {
        self.w.as_mut().expect("open until finished")
    }

    fn put(&mut self, b: &[u8]) -> Result<()> {
        crate::interrupt::check()?;
        self.bytes += b.len() as u64;
        if b.len() < PARALLEL_HASH_BYTES {
            self.sha.update(b);
            return self.file().write_all(b).map_err(|e| Error::io(&self.tmp, e));
        }
        // Hashed on a thread of its own while the write stages the same bytes and sends them
        // to the disk: one after the other on the writer thread, the two were the dump's limit.
        let (sha, w) = (&mut self.sha, self.w.as_mut().expect("open"));
        std::thread::scope(|s| {
            s.spawn(|| sha.update(b));
            w.write_all(b)
        })
        .map_err(|e| Error::io(&self.tmp, e))
    }
    fn finish(mut self) -> Result<FileEntry> {
        // Written and synced; closed before the rename.
        drop(self.w.take().expect("open").finish().map_err(|e| Error::io(&self.tmp, e))?);
        if crate::commit::defer(&self.tmp, &self.path) {
            // The scope renames it with the other results; it is no longer ours to remove.
            self.tmp = PathBuf::new();
        } else {
            std::fs::rename(&self.tmp, &self.path).map_err(|e| Error::io(&self.path, e))?;
        }
        Ok(FileEntry {
            name: std::mem::take(&mut self.name),
            bytes: self.bytes,
            sha256: std::mem::take(&mut self.sha)
                .finalize()
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect(),
        })
    }
}

impl Drop for Sink {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.tmp);
    }
}

/// One target's open files.
struct SetWriter {
    target: String,
    layout: Layout,
    hex: Option<Sink>,
    bin: Option<Sink>,
    count: u64,
    limit: u64,
    stem: String,
}

/// Refuse a set whose file names a reader would refuse (`names::is_safe`, which `regress`
/// applies to every name a manifest lists), before any file of it is made: `what` names the
/// source; the set's longest name is its environment map's where it has maps (`maps`: an
/// EMBM scene's top set), else its power table's.
pub fn check_set_names(what: &str, rename: &str, stem: &str, target: &str, maps: bool) -> Result<()> {
    let longest = longest_set_name(stem, target, maps);
    if crate::names::is_safe(&longest) {
        return Ok(());
    }
    let (max, n) = (crate::limits::MAX_NAME_CHARS as usize, longest.chars().count());
    let shorter = if n > max {
        format!("at least {} character{} shorter, ", n - max, if n - max == 1 { "" } else { "s" })
    } else {
        String::new()
    };
    // Say what is wrong with it: its length, the characters a plain name may not hold, or both.
    let mut odd: Vec<char> = longest.chars().filter(|&c| !crate::names::plain_char(c)).collect();
    odd.dedup();
    let mut why = Vec::new();
    if n > max {
        why.push(format!("{n} characters, more than the {max} of a plain name (MAX_NAME_CHARS)"));
    }
    if !odd.is_empty() {
        why.push(format!(
            "holding {}, which a plain name may not",
            odd.iter().map(|c| format!("{c:?}")).collect::<Vec<_>>().join(", ")
        ));
    }
    Err(Error::Other(format!(
        "{what}: the set `{stem}_{target}` would have file names such as `{longest}` ({}), so no regression could read it\n  fix: rename {rename}: {shorter}with only letters, digits, `_`, `.` or `-`",
        why.join("; ")
    )))
}

/// The longest file name of the set of `target` with `stem`: its environment map's where it
/// has maps, else its power table's.
fn longest_set_name(stem: &str, target: &str, maps: bool) -> String {
    let base = format!("{stem}_{target}");
    if maps {
        env_map_name(&base, "specular")
    } else {
        format!("{base}_power_table.hex")
    }
}

/// [`check_set_names`] of every set scene `s` (loaded from `name`) may give for `targets`.
/// `what` says how the user named the scene (`--source scene:NAME`, `--scene FILE`).
pub fn check_scene_names(cfg: &PipelineConfig, what: &str, name: &str, s: &crate::scene::Scene, targets: &[String]) -> Result<()> {
    let mut sets: Vec<(String, &String, bool)> = super::sources::scene_set_stems(cfg, name, s)
        .into_iter()
        .flat_map(|stem| targets.iter().map(move |t| (stem.clone(), t, cfg.embm() && t == "top")))
        .collect();
    // The longest name first, so the fix says by how much the name must shrink for all.
    sets.sort_by_key(|(stem, t, maps)| std::cmp::Reverse(longest_set_name(stem, t, *maps).len()));
    for (stem, t, maps) in sets {
        check_set_names(what, "the scene file", &stem, t, maps)?;
    }
    Ok(())
}

impl SetWriter {
    fn new(dir: &Path, stem: &str, target: &str, layout: Layout, o: &DumpOptions, limit: u64) -> Result<SetWriter> {
        // Whether the set gets maps is known at its end; the scene's own check covered them.
        check_set_names(&format!("the set {stem}"), "its source", stem, target, false)?;
        let base = format!("{stem}_{target}");
        Ok(SetWriter {
            target: target.into(),
            hex: if o.text {
                Some(Sink::new(dir.join(format!("{base}.hex")))?)
            } else {
                None
            },
            bin: if o.binary {
                Some(Sink::new(dir.join(format!("{base}.bin")))?)
            } else {
                None
            },
            layout,
            count: 0,
            limit,
            stem: base,
        })
    }

    fn full(&self) -> bool {
        self.count >= self.limit
    }

    /// Append pre-encoded records (`n` of them) in both forms.
    fn put_encoded(&mut self, hex: &str, bin: &[u8], n: u64) -> Result<()> {
        let n = n.min(self.limit - self.count.min(self.limit));
        if n == 0 {
            return Ok(());
        }
        if let Some(h) = &mut self.hex {
            let per = self.layout.hex_digits() + 1;
            h.put(&hex.as_bytes()[..per * n as usize])?;
        }
        if let Some(b) = &mut self.bin {
            b.put(&bin[..self.layout.bytes() * n as usize])?;
        }
        self.count += n;
        Ok(())
    }

    fn put(&mut self, r: &Record, line: &mut String, bytes: &mut Vec<u8>) -> Result<()> {
        if self.full() {
            return Ok(());
        }
        if let Some(h) = &mut self.hex {
            line.clear();
            line.push_str(&r.hex(self.layout.hex_digits()));
            line.push('\n');
            h.put(line.as_bytes())?;
        }
        if let Some(b) = &mut self.bin {
            bytes.clear();
            r.to_bytes(self.layout.bytes(), bytes);
            b.put(bytes)?;
        }
        self.count += 1;
        Ok(())
    }

    fn finish(self, dir: &Path, cfg: &PipelineConfig, src: &Source, o: &DumpOptions, n: u32) -> Result<VectorSet> {
        self.finish_with(dir, cfg, src, o, n, None, None)
    }

    /// [`Self::finish`] for a set that runs on its own environment maps `env` (EMBM scene
    /// sets: the object's), written beside it for the harness to load.
    fn finish_with(
        self,
        dir: &Path,
        cfg: &PipelineConfig,
        src: &Source,
        o: &DumpOptions,
        n: u32,
        env: Option<&EnvMaps>,
        pixels: Option<(&[[u32; 2]], [u32; 2])>,
    ) -> Result<VectorSet> {
        if self.count == 0 {
            return Err(Error::Other(format!(
                "{}: no vectors for target {}\n  fix: choose a source that exercises it",
                self.stem, self.target
            )));
        }
        let hex = self.hex.map(Sink::finish).transpose()?;
        let bin = self.bin.map(Sink::finish).transpose()?;
        let table_name = format!("{}_power_table.hex", self.stem);
        let rom = crate::rtlgen::rom::power_rom(cfg, n);
        let text = crate::rtlgen::rom::write(
            &rom,
            crate::rtlgen::rom::RomFormat::Hex,
            &crate::rtlgen::rom::rom_header(&rom, Some(cfg), &o.command, "power table of this vector set"),
        );
        let power_table = write_listed(dir, table_name, &text)?;
        let env_maps = match env {
            Some(maps) => Some(write_env_maps(dir, &self.stem, cfg, maps, &o.command)?),
            None => None,
        };
        let (pixels, image_size) = match pixels {
            Some((px, image)) => (Some(write_pixels(dir, &self.stem, px)?), Some(image)),
            None => (None, None),
        };
        let (module, latency, initiation_interval) = super::manifest::timing(cfg, &self.target);
        let m = Manifest {
            generator: crate::TOOL.into(),
            command: o.command.clone(),
            target: self.target.clone(),
            module,
            source: src.to_string(),
            seed: matches!(src, Source::Random(_)).then_some(o.seed),
            count: self.count,
            config_hash: cfg.hash(),
            config: cfg.clone(),
            shininess: n,
            record_bits: self.layout.bits,
            record_bytes: self.layout.bytes() as u32,
            columns: columns(&self.layout),
            hex,
            bin,
            power_table,
            latency,
            initiation_interval,
            env_maps,
            pixels,
            image_size,
        };
        let mp = dir.join(format!("{}.json", self.stem));
        crate::render::output::write_atomic(&mp, (serde_json::to_string_pretty(&m).expect("json") + "\n").as_bytes())?;
        // A format or map this set leaves out goes with the set it belonged to: beside the new
        // manifest it would be taken for this set's.
        let listed: Vec<&str> = m.files().iter().map(|f| f.name.as_str()).collect();
        for stale in ["hex", "bin"]
            .map(|x| format!("{}.{x}", self.stem))
            .into_iter()
            .chain(["diffuse", "specular"].map(|w| env_map_name(&self.stem, w)))
            .chain([pixels_name(&self.stem)])
        {
            if !listed.contains(&stale.as_str()) {
                crate::commit::retire(&dir.join(stale))?;
            }
        }
        Ok(VectorSet {
            target: self.target,
            manifest: mp,
            count: self.count,
        })
    }
}

/// Write `text` to `name` in `dir` (atomically) and give its manifest entry, from the bytes
/// written: under `commit::together` the file is not in place yet.
fn write_listed(dir: &Path, name: String, text: &str) -> Result<FileEntry> {
    crate::render::output::write_atomic(&dir.join(&name), text.as_bytes())?;
    Ok(FileEntry {
        name,
        bytes: text.len() as u64,
        sha256: Sha256::digest(text.as_bytes()).iter().map(|b| format!("{b:02x}")).collect(),
    })
}

/// The pixels file of a scene's top set.
fn pixels_name(stem: &str) -> String {
    format!("{stem}_pixels.txt")
}

/// Each record's pixel (`x y`, decimal, a line a record, in the records' order; row 0 at the
/// top), beside a scene's top set: where its colour goes in the image.
fn write_pixels(dir: &Path, stem: &str, pixels: &[[u32; 2]]) -> Result<FileEntry> {
    let text: String = pixels.iter().map(|[x, y]| format!("{x} {y}\n")).collect();
    write_listed(dir, pixels_name(stem), &text)
}

/// The file of set `stem`'s `which` (`diffuse`, `specular`) environment map.
fn env_map_name(stem: &str, which: &str) -> String {
    format!("{stem}_env_{which}.hex")
}

/// The two maps of a set (`{stem}_env_diffuse.hex`, `{stem}_env_specular.hex`), as the
/// `env_fetch` units' init files are written, and their manifest entries.
pub fn write_env_maps(dir: &Path, stem: &str, cfg: &PipelineConfig, maps: &EnvMaps, command: &str) -> Result<EnvMapFiles> {
    let one = |which: &str, map: &[[u32; 3]]| -> Result<FileEntry> {
        let name = env_map_name(stem, which);
        let rom = crate::rtlgen::rom::env_map_rom(cfg, map, which, "a scene object's lighting");
        let text = crate::rtlgen::rom::write(
            &rom,
            crate::rtlgen::rom::RomFormat::Hex,
            &crate::rtlgen::rom::rom_header(&rom, Some(cfg), command, &format!("{which} environment map of this vector set")),
        );
        write_listed(dir, name, &text)
    };
    // Only the maps the top has a port for (one per blend of the configuration).
    let has = |which: &str| crate::rtlgen::top::env_map_names(cfg).contains(&which);
    Ok(EnvMapFiles {
        diffuse: has("diffuse").then(|| one("diffuse", &maps.diffuse)).transpose()?,
        specular: has("specular").then(|| one("specular", &maps.specular)).transpose()?,
    })
}

/// Whether target `unit` (the top, or a unit) exists in the hardware of `cfg`.
pub fn unit_present(cfg: &PipelineConfig, unit: &str) -> bool {
    unit == "top" || crate::units::unit(unit).is_some_and(|u| u.included(cfg))
}

/// Top stimuli of a source, grouped by the memories they run on.
fn top_groups(cfg: &PipelineConfig, src: &Source, o: &DumpOptions, dir: &Path, top: bool) -> Result<Vec<SceneGroup>> {
    Ok(match src {
        Source::Corners(level) => {
            let cat = corners(cfg, *level);
            // The catalogue beside the top set (`top`: it is a target), whose records it
            // names one for one: record number and why it is there. A unit's corner set
            // holds its inputs traced from these and then its own corners, not one for one.
            if top {
                let text: String = cat.iter().enumerate().map(|(i, (why, _))| format!("{i}\t{why}\n")).collect();
                crate::render::output::write_atomic(&dir.join(format!("{}_catalogue.txt", src.stem())), text.as_bytes())?;
            }
            vec![SceneGroup {
                shininess: o.shininess.unwrap_or(cfg.shininess),
                stem: src.stem(),
                stims: cat.into_iter().map(|c| c.1).collect(),
                env: None,
                pixels: None,
            }]
        }
        Source::Scene(name) => super::sources::scene_groups(cfg, name, o.size)?,
        _ => unreachable!(),
    })
}

/// Refuse `exhaustive:unit` for a configuration without the unit, the sweep's own condition
/// in the same fix, so following it is enough (checked before the targets are).
pub fn exhaustive_unit_present(cfg: &PipelineConfig, unit: &str) -> Result<()> {
    match crate::units::unit(unit) {
        Some(u) if !unit_present(cfg, unit) => {
            let also = u.exhaustive_when().map_or(String::new(), |w| format!(", and for the sweep {w}"));
            Err(Error::Other(format!("exhaustive:{unit}: {}{also}", crate::units::absence(u, cfg))))
        }
        _ => Ok(()),
    }
}

/// What to change when a dump will not fit, in the options of the command that asked for it
/// (`DumpOptions::command`, the invocation): `regress` and `fuzz` dump for themselves, into
/// their work folder, and have neither `--out` nor `--format`.
fn space_fix(command: &str) -> &'static str {
    let words = shell_words::split(command).unwrap_or_default();
    match crate::shell::subcommand_at(&words).map(|i| words[i].as_str()) {
        Some("fit") => "a --work folder on a larger disk, or --no-regress (no regression of the chosen configuration)",
        Some("regress") => "fewer --random or --random-icarus records, fewer --target, a --work folder on a larger disk, or --stream random:N (records piped to the simulator, no file written)",
        Some("fuzz") => "fewer --random records, or a --work folder on a larger disk",
        Some("render") => "a smaller --size, or a --work folder on a larger disk",
        Some("bench") => "a --work folder on a larger disk (bench writes its dump, then as many bytes again to time the disk)",
        _ => "fewer records, --format bin (the text files are the larger part), fewer --target, or an --out on a larger disk",
    }
}

/// Refuse, before anything is written, a random dump of `n` records per target whose files
/// would not fit the free space under `dir` (a dump that fills the disk fails only at the
/// end, and fills it for everyone else meanwhile).
pub fn check_space(cfg: &PipelineConfig, n: u64, targets: &[String], dir: &Path, o: &DumpOptions) -> Result<()> {
    let per_record: u64 = targets
        .iter()
        .map(|t| {
            let l = super::targets::layout(cfg, t);
            u64::from(o.binary) * l.bytes() as u64 + u64::from(o.text) * (l.hex_digits() as u64 + 1)
        })
        .sum();
    let need = per_record.saturating_mul(n);
    let Some(free) = crate::limits::free_bytes(dir) else {
        return Ok(());
    };
    if need > free {
        // In the unit the smaller figure reads in, so a small disk's figures are not both 0.0 GB.
        let (unit, scale) = if need.min(free) >= 1_000_000_000 {
            ("GB", 1e9)
        } else if need.min(free) >= 1_000_000 {
            ("MB", 1e6)
        } else {
            ("kB", 1e3)
        };
        return Err(Error::Other(format!(
            "{}: {n} records of {} target(s) need about {:.1} {unit}, and the disk under it has {:.1} {unit} free\n  fix: {}",
            dir.display(),
            targets.len(),
            need as f64 / scale,
            free as f64 / scale,
            space_fix(&o.command)
        )));
    }
    Ok(())
}

/// Refuse, before anything is written, a dump that cannot give a whole, non-empty set.
fn check(cfg: &PipelineConfig, src: &Source, targets: &[String], o: &DumpOptions) -> Result<()> {
    if let Source::Scene(name) = src {
        super::sources::scene_sets_made(cfg, &format!("--source scene:{name}"))?;
    }
    if let Some(n) = o.shininess {
        crate::limits::check_count("--shininess", n.into(), 0, crate::limits::MAX_SHININESS.into(), "MAX_SHININESS")?;
    }
    match src {
        Source::Exhaustive(unit) => {
            exhaustive_unit_present(cfg, unit)?;
            exhaustive_count(cfg, unit).map(|_| ())
        }
        Source::Scene(name) => {
            let s = crate::scene::Scene::load(name)?;
            s.check_config(cfg, &crate::config::origin())?;
            check_scene_names(cfg, &format!("--source scene:{name}"), name, &s, targets)?;
            let (w, h) = o.size.unwrap_or((s.size[0], s.size[1]));
            crate::limits::check_render(crate::limits::PixelUse::SceneVectors, &s.file, w, h, s.triangles())
        }
        Source::Corners(_) | Source::Random(_) => Ok(()),
    }
}

/// Dump `src` for `targets` ("top" and unit names) into `dir`.
pub fn dump(cfg: &PipelineConfig, src: &Source, targets: &[String], dir: &Path, o: &DumpOptions) -> Result<Vec<VectorSet>> {
    // A signal stops the dump through its error path, which removes the temporary files.
    let _cleanup = crate::interrupt::cleanup();
    let targets: Vec<String> = targets.iter().filter(|t| *t == "top" || unit_present(cfg, t)).cloned().collect();
    check(cfg, src, &targets, o)?;
    crate::render::output::make_folder(dir)?;
    if let Source::Random(n) = src {
        check_space(cfg, *n, &targets, dir, o)?;
    }
    if let (Source::Scene(name), true) = (src, cfg.embm()) {
        if let Some(t) = targets.iter().find(|t| t.starts_with("env_fetch")) {
            return Err(Error::Other(format!(
                "--source scene:{name} --target {t}: a scene's fragments read each object's own maps, which only the top loads (its env_diffuse_*/env_specular_* ports); the unit's own harness runs on the power-up map\n  fix: dump the scene for the top, and {t} from corners, random:N or exhaustive:{t}"
            )));
        }
    }
    let mut out = Vec::new();
    match src {
        Source::Exhaustive(unit) => {
            let stims = exhaustive(cfg, unit)?;
            let n = o.shininess.unwrap_or(cfg.shininess);
            let mem = MemoryContents::new(cfg, n);
            let stem = if o.shininess.is_some() {
                format!("{}_n{n}", src.stem())
            } else {
                src.stem()
            };
            let mut w = SetWriter::new(dir, &stem, unit, unit_layout(cfg, unit), o, u64::MAX)?;
            write_units(cfg, &mem.view(), &stims, &mut [&mut w])?;
            out.push(w.finish(dir, cfg, src, o, n)?);
        }
        Source::Random(n) => {
            let shin = o.shininess.unwrap_or(cfg.shininess);
            let contents = MemoryContents::new(cfg, shin);
            let mut ws = open(dir, &src.stem(), &targets, cfg, o, *n)?;
            let mem = &contents.view();
            const CHUNK: u64 = RANDOM_CHUNK;
            let chunks = n.div_ceil(CHUNK);
            let maker = TopRecords::new(cfg, *mem);
            let tl = &maker.layout;
            let batch = 4 * rayon::current_num_threads() as u64;
            // Encoding runs on the rayon pool while a writer thread hashes and writes the
            // previous batch, so the disk and the cores work at the same time.
            let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<(u64, Vec<TopStim>, String, Vec<u8>)>>(1);
            let want_units = ws.iter().any(|w| w.target != "top");
            // Binary buffers the writer is done with, for the next chunks: fresh ones would
            // each cost their pages' first-touch faults.
            let spare: std::sync::Mutex<Vec<Vec<u8>>> = Default::default();
            let spare = &spare;
            ws = std::thread::scope(|scope| -> Result<Vec<SetWriter>> {
                let writer = scope.spawn(move || -> Result<Vec<SetWriter>> {
                    for batch in rx {
                        for (len, stims, hex, bin) in batch {
                            for w in ws.iter_mut().filter(|w| w.target == "top") {
                                w.put_encoded(&hex, &bin, len)?;
                            }
                            if want_units && ws.iter().any(|w| w.target != "top" && !w.full()) {
                                write_tops(cfg, mem, &stims, &mut ws, false)?;
                            }
                            spare.lock().expect("buffer pool").push(bin);
                        }
                    }
                    Ok(ws)
                });
                let mut c0 = 0;
                while c0 < chunks {
                    let c1 = (c0 + batch).min(chunks);
                    // Unit vectors are derived from the first chunks only: each unit set stops at N.
                    let keep_stims = want_units && c0 * CHUNK < *n;
                    // Each chunk has its own stream, so chunks are generated in parallel and
                    // the bytes still depend on the seed alone.
                    let done = (c0..c1)
                        .into_par_iter()
                        .map(|c| {
                            let mut bin = spare.lock().expect("buffer pool").pop().unwrap_or_default();
                            bin.clear();
                            bin.reserve(CHUNK as usize * tl.bytes());
                            let mut hex = String::new();
                            let (len, stims) =
                                maker.random_chunk(o.seed, c, *n, o.binary.then_some(&mut bin), o.text.then_some(&mut hex), keep_stims)?;
                            Ok((len, stims, hex, bin))
                        })
                        .collect::<Result<Vec<(u64, Vec<TopStim>, String, Vec<u8>)>>>()?;
                    if tx.send(done).is_err() {
                        break;
                    }
                    c0 = c1;
                }
                drop(tx);
                writer.join().expect("writer thread")
            })?;
            for w in ws {
                out.push(w.finish(dir, cfg, src, o, shin)?);
            }
        }
        _ => {
            for g in top_groups(cfg, src, o, dir, targets.iter().any(|t| t == "top"))? {
                let (n, stims) = (g.shininess, &g.stims);
                let mem = MemoryContents::new(cfg, n).with_env(g.env.as_ref());
                let mut ws = open(dir, &g.stem, &targets, cfg, o, u64::MAX)?;
                write_tops(cfg, &mem.view(), stims, &mut ws, true)?;
                if matches!(src, Source::Corners(_)) {
                    // Each unit's own edges follow the ones the top corners reach.
                    let own: Vec<UnitStim> = ws
                        .iter()
                        .filter_map(|w| crate::units::unit(&w.target))
                        .flat_map(|u| {
                            u.corners(cfg)
                                .into_iter()
                                .map(move |(_, inputs)| UnitStim { unit: u.name(), inputs })
                        })
                        .collect();
                    let mut refs: Vec<&mut SetWriter> = ws.iter_mut().collect();
                    write_units(cfg, &mem.view(), &own, &mut refs)?;
                }
                // Every set of the group must hold vectors before any is finished.
                if let Some(w) = ws.iter().find(|w| w.count == 0) {
                    return Err(Error::Other(format!(
                        "{}: no vectors for target {}\n  fix: choose a source that exercises it",
                        w.stem, w.target
                    )));
                }
                for w in ws {
                    // The top loads the maps through its ports; a unit's harness has none.
                    // The pixels are the top's records' (a unit set is not one for one).
                    let (env, pixels) = match w.target == "top" {
                        true => (g.env.as_ref(), g.pixels.as_ref().map(|(px, image)| (&px[..], *image))),
                        false => (None, None),
                    };
                    out.push(w.finish_with(dir, cfg, src, o, n, env, pixels)?);
                }
            }
            if matches!(src, Source::Scene(_)) {
                retire_other_scene_sets(dir, src, &targets, &out)?;
            }
        }
    }
    Ok(out)
}

/// A scene's sets of an earlier dump into `dir` that this one did not write again (the
/// scene's objects grouped otherwise since: one power table where there were two), with
/// every file their manifests list: left beside the new sets, a regression would run them
/// and a testbench rebuilding the image from every pixels file would mix two scenes. Only a
/// manifest gbump wrote for the same source and one of `targets` is taken for one.
fn retire_other_scene_sets(dir: &Path, src: &Source, targets: &[String], written: &[VectorSet]) -> Result<()> {
    let base = src.stem();
    let ours: Vec<&std::ffi::OsStr> = written.iter().filter_map(|v| v.manifest.file_name()).collect();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let n = name.to_string_lossy();
        // A manifest of one of the scene's sets (`{base}_{target}.json`, `{base}_nS_...`);
        // its own source and target below say whether it is one this dump replaces.
        if !(n.starts_with(&format!("{base}_")) && n.ends_with(".json")) || ours.contains(&name.as_os_str()) {
            continue;
        }
        let Ok(m) = std::fs::read_to_string(e.path())
            .map_err(|_| ())
            .and_then(|t| serde_json::from_str::<Manifest>(&t).map_err(|_| ()))
        else {
            continue;
        };
        if m.source != src.to_string() || !targets.contains(&m.target) {
            continue;
        }
        for f in m.files() {
            // A listed name is a plain file name (`verify` refuses any other); never a path.
            if Path::new(&f.name).file_name() == Some(std::ffi::OsStr::new(&f.name)) {
                crate::commit::retire(&dir.join(&f.name))?;
            }
        }
        crate::commit::retire(&e.path())?;
    }
    Ok(())
}

fn open(dir: &Path, stem: &str, targets: &[String], cfg: &PipelineConfig, o: &DumpOptions, limit: u64) -> Result<Vec<SetWriter>> {
    targets
        .iter()
        .map(|t| {
            let l = super::targets::layout(cfg, t);
            SetWriter::new(dir, stem, t, l, o, limit)
        })
        .collect()
}

/// A unit stimulus with the model's outputs.
type UnitEval = (UnitStim, Vec<Vec<i64>>);

/// Write the records of `stims` for every writer (the top's only when `with_top`).
fn write_tops(cfg: &PipelineConfig, mem: &Memories, stims: &[TopStim], ws: &mut [SetWriter], with_top: bool) -> Result<()> {
    let want_units = ws.iter().any(|w| w.target != "top" && !w.full());
    let tl = top_layout(cfg);
    if with_top {
        // These records come from the readable model (its traces feed the unit sets); the
        // fast model must agree with them as with every other set.
        let mut colours = vec![[0u32; 3]; stims.len()];
        TopRecords::new(cfg, *mem).colours(0, stims, &mut colours)?;
    }
    // A chunk at a time: a scene's fragments held their every unit evaluation at once, a few
    // kB a fragment per light, which the memory plan did not count.
    let (mut line, mut bytes) = (String::new(), Vec::new());
    for stims in stims.chunks(RANDOM_CHUNK as usize) {
        let evals: Vec<(Record, Vec<UnitEval>)> = stims
            .par_iter()
            .map(|s| {
                let t = eval_top(cfg, mem, s);
                let units = if want_units {
                    unit_stims(cfg, s, &t)
                        .into_iter()
                        .filter(|u| unit_present(cfg, u.unit))
                        .map(|u| {
                            let out = eval_unit(cfg, mem, &u);
                            (u, out)
                        })
                        .collect()
                } else {
                    Vec::new()
                };
                (top_record(cfg, &tl, s, &t), units)
            })
            .collect();
        for (rec, units) in &evals {
            for w in ws.iter_mut() {
                if with_top && w.target == "top" {
                    w.put(rec, &mut line, &mut bytes)?;
                }
            }
            for (u, outs) in units {
                for w in ws.iter_mut().filter(|w| w.target == u.unit) {
                    let r = unit_record(&w.layout, u, outs);
                    w.put(&r, &mut line, &mut bytes)?;
                }
            }
        }
    }
    Ok(())
}

fn write_units(cfg: &PipelineConfig, mem: &Memories, stims: &[UnitStim], ws: &mut [&mut SetWriter]) -> Result<()> {
    let (mut line, mut bytes) = (String::new(), Vec::new());
    for s in stims {
        let outs = eval_unit(cfg, mem, s);
        for w in ws.iter_mut().filter(|w| w.target == s.unit) {
            let r = unit_record(&w.layout, s, &outs);
            w.put(&r, &mut line, &mut bytes)?;
        }
    }
    Ok(())
}
