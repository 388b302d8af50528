//! `power_rom = true`: the power table is a ROM holding x^shininess. What it cannot run is
//! refused with the field and the fix: a top vector set for another shininess, a scene with a
//! specular object of another shininess, a configuration without a specular path.

use assert_cmd::Command;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn gbump() -> Command {
    let mut c = Command::cargo_bin("gbump").unwrap();
    c.current_dir(root());
    c
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A top set for another shininess is refused where it would be made (`gbump vectors`) and,
/// made some other way (here: a manifest edited to name another table), where it would run.
/// Unit sets are not refused: `regress` itself sweeps the power unit at many shininesses.
#[test]
fn a_top_set_for_another_shininess_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let v = dir.path().join("v");
    let base = ["vectors", "--config", "tests/configs/power_rom.toml", "--shininess"];
    let o = gbump()
        .args(base)
        .args(["32", "--source", "random:50", "--target", "top", "--out"])
        .arg(&v)
        .assert()
        .failure();
    let t = stderr(o.get_output());
    assert!(
        t.contains("--shininess 32") && t.contains("ROM holding shininess 24") && t.contains("fix:"),
        "{t}"
    );
    assert!(!v.exists(), "a refused set left {v:?}");
    gbump()
        .args(base)
        .args(["5", "--source", "exhaustive:power_unit", "--out"])
        .arg(dir.path().join("unit"))
        .assert()
        .success();
    gbump()
        .args([
            "vectors",
            "--config",
            "tests/configs/power_rom.toml",
            "--source",
            "random:50",
            "--target",
            "top",
            "--out",
        ])
        .arg(&v)
        .assert()
        .success();
    let m = v.join("random50_top.json");
    // The top-level field (two spaces in); the configuration's own stays 24.
    let text = std::fs::read_to_string(&m)
        .unwrap()
        .replace("\n  \"shininess\": 24", "\n  \"shininess\": 32");
    assert!(text.contains("\n  \"shininess\": 32"), "the manifest names its table");
    std::fs::write(&m, text).unwrap();
    let o = gbump()
        .args([
            "regress",
            "--config",
            "tests/configs/power_rom.toml",
            "--sim",
            "icarus",
            "--vectors",
        ])
        .arg(&v)
        .arg("--work")
        .arg(dir.path().join("w"))
        .assert()
        .failure();
    // Its table file holds shininess 24's words, which the set check reads before the ROM's
    // own check (left as a second line of defence) could.
    let t = stderr(o.get_output());
    assert!(t.contains("table of shininess 32 (the manifest's)") && t.contains("fix:"), "{t}");
}

#[test]
fn a_scene_of_another_shininess_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let o = gbump()
        .args([
            "render",
            "--scene",
            "sphere_bricks_spots",
            "--config",
            "tests/configs/power_rom.toml",
            "--out",
        ])
        .arg(dir.path().join("out"))
        .assert()
        .failure();
    let t = stderr(o.get_output());
    assert!(t.contains("power_rom") && t.contains("shininess 32") && t.contains("fix:"), "{t}");
    assert!(!dir.path().join("out").exists());
}

#[test]
fn a_rom_without_a_specular_path_is_refused() {
    let e = gbump::config::PipelineConfig::from_toml("x.toml", "power_rom = true\nspecular = false\n").unwrap_err();
    let t = e.to_string();
    assert!(t.contains("x.toml") && t.contains("power_rom") && t.contains("fix:"), "{t}");
}

/// The interface says the table is a ROM and its load port unused, for a testbench written
/// from the interface alone.
#[test]
fn the_interface_says_the_table_is_a_rom() {
    let cfg = gbump::config::PipelineConfig::load(&root().join("tests/configs/power_rom.toml")).unwrap();
    let j: serde_json::Value = serde_json::from_str(&gbump::rtlgen::interface::interface_json(&cfg, "test")).unwrap();
    assert_eq!(j["power_table"]["rom"], true);
    assert!(
        j["power_table"]["load_port"].as_str().unwrap().starts_with("none"),
        "{}",
        j["power_table"]
    );
    let doc = gbump::rtlgen::integration_doc::markdown(&cfg);
    assert!(doc.contains("The power table is a ROM"), "{doc}");
}

/// An object without the specular blend reads no table: on a ROM configuration its fragments
/// join the ROM's shininess set instead of a set of their own that could not run.
#[test]
fn a_scene_with_a_non_specular_object_makes_one_set_at_the_roms_shininess() {
    let scene = root().join("tests/scenes/rom_mixed.toml");
    let cfg = gbump::scene::Scene::load(scene.to_str().unwrap()).unwrap().derive_config().unwrap();
    assert!(cfg.power_rom && cfg.shininess == 24, "{}", cfg.to_toml());
    let dir = tempfile::tempdir().unwrap();
    let o = gbump::vectors::DumpOptions {
        size: Some((48, 36)),
        ..gbump::vectors::DumpOptions::formats("test", false, true)
    };
    let sets = gbump::vectors::dump(
        &cfg,
        &gbump::vectors::Source::Scene(scene.display().to_string()),
        &["top".into()],
        dir.path(),
        &o,
    )
    .unwrap();
    assert_eq!(sets.len(), 1, "one set");
    let m: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&sets[0].manifest).unwrap()).unwrap();
    assert_eq!(m["shininess"], 24);
}
