//! Direct3D 6 environment-mapped bump mapping (paper §3.3): the lighting lives in an
//! environment map, and the bump map's (du, dv), through a 2×2 matrix, perturbs the map
//! coordinates per pixel. Assumptions: the map is a sphere map of the normal in view space
//! (coordinates (N·right, N·up), texel centres on a square grid), `EMBM_MAP` texels a side,
//! read bilinearly; the bump map's (du, dv) are the bump normal's tangent components (what
//! moves a unit normal's sphere-map coordinates, so a plane facing the viewer is exact); it
//! holds the diffuse and the specular lighting of the object's material
//! from the scene's bump lights taken as distant (their direction and spot factor at the
//! object's centre: the map's lights are stationary); the map coordinates are interpolated
//! from the vertices, and the 2×2 matrix is held per triangle, the view-space right and up
//! components of the triangle's T and B. Moving one light regenerates both maps of every
//! object it lights: `2 · EMBM_MAP²` texels each.

use super::common::{bump_normal, corners, finish, mix, Base};
use super::{Cost, Ctx, Engine};
use crate::model::power_table::powi_exact;
use crate::raster::{Hit, PixelGeom};
use crate::scene::lighting::{half_vector, light_dir, spot_factor};
use crate::scene::mesh::triangle_frame;
use glam::{DVec2, DVec3};

/// Texels along the environment map's side by default (`gbump engines --embm-map` changes it).
pub const EMBM_MAP: u32 = 64;

pub const EMBM: Engine = Engine {
    name: "embm",
    source: "paper §3.3 (Direct3D 6): (du, dv) through a 2×2 matrix perturbs environment-map coordinates",
    per_triangle: "the 2×2 matrix (4 words); the maps per object (2 · 64² texels at the default size)",
    per_fragment: "the map coordinates (2 words) and uv; four texels of two maps",
    cost: Cost {
        triangle: 10,
        triangle_per_light: 0,
        fragment: 2,
        fragment_per_light: 0,
    },
    shade,
    scene_blend: false,
    fixed: None,
};

/// The EMBM colour with the context's `embm_map`×`embm_map` environment map.
fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let p = c.p;
    let cam = &p.camera;
    let v = corners(p, hit);
    let st = |n: DVec3| {
        let n = n.try_normalize().unwrap_or(cam.to_viewer);
        DVec2::new(n.dot(cam.right), n.dot(cam.up))
    };
    let s0 = mix(hit, |i| st(v[i].n).extend(0.0)).truncate();
    let (_, t, b) = triangle_frame(&v);
    // The map is indexed by a unit normal's tangent-plane components, so the bump map's
    // (du, dv) are its normal's x and y: a tilt moves the coordinates by its sine.
    let nb = bump_normal(p, hit, g);
    let (du, dv) = (nb.x, nb.y);
    let m = [
        DVec2::new(t.dot(cam.right), t.dot(cam.up)),
        DVec2::new(b.dot(cam.right), b.dot(cam.up)),
    ];
    let s = s0 + m[0] * du + m[1] * dv;
    let (diff, spec) = lookup(c, hit.obj as usize, s);
    finish(p, hit, g, Base::Interpolated, diff, spec)
}

/// The two maps of object `obj` read bilinearly at sphere-map coordinates `s`.
fn lookup(c: &Ctx, obj: usize, s: DVec2) -> (DVec3, DVec3) {
    let n = c.embm_map as f64;
    // Texel (i, j) has its centre at ((i + 0.5) / n · 2 − 1, …); clamp to the grid's edge.
    let x = ((s.x + 1.0) * 0.5 * n - 0.5).clamp(0.0, n - 1.0);
    let y = ((s.y + 1.0) * 0.5 * n - 0.5).clamp(0.0, n - 1.0);
    let (x0, y0) = (x.floor().min(n - 2.0).max(0.0), y.floor().min(n - 2.0).max(0.0));
    let (fx, fy) = (x - x0, y - y0);
    let (mut d, mut sp) = (DVec3::ZERO, DVec3::ZERO);
    for (dx, dy, w) in [
        (0.0, 0.0, (1.0 - fx) * (1.0 - fy)),
        (1.0, 0.0, fx * (1.0 - fy)),
        (0.0, 1.0, (1.0 - fx) * fy),
        (1.0, 1.0, fx * fy),
    ] {
        let (td, ts) = texel(c, obj, (x0 + dx + 0.5) / n * 2.0 - 1.0, (y0 + dy + 0.5) / n * 2.0 - 1.0);
        d += td * w;
        sp += ts * w;
    }
    (d, sp)
}

/// One texel of the diffuse and specular maps: the lighting of the normal the sphere map
/// places at (sx, sy) (the disc's rim beyond it).
fn texel(c: &Ctx, obj: usize, sx: f64, sy: f64) -> (DVec3, DVec3) {
    let p = c.p;
    let cam = &p.camera;
    let r = (sx * sx + sy * sy).sqrt();
    let (sx, sy) = if r > 1.0 { (sx / r, sy / r) } else { (sx, sy) };
    let nz = (1.0 - sx * sx - sy * sy).max(0.0).sqrt();
    let n = (cam.right * sx + cam.up * sy + cam.to_viewer * nz).normalize();
    let so = &p.scene.objects[obj];
    let centre = c.centres[obj];
    let (mut d, mut s) = (DVec3::ZERO, DVec3::ZERO);
    for l in p.scene.bump_lights() {
        let ld = light_dir(l, centre, n);
        let hd = half_vector(ld, cam.to_viewer);
        let lc = DVec3::from_array(l.colour) * (l.k * spot_factor(l, centre));
        d += lc * n.dot(ld).max(0.0);
        s += lc * powi_exact(n.dot(hd).max(0.0), so.shininess);
    }
    (d, s)
}
