//! normalise_cube: an interpolated L or H scaled to unit length by a normalisation cube map
//! (Cg Tutorial §8.2), as a texture unit reads one: the vector's largest component picks the
//! face, the other two divided by it pick the texel, and the texel holds the unit vector
//! through its centre. No square root and no multiplier; the error is the map's resolution
//! (a direction is off by at most half a texel's diagonal), which `cube_map_face` trades for
//! memory.
//!
//! With `face` = 2^c texels along an edge (`cube_map_face`):
//!
//! 1. The major axis is x when |x| >= |y| and |x| >= |z|, else y when |y| >= |z|, else z (the
//!    order `reference::cube_map::cube_normalise` uses); its magnitude is `m`, and a zero vector
//!    stays zero.
//! 2. Each minor component p (y and z for x, x and z for y, x and y for z) picks the texel
//!    `i = min(floor((p + m) · face / (2m)), face - 1)`: an exact integer division with a
//!    (c+1)-bit quotient, the texture unit's face-coordinate divide.
//! 3. The six faces are one face turned and the face is symmetric about its centre lines,
//!    so the map is a quarter face: word `(a, b)` for `a, b < face/2` holds the unit vector
//!    through texel centre `((2a+1)/face, (2b+1)/face, 1)`, each component rounded to the
//!    output's LSB (`round(c · 2^F · scale)`, half up, with the scale L and H carry).
//!    Texel i reads quarter index `i - face/2` above the centre line and `face/2 - 1 - i`
//!    below it, where the component is negated.
//! 4. The major component takes the word's third value with v's sign there.

use super::normalise::Shape;
use crate::config::PipelineConfig;

/// The two minor axes of each major axis, in the order the texel indices are formed.
pub const MINORS: [[usize; 2]; 3] = [[1, 2], [0, 2], [0, 1]];

/// The major axis of `v`: the largest magnitude, ties going to the earlier axis.
pub fn major_axis(v: [i64; 3]) -> usize {
    let a = v.map(i64::abs);
    if a[0] >= a[1] && a[0] >= a[2] {
        0
    } else if a[1] >= a[2] {
        1
    } else {
        2
    }
}

/// Texel index along one face edge of `face` texels for minor component `p` of a vector
/// whose major magnitude is `m` (> 0, |p| <= m).
pub fn texel(p: i64, m: i64, face: u32) -> u32 {
    let q = ((p + m) as i128 * (face as i128 / 2)) / m as i128;
    (q as u32).min(face - 1)
}

/// The quarter-face index of texel `i` and whether the component is negative there.
pub fn quarter(i: u32, face: u32) -> (u32, bool) {
    let h = face / 2;
    if i >= h {
        (i - h, false)
    } else {
        (h - 1 - i, true)
    }
}

/// The unit vector through the centre of quarter-face texel `(a, b)`, unrounded, times the
/// unit length `shape` carries, in its LSBs: (minor 1, minor 2, major).
pub fn centre_direction(shape: &Shape, face: u32, a: u32, b: u32) -> [f64; 3] {
    let c = |k: u32| (2 * k + 1) as f64 / face as f64;
    let (u, w) = (c(a), c(b));
    let len = (u * u + w * w + 1.0).sqrt();
    let s = (shape.frac as f64).exp2() * shape.scale();
    [u / len * s, w / len * s, s / len]
}

/// Map word `(a, b)`: [`centre_direction`] rounded half up. Computed from correctly rounded
/// f64 operations, so every platform agrees.
pub fn word(shape: &Shape, face: u32, a: u32, b: u32) -> [i64; 3] {
    centre_direction(shape, face, a, b).map(|x| (x + 0.5).floor() as i64)
}

/// Words in the quarter face of a `face`-texel map.
pub fn words(face: u32) -> u32 {
    (face / 2) * (face / 2)
}

/// Bits of a word's largest component: the major's `2^F · scale` at most, unsigned.
pub fn component_bits(shape: &Shape) -> u32 {
    shape.width - 1
}

/// The texel `v` pierces: (major axis, the minors' quarter indices and signs). None for a
/// zero vector.
pub fn lookup(face: u32, v: [i64; 3]) -> Option<(usize, [(u32, bool); 2])> {
    let major = major_axis(v);
    let m = v[major].abs();
    if m == 0 {
        return None;
    }
    let q = MINORS[major].map(|k| quarter(texel(v[k], m, face), face));
    Some((major, q))
}

/// Place a word's values, unrounded or rounded, into x, y, z with their signs.
fn place<T: Copy + std::ops::Neg<Output = T>>(v: [i64; 3], major: usize, q: [(u32, bool); 2], w: [T; 3]) -> [T; 3] {
    let mut out = [w[2]; 3];
    out[major] = if v[major] < 0 { -w[2] } else { w[2] };
    for (k, &axis) in MINORS[major].iter().enumerate() {
        out[axis] = if q[k].1 { -w[k] } else { w[k] };
    }
    out
}

