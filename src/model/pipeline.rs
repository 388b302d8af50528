//! The whole Gouraud bump pipeline for one fragment: the units of this module's siblings in
//! the configured order (paper §5.1, Figs. 2 and 3), with the per-fragment enables of §4.2
//! and the unperturbed-normal bypass of §5.4.2.

use super::blend::{align_factor, blend};
use super::bump_fetch::{bump_fetch_index, bump_fetch_rgb, Palette};
use super::dot_clamp::dot_clamp;
use super::power_table::PowerTable;
use super::power_unit::power_unit;
use super::texture_modulate::{colour_round, texture_modulate};
use crate::config::{BlendOrder, PipelineConfig};

/// Light slots the model can hold (the config's upper limit).
pub const MAX_LIGHTS: usize = 8;

/// One bump light's state, in bump space (in the frame's space under `frame_transform`), as
/// the geometry engine loads it per triangle or the rasteriser sends it per fragment.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LightSlot {
    /// Light direction L_i, raw `s1.(lh-2)` components.
    pub l: [i64; 3],
    /// Half vector H_i, raw `s1.(lh-2)` components.
    pub h: [i64; 3],
    /// Light colour Lc_i, colour codes (an unused slot has colour 0).
    pub lc: [u32; 3],
    /// Spot/attenuation modulation k_i, raw `u1.K`.
    pub k: i64,
}

/// The bump state of one triangle (or, with `bump_state = "fragment"`, of one fragment):
/// every light slot, and under `frame_transform` the frame the bump normal is placed in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BumpState {
    pub lights: [LightSlot; MAX_LIGHTS],
    /// T, B and N, raw `s1.(lh-2)` components (`frame_transform`; unread otherwise).
    pub frame: super::frame_transform::Frame,
    /// EMBM's map coordinates and matrix (`env_map_bits` > 0; unread otherwise).
    pub env: super::env_map::EnvState,
}

/// A fetched bump texel: stored RGB codes, or a palette index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BumpTexel {
    Rgb([u32; 3]),
    Index(u8),
}

/// The per-fragment inputs of the pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FragmentIn {
    pub bump: BumpTexel,
    /// Interpolated Gouraud colour C_src.
    pub c_src: [u32; 3],
    /// Texture colour T (white when the object has no texture).
    pub tex: [u32; 3],
    pub diffuse_en: bool,
    pub specular_en: bool,
}

/// Every intermediate value of one fragment, for per-unit vectors and debugging.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Shaded {
    /// The bump normal as the fetch hands it on.
    pub fetched: [i64; 3],
    /// The fetched normal placed in the fragment's frame (`frame_transform`; the fetched
    /// normal otherwise): what `normalise_b` reads.
    pub framed: [i64; 3],
    /// The frame the fetched normal is placed in: the state's, or under `frame_build` the
    /// one built from its main direction and normal (`frame_transform`; zero otherwise).
    pub frame: super::frame_transform::Frame,
    /// The bump normal as the dot products see it (`normalise_b`d under `renormalise_bump`).
    pub b: [i64; 3],
    /// L_i and H_i as the dot products see them (`normalise`d under `renormalise`).
    pub l: [[i64; 3]; MAX_LIGHTS],
    pub h: [[i64; 3]; MAX_LIGHTS],
    pub flat: bool,
    pub fd: [i64; MAX_LIGHTS],
    /// Clamped B·H_i: the power table's index input.
    pub xh: [i64; MAX_LIGHTS],
    pub fs: [i64; MAX_LIGHTS],
    /// Aligned, enable-gated blend factors as the blend units receive them.
    pub dfac: [i64; MAX_LIGHTS],
    pub sfac: [i64; MAX_LIGHTS],
    /// Colour after each of the three stages, in pipeline order, as stage colours
    /// (`colour_guard_bits` fraction bits).
    pub stages: [[u32; 3]; 3],
    /// The final colour C_new: the last stage rounded to colour codes (`colour_round`; the
    /// last stage itself when there are no guard bits).
    pub out: [u32; 3],
    /// EMBM's texel and weights (`env_coords`; zero otherwise).
    pub env: super::env_map::EnvSample,
    /// EMBM's four texels of the diffuse and of the specular map (`env_fetch_*`).
    pub texels: [[[u32; 3]; 4]; 2],
}

