//! Golden-image tests: every built-in scene rendered through the bit-accurate model at a
//! small size must equal its checked-in PNG exactly. `GBUMP_BLESS=1 cargo test --test
//! golden_images` rewrites them after an intended change (review the diff images first).

#[path = "common/golden_png.rs"]
mod golden_png;

use gbump::render::output::codes_to_u8;
use gbump::render::render;
use gbump::scene::{builtin, Scene};

const W: u32 = 96;
const H: u32 = 72;

#[test]
fn every_builtin_scene_matches_its_golden_png() {
    let mut failures = Vec::new();
    for (name, _) in builtin::ALL {
        let s = Scene::load(name).unwrap();
        let cfg = s.derive_config().unwrap();
        let img = render(&s, &cfg, W, H, false).unwrap();
        assert_eq!(cfg.colour_bits, 8);
        failures.extend(golden_png::check(name, W, H, &codes_to_u8(&img.golden, img.colour_max)));
    }
    assert!(failures.is_empty(), "golden images differ:\n{}", failures.join("\n"));
}

/// The f64 Gouraud-equation image isolates quantisation error: with the default 8-bit
/// formats it must stay close to the golden image. Bounds are measured values with margin.
#[test]
fn quantisation_error_is_bounded() {
    for (name, min_psnr) in [
        ("torus_caps", 36.0),
        ("cg_wall_front", 36.0),
        ("cylinder_smooth", 33.0),
        ("flat_artifact", 36.0),
    ] {
        let s = Scene::load(name).unwrap();
        let cfg = s.derive_config().unwrap();
        let img = render(&s, &cfg, 128, 96, false).unwrap();
        let e = gbump::measure::image_metrics::compare(&img.golden, &img.gouraud, &img.covered, img.colour_max);
        println!(
            "{name}: golden vs f64 Gouraud PSNR {:.2} dB, max {:.1} LSB, mean {:.3} LSB",
            e.psnr_db, e.max_lsb, e.mean_lsb
        );
        assert!(
            e.psnr_db >= min_psnr,
            "{name}: PSNR {:.2} dB below {min_psnr} dB (max {:.1} LSB)",
            e.psnr_db,
            e.max_lsb
        );
        assert!(e.pixels > 1000, "{name}: only {} pixels covered", e.pixels);
    }
}

/// With linear arithmetic (no specular table) and 16-bit words, the model converges on the
/// f64 equations: the mean error falls well below one LSB.
#[test]
fn wide_formats_converge_on_f64_equations() {
    let s = Scene::load("cg_wall_front").unwrap();
    let mut cfg = s.derive_config().unwrap();
    cfg.specular = false;
    let narrow = render(&s, &cfg, 128, 64, false).unwrap();
    cfg.normal_bits = 14;
    cfg.dot_frac_bits = 14;
    let wide = render(&s, &cfg, 128, 64, false).unwrap();
    let en = gbump::measure::image_metrics::compare(&narrow.golden, &narrow.gouraud, &narrow.covered, 255);
    let ew = gbump::measure::image_metrics::compare(&wide.golden, &wide.gouraud, &wide.covered, 255);
    println!(
        "8-bit: mean {:.3} LSB max {:.2}; 14-bit: mean {:.3} LSB max {:.2}",
        en.mean_lsb, en.max_lsb, ew.mean_lsb, ew.max_lsb
    );
    assert!(ew.mean_lsb < en.mean_lsb, "wider formats must not be worse");
    assert!(
        ew.max_lsb <= 1.0,
        "14-bit normals and dots: max error {:.2} LSB should be colour rounding only",
        ew.max_lsb
    );
}

/// A palettised map (256 normals, paper §6) costs accuracy but stays recognisably close
/// (measured: 27.6 dB against the full map on torus_caps at 128×96).
#[test]
fn palettised_map_stays_close_to_full_map() {
    let s = Scene::load("torus_caps").unwrap();
    let cfg = s.derive_config().unwrap();
    let full = render(&s, &cfg, 128, 96, false).unwrap();
    let pal_cfg = gbump::PipelineConfig { palette: true, ..cfg };
    let pal = render(&s, &pal_cfg, 128, 96, false).unwrap();
    let f: Vec<[f64; 3]> = full.golden.iter().map(|c| c.map(|x| x as f64 / 255.0)).collect();
    let e = gbump::measure::image_metrics::compare(&pal.golden, &f, &pal.covered, 255);
    println!("palette vs full map: PSNR {:.2} dB, max {:.1} LSB", e.psnr_db, e.max_lsb);
    assert!(e.psnr_db > 25.0 && e.psnr_db.is_finite(), "PSNR {:.2} dB", e.psnr_db);
}
