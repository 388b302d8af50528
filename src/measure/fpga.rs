//! FPGA resources beside the gate equivalents (`gbump area --target ice40|ecp5|xilinx`): each
//! unit and the top synthesised alone with Yosys `synth_ice40` / `synth_ecp5` /
//! `synth_xilinx`, its `stat -json` sorted into LUTs, flip-flops, carry cells, DSPs, block
//! RAMs and LUT RAM; for iCE40 the top, inside the register shell of
//! `rtlgen::fpga_shell`, placed and routed by `nextpnr-ice40` for Fmax and utilisation.
//! A design that does not fit the device is a result ("does not fit", with nextpnr's
//! utilisation), not an error. Every synthesis and every place-and-route is cached under a
//! key of its inputs, the script and the tool's version (`src/cache.rs`).

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::rtlgen::units_v::module_name;
use crate::tool::{run_cmd, tail};
use crate::yosys::stat::{self as yosys_stat, Stat};
/// The targets and their cell libraries belong to Yosys; `gbump area --target` names them.
pub use crate::yosys::target::{Class, Target};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::process::Command;

/// One module's resources on one target.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct FpgaUnit {
    pub unit: String,
    pub module: String,
    pub luts: u64,
    pub flip_flops: u64,
    pub carry: u64,
    pub dsp: u64,
    pub block_ram: u64,
    /// LUTs used as RAM or shift registers (ECP5 TRELLIS_DPR16X4, Xilinx RAM*/SRL*).
    pub lut_ram: u64,
    /// Bits of the module's memories (every copy), counted before synthesis maps them: the
    /// storage the block RAMs hold, apart from the logic.
    #[serde(default)]
    pub memory_bits: u64,
    /// Every cell type and its count, as Yosys named them.
    pub cells: std::collections::BTreeMap<String, u64>,
}

impl FpgaUnit {
    /// `s` is the mapped design's statistics, `memory_bits` what the elaborated one held.
    pub fn from_stat(target: Target, unit: &str, module: &str, s: &Stat, memory_bits: u64) -> FpgaUnit {
        let n = |c: Class| s.count(|cell| target.classify(cell) == c);
        FpgaUnit {
            unit: unit.to_string(),
            module: module.to_string(),
            luts: n(Class::Lut),
            flip_flops: n(Class::FlipFlop),
            carry: n(Class::Carry),
            dsp: n(Class::Dsp),
            block_ram: n(Class::BlockRam),
            lut_ram: n(Class::LutRam),
            memory_bits,
            cells: s.cells.clone(),
        }
    }
}

/// One row of nextpnr's "Device utilisation".
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Utilisation {
    pub resource: String,
    pub used: u64,
    pub available: u64,
    pub percent: f64,
}

/// What nextpnr made of the design.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct PlaceRoute {
    pub tool: String,
    pub device: String,
    pub package: String,
    pub target_mhz: f64,
    /// The module placed: the top inside its register shell.
    pub placed: String,
    /// Pins of the shell (the core's own ports, for comparison, in `core_pins`).
    pub pins: u32,
    pub core_pins: u32,
    pub fits: bool,
    /// Max frequency of the core's clock after routing.
    pub fmax_mhz: Option<f64>,
    pub utilisation: Vec<Utilisation>,
    /// nextpnr's error when it does not fit.
    pub reason: Option<String>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct FpgaReport {
    pub config_hash: String,
    pub target: Target,
    pub yosys_version: String,
    pub script: String,
    pub units: Vec<FpgaUnit>,
    pub place_route: Option<PlaceRoute>,
}

impl FpgaReport {
    /// The top's row.
    pub fn top(&self) -> &FpgaUnit {
        self.units
            .iter()
            .find(|u| u.unit.starts_with("gbump_pipeline"))
            .expect("FPGA reports hold the top")
    }
}

/// What nextpnr's log says: utilisation rows, the last (post-route) Fmax of each clock, and
/// its ERROR lines.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NextpnrLog {
    pub utilisation: Vec<Utilisation>,
    pub fmax_mhz: Vec<(String, f64)>,
    pub errors: Vec<String>,
}

