//! The ROM bundle `gbump rom` writes: every ROM a configuration uses, named after what its
//! bytes depend on, in `$readmemh`, Intel MIF and Xilinx COE form.

use crate::config::PipelineConfig;
use crate::error::Result;
use crate::scene::Scene;
use std::path::Path;

/// The cube map's side when neither the configuration nor `--cube-size` gives one (the Cg
/// Tutorial's size).
pub const DEFAULT_CUBE: usize = 32;

/// The ROMs of `cfg` in every format: the power table for `shininess` (default the config's;
/// none for a squaring power unit, which has no memory), the bump palette (of `scene`'s maps,
/// or the default spiral) and the normalisation cube map of `cube` texels a face edge
/// (default the config's `cube_map_face`, else [`DEFAULT_CUBE`]). A shininess or cube size the
/// configuration's hardware cannot take (a power ROM or squaring unit built for another
/// shininess, another cube map) is refused, as every consumer of the files would refuse it.
/// `config_args` and `out` go into the regeneration command in each header.
pub fn rom_files(
    cfg: &PipelineConfig,
    scene: Option<&str>,
    config_args: &str,
    shininess: Option<u32>,
    cube: Option<usize>,
    out: &Path,
) -> Result<Vec<(String, String)>> {
    use crate::rtlgen::rom::{cube_map_rom, default_palette, palette_rom, power_rom, rom_header, write, RomFormat, DEFAULT_PALETTE};
    let (n, cube) = rom_choices(cfg, shininess, cube, ["--shininess", "--cube-size"])?;
    let hash = &cfg.hash()[..8];
    // A scene's palette is its first object's, as a palette configuration would store its map
    // (`palette` forced on); each object's bump map as the texture memory holds it, and
    // under a palette configuration every further object's own palette, which its map's
    // indices point into.
    let mut maps = Vec::new();
    // The power tables: the one asked for, or each one a scene's objects read (a vector dump
    // of the scene makes one set per table).
    let mut tables = std::collections::BTreeSet::from([n]);
    // EMBM's environment maps: the power-up ones, or each object's of a scene.
    let mut env = Vec::new();
    let (palette, source) = match scene {
        Some(s) => {
            let scene = Scene::load(s)?;
            if shininess.is_none() && !cfg.embm() {
                tables.extend((0..scene.objects.len() as u32).map(|i| crate::vectors::sources::group_key(cfg, &scene, i)));
            }
            let pcfg = PipelineConfig {
                palette: true,
                ..cfg.clone()
            };
            let pp = crate::raster::Prepared::new(&scene, &pcfg, 1, 1)?;
            let palette_of = |i: usize| pp.objects[i].stored.palette().cloned().expect("palette mode");
            // The configuration's own maps: the palettised ones above where it has a palette.
            let own;
            let p = match cfg.palette {
                true => &pp,
                false => {
                    own = crate::raster::Prepared::new(&scene, cfg, 1, 1)?;
                    &own
                }
            };
            for (i, (o, so)) in p.objects.iter().zip(&scene.objects).enumerate() {
                let object = format!("{} object {i}", scene.name);
                let palette_stem = match i {
                    0 => format!("bump_palette_{}_{hash}", scene.name),
                    _ => format!("bump_palette_{}_o{i}_{hash}", scene.name),
                };
                let filter = match &o.stored {
                    crate::bumpmap::storage::StoredMap::Palettised { .. } => {
                        if i > 0 {
                            maps.push((palette_stem.clone(), palette_rom(cfg, &palette_of(i), &object), Some(cfg)));
                        }
                        format!("nearest (a palette index); its palette is {palette_stem}")
                    }
                    _ => format!("{:?}", so.bump.filter).to_lowercase(),
                };
                maps.push((
                    format!("bump_map_{}_o{i}_{hash}", scene.name),
                    crate::rtlgen::rom::bump_map_rom(cfg, &o.stored, &object, &filter),
                    Some(cfg),
                ));
                // EMBM: the object's environment maps, which its records light with.
                env.extend(env_roms(cfg, &o.env, &format!("{}_o{i}", scene.name), &object));
            }
            (palette_of(0), scene.name.clone())
        }
        None => {
            let maps = crate::model::env_map::default_maps(cfg);
            env.extend(env_roms(
                cfg,
                &maps,
                crate::rtlgen::rom::DEFAULT_ENV_MAPS,
                crate::rtlgen::rom::DEFAULT_ENV_MAPS,
            ));
            (default_palette(cfg), DEFAULT_PALETTE.to_string())
        }
    };
    let cmd = format!(
        "gbump rom {} --shininess {n} --cube-size {cube} --out {}",
        config_args,
        crate::shell::quoted(&out.display().to_string())
    )
    .replace("  ", " ");
    let mut files = Vec::new();
    // A name carries what the contents depend on: the exponent, the palette's source, the
    // cube size; the config hash stands for the widths.
    // No table where the top reads none (a squaring unit computes x^n, EMBM lights from its maps).
    let table = crate::rtlgen::top::power_table_read(cfg);
    for (stem, rom, of) in [
        Some((
            format!("bump_palette_{source}_{hash}"),
            palette_rom(cfg, &palette, &source),
            Some(cfg),
        )),
        Some((format!("cube_map_{cube}x{cube}x6_rgb8"), cube_map_rom(cube), None)),
    ]
    .into_iter()
    .flatten()
    .chain(
        tables
            .into_iter()
            .filter(|_| table)
            .map(|n| (format!("power_table_n{n}_{hash}"), power_rom(cfg, n), Some(cfg))),
    )
    .chain(maps)
    .chain(env)
    {
        let hl = rom_header(&rom, of, &cmd, &rom.name);
        for f in RomFormat::ALL {
            files.push((format!("{stem}.{}", f.ext()), write(&rom, f, &hl)));
        }
    }
    Ok(files)
}

