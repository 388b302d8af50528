//! The generated RTL under real simulators (Icarus Verilog and Verilator must be installed:
//! scripts/install-tools.sh). Nothing here is skipped when a simulator is missing: the test
//! fails with the installer's name in the message.

#[path = "common/mutants.rs"]
mod mutants;

use assert_cmd::Command;
use gbump::sim::{Icarus, Simulator, Testbench, Verilator};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn gbump() -> Command {
    let mut c = Command::cargo_bin("gbump").unwrap();
    c.current_dir(root());
    c
}

fn regress(args: &[&str], work: &str) -> String {
    let out = gbump()
        .arg("regress")
        .args(args)
        .args(["--work", &format!("target/test-regress/{work}")])
        .assert();
    let o = out.get_output();
    let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "regress {args:?} failed:\n{text}");
    assert!(text.contains(", 0 failing run(s)"), "{text}");
    text
}

/// Every run line of a regress report: (sim, set, passed, failed).
fn runs(text: &str) -> Vec<(String, String, u64, u64)> {
    text.lines()
        .filter_map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            if f.len() == 5 && (f[0] == "icarus" || f[0] == "verilator") {
                Some((f[0].into(), f[1].into(), f[2].parse().ok()?, f[3].parse().ok()?))
            } else {
                None
            }
        })
        .collect()
}

/// The random counts of the default regression (Icarus, Verilator).
const FULL: (u64, u64) = (100_000, 1_000_000);
/// The other configurations' regressions: fewer random vectors and smaller scene images (every
/// scene still runs), so the suite stays within its time; `gbump regress --sim both` with the
/// config runs the full counts and image size. Icarus, a hundred times slower, is the second
/// opinion on the same kinds of sets: 3,000 random vectors per target (10,000 took a quarter
/// of these tests' time) where Verilator runs 200,000.
const SHORT: (u64, u64) = (3_000, 200_000);
/// The scene image of the short regressions: every scene, about 300 fragments each.
const SHORT_SCENES: &str = "32x24";

fn check_suite(text: &str, min_scenes: usize, counts: (u64, u64)) {
    check_suite_with(text, min_scenes, counts, 6);
}

/// [`check_suite`] with `power_sets` exhaustive power-unit sets (one for a squaring unit,
/// whose exponent is built in).
fn check_suite_with(text: &str, min_scenes: usize, counts: (u64, u64), power_sets: usize) {
    let r = runs(text);
    for sim in ["icarus", "verilator"] {
        let mine: Vec<_> = r.iter().filter(|x| x.0 == sim).collect();
        assert!(mine.iter().all(|x| x.3 == 0 && x.2 > 0), "{sim}: a run failed or was empty");
        let random_top = mine
            .iter()
            .find(|x| x.1.starts_with("random") && x.1.ends_with("_top"))
            .expect("random top set");
        assert_eq!(
            random_top.2,
            if sim == "icarus" { counts.0 } else { counts.1 },
            "{sim} random count"
        );
        assert!(mine.iter().any(|x| x.1 == "corners_level2_top"));
        // One top set also runs on the power table's power-up contents, nothing loaded.
        assert!(mine.iter().any(|x| x.1 == "corners_level2_top+power-up"), "{sim}: no power-up run");
        // The power unit exhaustively for the reset shininess and for n = 0, 1, 2, 254, 255, 1024.
        let power: Vec<_> = mine
            .iter()
            .filter(|x| x.1.starts_with("exhaustive_power_unit_n") && x.2 > 256)
            .collect();
        assert!(power.len() >= power_sets, "{sim}: exhaustive power-table sets: {power:?}");
        assert!(
            mine.iter().filter(|x| x.1.starts_with("scene_")).count() >= min_scenes,
            "{sim}: scene sets"
        );
    }
}

#[test]
fn regress_default_config_on_both_simulators() {
    // The default command: Verilator's full random count, Icarus's that of the other
    // configurations (its default of 100,000 random vectors on every unit took two minutes of
    // the suite; `scripts/run.sh` runs it whole), the scenes at a smaller image (every scene
    // still runs).
    let icarus = SHORT.0.to_string();
    let t = regress(
        &["--sim", "both", "--scene-size", SHORT_SCENES, "--random-icarus", &icarus],
        "default",
    );
    check_suite(&t, 12, (SHORT.0, FULL.1));
    // The defaults `scripts/run.sh` runs are FULL's.
    let help = gbump().args(["regress", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&help.stdout)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    for (flag, n) in [("--random <RANDOM>", FULL.1), ("--random-icarus <RANDOM_ICARUS>", FULL.0)] {
        let at = help.find(flag).unwrap_or_else(|| panic!("{flag} in {help}"));
        assert!(help[at..].contains(&format!("[default: {n}]")), "{flag}: {help}");
    }
}

/// The README's guarantee table states the counts the default regression runs here and the
/// command's own defaults.
#[test]
fn the_readme_states_the_default_regressions_counts() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let power = |n: u64| {
        let e = n.ilog10();
        assert_eq!(10u64.pow(e), n, "{n} is a power of ten");
        format!("10^{e}")
    };
    let want = format!(
        "the default configuration {},{:03} on Icarus / {} on Verilator per target, the others fewer, each test stating its own; `gbump regress --sim both` runs {} / {}",
        SHORT.0 / 1000,
        SHORT.0 % 1000,
        power(FULL.1),
        power(FULL.0),
        power(FULL.1)
    );
    assert!(flat.contains(&want), "README should say: {want}");
}

/// Short regressions of the other configurations (see [`SHORT`]).
fn regress_short(config: &str, work: &str, min_scenes: usize) {
    let t = regress_small_scenes(config, work, SHORT, &[]);
    check_suite(&t, min_scenes, SHORT);
}

/// A configuration's suite without the scenes, on both simulators, with 20,000 random
/// vectors on Verilator and 2,000 on Icarus.
fn regress_no_scenes(config: &str, work: &str) -> String {
    regress(
        &[
            "--sim",
            "both",
            "--config",
            config,
            "--random",
            "20000",
            "--random-icarus",
            "2000",
            "--no-scenes",
        ],
        work,
    )
}

#[test]
fn regress_one_light_parallel() {
    // Scenes with two bump lights do not fit one light slot; the other eleven run.
    regress_short("tests/configs/one_light_parallel.toml", "one_light_parallel", 11);
}

#[test]
fn regress_paper_sample_one_light() {
    // k_i as an on/off enable: the blends without their f·k multiplier.
    regress_short("tests/configs/paper_sample_one_light.toml", "paper_sample_one_light", 11);
}

/// `renormalise_bump`: the fetched bump normal through `normalise_b` before the dot products,
/// on the default serial top with the scenes (whose bilinear maps it renormalises), both
/// simulators, the unit's corners and random set among the runs, 0 mismatches. Symmetric
/// normals (its (2^(nb-1) - 1) multiply) at the narrowest and widest widths are in
/// `tests/fuzz_corners.rs` on Verilator, and `renormalise_bump_symmetric.toml` is linted.
#[test]
fn regress_renormalised_bump_normal_on_both_tops() {
    let t = regress(
        &[
            "--sim",
            "both",
            "--config",
            "tests/configs/renormalise_bump.toml",
            "--random-icarus",
            "2000",
            "--random",
            "100000",
            "--scene-size",
            SHORT_SCENES,
        ],
        "renormalise_bump",
    );
    let r = runs(&t);
    for sim in ["icarus", "verilator"] {
        let mine: Vec<_> = r.iter().filter(|x| x.0 == sim).collect();
        assert!(mine.iter().all(|x| x.3 == 0 && x.2 > 0), "{sim}: {t}");
        for set in ["corners_level2_normalise_b", "random"] {
            assert!(
                mine.iter().any(|x| x.1.starts_with(set) && x.1.ends_with("_normalise_b")),
                "{sim}: no {set} normalise_b set in\n{t}"
            );
        }
    }
    assert!(r.iter().filter(|x| x.1 == "scene_cg_wall_front_top").count() == 2, "{t}");
}

/// SGI's bit-accurate path (paper §3.4: L, H and k per vertex in tangent space, interpolated)
/// on the spotlit wall, on both simulators: the configuration `gbump config --engine sgi`
/// prints, the scene's fragments dumped under it (each carrying its own k), 0 mismatches.
#[test]
fn regress_sgi_on_the_spotlit_wall() {
    let work = root().join("target/test-regress/sgi_spot");
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    let scene = "tests/scenes/bump_spot.toml";
    let out = gbump().args(["config", "--scene", scene, "--engine", "sgi"]).assert().success();
    let cfg_path = work.join("sgi.toml");
    std::fs::write(&cfg_path, &out.get_output().stdout).unwrap();
    let cfg = gbump::config::PipelineConfig::load(&cfg_path).unwrap();
    assert!(cfg.interpolate_k, "{cfg:?}");
    let vectors = work.join("vectors");
    let source = format!("scene:{scene}");
    gbump()
        .args([
            "vectors",
            "--config",
            cfg_path.to_str().unwrap(),
            "--source",
            &source,
            "--size",
            "64x32",
            "--target",
            "top",
        ])
        .args(["--out", vectors.to_str().unwrap()])
        .assert()
        .success();
    let text = regress(
        &[
            "--sim",
            "both",
            "--config",
            cfg_path.to_str().unwrap(),
            "--vectors",
            vectors.to_str().unwrap(),
        ],
        "sgi_spot_runs",
    );
    let r = runs(&text);
    for sim in ["icarus", "verilator"] {
        let set = r
            .iter()
            .find(|x| x.0 == sim && x.1 == "scene_bump_spot_top")
            .unwrap_or_else(|| panic!("{sim}: no scene set in\n{text}"));
        assert!(set.2 > 1500 && set.3 == 0, "{sim}: {set:?}");
    }
}

