//! Tessellation of the scene's shapes into triangles with per-vertex tangent frames and uv.
//! Each shape is a map from the parameter square [0,1]² to a surface; the tangent is ∂P/∂u,
//! orthonormalised against the normal, and the binormal N × T, which gives the paper's
//! orthogonal P_u, P_v axes (§5.4.3).

use super::{teapot, Object, Shape};
use glam::{DMat3, DVec2, DVec3};
use std::f64::consts::{PI, TAU};

#[derive(Clone, Copy, Debug)]
pub struct Vertex {
    pub p: DVec3,
    pub n: DVec3,
    /// Unit tangent along +u, orthogonal to `n`.
    pub t: DVec3,
    /// Unit binormal along +v: `n × t`, flipped if the uv mapping is mirrored.
    pub b: DVec3,
    pub uv: DVec2,
}

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub verts: Vec<Vertex>,
    pub tris: Vec<[u32; 3]>,
}

impl Mesh {
    /// The three vertices of triangle `tri`.
    pub fn corners(&self, tri: u32) -> [Vertex; 3] {
        self.tris[tri as usize].map(|i| self.verts[i as usize])
    }
}

/// A triangle's own frame (N, T, B): its vertex frames averaged and re-orthonormalised, the
/// frame the Gouraud setup sends L and H in (and VISA+'s alignment matrix and EMBM's 2×2
/// matrix are built from).
pub fn triangle_frame(v: &[Vertex; 3]) -> (DVec3, DVec3, DVec3) {
    frame(v[0].n + v[1].n + v[2].n, v[0].t + v[1].t + v[2].t, v[0].b + v[1].b + v[2].b)
}

/// The triangle's plane frame (N, T, B): its geometric normal (turned to the vertex normals'
/// side) and the vertex tangents made orthogonal to it, the "tangent plane system" VISA+'s
/// alignment matrix is built from, the same on both triangles of a flat quad.
pub fn plane_frame(v: &[Vertex; 3]) -> (DVec3, DVec3, DVec3) {
    let mut n = (v[1].p - v[0].p).cross(v[2].p - v[0].p);
    if n.dot(v[0].n + v[1].n + v[2].n) < 0.0 {
        n = -n;
    }
    frame(n, v[0].t + v[1].t + v[2].t, v[0].b + v[1].b + v[2].b)
}

/// Orthonormal frame from a normal and raw partial derivatives; zero-length inputs (poles,
/// degenerate patches) fall back to a frame built from whatever is left, documented in
/// ARCHITECTURE.md.
pub fn frame(n: DVec3, pu: DVec3, pv: DVec3) -> (DVec3, DVec3, DVec3) {
    let n = n.try_normalize().or_else(|| pu.cross(pv).try_normalize()).unwrap_or(DVec3::Z);
    let mut t = (pu - n * n.dot(pu)).try_normalize().unwrap_or(DVec3::ZERO);
    if t == DVec3::ZERO {
        // (T, ∂P/∂v, N) right-handed: T = ∂P/∂v × N, as ∂P/∂u would point.
        t = pv.cross(n).try_normalize().unwrap_or_else(|| n.any_orthonormal_vector());
    }
    let mut b = n.cross(t);
    if pv.length_squared() > 0.0 && b.dot(pv) < 0.0 {
        b = -b;
    }
    (n, t, b)
}

/// Grid tessellation of a parametric surface `f(u, v) -> (P, ∂P/∂u, ∂P/∂v)`.
fn grid(segs: [u32; 2], uv_scale: [f64; 2], f: impl Fn(f64, f64) -> (DVec3, DVec3, DVec3), mesh: &mut Mesh) {
    let (su, sv) = (segs[0] as usize, segs[1] as usize);
    let base = mesh.verts.len() as u32;
    for j in 0..=sv {
        for i in 0..=su {
            let (u, v) = (i as f64 / su as f64, j as f64 / sv as f64);
            let (p, pu, pv) = f(u, v);
            let (n, t, b) = frame(pu.cross(pv), pu, pv);
            mesh.verts.push(Vertex {
                p,
                n,
                t,
                b,
                uv: DVec2::new(u * uv_scale[0], v * uv_scale[1]),
            });
        }
    }
    let row = su as u32 + 1;
    for j in 0..sv as u32 {
        for i in 0..su as u32 {
            let a = base + j * row + i;
            mesh.tris.push([a, a + 1, a + row + 1]);
            mesh.tris.push([a, a + row + 1, a + row]);
        }
    }
}

