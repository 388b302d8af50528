//! The per-pixel engines whose bit-accurate path places the bump normal in a frame per
//! fragment (`frame_transform`), each regressed in `tests/rtl_sim.rs`:
//! - Harmony (paper §3.5): the interpolated per-vertex frames;
//! - TexRam (paper §3.1): the frame built per fragment from the interpolated normal and main
//!   direction by the `frame_build` unit;
//! - VISA+ (paper §3.2): the triangle's alignment matrix with the interpolated normal
//!   (`triangle_frame`, a rasteriser choice on Harmony's top);
//! - Blinn (paper §2): TexRam's frame with L and H formed at the pixel (`pixel_lh`).
//!
//! Each renormalises the placed normal and the interpolated L and H. Their golden images are
//! exact (checked-in PNGs); each tracks its own f64 equations and its engine's f64 model; on
//! a plane, where every vertex frame is the same, all three are the bump-space path.

use gbump::config::PipelineConfig;
use gbump::engines::report::{compare, golden_image, render};
use gbump::engines::{engine, Maps};
use gbump::render::output::codes_to_u8;
use gbump::scene::Scene;
#[path = "common/golden_png.rs"]
mod golden_png;

const ENGINES: [&str; 5] = ["harmony", "texram", "visa", "visa_quaternion", "blinn"];

/// Scenes whose paths the PNGs hold: a curved, tessellated surface whose frames turn across
/// every triangle, and a textured one.
const SCENES: [&str; 2] = ["torus_caps", "blend_split"];

fn path_config(e: &str, s: &Scene) -> PipelineConfig {
    engine(e).unwrap().fixed_config(s).unwrap().unwrap()
}

#[test]
fn the_frame_paths_differ_by_where_the_frame_comes_from() {
    let s = Scene::load("torus_caps").unwrap();
    let harmony = path_config("harmony", &s);
    assert!(harmony.frame_transform && harmony.renormalise_bump && harmony.renormalise && harmony.interpolate_k);
    assert!(!harmony.self_shadow && !harmony.frame_build && !harmony.triangle_frame);
    let units: Vec<_> = gbump::units::included(&harmony).iter().map(|u| u.name()).collect();
    for u in ["frame_transform", "normalise_b", "normalise"] {
        assert!(units.contains(&u), "{u} missing from {units:?}");
    }
    // The frame enters with the fragment: a port of nine L/H words; a top without the unit
    // has no such port.
    let ports = gbump::rtlgen::top::port_list(&harmony);
    let frame = ports.iter().find(|p| p.name == "in_frame").expect("in_frame port");
    assert_eq!((frame.lanes, frame.fmt), (9, harmony.lh_fmt()));
    let plain = PipelineConfig {
        frame_transform: false,
        ..harmony.clone()
    };
    assert!(!gbump::rtlgen::top::port_list(&plain).iter().any(|p| p.name == "in_frame"));
    // TexRam's top is Harmony's with the frame_build unit, whose latency is what its
    // description says: two normalisations and a registered cross product after each.
    let texram = path_config("texram", &s);
    assert_eq!(
        texram,
        PipelineConfig {
            frame_build: true,
            ..harmony.clone()
        }
    );
    assert!(gbump::units::included(&texram).iter().any(|u| u.name() == "frame_build"));
    let (fb, norm) = (gbump::units::unit("frame_build").unwrap(), gbump::units::unit("normalise").unwrap());
    assert_eq!(fb.latency(&texram), 2 * norm.latency(&texram) + 2);
    // VISA+'s is Harmony's RTL: the rasteriser alone differs.
    let visa = path_config("visa", &s);
    assert_eq!(
        visa,
        PipelineConfig {
            triangle_frame: true,
            ..harmony.clone()
        }
    );
    let names = |c: &PipelineConfig| -> Vec<&str> { gbump::units::included(c).iter().map(|u| u.name()).collect() };
    assert_eq!(names(&visa), names(&harmony));
    assert_eq!(gbump::rtlgen::top::latency(&visa), gbump::rtlgen::top::latency(&harmony));
    // Blinn's is TexRam's with L and H formed at the pixel: the same units, H's normalise fed
    // from L's, which the frame's longer path hides (the same latency).
    let blinn = path_config("blinn", &s);
    assert_eq!(
        blinn,
        PipelineConfig {
            pixel_lh: true,
            ..texram.clone()
        }
    );
    assert_eq!(names(&blinn), names(&texram));
    assert_eq!(gbump::rtlgen::top::latency(&blinn), gbump::rtlgen::top::latency(&texram));
    let top = gbump::rtlgen::top::top(&blinn);
    assert!(top.contains("u_norm_h0 (.clk(clk), .v(hh0)"), "H's normalise reads the halved sum");
}

