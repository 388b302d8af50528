//! Light geometry shared by the rasteriser (per vertex, per triangle) and the reference
//! renderer (per pixel). Every degenerate case has a defined fallback so no NaN can leave.

use super::{Light, LightKind, Scene};
use glam::DVec3;

/// Unit vector from `p` towards the light. A point light sitting exactly on `p` has no
/// direction; it falls back to `fallback` (the surface normal: light from straight above).
pub fn light_dir(l: &Light, p: DVec3, fallback: DVec3) -> DVec3 {
    match l.kind {
        LightKind::Directional => DVec3::from_array(l.direction).normalize(),
        LightKind::Point | LightKind::Spot => (DVec3::from_array(l.position) - p).try_normalize().unwrap_or(fallback),
    }
}

/// Spot cone factor at `p` (1 for other kinds): cos^e of the angle off the axis inside the
/// cut-off, 0 outside.
pub fn spot_factor(l: &Light, p: DVec3) -> f64 {
    if l.kind != LightKind::Spot {
        return 1.0;
    }
    let axis = DVec3::from_array(l.direction).normalize();
    let Some(to_p) = (p - DVec3::from_array(l.position)).try_normalize() else {
        return 1.0;
    };
    let c = axis.dot(to_p);
    if c < l.cutoff_deg.to_radians().cos() {
        0.0
    } else {
        c.max(0.0).powf(l.exponent)
    }
}

/// Half vector of light direction `l` and viewer direction `v`. When the light is exactly
/// behind the viewer's opposite (l = -v) the half vector is undefined; `l` is used, which
/// gives no highlight on any surface facing the viewer.
pub fn half_vector(l: DVec3, v: DVec3) -> DVec3 {
    (l + v).try_normalize().unwrap_or(l)
}

/// The Gouraud colour at a surface point: ambient plus the lights that do not act on the
/// bumps (diffuse term with their cone), unclamped.
pub fn gouraud_colour(s: &Scene, p: DVec3, n: DVec3) -> DVec3 {
    let mut c = DVec3::from_array(s.ambient);
    for l in s.lights.iter().filter(|l| !l.bump) {
        let d = light_dir(l, p, n);
        c += DVec3::from_array(l.colour) * (n.dot(d).max(0.0) * spot_factor(l, p) * l.k);
    }
    c
}
