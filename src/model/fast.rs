//! The golden model's fast path: exactly [`shade`](super::shade)`(..).colour()`, from a value
//! built once per (configuration, power table, palette) that holds every per-configuration
//! constant already resolved (rounding increments, shifts, clamp limits, the expanded palette,
//! the power unit as a flat array over every clamped dot product). Why a second model: the
//! readable one re-derives formats, matches on rounding modes and the power unit, and keeps
//! every intermediate for the per-unit traces, per fragment; vector generation, streamed
//! regressions and the C ABI only need the colour, millions of times.
//!
//! Fragments are evaluated in batches by a function monomorphised on the light count and the
//! blend order, so the inner loop is unrolled and branch-free (enables and the flat bypass are
//! masks). Every caller that writes or checks records compares it with the readable model
//! (`vectors::check`), and `tests` below does so over random configurations and corners.

use super::bump_fetch::Palette;
use super::frame_transform::{framed_exact, Frame};
use super::pipeline::{BumpState, BumpTexel, FragmentIn};
use super::power_table::PowerTable;
use crate::config::{BlendOrder, PipelineConfig};
use crate::fixed::Rounding;
use crate::simd::Level;

/// `x / 2^down` (after `x · 2^up`) rounded as a [`Rounding`] says, as one add and two shifts:
/// `(x + bias + ((x >> down) & even)) >> down` is floor, half-up or half-to-even by the
/// constants alone (half-to-even adds half less one, plus one when the floor is odd).
#[derive(Clone, Copy, Debug)]
struct Requant {
    up: u32,
    down: u32,
    bias: i64,
    even: i64,
}

impl Requant {
    fn new(from_frac: u32, to_frac: u32, rnd: Rounding) -> Requant {
        let (up, down) = (to_frac.saturating_sub(from_frac), from_frac.saturating_sub(to_frac));
        let half = if down == 0 { 0 } else { 1i64 << (down - 1) };
        let (bias, even) = match rnd {
            _ if down == 0 => (0, 0),
            Rounding::Truncate => (0, 0),
            Rounding::HalfUp => (half, 0),
            Rounding::NearestEven => (half - 1, 1),
        };
        Requant { up, down, bias, even }
    }

    #[inline(always)]
    fn apply(self, x: i64) -> i64 {
        let x = x << self.up;
        (x + self.bias + ((x >> self.down) & self.even)) >> self.down
    }
}

/// One configuration's pipeline with its memories, ready to shade batches of fragments.
#[derive(Clone, Debug)]
pub struct FastModel {
    lights: usize,
    texture_last: bool,
    /// Offset-binary zero of a stored normal component.
    half: i64,
    /// The palette's entries already expanded (empty without a palette).
    palette: Vec<[i64; 3]>,
    flat: [i64; 3],
    skip_flat: bool,
    diffuse: bool,
    specular: bool,
    /// Exact B·V to fd, then the clamp to [0, dot_max].
    dot: Requant,
    dot_max: i64,
    /// fd to the common blend-factor format.
    diffuse_align: u32,
    /// Clamped B·H (every code 0..=2^F) to fs already aligned to the blend-factor format.
    specular_factor: Vec<i64>,
    /// The exact blend sum to stage-colour units.
    blend: Requant,
    /// The largest stage colour (1.0 with the guard bits).
    colour_max: i64,
    /// Fraction bits of a stage colour.
    guard: u32,
    /// The last stage colour to colour codes (`colour_round`; nothing without guard bits).
    round: Requant,
    /// `round(c·t / (2^w − 1))` as `((c·t + half) · m) >> s` (`fixed::UnormDiv`, exact for
    /// every product the stages make).
    tex_half: i64,
    tex_m: i64,
    tex_s: u32,
    /// Every light colour at this code (`white_lights`), or each slot's own.
    white: Option<u32>,
    /// The configuration, when it renormalises interpolated vectors before the dot products
    /// (`pipeline::renormalised`: the same integer steps as the readable model).
    renorm: Option<PipelineConfig>,
    /// The bump normal's shape, when the pipeline renormalises it after the fetch
    /// (`renormalise_bump`: `normalise_b`, the same integer steps as the readable model).
    renorm_b: Option<super::normalise::Shape>,
    /// `frame_transform`: the fetched normal placed in the state's frame, rounded as
    /// `model::frame_transform` rounds it and clamped to the normal's range (min, max).
    frame: Option<(Requant, i64, i64)>,
    /// `self_shadow`: a light below the surface is dropped per run (its k·Lc is zero), and a
    /// highlight is masked where B·L clamps to 0.
    self_shadow: bool,
    /// `frame_build` or `frame_quaternion`: the configuration its frame is formed in.
    built: Option<PipelineConfig>,
    /// EMBM (`env_map_bits` > 0): the configuration and its maps, shaded by the readable
    /// model (`pipeline::shade_embm`); no specialised path yet.
    embm: Option<(PipelineConfig, super::env_map::EnvMaps)>,
}

