//! The survey's engines (`gbump::engines`) against the Blinn reference. On a plane lit by a
//! distant light and seen by a parallel viewer every engine's approximation is exact, or
//! bounded by its own map's resolution: each is held to that, the actual difference printed.
//! On curved and locally lit scenes they must differ in the ways the paper says.

use assert_cmd::Command;
use gbump::engines::{engine, report, Maps, ENGINES};
use gbump::scene::Scene;

/// A bricked plane facing the camera, one directional light, shininess a power of two (so
/// the Cg Tutorial's squarings are exact), nearest bump filtering (so the Gouraud engines'
/// unnormalised filtered normal is the map's own).
const PLANE: &str = r#"
name = "engines_plane"
description = "a bricked plane under a distant light"
size = [96, 64]
ambient = [0.05, 0.05, 0.05]
self_shadowing = false

[camera]
eye = [0.0, 0.0, 6.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
height = 2.0

[[lights]]
kind = "directional"
direction = [0.3, 0.4, 1.0]
colour = [0.9, 0.9, 0.9]

[[objects]]
shape = { kind = "plane", size = [3.0, 2.0] }
segments = [6, 4]
uv_scale = [2.0, 1.0]
shininess = 8
texture = { kind = "constant", colour = [0.8, 0.45, 0.35] }
bump = { source = { kind = "bricks", rows = 8, cols = 4, mortar = 0.08 }, size = 128, strength = 3.0, method = "cg", filter = "nearest" }
"#;

fn plane_table(maps: Maps) -> report::Table {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("plane.toml");
    std::fs::write(&path, PLANE).unwrap();
    let all: Vec<_> = ENGINES.iter().collect();
    report::measure(&[path.display().to_string()], &all, None, maps).unwrap()
}

/// Largest error, in LSB, each engine may show on the plane with its maps at their finest:
/// floating-point noise, and for EMBM what bilinear reads of its finest map leave (measured
/// 0.00007 LSB, printed).
fn plane_bound(name: &str) -> f64 {
    match name {
        "embm" => 0.01,
        _ => 1e-6,
    }
}

const FINEST: Maps = Maps {
    renormalise_map: false,
    embm_map: gbump::limits::MAX_ENV_MAP_SIDE,
    cg_cube: gbump::limits::MAX_CUBE_SIDE,
};

#[test]
fn on_a_plane_every_engine_agrees_with_blinn_within_its_own_approximation() {
    // A 1024-texel cube face leaves at most atan(√2/1024) rad on L and H: under half an LSB.
    let t = plane_table(Maps { cg_cube: 1024, ..FINEST });
    let mut failures = Vec::new();
    for (e, r) in t.engines.iter().zip(&t.errors[0]) {
        println!(
            "{:16} max {:10.6} LSB, mean {:8.5} LSB, PSNR {:7.2} dB, seam max {:.6} LSB",
            e.name, r.max_lsb, r.mean_lsb, r.psnr_db, r.seam_max_lsb
        );
        let bound = if e.name == "cg" { 0.5 } else { plane_bound(e.name) };
        if r.max_lsb > bound {
            failures.push(format!("{}: {:.6} LSB > {bound}", e.name, r.max_lsb));
        }
        // On a plane no triangle's approximation differs from its neighbour's.
        if r.seam_max_lsb > bound.max(1e-6) {
            failures.push(format!("{}: a seam of {:.6} LSB on a plane", e.name, r.seam_max_lsb));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// A map-bound engine's error from its map shrinks as the map grows: EMBM against its
/// environment map's side (the paper: "reasonable lighting quality ... can only be achieved if
/// higher resolution textures are used"), the Cg engine against its cube map's face, each
/// measured against the same engine with its finest map.
#[test]
fn map_bound_engines_improve_with_their_maps() {
    let scene = Scene::load("torus_caps").unwrap();
    let img = |name: &str, maps: Maps| report::render(&scene, &[engine(name).unwrap()], 96, 72, maps).unwrap().remove(0);
    for (name, coarse, fine) in [
        ("embm", Maps { embm_map: 8, ..FINEST }, Maps { embm_map: 256, ..FINEST }),
        ("cg", Maps { cg_cube: 4, ..FINEST }, Maps { cg_cube: 64, ..FINEST }),
    ] {
        let best = img(name, FINEST);
        let (c, f) = (report::compare(&img(name, coarse), &best), report::compare(&img(name, fine), &best));
        println!(
            "{name}: against its finest map, coarse {:.3} LSB mean, fine {:.3} LSB mean",
            c.mean_lsb, f.mean_lsb
        );
        assert!(f.mean_lsb < c.mean_lsb / 4.0, "{name}: {} !< {} / 4", f.mean_lsb, c.mean_lsb);
    }
}

/// On curved surfaces the engines differ as the paper says: the per-pixel engines (TexRam,
/// VISA+ with quaternions, Harmony) stay close to Blinn; VISA+ with a per-triangle matrix has
/// seams the quaternion variant does not; the Gouraud engine, with L and H per triangle, is
/// the furthest of the rasteriser engines, and interpolating H (§6) brings it closer.
#[test]
fn on_curved_scenes_the_engines_rank_as_the_paper_says() {
    let all: Vec<_> = ENGINES.iter().collect();
    let t = report::measure(&["torus_caps".to_string()], &all, Some((160, 120)), Maps::default()).unwrap();
    let get = |n: &str| t.errors[0][t.engines.iter().position(|e| e.name == n).unwrap()];
    for e in &t.engines {
        let r = get(e.name);
        println!(
            "{:16} PSNR {:7.2} dB, max {:7.2}, mean {:.3}, seam max {:.2} mean {:.4}",
            e.name, r.psnr_db, r.max_lsb, r.mean_lsb, r.seam_max_lsb, r.seam_mean_lsb
        );
    }
    assert!(get("texram").psnr_db > 50.0 && get("harmony").psnr_db > 35.0);
    assert!(get("visa").seam_mean_lsb > 2.0 * get("visa_quaternion").seam_mean_lsb);
    assert!(get("visa_quaternion").psnr_db > get("visa").psnr_db);
    assert!(get("gouraud_h").mean_lsb < get("gouraud").mean_lsb);
}

#[test]
fn the_command_writes_its_table_sheet_and_csv_and_refuses_unknown_engines() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .args(["engines", "--scene", "cg_wall_front", "--size", "64x32", "--out"])
        .arg(dir.path())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    for e in ENGINES {
        assert!(
            text.contains(&format!("| cg_wall_front | {} |", e.name)),
            "{} missing:\n{text}",
            e.name
        );
    }
    for f in ["engines.md", "engines.csv", "engines.png"] {
        assert!(dir.path().join(f).is_file(), "{f}");
    }
    let img = image::open(dir.path().join("engines.png")).unwrap();
    assert!(img.width() > ENGINES.len() as u32 * 64 && img.height() > 2 * 32);
    // At a small size every column is still as wide as the longest engine name: no name is cut.
    let name_w = ENGINES.iter().map(|e| e.name.len() as u32).max().unwrap() * gbump::render::label::CHAR_W;
    assert!(name_w > 64, "the test needs a name wider than the image");
    assert!(
        img.width() >= ENGINES.len() as u32 * name_w,
        "{} px for {} columns of {name_w} px",
        img.width(),
        ENGINES.len()
    );
    let bad = Command::cargo_bin("gbump")
        .unwrap()
        .args(["engines", "--engine", "phong", "--out"])
        .arg(dir.path().join("bad"))
        .assert()
        .failure()
        .get_output()
        .stderr
        .clone();
    let msg = String::from_utf8(bad).unwrap();
    assert!(
        msg.contains("phong") && msg.contains("fix:") && msg.contains("visa_quaternion"),
        "{msg}"
    );
    assert!(!dir.path().join("bad").exists(), "a refused run wrote its folder");
}

/// The paper's claims, measured (`gbump claim NAME`), hold in the direction the paper says.
#[test]
fn the_papers_claims_hold_as_measured() {
    use gbump::engines::claims::claim;
    let ys = |c: &gbump::engines::claims::Claim, label: &str| -> Vec<f64> {
        c.series
            .iter()
            .find(|s| s.label.starts_with(label))
            .unwrap_or_else(|| panic!("no series {label}"))
            .points
            .iter()
            .map(|p| p.1)
            .collect()
    };
    // VISA+'s discontinuity grows with the angle between triangles; quaternions remove it.
    let v = claim("visa-seams").unwrap();
    for n in [8, 64] {
        let (visa, quat) = (ys(&v, &format!("VISA+ n = {n}")), ys(&v, &format!("quaternions n = {n}")));
        println!("n = {n}: VISA+ {visa:.3?}\n        quaternions {quat:.3?}");
        assert!(
            visa.last().unwrap() > &(5.0 * visa[0]),
            "VISA+ seams do not grow with the angle: {visa:?}"
        );
        assert!(
            visa.iter().zip(&quat).all(|(a, b)| b < &(a / 10.0)),
            "quaternions leave seams: {quat:?} against {visa:?}"
        );
        // The generated path's seams are the fixed point's own (about an LSB against Blinn,
        // pixel noise that does not grow with the angle) plus the model's discontinuity.
        let fixed = ys(&v, &format!("VISA+ bit-accurate n = {n}"));
        println!("        bit-accurate {fixed:.3?}");
        // In 8-bit output the generated path's seams are the fixed point's own (Harmony's
        // path, no per-triangle matrix) plus at most the f64 model's discontinuity, which
        // stays under half an LSB on average at every angle here.
        let harmony = ys(&v, &format!("Harmony bit-accurate n = {n}"));
        println!("        Harmony bit-accurate {harmony:.3?}");
        for ((f, h), m) in fixed.iter().zip(&harmony).zip(&visa) {
            assert!(*m < 0.5 && f - h < m + 0.5, "VISA+ {fixed:?}, Harmony {harmony:?}");
        }
    }
    // The flat-shading artefact: faceting falls with tessellation, the §5.4.2 fix and the §6
    // interpolation of H and L reduce it.
    let f = claim("flat-shading").unwrap();
    let (plain, fix, h, hl) = (
        ys(&f, "Gouraud bump"),
        ys(&f, "§5.4.2"),
        ys(&f, "§6 interpolated H"),
        ys(&f, "§6 interpolated H and L"),
    );
    println!("Gouraud {plain:.3?}\nfix {fix:.3?}\nH {h:.3?}\nH and L {hl:.3?}");
    assert!(plain.windows(2).all(|w| w[1] < w[0]), "{plain:?}");
    assert!(fix[0] < plain[0] / 2.0 && hl.iter().zip(&plain).all(|(a, b)| a < &(b / 2.0)));
    // Interpolating H alone helps, but the diffuse term stays faceted until L is too.
    assert!(h.iter().zip(&plain).all(|(a, b)| a < b) && hl.iter().zip(&h).all(|(a, b)| a < &(b / 2.0)));
    // Renormalising the interpolated vectors lowers the seams further at every tessellation.
    let hln = ys(&f, "renormalised H and L");
    println!("renormalised {hln:.3?}");
    assert!(hln.iter().zip(&hl).all(|(a, b)| a < b), "{hln:?} against {hl:?}");
    // EMBM: the map's share of the error falls with every doubling of the map.
    let e = claim("embm-resolution").unwrap();
    for s in &e.series {
        let y: Vec<f64> = s.points.iter().map(|p| p.1).collect();
        assert!(y.windows(2).all(|w| w[1] < w[0]), "{}: {y:?}", s.label);
    }
    // Its bit-accurate path at each map size it generates tracks the f64 engine, and its RAM
    // is four copies of both maps (8-bit colours: 24-bit words).
    let mut fixed_rows = 0;
    for row in e.markdown.lines().filter(|l| l.starts_with("| ") && !l.starts_with("| scene")) {
        let c: Vec<&str> = row.split('|').map(str::trim).collect();
        if c[7] == "–" {
            continue;
        }
        let (f64_db, fixed_db): (f64, f64) = (c[3].parse().unwrap(), c[7].parse().unwrap());
        assert!((f64_db - fixed_db).abs() < 0.5, "{row}");
        let side: u64 = c[2].parse().unwrap();
        assert_eq!(c[8].parse::<u64>().unwrap(), 2 * 4 * side * side * 24, "{row}");
        fixed_rows += 1;
    }
    assert_eq!(fixed_rows, 3 * 6, "{}", e.markdown);
    // The texture filter: renormalising the map's filtered normal lowers SGI's and Cg's error
    // at every bump strength.
    let m = claim("map-filter").unwrap();
    for engine in ["SGI", "Cg"] {
        let (filtered, renormalised) = (
            ys(&m, &format!("{engine}, as filtered")),
            ys(&m, &format!("{engine}, renormalised")),
        );
        println!("{engine}: as filtered {filtered:.3?}\n     renormalised {renormalised:.3?}");
        assert!(filtered.iter().zip(&renormalised).all(|(a, b)| b < a), "{engine}");
    }
    // And in bit-accurate form: the normalise_b unit (`renormalise_bump`) cuts the paper's
    // pipeline's error on the wall at every strength to a fraction of it.
    let (plain, fixed) = (
        ys(&m, "Gouraud bump, bit-accurate ("),
        ys(&m, "Gouraud bump, bit-accurate, renormalise_bump"),
    );
    println!("bit-accurate: {plain:.3?}\nrenormalise_bump: {fixed:.3?}");
    assert!(plain.iter().zip(&fixed).all(|(a, b)| b < &(a / 4.0)), "{plain:?} {fixed:?}");
    assert!(claim("phong").is_err());
}

/// The engines gbump generates as RTL (Gouraud bump mapping, paper §6's interpolating
/// variants, and SGI, whose datapath is `gouraud_hl`'s fed per-vertex k) carry their
/// bit-accurate path on every scene and no other engine claims one. On the plane a distant
/// light makes L, H and k the same at every vertex, so interpolating them changes nothing: the
/// unrenormalising paths' golden images, and so every figure, agree exactly, while the tops
/// differ (the interpolating ones take L and H per fragment).
#[test]
fn the_bit_accurate_paths_are_the_generated_engines_and_agree_on_the_plane() {
    let t = plane_table(Maps::default());
    let with: Vec<&str> = t
        .engines
        .iter()
        .zip(&t.fixed[0])
        .filter(|(_, f)| f.is_some())
        .map(|(e, _)| e.name)
        .collect();
    assert_eq!(
        with,
        [
            "blinn",
            "texram",
            "visa",
            "visa_quaternion",
            "embm",
            "sgi",
            "harmony",
            "gouraud",
            "gouraud_h",
            "gouraud_hl",
            "gouraud_hn",
            "gouraud_hln",
            "cg"
        ]
    );
    for (e, f) in t.engines.iter().zip(&t.fixed[0]) {
        assert_eq!(e.fixed.is_some(), f.is_some(), "{}", e.name);
    }
    let row = |name: &str| -> &report::Fixed {
        let i = t.engines.iter().position(|e| e.name == name).unwrap();
        t.fixed[0][i].as_ref().unwrap()
    };
    let e0 = row("gouraud").error;
    println!("bit-accurate paths on the plane: {e0:?}");
    for name in ["gouraud_h", "gouraud_hl", "sgi"] {
        let f = row(name);
        assert_eq!(
            (f.error.max_lsb, f.error.mean_lsb, f.error.psnr_db),
            (e0.max_lsb, e0.mean_lsb, e0.psnr_db),
            "{name}"
        );
    }
    // Renormalising a quantised unit vector moves it by at most an LSB of L and H, which the
    // dot products' rounding may pass on: within a colour LSB of the others. Harmony's path
    // renormalises the fetched normal as well (on a plane its frame is every vertex's),
    // TexRam's builds that frame again from its T and N, VISA+'s is the triangle's, its
    // quaternion variant's the vertices' rotation, and Blinn's forms H from the normalised L.
    for name in ["gouraud_hn", "gouraud_hln", "harmony", "texram", "visa", "visa_quaternion", "blinn"] {
        let f = row(name);
        println!("renormalised on the plane: {:?}", f.error);
        assert!(
            (f.error.max_lsb - e0.max_lsb).abs() <= 1.0 && (f.error.mean_lsb - e0.mean_lsb).abs() <= 0.05,
            "{:?}",
            f.error
        );
    }
    // EMBM's path stores its maps as colour codes and places the filter's sample to 1/16 of a
    // texel: within 3 LSB of Blinn on the plane, where its f64 model is within 0.3 (both
    // measured, printed).
    let embm = row("embm");
    println!("embm on the plane: bit-accurate {:?}", embm.error);
    assert!(embm.error.max_lsb <= 3.0 && embm.error.mean_lsb <= 0.3, "{:?}", embm.error);
    // Cg's path reads a cube map and squares: print it beside its f64 model.
    let cg = row("cg");
    let cg_f64 = &t.errors[0][t.engines.iter().position(|e| e.name == "cg").unwrap()];
    println!("cg on the plane: bit-accurate {:?}, f64 {cg_f64:?}", cg.error);
    let rows = [row("gouraud"), row("gouraud_h")];
    assert_ne!(rows[0].config_hash, rows[1].config_hash, "per-triangle and per-fragment tops");
    // The figures come from the configuration the table names, as `gbump area` would size it.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("plane.toml"), PLANE).unwrap();
    let s = Scene::load(&dir.path().join("plane.toml").display().to_string()).unwrap();
    let cfg = engine("gouraud_h").unwrap().fixed_config(&s).unwrap().unwrap();
    let area = gbump::measure::area_model::model_area(&cfg);
    assert_eq!(rows[1].config_hash, cfg.hash()[..8]);
    assert_eq!((rows[1].area_ge, rows[1].memory_bits), (area.top_ge, area.memory_bits));
    assert_eq!(rows[1].latency, gbump::rtlgen::top::latency(&cfg));
    let csv = t.csv();
    assert!(csv.lines().next().unwrap().ends_with("fixed_memory_bits,fixed_latency"));
    let fields = csv.lines().next().unwrap().split(',').count();
    assert!(csv.lines().all(|l| l.split(',').count() == fields), "{csv}");
    // Every engine has its path now: the table names none as f64 only.
    assert!(!t.markdown().contains("No bit-accurate path"));
}

/// `gbump config --engine E --scene S`: every reason line `# FIELD = VALUE: …` above the TOML
/// gives the value the TOML below it holds (a field the engine's path sets says so), for every
/// engine with a bit-accurate path on scenes with graded and on-off k, one and several lights.
#[test]
fn an_engines_config_comments_agree_with_its_values() {
    for scene in ["cg_wall_front", "torus_caps", "sphere_bricks_spots"] {
        for e in ENGINES.iter().filter(|e| e.fixed.is_some()) {
            let o = Command::cargo_bin("gbump")
                .unwrap()
                .args(["config", "--engine", e.name, "--scene", scene])
                .assert()
                .success();
            let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
            let toml_text: String = text.lines().filter(|l| !l.starts_with('#')).map(|l| format!("{l}\n")).collect();
            let cfg: gbump::PipelineConfig = toml::from_str(&toml_text).unwrap();
            let mut checked = 0;
            for l in text.lines() {
                let Some((field, rest)) = l.strip_prefix("# ").and_then(|r| r.split_once(" = ")) else {
                    continue;
                };
                if !field.chars().all(|c| c.is_ascii_lowercase() || c == '_') {
                    continue;
                }
                let value = rest.split(':').next().unwrap();
                assert_eq!(value, cfg.field_text(&toml_text, field), "{} on {scene}: {l}", e.name);
                checked += 1;
            }
            assert!(checked >= 4, "{} on {scene}: only {checked} reason lines in\n{text}", e.name);
            if cfg.power_unit == gbump::config::PowerUnitKind::Squaring {
                assert!(!text.contains("the table need never be reloaded"), "{} on {scene}:\n{text}", e.name);
            }
            // Advice to set a field holds for this configuration, or says it is refused here.
            for field in ["palette", "power_rom", "renormalise_bump"] {
                let advice = format!("{field} = true");
                for l in text.lines().filter(|l| l.starts_with('#') && l.contains(&advice)) {
                    let asked: String = toml_text
                        .lines()
                        .filter(|t| !t.starts_with(&format!("{field} =")))
                        .map(|t| format!("{t}\n"))
                        .collect::<String>()
                        + &advice;
                    let held = gbump::PipelineConfig::from_toml("advice.toml", &asked);
                    assert_eq!(
                        held.is_err(),
                        l.contains(&format!("{advice} is refused here")),
                        "{} on {scene}: {l}\n{held:?}",
                        e.name
                    );
                }
            }
        }
    }
}

/// `gbump engines --list` names every engine, with whether `gbump config --engine` takes it.
#[test]
fn the_engine_list_names_every_engine_and_its_path() {
    let o = Command::cargo_bin("gbump").unwrap().args(["engines", "--list"]).assert().success();
    let text = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    assert_eq!(text.lines().count(), ENGINES.len(), "{text}");
    for (l, e) in text.lines().zip(ENGINES) {
        let words: Vec<&str> = l.split_whitespace().collect();
        assert_eq!(words[0], e.name, "{l}");
        assert_eq!(l.contains("bit-accurate path"), e.fixed.is_some(), "{l}");
        let config = Command::cargo_bin("gbump")
            .unwrap()
            .args(["config", "--engine", e.name, "--scene", "cg_wall_front"])
            .output()
            .unwrap();
        assert_eq!(
            config.status.success(),
            e.fixed.is_some(),
            "{}: config --engine disagrees with the list",
            e.name
        );
    }
}
