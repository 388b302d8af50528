//! An analytical area model of the top's logic: what each unit is built of, counted from its
//! widths (`Unit::resources`, which mirrors the unit's emitter), times its copies in the top,
//! plus the top's own delay lines, banks and control as the top builder counts them
//! (`rtlgen::top::tally`); weighted into NAND2 gate equivalents by coefficients fitted by
//! least squares (on relative error) to Yosys's figures for each unit alone and for the top
//! (`gbump area`, RAMs apart). No Verilog is written or read to score a configuration.

use crate::config::PipelineConfig;
use crate::units::resources::{Resources, KINDS};

/// The regressors: register, Booth partial-product, unsigned and signed inferred array adder
/// cells, adder, select (comparator and multiplexer: one weight, as a free pair fits a
/// negative multiplexer weight) and bank bits, then a constant per module.
pub const REGRESSORS: usize = KINDS - 1;

/// Coefficients: GE per unit of each regressor, then the constant.
pub type Coefficients = [f64; REGRESSORS + 1];

/// The features of one module: its resource counts and the constant's weight.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Features {
    pub res: Resources,
}

impl Features {
    /// The model's regressors (the constant last).
    pub fn row(&self) -> [f64; REGRESSORS + 1] {
        let r = &self.res;
        [r.ff, r.pp, r.mul, r.smul, r.add, r.cmp + r.mux, r.array, 1.0]
    }
    /// GE under `coef`.
    pub fn ge(&self, coef: &Coefficients) -> f64 {
        self.row().iter().zip(coef).map(|(x, c)| x * c).sum()
    }
}

/// Coefficients fitted by `calibrate` on the calibration part of `SAMPLES` (`gbump area-model`
/// prints them).
pub const COEFFICIENTS: Coefficients = [
    3.6801505216328825,
    23.930374894943498,
    12.786451447502277,
    16.932291964863833,
    2.8517243651858553,
    0.6554040779892655,
    4.394633174871729,
    1.500567764697465,
];

/// The counts of `cfg`'s top: its own logic and every unit instance's.
pub fn resources(cfg: &PipelineConfig) -> Resources {
    tally_resources(cfg, &crate::rtlgen::top::tally(cfg))
}

/// The counts of a top tallied as `t`.
fn tally_resources(cfg: &PipelineConfig, t: &crate::rtlgen::module::Tally) -> Resources {
    t.glue + t.instances.iter().map(|i| instance_resources(cfg, i)).sum()
}

/// One instance's counts in the top, every copy.
fn instance_resources(cfg: &PipelineConfig, i: &crate::rtlgen::module::Instance) -> Resources {
    let u = crate::units::unit(i.unit).expect("the top instantiates units");
    let res = match i.factor_frac {
        // A blend whose factor holds fewer fraction bits is the blend of that factor width
        // (its extra low bits are zeros that synthesis removes).
        Some(f) => u.resources(&PipelineConfig {
            dot_frac_bits: f,
            power_frac_bits: f,
            ..cfg.clone()
        }),
        None => u.resources(cfg),
    };
    (res - single_slot_savings(cfg, i.unit)).scaled(i.copies as f64)
}

/// What a one-light serial top removes from each `light_accumulate` it instantiates: its slot
/// index never leaves 0, so `first` is constant and the running sum is the term alone (no
/// adder, no select); and the accumulator bits below what `blend_finish` reads drive nothing
/// (below the rounding shift when truncating, below its half bit when rounding half up; a
/// half-to-even rounding reads them all). The unit alone keeps all of it: its outputs are
/// ports.
fn single_slot_savings(cfg: &PipelineConfig, unit: &str) -> Resources {
    if unit != "light_accumulate" || cfg.lights != 1 {
        return Resources::default();
    }
    let aw = cfg.acc_fmt().width;
    let shift = crate::model::blend::sum_shift(cfg);
    let dead = match cfg.rounding {
        crate::fixed::Rounding::Truncate => shift,
        crate::fixed::Rounding::HalfUp => shift.saturating_sub(1),
        crate::fixed::Rounding::NearestEven => 0,
    };
    (Resources::muxes(aw) + Resources::adders(aw) + Resources::regs(dead)).scaled(3.0)
}

/// What `gbump sweep` reports of a top's area, by the model instead of Yosys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelArea {
    pub top_ge: f64,
    /// The blend hardware as instantiated (parallel blends, or accumulators and finishes).
    pub blend_ge: f64,
    pub flip_flops: u64,
    /// Bits of every RAM copy and register array (apart from the GE, as Yosys counts them).
    pub memory_bits: u64,
}

