//! The orthographic camera: the paper's parallel viewer (§4.1), so the view vector, and with
//! it every half vector of a parallel light, is the same for the whole image.

use super::CameraDesc;
use glam::{DVec2, DVec3};

#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: DVec3,
    pub target: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    /// Unit vector from the scene towards the viewer.
    pub to_viewer: DVec3,
    pub half_h: f64,
    pub half_w: f64,
    pub width: u32,
    pub height: u32,
}

impl Camera {
    pub fn new(d: &CameraDesc, width: u32, height: u32) -> Camera {
        let eye = DVec3::from_array(d.eye);
        let target = DVec3::from_array(d.target);
        let fwd = (target - eye).normalize();
        let up = DVec3::from_array(d.up);
        let mut right = fwd.cross(up);
        // An up vector parallel to the view falls back to the world axis least aligned with it
        // (scene validation refuses one, by the same test: relative to up's length, so a short
        // up is a direction like any other).
        if right.length_squared() < 1e-12 * up.length_squared() {
            let alt = if fwd.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
            right = fwd.cross(alt);
        }
        let right = right.normalize();
        let up = right.cross(fwd);
        let half_h = d.height / 2.0;
        Camera {
            eye,
            target,
            right,
            up,
            to_viewer: -fwd,
            half_h,
            half_w: half_h * width as f64 / height as f64,
            width,
            height,
        }
    }

    /// Pixel coordinates (x right, y down, pixel centres at +0.5) and depth (smaller is nearer).
    pub fn project(&self, p: DVec3) -> (DVec2, f64) {
        let d = p - self.target;
        let x = (d.dot(self.right) / self.half_w + 1.0) * 0.5 * self.width as f64;
        let y = (1.0 - d.dot(self.up) / self.half_h) * 0.5 * self.height as f64;
        (DVec2::new(x, y), -(p - self.eye).dot(self.to_viewer))
    }
}