#[test]
fn regress_renormalised_h_and_l() {
    // The normalise units before the dot products, symmetric normals (their scale in S);
    // scenes with more than two bump lights do not fit the two slots. Icarus evaluates the
    // Newton step's Booth rows slowly (about 2 ms a vector), so it runs 1,000 random vectors.
    let counts = (1_000u64, 100_000u64);
    let t = regress_small_scenes("tests/configs/renormalise_hl.toml", "renormalise_hl", counts, &[]);
    check_suite(&t, 10, counts);
    assert_unit_sets_ran(&t, "normalise");
}

/// `gbump regress --sim both --config CONFIG` with `counts` random top vectors (Icarus,
/// Verilator) and the scenes at 32x24, in work folder `work`, with `extra` arguments.
fn regress_small_scenes(config: &str, work: &str, counts: (u64, u64), extra: &[&str]) -> String {
    let (icarus, verilator) = (counts.0.to_string(), counts.1.to_string());
    let mut args = vec![
        "--sim",
        "both",
        "--config",
        config,
        "--random-icarus",
        &icarus,
        "--random",
        &verilator,
        "--scene-size",
        SHORT_SCENES,
    ];
    args.extend(extra);
    regress(&args, work)
}

/// `unit`'s own corner and random sets ran on both simulators.
fn assert_unit_sets_ran(t: &str, unit: &str) {
    let r = runs(t);
    for sim in ["icarus", "verilator"] {
        for set in ["corners", "random"] {
            assert!(
                r.iter()
                    .any(|x| x.0 == sim && x.1.starts_with(set) && x.1.ends_with(&format!("_{unit}"))),
                "{sim}: no {set} {unit} set in\n{t}"
            );
        }
    }
}

#[test]
fn regress_the_cg_tutorials_per_fragment_pipeline() {
    // The `cg` engine's path: normalise_cube units (Cg §8.2's normalisation cube map, 32
    // texels a face) in place of normalise, the squaring power unit (§8.3) and
    // self-shadowing (§8.5.3), on both simulators, with the cube unit's own corner and
    // random sets and the scenes of the power unit's shininess.
    let counts = (3_000u64, 100_000u64);
    let t = regress_small_scenes("tests/configs/cg_per_fragment.toml", "cg_per_fragment", counts, &[]);
    check_suite_with(&t, 4, counts, 1);
    assert_unit_sets_ran(&t, "normalise_cube");
    assert!(!runs(&t).iter().any(|x| x.1.ends_with("_normalise")), "{t}");
}

#[test]
fn regress_harmonys_interpolated_frame_pipeline() {
    // The `harmony` engine's path: the frame_transform unit places the fetched normal in the
    // fragment's frame (in_frame), normalise_b and normalise scale the normal, L and H; on
    // both simulators, the top's sets only (`--target top`: random, corners, power-up and
    // every scene that fits two lights, its frames and eye-space vectors from the
    // rasteriser). Its units are Blinn's, whose regression runs their own sets
    // (`frame_engine_units_are_blinns`).
    let t = regress_frame_top("tests/configs/harmony_frame.toml", "harmony_frame", &[]);
    assert!(t.contains("scene_cg_wall_front_top"), "{t}");
}

#[test]
fn regress_texrams_built_frame_pipeline() {
    // The `texram` engine's path: the frame_build unit forms the frame from the main
    // direction and the interpolated normal (in_frame's T and N lanes; the random sets drive
    // the B lanes too, which the top must not read), then Harmony's units; on both
    // simulators, the top's sets only, its units being Blinn's (see Harmony's above).
    regress_frame_top("tests/configs/texram_frame.toml", "texram_frame", &[]);
}

/// `gbump regress --target top` (and `--target U` for each of the engine's `own` units) on a
/// frame engine's top, both simulators, with every scene that fits two lights: only those
/// targets' sets run, none of them fails.
fn regress_frame_top(config: &str, work: &str, own: &[&str]) -> String {
    let counts = (1_000u64, 20_000u64);
    let mut targets = vec!["--target", "top"];
    for u in own {
        targets.extend(["--target", u]);
    }
    let t = regress_small_scenes(config, work, counts, &targets);
    check_suite_with(&t, 4, counts, 0);
    let r = runs(&t);
    let allowed =
        |set: &str| set.ends_with("_top") || set.ends_with("_top+power-up") || own.iter().any(|u| set.ends_with(&format!("_{u}")));
    assert!(r.iter().all(|x| allowed(&x.1)), "a set of another target ran:\n{t}");
    t
}

/// The frame engines whose regressions run only their top's sets and their own units'
/// (Harmony's, TexRam's, VISA+'s with quaternions) have Blinn's other units, Verilog for
/// Verilog but the configuration hash in the module names: the unit sets of
/// `regress_blinns_per_pixel_lighting` check the same logic.
#[test]
fn frame_engine_units_are_blinns() {
    use gbump::units::included;
    let load = |f: &str| gbump::PipelineConfig::load(&root().join(f)).unwrap();
    let blinn = load("tests/configs/blinn_pixel.toml");
    let bh = blinn.hash()[..8].to_string();
    for (f, own) in [
        ("tests/configs/texram_frame.toml", &[][..]),
        ("tests/configs/harmony_frame.toml", &[][..]),
        ("tests/configs/visa_quaternion_frame.toml", &["quat_frame"][..]),
    ] {
        let cfg = load(f);
        let h = cfg.hash()[..8].to_string();
        for u in included(&cfg).into_iter().filter(|u| !own.contains(&u.name())) {
            assert!(
                included(&blinn).iter().any(|b| b.name() == u.name()),
                "{f}: {} is not Blinn's",
                u.name()
            );
            let mine: Vec<(&str, String)> = u.verilog(&cfg).into_iter().map(|(n, v)| (n, v.replace(&h, &bh))).collect();
            assert_eq!(mine, u.verilog(&blinn), "{f}: {} differs from Blinn's", u.name());
        }
    }
}

#[test]
fn regress_blinns_per_pixel_lighting() {
    // The `blinn` engine's path: TexRam's frame with L and H formed at the pixel
    // (`pixel_lh`): H's normalise fed the halved sum of L's normalised output and the viewer
    // direction on the H lanes; on both simulators, with every scene that fits two lights
    // (the rasteriser sends each light's vector to the light unnormalised) and self-shadowing
    // on N·L.
    let counts = (1_000u64, 10_000u64);
    let t = regress_small_scenes("tests/configs/blinn_pixel.toml", "blinn_pixel", counts, &[]);
    check_suite_with(&t, 4, counts, 1);
    for unit in ["frame_build", "frame_transform", "normalise_b", "normalise"] {
        assert_unit_sets_ran(&t, unit);
    }
}

#[test]
fn regress_visa_quaternion_frame_pipeline() {
    // The `visa_quaternion` engine's path: the quat_frame unit forms the frame from the
    // interpolated quaternion (lanes 0 to 3) and normal (lanes 6 to 8); on both simulators,
    // the top's sets and the quat_frame unit's own corner and random sets, with every scene
    // that fits two lights; its other units are Blinn's (`frame_engine_units_are_blinns`).
    let t = regress_frame_top("tests/configs/visa_quaternion_frame.toml", "visa_quaternion_frame", &["quat_frame"]);
    assert_unit_sets_ran(&t, "quat_frame");
}

#[test]
fn regress_embms_environment_map_pipeline() {
    // EMBM (paper §3.3): env_coords and the two maps' env_fetch on both simulators, with
    // their own corner, random and exhaustive sets, and every built-in scene on its objects'
    // own maps (one set per object); the light path's units are absent.
    let t = regress_small_scenes("tests/configs/embm.toml", "embm", (2_000, 20_000), &[]);
    let r = runs(&t);
    for sim in ["icarus", "verilator"] {
        let scenes: Vec<_> = r.iter().filter(|x| x.0 == sim && x.1.starts_with("scene_")).collect();
        // Twelve scenes, cg_wall_floor's two objects in two sets.
        assert_eq!(scenes.len(), 13, "{sim}: {scenes:?}");
        assert!(scenes.iter().any(|x| x.1 == "scene_cg_wall_floor_o1_top"), "{sim}: {scenes:?}");
        // A set on its own maps has no power-up run: the power-up maps are not its.
        assert!(!r.iter().any(|x| x.1.starts_with("scene_") && x.1.ends_with("+power-up")), "{t}");
    }
    for unit in ["env_coords", "env_fetch_diffuse", "env_fetch_specular"] {
        assert_unit_sets_ran(&t, unit);
    }
    for absent in ["_dot_clamp", "_power_unit"] {
        assert!(!runs(&t).iter().any(|x| x.1.ends_with(absent)), "{absent} ran:\n{t}");
    }
    let r = runs(&t);
    for sim in ["icarus", "verilator"] {
        assert!(
            r.iter()
                .any(|x| x.0 == sim && x.1 == "exhaustive_env_fetch_diffuse_env_fetch_diffuse" && x.2 == 225),
            "{sim}: every block of the 16x16 map\n{t}"
        );
    }
}

