//! Normals of a height field. Paper Eq. 2: N = (fu, fv, 1)/|·| (our gradients point
//! downhill, so a raised bump lights from the light's side: N = (-s·fu, -s·fv, 1)/|·|, the
//! same as Eq. 1 with k = 1), from central differences; and the Cg tutorial's cross product of
//! forward difference vectors (1, 0, Hr−Hg) × (0, 1, Ha−Hg). `strength` scales the relief.

use super::height::HeightField;
use glam::DVec3;
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum NormalMethod {
    /// Paper Eq. 2 with central differences.
    #[default]
    Eq2,
    /// Cg tutorial §8.1.2 forward difference vectors.
    Cg,
}

/// A tileable map of unit normals in bump (tangent) space.
#[derive(Clone, Debug)]
pub struct NormalMap {
    pub w: usize,
    pub h: usize,
    pub data: Vec<DVec3>,
    /// Clamp instead of wrapping across the u edges (a baked facet map must not blend its two edges).
    pub clamp_u: bool,
}

impl NormalMap {
    pub fn at(&self, x: i64, y: i64) -> DVec3 {
        let xi = crate::bumpmap::sample::address(x, self.w, self.clamp_u);
        let yi = y.rem_euclid(self.h as i64) as usize;
        self.data[yi * self.w + xi]
    }

    /// Normals of `hf`; heights are in texel-size units times `strength`.
    pub fn from_height(hf: &HeightField, method: NormalMethod, strength: f64) -> NormalMap {
        let mut data = Vec::with_capacity(hf.w * hf.h);
        for y in 0..hf.h as i64 {
            for x in 0..hf.w as i64 {
                let (fu, fv) = match method {
                    NormalMethod::Eq2 => ((hf.at(x + 1, y) - hf.at(x - 1, y)) / 2.0, (hf.at(x, y + 1) - hf.at(x, y - 1)) / 2.0),
                    NormalMethod::Cg => (hf.at(x + 1, y) - hf.at(x, y), hf.at(x, y + 1) - hf.at(x, y)),
                };
                data.push(DVec3::new(-strength * fu, -strength * fv, 1.0).normalize());
            }
        }
        NormalMap {
            w: hf.w,
            h: hf.h,
            data,
            clamp_u: false,
        }
    }

    /// Tilt every normal about the v axis by the facet angle of a `sides`-sided prism, so that
    /// a flat facet shades like the smooth cylinder it approximates (paper §5.3, Fig. 5 B).
    pub fn curve_for_cylinder(&mut self, sides: u32) {
        let span = std::f64::consts::TAU / sides as f64;
        self.clamp_u = true;
        for y in 0..self.h {
            for x in 0..self.w {
                let theta = ((x as f64 + 0.5) / self.w as f64 - 0.5) * span;
                let n = self.data[y * self.w + x];
                let (s, c) = theta.sin_cos();
                self.data[y * self.w + x] = DVec3::new(c * n.x + s * n.z, n.y, -s * n.x + c * n.z).normalize();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bumpmap::HeightSource;

    #[test]
    fn flat_field_gives_up_normals_and_slopes_tilt_away() {
        let hf = HeightSource::Flat {}.generate(8, std::path::Path::new(".")).unwrap();
        for m in [NormalMethod::Eq2, NormalMethod::Cg] {
            assert!(NormalMap::from_height(&hf, m, 4.0).data.iter().all(|n| *n == DVec3::Z));
        }
        let ramp = HeightField {
            w: 4,
            h: 4,
            data: (0..16).map(|i| (i % 4) as f64 * 0.25).collect(),
        };
        let n = NormalMap::from_height(&ramp, NormalMethod::Cg, 1.0).at(1, 1);
        assert!(n.x < 0.0 && n.y.abs() < 1e-12, "uphill in +u tilts the normal to -u: {n}");
    }
}
