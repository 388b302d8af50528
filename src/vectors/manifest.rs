//! Vector-set manifests, and the check that a set on disk is whole and unchanged before a
//! simulator is pointed at it.

use super::layout::Layout;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::io::Read;
use std::path::{Path, PathBuf};

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
// A key gbump does not write is an edit: refused, with its line.
#[serde(deny_unknown_fields)]
pub struct FileEntry {
    pub name: String,
    pub bytes: u64,
    pub sha256: String,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
// A key gbump does not write is an edit: refused, with its line.
#[serde(deny_unknown_fields)]
pub struct ColumnEntry {
    pub name: String,
    pub role: String,
    pub lsb: u32,
    pub width: u32,
    pub lanes: u32,
    pub format: String,
    /// Rising edges after its record's other inputs at which a stimulus column is sampled
    /// (`light_accumulate`'s `acc_in`: latency - 1); 0 for every other column. A set written
    /// before the key existed reads as 0, so only an older `light_accumulate` set is refused,
    /// as a layout of another version, with the command that regenerates it.
    #[serde(default)]
    pub enters: u32,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
// A key gbump does not write is an edit: refused, with its line.
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub generator: String,
    pub command: String,
    pub target: String,
    pub module: String,
    /// The source as the command line spells it (`random:N`, `scene:NAME`, `corners`);
    /// manifests before it were spelled `Random(N)`, `Scene("NAME")`, `Corners(1)`.
    pub source: String,
    /// The seed of a random set, which alone draws from one; other sources write none (a
    /// manifest before this read `1` for every set).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    pub count: u64,
    pub config_hash: String,
    pub config: crate::PipelineConfig,
    pub shininess: u32,
    pub record_bits: u32,
    pub record_bytes: u32,
    pub columns: Vec<ColumnEntry>,
    pub hex: Option<FileEntry>,
    pub bin: Option<FileEntry>,
    pub power_table: FileEntry,
    /// Edges from a record's first input edge to its outputs (the top: from accept to
    /// out_valid), and edges between records (a unit takes one per edge).
    pub latency: u32,
    pub initiation_interval: u32,
    /// EMBM scene sets: the object's two maps, loaded through the top's `env_diffuse_*` and
    /// `env_specular_*` ports before the run (other sets run on the power-up maps).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub env_maps: Option<EnvMapFiles>,
    /// Scene top sets: each record's pixel, `x y` a line (`vectors::writer::write_pixels`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pixels: Option<FileEntry>,
    /// Scene top sets: the image the pixels lie in, [width, height].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image_size: Option<[u32; 2]>,
}

/// A set's environment maps, as `gbump rom` writes the power-up ones: one for each blend
/// the configuration has (the top has no other map's port).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
// A key gbump does not write is an edit: refused, with its line.
#[serde(deny_unknown_fields)]
pub struct EnvMapFiles {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse: Option<FileEntry>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub specular: Option<FileEntry>,
}

impl EnvMapFiles {
    /// (the top's load-port prefix, the manifest key naming it, the file) of each map the
    /// set has.
    pub fn each(&self) -> Vec<(&'static str, &'static str, &FileEntry)> {
        [
            ("env_diffuse", "env_maps.diffuse.name", self.diffuse.as_ref()),
            ("env_specular", "env_maps.specular.name", self.specular.as_ref()),
        ]
        .into_iter()
        .filter_map(|(p, k, f)| Some((p, k, f?)))
        .collect()
    }
}

impl Manifest {
    /// Every file the manifest names beside itself: the data files, the power table and the
    /// maps.
    pub fn files(&self) -> Vec<&FileEntry> {
        self.named_files().into_iter().map(|(_, f)| f).collect()
    }