#[test]
fn frame_paths_match_their_pngs() {
    let mut failures = Vec::new();
    for e in ENGINES {
        for name in SCENES {
            let s = Scene::load(name).unwrap();
            let (w, h) = (s.size[0] / 2, s.size[1] / 2);
            let img = gbump::render::render(&s, &path_config(e, &s), w, h, false).unwrap();
            let px = codes_to_u8(&img.golden, img.colour_max);
            failures.extend(golden_png::check(&format!("{name}_{e}"), w, h, &px));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// Each golden image against its own f64 equations (the frame, the renormalisations, in
/// f64) and against its engine's f64 model, on every built-in scene (printed).
#[test]
fn the_frame_paths_track_their_equations_and_their_engines_models() {
    for e in ENGINES {
        for (name, _) in gbump::scene::builtin::ALL {
            let s = Scene::load(name).unwrap();
            let (w, h) = (s.size[0] / 2, s.size[1] / 2);
            let cfg = path_config(e, &s);
            let img = gbump::render::render(&s, &cfg, w, h, false).unwrap();
            let own = gbump::measure::image_metrics::compare(&img.golden, &img.gouraud, &img.covered, cfg.colour_max());
            let f64_img = render(&s, &[engine(e).unwrap()], w, h, Maps::default()).unwrap().remove(0);
            let fixed = golden_image(&s, &cfg, &f64_img).unwrap();
            let model = compare(&fixed, &f64_img);
            println!(
                "{e} {name}: against its f64 equations {:.2} dB, mean {:.3} LSB; against its engine's f64 model {:.2} dB, mean {:.3} LSB",
                own.psnr_db, own.mean_lsb, model.psnr_db, model.mean_lsb
            );
            // The renormalised bump normal keeps the normal's 7 fraction bits; where a bright
            // light grazes a wall (cg_wall_*) that costs about 3 LSB mean, the same on the
            // bump-space path with the same units.
            assert!(own.psnr_db > 35.0 && own.mean_lsb < 3.5, "{e} {name}: {own:?}");
            assert!(model.psnr_db > 28.0, "{e} {name}: {model:?}");
        }
    }
}

/// On a plane every vertex frame is the same orthonormal frame (and the triangle's): placing
/// the normal in it and lighting with eye-space vectors is the bump-space pipeline with the
/// same vectors interpolated. Each frame path's golden image agrees with the bump-space
/// path's but for the transform's rounding (printed).
#[test]
fn on_a_plane_every_frame_path_is_the_bump_space_path() {
    let s = Scene::load("cg_wall_front").unwrap();
    let (w, h) = (s.size[0] / 2, s.size[1] / 2);
    let bump_space = PipelineConfig {
        frame_transform: false,
        ..path_config("harmony", &s)
    };
    let b = gbump::render::render(&s, &bump_space, w, h, false).unwrap();
    // Blinn's path lights with the pixel's own L and H, not the interpolated ones: below.
    let mut differing = Vec::new();
    for e in ENGINES.into_iter().filter(|&e| e != "blinn") {
        let a = gbump::render::render(&s, &path_config(e, &s), w, h, false).unwrap();
        let diff = |x: &[u32; 3], y: &[u32; 3]| (0..3).map(|c| x[c].abs_diff(y[c])).max().unwrap();
        let worst = a.golden.iter().zip(&b.golden).map(|(x, y)| diff(x, y)).max().unwrap();
        let differ = a.golden.iter().zip(&b.golden).filter(|(x, y)| x != y).count();
        println!(
            "{e} vs the bump-space path on a plane: {differ} of {} pixels differ, by {worst} LSB at most",
            a.golden.len()
        );
        assert!(
            worst <= 1 && differ * 100 <= a.golden.len(),
            "{e}: {differ} pixels differ, by up to {worst} LSB"
        );
        differing.push((e, differ, a.golden.len()));
    }
    // The README states the count for TexRam's and Harmony's paths.
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    for (e, differ, of) in differing.into_iter().filter(|(e, ..)| ["texram", "harmony"].contains(e)) {
        let of = format!("{},{:03}", of / 1000, of % 1000);
        let want = match differ {
            0 => format!("none of {of} pixels differ on `cg_wall_front`"),
            n => format!("{n} of {of} pixels differ on `cg_wall_front`"),
        };
        assert!(flat.contains(&want), "{e}: README should say: {want}");
    }
}

/// Blinn's path forms L and H at the pixel. Its f64 equations are Blinn's reference up to
/// what the pipeline interpolates (k under a spot light, C_src) and never further from it
/// than TexRam's (the same frame, L and H interpolated from the vertices) on the scenes lit
/// by point and spot lights; on the wall lit by a point light in front of it
/// (`cg_wall_front`: no spot, a constant C_src) they are the reference. Both golden images
/// against Blinn's f64 model are printed beside each other: the fixed point's own rounding
/// is what they show there.
#[test]
fn blinns_path_lights_at_the_pixel() {
    for name in ["cg_wall_front", "cg_wall_lower_left", "sphere_bricks_spots"] {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let blinn_f64 = render(&s, &[engine("blinn").unwrap()], w, h, Maps::default()).unwrap().remove(0);
        let mut equations = Vec::new();
        for e in ["blinn", "texram"] {
            let cfg = path_config(e, &s);
            let img = gbump::render::render(&s, &cfg, w, h, false).unwrap();
            let max = cfg.colour_max() as f64;
            let diffs = img.gouraud.iter().zip(&img.reference).zip(&img.covered).filter(|(_, c)| **c);
            let eq = gbump::measure::image_metrics::stats(diffs.map(|((a, b), _)| [0, 1, 2].map(|i| (a[i] - b[i]) * max)), max);
            let fixed = compare(&golden_image(&s, &cfg, &blinn_f64).unwrap(), &blinn_f64);
            println!(
                "{e} on {name}: its f64 equations against Blinn's reference mean {:.4} LSB, max {:.3}; its golden image against Blinn's f64 model {:.2} dB, mean {:.3} LSB",
                eq.mean_lsb, eq.max_lsb, fixed.psnr_db, fixed.mean_lsb
            );
            assert!(fixed.psnr_db > 30.0, "{e} {name}: {fixed:?}");
            equations.push(eq);
        }
        assert!(equations[0].mean_lsb <= equations[1].mean_lsb + 1e-9, "{name}: {equations:?}");
        if name == "cg_wall_front" {
            assert!(equations[0].max_lsb < 1e-6, "{name}: {:?}", equations[0]);
        }
    }
}
