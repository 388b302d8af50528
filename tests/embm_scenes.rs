//! EMBM (paper §3.3) on scenes: the rasteriser's half of the bit-accurate path. Each object
//! gets its own two environment maps (its lights baked in at its centre, quantised to colour
//! codes), each triangle its 2×2 matrix, each fragment its interpolated sphere-map
//! coordinates; the golden model (`env_coords`, `env_fetch`, the blends as the bilinear
//! filter) shades them. Its golden images are exact (checked-in PNGs); it tracks its own f64
//! equations (`reference::embm_f64`) and the `embm` engine's f64 model.

use gbump::config::{NormalRange, PipelineConfig};
use gbump::engines::report::{compare, golden_image, render};
use gbump::engines::{engine, Maps};
use gbump::model::env_map::{coord_frac, coordinate};
use gbump::raster::{fragment::fragments, rasterise::rasterise, Prepared};
use gbump::render::output::codes_to_u8;
use gbump::scene::Scene;
#[path = "common/golden_png.rs"]
mod golden_png;

fn embm_config(s: &Scene) -> PipelineConfig {
    engine("embm").unwrap().fixed_config(s).unwrap().unwrap()
}

#[test]
fn the_embm_path_is_a_valid_embm_top_on_every_scene() {
    for (name, _) in gbump::scene::builtin::ALL {
        let s = Scene::load(name).unwrap();
        let cfg = embm_config(&s);
        cfg.validate(name).unwrap();
        assert_eq!(cfg.env_map_side(), gbump::engines::embm::EMBM_MAP, "{name}");
        let units: Vec<_> = gbump::units::included(&cfg).iter().map(|u| u.name()).collect();
        for u in ["env_coords", "env_fetch_diffuse", "env_fetch_specular"] {
            assert!(units.contains(&u), "{name}: {u} missing from {units:?}");
        }
        // Any number of lights: they are in the maps.
        s.check_config(&cfg, name).unwrap();
    }
}

