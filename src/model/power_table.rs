//! The power table: the memory the power unit reads (paper §4.2: "a simple power table for
//! one shininess at a time … loaded similar to a color LUT"). For the paper's plain table,
//! entry i holds x_i^n with x_i = i/(N-1), so entry 0 is 0^n and entry N-1 is exactly 1.0, and
//! the index is fd·(N-1) (a shift and a subtract), rounded or truncated as the config says;
//! the interpolating designs of `power_unit` hold their knots here. The unit itself is
//! [`power_unit`](super::power_unit::power_unit).

use crate::config::{PipelineConfig, PowerIndex};
use crate::fixed::{shift_round, Rounding};

/// The table contents for one shininess.
#[derive(Clone, Debug, PartialEq)]
pub struct PowerTable {
    pub n: u32,
    /// Raw `u1.P` entries.
    pub entries: Vec<i64>,
}

/// x^n by binary exponentiation: only IEEE multiplications, so the result is the same on
/// every platform (libm `pow` is not correctly rounded and varies between libraries).
pub fn powi_exact(x: f64, n: u32) -> f64 {
    let (mut acc, mut base, mut e) = (1.0f64, x, n);
    while e > 0 {
        if e & 1 == 1 {
            acc *= base;
        }
        base *= base;
        e >>= 1;
    }
    acc
}

impl PowerTable {
    /// Build the contents for shininess `n` (0^0 is taken as 1, as OpenGL's pow does) for the
    /// configured power unit (the paper's table, or a `model::power_unit` alternative).
    pub fn build(cfg: &PipelineConfig, n: u32) -> PowerTable {
        PowerTable {
            n,
            entries: cfg.power_table_design().table(cfg.power_formats(), n),
        }
    }

    /// Index of the plain table's entry for clamped dot product `fd` (`u1.F`).
    #[inline]
    pub fn index(cfg: &PipelineConfig, fd: i64) -> usize {
        let scaled = (fd as i128) * (cfg.power_entries as i128 - 1);
        let rnd = match cfg.power_index {
            PowerIndex::Nearest => Rounding::HalfUp,
            PowerIndex::Truncate => Rounding::Truncate,
        };
        shift_round(scaled, cfg.dot_frac_bits, rnd) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::power_unit::power_unit;

    #[test]
    fn ends_and_exponents() {
        let cfg = PipelineConfig::default();
        let one = 1i64 << cfg.power_frac_bits;
        for n in [0u32, 1, 2, 16, 254, 255, 1024] {
            let t = PowerTable::build(&cfg, n);
            assert_eq!(t.entries.len(), 256);
            assert_eq!(*t.entries.last().unwrap(), one, "1^n = 1 for n={n}");
            assert_eq!(t.entries[0], if n == 0 { one } else { 0 }, "0^n for n={n}");
            assert_eq!(power_unit(&cfg, &t, 1 << cfg.dot_frac_bits), one);
            assert_eq!(power_unit(&cfg, &t, 0), t.entries[0]);
        }
        // n = 1 is the identity up to the index and entry quantisation.
        let t = PowerTable::build(&cfg, 1);
        for fd in 0..=256i64 {
            assert!((power_unit(&cfg, &t, fd) - fd).abs() <= 1, "fd={fd}");
        }
    }

    #[test]
    fn index_covers_table_exactly() {
        for idx in [PowerIndex::Nearest, PowerIndex::Truncate] {
            let cfg = PipelineConfig {
                power_entries: 64,
                power_index: idx,
                ..Default::default()
            };
            assert_eq!(PowerTable::index(&cfg, 0), 0);
            assert_eq!(PowerTable::index(&cfg, 256), 63);
            let mut prev = 0;
            for fd in 0..=256 {
                let i = PowerTable::index(&cfg, fd);
                assert!(i >= prev && i <= prev + 1);
                prev = i;
            }
        }
    }
}
