//! Paper §6's improvements as a configuration (`interpolate = "h" | "hl"`): the rasteriser
//! interpolates the half vectors (and light directions) per fragment, formed at each vertex
//! in its own frame, and the per-fragment top takes them on its fragment port. The golden
//! images are exact (checked-in PNGs), they track their own f64 equations, and they remove
//! the flat-shading artefact of Fig. 7 as the f64 engines `gouraud_h` and `gouraud_hl` do.

use gbump::config::{BumpStateAt, Interpolate, PipelineConfig};
use gbump::measure::image_metrics::compare;
#[path = "common/golden_png.rs"]
mod golden_png;

use gbump::render::output::codes_to_u8;
use gbump::render::render;
use gbump::scene::Scene;

const W: u32 = 96;
const H: u32 = 96;

fn config(how: Interpolate) -> PipelineConfig {
    let s = Scene::load("flat_artifact").unwrap();
    PipelineConfig {
        bump_state: BumpStateAt::Fragment,
        interpolate: how,
        ..s.derive_config().unwrap()
    }
}

/// The same with the interpolated vectors renormalised per fragment (parallel lights).
fn renormalised(how: Interpolate) -> PipelineConfig {
    PipelineConfig {
        renormalise: true,
        light_mode: gbump::config::LightMode::Parallel,
        ..config(how)
    }
}

/// The Cg Tutorial's size of normalisation cube map (§8.2) in place of the normalise unit.
const CUBE: u32 = 32;

/// Renormalised by reading a normalisation cube map of `CUBE` texels a face edge.
fn cube_mapped(how: Interpolate) -> PipelineConfig {
    PipelineConfig {
        cube_map_face: CUBE,
        ..renormalised(how)
    }
}

#[test]
fn renormalise_needs_interpolated_vectors_and_parallel_lights_and_keeps_old_hashes() {
    let e = PipelineConfig::from_toml("x.toml", "renormalise = true\n").unwrap_err().to_string();
    assert!(
        e.contains("x.toml") && e.contains("renormalise") && e.contains("interpolate = \"h\""),
        "{e}"
    );
    let serial = "renormalise = true\ninterpolate = \"h\"\nbump_state = \"fragment\"\nlight_mode = \"serial\"\n";
    let e = PipelineConfig::from_toml("x.toml", serial).unwrap_err().to_string();
    assert!(e.contains("light_mode = \"parallel\""), "{e}");
    let on = PipelineConfig::from_toml("x.toml", &serial.replace("serial", "parallel")).unwrap();
    assert!(on.to_toml().contains("renormalise = true"));
    assert!(!config(Interpolate::H).to_toml().contains("renormalise"));
    assert_eq!(PipelineConfig::from_toml("y.toml", &on.to_toml()).unwrap(), on);
}

#[test]
fn a_per_triangle_top_refuses_interpolated_vectors_and_the_default_hash_is_unchanged() {
    let e = PipelineConfig::from_toml("x.toml", "interpolate = \"h\"\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("x.toml") && e.contains("interpolate") && e.contains("bump_state = \"fragment\""),
        "{e}"
    );
    let bad = PipelineConfig::from_toml("x.toml", "interpolate = \"phong\"\nbump_state = \"fragment\"\n");
    assert!(bad.is_err());
    // Left out of the TOML when off, so every configuration from before keeps its hash.
    assert!(!PipelineConfig::default().to_toml().contains("interpolate"));
    let on = PipelineConfig::from_toml("x.toml", "interpolate = \"hl\"\nbump_state = \"fragment\"\n").unwrap();
    assert!(on.to_toml().contains("interpolate = \"hl\""));
    assert_eq!(PipelineConfig::from_toml("y.toml", &on.to_toml()).unwrap(), on);
    assert_ne!(
        on.hash(),
        PipelineConfig {
            interpolate: Interpolate::None,
            ..on.clone()
        }
        .hash()
    );
}

#[test]
fn interpolated_golden_images_match_their_pngs() {
    let s = Scene::load("flat_artifact").unwrap();
    for (how, name) in [(Interpolate::H, "h"), (Interpolate::Hl, "hl")] {
        let img = render(&s, &config(how), W, H, false).unwrap();
        let px = codes_to_u8(&img.golden, img.colour_max);
        if let Some(diff) = golden_png::check(&format!("flat_artifact_interpolate_{name}"), W, H, &px) {
            panic!("{diff}");
        }
    }
    for (cfg, name) in [
        (renormalised(Interpolate::Hl), "renormalise_hl"),
        (cube_mapped(Interpolate::Hl), "cube_map_hl"),
    ] {
        let img = render(&s, &cfg, W, H, false).unwrap();
        let px = codes_to_u8(&img.golden, img.colour_max);
        if let Some(diff) = golden_png::check(&format!("flat_artifact_{name}"), W, H, &px) {
            panic!("{diff}");
        }
    }
}

/// The golden image stays within quantisation of its own f64 equations, and interpolating
/// brings it closer to Blinn, H a little, H and L much, renormalised H and L more, by the
/// normalise unit or, within the map's resolution, by a cube map (measured, printed).
#[test]
fn interpolation_removes_the_flat_shading_and_tracks_its_equations() {
    let s = Scene::load("flat_artifact").unwrap();
    let mut to_blinn = Vec::new();
    // The last one renormalises the interpolated vectors (the normalise unit).
    let cfgs = [
        ("None", config(Interpolate::None)),
        ("H", config(Interpolate::H)),
        ("Hl", config(Interpolate::Hl)),
        ("Hl renormalised", renormalised(Interpolate::Hl)),
        ("Hl cube-mapped", cube_mapped(Interpolate::Hl)),
    ];
    for (name, cfg) in cfgs {
        let img = render(&s, &cfg, 192, 192, false).unwrap();
        let own = compare(&img.golden, &img.gouraud, &img.covered, cfg.colour_max());
        let blinn = compare(&img.golden, &img.reference, &img.covered, cfg.colour_max());
        println!(
            "{name}: against its f64 equations {:.2} dB, max {:.1}; against Blinn {:.2} dB, mean {:.3}",
            own.psnr_db, own.max_lsb, blinn.psnr_db, blinn.mean_lsb
        );
        assert!(own.psnr_db > 38.0, "{name}: {own:?}");
        to_blinn.push(blinn.mean_lsb);
    }
    assert!(to_blinn[1] < to_blinn[0] && to_blinn[2] < to_blinn[0] / 1.5, "{to_blinn:?}");
    assert!(to_blinn[3] < to_blinn[2] / 1.5, "{to_blinn:?}");
    // The map's directions are off by up to half a texel's diagonal: between the two.
    assert!(to_blinn[3] < to_blinn[4] && to_blinn[4] < to_blinn[2] / 1.5, "{to_blinn:?}");
    // The README states the figures measured here.
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let want = format!("falls from {:.1} to {:.1} LSB with `hl`", to_blinn[0], to_blinn[2]);
    assert!(flat.contains(&want), "README should say: {want}");
    let want = format!("and to {:.1} LSB with `renormalise = true`", to_blinn[3]);
    assert!(flat.contains(&want), "README should say: {want}");
    let want = format!("{:.1} LSB with a {CUBE}-texel normalisation cube map", to_blinn[4]);
    assert!(flat.contains(&want), "README should say: {want}");
}
