//! Height fields: tileable grids of heights in [0, 1], from procedures after the paper's
//! figures (bricks, sphere caps, mexican hat) or from a greyscale PNG.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// A tileable height field; `at` wraps around both edges.
#[derive(Clone, Debug)]
pub struct HeightField {
    pub w: usize,
    pub h: usize,
    pub data: Vec<f64>,
}

impl HeightField {
    pub fn at(&self, x: i64, y: i64) -> f64 {
        let xi = x.rem_euclid(self.w as i64) as usize;
        let yi = y.rem_euclid(self.h as i64) as usize;
        self.data[yi * self.w + xi]
    }

    fn from_fn(size: usize, f: impl Fn(f64, f64) -> f64) -> HeightField {
        let data = (0..size * size)
            .map(|i| f(((i % size) as f64 + 0.5) / size as f64, ((i / size) as f64 + 0.5) / size as f64))
            .collect();
        HeightField { w: size, h: size, data }
    }
}

/// Where a height field comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum HeightSource {
    /// No relief: every normal is (0, 0, 1) (paper Fig. 7's constant bump normals). An empty
    /// struct variant, so a stray key beside `kind` is refused as in every other table.
    Flat {},
    /// Running-bond bricks with recessed mortar (Cg tutorial Fig. 8-1, paper Fig. 6).
    Bricks { rows: u32, cols: u32, mortar: f64 },
    /// A grid of hemispherical caps (paper Fig. 4).
    SphereCaps { cells: u32, radius: f64 },
    /// The "mexican hat" (Ricker wavelet) in each cell (paper Fig. 9).
    MexicanHat { cells: u32, sigma: f64 },
    /// Greyscale PNG; black is low, white is high.
    Png { path: PathBuf },
}

/// Deterministic per-cell hash in [0, 1): brick-to-brick height variation without a RNG.
fn hash01(a: u32, b: u32) -> f64 {
    let mut x = a.wrapping_mul(0x9E37_79B1) ^ b.wrapping_mul(0x85EB_CA77) ^ 0x27D4_EB2F;
    x ^= x >> 15;
    x = x.wrapping_mul(0x2C1B_3C6D);
    x ^= x >> 12;
    (x & 0xFFFF) as f64 / 65536.0
}

impl HeightSource {
    /// Generate at `size`×`size` (PNG sources keep their own size). `base` resolves relative paths.
    pub fn generate(&self, size: usize, base: &std::path::Path) -> Result<HeightField> {
        Ok(match self {
            HeightSource::Flat {} => HeightField::from_fn(size, |_, _| 0.5),
            HeightSource::Bricks { rows, cols, mortar } => {
                let (rows, cols, m) = (*rows as f64, *cols as f64, *mortar);
                HeightField::from_fn(size, |u, v| {
                    let row = (v * rows).floor();
                    let shift = if row as i64 % 2 == 1 { 0.5 } else { 0.0 };
                    let col = (u * cols + shift).floor();
                    let fu = (u * cols + shift).fract();
                    let fv = (v * rows).fract();
                    // Distance to the nearest joint in brick heights (a brick is rows/cols heights wide).
                    let d = (fu.min(1.0 - fu) * cols.recip() * rows).min(fv.min(1.0 - fv));
                    if d < m {
                        0.0
                    } else {
                        let bevel = ((d - m) / m).min(1.0);
                        0.7 + 0.3 * hash01(row as u32, col.rem_euclid(cols) as u32) * bevel
                    }
                })
            }
            HeightSource::SphereCaps { cells, radius } => {
                let (c, r) = (*cells as f64, *radius);
                HeightField::from_fn(size, |u, v| {
                    let (x, y) = ((u * c).fract() - 0.5, (v * c).fract() - 0.5);
                    let d2 = x * x + y * y;
                    if d2 < r * r {
                        (r * r - d2).sqrt() / r
                    } else {
                        0.0
                    }
                })
            }
            HeightSource::MexicanHat { cells, sigma } => {
                let (c, s) = (*cells as f64, *sigma);
                HeightField::from_fn(size, |u, v| {
                    let (x, y) = ((u * c).fract() - 0.5, (v * c).fract() - 0.5);
                    let q = (x * x + y * y) / (s * s);
                    0.5 + 0.5 * (1.0 - q) * (-q / 2.0).exp()
                })
            }
            HeightSource::Png { path } => {
                let p = if path.is_absolute() { path.clone() } else { base.join(path) };
                let img = read_png(&p)?.to_luma16();
                let (w, h) = (img.width() as usize, img.height() as usize);
                if w < 2 || h < 2 {
                    return Err(Error::Image {
                        path: p,
                        msg: format!("{w}x{h} is too small (at least 2x2)"),
                    });
                }
                HeightField {
                    w,
                    h,
                    data: img.pixels().map(|px| px.0[0] as f64 / 65535.0).collect(),
                }
            }
        })
    }
}

/// Decode a height-map image, refusing from its header alone one larger than
/// `MAX_BUMP_SIDE` (a small file can declare a picture of gigabytes).
fn read_png(p: &std::path::Path) -> Result<image::DynamicImage> {
    use crate::limits::MAX_BUMP_SIDE;
    let bad = |msg: String| Error::Image {
        path: p.to_path_buf(),
        msg,
    };
    crate::limits::check_not_pipe(p, "give a PNG file")?;
    crate::limits::note_input(p);
    let open = || {
        image::ImageReader::open(p)
            .and_then(|r| r.with_guessed_format())
            .map_err(|e| bad(e.to_string()))
    };
    // The header read without the decoder's allocation limit, which a declared size of
    // gigabytes trips before the side can be named.
    let mut header = open()?;
    header.no_limits();
    let (w, h) = header.into_dimensions().map_err(|e| bad(e.to_string()))?;
    if w > MAX_BUMP_SIDE || h > MAX_BUMP_SIDE {
        return Err(bad(format!(
            "its header declares {w}x{h} texels, more than MAX_BUMP_SIDE = {MAX_BUMP_SIDE} per side (scale it down)"
        )));
    }
    let mut r = open()?;
    let mut lim = image::Limits::default();
    lim.max_image_width = Some(MAX_BUMP_SIDE);
    lim.max_image_height = Some(MAX_BUMP_SIDE);
    r.limits(lim);
    r.decode().map_err(|e| bad(e.to_string()))
}
