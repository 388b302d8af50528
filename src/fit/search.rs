//! The search of `gbump fit`: for every choice that changes the arithmetic (power unit, rounding,
//! normal range, palette), shrink each width (colour guard bits among them) in turn to the smallest that keeps the budget
//! (a bisection per width, rounds until nothing shrinks); then size the winners that no other
//! winner covers width by width, and keep the smallest. The light mode and depth stay the
//! base's (results do not depend on them), parallel lights only when the throughput asks.

use super::budget::Measured;
use super::evaluate::Evaluator;
use crate::config::{limit, LightMode, NormalRange, PipelineConfig, PowerUnitKind};
use crate::error::Result;
use crate::fixed::Rounding;

/// The widths the search shrinks, in the order it tries them. The colour guard bits go first:
/// from the generous start the colour stages' roundings are the error that is left, so they
/// shrink to what the budget needs of them before the other widths spend the rest.
pub const WIDTHS: [&str; 7] = [
    "colour_guard_bits",
    "power_entries",
    "power_segments",
    "normal_bits",
    "lh_bits",
    "dot_frac_bits",
    "power_frac_bits",
];

/// The arithmetic choices the search makes, beside the widths.
const CHOICES: [&str; 4] = ["power_unit", "rounding", "normal_range", "palette"];

/// The widths of the stored and sent inputs. An `exact<=` budget measures the arithmetic on the
/// stored codes, not how well the codes hold the true vectors, so under it these stay the
/// base's: narrower inputs make the arithmetic exact by making the inputs coarse (3-bit
/// normals, 4-bit L and H "met" exact<=1), a loss that budget cannot see.
pub const INPUT_WIDTHS: [&str; 2] = ["normal_bits", "lh_bits"];

/// Rounds of shrinking over all widths at most (the last round usually changes nothing).
const ROUNDS: usize = 3;

/// A measured candidate.
#[derive(Clone, Debug)]
pub struct Candidate {
    pub cfg: PipelineConfig,
    pub measured: Measured,
    pub met: bool,
    pub area_ge: f64,
    /// Fragments per clock (1 / initiation interval).
    pub throughput: f64,
}

/// What the search may choose from.
#[derive(Clone, Debug)]
pub struct Space {
    pub power_units: Vec<PowerUnitKind>,
    pub roundings: Vec<Rounding>,
    pub normal_ranges: Vec<NormalRange>,
    pub palettes: Vec<bool>,
    /// Widths a scene's `[pipeline]` sets: kept at the base's value, never shrunk.
    pub pinned: Vec<&'static str>,
    /// Every field the search would choose that a scene's `[pipeline]` sets (choices and
    /// widths), for messages.
    pub kept: Vec<&'static str>,
}

impl Space {
    /// Every choice; a palette only when the scenes' maps fit one exactly.
    pub fn full(palette_exact: bool) -> Space {
        Space {
            power_units: vec![PowerUnitKind::Table, PowerUnitKind::Lerp, PowerUnitKind::Segmented],
            roundings: vec![Rounding::HalfUp, Rounding::Truncate, Rounding::NearestEven],
            normal_ranges: vec![NormalRange::Binary, NormalRange::Symmetric],
            palettes: if palette_exact { vec![false, true] } else { vec![false] },
            pinned: Vec::new(),
            kept: Vec::new(),
        }
    }

    /// Every field of `set` (the keys of the scenes' `[pipeline]` tables) that the search
    /// would choose stays `base`'s: a scene that asks for a palette, a rounding or a width
    /// gets it, and the search chooses the rest.
    pub fn pin(mut self, base: &PipelineConfig, set: &std::collections::BTreeSet<String>) -> Space {
        let has = |f: &str| set.contains(f);
        self.kept = CHOICES.into_iter().chain(WIDTHS).filter(|f| has(f)).collect();
        if has("power_unit") {
            self.power_units = vec![base.power_unit];
        }
        if has("rounding") {
            self.roundings = vec![base.rounding];
        }
        if has("normal_range") {
            self.normal_ranges = vec![base.normal_range];
        }
        if has("palette") {
            self.palettes = vec![base.palette];
        }
        self.pinned = WIDTHS.into_iter().filter(|f| has(f)).collect();
        self
    }
}

impl Space {
    /// The generous start of every combination of the arithmetic choices.
    fn starts(&self, base: &PipelineConfig) -> Vec<PipelineConfig> {
        let mut out = Vec::new();
        for &kind in &self.power_units {
            for &rounding in &self.roundings {
                for &normal_range in &self.normal_ranges {
                    for &palette in &self.palettes {
                        let mut c = PipelineConfig {
                            rounding,
                            normal_range,
                            palette,
                            ..start(base, kind)
                        };
                        for f in &self.pinned {
                            c = set(&c, f, get(base, f));
                        }
                        out.push(c);
                    }
                }
            }
        }
        out
    }
}

fn get(cfg: &PipelineConfig, field: &str) -> u32 {
    match field {
        "power_entries" => cfg.power_entries.trailing_zeros(),
        f => cfg.get(f),
    }
}

