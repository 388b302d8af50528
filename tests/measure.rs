//! The trade-off meter's measurements as a user runs them: Yosys area and error against
//! exact arithmetic.

use assert_cmd::Command;

#[test]
fn area_reports_every_unit_with_yosys_figures() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("area.json");
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "area",
            "--config",
            "tests/configs/one_light_parallel.toml",
            "--work",
            "target/test-area",
            "--json",
        ])
        .arg(&json)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    assert!(text.contains("Yosys 0.") && text.contains("abc -g cmos2"), "{text}");
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let units = r["units"].as_array().unwrap();
    assert_eq!(units.len(), 7, "six units and the top");
    for u in units {
        assert!(u["gate_equivalents"].as_f64().unwrap() > 10.0, "{u}");
        assert_eq!(u["gate_equivalents"].as_f64().unwrap() * 4.0, u["transistors"].as_f64().unwrap());
    }
    let get = |name: &str| units.iter().find(|u| u["unit"].as_str().unwrap().starts_with(name)).unwrap();
    assert_eq!(get("power_unit")["memory_bits"], 256 * 9);
    // The table is a RAM, a black box apart from the logic: its words and its read register
    // are in the RAM's bits, not in the flip-flops or the GE.
    assert_eq!(get("power_unit")["flip_flops"], 0, "the table's words are not flip-flops");
    // One RAM copy for one read port, and the top's output buffer, a RAM too. The parallel
    // top's register banks are flip-flops in this flow, counted there and not in the RAM bits.
    let cfg = gbump::PipelineConfig::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/configs/one_light_parallel.toml"))
        .unwrap();
    let own_ram = gbump::rtlgen::top::ram_bits(&cfg) as u64;
    assert!(own_ram > 0, "the output buffer is a RAM");
    assert_eq!(get("gbump_pipeline")["memory_bits"], 256 * 9 + own_ram);
    let register_banks = gbump::rtlgen::top::array_bits(&cfg) as u64 - own_ram;
    let ffs = get("gbump_pipeline")["flip_flops"].as_u64().unwrap();
    assert!(ffs > register_banks, "{ffs} flip-flops hold the register banks");
    assert!(ffs < 256 * 9, "{ffs} flip-flops: the table's words are not among them");
    assert!(get("dot_clamp")["logic_depth"].as_u64().unwrap() > 10);
    let top = get("gbump_pipeline")["gate_equivalents"].as_f64().unwrap();
    let dot = get("dot_clamp")["gate_equivalents"].as_f64().unwrap();
    assert!(top > 2.0 * dot, "the top holds two dot products and more");
}

#[test]
fn error_report_bounds_each_unit() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("err.json");
    Command::cargo_bin("gbump")
        .unwrap()
        .args(["error", "--random", "3000", "--size", "48x36", "--json"])
        .arg(&json)
        .assert()
        .success();
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let unit = |name: &str, src: &str| {
        r["units"]
            .as_array()
            .unwrap()
            .iter()
            .find(|u| u["unit"] == name && u["source"].as_str().unwrap().starts_with(src))
            .unwrap()
            .clone()
    };
    for (u, src) in [
        ("dot_clamp", "corners"),
        ("diffuse_blend", "random"),
        ("specular_blend", "random"),
        ("texture_modulate", "exhaustive"),
    ] {
        let e = unit(u, src);
        assert!(e["max_lsb"].as_f64().unwrap() <= 0.5 + 1e-9, "{u}: {e}");
        assert!(e["samples"].as_u64().unwrap() > 100);
    }
    // The power table errs between its entries; at n = 16 and 256 entries, under 1 LSB.
    let p = unit("power_unit", "exhaustive");
    assert!(p["max_lsb"].as_f64().unwrap() < 1.0 && p["max_lsb"].as_f64().unwrap() > 0.5, "{p}");
    assert!(r["scenes"].as_array().unwrap().len() >= 11);
}

/// `gbump error --scene FILE` measures the file's own scene first, beside the built-in ones
/// its configuration renders, and names each built-in one it leaves out and why (a one-light
/// configuration cannot render a two-light scene).
#[test]
fn error_measures_the_scene_given_and_names_the_scenes_left_out() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("err.json");
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .args([
            "error",
            "--scene",
            "tests/scenes/bump_spot.toml",
            "--random",
            "100",
            "--size",
            "24x18",
            "--json",
        ])
        .arg(&json)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).into_owned();
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(r["scenes"][0]["scene"], "bump_spot", "the scene given comes first: {}", r["scenes"]);
    let left: Vec<&str> = r["left_out"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["scene"].as_str().unwrap())
        .collect();
    assert!(left.contains(&"torus_caps"), "{left:?}");
    assert!(text.contains("Left out") && text.contains("- torus_caps: "), "{text}");
    // Every built-in scene is either measured or named as left out.
    let measured = r["scenes"].as_array().unwrap().len() - 1;
    assert_eq!(measured + left.len(), gbump::scene::builtin::ALL.len());
}
