//! The power unit's design space: every design of `model::power_unit` evaluated exhaustively
//! over its input codes and every exponent 1..=255, against its storage and multipliers.

use crate::model::power_unit::{PowerDesign, PowerFormats};
use rayon::prelude::*;
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct DesignResult {
    pub design: PowerDesign,
    pub label: String,
    pub rom_bits: u64,
    pub multipliers: u32,
    pub multiplier_bits: u32,
    pub max_lsb: f64,
    pub worst_n: u32,
    pub worst_x: i64,
    pub mean_lsb: f64,
}

/// The designs compared by default.
pub fn default_designs() -> Vec<PowerDesign> {
    let mut v = Vec::new();
    for entries in [64, 128, 256, 512] {
        for nearest in [true, false] {
            v.push(PowerDesign::Table { entries, nearest });
        }
    }
    for knots in [16, 32, 64, 128, 256] {
        v.push(PowerDesign::Lerp { knots });
    }
    for segments in [4, 6, 8, 10, 12] {
        for per_segment in [8, 16, 32, 64] {
            for lerp in [false, true] {
                v.push(PowerDesign::Segmented { segments, per_segment, lerp });
            }
        }
    }
    for guard in [0, 2, 4, 6] {
        v.push(PowerDesign::Squaring { guard });
    }
    v
}

pub fn evaluate(fm: PowerFormats, designs: &[PowerDesign], max_n: u32) -> Vec<DesignResult> {
    designs
        .par_iter()
        .filter(|d| match d {
            PowerDesign::Segmented { segments, .. } => *segments < fm.f,
            _ => true,
        })
        .map(|d| {
            let (max_lsb, worst_n, worst_x, mean_lsb) = d.worst_error(fm, 1..=max_n);
            let (m, mb) = d.multipliers(fm);
            DesignResult { design: *d, label: d.label(), rom_bits: d.rom_bits(fm), multipliers: m, multiplier_bits: mb, max_lsb, worst_n, worst_x, mean_lsb }
        })
        .collect()
}

pub fn markdown(fm: PowerFormats, rs: &[DesignResult], max_n: u32) -> String {
    let mut s = format!(
        "Power units, input u1.{} (x = fd/2^{}), output u1.{}; error in output LSBs against exact x^n over every input and every n in 1..={max_n}\n\n| design | ROM bits | multipliers | max error | at n, x | mean | within 1 LSB |\n|---|---:|---:|---:|---|---:|---|\n",
        fm.f, fm.f, fm.p
    );
    let mut sorted: Vec<&DesignResult> = rs.iter().collect();
    sorted.sort_by(|a, b| (a.max_lsb > 1.0).cmp(&(b.max_lsb > 1.0)).then(a.multipliers.cmp(&b.multipliers)).then(a.rom_bits.cmp(&b.rom_bits)));
    for r in sorted {
        let m = if r.multipliers == 0 { "0".to_string() } else { format!("{} x {}b", r.multipliers, r.multiplier_bits) };
        s += &format!("| {} | {} | {} | {:.3} | {}, {}/2^{} | {:.4} | {} |\n", r.label, r.rom_bits, m, r.max_lsb, r.worst_n, r.worst_x, fm.f, r.mean_lsb, if r.max_lsb <= 1.0 { "yes" } else { "no" });
    }
    s
}
