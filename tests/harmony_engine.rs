//! Harmony's per-fragment datapath (paper §3.5) as a bit-accurate path (`gbump config
//! --engine harmony`): the bump normal placed in the interpolated per-vertex frame by the
//! `frame_transform` unit and renormalised, L and H interpolated in eye space and
//! renormalised. Its golden images are exact (checked-in PNGs); it tracks its own f64
//! equations and Harmony's f64 model; on a plane, where every frame is the same, it is the
//! Gouraud pipeline with interpolated, renormalised L and H to within the transform's
//! rounding.

use gbump::engines::report::{compare, golden_image, render};
use gbump::engines::{engine, Maps};
use gbump::render::output::codes_to_u8;
use gbump::scene::Scene;
#[path = "common/golden_png.rs"]
mod golden_png;

/// Scenes whose Harmony path the PNGs hold: a curved, tessellated surface whose frames turn
/// across every triangle, and a textured one.
const SCENES: [&str; 2] = ["torus_caps", "blend_split"];

fn harmony_config(s: &Scene) -> gbump::config::PipelineConfig {
    engine("harmony").unwrap().fixed_config(s).unwrap().unwrap()
}

#[test]
fn the_harmony_path_is_the_frame_transform_with_renormalised_vectors() {
    let s = Scene::load("torus_caps").unwrap();
    let cfg = harmony_config(&s);
    assert!(cfg.frame_transform && cfg.renormalise_bump && cfg.renormalise && cfg.interpolate_k);
    assert!(!cfg.self_shadow);
    let units: Vec<_> = gbump::units::included(&cfg).iter().map(|u| u.name()).collect();
    for u in ["frame_transform", "normalise_b", "normalise"] {
        assert!(units.contains(&u), "{u} missing from {units:?}");
    }
    // The frame enters with the fragment: a port of nine L/H words.
    let ports = gbump::rtlgen::top::port_list(&cfg);
    let frame = ports.iter().find(|p| p.name == "in_frame").expect("in_frame port");
    assert_eq!((frame.lanes, frame.fmt), (9, cfg.lh_fmt()));
    // A top without the unit has no such port.
    let mut plain = cfg.clone();
    plain.frame_transform = false;
    assert!(!gbump::rtlgen::top::port_list(&plain).iter().any(|p| p.name == "in_frame"));
}

#[test]
fn harmony_bit_accurate_paths_match_their_pngs() {
    let mut failures = Vec::new();
    for name in SCENES {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let img = gbump::render::render(&s, &harmony_config(&s), w, h, false).unwrap();
        let px = codes_to_u8(&img.golden, img.colour_max);
        failures.extend(golden_png::check(&format!("{name}_harmony"), w, h, &px));
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// The golden image against its own f64 equations (the frame, the renormalisations, in f64)
/// and against Harmony's f64 model, on every built-in scene (printed).
#[test]
fn the_harmony_path_tracks_its_equations_and_harmonys_model() {
    for (name, _) in gbump::scene::builtin::ALL {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let cfg = harmony_config(&s);
        let img = gbump::render::render(&s, &cfg, w, h, false).unwrap();
        let own = gbump::measure::image_metrics::compare(&img.golden, &img.gouraud, &img.covered, cfg.colour_max());
        let f64_img = render(&s, &[engine("harmony").unwrap()], w, h, Maps::default()).unwrap().remove(0);
        let fixed = golden_image(&s, &cfg, &f64_img).unwrap();
        let model = compare(&fixed, &f64_img);
        println!(
            "{name}: against its f64 equations {:.2} dB, mean {:.3} LSB; against Harmony's f64 model {:.2} dB, mean {:.3} LSB",
            own.psnr_db, own.mean_lsb, model.psnr_db, model.mean_lsb
        );
        // The renormalised bump normal keeps the normal's 7 fraction bits; where a bright
        // light grazes a wall (cg_wall_*) that costs about 3 LSB mean, the same on the
        // bump-space path with the same units.
        assert!(own.psnr_db > 35.0 && own.mean_lsb < 3.5, "{name}: {own:?}");
        assert!(model.psnr_db > 28.0, "{name}: {model:?}");
    }
}

/// On a plane every vertex frame is the same, so placing the normal in the frame and
/// lighting with eye-space vectors is the bump-space pipeline with the same vectors
/// interpolated: the two golden images agree but for the transform's rounding (printed).
#[test]
fn on_a_plane_the_frame_path_is_the_bump_space_path() {
    let s = Scene::load("cg_wall_front").unwrap();
    let (w, h) = (s.size[0] / 2, s.size[1] / 2);
    let framed = harmony_config(&s);
    let bump_space = gbump::config::PipelineConfig {
        frame_transform: false,
        ..framed.clone()
    };
    let a = gbump::render::render(&s, &framed, w, h, false).unwrap();
    let b = gbump::render::render(&s, &bump_space, w, h, false).unwrap();
    let diff = |x: &[u32; 3], y: &[u32; 3]| (0..3).map(|c| x[c].abs_diff(y[c])).max().unwrap();
    let worst = a.golden.iter().zip(&b.golden).map(|(x, y)| diff(x, y)).max().unwrap();
    let differ = a.golden.iter().zip(&b.golden).filter(|(x, y)| x != y).count();
    println!(
        "frame path vs bump-space path on a plane: {differ} of {} pixels differ, by {worst} LSB at most",
        a.golden.len()
    );
    assert!(
        worst <= 1 && differ * 100 <= a.golden.len(),
        "{differ} pixels differ, by up to {worst} LSB"
    );
}
