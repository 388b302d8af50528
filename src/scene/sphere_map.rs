//! The sphere map of Direct3D 6 environment-mapped bump mapping (paper §3.3) in a scene's
//! terms, f64: where a normal reads it (its view-space (right, up) components, texel i of n
//! a side centred at (i + 1/2)·2/n − 1, the rim beyond the unit disc taking the rim's
//! normal), a triangle's 2×2 matrix (the (right, up) components of its T and B), an object's
//! centre, a texel's lighting (the scene's bump lights taken as distant at that centre: the
//! map's lights are stationary) and the bilinear read. The `embm` engine, EMBM's f64
//! equations (`reference::embm_f64`) and its setup (`raster::env_setup`) all build on it.

use crate::model::power_table::powi_exact;
use crate::scene::lighting::{half_vector, light_dir, spot_factor};
use crate::scene::mesh::{triangle_frame, Mesh, Vertex};
use crate::scene::{Camera, Scene};
use glam::{DVec2, DVec3};

/// Where a normal reads the sphere map: its unit direction's (right, up) components (the
/// viewer's direction for a zero normal).
pub fn sphere_coords(cam: &Camera, n: DVec3) -> DVec2 {
    let n = n.try_normalize().unwrap_or(cam.to_viewer);
    DVec2::new(n.dot(cam.right), n.dot(cam.up))
}

/// The map coordinates at the hit: the vertex normals' coordinates interpolated.
pub fn coords_at(cam: &Camera, v: &[Vertex; 3], bary: [f64; 3]) -> DVec2 {
    (0..3).map(|i| sphere_coords(cam, v[i].n) * bary[i]).sum()
}

/// The triangle's 2×2 matrix: its columns ds/du and ds/dv, the view-space (right, up)
/// components of its T and B (the averaged, re-orthonormalised frame the setup sends).
pub fn triangle_matrix(cam: &Camera, v: &[Vertex; 3]) -> [DVec2; 2] {
    let (_, t, b) = triangle_frame(v);
    [
        DVec2::new(t.dot(cam.right), t.dot(cam.up)),
        DVec2::new(b.dot(cam.right), b.dot(cam.up)),
    ]
}

/// The mean of a mesh's vertices: where an object's map lights are evaluated.
pub fn centre(mesh: &Mesh) -> DVec3 {
    mesh.verts.iter().map(|v| v.p).sum::<DVec3>() / mesh.verts.len().max(1) as f64
}

/// Texel (x, y)'s centre in map coordinates, of a map `side` texels a side.
pub fn texel_centre(side: u32, x: u32, y: u32) -> (f64, f64) {
    let c = |i: u32| (i as f64 + 0.5) / side as f64 * 2.0 - 1.0;
    (c(x), c(y))
}

/// The diffuse and specular lighting of object `obj` (centre `centre`) for the normal the
/// sphere map places at (sx, sy).
pub fn texel(scene: &Scene, cam: &Camera, obj: usize, centre: DVec3, sx: f64, sy: f64) -> (DVec3, DVec3) {
    let r = (sx * sx + sy * sy).sqrt();
    let (sx, sy) = if r > 1.0 { (sx / r, sy / r) } else { (sx, sy) };
    let nz = (1.0 - sx * sx - sy * sy).max(0.0).sqrt();
    let n = (cam.right * sx + cam.up * sy + cam.to_viewer * nz).normalize();
    let shininess = scene.objects[obj].shininess;
    let (mut d, mut s) = (DVec3::ZERO, DVec3::ZERO);
    for l in scene.bump_lights() {
        let ld = light_dir(l, centre, n);
        let hd = half_vector(ld, cam.to_viewer);
        let lc = DVec3::from_array(l.colour) * (l.k * spot_factor(l, centre));
        d += lc * n.dot(ld).max(0.0);
        s += lc * powi_exact(n.dot(hd).max(0.0), shininess);
    }
    (d, s)
}

/// Both maps read bilinearly at map coordinates `s`, `side` texels a side, texel (x, y)
/// given by `at` (its diffuse and specular colour).
pub fn lookup(side: u32, s: DVec2, at: impl Fn(u32, u32) -> (DVec3, DVec3)) -> (DVec3, DVec3) {
    let n = side as f64;
    // Texel i's centre at s = (i + 1/2)·2/n − 1; the grid's edge clamps.
    let axis = |s: f64| {
        let x = ((s + 1.0) * 0.5 * n - 0.5).clamp(0.0, n - 1.0);
        let x0 = x.floor().min(n - 2.0).max(0.0);
        (x0 as u32, x - x0)
    };
    let ((x0, fx), (y0, fy)) = (axis(s.x), axis(s.y));
    let (mut d, mut sp) = (DVec3::ZERO, DVec3::ZERO);
    for (dx, dy, w) in [
        (0, 0, (1.0 - fx) * (1.0 - fy)),
        (1, 0, fx * (1.0 - fy)),
        (0, 1, (1.0 - fx) * fy),
        (1, 1, fx * fy),
    ] {
        let (td, ts) = at(x0 + dx, y0 + dy);
        d += td * w;
        sp += ts * w;
    }
    (d, sp)
}
