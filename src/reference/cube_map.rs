//! The normalisation cube map in f64 (Cg §8.4): what a cube map of unit vectors, read
//! nearest, gives back for a direction. The Cg engine and the f64 Gouraud image under
//! `cube_map_face` both read it.

use glam::DVec3;

/// The unit vector a normalisation cube map of `face` texels a side holds for direction `v`:
/// the texel `v` pierces, read nearest, holds the direction through its centre.
pub fn cube_normalise(v: DVec3, face: u32) -> DVec3 {
    let a = v.abs();
    // The major axis picks the face; the other two components, over it, the texel.
    let (major, u, w) = if a.x >= a.y && a.x >= a.z {
        (0, v.y / a.x, v.z / a.x)
    } else if a.y >= a.z {
        (1, v.x / a.y, v.z / a.y)
    } else {
        (2, v.x / a.z, v.y / a.z)
    };
    if !(u.is_finite() && w.is_finite()) {
        return DVec3::Z;
    }
    let centre = |c: f64| {
        let i = (((c + 1.0) * 0.5 * face as f64).floor()).clamp(0.0, face as f64 - 1.0);
        (i + 0.5) / face as f64 * 2.0 - 1.0
    };
    let (cu, cw) = (centre(u), centre(w));
    let s = v.to_array()[major].signum();
    let d = match major {
        0 => DVec3::new(s, cu, cw),
        1 => DVec3::new(cu, s, cw),
        _ => DVec3::new(cu, cw, s),
    };
    d.normalize()
}
