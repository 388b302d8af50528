//! The power unit's design space: every design of `model::power_unit` evaluated exhaustively
//! over its input codes and every exponent 1..=255, against its storage and multipliers.

use crate::model::power_unit::{PowerFormats, PowerUnitDesign};
use rayon::prelude::*;
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct DesignResult {
    pub design: PowerUnitDesign,
    pub label: String,
    pub rom_bits: u64,
    pub multipliers: u32,
    pub multiplier_bits: u32,
    pub max_lsb: f64,
    pub worst_n: u32,
    pub worst_x: i64,
    pub mean_lsb: f64,
}

/// The designs compared by default.
pub fn default_designs() -> Vec<PowerUnitDesign> {
    let mut v = Vec::new();
    for entries in [64, 128, 256, 512] {
        for nearest in [true, false] {
            v.push(PowerUnitDesign::Table { entries, nearest });
        }
    }
    for knots in [16, 32, 64, 128, 256] {
        v.push(PowerUnitDesign::Lerp { knots });
    }
    for segments in [4, 6, 8, 10, 12] {
        for per_segment in [8, 16, 32, 64] {
            for lerp in [false, true] {
                v.push(PowerUnitDesign::Segmented {
                    segments,
                    per_segment,
                    lerp,
                });
            }
        }
    }
    for guard in [0, 2, 4, 6] {
        v.push(PowerUnitDesign::Squaring { guard });
    }
    v
}

/// Every design that fits the formats, checked over every input and every n in 1..=max_n
/// (minutes at wide formats, so each finished design is reported as progress).
pub fn evaluate(fm: PowerFormats, designs: &[PowerUnitDesign], max_n: u32) -> Vec<DesignResult> {
    let fits: Vec<&PowerUnitDesign> = designs
        .iter()
        .filter(|d| match d {
            PowerUnitDesign::Segmented { segments, .. } => *segments < fm.f,
            _ => true,
        })
        .collect();
    let progress = crate::progress::Progress::new(&format!("power-space u1.{}", fm.f), fits.len() as u64);
    fits.par_iter()
        .map(|d| {
            progress.start(&d.label());
            let (max_lsb, worst_n, worst_x, mean_lsb) = d.worst_error(fm, 1..=max_n);
            progress.done(&format!("{}: max {max_lsb:.3} LSB", d.label()));
            let (m, mb) = d.multipliers(fm);
            DesignResult {
                design: **d,
                label: d.label(),
                rom_bits: d.rom_bits(fm),
                multipliers: m,
                multiplier_bits: mb,
                max_lsb,
                worst_n,
                worst_x,
                mean_lsb,
            }
        })
        .collect()
}

pub fn markdown(fm: PowerFormats, rs: &[DesignResult], max_n: u32) -> String {
    let mut s = format!(
        "Power units, input u1.{} (x = fd/2^{}), output u1.{}; error in output LSBs against exact x^n over every input and every n in 1..={max_n}\n\n| design | ROM bits | multipliers | max error | at n, x | mean | within 1 LSB |\n|---|---:|---:|---:|---|---:|---|\n",
        fm.f, fm.f, fm.p
    );
    let mut sorted: Vec<&DesignResult> = rs.iter().collect();
    sorted.sort_by(|a, b| {
        (a.max_lsb > 1.0)
            .cmp(&(b.max_lsb > 1.0))
            .then(a.multipliers.cmp(&b.multipliers))
            .then(a.rom_bits.cmp(&b.rom_bits))
    });
    for r in sorted {
        let m = if r.multipliers == 0 {
            "0".to_string()
        } else {
            format!("{} x {}b", r.multipliers, r.multiplier_bits)
        };
        s += &format!(
            "| {} | {} | {} | {:.3} | {}, {}/2^{} | {:.4} | {} |\n",
            r.label,
            r.rom_bits,
            m,
            r.max_lsb,
            r.worst_n,
            r.worst_x,
            fm.f,
            r.mean_lsb,
            if r.max_lsb <= 1.0 { "yes" } else { "no" }
        );
    }
    s += &format!(
        "\nThe squaring rows are a design study: square-and-multiply for every n, with the guard bits shown. The pipeline's `power_unit = \"squaring\"` is built for one shininess, rounded to a power of two (its squarings alone, the Cg Tutorial's form), with {} guard bits (`SQUARING_GUARD_BITS`); `gbump error` measures it under a configuration. The segmented rows without `lerp` are a design study too: each entry holds one constant, the mean of x^n at its first and last code (the minimax constant), so x = 0 reads half of the last entry's range; the pipeline's `power_unit = \"segmented\"` is the `lerp` form, which interpolates between knots at the entries' boundaries and gives fs(0) = 0.\n",
        crate::config::SQUARING_GUARD_BITS
    );
    s
}

/// Write a design's RTL, its ROM (for exponent `n`) and return the Verilog file paths.
fn write_design(d: &PowerUnitDesign, fm: PowerFormats, n: u32, dir: &std::path::Path) -> crate::Result<(String, Vec<std::path::PathBuf>)> {
    use crate::error::Error;
    use crate::rtlgen::power_units::{name, rom, rom_depth, unit};
    crate::render::output::make_folder(dir)?;
    let m = name(d, fm);
    let mut files = vec![dir.join(format!("{m}.v"))];
    std::fs::write(&files[0], unit(d, fm, n)).map_err(|e| Error::io(dir, e))?;
    let depth = rom_depth(d, fm);
    if depth > 0 {
        let words: String = d.table(fm, n).iter().map(|v| format!("{v:x}\n")).collect();
        std::fs::write(dir.join(format!("{m}.hex")), words).map_err(|e| Error::io(dir, e))?;
        let rp = dir.join(format!("{m}_rom.v"));
        std::fs::write(&rp, rom(&m, fm.p + 1, depth)).map_err(|e| Error::io(dir, e))?;
        files.push(rp);
    }
    Ok((m, files))
}

