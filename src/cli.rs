//! The whole command line: one clap definition and one function per subcommand.

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::render::output::write_atomic;
use crate::scene::{builtin, Scene};
use clap::{Parser, Subcommand};

/// `println!` that returns an error (naming standard output) instead of panicking when stdout
/// is closed or full (`gbump scenes > /dev/full`, a closed pipe).
macro_rules! outln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout(), $($t)*).map_err(|e| Error::io(crate::error::STDOUT, e))?
    }};
}

macro_rules! out {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        write!(std::io::stdout(), $($t)*).and_then(|_| std::io::stdout().flush()).map_err(|e| Error::io(crate::error::STDOUT, e))?
    }};
}
use std::path::{Path, PathBuf};

#[derive(Parser)]
#[command(
    name = "gbump",
    version = crate::LONG_VERSION,
    about = "Golden model, RTL generator and regression runner for Gouraud Bump Mapping hardware"
)]
pub struct Cli {
    #[command(subcommand)]
    pub cmd: Cmd,
    /// Stop any simulator, build or synthesis that runs longer than this, in seconds, and
    /// fail (default: the GBUMP_TOOL_TIMEOUT environment variable, else no limit)
    #[arg(long, global = true, value_name = "SECONDS")]
    // Read as text, so a refusal echoes what was typed (`1e400`, not `inf`).
    pub tool_timeout: Option<String>,
}

