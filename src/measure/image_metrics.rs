//! Image error of the golden image against an f64 image, in colour LSBs, over covered pixels
//! (the background is the same in every image and would only flatter the figures).

use serde::Serialize;

#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct ImageError {
    /// Peak signal-to-noise ratio in dB: infinite when identical, which JSON cannot hold, so
    /// a report writes it as `null` beside `identical: true`.
    pub psnr_db: f64,
    /// Whether every covered pixel is equal (no difference at all).
    pub identical: bool,
    /// Largest per-channel error, in LSBs of the colour format.
    pub max_lsb: f64,
    pub mean_lsb: f64,
    /// Share of covered pixels with any channel off by more than 1 LSB.
    pub over_1lsb: f64,
    pub pixels: usize,
}

/// Per-pixel largest channel error in LSBs (0 for uncovered pixels).
pub fn error_map(golden: &[[u32; 3]], other: &[[f64; 3]], covered: &[bool], max: u32) -> Vec<f64> {
    golden
        .iter()
        .zip(other)
        .zip(covered)
        .map(|((g, o), c)| {
            if *c {
                (0..3)
                    .map(|i| (g[i] as f64 - o[i].clamp(0.0, 1.0) * max as f64).abs())
                    .fold(0.0, f64::max)
            } else {
                0.0
            }
        })
        .collect()
}

pub fn compare(golden: &[[u32; 3]], other: &[[f64; 3]], covered: &[bool], max: u32) -> ImageError {
    let diffs = golden
        .iter()
        .zip(other)
        .zip(covered)
        .filter(|(_, c)| **c)
        .map(|((g, o), _)| [0, 1, 2].map(|i| g[i] as f64 - o[i].clamp(0.0, 1.0) * max as f64));
    stats(diffs, max as f64)
}

/// The figures of per-pixel channel differences `diffs` (in LSBs of a format whose largest
/// code is `max`), one item per covered pixel.
pub fn stats(diffs: impl Iterator<Item = [f64; 3]>, max: f64) -> ImageError {
    let (mut se, mut sum, mut worst, mut over, mut n) = (0.0f64, 0.0f64, 0.0f64, 0usize, 0usize);
    for d in diffs {
        n += 1;
        let mut px_worst = 0.0f64;
        for d in d {
            se += d * d;
            sum += d.abs();
            px_worst = px_worst.max(d.abs());
        }
        worst = worst.max(px_worst);
        over += usize::from(px_worst > 1.0);
    }
    let samples = (3 * n).max(1) as f64;
    let mse = se / samples;
    let psnr = if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (max.powi(2) / mse).log10()
    };
    ImageError {
        psnr_db: psnr,
        identical: mse == 0.0,
        max_lsb: worst,
        mean_lsb: sum / samples,
        over_1lsb: over as f64 / n.max(1) as f64,
        pixels: n,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_is_infinite_and_offsets_measure() {
        let g = vec![[255u32, 0, 128]; 4];
        let o = vec![[1.0, 0.0, 128.0 / 255.0]; 4];
        let e = compare(&g, &o, &[true; 4], 255);
        assert!(e.psnr_db.is_infinite() && e.max_lsb < 1e-9 && e.identical);
        let json = serde_json::to_value(e).unwrap();
        assert!(json["psnr_db"].is_null() && json["identical"] == true, "{json}");
        let o2 = vec![[1.0, 2.0 / 255.0, 128.0 / 255.0]; 4];
        let e = compare(&g, &o2, &[true; 4], 255);
        assert!((e.max_lsb - 2.0).abs() < 1e-9 && e.over_1lsb == 1.0 && !e.identical, "{e:?}");
        // mse = 4/3 → psnr = 10 log10(255² · 3/4)
        assert!((e.psnr_db - 10.0 * (255f64.powi(2) * 0.75).log10()).abs() < 1e-9);
    }
}
