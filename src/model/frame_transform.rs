//! frame_transform: the fetched bump normal placed in the fragment's frame (Harmony, paper
//! §3.5), `v = T b_x + B b_y + N b_z`. Each component is a sum of three products, exact
//! (the dot products' own format), then one rounding to the normal's format and a clamp
//! to its range: an interpolated frame is not orthonormal, so the sum may leave the unit
//! ball, and the `normalise_b` unit after it (under `renormalise_bump`) scales it back.

use crate::config::PipelineConfig;
use crate::fixed::{requant, Overflow};

/// The frame as it enters with a fragment: T, B and N (`frame[0..3]`), raw `s1.(lh-2)`.
pub type Frame = [[i64; 3]; 3];

/// Component `c` of `T b_x + B b_y + N b_z`, exact, in [`PipelineConfig::dot_exact_fmt`].
#[inline(always)]
pub fn framed_exact(b: [i64; 3], frame: &Frame, c: usize) -> i64 {
    b[0] * frame[0][c] + b[1] * frame[1][c] + b[2] * frame[2][c]
}

/// `b` placed in `frame`, rounded to the normal's format and clamped to its range.
pub fn frame_transform(cfg: &PipelineConfig, b: [i64; 3], frame: &Frame) -> [i64; 3] {
    let (from, to) = (cfg.dot_exact_fmt(), cfg.normal_fmt());
    std::array::from_fn(|c| requant(framed_exact(b, frame, c), from, to, cfg.rounding, Overflow::Saturate))
}

/// [`frame_transform`] without its rounding, in the normal's LSBs (clamped as the unit
/// saturates).
pub fn frame_transform_exact(cfg: &PipelineConfig, b: [i64; 3], frame: &Frame) -> [f64; 3] {
    let (from, to) = (cfg.dot_exact_fmt(), cfg.normal_fmt());
    let scale = 2f64.powi((from.frac - to.frac) as i32);
    std::array::from_fn(|c| (framed_exact(b, frame, c) as f64 / scale).clamp(to.min_raw() as f64, to.max_raw() as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_identity_frame_keeps_the_normal_and_a_turned_one_turns_it() {
        let cfg = PipelineConfig::default();
        let one = 1i64 << (cfg.lh_bits - 2);
        let id = [[one, 0, 0], [0, one, 0], [0, 0, one]];
        for b in [[0, 0, 127], [-128, 5, 90], [127, -128, -128]] {
            assert_eq!(frame_transform(&cfg, b, &id), b);
        }
        // T = y, B = z, N = x: (b_x, b_y, b_z) lands on (b_z, b_x, b_y).
        let turned = [[0, one, 0], [0, 0, one], [one, 0, 0]];
        assert_eq!(frame_transform(&cfg, [10, -20, 100], &turned), [100, 10, -20]);
        // A frame whose axes all lean the same way leaves the unit ball: the sum clamps.
        let lean = [[one; 3], [one; 3], [one; 3]];
        assert_eq!(frame_transform(&cfg, [127, 127, 127], &lean), [127; 3]);
        assert_eq!(frame_transform(&cfg, [-128, -128, -128], &lean), [-128; 3]);
    }
}

#[cfg(test)]
mod identity {
    use crate::config::{BumpStateAt, PipelineConfig};
    use crate::model::{shade, PowerTable};

    /// With the identity frame a top with the unit shades every fragment as the same top
    /// without it, over random configurations and stimuli (the integration notes say so).
    #[test]
    fn the_identity_frame_is_the_bump_space_pipeline() {
        let mut rng = crate::vectors::rng::SplitMix64(0xF8A3E);
        let mut checked = 0;
        for _ in 0..40 {
            let mut cfg = crate::sim::fuzz::random_config(&mut rng);
            cfg.bump_state = BumpStateAt::Fragment;
            cfg.self_shadow = false;
            let plain = PipelineConfig {
                frame_transform: false,
                ..cfg.clone().canonical()
            };
            let framed = PipelineConfig {
                frame_transform: true,
                ..plain.clone()
            };
            if framed.validate("t").is_err() {
                continue;
            }
            let table = PowerTable::build(&plain, plain.shininess);
            let palette = crate::rtlgen::rom::default_palette(&plain);
            let one = 1i64 << (plain.lh_bits - 2);
            for s in crate::vectors::sources::random_chunk(&plain, 0, 0, 300) {
                let mut st = s.state;
                st.frame = [[one, 0, 0], [0, one, 0], [0, 0, one]];
                let a = shade(&plain, &table, Some(&palette), &s.state, &s.frag).colour();
                let b = shade(&framed, &table, Some(&palette), &st, &s.frag).colour();
                assert_eq!(a, b, "{}", framed.to_toml());
                checked += 1;
            }
        }
        assert!(checked > 3000, "{checked}");
    }
}
