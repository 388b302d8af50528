//! An area model of the top's logic without Yosys: the structure the emitters write (register
//! bits, Booth partial-product bits, adder bits, multiplexer bits), read from the generated
//! Verilog of every module and multiplied out over the instance tree, weighted by coefficients
//! fitted by least squares to Yosys's gate equivalents (`gbump area`, RAMs apart). Reading the
//! emitted text keeps the model in step with the emitters: a unit that changes its structure
//! changes its features, with nothing restated here. Not yet good enough to rank designs (held
//! out: mean 55 % off Yosys, a negative adder coefficient; inferred `*` products and Booth rows
//! inside functions are not counted), so `gbump fit` sizes with Yosys; the samples and the
//! calibration command are here for the next features.

use crate::config::PipelineConfig;
use std::collections::HashMap;

/// Structural features of a design, in bits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Features {
    /// Register bits (every `reg` that is not a memory).
    pub ff: f64,
    /// Booth partial-product bits (`*_pp` wires): a select and an XOR per bit.
    pub pp: f64,
    /// Adder and subtractor bits: each binary `+` or `-` counts the width it drives.
    pub add: f64,
    /// Two-way multiplexer bits: each `?` counts the width it drives.
    pub mux: f64,
}

impl Features {
    fn accumulate(&mut self, o: &Features) {
        self.ff += o.ff;
        self.pp += o.pp;
        self.add += o.add;
        self.mux += o.mux;
    }
    /// The features as the model's regressors (the constant last).
    pub fn row(&self) -> [f64; 5] {
        [self.ff, self.pp, self.add, self.mux, 1.0]
    }
    /// GE under `coef`.
    pub fn ge(&self, coef: &[f64; 5]) -> f64 {
        self.row().iter().zip(coef).map(|(x, c)| x * c).sum()
    }
}

/// Coefficients (GE per bit of each feature, then a constant), fitted by `calibrate` on the
/// calibration half of `AREA_MODEL_DATA`.
pub const COEFFICIENTS: [f64; 5] = [
    13.62945266320051,
    20.411004442363588,
    -21.54710909127038,
    84.17995484418712,
    -426.7522453115101,
];

/// Width of a `[h:l]` range at the start of `s` (1 when there is none).
fn range_width(s: &str) -> (u32, &str) {
    let t = s.trim_start();
    if let Some(rest) = t.strip_prefix('[') {
        if let Some(end) = rest.find(']') {
            let r = &rest[..end];
            if let Some((h, l)) = r.split_once(':') {
                if let (Ok(h), Ok(l)) = (h.trim().parse::<i64>(), l.trim().parse::<i64>()) {
                    return ((h - l).unsigned_abs() as u32 + 1, &rest[end + 1..]);
                }
            }
        }
    }
    (1, t)
}

/// `+`, `-` and `?` operators of an expression, outside index brackets and replication counts.
fn operators(expr: &str) -> (u32, u32) {
    let mut depth = 0;
    let (mut add, mut mux) = (0, 0);
    let b = expr.as_bytes();
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'[' => depth += 1,
            b']' => depth -= 1,
            b'+' | b'-' if depth == 0 => {
                // `+:` is a part select; a sign after `(`, `{` or `,` is no adder.
                let next = b.get(i + 1).copied().unwrap_or(b' ');
                let prev = b[..i].iter().rev().find(|c| !c.is_ascii_whitespace()).copied().unwrap_or(b'(');
                if next != b':' && !matches!(prev, b'(' | b'{' | b',' | b'=' | b'?' | b':') {
                    add += 1;
                }
            }
            b'?' if depth == 0 => mux += 1,
            _ => {}
        }
    }
    (add, mux)
}