/// A scene's EMBM set holds its object's maps, which the harnesses load: the same records
/// fail on the power-up maps (the harness run without them), and the RTL renders the scene
/// as the golden model does, from files and streamed.
#[test]
fn embm_scene_sets_run_on_their_objects_maps() {
    let dir = root().join("target/test-regress/embm_scene");
    let _ = std::fs::remove_dir_all(&dir);
    let cfg = "tests/configs/embm.toml";
    gbump()
        .args([
            "vectors",
            "--source",
            "scene:cg_wall_floor",
            "--size",
            "48x32",
            "--target",
            "top",
            "--config",
            cfg,
        ])
        .arg("--out")
        .arg(dir.join("v"))
        .assert()
        .success();
    let mut sets = Vec::new();
    for o in ["o0", "o1"] {
        let m = dir.join(format!("v/scene_cg_wall_floor_{o}_top.json"));
        let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&m).unwrap()).unwrap();
        assert!(
            j["env_maps"]["diffuse"]["name"].as_str().unwrap().ends_with("_env_diffuse.hex"),
            "{j}"
        );
        sets.push(m.display().to_string());
    }
    let work = dir.join("work").display().to_string();
    let t = regress(
        &["--sim", "both", "--config", cfg, "--vectors", &sets[0], "--vectors", &sets[1]],
        "embm_scene/work",
    );
    assert_eq!(runs(&t).len(), 4, "{t}");
    // The harness regress built, on the first set without its maps: the power-up maps light
    // another scene.
    let build = std::fs::read_dir(Path::new(&work).join("build"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.file_name().unwrap().to_string_lossy().starts_with("verilator_harness"))
        .expect("the harness build");
    let v = dir.join("v");
    let out = std::process::Command::new(build.join("harness"))
        .args([
            "--vectors",
            "scene_cg_wall_floor_o0_top.bin",
            "--table",
            "scene_cg_wall_floor_o0_top_power_table.hex",
        ])
        .current_dir(&v)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&out.stdout);
    // A verdict, with mismatches: not a harness that refused to run.
    let failed: u64 = log
        .lines()
        .find_map(|l| l.strip_suffix(" failed")?.rsplit(' ').next()?.parse().ok())
        .unwrap_or_else(|| panic!("no verdict line:\n{log}"));
    assert!(!out.status.success() && failed > 0, "{log}");
    // Rendered through the RTL and streamed: the same images and verdicts.
    let render_rtl = |config: &Path, tag: &str| {
        let r = gbump()
            .args(["render", "--rtl", "--scene", "cg_wall_floor", "--size", "48x32", "--config"])
            .arg(config)
            .arg("--out")
            .arg(dir.join(format!("img_{tag}")))
            .arg("--work")
            .arg(dir.join(format!("render_{tag}")))
            .assert()
            .success();
        let text = String::from_utf8_lossy(&r.get_output().stdout).into_owned() + &String::from_utf8_lossy(&r.get_output().stderr);
        assert!(text.contains(" 0 pixel(s) differ"), "{tag}: {text}");
    };
    render_rtl(&root().join(cfg), "both_maps");
    // A top with one blend has one map and one load port: its sets name and load that one.
    let diffuse_only = dir.join("diffuse_only.toml");
    std::fs::write(
        &diffuse_only,
        std::fs::read_to_string(root().join(cfg)).unwrap() + "specular = false\n",
    )
    .unwrap();
    render_rtl(&diffuse_only, "diffuse_only");
    let t = regress(
        &["--stream", "scene:cg_wall_floor", "--scene-size", "48x32", "--config", cfg],
        "embm_scene/stream",
    );
    assert_eq!(
        runs(&t).iter().filter(|x| x.1.starts_with("stream_scene_cg_wall_floor_o")).count(),
        2,
        "{t}"
    );
}

#[test]
fn regress_interpolated_h_and_l() {
    // Paper §6: each scene fragment carries its own interpolated L and H on the fragment
    // port; scenes with more than two bump lights do not fit the two slots.
    regress_short("tests/configs/interpolate_hl.toml", "interpolate_hl", 10);
}

#[test]
fn regress_colour_guard_bits_on_both_tops() {
    // Stage colours with guard bits and colour_round at the end: the serial top in Fig. 2's
    // order with the scenes, and a parallel top in Fig. 3's order rounding half to even.
    regress_short("tests/configs/colour_guard.toml", "colour_guard", 12);
    let t = regress_no_scenes("tests/configs/colour_guard_parallel.toml", "colour_guard_parallel");
    let r = runs(&t);
    // colour_round whole; texture_modulate's u11.3 x u8 pairs exceed the exhaustive cap, so
    // its random unit set (random<N>_texture_modulate, N per simulator).
    for (start, end) in [("exhaustive_colour_round", "_colour_round"), ("random", "_texture_modulate")] {
        let set = format!("{start}…{end}");
        assert!(
            r.iter()
                .filter(|x| x.1.starts_with(start) && x.1.ends_with(end) && x.3 == 0 && x.2 > 0)
                .count()
                == 2,
            "{set} on both simulators:\n{t}"
        );
    }
}

#[test]
fn regress_white_lights_on_their_scene_and_a_per_fragment_top() {
    // The configuration derived from a scene of white bump lights (no light-colour multiply,
    // no Lc in the bank RAM), regressed on that scene's own fragments too.
    let t = regress(
        &[
            "--sim",
            "both",
            "--scene",
            "tests/scenes/white_lights.toml",
            "--random-icarus",
            "2000",
            "--random",
            "20000",
            "--scene-size",
            SHORT_SCENES,
        ],
        "white_lights",
    );
    let r = runs(&t);
    assert!(
        r.iter().filter(|x| x.1 == "scene_white_lights_top" && x.3 == 0 && x.2 > 0).count() == 2,
        "the scene's own fragments on both simulators:\n{t}"
    );
    regress_no_scenes(
        "tests/configs/white_lights_fragment_parallel.toml",
        "white_lights_fragment_parallel",
    );
}

/// A white-light term that multiplies by 2^c instead of 2^c - 1 is caught by the blend's
/// random unit set and the top's, on both simulators (the corners saturate or round it away).
#[test]
fn a_white_light_term_without_its_subtract_is_caught() {
    use gbump::sim::regress::run_sets;
    let (cfg, work, rtl) = mutant_rtl(
        Some("tests/configs/white_lights_fragment_parallel.toml"),
        "mutant_white",
        &[("light_term", mutants::white_term_no_subtract)],
    );
    let o = mutant_dump_options();
    let vec_dir = work.join("vectors");
    let mut sets = Vec::new();
    let d = gbump::vectors::dump(
        &cfg,
        &gbump::vectors::Source::Random(20_000),
        &["diffuse_blend".into(), "top".into()],
        &vec_dir,
        &o,
    )
    .unwrap();
    sets.extend(d.iter().map(|s| (s.manifest.clone(), None)));
    let res = run_sets(&cfg, &sets, &rtl, &mutant_run_options(&work)).unwrap();
    assert_eq!(res.len(), 4);
    for r in res {
        let out = r.outcome.unwrap();
        assert!(out.failed >= 1, "{:?} {}: the mutant passed", r.sim, r.set);
    }
}

/// EMBM's units wrong in two ways, each caught on both simulators: the diffuse map's second
/// texel read from the first's address (by the unit's random and exhaustive sets and the
/// top's), and the last texel's sub-texel fraction one short (by the corners, which hold
/// the map's far edge).
#[test]
fn embm_mutants_are_caught() {
    use gbump::sim::regress::run_sets;
    let (cfg, work, rtl) = mutant_rtl(
        Some("tests/configs/embm.toml"),
        "mutant_embm",
        &[
            ("env_fetch_diffuse", mutants::env_fetch_second_texel),
            ("env_coords", mutants::env_coords_edge_fraction),
        ],
    );
    let o = mutant_dump_options();
    let mut sets = Vec::new();
    for (src, targets) in [
        (gbump::vectors::Source::Random(5_000), vec!["env_fetch_diffuse", "top"]),
        (
            gbump::vectors::Source::Exhaustive("env_fetch_diffuse".into()),
            vec!["env_fetch_diffuse"],
        ),
        (gbump::vectors::Source::Corners(2), vec!["env_coords"]),
    ] {
        let targets: Vec<String> = targets.into_iter().map(String::from).collect();
        let d = gbump::vectors::dump(&cfg, &src, &targets, &work.join("vectors"), &o).unwrap();
        sets.extend(d.iter().map(|s| (s.manifest.clone(), None)));
    }
    let res = run_sets(&cfg, &sets, &rtl, &mutant_run_options(&work)).unwrap();
    assert_eq!(res.len(), 8, "four sets on two simulators");
    for r in res {
        let out = r.outcome.unwrap();
        assert!(out.failed >= 1, "{:?} {}: the mutant passed", r.sim, r.set);
    }
}