/// EMBM's environment maps `maps` as ROMs (one per map the top has a port for), named
/// `env_<which>_<source>_<hash>`; none for another configuration. `what` is the maps' source
/// in the ROM's header.
fn env_roms<'a>(
    cfg: &'a PipelineConfig,
    maps: &crate::model::env_map::EnvMaps,
    source: &str,
    what: &str,
) -> Vec<(String, crate::rtlgen::rom::Rom, Option<&'a PipelineConfig>)> {
    let hash = &cfg.hash()[..8];
    crate::rtlgen::top::env_map_names(cfg)
        .into_iter()
        .map(|which| {
            (
                format!("env_{which}_{source}_{hash}"),
                crate::rtlgen::rom::env_map_rom(cfg, maps.named(which), which, what),
                Some(cfg),
            )
        })
        .collect()
}

/// The shininess and cube-map size a ROM request comes to, whoever asks (`gbump rom`, the
/// Python module's `Config.rom`): `shininess` (default the configuration's) must be one its
/// hardware serves, `cube` (default the configuration's `cube_map_face`, else
/// [`DEFAULT_CUBE`]) the map its `normalise_cube` unit reads. `names` spells the two choices
/// as the caller does (`--shininess` and `--cube-size`, or `shininess=` and `cube_size=`).
pub fn rom_choices(cfg: &PipelineConfig, shininess: Option<u32>, cube: Option<usize>, names: [&str; 2]) -> Result<(u32, usize)> {
    use crate::limits::{check_count, MAX_CUBE_SIDE, MAX_SHININESS};
    let [sn, cn] = names;
    if let (Some(n), true) = (shininess, cfg.embm()) {
        return Err(crate::error::Error::Other(format!(
            "{}: EMBM has no power unit (its specular light comes from the environment map)\n  fix: drop {sn}",
            crate::names::choice(sn, n)
        )));
    }
    let n = shininess.unwrap_or(cfg.shininess);
    check_count(sn, n.into(), 0, MAX_SHININESS.into(), "MAX_SHININESS")?;
    if let Some(fixed) = cfg.fixed_shininess().filter(|_| n != cfg.shininess) {
        return Err(fixed.refuse(sn, n));
    }
    let cube = match (cube, cfg.cube_map_face as usize) {
        (Some(c), face) if face != 0 && c != face => {
            return Err(crate::error::Error::Other(format!(
                "{}: the configuration's normalise_cube unit reads a map of {face} texels a face edge (cube_map_face = {face})\n  fix: drop {cn} (the map is the configuration's), or give a configuration whose cube_map_face is the size you want",
                crate::names::choice(cn, c)
            )))
        }
        (Some(c), _) => c,
        (None, 0) => DEFAULT_CUBE,
        (None, face) => face,
    };
    check_count(cn, cube as u64, 1, MAX_CUBE_SIDE.into(), "MAX_CUBE_SIDE")?;
    Ok((n, cube))
}

/// The files of an earlier `gbump rom --scene` into `out` that this one's `files` leave out:
/// an object's bump map or palette past the scene's objects now (the scene lost an object),
/// which would otherwise pass for the scene's.
pub fn stale_scene_roms(out: &Path, scene: &str, cfg: &PipelineConfig, files: &[(String, String)]) -> Vec<std::path::PathBuf> {
    let Ok(scene) = Scene::load(scene) else {
        return Vec::new();
    };
    let hash = &cfg.hash()[..8];
    let Ok(entries) = std::fs::read_dir(out) else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter_map(|e| {
            let n = e.file_name().to_string_lossy().into_owned();
            let object = ["bump_map", "bump_palette"].iter().find_map(|kind| {
                let rest = n.strip_prefix(&format!("{kind}_{}_o", scene.name))?;
                let (i, tail) = rest.split_once('_')?;
                let ext = tail.strip_prefix(hash)?.strip_prefix('.')?;
                (["hex", "mif", "coe"].contains(&ext) && i.bytes().all(|b| b.is_ascii_digit())).then_some(())
            });
            (object.is_some() && !files.iter().any(|(f, _)| *f == n)).then(|| e.path())
        })
        .collect()
}
