//! Every power-unit design's RTL equals its model for every input code (Icarus), for a small,
//! a middle and the largest 8-bit exponent.

use gbump::measure::power_space::verify_rtl;
use gbump::model::power_unit::{PowerFormats, PowerUnitDesign};

#[test]
fn power_unit_rtl_matches_the_model_exhaustively() {
    let work = tempfile::tempdir().unwrap();
    let designs = [
        PowerUnitDesign::Table {
            entries: 256,
            nearest: true,
        },
        PowerUnitDesign::Table {
            entries: 128,
            nearest: false,
        },
        PowerUnitDesign::Lerp { knots: 64 },
        PowerUnitDesign::Segmented {
            segments: 6,
            per_segment: 16,
            lerp: true,
        },
        PowerUnitDesign::Segmented {
            segments: 4,
            per_segment: 64,
            lerp: false,
        },
        PowerUnitDesign::Segmented {
            segments: 8,
            per_segment: 64,
            lerp: true,
        },
        PowerUnitDesign::Squaring { guard: 6 },
    ];
    for fm in [PowerFormats { f: 8, p: 8 }, PowerFormats { f: 12, p: 8 }] {
        for d in &designs {
            if let PowerUnitDesign::Segmented { segments, .. } = d {
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
