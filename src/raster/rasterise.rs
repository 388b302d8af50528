//! The z-buffered triangle rasteriser. Pixel centres are sampled; a pixel belongs to a
//! triangle when all three edge functions are ≥ 0 (either winding: closed and open shapes
//! alike are drawn without culling); nearer depth wins, ties keep the first triangle drawn.
//! The eye is the near plane: a pixel whose point lies behind it (depth below 0) is not
//! drawn, so an object behind the camera neither shows nor hides what is in front.
//! Zero-area triangles cover nothing.

use super::Prepared;
use crate::error::{Error, Result};
use glam::DVec2;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub obj: u32,
    pub tri: u32,
    /// Barycentric weights of the triangle's three vertices.
    pub bary: [f64; 3],
}

pub struct GBuffer {
    pub w: u32,
    pub h: u32,
    pub hits: Vec<Option<Hit>>,
}

fn edge(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

/// The pixels each object covers, or an error when no object covers a pixel centre: every
/// measure of such an image (PSNR, error, a regression over its fragments) would pass
/// without testing anything.
pub fn rasterise(p: &Prepared) -> Result<GBuffer> {
    let (w, h) = (p.camera.width, p.camera.height);
    let hits = hits_of(p, &p.camera);
    if hits.iter().all(Option::is_none) {
        let [sw, sh] = p.scene.size;
        let own = || crate::scene::camera::Camera::new(&p.scene.camera, sw, sh);
        if (w < sw || h < sh) && covers_any(p, &own()) {
            // Covered at the scene's own size, not at the smaller one asked for: the size is
            // what to change (otherwise the camera or the objects are, as below).
            return Err(Error::NoPixelAtSize {
                scene: p.scene.name.clone(),
                w,
                h,
                own: [sw, sh],
            });
        }
        return Err(Error::field(
            &p.scene.file,
            "objects",
            format!("no object covers a pixel centre in front of camera.eye at {w}×{h}: the image is background only, so no fragment reaches the pipeline"),
            "point camera.target at the objects, move camera.eye back so they lie in front of it (the eye is the near plane), lower camera.height (the view's height in world units), or make the objects larger than a pixel",
        ));
    }
    Ok(GBuffer { w, h, hits })
}

/// The nearest object's triangle at each pixel centre of `camera`'s image (row by row).
fn hits_of(p: &Prepared, camera: &crate::scene::camera::Camera) -> Vec<Option<Hit>> {
    let (w, h) = (camera.width, camera.height);
    let mut hits = vec![None; (w * h) as usize];
    let mut depth = vec![f64::INFINITY; (w * h) as usize];
    covers(p, camera, |i, obj, tri, bary, z| {
        if z < depth[i] {
            depth[i] = z;
            hits[i] = Some(Hit { obj, tri, bary });
        }
        true
    });
    hits
}

/// Whether any object covers a pixel centre of `camera`'s image, found without a buffer of
/// the image (the scene's own size, asked only to word an error, was never planned for).
fn covers_any(p: &Prepared, camera: &crate::scene::camera::Camera) -> bool {
    let mut any = false;
    covers(p, camera, |_, _, _, _, _| {
        any = true;
        false
    });
    any
}

/// `f(pixel, object, triangle, barycentrics, depth)` for each pixel centre of `camera`'s image
/// a triangle covers in front of the eye, until `f` returns false.
fn covers(p: &Prepared, camera: &crate::scene::camera::Camera, mut f: impl FnMut(usize, u32, u32, [f64; 3], f64) -> bool) {
    let (w, h) = (camera.width, camera.height);
    for (oi, o) in p.objects.iter().enumerate() {
        let proj: Vec<(DVec2, f64)> = o.mesh.verts.iter().map(|v| camera.project(v.p)).collect();
        for (ti, t) in o.mesh.tris.iter().enumerate() {
            let [a, b, c] = t.map(|i| proj[i as usize]);
            let area = edge(a.0, b.0, c.0);
            if area.abs() < 1e-12 || !area.is_finite() {
                continue;
            }
            let x0 = a.0.x.min(b.0.x).min(c.0.x).floor().max(0.0) as u32;
            let x1 = (a.0.x.max(b.0.x).max(c.0.x).ceil() as i64).clamp(0, w as i64) as u32;
            let y0 = a.0.y.min(b.0.y).min(c.0.y).floor().max(0.0) as u32;
            let y1 = (a.0.y.max(b.0.y).max(c.0.y).ceil() as i64).clamp(0, h as i64) as u32;
            for y in y0..y1 {
                for x in x0..x1 {
                    let q = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                    let wa = edge(b.0, c.0, q) / area;
                    let wb = edge(c.0, a.0, q) / area;
                    let wc = edge(a.0, b.0, q) / area;
                    if wa < 0.0 || wb < 0.0 || wc < 0.0 {
                        continue;
                    }
                    let z = wa * a.1 + wb * b.1 + wc * c.1;
                    if z >= 0.0 && !f((y * w + x) as usize, oi as u32, ti as u32, [wa, wb, wc], z) {
                        return;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// The hits of `text` (a scene) at 32×16.
    fn hits(text: &str) -> Vec<Option<(u32, u32)>> {
        let s = Scene::from_toml("t.toml", text, std::path::Path::new("scenes")).unwrap();
        let cfg = s.derive_config().unwrap();
        let p = Prepared::new(&s, &cfg, 32, 16).unwrap();
        rasterise(&p).unwrap().hits.iter().map(|h| h.map(|h| (h.obj, h.tri))).collect()
    }

    #[test]
    fn an_object_behind_the_eye_neither_shows_nor_hides() {
        let wall = crate::scene::builtin::get("cg_wall_front").unwrap();
        // A sphere behind the eye (z = 6), over the wall's centre.
        let behind = format!("{wall}\n[[objects]]\nshape = {{ kind = \"sphere\", radius = 1.5 }}\ntranslate = [0.0, 0.0, 9.0]\nsegments = [16, 8]\nshininess = 8\nbump = {{ source = {{ kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }}, size = 64, strength = 1.0 }}\n");
        let (alone, with) = (hits(wall), hits(&behind));
        assert!(with.iter().flatten().all(|&(o, _)| o == 0), "the sphere behind the eye was drawn");
        assert_eq!(alone, with);
        // In front of the eye the same sphere hides the wall's centre.
        let front = behind.replace("translate = [0.0, 0.0, 9.0]", "translate = [0.0, 0.0, 3.0]");
        assert!(hits(&front).iter().flatten().any(|&(o, _)| o == 1));
    }
}
