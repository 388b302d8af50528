//! A warning is said once per command, however many times the command reads the file that
//! causes it (a scene is read to check it, to size the pipeline and to render it).

use std::process::Command;

#[test]
fn a_deprecated_field_in_a_scene_is_warned_once_per_command() {
    let d = tempfile::tempdir().unwrap();
    let scene = include_str!("../scenes/torus_caps.toml").to_string() + "\n[pipeline]\nk_bits = 8\n";
    std::fs::write(d.path().join("s.toml"), scene).unwrap();
    for args in [
        &["render", "--scene", "s.toml", "--out", "r"][..],
        &["rom", "--scene", "s.toml", "--out", "ro"],
        &["vectors", "--source", "scene:s.toml", "--out", "v"],
    ] {
        let o = Command::new(assert_cmd::cargo::cargo_bin("gbump"))
            .args(args)
            .current_dir(d.path())
            .env("GBUMP_CACHE", d.path().join("cache"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{args:?}: {err}");
        assert_eq!(err.matches("`k_bits` is deprecated").count(), 1, "{args:?}: {err}");
    }
}

/// `k_frac_bits = 0` is a precision a sweep may ask for, so on a scene whose lights grade
/// k_i it is said (each k_i becomes 0 or 1), once, and the render goes on; on a scene whose
/// every k_i is 0 or 1 it costs nothing and is not said.
#[test]
fn zero_k_fraction_bits_on_graded_lights_is_said_once() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("k0.toml"), "k_frac_bits = 0\n").unwrap();
    let render = |scene: &str| {
        let o = Command::new(assert_cmd::cargo::cargo_bin("gbump"))
            .args(["render", "--scene", scene, "--config", "k0.toml", "--out", "r", "--size", "64x48"])
            .current_dir(d.path())
            .env("GBUMP_CACHE", d.path().join("cache"))
            .output()
            .unwrap();
        assert!(o.status.success(), "{scene}: {}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let err = render(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/scenes/bump_spot.toml"));
    assert_eq!(err.matches("k_frac_bits = 0 rounds each k_i to 0 or 1").count(), 1, "{err}");
    assert!(
        err.contains("k0.toml") && err.contains("lights[0] (spot exponent 2)") && err.contains("fix: set k_frac_bits = 8"),
        "{err}"
    );
    let err = render("torus_caps");
    assert!(!err.contains("k_frac_bits"), "{err}");
}