/// One module's own features and the modules it instantiates.
fn module_features(text: &str, modules: &[String]) -> (Features, Vec<String>) {
    let mut widths: HashMap<String, u32> = HashMap::new();
    let mut f = Features::default();
    let mut insts = Vec::new();
    for line in text.lines().map(str::trim) {
        if line.starts_with("//") || line.is_empty() {
            continue;
        }
        let first = line.split(|c: char| !c.is_ascii_alphanumeric() && c != '_').next().unwrap_or("");
        if modules.iter().any(|m| m == first) && !line.starts_with("module") {
            insts.push(first.to_string());
            continue;
        }
        // Declarations: `[input|output] (wire|reg) [h:l] name [= expr];`
        let decl = line.trim_start_matches("input").trim_start_matches("output").trim_start();
        for kind in ["wire", "reg"] {
            if let Some(rest) = decl.strip_prefix(kind).filter(|r| r.starts_with([' ', '['])) {
                let (w, rest) = range_width(rest);
                let rest = rest.trim_start().trim_start_matches("signed").trim_start();
                let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
                let after = rest[name.len()..].trim_start();
                if name.is_empty() || after.starts_with('[') {
                    // A memory: the RAM module's array or a register file, not logic here.
                    continue;
                }
                widths.insert(name.clone(), w);
                if kind == "reg" {
                    f.ff += w as f64;
                }
                if name.ends_with("_pp") {
                    f.pp += w as f64;
                }
                if let Some(expr) = after.strip_prefix('=') {
                    let (a, m) = operators(expr);
                    f.add += (a * w) as f64;
                    f.mux += (m * w) as f64;
                }
            }
        }
        // Assignments: `assign x = e;` and `x <= e;` (the target's declared width, or its range).
        let assign = line.strip_prefix("assign ").and_then(|r| r.split_once(" = ")).or_else(|| {
            line.rsplit_once(" <= ")
                .map(|(l, r)| (l.rsplit([' ', ')']).next().unwrap_or(l), r))
                .filter(|(l, _)| !l.is_empty())
        });
        if let Some((target, expr)) = assign {
            let name: String = target
                .trim()
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            let sel = &target.trim()[name.len()..];
            let w = if sel.starts_with('[') && sel.contains(':') {
                range_width(sel).0
            } else {
                widths.get(&name).copied().unwrap_or(1)
            };
            let (a, m) = operators(expr);
            f.add += (a * w) as f64;
            f.mux += (m * w) as f64;
        }
    }
    (f, insts)
}

