//! SGI (paper §3.4, Peercy et al. 1997): a tangent-space normal map (Eq. 1, here with k = 1,
//! the map every engine reads), L and H transformed into each vertex's tangent space by the
//! geometry engine and interpolated over the triangle, lit per pixel by dot products with the
//! map's normal. Assumptions: the interpolated L and H are not renormalised (the text
//! interpolates them "homogeneously" and says no more); each light's k and spot factor is
//! taken at the vertices and interpolated with them; the map's normal is what the texture
//! unit's filter makes of the stored unit normals, not renormalised after filtering (the text
//! normalises the map's entries, Eq. 1, and says nothing of filtering); and there is no
//! self-shadowing term (§3.4 has none; the Cg Tutorial's §8.5.3 adds one). So the per-fragment
//! datapath is exactly the one `gouraud_hl` generates, fed per-vertex k (`interpolate_k`): the
//! bit-accurate path is that top, the scene's blend order and flat bypass replaced by this
//! engine's combination.

use super::common::{corners, finish, map_normal, mix, Base};
use super::{Cost, Ctx, Engine, PerFragment};
use crate::config::Interpolate;
use crate::model::power_table::powi_exact;
use crate::raster::{Hit, PixelGeom};
use crate::scene::lighting::spot_factor;
use glam::DVec3;

pub const SGI: Engine = Engine {
    name: "sgi",
    source: "paper §3.4 (SGI), Eq. 1: tangent-space normal map, per-vertex L and H in tangent space, interpolated",
    per_triangle: "L and H per light per vertex in that vertex's tangent space (18 words a light)",
    per_fragment: "uv; L and H per light (6 words a light, not renormalised)",
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
        renormalise: false,
        interpolate_k: true,
        renormalise_bump: false,
        ..PerFragment::PER_TRIANGLE
    }),
};

fn shade(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let p = c.p;
    let so = &p.scene.objects[hit.obj as usize];
    let v = corners(p, hit);
    let nb = map_normal(c, hit, g);
    let (mut diff, mut spec) = (DVec3::ZERO, DVec3::ZERO);
    // Each light's L and H at each vertex in that vertex's tangent space.
    let vv = crate::raster::tri_state::vertex_vectors(p.scene, &p.camera, &v);
    for (l, at) in p.scene.bump_lights().zip(&vv) {
        let lt = mix(hit, |i| at[i].0);
        let ht = mix(hit, |i| at[i].1);
        let k = mix(hit, |i| DVec3::splat(l.k * spot_factor(l, v[i].p))).x;
        let (fd, fs) = (nb.dot(lt).clamp(0.0, 1.0), nb.dot(ht).clamp(0.0, 1.0));
        let lc = DVec3::from_array(l.colour) * k;
        diff += lc * fd;
        spec += lc * powi_exact(fs, so.shininess);
    }
    finish(p, hit, g, Base::Interpolated, diff, spec)
}
