//! The checked-in rtl/ and vectors/ must be exactly what gbump generates today for the default
//! configuration. Regenerate with scripts/regen.sh after an intended change.

use gbump::vectors::{dump, DumpOptions, Source};
use gbump::PipelineConfig;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn compare(dir: &Path, files: &[(String, Vec<u8>)]) -> Vec<String> {
    let mut stale = Vec::new();
    for (name, bytes) in files {
        match std::fs::read(dir.join(name)) {
            Ok(have) if &have == bytes => {}
            Ok(_) => stale.push(format!("{} differs", dir.join(name).display())),
            Err(_) => stale.push(format!("{} is missing", dir.join(name).display())),
        }
    }
    stale
}

#[test]
fn checked_in_rtl_and_roms_are_current() {
    let cfg = PipelineConfig::default();
    let rtl: Vec<(String, Vec<u8>)> = gbump::rtlgen::generate(&cfg, "gbump rtl --out rtl")
        .into_iter()
        .map(|(n, t)| (n, t.into_bytes()))
        .collect();
    let mut stale = compare(&root().join("rtl"), &rtl);
    let roms = gbump::rtlgen::rom_files::rom_files(&cfg, None, "", Some(16), Some(32), Path::new("rtl/rom")).unwrap();
    stale.extend(compare(
        &root().join("rtl/rom"),
        &roms.into_iter().map(|(n, t)| (n, t.into_bytes())).collect::<Vec<_>>(),
    ));
    assert!(
        stale.is_empty(),
        "stale generated files (run scripts/regen.sh):\n{}",
        stale.join("\n")
    );
}

#[test]
fn checked_in_vectors_are_current() {
    let cfg = PipelineConfig::default();
    let tmp = tempfile::tempdir().unwrap();
    let all: Vec<String> = gbump::vectors::targets::all_targets().iter().map(|s| s.to_string()).collect();
    for (src, cmd) in [
        (Source::Corners(1), "gbump vectors --source corners --out vectors"),
        (Source::Random(256), "gbump vectors --source random:256 --seed 1 --out vectors"),
    ] {
        let o = DumpOptions::formats(cmd, true, true);
        dump(&cfg, &src, &all, tmp.path(), &o).unwrap();
    }
    let files: Vec<(String, Vec<u8>)> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap())
        })
        .collect();
    assert!(files.len() > 20);
    let stale = compare(&root().join("vectors"), &files);
    assert!(stale.is_empty(), "stale vectors (run scripts/regen.sh):\n{}", stale.join("\n"));
    for f in &files {
        if f.0.ends_with(".json") && !f.0.contains("power_unit.") {
            gbump::vectors::verify(&root().join("vectors").join(&f.0)).unwrap();
        }
    }
}

#[test]
fn regeneration_is_deterministic() {
    let cfg = PipelineConfig {
        lights: 2,
        light_mode: gbump::config::LightMode::Parallel,
        colour_guard_bits: 2,
        ..Default::default()
    };
    assert_eq!(gbump::rtlgen::generate(&cfg, "x"), gbump::rtlgen::generate(&cfg, "x"));
    for (name, text) in gbump::rtlgen::generate(&cfg, "x") {
        assert!(text.is_ascii(), "{name}: generated files are ASCII");
        if name.ends_with(".v") {
            assert!(text.contains("`default_nettype none") && text.contains("`timescale"), "{name}");
            assert!(text.contains("do not edit") && text.contains(&cfg.hash()), "{name}: header");
        }
    }
}

#[test]
fn readme_interface_table_is_current() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let table = gbump::rtlgen::interface::interface_markdown(&PipelineConfig::default());
    assert!(
        readme.contains(&table),
        "README's interface table is stale: paste the output of `gbump interface`"
    );
}

#[test]
fn readme_integration_section_is_current() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let section = gbump::rtlgen::integration_doc::markdown(&PipelineConfig::default());
    assert!(
        readme.contains(&section),
        "README's integration section is stale: paste the output of `gbump integration`"
    );
}

/// The README's upgrade table is the list of renames `src/renamed.rs` checks.
#[test]
fn readme_upgrade_table_is_current() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.contains(&gbump::renamed::markdown()),
        "README's upgrade table is stale: paste gbump::renamed::markdown()"
    );
}

/// The latency of every unit and top at every `pipeline_depth`, as the README states it, is
/// what the units and the scheduler return today (the benches check the top's per vector).
#[test]
fn readme_timing_table_is_current() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let table = gbump::units::timing::markdown();
    assert!(
        readme.contains(&table),
        "README's timing table is stale: paste the output of `gbump timing`"
    );
    // The default depth the README names is the configuration's default.
    let d = gbump::config::PipelineConfig::default().pipeline_depth;
    assert!(
        readme.contains(&format!("default `pipeline_depth = {d}`")),
        "README names another default depth"
    );
}