pub fn parse_nextpnr(log: &str) -> NextpnrLog {
    let mut r = NextpnrLog::default();
    let mut in_util = false;
    for line in log.lines() {
        let body = line.trim_start_matches("Info:").trim();
        if line.contains("Device utilisation:") {
            in_util = true;
            r.utilisation.clear();
            continue;
        }
        if in_util {
            // "ICESTORM_LC:  6005/ 7680    78%"
            let row = body.split_once(':').and_then(|(name, rest)| {
                let (used, rest) = rest.split_once('/')?;
                let mut it = rest.split_whitespace();
                let available = it.next()?.parse().ok()?;
                let percent = it.next()?.trim_end_matches('%').parse().ok()?;
                Some(Utilisation {
                    resource: name.trim().to_string(),
                    used: used.trim().parse().ok()?,
                    available,
                    percent,
                })
            });
            match row {
                Some(u) => {
                    r.utilisation.push(u);
                    continue;
                }
                None => in_util = false,
            }
        }
        if let Some(rest) = body.split("Max frequency for clock").nth(1) {
            // " 'clk$SB_IO_IN_$glb_clk': 31.60 MHz (PASS at 12.00 MHz)"
            let parsed = rest.rsplit_once("':").and_then(|(clock, f)| {
                let mhz = f.split_whitespace().next()?.parse().ok()?;
                Some((clock.trim().trim_start_matches('\'').to_string(), mhz))
            });
            if let Some((clock, mhz)) = parsed {
                r.fmax_mhz.retain(|(c, _)| *c != clock);
                r.fmax_mhz.push((clock, mhz));
            }
        }
        if line.starts_with("ERROR:") {
            r.errors.push(line.trim().to_string());
        }
    }
    r
}

/// Whether a failed nextpnr run failed because the design does not fit the device.
pub fn does_not_fit(p: &NextpnrLog) -> bool {
    p.utilisation.iter().any(|u| u.used > u.available)
        || p.errors.iter().any(|e| {
            e.contains("Unable to find a placement location")
                || e.contains("no BELs remaining")
                || e.contains("Unable to place cell")
                || e.contains("failed to place")
        })
}

/// The iCE40 device placed and routed on when none is named.
pub const DEFAULT_DEVICE: &str = "hx8k";

/// iCE40 devices nextpnr-ice40 knows, with the package gbump uses for each (the one with the
/// most pins).
pub const ICE40_DEVICES: [(&str, &str); 6] = [
    ("hx1k", "tq144"),
    ("hx4k", "tq144"),
    ("hx8k", "ct256"),
    ("lp1k", "tq144"),
    ("lp8k", "cm225"),
    ("up5k", "sg48"),
];

/// Target frequency given to nextpnr (timing-driven placement; Fmax is reported either way).
pub const TARGET_MHZ: f64 = 50.0;
const SEED: u32 = 1;

pub fn ice40_package(device: &str) -> Result<&'static str> {
    ICE40_DEVICES.iter().find(|(d, _)| *d == device).map(|(_, p)| *p).ok_or_else(|| {
        Error::Other(format!(
            "--device {device}: not an iCE40 device gbump knows\n  fix: use one of {}",
            ICE40_DEVICES.iter().map(|d| d.0).collect::<Vec<_>>().join(", ")
        ))
    })
}

/// Refuse a missing tool before anything runs.
pub fn require(target: Target) -> Result<()> {
    crate::yosys::require()?;
    if target == Target::Ice40 {
        crate::tool::require("nextpnr-ice40")?;
    }
    Ok(())
}

