//! The Cg Tutorial's per-fragment bump mapping (§8.1–8.5): a tangent-space normal map; the
//! light direction and the half-angle vector formed per vertex in that vertex's tangent
//! space, interpolated, and normalised per fragment by a normalisation cube map; the specular
//! power by successive squarings; geometric self-shadowing (§8.5.3) where the scene asks for
//! it; the decal as the texture colour. Assumptions: the cube map has 32×32 texels a face
//! (the text's "typically sufficient") read nearest, each texel the unit vector through its
//! centre (its 8-bit range compression is arithmetic, the fixed-point model's part); the
//! exponent is the power of two nearest the material's shininess on a log scale (the text squares three
//! times for 8); no scene has a gloss map, so the gloss is 1; the normal map's sample is
//! range-expanded and used as the filter leaves it, not renormalised (Example 8-2's
//! `expand(tex2D(normalMap, …))`).
//!
//! The bit-accurate path is `gouraud_hl`'s datapath with the Cg pieces in hardware: L and H
//! interpolated per fragment and read through a `CUBE_FACE`-texel normalisation cube map
//! (`cube_map_face`, the `normalise_cube` unit), the specular power by successive squarings
//! (`power_unit = "squaring"`), and self-shadowing where the scene asks (`self_shadow`).
//! Where it departs from the f64 model above: each light's k (its spot factor) is taken at
//! the vertices and interpolated, as SGI's path does, not at the pixel, and the non-bump
//! colour C_src is interpolated from the vertices by the rasteriser rather than formed per
//! pixel; the map is always `CUBE_FACE` texels (`gbump engines --cg-cube` changes the f64
//! model's only).

use super::common::{corners, finish, map_normal, mix, tangent_factors, Base};
use super::{Cost, Ctx, Engine, PerFragment};
use crate::config::Interpolate;
use crate::model::power_unit::squarings_exponent;
use crate::raster::{Hit, PixelGeom};
use crate::reference::cube_map::cube_normalise;
use crate::scene::lighting::spot_factor;
use glam::DVec3;

pub const CG: Engine = Engine {
    name: "cg",
    source: "Cg Tutorial §8.1–8.5: normal map, normalisation cube map, squarings, self-shadowing, decal",
    per_triangle: "L and H per light per vertex in tangent space (18 words a light)",
    per_fragment: "uv; L and H per light (6 words a light), two cube-map reads a light",
    cost: Cost {
        triangle: 0,
        triangle_per_light: 18,
        fragment: 0,
        fragment_per_light: 6,
    },
    shade,
    scene_blend: false,
    fixed: Some(PerFragment {
        interpolate: Interpolate::Hl,
        renormalise: true,
        interpolate_k: true,
        renormalise_bump: false,
        cube_map_face: CUBE_FACE,
        squaring: true,
        self_shadow: true,
        ..PerFragment::PER_TRIANGLE
    }),
};

/// Texels along a cube-map face edge by default (`gbump engines --cg-cube` changes it).
pub const CUBE_FACE: u32 = 32;

fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let p = c.p;
    let so = &p.scene.objects[hit.obj as usize];
    let v = corners(p, hit);
    let nb = map_normal(c, hit, g);
    let e = squarings_exponent(so.shininess);
    let (mut diff, mut spec) = (DVec3::ZERO, DVec3::ZERO);
    // Each light's L and H at each vertex in that vertex's tangent space.
    let vv = crate::raster::tri_state::vertex_vectors(p.scene, &p.camera, &v);
    for (l, at) in p.scene.bump_lights().zip(&vv) {
        let lt = cube_normalise(mix(hit, |i| at[i].0), c.cg_cube);
        let ht = cube_normalise(mix(hit, |i| at[i].1), c.cg_cube);
        let (fd, fs) = tangent_factors(p, nb, lt, ht);
        // The spot factor at the pixel's interpolated position (the Tutorial's lights have no
        // cone; a per-pixel cone keeps the comparison about normalisation alone).
        let lc = DVec3::from_array(l.colour) * (l.k * spot_factor(l, g.p));
        diff += lc * fd;
        spec += lc * fs.powi(e as i32);
    }
    finish(p, hit, g, Base::PerPixel, diff, spec)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cube_map_gives_unit_vectors_near_the_direction() {
        for v in [DVec3::new(3.0, 1.5, 0.9), DVec3::new(-0.2, 0.1, -4.0), DVec3::new(0.0, -2.0, 0.3)] {
            let c = cube_normalise(v, 32);
            assert!((c.length() - 1.0).abs() < 1e-12);
            // A texel's half-diagonal is √2/32 in face units at unit distance: the direction
            // through its centre is at most atan(√2/32) off.
            assert!(c.dot(v.normalize()) >= (2.0f64.sqrt() / 32.0).atan().cos(), "{v} -> {c}");
        }
        // The Tutorial's example: (3, 1.5, 0.9) is about (0.86, 0.43, 0.26), here within the
        // texel's half-diagonal (√2/32 ≈ 0.044).
        let c = cube_normalise(DVec3::new(3.0, 1.5, 0.9), 32);
        assert!((c - DVec3::new(0.86, 0.43, 0.26)).length() < 0.044, "{c}");
    }

    #[test]
    fn squarings_reach_the_nearest_power_of_two() {
        assert_eq!(
            [0, 1, 2, 3, 6, 8, 11, 12, 24, 32, 45].map(squarings_exponent),
            [0, 1, 2, 4, 8, 8, 8, 16, 32, 32, 32]
        );
    }
}
