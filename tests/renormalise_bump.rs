//! `renormalise_bump = true`: the fetched bump normal scaled back to unit length by a
//! `normalise_b` unit before the dot products. A bilinear filter shortens the normal where
//! neighbouring texels disagree; on the Cg brick wall at half its size, where every pixel
//! samples between texels, that is most of the paper's pipeline's error against Blinn, and
//! the unit removes it. The golden image tracks its own f64 equations either way.

use gbump::config::PipelineConfig;
use gbump::measure::image_metrics::compare;
use gbump::render::render;
use gbump::scene::Scene;

#[test]
fn renormalising_the_fetched_normal_removes_the_filters_shortening() {
    let s = Scene::load("cg_wall_front").unwrap();
    let base = s.derive_config().unwrap();
    let mut figures = Vec::new();
    for on in [false, true] {
        let cfg = PipelineConfig {
            renormalise_bump: on,
            ..base.clone()
        };
        let img = render(&s, &cfg, 128, 64, false).unwrap();
        let blinn = compare(&img.golden, &img.reference, &img.covered, cfg.colour_max());
        let own = compare(&img.golden, &img.gouraud, &img.covered, cfg.colour_max());
        println!(
            "renormalise_bump = {on}: against Blinn {:.2} dB, mean {:.3}; against its f64 equations {:.2} dB",
            blinn.psnr_db, blinn.mean_lsb, own.psnr_db
        );
        assert!(own.psnr_db > 38.0, "{on}: {own:?}");
        figures.push(blinn);
    }
    assert!(figures[1].mean_lsb < figures[0].mean_lsb / 5.0, "{figures:?}");
    // The README states the figures measured here.
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let want = format!(
        "falls from {:.1} to {:.1} LSB (PSNR {:.1} to {:.1} dB)",
        figures[0].mean_lsb, figures[1].mean_lsb, figures[0].psnr_db, figures[1].psnr_db
    );
    assert!(flat.contains(&want), "README should say: {want}");
}

/// Left out of the TOML when false (no hash changed), valid with either light mode and bump
/// state, and the unit is in the top exactly when it is set.
#[test]
fn the_field_keeps_old_hashes_and_places_the_unit() {
    assert!(!PipelineConfig::default().to_toml().contains("renormalise_bump"));
    for toml in [
        "renormalise_bump = true\n",
        "renormalise_bump = true\nlight_mode = \"parallel\"\nlights = 2\n",
        "renormalise_bump = true\nbump_state = \"fragment\"\n",
    ] {
        let cfg = PipelineConfig::from_toml("x.toml", toml).unwrap();
        assert!(cfg.to_toml().contains("renormalise_bump = true"));
        assert_eq!(PipelineConfig::from_toml("y.toml", &cfg.to_toml()).unwrap(), cfg);
        let names: Vec<&str> = gbump::units::included(&cfg).iter().map(|u| u.name()).collect();
        assert!(names.contains(&"normalise_b"), "{names:?}");
        let rtl = gbump::rtlgen::top::top(&cfg);
        assert!(rtl.contains("u_norm_b"), "{toml}");
        let off = PipelineConfig {
            renormalise_bump: false,
            ..cfg.clone()
        };
        assert_ne!(off.hash(), cfg.hash());
        assert!(!gbump::rtlgen::top::top(&off).contains("u_norm_b"));
    }
}

/// A palette index is not filtered, so the unit would only cost area: refused with the fix;
/// the integration notes say what the unit does to `in_bump`.
#[test]
fn a_palette_is_refused_and_the_integration_notes_explain_the_unit() {
    let e = PipelineConfig::from_toml("x.toml", "renormalise_bump = true\npalette = true\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("x.toml") && e.contains("renormalise_bump") && e.contains("unit-length palette entries"),
        "{e}"
    );
    let cfg = PipelineConfig::from_toml("x.toml", "renormalise_bump = true\nskip_flat = true\n").unwrap();
    let doc = gbump::rtlgen::integration_doc::markdown(&cfg);
    assert!(
        doc.contains("**Renormalised inputs.**") && doc.contains("compares the fetched code"),
        "{doc}"
    );
    assert!(!gbump::rtlgen::integration_doc::markdown(&PipelineConfig::default()).contains("Renormalised inputs"));
    // A scene with bilinear maps is told about the unit by `gbump config --scene`.
    let s = gbump::scene::Scene::load("cg_wall_front").unwrap();
    let why = gbump::scene::needs::SceneNeeds::of(&s)
        .explain(&s, &s.derive_config().unwrap())
        .unwrap();
    assert!(
        why.contains("# renormalise_bump = false: objects [0] filter their maps bilinearly"),
        "{why}"
    );
}
