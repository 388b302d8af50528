//! `gbump fit`: issue 12's run end to end (torus_caps within max<=2, the choice regressed on
//! both simulators), the other budgets, and bad or unreachable budgets failing cleanly with
//! nothing written. The search's own edges are `fit::search`'s unit test.

use assert_cmd::Command;

fn gbump() -> Command {
    let mut c = Command::cargo_bin("gbump").unwrap();
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn text(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

#[test]
fn bad_and_unreachable_budgets_fail_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit");
    for (budget, want) in [("max<2", "fix: use max<=LSB"), ("max<=0", "fix: loosen the budget")] {
        let o = gbump()
            .args(["fit", "--scene", "flat_artifact", "--no-regress", "--budget", budget, "--out"])
            .arg(&out)
            .assert()
            .failure();
        let t = text(o.get_output());
        assert!(t.contains(want), "{budget}: {t}");
        assert!(!out.exists(), "{budget}: output written");
    }
}

/// The chosen configuration's budget measure, from the line `gbump fit` prints.
fn printed(t: &str, key: &str) -> f64 {
    let line = t
        .lines()
        .find(|l| l.starts_with("fit "))
        .unwrap_or_else(|| panic!("no fit line: {t}"));
    let at = line.find(key).unwrap_or_else(|| panic!("no {key} in {line}")) + key.len();
    line[at..]
        .trim_start()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("{key} in {line}"))
}

#[test]
fn torus_caps_within_max_2_is_fitted_regressed_and_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit");
    let o = gbump()
        .args(["fit", "--scene", "torus_caps", "--budget", "max<=2", "--out"])
        .arg(&out)
        .arg("--work")
        .arg(dir.path().join("work"))
        .assert()
        .success();
    let t = text(o.get_output());
    assert!(printed(&t, "per clock): max") <= 2.0, "{t}");
    assert!(t.contains("passes on Icarus and Verilator"), "{t}");
    // ARCHITECTURE.md states this run's candidate count.
    let measured = t.split(" configurations measured").next().unwrap().rsplit(' ').next().unwrap();
    let arch = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/ARCHITECTURE.md")).unwrap();
    assert!(
        arch.contains(&format!("measures {measured} candidates")),
        "ARCHITECTURE.md should say `measures {measured} candidates`: {t}"
    );
    // The written configuration is the one printed, and loads.
    let toml = std::fs::read_to_string(out.join("fit.toml")).unwrap();
    let cfg = gbump::config::PipelineConfig::from_toml("fit.toml", &toml).unwrap();
    assert!(t.contains(&format!("chosen {}", &cfg.hash()[..8])), "{t}");
    for f in ["front.csv", "front.svg"] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    // Every candidate row has its area, not only the front's.
    let csv = std::fs::read_to_string(out.join("front.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "area_ge").unwrap();
    assert!(csv.lines().count() > 10, "{csv}");
    for row in csv.lines().skip(1) {
        let ge: f64 = row
            .split(',')
            .nth(col)
            .unwrap()
            .parse()
            .unwrap_or_else(|_| panic!("no area in {row}"));
        assert!(ge > 1000.0, "{row}");
    }
}

#[test]
fn psnr_and_exact_budgets_fit_and_an_unreachable_one_names_its_floor() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit");
    let o = gbump()
        .args(["fit", "--scene", "torus_caps", "--budget", "psnr>=50", "--no-regress", "--out"])
        .arg(&out)
        .assert()
        .success();
    let t = text(o.get_output());
    assert!(printed(&t, "PSNR") >= 50.0, "{t}");
    // exact<=1 needs guard bits between the colour stages: without them three roundings in a
    // row (diffuse, texture, specular) put the pipeline 1.2 LSB from exact arithmetic at any
    // width. The stored inputs keep the scene's widths (the budget cannot see them).
    let out1 = dir.path().join("fit1");
    let o = gbump()
        .args(["fit", "--scene", "torus_caps", "--budget", "exact<=1", "--no-regress", "--out"])
        .arg(&out1)
        .assert()
        .success();
    let t = text(o.get_output());
    assert!(printed(&t, "clock): exact") <= 1.0, "{t}");
    let cfg = gbump::config::PipelineConfig::load(&out1.join("fit.toml")).unwrap();
    assert!(cfg.colour_guard_bits > 0, "exact<=1 without guard bits: {t}");
    let scene_cfg = gbump::scene::Scene::load("torus_caps").unwrap().derive_config().unwrap();
    assert_eq!((cfg.normal_bits, cfg.lh_bits), (scene_cfg.normal_bits, scene_cfg.lh_bits), "{t}");
    // The last rounding to colour codes alone costs half an LSB: below that nothing fits, the
    // search says so and writes nothing.
    let out2 = dir.path().join("fit2");
    let o = gbump()
        .args(["fit", "--scene", "torus_caps", "--budget", "exact<=0.45", "--no-regress", "--out"])
        .arg(&out2)
        .assert()
        .failure();
    let t = text(o.get_output());
    assert!(t.contains("the best measured 0.5") && t.contains("fix: loosen the budget"), "{t}");
    assert!(!out2.exists());
}

