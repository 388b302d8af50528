//! Area by Yosys: each unit (and the top) synthesised alone with
//! `synth -flatten; dffunmap; abc -g cmos2; stat -json -tech cmos` (`yosys::scripts::cmos_area`,
//! read by `yosys::stat`), reported as NAND2 gate equivalents (transistors / 4), with
//! flip-flops, logic depth (`ltp -noff`, read by `yosys::ltp`) and memory bits. The RAMs are
//! black boxes there, so the GE are logic only and the memory's bits stand apart, as the
//! paper counts a table "equal in size to a colour LUT".

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::rtlgen::units_v::module_name;
use crate::yosys::scripts::cmos_area;
use serde::{Deserialize, Serialize};
use std::path::Path;

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct UnitArea {
    pub unit: String,
    pub module: String,
    pub transistors: u64,
    pub gate_equivalents: f64,
    pub flip_flops: u64,
    pub logic_depth: u64,
    /// Bits of the unit's RAMs (every copy), measured by Yosys; not in the GE.
    #[serde(alias = "rom_bits")]
    pub memory_bits: u64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct AreaReport {
    pub config_hash: String,
    pub yosys_version: String,
    pub script: String,
    pub units: Vec<UnitArea>,
}

impl AreaReport {
    /// The top's row.
    pub fn top(&self) -> &UnitArea {
        self.units
            .iter()
            .find(|u| u.unit.starts_with("gbump_pipeline"))
            .expect("area reports hold the top")
    }
}

/// Transistors and flip-flops from `stat -json -tech cmos`, logic depth from `ltp -noff`,
/// memory bits from the `stat -json` taken before the RAMs became black boxes.
fn parse_stat(stat: &str, ltp: &str, memory: &str) -> Option<(u64, u64, u64, u64)> {
    let s = crate::yosys::stat::parse(stat)?;
    let m = crate::yosys::stat::parse(memory)?;
    let ffs = s.count(|c| c.starts_with("$_DFF"));
    Some((s.transistors?, ffs, crate::yosys::ltp::depth(ltp), m.memory_bits))
}

/// Synthesise every unit present in `cfg` and the top.
pub fn area(cfg: &PipelineConfig, work: &Path, command: &str) -> Result<AreaReport> {
    crate::yosys::require()?;
    let dir = work.join(format!("area_{}", &cfg.hash()[..8]));
    let v = crate::sim::regress::write_rtl(cfg, &dir, command)?.sources;
    let files: Vec<String> = v
        .iter()
        .map(|p| p.file_name().expect("file").to_string_lossy().into_owned())
        .collect();
    let version = crate::yosys::version();
    // The sources are absolute (write_rtl), so each unit's script runs from its own folder.
    let abs: Vec<String> = v.iter().map(|p| p.display().to_string()).collect();
    let mut units: Vec<(String, String)> = crate::sim::testbench::units_of(cfg)
        .iter()
        .map(|u| (u.to_string(), module_name(cfg, u)))
        .collect();
    units.push(("gbump_pipeline (top)".into(), module_name(cfg, "gbump_pipeline")));
    let progress = crate::progress::Progress::new("area", units.len() as u64);
    let results: Vec<Result<UnitArea>> = {
        use rayon::prelude::*;
        units
            .par_iter()
            .map(|(unit, module)| {
                progress.start(&format!("yosys {module}"));
                let sub = dir.join(format!("syn_{module}"));
                let (ok, log) = crate::yosys::run(
                    &cmos_area(&abs, module),
                    Path::new("area.ys"),
                    &sub,
                    &["area.json", "area.ltp", "memory.json"],
                )?;
                let read = |f: &str| std::fs::read_to_string(sub.join(f)).unwrap_or_default();
                let (t, ffs, depth, memory_bits) = match (ok, parse_stat(&read("area.json"), &read("area.ltp"), &read("memory.json"))) {
                    (true, Some(x)) => x,
                    _ => {
                        return Err(Error::Other(format!(
                            "yosys could not synthesise {module}:\n{}\n{}",
                            crate::tool::log_tail("yosys", &log, 15),
                            crate::tool::synthesis_fix(&log)
                        )))
                    }
                };
                progress.done(&format!("{unit}: {:.0} GE", t as f64 / 4.0));
                Ok(UnitArea {
                    unit: unit.clone(),
                    module: module.clone(),
                    transistors: t,
                    gate_equivalents: t as f64 / 4.0,
                    flip_flops: ffs,
                    logic_depth: depth,
                    memory_bits,
                })
            })
            .collect()
    };
    drop(progress);
    let units = results.into_iter().collect::<Result<Vec<_>>>()?;
    Ok(AreaReport {
        config_hash: cfg.hash(),
        yosys_version: version,
        script: cmos_area(&files, "<module>"),
        units,
    })
}

/// Markdown table of a report.
pub fn markdown(r: &AreaReport) -> String {
    let mut s = format!("Area of config `{}` ({}; script per module: RAMs as black boxes, `synth -flatten; dffunmap; abc -g cmos2; stat -tech cmos`, GE = transistors / 4: logic only, the RAMs' bits apart)\n\n| unit | logic GE | transistors | flip-flops | logic depth | RAM bits |\n|---|---:|---:|---:|---:|---:|\n", r.config_hash, r.yosys_version);
    for u in &r.units {
        s += &format!(
            "| {} | {:.0} | {} | {} | {} | {} |\n",
            u.unit, u.gate_equivalents, u.transistors, u.flip_flops, u.logic_depth, u.memory_bits
        );
    }
    s
}

/// Yosys area of `cfg`, shared by every point of the same configuration whatever the scene.
pub(crate) fn cached_area(cfg: &PipelineConfig, work: &Path) -> Result<AreaReport> {
    let mut k = crate::cache::Key::new("area");
    k.add(cfg.to_toml().as_bytes())
        .add(crate::yosys::scripts::cmos_area(&[], "").as_bytes())
        .add_tool("yosys");
    let file = work.join("area").join(format!("{}.json", k.finish()));
    if let Some(r) = std::fs::read_to_string(&file)
        .ok()
        .and_then(|t| serde_json::from_str::<AreaReport>(&t).ok())
    {
        if r.config_hash == cfg.hash() {
            return Ok(r);
        }
    }
    let r = area(cfg, &work.join("area"), "gbump sweep")?;
    crate::render::output::write_atomic(&file, serde_json::to_string_pretty(&r).expect("json").as_bytes())?;
    Ok(r)
}
