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