impl FastModel {
    /// The fast model of `cfg` with power table `table` and (palette configurations) `palette`.
    pub fn new(cfg: &PipelineConfig, table: &PowerTable, palette: Option<&Palette>) -> FastModel {
        FastModel::with_maps(cfg, table, palette, super::env_map::default_maps(cfg))
    }

    /// The fast model of `cfg` with the memories `mem` (EMBM's maps among them).
    pub fn of(cfg: &PipelineConfig, mem: &crate::units::Memories) -> FastModel {
        FastModel::with_maps(cfg, mem.table, Some(mem.palette), mem.env.clone())
    }

    /// Texel `i` of EMBM's map `which` is now `texel`, as the model's memories were changed;
    /// nothing without maps.
    pub fn set_env_texel(&mut self, which: &str, i: usize, texel: [u32; 3]) {
        if let Some((_, maps)) = &mut self.embm {
            maps.named_mut(which)[i] = texel;
        }
    }

    fn with_maps(cfg: &PipelineConfig, table: &PowerTable, palette: Option<&Palette>, maps: super::env_map::EnvMaps) -> FastModel {
        let half = 1i64 << (cfg.normal_bits - 1);
        let factor = cfg.factor_frac();
        let dot_max = 1i64 << cfg.dot_frac_bits;
        let div = super::texture_modulate::divider(cfg);
        FastModel {
            lights: cfg.lights as usize,
            texture_last: cfg.blend_order == BlendOrder::TextureLast,
            half,
            palette: palette.map_or(Vec::new(), |p| p.0.iter().map(|e| e.map(|c| c as i64 - half)).collect()),
            flat: cfg.flat_normal(),
            skip_flat: cfg.skip_flat,
            diffuse: cfg.diffuse,
            specular: cfg.specular,
            dot: Requant::new(cfg.dot_exact_fmt().frac, cfg.dot_frac_bits, cfg.rounding),
            dot_max,
            diffuse_align: factor - cfg.dot_frac_bits,
            specular_factor: (0..=dot_max)
                .map(|x| crate::model::power_unit::power_unit(cfg, table, x) << (factor - cfg.power_frac_bits))
                .collect(),
            blend: Requant::new(factor + cfg.k_frac_bits, cfg.colour_guard_bits, cfg.rounding),
            colour_max: cfg.stage_colour_max(),
            guard: cfg.colour_guard_bits,
            round: Requant::new(cfg.colour_guard_bits, 0, cfg.rounding),
            tex_half: div.half as i64,
            tex_m: div.m as i64,
            tex_s: div.s,
            white: cfg.white_lights.then(|| cfg.colour_max()),
            renorm: cfg.renormalise.then(|| cfg.clone()),
            renorm_b: cfg.renormalise_bump.then(|| super::normalise::Shape::bump(cfg)),
            frame: cfg.frame_transform.then(|| {
                let nf = cfg.normal_fmt();
                (
                    Requant::new(cfg.dot_exact_fmt().frac, nf.frac, cfg.rounding),
                    nf.min_raw(),
                    nf.max_raw(),
                )
            }),
            self_shadow: cfg.self_shadow,
            built: (cfg.frame_build || cfg.frame_quaternion).then(|| cfg.clone()),
            embm: cfg.embm().then(|| (cfg.clone(), maps)),
        }
    }

