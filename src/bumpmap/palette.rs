//! Palettised bump maps (paper §6: "with eight bit addressing a table lookup (bump) texture,
//! up to 256 surface orientations can be modeled"). The palette is chosen by k-means over the
//! map's distinct stored codes, weighted by their counts and seeded by farthest-point
//! sampling from the most frequent code, so it is deterministic, spreads over the whole set of
//! orientations, and is exact whenever a map has at most 256 distinct normals.

use crate::config::PipelineConfig;
use crate::model::bump_fetch::{expand, Palette};
use std::collections::HashMap;

const ENTRIES: usize = 256;
const ITERATIONS: usize = 12;

fn dist2(cfg: &PipelineConfig, a: [u32; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (expand(cfg, a[i]) as f64 - b[i]).powi(2)).sum()
}

/// Palette and per-texel indices for stored codes.
pub fn build_palette(cfg: &PipelineConfig, codes: &[[u32; 3]]) -> (Palette, Vec<u8>) {
    let mut counts: HashMap<[u32; 3], usize> = HashMap::new();
    for c in codes {
        *counts.entry(*c).or_default() += 1;
    }
    let mut uniq: Vec<([u32; 3], usize)> = counts.into_iter().collect();
    uniq.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let flat_code = [0, 0, cfg.normal_fmt().max_raw()].map(|b| crate::model::bump_fetch::compress(cfg, b));
    let mut centres: Vec<[f64; 3]> = uniq.iter().take(ENTRIES).map(|(c, _)| c.map(|x| expand(cfg, x) as f64)).collect();
    if uniq.len() > ENTRIES {
        centres = farthest_points(cfg, &uniq);
        for _ in 0..ITERATIONS {
            let mut sum = vec![[0f64; 3]; centres.len()];
            let mut wsum = vec![0f64; centres.len()];
            for (c, n) in &uniq {
                let k = nearest(cfg, &centres, *c);
                for i in 0..3 {
                    sum[k][i] += expand(cfg, c[i]) as f64 * *n as f64;
                }
                wsum[k] += *n as f64;
            }
            for k in 0..centres.len() {
                if wsum[k] > 0.0 {
                    centres[k] = sum[k].map(|s| s / wsum[k]);
                }
            }
        }
    }
    let half = (1i64 << (cfg.normal_bits - 1)) as f64;
    let mut entries: Vec<[u32; 3]> = centres
        .iter()
        .map(|c| c.map(|x| (x.round().clamp(-half, half - 1.0) + half) as u32))
        .collect();
    entries.resize(ENTRIES, flat_code);
    let snapped: Vec<[f64; 3]> = entries.iter().map(|e| e.map(|x| expand(cfg, x) as f64)).collect();
    let mut lut: HashMap<[u32; 3], u8> = HashMap::new();
    let indices = codes
        .iter()
        .map(|c| *lut.entry(*c).or_insert_with(|| nearest(cfg, &snapped, *c) as u8))
        .collect();
    (Palette(entries), indices)
}

/// Greedy farthest-point seeds: each new centre is the code farthest from all chosen so far.
fn farthest_points(cfg: &PipelineConfig, uniq: &[([u32; 3], usize)]) -> Vec<[f64; 3]> {
    let pt = |c: [u32; 3]| c.map(|x| expand(cfg, x) as f64);
    let mut centres = vec![pt(uniq[0].0)];
    let mut d: Vec<f64> = uniq.iter().map(|(c, _)| dist2(cfg, *c, centres[0])).collect();
    while centres.len() < ENTRIES {
        let (far, _) = d
            .iter()
            .enumerate()
            .fold((0, -1.0), |best, (i, &x)| if x > best.1 { (i, x) } else { best });
        let z = pt(uniq[far].0);
        centres.push(z);
        for (i, (c, _)) in uniq.iter().enumerate() {
            d[i] = d[i].min(dist2(cfg, *c, z));
        }
    }
    centres
}

fn nearest(cfg: &PipelineConfig, centres: &[[f64; 3]], c: [u32; 3]) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (k, z) in centres.iter().enumerate() {
        let d = dist2(cfg, c, *z);
        if d < best.0 {
            best = (d, k);
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn few_normals_are_kept_exactly() {
        let cfg = PipelineConfig {
            palette: true,
            ..Default::default()
        };
        let codes: Vec<[u32; 3]> = (0..1000u32).map(|i| [100 + i % 7, 128, 250]).collect();
        let (p, idx) = build_palette(&cfg, &codes);
        for (c, i) in codes.iter().zip(&idx) {
            assert_eq!(p.0[*i as usize], *c);
        }
    }

    #[test]
    fn many_normals_stay_close() {
        let cfg = PipelineConfig {
            palette: true,
            ..Default::default()
        };
        let codes: Vec<[u32; 3]> = (0..4096u32).map(|i| [64 + i % 64, 64 + i / 64, 240]).collect();
        let (p, idx) = build_palette(&cfg, &codes);
        let worst = codes
            .iter()
            .zip(&idx)
            .map(|(c, i)| {
                let e = p.0[*i as usize];
                (0..3).map(|k| (c[k] as i64 - e[k] as i64).abs()).max().unwrap()
            })
            .max()
            .unwrap();
        assert!(
            worst <= 4,
            "4096 codes on a 64x64 grid into 256 entries: worst component error {worst}"
        );
    }
}