#[derive(Subcommand)]
pub enum Cmd {
    /// List the built-in scenes, or print one as TOML.
    Scenes {
        /// Print a built-in scene's TOML (a template for your own), or check a scene file (as
        /// `gbump render` does, rendering it at its own size) and print it.
        #[arg(long, value_name = "NAME|FILE")]
        show: Option<String>,
    },
    /// Render a scene: golden image, f64 Gouraud-equation image, per-pixel reference, heat map.
    Render {
        /// Built-in scene name or path to a scene .toml file.
        #[arg(long, default_value = builtin::DEFAULT)]
        scene: String,
        #[arg(long, value_name = "DIR", value_parser = output_dir)]
        out: PathBuf,
        /// Image size WxH (default: the scene's).
        #[arg(long, value_name = "WxH")]
        size: Option<String>,
        /// Pipeline configuration TOML (default: derived from the scene).
        #[arg(long, value_name = "FILE")]
        config: Option<PathBuf>,
        /// Also render through the Verilated RTL and require it to equal the golden image.
        #[arg(long)]
        rtl: bool,
        /// Work folder of --rtl: generated RTL and the cached Verilator build.
        #[arg(long, default_value = crate::sim::rtl_image::RENDER_WORK, value_parser = output_dir, requires = "rtl")]
        work: PathBuf,
    },
    /// Generate the Verilog, ROM init file and interface JSON of a configuration.
    Rtl {
        #[command(flatten)]
        pick: ConfigPick,
        #[arg(long, value_name = "DIR", value_parser = output_dir)]
        out: PathBuf,
    },
    /// Write LUT ROM init files (.hex, .mif, .coe): power table, bump palette, cube map.
    Rom {
        #[command(flatten)]
        pick: ConfigPick,
        #[arg(long, value_name = "DIR", value_parser = output_dir)]
        out: PathBuf,
        /// Shininess of the power table (default: the config's).
        #[arg(long)]
        shininess: Option<u32>,
        /// Side of each normalisation cube-map face (default: the config's cube_map_face, else 32).
        #[arg(long)]
        cube_size: Option<usize>,
        /// With --scene: the configuration is engine NAME's bit-accurate path on the scene, as
        /// `gbump config --scene S --engine NAME` prints it (`embm`: each object's environment
        /// maps).
        #[arg(long, value_name = "NAME", requires = "scene")]
        engine: Option<String>,
    },
    /// Dump stimulus/response vectors from the golden model (text, binary and a manifest).
    Vectors {
        /// scene:NAME (under the scene's own configuration unless --config or --scene names one) | corners | random:N | exhaustive:UNIT
        #[arg(long)]
        source: String,
        /// `all`, `top`, or a unit name (repeatable).
        #[arg(long, default_value = "all")]
        target: Vec<String>,
        #[command(flatten)]
        pick: ConfigPick,
        /// Folder for the sets: each set is SET.json (its manifest), SET.hex, SET.bin and
        /// SET_power_table.hex (a scene's top set also SET_pixels.txt, each record's pixel,
        /// and under EMBM SET_env_diffuse.hex and SET_env_specular.hex), SET being
        /// SOURCE_TARGET with SOURCE corners, corners_level2, random<N>, scene_<NAME> (_nS or
        /// _oI added where a scene has several power tables or EMBM objects) or
        /// exhaustive_<UNIT>, e.g. random1000_top.
        #[arg(long, value_name = "DIR", value_parser = output_dir)]
        out: PathBuf,
        /// Seed of random sources (default 1).
        #[arg(long)]
        seed: Option<u64>,
        /// Which files to write.
        #[arg(long, value_enum, default_value = "both")]
        format: VecFormat,
        /// Image size for scene sources (default: the scene's).
        #[arg(long, value_name = "WxH")]
        size: Option<String>,
        /// Corner-catalogue level (with --source corners; default 1).
        #[arg(long, value_parser = clap::value_parser!(u8).range(1..=2))]
        level: Option<u8>,
        /// Power-table shininess for corners, random and exhaustive sources (default: the config's).
        #[arg(long)]
        shininess: Option<u32>,
    },
    /// Run the generated RTL against golden vectors under Icarus and/or Verilator.
    Regress {
        #[arg(long, value_enum, default_value = "both")]
        sim: SimChoice,
        #[command(flatten)]
        pick: ConfigPick,
        /// Run these vector manifests (JSON files or folders of them; a folder's subfolders are not read) instead of the default suite.
        #[arg(long, value_name = "PATH")]
        vectors: Vec<PathBuf>,
        /// Stream random:N, scene:NAME or corners through the Verilator harness instead: made in
        /// this process and piped, no vector file (N up to MAX_STREAM_VECTORS).
        #[arg(long, value_name = "SOURCE", conflicts_with = "vectors")]
        stream: Option<String>,
        /// Random top vectors on Verilator (0 skips the random sets).
        #[arg(long, default_value_t = 1_000_000, conflicts_with_all = ["vectors", "stream"])]
        random: u64,
        /// Random top vectors on Icarus (0 skips the random sets).
        #[arg(long, default_value_t = 100_000, conflicts_with_all = ["vectors", "stream"])]
        random_icarus: u64,
        /// Seed of the random sets, or of `--stream random:N` (default 1).
        #[arg(long, conflicts_with = "vectors")]
        seed: Option<u64>,
        /// Skip the built-in scenes' fragments.
        #[arg(long, conflicts_with_all = ["vectors", "stream"])]
        no_scenes: bool,
        /// The default suite's sets for `all`, `top` or a unit name only (repeatable): the
        /// scene sets and the power-up run are top sets, the exhaustive sweeps their unit's.
        #[arg(long, default_value = "all", conflicts_with_all = ["vectors", "stream"])]
        target: Vec<String>,
        /// Scene image size for fragment vectors.
        #[arg(long, value_name = "WxH", conflicts_with = "vectors")]
        scene_size: Option<String>,
        /// Work folder: generated RTL, vectors and cached builds.
        #[arg(long, default_value = "target/gbump-regress", value_parser = output_dir)]
        work: PathBuf,
        /// Write JUnit XML here.
        #[arg(long, value_name = "FILE", value_parser = output_file)]
        junit: Option<PathBuf>,
        /// Dump waveforms (FST) of every run.
        #[arg(long)]
        waves: bool,
        #[arg(long, default_value_t = crate::sim::regress::MAX_ERRORS)]
        max_errors: u32,
    },
    /// Lint the generated RTL: verilator --lint-only -Wall, iverilog -Wall, and Yosys synthesis checks.
    Lint {
        #[command(flatten)]
        pick: ConfigPick,
        #[arg(long, default_value = "target/gbump-lint", value_parser = output_dir)]
        work: PathBuf,
    },
    /// Draw random valid configurations; generate, lint and simulate each on Verilator.
    Fuzz {
        /// Stop after this many minutes.
        #[arg(long, default_value_t = 10.0)]
        minutes: f64,
        /// Stop after this many configurations (whichever comes first).
        #[arg(long)]
        configs: Option<u64>,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Random top vectors per configuration (unit sets get as many each).
        #[arg(long, default_value_t = 2000)]
        random: u64,
        #[arg(long, default_value = "target/gbump-fuzz", value_parser = output_dir)]
        work: PathBuf,
    },
    /// Yosys area per unit and in total: gate equivalents, flip-flops, logic depth, ROM bits;
    /// or FPGA resources (and, for iCE40, Fmax and utilisation from nextpnr).
    Area {
        #[command(flatten)]
        pick: ConfigPick,
        #[arg(long, default_value = "target/gbump-area", value_parser = output_dir)]
        work: PathBuf,
        /// cmos: NAND2 gate equivalents; ice40, ecp5, xilinx: LUTs, flip-flops, carry, DSP, RAM.
        #[arg(long, value_enum, default_value = "cmos")]
        target: crate::measure::fpga::Target,
        /// iCE40 device for place and route (hx1k, hx4k, hx8k, lp1k, lp8k, up5k; default hx8k).
        #[arg(long)]
        device: Option<String>,
        /// Also write the report as JSON.
        #[arg(long, value_name = "FILE", value_parser = output_file)]
        json: Option<PathBuf>,
    },
    /// Error against exact arithmetic per unit and for the pipeline, and image error per scene.
    Error {
        #[command(flatten)]
        pick: ConfigPick,
        /// Random stimuli per unit (the table's samples count outputs: one per channel and light of each stimulus).
        #[arg(long, default_value_t = 100_000)]
        random: u64,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Image size for the per-scene table.
        #[arg(long, value_name = "WxH", default_value = crate::measure::scene_error::IMAGE_SIZE_ARG)]
        size: String,
        /// Also write the report as JSON.
        #[arg(long, value_name = "FILE", value_parser = output_file)]
        json: Option<PathBuf>,
    },
    /// Compare power-unit designs (tables, interpolation, segments, squaring) for every n.
    PowerSpace {
        #[command(flatten)]
        pick: ConfigPick,
        /// Largest exponent to check (1..=MAX_SHININESS).
        #[arg(long, default_value_t = 255, value_parser = clap::value_parser!(u32).range(1..=crate::limits::MAX_SHININESS as i64))]
        max_n: u32,
        #[arg(long, value_name = "FILE", value_parser = output_file)]
        json: Option<PathBuf>,
        /// Also synthesise the plain tables and every design within 1 LSB with Yosys.
        #[arg(long)]
        area: bool,
        #[arg(long, default_value = "target/gbump-power", value_parser = output_dir)]
        work: PathBuf,
    },
    /// Sweep a grid of configurations: CSV, JSON and an SVG of error against area with the Pareto front.
    Sweep {
        /// The space: [base] overrides and [grid] arrays of values (see sweeps/small.toml).
        #[arg(long, value_name = "FILE")]
        space: PathBuf,
        #[arg(long, value_name = "DIR", value_parser = output_dir)]
        out: PathBuf,
        /// Cache of finished configurations (a re-run resumes from it).
        #[arg(long, default_value = "target/gbump-sweep", value_parser = output_dir)]
        work: PathBuf,
        /// Size every point with Yosys (about 30 s a configuration) instead of the area model.
        #[arg(long)]
        yosys: bool,
    },
    /// The smallest configuration that renders the scenes within an error budget, and the front around it.
    Fit {
        /// A built-in scene or a scene file (repeat for several).
        #[arg(long, required = true)]
        scene: Vec<String>,
        /// max<=LSB or psnr>=DB (golden against the f64 Gouraud image), or exact<=LSB (against exact arithmetic on random inputs).
        #[arg(long)]
        budget: String,
        /// Fragments per clock at least (1 = one per clock; a serial top of n lights gives 1/n).
        #[arg(long, default_value_t = 0.0)]
        min_throughput: f64,
        /// Where fit.toml, front.csv and front.svg go.
        #[arg(long, default_value = "out/fit", value_name = "DIR", value_parser = output_dir)]
        out: PathBuf,
        /// Skip generating, linting and regressing the chosen configuration on both simulators.
        #[arg(long)]
        no_regress: bool,
        /// Also synthesise the chosen configuration and the front with Yosys (about 30 s a
        /// configuration) and print each beside the area model's estimate.
        #[arg(long)]
        yosys: bool,
        /// Deepen the chosen pipeline until the top, placed and routed on an iCE40 (nextpnr,
        /// minutes per depth), reaches this clock in MHz.
        #[arg(long, value_name = "MHZ")]
        min_fmax: Option<f64>,
        /// The iCE40 device of --min-fmax (hx1k, hx4k, hx8k, lp1k, lp8k, up5k; default hx8k).
        #[arg(long, requires = "min_fmax")]
        device: Option<String>,
        #[arg(long, default_value = "target/gbump-fit", value_parser = output_dir)]
        work: PathBuf,
    },
    /// Every built-in scene under max<=2, psnr>=50 and exact<=1: the scene's default
    /// configuration against the one `gbump fit` chooses (area model, no regression).
    FitTable {
        /// Only these scenes (built-in name or file; repeatable; default every built-in scene).
        #[arg(long)]
        scene: Vec<String>,
        /// Also write the table (Markdown) to this file; it is printed either way.
        #[arg(long, value_name = "FILE", value_parser = output_file)]
        write: Option<PathBuf>,
    },
    /// Fit the area model to Yosys on the first configurations and check it on the rest.
    AreaModel {
        /// Configuration files (a folder: every .toml in it, in name order).
        #[arg(long, value_name = "DIR")]
        configs: PathBuf,
        /// How many of them (in order) to fit on; the rest are held out.
        #[arg(long, default_value_t = AREA_MODEL_CALIBRATE)]
        calibrate: usize,
        /// Write every sample (config, Yosys GE, estimate) here, one JSON object a line.
        #[arg(long, value_name = "FILE", value_parser = output_file)]
        write: Option<PathBuf>,
        #[arg(long, default_value = "target/gbump-areamodel", value_parser = output_dir)]
        work: PathBuf,
    },
    /// The survey's bump engines (paper §2-3, §6; Cg §8) in f64 on the same scenes, against the
    /// Blinn reference: PSNR, max/mean error, pixels > 1 LSB, seam error; engines.md, .csv, .png.
    Engines {
        /// Scenes (built-in names or .toml paths); every built-in scene when none is given.
        #[arg(long = "scene", value_name = "NAME")]
        scenes: Vec<String>,
        /// Engines to run (the Blinn reference is always run); every engine when none is given.
        #[arg(long = "engine", value_name = "NAME")]
        engines: Vec<String>,
        /// Image size WxH (default: each scene's own, halved).
        #[arg(long)]
        size: Option<String>,
        /// Texels along a side of EMBM's environment maps.
        #[arg(long, default_value_t = crate::engines::embm::EMBM_MAP)]
        embm_map: u32,
        /// Texels along a face edge of the Cg engine's f64 normalisation cube map (its
        /// bit-accurate path's cube is its configuration's cube_map_face).
        #[arg(long, default_value_t = crate::engines::cg::CUBE_FACE)]
        cg_cube: u32,
        /// What-if: the engines that light with the map's filtered normal directly (SGI, Cg)
        /// renormalise it first (neither text does; f64 only).
        #[arg(long)]
        renormalise_map: bool,
        #[arg(long, default_value = "out/engines", value_parser = output_dir)]
        out: PathBuf,
        /// Print every engine's name, whether it has a bit-accurate path (`gbump config
        /// --engine`), and its source, and stop.
        #[arg(long, conflicts_with_all = ["scenes", "engines", "size", "out", "embm_map", "cg_cube", "renormalise_map"])]
        list: bool,
    },
    /// One of the paper's claims about the engines, measured: NAME.md and NAME.svg (the
    /// sections of docs/REPORT.md). `--list` names them.
    Claim {
        /// visa-seams, flat-shading, embm-resolution or map-filter.
        #[arg(required_unless_present = "list")]
        name: Option<String>,
        /// Print the claims' names and what each measures, and stop.
        #[arg(long, conflicts_with_all = ["name", "out"])]
        list: bool,
        #[arg(long, default_value = "out/claims", value_parser = output_dir)]
        out: PathBuf,
    },
    /// Measure speed: model, vector dump, Icarus, Verilator harness and raw Verilated rate.
    Bench {
        #[command(flatten)]
        pick: ConfigPick,
        #[arg(long, default_value = "target/gbump-bench", value_parser = output_dir)]
        work: PathBuf,
    },
    /// Write docs/REPORT.md: area, error, the power unit's design space, a sweep and speed.
    Report {
        #[arg(long, default_value = "docs", value_name = "DIR", value_parser = output_dir)]
        out: PathBuf,
        #[arg(long, default_value = DEFAULT_REPORT_SPACE, value_name = "FILE")]
        space: PathBuf,
        #[arg(long, default_value = "target/gbump-report", value_parser = output_dir)]
        work: PathBuf,
    },
    /// Lockstep co-simulation on Verilator: the generated top against the golden model through
    /// DPI-C (libgbump), random fragments from the model's own stream, no vector file.
    Cosim {
        #[command(flatten)]
        pick: ConfigPick,
        /// Check this RTL folder (`gbump rtl --out DIR`) instead of generating the configuration's.
        #[arg(long, value_name = "DIR")]
        rtl: Option<PathBuf>,
        /// Random fragments (record k is record k of `gbump vectors --source random:N --seed S`).
        #[arg(long, default_value_t = 10_000)]
        random: u64,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Idle in_valid for 1-3 cycles before every Nth fragment (0: never).
        #[arg(long, default_value_t = crate::sim::regress::BUBBLES)]
        bubbles: u32,
        #[arg(long, default_value_t = crate::sim::regress::MAX_ERRORS)]
        max_errors: u32,
        /// The gbump C library (default: libgbump.so beside this executable).
        #[arg(long, value_name = "FILE")]
        lib: Option<PathBuf>,
        /// Work folder: generated RTL and the cached Verilator build.
        #[arg(long, default_value = "target/gbump-cosim", value_parser = output_dir)]
        work: PathBuf,
    },
    /// Print the interface table (every unit's ports, formats and latency) as Markdown.
    Interface {
        #[command(flatten)]
        pick: ConfigPick,
    },
    /// Print the README's "Integrating the RTL" section (protocol, reset, table loading, lanes, vector layout) for a configuration.
    Integration {
        #[command(flatten)]
        pick: ConfigPick,
    },
    /// Print a pipeline configuration as TOML with its hash: the default, or a scene's, or an
    /// engine's bit-accurate path on a scene (what `gbump engines` renders, area-counts and
    /// what `gbump regress --config` then simulates).
    Config {
        #[arg(long)]
        scene: Option<String>,
        /// An engine with a bit-accurate path (`gbump engines --list` names them); needs --scene.
        #[arg(long, requires = "scene")]
        engine: Option<String>,
    },
    /// Print the bounds on every size and count (the README's Limits table) as Markdown.
    Limits,
    /// Print every unit's latency at each pipeline_depth and where its register cuts sit (the
    /// README's timing table) as Markdown; with --config or --scene, that configuration's
    /// units and top at each depth.
    Timing {
        #[command(flatten)]
        pick: ConfigPick,
    },
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum VecFormat {
    Hex,
    Bin,
    Both,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum SimChoice {
    Icarus,
    Verilator,
    Both,
}

impl SimChoice {
    pub fn sims(self) -> Vec<crate::sim::Sim> {
        use crate::sim::Sim;
        match self {
            SimChoice::Icarus => vec![Sim::Icarus],
            SimChoice::Verilator => vec![Sim::Verilator],
            SimChoice::Both => vec![Sim::Icarus, Sim::Verilator],
        }
    }
}

/// An output folder named on the command line, checked before any work: not a file, and
/// not under a file, so a long run does not end by failing to make it.
fn output_dir(s: &str) -> std::result::Result<PathBuf, String> {
    let p = PathBuf::from(s);
    if p.exists() && !p.is_dir() {
        return Err(format!("{s} is a file, not a folder (fix: give a folder path, or move the file)"));
    }
    under_folders(p)
}

/// An output file named on the command line, checked before any work: not a folder, and
/// under a folder (existing or to be made) rather than under a file, so a long run does not
/// end by failing to write its result.
fn output_file(s: &str) -> std::result::Result<PathBuf, String> {
    let p = PathBuf::from(s);
    if p.is_dir() {
        return Err(format!("{s} is a folder; give a file name (fix: e.g. {s}/result)"));
    }
    if s.ends_with(std::path::MAIN_SEPARATOR) {
        // A missing folder named as one: no file name to write.
        return Err(format!(
            "{s} ends in {0}, so it names a folder; give a file name (fix: e.g. {s}result)",
            std::path::MAIN_SEPARATOR
        ));
    }
    under_folders(p)
}

/// `p` when its nearest existing ancestor is a folder (what is missing is made on writing).
fn under_folders(p: PathBuf) -> std::result::Result<PathBuf, String> {
    nearest_folder(&p)?;
    Ok(p)
}

/// The folder `p`'s files go in: `p` itself when it is a folder, else its nearest existing
/// ancestor; an error when a file stands in the way.
fn nearest_folder(p: &Path) -> std::result::Result<PathBuf, String> {
    let mut up = if p.is_dir() { Some(p) } else { p.parent() };
    loop {
        match up {
            Some(a) if a.as_os_str().is_empty() => return Ok(PathBuf::from(".")),
            Some(a) if a.is_dir() => return Ok(a.to_path_buf()),
            Some(a) if a.exists() => {
                return Err(format!(
                    "{} is a file, not a folder (fix: give a path through folders)",
                    a.display()
                ))
            }
            Some(a) => up = a.parent(),
            None => return Ok(PathBuf::from("/")),
        }
    }
}

/// The sweep space `gbump report` measures by default: the checkout's own.
const DEFAULT_REPORT_SPACE: &str = "sweeps/small.toml";

/// Configurations `gbump area-model` fits on by default (`--calibrate`).
pub const AREA_MODEL_CALIBRATE: usize = 14;

/// The options that name where a command writes.
const OUTPUT_OPTIONS: [&str; 5] = ["out", "work", "json", "junit", "write"];

/// Every output option given on the command line (not a default: a command that never writes
/// there must not fail for it) is tried with a file made and removed in the folder it writes
/// in, so a folder of /proc, a read-only mount or a folder without write permission fails now,
/// not after a search or a synthesis.
fn probe_outputs(m: &clap::ArgMatches) -> Result<()> {
    let Some((_, sub)) = m.subcommand() else {
        return Ok(());
    };
    for id in OUTPUT_OPTIONS {
        // Only the command's own options (asking about another is a programming error to clap).
        if !sub.ids().any(|i| i.as_str() == id) || sub.value_source(id) != Some(clap::parser::ValueSource::CommandLine) {
            continue;
        }
        let Ok(Some(p)) = sub.try_get_one::<PathBuf>(id) else {
            continue;
        };
        // A device or pipe named as the output (/dev/stdout) is written in place, not beside.
        if std::fs::metadata(p).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
            continue;
        }
        let folder = nearest_folder(p).map_err(|e| Error::Other(format!("--{id} {}: {e}", p.display())))?;
        let probe = folder.join(format!(".gbump-write-check{}", std::process::id()));
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&probe) {
            Ok(_) => {
                let _ = std::fs::remove_file(&probe);
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => {
                return Err(Error::Other(format!(
                    "--{id} {}: cannot write in {}: {e}\n  fix: give a path under a folder you can write to",
                    p.display(),
                    folder.display()
                )))
            }
        }
    }
    Ok(())
}

/// The scene's reasons (`# FIELD = VALUE: why`) under an engine's path: a field the engine
/// sets otherwise says so and keeps the scene's value beside it, so no comment contradicts the
/// TOML below it; under a squaring power unit the shininess has no table.
fn engine_why(why: &str, scene: &PipelineConfig, fixed: &PipelineConfig) -> String {
    let (st, ft) = (scene.to_toml(), fixed.to_toml());
    why.lines()
        .map(|l| {
            let field = l
                .strip_prefix("# ")
                .and_then(|r| r.split_once(" = "))
                .map(|(f, _)| f)
                .filter(|f| f.chars().all(|c| c.is_ascii_lowercase() || c == '_'));
            let values = field.map(|f| (scene.field_text(&st, f), fixed.field_text(&ft, f)));
            match (field, values) {
                (Some(f), Some((was, now))) if was != now => {
                    format!("# {f} = {now}: set by the engine's path (the scene alone: {f} = {was})\n")
                }
                (Some("shininess"), _) if fixed.power_unit == crate::config::PowerUnitKind::Squaring => format!(
                    "# shininess = {0}: the scene's; the engine's squaring power unit computes x^{0} by successive squarings (no table)\n",
                    fixed.shininess
                ),
                (Some("shininess"), _) if fixed.embm() => format!(
                    "# shininess = {0}: the scene's; EMBM has no power table: the specular environment map holds x^{0}, built when the map is\n",
                    fixed.shininess
                ),
                (Some("k_frac_bits"), _) if fixed.embm() => format!(
                    "# k_frac_bits = {}: no k under EMBM (its four light slots are the bilinear filter's texels; the maps hold the lights)\n",
                    fixed.k_frac_bits
                ),
                _ => unheld_advice(l, fixed),
            }
        })
        .collect()
}

/// Engine `name`'s bit-accurate configuration on `scene` (`gbump config --engine`, `gbump rom
/// --engine`).
fn engine_config(scene: &Scene, name: &str) -> Result<PipelineConfig> {
    let e = crate::engines::fixed_engine(name)?;
    let fixed = e.fixed_config(scene)?.expect("fixed_engine has a bit-accurate path");
    fixed.validate(&format!("{} (engine {name})", scene.file))?;
    Ok(fixed)
}

/// A line of a scene's needs as it holds for an engine's configuration: advice to set a field
/// (`palette = true holds them exactly`, `power_rom = true makes it a ROM`) that the engine's
/// configuration refuses gives the refusal's reason instead, so no line suggests a
/// configuration `gbump` then refuses.
fn unheld_advice(line: &str, fixed: &PipelineConfig) -> String {
    let advice: [(&str, fn(&mut PipelineConfig)); 3] = [
        ("palette = true", |c| c.palette = true),
        ("power_rom = true", |c| c.power_rom = true),
        ("renormalise_bump = true", |c| c.renormalise_bump = true),
    ];
    for (words, set) in advice {
        let Some(at) = line.find(words) else { continue };
        let mut c = fixed.clone();
        set(&mut c);
        if let Err(e) = c.validate("the engine's configuration") {
            let why = match &e {
                Error::Field { msg, .. } => msg.clone(),
                e => e.to_string().lines().next().unwrap_or_default().to_string(),
            };
            // The advice is the clause from `words` to its end; the line's facts before it stay.
            let (keep, _) = line.split_at(at);
            let keep = keep.trim_end_matches(['(', ' ', ';']);
            return format!("{keep} ({words} is refused here: {why})\n");
        }
    }
    format!("{line}\n")
}

/// Refuse an output file that is one of the inputs this run has read (checked as soon as the
/// inputs are, before any work; `write_atomic` checks again when it writes).
fn not_inputs(outputs: &[Option<&Path>]) -> Result<()> {
    outputs.iter().flatten().try_for_each(|o| crate::limits::check_not_input(o))
}

/// Refuse a repeatable option naming one value twice (the run would do its work twice).
fn named_once(flag: &str, values: &[String]) -> Result<()> {
    match values.iter().enumerate().find(|(i, v)| values[..*i].contains(v)) {
        Some((_, v)) => Err(Error::Other(format!("{flag} {v} is given more than once\n  fix: name each once"))),
        None => Ok(()),
    }
}

/// The iCE40 device `area` places and routes on: refused for a target that is not placed and
/// routed, the default when none is named.
fn device_for(target: crate::measure::fpga::Target, device: Option<String>) -> Result<String> {
    if device.is_some() && target != crate::measure::fpga::Target::Ice40 {
        let name = clap::ValueEnum::to_possible_value(&target).map_or(String::new(), |v| v.get_name().to_string());
        return Err(Error::Other(format!(
            "--device has no effect on --target {name}: only ice40 is placed and routed on a device\n  fix: drop --device, or use --target ice40"
        )));
    }
    Ok(device.unwrap_or_else(|| crate::measure::fpga::DEFAULT_DEVICE.into()))
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
        crate::scene::pick_config(self.config.as_deref(), self.scene.as_deref())
    }

