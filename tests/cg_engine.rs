//! The Cg Tutorial's per-fragment bump mapping (ch. 8) as a bit-accurate path (`gbump config
//! --engine cg`): L and H interpolated and read through a normalisation cube map
//! (`normalise_cube`), the specular power by successive squarings (`power_unit =
//! "squaring"`), and geometric self-shadowing (`self_shadow`) where the scene asks for it.
//! Its golden images are exact (checked-in PNGs), it tracks its own f64 equations and the
//! Cg engine's f64 model, and self-shadowing changes exactly the pixels it should.

use assert_cmd::Command;
use gbump::config::PowerUnitKind;
use gbump::engines::report::{compare, golden_image, render};
use gbump::engines::{engine, Maps};
use gbump::render::output::codes_to_u8;
use gbump::scene::Scene;
#[path = "common/golden_png.rs"]
mod golden_png;

/// Scenes whose Cg path the PNGs hold: the brick wall lit from the lower left (its light
/// grazes the wall, so self-shadowing cuts), and a scene of shininess 20 (squared to 16).
const SCENES: [&str; 2] = ["cg_wall_lower_left", "blend_split"];

fn cg_config(s: &Scene) -> gbump::config::PipelineConfig {
    engine("cg").unwrap().fixed_config(s).unwrap().unwrap()
}

#[test]
fn the_cg_path_is_the_cube_map_squarings_and_self_shadowing() {
    let s = Scene::load("cg_wall_lower_left").unwrap();
    assert!(s.self_shadowing);
    let cfg = cg_config(&s);
    assert_eq!(cfg.power_unit, PowerUnitKind::Squaring);
    assert_eq!(cfg.cube_map_face, gbump::engines::cg::CUBE_FACE);
    assert!(cfg.self_shadow && cfg.renormalise && cfg.interpolate_k);
    // A scene that does not ask for self-shadowing gets none.
    assert!(!cg_config(&Scene::load("blend_split").unwrap()).self_shadow);
    // The command prints the same configuration.
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .args(["config", "--scene", "cg_wall_lower_left", "--engine", "cg"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains(&format!("# config hash {}", cfg.hash())), "{text}");
    for line in ["power_unit = \"squaring\"", "cube_map_face = 32", "self_shadow = true"] {
        assert!(text.contains(line), "{line}: {text}");
    }
    // The README states the squaring unit's latency from the unit's description.
    let lat = gbump::units::unit("power_unit").unwrap().latency(&cfg);
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let want = format!(
        "at the Cg path's depth {} the chain is cut in {}, the unit's output register and {} cuts (latency {lat})",
        cfg.pipeline_depth,
        ["one", "two", "three", "four"][lat as usize - 1],
        ["no", "one", "two", "three"][lat as usize - 1],
    );
    assert!(flat.contains(&want), "README should say: {want}");
}

#[test]
fn cg_bit_accurate_paths_match_their_pngs() {
    let mut failures = Vec::new();
    for name in SCENES {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let img = gbump::render::render(&s, &cg_config(&s), w, h, false).unwrap();
        let px = codes_to_u8(&img.golden, img.colour_max);
        failures.extend(golden_png::check(&format!("{name}_cg"), w, h, &px));
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// The golden image against its own f64 equations (cube map, squarings and self-shadowing
/// in f64) and against the Cg engine's f64 model, on every built-in scene (printed); and on
/// the grazing-light wall, self-shadowing darkens pixels and never brightens one.
#[test]
fn the_cg_path_tracks_its_equations_and_self_shadows() {
    for (name, _) in gbump::scene::builtin::ALL {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let cfg = cg_config(&s);
        let img = gbump::render::render(&s, &cfg, w, h, false).unwrap();
        let own = gbump::measure::image_metrics::compare(&img.golden, &img.gouraud, &img.covered, cfg.colour_max());
        let f64_img = render(&s, &[engine("cg").unwrap()], w, h, Maps::default()).unwrap().remove(0);
        let fixed = golden_image(&s, &cfg, &f64_img).unwrap();
        let model = compare(&fixed, &f64_img);
        println!(
            "{name}: against its f64 equations {:.2} dB, mean {:.3} LSB; against Cg's f64 model {:.2} dB, mean {:.3} LSB",
            own.psnr_db, own.mean_lsb, model.psnr_db, model.mean_lsb
        );
        assert!(own.psnr_db > 36.0 && own.mean_lsb < 2.5, "{name}: {own:?}");
        assert!(model.psnr_db > 30.0, "{name}: {model:?}");
    }
    let s = Scene::load("cg_wall_lower_left").unwrap();
    let (w, h) = (s.size[0] / 2, s.size[1] / 2);
    let on = cg_config(&s);
    let off = gbump::config::PipelineConfig {
        self_shadow: false,
        ..on.clone()
    };
    let a = gbump::render::render(&s, &on, w, h, false).unwrap().golden;
    let b = gbump::render::render(&s, &off, w, h, false).unwrap().golden;
    let darker = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert!(
        a.iter().zip(&b).all(|(x, y)| (0..3).all(|c| x[c] <= y[c])),
        "self-shadowing brightened a pixel"
    );
    println!("self-shadowing darkens {darker} of {} pixels", a.len());
    assert!(darker > 0);
}
