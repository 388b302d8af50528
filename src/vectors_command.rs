//! `gbump vectors`: one dump from the command's choices. A flag the source ignores is
//! refused (it would let a user believe the set is something it is not), a scene source
//! targets the scene's own configuration unless one is given, and a failed dump leaves no
//! partial set behind. (Its place is `vectors/`, which is being rewritten; see ARCHITECTURE.)

use crate::error::Result;
use crate::scene::Scene;
use crate::vectors::{dump, DumpOptions, Source};
use std::path::Path;

/// What `gbump vectors` was asked for.
pub struct VectorsRequest<'a> {
    /// `scene:NAME | corners | random:N | exhaustive:UNIT`.
    pub source: &'a str,
    /// `all`, `top`, or unit names.
    pub targets: &'a [String],
    /// `--config` and `--scene`.
    pub config: Option<&'a Path>,
    pub scene: Option<&'a str>,
    pub out: &'a Path,
    pub seed: Option<u64>,
    /// Which files to write.
    pub text: bool,
    pub binary: bool,
    /// `WxH`, scene sources only.
    pub size: Option<&'a str>,
    /// Corner-catalogue level, corner sources only.
    pub level: Option<u8>,
    pub shininess: Option<u32>,
    /// The command line, for the files' headers.
    pub command: String,
}

/// Dump the vectors; one line per set and a total to `say`.
pub fn vectors(r: &VectorsRequest, say: &mut dyn FnMut(&str) -> Result<()>) -> Result<()> {
    let source = r.source;
    let mut src = Source::parse(source)?;
    let spelling = crate::vectors::choices::Spelling::cli(source);
    let asked = crate::vectors::choices::Asked {
        seed: r.seed.is_some(),
        shininess: r.shininess,
        size: r.size.is_some(),
        level: r.level.is_some(),
    };
    crate::vectors::choices::refuse_ignored(&src, &asked, &spelling)?;
    if let Source::Corners(l) = &mut src {
        *l = r.level.unwrap_or(1);
    }
    let seed = r.seed.unwrap_or(1);
    // Every flag is checked before anything is loaded or said.
    let size = r.size.map(|s| crate::limits::parse_size("--size", s)).transpose()?;
    // A scene source renders under the scene's own configuration unless one is given, and says so.
    let cfg = match (&src, r.config, r.scene) {
        (Source::Scene(name), None, None) => {
            let c = Scene::load(name)?.derive_config()?;
            own_config_note(&format!("--source {source}"), name, &c);
            c
        }
        _ => crate::scene::pick_config(r.config, r.scene)?,
    };
    if let Source::Exhaustive(u) = &src {
        crate::vectors::writer::exhaustive_unit_present(&cfg, u)?;
    }
    let mut targets = crate::vectors::targets::resolve(&cfg, r.targets)?;
    if let (Source::Scene(_), true, false) = (&src, cfg.embm(), r.targets.iter().any(|t| t.starts_with("env_fetch"))) {
        // A scene's fragments read each object's maps, which only the top loads: `all` leaves
        // the map readers' own sets out (named, they are refused with the reason).
        let skipped: Vec<String> = targets.iter().filter(|t| t.starts_with("env_fetch")).cloned().collect();
        if !skipped.is_empty() {
            targets.retain(|t| !t.starts_with("env_fetch"));
            eprintln!(
                "note: --source {source}: {} left out (a scene's fragments read each object's own maps, which only the top loads)",
                skipped.join(", ")
            );
        }
    }
    if let Source::Exhaustive(u) = &src {
        // An exhaustive source sweeps one unit's inputs: it writes that unit's set only.
        if r.targets.iter().any(|t| t != "all" && t != u) {
            return Err(spelling.ignored("--target", &format!("an exhaustive source writes the set of its unit `{u}` only")));
        }
    }
    // The targets whose sets this dump writes.
    let written: Vec<&str> = match &src {
        Source::Exhaustive(u) => vec![u.as_str()],
        _ => targets.iter().map(String::as_str).collect(),
    };
    crate::vectors::choices::refuse_unservable(&cfg, &written, &asked, &spelling)?;
    let opts = DumpOptions {
        text: r.text,
        binary: r.binary,
        seed,
        size,
        command: r.command.clone(),
        shininess: r.shininess,
    };
    let t0 = std::time::Instant::now();
    let before = set_configs(r.out);
    // Every set lands together or none does: a failed or interrupted dump over an earlier one
    // leaves the earlier one whole.
    let sets = crate::render::output::undo_on_error(r.out, || crate::commit::together(|| dump(&cfg, &src, &targets, r.out, &opts)))?;
    let secs = t0.elapsed().as_secs_f64();
    mixed_folder_warning(r.out, &cfg.hash(), &before, &sets);
    for s in &sets {
        say(&format!("{:18} {:>10} vectors  {}", s.target, s.count, s.manifest.display()))?;
    }
    let total: u64 = sets.iter().map(|s| s.count).sum();
    say(&format!("{total} vectors for config {} in {secs:.2} s", cfg.hash()))
}