/// The model's figures for `cfg`'s top.
pub fn model_area(cfg: &PipelineConfig) -> ModelArea {
    let t = crate::rtlgen::top::tally(cfg);
    let (mut blend, mut memory) = (0.0, crate::rtlgen::top::array_bits(cfg) as u64);
    for i in &t.instances {
        let u = crate::units::unit(i.unit).expect("the top instantiates units");
        if ["diffuse_blend", "specular_blend", "light_accumulate", "blend_finish"].contains(&i.unit) {
            blend += Features {
                res: instance_resources(cfg, i),
            }
            .ge(&COEFFICIENTS);
        }
        if let Some(m) = u.memory(cfg) {
            // An interpolating power unit reads two knots per port: two copies; an EMBM fetch
            // reads its 2x2 block from four.
            let per_port = if i.unit == "power_unit" && cfg.power_unit != crate::config::PowerUnitKind::Table {
                2
            } else if i.unit.starts_with("env_fetch") {
                crate::rtlgen::env_v::FETCH_COPIES
            } else {
                1
            };
            memory += (m.depth * m.data_bits * i.copies * per_port) as u64;
        }
    }
    let res = tally_resources(cfg, &t);
    ModelArea {
        top_ge: Features { res }.ge(&COEFFICIENTS),
        blend_ge: blend,
        flip_flops: res.ff.round() as u64,
        memory_bits: memory,
    }
}

/// The features of `cfg`'s top.
pub fn features(cfg: &PipelineConfig) -> Features {
    Features { res: resources(cfg) }
}

/// The features of `unit` alone (one read port), as `gbump area` synthesises it.
pub fn unit_features(cfg: &PipelineConfig, unit: &str) -> Option<Features> {
    crate::units::unit(unit).map(|u| Features { res: u.resources(cfg) })
}

/// Estimated logic GE of `cfg`'s top with `coef`.
pub fn estimate_with(cfg: &PipelineConfig, coef: &Coefficients) -> f64 {
    features(cfg).ge(coef)
}

/// Estimated logic GE of `cfg`'s top (RAM bits apart).
pub fn estimate(cfg: &PipelineConfig) -> f64 {
    estimate_with(cfg, &COEFFICIENTS)
}

/// Coefficients for `(features, measured GE)` samples that minimise the relative error:
/// least squares weighted by 1/GE-predicted, iterated from 1/GE-measured (weighting by the
/// measurement alone biases every estimate low), each step solved by the normal equations with
/// partial pivoting; a regressor no sample exercises gets 0.
pub fn calibrate(samples: &[(Features, f64)]) -> Coefficients {
    let mut weight: Vec<f64> = samples.iter().map(|(_, y)| 1.0 / y.max(1.0)).collect();
    let mut coef = [0.0; REGRESSORS + 1];
    for _ in 0..10 {
        coef = weighted_least_squares(samples, &weight);
        weight = samples.iter().map(|(f, _)| 1.0 / f.ge(&coef).max(1.0)).collect();
    }
    coef
}