/// Synthesise `module` (cached): its `stat -json`, its memory bits and, with `netlist`, its
/// JSON netlist path.
fn synth(target: Target, rtl: &crate::sim::rtl_files::Rtl, module: &str, work: &Path, netlist: bool) -> Result<(Stat, u64, PathBuf)> {
    let names: Vec<String> = rtl
        .sources
        .iter()
        .map(|p| p.file_name().expect("file").to_string_lossy().into_owned())
        .collect();
    let mut k = crate::cache::Key::new("fpga synth");
    k.add(crate::yosys::scripts::fpga(target, &names, module, Path::new("OUT"), netlist).as_bytes());
    for f in rtl.sources.iter().chain([&rtl.init_file]) {
        k.add_file(f)?;
    }
    k.add_tool("yosys");
    let dir = std::path::absolute(work.join("synth").join(format!("{module}_{}_{}", target.name(), k.finish())))
        .map_err(|e| Error::io(work, e))?;
    let outputs: &[&str] = if netlist {
        &["stat.json", "memory.json", "netlist.json"]
    } else {
        &["stat.json", "memory.json"]
    };
    let dir = crate::cache::build_dir(&dir, outputs, |tmp| {
        let script = crate::yosys::scripts::fpga(target, &names, module, tmp, netlist);
        let (ok, log) = crate::yosys::run(&script, &tmp.join("synth.ys"), &rtl.dir, &[])?;
        let parsed = |f: &str| std::fs::read_to_string(tmp.join(f)).ok().and_then(|t| yosys_stat::parse(&t));
        if !ok || parsed("stat.json").is_none() || parsed("memory.json").is_none() {
            return Err(Error::Other(format!(
                "yosys could not synthesise {module} for {}:\n{}\n{}",
                target.name(),
                crate::tool::log_tail("yosys", &log, 15),
                crate::tool::synthesis_fix(&log)
            )));
        }
        Ok(())
    })?;
    let text = std::fs::read_to_string(dir.join("stat.json")).map_err(|e| Error::io(&dir, e))?;
    let stat = yosys_stat::parse(&text).ok_or_else(|| Error::Other(format!("{}: not Yosys stat -json output", dir.display())))?;
    let mem = std::fs::read_to_string(dir.join("memory.json")).map_err(|e| Error::io(&dir, e))?;
    let mem = yosys_stat::parse(&mem).ok_or_else(|| Error::Other(format!("{}: not Yosys stat -json output", dir.display())))?;
    Ok((stat, mem.memory_bits, dir.join("netlist.json")))
}

/// Place and route a netlist on an iCE40 (cached): nextpnr's log and whether it succeeded.
fn place_route(netlist: &Path, device: &str, package: &str, work: &Path) -> Result<(bool, String)> {
    let mut k = crate::cache::Key::new("nextpnr-ice40");
    k.add_file(netlist)?
        .add(device.as_bytes())
        .add(package.as_bytes())
        .add(&TARGET_MHZ.to_le_bytes())
        .add(&SEED.to_le_bytes())
        .add_tool("nextpnr-ice40");
    let dir = std::path::absolute(work.join("pnr").join(format!("{device}_{}", k.finish()))).map_err(|e| Error::io(work, e))?;
    let dir = crate::cache::build_dir(&dir, &["pnr.log", "status"], |tmp| {
        let mut c = Command::new("nextpnr-ice40");
        c.arg(format!("--{device}"))
            .args(["--package", package, "--freq", &TARGET_MHZ.to_string(), "--seed", &SEED.to_string()])
            .arg("--timing-allow-fail")
            .arg("--json")
            .arg(netlist)
            .current_dir(tmp);
        let (ok, log, _) = run_cmd(&mut c, "nextpnr-ice40")?;
        if log.contains("nextpnr-ice40: killed by signal") {
            return Err(Error::Other(format!("nextpnr-ice40 was killed:\n{}", tail(&log, 10))));
        }
        std::fs::write(tmp.join("pnr.log"), &log).map_err(|e| Error::io(tmp, e))?;
        std::fs::write(tmp.join("status"), if ok { "ok\n" } else { "failed\n" }).map_err(|e| Error::io(tmp, e))
    })?;
    let log = std::fs::read_to_string(dir.join("pnr.log")).map_err(|e| Error::io(&dir, e))?;
    let status = std::fs::read_to_string(dir.join("status")).map_err(|e| Error::io(&dir, e))?;
    Ok((status.trim() == "ok", log))
}

