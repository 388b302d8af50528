//! The sweep as a user runs it: a small grid, its CSV/JSON/SVG, the Pareto front, and a
//! second run served from the cache with the same results.

use assert_cmd::Command;

#[test]
fn a_small_sweep_writes_tables_and_a_plot_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let space = dir.path().join("tiny.toml");
    std::fs::write(&space, "scene = \"cg_wall_front\"\n[base]\nlights = 1\nlight_mode = \"parallel\"\n[grid]\nnormal_bits = [5, 8]\npower_entries = [64, 2048]\n").unwrap();
    let work = dir.path().join("work");
    let run = || {
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .args(["sweep", "--yosys", "--space"])
            .arg(&space)
            .arg("--out")
            .arg(dir.path().join("out"))
            .arg("--work")
            .arg(&work)
            .assert()
            .success();
        // The skipped points are noted once (the space's check on loading once printed it too).
        let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
        assert_eq!(err.matches("2 of 4 grid points are invalid combinations").count(), 1, "{err}");
        String::from_utf8_lossy(&o.get_output().stdout).into_owned()
    };
    let t0 = std::time::Instant::now();
    let first = run();
    let cold = t0.elapsed();
    // power_entries = 2048 exceeds the 257 codes of an 8-bit dot product: those are skipped.
    assert!(first.contains("2 configurations"), "{first}");
    let csv = std::fs::read_to_string(dir.path().join("out/tiny.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
    assert!(csv.contains("normal_bits=5") && csv.contains("normal_bits=8"));
    let svg = std::fs::read_to_string(dir.path().join("out/tiny.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("paper: 10k-25k GE") && svg.matches("<circle").count() >= 2);
    let pts: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.path().join("out/tiny.json")).unwrap()).unwrap();
    assert!(pts.as_array().unwrap().iter().any(|p| p["pareto"] == true));
    assert!(pts.as_array().unwrap().iter().all(|p| p["top_ge"].as_f64().unwrap() > 1000.0));
    let t1 = std::time::Instant::now();
    let second = run();
    assert!(t1.elapsed() < cold / 2, "the second run should come from the cache");
    assert_eq!(std::fs::read_to_string(dir.path().join("out/tiny.csv")).unwrap(), csv);
    assert!(second.contains("2 configurations"));
    // The same grid sized by the area model (the default): the same error columns, each top
    // within 25 % of Yosys, and the plot says which area it shows.
    let model_run = || {
        Command::cargo_bin("gbump")
            .unwrap()
            .args(["sweep", "--space"])
            .arg(&space)
            .arg("--out")
            .arg(dir.path().join("model"))
            .arg("--work")
            .arg(&work)
            .assert()
            .success();
    };
    model_run();
    let model: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.path().join("model/tiny.json")).unwrap()).unwrap();
    for (m, y) in model.as_array().unwrap().iter().zip(pts.as_array().unwrap()) {
        assert_eq!((m["area_by"].as_str(), y["area_by"].as_str()), (Some("model"), Some("yosys")));
        assert_eq!(m["max_error_lsb"], y["max_error_lsb"]);
        let (a, b) = (m["top_ge"].as_f64().unwrap(), y["top_ge"].as_f64().unwrap());
        assert!((a - b).abs() <= 0.25 * b, "{}: model {a:.0} GE, Yosys {b:.0} GE", m["label"]);
    }
    let svg = std::fs::read_to_string(dir.path().join("model/tiny.svg")).unwrap();
    assert!(svg.contains("(area model)"), "the plot does not say its area is the model's");
    // A run with the cache whole is served from it (no point file is written again); a
    // cached point with any one field edited (its hash, an impossible area, error or PSNR) is
    // measured again, never served: both runs then give what they gave.
    let before = (
        std::fs::read_to_string(dir.path().join("out/tiny.json")).unwrap(),
        std::fs::read_to_string(dir.path().join("model/tiny.json")).unwrap(),
    );
    let points = || {
        let mut v: Vec<_> = std::fs::read_dir(work.join("points"))
            .unwrap()
            .map(|e| {
                let p = e.unwrap().path();
                let m = std::fs::metadata(&p).unwrap().modified().unwrap();
                (p, m)
            })
            .collect();
        v.sort();
        v
    };
    let cached = points();
    assert_eq!(cached.len(), 4, "two points, each sized by Yosys and by the model");
    std::thread::sleep(std::time::Duration::from_millis(20));
    run();
    model_run();
    assert_eq!(points(), cached, "a whole cache entry was measured again");
    // The model's area is checked against the model; Yosys's cannot be without Yosys.
    let (mut yosys_edits, mut model_edits): (Vec<(&str, serde_json::Value)>, Vec<(&str, serde_json::Value)>) = (
        vec![("config_hash", "4ac26b256a9a0341".into()), ("max_error_lsb", (-5.0).into())],
        vec![("top_ge", 1.0.into()), ("mean_error_lsb", 1e9.into())],
    );
    for (path, _) in &cached {
        let mut p: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
        let (field, value) = if p["area_by"] == "model" {
            model_edits.pop()
        } else {
            yosys_edits.pop()
        }
        .expect("two of each");
        p[field] = value;
        std::fs::write(path, serde_json::to_vec(&p).unwrap()).unwrap();
    }
    run();
    model_run();
    let after = (
        std::fs::read_to_string(dir.path().join("out/tiny.json")).unwrap(),
        std::fs::read_to_string(dir.path().join("model/tiny.json")).unwrap(),
    );
    assert!(after == before, "an edited cache entry was served");
    assert!(
        points().iter().zip(&cached).all(|(now, then)| now.1 != then.1),
        "an edited cache entry was not measured again"
    );
}

