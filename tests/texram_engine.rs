//! TexRam's per-fragment datapath (paper §3.1) as a bit-accurate path (`gbump config
//! --engine texram`): the frame built per fragment from the interpolated normal and main
//! direction by the `frame_build` unit, the bump normal placed in it and renormalised, L and
//! H interpolated in eye space and renormalised. Its golden images are exact (checked-in
//! PNGs); it tracks its own f64 equations and TexRam's f64 model; on a plane, where every
//! vertex frame is the same orthonormal frame, it is Harmony's path to within the
//! normalisations' rounding.

use gbump::engines::report::{compare, golden_image, render};
use gbump::engines::{engine, Maps};
use gbump::render::output::codes_to_u8;
use gbump::scene::Scene;
#[path = "common/golden_png.rs"]
mod golden_png;

/// Scenes whose TexRam path the PNGs hold: a curved, tessellated surface whose frames turn
/// across every triangle, and a textured one.
const SCENES: [&str; 2] = ["torus_caps", "blend_split"];

fn texram_config(s: &Scene) -> gbump::config::PipelineConfig {
    engine("texram").unwrap().fixed_config(s).unwrap().unwrap()
}

#[test]
fn the_texram_path_builds_its_frame_per_fragment() {
    let s = Scene::load("torus_caps").unwrap();
    let cfg = texram_config(&s);
    assert!(cfg.frame_build && cfg.frame_transform && cfg.renormalise_bump && cfg.renormalise);
    let units: Vec<_> = gbump::units::included(&cfg).iter().map(|u| u.name()).collect();
    for u in ["frame_build", "frame_transform", "normalise_b", "normalise"] {
        assert!(units.contains(&u), "{u} missing from {units:?}");
    }
    // The frame_build unit's latency is what its description says: two normalisations and a
    // registered cross product after each.
    let fb = gbump::units::unit("frame_build").unwrap();
    let norm = gbump::units::unit("normalise").unwrap();
    assert_eq!(fb.latency(&cfg), 2 * norm.latency(&cfg) + 2);
    // Harmony's path is the same top without the unit.
    let harmony = engine("harmony").unwrap().fixed_config(&s).unwrap().unwrap();
    assert_eq!(
        harmony,
        gbump::config::PipelineConfig {
            frame_build: false,
            ..cfg.clone()
        }
    );
}

#[test]
fn texram_bit_accurate_paths_match_their_pngs() {
    let mut failures = Vec::new();
    for name in SCENES {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let img = gbump::render::render(&s, &texram_config(&s), w, h, false).unwrap();
        let px = codes_to_u8(&img.golden, img.colour_max);
        failures.extend(golden_png::check(&format!("{name}_texram"), w, h, &px));
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// The golden image against its own f64 equations (the built frame, the renormalisations,
/// in f64) and against TexRam's f64 model, on every built-in scene (printed).
#[test]
fn the_texram_path_tracks_its_equations_and_texrams_model() {
    for (name, _) in gbump::scene::builtin::ALL {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let cfg = texram_config(&s);
        let img = gbump::render::render(&s, &cfg, w, h, false).unwrap();
        let own = gbump::measure::image_metrics::compare(&img.golden, &img.gouraud, &img.covered, cfg.colour_max());
        let f64_img = render(&s, &[engine("texram").unwrap()], w, h, Maps::default()).unwrap().remove(0);
        let fixed = golden_image(&s, &cfg, &f64_img).unwrap();
        let model = compare(&fixed, &f64_img);
        println!(
            "{name}: against its f64 equations {:.2} dB, mean {:.3} LSB; against TexRam's f64 model {:.2} dB, mean {:.3} LSB",
            own.psnr_db, own.mean_lsb, model.psnr_db, model.mean_lsb
        );
        // As Harmony's path: the renormalised 8-bit bump normal under a grazing light
        // (cg_wall_*) costs about 3 LSB mean, on the bump-space path too.
        assert!(own.psnr_db > 35.0 && own.mean_lsb < 3.5, "{name}: {own:?}");
        assert!(model.psnr_db > 28.0, "{name}: {model:?}");
    }
}

/// On a plane every vertex frame is the same orthonormal frame, so the frame built from its
/// T and N is that frame again: the TexRam path's golden image is Harmony's but for the
/// normalisations' rounding of the axes (printed).
#[test]
fn on_a_plane_the_built_frame_is_the_interpolated_one() {
    let s = Scene::load("cg_wall_front").unwrap();
    let (w, h) = (s.size[0] / 2, s.size[1] / 2);
    let built = texram_config(&s);
    let interpolated = gbump::config::PipelineConfig {
        frame_build: false,
        ..built.clone()
    };
    let a = gbump::render::render(&s, &built, w, h, false).unwrap();
    let b = gbump::render::render(&s, &interpolated, w, h, false).unwrap();
    let diff = |x: &[u32; 3], y: &[u32; 3]| (0..3).map(|c| x[c].abs_diff(y[c])).max().unwrap();
    let worst = a.golden.iter().zip(&b.golden).map(|(x, y)| diff(x, y)).max().unwrap();
    let differ = a.golden.iter().zip(&b.golden).filter(|(x, y)| x != y).count();
    println!(
        "built frame vs interpolated frame on a plane: {differ} of {} pixels differ, by {worst} LSB at most",
        a.golden.len()
    );
    assert!(
        worst <= 1 && differ * 100 <= a.golden.len(),
        "{differ} pixels differ, by up to {worst} LSB"
    );
}
