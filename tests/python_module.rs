//! The Python module (python/, `import gbump`) for real: built and installed by
//! scripts/python-module.sh (seconds when current), checked record for record against the
//! files gbump writes (python/tests/check_module.py), and used as the scoreboard of the cocotb
//! example (examples/cocotb_model) on Icarus: zero mismatches on the default and a one-light
//! configuration, and a failure on a mutant RTL. A missing tool fails, naming the fix.

use assert_cmd::Command as Gbump;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn need(tool: &str) {
    let found = std::env::var_os("PATH").is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(tool).is_file()));
    assert!(found, "{tool} is not installed: run scripts/install-tools.sh");
}

/// Run `cmd`; (success, stdout + stderr).
fn run(cmd: &mut Command) -> (bool, String) {
    let out = cmd.output().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    let log = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.success(), log)
}

/// Build and install the module once per test process, from this source tree, so no test
/// runs a stale module. Cargo's own variables for this test are dropped, so the nested build
/// sees the environment `cargo build` would.
fn module() {
    static BUILT: OnceLock<Result<(), String>> = OnceLock::new();
    let r = BUILT.get_or_init(|| {
        need("maturin");
        need("python3");
        let mut c = Command::new(root().join("scripts/python-module.sh"));
        for (k, _) in std::env::vars_os() {
            let k = k.to_string_lossy().into_owned();
            if k == "CARGO"
                || (k.starts_with("CARGO_")
                    && !k.starts_with("CARGO_HOME")
                    && !k.starts_with("CARGO_TARGET_DIR")
                    && !k.starts_with("CARGO_BUILD_JOBS"))
            {
                c.env_remove(k);
            }
        }
        match run(&mut c) {
            (true, _) => Ok(()),
            (false, log) => Err(format!("scripts/python-module.sh failed (run scripts/install-tools.sh):\n{log}")),
        }
    });
    if let Err(e) = r {
        panic!("{e}");
    }
}

fn gbump_exe() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_gbump"))
}

/// `gbump rtl` of `config` (None: the default) into `dir`; the interface JSON's path.
fn rtl(config: Option<&str>, dir: &Path) -> PathBuf {
    let mut cmd = Gbump::cargo_bin("gbump").unwrap();
    cmd.args(["rtl", "--out", dir.to_str().unwrap()]);
    let cfg = match config {
        Some(c) => {
            let p = root().join(c);
            cmd.arg("--config").arg(&p);
            gbump::PipelineConfig::load(&p).unwrap()
        }
        None => gbump::PipelineConfig::default(),
    };
    assert!(cmd.output().unwrap().status.success());
    dir.join(format!("{}.json", gbump::rtlgen::units_v::module_name(&cfg, "gbump_pipeline")))
}

/// The cocotb scoreboard example on the RTL of `iface`, from `cwd`; (success, log).
fn scoreboard(cwd: &Path, iface: &Path, count: u32) -> (bool, String) {
    std::fs::create_dir_all(cwd).unwrap();
    let mut c = Command::new("make");
    c.current_dir(cwd)
        .arg("-f")
        .arg(root().join("examples/cocotb_model/Makefile"))
        .arg(format!("INTERFACE={}", iface.display()))
        .arg(format!("COUNT={count}"))
        .args(["BUBBLES=0.25", "SEED=5", "SHININESS=40"]);
    run(&mut c)
}

#[test]
fn the_module_gives_the_records_roms_and_interface_gbump_writes() {
    module();
    for config in [None, Some("tests/configs/one_light_parallel.toml")] {
        let tmp = tempfile::tempdir().unwrap();
        let mut c = Command::new("python3");
        c.arg(root().join("python/tests/check_module.py")).arg(gbump_exe()).arg(tmp.path());
        if let Some(cfg) = config {
            c.arg(root().join(cfg));
        }
        let (ok, log) = run(&mut c);
        assert!(
            ok && log.contains(" passed, 0 failed"),
            "check_module.py, config {config:?}:\n{log}"
        );
    }
}

