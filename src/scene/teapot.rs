//! Newell's Utah teapot (public-domain Bezier data in `teapot.dat`), evaluated as bicubic
//! patches with their partial derivatives.

use glam::DVec3;

const DATA: &str = include_str!("teapot.dat");

/// The 32 patches, each as 16 control points (row-major).
pub fn patches() -> Vec<[DVec3; 16]> {
    let mut verts = Vec::new();
    let mut idx = Vec::new();
    for line in DATA.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f64> = it.map(|x| x.parse().expect("teapot.dat number")).collect();
                verts.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("p") => idx.push(it.map(|x| x.parse::<usize>().expect("teapot.dat index")).collect::<Vec<_>>()),
            _ => {}
        }
    }
    // Centre the teapot on the origin: the data sits on z = 0 with its rim at z ≈ 2.4.
    idx.iter()
        .map(|p| std::array::from_fn(|k| verts[p[k]] - DVec3::new(0.0, 0.0, 1.575)))
        .collect()
}

fn bern(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    (
        [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t],
        [-3.0 * s * s, 3.0 * s * s - 6.0 * t * s, 6.0 * t * s - 3.0 * t * t, 3.0 * t * t],
    )
}

/// Position and partial derivatives of `patch` at (u, v). The data's rows run along v; the
/// normal ∂P/∂u × ∂P/∂v points out of the body for this orientation.
pub fn eval(patch: &[DVec3; 16], u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
    let (bu, du) = bern(u);
    let (bv, dv) = bern(v);
    let (mut p, mut pu, mut pv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for i in 0..4 {
        for j in 0..4 {
            let c = patch[i * 4 + j];
            p += c * bv[i] * bu[j];
            pu += c * bv[i] * du[j];
            pv += c * dv[i] * bu[j];
        }
    }
    // Degenerate edges (lid knob, bottom centre) have a zero derivative: step inside a little.
    if pu.length_squared() < 1e-16 || pv.length_squared() < 1e-16 {
        let (u2, v2) = (u.clamp(1e-4, 1.0 - 1e-4), v.clamp(1e-4, 1.0 - 1e-4));
        if (u2, v2) != (u, v) {
            let (_, a, b) = eval(patch, u2, v2);
            return (p, a, b);
        }
    }
    (p, pu, pv)
}
