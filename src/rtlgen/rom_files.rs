//! The ROM bundle `gbump rom` writes: every ROM a configuration uses, named after what its
//! bytes depend on, in `$readmemh`, Intel MIF and Xilinx COE form.

use crate::config::PipelineConfig;
use crate::error::Result;
use crate::scene::Scene;
use std::path::Path;

/// Every ROM of `cfg` in every format: the power table for `shininess` (default the config's),
/// the bump palette (of `scene`'s maps, or the default spiral) and the normalisation cube map.
/// `config_args` and `out` go into the regeneration command in each header.
pub fn rom_files(
    cfg: &PipelineConfig,
    scene: Option<&str>,
    config_args: &str,
    shininess: Option<u32>,
    cube: usize,
    out: &Path,
) -> Result<Vec<(String, String)>> {
    use crate::limits::{check_count, MAX_CUBE_SIDE, MAX_SHININESS};
    use crate::rtlgen::rom::{cube_map_rom, default_palette, palette_rom, power_rom, rom_header, write, RomFormat, DEFAULT_PALETTE};
    let n = shininess.unwrap_or(cfg.shininess);
    check_count("--shininess", n.into(), 0, MAX_SHININESS.into(), "MAX_SHININESS")?;
    check_count("--cube-size", cube as u64, 1, MAX_CUBE_SIDE.into(), "MAX_CUBE_SIDE")?;
    let (palette, source) = match scene {
        Some(s) => {
            let scene = Scene::load(s)?;
            let pcfg = PipelineConfig {
                palette: true,
                ..cfg.clone()
            };
            let p = crate::raster::Prepared::new(&scene, &pcfg, 1, 1)?;
            (p.objects[0].stored.palette().cloned().expect("palette mode"), scene.name.clone())
        }
        None => (default_palette(cfg), DEFAULT_PALETTE.to_string()),
    };
    let cmd = format!(
        "gbump rom {} --shininess {n} --cube-size {cube} --out {}",
        config_args,
        crate::shell::quoted(&out.display().to_string())
    )
    .replace("  ", " ");
    let hash = &cfg.hash()[..8];
    let mut files = Vec::new();
    // A name carries what the contents depend on: the exponent, the palette's source, the
    // cube size; the config hash stands for the widths.
    for (stem, rom, of) in [
        (format!("power_table_n{n}_{hash}"), power_rom(cfg, n), Some(cfg)),
        (
            format!("bump_palette_{source}_{hash}"),
            palette_rom(cfg, &palette, &source),
            Some(cfg),
        ),
        (format!("cube_map_{cube}x{cube}x6_rgb8"), cube_map_rom(cube), None),
    ] {
        let hl = rom_header(&rom, of, &cmd, &rom.name);
        for f in RomFormat::ALL {
            files.push((format!("{stem}.{}", f.ext()), write(&rom, f, &hl)));
        }
    }
    Ok(files)
}