#[test]
fn a_bad_min_fmax_is_refused_before_the_search() {
    let o = gbump()
        .args([
            "fit",
            "--scene",
            "torus_caps",
            "--budget",
            "max<=2",
            "--no-regress",
            "--min-fmax=-3",
            "--out",
            "/nonexistent/x",
        ])
        .assert()
        .failure();
    let t = text(o.get_output());
    assert!(t.contains("--min-fmax -3") && t.contains("fix:"), "{t}");
}

/// `gbump fit-table --scene S --write F`: one row per budget for the scene, the file equal to
/// what it prints; an unknown scene is refused before any fit, with nothing written.
#[test]
fn fit_table_writes_its_rows_for_the_scenes_asked() {
    let dir = tempfile::tempdir().unwrap();
    // bump_spot at a small size: three fits in seconds.
    let scene = dir.path().join("small_spot.toml");
    let text_of = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/scenes/bump_spot.toml")).unwrap();
    assert!(text_of.contains("size = [128, 64]"));
    std::fs::write(&scene, text_of.replace("size = [128, 64]", "size = [48, 24]")).unwrap();
    let table = dir.path().join("table.md");
    let o = gbump()
        .args(["fit-table", "--scene"])
        .arg(&scene)
        .arg("--write")
        .arg(&table)
        .assert()
        .success();
    let printed = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    let written = std::fs::read_to_string(&table).unwrap();
    assert_eq!(printed.trim_end(), written.trim_end());
    let rows: Vec<&str> = written.lines().filter(|l| l.contains("small_spot.toml")).collect();
    assert_eq!(rows.len(), gbump::fit::table::BUDGETS.len(), "{written}");
    for b in gbump::fit::table::BUDGETS {
        assert!(rows.iter().any(|r| r.contains(&format!("`{b}`"))), "{b}: {written}");
    }
    assert!(String::from_utf8_lossy(&o.get_output().stderr).contains("[3/3]"));
    let missing = dir.path().join("none.md");
    let o = gbump()
        .args(["fit-table", "--scene", "torus_caps", "--scene", "no_such_scene", "--write"])
        .arg(&missing)
        .assert()
        .failure();
    let t = text(o.get_output());
    assert!(t.contains("no_such_scene") && !t.contains("[1/"), "{t}");
    assert!(!missing.exists());
}

/// A fit whose chosen configuration fails its regression (here a Verilator that crashes) writes
/// nothing: a fit.toml beside a failed run would read as a verified choice. The message says
/// so, and the crash's fix.
#[test]
fn a_fit_whose_regression_fails_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let bin = dir.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    let fake = bin.join("verilator");
    std::fs::write(
        &fake,
        "#!/bin/sh\nif [ \"$1\" = --version ]; then exec /usr/bin/verilator --version; fi\nkill -SEGV $$\n",
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap());
    let out = dir.path().join("o");
    let o = gbump()
        .env("PATH", path)
        .args(["fit", "--scene", "torus_caps", "--budget", "max<=2", "--out"])
        .arg(&out)
        .arg("--work")
        .arg(dir.path().join("w"))
        .output()
        .unwrap();
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    assert!(
        t.contains("did not pass") && t.contains("were not written") && t.contains("reinstall"),
        "{t}"
    );
    assert!(!out.join("fit.toml").exists() && !out.join("front.csv").exists(), "{t}");
}