/// The fewest segments (around u, along v) that give `shape` a solid of non-zero area: a
/// closed shape needs three sides around a circle (two make a flat double-sided sliver, one a
/// line), and a sphere two bands from pole to pole; a prism's sides replace `segments[0]`.
pub fn min_segments(shape: &Shape) -> [u32; 2] {
    match shape {
        Shape::Sphere { .. } => [3, 2],
        Shape::Torus { .. } => [3, 3],
        Shape::Cylinder { sides: 0, .. } => [3, 1],
        Shape::Cylinder { .. } | Shape::Plane { .. } | Shape::Teapot {} => [1, 1],
    }
}

/// Triangles `tessellate` makes of `o`, counted before any is built (see `limits.rs`).
pub fn triangle_count(o: &Object) -> u64 {
    let [su, sv] = o.segments.map(u64::from);
    match &o.shape {
        Shape::Cylinder { sides, .. } if *sides > 0 => 2 * u64::from(*sides) * sv,
        Shape::Teapot {} => 32 * 2 * su * sv,
        _ => 2 * su * sv,
    }
}

/// Tessellate an object and place it in the world.
pub fn tessellate(o: &Object) -> Mesh {
    let mut m = Mesh::default();
    let s = o.segments;
    let uvs = o.uv_scale;
    match &o.shape {
        Shape::Plane { size } => {
            let (w, h) = (size[0], size[1]);
            grid(
                s,
                uvs,
                |u, v| (DVec3::new((u - 0.5) * w, (v - 0.5) * h, 0.0), DVec3::X * w, DVec3::Y * h),
                &mut m,
            );
        }
        Shape::Sphere { radius: r } => grid(
            s,
            uvs,
            |u, v| {
                let (th, ph) = (u * TAU, (v - 0.5) * PI);
                let p = DVec3::new(ph.cos() * th.cos(), ph.cos() * th.sin(), ph.sin()) * *r;
                let pu = DVec3::new(-ph.cos() * th.sin(), ph.cos() * th.cos(), 0.0) * r * TAU;
                let pv = DVec3::new(-ph.sin() * th.cos(), -ph.sin() * th.sin(), ph.cos()) * r * PI;
                // At the poles ∂P/∂u vanishes; it is replaced by ∂P/∂v × N, the direction it
                // takes beside the pole, so ∂P/∂u × ∂P/∂v stays the outward normal (N × ∂P/∂v
                // pointed it into the sphere: a dark disc at each pole).
                let n = p.normalize();
                (p, if pu.length() < 1e-9 { pv.cross(n) } else { pu }, pv)
            },
            &mut m,
        ),
        Shape::Cylinder {
            radius: r,
            height: h,
            sides,
        } => {
            let segs = if *sides > 0 { [*sides, s[1]] } else { s };
            grid(
                segs,
                uvs,
                |u, v| {
                    let th = u * TAU;
                    let p = DVec3::new(r * th.cos(), r * th.sin(), (v - 0.5) * h);
                    (p, DVec3::new(-th.sin(), th.cos(), 0.0) * r * TAU, DVec3::Z * *h)
                },
                &mut m,
            );
            if *sides > 0 {
                facet_cylinder(&mut m, *sides as usize, s[1] as usize);
            }
        }
        Shape::Torus { major: big, minor: small } => grid(
            s,
            uvs,
            |u, v| {
                let (a, b) = (u * TAU, v * TAU);
                let ring = big + small * b.cos();
                let p = DVec3::new(ring * a.cos(), ring * a.sin(), small * b.sin());
                let pu = DVec3::new(-ring * a.sin(), ring * a.cos(), 0.0) * TAU;
                let pv = DVec3::new(-small * b.sin() * a.cos(), -small * b.sin() * a.sin(), small * b.cos()) * TAU;
                (p, pu, pv)
            },
            &mut m,
        ),
        Shape::Teapot {} => {
            for patch in teapot::patches() {
                grid(s, uvs, |u, v| teapot::eval(&patch, u, v), &mut m);
            }
        }
    }
    place(&mut m, o);
    m
}