    /// The arguments that select this configuration, for regeneration commands in headers.
    pub fn args(&self) -> String {
        match (&self.config, &self.scene) {
            (Some(p), _) => format!("--config {}", quoted(&recorded_path(&p.display().to_string()))),
            (None, Some(s)) => format!("--scene {}", quoted(&recorded_path(s))),
            (None, None) => String::new(),
        }
    }
}

/// Take the work folder for this run, once every input has been checked: one run per folder,
/// in a folder every simulator and make can take.
fn lock_work(work: &Path) -> Result<crate::work_lock::WorkLock> {
    crate::sim::check_tool_path(work, "--work")?;
    crate::work_lock::WorkLock::acquire(work, &invocation())
}

/// Where a library command's lines go: standard output, an error (not a panic) when it is
/// closed or full.
fn say(line: &str) -> Result<()> {
    outln!("{line}");
    Ok(())
}

/// Refuse an empty argument (`--out ""`, `--out=`): every value gbump takes names something,
/// and an empty path would quietly mean the working folder.
fn refuse_empty_arguments() -> Result<()> {
    let args: Vec<std::ffi::OsString> = std::env::args_os().skip(1).collect();
    for (i, a) in args.iter().enumerate() {
        let a = a.to_string_lossy();
        let flag = if a.is_empty() {
            Some(
                i.checked_sub(1)
                    .map_or("an argument".into(), |j| args[j].to_string_lossy().into_owned()),
            )
        } else if a.starts_with("--") && a.ends_with('=') {
            Some(a.trim_end_matches('=').to_string())
        } else {
            None
        };
        if let Some(flag) = flag {
            return Err(Error::Other(format!(
                "{flag}: an empty value\n  fix: give {flag} a value (`gbump --help` lists what each command takes)"
            )));
        }
    }
    Ok(())
}