#[test]
fn embm_paths_match_their_pngs() {
    let mut failures = Vec::new();
    for name in ["torus_caps", "blend_split"] {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let img = gbump::render::render(&s, &embm_config(&s), w, h, false).unwrap();
        let px = codes_to_u8(&img.golden, img.colour_max);
        failures.extend(golden_png::check(&format!("{name}_embm"), w, h, &px));
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// The bounds the README states for every built-in scene's EMBM golden image against its
/// own f64 equations (checked there by the test below).
const EMBM_MAX_LSB: f64 = 12.0;
const EMBM_MEAN_LSB: f64 = 1.0;

#[test]
fn the_readme_states_the_bounds_this_suite_checks() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let want = format!("within {EMBM_MAX_LSB} LSB max and {EMBM_MEAN_LSB} LSB mean of its own f64 equations (`tests/embm_scenes.rs`");
    assert!(flat.contains(&want), "README should say: {want}");
}

/// The golden image against its own f64 equations (the same maps, coordinates and filter
/// unrounded) and against the engine's f64 model, on every built-in scene (printed). The
/// rounding that separates them is the maps' colour codes and the 4-bit sub-texel position.
#[test]
fn the_embm_path_tracks_its_equations_and_its_engines_model() {
    for (name, _) in gbump::scene::builtin::ALL {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let cfg = embm_config(&s);
        let img = gbump::render::render(&s, &cfg, w, h, false).unwrap();
        let own = gbump::measure::image_metrics::compare(&img.golden, &img.gouraud, &img.covered, cfg.colour_max());
        let f64_img = render(&s, &[engine("embm").unwrap()], w, h, Maps::default()).unwrap().remove(0);
        let model = compare(&golden_image(&s, &cfg, &f64_img).unwrap(), &f64_img);
        println!(
            "embm {name}: against its f64 equations {:.2} dB, max {:.1}, mean {:.3} LSB; against the engine's f64 model {:.2} dB, mean {:.3} LSB",
            own.psnr_db, own.max_lsb, own.mean_lsb, model.psnr_db, model.mean_lsb
        );
        assert!(own.pixels > 500, "{name}: {own:?}");
        assert!(
            own.psnr_db > 40.0 && own.mean_lsb < EMBM_MEAN_LSB && own.max_lsb < EMBM_MAX_LSB,
            "{name}: {own:?}"
        );
        // The engine reads the same filtered normal and the same clamped maps at the same
        // size: its model is these equations, so the two figures agree.
        assert!((model.mean_lsb - own.mean_lsb).abs() < 0.005, "{name}: {model:?} against {own:?}");
    }
}

/// What the setup sends reproduces the f64 geometry: for every fragment, the exact
/// coordinate `env_coords` forms from the sent st, M and the fetched codes is the f64
/// coordinate (interpolated st plus M times the fetched normal's x and y) within the
/// rounding of st and M. A symmetric normal range, whose codes are the normal divided by
/// its scale, checks that M is sent times that scale as L and H are.
#[test]
fn the_sent_coordinates_are_the_f64_coordinates() {
    for range in [NormalRange::Binary, NormalRange::Symmetric] {
        let s = Scene::load("torus_caps").unwrap();
        let cfg = PipelineConfig {
            normal_range: range,
            ..embm_config(&s)
        };
        let p = Prepared::new(&s, &cfg, 96, 72).unwrap();
        let frags = fragments(&p, &rasterise(&p).unwrap());
        assert!(frags.len() > 1000);
        let g = (1u64 << coord_frac(&cfg)) as f64;
        let nb_one = (1u64 << (cfg.normal_bits - 1)) as f64;
        let lh_lsb = 1.0 / (1u64 << (cfg.lh_bits - 2)) as f64;
        let mut worst = 0f64;
        for f in &frags {
            let b = gbump::model::pipeline::shade_embm(&cfg, &p.objects[f.obj as usize].env, &f.state, &f.frag).b;
            let v = p.objects[f.obj as usize].mesh.corners(f.tri);
            let cam = &p.camera;
            // The fetched codes as the normal they stand for.
            let (du, dv) = (b[0] as f64 / nb_one * cfg.normal_scale(), b[1] as f64 / nb_one * cfg.normal_scale());
            let [mt, mb] = gbump::scene::sphere_map::triangle_matrix(cam, &v);
            // The fragment's barycentric weights are not kept: take st from what was sent.
            let st = [f.state.env.st[0], f.state.env.st[1]].map(|x| x as f64 * lh_lsb);
            let want = [st[0] + mt.x * du + mb.x * dv, st[1] + mt.y * du + mb.y * dv];
            let m = f.state.env.m;
            let got = [
                coordinate(&cfg, f.state.env.st[0], m[0], m[2], [b[0], b[1]]) as f64 / g,
                coordinate(&cfg, f.state.env.st[1], m[1], m[3], [b[0], b[1]]) as f64 / g,
            ];
            for a in 0..2 {
                worst = worst.max((got[a] - want[a]).abs());
            }
        }
        println!("{range:?}: sent coordinates within {worst:.2e} of f64 (L/H LSB {lh_lsb:.2e})");
        // M's rounding (half an LSB a component) times |du| + |dv| <= 2.
        assert!(worst <= lh_lsb, "{range:?}: {worst}");
    }
}

/// The interpolated coordinates are rounded once, per fragment, from the vertex normals'.
#[test]
fn the_interpolated_coordinates_are_the_vertex_normals_sphere_coordinates() {
    let s = Scene::load("torus_caps").unwrap();
    let cfg = embm_config(&s);
    let p = Prepared::new(&s, &cfg, 96, 72).unwrap();
    let gb = rasterise(&p).unwrap();
    let lh_lsb = 1.0 / (1u64 << (cfg.lh_bits - 2)) as f64;
    let mut n = 0;
    for hit in gb.hits.iter().flatten() {
        let st = gbump::raster::fragment::state_at(&p, hit).env.st;
        let v = p.objects[hit.obj as usize].mesh.corners(hit.tri);
        let want = gbump::scene::sphere_map::coords_at(&p.camera, &v, hit.bary);
        assert!(
            (st[0] as f64 * lh_lsb - want.x).abs() <= lh_lsb / 2.0 && (st[1] as f64 * lh_lsb - want.y).abs() <= lh_lsb / 2.0,
            "{st:?} for {want:?}"
        );
        n += 1;
    }
    assert!(n > 1000);
}

/// Each object's maps are its own lighting: texel for texel the f64 texel clamped and rounded
/// to colour codes (spot-checked against `embm_f64::texel`, the engine's own); the wall and
/// the floor of `cg_wall_floor` (one light, two places, two materials) get different maps.
#[test]
fn each_object_has_its_own_maps() {
    let s = Scene::load("cg_wall_floor").unwrap();
    let cfg = embm_config(&s);
    let p = Prepared::new(&s, &cfg, 64, 64).unwrap();
    let side = cfg.env_map_side();
    let max = cfg.colour_max() as f64;
    for (i, o) in p.objects.iter().enumerate() {
        assert_eq!(o.env.diffuse.len(), (side * side) as usize);
        for (x, y) in [(0, 0), (side / 2, side / 2), (side - 1, 3), (7, side - 2)] {
            let (sx, sy) = gbump::scene::sphere_map::texel_centre(side, x, y);
            let (d, sp) = gbump::scene::sphere_map::texel(&s, &p.camera, i, o.centre, sx, sy);
            let code = |v: f64| (v.clamp(0.0, 1.0) * max).round() as u32;
            let at = (y * side + x) as usize;
            assert_eq!(o.env.diffuse[at], d.to_array().map(code), "object {i} texel ({x}, {y})");
            assert_eq!(o.env.specular[at], sp.to_array().map(code), "object {i} texel ({x}, {y})");
        }
        // Lit somewhere: the maps are not blank.
        assert!(o.env.diffuse.iter().any(|t| t.iter().any(|&c| c > 0)), "object {i}");
    }
    assert_eq!(p.objects.len(), 2);
    assert_ne!(p.objects[0].env, p.objects[1].env, "two objects, two maps");
    // A stored texel is clamped: a light summing above full scale saturates in the map.
    let max = cfg.colour_max();
    assert!(p.objects.iter().all(|o| o.env.specular.iter().flatten().all(|&c| c <= max)));
}

/// A scene's EMBM sets are one per object, each naming its maps; the map readers' own unit
/// sets are left out of `--target all` (said) and refused when named, since their harness
/// has no load port.
#[test]
fn embm_scene_sets_are_per_object_with_their_maps() {
    use assert_cmd::Command;
    let dir = tempfile::tempdir().unwrap();
    let s = Scene::load("cg_wall_floor").unwrap();
    let cfg_path = dir.path().join("embm.toml");
    std::fs::write(&cfg_path, embm_config(&s).to_toml()).unwrap();
    let run = |target: &str, out: &str| {
        Command::cargo_bin("gbump")
            .unwrap()
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args([
                "vectors",
                "--source",
                "scene:cg_wall_floor",
                "--size",
                "48x32",
                "--target",
                target,
                "--config",
            ])
            .arg(&cfg_path)
            .arg("--out")
            .arg(dir.path().join(out))
            .output()
            .unwrap()
    };
    let out = run("all", "v");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{err}");
    assert!(err.contains("env_fetch_diffuse, env_fetch_specular left out"), "{err}");
    let v = dir.path().join("v");
    assert!(!v.join("scene_cg_wall_floor_o0_env_fetch_diffuse.json").exists());
    for o in 0..2 {
        let (m, _) = gbump::vectors::verify(&v.join(format!("scene_cg_wall_floor_o{o}_top.json"))).unwrap();
        let e = m.env_maps.expect("the object's maps");
        // The maps as the prepared scene holds them, word for word.
        let p = Prepared::new(&s, &m.config, 48, 32).unwrap();
        let text = std::fs::read_to_string(v.join(&e.diffuse.expect("a diffuse map").name)).unwrap();
        let words: Vec<u64> = text
            .lines()
            .filter(|l| !l.starts_with("//") && !l.trim().is_empty())
            .map(|l| u64::from_str_radix(l.trim(), 16).unwrap())
            .collect();
        let cb = m.config.colour_bits;
        let want: Vec<u64> = p.objects[o]
            .env
            .diffuse
            .iter()
            .map(|c| c[0] as u64 | (c[1] as u64) << cb | (c[2] as u64) << (2 * cb))
            .collect();
        assert_eq!(words, want, "object {o}");
        // A unit set names no maps: its harness cannot load them.
        let (u, _) = gbump::vectors::verify(&v.join(format!("scene_cg_wall_floor_o{o}_env_coords.json"))).unwrap();
        assert!(u.env_maps.is_none());
    }
    assert_ne!(
        std::fs::read(v.join("scene_cg_wall_floor_o0_top_env_diffuse.hex")).unwrap(),
        std::fs::read(v.join("scene_cg_wall_floor_o1_top_env_diffuse.hex")).unwrap(),
        "two objects, two maps"
    );
    let out = run("env_fetch_diffuse", "w");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success() && err.contains("only the top loads"), "{err}");
}

/// `gbump render` under an EMBM configuration names what its f64 image is: EMBM's own
/// equations, and within the bound above of the golden image.
#[test]
fn the_render_names_embms_equations() {
    use assert_cmd::Command;
    let dir = tempfile::tempdir().unwrap();
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "render",
            "--scene",
            "torus_caps",
            "--size",
            "96x72",
            "--config",
            "tests/configs/embm.toml",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{text}");
    let line = text
        .lines()
        .find(|l| l.contains("golden vs f64 EMBM equations"))
        .unwrap_or_else(|| panic!("{text}"));
    let max: f64 = line
        .split("max")
        .nth(1)
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(max < 12.0, "{line}");
}