#[test]
fn regress_power_table_as_a_rom() {
    // The table's write port tied off: every top set runs on the ROM's contents (the load
    // the benches still drive is ignored), the scenes of its one shininess among them.
    let t = regress(
        &[
            "--sim",
            "both",
            "--config",
            "tests/configs/power_rom.toml",
            "--random-icarus",
            "2000",
            "--random",
            "20000",
            "--scene-size",
            SHORT_SCENES,
        ],
        "power_rom",
    );
    assert!(runs(&t).iter().any(|x| x.1 == "scene_torus_caps_top" && x.3 == 0), "{t}");
}

#[test]
fn regress_four_lights_serial_dot10() {
    regress_short("tests/configs/four_serial_dot10.toml", "four_serial_dot10", 12);
}

/// Lints each configuration (`None`: the default); two tests so the suite lints on both cores.
fn lint_clean(work: &str, configs: &[Option<&str>]) {
    for cfg in configs {
        let mut c = gbump();
        c.args(["lint", "--work", work]);
        if let Some(p) = cfg {
            c.args(["--config", p]);
        }
        let o = c.assert().success();
        assert!(String::from_utf8_lossy(&o.get_output().stdout).contains("clean"), "{cfg:?}");
    }
}

/// The lint's Yosys check on one module: whether it passes, and Yosys's log.
fn yosys_check(verilog: &str) -> (bool, String) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.v"), verilog).unwrap();
    let script = gbump::yosys::scripts::check(&["m.v".to_string()], "m");
    gbump::yosys::run(&script, Path::new("lint.ys"), dir.path(), &[]).unwrap()
}

#[test]
fn the_synthesis_check_catches_latches_multiple_drivers_loops_and_passes_clean_logic() {
    let clean = "module m(input clk, input [3:0] a, input s, output reg [3:0] q);\n  always @(posedge clk) q <= s ? a : ~a;\nendmodule\n";
    let (ok, log) = yosys_check(clean);
    assert!(ok, "clean logic refused:\n{log}");
    // Each defect with the words Yosys refuses it in, so an unrelated failure does not pass.
    let defects = [
        (
            "latch",
            "module m(input [3:0] a, input s, output reg [3:0] q);\n  always @* if (s) q = a;\nendmodule\n",
            "t:$dlatch",
        ),
        (
            "two drivers",
            "module m(input [3:0] a, input [3:0] b, output [3:0] q);\n  assign q = a;\n  assign q = b;\nendmodule\n",
            "multiple conflicting drivers",
        ),
        (
            "combinational loop",
            "module m(input [3:0] a, output [3:0] q);\n  wire [3:0] x;\n  assign x = q + a;\n  assign q = x ^ 4'd1;\nendmodule\n",
            "found logic loop",
        ),
    ];
    for (what, v, why) in defects {
        let (ok, log) = yosys_check(v);
        assert!(
            !ok && log.contains(why),
            "{what}: the synthesis check did not refuse it for `{why}`:\n{log}"
        );
    }
}

#[test]
fn lint_is_clean_for_every_test_configuration() {
    lint_clean(
        "target/test-lint",
        &[
            None,
            Some("tests/configs/one_light_parallel.toml"),
            Some("tests/configs/paper_sample_one_light.toml"),
            Some("tests/configs/four_serial_dot10.toml"),
            Some("tests/configs/fuzz_found_wide_dot.toml"),
            Some("tests/configs/fuzz_found_equal_frac.toml"),
            Some("tests/configs/segmented_power.toml"),
        ],
    );
}

#[test]
fn lint_is_clean_for_every_other_test_configuration() {
    lint_clean(
        "target/test-lint-2",
        &[
            Some("tests/configs/palette_serial.toml"),
            Some("tests/configs/palette_parallel.toml"),
            Some("tests/configs/fragment_state.toml"),
            Some("tests/configs/three_banks_serial.toml"),
            Some("tests/configs/fuzz_found_serial_no_specular.toml"),
            Some("tests/configs/inferred_multipliers.toml"),
            Some("tests/configs/one_bit_k_fragment.toml"),
            Some("tests/configs/colour_guard.toml"),
            Some("tests/configs/colour_guard_parallel.toml"),
            Some("tests/configs/white_lights_fragment_parallel.toml"),
            Some("tests/configs/power_rom.toml"),
        ],
    );
}

#[test]
fn lint_is_clean_for_the_renormalising_configuration() {
    // Its own test: the normalise units are the slowest to synthesise, so they run beside the others.
    lint_clean(
        "target/test-lint-3",
        &[
            Some("tests/configs/renormalise_hl.toml"),
            Some("tests/configs/renormalise_bump.toml"),
            Some("tests/configs/renormalise_bump_symmetric.toml"),
            Some("tests/configs/cube_map_hl.toml"),
        ],
    );
}

#[test]
fn images_through_the_rtl_equal_the_golden_images() {
    for scene in ["torus_caps", "blend_split", "cylinder_smooth"] {
        let dir = tempfile::tempdir().unwrap();
        let o = gbump()
            .args(["render", "--rtl", "--size", "96x72", "--scene", scene, "--out"])
            .arg(dir.path())
            .assert()
            .success();
        let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
        assert!(text.contains("0 pixel(s) differ"), "{text}");
        let a = image::open(dir.path().join(format!("{scene}_rtl.png"))).unwrap().to_rgb8();
        let b = image::open(dir.path().join(format!("{scene}_golden.png"))).unwrap().to_rgb8();
        assert_eq!(a.as_raw(), b.as_raw());
        // A later run without --rtl (another size) leaves no RTL image of the earlier one.
        let o = gbump()
            .args(["render", "--size", "32x24", "--scene", scene, "--out"])
            .arg(dir.path())
            .assert()
            .success();
        let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
        assert!(text.contains(&format!("removed {scene}_rtl.png")), "{text}");
        assert!(!dir.path().join(format!("{scene}_rtl.png")).exists(), "a stale RTL image stayed");
    }
}

/// Vector dumps of the mutant tests: text and binary, seed 1.
fn mutant_dump_options() -> gbump::vectors::DumpOptions {
    gbump::vectors::DumpOptions::formats("test", true, true)
}

/// A mutant's RTL under `target/test-regress/<work>`: the configuration of `config` (None: the
/// default) written out, then for each `(file, mutate)` the first source whose name holds
/// `file` rewritten by `mutate`, which must find what it changes.
fn mutant_rtl(
    config: Option<&str>,
    work: &str,
    mutations: &[(&str, Mutant)],
) -> (gbump::PipelineConfig, PathBuf, gbump::sim::rtl_files::Rtl) {
    let cfg = config.map_or_else(gbump::PipelineConfig::default, |c| {
        gbump::PipelineConfig::load(&root().join(c)).unwrap()
    });
    let work = std::path::absolute(root().join("target/test-regress").join(work)).unwrap();
    let rtl = gbump::sim::regress::write_rtl(&cfg, &work.join("rtl"), "mutant").unwrap();
    for (file, mutate) in mutations {
        let f = rtl.sources.iter().find(|p| p.to_string_lossy().contains(file)).unwrap();
        let text = std::fs::read_to_string(f).unwrap();
        std::fs::write(f, mutate(&text).unwrap_or_else(|| panic!("{file}: nothing to mutate"))).unwrap();
    }
    (cfg, work, rtl)
}

type Mutant = fn(&str) -> Option<String>;

/// Runs of the mutant tests: both simulators, the given sets only, stalls and bubbles on,
/// stopping after 5 mismatches.
fn mutant_run_options(work: &Path) -> gbump::sim::regress::RegressOptions {
    gbump::sim::regress::RegressOptions {
        sims: vec![gbump::sim::Sim::Icarus, gbump::sim::Sim::Verilator],
        random_verilator: 0,
        random_icarus: 0,
        seed: 1,
        scenes: false,
        own_scenes: Vec::new(),
        scene_size: None,
        work: work.to_path_buf(),
        waves: false,
        max_errors: 5,
        command: "test".into(),
        bubbles: 7,
        stall: 13,
        power_up: false,
        targets: vec!["all".into()],
    }
}