/// Refuse an argument that is not UTF-8, naming its option (or its place): clap says only
/// "invalid UTF-8 was detected in one or more arguments".
fn refuse_non_utf8_arguments() -> Result<()> {
    let Some(i) = std::env::args_os().skip(1).position(|a| a.to_str().is_none()) else {
        return Ok(());
    };
    let args = lossy_arguments();
    Err(Error::Other(format!(
        "{} {:?}: not UTF-8 (\u{fffd} marks each byte that is not), and gbump reads every path and value as UTF-8\n  fix: rename the file or folder to a UTF-8 name",
        option_of(&args, i),
        args[i]
    )))
}

/// The command line after the program's name, each argument as text (`\u{fffd}` for a byte
/// that is not UTF-8).
fn lossy_arguments() -> Vec<String> {
    std::env::args_os().skip(1).map(|a| a.to_string_lossy().into_owned()).collect()
}

/// How a message names argument `i`: the option before it, whose value it is, or its place.
fn option_of(args: &[String], i: usize) -> String {
    match i.checked_sub(1).map(|j| &args[j]) {
        Some(f) if f.starts_with('-') => f.clone(),
        _ => format!("argument {}", i + 1),
    }
}

/// Refuse an argument holding a control character (a newline, a tab, a bell: pasted or
/// typed by mistake), naming its option and showing it escaped: no path or value of gbump
/// takes one, and passed on it would break the message that quotes it or end up raw in
/// every file that records the command line. Run after clap's parse, so that an unknown
/// subcommand or a refused value keeps clap's own message.
fn refuse_control_characters() -> Result<()> {
    let args = lossy_arguments();
    let Some(i) = args.iter().position(|a| a.chars().any(char::is_control)) else {
        return Ok(());
    };
    let (what, value) = match args[i].split_once('=') {
        Some((f, v)) if f.starts_with("--") => (f.to_string(), v),
        _ => (option_of(&args, i), args[i].as_str()),
    };
    Err(Error::Other(format!(
        "{what} {value:?}: holds a control character, which no gbump path or value takes\n  fix: give it again without the control character (shown escaped above)"
    )))
}

/// Refuse a negative number given to an option (`--random -5`, `--seed=-1`, and `-0`): no
/// option of gbump takes a sign, and the parser would otherwise call it an unknown argument
/// (or, after `=`, read `-0` as 0).
fn refuse_negative_numbers() -> Result<()> {
    let args = lossy_arguments();
    // A number, or a value that starts as one (`-16x12`, a size): clap would read it as an
    // unknown short option and say `unexpected argument '-1'`.
    let negative = |v: &str| {
        v.strip_prefix('-')
            .is_some_and(|r| r.parse::<f64>().is_ok_and(|x| !x.is_nan()) || r.starts_with(|c: char| c.is_ascii_digit()))
    };
    for (i, a) in args.iter().enumerate() {
        let (flag, value) = match a.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f, v),
            _ if a.starts_with("--") && i + 1 < args.len() => (a.as_str(), args[i + 1].as_str()),
            _ => continue,
        };
        if negative(value) {
            return Err(Error::Other(format!(
                "{flag} {value}: a negative number, which no gbump option takes\n  fix: give {flag} a value in its range (`gbump <command> --help` names each option's)"
            )));
        }
    }
    Ok(())
}

/// Clap's own answer (help, version, a usage error) and its exit code; a usage error quotes
/// the argument as given, so its control characters are shown escaped as gbump's own errors
/// show them (a carriage return could overwrite the message on a terminal).
fn clap_exit(e: clap::Error) -> ! {
    use clap::error::ErrorKind;
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        // Written and flushed here, so a failed write (a full disk, /dev/full) is an error,
        // not the silent success `exit` gives; a reader that closed the pipe ends it quietly.
        use std::io::Write;
        let written = e.print().and_then(|_| std::io::stdout().flush());
        match written {
            Ok(()) => std::process::exit(e.exit_code()),
            Err(w) if w.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(128 + 13),
            Err(w) => {
                eprintln!("gbump: error: standard output: {w}\n  fix: write the help where there is room (a file on a disk with space, or the terminal)");
                std::process::exit(1)
            }
        }
    }
    if let Some(msg) = value_refusal(&e) {
        eprintln!("gbump: error: {}", crate::error::shown(&msg));
        std::process::exit(1);
    }
    eprint!("{}", crate::error::shown(&e.render().to_string()));
    std::process::exit(e.exit_code())
}

/// A value the parser took and gbump's own check refused (a number out of its range, an
/// output folder that is a file) as gbump words every error, with the exit status 1 the README
/// gives a value out of range; None for what is clap's to refuse (a number that is not one,
/// an unknown option), which keeps clap's message and status 2.
fn value_refusal(e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if e.kind() != ErrorKind::ValueValidation {
        return None;
    }
    let src = std::error::Error::source(e)?;
    if src.is::<std::num::ParseIntError>() || src.is::<std::num::ParseFloatError>() {
        return None;
    }
    let text = |k| match e.get(k) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    // clap names the option with its value's placeholder (`--level <LEVEL>`).
    let arg = text(ContextKind::InvalidArg)?;
    let flag = arg.split(' ').next().unwrap_or(&arg).to_string();
    let value = text(ContextKind::InvalidValue).unwrap_or_default();
    let why = src.to_string();
    let (what, fix) = match why.split_once(" (fix: ") {
        Some((w, f)) => (w.to_string(), f.strip_suffix(')').unwrap_or(f).to_string()),
        None => match why.split_once(" is not in ") {
            Some((_, range)) => (why.clone(), format!("use {range}")),
            None => (why.clone(), format!("give a value {flag} takes (its line in the command's --help)")),
        },
    };
    Some(format!("{flag} {value}: {what}\n  fix: {fix}"))
}

