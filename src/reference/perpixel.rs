//! Per-pixel Blinn–Phong bump mapping in f64 (see the module above for what it models).

use crate::bumpmap::sample::sample_normal;
use crate::model::power_table::powi_exact;
use crate::raster::{Hit, PixelGeom, Prepared};
use crate::scene::lighting::{gouraud_colour, half_vector, light_dir, spot_factor};
use crate::scene::mesh::frame;
use glam::DVec3;

/// Diffuse and specular factors of one light for perturbed normal `np`, geometric normal
/// `n`, light direction `ld` and half vector `hd`. With `self_shadowing` this is the Cg
/// Tutorial's §8.5.3 rule, a hard cut-off as its code has it:
/// `diffuse = light.z > 0 ? max(dot(normal, light), 0) : 0` and
/// `specular = dot(normal, light) > 0 && light.z > 0 ? max(dot(normal, halfAngle), 0) : 0`,
/// where `light.z` is the light's component along the geometric normal.
pub fn light_factors(np: DVec3, n: DVec3, ld: DVec3, hd: DVec3, self_shadowing: bool) -> (f64, f64) {
    let diffuse = np.dot(ld).max(0.0);
    let specular = np.dot(hd).max(0.0);
    if !self_shadowing {
        return (diffuse, specular);
    }
    if n.dot(ld) <= 0.0 {
        return (0.0, 0.0);
    }
    (diffuse, if np.dot(ld) > 0.0 { specular } else { 0.0 })
}

/// Reference colour of one pixel, each channel in [0, 1].
pub fn shade(p: &Prepared, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let so = &p.scene.objects[hit.obj as usize];
    let o = &p.objects[hit.obj as usize];
    let (n, t, b) = frame(g.n, g.t, g.b);
    let nb = sample_normal(&o.normals, g.uv, so.bump.filter);
    let np = (t * nb.x + b * nb.y + n * nb.z).try_normalize().unwrap_or(n);
    let c_src = gouraud_colour(p.scene, g.p, n);
    let view = p.camera.to_viewer;
    let (mut diff, mut spec) = (DVec3::ZERO, DVec3::ZERO);
    for l in p.scene.bump_lights() {
        let ld = light_dir(l, g.p, n);
        let hd = half_vector(ld, view);
        let lc = DVec3::from_array(l.colour) * (l.k * spot_factor(l, g.p));
        let (fd, fs) = light_factors(np, n, ld, hd, p.scene.self_shadowing);
        if so.diffuse {
            diff += lc * fd;
        }
        if so.specular {
            spec += lc * powi_exact(fs, so.shininess);
        }
    }
    let tex = crate::raster::assets::texture_at(so, g.uv);
    ((c_src + diff).min(DVec3::ONE) * tex + spec).min(DVec3::ONE)
}
