//! `interpolate_k = true`: the rasteriser interpolates each bump light's k (intensity times
//! spot factor) from the vertices, as SGI's per-vertex lighting does (paper §3.4), and the
//! per-fragment top takes it on its fragment port with the rest of the bump state. SGI's
//! bit-accurate path is that, with L and H interpolated (`gbump config --engine sgi`): its
//! golden image is exact (a checked-in PNG), stays within quantisation of SGI's f64 model on
//! every built-in scene, and follows a spotlight's cone across triangles where the
//! per-triangle k steps.

use assert_cmd::Command;
use gbump::config::{Interpolate, PipelineConfig};
use gbump::engines::report::{compare, render, EngineImage};
use gbump::engines::{engine, Maps};
use gbump::raster::fragment::state_at;
use gbump::raster::rasterise::rasterise;
use gbump::raster::tri_state::send_k;
use gbump::raster::Prepared;
use gbump::render::output::codes_to_u8;
use gbump::scene::lighting::spot_factor;
use gbump::scene::Scene;
#[path = "common/golden_png.rs"]
mod golden_png;

const SPOT: &str = "tests/scenes/bump_spot.toml";

fn sgi_config(s: &Scene) -> PipelineConfig {
    engine("sgi").unwrap().fixed_config(&s).unwrap().unwrap()
}

/// Engine `name`'s bit-accurate image of `s` at `w`×`h` as an engine image, and its f64 image.
fn engine_images(name: &str, s: &Scene, w: u32, h: u32) -> (EngineImage, EngineImage) {
    let e = engine(name).unwrap();
    let f64_img = render(s, &[e], w, h, Maps::default()).unwrap().remove(0);
    let cfg = e.fixed_config(&s).unwrap().unwrap();
    let fixed = gbump::engines::report::golden_image(s, &cfg, &f64_img).unwrap();
    (fixed, f64_img)
}

#[test]
fn interpolate_k_needs_per_fragment_state_and_keeps_old_hashes() {
    let e = PipelineConfig::from_toml("x.toml", "interpolate_k = true\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("x.toml") && e.contains("interpolate_k") && e.contains("bump_state = \"fragment\""),
        "{e}"
    );
    let e = PipelineConfig::from_toml("x.toml", "interpolate_k = true\nbump_state = \"fragment\"\nk_frac_bits = 0\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("interpolate_k") && e.contains("k_frac_bits"), "{e}");
    let on = PipelineConfig::from_toml("x.toml", "interpolate_k = true\nbump_state = \"fragment\"\n").unwrap();
    assert!(on.to_toml().contains("interpolate_k = true"));
    assert_eq!(PipelineConfig::from_toml("y.toml", &on.to_toml()).unwrap(), on);
    assert!(!PipelineConfig::default().to_toml().contains("interpolate_k"));
    assert_ne!(
        on.hash(),
        PipelineConfig {
            interpolate_k: false,
            renormalise_bump: false,
            ..on.clone()
        }
        .hash()
    );
    // SGI's path on any scene: L, H and k per fragment, the scene's blend choices replaced by
    // the engine's own combination.
    let s = Scene::load("flat_artifact_fixed").unwrap();
    let cfg = sgi_config(&s);
    assert!(cfg.skip_flat.eq(&false) && s.derive_config().unwrap().skip_flat);
    assert_eq!(
        (cfg.interpolate, cfg.interpolate_k, cfg.renormalise),
        (Interpolate::Hl, true, false)
    );
    cfg.validate("sgi").unwrap();
}