impl Shaded {
    /// The final colour C_new.
    pub fn colour(&self) -> [u32; 3] {
        self.out
    }
}

/// Light slot `s`'s L and H as the dot products see them: the slot's own, or under
/// `renormalise` each interpolated one through the `normalise` unit (H, and L with
/// `interpolate = "hl"`; a per-triangle L is a unit vector already). Under `pixel_lh` the
/// H lanes carry the viewer direction V, and H is the `normalise` of the normalised L and V
/// halved ([`half_sum`]).
#[inline]
pub fn dot_vectors(cfg: &PipelineConfig, s: &LightSlot) -> ([i64; 3], [i64; 3]) {
    use super::normalise::{normalise, renormalised};
    let (nl, nh) = renormalised(cfg);
    let pick = |on: bool, v: [i64; 3]| if on { normalise(cfg, v) } else { v };
    let l = pick(nl, s.l);
    if cfg.pixel_lh {
        return (l, normalise(cfg, half_sum(l, s.h)));
    }
    (l, pick(nh, s.h))
}

/// (a + b)/2 per component, rounded down (the sum one bit wider, its low bit dropped): the
/// halved sum of two vectors of at most unit length stays inside the L/H word.
#[inline]
pub fn half_sum(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    std::array::from_fn(|c| (a[c] + b[c]) >> 1)
}

/// `state` with every slot's L and H as the dot products see them ([`dot_vectors`]).
pub fn renormalised(cfg: &PipelineConfig, state: &BumpState) -> BumpState {
    let mut st = *state;
    for s in st.lights.iter_mut().take(cfg.lights as usize) {
        (s.l, s.h) = dot_vectors(cfg, s);
    }
    st
}

/// Whether light direction `l` (as the dot products see it) is above the surface, L_z > 0:
/// under `self_shadow` a light below it adds nothing.
#[inline]
pub fn self_shadow_lit(l: [i64; 3]) -> bool {
    l[2] > 0
}

/// The surface normal in the space L is given in, under `frame_transform` with `self_shadow`:
/// the unperturbed normal (0, 0, 1) placed in the fragment's frame by the same
/// `frame_transform` unit the bump normal goes through (its N column, in the normal's
/// format). None when L is in bump space, where the surface normal is z itself.
pub fn surface_normal(cfg: &PipelineConfig, frame: &super::frame_transform::Frame) -> Option<[i64; 3]> {
    (cfg.self_shadow && cfg.frame_transform).then(|| super::frame_transform::frame_transform(cfg, cfg.flat_normal(), frame))
}

/// Whether light direction `l` (as the dot products see it) is above the surface: L_z > 0 in
/// bump space ([`self_shadow_lit`]); with a frame, N·L above 0 as the `dot_clamp` unit
/// forms it from the [`surface_normal`] (a product that rounds to 0 is below).
#[inline]
pub fn lit(cfg: &PipelineConfig, surface: Option<[i64; 3]>, l: [i64; 3]) -> bool {
    match surface {
        Some(n) => dot_clamp(cfg, n, l) > 0,
        None => self_shadow_lit(l),
    }
}