pub fn run() -> anyhow::Result<()> {
    crate::limits::record_inputs();
    refuse_empty_arguments()?;
    refuse_non_utf8_arguments()?;
    refuse_negative_numbers()?;
    let matches = <Cli as clap::CommandFactory>::command()
        .try_get_matches()
        .unwrap_or_else(|e| clap_exit(e));
    refuse_control_characters()?;
    probe_outputs(&matches)?;
    record_given(&matches);
    let cli = match <Cli as clap::FromArgMatches>::from_arg_matches(&matches) {
        Ok(c) => c,
        Err(e) => clap_exit(e),
    };
    crate::tool::set_time_limit(cli.tool_timeout.as_deref())?;
    match cli.cmd {
        Cmd::Scenes { show } => scenes(show)?,
        Cmd::Render {
            scene,
            out,
            size,
            config,
            rtl,
            work,
        } => {
            let r = crate::render::report::RenderRequest {
                scene: &scene,
                out: &out,
                size: size.as_deref(),
                config: config.as_deref(),
                rtl: rtl.then_some(work.as_path()),
            };
            crate::render::report::render(&r, || lock_work(&work), &mut say)?
        }
        Cmd::Rtl { pick, out } => {
            crate::sim::check_out_path(&out)?;
            let cfg = pick.resolve()?;
            let cmd = format!("gbump rtl {} --out {}", pick.args(), quoted(&out.display().to_string())).replace("  ", " ");
            let files = crate::rtlgen::generate(&cfg, &cmd);
            crate::render::output::write_files(&out, &files)?;
            outln!(
                "wrote {} files for config {} to {} (top {}, latency {} cycles)",
                files.len(),
                cfg.hash(),
                out.display(),
                crate::rtlgen::units_v::module_name(&cfg, "gbump_pipeline"),
                crate::rtlgen::top::latency(&cfg)
            );
        }
        Cmd::Rom {
            pick,
            out,
            shininess,
            cube_size,
            engine,
        } => {
            let (cfg, args) = match (&engine, &pick.scene) {
                (Some(name), Some(scene)) => (
                    engine_config(&Scene::load(scene)?, name)?,
                    format!("{} --engine {}", pick.args(), quoted(name)),
                ),
                _ => (pick.resolve()?, pick.args()),
            };
            let files = crate::rtlgen::rom_files::rom_files(&cfg, pick.scene.as_deref(), &args, shininess, cube_size, &out)?;
            let stale = match &pick.scene {
                Some(s) => crate::rtlgen::rom_files::stale_scene_roms(&out, s, &cfg, &files),
                None => Vec::new(),
            };
            crate::render::output::write_files(&out, &files)?;
            for p in &stale {
                crate::commit::retire(p)?;
            }
            outln!("wrote {} ROM files to {}", files.len(), out.display());
            if let Some((_, why)) = (!crate::rtlgen::top::power_table_read(&cfg))
                .then(|| crate::rtlgen::top::unused_load_docs(&cfg))
                .flatten()
            {
                // Said, since every other configuration's set of files has one.
                outln!("no power table: the top reads none ({})", why.trim_start_matches("unused: "));
            }
            if !stale.is_empty() {
                outln!("removed {} ROM file(s) of objects the scene no longer has", stale.len());
            }
        }
        Cmd::Vectors {
            source,
            target,
            pick,
            out,
            seed,
            format,
            size,
            level,
            shininess,
        } => {
            crate::sim::check_out_path(&out)?;
            let r = crate::vectors_command::VectorsRequest {
                source: &source,
                targets: &target,
                config: pick.config.as_deref(),
                scene: pick.scene.as_deref(),
                out: &out,
                seed,
                text: !matches!(format, VecFormat::Bin),
                binary: !matches!(format, VecFormat::Hex),
                size: size.as_deref(),
                level,
                shininess,
                command: invocation(),
            };
            crate::vectors_command::vectors(&r, &mut say)?
        }
        Cmd::Regress {
            sim,
            pick,
            vectors,
            stream,
            random,
            random_icarus,
            seed,
            no_scenes,
            target,
            scene_size,
            work,
            junit,
            waves,
            max_errors,
        } => {
            use crate::limits::{check_count, MAX_RANDOM_VECTORS};
            check_count("--random", random, 0, MAX_RANDOM_VECTORS, "MAX_RANDOM_VECTORS")?;
            check_count("--random-icarus", random_icarus, 0, MAX_RANDOM_VECTORS, "MAX_RANDOM_VECTORS")?;
            crate::limits::check_max_errors(max_errors)?;
            if let (Some(sz), false) = (&scene_size, no_scenes) {
                let (w, h) = crate::limits::parse_size("--scene-size", sz)?;
                crate::measure::scene_error::check_builtin_renders(crate::limits::PixelUse::SceneVectors, w, h)?;
            }
            // A configuration derived from a scene file is regressed on that scene too.
            let own_scenes = crate::scene::builtin::files_among(pick.scene.iter());
            let opts = crate::sim::regress::RegressOptions {
                sims: sim.sims(),
                random_verilator: random,
                random_icarus,
                seed: seed.unwrap_or(1),
                scenes: !no_scenes,
                own_scenes,
                scene_size: scene_size
                    .as_deref()
                    .map(|s| crate::limits::parse_size("--scene-size", s))
                    .transpose()?,
                work: std::path::absolute(&work).map_err(|e| Error::io(&work, e))?,
                waves,
                max_errors,
                command: invocation(),
                bubbles: crate::sim::regress::BUBBLES,
                stall: crate::sim::regress::STALL,
                power_up: true,
                targets: target,
            };
            // Sets run alone carry their configuration: with no --config or --scene it is
            // the first manifest's (written to the work folder, so generated headers can
            // name it), and check_sets refuses any set of another. Nothing is written or
            // said until every given set has been checked whole (`regress`'s `announce`).
            let stream = stream.map(|s| crate::sim::stream::StreamSource::parse(&s)).transpose()?;
            // What a stream does not use is refused, not passed over.
            if let Some(src) = &stream {
                let random = matches!(src, crate::sim::stream::StreamSource::Random(_));
                if let (Some(n), false) = (seed, random) {
                    return Err(Error::Other(format!(
                        "--seed {n}: no effect on this run: a --stream of corners or of a scene draws nothing at random\n  fix: drop --seed, or stream random:N"
                    ))
                    .into());
                }
                if waves {
                    return Err(Error::Other(
                        "--waves: the streamed harness writes no waveforms\n  fix: drop --waves, or write the records with `gbump vectors` and run them with --vectors DIR --waves".into(),
                    )
                    .into());
                }
            }
            // A simulator's random count, and the seed, where this run does not use them:
            // refused, not passed over.
            if stream.is_none() {
                let sims = sim.sims();
                let (verilator, icarus) = (sims.contains(&crate::sim::Sim::Verilator), sims.contains(&crate::sim::Sim::Icarus));
                for (id, flag, n, runs, other) in [
                    ("random", "--random", random, verilator, "--random-icarus is Icarus's"),
                    ("random_icarus", "--random-icarus", random_icarus, icarus, "--random is Verilator's"),
                ] {
                    // A count of 0 asks for nothing, so it contradicts nothing.
                    if given(id) && n > 0 && !runs {
                        return Err(Error::Other(format!(
                            "{flag} {n}: no effect on this run: it counts the random vectors of the simulator --sim leaves out\n  fix: drop {flag} ({other}), or add that simulator with --sim"
                        ))
                        .into());
                    }
                }
                let random_runs = (verilator && random > 0) || (icarus && random_icarus > 0);
                if let (Some(n), false) = (seed, random_runs) {
                    return Err(Error::Other(format!(
                        "--seed {n}: no effect on this run: no simulator it runs has random vectors (their counts are 0)\n  fix: drop --seed, or give --random / --random-icarus a count above 0"
                    ))
                    .into());
                }
            }
            // --scene-size sizes scene fragments: refused where this run makes none, rather
            // than passed over.
            if let Some(sz) = &scene_size {
                let scene_stream = matches!(stream, Some(crate::sim::stream::StreamSource::Scene(_)));
                let top_sets = opts.targets.iter().any(|t| t == "all" || t == "top");
                let why = if stream.is_some() && !scene_stream {
                    Some("a --stream of random or corner records has no scene fragments")
                } else if stream.is_none() && no_scenes && opts.own_scenes.is_empty() {
                    Some("--no-scenes leaves the scenes out")
                } else if stream.is_none() && !top_sets {
                    Some("--target leaves out the top, whose sets the scenes are")
                } else {
                    None
                };
                if let Some(why) = why {
                    return Err(Error::Other(format!(
                        "--scene-size {sz}: no effect on this run: {why}\n  fix: drop --scene-size, or run scene fragments (the default suite, or --stream scene:NAME)"
                    ))
                    .into());
                }
            }
            let mut from_manifest = None;
            let (cfg, pick) = match (&pick.config, &pick.scene, vectors.is_empty(), &stream) {
                // A scene streams under the scene's own configuration unless one is given, as
                // `gbump vectors --source scene:NAME` writes it, and says so.
                (None, None, _, Some(crate::sim::stream::StreamSource::Scene(name))) => {
                    let own = ConfigPick {
                        config: None,
                        scene: Some(name.clone()),
                    };
                    let c = own.resolve()?;
                    crate::vectors_command::own_config_note(&format!("--stream scene:{name}"), name, &c);
                    (c, own)
                }
                (None, None, false, _) => {
                    let first = crate::sim::regress_cmd::given_manifests(&vectors)?.remove(0);
                    let m = crate::vectors::manifest::read_fields(&first)?;
                    let dir = std::path::absolute(&work).map_err(|e| Error::io(&work, e))?;
                    let file = dir.join(format!("config_{}.toml", m.config.hash()));
                    from_manifest = Some((file.clone(), first));
                    (
                        m.config,
                        ConfigPick {
                            config: Some(file),
                            scene: None,
                        },
                    )
                }
                _ => (pick.resolve()?, pick),
            };
            // A target the configuration lacks is refused before the work folder is touched.
            crate::vectors::targets::resolve(&cfg, &opts.targets)?;
            if let (Some(sz), true, None) = (&scene_size, cfg.palette, &stream) {
                // The suite makes no scene sets for a palette configuration (`scene_sets_made`).
                return Err(Error::Other(format!(
                    "--scene-size {sz}: no effect on this run: a palette configuration ({}) makes no scene vector sets\n  fix: drop --scene-size, or regress a configuration with palette = false",
                    cfg.hash()
                ))
                .into());
            }
            not_inputs(&[junit.as_deref()])?;
            if let Some(src) = stream {
                if matches!(sim, SimChoice::Icarus) {
                    return Err(Error::Other(
                        "--stream runs on Verilator (its C++ harness reads the pipe)\n  fix: drop --sim icarus, or write the vectors with `gbump vectors` and run them with --vectors".into(),
                    )
                    .into());
                }
                crate::sim::stream::regress_stream(
                    &cfg,
                    &pick.args(),
                    &src,
                    &opts,
                    junit.as_deref(),
                    || lock_work(&opts.work),
                    &mut say,
                )?;
                return Ok(());
            }
            let announce = |say: &mut dyn FnMut(&str) -> Result<()>| -> Result<()> {
                if let Some((file, first)) = &from_manifest {
                    crate::render::output::make_folder(&opts.work)?;
                    crate::render::output::write_atomic(file, cfg.to_toml().as_bytes())?;
                    say(&format!("configuration {} from {}", cfg.hash(), first.display()))?;
                }
                Ok(())
            };
            crate::sim::regress_cmd::regress(
                &cfg,
                &pick.args(),
                &vectors,
                &opts,
                junit.as_deref(),
                || lock_work(&opts.work),
                announce,
                &mut say,
            )?
        }
        Cmd::Lint { pick, work } => {
            let cfg = pick.resolve()?;
            crate::sim::lint::require_tools()?;
            let _lock = lock_work(&work)?;
            crate::sim::lint::lint(&cfg, &work, &pick.args(), &mut say)?
        }
        Cmd::Fuzz {
            minutes,
            configs,
            seed,
            random,
            work,
        } => crate::sim::fuzz::run_for(minutes, configs, seed, random, &work, || lock_work(&work), &mut say)?,
        Cmd::Area {
            pick,
            work,
            json,
            target,
            device,
        } if target != crate::measure::fpga::Target::Cmos => {
            let device = device_for(target, device)?;
            let cfg = pick.resolve()?;
            not_inputs(&[json.as_deref()])?;
            crate::measure::fpga::ice40_package(&device)?;
            crate::measure::fpga::require(target)?;
            let _lock = lock_work(&work)?;
            let r = crate::measure::fpga::fpga_area(&cfg, target, &device, true, &work, &format!("gbump rtl {}", pick.args()))?;
            if let Some(j) = json {
                write_atomic(&j, serde_json::to_string_pretty(&r).expect("json").as_bytes())?;
            }
            out!("{}", crate::measure::fpga::markdown(&r));
        }
        Cmd::Area {
            pick,
            work,
            json,
            target,
            device,
        } => {
            device_for(target, device)?;
            let cfg = pick.resolve()?;
            not_inputs(&[json.as_deref()])?;
            let _lock = lock_work(&work)?;
            let r = crate::measure::area::area(&cfg, &work, &format!("gbump rtl {}", pick.args()))?;
            if let Some(j) = json {
                write_atomic(&j, serde_json::to_string_pretty(&r).expect("json").as_bytes())?;
            }
            out!("{}", crate::measure::area::markdown(&r));
        }
        Cmd::Error {
            pick,
            random,
            seed,
            size,
            json,
        } => {
            let cfg = pick.resolve()?;
            not_inputs(&[json.as_deref()])?;
            let (w, h) = crate::limits::parse_size("--size", &size)?;
            crate::limits::check_count("--random", random, 1, crate::limits::MAX_ERROR_STIMULI, "MAX_ERROR_STIMULI")?;
            crate::measure::scene_error::check_builtin_renders(crate::limits::PixelUse::Error, w, h)?;
            // Everything is measured and written before anything is printed: a run that fails
            // prints no report. A built-in scene that covers no pixel at this size is the
            // size's fault, not the scene file's.
            let stats = crate::measure::unit_error::unit_errors(&cfg, random, seed);
            // The scene that gave the configuration is measured too, first: a file of one's
            // own is the scene one asked about. Its faults are its own, not the size's.
            let own = match pick.scene.as_deref().filter(|_| pick.config.is_none()) {
                Some(s) if crate::scene::builtin::get(s).is_none() => {
                    Some(crate::measure::scene_error::scene_error(&Scene::load(s)?, &cfg, w, h)?)
                }
                _ => None,
            };
            let (scenes, left_out) = crate::measure::scene_error::scene_errors(&cfg, w, h).map_err(|e| match e {
                Error::NoPixelAtSize { .. } => Error::Other(format!(
                    "--size {w}x{h}: {}\n  fix: give a larger --size (the default is {})",
                    e.to_string().lines().next().unwrap_or_default(),
                    crate::measure::scene_error::IMAGE_SIZE_ARG
                )),
                Error::Field { ref field, .. } if field == "objects" => {
                    let first = e.to_string().lines().next().unwrap_or_default().to_string();
                    Error::Other(format!(
                        "--size {w}x{h}: {first}\n  fix: give a larger --size (the default is {})",
                        crate::measure::scene_error::IMAGE_SIZE_ARG
                    ))
                }
                other => other,
            })?;
            let scenes: Vec<_> = own.into_iter().chain(scenes).collect();
            if let Some(j) = json {
                let v = serde_json::json!({"config_hash": cfg.hash(), "config": cfg, "units": stats,
                    "scenes": scenes.iter().map(|(n, g, r)| serde_json::json!({"scene": n, "vs_gouraud_f64": g, "vs_reference": r})).collect::<Vec<_>>(),
                    "left_out": left_out.iter().map(|(n, why)| serde_json::json!({"scene": n, "why": why})).collect::<Vec<_>>()});
                write_atomic(&j, serde_json::to_string_pretty(&v).expect("json").as_bytes())?;
            }
            out!("{}", crate::measure::unit_error::markdown(&cfg, &stats));
            out!(
                "\nImage error per scene at {w}x{h} (covered pixels; LSBs of colour{})\n\n{}",
                if cfg.embm() {
                    "; the f64 columns are EMBM's own equations, `reference::embm_f64`, with each object's maps"
                } else {
                    ""
                },
                crate::measure::scene_error::scene_error_table(&scenes)
            );
            if !left_out.is_empty() {
                out!("\nLeft out, needing more than this configuration holds:\n");
                for (name, why) in &left_out {
                    out!("- {name}: {why}\n");
                }
            }
        }
        Cmd::PowerSpace {
            pick,
            max_n,
            json,
            area,
            work,
        } => {
            let cfg = pick.resolve()?;
            not_inputs(&[json.as_deref()])?;
            if area {
                crate::yosys::require()?;
                crate::sim::check_tool_path(&work, "--work")?;
            }
            let fm = crate::model::power_unit::PowerFormats {
                f: cfg.dot_frac_bits,
                p: cfg.power_frac_bits,
            };
            let rs = crate::measure::power_space::evaluate(fm, &crate::measure::power_space::default_designs(), max_n);
            // Everything is measured, then written, then printed: a failing run leaves no file
            // and prints no report.
            let _lock = area.then(|| lock_work(&work)).transpose()?;
            let rows = area.then(|| crate::measure::power_space::area_rows(fm, &rs, &work)).transpose()?;
            if let Some(j) = &json {
                write_atomic(j, serde_json::to_string_pretty(&rs).expect("json").as_bytes())?;
            }
            out!("{}", crate::measure::power_space::markdown(fm, &rs, max_n));
            if let Some(rows) = rows {
                out!("\nYosys area of the datapath (ROM as a black box, contents for n = 16; `synth -flatten; dffunmap; abc -g cmos2; stat -tech cmos`, GE = transistors / 4)\n\n| design | max error | ROM bits | datapath GE |\n|---|---:|---:|---:|\n");
                out!("{rows}");
            }
        }
        Cmd::AreaModel {
            configs,
            calibrate,
            write,
            work,
        } => {
            let coefficients = crate::measure::area_model::REGRESSORS + 1;
            if calibrate < coefficients {
                return Err(Error::Other(format!(
                    "--calibrate {calibrate}: the model has {coefficients} coefficients, and fewer configurations than that cannot determine them\n  fix: --calibrate {coefficients} or more (the default is {})",
                    AREA_MODEL_CALIBRATE
                ))
                .into());
            }
            let files = crate::measure::area_model::configs_in(&configs)?;
            if files.len() <= calibrate {
                return Err(Error::Other(format!(
                    "{}: {} configuration(s), none left to check after --calibrate {calibrate}\n  fix: add configurations or lower --calibrate",
                    configs.display(),
                    files.len()
                ))
                .into());
            }
            // Every configuration is read before the first synthesis, so a bad one fails now.
            for f in &files {
                PipelineConfig::load(f)?;
            }
            not_inputs(&[write.as_deref()])?;
            crate::yosys::require()?;
            let _lock = lock_work(&work)?;
            let (coef, samples) =
                crate::measure::area_model::calibrate_and_check(&files, calibrate, &work, &mut |m| eprintln!("area-model: {m}"))?;
            let cfgs: Vec<PipelineConfig> = samples.iter().map(|x| x.config.clone()).collect();
            let rate = crate::measure::area_model::scoring_rate(&cfgs);
            if let Some(w) = write {
                let lines: String = samples.iter().map(|x| serde_json::to_string(x).expect("json") + "\n").collect();
                write_atomic(&w, lines.as_bytes())?;
            }
            out!("{}", crate::measure::area_model::markdown(&coef, &samples, rate));
            // At full precision, for `area_model::COEFFICIENTS`.
            eprintln!("area-model: coefficients {coef:?}");
        }
        Cmd::Fit {
            scene,
            budget,
            min_throughput,
            out,
            no_regress,
            yosys,
            min_fmax,
            device,
            work,
        } => {
            let budget = crate::fit::budget::Budget::parse(&budget)?;
            if !(0.0..=1.0).contains(&min_throughput) {
                return Err(Error::Other(format!(
                    "--min-throughput {min_throughput}: {}\n  fix: use a value in 0..=1 (1/n for a serial top of n lights)",
                    if min_throughput > 1.0 {
                        "a top takes at most one fragment per clock"
                    } else {
                        "not a number of fragments per clock (0 or more)"
                    }
                ))
                .into());
            }
            // Every input and tool is checked before the work folder is taken.
            let device = device.unwrap_or_else(|| crate::measure::fpga::DEFAULT_DEVICE.into());
            named_once("--scene", &scene)?;
            for s in &scene {
                Scene::load(s)?;
            }
            if !no_regress {
                // The fit regresses its choice on both simulators: missing ones are said now,
                // not after the search.
                crate::sim::require(crate::sim::Sim::Icarus)?;
                crate::sim::require(crate::sim::Sim::Verilator)?;
                crate::fit::run::check_regressable(&scene)?;
            }
            if yosys {
                crate::yosys::require()?;
            }
            if let Some(f) = min_fmax {
                if !f.is_finite() || f <= 0.0 {
                    return Err(Error::Other(format!("--min-fmax {f}: not a clock\n  fix: a frequency in MHz above 0, e.g. 40")).into());
                }
                crate::measure::fpga::ice40_package(&device)?;
                crate::measure::fpga::require(crate::measure::fpga::Target::Ice40)?;
            }
            let _lock = lock_work(&work)?;
            // The search sizes with the analytical model; Yosys confirms on request.
            let area = |c: &PipelineConfig| Ok(crate::measure::area_model::estimate(c));
            let mut fit = crate::fit::run::fit(&scene, budget, min_throughput, &area)?;
            let fmax = match min_fmax {
                Some(f) => Some(crate::fit::run::deepen_for_fmax(
                    &mut fit.chosen,
                    f,
                    &device,
                    &work.join("fpga"),
                    &mut |m| eprintln!("fit: {m}"),
                )?),
                None => None,
            };
            let c = &fit.chosen;
            outln!(
                "fit {budget} on {}: {} configurations measured in {:.1} s; chosen {} ({:.0} GE by the area model, {} fragment(s) per clock): {}",
                scene.join(", "),
                fit.evaluations,
                fit.seconds,
                &c.cfg.hash()[..8],
                c.area_ge,
                c.throughput,
                c.measured.describe()
            );
            if let Some(f) = fmax {
                outln!("iCE40 {device}: {f:.1} MHz at pipeline_depth {} (nextpnr)", c.cfg.pipeline_depth);
            }
            outln!("{}", c.cfg.to_toml());
            if yosys {
                let area_work = work.join("area");
                let mut front: Vec<&crate::fit::search::Candidate> = vec![c];
                front.extend(fit.front.iter().filter(|f| f.cfg != c.cfg));
                for f in front {
                    let ge = crate::measure::area::area(&f.cfg, &area_work, "gbump fit")?.top().gate_equivalents;
                    outln!(
                        "yosys: {} {:.0} GE, the model {:.0} GE ({:+.1} %){}",
                        &f.cfg.hash()[..8],
                        ge,
                        f.area_ge,
                        100.0 * (f.area_ge - ge) / ge,
                        if f.cfg == c.cfg { " (chosen)" } else { "" }
                    );
                }
            }
            if !no_regress {
                let opts = crate::fit::run::regress_options(&work.join("regress"), invocation(), &scene)?;
                let t0 = std::time::Instant::now();
                // The RTL's header and any replay name a file that exists: the choice as regressed,
                // kept in the work folder (fit.toml in --out is written only once it passes).
                let regressed = work.join("regress").join("fit.toml");
                write_atomic(&regressed, fit.toml().as_bytes())?;
                crate::sim::regress_cmd::regress(
                    &c.cfg,
                    &format!("--config {}", crate::shell::quoted(&regressed.display().to_string())),
                    &[],
                    &opts,
                    None,
                    || lock_work(&work.join("regress")),
                    |_| Ok(()),
                    &mut |l| {
                        outln!("{l}");
                        Ok(())
                    },
                )
                .map_err(|e| {
                    // Its results are written only for a configuration that passes: a fit.toml
                    // beside a failed run would read as a verified choice.
                    Error::Other(format!(
                        "the regression of the chosen configuration {} did not pass, so fit.toml, front.csv and front.svg were not written (the configuration is {}): {e}",
                        &c.cfg.hash()[..8],
                        regressed.display()
                    ))
                })?;
                outln!(
                    "the chosen configuration passes on Icarus and Verilator ({:.0} s)",
                    t0.elapsed().as_secs_f64()
                );
            }
            crate::render::output::write_files(
                &out,
                &[
                    ("fit.toml".to_string(), fit.toml()),
                    ("front.csv".to_string(), fit.csv()),
                    ("front.svg".to_string(), fit.svg()),
                ],
            )?;
            outln!(
                "front: {} of {} candidates; wrote fit.toml, front.csv, front.svg in {}",
                fit.front.len(),
                fit.seen.len(),
                out.display()
            );
        }
        Cmd::FitTable { scene, write } => {
            named_once("--scene", &scene)?;
            let rows = crate::fit::table::rows(&scene, &mut |m| eprintln!("fit-table: {m}"))?;
            let md = crate::fit::table::markdown(&rows);
            // Written before it is printed: a file that cannot be written fails the run.
            if let Some(f) = &write {
                write_atomic(f, md.as_bytes())?;
            }
            out!("{md}");
        }
        Cmd::Sweep { space, out, work, yosys } => {
            let name = space.file_stem().map_or("sweep".into(), |s| s.to_string_lossy().into_owned());
            crate::names::check(&space.display().to_string(), "file name", &name)?;
            let sp = crate::measure::sweep::Space::load(&space)?;
            // The results are named after the space: none may be the space itself.
            let results = ["csv", "json", "svg"].map(|ext| out.join(format!("{name}.{ext}")));
            not_inputs(&results.each_ref().map(|p| Some(p.as_path())))?;
            let _lock = lock_work(&work)?;
            let t0 = std::time::Instant::now();
            let pts = crate::measure::sweep::sweep(&sp, &space.display().to_string(), &work, true, yosys)?;
            let files = vec![
                (format!("{name}.csv"), crate::measure::sweep::csv(&pts)),
                (format!("{name}.json"), serde_json::to_string_pretty(&pts).expect("json")),
                (
                    format!("{name}.svg"),
                    crate::measure::sweep::svg(
                        &pts,
                        &format!(
                            "{name}: error against area ({} configurations, area by {})",
                            pts.len(),
                            if yosys { "Yosys" } else { "the area model" }
                        ),
                    ),
                ),
            ];
            crate::render::output::write_files(&out, &files)?;
            outln!(
                "{} configurations in {:.0} s (area by {}); Pareto front: {}",
                pts.len(),
                t0.elapsed().as_secs_f64(),
                if yosys { "Yosys" } else { "the area model; --yosys to synthesise" },
                pts.iter()
                    .filter(|p| p.pareto)
                    .map(|p| p.label.as_str())
                    .collect::<Vec<_>>()
                    .join("; ")
            );
            outln!(
                "wrote {} in {}",
                files.iter().map(|f| f.0.as_str()).collect::<Vec<_>>().join(", "),
                out.display()
            );
        }
        Cmd::Engines { list: true, .. } => {
            for e in crate::engines::ENGINES {
                let path = if e.fixed.is_some() { "bit-accurate path" } else { "f64 only" };
                outln!("{:16} {path:17} {}", e.name, e.source);
            }
        }
        Cmd::Engines {
            scenes,
            engines,
            size,
            embm_map,
            cg_cube,
            renormalise_map,
            out,
            list: false,
        } => engines_command(
            &scenes,
            &engines,
            size.as_deref(),
            crate::engines::Maps {
                embm_map,
                cg_cube,
                renormalise_map,
            },
            &out,
        )?,
        Cmd::Claim { name, list, out } => {
            if list {
                for (n, what) in crate::engines::claims::CLAIMS {
                    outln!("{n:18} {what}");
                }
            } else {
                let c = crate::engines::claims::claim(name.as_deref().expect("clap requires it"))?;
                crate::render::output::write_files(
                    &out,
                    &[
                        (format!("{}.md", c.name), c.markdown.as_bytes()),
                        (format!("{}.svg", c.name), c.svg.as_bytes()),
                    ],
                )?;
                out!("{}", c.markdown);
                outln!("wrote {0}.md and {0}.svg in {1}", c.name, out.display());
            }
        }
        Cmd::Bench { pick, work } => {
            let cfg = pick.resolve()?;
            let _lock = lock_work(&work)?;
            out!("{}", crate::measure::bench::bench(&cfg, &work)?)
        }
        Cmd::Report { out, space, work } => {
            if !space.exists() && space == Path::new(DEFAULT_REPORT_SPACE) {
                return Err(Error::Other(format!(
                    "--space {DEFAULT_REPORT_SPACE}: not found from {}; it is the default, the gbump checkout's own sweep space\n  fix: run gbump report from the checkout, or pass --space FILE (a sweep space, as `gbump sweep --space` takes)",
                    std::env::current_dir().map(|d| d.display().to_string()).unwrap_or_else(|_| "this folder".into())
                ))
                .into());
            }
            let files = crate::measure::report::report(&out, &work, &space, || lock_work(&work))?;
            crate::render::output::write_files(&out, &files)?;
            outln!(
                "wrote {} in {}",
                files.iter().map(|f| f.0.as_str()).collect::<Vec<_>>().join(", "),
                out.display()
            );
        }
        Cmd::Cosim {
            pick,
            rtl,
            random,
            seed,
            bubbles,
            max_errors,
            lib,
            work,
        } => cosim(&pick, rtl, random, seed, bubbles, max_errors, lib, &work)?,
        Cmd::Interface { pick } => out!("{}", crate::rtlgen::interface::interface_markdown(&pick.resolve()?)),
        Cmd::Integration { pick } => out!("{}", crate::rtlgen::integration_doc::markdown(&pick.resolve()?)),
        Cmd::Config { scene, engine } => match scene {
            Some(s) => {
                let scene = Scene::load(&s)?;
                let cfg = scene.derive_config()?;
                let why = crate::scene::needs::SceneNeeds::of(&scene).explain(&scene, &cfg)?;
                match engine {
                    None => out!("{why}# config hash {}\n{}", cfg.hash(), cfg.to_toml()),
                    Some(name) => {
                        let fixed = engine_config(&scene, &name)?;
                        let why = engine_why(&why, &cfg, &fixed);
                        out!(
                            "{why}# engine {name}'s bit-accurate path on this scene: {}\n# config hash {}\n{}",
                            crate::engines::fixed_engine(&name)?.fixed.expect("a bit-accurate path"),
                            fixed.hash(),
                            fixed.to_toml()
                        );
                    }
                }
            }
            None => {
                let cfg = PipelineConfig::default();
                out!(
                    "# config hash {}\n{}# interpolate = \"none\"  (\"h\" or \"hl\": the rasteriser interpolates H, or H and L, per fragment, paper §6; needs bump_state = \"fragment\"; written only when set, so older hashes stay)\n# colour_guard_bits = 0  (0..={}: fraction bits the colour keeps between the diffuse blend, the texture modulation and the specular blend, rounded once at the end by colour_round; written only when above 0, so older hashes stay)\n# white_lights = false  (true: every bump light is white, so the Lc multiplies go; tri_lc/in_lc stay on the interface, unused; written only when true, so older hashes stay)\n# power_rom = false  (true: the power table is a ROM holding x^shininess, its load port unused; written only when true, so older hashes stay)\n# renormalise = false  (true: a normalise unit scales each interpolated L and H back to unit length per fragment, a reciprocal-square-root table and Newton steps; needs interpolate and light_mode = \"parallel\"; written only when true, so older hashes stay)\n# interpolate_k = false  (true: the rasteriser interpolates each light's k, intensity times spot factor, from the vertices; needs bump_state = \"fragment\"; no RTL changes; written only when true, so older hashes stay)\n# renormalise_bump = false  (true: a normalise_b unit scales the fetched bump normal back to unit length before the dot products, undoing the texture filter's shortening; written only when true, so older hashes stay)\n# cube_map_face = 0  (4..={}, a power of two: with renormalise, a normalise_cube unit reads a normalisation cube map of that many texels a face edge, Cg §8.2, instead of computing 1/|v|; written only when set, so older hashes stay)\n# self_shadow = false  (true: geometric self-shadowing, Cg sec. 8.5.3: a light below the surface (L_z <= 0; with frame_transform, N.L <= 0 with the frame's normal) adds nothing and a bump facing away from a light gets no highlight from it; needs diffuse; written only when true, so older hashes stay)\n# frame_transform = false  (true: Harmony, paper sec. 3.5: the fetched bump normal is placed in a frame T, B, N that enters with every fragment on in_frame, a frame_transform unit, so L and H are given in the frame's space; needs bump_state = \"fragment\"; written only when true, so older hashes stay)\n# frame_build = false  (true: TexRam, paper sec. 3.1: in_frame carries the main direction m in its T lanes and the interpolated normal N_i in its N lanes, and a frame_build unit forms N = N_i/|N_i|, B = N x m/|N x m|, T = B x N per fragment; needs frame_transform; written only when true, so older hashes stay)\n# triangle_frame = false  (true: VISA+, paper sec. 3.2: the rasteriser sends the triangle's plane T and B with the interpolated normal N_i as the frame, a per-triangle alignment matrix; no RTL changes; needs frame_transform, not with frame_build; written only when true, so older hashes stay)\n# frame_quaternion = false  (true: VISA+ with quaternions, paper sec. 3.2 [5]: in_frame's lanes 0-3 carry an interpolated vertex quaternion (w, x, y, z) and lanes 6-8 the interpolated normal N_i, and a quat_frame unit forms T and B as its rotation's columns and N = N_i, all times |q|^2, per fragment; needs frame_transform, not with frame_build or triangle_frame; written only when true, so older hashes stay)\n# pixel_lh = false  (true: Blinn, paper sec. 2: L and H formed at the pixel: each light's L lanes carry its vector to the light unnormalised (exact when interpolated), the H lanes the viewer direction V, and H = normalise((normalise(L) + V)/2); needs frame_transform, interpolate = \"hl\" and renormalise; written only when true, so older hashes stay)\n# env_map_bits = 0  (2..={}: EMBM, paper sec. 3.3: two environment maps of 2^env_map_bits texels a side, read at the sphere-map coordinates in_st moved by the triangle's 2x2 matrix in_m times the bump normal, bilinearly filtered into the diffuse and the specular blend; needs lights = 4, light_mode = \"parallel\", bump_state = \"fragment\" and more: `gbump config --engine embm --scene S` prints a whole one; written only when set, so older hashes stay)\n",
                    cfg.hash(),
                    cfg.to_toml(),
                    crate::config::limit("colour_guard_bits").1,
                    crate::config::limit("cube_map_face").1,
                    crate::config::limit("env_map_bits").1
                );
            }
        },
        Cmd::Limits => out!("{}\n{}", crate::limits::markdown(), crate::config::limits_markdown()),
        Cmd::Timing { pick } => match (&pick.config, &pick.scene) {
            (None, None) => out!("{}", crate::units::timing::markdown()),
            _ => out!("{}", crate::units::timing::config_markdown(&pick.resolve()?)),
        },
    }
    Ok(())
}

