//! The render CLI as a user runs it, and its refusals of bad input.

use assert_cmd::Command;
use std::path::Path;

fn gbump() -> Command {
    Command::cargo_bin("gbump").unwrap()
}

#[test]
fn scenes_lists_every_builtin() {
    let out = gbump().arg("scenes").assert().success().get_output().stdout.clone();
    let text = String::from_utf8(out).unwrap();
    for (name, _) in gbump::scene::builtin::ALL {
        assert!(text.contains(name), "{name} missing from:\n{text}");
    }
}

#[test]
fn render_writes_four_images_and_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let out = gbump()
        .args(["render", "--scene", "cg_wall_front", "--size", "64x32", "--out"])
        .arg(dir.path())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains("PSNR"), "{text}");
    for f in ["golden", "reference", "gouraud_f64", "diff"] {
        let p = dir.path().join(format!("cg_wall_front_{f}.png"));
        let img = image::open(&p).unwrap();
        assert_eq!((img.width(), img.height()), (64, 32), "{f}");
    }
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.path().join("cg_wall_front_metrics.json")).unwrap()).unwrap();
    assert!(m["golden_vs_reference"]["psnr_db"].as_f64().unwrap() > 20.0);
    // Nothing half-written is left behind.
    assert!(std::fs::read_dir(dir.path())
        .unwrap()
        .all(|e| !e.unwrap().file_name().to_string_lossy().contains(".tmp")));
}

fn expect_error(args: &[&str], dir: &Path, needles: &[&str]) {
    let out = gbump().args(args).current_dir(dir).assert().failure().get_output().stderr.clone();
    let text = String::from_utf8(out).unwrap();
    for n in needles {
        assert!(text.contains(n), "stderr lacks `{n}`:\n{text}");
    }
    assert!(!text.contains("panicked"), "{text}");
}

#[test]
fn bad_scene_inputs_are_refused_with_place_and_fix() {
    let dir = tempfile::tempdir().unwrap();
    let base = gbump::scene::builtin::get("cg_wall_front").unwrap();
    let cases: &[(&str, String, &[&str])] = &[
        (
            "nan.toml",
            base.replace("height = 2.0", "height = nan"),
            &["nan.toml", "camera.height", "finite"],
        ),
        (
            "inf.toml",
            base.replace("colour = [0.95, 0.95, 0.95]", "colour = [inf, 0.95, 0.95]"),
            &["inf.toml", "lights[0].colour[0]", "finite"],
        ),
        (
            "neg.toml",
            base.replace("size = [256, 128]", "size = [0, 128]"),
            &["neg.toml", "size[0]", "1..=8192"],
        ),
        (
            "type.toml",
            base.replace("shininess = 8", "shininess = \"eight\""),
            &["type.toml:", "fix:"],
        ),
        ("syntax.toml", base.replace("[camera]", "[camera"), &["syntax.toml:", "fix:"]),
        (
            "unknown.toml",
            base.replace("shininess = 8", "shininess = 8\nshinyness = 3"),
            &["unknown field", "shinyness"],
        ),
        (
            "strength.toml",
            base.replace("strength = 10.0", "strength = -1.0"),
            &["objects[0].bump.strength", "out of range"],
        ),
    ];
    for (file, text, needles) in cases {
        std::fs::write(dir.path().join(file), text).unwrap();
        expect_error(&["render", "--scene", file, "--out", "o"], dir.path(), needles);
        assert!(
            !dir.path().join("o").join("cg_wall_front_golden.png").exists(),
            "{file}: output written for bad input"
        );
    }
    expect_error(
        &["render", "--scene", "no_such_scene", "--out", "o"],
        dir.path(),
        &["unknown scene", "gbump scenes"],
    );
    expect_error(
        &["render", "--scene", "torus_caps", "--size", "0x10", "--out", "o"],
        dir.path(),
        &["--size"],
    );
}

#[test]
fn bad_config_and_missing_png_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("c.toml"), "lights = 1\nnormal_bits = 64\n").unwrap();
    expect_error(
        &["render", "--scene", "torus_caps", "--config", "c.toml", "--out", "o"],
        dir.path(),
        &["c.toml", "normal_bits", "3..=16"],
    );
    std::fs::write(dir.path().join("c.toml"), "lights = 1\n").unwrap();
    expect_error(
        &["render", "--scene", "torus_caps", "--config", "c.toml", "--out", "o"],
        dir.path(),
        &["2 bump lights", "lights = 2"],
    );
    let base = gbump::scene::builtin::get("cg_wall_front").unwrap();
    let png = base.replace(
        "source = { kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }",
        "source = { kind = \"png\", path = \"missing.png\" }",
    );
    std::fs::write(dir.path().join("png.toml"), png).unwrap();
    expect_error(
        &["render", "--scene", "png.toml", "--out", "o"],
        dir.path(),
        &["missing.png", "PNG"],
    );
    std::fs::write(dir.path().join("bad.png"), b"not a png").unwrap();
    std::fs::write(
        dir.path().join("png2.toml"),
        base.replace(
            "source = { kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }",
            "source = { kind = \"png\", path = \"bad.png\" }",
        ),
    )
    .unwrap();
    expect_error(&["render", "--scene", "png2.toml", "--out", "o"], dir.path(), &["bad.png"]);
}

#[test]
fn png_height_map_renders() {
    let dir = tempfile::tempdir().unwrap();
    let img = image::GrayImage::from_fn(32, 32, |x, y| image::Luma([((x * 7 + y * 3) % 256) as u8]));
    img.save(dir.path().join("h.png")).unwrap();
    let base = gbump::scene::builtin::get("cg_wall_front").unwrap();
    std::fs::write(
        dir.path().join("s.toml"),
        base.replace(
            "source = { kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }",
            "source = { kind = \"png\", path = \"h.png\" }",
        ),
    )
    .unwrap();
    gbump()
        .args(["render", "--scene", "s.toml", "--size", "32x16", "--out", "o"])
        .current_dir(dir.path())
        .assert()
        .success();
    assert!(dir.path().join("o/cg_wall_front_golden.png").exists());
}

#[test]
fn unwritable_output_is_an_error() {
    expect_error(
        &[
            "render",
            "--scene",
            "cg_wall_front",
            "--size",
            "16x8",
            "--out",
            "/proc/gbump_cannot",
        ],
        Path::new("."),
        &["/proc/gbump_cannot"],
    );
}

#[test]
fn a_scene_source_says_which_configuration_its_vectors_target() {
    let dir = tempfile::tempdir().unwrap();
    let scene_cfg = gbump::scene::Scene::load("torus_caps").unwrap().derive_config().unwrap();
    let o = assert_cmd::Command::cargo_bin("gbump")
        .unwrap()
        .args([
            "vectors",
            "--source",
            "scene:torus_caps",
            "--target",
            "top",
            "--size",
            "32x24",
            "--out",
        ])
        .arg(dir.path())
        .assert()
        .success();
    let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    let out = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    assert!(
        err.contains("scene's own configuration") && err.contains(&scene_cfg.hash()) && err.contains("--config"),
        "{err}"
    );
    assert!(out.contains(&scene_cfg.hash()), "{out}");
}
