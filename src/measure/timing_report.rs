//! The report's "timing as a parameter" section: the one-light parallel top, with the default
//! arithmetic and as the paper's sample implementation (k_i an on/off enable), at every
//! `pipeline_depth` (logic GE with the RAMs apart, flip-flops, RAM bits, latency, iCE40 LUTs,
//! block RAMs and Fmax after place and route), set against the paper's band and the figures
//! measured before the RAMs and the depth existed; then whether the default top fits an HX8K.

use super::fpga::{fpga_area, FpgaReport, Target};
use crate::config::PipelineConfig;
use crate::error::Result;
use std::path::Path;

/// The paper's estimate for the added units (Ernst et al. 1998, §4.2), in gate equivalents.
pub const PAPER_GE: (f64, f64) = (10_000.0, 25_000.0);
/// Measured before this section existed (issue 10, the one-light parallel top with the power
/// table as a register file and every unit in one cycle): total GE, of it the table's
/// flip-flops, and iCE40 HX8K Fmax. Quoted, not re-measured: that RTL is gone.
pub const BEFORE: (f64, f64, f64) = (53_000.0, 24_000.0, 31.6);

/// The one-light configurations of the section: (test config file, its TOML).
pub const ONE_LIGHT_CONFIGS: [(&str, &str); 2] = [
    ("tests/configs/one_light_parallel.toml", super::configs::ONE_LIGHT_PARALLEL),
    ("tests/configs/paper_sample_one_light.toml", super::configs::PAPER_SAMPLE_ONE_LIGHT),
];

/// A one-light configuration (`toml`) at `depth`.
pub fn one_light(toml: &str, depth: u32) -> Result<PipelineConfig> {
    let mut cfg = PipelineConfig::from_toml("one_light", toml)?;
    cfg.pipeline_depth = depth;
    cfg.validate("one_light")?;
    Ok(cfg)
}

fn fmax(r: &FpgaReport) -> String {
    match &r.place_route {
        Some(p) if p.fits => p.fmax_mhz.map_or("-".into(), |f| format!("{f:.1}")),
        Some(_) => "does not fit".into(),
        None => "-".into(),
    }
}

fn logic_cells(r: &FpgaReport) -> String {
    r.place_route
        .as_ref()
        .and_then(|p| p.utilisation.iter().find(|u| u.resource == "ICESTORM_LC"))
        .map_or("-".into(), |u| format!("{}/{} ({:.0} %)", u.used, u.available, u.percent))
}

/// The section's Markdown; `work` holds the area and FPGA caches.
pub fn section(work: &Path) -> Result<String> {
    let (lo, hi) = PAPER_GE;
    let (ge0, table0, f0) = BEFORE;
    let mut s = format!(
        "`gbump area` and `gbump area --target ice40` with `--config C` plus `pipeline_depth = D`, for C = `tests/configs/one_light_parallel.toml` (the default arithmetic) and `tests/configs/paper_sample_one_light.toml` (the same with `k_frac_bits = 0`: k_i an on/off enable, no f·k multiplier, as in the paper's sample implementation where k \"has no effect\"). Logic GE: the RAMs are black boxes (`src/rtlgen/ram.rs`), so their bits stand apart, as the paper's table \"equal in size to a colour LUT\"; the output buffer is a RAM too. Before (issue 10, quoted): {ge0:.0} GE with {table0:.0} of it the table's flip-flops, {f0} MHz on an HX8K. Paper: {lo:.0}-{hi:.0} GE for the added units, \"depending on the accuracy of all relevant input fields\".\n\n| configuration | pipeline_depth | latency | logic GE | in the paper's band | flip-flops | RAM bits | iCE40 LUTs | iCE40 block RAMs | iCE40 logic cells | HX8K Fmax (MHz) | vs {f0} MHz |\n|---|---:|---:|---:|---|---:|---:|---:|---:|---|---:|---:|\n"
    );
    for (file, toml) in ONE_LIGHT_CONFIGS {
        for d in 1..=crate::limits::MAX_PIPELINE_DEPTH {
            let cfg = one_light(toml, d)?;
            let a = super::area::area(&cfg, &work.join("area"), "gbump report")?;
            let top = a.top();
            let f = fpga_area(&cfg, Target::Ice40, "hx8k", false, &work.join("fpga"), "gbump report")?;
            let ratio = f
                .place_route
                .as_ref()
                .and_then(|p| p.fmax_mhz.filter(|_| p.fits))
                .map_or("-".into(), |m| format!("{:.2}x", m / f0));
            let band = if top.gate_equivalents >= lo && top.gate_equivalents <= hi {
                "yes"
            } else if top.gate_equivalents < lo {
                "below"
            } else {
                "above"
            };
            s += &format!(
                "| `{file}` | {d} | {} | {:.0} | {band} | {} | {} | {} | {} | {} | {} | {ratio} |\n",
                crate::rtlgen::top::latency(&cfg),
                top.gate_equivalents,
                top.flip_flops,
                top.memory_bits,
                f.top().luts,
                f.top().block_ram,
                logic_cells(&f),
                fmax(&f)
            );
        }
    }
    let cfg = PipelineConfig::default();
    let f = fpga_area(&cfg, Target::Ice40, "hx8k", false, &work.join("fpga"), "gbump report")?;
    let fits = f.place_route.as_ref().is_some_and(|p| p.fits);
    s += &format!(
        "\nThe default top (4 lights, serial, `pipeline_depth = {}`) on an HX8K: {} ({} LUTs, {} block RAMs of {} RAM bits, logic cells {}, Fmax (MHz): {}). Both are per-triangle tops (`bump_state = \"triangle\"`): the bump state sits in two banks loaded by the setup port, as register banks in the parallel top and as one RAM (block RAM here, written a light slot per edge) in the serial top; multipliers are Booth-recoded (`src/rtlgen/booth.rs`).\n",
        cfg.pipeline_depth,
        if fits { "**fits**" } else { "**does not fit**" },
        f.top().luts,
        f.top().block_ram,
        f.top().memory_bits,
        logic_cells(&f),
        fmax(&f)
    );
    Ok(s)
}
