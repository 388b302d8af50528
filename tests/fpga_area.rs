//! FPGA figures as a user runs them: `gbump area --target ice40|ecp5|xilinx` on the one-light
//! parallel configuration (resources per unit, the iCE40 placed and routed in its register
//! shell with Fmax and utilisation), a device too small reported as such, and missing tools
//! or unknown devices refused with the fix. Synthesis and place and route are cached in
//! `target/test-fpga`, so only a cold run pays for them (about 3.5 minutes on two cores).

use assert_cmd::Command;
use serde_json::Value;

const CONFIG: &str = "tests/configs/one_light_parallel.toml";
const WORK: &str = "target/test-fpga";

fn area(target: &str, extra: &[&str]) -> (String, Value) {
    area_of(CONFIG, target, extra)
}

fn area_of(config: &str, target: &str, extra: &[&str]) -> (String, Value) {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("fpga.json");
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["area", "--target", target, "--config", config, "--work", WORK])
        .args(extra)
        .arg("--json")
        .arg(&json)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    (text, serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap())
}

fn unit<'a>(r: &'a Value, name: &str) -> &'a Value {
    r["units"]
        .as_array()
        .unwrap()
        .iter()
        .find(|u| u["unit"].as_str().unwrap().starts_with(name))
        .unwrap_or_else(|| panic!("no {name} in {r}"))
}

fn n(v: &Value, key: &str) -> u64 {
    v[key].as_u64().unwrap_or_else(|| panic!("{key} in {v}"))
}

#[test]
fn ice40_places_and_routes_the_one_light_top_and_a_too_small_device_is_a_result() {
    let (text, r) = area("ice40", &[]);
    assert!(text.contains("**Fmax ") && text.contains("register shell"), "{text}");
    assert_eq!(r["units"].as_array().unwrap().len(), 7, "six units and the top: {r}");
    let top = unit(&r, "gbump_pipeline");
    assert!(n(top, "luts") > 1000 && n(top, "flip_flops") > 100 && n(top, "carry") > 0, "{top}");
    assert_eq!(n(unit(&r, "power_unit"), "block_ram"), 1, "the power table is one SB_RAM40_4K");
    // The power table (one RAM copy for one read port), the triangle banks and the output
    // buffer: every Verilog memory of the top, each counted once.
    let cfg = gbump::PipelineConfig::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(CONFIG)).unwrap();
    let want = cfg.power_depth() * (cfg.power_frac_bits + 1) + gbump::rtlgen::top::array_bits(&cfg);
    assert_eq!(n(top, "memory_bits"), want as u64, "{top}");
    let pr = &r["place_route"];
    assert_eq!(pr["fits"], true, "{pr}");
    assert_eq!(pr["device"], "hx8k");
    assert_eq!(pr["pins"], 7);
    assert!(n(pr, "core_pins") > 206, "more pins than the ct256 package bonds: {pr}");
    let fmax = pr["fmax_mhz"].as_f64().unwrap();
    // The issue measured 31.6 MHz (the one-cycle multiply-and-round in diffuse_blend).
    assert!((10.0..200.0).contains(&fmax), "{fmax}");
    assert!(text.contains(&format!("**Fmax {fmax:.2} MHz**")), "{text}");
    let util = pr["utilisation"].as_array().unwrap();
    let row = |name: &str| {
        util.iter()
            .find(|u| u["resource"] == name)
            .unwrap_or_else(|| panic!("{name}: {pr}"))
    };
    let lc = row("ICESTORM_LC");
    assert!(n(lc, "used") >= n(top, "luts") && n(lc, "used") <= n(lc, "available"), "{lc}");
    // Placed as synthesised: the power table, and the banks and buffer Yosys maps to RAM.
    assert_eq!(n(row("ICESTORM_RAM"), "used"), n(top, "block_ram"));
    assert_eq!(n(row("SB_IO"), "used"), 7, "the shell's pins");
    // The same netlist on an HX1K (1280 logic cells): a clear result, not a crash.
    let (small, s) = area("ice40", &["--device", "hx1k"]);
    assert!(small.contains("**Does not fit** the hx1k: needs ICESTORM_LC"), "{small}");
    assert_eq!(s["place_route"]["fits"], false);
    assert!(s["place_route"]["fmax_mhz"].is_null());
    assert_eq!(s["units"], r["units"], "synthesis does not depend on the device");
}