/// The normalised L or H, raw `s1.F` components: the unit's arithmetic.
pub fn cube_normalise(cfg: &PipelineConfig, v: [i64; 3]) -> [i64; 3] {
    let face = cfg.cube_map_face;
    match lookup(face, v) {
        None => [0; 3],
        Some((major, q)) => place(v, major, q, word(&Shape::lh(cfg), face, q[0].0, q[1].0)),
    }
}

/// The same without the map's rounding: the direction through the texel's centre, in output
/// LSBs (the texel choice is the map's approximation, not a rounding, so it is kept).
pub fn cube_normalise_exact(cfg: &PipelineConfig, v: [i64; 3]) -> [f64; 3] {
    let face = cfg.cube_map_face;
    match lookup(face, v) {
        None => [0.0; 3],
        Some((major, q)) => place(v, major, q, centre_direction(&Shape::lh(cfg), face, q[0].0, q[1].0)),
    }
}

/// Largest angle, in radians, between a vector and the direction the map returns for it
/// (before rounding): half a texel's diagonal seen from the face's centre, at the face's
/// centre where a texel subtends the most, `atan(√2 / face)`.
pub fn angle_bound(face: u32) -> f64 {
    (2f64.sqrt() / face as f64).atan()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn cfg(face: u32) -> PipelineConfig {
        PipelineConfig {
            bump_state: crate::config::BumpStateAt::Fragment,
            interpolate: crate::config::Interpolate::Hl,
            renormalise: true,
            light_mode: crate::config::LightMode::Parallel,
            cube_map_face: face,
            ..Default::default()
        }
    }

    /// The integer texel choice is the f64 engine's (`reference::cube_map::cube_normalise`), away from
    /// texel edges where f64's division may round either way; the result's direction is
    /// within the map's angle bound plus its rounding, for every face size.
    #[test]
    fn agrees_with_the_f64_cube_map_and_stays_within_its_bound() {
        let mut rng = crate::vectors::rng::SplitMix64(5);
        for face in [4u32, 8, 16, 32, 64, 128] {
            let c = cfg(face);
            let one = (1i64 << (c.lh_bits - 2)) as f64;
            for _ in 0..20_000 {
                let v = [0; 3].map(|_| rng.range(-(1 << 14), 1 << 14));
                let got = cube_normalise(&c, v);
                let d = DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64);
                if d.length() == 0.0 {
                    assert_eq!(got, [0; 3]);
                    continue;
                }
                let f = crate::reference::cube_map::cube_normalise(d, face) * one;
                let g = DVec3::new(got[0] as f64, got[1] as f64, got[2] as f64);
                // Rounding moves each component by half an LSB at most.
                assert!(
                    (g - f).abs().max_element() <= 0.5 + 1e-9 || near_edge(v, face),
                    "face {face} v {v:?}: {g} vs {f}"
                );
                let angle = g.normalize().dot(d.normalize()).clamp(-1.0, 1.0).acos();
                assert!(angle <= angle_bound(face) + 2.0 / one, "face {face} v {v:?}: {angle}");
                assert!(
                    (g.length() / one - 1.0).abs() <= 1.5 / one,
                    "face {face} v {v:?}: length {}",
                    g.length() / one
                );
            }
        }
    }

    /// Whether a minor component of `v` lies within a rounding of a texel edge.
    fn near_edge(v: [i64; 3], face: u32) -> bool {
        let major = major_axis(v);
        let m = v[major].abs() as f64;
        MINORS[major].iter().any(|&k| {
            let t = (v[k] as f64 + m) * face as f64 / (2.0 * m);
            (t - t.round()).abs() < 1e-9
        })
    }

    #[test]
    fn axes_signs_and_edges() {
        let c = cfg(32);
        let one = 1i64 << 14;
        // An axis pierces the face's four central texels: their common corner's direction.
        let z = cube_normalise(&c, [0, 0, one]);
        assert!(z[2] > 0 && z[0] == z[1] && z[0] > 0, "{z:?}");
        let nz = cube_normalise(&c, [0, 0, -one]);
        assert_eq!(nz, [z[0], z[1], -z[2]]);
        // The faces are one face turned: the same minors on another axis give the same word.
        assert_eq!(cube_normalise(&c, [3000, -one, 7000]), {
            let w = cube_normalise(&c, [3000, 7000, -one]);
            [w[0], w[2], w[1]]
        });
        // Sign symmetry: negating a minor negates its component.
        let a = cube_normalise(&c, [5000, 9000, one]);
        let b = cube_normalise(&c, [-5000, 9000, one]);
        assert_eq!(b, [-a[0], a[1], a[2]]);
        // A minor equal to the major lands in the last texel, not past it.
        assert_eq!(texel(one, one, 32), 31);
        assert_eq!(texel(-one, one, 32), 0);
        // Ties between axes go to the earlier one.
        assert_eq!(major_axis([7, -7, 7]), 0);
        assert_eq!(major_axis([1, -7, 7]), 1);
        assert_eq!(cube_normalise(&c, [0; 3]), [0; 3]);
    }
}