fn engines_command(scenes: &[String], engines: &[String], size: Option<&str>, maps: crate::engines::Maps, out: &Path) -> Result<()> {
    use crate::engines::{engine, report, ENGINES};
    use crate::limits::{check_count, MAX_CUBE_SIDE, MAX_ENV_MAP_SIDE};
    check_count("--embm-map", maps.embm_map.into(), 2, MAX_ENV_MAP_SIDE.into(), "MAX_ENV_MAP_SIDE")?;
    check_count("--cg-cube", maps.cg_cube.into(), 1, MAX_CUBE_SIDE.into(), "MAX_CUBE_SIDE")?;
    named_once("--scene", scenes)?;
    named_once("--engine", engines)?;
    let picked: Vec<&'static crate::engines::Engine> = if engines.is_empty() {
        ENGINES.iter().collect()
    } else {
        engines
            .iter()
            .map(|n| {
                engine(n).ok_or_else(|| {
                    Error::Other(format!(
                        "--engine {n}: no such engine\n  fix: use one of {}",
                        ENGINES.iter().map(|e| e.name).collect::<Vec<_>>().join(", ")
                    ))
                })
            })
            .collect::<Result<_>>()?
    };
    let scenes: Vec<String> = if scenes.is_empty() {
        builtin::ALL.iter().map(|(n, _)| n.to_string()).collect()
    } else {
        scenes.to_vec()
    };
    let size = size.map(|s| crate::limits::parse_size("--size", s)).transpose()?;
    let t = report::measure(&scenes, &picked, size, maps)?;
    let (w, h, px) = t.contact_sheet();
    let md = t.markdown();
    let png = crate::render::output::encode_png(w, h, &px)?;
    crate::render::output::write_files(
        out,
        &[
            ("engines.md".to_string(), md.clone().into_bytes()),
            ("engines.csv".to_string(), t.csv().into_bytes()),
            ("engines.png".to_string(), png),
        ],
    )?;
    out!("{md}");
    outln!("wrote engines.md, engines.csv, engines.png in {}", out.display());
    Ok(())
}

