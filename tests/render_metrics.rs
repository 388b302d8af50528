//! The README's definitions of `<scene>_metrics.json` and of the PNGs, computed here from
//! the text (independently of `measure::image_metrics`) on the images `gbump render`'s own
//! library call makes, and compared with what the command writes.

use assert_cmd::Command;
use gbump::render::{render, report::scene_and_config};

/// The README's figures of one comparison: codes against values in [0, 1] (clamped), over
/// the covered pixels.
fn figures(codes: &[[u32; 3]], values: &[[f64; 3]], covered: &[bool], c: u32) -> serde_json::Value {
    let top = ((1u64 << c) - 1) as f64;
    let mut d = Vec::new();
    let mut over = 0usize;
    let mut pixels = 0usize;
    for ((code, v), cov) in codes.iter().zip(values).zip(covered) {
        if !cov {
            continue;
        }
        pixels += 1;
        let px: Vec<f64> = (0..3).map(|i| code[i] as f64 - v[i].clamp(0.0, 1.0) * top).collect();
        if px.iter().any(|x| x.abs() > 1.0) {
            over += 1;
        }
        d.extend(px);
    }
    let n = d.len() as f64;
    let mse = d.iter().map(|x| x * x).sum::<f64>() / n;
    serde_json::json!({
        "psnr_db": if mse == 0.0 { serde_json::Value::Null } else { (10.0 * (top * top / mse).log10()).into() },
        "max_lsb": d.iter().fold(0.0f64, |m, x| m.max(x.abs())),
        "mean_lsb": d.iter().map(|x| x.abs()).sum::<f64>() / n,
        "over_1lsb": over as f64 / pixels as f64,
        "pixels": pixels,
        "identical": mse == 0.0,
    })
}

fn close(a: &serde_json::Value, b: &serde_json::Value, what: &str) {
    for k in ["psnr_db", "max_lsb", "mean_lsb", "over_1lsb", "pixels", "identical"] {
        let (x, y) = (&a[k], &b[k]);
        let same = match (x.as_f64(), y.as_f64()) {
            (Some(x), Some(y)) => (x - y).abs() <= 1e-9 * x.abs().max(1.0),
            _ => x == y,
        };
        assert!(same, "{what}.{k}: the command wrote {x}, the README's definition gives {y}");
    }
}

#[test]
fn the_metrics_and_pngs_are_what_the_readme_defines() {
    // A scene with textures, blends and ties, at a 10-bit colour width too (the PNG scaling
    // is then not the identity).
    for (scene, extra) in [("blend_split", None), ("torus_caps", Some("colour_bits = 10\n"))] {
        let dir = tempfile::tempdir().unwrap();
        let (s, mut cfg) = scene_and_config(scene, None).unwrap();
        let mut cmd = Command::cargo_bin("gbump").unwrap();
        cmd.args(["render", "--scene", scene, "--size", "64x48", "--out"]).arg(dir.path());
        if let Some(extra) = extra {
            let text = toml::to_string(&cfg).unwrap();
            let text = text
                .lines()
                .filter(|l| !l.starts_with("colour_bits"))
                .collect::<Vec<_>>()
                .join("\n")
                + "\n"
                + extra;
            let f = dir.path().join("c.toml");
            std::fs::write(&f, &text).unwrap();
            cfg = gbump::PipelineConfig::from_toml("c.toml", &text).unwrap();
            cmd.arg("--config").arg(&f);
        }
        cmd.assert().success();
        let img = render(&s, &cfg, 64, 48, false).unwrap();
        let c = cfg.colour_bits;
        let written: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.path().join(format!("{scene}_metrics.json"))).unwrap()).unwrap();
        let top = (1u64 << c) - 1;
        let rounded: Vec<[u32; 3]> = img
            .gouraud
            .iter()
            .map(|p| p.map(|v| (v.clamp(0.0, 1.0) * top as f64).round() as u32))
            .collect();
        close(
            &written["golden_vs_reference"],
            &figures(&img.golden, &img.reference, &img.covered, c),
            "golden_vs_reference",
        );
        close(
            &written["golden_vs_gouraud_f64"],
            &figures(&img.golden, &img.gouraud, &img.covered, c),
            "golden_vs_gouraud_f64",
        );
        close(
            &written["gouraud_f64_vs_reference"],
            &figures(&rounded, &img.reference, &img.covered, c),
            "gouraud_f64_vs_reference",
        );
        // The PNGs: codes scaled to 8 bits as the README says, f64 values rounded to nearest.
        let png = |f: &str| {
            image::open(dir.path().join(format!("{scene}_{f}.png")))
                .unwrap()
                .to_rgb8()
                .into_raw()
        };
        let golden: Vec<u8> = img
            .golden
            .iter()
            .flat_map(|p| p.map(|x| ((255 * x as u64 + top / 2) / top) as u8))
            .collect();
        assert_eq!(png("golden"), golden, "{scene}: the golden PNG");
        let f64_png = |v: &[[f64; 3]]| -> Vec<u8> {
            v.iter()
                .flat_map(|p| p.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8))
                .collect()
        };
        assert_eq!(png("gouraud_f64"), f64_png(&img.gouraud), "{scene}: the f64 Gouraud PNG");
        assert_eq!(png("reference"), f64_png(&img.reference), "{scene}: the reference PNG");
    }
}