/// Turn a nextpnr run into a result: fits with its Fmax, does not fit with its reason, or an
/// error for any other failure.
pub fn place_route_result(ok: bool, log: &str, device: &str, package: &str, placed: &str, pins: u32, core_pins: u32) -> Result<PlaceRoute> {
    let p = parse_nextpnr(log);
    let fmax = p.fmax_mhz.iter().map(|f| f.1).reduce(f64::min);
    let base = PlaceRoute {
        tool: crate::cache::tool_version("nextpnr-ice40"),
        device: device.to_string(),
        package: package.to_string(),
        target_mhz: TARGET_MHZ,
        placed: placed.to_string(),
        pins,
        core_pins,
        fits: ok,
        fmax_mhz: if ok { fmax } else { None },
        utilisation: p.utilisation.clone(),
        reason: None,
    };
    if ok {
        if base.fmax_mhz.is_none() || base.utilisation.is_empty() {
            return Err(Error::Other(format!(
                "nextpnr-ice40 routed {placed} but printed no Fmax or utilisation:\n{}",
                tail(log, 15)
            )));
        }
        return Ok(base);
    }
    if does_not_fit(&p) {
        let over: Vec<String> = p
            .utilisation
            .iter()
            .filter(|u| u.used > u.available)
            .map(|u| format!("{} {}/{} ({:.0} %)", u.resource, u.used, u.available, u.percent))
            .collect();
        let reason = if over.is_empty() {
            p.errors.first().cloned().unwrap_or_default()
        } else {
            format!("needs {}", over.join(", "))
        };
        return Ok(PlaceRoute {
            reason: Some(reason),
            ..base
        });
    }
    Err(Error::Other(format!(
        "nextpnr-ice40 failed on {placed} ({device}, {package}):\n{}",
        tail(log, 15)
    )))
}

/// One unit of `cfg` synthesised alone for `target` (cached; no place and route): how its
/// memory maps (block RAM, LUT RAM or flip-flops) without the cost of the whole top.
pub fn unit_resources(cfg: &PipelineConfig, target: Target, unit: &str, work: &Path, command: &str) -> Result<FpgaUnit> {
    crate::yosys::require()?;
    let u = crate::units::unit(unit).filter(|u| u.included(cfg)).ok_or_else(|| {
        Error::Other(format!(
            "{unit}: not a unit of this configuration\n  fix: use one of {}",
            crate::sim::testbench::units_of(cfg).join(", ")
        ))
    })?;
    let dir = work.join(format!("fpga_{}", &cfg.hash()[..8]));
    let rtl = crate::sim::rtl_files::write_rtl(cfg, &dir.join("rtl"), command)?;
    let module = module_name(cfg, u.name());
    let (s, bits, _) = synth(target, &rtl, &module, &dir, false)?;
    Ok(FpgaUnit::from_stat(target, unit, &module, &s, bits))
}

/// Synthesise every unit of `cfg` (with `per_unit`) and the top for `target`; for iCE40 also
/// place and route the top in its register shell on `device`.
pub fn fpga_area(cfg: &PipelineConfig, target: Target, device: &str, per_unit: bool, work: &Path, command: &str) -> Result<FpgaReport> {
    require(target)?;
    let package = ice40_package(device)?;
    let dir = work.join(format!("fpga_{}", &cfg.hash()[..8]));
    let mut rtl = crate::sim::rtl_files::write_rtl(cfg, &dir.join("rtl"), command)?;
    let shell = crate::rtlgen::fpga_shell::name(cfg);
    if target == Target::Ice40 {
        let p = rtl.dir.join(format!("{shell}.v"));
        crate::render::output::write_atomic(&p, crate::rtlgen::fpga_shell::shell(cfg).as_bytes())?;
        rtl.sources.push(p);
    }
    let mut jobs: Vec<(String, String, bool)> = Vec::new();
    if per_unit {
        for u in crate::sim::testbench::units_of(cfg) {
            jobs.push((u.to_string(), module_name(cfg, u), false));
        }
    }
    jobs.push(("gbump_pipeline (top)".into(), module_name(cfg, "gbump_pipeline"), false));
    if target == Target::Ice40 {
        jobs.push(("fpga shell".into(), shell.clone(), true));
    }
    let results: Vec<Result<(FpgaUnit, PathBuf)>> = {
        use rayon::prelude::*;
        jobs.par_iter()
            .map(|(unit, module, netlist)| {
                let (s, bits, path) = synth(target, &rtl, module, &dir, *netlist)?;
                Ok((FpgaUnit::from_stat(target, unit, module, &s, bits), path))
            })
            .collect()
    };
    let mut units = Vec::new();
    let mut netlist = None;
    for r in results {
        let (u, path) = r?;
        if u.module == shell {
            netlist = Some(path);
        } else {
            units.push(u);
        }
    }
    let place_route = match netlist {
        None => None,
        Some(n) => {
            let (ok, log) = place_route(&n, device, package, &dir)?;
            let core_pins = crate::rtlgen::top::top_ports(cfg).iter().map(|p| p.2).sum();
            Some(place_route_result(
                ok,
                &log,
                device,
                package,
                &shell,
                crate::rtlgen::fpga_shell::PINS.len() as u32,
                core_pins,
            )?)
        }
    };
    Ok(FpgaReport {
        config_hash: cfg.hash(),
        target,
        yosys_version: crate::yosys::version(),
        script: crate::yosys::scripts::fpga_summary(target),
        units,
        place_route,
    })
}

