//! Gouraud bump mapping (paper §4–5) and the §6 improvements. The paper's engine holds each
//! light's L and H per triangle, in the triangle's bump frame, so the highlight is flat over
//! a triangle (Fig. 7); §6 proposes interpolating the half vector ("no flat shading effect")
//! and/or the light directions, one per light. Assumptions for the variants: an interpolated
//! vector is formed at each vertex in that vertex's own frame (so it follows the surface's
//! curvature as Phong's normal does) and is not renormalised, and k stays per triangle as in
//! the paper's bump state; the rest (clamps, blend order, skip_flat) is the paper's engine's
//! own (`reference::gouraud_f64::shade_with`).

use super::common::{corners, mix, to_frame};
use super::{Cost, Ctx, Engine};
use crate::raster::{Hit, PixelGeom, Prepared};
use crate::scene::lighting::{half_vector, light_dir};
use crate::scene::mesh::frame;
use glam::DVec3;

pub const GOURAUD: Engine = Engine {
    name: "gouraud",
    source: "paper §4–5: L and H per triangle in bump space, blended onto the Gouraud colour",
    per_triangle: "L, H, Lc, k per light (10 words a light)",
    per_fragment: "the Gouraud colour and uv: nothing per light",
    cost: Cost {
        triangle: 0,
        triangle_per_light: 10,
        fragment: 0,
        fragment_per_light: 0,
    },
    shade: shade_paper,
};

pub const GOURAUD_H: Engine = Engine {
    name: "gouraud_h",
    source: "paper §6: Gouraud bump mapping with the half vector interpolated",
    per_triangle: "L, Lc, k per light and H per light per vertex (16 words a light)",
    per_fragment: "the Gouraud colour, uv, H per light (3 words a light)",
    cost: Cost {
        triangle: 0,
        triangle_per_light: 16,
        fragment: 0,
        fragment_per_light: 3,
    },
    shade: shade_h,
};

pub const GOURAUD_HL: Engine = Engine {
    name: "gouraud_hl",
    source: "paper §6: Gouraud bump mapping with the half vector and the light direction interpolated",
    per_triangle: "Lc, k per light and L and H per light per vertex (22 words a light)",
    per_fragment: "the Gouraud colour, uv, L and H per light (6 words a light)",
    cost: Cost {
        triangle: 0,
        triangle_per_light: 22,
        fragment: 0,
        fragment_per_light: 6,
    },
    shade: shade_hl,
};

fn shade_paper(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::gouraud_f64::shade(c.p, hit, g)
}

fn shade_h(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    shade_with(c.p, hit, g, false)
}

fn shade_hl(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    shade_with(c.p, hit, g, true)
}

fn shade_with(p: &Prepared, hit: &Hit, g: &PixelGeom, interpolate_l: bool) -> DVec3 {
    let ts = &p.objects[hit.obj as usize].tris[hit.tri as usize];
    let v = corners(p, hit);
    let lights: Vec<_> = p.scene.bump_lights().collect();
    // Each light's L and H at each vertex, in that vertex's own frame.
    let at = |i: usize, j: usize| {
        let (n, t, b) = frame(v[j].n, v[j].t, v[j].b);
        let ld = light_dir(lights[i], v[j].p, n);
        (to_frame(ld, n, t, b), to_frame(half_vector(ld, p.camera.to_viewer), n, t, b))
    };
    crate::reference::gouraud_f64::shade_with(p, hit, g, |i| {
        let l = if interpolate_l { mix(hit, |j| at(i, j).0) } else { ts.l[i] };
        (l, mix(hit, |j| at(i, j).1))
    })
}