fn scenes(show: Option<String>) -> Result<()> {
    match show {
        Some(name) => match builtin::get(&name) {
            Some(text) => out!("{text}"),
            None => {
                // A file is checked as `gbump render` checks it before it is shown: loaded, its
                // configuration derived, its maps read and its image rendered at its own size
                // (an object must cover a pixel), so what passes here renders.
                let s = Scene::load(&name)?;
                let cfg = s.derive_config()?;
                let (w, h) = (s.size[0], s.size[1]);
                crate::render::report::renderable(&s, crate::limits::PixelUse::Render, w, h)?;
                crate::render::render(&s, &cfg, w, h, false)?;
                out!("{}", crate::limits::read_text(Path::new(&name))?)
            }
        },
        None => {
            for (name, text) in builtin::ALL {
                let s = Scene::from_toml(name, text, Path::new("scenes"))?;
                outln!("{name:22} {}", s.description);
            }
        }
    }
    Ok(())
}

/// The command line as a user would type it (program name `gbump`, whatever the path), so
/// that generated files do not depend on where the binary lives.
/// The subcommand's options typed on the command line (not defaulted), by their field names.
static GIVEN: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();

fn record_given(matches: &clap::ArgMatches) {
    if let Some((_, sub)) = matches.subcommand() {
        let ids = sub
            .ids()
            .filter(|id| sub.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine))
            .map(|id| id.to_string())
            .collect();
        let _ = GIVEN.set(ids);
    }
}

