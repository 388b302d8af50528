//! Rendering through the RTL: a scene's fragments stream through the Verilated pipeline (the
//! C++ harness's `--dump`), and the colours it returns are placed back at their pixels. The
//! result must equal the golden model's image bit for bit.

use super::regress::write_rtl;
use super::testbench::harness_top;
use super::{Simulator, Verilator};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::raster::{fragment::fragments, rasterise::rasterise, Prepared};
use crate::scene::Scene;
use crate::vectors::{dump, verify, DumpOptions, Source};
use std::path::Path;

/// Where `gbump render --rtl` builds and caches.
pub const RENDER_WORK: &str = "target/gbump-render";

/// The image the RTL renders: background where no fragment lands.
pub fn rtl_image(scene_name: &str, cfg: &PipelineConfig, w: u32, h: u32, work: &Path) -> Result<Vec<[u32; 3]>> {
    let work = std::path::absolute(work).map_err(|e| Error::io(work, e))?;
    let scene = Scene::load(scene_name)?;
    let hash = &cfg.hash()[..8];
    let rtl = write_rtl(cfg, &work.join(format!("rtl_{hash}")), "gbump render --rtl")?;
    let vdir = work.join(format!("image_{hash}_{}", scene.name));
    let opts = DumpOptions {
        seed: 0,
        size: Some((w, h)),
        ..DumpOptions::formats(
            format!("gbump render --rtl --scene {}", crate::shell::quoted(scene_name)),
            false,
            true,
        )
    };
    let sets = dump(cfg, &Source::Scene(scene_name.to_string()), &["top".to_string()], &vdir, &opts)?;
    let exe = Verilator.build_harness(
        &work.join("build"),
        &crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline"),
        &harness_top(cfg),
        &rtl,
    )?;
    // The same fragments in the same order as the dump, to know where each colour goes.
    let p = Prepared::new(&scene, cfg, w, h)?;
    let frags = fragments(&p, &rasterise(&p)?);
    let bg = crate::raster::fragment::colour_codes(glam::DVec3::from_array(scene.camera.background), cfg.colour_max());
    let mut img = vec![bg; (w * h) as usize];
    // The dump's groups in their order (`scene_groups`): one set each.
    let key = |obj: u32| crate::vectors::sources::group_key(cfg, &scene, obj);
    let keys: std::collections::BTreeSet<u32> = frags.iter().map(|f| key(f.obj)).collect();
    if keys.len() != sets.len() {
        return Err(Error::Other(format!(
            "render --rtl: the dump wrote {} top set(s) for {} group(s) of fragments; colours would land on the wrong pixels",
            sets.len(),
            keys.len()
        )));
    }
    for (set, k) in sets.into_iter().zip(keys) {
        let (m, dir) = verify(&set.manifest)?;
        let mine: Vec<_> = frags.iter().filter(|f| key(f.obj) == k).collect();
        let out = dir.join(format!("{}.rtl_out", m.module));
        let bin = dir.join(&m.bin.as_ref().expect("binary set").name);
        let args = [
            "--vectors".to_string(),
            bin.display().to_string(),
            "--table".into(),
            dir.join(&m.power_table.name).display().to_string(),
            "--dump".into(),
            out.display().to_string(),
            "--no-check".into(),
        ];
        let args: Vec<String> = args
            .into_iter()
            .chain(super::regress::harness_memory_args(m.env_maps.as_ref(), &dir))
            .collect();
        let res = Verilator.run(&exe, &args, None, &dir, "verilator render")?;
        let bytes = std::fs::read(&out).map_err(|e| Error::io(&out, e))?;
        if bytes.len() != mine.len() * 8 || res.passed as usize != mine.len() {
            return Err(Error::Other(format!(
                "the RTL returned {} colours for {} fragments",
                bytes.len() / 8,
                mine.len()
            )));
        }
        let c = cfg.colour_bits;
        let mask = (1u64 << c) - 1;
        for (f, b) in mine.iter().zip(bytes.chunks_exact(8)) {
            let v = u64::from_le_bytes(b.try_into().expect("8 bytes"));
            img[(f.y * w + f.x) as usize] = [0, 1, 2].map(|i| ((v >> (i * c)) & mask) as u32);
        }
        let _ = std::fs::remove_file(&out);
    }
    Ok(img)
}
