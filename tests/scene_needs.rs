//! What a scene needs of the pipeline (`scene::needs`): `gbump config --scene` says why each
//! derived field has its value, and stripping what the scene does not use changes no pixel.

use assert_cmd::Command;
use gbump::config::PipelineConfig;
use gbump::scene::needs::SceneNeeds;
use gbump::scene::{builtin, Scene};

#[test]
fn config_for_a_scene_says_why() {
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["config", "--scene", "sphere_bricks_spots"])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    for want in [
        "# lights = 1: 1 bump light(s): light 0 (directional); 2 more carried by the Gouraud colour",
        "# shininess = 32: the set {32}",
        "# k_frac_bits = 0: every bump light's k_i is 0 or 1",
        "distinct stored normals at normal_bits = 8",
        "\nk_frac_bits = 0\n",
        "\nlights = 1\n",
    ] {
        assert!(text.contains(want), "no `{want}` in:\n{text}");
    }
    // The comments come first and the rest still reads as the configuration.
    let cfg = PipelineConfig::from_toml("stdout", &text).unwrap();
    assert_eq!(cfg.k_frac_bits, 0);
}

#[test]
fn a_graded_k_keeps_its_fraction_bits_and_names_the_light() {
    let mut s = Scene::load("cg_wall_front").unwrap();
    assert!(SceneNeeds::of(&s).k_on_off);
    s.lights[0].k = 0.5;
    let needs = SceneNeeds::of(&s);
    assert!(!needs.k_on_off);
    assert_eq!(needs.sized().k_frac_bits, PipelineConfig::default().k_frac_bits);
    let why = needs.explain(&s, &needs.sized()).unwrap();
    assert!(why.contains("light 0: k = 0.5"), "{why}");
}

/// k_i of 0 or 1 at 0 fraction bits is exact: every built-in scene whose k_i are on/off renders
/// the same golden image with the derived configuration and with the default k width.
#[test]
fn stripping_the_k_multiplier_changes_no_pixel() {
    let mut stripped = 0;
    for (name, _) in builtin::ALL {
        let s = Scene::load(name).unwrap();
        let derived = s.derive_config().unwrap();
        if derived.k_frac_bits != 0 {
            continue;
        }
        stripped += 1;
        let wide = PipelineConfig {
            k_frac_bits: PipelineConfig::default().k_frac_bits,
            ..derived.clone()
        };
        let a = gbump::render::render(&s, &derived, 64, 48, false).unwrap();
        let b = gbump::render::render(&s, &wide, 64, 48, false).unwrap();
        assert_eq!(a.golden, b.golden, "{name}");
    }
    assert!(stripped >= 5, "only {stripped} scenes have on/off k");
}

fn white_scene() -> Scene {
    Scene::load(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/scenes/white_lights.toml")).unwrap()
}

/// A scene whose bump lights are all white derives `white_lights = true`, and dropping the
/// light-colour multiply changes no pixel: every Lc is the largest code, so f·k·Lc is the
/// same with the multiply and with the shift and subtract.
#[test]
fn stripping_the_light_colour_multiply_changes_no_pixel() {
    let s = white_scene();
    let derived = s.derive_config().unwrap();
    assert!(derived.white_lights, "white bump lights derive white_lights");
    let why = SceneNeeds::of(&s).explain(&s, &derived).unwrap();
    assert!(why.contains("# white_lights = true: every bump light is white"), "{why}");
    let coloured = PipelineConfig {
        white_lights: false,
        ..derived.clone()
    };
    let a = gbump::render::render(&s, &derived, 64, 48, false).unwrap();
    let b = gbump::render::render(&s, &coloured, 64, 48, false).unwrap();
    assert_eq!(a.golden, b.golden);
    // The strip is smaller: no Lc multiply, no Lc in the banks (the area model).
    let (ga, gb) = (
        gbump::measure::area_model::estimate(&derived),
        gbump::measure::area_model::estimate(&coloured),
    );
    assert!(ga < gb, "white {ga:.0} GE against coloured {gb:.0} GE");
    // No built-in scene has white bump lights: none derives the strip.
    for (name, _) in builtin::ALL {
        assert!(!Scene::load(name).unwrap().derive_config().unwrap().white_lights, "{name}");
    }
}

/// A configuration without the light-colour multiply refuses a scene with a coloured bump
/// light, naming the field and the fix, rather than rendering it with white lights.
#[test]
fn white_lights_refuse_a_coloured_scene() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("white.toml");
    std::fs::write(&cfg, "white_lights = true\nlights = 2\n").unwrap();
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["render", "--scene", "torus_caps", "--out"])
        .arg(dir.path().join("out"))
        .arg("--config")
        .arg(&cfg)
        .assert()
        .failure();
    let t = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    assert!(
        t.contains("white_lights") && t.contains("coloured bump light") && t.contains("fix:"),
        "{t}"
    );
    assert!(!dir.path().join("out").exists(), "nothing written");
}