    /// The frame a state's fragments are placed in: its own, or the one `frame_build` or
    /// `quat_frame` forms from it (once per state: a run's fragments share one state).
    /// The state's own frame is lent, not copied: a copy, read back wider than the random
    /// state's stores wrote it, stalled every run.
    #[inline(always)]
    fn fragment_frame<'f>(&self, frame: &'f Frame) -> std::borrow::Cow<'f, Frame> {
        match &self.built {
            Some(cfg) => std::borrow::Cow::Owned(super::frame_build::fragment_frame(cfg, frame)),
            None => std::borrow::Cow::Borrowed(frame),
        }
    }

    /// The fetched bump normal as the dot products see it (`frame`: the fragment's, read
    /// under `frame_transform`).
    #[inline(always)]
    fn dot_normal(&self, v: [i64; 3], frame: &Frame) -> [i64; 3] {
        let v = match self.frame {
            Some((q, lo, hi)) => std::array::from_fn(|c| q.apply(framed_exact(v, frame, c)).clamp(lo, hi)),
            None => v,
        };
        match &self.renorm_b {
            Some(shape) => super::normalise::normalise_shape(shape, v),
            None => v,
        }
    }

    /// A fragment's bump normal as the dot products see it, and its diffuse and specular
    /// masks: all ones where the blend adds, zero where it is off (an enable, or the flat
    /// bypass), so the factors are masked rather than branched on.
    #[inline(always)]
    fn normal_and_masks(&self, f: &FragmentIn, frame: &Frame) -> ([i64; 3], i64, i64) {
        let b = match f.bump {
            BumpTexel::Rgb(c) => [c[0] as i64 - self.half, c[1] as i64 - self.half, c[2] as i64 - self.half],
            BumpTexel::Index(x) => self.palette[x as usize],
        };
        // Compared a component at a time: an array compare read the three just stored as one
        // wide load, which stalled on store forwarding for a sixth of the model's time.
        let bypass = self.skip_flat & (b[0] == self.flat[0]) & (b[1] == self.flat[1]) & (b[2] == self.flat[2]);
        let dmask = -i64::from(self.diffuse & f.diffuse_en & !bypass);
        let smask = -i64::from(self.specular & f.specular_en & !bypass);
        // Neither a frame nor a renormaliser: `b` as it is, kept in registers (through
        // `dot_normal`'s match it was copied on the stack and read back wider than written,
        // a store-forwarding stall on every fragment). Tested here, not in `dot_normal`:
        // there it made one-fragment runs 10 ns slower.
        let b = if self.frame.is_none() && self.renorm_b.is_none() {
            b
        } else {
            self.dot_normal(b, frame)
        };
        (b, dmask, smask)
    }

    /// The colours of `frags`, fragments of one triangle with bump state `state`, into `out`:
    /// the state's per-light products are formed once for the whole run.
    ///
    /// # Panics
    /// As [`colours`](Self::colours).
    pub fn colours_run(&self, state: &BumpState, frags: &[FragmentIn], out: &mut [[u32; 3]]) {
        self.colours_run_at(crate::simd::level(), state, frags, out)
    }

    /// [`colours_run`](Self::colours_run) with the loop compiled for `level` (every level gives
    /// the same colours; the tests check each one this CPU has).
    ///
    /// # Panics
    /// As [`colours`](Self::colours), and when the CPU lacks `level`.
    pub fn colours_run_at(&self, level: Level, state: &BumpState, frags: &[FragmentIn], out: &mut [[u32; 3]]) {
        assert_eq!(frags.len(), out.len(), "one colour per fragment");
        assert!(crate::simd::supported(level), "{level:?} is beyond this CPU");
        if let Some((cfg, maps)) = &self.embm {
            for (f, o) in frags.iter().zip(out.iter_mut()) {
                *o = super::pipeline::shade_embm(cfg, maps, state, f).colour();
            }
            return;
        }
        let owned;
        let state = match &self.renorm {
            Some(cfg) => {
                owned = super::pipeline::renormalised(cfg, state);
                &owned
            }
            None => state,
        };
        let frame = &*self.fragment_frame(&state.frame);
        macro_rules! by_lights {
            ($tl:literal) => {
                match self.lights {
                    1 => self.run_lit::<1, $tl>(level, state, frame, frags, out),
                    2 => self.run_lit::<2, $tl>(level, state, frame, frags, out),
                    3 => self.run_lit::<3, $tl>(level, state, frame, frags, out),
                    4 => self.run_lit::<4, $tl>(level, state, frame, frags, out),
                    5 => self.run_lit::<5, $tl>(level, state, frame, frags, out),
                    6 => self.run_lit::<6, $tl>(level, state, frame, frags, out),
                    7 => self.run_lit::<7, $tl>(level, state, frame, frags, out),
                    8 => self.run_lit::<8, $tl>(level, state, frame, frags, out),
                    n => unreachable!("{n} lights: the configuration allows 1 to 8"),
                }
            };
        }
        if self.texture_last {
            by_lights!(true)
        } else {
            by_lights!(false)
        }
    }

    /// The run's lights formed in place, then [`run_at`](Self::run_at).
    #[inline(always)]
    fn run_lit<const N: usize, const TEXTURE_LAST: bool>(
        &self,
        level: Level,
        state: &BumpState,
        frame: &Frame,
        frags: &[FragmentIn],
        out: &mut [[u32; 3]],
    ) {
        // Formed where they are read: returned by value, the array was copied on the stack
        // and read back wider than written, a store-forwarding stall every run.
        let mut lights = [Light::default(); N];
        self.lights_into(state, frame, &mut lights);
        self.run_at::<N, TEXTURE_LAST>(level, &lights, frame, frags, out)
    }

    /// [`run`](Self::run) compiled for `level`, which the CPU must have.
    #[inline(always)]
    fn run_at<const N: usize, const TEXTURE_LAST: bool>(
        &self,
        level: Level,
        lights: &[Light; N],
        frame: &Frame,
        frags: &[FragmentIn],
        out: &mut [[u32; 3]],
    ) {
        let m = self;
        if frags.len() <= SCALAR_MAX {
            // A run too short for a block, a fragment at a time, apart from the vector loop
            // (whose entry broadcasts every constant to a register, more than such a run
            // costs). Compiled for the level too: the baseline build of it, across the lights,
            // was a ninth of a vector dump's time.
            return crate::simd::at_level!(level, [const N: usize, const TEXTURE_LAST: bool] [N, TEXTURE_LAST] fn(
                m: &FastModel,
                lights: &[Light; N],
                frame: &Frame,
                frags: &[FragmentIn],
                out: &mut [[u32; 3]],
            ) {
                m.each_alone::<N, TEXTURE_LAST>(lights, frame, frags, out)
            });
        }
        crate::simd::at_level!(level, [const N: usize, const TEXTURE_LAST: bool] [N, TEXTURE_LAST] fn(
            m: &FastModel,
            lights: &[Light; N],
            frame: &Frame,
            frags: &[FragmentIn],
            out: &mut [[u32; 3]],
        ) {
            m.run_blocks::<N, TEXTURE_LAST>(lights, frame, frags, out)
        })
    }

    /// Each fragment on its own ([`one`](Self::one)): the body of every short run's loop.
    #[inline(always)]
    fn each_alone<const N: usize, const TEXTURE_LAST: bool>(
        &self,
        lights: &[Light; N],
        frame: &Frame,
        frags: &[FragmentIn],
        out: &mut [[u32; 3]],
    ) {
        for (f, o) in frags.iter().zip(out.iter_mut()) {
            *o = self.one::<N, TEXTURE_LAST>(lights, frame, f);
        }
    }

    /// One triangle's fragments a block of [`LANES`] at a time, each value of the block in
    /// its own array so that every step is one vector operation across the block.
    #[inline(always)]
    fn run_blocks<const N: usize, const TEXTURE_LAST: bool>(
        &self,
        lights: &[Light; N],
        frame: &Frame,
        frags: &[FragmentIn],
        out: &mut [[u32; 3]],
    ) {
        for (f, o) in frags.chunks(LANES).zip(out.chunks_mut(LANES)) {
            if f.len() <= SCALAR_MAX {
                // Too few to fill a block: each alone costs less than a block of padding.
                self.each_alone::<N, TEXTURE_LAST>(lights, frame, f, o);
            } else {
                self.block::<N, TEXTURE_LAST>(lights, frame, f, o);
            }
        }
    }

    #[inline(always)]
    fn block<const N: usize, const TEXTURE_LAST: bool>(
        &self,
        lights: &[Light; N],
        frame: &Frame,
        frags: &[FragmentIn],
        out: &mut [[u32; 3]],
    ) {
        let mut b = [[0i64; LANES]; 3];
        let (mut dmask, mut smask) = ([0i64; LANES], [0i64; LANES]);
        let (mut c_src, mut tex) = ([[0i64; LANES]; 3], [[0i64; LANES]; 3]);
        for (i, f) in frags.iter().enumerate().take(LANES) {
            let v;
            (v, dmask[i], smask[i]) = self.normal_and_masks(f, frame);
            for ch in 0..3 {
                b[ch][i] = v[ch];
                c_src[ch][i] = (f.c_src[ch] as i64) << self.guard;
                tex[ch][i] = f.tex[ch] as i64;
            }
        }
        let (mut dacc, mut sacc) = ([[0i64; LANES]; 3], [[0i64; LANES]; 3]);
        let top = self.specular_factor.len() as i64 - 1;
        for s in lights {
            let mut dh = [0i64; LANES];
            let mut lmask = [0i64; LANES];
            for i in 0..LANES {
                let dl = self
                    .dot
                    .apply(b[0][i] * s.l[0] + b[1][i] * s.l[1] + b[2][i] * s.l[2])
                    .clamp(0, self.dot_max);
                let fd = (dl << self.diffuse_align) & dmask[i];
                // Self-shadowing: no highlight where B·L clamps to 0.
                lmask[i] = -i64::from(!self.self_shadow | (dl > 0));
                dh[i] = self.dot.apply(b[0][i] * s.h[0] + b[1][i] * s.h[1] + b[2][i] * s.h[2]).clamp(0, top);
                for ch in 0..3 {
                    dacc[ch][i] += fd * s.klc[ch];
                }
            }
            let mut fs = [0i64; LANES];
            for i in 0..LANES {
                // SAFETY: `dh` is clamped to 0..=top, the table's last index.
                fs[i] = unsafe { *self.specular_factor.get_unchecked(dh[i] as usize) } & smask[i] & lmask[i];
            }
            for ch in 0..3 {
                for i in 0..LANES {
                    sacc[ch][i] += fs[i] * s.klc[ch];
                }
            }
        }
        let mut c = c_src;
        self.close_block(&mut c, &dacc);
        if TEXTURE_LAST {
            self.close_block(&mut c, &sacc);
            self.texture_block(&mut c, &tex);
        } else {
            self.texture_block(&mut c, &tex);
            self.close_block(&mut c, &sacc);
        }
        // Written out: `[0, 1, 2].map(..)` stayed a call per fragment, through the stack.
        let r = |x: i64| self.round.apply(x) as u32;
        for (i, o) in out.iter_mut().enumerate().take(LANES) {
            *o = [r(c[0][i]), r(c[1][i]), r(c[2][i])];
        }
    }

    /// The colour of one fragment (for many, [`colours`](Self::colours) chooses the
    /// specialised loop once per batch instead of once per fragment).
    pub fn colour(&self, state: &BumpState, frag: &FragmentIn) -> [u32; 3] {
        let mut out = [[0; 3]];
        self.colours(std::slice::from_ref(&(state, frag)), |x| (x.0, x.1), &mut out);
        out[0]
    }

    /// The colours of `items` (each gives its triangle's state and its fragment) into `out`.
    ///
    /// # Panics
    /// When `out` is not as long as `items`, or a palette index is given to a model built
    /// without a palette.
    pub fn colours<T>(&self, items: &[T], get: impl Fn(&T) -> (&BumpState, &FragmentIn), out: &mut [[u32; 3]]) {
        assert_eq!(items.len(), out.len(), "one colour per fragment");
        if let Some((cfg, maps)) = &self.embm {
            for (item, o) in items.iter().zip(out.iter_mut()) {
                let (state, f) = get(item);
                *o = super::pipeline::shade_embm(cfg, maps, state, f).colour();
            }
            return;
        }
        macro_rules! by_lights {
            ($tl:literal) => {
                match self.lights {
                    1 => self.batch::<1, $tl, T>(items, get, out),
                    2 => self.batch::<2, $tl, T>(items, get, out),
                    3 => self.batch::<3, $tl, T>(items, get, out),
                    4 => self.batch::<4, $tl, T>(items, get, out),
                    5 => self.batch::<5, $tl, T>(items, get, out),
                    6 => self.batch::<6, $tl, T>(items, get, out),
                    7 => self.batch::<7, $tl, T>(items, get, out),
                    8 => self.batch::<8, $tl, T>(items, get, out),
                    n => unreachable!("{n} lights: the configuration allows 1 to 8"),
                }
            };
        }
        if self.texture_last {
            by_lights!(true)
        } else {
            by_lights!(false)
        }
    }

    fn batch<const N: usize, const TEXTURE_LAST: bool, T>(
        &self,
        items: &[T],
        get: impl Fn(&T) -> (&BumpState, &FragmentIn),
        out: &mut [[u32; 3]],
    ) {
        for (it, o) in items.iter().zip(out.iter_mut()) {
            let (state, frag) = get(it);
            let frame = self.fragment_frame(&state.frame);
            let l = match &self.renorm {
                Some(cfg) => self.lights::<N>(&super::pipeline::renormalised(cfg, state), &frame),
                None => self.lights::<N>(state, &frame),
            };
            *o = self.one::<N, TEXTURE_LAST>(&l, &frame, frag);
        }
    }

    #[inline(always)]
    fn dot(&self, b: [i64; 3], v: [i64; 3]) -> i64 {
        self.dot.apply(b[0] * v[0] + b[1] * v[1] + b[2] * v[2]).clamp(0, self.dot_max)
    }

    /// `c_in + round(acc)`, saturated: one channel of one blend's close.
    #[inline(always)]
    fn close_channel(&self, c_in: i64, acc: i64) -> i64 {
        (c_in + self.blend.apply(acc)).min(self.colour_max)
    }

    /// `round(c·t / (2^w − 1))` on a stage colour: one channel of the texture modulation
    /// (the hardware's divider, `fixed::UnormDiv`).
    #[inline(always)]
    fn texture_channel(&self, c: i64, t: i64) -> i64 {
        ((c * t + self.tex_half) * self.tex_m) >> self.tex_s
    }

    /// [`close_channel`](Self::close_channel) on every channel.
    #[inline(always)]
    fn close(&self, c_in: [u32; 3], acc: [i64; 3]) -> [u32; 3] {
        // Written out: `[0, 1, 2].map(..)` became a call per channel.
        let ch = |i: usize| self.close_channel(c_in[i] as i64, acc[i]) as u32;
        [ch(0), ch(1), ch(2)]
    }

    /// [`close`](Self::close) across a block.
    #[inline(always)]
    fn close_block(&self, c: &mut [[i64; LANES]; 3], acc: &[[i64; LANES]; 3]) {
        // One flat loop: nested over channels and lanes, it was vectorised as gathers and
        // scatters of four lanes.
        for (c, a) in c.as_flattened_mut().iter_mut().zip(acc.as_flattened()) {
            *c = self.close_channel(*c, *a);
        }
    }

    /// [`texture`](Self::texture) across a block.
    #[inline(always)]
    fn texture_block(&self, c: &mut [[i64; LANES]; 3], tex: &[[i64; LANES]; 3]) {
        // Flat, as `close_block`.
        for (c, t) in c.as_flattened_mut().iter_mut().zip(tex.as_flattened()) {
            *c = self.texture_channel(*c, *t);
        }
    }

    /// [`texture_channel`](Self::texture_channel) on every channel.
    #[inline(always)]
    fn texture(&self, c: [u32; 3], t: [u32; 3]) -> [u32; 3] {
        let ch = |i: usize| self.texture_channel(c[i] as i64, t[i] as i64) as u32;
        [ch(0), ch(1), ch(2)]
    }

    #[inline(always)]
    fn one<const N: usize, const TEXTURE_LAST: bool>(&self, lights: &[Light; N], frame: &Frame, frag: &FragmentIn) -> [u32; 3] {
        let (b, dmask, smask) = self.normal_and_masks(frag, frame);
        let (mut dacc, mut sacc) = ([0i64; 3], [0i64; 3]);
        for s in lights {
            let dl = self.dot(b, s.l);
            let fd = (dl << self.diffuse_align) & dmask;
            let lmask = -i64::from(!self.self_shadow | (dl > 0));
            let fs = self.specular_factor[self.dot(b, s.h) as usize] & smask & lmask;
            for ch in 0..3 {
                dacc[ch] += fd * s.klc[ch];
                sacc[ch] += fs * s.klc[ch];
            }
        }
        let lit = self.close(frag.c_src.map(|c| c << self.guard), dacc);
        let last = if TEXTURE_LAST {
            self.texture(self.close(lit, sacc), frag.tex)
        } else {
            self.close(self.texture(lit, frag.tex), sacc)
        };
        last.map(|c| self.round.apply(c as i64) as u32)
    }
}