    /// [`Self::files`] with the key each is named under (`hex.name`, `env_maps.diffuse.name`).
    pub fn named_files(&self) -> Vec<(&'static str, &FileEntry)> {
        let mut v: Vec<(&'static str, &FileEntry)> = [
            ("hex.name", self.hex.as_ref()),
            ("bin.name", self.bin.as_ref()),
            ("power_table.name", Some(&self.power_table)),
            ("pixels.name", self.pixels.as_ref()),
        ]
        .into_iter()
        .filter_map(|(k, f)| Some((k, f?)))
        .collect();
        if let Some(e) = &self.env_maps {
            v.extend(e.each().into_iter().map(|(_, k, f)| (k, f)));
        }
        v
    }
}

pub fn columns(l: &Layout) -> Vec<ColumnEntry> {
    l.columns
        .iter()
        .map(|c| ColumnEntry {
            name: c.name.clone(),
            role: format!("{:?}", c.role).to_lowercase(),
            lsb: c.lsb,
            width: c.width,
            lanes: c.lanes,
            format: c.format.clone(),
            enters: c.enters,
        })
        .collect()
}

/// sha256 of a file, hex.
pub fn sha256_file(p: &Path) -> Result<(u64, String)> {
    sha256_visit(p, |_, _| {})
}

/// [`sha256_file`], handing every block read to `see` with its offset in the file (so a
/// check of the contents costs no second read).
fn sha256_visit(p: &Path, mut see: impl FnMut(u64, &[u8])) -> Result<(u64, String)> {
    // A pipe in a data file's place would hang the open; every file a set names is hashed here.
    crate::limits::check_not_pipe(p, "put back the regular file `gbump vectors` wrote, or regenerate the set")?;
    let mut f = std::fs::File::open(p).map_err(|e| Error::io(p, e))?;
    // A set's file is an input of the run: no result (`--junit`, say) may be written over it.
    crate::limits::note_input(p);
    let mut h = Sha256::new();
    let mut buf = vec![0u8; 1 << 20];
    let mut n = 0u64;
    loop {
        let k = f.read(&mut buf).map_err(|e| Error::io(p, e))?;
        if k == 0 {
            break;
        }
        see(n, &buf[..k]);
        n += k as u64;
        h.update(&buf[..k]);
    }
    Ok((n, h.finalize().iter().map(|b| format!("{b:02x}")).collect()))
}

/// The first binary record (0-based) whose last byte sets a bit above the record's bits:
/// the harness would drop it unseen, so a file carrying one is not what the writer made.
struct PaddingCheck {
    record_bytes: u64,
    /// The bits of a record's last byte that must be zero.
    mask: u8,
    first_bad: Option<u64>,
}

impl PaddingCheck {
    fn new(m: &Manifest) -> PaddingCheck {
        let used = m.record_bits % 8;
        PaddingCheck {
            record_bytes: m.record_bytes.max(1) as u64,
            mask: if used == 0 { 0 } else { !((1u8 << used) - 1) },
            first_bad: None,
        }
    }

