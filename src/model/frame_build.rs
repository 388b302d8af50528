//! frame_build: TexRam's frame, built per fragment (paper §3.1) from the interpolated normal
//! N_i and the main direction m: N = N_i/|N_i|, e1 = m×N/|m×N|, e2 = N×e1. gbump's axes
//! are B = −e1 and T = e2, so `T b_x + B b_y + N b_z` keeps the map's handedness (B along
//! +v for a right-handed (T, B, N)); B is formed as N×m, whose rounding is exact where
//! −(m×N) would round the other way at a tie, and T as B×N (= N×e1).
//!
//! Each axis is `s1.(lh-2)` at plain unit length ([`Shape::frame`]): N and B by the
//! normalise unit's arithmetic, each cross product exact then one rounding to the format and
//! a clamp to its range. A main direction along N, or a zero N_i, gives zero axes (the
//! normalise unit keeps zero at zero): the bump normal then lands on N b_z, or on zero.

use super::frame_transform::Frame;
use super::normalise::{normalise_exact_shape, normalise_shape, Shape};
use crate::config::PipelineConfig;
use crate::fixed::{requant, Format, Overflow};

/// The exact cross product's format: two `s1.(lh-2)` products and their difference.
pub fn cross_exact_fmt(cfg: &PipelineConfig) -> Format {
    let f = cfg.lh_fmt();
    Format::s(2 * f.width + 1, 2 * f.frac)
}

/// Component `c` of `a × b`, exact, in [`cross_exact_fmt`].
#[inline(always)]
pub fn cross_exact(a: [i64; 3], b: [i64; 3], c: usize) -> i64 {
    let (i, j) = ((c + 1) % 3, (c + 2) % 3);
    a[i] * b[j] - a[j] * b[i]
}

/// `a × b` rounded to `s1.(lh-2)` and clamped to its range.
pub fn cross(cfg: &PipelineConfig, a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    let (from, to) = (cross_exact_fmt(cfg), cfg.lh_fmt());
    std::array::from_fn(|c| requant(cross_exact(a, b, c), from, to, cfg.rounding, Overflow::Saturate))
}

/// The frame (T, B, N) built from the main direction `m` and the interpolated normal `n_i`
/// (raw `s1.(lh-2)`), as the unit computes it.
pub fn frame_build(cfg: &PipelineConfig, m: [i64; 3], n_i: [i64; 3]) -> Frame {
    let shape = Shape::frame(cfg);
    let n = normalise_shape(&shape, n_i);
    let b = normalise_shape(&shape, cross(cfg, n, m));
    let t = cross(cfg, b, n);
    [t, b, n]
}

/// The same in f64 without roundings, in `s1.(lh-2)` LSBs: the frame an exact unit would
/// build from the same codes.
pub fn frame_build_exact(cfg: &PipelineConfig, m: [i64; 3], n_i: [i64; 3]) -> [[f64; 3]; 3] {
    let shape = Shape::frame(cfg);
    let one = (shape.frac as f64).exp2();
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if l == 0.0 {
            [0.0; 3]
        } else {
            v.map(|x| x / l)
        }
    };
    let cross = |a: [f64; 3], b: [f64; 3]| -> [f64; 3] {
        std::array::from_fn(|c| {
            let (i, j) = ((c + 1) % 3, (c + 2) % 3);
            a[i] * b[j] - a[j] * b[i]
        })
    };
    let n = normalise_exact_shape(&shape, n_i).map(|x| x / one);
    // N × m clamped to the format's range, as the unit's rounding saturates (an m longer
    // than 2 can leave it).
    let f = cfg.lh_fmt();
    let b = unit(cross(n, m.map(|x| x as f64 / one)).map(|x| x.clamp(f.min_raw() as f64 / one, f.max_raw() as f64 / one)));
    let t = cross(b, n);
    [t, b, n].map(|v| v.map(|x| x * one))
}