/// `mutant` applied to `file` of `config`'s RTL, run on Icarus against one vector set per
/// `(target, source)`: every set must fail at least `min_failed` times. Returns the runs.
fn assert_mutant_caught(
    config: &str,
    work: &str,
    file: &str,
    mutant: Mutant,
    targets: &[(&str, gbump::vectors::Source)],
    min_failed: u64,
) -> Vec<gbump::sim::regress::RunResult> {
    let (cfg, work, rtl) = mutant_rtl(Some(config), work, &[(file, mutant)]);
    let vec_dir = work.join("vectors");
    let o = mutant_dump_options();
    let sets: Vec<_> = targets
        .iter()
        .map(|(t, src)| {
            let got = gbump::vectors::dump(&cfg, src, &[t.to_string()], &vec_dir, &o).unwrap();
            (got[0].manifest.clone(), None)
        })
        .collect();
    // Icarus only: building the mutant's Verilator models would take most of the test, and
    // the regressions run the real units on both.
    let opts = gbump::sim::regress::RegressOptions {
        sims: vec![gbump::sim::Sim::Icarus],
        ..mutant_run_options(&work)
    };
    let res = gbump::sim::regress::run_sets(&cfg, &sets, &rtl, &opts).unwrap();
    assert_eq!(res.len(), targets.len());
    for r in &res {
        let out = r.outcome.as_ref().unwrap();
        assert!(out.failed >= min_failed, "{file} mutant, {} set: it passed", r.set);
    }
    res
}

#[test]
fn a_wrong_rounding_constant_in_the_rtl_is_caught_and_reported() {
    use gbump::sim::regress::run_sets;
    let (cfg, work, rtl) = mutant_rtl(None, "mutant", &[("texture_modulate", mutants::texture_rounding)]);
    let vec_dir = work.join("vectors");
    let o = mutant_dump_options();
    let sets = gbump::vectors::dump(
        &cfg,
        &gbump::vectors::Source::Exhaustive("texture_modulate".into()),
        &["texture_modulate".into()],
        &vec_dir,
        &o,
    )
    .unwrap();
    let opts = mutant_run_options(&work);
    // The unit set runs through the all-units testbench; the random top set through the top
    // testbench on Icarus and the C++ harness on Verilator.
    let tops = gbump::vectors::dump(&cfg, &gbump::vectors::Source::Random(20_000), &["top".into()], &vec_dir, &o).unwrap();
    let top = tops[0].manifest.clone();
    let res = run_sets(&cfg, &[(sets[0].manifest.clone(), None), (top, None)], &rtl, &opts).unwrap();
    assert_eq!(res.len(), 4);
    for r in res {
        let out = r.outcome.unwrap();
        assert!(out.failed >= 5, "{:?} {}: the mutant passed", r.sim, r.set);
        let unit = if r.target == "top" { "gbump_pipeline" } else { "texture_modulate" };
        assert!(
            out.log.contains(&format!("MISMATCH unit {unit}"))
                && out.log.contains("expected")
                && out.log.contains("stopping after 5 mismatches"),
            "{}",
            out.log
        );
    }
}

/// Guard bits between the colour stages: a colour_round that truncates and a texture divider
/// with one shifted add fewer are each caught by their unit's exhaustive set, and the top's
/// random set catches them together, on both simulators.
#[test]
fn guard_bit_mutants_are_caught_by_their_unit_sets_and_the_top() {
    use gbump::sim::regress::run_sets;
    let (cfg, work, rtl) = mutant_rtl(
        Some("tests/configs/colour_guard.toml"),
        "mutant_guard",
        &[
            ("colour_round", mutants::colour_round_truncates),
            ("texture_modulate", mutants::texture_divider_term),
        ],
    );
    let vec_dir = work.join("vectors");
    let o = mutant_dump_options();
    let mut sets = Vec::new();
    for unit in ["colour_round", "texture_modulate"] {
        let d = gbump::vectors::dump(&cfg, &gbump::vectors::Source::Exhaustive(unit.into()), &[unit.into()], &vec_dir, &o).unwrap();
        sets.push((d[0].manifest.clone(), None));
    }
    let tops = gbump::vectors::dump(&cfg, &gbump::vectors::Source::Random(20_000), &["top".into()], &vec_dir, &o).unwrap();
    sets.push((tops[0].manifest.clone(), None));
    let res = run_sets(&cfg, &sets, &rtl, &mutant_run_options(&work)).unwrap();
    assert_eq!(res.len(), 6);
    for r in res {
        let out = r.outcome.unwrap();
        assert!(out.failed >= 5, "{:?} {}: the mutant passed", r.sim, r.set);
        let unit = if r.target == "top" { "gbump_pipeline" } else { r.target.as_str() };
        assert!(out.log.contains(&format!("MISMATCH unit {unit}")), "{}", out.log);
    }
}

/// normalise with a Newton step fewer is caught by its unit's random set and by the top's
/// random set (the table alone is within a few LSB, so only a bit-exact bench sees it).
#[test]
fn a_normalise_with_a_newton_step_fewer_is_caught() {
    use gbump::vectors::Source;
    let res = assert_mutant_caught(
        "tests/configs/renormalise_hl.toml",
        "mutant_newton",
        "normalise",
        mutants::normalise_step_fewer,
        &[("normalise", Source::Random(500)), ("top", Source::Random(500))],
        5,
    );
    for r in res {
        let out = r.outcome.unwrap();
        let unit = if r.target == "top" { "gbump_pipeline" } else { "normalise" };
        assert!(out.log.contains(&format!("MISMATCH unit {unit}")), "{}", out.log);
    }
}

/// The Cg path's three pieces, each broken alone, are caught on Icarus: the cube unit's
/// last-texel clamp by its corner set (a minor equal to the major; random draws almost never
/// land there), the self-shadowing gate by the top's random set (lights below the surface and
/// bumps facing away are among its draws), one squaring fewer by the power unit's exhaustive
/// set and the top's random set.
#[test]
fn the_cg_paths_mutants_are_caught() {
    use gbump::vectors::Source;
    let cases: [(&str, &str, Mutant, Vec<(&str, Source)>); 3] = [
        (
            "mutant_cube",
            "normalise_cube",
            mutants::cube_unclamped,
            vec![("normalise_cube", Source::Corners(1))],
        ),
        (
            "mutant_shadow",
            "gbump_pipeline",
            mutants::self_shadow_open,
            vec![("top", Source::Random(3_000))],
        ),
        (
            "mutant_squaring",
            "power_unit",
            mutants::squaring_one_fewer,
            vec![
                ("power_unit", Source::Exhaustive("power_unit".into())),
                ("top", Source::Random(3_000)),
            ],
        ),
    ];
    for (work, file, mutant, targets) in cases {
        assert_mutant_caught("tests/configs/cg_per_fragment.toml", work, file, mutant, &targets, 1);
    }
}

/// Harmony's frame transposed in one pair of elements (T_y read where B_x belongs): the
/// frame unit's random set and the top's random set both catch it; the identity-frame
/// corners could not.
#[test]
fn a_transposed_frame_is_caught() {
    use gbump::vectors::Source;
    assert_mutant_caught(
        "tests/configs/harmony_frame.toml",
        "mutant_frame",
        "frame_transform",
        mutants::frame_transposed,
        &[("frame_transform", Source::Random(2_000)), ("top", Source::Random(3_000))],
        1,
    );
}

/// Harmony's self-shadowing gate in the frame (N·L through a second frame_transform and a
/// dot_clamp per light) left open: the top's random set catches it (random frames and
/// lights put L below the frame's surface often).
#[test]
fn an_open_self_shadow_gate_in_a_frame_is_caught() {
    use gbump::vectors::Source;
    let cfg = gbump::config::PipelineConfig::load(std::path::Path::new("tests/configs/harmony_frame.toml")).unwrap();
    assert!(cfg.self_shadow && cfg.frame_transform, "the configuration gates in a frame");
    assert_mutant_caught(
        "tests/configs/harmony_frame.toml",
        "mutant_frame_gate",
        "gbump_pipeline",
        mutants::self_shadow_open,
        &[("top", Source::Random(3_000))],
        1,
    );
}

/// Blinn's path with light 0's half sum not halved (H's normalise reads the low bits of
/// L + V): the top's random set catches it.
#[test]
fn an_unhalved_pixel_half_vector_is_caught() {
    use gbump::vectors::Source;
    assert_mutant_caught(
        "tests/configs/blinn_pixel.toml",
        "mutant_pixel_lh",
        "gbump_pipeline",
        mutants::half_sum_not_halved,
        &[("top", Source::Random(2_000))],
        1,
    );
}

#[test]
fn a_reversed_frame_cross_product_is_caught() {
    use gbump::vectors::Source;
    assert_mutant_caught(
        "tests/configs/texram_frame.toml",
        "mutant_texram",
        "frame_build",
        mutants::frame_cross_reversed,
        &[("frame_build", Source::Random(2_000)), ("top", Source::Random(3_000))],
        1,
    );
}