fn set(cfg: &PipelineConfig, field: &str, v: u32) -> PipelineConfig {
    let mut c = cfg.clone();
    match field {
        "power_entries" => c.power_entries = 1 << v,
        "power_segments" => c.power_segments = v,
        "normal_bits" => c.normal_bits = v,
        "lh_bits" => c.lh_bits = v,
        "dot_frac_bits" => c.dot_frac_bits = v,
        "power_frac_bits" => c.power_frac_bits = v,
        "colour_guard_bits" => c.colour_guard_bits = v,
        f => unreachable!("not a searched width: {f}"),
    }
    c
}

fn range(field: &str) -> (u32, u32) {
    match field {
        "power_entries" => {
            let (lo, hi) = limit("power_entries");
            (lo.trailing_zeros(), hi.trailing_zeros())
        }
        f => limit(f),
    }
}

/// The generous start of a search: every width near its top, entries that the widths allow.
pub fn start(base: &PipelineConfig, kind: PowerUnitKind) -> PipelineConfig {
    let mut c = base.clone();
    c.power_unit = kind;
    c.normal_bits = limit("normal_bits").1;
    c.lh_bits = limit("lh_bits").1;
    c.dot_frac_bits = limit("dot_frac_bits").1;
    c.power_frac_bits = limit("power_frac_bits").1;
    c.colour_guard_bits = limit("colour_guard_bits").1;
    match kind {
        PowerUnitKind::Segmented => {
            c.power_segments = limit("power_segments").1.min(c.dot_frac_bits - 1);
            c.power_entries = 256;
        }
        // As many entries as the index has codes: the table is then exact at every input.
        _ => c.power_entries = limit("power_entries").1.min(1 << c.dot_frac_bits),
    }
    // A base of another unit may hold segments this one has none of.
    c.canonical()
}

/// The search's record: every candidate measured, for the front.
pub struct Search<'a> {
    pub eval: &'a mut Evaluator,
    pub area: &'a dyn Fn(&PipelineConfig) -> Result<f64>,
    pub seen: Vec<Candidate>,
}