#[test]
fn ecp5_and_xilinx_count_luts_flip_flops_and_dsps() {
    for target in ["ecp5", "xilinx"] {
        // Booth rows (the default) are logic: no DSP block (one target shows it).
        if target == "ecp5" {
            let (_, booth) = area(target, &[]);
            assert_eq!(n(unit(&booth, "gbump_pipeline"), "dsp"), 0, "{target}: Booth rows are logic");
        }
        let (text, r) = area_of("tests/configs/inferred_multipliers.toml", target, &[]);
        assert!(text.contains(&format!("on {target} (Yosys 0.")), "{text}");
        assert!(r["place_route"].is_null(), "only iCE40 is placed and routed");
        let top = unit(&r, "gbump_pipeline");
        assert!(n(top, "luts") > 50 && n(top, "flip_flops") > 100, "{target}: {top}");
        assert!(
            n(top, "dsp") > 0,
            "{target}: `multipliers = \"inferred\"` maps to DSP blocks: {top}"
        );
        for u in r["units"].as_array().unwrap() {
            // A table's register is its block RAM's read register.
            assert!(
                n(u, "flip_flops") > 0 || n(u, "block_ram") > 0,
                "{target}: every unit is registered: {u}"
            );
            assert!(
                n(u, "luts") + n(u, "carry") + n(u, "dsp") + n(u, "lut_ram") + n(u, "block_ram") > 0 || u["unit"] == "bump_fetch",
                "{target}: {u}"
            );
        }
        let pt = unit(&r, "power_unit");
        assert!(
            n(pt, "block_ram") == 1 && n(pt, "lut_ram") == 0,
            "{target}: one DP16KD or RAMB18E1: {pt}"
        );
        assert_eq!(n(pt, "memory_bits"), 256 * 9, "{target}: {pt}");
    }
}

#[test]
fn a_missing_place_and_route_tool_or_an_unknown_device_is_refused_with_the_fix() {
    let bin = tempfile::tempdir().unwrap();
    let yosys = std::env::split_paths(&std::env::var_os("PATH").unwrap())
        .map(|d| d.join("yosys"))
        .find(|p| p.exists())
        .expect("yosys on PATH");
    std::os::unix::fs::symlink(yosys, bin.path().join("yosys")).unwrap();
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .env("PATH", bin.path())
        .args(["area", "--target", "ice40", "--work"])
        .arg(bin.path().join("work"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    assert!(
        err.contains("nextpnr-ice40 is not installed")
            && err.contains("scripts/install-tools.sh")
            && err.contains("apt-get install -y nextpnr-ice40"),
        "{err}"
    );
    assert!(!bin.path().join("work").exists(), "nothing written before the check");
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["area", "--target", "ice40", "--device", "xc7a35t", "--work"])
        .arg(bin.path().join("work"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    assert!(err.contains("--device xc7a35t") && err.contains("hx8k"), "{err}");
}

/// The memories are block RAMs on iCE40 (cheap: a 64-entry table and the palette, each unit
/// synthesised alone, no place and route): no flip-flops for the words or the read register,
/// and their bits counted apart from the logic. ECP5 and Xilinx: the test above.
#[test]
fn the_power_table_and_the_palette_map_to_block_ram_on_ice40() {
    use gbump::measure::fpga::{unit_resources, Target};
    let cfg = gbump::config::PipelineConfig {
        lights: 1,
        palette: true,
        power_entries: 64,
        ..Default::default()
    };
    let work = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(WORK).join("bram");
    for target in [Target::Ice40] {
        let pt = unit_resources(&cfg, target, "power_unit", &work, "test").unwrap();
        assert!(pt.block_ram >= 1 && pt.lut_ram == 0, "{target:?}: {pt:?}");
        assert_eq!(pt.flip_flops, 0, "{target:?}: the read register is the block RAM's: {pt:?}");
        assert_eq!(pt.memory_bits, 64 * 9, "{target:?}");
        let pal = unit_resources(&cfg, target, "palette_fetch", &work, "test").unwrap();
        assert!(pal.block_ram >= 1 && pal.lut_ram == 0 && pal.flip_flops == 0, "{target:?}: {pal:?}");
        assert_eq!(pal.memory_bits, 256 * 3 * 8, "{target:?}");
    }
}