/// Shade one fragment. `palette` must be given when `cfg.palette` is set; an EMBM
/// configuration shades through [`shade_embm`], which reads its maps.
pub fn shade(cfg: &PipelineConfig, table: &PowerTable, palette: Option<&Palette>, state: &BumpState, frag: &FragmentIn) -> Shaded {
    assert!(!cfg.embm(), "an EMBM configuration shades with its maps (shade_embm)");
    let n = cfg.lights as usize;
    let b = match frag.bump {
        BumpTexel::Rgb(rgb) => bump_fetch_rgb(cfg, rgb),
        BumpTexel::Index(i) => bump_fetch_index(cfg, palette.expect("palette mode needs a palette"), i),
    };
    // The flat bypass compares the fetched normal; the dot products see it renormalised.
    let flat = b == cfg.flat_normal();
    let bypass = cfg.skip_flat && flat;
    let diffuse_on = cfg.diffuse && frag.diffuse_en && !bypass;
    let specular_on = cfg.specular && frag.specular_en && !bypass;
    let fetched = b;
    let frame = if cfg.frame_transform {
        super::frame_build::fragment_frame(cfg, &state.frame)
    } else {
        Default::default()
    };
    let framed = if cfg.frame_transform {
        super::frame_transform::frame_transform(cfg, b, &frame)
    } else {
        b
    };
    let b = if cfg.renormalise_bump {
        super::normalise::normalise_bump(cfg, framed)
    } else {
        framed
    };

    let mut out = Shaded {
        fetched,
        framed,
        frame,
        b,
        flat,
        ..Default::default()
    };
    let surface = surface_normal(cfg, &frame);
    let mut kd = [0i64; MAX_LIGHTS];
    let mut lc = [[0u32; 3]; MAX_LIGHTS];
    let mut dfac = [0i64; MAX_LIGHTS];
    let mut sfac = [0i64; MAX_LIGHTS];
    for i in 0..n {
        let s = &state.lights[i];
        kd[i] = s.k;
        lc[i] = cfg.light_colour(s.lc);
        (out.l[i], out.h[i]) = dot_vectors(cfg, s);
        if cfg.diffuse {
            out.fd[i] = dot_clamp(cfg, b, out.l[i]);
            if diffuse_on {
                dfac[i] = align_factor(cfg, out.fd[i], cfg.dot_frac_bits);
            }
        }
        if cfg.specular {
            out.xh[i] = dot_clamp(cfg, b, out.h[i]);
            out.fs[i] = power_unit(cfg, table, out.xh[i]);
            if specular_on {
                sfac[i] = align_factor(cfg, out.fs[i], cfg.power_frac_bits);
            }
        }
        if cfg.self_shadow {
            // Cg §8.5.3: a light below the surface adds nothing; a bump facing away from it
            // gets no highlight.
            let lit = lit(cfg, surface, out.l[i]);
            if !lit {
                dfac[i] = 0;
            }
            if !lit || out.fd[i] == 0 {
                sfac[i] = 0;
            }
        }
    }
    let diffuse = |c| blend(cfg, c, &dfac[..n], &kd[..n], &lc[..n]);
    let specular = |c| blend(cfg, c, &sfac[..n], &kd[..n], &lc[..n]);
    (out.stages, out.out) = colour_stages(cfg, frag, diffuse, specular);
    out.dfac = dfac;
    out.sfac = sfac;
    out
}

/// The three colour stages from C_src in the configured blend order (paper Figs. 2 and 3),
/// and the final colour rounded to codes.
fn colour_stages(
    cfg: &PipelineConfig,
    frag: &FragmentIn,
    diffuse: impl Fn([u32; 3]) -> [u32; 3],
    specular: impl Fn([u32; 3]) -> [u32; 3],
) -> ([[u32; 3]; 3], [u32; 3]) {
    let texture = |c| texture_modulate(cfg, c, frag.tex);
    let s0 = diffuse(frag.c_src.map(|c| c << cfg.colour_guard_bits));
    let (s1, s2) = match cfg.blend_order {
        BlendOrder::DiffuseTextureSpecular => {
            let t = texture(s0);
            (t, specular(t))
        }
        BlendOrder::TextureLast => {
            let s = specular(s0);
            (s, texture(s))
        }
    };
    ([s0, s1, s2], colour_round(cfg, s2))
}