impl Search<'_> {
    fn note(&mut self, cfg: &PipelineConfig) -> Result<bool> {
        if cfg.validate("fit").is_err() {
            return Ok(false);
        }
        let before = self.eval.evaluations;
        let measured = self.eval.measure(cfg)?;
        let met = self.eval.budget().met(&measured);
        // A configuration measured before is in `seen` already.
        if self.eval.evaluations > before {
            self.seen.push(Candidate {
                cfg: cfg.clone(),
                measured,
                met,
                // Sized as the front is (the area model: microseconds), so front.csv has an
                // area on every row; Yosys confirms only the chosen one (`run`).
                area_ge: (self.area)(cfg)?,
                throughput: 1.0 / cfg.initiation_interval() as f64,
            });
        }
        Ok(met)
    }

    /// The smallest widths from `cfg` that keep the budget, or None when `cfg` misses it.
    /// `pinned` widths stay as they are ([`Space::pinned`]).
    pub fn shrink(&mut self, cfg: PipelineConfig, pinned: &[&str]) -> Result<Option<PipelineConfig>> {
        if !self.note(&cfg)? {
            return Ok(None);
        }
        let mut cfg = cfg;
        let inputs_kept = !self.eval.budget().needs_images();
        for _ in 0..ROUNDS {
            let mut changed = false;
            for field in WIDTHS {
                if field == "power_segments" && cfg.power_unit != PowerUnitKind::Segmented {
                    continue;
                }
                if (inputs_kept && INPUT_WIDTHS.contains(&field)) || pinned.contains(&field) {
                    continue;
                }
                let (lo, _) = range(field);
                let (mut a, mut b) = (lo, get(&cfg, field));
                // b keeps the budget; find the smallest such value, assuming error falls with width.
                while a < b {
                    let mid = (a + b) / 2;
                    if self.note(&set(&cfg, field, mid))? {
                        b = mid;
                    } else {
                        a = mid + 1;
                    }
                }
                if b != get(&cfg, field) {
                    cfg = set(&cfg, field, b);
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        Ok(Some(cfg))
    }

    /// The smallest configuration over `space` that keeps the budget with at least
    /// `min_throughput` fragments per clock; None when nothing does. Each arithmetic choice
    /// shrinks to its own widths (no area needed); a winner whose widths are all at least
    /// another's of the same power unit and palette makes the same or a larger top, so only the
    /// rest are sized by `area`, in the base's light mode and depth (parallel lights only when
    /// the throughput asks for it). Returns the winners sized, for the front.
    pub fn run(&mut self, base: &PipelineConfig, space: &Space, min_throughput: f64) -> Result<(Option<Candidate>, Vec<Candidate>)> {
        let mut winners: Vec<(PipelineConfig, Measured)> = Vec::new();
        let inputs_kept = !self.eval.budget().needs_images();
        for mut c in space.starts(base) {
            if inputs_kept {
                (c.normal_bits, c.lh_bits) = (base.normal_bits, base.lh_bits);
            }
            if let Some(w) = self.shrink(c, &space.pinned)? {
                let m = self.eval.measure(&w)?;
                winners.push((w, m));
            }
        }
        let widths = |c: &PipelineConfig| WIDTHS.map(|f| get(c, f));
        let covers = |a: &PipelineConfig, b: &PipelineConfig| {
            a.power_unit == b.power_unit && a.palette == b.palette && widths(a).iter().zip(widths(b)).all(|(x, y)| *x <= y)
        };
        let mut kept: Vec<&(PipelineConfig, Measured)> = Vec::new();
        for (i, w) in winners.iter().enumerate() {
            let beaten = winners
                .iter()
                .enumerate()
                .any(|(j, o)| j != i && covers(&o.0, &w.0) && (widths(&o.0) != widths(&w.0) || j < i));
            if !beaten {
                kept.push(w);
            }
        }
        let mut sized = Vec::new();
        for (w, measured) in kept {
            let mut c = w.clone();
            if (1.0 / c.initiation_interval() as f64) < min_throughput {
                c.light_mode = LightMode::Parallel;
            }
            let throughput = 1.0 / c.initiation_interval() as f64;
            if throughput < min_throughput || c.validate("fit").is_err() {
                continue;
            }
            sized.push(Candidate {
                area_ge: (self.area)(&c)?,
                cfg: c,
                measured: *measured,
                met: true,
                throughput,
            });
        }
        let best = sized.iter().min_by(|a, b| a.area_ge.total_cmp(&b.area_ge)).cloned();
        Ok((best, sized))
    }
}

/// The candidates no other beats in area, error and throughput at once.
pub fn pareto(cands: &[Candidate], error: impl Fn(&Measured) -> f64) -> Vec<&Candidate> {
    let dominated = |a: &Candidate| {
        cands.iter().any(|b| {
            let (ea, eb) = (error(&a.measured), error(&b.measured));
            b.area_ge <= a.area_ge
                && eb <= ea
                && b.throughput >= a.throughput
                && (b.area_ge < a.area_ge || eb < ea || b.throughput > a.throughput)
        })
    };
    let mut front: Vec<&Candidate> = cands.iter().filter(|a| !dominated(a)).collect();
    front.sort_by(|a, b| a.area_ge.total_cmp(&b.area_ge));
    front
}

#[cfg(test)]
mod tests {
    /// A field a scene's [pipeline] sets is kept: its choice alone is searched, and a pinned
    /// width starts, and stays, at the base's value.
    #[test]
    fn fields_a_scene_sets_are_not_searched() {
        use super::*;
        let base = PipelineConfig {
            rounding: Rounding::Truncate,
            normal_bits: 7,
            ..PipelineConfig::default()
        };
        let set = ["rounding", "normal_bits", "blend_order"].map(String::from).into_iter().collect();
        let space = Space::full(true).pin(&base, &set);
        assert_eq!(space.roundings, vec![Rounding::Truncate]);
        assert_eq!(space.palettes, vec![false, true], "palette is not set, so still searched");
        assert_eq!(space.pinned, vec!["normal_bits"]);
        let starts = space.starts(&base);
        assert!(!starts.is_empty() && starts.iter().all(|c| c.normal_bits == 7 && c.rounding == Rounding::Truncate));
        assert!(
            starts.iter().all(|c| c.lh_bits == limit("lh_bits").1),
            "the other widths start at their top"
        );
    }

    use super::*;
    use crate::fit::budget::Budget;

    /// After the search, every width one step narrower misses the budget: the shrink stops at
    /// the edge, not before it.
    #[test]
    fn shrunk_widths_keep_the_budget_and_one_step_less_misses_it() {
        let mut s = crate::scene::Scene::load("torus_caps").unwrap();
        s.size = [64, 48];
        let base = s.derive_config().unwrap();
        let mut ev = Evaluator::new(vec![s], &base, Budget::Psnr(45.0)).unwrap();
        let area = |c: &PipelineConfig| Ok((c.normal_bits * c.lh_bits + c.dot_frac_bits + c.power_frac_bits) as f64);
        let mut search = Search {
            eval: &mut ev,
            area: &area,
            seen: Vec::new(),
        };
        let w = search
            .shrink(start(&base, PowerUnitKind::Table), &[])
            .unwrap()
            .expect("the generous start meets 45 dB");
        assert!(search.seen.iter().any(|c| !c.met), "the search never probed below the budget");
        let mut edges = 0;
        for field in WIDTHS.into_iter().filter(|f| *f != "power_segments") {
            let v = get(&w, field);
            let narrower = set(&w, field, v - 1);
            if v > range(field).0 && narrower.validate("t").is_ok() {
                edges += 1;
                assert!(!ev.met(&narrower).unwrap(), "{field} = {} still meets the budget", v - 1);
            }
        }
        assert!(edges >= 3, "only {edges} widths could narrow");
        assert!(ev.met(&w).unwrap());
    }
}