/// A prism's facets are flat: give each facet its own vertices with the facet's normal, so
/// Gouraud shading is flat per facet and only the baked bump map can make it look round.
fn facet_cylinder(m: &mut Mesh, sides: usize, rows: usize) {
    let old = std::mem::take(m);
    let row = sides + 1;
    for i in 0..sides {
        let v00 = old.verts[i];
        let v10 = old.verts[i + 1];
        let n = ((v00.n + v10.n) * 0.5).normalize();
        let t = (v10.p - v00.p).normalize();
        let base = m.verts.len() as u32;
        for j in 0..=rows {
            for k in [i, i + 1] {
                let src = old.verts[j * row + k];
                // Facet-local u runs 0..1 across the facet so the baked map repeats per facet.
                let u = if k == i { 0.0 } else { 1.0 };
                m.verts.push(Vertex {
                    p: src.p,
                    n,
                    t,
                    b: n.cross(t),
                    uv: DVec2::new(u, src.uv.y),
                });
            }
        }
        for j in 0..rows as u32 {
            let a = base + 2 * j;
            m.tris.push([a, a + 1, a + 3]);
            m.tris.push([a, a + 3, a + 2]);
        }
    }
}

fn place(m: &mut Mesh, o: &Object) {
    let r = o.rotate_deg.map(f64::to_radians);
    let rot = DMat3::from_rotation_z(r[2]) * DMat3::from_rotation_y(r[1]) * DMat3::from_rotation_x(r[0]);
    let tr = DVec3::from_array(o.translate);
    for v in &mut m.verts {
        v.p = rot * (v.p * o.scale) + tr;
        v.n = rot * v.n;
        v.t = rot * v.t;
        v.b = rot * v.b;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every object of every built-in scene with its mesh.
    fn builtin_meshes() -> Vec<(Object, Mesh)> {
        let mut v = Vec::new();
        for text in super::super::builtin::ALL.iter().map(|(_, t)| *t) {
            let s = super::super::Scene::from_toml("t", text, std::path::Path::new("scenes")).unwrap();
            v.extend(s.objects.into_iter().map(|o| {
                let m = tessellate(&o);
                (o, m)
            }));
        }
        v
    }

    #[test]
    fn frames_are_orthonormal_everywhere() {
        for (_, m) in builtin_meshes() {
            for v in &m.verts {
                assert!(v.n.is_finite() && v.t.is_finite() && v.b.is_finite());
                assert!((v.n.length() - 1.0).abs() < 1e-9 && (v.t.length() - 1.0).abs() < 1e-9);
                assert!(v.n.dot(v.t).abs() < 1e-9 && v.n.dot(v.b).abs() < 1e-9);
            }
        }
    }

    /// Every vertex normal of a sphere points away from its centre (a pole's normal once
    /// pointed in), and every frame is right-handed (no built-in shape mirrors its uv mapping).
    #[test]
    fn normals_point_outward_and_frames_are_right_handed() {
        for (o, m) in builtin_meshes() {
            let centre = m.verts.iter().map(|v| v.p).sum::<DVec3>() / m.verts.len() as f64;
            for v in &m.verts {
                assert!(v.t.cross(v.b).dot(v.n) > 0.5, "{:?}: left-handed frame at {:?}", o.shape, v.p);
                if matches!(o.shape, Shape::Sphere { .. }) {
                    assert!(v.n.dot(v.p - centre) > 0.0, "{:?}: inward normal at {:?}", o.shape, v.p);
                }
            }
        }
    }
}