/// The output buffer reads its RAM one entry ahead; an entry that is the head at the edge that
/// writes it must come from the bypass register. Stalled top runs on both simulators see the
/// difference (Icarus and Verilator both return the RAM's old word).
#[test]
fn an_output_buffer_that_reads_its_ram_during_the_write_is_caught() {
    use gbump::sim::regress::run_sets;
    let (cfg, work, rtl) = mutant_rtl(
        Some("tests/configs/one_light_parallel.toml"),
        "mutant_bypass",
        &[("gbump_pipeline", mutants::output_bypass)],
    );
    let o = mutant_dump_options();
    let vec_dir = work.join("vectors");
    let tops = gbump::vectors::dump(&cfg, &gbump::vectors::Source::Random(5_000), &["top".into()], &vec_dir, &o).unwrap();
    let opts = mutant_run_options(&work);
    let res = run_sets(&cfg, &[(tops[0].manifest.clone(), None)], &rtl, &opts).unwrap();
    assert_eq!(res.len(), 2);
    for r in res {
        let out = r.outcome.unwrap();
        assert!(out.failed >= 5, "{:?}: the mutant passed", r.sim);
        assert!(out.log.contains("MISMATCH unit gbump_pipeline"), "{}", out.log);
    }
}

/// A missing tool is named with its install command, and the run leaves no trace: the work
/// folder it would have made is not there afterwards (its lock file included).
#[test]
fn a_missing_simulator_is_an_error_that_names_the_fix() {
    let empty = tempfile::tempdir().unwrap();
    let d = tempfile::tempdir().unwrap();
    for (args, tool) in [
        (vec!["regress", "--sim", "icarus"], "iverilog"),
        (vec!["lint"], "verilator"),
        (vec!["area"], "yosys"),
    ] {
        let work = d.path().join(args[0]).join("work");
        let o = gbump()
            .env("PATH", empty.path())
            .args(&args)
            .arg("--work")
            .arg(&work)
            .assert()
            .failure();
        let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
        assert!(
            err.contains(&format!("{tool} is not installed")) && err.contains(&format!("apt-get install -y {tool}")),
            "{args:?}: {err}"
        );
        assert!(!d.path().join(args[0]).exists(), "{args:?} left {}", work.display());
    }
}

#[test]
fn truncated_or_corrupted_vectors_are_refused_before_simulation() {
    let dir = tempfile::tempdir().unwrap();
    for f in std::fs::read_dir(root().join("vectors")).unwrap() {
        let p = f.unwrap().path();
        if p.file_name().unwrap().to_string_lossy().starts_with("corners_top") {
            std::fs::copy(&p, dir.path().join(p.file_name().unwrap())).unwrap();
        }
    }
    let hex = dir.path().join("corners_top.hex");
    let text = std::fs::read_to_string(&hex).unwrap();
    std::fs::write(&hex, &text[..text.len() / 2]).unwrap();
    let o = gbump()
        .args(["regress", "--sim", "icarus", "--work", "target/test-regress/trunc", "--vectors"])
        .arg(dir.path().join("corners_top.json"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    assert!(
        err.contains("corners_top.hex") && err.contains("does not match its manifest") && err.contains("regenerate"),
        "{err}"
    );
    let bin = dir.path().join("corners_top.bin");
    let mut b = std::fs::read(&bin).unwrap();
    b[3] ^= 1;
    std::fs::write(&hex, &text).unwrap();
    std::fs::write(&bin, b).unwrap();
    let o = gbump()
        .args(["regress", "--sim", "verilator", "--work", "target/test-regress/trunc", "--vectors"])
        .arg(dir.path().join("corners_top.json"))
        .assert()
        .failure();
    assert!(String::from_utf8_lossy(&o.get_output().stderr).contains("corners_top.bin"));
}

#[test]
fn a_testbench_given_no_vectors_fails() {
    let cfg = gbump::PipelineConfig::default();
    let work = std::path::absolute(root().join("target/test-regress/empty")).unwrap();
    let rtl = gbump::sim::regress::write_rtl(&cfg, &work.join("rtl"), "x").unwrap();
    let exe = Icarus
        .build(
            &work.join("build"),
            &Testbench::new(
                &gbump::rtlgen::kit::tb_module_name(&cfg),
                &gbump::sim::testbench::tb_top(&cfg, &rtl),
            ),
            &rtl,
        )
        .unwrap();
    std::fs::write(work.join("empty.hex"), "").unwrap();
    let table = root().join(format!("rtl/power_table_{}.hex", &cfg.hash()[..8]));
    let plus = [
        format!("+vectors={}", work.join("empty.hex").display()),
        format!("+table={}", table.display()),
    ];
    let e = Icarus.run(&exe, &plus, None, &work, "empty").unwrap_err().to_string();
    assert!(e.contains("checked no vectors"), "{e}");
}

/// A set run alone carries its configuration: no --config or --scene needed to regress a
/// scene's vectors, and another configuration given is refused with the way out.
#[test]
fn a_set_run_alone_is_regressed_under_its_manifests_configuration() {
    let dir = tempfile::tempdir().unwrap();
    gbump()
        .args([
            "vectors",
            "--scene",
            "torus_caps",
            "--source",
            "random:40",
            "--target",
            "top",
            "--format",
            "hex",
            "--out",
        ])
        .arg(dir.path())
        .assert()
        .success();
    let hash = gbump::scene::pick_config(None, Some("torus_caps")).unwrap().hash();
    let o = gbump()
        .args(["regress", "--sim", "icarus", "--work", "target/test-regress/alone", "--vectors"])
        .arg(dir.path())
        .assert()
        .success();
    let out = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    assert!(
        out.contains(&format!("configuration {hash} from")) && out.contains("0 failing run(s)"),
        "{out}"
    );
    let o = gbump()
        .args(["regress", "--sim", "icarus", "--work", "target/test-regress/alone", "--vectors"])
        .arg(dir.path())
        .args(["--scene", "teapot_hat"])
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    assert!(err.contains("run each as `gbump regress --vectors MANIFEST` alone"), "{err}");
}

/// The generated testbench, run by hand as FuseSoC or a script would: exit code 0 only when
/// every vector passed; a mismatch, a line that is not hex digits, or a file that does not
/// open gives 1, and gbump's own verdict of the same runs still says what failed.
#[test]
fn the_testbench_exit_code_is_its_verdict() {
    let cfg = gbump::PipelineConfig::default();
    let work = std::path::absolute(root().join("target/test-regress/exit_code")).unwrap();
    let rtl = gbump::sim::regress::write_rtl(&cfg, &work.join("rtl"), "x").unwrap();
    let table = root().join(format!("rtl/power_table_{}.hex", &cfg.hash()[..8]));
    let good = std::fs::read_to_string(root().join("vectors/corners_top.hex")).unwrap();
    let sims: [(&dyn Simulator, &str); 2] = [(&Icarus, "icarus"), (&Verilator, "verilator")];
    for (sim, name) in sims {
        let work = work.join(name);
        let exe = sim
            .build(
                &work.join("build"),
                &Testbench {
                    waves: true,
                    ..Testbench::new(
                        &gbump::rtlgen::kit::tb_module_name(&cfg),
                        &gbump::sim::testbench::tb_top(&cfg, &rtl),
                    )
                },
                &rtl,
            )
            .unwrap();
        // The binary as a script or FuseSoC runs it, outside gbump.
        let direct = |plus: &[String]| {
            let mut c = if name == "icarus" {
                let mut c = std::process::Command::new("vvp");
                c.arg("-n").arg(&exe);
                c
            } else {
                std::process::Command::new(&exe)
            };
            let o = c.args(plus).current_dir(&work).output().unwrap();
            (o.status.code(), String::from_utf8_lossy(&o.stdout).to_string())
        };
        let run = |file: &str, text: &str| {
            let f = work.join(file);
            std::fs::write(&f, text).unwrap();
            let plus = [format!("+vectors={}", f.display()), format!("+table={}", table.display())];
            (direct(&plus), sim.run(&exe, &plus, None, &work, file))
        };
        let ((code, _), v) = run("good.hex", &good);
        assert_eq!(code, Some(0), "{name}");
        assert_eq!(v.unwrap().failed, 0);
        // The good set with record `r`'s digit `at` replaced by `d`, run: its exit code must
        // be 1; the verdict.
        let edited = |file: &str, r: usize, at: usize, d: char| {
            let mut lines: Vec<String> = good.lines().map(str::to_string).collect();
            lines[r].replace_range(at..at + 1, &d.to_string());
            let ((code, log), v) = run(file, &(lines.join("\n") + "\n"));
            assert_eq!(code, Some(1), "{name}: {file} exits 1:\n{log}");
            v
        };
        // One bit of the expected colour flipped is one mismatch.
        let out = gbump::vectors::targets::top_layout(&cfg).column("out_c").lsb as usize;
        let line2 = good.lines().nth(2).unwrap();
        let at = line2.len() - 1 - out / 4;
        let d = line2.as_bytes()[at] as char;
        let flipped = char::from_digit(d.to_digit(16).unwrap() ^ (1 << (out % 4)), 16).unwrap();
        let v = edited("mismatch.hex", 2, at, flipped);
        assert_eq!(v.unwrap().failed, 1, "{name}: the verdict reads past the exit line");
        // The failing run's waveform is whole: the exit closes it as $finish would.
        let fst = work.join("mismatch.fst");
        let _ = std::fs::remove_file(&fst);
        let plus = [
            format!("+vectors={}", work.join("mismatch.hex").display()),
            format!("+table={}", table.display()),
        ];
        let (ok, log, _) = sim.run_log(&exe, &plus, Some(&fst), &work, "waves").unwrap();
        let bytes = std::fs::metadata(&fst).map_or(0, |m| m.len());
        assert!(!ok && bytes > 4000, "{name}: a failing run's waveform is {bytes} bytes:\n{log}");
        // Judged, the waves are written under a temporary name and put in place, a failing
        // run's too, with no temporary left.
        let judged = work.join("judged.fst");
        let _ = std::fs::remove_file(&judged);
        let v = sim.run(&exe, &plus, Some(&judged), &work, "waves").unwrap();
        assert_eq!(v.failed, 1, "{name}");
        assert!(std::fs::metadata(&judged).is_ok_and(|m| m.len() > 4000), "{name}: no judged waves");
        let left: Vec<_> = std::fs::read_dir(&work)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("judged.fst") && n.contains(".tmp"))
            .collect();
        assert!(left.is_empty(), "{name}: {left:?}");
        let e = edited("malformed.hex", 4, 3, 'g').unwrap_err().to_string();
        assert!(e.contains("line 5: a character that is not a hex digit"), "{name}: {e}");
        // An x, z or ? digit is refused, not driven, on both simulators (Verilator is
        // two-state, so the testbench looks for the digit itself).
        for d in ['x', 'z', '?'] {
            let e = edited("unknown.hex", 6, 2, d).unwrap_err().to_string();
            assert!(e.contains("line 7 holds an x, z or ? digit"), "{name}, {d}: {e}");
        }
        let (code, log) = direct(&[format!("+vectors={}", work.join("absent.hex").display())]);
        assert_eq!(code, Some(1), "{name}: {log}");
        assert!(log.contains(gbump::rtlgen::testbench::EXIT_MARK), "{name}: {log}");
    }
    // The README quotes the last line a failed run prints.
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.contains(gbump::rtlgen::testbench::EXIT_MARK),
        "the README does not quote the exit line"
    );
}

