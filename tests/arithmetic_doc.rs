//! The README's arithmetic section ("Number formats": which rounding each narrowing uses, the
//! blend alignment, the flat code, the power units' formulas), checked against the model:
//! each statement an independent implementer relies on fails here if the model drifts.

use gbump::config::{NormalRange, PowerUnitKind};
use gbump::fixed::Rounding;
use gbump::model::power_unit::{power_unit, squarings_exponent};
use gbump::model::{shade, BumpState, BumpTexel, FragmentIn, PowerTable};
use gbump::PipelineConfig;

const ROUNDINGS: [Rounding; 3] = [Rounding::Truncate, Rounding::HalfUp, Rounding::NearestEven];

fn with(base: &PipelineConfig, r: Rounding) -> PipelineConfig {
    PipelineConfig {
        rounding: r,
        ..base.clone()
    }
}

fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap()
}

/// Every power unit design, its table and its interpolation: the same fs under every
/// `rounding`, for every input code and a spread of shininesses.
#[test]
fn power_units_round_half_up_whatever_rounding_says() {
    for kind in [
        PowerUnitKind::Table,
        PowerUnitKind::Lerp,
        PowerUnitKind::Segmented,
        PowerUnitKind::Squaring,
    ] {
        let base = PipelineConfig {
            power_unit: kind,
            power_entries: if kind == PowerUnitKind::Segmented { 8 } else { 64 },
            power_segments: 4,
            ..PipelineConfig::default()
        };
        for n in [1, 2, 5, 16, 23, 40] {
            let outs: Vec<Vec<i64>> = ROUNDINGS
                .iter()
                .map(|&r| {
                    let cfg = with(&base, r);
                    let table = PowerTable::build(&cfg, n);
                    (0..=1i64 << cfg.dot_frac_bits).map(|x| power_unit(&cfg, &table, x)).collect()
                })
                .collect();
            assert!(outs.windows(2).all(|w| w[0] == w[1]), "{kind:?} n = {n}: fs depends on `rounding`");
        }
    }
}

/// The texture modulation alone (both blends off): C_src · T the same under every rounding,
/// with and without guard bits, on a grid of codes.
#[test]
fn texture_modulation_ignores_rounding_and_blends_follow_it() {
    for g in [0, 2] {
        let base = PipelineConfig {
            colour_guard_bits: g,
            ..PipelineConfig::default()
        };
        let cfgs: Vec<PipelineConfig> = ROUNDINGS.iter().map(|&r| with(&base, r)).collect();
        let tables: Vec<PowerTable> = cfgs.iter().map(|c| PowerTable::build(c, c.shininess)).collect();
        let state = BumpState::default();
        for c in (0..256u32).step_by(3) {
            for t in (0..256u32).step_by(5) {
                let frag = FragmentIn {
                    bump: BumpTexel::Rgb([128, 128, 255]),
                    c_src: [c, 255 - c, c / 2],
                    tex: [t, t / 3, 255 - t],
                    diffuse_en: false,
                    specular_en: false,
                };
                // The texture stage's own output (stage 1 of diffuse, texture, specular): the
                // last step to colour codes (`colour_round`, g > 0) follows `rounding`.
                let outs: Vec<[u32; 3]> = cfgs
                    .iter()
                    .zip(&tables)
                    .map(|(cfg, tb)| shade(cfg, tb, None, &state, &frag).stages[1])
                    .collect();
                assert!(outs.windows(2).all(|w| w[0] == w[1]), "g = {g}, c = {c}, t = {t}: {outs:?}");
            }
        }
    }
    // The blends' one rounding does follow it: a lit fragment differs somewhere.
    let cfgs: Vec<PipelineConfig> = ROUNDINGS.iter().map(|&r| with(&PipelineConfig::default(), r)).collect();
    let mut differs = false;
    for x in 0..200u32 {
        let mut state = BumpState::default();
        state.lights[0].l = [0, 0, 1 << 14];
        state.lights[0].h = [0, 0, 1 << 14];
        state.lights[0].lc = [255, 200, 100];
        state.lights[0].k = 1 << PipelineConfig::default().k_frac_bits;
        let frag = FragmentIn {
            bump: BumpTexel::Rgb([128 + x % 40, 128 - x % 30, 200 + x % 55]),
            c_src: [10, 20, 30],
            tex: [255; 3],
            diffuse_en: true,
            specular_en: true,
        };
        let outs: Vec<[u32; 3]> = cfgs
            .iter()
            .map(|c| shade(c, &PowerTable::build(c, c.shininess), None, &state, &frag).colour())
            .collect();
        differs |= outs[0] != outs[1];
    }
    assert!(differs, "truncate and half up give the same colours: the blends ignore `rounding`");
}