#[test]
fn power_space_finds_designs_within_one_lsb() {
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["power-space", "--max-n", "255"])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    let within: Vec<&str> = text.lines().filter(|l| l.ends_with("| yes |")).collect();
    assert!(within.iter().any(|l| l.contains("segmented") && l.contains("lerp")), "{text}");
    assert!(
        within.iter().any(|l| l.contains("table 256 nearest")),
        "with an 8-bit dot product the paper's table is within 1 LSB"
    );
}

#[test]
fn one_work_folder_never_serves_one_scenes_results_for_another() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "[base]\nlights = 2\nlight_mode = \"parallel\"\n[grid]\nnormal_bits = [8]\n";
    let run = |scene: &str, work: &str| -> String {
        let space = dir.path().join(format!("{scene}.toml"));
        std::fs::write(&space, format!("scene = \"{scene}\"\n{grid}")).unwrap();
        Command::cargo_bin("gbump")
            .unwrap()
            .args(["sweep", "--space"])
            .arg(&space)
            .arg("--out")
            .arg(dir.path().join(work).join("out"))
            .arg("--work")
            .arg(dir.path().join(work))
            .assert()
            .success();
        let csv = std::fs::read_to_string(dir.path().join(work).join(format!("out/{scene}.csv"))).unwrap();
        let row = csv.lines().nth(1).unwrap().to_string();
        row.split(',').nth(10).unwrap().to_string()
    };
    let torus = run("torus_caps", "shared");
    let wall_shared = run("cg_wall_front", "shared");
    // A fresh folder: the area model sizes the points, so only the scene's measurements
    // differ between the two runs.
    let wall_fresh = run("cg_wall_front", "fresh");
    assert_ne!(torus, wall_shared, "the second scene was served the first scene's PSNR");
    assert_eq!(wall_shared, wall_fresh, "a shared work folder and a fresh one disagree");
}

/// A grid point whose base or grid value is inert beside its other values (segments of a
/// table power unit) is the design it describes, not refused; points that differ only there
/// are one design, measured once.
#[test]
fn grid_points_differing_only_in_an_unused_field_are_one_design() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("space.toml");
    std::fs::write(
        &p,
        "scene = \"cg_wall_front\"\n[base]\npower_segments = 4\n[grid]\npower_unit = [\"table\", \"segmented\"]\ntriangle_banks = [2, 3]\nbump_state = [\"triangle\", \"fragment\"]\n",
    )
    .unwrap();
    let space = gbump::measure::sweep::Space::load(&p).unwrap();
    let cfgs = space.configs(&p.display().to_string()).unwrap();
    // 2 units x (2 bank counts under triangle state + 1 design under fragment state).
    assert_eq!(cfgs.len(), 6, "{:#?}", cfgs.iter().map(|c| &c.0).collect::<Vec<_>>());
    let table = cfgs
        .iter()
        .filter(|(_, c)| c.power_unit == gbump::config::PowerUnitKind::Table)
        .count();
    assert_eq!(table, 3);
    for (lab, c) in &cfgs {
        assert_eq!(c.clone().canonical().hash(), c.hash(), "{lab} is not canonical");
    }
}

/// A grid point with fewer light slots than the scene's bump lights cannot render it (`gbump
/// render` refuses it): skipped with a note that names it, never measured with its area
/// beside another design's image.
#[test]
fn points_that_cannot_render_the_scene_are_skipped_and_named() {
    let dir = tempfile::tempdir().unwrap();
    let space = dir.path().join("sp.toml");
    std::fs::write(&space, "scene = \"torus_caps\"\n[grid]\nlights = [1, 2]\n").unwrap();
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["sweep", "--space"])
        .arg(&space)
        .arg("--out")
        .arg(dir.path().join("out"))
        .arg("--work")
        .arg(dir.path().join("work"))
        .assert()
        .success();
    let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    assert!(
        err.contains("1 of the 2 designs in the grid cannot render the scene torus_caps and are skipped (the first, lights=1:")
            && err.contains("2 bump lights"),
        "{err}"
    );
    let pts: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.path().join("out/sp.json")).unwrap()).unwrap();
    let labels: Vec<&str> = pts.as_array().unwrap().iter().map(|p| p["label"].as_str().unwrap()).collect();
    assert_eq!(labels, ["lights=2"]);
}

/// A renamed field under its old name in a sweep space is said at its own line in the space
/// file, once, and refused beside its new name at that line (the composed points' TOML had
/// put both at 1:1, once per value).
#[test]
fn a_renamed_field_in_a_space_is_named_at_its_line() {
    let d = tempfile::tempdir().unwrap();
    let run = |text: &str| {
        std::fs::write(d.path().join("sp.toml"), text).unwrap();
        let o = std::process::Command::new(assert_cmd::cargo::cargo_bin("gbump"))
            .args(["sweep", "--space", "sp.toml", "--out", "o", "--work", "w"])
            .current_dir(d.path())
            .output()
            .unwrap();
        (o.status.success(), String::from_utf8_lossy(&o.stderr).into_owned())
    };
    let (ok, err) = run("scene = \"torus_caps\"\n[grid]\ndot_bits = [8]\ndot_frac_bits = [8]\n");
    assert!(
        !ok && err.contains("sp.toml:3") && err.contains("given twice") && !err.contains(":1:1"),
        "{err}"
    );
    let (ok, err) = run("scene = \"torus_caps\"\n[base]\nnormal_bits = 8\n[grid]\ndot_bits = [8]\n");
    assert!(ok, "{err}");
    assert_eq!(err.matches("is deprecated").count(), 1, "{err}");
    assert!(err.contains("sp.toml:5") && !err.contains(":1:1"), "{err}");
}