#[test]
fn the_cocotb_scoreboard_passes_on_the_default_and_rejects_a_mutant() {
    need("make");
    need("iverilog");
    need("cocotb-config");
    module();
    let tmp = tempfile::tempdir().unwrap();
    let iface = rtl(None, &tmp.path().join("rtl"));
    let (ok, log) = scoreboard(&tmp.path().join("run"), &iface, 200);
    assert!(ok && log.contains("200 passed, 0 failed") && log.contains("FAIL=0"), "{log}");

    // One operator flipped in texture_modulate (round(c·t/255) by add-and-shift): caught.
    let rtl_dir = iface.parent().unwrap();
    let f = std::fs::read_dir(rtl_dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.file_name().unwrap().to_string_lossy().starts_with("texture_modulate_"))
        .unwrap();
    let v = std::fs::read_to_string(&f).unwrap();
    let flipped = v.replacen("p1 + (p1 >>", "p1 - (p1 >>", 1);
    assert_ne!(v, flipped, "{}: the operator to flip is gone; pick another", f.display());
    std::fs::write(&f, flipped).unwrap();
    let (ok, log) = scoreboard(&tmp.path().join("run"), &iface, 200);
    assert!(
        !ok && log.contains("MISMATCH fragment") && log.contains("out_c expected"),
        "the mutant passed:\n{log}"
    );
}

#[test]
fn the_cocotb_scoreboard_passes_on_one_light() {
    need("make");
    need("iverilog");
    need("cocotb-config");
    module();
    let tmp = tempfile::tempdir().unwrap();
    let iface = rtl(Some("tests/configs/one_light_parallel.toml"), &tmp.path().join("rtl"));
    let (ok, log) = scoreboard(&tmp.path().join("run"), &iface, 400);
    assert!(ok && log.contains("400 passed, 0 failed") && log.contains("FAIL=0"), "{log}");
}

/// docs/SCENES.md is enough to rebuild every scene's records: an independent front end
/// written from it alone (`tests/scenes_doc/independent_renderer.py`) gives every stimulus
/// column of every record, in order, of each built-in scene and of a mixed scene under
/// several configurations (symmetric 10-bit normals and 10-bit colours, k_frac_bits 0 and
/// 5, interpolated H and H+L with interpolated k), as the model does.
#[test]
fn the_scene_reference_rebuilds_every_scenes_records() {
    module();
    let dir = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(root().join("tests/scenes_doc/mixed.toml")).unwrap();
    let variants = [
        ("", ""),
        (
            "symmetric",
            "normal_range = \"symmetric\"\nnormal_bits = 10\nlh_bits = 12\ncolour_bits = 10\nk_frac_bits = 5\n",
        ),
        ("k0", "k_frac_bits = 0\n"),
        ("hl", "bump_state = \"fragment\"\ninterpolate = \"hl\"\ninterpolate_k = true\n"),
        ("h", "bump_state = \"fragment\"\ninterpolate = \"h\"\n"),
    ];
    let mut scenes: Vec<String> = gbump::scene::builtin::ALL.iter().map(|(s, _)| s.to_string()).collect();
    // docs/SCENES.md states how many built-in scenes this test rebuilds.
    let doc = std::fs::read_to_string(root().join("docs/SCENES.md")).unwrap();
    let flat = doc.split_whitespace().collect::<Vec<_>>().join(" ");
    let want = format!("runs it on all {} built-in scenes", scenes.len());
    assert!(flat.contains(&want), "docs/SCENES.md should say: {want}");
    for (tag, pipeline) in variants {
        let p = dir.path().join(format!("mixed{tag}.toml"));
        let text = base.replacen("name = \"mixed\"", &format!("name = \"mixed{tag}\""), 1);
        let text = if pipeline.is_empty() {
            text
        } else {
            format!("{text}[pipeline]\n{pipeline}")
        };
        std::fs::write(&p, text).unwrap();
        scenes.push(p.display().to_string());
    }
    let (ok, log) = run(Command::new("python3")
        .arg(root().join("tests/scenes_doc/independent_renderer.py"))
        .args(&scenes));
    assert!(ok, "{log}");
    for s in &scenes {
        assert!(
            log.lines().any(|l| l.starts_with(&format!("{s} OK "))),
            "{s}: the records rebuilt from docs/SCENES.md differ from the model's:\n{log}"
        );
    }
}