/// The squaring unit's exponent is nearest on a log scale, as the README's examples say.
#[test]
fn the_squaring_exponent_is_nearest_on_a_log_scale() {
    for (n, e) in [(0, 0), (1, 1), (3, 4), (8, 8), (20, 16), (22, 16), (23, 32), (45, 32), (46, 64)] {
        assert_eq!(squarings_exponent(n), e, "n = {n}");
    }
    let text = readme();
    assert!(text.contains("20 → 16, 23 → 32, 45 → 32, 46 → 64"), "the README's examples changed");
    // n = 0 gives 1 everywhere; n = 1 gives x re-rounded to P bits through W = P + 4.
    let cfg = PipelineConfig {
        power_unit: PowerUnitKind::Squaring,
        ..PipelineConfig::default()
    };
    let (f, p) = (cfg.dot_frac_bits, cfg.power_frac_bits);
    let r = |v: i64, sh: u32| (v + (1 << (sh - 1))) >> sh;
    for x in 0..=1i64 << f {
        assert_eq!(power_unit(&cfg, &PowerTable::build(&cfg, 0), x), 1 << p);
        let w = p + 4;
        let xw = r(x << w, f);
        assert_eq!(power_unit(&cfg, &PowerTable::build(&cfg, 1), x), r(xw, 4), "x = {x}");
    }
}

/// fd and fs are aligned to max(dot_frac_bits, power_frac_bits); the sum keeps A + K bits.
#[test]
fn blend_factors_are_aligned_to_the_wider_fraction() {
    for (d, p) in [(8, 8), (10, 7), (6, 12)] {
        let cfg = PipelineConfig {
            dot_frac_bits: d,
            power_frac_bits: p,
            ..PipelineConfig::default()
        };
        assert_eq!(cfg.factor_frac(), d.max(p));
        assert_eq!(cfg.acc_fmt().frac, d.max(p) + cfg.k_frac_bits, "d = {d}, p = {p}");
    }
}

/// The flat code is (2^(w-1), 2^(w-1), 2^w - 1) in either normal range, and under skip_flat
/// it gives C_src · T whatever the lights.
#[test]
fn the_flat_code_is_the_one_the_readme_gives() {
    for range in [NormalRange::Binary, NormalRange::Symmetric] {
        let cfg = PipelineConfig {
            normal_range: range,
            skip_flat: true,
            ..PipelineConfig::default()
        };
        let w = cfg.normal_bits;
        let flat = [1u32 << (w - 1), 1 << (w - 1), (1 << w) - 1];
        assert_eq!(gbump::model::bump_fetch::bump_fetch_rgb(&cfg, flat), cfg.flat_normal(), "{range:?}");
        let mut state = BumpState::default();
        for s in state.lights.iter_mut().take(cfg.lights as usize) {
            (s.l, s.h, s.lc, s.k) = ([0, 0, 1 << 14], [0, 0, 1 << 14], [255; 3], 1 << cfg.k_frac_bits);
        }
        let frag = FragmentIn {
            bump: BumpTexel::Rgb(flat),
            c_src: [100, 50, 25],
            tex: [255, 128, 0],
            diffuse_en: true,
            specular_en: true,
        };
        let table = PowerTable::build(&cfg, cfg.shininess);
        let want = gbump::model::texture_modulate::texture_modulate(&cfg, frag.c_src, frag.tex);
        assert_eq!(shade(&cfg, &table, None, &state, &frag).colour(), want, "{range:?}");
    }
}

