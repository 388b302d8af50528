//! Per-pixel Blinn–Phong bump mapping in f64 (see the module above for what it models).

use crate::bumpmap::sample::sample_normal;
use crate::model::power_table::powi_exact;
use crate::raster::{Hit, PixelGeom, Prepared};
use crate::scene::lighting::{gouraud_colour, half_vector, light_dir, spot_factor};
use crate::scene::mesh::frame;
use glam::DVec3;

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
        if so.diffuse {
            diff += lc * np.dot(ld).max(0.0);
        }
        if so.specular {
            spec += lc * powi_exact(np.dot(hd).max(0.0), so.shininess);
        }
    }
    let tex = crate::raster::assets::texture_at(so, g.uv);
    ((c_src + diff).min(DVec3::ONE) * tex + spec).min(DVec3::ONE)
}
