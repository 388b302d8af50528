//! `gbump fit-table`: every built-in scene under each of the report's budgets, the scene's
//! default configuration (`gbump config --scene`) against the configuration `gbump fit`
//! chooses, by the area model and by the budget's own measure (docs/REPORT.md).

use super::budget::{Budget, Measured};
use super::evaluate::Evaluator;
use crate::config::PipelineConfig;
use crate::error::Result;
use crate::scene::Scene;

/// The budgets of the table: issue 12's three.
pub const BUDGETS: [&str; 3] = ["max<=2", "psnr>=50", "exact<=1"];

/// One scene under one budget.
pub struct Row {
    pub scene: String,
    pub budget: Budget,
    pub default: (PipelineConfig, Measured),
    /// The fitted configuration and its measure, or why there is none.
    pub fitted: std::result::Result<(PipelineConfig, Measured), String>,
}

/// `scenes` (built-in names or files; empty: every built-in scene) under every budget of
/// [`BUDGETS`] (no regression: `gbump fit` runs it). Every scene is loaded before the first
/// fit, so a wrong name fails at once.
pub fn rows(scenes: &[String], say: &mut dyn FnMut(&str)) -> Result<Vec<Row>> {
    let area = |c: &PipelineConfig| Ok(crate::measure::area_model::estimate(c));
    let names: Vec<String> = if scenes.is_empty() {
        crate::scene::builtin::ALL.iter().map(|(n, _)| n.to_string()).collect()
    } else {
        scenes.to_vec()
    };
    for name in &names {
        Scene::load(name)?;
    }
    let mut out = Vec::new();
    let total = names.len() * BUDGETS.len();
    let t0 = std::time::Instant::now();
    for name in &names {
        let name = name.as_str();
        for b in BUDGETS {
            let budget = Budget::parse(b)?;
            let scene = Scene::load(name)?;
            let default = scene.derive_config()?;
            let measured = Evaluator::new(vec![scene], &default, budget)?.measure(&default)?;
            let fitted = match super::run::fit(&[name.to_string()], budget, 0.0, &area) {
                Ok(f) => Ok((f.chosen.cfg, f.chosen.measured)),
                // Only "nothing meets the budget" is a row; any other failure stops the table.
                Err(crate::error::Error::Other(m)) if m.starts_with("no configuration") => {
                    Err(m.lines().next().unwrap_or_default().to_string())
                }
                Err(e) => return Err(e),
            };
            // A counter and the time so far: the table takes minutes (a fit per row).
            say(&format!(
                "[{}/{total}] {name} {budget}: {} ({:.0} s)",
                out.len() + 1,
                if fitted.is_ok() { "fitted" } else { "none meets it" },
                t0.elapsed().as_secs_f64()
            ));
            out.push(Row {
                scene: name.to_string(),
                budget,
                default: (default, measured),
                fitted,
            });
        }
    }
    Ok(out)
}

fn measure(b: Budget, m: &Measured) -> String {
    match b {
        Budget::Max(_) => format!("{:.2} LSB", m.max_lsb),
        Budget::Psnr(_) => format!("{:.2} dB", m.psnr_db),
        Budget::Exact(_) => format!("{:.3} LSB", m.exact_lsb),
    }
}

fn widths(c: &PipelineConfig) -> String {
    let unit = match c.power_unit {
        crate::config::PowerUnitKind::Segmented => format!("segmented {}x{}", c.power_segments, c.power_entries),
        k => format!("{k:?} {}", c.power_entries).to_lowercase(),
    };
    format!(
        "{unit}, n{} lh{} f{} p{} g{}, {}, {}",
        c.normal_bits,
        c.lh_bits,
        c.dot_frac_bits,
        c.power_frac_bits,
        c.colour_guard_bits,
        format!("{:?}", c.rounding).to_lowercase(),
        format!("{:?}", c.normal_range).to_lowercase()
    )
}

/// The table, with the 127/128 loss of each configuration (`unit_error::flat_highlight_loss`).
pub fn markdown(rows: &[Row]) -> String {
    use crate::measure::area_model::estimate;
    use crate::measure::unit_error::flat_highlight_loss;
    let mut s = String::from("| scene | budget | default GE | default error | fitted GE | fitted error | fitted: power unit (segments x entries), normal, L/H, dot and power fraction bits, colour guard bits, rounding, normal range | 127/128 loss default → fitted |\n|---|---|---:|---:|---:|---:|---|---|\n");
    for r in rows {
        let (dc, dm) = &r.default;
        let (fge, fe, fw, loss) = match &r.fitted {
            Ok((c, m)) => (
                format!("{:.0}", estimate(c)),
                measure(r.budget, m),
                widths(c),
                format!("{:.2} → {:.2} LSB", flat_highlight_loss(dc), flat_highlight_loss(c)),
            ),
            Err(why) => ("—".into(), "—".into(), why.clone(), format!("{:.2} LSB", flat_highlight_loss(dc))),
        };
        s += &format!(
            "| {} | `{}` | {:.0} | {} | {fge} | {fe} | {fw} | {loss} |\n",
            r.scene,
            r.budget,
            estimate(dc),
            measure(r.budget, dm)
        );
    }
    s
}

/// The report's section: what the table compares and how to reproduce it, then the table.
pub fn section(say: &mut dyn FnMut(&str)) -> Result<String> {
    let rows = rows(&[], say)?;
    Ok(format!(
        "`gbump fit-table` (each row is `gbump fit --scene S --budget B --no-regress`; `gbump fit` also regresses its choice on both simulators). Areas are the area model's (logic GE, RAM bits apart); errors are the budget's own measure: max and PSNR of the golden image against the f64 Gouraud image, exact = the pipeline against exact arithmetic on random stored inputs. The 127/128 loss is the flat normal's highlight under H straight above, in colour LSBs (`normal_range = \"binary\"` stores +1.0 as 127/128 at 8 bits; `\"symmetric\"` stores +1.0 and sends L, H times 128/127 per triangle, at no per-fragment cost).\n\n{}",
        markdown(&rows)
    ))
}