/// The configuration hash of every vector manifest in `dir`, by file name (a file that is
/// not one is passed over).
fn set_configs(dir: &std::path::Path) -> std::collections::BTreeMap<String, String> {
    // Only a vector manifest has both keys (an interface JSON has a config_hash alone).
    #[derive(serde::Deserialize)]
    struct Hash {
        config_hash: String,
        #[allow(dead_code)]
        record_bits: u32,
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Default::default();
    };
    entries
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "json") && e.metadata().is_ok_and(|m| m.is_file() && m.len() < 1 << 20))
        .filter_map(|e| {
            let text = std::fs::read_to_string(e.path()).ok()?;
            let h: Hash = serde_json::from_str(&text).ok()?;
            Some((e.file_name().to_string_lossy().into_owned(), h.config_hash))
        })
        .collect()
}

/// Set files are named by source and target, not configuration: a dump into a folder that
/// held another configuration's sets replaced those of the same names and left the others
/// beside its own, silently (a testbench that opens `corners_dot_clamp.hex` by name then reads
/// records of another width, and `gbump regress` refuses the folder). Say both.
fn mixed_folder_warning(
    dir: &std::path::Path,
    hash: &str,
    before: &std::collections::BTreeMap<String, String>,
    sets: &[crate::vectors::VectorSet],
) {
    // A manifest's name and the start of its hash (any text a file holds: cut by characters).
    let named = |n: &str, h: &str| format!("{n} (config {})", h.chars().take(8).collect::<String>());
    let written: Vec<String> = sets
        .iter()
        .filter_map(|s| s.manifest.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    let replaced: Vec<String> = written
        .iter()
        .filter_map(|n| before.get(n).filter(|h| *h != hash).map(|h| named(n, h)))
        .collect();
    let beside: Vec<String> = set_configs(dir)
        .into_iter()
        .filter(|(n, h)| h != hash && !written.contains(n))
        .map(|(n, h)| named(&n, &h))
        .collect();
    if replaced.is_empty() && beside.is_empty() {
        return;
    }
    let mut what = Vec::new();
    if !replaced.is_empty() {
        what.push(format!(
            "replaced another configuration's set(s) of the same name: {}",
            replaced.join(", ")
        ));
    }
    if !beside.is_empty() {
        what.push(format!(
            "the folder also holds another configuration's set(s): {}",
            beside.join(", ")
        ));
    }
    crate::warn::warn(format!(
        "gbump: warning: --out {}: {} (set files are named by source and target, not by configuration; `gbump regress` refuses a folder that mixes configurations)\n  fix: give each configuration a folder of its own",
        dir.display(),
        what.join("; ")
    ));
}

/// Say that `what` (`--source scene:NAME`, `--stream scene:NAME`) runs under scene `name`'s
/// own configuration `cfg`, with the command that prints it (pasted back whole: a scene file
/// named `-x.toml` or with spaces is given as `--scene=NAME`, shell-quoted).
pub fn own_config_note(what: &str, name: &str, cfg: &crate::config::PipelineConfig) {
    eprintln!(
        "note: {what} targets the scene's own configuration {} (`gbump config --scene={}` prints it); pass --config to target another",
        cfg.hash(),
        crate::shell::quoted(name)
    );
}