/// Shade one fragment of an EMBM configuration (`env_map_bits` > 0) with `maps`: the
/// fetched normal's (x, y) through `env_coords`, the four texels of each map through
/// `env_fetch`, and the blends as light slots whose factors are the bilinear weights, k one
/// and colours the texels: D = Σ w_i·diffuse_i and S = Σ w_i·specular_i, each rounded once,
/// in the configured blend order. The flat bypass and the enables act as for any top.
pub fn shade_embm(cfg: &PipelineConfig, maps: &super::env_map::EnvMaps, state: &BumpState, frag: &FragmentIn) -> Shaded {
    use super::env_map::{env_coords, env_fetch, WEIGHT_FRAC_BITS};
    let b = match frag.bump {
        BumpTexel::Rgb(rgb) => bump_fetch_rgb(cfg, rgb),
        BumpTexel::Index(_) => unreachable!("EMBM configurations have no palette"),
    };
    let flat = b == cfg.flat_normal();
    let bypass = cfg.skip_flat && flat;
    let diffuse_on = cfg.diffuse && frag.diffuse_en && !bypass;
    let specular_on = cfg.specular && frag.specular_en && !bypass;
    let env = env_coords(cfg, [b[0], b[1]], state.env.st, state.env.m);
    let mut out = Shaded {
        fetched: b,
        framed: b,
        b,
        flat,
        env,
        ..Default::default()
    };
    let kone = [1i64 << cfg.k_frac_bits; 4];
    let td = env_fetch(maps.bits, &maps.diffuse, env.x0, env.y0);
    let ts = env_fetch(maps.bits, &maps.specular, env.x0, env.y0);
    out.texels = [td, ts];
    let (mut dfac, mut sfac) = ([0i64; MAX_LIGHTS], [0i64; MAX_LIGHTS]);
    for i in 0..4 {
        if cfg.diffuse {
            out.fd[i] = env.w[i] << (cfg.dot_frac_bits - WEIGHT_FRAC_BITS);
            if diffuse_on {
                dfac[i] = align_factor(cfg, out.fd[i], cfg.dot_frac_bits);
            }
        }
        if cfg.specular {
            out.fs[i] = env.w[i] << (cfg.power_frac_bits - WEIGHT_FRAC_BITS);
            if specular_on {
                sfac[i] = align_factor(cfg, out.fs[i], cfg.power_frac_bits);
            }
        }
    }
    // A blend the configuration leaves out has zero factors: it passes its colour on.
    let diffuse = |c| blend(cfg, c, &dfac[..4], &kone, &td);
    let specular = |c| blend(cfg, c, &sfac[..4], &kone, &ts);
    (out.stages, out.out) = colour_stages(cfg, frag, diffuse, specular);
    out.dfac = dfac;
    out.sfac = sfac;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(cfg: &PipelineConfig) -> i64 {
        1 << (cfg.lh_bits - 2)
    }

    fn frag(c: u32, t: u32) -> FragmentIn {
        FragmentIn {
            bump: BumpTexel::Rgb([128, 128, 255]),
            c_src: [c; 3],
            tex: [t; 3],
            diffuse_en: true,
            specular_en: true,
        }
    }

    #[test]
    fn every_light_at_full_colour_saturates() {
        let cfg = PipelineConfig {
            lights: 8,
            ..Default::default()
        };
        let t = PowerTable::build(&cfg, 1);
        let mut st = BumpState::default();
        for s in st.lights.iter_mut() {
            *s = LightSlot {
                l: [0, 0, one(&cfg)],
                h: [0, 0, one(&cfg)],
                lc: [255; 3],
                k: 1 << cfg.k_frac_bits,
            };
        }
        let r = shade(&cfg, &t, None, &st, &frag(255, 255));
        assert_eq!(r.colour(), [255; 3]);
        let r = shade(&cfg, &t, None, &st, &frag(0, 0));
        // Texture black kills diffuse, specular still adds in the split order (Fig. 2).
        assert_eq!(r.stages[1], [0; 3]);
        assert_eq!(r.colour(), [255; 3]);
        let cfg3 = PipelineConfig {
            blend_order: BlendOrder::TextureLast,
            ..cfg
        };
        assert_eq!(
            shade(&cfg3, &t, None, &st, &frag(0, 0)).colour(),
            [0; 3],
            "Fig. 3: black texture colour stays black"
        );
    }

    #[test]
    fn single_light_exact_value() {
        let cfg = PipelineConfig::default();
        let t = PowerTable::build(&cfg, 1);
        let mut st = BumpState::default();
        // L straight above: fd = 127/128 → 254/256; colour 200, k = 1: 200*254/256 = 198.4375 → 198.
        st.lights[0] = LightSlot {
            l: [0, 0, one(&cfg)],
            h: [one(&cfg), 0, 0],
            lc: [200, 0, 0],
            k: 256,
        };
        let r = shade(&cfg, &t, None, &st, &frag(10, 255));
        assert_eq!(r.fd[0], 254);
        assert_eq!(r.fs[0], 0);
        assert_eq!(r.colour(), [208, 10, 10]);
    }

    #[test]
    fn k_zero_and_disabled_units_change_nothing() {
        let cfg = PipelineConfig::default();
        let t = PowerTable::build(&cfg, 8);
        let mut st = BumpState::default();
        st.lights[0] = LightSlot {
            l: [0, 0, one(&cfg)],
            h: [0, 0, one(&cfg)],
            lc: [255; 3],
            k: 0,
        };
        assert_eq!(shade(&cfg, &t, None, &st, &frag(77, 255)).colour(), [77; 3]);
        st.lights[0].k = 256;
        let mut f = frag(77, 255);
        f.diffuse_en = false;
        f.specular_en = false;
        assert_eq!(shade(&cfg, &t, None, &st, &f).colour(), [77; 3]);
        let skip = PipelineConfig {
            skip_flat: true,
            ..cfg.clone()
        };
        assert_eq!(shade(&skip, &t, None, &st, &frag(77, 255)).colour(), [77; 3], "§5.4.2 bypass");
        let mut bumped = frag(77, 255);
        bumped.bump = BumpTexel::Rgb([140, 128, 250]);
        assert_ne!(shade(&skip, &t, None, &st, &bumped).colour(), [77; 3]);
    }

    #[test]
    fn serial_and_parallel_agree() {
        let a = PipelineConfig::default();
        let b = PipelineConfig {
            light_mode: crate::config::LightMode::Parallel,
            ..a.clone()
        };
        let t = PowerTable::build(&a, 32);
        let mut st = BumpState::default();
        for (i, s) in st.lights.iter_mut().enumerate().take(4) {
            *s = LightSlot {
                l: [1000 * i as i64, -3000, 12000],
                h: [-500, 2000 * i as i64, 15000],
                lc: [90, 180, 255],
                k: 200,
            };
        }
        for c in [0, 100, 255] {
            assert_eq!(shade(&a, &t, None, &st, &frag(c, 200)), shade(&b, &t, None, &st, &frag(c, 200)));
        }
    }

    /// Cg §8.5.3: a light below the surface (L_z <= 0) adds nothing, and a bump facing away
    /// from a light above it (B·L clamped to 0) gets no highlight from it.
    #[test]
    fn self_shadowing_cuts_lights_below_the_surface_and_highlights_facing_away() {
        let base = PipelineConfig {
            lights: 1,
            light_mode: crate::config::LightMode::Parallel,
            ..Default::default()
        };
        let cfg = PipelineConfig {
            self_shadow: true,
            ..base.clone()
        };
        let t = PowerTable::build(&cfg, 1);
        let one = one(&cfg);
        let mut st = BumpState::default();
        // L grazing below the surface, H straight up: without the cut both terms add.
        st.lights[0] = LightSlot {
            l: [one, 0, -one / 8],
            h: [0, 0, one],
            lc: [255; 3],
            k: 256,
        };
        let mut f = frag(40, 255);
        // A bump tilted towards the light, so B·L > 0 although L is below the surface.
        f.bump = BumpTexel::Rgb([200, 128, 220]);
        let plain = shade(&base, &t, None, &st, &f);
        assert!(plain.fd[0] > 0 && plain.colour()[0] > 40, "{plain:?}");
        assert_eq!(shade(&cfg, &t, None, &st, &f).colour(), [40; 3]);
        // L above the surface, the bump facing away: diffuse 0, and the highlight cut.
        st.lights[0].l = [-one, 0, one / 8];
        let plain = shade(&base, &t, None, &st, &f);
        assert!(plain.fd[0] == 0 && plain.colour()[0] > 40, "{plain:?}");
        assert_eq!(shade(&cfg, &t, None, &st, &f).colour(), [40; 3]);
        // L above, facing it: unchanged.
        st.lights[0].l = [one / 2, 0, one / 2];
        assert_eq!(shade(&cfg, &t, None, &st, &f), shade(&base, &t, None, &st, &f));
    }
}