/// Every fragment's k is the barycentric mix of the spot factors at its triangle's vertices,
/// rounded as the setup rounds the triangle's own (and without the option, the triangle's);
/// on the spotlit wall the two differ on most fragments.
#[test]
fn each_fragment_carries_k_interpolated_from_its_vertices() {
    let s = Scene::load(SPOT).unwrap();
    let cfg = sgi_config(&s);
    let light = s.bump_lights().next().unwrap();
    let per_tri = PipelineConfig {
        interpolate_k: false,
        renormalise_bump: false,
        ..cfg.clone()
    };
    let p = Prepared::new(&s, &cfg, 128, 64).unwrap();
    let pt = Prepared::new(&s, &per_tri, 128, 64).unwrap();
    let gb = rasterise(&p).unwrap();
    let (mut n, mut differ) = (0, 0);
    for hit in gb.hits.iter().flatten() {
        let v = p.objects[hit.obj as usize].mesh.corners(hit.tri);
        let k: f64 = (0..3).map(|j| hit.bary[j] * light.k * spot_factor(light, v[j].p)).sum();
        let got = state_at(&p, hit).lights[0].k;
        assert_eq!(got, send_k(&cfg, k), "fragment at {:?}", hit.bary);
        let tri = state_at(&pt, hit).lights[0].k;
        assert_eq!(tri, p.objects[hit.obj as usize].tris[hit.tri as usize].fixed.lights[0].k);
        n += 1;
        differ += usize::from(got != tri);
    }
    println!("{differ} of {n} fragments carry a k other than their triangle's");
    assert!(differ * 2 > n, "{differ} of {n}");
}

#[test]
fn sgi_bit_accurate_path_matches_its_png() {
    let s = Scene::load(SPOT).unwrap();
    let (w, h) = (128, 64);
    let img = gbump::render::render(&s, &sgi_config(&s), w, h, false).unwrap();
    let px = codes_to_u8(&img.golden, img.colour_max);
    if let Some(diff) = golden_png::check("bump_spot_sgi", w, h, &px) {
        panic!("{diff}");
    }
}

/// The bit-accurate path against SGI's f64 model on every built-in scene and the spotlit wall:
/// the same engine, so only quantisation (8-bit normals, 16-bit L and H, u1.8 k, the power
/// table's steps amplified by the shininess, three colour roundings) separates them, as it
/// separates `gouraud_hl`'s path from its f64 equations (measured, printed).
#[test]
fn sgi_bit_accurate_path_tracks_its_f64_model_on_every_scene() {
    let mut names: Vec<String> = gbump::scene::builtin::ALL.iter().map(|(n, _)| n.to_string()).collect();
    names.push(SPOT.into());
    for name in &names {
        let s = Scene::load(name).unwrap();
        let (w, h) = (s.size[0] / 2, s.size[1] / 2);
        let (fixed, f64_img) = engine_images("sgi", &s, w, h);
        let e = compare(&fixed, &f64_img);
        let (hl_fixed, hl_f64) = engine_images("gouraud_hl", &s, w, h);
        let hl = compare(&hl_fixed, &hl_f64);
        println!(
            "{name}: bit-accurate against f64 sgi: mean {:.3} LSB, max {:.1} LSB, {:.1} % over 1 LSB, PSNR {:.1} dB (gouraud_hl's own: mean {:.3} LSB, PSNR {:.1} dB)",
            e.mean_lsb,
            e.max_lsb,
            100.0 * e.over_1lsb,
            e.psnr_db,
            hl.mean_lsb,
            hl.psnr_db
        );
        // Where the scene blends as SGI does, the two engines are one datapath and their gaps
        // are equal (`sgi_f64_model_is_the_datapath_it_generates`); elsewhere the flat bypass
        // or the texture-last order keep colours exact that SGI rounds.
        assert!(e.psnr_db > 32.0 && e.mean_lsb < 4.0, "{name}: {e:?} against {hl:?}");
    }
}