    fn see(&mut self, at: u64, block: &[u8]) {
        if self.mask == 0 || self.first_bad.is_some() {
            return;
        }
        let r = self.record_bytes;
        // The offset of the first record end within this block.
        let mut i = (r - 1 - at % r) % r;
        while (i as usize) < block.len() {
            if block[i as usize] & self.mask != 0 {
                self.first_bad = Some((at + i) / r);
                return;
            }
            i += r;
        }
    }
}

/// What a set of `target` names about its module: (module name, latency, initiation
/// interval), as the writer states them and the checker expects them.
pub fn timing(cfg: &crate::PipelineConfig, target: &str) -> (String, u32, u32) {
    if target == "top" {
        (
            crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline"),
            crate::rtlgen::top::latency(cfg),
            cfg.initiation_interval(),
        )
    } else {
        let latency = crate::units::unit(target).map_or(1, |u| u.latency(cfg));
        (crate::rtlgen::units_v::module_name(cfg, target), latency, 1)
    }
}

/// The manifest's own fields against each other: its configuration is a valid one and the
/// one its hash names, its target is a set this configuration has, its record layout is that
/// target's, its shininess in range. The data files' checksums cannot see an edited manifest.
fn check_fields(manifest: &Path, m: &Manifest) -> Result<()> {
    // `gbump vectors` writes at least one of the two (`--format`); a set with neither has no
    // records to run.
    if m.hex.is_none() && m.bin.is_none() {
        return Err(Error::Other(format!(
            "{}: names neither a `hex` nor a `bin` file, so the set has no records: the manifest was edited\n  fix: regenerate the set with: {}",
            manifest.display(),
            regenerate_into(&recorded_command(m), &folder_of(manifest))
        )));
    }
    // An EMBM scene's top set runs on its object's maps, one for each map the top has; no
    // other set names any.
    let scene_top = m.config.embm() && m.target == "top" && matches!(manifest_source(&m.source), Some(super::sources::Source::Scene(_)));
    let want: Vec<&str> = crate::rtlgen::top::env_map_memories(&m.config).iter().map(|x| x.prefix).collect();
    let have: Vec<&str> = m
        .env_maps
        .as_ref()
        .map_or_else(Vec::new, |e| e.each().into_iter().map(|(p, _, _)| p).collect());
    if scene_top && have != want {
        return Err(Error::Other(format!(
            "{}: an EMBM scene set runs on its object's maps ({}), but the manifest names {}: the manifest was edited\n  fix: regenerate the set with `gbump vectors`",
            manifest.display(),
            want.join(", "),
            if have.is_empty() { "none".to_string() } else { have.join(", ") }
        )));
    }
    if m.env_maps.is_some() && !scene_top {
        return Err(Error::Other(format!(
            "{}: names environment maps, which only an EMBM configuration's top set of a scene loads (target {}, env_map_bits = {}): the manifest was edited\n  fix: regenerate the set with `gbump vectors`",
            manifest.display(),
            m.target,
            m.config.env_map_bits
        )));
    }
    let file = manifest.display().to_string();
    let dir = folder_of(manifest);
    let regen = format!("regenerate the set with: {}", regenerate_into(&recorded_command(&m), &dir));
    // A configuration refused by today's rules (a set from an older gbump, an edited manifest)
    // is fixed by regenerating the set, not by editing the manifest.
    m.config
        .validate(&file)
        .map_err(|e| Error::field(&file, "config", e.to_string(), &regen))?;
    if m.config.hash() != m.config_hash {
        return Err(Error::field(
            &file,
            "config",
            format!(
                "the configuration's hash is {}, not the config_hash {} the set names",
                m.config.hash(),
                m.config_hash
            ),
            regen,
        ));
    }
    if !super::writer::unit_present(&m.config, &m.target) {
        return Err(Error::field(
            &file,
            "target",
            format!("`{}` is not `top` or a unit of this configuration", m.target),
            regen,
        ));
    }
    if m.shininess > crate::limits::MAX_SHININESS {
        return Err(Error::field(
            &file,
            "shininess",
            format!("{} is above MAX_SHININESS = {}", m.shininess, crate::limits::MAX_SHININESS),
            regen,
        ));
    }
    let l = super::targets::layout(&m.config, &m.target);
    let (module, latency, ii) = timing(&m.config, &m.target);
    // The module and the columns of another target of the configuration: the `target` was
    // edited, and the set is that target's (the fix regenerates that one).
    let owner = super::targets::resolve(&m.config, &["all".to_string()])
        .unwrap_or_default()
        .into_iter()
        .find(|t| t != &m.target && timing(&m.config, t).0 == m.module && columns(&super::targets::layout(&m.config, t)) == m.columns);
    if let Some(owner) = owner {
        let fixed = Manifest {
            target: owner.clone(),
            ..m.clone()
        };
        return Err(Error::field(
            &file,
            "target",
            format!(
                "`{}` is not this set's target: its module {} and record columns are `{owner}`'s",
                m.target, m.module
            ),
            format!("regenerate the set with: {}", regenerate_into(&recorded_command(&fixed), &dir)),
        ));
    }
    if m.module != module || m.latency != latency || m.initiation_interval != ii {
        // The first of the three that differs is the field named.
        let field = if m.module != module {
            "module"
        } else if m.latency != latency {
            "latency"
        } else {
            "initiation_interval"
        };
        return Err(Error::field(
            &file,
            field,
            format!(
                "module {}, latency {}, interval {} are not this configuration's {} ({module}, {latency}, {ii})",
                m.module, m.latency, m.initiation_interval, m.target
            ),
            regen,
        ));
    }
    let want = columns(&l);
    if m.record_bits != l.bits || m.record_bytes as usize != l.bytes() || m.columns != want {
        // The first column that differs, by place: what an edit or a reorder changed.
        let differs = (0..want.len().max(m.columns.len()))
            .find(|&i| m.columns.get(i) != want.get(i))
            .map(|i| {
                let say = |c: Option<&ColumnEntry>| {
                    c.map_or("nothing".to_string(), |c| {
                        format!(
                            "`{}` ({}, {}) at lsb {}, {} bits x {} lanes, entering {} edge(s) late",
                            c.name, c.role, c.format, c.lsb, c.width, c.lanes, c.enters
                        )
                    })
                };
                format!(
                    "; column {i} is {} where the layout has {}",
                    say(m.columns.get(i)),
                    say(want.get(i))
                )
            });
        return Err(Error::field(
            &file,
            "columns",
            format!(
                "the record layout ({} bits, {} bytes, {} columns) is not the {} layout of this configuration ({} bits, {} bytes, {} columns){}",
                m.record_bits,
                m.record_bytes,
                m.columns.len(),
                m.target,
                l.bits,
                l.bytes(),
                want.len(),
                differs.unwrap_or_default()
            ),
            regen,
        ));
    }
    Ok(())
}

/// Load a manifest and check every file it names: present, right size, same sha256.
pub fn verify(manifest: &Path) -> Result<(Manifest, PathBuf)> {
    let dir = folder_of(manifest);
    let m = read_fields(manifest)?;
    check_files(manifest, m, dir)
}

/// A manifest read and its fields checked against each other (not its data files: see
/// [`verify`]), for a caller that only needs its configuration before the files are read.
pub fn read_fields(manifest: &Path) -> Result<Manifest> {
    let text = crate::limits::read_text_as(
        manifest,
        "a gbump vector manifest",
        "give the set's .json manifest (`gbump vectors` writes it beside the .hex and .bin files)",
    )?;
    let m: Manifest = serde_json::from_str(&text).map_err(|e| {
        // A data file of a set given in place of its manifest: name the manifest beside it.
        let data = manifest.extension().and_then(|x| x.to_str()).filter(|x| ["hex", "bin"].contains(x));
        let fix = match data {
            Some(x) => format!(
                "give the set's manifest, {} (the .{x} file is one of the data files it lists)",
                manifest.with_extension("json").display()
            ),
            None => "give a set's .json manifest as `gbump vectors` writes it, or regenerate the set with `gbump vectors`".into(),
        };
        Error::Input {
            file: manifest.display().to_string(),
            line: e.line(),
            // serde_json counts columns from 1, and says 0 before a line's first character.
            col: e.column().max(1),
            msg: format!("not a gbump vector manifest: {e}"),
            fix,
        }
    })?;
    check_fields(manifest, &m)?;
    // A manifest names files beside itself, never elsewhere.
    for (key, f) in m.named_files() {
        crate::names::check(&manifest.display().to_string(), key, &f.name)?;
    }
    Ok(m)
}

/// The data files of a manifest whose fields were checked: names, sizes, checksums, records.
fn check_files(manifest: &Path, m: Manifest, dir: PathBuf) -> Result<(Manifest, PathBuf)> {
    if m.count == 0 {
        return Err(Error::Other(format!(
            "{}: the set holds no vectors\n  fix: a regression over zero vectors proves nothing; regenerate with a non-empty source",
            manifest.display()
        )));
    }
    let files = m.files();
    let regen = regenerate_into(&recorded_command(&m), &dir);
    let mut padding = PaddingCheck::new(&m);
    for f in files {
        let p = dir.join(&f.name);
        if !p.exists() {
            return Err(Error::Other(format!(
                "{}: named by its manifest {} but not there (moved, deleted, or the manifest copied without it)\n  fix: copy the set's files together, or regenerate with: {regen}",
                p.display(),
                manifest.display()
            )));
        }
        let is_bin = m.bin.as_ref().is_some_and(|b| std::ptr::eq(b, f));
        let (bytes, sha) = sha256_visit(&p, |at, block| {
            if is_bin {
                padding.see(at, block)
            }
        })?;
        if bytes != f.bytes || sha != f.sha256 {
            // One extra byte a line is what a CRLF conversion does to a text set.
            let is_hex = m.hex.as_ref().is_some_and(|h| std::ptr::eq(h, f));
            let crlf = is_hex && f.bytes > 0 && bytes == f.bytes + m.count;
            let (why, fix) = if crlf {
                (
                    "its lines end in CRLF (one byte more per record)",
                    "convert it back to LF line ends (dos2unix), or regenerate with",
                )
            } else {
                ("truncated, corrupted or from another run", "regenerate with")
            };
            return Err(Error::Other(format!(
                "{}: does not match its manifest {} ({} bytes, sha256 {}…; expected {} bytes, sha256 {}…): {why}\n  fix: {fix}: {regen}",
                p.display(),
                manifest.display(),
                bytes,
                &sha[..12],
                f.bytes,
                &f.sha256[..12.min(f.sha256.len())]
            )));
        }
    }
    if let Some(b) = &m.bin {
        if b.bytes != m.count * m.record_bytes as u64 {
            return Err(Error::Other(format!(
                "{}: {} bytes is not {} records of {} bytes\n  fix: regenerate with: {regen}",
                dir.join(&b.name).display(),
                b.bytes,
                m.count,
                m.record_bytes,
            )));
        }
    }
    if let (Some(b), Some(r)) = (&m.bin, padding.first_bad) {
        return Err(Error::Other(format!(
            "{}: record {r} sets a bit above the record's {} bits (its last byte's top bits are padding, always zero)\n  fix: the set is not as `gbump vectors` wrote it; regenerate with: {regen}",
            dir.join(&b.name).display(),
            m.record_bits
        )));
    }
    // A checksum proves only that the file is the one the manifest names; a manifest edited
    // beside an edited file proves nothing, so the text records are read as the simulators
    // will read them: as many lines as the set's count, each one record's digits, no bit
    // above the record. Where the set has both files (Icarus reads the text, Verilator the
    // binary), they must hold the same records, or the two simulators judge different sets.
    check_power_table(&dir.join(&m.power_table.name), &m, &regen)?;
    if let Some(e) = &m.env_maps {
        for (_, _, f) in e.each() {
            check_env_map(&dir.join(&f.name), &m, &regen)?;
        }
    }
    if let Some(h) = &m.hex {
        let bin = m.bin.as_ref().map(|b| dir.join(&b.name));
        check_hex_records(&dir.join(&h.name), bin.as_deref(), &m, &regen)?;
    }
    Ok((m, dir))
}

/// The command that made `m`, as a fix may repeat it: its recorded `command` when that is a
/// `gbump vectors` command naming the manifest's own source, else one made from the
/// manifest's fields, so that an edited manifest's command, or one `gbump vectors` does not
/// take (a regression's), is never repeated to the user as a fix.
pub fn recorded_command(m: &Manifest) -> String {
    use super::sources::Source;
    use crate::shell::{option_value, quoted, subcommand_at};
    let src = manifest_source(&m.source);
    let words = shell_words::split(&m.command).unwrap_or_default();
    // gbump records itself as plain `gbump`: a path is an edit.
    let gbump = words.first().is_some_and(|w| w == "gbump");
    let vectors = subcommand_at(&words).is_some_and(|i| words[i] == "vectors");
    // The source as typed (`random:1_000_000`, `--level 2`).
    let named = option_value(&words, "--source")
        .and_then(|s| Source::parse(s).ok())
        .map(|s| with_level(s, option_value(&words, "--level").and_then(|l| l.parse().ok())));
    if gbump && vectors && src.is_some() && named == src {
        return m.command.clone();
    }
    let spelt = src.as_ref().map_or(m.source.clone(), Source::to_string);
    // A scene's path may hold spaces: only the level is split off.
    let (source, level) = match spelt.split_once(" --level ") {
        Some((s, l)) => (s, format!(" --level {l}")),
        None => (spelt.as_str(), String::new()),
    };
    let mut cmd = format!("gbump vectors --source {}{level}", quoted(source));
    if let (Some(Source::Random(_)), Some(seed)) = (&src, m.seed) {
        cmd += &format!(" --seed {seed}");
    }
    // A scene's sets take their shininess from its objects.
    if m.shininess != m.config.shininess && !matches!(src, Some(Source::Scene(_))) {
        cmd += &format!(" --shininess {}", m.shininess);
    }
    cmd + &format!(" --target {} --config CONFIG.toml", quoted(&m.target))
}

/// `src` at corner level `level`, where one is given (`--level` applies to corners alone).
fn with_level(src: super::sources::Source, level: Option<u8>) -> super::sources::Source {
    match (src, level) {
        (super::sources::Source::Corners(_), Some(l)) => super::sources::Source::Corners(l),
        (src, _) => src,
    }
}

/// A manifest's `source` as a [`Source`](super::sources::Source): spelt as the command line
/// spells it (`random:20`, `corners --level 2`, `scene:FILE`), or as older manifests wrote it
/// (`Random(20)`, `Corners(2)`, `Scene("wall")`, `Exhaustive("power")`); None for anything
/// else (an edited manifest).
fn manifest_source(source: &str) -> Option<super::sources::Source> {
    use super::sources::Source;
    // A scene file's path is taken as written, as `--source scene:` took it.
    if let Some(n) = source.strip_prefix("scene:") {
        return Some(Source::Scene(n.to_string()));
    }
    let old = source.strip_suffix(')').and_then(|s| s.split_once('('));
    Some(match old.map(|(kind, arg)| (kind, arg.trim_matches('"'))) {
        Some(("Random", n)) => Source::Random(n.parse().ok()?),
        Some(("Corners", l)) => Source::Corners(l.parse().ok()?),
        Some(("Scene", n)) => Source::Scene(n.to_string()),
        Some(("Exhaustive", u)) => Source::Exhaustive(u.to_string()),
        Some(_) => return None,
        None => {
            let (s, level) = match source.split_once(" --level ") {
                Some((s, l)) => (s, Some(l.parse().ok()?)),
                None => (source, None),
            };
            with_level(Source::parse(s).ok()?, level)
        }
    })
}

/// `command` (the one that wrote a set, its words shell-quoted) writing into `dir` instead of
/// its own `--out`, so the fix a failed check prints regenerates the set it found wherever it
/// now lies: [`regenerate_words`] quoted for a shell, and [`relative_note`].
pub fn regenerate_into(command: &str, dir: &Path) -> String {
    let words = regenerate_words(command, dir);
    quoted_words(&words) + &relative_note(&words)
}

/// The words of `command` with its `--out` set to `dir`. Words are split as a POSIX shell
/// would, so a quoted `--out 'my dir'` is one word.
pub fn regenerate_words(command: &str, dir: &Path) -> Vec<String> {
    let d = dir.display().to_string();
    let d = if d.is_empty() { ".".to_string() } else { d };
    // A command that does not split as shell words (an edited manifest) splits at spaces.
    let mut words = shell_words::split(command).unwrap_or_else(|_| command.split_whitespace().map(str::to_string).collect());
    match words.iter().position(|w| w == "--out" || w.starts_with("--out=")) {
        Some(i) if words[i] == "--out" && i + 1 < words.len() => words[i + 1] = d,
        Some(i) => words[i] = format!("--out={d}"),
        None => words.extend(["--out".to_string(), d]),
    }
    words
}

pub use crate::shell::quoted_words;

/// A configuration or scene file named relative to where the set was made (`--config F`,
/// `--scene F`, `--source scene:F`) is found only from there (the manifest does not record
/// that folder): a note saying so, or nothing.
pub fn relative_note(words: &[String]) -> String {
    let relative: Vec<&str> = words
        .iter()
        .enumerate()
        .filter_map(|(i, w)| {
            let (flag, v) = match w.split_once('=') {
                Some((f, v)) if f.starts_with("--") => (f, v),
                _ if i + 1 < words.len() => (w.as_str(), words[i + 1].as_str()),
                _ => return None,
            };
            match flag {
                "--config" | "--scene" => Some(v),
                "--source" => v.strip_prefix("scene:"),
                _ => None,
            }
        })
        .filter(|v| v.ends_with(".toml") && Path::new(v).is_relative())
        .collect();
    if relative.is_empty() {
        return String::new();
    }
    format!(
        " (from the folder the set was made in: {} relative to it)",
        relative.iter().map(|f| format!("`{f}` is")).collect::<Vec<_>>().join(", ")
    )
}

/// A set's map holds one word per texel, each within the map's {B, G, R} width (the files'
/// checksums cannot see an edited manifest beside an edited map).
fn check_env_map(path: &Path, m: &Manifest, regen: &str) -> Result<()> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let side = m.config.env_map_side() as usize;
    let bits = 3 * m.config.colour_bits;
    let words: Vec<&str> = text
        .lines()
        .map(|l| l.split("//").next().unwrap_or("").trim())
        .filter(|l| !l.is_empty())
        .collect();
    let bad = words
        .iter()
        .position(|w| u64::from_str_radix(w, 16).map_or(true, |v| bits < 64 && v >> bits != 0));
    if words.len() != side * side || bad.is_some() {
        return Err(Error::Other(format!(
            "{}: {} words where the {side}x{side} map has {} of {bits} bits{}: the map or its manifest was edited\n  fix: regenerate with: {regen}",
            path.display(),
            words.len(),
            side * side,
            bad.map_or(String::new(), |i| format!(" (word {i}, `{}`, is not one)", words[i]))
        )));
    }
    Ok(())
}