/// Simulate a design under Icarus over every input code and compare with the model.
/// Returns the number of inputs checked.
pub fn verify_rtl(d: &PowerUnitDesign, fm: PowerFormats, n: u32, dir: &std::path::Path) -> crate::Result<u64> {
    use crate::error::Error;
    use crate::sim::Simulator;
    let (m, files) = write_design(d, fm, n, dir)?;
    let tb = format!(
        "`timescale 1ns / 1ps\nmodule tb;\nreg clk = 0;\nreg [{f}:0] x = 0;\nwire [{p}:0] fs;\n{m} dut (.clk(clk), .x(x), .fs(fs));\ninteger i;\ninitial begin\n  for (i = 0; i <= {top}; i = i + 1) begin\n    x = i; #1 clk = 1; #1 clk = 0;\n    $display(\"%0d %0d\", i, fs);\n  end\n  $finish;\nend\nendmodule\n",
        f = fm.f, p = fm.p, top = 1u64 << fm.f
    );
    // The ROM reads its table by bare name, so the bench runs in `dir`; the init file is
    // recorded for completeness (Icarus's build does not read it).
    let rtl = crate::sim::rtl_files::Rtl {
        dir: dir.to_path_buf(),
        init_file: dir.join(format!("{m}.hex")),
        sources: files,
        waivers: vec![],
        memory_inits: vec![],
    };
    let sim = crate::sim::Icarus;
    let exe = sim
        .build(dir, &crate::sim::Testbench::new("tb", &tb), &rtl)
        .map_err(|e| Error::Other(format!("{m}: {e}")))?;
    // The bench prints one line per input, not the regression's summary, so it is read here.
    let (ok, out, _) = sim.run_log(&exe, &[], None, dir, "vvp")?;
    // Every line may be out before a crash: a bench that did not exit cleanly does not count.
    if !ok {
        return Err(Error::Other(format!(
            "{m}: the design's bench exited with an error\n{}\n  fix: rerun; if it fails again, reinstall Icarus (scripts/install-tools.sh)",
            crate::tool::tail(&out, 10)
        )));
    }
    let table = d.table(fm, n);
    let mut checked = 0;
    for line in out.lines() {
        let v: Vec<i64> = line.split_whitespace().filter_map(|t| t.parse().ok()).collect();
        if v.len() != 2 {
            continue;
        }
        let want = d.eval(fm, &table, n, v[0]);
        if want != v[1] {
            return Err(Error::Other(format!(
                "{m} (n = {n}): x = {} gives {} in RTL, {want} in the model",
                v[0], v[1]
            )));
        }
        checked += 1;
    }
    if checked != (1u64 << fm.f) + 1 {
        return Err(Error::Other(format!(
            "{m}: checked {checked} inputs\n{}",
            crate::tool::tail(&out, 10)
        )));
    }
    Ok(checked)
}

/// Yosys gate equivalents of a design's datapath, its ROM left as a black box.
pub fn area_ge(d: &PowerUnitDesign, fm: PowerFormats, n: u32, dir: &std::path::Path) -> crate::Result<f64> {
    use crate::error::Error;
    let (m, files) = write_design(d, fm, n, dir)?;
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().expect("name").to_string_lossy().into_owned())
        .collect();
    let script = crate::yosys::scripts::power_datapath(&names, &m, files.len() > 1);
    let (ok, log) = crate::yosys::run(&script, std::path::Path::new("area.ys"), dir, &["area.json"])?;
    let stat = std::fs::read_to_string(dir.join("area.json")).unwrap_or_default();
    let t = crate::yosys::stat::parse(&stat).and_then(|s| s.transistors);
    match (ok, t) {
        (true, Some(t)) => Ok(t as f64 / 4.0),
        _ => Err(Error::Other(format!("yosys failed on {m}:\n{}", crate::tool::tail(&log, 10)))),
    }
}

/// Markdown rows (design, max error, ROM bits, datapath GE) of the designs worth building:
/// those within 1 LSB, and the paper's 256-entry table for comparison; each synthesised in
/// its own folder under `work`, cheapest ROM first.
pub fn area_rows(fm: PowerFormats, rs: &[DesignResult], work: &std::path::Path) -> crate::Result<String> {
    let mut pick: Vec<&DesignResult> = rs
        .iter()
        .filter(|r| r.max_lsb <= 1.0 || matches!(r.design, PowerUnitDesign::Table { entries: 256, .. }))
        .collect();
    pick.sort_by_key(|r| r.rom_bits);
    let progress = crate::progress::Progress::new("power-space area", pick.len() as u64);
    let mut s = String::new();
    for r in pick {
        progress.start(&format!("yosys {}", r.label));
        let ge = area_ge(&r.design, fm, 16, &work.join(crate::rtlgen::power_units::name(&r.design, fm)))?;
        progress.done(&format!("{}: {ge:.0} GE", r.label));
        s += &format!("| {} | {:.3} | {} | {:.0} |\n", r.label, r.max_lsb, r.rom_bits, ge);
    }
    Ok(s)
}
