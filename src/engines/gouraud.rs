//! Gouraud bump mapping (paper §4–5) and the §6 improvements. The paper's engine holds each
//! light's L and H per triangle, in the triangle's bump frame, so the highlight is flat over
//! a triangle (Fig. 7); §6 proposes interpolating the half vector ("no flat shading effect")
//! and/or the light directions, one per light. Assumptions for the variants: an interpolated
//! vector is formed at each vertex in that vertex's own frame (so it follows the surface's
//! curvature as Phong's normal does) and is not renormalised (the `_n` variants renormalise
//! it per fragment, as the `normalise` unit does), and k stays per triangle as in
//! the paper's bump state; the rest (clamps, blend order, skip_flat) is the paper's engine's
//! own (`reference::gouraud_f64::shade_with`).

use super::{Cost, Ctx, Engine, PerFragment};
use crate::config::Interpolate;
use crate::raster::{Hit, PixelGeom};
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
    scene_blend: true,
    fixed: Some(PerFragment {
        interpolate: Interpolate::None,
        renormalise: false,
        interpolate_k: false,
        renormalise_bump: false,
        ..PerFragment::PER_TRIANGLE
    }),
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
    scene_blend: true,
    fixed: Some(PerFragment {
        interpolate: Interpolate::H,
        renormalise: false,
        interpolate_k: false,
        renormalise_bump: false,
        ..PerFragment::PER_TRIANGLE
    }),
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
    scene_blend: true,
    fixed: Some(PerFragment {
        interpolate: Interpolate::Hl,
        renormalise: false,
        interpolate_k: false,
        renormalise_bump: false,
        ..PerFragment::PER_TRIANGLE
    }),
};

pub const GOURAUD_HN: Engine = Engine {
    name: "gouraud_hn",
    source: "paper §6 with the interpolated half vector renormalised per fragment (the normalise unit), as per-pixel engines do",
    per_triangle: "L, Lc, k per light and H per light per vertex (16 words a light)",
    per_fragment: "the Gouraud colour, uv, H per light (3 words a light), one normalisation a light",
    cost: Cost {
        triangle: 0,
        triangle_per_light: 16,
        fragment: 0,
        fragment_per_light: 3,
    },
    shade: shade_hn,
    scene_blend: true,
    fixed: Some(PerFragment {
        interpolate: Interpolate::H,
        renormalise: true,
        interpolate_k: false,
        renormalise_bump: false,
        ..PerFragment::PER_TRIANGLE
    }),
};

pub const GOURAUD_HLN: Engine = Engine {
    name: "gouraud_hln",
    source: "paper §6 with the interpolated half vector and light direction renormalised per fragment (the normalise unit)",
    per_triangle: "Lc, k per light and L and H per light per vertex (22 words a light)",
    per_fragment: "the Gouraud colour, uv, L and H per light (6 words a light), two normalisations a light",
    cost: Cost {
        triangle: 0,
        triangle_per_light: 22,
        fragment: 0,
        fragment_per_light: 6,
    },
    shade: shade_hln,
    scene_blend: true,
    fixed: Some(PerFragment {
        interpolate: Interpolate::Hl,
        renormalise: true,
        interpolate_k: false,
        renormalise_bump: false,
        ..PerFragment::PER_TRIANGLE
    }),
};

fn shade_paper(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::gouraud_f64::shade_interpolating(c.p, hit, g, fixed_variant(&GOURAUD))
}

fn shade_h(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::gouraud_f64::shade_interpolating(c.p, hit, g, fixed_variant(&GOURAUD_H))
}

fn shade_hn(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::gouraud_f64::shade_interpolating(c.p, hit, g, fixed_variant(&GOURAUD_HN))
}

fn shade_hln(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::gouraud_f64::shade_interpolating(c.p, hit, g, fixed_variant(&GOURAUD_HLN))
}

fn shade_hl(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    crate::reference::gouraud_f64::shade_interpolating(c.p, hit, g, fixed_variant(&GOURAUD_HL))
}

/// A Gouraud variant's per-fragment choices: its f64 model and its bit-accurate path are the
/// same engine.
fn fixed_variant(e: &Engine) -> PerFragment {
    e.fixed.expect("every Gouraud variant has a bit-accurate path")
}
