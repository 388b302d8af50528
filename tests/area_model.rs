//! The area model (`measure::area_model`) against Yosys: the checked-in samples of
//! `tests/area_model/samples.jsonl` (random valid configurations, from `gbump area-model
//! --configs tests/area_model/configs --write tests/area_model/samples.jsonl`), and one live
//! synthesis.

use gbump::measure::area_model::{calibrate, features, COEFFICIENTS};

#[test]
fn the_checked_in_coefficients_are_the_fit_of_the_calibration_half() {
    // The samples the command fitted on carry `calibration`.
    let fitted: Vec<_> = gbump::measure::area_model::checked_in()
        .into_iter()
        .filter(|s| s.calibration)
        .map(|s| (features(&s.config), s.yosys_ge))
        .collect();
    let got = calibrate(&fitted);
    for (g, c) in got.iter().zip(COEFFICIENTS) {
        assert!((g - c).abs() <= 1e-3 * c.abs().max(1.0), "refit {got:?} against {COEFFICIENTS:?}");
    }
}

/// The held-out accuracy the report states (`area_model::report_section`, from the same samples):
/// today a mean of 55 % and a max of 244 %, far from issue 12's 10 % / 20 %, which is why
/// `gbump fit` sizes its winners with Yosys. This bounds it so that a change to the emitters or
/// the features that makes the model worse is seen.
#[test]
fn held_out_accuracy_is_what_the_report_states() {
    let (mean, max, n) = gbump::measure::area_model::held_out_error(&gbump::measure::area_model::checked_in());
    assert!(n >= 30, "{n} held out");
    assert!(mean <= 0.60 && max <= 2.6, "mean {:.1} %, max {:.1} %", 100.0 * mean, 100.0 * max);
}