fn readback(hex: &Path, width: u32, depth: usize) -> Vec<u64> {
    let work = tempfile::tempdir().unwrap();
    let exe = work.path().join("rb.vvp");
    let st = std::process::Command::new("iverilog")
        .args(["-g2005", "-o"])
        .arg(&exe)
        .arg(format!("-Prom_readback.WIDTH={width}"))
        .arg(format!("-Prom_readback.DEPTH={depth}"))
        .arg(format!("-Prom_readback.FILE=\"{}\"", hex.display()))
        .arg(root().join("testbench/rom_readback.v"))
        .status()
        .expect("iverilog is not installed: run scripts/install-tools.sh");
    assert!(st.success());
    let out = std::process::Command::new("vvp").arg("-n").arg(&exe).output().unwrap();
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter(|l| !l.is_empty() && !l.contains("$finish"))
        .map(|l| u64::from_str_radix(l.trim(), 16).unwrap_or_else(|_| panic!("{l}")))
        .collect()
}

#[test]
fn every_rom_read_by_a_simulator_equals_the_model() {
    use gbump::rtlgen::rom::{cube_map_rom, default_palette, palette_rom, parse, power_rom, RomFormat, DEFAULT_PALETTE};
    let cfg = gbump::PipelineConfig::default();
    let h = &cfg.hash()[..8];
    for (stem, rom) in [
        (format!("power_table_n16_{h}"), power_rom(&cfg, 16)),
        (
            format!("bump_palette_{DEFAULT_PALETTE}_{h}"),
            palette_rom(&cfg, &default_palette(&cfg), DEFAULT_PALETTE),
        ),
        ("cube_map_32x32x6_rgb8".to_string(), cube_map_rom(32)),
    ] {
        let dir = root().join("rtl/rom");
        assert_eq!(
            readback(&dir.join(format!("{stem}.hex")), rom.width, rom.words.len()),
            rom.words,
            "{stem}.hex under Icarus"
        );
        for f in [RomFormat::Mif, RomFormat::Coe] {
            let text = std::fs::read_to_string(dir.join(format!("{stem}.{}", f.ext()))).unwrap();
            assert_eq!(parse(&text, f).unwrap(), rom.words, "{stem}.{}", f.ext());
        }
    }
    // The reset contents the pipeline itself loads.
    let t = gbump::model::PowerTable::build(&cfg, cfg.shininess);
    let words: Vec<u64> = t.entries.iter().map(|&e| e as u64).collect();
    assert_eq!(readback(&root().join(format!("rtl/power_table_{h}.hex")), 9, 256), words);
}

#[test]
fn outputs_are_never_x_after_reset_and_an_ungated_output_is_caught() {
    use gbump::sim::regress::write_rtl;
    let cfg = gbump::PipelineConfig::default();
    let work = std::path::absolute(root().join("target/test-regress/xcheck")).unwrap();
    let vectors = root().join("vectors");
    let plus = [
        format!("+vectors={}", vectors.join("corners_top.hex").display()),
        format!("+table={}", vectors.join("corners_top_power_table.hex").display()),
    ];
    // The generated pipeline: no X, every vector passes.
    let rtl = write_rtl(&cfg, &work.join("rtl"), "x").unwrap();
    let exe = Icarus
        .build(
            &work.join("build"),
            &Testbench::new(
                &gbump::rtlgen::kit::tb_module_name(&cfg),
                &gbump::sim::testbench::tb_top(&cfg, &rtl),
            ),
            &rtl,
        )
        .unwrap();
    let ok = Icarus.run(&exe, &plus, None, &work, "x").unwrap();
    assert_eq!(ok.failed, 0, "{}", ok.log);
    // The same pipeline with its output gate removed: its X before the first result is reported.
    let top = rtl.sources.iter().find(|p| p.to_string_lossy().contains("gbump_pipeline")).unwrap();
    let text = std::fs::read_to_string(top).unwrap();
    let mutant_dir = work.join("mutant");
    let rtl2 = write_rtl(&cfg, &mutant_dir, "x").unwrap();
    let top2 = rtl2
        .sources
        .iter()
        .find(|p| p.to_string_lossy().contains("gbump_pipeline"))
        .unwrap();
    std::fs::write(top2, mutants::output_ungated(&text).expect("the output gate")).unwrap();
    let exe2 = Icarus
        .build(
            &work.join("build"),
            &Testbench::new(
                &gbump::rtlgen::kit::tb_module_name(&cfg),
                &gbump::sim::testbench::tb_top(&cfg, &rtl2),
            ),
            &rtl2,
        )
        .unwrap();
    let bad = Icarus.run(&exe2, &plus, None, &work, "x").unwrap();
    assert!(bad.failed > 0 && bad.log.contains("X on outputs after reset"), "{}", bad.log);
    // Once results have come out, the ungated output holds the last one while out_valid is
    // low, which the notes say is 0.
    assert!(bad.log.contains("out_c is not 0 while out_valid is low"), "{}", bad.log);
    // The C++ harness of `gbump regress` checks the same (Verilator has no X to show first).
    let top = gbump::rtlgen::units_v::module_name(&cfg, "gbump_pipeline");
    let cpp = gbump::sim::testbench::harness_top(&cfg);
    let exe3 = Verilator.build_harness(&work.join("build"), &top, &cpp, &rtl2).unwrap();
    let bin = vectors.join("corners_top.bin").display().to_string();
    let table = vectors.join("corners_top_power_table.hex").display().to_string();
    let log = match Verilator.run(&exe3, &["--vectors".into(), bin, "--table".into(), table], None, &work, "x") {
        Ok(o) => o.log,
        Err(e) => e.to_string(),
    };
    // Its own line, with the value it saw.
    assert!(log.contains("out_c is not 0 while out_valid is low: out_c="), "{log}");
}

#[test]
fn verilator_with_unique_x_values_agrees_with_the_model_over_several_seeds() {
    use gbump::sim::regress::write_rtl;
    let cfg = gbump::PipelineConfig::default();
    let work = std::path::absolute(root().join("target/test-regress/xunique")).unwrap();
    let rtl = write_rtl(&cfg, &work.join("rtl"), "x").unwrap();
    let tb = gbump::sim::testbench::tb_top(&cfg, &rtl);
    let exe = Verilator
        .build(
            &work.join("build"),
            &Testbench {
                x_unique: true,
                ..Testbench::new(&gbump::rtlgen::kit::tb_module_name(&cfg), &tb)
            },
            &rtl,
        )
        .unwrap();
    let v = root().join("vectors");
    for set in ["corners_top", "random256_top"] {
        for seed in [1, 7, 12345] {
            let args = [
                format!("+vectors={}", v.join(format!("{set}.hex")).display()),
                format!("+table={}", v.join(format!("{set}_power_table.hex")).display()),
                format!("+verilator+seed+{seed}"),
                "+verilator+rand+reset+2".to_string(),
            ];
            let o = Verilator.run(&exe, &args, None, &work, "x-unique").unwrap();
            assert!(o.failed == 0 && o.passed > 0, "{set} seed {seed}:\n{}", o.log);
        }
    }
}