/// The segmented table holds S (M + 1) knots, as the README and the ROM header say.
#[test]
fn a_segmented_table_holds_its_knots() {
    let cfg = PipelineConfig {
        power_unit: PowerUnitKind::Segmented,
        power_segments: 6,
        power_entries: 16,
        ..PipelineConfig::default()
    };
    let t = PowerTable::build(&cfg, 16);
    assert_eq!(t.entries.len(), 6 * 17);
    let header = gbump::rtlgen::rom::power_rom(&cfg, 16).layout;
    assert!(header.contains("6 segments of 17 knots"), "{header}");
}

/// dot_clamp's corner catalogue holds exact rounding ties, so every corner set tells the three
/// roundings apart at the dot product (random stimuli hit a tie about once in 20 000).
#[test]
fn the_dot_corners_hold_rounding_ties() {
    for (nb, lh, d) in [(8, 16, 8), (6, 12, 10), (10, 10, 12)] {
        let base = PipelineConfig {
            normal_bits: nb,
            lh_bits: lh,
            dot_frac_bits: d,
            ..PipelineConfig::default()
        };
        let unit = gbump::units::unit("dot_clamp").unwrap();
        let ties: Vec<_> = unit.corners(&base).into_iter().filter(|c| c.0.contains("rounding tie")).collect();
        assert_eq!(ties.len(), 2, "nb {nb} lh {lh} d {d}");
        for (name, lanes) in ties {
            let got: Vec<i64> = ROUNDINGS
                .iter()
                .map(|&r| {
                    let b: [i64; 3] = lanes[0].clone().try_into().unwrap();
                    let v: [i64; 3] = lanes[1].clone().try_into().unwrap();
                    gbump::model::dot_clamp::dot_clamp(&with(&base, r), b, v)
                })
                .collect();
            let want = if name.contains("1/2") { [0, 1, 0] } else { [1, 2, 2] };
            assert_eq!(got, want, "{name}: truncate, half up, nearest even");
        }
    }
}

/// The top's corner set holds the same two ties on B·L, and where an fd LSB is worth a colour
/// LSB or more (`dot_frac_bits <= colour_bits`; finer ties round away in the blend) its
/// colours tell the three roundings apart, so a corner regression alone catches a top built
/// for another `rounding`.
#[test]
fn the_top_corners_tell_the_three_roundings_apart() {
    for (nb, lh, d, lights) in [(8, 16, 8, 4), (6, 12, 6, 1), (10, 10, 4, 2), (16, 24, 8, 1), (3, 4, 2, 1)] {
        let base = PipelineConfig {
            normal_bits: nb,
            lh_bits: lh,
            dot_frac_bits: d,
            lights,
            ..PipelineConfig::default()
        };
        let ties: Vec<_> = gbump::vectors::sources::corners(&base, 1)
            .into_iter()
            .filter(|c| c.0.contains("rounding tie"))
            .collect();
        assert_eq!(
            ties.len(),
            2,
            "nb {nb} lh {lh} d {d}: {:?}",
            ties.iter().map(|t| &t.0).collect::<Vec<_>>()
        );
        let colours: Vec<Vec<[u32; 3]>> = ROUNDINGS
            .iter()
            .map(|&r| {
                let cfg = with(&base, r);
                let table = PowerTable::build(&cfg, cfg.shininess);
                ties.iter()
                    .map(|(_, s)| shade(&cfg, &table, None, &s.state, &s.frag).colour())
                    .collect()
            })
            .collect();
        assert!(
            colours[0] != colours[1] && colours[1] != colours[2] && colours[0] != colours[2],
            "nb {nb} lh {lh} d {d}: truncate, half up, nearest even give {colours:?}"
        );
    }
}