fn weighted_least_squares(samples: &[(Features, f64)], weight: &[f64]) -> Coefficients {
    const N: usize = REGRESSORS + 1;
    let mut a = [[0.0f64; N + 1]; N];
    for ((f, y), w) in samples.iter().zip(weight) {
        let r = f.row().map(|x| x * w);
        for i in 0..N {
            for j in 0..N {
                a[i][j] += r[i] * r[j];
            }
            a[i][N] += r[i] * y * w;
        }
    }
    for col in 0..N {
        let p = (col..N).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs())).expect("rows");
        a.swap(col, p);
        let d = a[col][col];
        if d.abs() < 1e-12 {
            continue;
        }
        for x in &mut a[col][col..] {
            *x /= d;
        }
        let pivot = a[col];
        for (i, row) in a.iter_mut().enumerate() {
            if i != col {
                let k = row[col];
                for (x, p) in row[col..].iter_mut().zip(&pivot[col..]) {
                    *x -= k * p;
                }
            }
        }
    }
    std::array::from_fn(|i| if a[i][i].abs() < 1e-12 { 0.0 } else { a[i][N] })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_grow_with_the_widths() {
        let small = PipelineConfig {
            lights: 1,
            ..Default::default()
        };
        let wide = PipelineConfig {
            lh_bits: 20,
            normal_bits: 12,
            ..small.clone()
        };
        let (a, b) = (resources(&small), resources(&wide));
        assert!(b.pp > a.pp && b.add > a.add && b.ff >= a.ff, "{a:?} {b:?}");
        assert!(a.ff > 100.0 && a.pp > 100.0 && a.add > 100.0 && a.mux > 10.0, "{a:?}");
    }

    #[test]
    fn calibration_recovers_known_coefficients() {
        let coef: Coefficients = [4.0, 2.5, 6.0, 9.0, 7.0, 3.0, 5.0, 300.0];
        let samples: Vec<(Features, f64)> = (0..16)
            .map(|i| {
                let f = Features {
                    res: Resources {
                        ff: 100.0 + 37.0 * i as f64,
                        pp: 500.0 + (i * i) as f64 * 13.0,
                        mul: ((i * 5) % 7) as f64 * 40.0,
                        smul: ((i * 3) % 5) as f64 * 70.0 + i as f64,
                        array: ((i * 13) % 9) as f64 * 25.0,
                        add: 800.0 + ((i * 7) % 5) as f64 * 90.0,
                        cmp: 30.0 + ((i * 11) % 6) as f64 * 9.0,
                        mux: 50.0 + ((i * 3) % 4) as f64 * 20.0,
                    },
                };
                (f, f.ge(&coef))
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
    /// Yosys GE of each unit synthesised alone (`gbump area`'s rows), for the calibration.
    #[serde(default)]
    pub units: Vec<(String, f64)>,
}

impl Sample {
    /// The calibration rows of this sample: the top, and each unit alone.
    pub fn rows(&self) -> Vec<(Features, f64)> {
        let mut v = vec![(features(&self.config), self.yosys_ge)];
        for (u, ge) in &self.units {
            if let Some(f) = unit_features(&self.config, u) {
                v.push((f, *ge));
            }
        }
        v
    }
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
) -> crate::error::Result<(Coefficients, Vec<Sample>)> {
    let mut rows = Vec::new();
    for (i, p) in configs.iter().enumerate() {
        let cfg = PipelineConfig::load(p)?;
        // Cached by configuration, script and Yosys version, as `gbump sweep` caches.
        let r = super::area::cached_area(&cfg, work)?;
        let ge = r.top().gate_equivalents;
        say(&format!(
            "[{}/{}] {} ({}): {ge:.0} GE",
            i + 1,
            configs.len(),
            p.display(),
            &cfg.hash()[..8]
        ));
        let units = r
            .units
            .iter()
            .filter(|u| !u.unit.starts_with("gbump_pipeline"))
            .map(|u| (u.unit.clone(), u.gate_equivalents))
            .collect();
        rows.push(Sample {
            file: p.display().to_string(),
            hash: cfg.hash(),
            yosys_ge: ge,
            model_ge: f64::NAN,
            calibration: i < calibrate_on,
            config: cfg,
            units,
        });
    }
    let coef = calibrate(&rows.iter().filter(|s| s.calibration).flat_map(|s| s.rows()).collect::<Vec<_>>());
    for s in &mut rows {
        s.model_ge = estimate_with(&s.config, &coef);
    }
    Ok((coef, rows))
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
pub fn markdown(coef: &Coefficients, samples: &[Sample], rate: f64) -> String {
    let (mean, max, n) = held_out_error(samples);
    let worst = samples
        .iter()
        .filter(|s| !s.calibration)
        .max_by(|a, b| {
            ((a.model_ge - a.yosys_ge) / a.yosys_ge)
                .abs()
                .total_cmp(&((b.model_ge - b.yosys_ge) / b.yosys_ge).abs())
        })
        .map_or(String::new(), |w| format!(" The worst held-out configuration is `{}`.", w.file));
    let mut s = format!(
        "Area model (`src/measure/area_model.rs`): GE = {:.2} per register bit + {:.2} per Booth row bit after a product's first (its full adder in the tree) + {:.2} per adder cell of an unsigned and {:.2} of a signed inferred multiplier array (a x (b-1) for an a x b product) + {:.2} per adder bit + {:.2} per comparator, multiplexer or AND-gate bit (an inferred array's a x b AND gates and every Booth row bit's select among them) + {:.2} per bank bit read + {:.0}, fitted on {} configurations (each top and each unit alone); held out: {n} configurations, mean error {:.1} %, max {:.1} % on the top; {rate:.0} configurations scored per second on every core.{worst}\n\n| config | hash | Yosys GE | model GE | error | |\n|---|---|---:|---:|---:|---|\n",
        coef[0],
        coef[1],
        coef[2],
        coef[3],
        coef[4],
        coef[5],
        coef[6],
        coef[7],
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

/// Configurations scored per second on every core: `cfgs` in turn, each changed in one width
/// per score so that no two scores see the same configuration, for about a second.
pub fn scoring_rate(cfgs: &[PipelineConfig]) -> f64 {
    use rayon::prelude::*;
    if cfgs.is_empty() {
        return 0.0;
    }
    let t0 = std::time::Instant::now();
    let mut n = 0usize;
    while t0.elapsed().as_secs_f64() < 1.0 {
        let batch = 2048;
        (n..n + batch).into_par_iter().for_each(|i| {
            let mut c = cfgs[i % cfgs.len()].clone();
            // lh_bits from 8 to 19 (inside every limit) so that each score is a new top.
            c.lh_bits = 8 + (i / cfgs.len() % 12) as u32;
            std::hint::black_box(estimate(&c));
        });
        n += batch;
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