#[test]
fn the_segmented_power_unit_in_the_pipeline_matches_the_model() {
    regress(
        &[
            "--sim",
            "both",
            "--config",
            "tests/configs/segmented_power.toml",
            "--random",
            "30000",
            "--random-icarus",
            "2000",
            "--no-scenes",
        ],
        "segmented",
    );
}

#[test]
fn the_palette_unit_matches_the_model_on_both_tops() {
    // Random vectors on Verilator and on Icarus, as the README's guarantee table states them.
    const RANDOM: u32 = 30_000;
    const RANDOM_ICARUS: u32 = 2_000;
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let thousands = |n: u32| format!("{},{:03}", n / 1000, n % 1000);
    let said = format!(
        "{} / {} random vectors (Verilator / Icarus)",
        thousands(RANDOM),
        thousands(RANDOM_ICARUS)
    );
    assert!(readme.contains(&said), "README.md should say: {said}");
    for (cfg, work, scenes) in [
        ("tests/configs/palette_serial.toml", "palette_serial", "--no-scenes"),
        // Without --no-scenes: the built-in scene sets are skipped, and regress says so.
        ("tests/configs/palette_parallel.toml", "palette_parallel", "--seed=1"),
    ] {
        let t = regress(
            &[
                "--sim",
                "both",
                "--config",
                cfg,
                "--random",
                &RANDOM.to_string(),
                "--random-icarus",
                &RANDOM_ICARUS.to_string(),
                scenes,
            ],
            work,
        );
        assert_eq!(t.contains("the built-in scene sets are skipped"), scenes != "--no-scenes", "{t}");
        let r = runs(&t);
        assert!(r.iter().all(|x| !x.1.starts_with("scene_")), "{t}");
        // Palette indices 0 and 255 are among the corners, and the palette is swept whole.
        for set in ["corners_level2_palette_fetch", "exhaustive_palette_fetch_palette_fetch"] {
            assert!(
                r.iter().filter(|x| x.1 == set && x.3 == 0 && x.2 > 0).count() == 2,
                "{set} on both simulators:\n{t}"
            );
        }
    }
}

#[test]
fn the_per_fragment_top_and_a_three_bank_top_match_the_model() {
    for (cfg, work) in [
        ("tests/configs/fragment_state.toml", "fragment_state"),
        ("tests/configs/three_banks_serial.toml", "three_banks"),
    ] {
        let t = regress_no_scenes(cfg, work);
        let r = runs(&t);
        assert!(
            r.iter()
                .filter(|x| x.1.starts_with("random") && x.1.ends_with("_top") && x.3 == 0 && x.2 > 0)
                .count()
                == 2,
            "the random top set on both simulators:\n{t}"
        );
    }
}

#[test]
fn the_configurations_the_fuzzer_found_simulate_clean() {
    for (cfg, work) in [
        ("tests/configs/fuzz_found_wide_dot.toml", "fuzz_found"),
        ("tests/configs/fuzz_found_equal_frac.toml", "fuzz_found_eq"),
    ] {
        regress_no_scenes(cfg, work);
    }
}

#[test]
fn random_configurations_generate_lint_and_simulate_clean() {
    let o = gbump()
        .args([
            "fuzz",
            "--configs",
            "2",
            "--seed",
            "7",
            "--random",
            "1000",
            "--work",
            "target/test-regress/fuzz",
        ])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    // Two random draws here; the fixed corners (`fuzz::corner_configs`) run in tests/fuzz_corners.rs.
    assert!(text.contains("fuzz: 2 configurations"), "{text}");
}

/// The top testbench builds and passes on both simulators for a configuration whose record
/// line is wider than Verilator's 2048-bit string limit (it decodes the line a character at
/// a time there).
#[test]
fn the_testbench_reads_records_wider_than_verilators_strings() {
    let cfg = gbump::PipelineConfig::from_toml(
        "wide",
        "lh_bits = 24\ncolour_bits = 12\nk_frac_bits = 12\nnormal_bits = 16\nbump_state = \"fragment\"\nframe_transform = true\n",
    )
    .unwrap();
    let digits = gbump::vectors::targets::top_layout(&cfg).hex_digits();
    assert!(8 * (digits + 2) > 2048, "{digits} digits: no longer wider than 2048 bits");
    let work = std::path::absolute(root().join("target/test-regress/wide_tb")).unwrap();
    let _ = std::fs::remove_dir_all(work.join("v"));
    let rtl = gbump::sim::regress::write_rtl(&cfg, &work.join("rtl"), "x").unwrap();
    let o = gbump::vectors::DumpOptions::formats("test", true, false);
    let sets = gbump::vectors::dump(&cfg, &gbump::vectors::Source::Corners(1), &["top".into()], &work.join("v"), &o).unwrap();
    let (m, dir) = gbump::vectors::verify(&sets[0].manifest).unwrap();
    let plus = [
        format!("+vectors={}", dir.join(&m.hex.as_ref().unwrap().name).display()),
        format!("+table={}", dir.join(&m.power_table.name).display()),
        format!("+count={}", m.count),
    ];
    let sims: [(&dyn Simulator, &str); 2] = [(&Icarus, "icarus"), (&Verilator, "verilator")];
    for (sim, name) in sims {
        let text = gbump::sim::testbench::tb_top(&cfg, &rtl);
        let exe = sim
            .build(
                &work.join(name),
                &Testbench::new(&gbump::rtlgen::kit::tb_module_name(&cfg), &text),
                &rtl,
            )
            .unwrap();
        let v = sim.run(&exe, &plus, None, &work, name).unwrap();
        assert_eq!((v.passed, v.failed), (m.count, 0), "{name}");
    }
}

/// Unit records stream one per clock, as a testbench written from the manifest drives them:
/// `light_accumulate`'s `acc_in` says it enters `latency - 1` edges after the record's other
/// inputs (the running sum fed back into the last stage), every other column that it enters
/// with them. Skewed as the manifest says, every record passes on both simulators; driven
/// with the others, the unit adds a later record's sum and the run fails.
#[test]
fn unit_records_stream_one_per_clock_with_each_column_entering_as_its_manifest_says() {
    let cfg = gbump::PipelineConfig::default();
    let unit = gbump::units::unit("light_accumulate").unwrap();
    let lat = unit.latency(&cfg);
    assert!(lat >= 2, "light_accumulate's latency {lat}: acc_in no longer enters late");
    let work = std::path::absolute(root().join("target/test-regress/unit_stream")).unwrap();
    let _ = std::fs::remove_dir_all(work.join("v"));
    let rtl = gbump::sim::regress::write_rtl(&cfg, &work.join("rtl"), "x").unwrap();
    let o = gbump::vectors::DumpOptions::formats("test", true, false);
    let sets = gbump::vectors::dump(
        &cfg,
        &gbump::vectors::Source::Random(2000),
        &["light_accumulate".into()],
        &work.join("v"),
        &o,
    )
    .unwrap();
    let (m, dir) = gbump::vectors::verify(&sets[0].manifest).unwrap();
    for c in &m.columns {
        let want = if c.name == "acc_in" { lat - 1 } else { 0 };
        assert_eq!(c.enters, want, "column {} of {}", c.name, sets[0].manifest.display());
    }
    let plus = [
        "+unit=light_accumulate".to_string(),
        format!("+vectors={}", dir.join(&m.hex.as_ref().unwrap().name).display()),
        format!("+table={}", dir.join(&m.power_table.name).display()),
    ];
    let tb = gbump::sim::testbench::tb_units(&cfg, &rtl);
    let skewed = format!("light_accumulate_acc_in = hist[{}]", lat - 1);
    assert!(tb.contains(&skewed), "the unit testbench drives acc_in otherwise");
    let aligned = tb.replace(&skewed, "light_accumulate_acc_in = hist[0]");
    let sims: [(&dyn Simulator, &str); 2] = [(&Icarus, "icarus"), (&Verilator, "verilator")];
    for (sim, name) in sims {
        for (text, skew) in [(&tb, true), (&aligned, false)] {
            let exe = sim
                .build(&work.join(format!("{name}_{skew}")), &Testbench::new("tb_units", text), &rtl)
                .unwrap();
            let (_, log, _) = sim.run_log(&exe, &plus, None, &work, name).unwrap();
            let (passed, failed) = gbump::sim::verdict::parse_summary(&log).unwrap_or_else(|| panic!("{name}: no summary:\n{log}"));
            if skew {
                assert_eq!((passed, failed), (m.count, 0), "{name}, acc_in skewed:\n{log}");
            } else {
                assert!(failed > 0, "{name}: acc_in driven with the other inputs passes:\n{log}");
            }
        }
    }
}
