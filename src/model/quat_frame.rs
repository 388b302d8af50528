//! quat_frame: VISA+'s alignment matrix from an interpolated vertex quaternion (paper §3.2
//! and its [5]), `N' = N + A·V` with A's columns the rotation's T and B and N the
//! interpolated normal N_i. T and B are the rotation's first two columns in the homogeneous
//! form, each entry a sum of the quaternion's ten products, `T = (w²+x²−y²−z², 2(xy+wz),
//! 2(xz−wy))`, `B = (2(xy−wz), w²−x²+y²−z², 2(yz+wx))`: an interpolated quaternion is shorter
//! than unit, and the homogeneous form gives `|q|²` times the rotation of `q/|q|`, so N_i is
//! scaled by the same `|q|² = w²+x²+y²+z²` and every axis carries one factor, which the
//! `normalise_b` unit after the transform removes: no quaternion normalisation, no division.
//! Each entry of T and B is exact, then one rounding to `s1.(lh-2)` and a clamp; `|q|²` is
//! rounded to `s?.(lh-2)` (wide enough for any codes), its products with N_i rounded once more
//! and clamped.

use super::frame_transform::Frame;
use crate::config::PipelineConfig;
use crate::fixed::{requant, Format, Overflow};

/// The exact entries' format: sums of four `s1.(lh-2)` products, doubled.
pub fn entry_exact_fmt(cfg: &PipelineConfig) -> Format {
    let f = cfg.lh_fmt();
    Format::s(2 * f.width + 3, 2 * f.frac)
}

/// The frame's entries `[axis][component]`, exact, for `q = (w, x, y, z)` in any number
/// type (the model's integers, the f64 equations).
pub fn homogeneous<T>(q: [T; 4]) -> [[T; 3]; 3]
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Sub<Output = T> + std::ops::Mul<Output = T>,
{
    let [w, x, y, z] = q;
    let two = |a: T| a + a;
    [
        [w * w + x * x - y * y - z * z, two(x * y + w * z), two(x * z - w * y)],
        [two(x * y - w * z), w * w - x * x + y * y - z * z, two(y * z + w * x)],
        [two(x * z + w * y), two(y * z - w * x), w * w - x * x - y * y + z * z],
    ]
}

/// `|q|²` rounded: `s?.(lh-2)` with room for the largest codes (16 in real units).
pub fn length2_fmt(cfg: &PipelineConfig) -> Format {
    Format::s(cfg.lh_bits + 4, cfg.lh_bits - 2)
}

/// `|q|²` times a component of N_i, exact.
pub fn scaled_exact_fmt(cfg: &PipelineConfig) -> Format {
    let (a, b) = (length2_fmt(cfg), cfg.lh_fmt());
    Format::s(a.width + b.width, a.frac + b.frac)
}

/// `w² + x² + y² + z²`, rounded to [`length2_fmt`].
pub fn length2(cfg: &PipelineConfig, q: [i64; 4]) -> i64 {
    let s: i64 = q.iter().map(|&x| x * x).sum();
    requant(s, entry_exact_fmt(cfg), length2_fmt(cfg), cfg.rounding, Overflow::Saturate)
}

/// The frame (T, B, |q|² N_i) of `q` (raw `s1.(lh-2)` lanes w, x, y, z) and `n_i`, as the
/// unit computes it.
pub fn quat_frame(cfg: &PipelineConfig, q: [i64; 4], n_i: [i64; 3]) -> Frame {
    let (from, to) = (entry_exact_fmt(cfg), cfg.lh_fmt());
    let h = homogeneous(q);
    let s = length2(cfg, q);
    let round = |e: i64| requant(e, from, to, cfg.rounding, Overflow::Saturate);
    [
        h[0].map(round),
        h[1].map(round),
        n_i.map(|x| requant(s * x, scaled_exact_fmt(cfg), to, cfg.rounding, Overflow::Saturate)),
    ]
}

