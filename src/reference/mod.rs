//! The f64 yardsticks. [`perpixel`] is per-pixel Blinn–Phong bump mapping with everything
//! the hardware approximates done properly: interpolated tangent frames, Blinn's perturbed
//! normal renormalised, per-pixel light and half vectors, exact powers, per-pixel spotlights.
//! [`gouraud_f64`] evaluates the Gouraud bump equations themselves (per-triangle L and H,
//! interpolated Gouraud colour, filtered but unnormalised bump normals) without any
//! quantisation. Golden − gouraud_f64 is quantisation error; gouraud_f64 − perpixel is the
//! algorithm's own error. [`embm_f64`] is EMBM's geometry and maps, which its engine and
//! its bit-accurate path share.

pub mod cube_map;
pub mod embm_f64;
pub mod gouraud_f64;
pub mod perpixel;

use crate::raster::{Hit, PixelGeom, Prepared};

/// The configuration's own equations in f64 at a fragment (what the golden model rounds):
/// EMBM's maps under `env_map_bits`, else the Gouraud bump equations.
pub fn equations(p: &Prepared, hit: &Hit, g: &PixelGeom) -> glam::DVec3 {
    match p.cfg.embm() {
        true => embm_f64::shade(p, hit, g),
        false => gouraud_f64::shade(p, hit, g),
    }
}
