//! Direct3D 6 environment-mapped bump mapping (paper §3.3) in f64 at a rasterised fragment,
//! on `scene::sphere_map`'s geometry, which EMBM's bit-accurate setup quantises, so the engine
//! and its path read the same maps at the same coordinates. Per fragment the coordinates interpolated from the vertex normals are moved by the bump map's (du, dv)
//! through the triangle's 2×2 matrix, the view-space (right, up) components of its T and B.

use crate::raster::{Hit, PixelGeom, Prepared};
use crate::scene::sphere_map::{coords_at, lookup, texel, texel_centre, triangle_matrix};
use glam::{DVec2, DVec3};

/// The map coordinates the fragment at `hit` reads with bump normal `nb` (tangent space):
/// its interpolated coordinates moved by (du, dv) = (nb.x, nb.y) through the triangle's matrix.
pub fn perturbed_coords(p: &Prepared, hit: &Hit, nb: DVec3) -> DVec2 {
    let v = p.objects[hit.obj as usize].mesh.corners(hit.tri);
    let m = triangle_matrix(&p.camera, &v);
    coords_at(&p.camera, &v, hit.bary) + m[0] * nb.x + m[1] * nb.y
}

/// The diffuse and specular light the fragment at `hit` reads with bump normal `nb` from its
/// object's two maps of `side` texels a side: each texel's lighting clamped to [0, 1], as a
/// map of stored colours holds it, read bilinearly and exactly at the perturbed coordinates.
pub fn maps_lighting(p: &Prepared, hit: &Hit, nb: DVec3, side: u32) -> (DVec3, DVec3) {
    let obj = hit.obj as usize;
    let centre = p.objects[obj].centre;
    lookup(side, perturbed_coords(p, hit, nb), |x, y| {
        let (sx, sy) = texel_centre(side, x, y);
        let (d, s) = texel(p.scene, &p.camera, obj, centre, sx, sy);
        (d.clamp(DVec3::ZERO, DVec3::ONE), s.clamp(DVec3::ZERO, DVec3::ONE))
    })
}

/// The configuration's EMBM path in f64 (what the golden model rounds): the filtered,
/// unnormalised bump normal as the pipeline fetches it, the maps at the configuration's size,
/// then the configuration's blend.
pub fn shade(p: &Prepared, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let cfg = p.cfg;
    let so = &p.scene.objects[hit.obj as usize];
    let nb = super::gouraud_f64::filtered_normal(&p.objects[hit.obj as usize].normals, g.uv, so.bump.filter);
    let bypass = cfg.skip_flat && (nb - DVec3::Z).length() < 1e-9;
    let (diff, spec) = maps_lighting(p, hit, nb, cfg.env_map_side());
    let d = if cfg.diffuse && so.diffuse && !bypass { diff } else { DVec3::ZERO };
    let s = if cfg.specular && so.specular && !bypass {
        spec
    } else {
        DVec3::ZERO
    };
    super::gouraud_f64::combine(cfg, so, g, d, s)
}
