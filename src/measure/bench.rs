//! `gbump bench`: the speed side of the trade, measured in one run — golden-model fragments
//! per second (1 and 4 lights, beside the f64 reference), vector-dump bandwidth, vectors per
//! second under Icarus and under the Verilator C++ harness, and the raw evaluation rate of
//! the same Verilated model with no I/O (the ceiling of any regression).

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::raster::fragment::{fragments, pixel_geom};
use crate::raster::rasterise::rasterise;
use crate::raster::Prepared;
use crate::reference::perpixel;
use crate::render::golden_image;
use crate::scene::Scene;
use crate::sim::{Icarus, Simulator, Testbench, Verilator};
use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;

/// A full-coverage brick wall lit by `lights` parallel lights.
pub fn bench_scene(lights: usize) -> Scene {
    let mut text =
        String::from("name = \"bench\"\n[camera]\neye = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nheight = 1.9\n");
    let dirs = ["[0.3, 0.2, 1.0]", "[-0.5, 0.1, 0.8]", "[0.1, -0.6, 0.7]", "[0.6, 0.6, 0.5]"];
    for d in dirs.iter().take(lights) {
        text += &format!("[[lights]]\nkind = \"directional\"\ndirection = {d}\ncolour = [0.5, 0.5, 0.5]\n");
    }
    text += "[[objects]]\nshape = { kind = \"plane\", size = [2.0, 2.0] }\nshininess = 32\nuv_scale = [4.0, 4.0]\nbump = { source = { kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }, size = 256 }\n";
    Scene::from_toml("bench", &text, Path::new(".")).expect("bench scene")
}

/// (golden, reference) million fragments per second at `side`², best of three.
pub fn model_rate(lights: usize, side: u32) -> (f64, f64, usize) {
    let s = bench_scene(lights);
    let cfg = s.derive_config().expect("config");
    let p = Prepared::new(&s, &cfg, side, side).expect("prepare");
    let gb = rasterise(&p);
    let frags = fragments(&p, &gb);
    let bar = indicatif::ProgressBar::hidden();
    let best = |f: &dyn Fn()| {
        (0..3)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let g = best(&|| {
        std::hint::black_box(golden_image(&p, &frags, &bar));
    });
    let r = best(&|| {
        std::hint::black_box(
            gb.hits
                .par_iter()
                .flatten()
                .map(|h| perpixel::shade(&p, h, &pixel_geom(&p, h)).x)
                .sum::<f64>(),
        );
    });
    let n = frags.len() as f64;
    (n / g / 1e6, n / r / 1e6, frags.len())
}

/// Every figure as a Markdown table.
pub fn bench(cfg: &PipelineConfig, work: &Path) -> Result<String> {
    let work = std::path::absolute(work).map_err(|e| Error::io(work, e))?;
    let mut s = format!("Speed on this machine ({} threads), config `{}` ({:?} lights x{}) for the simulators\n\n| measurement | figure | how |\n|---|---:|---|\n", rayon::current_num_threads(), cfg.hash(), cfg.light_mode, cfg.lights);
    let progress = crate::progress::Progress::new("bench", 5);
    for lights in [1, 4] {
        progress.start(&format!("model and reference, {lights} light(s)"));
        let (g, r, n) = model_rate(lights, 1024);
        progress.done(&format!("model, {lights} light(s): {g:.1} Mfragments/s"));
        s += &format!("| golden model, {lights} light(s) | {g:.1} Mfragments/s | 1024x1024 brick wall, {n} fragments, best of 3 |\n");
        s += &format!("| f64 per-pixel reference, {lights} light(s) | {r:.1} Mfragments/s | same fragments |\n");
    }
    let vdir = work.join("vectors");
    let _ = std::fs::remove_dir_all(&vdir);
    let all = ["top".to_string()];
    let o = crate::vectors::DumpOptions {
        text: false,
        binary: true,
        seed: 1,
        size: None,
        command: "gbump bench".into(),
        shininess: None,
    };
    let t = Instant::now();
    let sets = crate::vectors::dump(cfg, &crate::vectors::Source::Random(2_000_000), &all, &vdir, &o)?;
    let secs = t.elapsed().as_secs_f64();
    let (m, dir) = crate::vectors::verify(&sets[0].manifest)?;
    let bytes = m.bin.as_ref().expect("bin").bytes as f64;
    s += &format!(
        "| vector dump (binary, top) | {:.0} MB/s | 2,000,000 records of {} bytes in {secs:.2} s |\n",
        bytes / secs / 1e6,
        m.record_bytes
    );
    progress.done("vector dump");
    progress.start("Verilator");
    let rtl = crate::sim::rtl_files::write_rtl(cfg, &work.join("rtl"), "gbump bench")?;
    let table = dir.join(&m.power_table.name).display().to_string();
    if crate::tool::have("verilator") {
        let exe = Verilator.build_harness(
            &work.join("build"),
            &crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline"),
            &crate::sim::testbench::harness_top(cfg),
            &rtl,
        )?;
        let bin = dir.join(&m.bin.as_ref().expect("bin").name).display().to_string();
        let out = Verilator.run(
            &exe,
            &["--vectors".into(), bin.clone(), "--table".into(), table.clone()],
            None,
            &work,
            "harness",
        )?;
        s += &format!(
            "| Verilator C++ harness | {:.2} M vectors/s | {} vectors checked in {:.2} s (file load included) |\n",
            out.passed as f64 / out.seconds / 1e6,
            out.passed,
            out.seconds
        );
        let raw = Verilator.run(
            &exe,
            &[
                "--vectors".into(),
                bin,
                "--table".into(),
                table.clone(),
                "--raw".into(),
                "20000000".into(),
            ],
            None,
            &work,
            "raw",
        )?;
        let line = raw.log.lines().find(|l| l.starts_with("raw:")).unwrap_or("").to_string();
        s += &format!(
            "| Verilated model, no I/O | {} | `harness --raw 20000000` |\n",
            line.trim_start_matches("raw: ")
        );
    } else {
        s += "| Verilator | not installed | scripts/install-tools.sh |\n";
    }
    progress.done("Verilator");
    progress.start("Icarus");
    if crate::tool::have("iverilog") {
        let hexdir = work.join("hex");
        let _ = std::fs::remove_dir_all(&hexdir);
        let ho = crate::vectors::DumpOptions {
            text: true,
            binary: false,
            ..o
        };
        let hs = crate::vectors::dump(cfg, &crate::vectors::Source::Random(20_000), &all, &hexdir, &ho)?;
        let (hm, hd) = crate::vectors::verify(&hs[0].manifest)?;
        let tb = crate::sim::testbench::tb_top(cfg, &rtl);
        let exe = Icarus.build(&work.join("build"), &Testbench::new("tb_top", &tb), &rtl)?;
        let plus = [
            format!("+vectors={}", hd.join(&hm.hex.as_ref().expect("hex").name).display()),
            format!("+table={}", hd.join(&hm.power_table.name).display()),
        ];
        let out = Icarus.run(&exe, &plus, None, &work, "icarus")?;
        s += &format!(
            "| Icarus, Verilog testbench | {:.0} vectors/s | {} text vectors in {:.2} s |\n",
            out.passed as f64 / out.seconds,
            out.passed,
            out.seconds
        );
    } else {
        s += "| Icarus | not installed | scripts/install-tools.sh |\n";
    }
    progress.done("Icarus");
    let _ = std::fs::remove_dir_all(&vdir);
    Ok(s)
}
