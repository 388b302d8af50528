//! Rendering through the RTL: a scene's fragments stream through the Verilated pipeline (the
//! C++ harness's `--dump`), and the colours it returns are placed back at their pixels. The
//! result must equal the golden model's image bit for bit.

use super::regress::write_rtl;
use super::testbench::harness_top;
use super::{Simulator, Verilator};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
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
    let bg = crate::raster::fragment::colour_codes(glam::DVec3::from_array(scene.camera.background), cfg.colour_max());
    let mut img = vec![bg; (w * h) as usize];
    for set in sets {
        let (m, dir) = verify(&set.manifest)?;
        // Where each record's colour goes: the pixels file the dump wrote beside the set.
        let mine = read_pixels(&m, &dir, w, h)?;
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
        for ([x, y], b) in mine.iter().zip(bytes.chunks_exact(8)) {
            let v = u64::from_le_bytes(b.try_into().expect("8 bytes"));
            img[(y * w + x) as usize] = [0, 1, 2].map(|i| ((v >> (i * c)) & mask) as u32);
        }
        let _ = std::fs::remove_file(&out);
    }
    Ok(img)
}

/// The pixels of a scene set's records (its manifest's `pixels` file): one per record, each
/// inside the `w` x `h` image.
fn read_pixels(m: &crate::vectors::Manifest, dir: &Path, w: u32, h: u32) -> Result<Vec<[u32; 2]>> {
    let entry = m.pixels.as_ref().ok_or_else(|| {
        Error::Other(format!(
            "{}: a scene set without a pixels file: its colours have nowhere to go\n  fix: this is a gbump bug; report it with the scene",
            m.module
        ))
    })?;
    if m.image_size.is_some_and(|s| s != [w, h]) {
        return Err(Error::Other(format!(
            "{}: its pixels lie in a {:?} image, not the {w}x{h} one rendered\n  fix: this is a gbump bug; report it with the scene",
            m.module, m.image_size
        )));
    }
    let p = dir.join(&entry.name);
    let text = std::fs::read_to_string(&p).map_err(|e| Error::io(&p, e))?;
    let bad = |line: usize, why: &str| {
        Error::Other(format!(
            "{}:{line}: {why}\n  fix: this is a gbump bug; report it with the scene",
            p.display()
        ))
    };
    let px = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            let v: Vec<u32> = l.split(' ').filter_map(|x| x.parse().ok()).collect();
            match v[..] {
                [x, y] if x < w && y < h => Ok([x, y]),
                _ => Err(bad(i + 1, &format!("`{l}` is not a pixel `x y` of the {w}x{h} image"))),
            }
        })
        .collect::<Result<Vec<_>>>()?;
    if px.len() as u64 != m.count {
        return Err(bad(px.len(), &format!("{} pixels for {} records", px.len(), m.count)));
    }
    Ok(px)
}