/// The features of `cfg`'s top, every module counted once per instance; the RAM module is a
/// black box (its bits stand apart, as in `gbump area`).
pub fn features(cfg: &PipelineConfig) -> Features {
    let files = crate::rtlgen::generate(cfg, "area model");
    let ram = crate::rtlgen::units_v::module_name(cfg, crate::rtlgen::ram::RAM);
    let mods: Vec<(String, String)> = files
        .into_iter()
        .filter(|(n, _)| n.ends_with(".v"))
        .map(|(n, t)| (n.trim_end_matches(".v").to_string(), t))
        .collect();
    let names: Vec<String> = mods.iter().map(|m| m.0.clone()).collect();
    let parsed: HashMap<&str, (Features, Vec<String>)> = mods.iter().map(|(n, t)| (n.as_str(), module_features(t, &names))).collect();
    fn total(m: &str, parsed: &HashMap<&str, (Features, Vec<String>)>, ram: &str) -> Features {
        if m == ram {
            return Features::default();
        }
        let Some((own, insts)) = parsed.get(m) else {
            return Features::default();
        };
        let mut f = *own;
        for i in insts {
            f.accumulate(&total(i, parsed, ram));
        }
        f
    }
    total(&crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline"), &parsed, &ram)
}

/// Estimated logic GE of `cfg`'s top with `coef`.
pub fn estimate_with(cfg: &PipelineConfig, coef: &[f64; 5]) -> f64 {
    features(cfg).ge(coef)
}

/// Estimated logic GE of `cfg`'s top (RAM bits apart).
pub fn estimate(cfg: &PipelineConfig) -> f64 {
    estimate_with(cfg, &COEFFICIENTS)
}

/// Least-squares coefficients for `(features, measured GE)` samples (normal equations,
/// Gaussian elimination with partial pivoting).
pub fn calibrate(samples: &[(Features, f64)]) -> [f64; 5] {
    let mut a = [[0.0f64; 6]; 5];
    for (f, y) in samples {
        let r = f.row();
        for i in 0..5 {
            for j in 0..5 {
                a[i][j] += r[i] * r[j];
            }
            a[i][5] += r[i] * y;
        }
    }
    for col in 0..5 {
        let p = (col..5).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs())).expect("rows");
        a.swap(col, p);
        let d = a[col][col];
        if d.abs() < 1e-12 {
            continue;
        }
        for j in col..6 {
            a[col][j] /= d;
        }
        for i in 0..5 {
            if i != col {
                let k = a[i][col];
                for j in col..6 {
                    a[i][j] -= k * a[col][j];
                }
            }
        }
    }
    [a[0][5], a[1][5], a[2][5], a[3][5], a[4][5]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operators_skip_part_selects_signs_and_indices() {
        assert_eq!(operators(" a + b - c;"), (2, 0));
        assert_eq!(operators(" x[j*4 +: 4] + {1'b0, y[3:0]};"), (1, 0));
        assert_eq!(operators(" s ? a + b : -c;"), (1, 1));
    }

    #[test]
    fn features_grow_with_the_widths() {
        let small = PipelineConfig {
            lights: 1,
            ..Default::default()
        };
        let wide = PipelineConfig {
            lh_bits: 20,
            normal_bits: 12,
            ..small.clone()
        };
        let (a, b) = (features(&small), features(&wide));
        assert!(b.pp > a.pp && b.add > a.add && b.ff >= a.ff, "{a:?} {b:?}");
        assert!(a.ff > 100.0 && a.pp > 100.0 && a.add > 100.0 && a.mux > 10.0, "{a:?}");
    }

    #[test]
    fn calibration_recovers_known_coefficients() {
        let coef = [4.0, 2.5, 7.0, 2.0, 300.0];
        let samples: Vec<(Features, f64)> = (0..12)
            .map(|i| {
                let f = Features {
                    ff: 100.0 + 37.0 * i as f64,
                    pp: 500.0 + (i * i) as f64 * 13.0,
                    add: 800.0 + ((i * 7) % 5) as f64 * 90.0,
                    mux: 50.0 + ((i * 3) % 4) as f64 * 20.0,
                };
                let y = f.row().iter().zip(&coef).map(|(x, c)| x * c).sum();
                (f, y)
            })
            .collect();
        let got = calibrate(&samples);
        for (g, c) in got.iter().zip(coef) {
            assert!((g - c).abs() < 1e-6 * c.max(1.0), "{got:?}");
        }
    }
}

/// One configuration of a calibration or check: its file, features, Yosys GE and the model's.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    pub file: String,
    pub hash: String,
    pub yosys_ge: f64,
    pub model_ge: f64,
    pub calibration: bool,
    pub config: PipelineConfig,
}

/// The checked-in calibration and held-out samples (`gbump area-model --configs
/// tests/area_model/configs --write tests/area_model/samples.jsonl`), one JSON object a line.
pub const SAMPLES: &str = include_str!("../../tests/area_model/samples.jsonl");

/// [`SAMPLES`] with the model's estimate under [`COEFFICIENTS`] (the checked-in estimate is
/// the one the command fitted).
pub fn checked_in() -> Vec<Sample> {
    SAMPLES
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let mut s: Sample = serde_json::from_str(l).expect("samples.jsonl holds samples");
            s.model_ge = estimate(&s.config);
            s
        })
        .collect()
}

