//! Golden-model throughput: fragments per second for a 1024×1024 render with 1 and with 4
//! bump lights, beside the f64 per-pixel reference on the same fragments. Run with
//! `cargo bench --bench model_throughput`; it prints one line per measurement.

use gbump::raster::fragment::{fragments, pixel_geom};
use gbump::raster::rasterise::rasterise;
use gbump::raster::Prepared;
use gbump::reference::perpixel;
use gbump::render::golden_image;
use gbump::scene::Scene;
use indicatif::ProgressBar;
use rayon::prelude::*;
use std::time::Instant;

fn scene(lights: usize) -> Scene {
    let mut text = String::from(
        "name = \"bench\"\n[camera]\neye = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nheight = 1.9\n",
    );
    let dirs = ["[0.3, 0.2, 1.0]", "[-0.5, 0.1, 0.8]", "[0.1, -0.6, 0.7]", "[0.6, 0.6, 0.5]"];
    for d in dirs.iter().take(lights) {
        text += &format!("[[lights]]\nkind = \"directional\"\ndirection = {d}\ncolour = [0.5, 0.5, 0.5]\n");
    }
    text += "[[objects]]\nshape = { kind = \"plane\", size = [2.0, 2.0] }\nshininess = 32\nuv_scale = [4.0, 4.0]\n\
             bump = { source = { kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }, size = 256 }\n";
    Scene::from_toml("bench", &text, std::path::Path::new(".")).unwrap()
}

fn main() {
    // `cargo bench` passes --bench; under `cargo test --all-targets` this runs as a quick smoke test.
    let full = std::env::args().any(|a| a == "--bench");
    let side = if full { 1024 } else { 128 };
    let threads = rayon::current_num_threads();
    for lights in [1, 4] {
        let s = scene(lights);
        let cfg = s.derive_config().unwrap();
        let p = Prepared::new(&s, &cfg, side, side).unwrap();
        let gb = rasterise(&p);
        let frags = fragments(&p, &gb);
        let n = frags.len() as f64;
        let bar = ProgressBar::hidden();
        // Best of three, to keep one-off scheduling noise out of the figure.
        let mut best = f64::INFINITY;
        let mut check = 0u64;
        for _ in 0..3 {
            let t = Instant::now();
            let img = golden_image(&p, &frags, &bar);
            best = best.min(t.elapsed().as_secs_f64());
            check = img.iter().map(|c| c[0] as u64 + c[1] as u64 + c[2] as u64).sum();
        }
        println!("golden model   {lights} light(s): {:8.2} Mfragments/s ({n} fragments, {threads} threads, checksum {check})", n / best / 1e6);
        let mut best_ref = f64::INFINITY;
        for _ in 0..3 {
            let t = Instant::now();
            let sum: f64 = gb.hits.par_iter().flatten().map(|h| perpixel::shade(&p, h, &pixel_geom(&p, h)).x).sum();
            best_ref = best_ref.min(t.elapsed().as_secs_f64());
            assert!(sum.is_finite());
        }
        println!("f64 reference  {lights} light(s): {:8.2} Mfragments/s (interpolation + shading)", n / best_ref / 1e6);
    }
}