/// Markdown: a resource table and, for iCE40, the place-and-route result.
pub fn markdown(r: &FpgaReport) -> String {
    let [l, f, c, d, b] = r.target.cell_names();
    let mut s = format!(
        "FPGA resources of config `{}` on {} ({}; script per module: `{}`)\n\n| unit | LUTs ({l}) | flip-flops ({f}) | carry ({c}) | DSP ({d}) | block RAM ({b}) | RAM bits | LUT RAM/SRL |\n|---|---:|---:|---:|---:|---:|---:|---:|\n",
        r.config_hash,
        r.target.name(),
        r.yosys_version,
        r.script
    );
    for u in &r.units {
        s += &format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} |\n",
            u.unit, u.luts, u.flip_flops, u.carry, u.dsp, u.block_ram, u.memory_bits, u.lut_ram
        );
    }
    if let Some(p) = &r.place_route {
        s += &format!(
            "\nPlace and route: {} on iCE40 {} ({}), target {} MHz, seed {SEED}. The top has {} pins, more than the package bonds, so it is placed inside `{}`, a register shell that shifts the inputs in through a serial chain and the outputs out of a parallel-load register, a register on each of its {} pins; Fmax is the core's clock.\n\n",
            p.tool, p.device, p.package, p.target_mhz, p.core_pins, p.placed, p.pins
        );
        match (p.fits, p.fmax_mhz) {
            (true, Some(fm)) => s += &format!("**Fmax {fm:.2} MHz** (clk, after routing)\n\n"),
            _ => {
                s += &format!(
                    "**Does not fit** the {}: {}\n\n",
                    p.device,
                    p.reason.as_deref().unwrap_or("nextpnr could not place it")
                )
            }
        }
        s += "| resource | used | available | utilisation |\n|---|---:|---:|---:|\n";
        for u in &p.utilisation {
            s += &format!("| {} | {} | {} | {:.0} % |\n", u.resource, u.used, u.available, u.percent);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Captured from nextpnr-ice40 0.4-1+b1 (Debian bookworm): the one-light parallel top in its
    /// shell on an HX8K (lines of the log; the first Fmax is the placer's estimate).
    const ROUTED: &str = "Info: Device utilisation:
Info: \t         ICESTORM_LC:  6396/ 7680    83%
Info: \t        ICESTORM_RAM:     1/   32     3%
Info: \t               SB_IO:     7/  256     2%
Info: \t               SB_GB:     3/    8    37%
Info: \t        ICESTORM_PLL:     0/    2     0%
Info: \t         SB_WARMBOOT:     0/    1     0%

Info: Placed 7 cells based on constraints.
Info: Max frequency for clock 'clk$SB_IO_IN_$glb_clk': 34.42 MHz (FAIL at 50.00 MHz)
Warning: Max frequency for clock 'clk$SB_IO_IN_$glb_clk': 32.81 MHz (FAIL at 50.00 MHz)
2 warnings, 0 errors

Info: Program finished normally.
";

    /// Captured: the same design on an HX1K.
    const TOO_BIG: &str = "Info: Device utilisation:
Info: \t         ICESTORM_LC:  6396/ 1280   499%
Info: \t        ICESTORM_RAM:     1/   16     6%
Info: \t               SB_IO:     7/  112     6%
Info: \t               SB_GB:     3/    8    37%
Info: \t        ICESTORM_PLL:     0/    1     0%
Info: \t         SB_WARMBOOT:     0/    1     0%

Info: Placed 0 cells based on constraints.
ERROR: Unable to place cell 'u_core.u_diffuse_blend.fin.add2_r_SB_LUT4_O_9_LC', no BELs remaining to implement cell type 'ICESTORM_LC'
1 warning, 1 error
";

    /// Captured: the bare one-light top (250 pins, no shell) on the HX8K's ct256 package.
    const PINS: &str = "Info: Device utilisation:
Info: \t         ICESTORM_LC:  6005/ 7680    78%
Info: \t        ICESTORM_RAM:     1/   32     3%
Info: \t               SB_IO:   250/  256    97%
Info: \t               SB_GB:     1/    8    12%
ERROR: Unable to find a placement location for cell 'in_l[43]$sb_io'
1 warning, 1 error
";

    #[test]
    fn reads_utilisation_and_the_post_route_fmax() {
        let p = parse_nextpnr(ROUTED);
        assert_eq!(p.utilisation.len(), 6);
        assert_eq!(
            p.utilisation[0],
            Utilisation {
                resource: "ICESTORM_LC".into(),
                used: 6396,
                available: 7680,
                percent: 83.0
            }
        );
        assert_eq!(p.utilisation[5].resource, "SB_WARMBOOT");
        assert_eq!(p.fmax_mhz, vec![("clk$SB_IO_IN_$glb_clk".to_string(), 32.81)]);
        assert!(p.errors.is_empty() && !does_not_fit(&p));
        let r = place_route_result(true, ROUTED, "hx8k", "ct256", "shell", 7, 250).unwrap();
        assert!(r.fits && r.fmax_mhz == Some(32.81));
        assert!(markdown_of(r).contains("**Fmax 32.81 MHz**"));
    }

    fn markdown_of(p: PlaceRoute) -> String {
        markdown(&FpgaReport {
            config_hash: "h".into(),
            target: Target::Ice40,
            yosys_version: "Yosys".into(),
            script: crate::yosys::scripts::fpga_summary(Target::Ice40),
            units: vec![],
            place_route: Some(p),
        })
    }

    #[test]
    fn too_many_cells_or_pins_is_a_result_and_other_failures_are_errors() {
        for (log, why) in [
            (TOO_BIG, "ICESTORM_LC 6396/1280 (499 %)"),
            (PINS, "Unable to find a placement location"),
        ] {
            let r = place_route_result(false, log, "hx8k", "ct256", "shell", 7, 640).unwrap();
            assert_eq!(parse_nextpnr(log).errors.len(), 1);
            assert!(!r.fits && r.fmax_mhz.is_none());
            assert!(r.reason.as_deref().unwrap().contains(why), "{r:?}");
            assert!(markdown_of(r).contains("**Does not fit** the hx8k"));
        }
        let e = place_route_result(false, "ERROR: Failed to parse JSON\n", "hx8k", "ct256", "shell", 7, 640).unwrap_err();
        assert!(e.to_string().contains("nextpnr-ice40 failed"), "{e}");
        assert!(place_route_result(true, "Info: Routing..\n", "hx8k", "ct256", "shell", 7, 640).is_err());
    }

    #[test]
    fn cells_fall_into_their_columns() {
        let s = yosys_stat::Stat {
            cells: [
                ("LUT6", 10),
                ("LUT2", 5),
                ("FDRE", 7),
                ("CARRY4", 2),
                ("DSP48E1", 3),
                ("RAMB18E1", 1),
                ("RAM64M", 12),
                ("SRL16E", 4),
                ("MUXF7", 9),
            ]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect(),
            ..Default::default()
        };
        let u = FpgaUnit::from_stat(Target::Xilinx, "u", "m", &s, 0);
        assert_eq!((u.luts, u.flip_flops, u.carry, u.dsp, u.block_ram, u.lut_ram), (15, 7, 2, 3, 1, 16));
        assert_eq!(Target::Ice40.classify("SB_DFFSR"), Class::FlipFlop);
        assert_eq!(Target::Ecp5.classify("MULT18X18D"), Class::Dsp);
        assert_eq!(Target::Ecp5.classify("PFUMX"), Class::Other);
        assert!(ice40_package("hx8k").is_ok() && ice40_package("xc7a35t").is_err());
    }
}
