//! What the engines share: a hit's vertices, barycentric mixes, the bump-map normal and its
//! offsets, per-pixel lighting for a perturbed normal, and the final colour combination.

use super::Ctx;
use crate::model::power_table::powi_exact;
use crate::raster::{Hit, PixelGeom, Prepared};
use crate::scene::lighting::{gouraud_colour, half_vector, light_dir, spot_factor};
use crate::scene::mesh::Vertex;
use glam::DVec3;

/// The three vertices of the hit's triangle.
pub fn corners(p: &Prepared, hit: &Hit) -> [Vertex; 3] {
    p.objects[hit.obj as usize].mesh.corners(hit.tri)
}

/// `Σ w_i f(i)` over the hit's barycentric weights.
pub fn mix(hit: &Hit, f: impl Fn(usize) -> DVec3) -> DVec3 {
    f(0) * hit.bary[0] + f(1) * hit.bary[1] + f(2) * hit.bary[2]
}

pub use crate::scene::mesh::plane_frame;

/// The bump map's unit normal at the pixel, in tangent space.
pub fn bump_normal(p: &Prepared, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let so = &p.scene.objects[hit.obj as usize];
    crate::bumpmap::sample::sample_normal(&p.objects[hit.obj as usize].normals, g.uv, so.bump.filter)
}

/// The map's normal as a texture unit hands it to an engine that lights with it directly: the
/// stored unit normals filtered, so shorter than 1 between texels that disagree, unless the
/// context asks for the what-if of renormalising it ([`Ctx::renormalise_map`]).
pub fn map_normal(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    if c.renormalise_map {
        return bump_normal(c.p, hit, g);
    }
    let so = &c.p.scene.objects[hit.obj as usize];
    crate::reference::gouraud_f64::filtered_normal(&c.p.objects[hit.obj as usize].normals, g.uv, so.bump.filter)
}

/// The bump normal as tangent-plane offsets (the height gradient `(x/z, y/z)` that Eq. 1
/// normalises); a normal at or below the tangent plane gives the largest offset the map's
/// own normals reach.
pub fn offsets(nb: DVec3) -> (f64, f64) {
    let z = nb.z.max(1e-3);
    (nb.x / z, nb.y / z)
}

/// Diffuse and specular sums for perturbed normal `np` with per-pixel light and half vectors
/// at the pixel, each light's colour times its k and spot factor; `n` is the geometric
/// normal (self-shadowing).
pub fn per_pixel_lights(p: &Prepared, hit: &Hit, g: &PixelGeom, np: DVec3, n: DVec3) -> (DVec3, DVec3) {
    let so = &p.scene.objects[hit.obj as usize];
    let (mut diff, mut spec) = (DVec3::ZERO, DVec3::ZERO);
    for l in p.scene.bump_lights() {
        let ld = light_dir(l, g.p, n);
        let hd = half_vector(ld, p.camera.to_viewer);
        let lc = DVec3::from_array(l.colour) * (l.k * spot_factor(l, g.p));
        let (fd, fs) = crate::reference::perpixel::light_factors(np, n, ld, hd, p.scene.self_shadowing);
        diff += lc * fd;
        spec += lc * powi_exact(fs, so.shininess);
    }
    (diff, spec)
}

/// Where an engine's `C_src` comes from.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Base {
    /// Evaluated at the pixel with the interpolated normal (per-pixel engines).
    PerPixel,
    /// Interpolated from the vertices (engines on a Gouraud rasteriser).
    Interpolated,
}

/// The final colour: `min(min(C_src + D, 1) · T + S, 1)`, D and S gated by the object's
/// diffuse and specular flags.
pub fn finish(p: &Prepared, hit: &Hit, g: &PixelGeom, base: Base, diff: DVec3, spec: DVec3) -> DVec3 {
    let so = &p.scene.objects[hit.obj as usize];
    let c = match base {
        Base::PerPixel => gouraud_colour(p.scene, g.p, g.n.try_normalize().unwrap_or(DVec3::Z)),
        Base::Interpolated => g.c_src,
    }
    .clamp(DVec3::ZERO, DVec3::ONE);
    let d = if so.diffuse { diff } else { DVec3::ZERO };
    let s = if so.specular { spec } else { DVec3::ZERO };
    let tex = crate::raster::assets::texture_at(so, g.uv);
    ((c + d).min(DVec3::ONE) * tex + s).min(DVec3::ONE)
}

/// Diffuse and specular factors of tangent-space vectors: bump normal `nb` against light
/// `l` and half vector `h` (either interpolated, not renormalised unless the engine does),
/// clamped to [0, 1]; with the scene's self-shadowing, cut where the light is below the
/// surface (`l.z <= 0`) as the Cg Tutorial §8.5.3 does.
pub fn tangent_factors(p: &Prepared, nb: DVec3, l: DVec3, h: DVec3) -> (f64, f64) {
    let fd = nb.dot(l).clamp(0.0, 1.0);
    let fs = nb.dot(h).clamp(0.0, 1.0);
    if p.scene.self_shadowing && (l.z <= 0.0 || nb.dot(l) <= 0.0) {
        return (if l.z <= 0.0 { 0.0 } else { fd }, 0.0);
    }
    (fd, fs)
}
