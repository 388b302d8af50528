//! The whole command line: one clap definition and one function per subcommand.

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::measure::image_metrics::{compare, error_map};
use crate::render::output::{codes_to_u8, f64_to_u8, heat_map, write_atomic, write_png};
use crate::scene::{builtin, Scene};
use clap::{Parser, Subcommand};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

#[derive(Parser)]
#[command(name = "gbump", version, about = "Golden model, RTL generator and regression runner for Gouraud Bump Mapping hardware")]
pub struct Cli {
    #[command(subcommand)]
    pub cmd: Cmd,
}

#[derive(Subcommand)]
pub enum Cmd {
    /// List the built-in scenes, or print one as TOML.
    Scenes {
        #[arg(long, value_name = "NAME")]
        show: Option<String>,
    },
    /// Render a scene: golden image, f64 Gouraud-equation image, per-pixel reference, heat map.
    Render {
        /// Built-in scene name or path to a scene .toml file.
        #[arg(long, default_value = builtin::DEFAULT)]
        scene: String,
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Image size WxH (default: the scene's).
        #[arg(long, value_name = "WxH")]
        size: Option<String>,
        /// Pipeline configuration TOML (default: derived from the scene).
        #[arg(long, value_name = "FILE")]
        config: Option<PathBuf>,
    },
    /// Generate the Verilog, ROM init file and interface JSON of a configuration.
    Rtl {
        #[command(flatten)]
        pick: ConfigPick,
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Write LUT ROM init files (.hex, .mif, .coe): power table, bump palette, cube map.
    Rom {
        #[command(flatten)]
        pick: ConfigPick,
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Shininess of the power table (default: the config's).
        #[arg(long)]
        shininess: Option<u32>,
        /// Side of each normalisation cube-map face.
        #[arg(long, default_value_t = 32)]
        cube_size: usize,
    },
    /// Print a pipeline configuration as TOML with its hash: the default, or a scene's.
    Config {
        #[arg(long)]
        scene: Option<String>,
    },
}

/// Which configuration a command works on: a TOML file, a scene's derived one, or the default.
#[derive(clap::Args, Clone, Debug)]
pub struct ConfigPick {
    /// Pipeline configuration TOML.
    #[arg(long, value_name = "FILE", conflicts_with = "scene")]
    pub config: Option<PathBuf>,
    /// Derive the configuration from a scene (built-in name or file).
    #[arg(long)]
    pub scene: Option<String>,
}

impl ConfigPick {
    pub fn resolve(&self) -> Result<PipelineConfig> {
        match (&self.config, &self.scene) {
            (Some(p), _) => PipelineConfig::load(p),
            (None, Some(s)) => Scene::load(s)?.derive_config(),
            (None, None) => Ok(PipelineConfig::default()),
        }
    }

    /// The arguments that select this configuration, for regeneration commands in headers.
    pub fn args(&self) -> String {
        match (&self.config, &self.scene) {
            (Some(p), _) => format!("--config {}", p.display()),
            (None, Some(s)) => format!("--scene {s}"),
            (None, None) => String::new(),
        }
    }
}

/// Write every file into `dir` atomically; on any failure remove what this call wrote.
pub fn write_files(dir: &Path, files: &[(String, String)]) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    for (i, (name, text)) in files.iter().enumerate() {
        if let Err(e) = write_atomic(&dir.join(name), text.as_bytes()) {
            for (n, _) in &files[..i] {
                let _ = std::fs::remove_file(dir.join(n));
            }
            return Err(e);
        }
    }
    Ok(())
}

pub fn run() -> anyhow::Result<()> {
    let cli = Cli::parse();
    match cli.cmd {
        Cmd::Scenes { show } => scenes(show)?,
        Cmd::Render { scene, out, size, config } => render(&scene, &out, size.as_deref(), config.as_deref())?,
        Cmd::Rtl { pick, out } => {
            let cfg = pick.resolve()?;
            let cmd = format!("gbump rtl {} --out {}", pick.args(), out.display()).replace("  ", " ");
            let files = crate::rtlgen::generate(&cfg, &cmd);
            write_files(&out, &files)?;
            println!("wrote {} files for config {} to {} (top {}, latency {} cycles)", files.len(), cfg.hash(), out.display(),
                crate::rtlgen::units_v::module_name(&cfg, "gbump_pipeline"), crate::rtlgen::top::latency(&cfg));
        }
        Cmd::Rom { pick, out, shininess, cube_size } => {
            let cfg = pick.resolve()?;
            let files = rom_files(&cfg, &pick, shininess, cube_size, &out)?;
            write_files(&out, &files)?;
            println!("wrote {} ROM files to {}", files.len(), out.display());
        }
        Cmd::Config { scene } => {
            let cfg = match scene {
                Some(s) => Scene::load(&s)?.derive_config()?,
                None => PipelineConfig::default(),
            };
            print!("# config hash {}\n{}", cfg.hash(), cfg.to_toml());
        }
    }
    Ok(())
}

fn scenes(show: Option<String>) -> Result<()> {
    match show {
        Some(name) => print!("{}", builtin::get(&name).ok_or(Error::UnknownScene { name: name.clone() })?),
        None => {
            for (name, text) in builtin::ALL {
                let s = Scene::from_toml(name, text, Path::new("scenes"))?;
                println!("{name:22} {}", s.description);
            }
        }
    }
    Ok(())
}

/// Parse `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32)> {
    let bad = || Error::Other(format!("--size {s}: expected WxH with 1..=16384 pixels per side, e.g. 512x384"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?);
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(bad());
    }
    Ok((w, h))
}

/// Scene plus the configuration to render it with (a given file, or derived).
pub fn scene_and_config(scene: &str, config: Option<&Path>) -> Result<(Scene, PipelineConfig)> {
    let s = Scene::load(scene)?;
    let cfg = match config {
        Some(p) => {
            let c = PipelineConfig::load(p)?;
            s.check_config(&c, &p.display().to_string())?;
            c
        }
        None => s.derive_config()?,
    };
    Ok((s, cfg))
}

fn render(scene: &str, out: &Path, size: Option<&str>, config: Option<&Path>) -> Result<()> {
    let (s, cfg) = scene_and_config(scene, config)?;
    let (w, h) = match size {
        Some(sz) => parse_size(sz)?,
        None => (s.size[0], s.size[1]),
    };
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let t0 = std::time::Instant::now();
    let img = crate::render::render(&s, &cfg, w, h, std::io::stderr().is_terminal())?;
    let secs = t0.elapsed().as_secs_f64();
    let max = img.colour_max;
    let vs_ref = compare(&img.golden, &img.reference, &img.covered, max);
    let vs_gou = compare(&img.golden, &img.gouraud, &img.covered, max);
    let alg = compare(&crate::render::output::quantise(&img.gouraud, max), &img.reference, &img.covered, max);
    let emap = error_map(&img.golden, &img.reference, &img.covered, max);
    let name = &s.name;
    let files = [
        (format!("{name}_golden.png"), codes_to_u8(&img.golden, max)),
        (format!("{name}_gouraud_f64.png"), f64_to_u8(&img.gouraud)),
        (format!("{name}_reference.png"), f64_to_u8(&img.reference)),
        (format!("{name}_diff.png"), heat_map(&emap, vs_ref.max_lsb.max(4.0))),
    ];
    for (f, px) in &files {
        write_png(&out.join(f), w, h, px)?;
    }
    let report = serde_json::json!({
        "scene": name, "size": [w, h], "config_hash": cfg.hash(), "fragments": vs_ref.pixels,
        "golden_vs_reference": vs_ref, "golden_vs_gouraud_f64": vs_gou, "gouraud_f64_vs_reference": alg,
        "seconds": secs,
    });
    write_atomic(&out.join(format!("{name}_metrics.json")), serde_json::to_string_pretty(&report).expect("json").as_bytes())?;
    println!("scene {name} {w}x{h}, config {}, {} fragments, {:.2} s", cfg.hash(), vs_ref.pixels, secs);
    println!("  golden vs per-pixel reference: PSNR {:6.2} dB, max {:5.1} LSB, mean {:.3} LSB, {:5.2}% of pixels off by >1 LSB", vs_ref.psnr_db, vs_ref.max_lsb, vs_ref.mean_lsb, 100.0 * vs_ref.over_1lsb);
    println!("  golden vs f64 Gouraud bump   : PSNR {:6.2} dB, max {:5.1} LSB, mean {:.3} LSB, {:5.2}% of pixels off by >1 LSB", vs_gou.psnr_db, vs_gou.max_lsb, vs_gou.mean_lsb, 100.0 * vs_gou.over_1lsb);
    println!("  wrote {} and {name}_metrics.json in {}", files.iter().map(|f| f.0.as_str()).collect::<Vec<_>>().join(", "), out.display());
    Ok(())
}

fn rom_files(cfg: &PipelineConfig, pick: &ConfigPick, shininess: Option<u32>, cube: usize, out: &Path) -> Result<Vec<(String, String)>> {
    use crate::rtlgen::rom::{cube_map_rom, default_palette, palette_rom, power_rom, write, RomFormat};
    let n = shininess.unwrap_or(cfg.shininess);
    if n > 1024 {
        return Err(Error::Other(format!("--shininess {n}: out of range\n  fix: use 0..=1024")));
    }
    if !(1..=1024).contains(&cube) {
        return Err(Error::Other(format!("--cube-size {cube}: out of range\n  fix: use 1..=1024 texels per face side")));
    }
    let palette = match &pick.scene {
        Some(s) => {
            let scene = Scene::load(s)?;
            let pcfg = PipelineConfig { palette: true, ..cfg.clone() };
            let p = crate::raster::Prepared::new(&scene, &pcfg, 1, 1)?;
            p.objects[0].stored.palette().cloned().expect("palette mode")
        }
        None => default_palette(cfg),
    };
    let cmd = format!("gbump rom {} --shininess {n} --cube-size {cube} --out {}", pick.args(), out.display()).replace("  ", " ");
    let hash = &cfg.hash()[..8];
    let mut files = Vec::new();
    for (stem, rom) in [
        (format!("power_table_n{n}_{hash}"), power_rom(cfg, n)),
        (format!("bump_palette_{hash}"), palette_rom(cfg, &palette)),
        (format!("cube_map_{cube}"), cube_map_rom(cube)),
    ] {
        let hl = crate::rtlgen::header::header_lines(cfg, &cmd, &rom.name);
        for f in RomFormat::ALL {
            files.push((format!("{stem}.{}", f.ext()), write(&rom, f, &hl)));
        }
    }
    Ok(files)
}
