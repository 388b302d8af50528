//! The error budget of `gbump fit`: what "within this error" means.

use crate::error::{Error, Result};

/// One bound on the error of a configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Budget {
    /// `max<=X`: the largest colour error, in LSB, of the golden image against the f64
    /// Gouraud image of the same scene, over every scene.
    Max(f64),
    /// `psnr>=X`: the lowest PSNR (dB) of the golden image against the f64 Gouraud image.
    Psnr(f64),
    /// `exact<=X`: the largest error, in LSB, of the whole pipeline against exact arithmetic of
    /// the same equations on random stored inputs (`gbump error`'s pipeline row).
    Exact(f64),
}

/// What a configuration measured, for the budget and the front.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Measured {
    /// Worst max LSB and worst PSNR over the scenes, against the f64 Gouraud images.
    pub max_lsb: f64,
    pub psnr_db: f64,
    /// Pipeline max LSB against exact arithmetic on random inputs (measured when the budget
    /// asks for it; NaN otherwise).
    pub exact_lsb: f64,
}

impl Measured {
    /// The measures that were taken, in words (a measure the budget did not ask for is NaN
    /// and left out).
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if !self.max_lsb.is_nan() {
            parts.push(format!("max {:.2} LSB", self.max_lsb));
        }
        if !self.psnr_db.is_nan() {
            parts.push(format!("PSNR {:.2} dB", self.psnr_db));
        }
        if !parts.is_empty() {
            parts = vec![format!("{} against the f64 Gouraud images", parts.join(", "))];
        }
        if !self.exact_lsb.is_nan() {
            parts.push(format!(
                "exact {:.3} LSB against exact arithmetic on random stored inputs",
                self.exact_lsb
            ));
        }
        parts.join("; ")
    }
}

impl Budget {
    pub fn parse(text: &str) -> Result<Budget> {
        let bad = || {
            Error::Other(format!(
                "--budget `{text}` is not a budget\n  fix: use max<=LSB (against the f64 Gouraud image), psnr>=DB, or exact<=LSB (against exact arithmetic), e.g. max<=2"
            ))
        };
        // Spaces around the name, the operator and the bound, not inside them: `max< =2` or
        // `ma x<=2` is a typo to name, not a budget to guess.
        let (name, op, value) = match text.find(['<', '>']) {
            Some(i) => (
                text[..i].trim(),
                text[i..].get(..2).unwrap_or(""),
                text[i..].get(2..).unwrap_or("").trim(),
            ),
            None => return Err(bad()),
        };
        let kind = match (name, op) {
            ("max", "<=") => "max",
            ("psnr", ">=") => "psnr",
            ("exact", "<=") => "exact",
            _ => return Err(bad()),
        };
        let v: f64 = value.parse().map_err(|_| bad())?;
        // An error in LSBs cannot exceed the widest colour's range.
        let lsb_max = ((1u64 << crate::config::limit("colour_bits").1) - 1) as f64;
        if !v.is_finite() || v < 0.0 || (kind == "psnr" && v > 200.0) || (kind != "psnr" && v > lsb_max) {
            return Err(Error::Other(format!(
                "--budget `{text}`: the bound is out of range\n  fix: a finite bound, at least 0 (PSNR at most 200 dB, an error at most {lsb_max} LSB)"
            )));
        }
        Ok(match kind {
            "max" => Budget::Max(v),
            "psnr" => Budget::Psnr(v),
            _ => Budget::Exact(v),
        })
    }

    /// Whether `m` is within the budget.
    pub fn met(&self, m: &Measured) -> bool {
        match *self {
            Budget::Max(x) => m.max_lsb <= x,
            Budget::Psnr(x) => m.psnr_db >= x,
            Budget::Exact(x) => m.exact_lsb <= x,
        }
    }

    /// The measure the budget bounds, as the front's error axis (smaller is better).
    pub fn error(&self, m: &Measured) -> f64 {
        match self {
            Budget::Max(_) => m.max_lsb,
            Budget::Psnr(_) => -m.psnr_db,
            Budget::Exact(_) => m.exact_lsb,
        }
    }

    pub fn needs_images(&self) -> bool {
        !matches!(self, Budget::Exact(_))
    }
}

use crate::scene::validate::short;

impl std::fmt::Display for Budget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Budget::Max(x) => write!(f, "max<={}", short(*x)),
            Budget::Psnr(x) => write!(f, "psnr>={}", short(*x)),
            Budget::Exact(x) => write!(f, "exact<={}", short(*x)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_parse_and_bad_ones_name_the_fix() {
        assert_eq!(Budget::parse("max<=2").unwrap(), Budget::Max(2.0));
        assert_eq!(Budget::parse("psnr >= 50").unwrap(), Budget::Psnr(50.0));
        assert_eq!(Budget::parse("exact<=1").unwrap(), Budget::Exact(1.0));
        assert_eq!(Budget::parse(" max <= 2.5 ").unwrap(), Budget::Max(2.5));
        // A bound prints as it was given, not as hundreds of digits.
        assert_eq!(Budget::parse("max<=1e-300").unwrap().to_string(), "max<=1e-300");
        assert_eq!(Budget::parse("psnr>=50").unwrap().to_string(), "psnr>=50");
        // A space inside the name, the operator or the number is a typo, not a budget.
        for bad in [
            "max<2",
            "psnr>=",
            "exact<=NaN",
            "max<=-1",
            "lsb<=2",
            "max< =2",
            "ma x<=2",
            "max<=2 5",
            "max>=2",
            "psnr<=50",
            "max<<=2",
        ] {
            let e = Budget::parse(bad).unwrap_err().to_string();
            assert!(e.contains("fix:"), "{bad}: {e}");
        }
        let m = Measured {
            max_lsb: 2.0,
            psnr_db: 49.9,
            exact_lsb: 1.5,
        };
        assert!(Budget::Max(2.0).met(&m) && !Budget::Psnr(50.0).met(&m) && !Budget::Exact(1.0).met(&m));
    }
}