/// Calibrate on the first `calibrate` of `configs` (Yosys, cached in `work`) and check on the
/// rest: the fitted coefficients and every sample with the model's estimate under them.
pub fn calibrate_and_check(
    configs: &[std::path::PathBuf],
    calibrate_on: usize,
    work: &std::path::Path,
    say: &mut dyn FnMut(&str),
) -> crate::error::Result<([f64; 5], Vec<Sample>)> {
    let mut rows = Vec::new();
    for (i, p) in configs.iter().enumerate() {
        let cfg = PipelineConfig::load(p)?;
        // The command `gbump area --config P` writes in the headers, so its cache serves here.
        let r = super::area::area(&cfg, work, &format!("gbump rtl --config {}", p.display()))?;
        let ge = r.top().gate_equivalents;
        say(&format!(
            "[{}/{}] {} ({}): {ge:.0} GE",
            i + 1,
            configs.len(),
            p.display(),
            &cfg.hash()[..8]
        ));
        rows.push((p.display().to_string(), cfg.clone(), features(&cfg), ge));
    }
    let n = calibrate_on.min(rows.len());
    let coef = calibrate(&rows[..n].iter().map(|r| (r.2, r.3)).collect::<Vec<_>>());
    let samples = rows
        .iter()
        .enumerate()
        .map(|(i, (p, cfg, f, ge))| Sample {
            file: p.clone(),
            hash: cfg.hash(),
            yosys_ge: *ge,
            model_ge: f.ge(&coef),
            calibration: i < n,
            config: cfg.clone(),
        })
        .collect();
    Ok((coef, samples))
}

/// Mean and max relative error of the held-out samples.
pub fn held_out_error(samples: &[Sample]) -> (f64, f64, usize) {
    let errs: Vec<f64> = samples
        .iter()
        .filter(|s| !s.calibration)
        .map(|s| (s.model_ge - s.yosys_ge).abs() / s.yosys_ge)
        .collect();
    let n = errs.len();
    (
        errs.iter().sum::<f64>() / n.max(1) as f64,
        errs.iter().cloned().fold(0.0, f64::max),
        n,
    )
}

/// The table `gbump area-model` prints.
pub fn markdown(coef: &[f64; 5], samples: &[Sample], rate: f64) -> String {
    let (mean, max, n) = held_out_error(samples);
    let mut s = format!(
        "Area model (`src/measure/area_model.rs`): GE = {:.3} per register bit + {:.3} per Booth partial-product bit + {:.3} per adder bit + {:.3} per multiplexer bit + {:.0}, fitted on {} configurations; held out: {n} configurations, mean error {:.1} %, max {:.1} %; {rate:.0} configurations scored per second.\n\n| config | hash | Yosys GE | model GE | error | |\n|---|---|---:|---:|---:|---|\n",
        coef[0],
        coef[1],
        coef[2],
        coef[3],
        coef[4],
        samples.iter().filter(|s| s.calibration).count(),
        100.0 * mean,
        100.0 * max
    );
    for x in samples {
        s += &format!(
            "| `{}` | `{}` | {:.0} | {:.0} | {:+.1} % | {} |\n",
            x.file,
            &x.hash[..8],
            x.yosys_ge,
            x.model_ge,
            100.0 * (x.model_ge - x.yosys_ge) / x.yosys_ge,
            if x.calibration { "calibration" } else { "held out" }
        );
    }
    s
}

/// Configurations scored per second, over `cfgs` in turn for about a second.
pub fn scoring_rate(cfgs: &[PipelineConfig]) -> f64 {
    let t0 = std::time::Instant::now();
    let mut n = 0;
    while t0.elapsed().as_secs_f64() < 1.0 && !cfgs.is_empty() {
        std::hint::black_box(features(&cfgs[n % cfgs.len()]));
        n += 1;
    }
    n as f64 / t0.elapsed().as_secs_f64()
}

/// The `.toml` files of `dir`, in name order (the order `calibrate_and_check` splits them in).
pub fn configs_in(dir: &std::path::Path) -> crate::error::Result<Vec<std::path::PathBuf>> {
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| crate::error::Error::io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    Ok(files)
}

/// The report's section: the checked-in samples under the checked-in coefficients, and the
/// scoring rate measured now.
pub fn report_section() -> String {
    let samples = checked_in();
    let cfgs: Vec<PipelineConfig> = samples.iter().map(|s| s.config.clone()).collect();
    markdown(&COEFFICIENTS, &samples, scoring_rate(&cfgs))
}