/// Fragments of one block: AVX-512 holds eight 64-bit values.
const LANES: usize = 8;
/// Fragments that go one at a time rather than as a padded block.
const SCALAR_MAX: usize = 2;

/// One light slot as the blends use it: L, H, and k·Lc per channel (the product the exact
/// blend sum multiplies by the factor; formed once per triangle).
#[derive(Clone, Copy, Default)]
struct Light {
    l: [i64; 3],
    h: [i64; 3],
    klc: [i64; 3],
}

impl FastModel {
    /// Each light's vectors and k·Lc for a run; a light below the surface adds nothing under
    /// self-shadowing (`pipeline::lit`: L_z in bump space, N·L in a frame, whose N is the
    /// unperturbed normal placed in `frame`).
    #[inline(always)]
    fn lights<const N: usize>(&self, state: &BumpState, frame: &Frame) -> [Light; N] {
        let mut out = [Light::default(); N];
        self.lights_into(state, frame, &mut out);
        out
    }

    /// [`lights`](Self::lights) into `out`.
    #[inline(always)]
    fn lights_into<const N: usize>(&self, state: &BumpState, frame: &Frame, out: &mut [Light; N]) {
        let surface = match self.frame {
            Some((q, lo, hi)) if self.self_shadow => {
                Some(std::array::from_fn(|c| q.apply(framed_exact(self.flat, frame, c)).clamp(lo, hi)))
            }
            _ => None,
        };
        // A loop, not `array::from_fn`: that stayed a call per run, 4 % of a vector dump.
        for (o, s) in out.iter_mut().zip(&state.lights) {
            let lit = match surface {
                Some(n) => self.dot(n, s.l) > 0,
                None => super::pipeline::self_shadow_lit(s.l),
            };
            let lc = if self.self_shadow && !lit {
                [0; 3]
            } else {
                self.white.map_or(s.lc, |m| [m; 3])
            };
            // Field by field: a whole `Light` built aside and copied in went through the
            // stack in pieces of other widths, and its reads stalled on store forwarding.
            o.l = s.l;
            o.h = s.h;
            o.klc = [s.k * lc[0] as i64, s.k * lc[1] as i64, s.k * lc[2] as i64];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vectors::rng::SplitMix64;
    use crate::vectors::sources::{corners, random_chunk};

    /// Every fragment of `stims` gets the readable model's colour, in one batch and alone.
    fn agree(cfg: &PipelineConfig, shininess: u32, stims: &[crate::vectors::targets::TopStim]) {
        let mem = crate::units::MemoryContents::new(cfg, shininess);
        let fast = FastModel::of(cfg, &mem.view());
        let mut out = vec![[0; 3]; stims.len()];
        fast.colours(stims, |s| (&s.state, &s.frag), &mut out);
        for (s, got) in stims.iter().zip(&out) {
            let want = mem.view().shade(cfg, &s.state, &s.frag).colour();
            assert_eq!(*got, want, "config {}:\n{}\nn = {shininess}, {s:?}", cfg.hash(), cfg.to_toml());
            assert_eq!(fast.colour(&s.state, &s.frag), want);
        }
        // A triangle's fragments together, as the encoder gives them (runs of every length
        // across the block size), at every vector level this CPU has.
        let mut runs: Vec<(&BumpState, Vec<FragmentIn>, Vec<[u32; 3]>)> = Vec::new();
        for (s, want) in stims.iter().zip(&out) {
            match runs.last_mut() {
                Some((st, fr, w)) if **st == s.state && !s.tri_start => {
                    fr.push(s.frag);
                    w.push(*want);
                }
                _ => runs.push((&s.state, vec![s.frag], vec![*want])),
            }
        }
        // One run longer than any block, out of every fragment under the first state.
        let long: Vec<FragmentIn> = stims.iter().take(3 * super::LANES + 5).map(|s| s.frag).collect();
        let long_want: Vec<[u32; 3]> = long.iter().map(|f| mem.view().shade(cfg, &stims[0].state, f).colour()).collect();
        runs.push((&stims[0].state, long, long_want));
        for level in crate::simd::Level::Avx512
            .and_below()
            .into_iter()
            .filter(|l| crate::simd::supported(*l))
        {
            for (state, frags, want) in &runs {
                let mut got = vec![[0; 3]; frags.len()];
                fast.colours_run_at(level, state, frags, &mut got);
                assert_eq!(&got, want, "config {} at {level:?}, a run of {}", cfg.hash(), frags.len());
            }
        }
    }

    /// Random valid configurations as `gbump fuzz` draws them, each on random records and on
    /// its level-2 corners, at a random shininess.
    #[test]
    fn random_configurations_agree_with_the_readable_model() {
        let mut rng = SplitMix64(0x5EED_FA57);
        for i in 0..150 {
            let cfg = crate::sim::fuzz::random_config(&mut rng);
            let n = rng.range(0, crate::limits::MAX_SHININESS as i64) as u32;
            let mut stims = random_chunk(&cfg, i, 0, 1500);
            stims.extend(corners(&cfg, 2).into_iter().map(|c| c.1));
            agree(&cfg, n, &stims);
        }
    }

    /// The configurations at the edges of the space (`gbump fuzz`'s fixed list), every
    /// rounding and both blend orders of the default.
    #[test]
    fn corner_configurations_agree_with_the_readable_model() {
        let mut cfgs: Vec<PipelineConfig> = crate::sim::fuzz::corner_configs().into_iter().map(|c| c.1).collect();
        cfgs.extend(crate::sim::fuzz::normalise_configs());
        for rounding in [Rounding::Truncate, Rounding::HalfUp, Rounding::NearestEven] {
            for blend_order in [BlendOrder::DiffuseTextureSpecular, BlendOrder::TextureLast] {
                for skip_flat in [false, true] {
                    cfgs.push(PipelineConfig {
                        rounding,
                        blend_order,
                        skip_flat,
                        ..Default::default()
                    });
                }
            }
        }
        for (i, cfg) in cfgs.iter().enumerate() {
            let mut stims = random_chunk(cfg, 77 + i as u64, 0, 3000);
            stims.extend(corners(cfg, 2).into_iter().map(|c| c.1));
            for n in [0, 1, cfg.shininess, crate::limits::MAX_SHININESS] {
                agree(cfg, n, &stims);
            }
        }
    }

    /// The rounding constants against `fixed::shift_round` on every value near the ties.
    #[test]
    fn requant_is_shift_round() {
        for rnd in [Rounding::Truncate, Rounding::HalfUp, Rounding::NearestEven] {
            for (from, to) in [(4, 4), (3, 6), (9, 2), (20, 8), (1, 0)] {
                let r = Requant::new(from, to, rnd);
                for x in -300i64..300 {
                    let want = if to >= from {
                        (x as i128) << (to - from)
                    } else {
                        crate::fixed::shift_round(x as i128, from - to, rnd)
                    };
                    assert_eq!(r.apply(x) as i128, want, "{rnd:?} {from}->{to} x={x}");
                }
            }
        }
    }
}