/// The same without the roundings, in `s1.(lh-2)` LSBs (clamped as the unit saturates).
pub fn quat_frame_exact(cfg: &PipelineConfig, q: [i64; 4], n_i: [i64; 3]) -> [[f64; 3]; 3] {
    let (from, to) = (entry_exact_fmt(cfg), cfg.lh_fmt());
    let scale = ((from.frac - to.frac) as f64).exp2();
    let clamp = |x: f64| x.clamp(to.min_raw() as f64, to.max_raw() as f64);
    let h = homogeneous(q).map(|v| v.map(|e| e as f64 / scale));
    let s: f64 = q.iter().map(|&x| (x as f64).powi(2)).sum::<f64>() / scale / (to.frac as f64).exp2();
    [h[0].map(clamp), h[1].map(clamp), n_i.map(|x| clamp(s * x as f64))]
}

/// The quaternion lanes of a fragment's frame port (w, x, y, z at lanes 0 to 3) and its
/// normal lanes (N_i at lanes 6 to 8).
pub fn lanes(frame: &Frame) -> ([i64; 4], [i64; 3]) {
    ([frame[0][0], frame[0][1], frame[0][2], frame[1][0]], frame[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quaternions_give_their_rotations_scaled_by_their_squared_length() {
        let cfg = PipelineConfig::default();
        let one = 1i64 << (cfg.lh_bits - 2);
        let id = [[one, 0, 0], [0, one, 0], [0, 0, one]];
        let z = [0, 0, one];
        assert_eq!(quat_frame(&cfg, [one, 0, 0, 0], z), id);
        assert_eq!(quat_frame(&cfg, [-one, 0, 0, 0], z), id);
        // 180° about x: T stays, B turns over; N is the normal given.
        assert_eq!(quat_frame(&cfg, [0, one, 0, 0], z), [[one, 0, 0], [0, -one, 0], [0, 0, one]]);
        // 90° about z, at 70 % length: T = y, B = −x, and N, all times 0.49.
        let h = one * 7 / 10;
        let s = (h as f64 / 2f64.sqrt()).round() as i64;
        let f = quat_frame(&cfg, [s, 0, 0, s], z);
        let l = (2 * s * s) as f64 / one as f64;
        for (got, want) in [(f[0][1], l), (f[1][0], -l), (f[2][2], l), (f[0][0], 0.0)] {
            assert!((got as f64 - want).abs() <= 1.0, "{f:?}");
        }
        // Within an LSB or so of the exact frame over random codes.
        let mut rng = crate::vectors::rng::SplitMix64(0x0A7);
        for _ in 0..10_000 {
            let mut r = || (rng.next_u64() % (2 * one as u64)) as i64 - one;
            let (q, n) = ([r(), r(), r(), r()], [r(), r(), r()]);
            let (got, want) = (quat_frame(&cfg, q, n), quat_frame_exact(&cfg, q, n));
            for v in 0..3 {
                for c in 0..3 {
                    // N: two roundings, |q|² rounded then times an N_i component of at most 1.0 here.
                    let bound = if v == 2 { 1.0 + 1e-9 } else { 0.5 };
                    assert!((got[v][c] as f64 - want[v][c]).abs() <= bound, "{q:?} {n:?}: {got:?} {want:?}");
                }
            }
        }
        // The f64 form agrees with glam's rotation of the normalised quaternion.
        let q = glam::DQuat::from_xyzw(0.3, -0.2, 0.5, 0.7);
        let m = glam::DMat3::from_quat(q.normalize());
        let e = homogeneous([q.w, q.x, q.y, q.z]);
        let len2 = q.length_squared();
        for (axis, col) in [m.x_axis, m.y_axis, m.z_axis].iter().enumerate() {
            for c in 0..3 {
                assert!((e[axis][c] / len2 - col[c]).abs() < 1e-12);
            }
        }
    }
}