/// Interpolated k follows the spotlight's cone across triangle edges, where the triangle's k
/// steps (Fig. 7's artefact, for the cone instead of the highlight): SGI's seams against Blinn
/// are a fraction of `gouraud_hl`'s, bit-accurate and in f64.
#[test]
fn interpolated_k_removes_the_spot_cones_seams() {
    let t = gbump::engines::report::measure(
        &[SPOT.into()],
        &[engine("sgi").unwrap(), engine("gouraud_hl").unwrap()],
        Some((128, 64)),
        Maps::default(),
    )
    .unwrap();
    let names: Vec<&str> = t.engines.iter().map(|e| e.name).collect();
    assert_eq!(names, ["blinn", "sgi", "gouraud_hl"]);
    let (sgi, hl) = (&t.errors[0][1], &t.errors[0][2]);
    let (fsgi, fhl) = (t.fixed[0][1].as_ref().unwrap(), t.fixed[0][2].as_ref().unwrap());
    println!(
        "seam mean against blinn: f64 sgi {:.2} gouraud_hl {:.2}; bit-accurate sgi {:.2} gouraud_hl {:.2}",
        sgi.seam_mean_lsb, hl.seam_mean_lsb, fsgi.error.seam_mean_lsb, fhl.error.seam_mean_lsb
    );
    assert!(sgi.seam_mean_lsb * 2.0 < hl.seam_mean_lsb, "{sgi:?} {hl:?}");
    assert!(
        fsgi.error.seam_mean_lsb * 2.0 < fhl.error.seam_mean_lsb,
        "{:?} {:?}",
        fsgi.error,
        fhl.error
    );
    // The same top: k was always on the per-fragment port.
    assert_eq!(
        (fsgi.area_ge, fsgi.flip_flops, fsgi.latency),
        (fhl.area_ge, fhl.flip_flops, fhl.latency)
    );
}

/// `gbump config --engine` prints the configuration the table names; an unknown engine is
/// refused with the engines that have a path.
#[test]
fn the_config_command_prints_an_engines_path() {
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["config", "--scene", SPOT, "--engine", "sgi"])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).into_owned();
    let s = Scene::load(SPOT).unwrap();
    let cfg = sgi_config(&s);
    assert!(text.contains(&format!("# config hash {}", cfg.hash())), "{text}");
    let toml: String = text.lines().filter(|l| !l.starts_with('#')).map(|l| format!("{l}\n")).collect();
    assert_eq!(PipelineConfig::from_toml("printed", &toml).unwrap(), cfg);
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["config", "--scene", SPOT, "--engine", "phong"])
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        err.contains("--engine phong") && err.contains("no such engine") && err.contains("sgi"),
        "{err}"
    );
}

/// SGI's f64 model (`engines::sgi`, written from §3.4) and the Gouraud f64 equations with L, H
/// and k interpolated (`reference::gouraud_f64`, which the golden model tracks) are one
/// computation wherever the scene blends as SGI does: pixel for pixel to rounding, so the
/// bit-accurate path models SGI and nothing else.
#[test]
fn sgi_f64_model_is_the_datapath_it_generates() {
    use gbump::config::{BlendOrder, PerFragment};
    use gbump::raster::fragment::pixel_geom;
    let how = PerFragment {
        interpolate: Interpolate::Hl,
        renormalise: false,
        interpolate_k: true,
        renormalise_bump: false,
        ..PerFragment::PER_TRIANGLE
    };
    let mut names: Vec<String> = gbump::scene::builtin::ALL.iter().map(|(n, _)| n.to_string()).collect();
    names.push(SPOT.into());
    let mut checked = 0;
    for name in &names {
        let s = Scene::load(name).unwrap();
        let cfg = s.derive_config().unwrap();
        if cfg.skip_flat || cfg.blend_order != BlendOrder::DiffuseTextureSpecular {
            continue;
        }
        let p = Prepared::new(&s, &cfg, s.size[0] / 4, s.size[1] / 4).unwrap();
        let ctx = gbump::engines::Ctx::new(&p, Maps::default());
        let sgi = engine("sgi").unwrap();
        let mut worst = 0.0f64;
        for hit in rasterise(&p).unwrap().hits.iter().flatten() {
            let g = pixel_geom(&p, hit);
            let a = (sgi.shade)(&ctx, hit, &g);
            let b = gbump::reference::gouraud_f64::shade_interpolating(&p, hit, &g, how);
            worst = worst.max((a - b).abs().max_element());
        }
        println!("{name}: largest difference {worst:e}");
        assert!(worst < 1e-9, "{name}: {worst}");
        checked += 1;
    }
    assert!(checked >= 10, "{checked} scenes");
}
