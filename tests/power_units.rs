//! Every power-unit design's RTL equals its model for every input code (Icarus), for a small,
//! a middle and the largest 8-bit exponent.

use gbump::measure::power_space::verify_rtl;
use gbump::model::power_unit::{PowerDesign, PowerFormats};

#[test]
fn power_unit_rtl_matches_the_model_exhaustively() {
    let work = tempfile::tempdir().unwrap();
    let designs = [
        PowerDesign::Table {
            entries: 256,
            nearest: true,
        },
        PowerDesign::Table {
            entries: 128,
            nearest: false,
        },
        PowerDesign::Lerp { knots: 64 },
        PowerDesign::Segmented {
            segments: 6,
            per_segment: 16,
            lerp: true,
        },
        PowerDesign::Segmented {
            segments: 4,
            per_segment: 64,
            lerp: false,
        },
        PowerDesign::Segmented {
            segments: 8,
            per_segment: 64,
            lerp: true,
        },
        PowerDesign::Squaring { guard: 6 },
    ];
    for fm in [PowerFormats { f: 8, p: 8 }, PowerFormats { f: 12, p: 8 }] {
        for d in &designs {
            if let PowerDesign::Segmented { segments, .. } = d {
                if *segments >= fm.f {
                    continue;
                }
            }
            for n in [1, 16, 255] {
                let dir = work.path().join(format!("{}_{n}", gbump::rtlgen::power_units::name(d, fm)));
                let checked = verify_rtl(d, fm, n, &dir).unwrap();
                assert_eq!(checked, (1 << fm.f) + 1);
            }
        }
    }
}
