//! Every surface of every built-in scene is there to be seen lit: a wall turned away from
//! the camera or from every light renders as ambient-only and hides whatever the scene is
//! meant to show (cg_wall_floor once did, with its wall facing -y). Checked per object on the
//! pixels it wins in the z-buffer, so occluded back faces of closed shapes do not count.

use gbump::raster::fragment::pixel_geom;
use gbump::raster::rasterise::rasterise;
use gbump::raster::Prepared;
use gbump::scene::lighting::{light_dir, spot_factor};
use gbump::scene::{builtin, Scene};
use glam::DVec3;

const W: u32 = 96;
const H: u32 = 72;
/// Smallest share of the image an object must cover to count as part of the picture.
const MIN_COVER: f64 = 0.01;

#[test]
fn every_builtin_surface_faces_the_camera_and_a_light() {
    let mut bad = Vec::new();
    for (name, _) in builtin::ALL {
        let s = Scene::load(name).unwrap();
        let cfg = s.derive_config().unwrap();
        let p = Prepared::new(&s, &cfg, W, H).unwrap();
        let gb = rasterise(&p).unwrap();
        for obj in 0..s.objects.len() {
            let geoms: Vec<_> = gb
                .hits
                .iter()
                .flatten()
                .filter(|h| h.obj as usize == obj)
                .map(|h| pixel_geom(&p, h))
                .collect();
            let cover = geoms.len() as f64 / (W * H) as f64;
            if cover < MIN_COVER {
                bad.push(format!("{name} object {obj}: covers {:.2}% of the image", 100.0 * cover));
                continue;
            }
            let mean = |f: &dyn Fn(DVec3, DVec3) -> f64| geoms.iter().map(|g| f(g.p, g.n.normalize())).sum::<f64>() / geoms.len() as f64;
            let facing = mean(&|_, n| n.dot(p.camera.to_viewer));
            let lit = s
                .lights
                .iter()
                .map(|l| mean(&|x, n| n.dot(light_dir(l, x, n)).max(0.0) * spot_factor(l, x)))
                .fold(0.0, f64::max);
            if facing <= 0.0 {
                bad.push(format!("{name} object {obj}: mean N·V = {facing:.3}, faces away from the camera"));
            }
            if lit <= 0.05 {
                bad.push(format!(
                    "{name} object {obj}: best mean max(0, N·L) = {lit:.3}, unlit by every light"
                ));
            }
        }
    }
    assert!(bad.is_empty(), "surfaces that cannot be seen lit:\n{}", bad.join("\n"));
}