/// The frame a fragment's state carries into `frame_transform`: built from its T and N lanes
/// under `frame_build`, from its quaternion and normal lanes under `frame_quaternion`, else
/// the state's own.
pub fn fragment_frame(cfg: &PipelineConfig, state: &Frame) -> Frame {
    if cfg.frame_build {
        frame_build(cfg, state[0], state[2])
    } else if cfg.frame_quaternion {
        let (q, n_i) = super::quat_frame::lanes(state);
        super::quat_frame::quat_frame(cfg, q, n_i)
    } else {
        *state
    }
}

/// [`fragment_frame`] without the roundings of a unit that forms it, in `s1.(lh-2)` LSBs:
/// None when the state's frame enters as it is.
pub fn fragment_frame_exact(cfg: &PipelineConfig, state: &Frame) -> Option<[[f64; 3]; 3]> {
    if cfg.frame_build {
        Some(frame_build_exact(cfg, state[0], state[2]))
    } else if cfg.frame_quaternion {
        let (q, n_i) = super::quat_frame::lanes(state);
        Some(super::quat_frame::quat_frame_exact(cfg, q, n_i))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_is_orthonormal_and_follows_the_main_direction() {
        let cfg = PipelineConfig::default();
        let one = 1i64 << (cfg.lh_bits - 2);
        // m along x, N along z, both shortened: the identity frame.
        assert_eq!(
            frame_build(&cfg, [one * 7 / 10, 0, 0], [0, 0, one * 8 / 10]),
            [[one, 0, 0], [0, one, 0], [0, 0, one]]
        );
        // A main direction leaning towards N: T is its part perpendicular to N.
        assert_eq!(frame_build(&cfg, [one / 2, 0, one / 2], [0, 0, one])[0], [one, 0, 0]);
        // m along N: no direction perpendicular to N, zero axes; a zero N: all zero.
        assert_eq!(frame_build(&cfg, [0, 0, one], [0, 0, one]), [[0; 3], [0; 3], [0, 0, one]]);
        assert_eq!(frame_build(&cfg, [one, 0, 0], [0; 3]), [[0; 3]; 3]);
        // Random directions: within a few LSBs of the exact frame, and right-handed.
        let mut rng = crate::vectors::rng::SplitMix64(0xF3A3E);
        let mut worst = 0f64;
        for _ in 0..20_000 {
            let r = |rng: &mut crate::vectors::rng::SplitMix64| std::array::from_fn(|_| (rng.next_u64() % (2 * one as u64)) as i64 - one);
            let (m, n) = (r(&mut rng), r(&mut rng));
            let got = frame_build(&cfg, m, n);
            let want = frame_build_exact(&cfg, m, n);
            // The axes' error grows as m turns towards N: B's direction is that of N × m,
            // whose rounding and whose N's error are divided by |N × m|. Scaled by that
            // length (|m| up to √3 here) the error is bounded.
            let len = |v: [i64; 3]| (v.iter().map(|&x| (x as f64).powi(2)).sum::<f64>()).sqrt();
            let nm = len(std::array::from_fn(|c| cross_exact(n, m, c))) / (len(n) * one as f64);
            if nm < 1.0 / 64.0 {
                continue; // m within a degree of N: no direction to speak of
            }
            for v in 0..3 {
                for c in 0..3 {
                    worst = worst.max((got[v][c] as f64 - want[v][c]).abs() * nm.min(1.0));
                }
            }
            let tb = [
                cross_exact(got[0], got[1], 0),
                cross_exact(got[0], got[1], 1),
                cross_exact(got[0], got[1], 2),
            ];
            for c in 0..3 {
                let off = (tb[c] as f64 / one as f64 - got[2][c] as f64).abs() * nm.min(1.0);
                assert!(off < 8.0, "T×B = N: {tb:?} {got:?}");
            }
        }
        assert!(worst < 3.0, "{worst}");
        assert!(worst > 0.25, "{worst}");
    }
}
