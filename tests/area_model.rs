//! The area model (`measure::area_model`) against Yosys: the checked-in samples of
//! `tests/area_model/samples.jsonl` (random valid configurations, each top and each unit
//! synthesised alone, from `gbump area-model --configs tests/area_model/configs --write
//! tests/area_model/samples.jsonl`).

use gbump::measure::area_model::{calibrate, checked_in, held_out_error, COEFFICIENTS};

#[test]
fn the_checked_in_coefficients_are_the_fit_of_the_calibration_part() {
    let rows: Vec<_> = checked_in().into_iter().filter(|s| s.calibration).flat_map(|s| s.rows()).collect();
    assert!(rows.len() > 60, "{} calibration rows: the samples lost their units", rows.len());
    let got = calibrate(&rows);
    for (g, c) in got.iter().zip(COEFFICIENTS) {
        assert!((g - c).abs() <= 1e-6 * c.abs().max(1.0), "refit {got:?} against {COEFFICIENTS:?}");
    }
    // Every weight is a cost: a negative one would rank a design with more logic as smaller.
    assert!(COEFFICIENTS.iter().all(|&c| c > 0.0), "{COEFFICIENTS:?}");
}

/// The held-out accuracy the report states (`area_model::report_section`, from the same
/// samples): issue 12 asks for a mean within 10 % and a maximum within 20 %.
#[test]
fn held_out_accuracy_is_what_the_report_states() {
    let (mean, max, n) = held_out_error(&checked_in());
    assert!(n >= 30, "{n} held out");
    assert!(mean <= 0.10 && max <= 0.20, "mean {:.1} %, max {:.1} %", 100.0 * mean, 100.0 * max);
}

/// Ranking is what the search uses the model for: over the held-out tops, a pair the model
/// orders one way is ordered the same way by Yosys at least 90 % of the time.
#[test]
fn the_model_orders_held_out_tops_as_yosys_does() {
    let s: Vec<_> = checked_in().into_iter().filter(|s| !s.calibration).collect();
    let (mut agree, mut pairs) = (0, 0);
    for a in &s {
        for b in &s {
            if a.file < b.file {
                pairs += 1;
                if (a.model_ge < b.model_ge) == (a.yosys_ge < b.yosys_ge) {
                    agree += 1;
                }
            }
        }
    }
    let share = agree as f64 / pairs as f64;
    assert!(
        share >= 0.9,
        "{agree} of {pairs} pairs ordered as Yosys orders them ({:.1} %)",
        100.0 * share
    );
}
