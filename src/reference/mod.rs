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