/// Whether the option of field `id` was typed, rather than left at its default.
fn given(id: &str) -> bool {
    GIVEN.get().is_some_and(|g| g.iter().any(|x| x == id))
}

pub fn invocation() -> String {
    let args: Vec<String> = std::env::args().skip(1).collect();
    std::iter::once("gbump".to_string())
        .chain(recorded_args(&args).iter().map(|a| quoted(a)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Options whose value is an input file a recorded command must find again.
const INPUT_FILE_OPTIONS: [&str; 3] = ["--config", "--scene", "--space"];

/// `args` as a file or a manifest records them: an input file named by a relative path
/// (`--config`, `--scene`, `--space`, `--source scene:FILE`) by its absolute one, so that the
/// command repeats from any folder (a set's `command`, an RTL folder's `regenerate`); every
/// other word as typed.
pub fn recorded_args(args: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::with_capacity(args.len());
    for a in args {
        let after = out.last().map(String::as_str);
        let rewritten = if after.is_some_and(|f| INPUT_FILE_OPTIONS.contains(&f)) {
            recorded_path(a)
        } else if let Some((f, v)) = a.split_once('=').filter(|(f, _)| INPUT_FILE_OPTIONS.contains(f)) {
            format!("{f}={}", recorded_path(v))
        } else if let Some(file) = a.strip_prefix("scene:").filter(|_| after == Some("--source")) {
            format!("scene:{}", recorded_path(file))
        } else if let Some(file) = a.strip_prefix("--source=scene:") {
            format!("--source=scene:{}", recorded_path(file))
        } else {
            a.clone()
        };
        out.push(rewritten);
    }
    out
}

/// `p` by its absolute path when it names an existing file by a relative one (a built-in
/// scene's name, or anything else, stays as typed).
pub fn recorded_path(p: &str) -> String {
    let path = Path::new(p);
    if path.is_relative() && path.is_file() {
        if let Ok(abs) = std::path::absolute(path) {
            return abs.display().to_string();
        }
    }
    p.to_string()
}

pub use crate::shell::quoted;

#[allow(clippy::too_many_arguments)]
fn cosim(
    pick: &ConfigPick,
    rtl: Option<PathBuf>,
    random: u64,
    seed: u64,
    bubbles: u32,
    max_errors: u32,
    lib: Option<PathBuf>,
    work: &Path,
) -> Result<()> {
    let cfg = pick.resolve()?;
    crate::limits::check_count("--random", random, 1, crate::limits::MAX_RANDOM_VECTORS, "MAX_RANDOM_VECTORS")?;
    crate::limits::check_max_errors(max_errors)?;
    let o = crate::cosim::CosimOptions {
        work: std::path::absolute(work).map_err(|e| Error::io(work, e))?,
        rtl,
        lib,
        count: random,
        seed,
        bubbles,
        max_errors,
        command: format!("gbump rtl {}", pick.args()),
    };
    crate::cosim::check_inputs(&cfg, &o)?;
    let _lock = lock_work(work)?;
    let r = crate::cosim::cosim(&cfg, &o)?;
    // The flags that pick the configuration, for the replay hint.
    let a = if pick.args().is_empty() { String::new() } else { pick.args() + " " };
    for l in r
        .log
        .lines()
        .filter(|l| ["cosim:", "MISMATCH", "  ", "stopping"].iter().any(|p| l.starts_with(p)))
    {
        outln!("{l}");
    }
    outln!("{} passed, {} failed ({:.1} s)", r.passed, r.failed, r.seconds);
    if r.failed > 0 {
        let vectors = format!("gbump vectors --source random:{random} --seed {seed} --target top {a}--out DIR");
        // `gbump regress` simulates the RTL it generates: RTL given with --rtl replays through
        // that folder's own FuseSoC core, or the replay would test other RTL and pass.
        let replay = match &o.rtl {
            None => format!("{vectors}, then gbump regress --sim verilator {a}--vectors DIR"),
            Some(dir) => format!(
                "{vectors} --format hex, then fusesoc --cores-root {} run --target sim_verilator gbump:gbump:{} --vectors=DIR/random{random}_top.hex --count={random} --table=DIR/random{random}_top_power_table.hex (the --rtl folder's own core and testbench)",
                quoted(&dir.display().to_string()),
                crate::rtlgen::units_v::module_name(&cfg, "gbump_pipeline")
            ),
        };
        return Err(Error::Other(format!(
            "cosim: {} mismatches between the RTL and the model\n  fix: replay the seed as vectors: {replay}",
            r.failed,
        )));
    }
    Ok(())
}