/// The folder a manifest's files lie in: its parent, `.` for a bare file name.
fn folder_of(manifest: &Path) -> PathBuf {
    match manifest.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Every line of a set's text records: `m.count` lines of `hex_digits` hex digits whose
/// value fits `record_bits`, each the same record as the binary file's (`bin`), if any.
fn check_hex_records(p: &Path, bin: Option<&Path>, m: &Manifest, regen: &str) -> Result<()> {
    use std::io::BufRead;
    let digits = (m.record_bits as usize).div_ceil(4);
    // The top digit holds this many of the record's bits.
    let top_bits = m.record_bits as usize - 4 * (digits - 1);
    let bad = |line: u64, what: String| Error::Input {
        file: p.display().to_string(),
        line: line as usize,
        col: 1,
        msg: what,
        fix: format!("the set is not as `gbump vectors` wrote it; regenerate with: {regen}"),
    };
    let f = std::fs::File::open(p).map_err(|e| Error::io(p, e))?;
    let mut bin = match bin {
        Some(b) => Some((
            b,
            std::io::BufReader::with_capacity(1 << 20, std::fs::File::open(b).map_err(|e| Error::io(b, e))?),
        )),
        None => None,
    };
    let mut record = vec![0u8; m.record_bytes as usize];
    let mut first_differing = None;
    let mut n = 0u64;
    for line in std::io::BufReader::with_capacity(1 << 20, f).split(b'\n') {
        let line = line.map_err(|e| Error::io(p, e))?;
        n += 1;
        if line.is_empty() || line == b"\r" {
            // A blank line (an editor's extra newline at the end, say) is not a record.
            return Err(bad(
                n,
                format!("an empty line; every line is one record of {digits} hex digits (delete the empty line, or regenerate the set)"),
            ));
        }
        if n > m.count {
            return Err(bad(n, format!("more records than the {} the manifest counts", m.count)));
        }
        if n == 1 && line.starts_with(b"\xEF\xBB\xBF") {
            // An editor that saved the file as "UTF-8 with BOM".
            return Err(bad(
                n,
                "the file starts with a UTF-8 byte-order mark (3 bytes before the first digit); gbump writes none: save it without the mark, or regenerate the set".to_string(),
            ));
        }
        if line.len() == digits + 1 && line.last() == Some(&b'\r') {
            // An editor or a transfer that wrote Windows line ends.
            return Err(bad(
                n,
                "the line ends in a carriage return (CRLF line ends); gbump writes LF only, convert the file back (dos2unix) or regenerate it".to_string(),
            ));
        }
        if line.len() != digits {
            return Err(bad(
                n,
                format!(
                    "{} characters; a record of {} bits is {digits} hex digits",
                    line.len(),
                    m.record_bits
                ),
            ));
        }
        if let Some(k) = line.iter().position(|c| !c.is_ascii_hexdigit()) {
            return Err(bad(n, format!("character {} ({:?}) is not a hex digit", k + 1, line[k] as char)));
        }
        let top = (line[0] as char).to_digit(16).unwrap_or(0);
        if top >> top_bits != 0 {
            return Err(bad(
                n,
                format!(
                    "the first digit {:?} sets a bit above the record's {} bits",
                    line[0] as char, m.record_bits
                ),
            ));
        }
        if let Some((b, r)) = &mut bin {
            use std::io::Read;
            r.read_exact(&mut record).map_err(|e| Error::io(*b, e))?;
            // Byte j of the little-endian binary record is the text's digit pair j from the end.
            let digit = |i: usize| (line[i] as char).to_digit(16).unwrap_or(0) as u8;
            let differs = record.iter().enumerate().position(|(j, &byte)| {
                let lo = digits - 1 - 2 * j;
                let hi = if lo > 0 { digit(lo - 1) } else { 0 };
                byte != hi << 4 | digit(lo)
            });
            // Said after the whole file is read: a line missing or added shows as every
            // later record differing, and the count says it better.
            if let (Some(j), None) = (differs, &first_differing) {
                first_differing = Some(bad(
                    n,
                    format!(
                        "record {} is not the binary file's record {} ({}, byte {j} differs): Icarus reads the text and Verilator the binary, so the two would judge different vectors",
                        n - 1,
                        n - 1,
                        b.display()
                    ),
                ));
            }
        }
    }
    if n != m.count {
        return Err(bad(n, format!("{n} records; the manifest counts {}", m.count)));
    }
    first_differing.map_or(Ok(()), Err)
}

/// The set's power table holds the words of the manifest's shininess under its configuration
/// (a manifest whose `shininess` was edited would otherwise load one table and expect
/// another's results, and drop the power-up run it thinks does not apply).
fn check_power_table(p: &Path, m: &Manifest, regen: &str) -> Result<()> {
    let data = |text: &str| -> Vec<String> {
        text.lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with("//"))
            .map(str::to_ascii_lowercase)
            .collect()
    };
    let rom = crate::rtlgen::rom::power_rom(&m.config, m.shininess);
    let want = data(&crate::rtlgen::rom::write(&rom, crate::rtlgen::rom::RomFormat::Hex, &[]));
    let got = data(&crate::limits::read_text(p)?);
    if let Some(i) = (0..want.len().max(got.len())).find(|&i| want.get(i) != got.get(i)) {
        return Err(Error::Other(format!(
            "{}: word {i} of the power table is {}, but the table of shininess {} (the manifest's) under this configuration has {}: the manifest or the table was edited\n  fix: regenerate with: {regen}",
            p.display(),
            got.get(i).map_or("missing", String::as_str),
            m.shininess,
            want.get(i).map_or("no such word", String::as_str),
        )));
    }
    Ok(())
}
