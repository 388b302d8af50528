//! Where stimuli come from: fragments of real scenes, a catalogue of corner cases, seeded
//! random cases, and exhaustive sweeps of the units small enough to sweep.

use super::rng::{Span, SplitMix64};
use super::targets::{TopStim, UnitStim};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::model::{BumpState, BumpTexel, FragmentIn, LightSlot, MAX_LIGHTS};

/// A parsed `--source`.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    Scene(String),
    /// The corner-case catalogue at a level (1: each unit's edges; 2: adds sweeps around them).
    Corners(u8),
    Random(u64),
    Exhaustive(String),
}

impl Source {
    pub fn parse(s: &str) -> Result<Source> {
        Source::parse_as(s, &format!("--source {s}"))
    }

    /// [`parse`](Self::parse), its messages naming the source as the caller spelt it
    /// (`named`: `--source random:0`, or a library call's `source "random:0"`).
    pub fn parse_as(s: &str, named: &str) -> Result<Source> {
        let bad = || {
            Error::Other(format!(
                "{named}: not understood\n  fix: use scene:NAME, corners, random:N or exhaustive:UNIT"
            ))
        };
        Ok(match s.split_once(':') {
            None if s == "corners" => Source::Corners(1),
            Some(("scene", n)) if !n.is_empty() => {
                let src = Source::Scene(n.to_string());
                // The scene file's stem names every file of the set: the fix is to rename the
                // file (a built-in scene's name is always plain).
                super::writer::check_set_names(named, "the scene file", &src.stem(), "top", false)?;
                src
            }
            Some(("random", n)) => {
                let max = crate::limits::MAX_RANDOM_VECTORS;
                Source::Random(crate::limits::parse_count(named, n, 1, max, "MAX_RANDOM_VECTORS")?)
            }
            Some(("exhaustive", u)) => {
                crate::names::check(named, "exhaustive:UNIT", u)?;
                Source::Exhaustive(u.to_string())
            }
            _ => return Err(bad()),
        })
    }

    /// File-name stem.
    pub fn stem(&self) -> String {
        match self {
            Source::Scene(n) => format!(
                "scene_{}",
                std::path::Path::new(n)
                    .file_stem()
                    .map_or(n.clone(), |s| s.to_string_lossy().into())
            ),
            Source::Corners(1) => "corners".into(),
            Source::Corners(l) => format!("corners_level{l}"),
            Source::Random(n) => format!("random{n}"),
            Source::Exhaustive(u) => format!("exhaustive_{u}"),
        }
    }
}

/// The source as the command line spells it (`--source` and, for a corner level above 1,
/// `--level`), which manifests record.
impl std::fmt::Display for Source {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Source::Scene(n) => write!(f, "scene:{n}"),
            Source::Corners(1) => write!(f, "corners"),
            Source::Corners(l) => write!(f, "corners --level {l}"),
            Source::Random(n) => write!(f, "random:{n}"),
            Source::Exhaustive(u) => write!(f, "exhaustive:{u}"),
        }
    }
}

fn one(cfg: &PipelineConfig) -> i64 {
    1 << (cfg.lh_bits - 2)
}

/// Three draws in order (as `[0; 3].map(..)` draws them, without its call per element).
#[inline(always)]
fn three<T>(mut f: impl FnMut() -> T) -> [T; 3] {
    let a = f();
    let b = f();
    [a, b, f()]
}

/// `x.round() as i64` for the |x| ≤ 2^52 (and NaN, as 0) that `unit_codes` makes, without the
/// library call `round` is on a baseline CPU: the truncation and the remainder are exact there.
/// Beyond 2^62 it gives ±2^62 (every caller clamps to a narrower range).
#[inline(always)]
fn round_half_away(x: f64) -> i64 {
    const WIDE: f64 = (1u64 << 62) as f64;
    // `as` saturates, which kept every conversion scalar (a compare and two moves per value);
    // with NaN and the out-of-range already mapped, the conversion is one vector instruction.
    let x = if x.is_nan() { 0.0 } else { x.clamp(-WIDE, WIDE) };
    // SAFETY: `x` is finite and within ±2^62, so its truncation is an i64.
    let t: i64 = unsafe { x.to_int_unchecked() };
    let f = x - t as f64;
    t + i64::from(f >= 0.5) - i64::from(f <= -0.5)
}

/// Random stimuli per independently seeded chunk: `random:N` record `i` is draw `i % RANDOM_CHUNK`
/// of chunk `i / RANDOM_CHUNK`'s stream, so chunks generate in parallel and the bytes depend on
/// the seed alone (the C ABI's stimulus stream replays the same records one by one).
pub const RANDOM_CHUNK: u64 = 1 << 14;

/// The generator of chunk `chunk` of the random stream `seed`.
pub fn chunk_rng(seed: u64, chunk: u64) -> SplitMix64 {
    SplitMix64(seed ^ chunk.wrapping_mul(0xA076_1D64_78BD_642F))
}

/// A random triangle's bump state: half realistic (unit vectors), half raw codes over the
/// whole of every format.
pub fn random_state(cfg: &PipelineConfig, rng: &mut SplitMix64) -> BumpState {
    let mut state = BumpState::default();
    random_state_into(cfg, rng, &mut state);
    state
}

/// [`random_state`] written over `state`, which must be the default or an earlier state of
/// the same configuration (every field this configuration draws is written; the rest stay
/// as they were): a triangle's state is made in place, not copied.
pub fn random_state_into(cfg: &PipelineConfig, rng: &mut SplitMix64, state: &mut BumpState) {
    random_state_with(cfg, &k_range(cfg), rng, state)
}

/// The range k is drawn over, 0 to one: its constant costs a 128-bit division, once per
/// stream rather than per triangle.
fn k_range(cfg: &PipelineConfig) -> Span {
    Span::new(0, 1i64 << cfg.k_frac_bits)
}

/// [`random_state_into`] with `cfg`'s [`k_range`].
fn random_state_with(cfg: &PipelineConfig, k: &Span, rng: &mut SplitMix64, state: &mut BumpState) {
    crate::simd::at_level!(crate::simd::level(), [] [] fn(cfg: &PipelineConfig, k: &Span, rng: &mut SplitMix64, state: &mut BumpState) {
        fill_state(cfg, k, rng, state)
    })
}

/// [`random_state`]'s draws: every light's ([`light_draws`]), then its unit vectors made
/// for every light at once, lane by lane, so the square roots and divisions of all of them
/// run side by side. Each lane is the same IEEE operations in the same order as one vector
/// alone, so the codes do not depend on how many lanes run at once.
#[inline(always)]
fn fill_state(cfg: &PipelineConfig, k: &Span, rng: &mut SplitMix64, state: &mut BumpState) {
    use super::rng::range_of;
    if cfg.embm() {
        state.env = random_env(cfg, rng);
        return;
    }
    let raw = rng.chance(0.5);
    let lh = cfg.lh_fmt();
    let n = cfg.lights as usize;
    // Each light's L and H draws, a component a row (so a row is one vector register):
    // vector 2i is light i's L, 2i + 1 its H.
    let mut x = [[0u64; 2 * MAX_LIGHTS]; 3];
    if n <= MAX_LIGHTS / 2 {
        light_draws::<{ LIGHT_DRAWS_MOST * MAX_LIGHTS / 2 }>(cfg, k, rng, &mut state.lights[..n], &mut x);
    } else {
        light_draws::<{ LIGHT_DRAWS_MOST * MAX_LIGHTS }>(cfg, k, rng, &mut state.lights[..n], &mut x);
    }
    let mut v = [[0i64; 2 * MAX_LIGHTS]; 3];
    if raw {
        for (v, x) in v.iter_mut().zip(&x) {
            for (v, x) in v.iter_mut().zip(x).take(2 * n) {
                *v = range_of(*x, lh.min_raw(), lh.max_raw());
            }
        }
    } else if n <= MAX_LIGHTS / 2 {
        // Half the lanes hold every vector of up to four lights: one register's worth.
        unit_codes::<MAX_LIGHTS>(cfg, &x, &mut v);
    } else {
        unit_codes::<{ 2 * MAX_LIGHTS }>(cfg, &x, &mut v);
    }
    for (i, s) in state.lights.iter_mut().take(n).enumerate() {
        s.l = [v[0][2 * i], v[1][2 * i], v[2][2 * i]];
        s.h = [v[0][2 * i + 1], v[1][2 * i + 1], v[2][2 * i + 1]];
    }
    if cfg.frame_transform {
        // Drawn after the lights, so a configuration without a frame draws what it drew.
        state.frame = random_frame(cfg, rng, raw);
    }
}

/// The most draws one light takes: L, H, Lc and k's coin, and k where the coin says so.
const LIGHT_DRAWS_MOST: usize = 11;

/// Each light's draws in turn (L and H into `x`, Lc and k into its slot), from one block of
/// `B` values (at least [`LIGHT_DRAWS_MOST`] a light) drawn ahead: a light's draws start
/// where the one before it stopped, one further on when its k took a draw of its own. Drawn
/// light by light, each light's mixes waited for the coin before them (a branch wrong half
/// the time); from the block, they all run at once and a coin only moves an index.
#[inline(always)]
fn light_draws<const B: usize>(
    cfg: &PipelineConfig,
    k_range: &Span,
    rng: &mut SplitMix64,
    slots: &mut [LightSlot],
    x: &mut [[u64; 2 * MAX_LIGHTS]; 3],
) {
    use super::rng::{range_of, unit_of};
    let cmax = cfg.colour_max() as i64;
    let kone = 1i64 << cfg.k_frac_bits;
    let block = rng.peek_block::<B>();
    let mut at = 0;
    for (i, s) in slots.iter_mut().enumerate() {
        let b = &block[at..at + LIGHT_DRAWS_MOST];
        for c in 0..3 {
            x[c][2 * i] = b[c];
            x[c][2 * i + 1] = b[3 + c];
        }
        // Written out: `[6, 7, 8].map(..)` stayed a call whose three narrow stores were read
        // back as one wide load, a store-forwarding stall per light.
        s.lc = [
            range_of(b[6], 0, cmax) as u32,
            range_of(b[7], 0, cmax) as u32,
            range_of(b[8], 0, cmax) as u32,
        ];
        // Heads (half the time) k is drawn, else it is one.
        let drawn = unit_of(b[9]) >= 0.5;
        let k = k_range.of(b[10]);
        s.k = if drawn { k } else { kone };
        at += LIGHT_DRAWS_MOST - 1 + drawn as usize;
    }
    rng.skip(at as u64);
}

/// EMBM's random state: half the time raw codes over the whole L/H format (clamping at
/// the map's edges, the widest sums), else map coordinates inside the map, in [-1, 1], and a
/// matrix of entries in [-1, 1] scaled together by a factor in [0, 1] (a gentle or a steep
/// perturbation).
fn random_env(cfg: &PipelineConfig, rng: &mut SplitMix64) -> crate::model::env_map::EnvState {
    use super::rng::{range_of, unit_of};
    let lh = cfg.lh_fmt();
    let x = rng.next_block::<8>();
    if unit_of(x[0]) < 0.5 {
        return crate::model::env_map::EnvState {
            st: [1, 2].map(|i| range_of(x[i], lh.min_raw(), lh.max_raw())),
            m: [3, 4, 5, 6].map(|i| range_of(x[i], lh.min_raw(), lh.max_raw())),
        };
    }
    let one = one(cfg);
    let scale = unit_of(x[7]);
    crate::model::env_map::EnvState {
        st: [1, 2].map(|i| range_of(x[i], -one, one)),
        m: [3, 4, 5, 6].map(|i| (range_of(x[i], -one, one) as f64 * scale).round() as i64),
    }
}

/// A random frame (`frame_transform`): raw codes over the whole L/H format, or an
/// orthonormal frame with each axis shortened to 70–100 % of unit length, as interpolating
/// unit vectors between vertices shortens them.
fn random_frame(cfg: &PipelineConfig, rng: &mut SplitMix64, raw: bool) -> crate::model::frame_transform::Frame {
    use super::rng::{range_of, unit_of};
    use glam::DVec3;
    let lh = cfg.lh_fmt();
    let x = rng.next_block::<9>();
    if raw {
        return std::array::from_fn(|i| std::array::from_fn(|c| range_of(x[3 * i + c], lh.min_raw(), lh.max_raw())));
    }
    let v = |k: usize| {
        DVec3::new(
            unit_of(x[k]) * 2.0 - 1.0,
            unit_of(x[k + 1]) * 2.0 - 1.0,
            unit_of(x[k + 2]) * 2.0 - 1.0,
        )
    };
    let n = v(0).try_normalize().unwrap_or(DVec3::Z);
    let t = (v(3) - n * n.dot(v(3)))
        .try_normalize()
        .unwrap_or_else(|| n.any_orthonormal_vector());
    let b = n.cross(t);
    let one = one(cfg) as f64;
    [t, b, n]
        .iter()
        .enumerate()
        .map(|(i, a)| {
            (*a * (0.7 + 0.3 * unit_of(x[6 + i])))
                .to_array()
                .map(|c| round_half_away(c * one).clamp(lh.min_raw(), lh.max_raw()))
        })
        .collect::<Vec<_>>()
        .try_into()
        .expect("three axes")
}

/// Every drawn vector (`u(0)·2 − 1, u(1)·2 − 1, u(2)·1.2 − 0.2`) scaled to unit length and
/// rounded to L/H codes (half away from zero, clamped), a vector a lane and a component a
/// row: straight-line arithmetic over fixed-size arrays, which the compiler runs in vector
/// registers where the caller is compiled for them.
#[inline(always)]
fn unit_codes<const V: usize>(cfg: &PipelineConfig, x: &[[u64; 2 * MAX_LIGHTS]; 3], out: &mut [[i64; 2 * MAX_LIGHTS]; 3]) {
    use super::rng::unit_of;
    let one = one(cfg) as f64;
    let (lo, hi) = (cfg.lh_fmt().min_raw(), cfg.lh_fmt().max_raw());
    let [o0, o1, o2] = out;
    // One loop over the lanes, every access a lane's own: split into a loop per step, the
    // compiler vectorised across the components instead, with gathers and scatters.
    for k in 0..V {
        let c0 = unit_of(x[0][k]) * 2.0 - 1.0;
        let c1 = unit_of(x[1][k]) * 2.0 - 1.0;
        let c2 = unit_of(x[2][k]) * 1.2 - 0.2;
        let len = (c0 * c0 + c1 * c1 + c2 * c2).sqrt();
        o0[k] = round_half_away(c0 / len * one).clamp(lo, hi);
        o1[k] = round_half_away(c1 / len * one).clamp(lo, hi);
        o2[k] = round_half_away(c2 / len * one).clamp(lo, hi);
    }
}

/// A random fragment: raw codes over the whole of every format, blends mostly enabled.
#[inline(always)]
pub fn random_fragment(cfg: &PipelineConfig, rng: &mut SplitMix64) -> FragmentIn {
    if !cfg.palette {
        // The same draws in the same order, made as one block.
        return rgb_fragment(cfg, &rng.next_block::<FRAGMENT_DRAWS>());
    }
    let cmax = cfg.colour_max() as i64;
    let nmax = (1i64 << cfg.normal_bits) - 1;
    let codes = three(|| rng.range(0, nmax) as u32);
    let bump = if cfg.palette {
        BumpTexel::Index(rng.range(0, 255) as u8)
    } else {
        BumpTexel::Rgb(codes)
    };
    FragmentIn {
        bump,
        c_src: three(|| rng.range(0, cmax) as u32),
        tex: three(|| rng.range(0, cmax) as u32),
        diffuse_en: rng.chance(0.85),
        specular_en: rng.chance(0.85),
    }
}

/// Draws of one RGB-bump fragment.
const FRAGMENT_DRAWS: usize = 11;

/// The RGB-bump fragment of its eleven draws: three normal codes, the source and texture
/// colours, the two blend enables.
#[inline(always)]
fn rgb_fragment(cfg: &PipelineConfig, x: &[u64]) -> FragmentIn {
    use super::rng::{range_of, unit_of};
    let (cmax, nmax) = (cfg.colour_max() as i64, (1i64 << cfg.normal_bits) - 1);
    let code = |i: usize| range_of(x[i], 0, nmax) as u32;
    let colour = |i: usize| range_of(x[i], 0, cmax) as u32;
    FragmentIn {
        bump: BumpTexel::Rgb([code(0), code(1), code(2)]),
        c_src: [colour(3), colour(4), colour(5)],
        tex: [colour(6), colour(7), colour(8)],
        diffuse_en: unit_of(x[9]) < 0.85,
        specular_en: unit_of(x[10]) < 0.85,
    }
}

/// A random stimulus that is a triangle of its own.
pub fn random_stim(cfg: &PipelineConfig, rng: &mut SplitMix64) -> TopStim {
    let state = random_state(cfg, rng);
    TopStim {
        frag: random_fragment(cfg, rng),
        state,
        tri_start: true,
    }
}

/// The random stream: triangles of random fragment counts (`ONE_FRAGMENT_SHARE` of them one
/// fragment, so one-fragment triangles come back to back; at most `TRIANGLE_MAX_FRAGMENTS`),
/// each fragment random. Every
/// chunk of `RANDOM_CHUNK` records starts a new triangle, so chunks stay independent.
/// Records `c * RANDOM_CHUNK ..` of `random:count` with `seed`: chunk `c` of the stream.
pub fn random_chunk(cfg: &PipelineConfig, seed: u64, c: u64, count: u64) -> Vec<TopStim> {
    let mut tris = RandomTriangles::new(cfg, chunk_rng(seed, c));
    (0..RANDOM_CHUNK.min(count - c * RANDOM_CHUNK)).map(|_| tris.next(cfg)).collect()
}

/// The random stream's triangles as its draws make them (a chunk's last triangle, cut at
/// the chunk's end, apart): the share that are one fragment, and the mean fragment count.
/// `ONE_FRAGMENT_SHARE` of them are drawn as one; the rest draw a span 2^r, r uniform over
/// every power of two up to `TRIANGLE_MAX_FRAGMENTS`, then a length uniform in 1..=span.
pub fn random_triangle_shape() -> (f64, f64) {
    let scales = TRIANGLE_MAX_FRAGMENTS.ilog2() + 1;
    let p = (1.0 - ONE_FRAGMENT_SHARE) / scales as f64;
    (0..scales).fold((ONE_FRAGMENT_SHARE, ONE_FRAGMENT_SHARE), |(one, mean), r| {
        let span = (1u64 << r) as f64;
        (one + p / span, mean + p * (span + 1.0) / 2.0)
    })
}

/// Most fragments of one random triangle (a power of two).
pub const TRIANGLE_MAX_FRAGMENTS: u64 = 64;
/// Share of random triangles with one fragment.
pub const ONE_FRAGMENT_SHARE: f64 = 0.25;

pub struct RandomTriangles {
    rng: SplitMix64,
    state: BumpState,
    left: u64,
    /// The configuration's [`k_range`].
    k: Span,
}

impl RandomTriangles {
    /// The triangles of `cfg` (the configuration every later call is given) drawn from `rng`.
    pub fn new(cfg: &PipelineConfig, rng: SplitMix64) -> RandomTriangles {
        RandomTriangles {
            rng,
            state: BumpState::default(),
            left: 0,
            k: k_range(cfg),
        }
    }

    pub fn next(&mut self, cfg: &PipelineConfig) -> TopStim {
        let tri_start = self.start(cfg);
        self.left -= 1;
        TopStim {
            frag: random_fragment(cfg, &mut self.rng),
            state: self.state,
            tri_start,
        }
    }

    /// The next records as one run of a triangle: up to `max` (>= 1) fragments into `frags`
    /// (cleared first), the triangle's state, and whether the run starts the triangle. The
    /// same draws as as many [`next`](Self::next) calls, without a copy of the state per
    /// fragment.
    pub fn next_run(&mut self, cfg: &PipelineConfig, max: usize, frags: &mut Vec<FragmentIn>) -> (&BumpState, bool) {
        let tri_start = self.start(cfg);
        let k = (self.left as usize).min(max);
        frags.clear();
        let rng = &mut self.rng;
        crate::simd::at_level!(crate::simd::level(), [] [] fn(cfg: &PipelineConfig, rng: &mut SplitMix64, k: usize, frags: &mut Vec<FragmentIn>) {
            fragments(cfg, rng, k, frags)
        });
        self.left -= k as u64;
        (&self.state, tri_start)
    }

    /// Draw the next triangle when the current one is done; whether it did.
    fn start(&mut self, cfg: &PipelineConfig) -> bool {
        let tri_start = self.left == 0;
        if tri_start {
            self.left = if self.rng.chance(ONE_FRAGMENT_SHARE) {
                1
            } else {
                // Lengths spread over every scale: a power-of-two span, then uniform in it.
                let span = 1i64 << self.rng.range(0, TRIANGLE_MAX_FRAGMENTS.ilog2() as i64);
                1 + self.rng.range(0, span - 1) as u64
            };
            random_state_with(cfg, &self.k, &mut self.rng, &mut self.state);
        }
        tri_start
    }
}

/// `k` random fragments onto `frags` (each fragment's draws are one block of mixes, which
/// the vector variants below run side by side).
#[inline(always)]
fn fragments(cfg: &PipelineConfig, rng: &mut SplitMix64, k: usize, frags: &mut Vec<FragmentIn>) {
    if cfg.palette {
        frags.extend((0..k).map(|_| random_fragment(cfg, rng)));
        return;
    }
    // Up to eight fragments' draws at a time, as one fixed-size block of the fewest fragments
    // that hold them (the block is drawn whole and only its fragments' part taken): the same
    // values as one fragment at a time. Most triangles are short, and a block of eight for
    // one fragment spent most of its mixes on nothing.
    const AT_ONCE: usize = 8;
    let mut left = k;
    while left > 0 {
        let m = left.min(AT_ONCE);
        match m {
            1 => take_fragments::<{ FRAGMENT_DRAWS }>(cfg, rng, m, frags),
            2 => take_fragments::<{ 2 * FRAGMENT_DRAWS }>(cfg, rng, m, frags),
            3 | 4 => take_fragments::<{ 4 * FRAGMENT_DRAWS }>(cfg, rng, m, frags),
            _ => take_fragments::<{ AT_ONCE * FRAGMENT_DRAWS }>(cfg, rng, m, frags),
        }
        left -= m;
    }
}

/// `m` fragments from one block of `B` draws (at least `m` fragments' worth).
#[inline(always)]
fn take_fragments<const B: usize>(cfg: &PipelineConfig, rng: &mut SplitMix64, m: usize, frags: &mut Vec<FragmentIn>) {
    let x = rng.peek_block::<B>();
    rng.skip((m * FRAGMENT_DRAWS) as u64);
    // A loop, not `extend` of a `map`: that became a call of its own, compiled without the
    // caller's vector instructions.
    for x in x.chunks_exact(FRAGMENT_DRAWS).take(m) {
        frags.push(rgb_fragment(cfg, x));
    }
}

/// Refuse scene vectors for a palette configuration, whose memory a scene would load per
/// object, which no harness does yet (each palettised map has its own palette). `what`
/// names the request (`--source scene:NAME`); the fix says what to use instead, or to drop
/// `--rtl` where `what` renders. EMBM's per-object maps are loaded (`SceneGroup::env`).
pub fn scene_sets_made(cfg: &PipelineConfig, what: &str) -> Result<()> {
    if !cfg.palette {
        return Ok(());
    }
    let fix = "use corners, random:N or exhaustive:palette_fetch (all on the power-up palette), or set palette = false";
    let fix = if what.contains("--rtl") {
        "drop --rtl (the golden image needs no vectors), or set palette = false"
    } else if what.contains("--stream") {
        "stream random:N or corners (on the power-up palette), or set palette = false"
    } else {
        fix
    };
    Err(Error::Other(format!(
        "{what}: scene vectors of a palette configuration are not made yet: each palettised map has its own palette, loaded per object\n  fix: {fix}"
    )))
}

/// Every stem a set of scene `s` (loaded from `name`) may take under `cfg`: one per group
/// key its objects give (`scene_groups` keeps those that hold fragments, and drops the
/// suffix when one group is left), so a check of these before rasterising covers the names
/// the dump will make.
pub fn scene_set_stems(cfg: &PipelineConfig, name: &str, s: &crate::scene::Scene) -> Vec<String> {
    let stem = Source::Scene(name.to_string()).stem();
    let keys: std::collections::BTreeSet<u32> = (0..s.objects.len() as u32).map(|o| group_key(cfg, s, o)).collect();
    let tag = if cfg.embm() { "_o" } else { "_n" };
    std::iter::once(stem.clone())
        .chain(keys.iter().filter(|_| keys.len() > 1).map(|k| format!("{stem}{tag}{k}")))
        .collect()
}

/// One run of a scene's fragments: those that share the top's memories.
pub struct SceneGroup {
    /// The power table's shininess.
    pub shininess: u32,
    /// The set's stem (`scene_NAME`, `_nS` or `_oI` when the scene has several groups).
    pub stem: String,
    pub stims: Vec<TopStim>,
    /// EMBM: the object's two maps, which the harness loads before the run.
    pub env: Option<crate::model::env_map::EnvMaps>,
    /// A scene's groups: each record's pixel, `[x, y]` (row 0 at the top), one for one with
    /// `stims`, and the image they lie in, [width, height]; the dump writes them beside the
    /// top set (`_pixels.txt`).
    pub pixels: Option<(Vec<[u32; 2]>, [u32; 2])>,
}

/// The group a fragment of object `obj` of scene `s` goes with under `cfg`: its object under
/// EMBM (each object has its own maps), else its power table's shininess.
pub fn group_key(cfg: &PipelineConfig, s: &crate::scene::Scene, obj: u32) -> u32 {
    let o = &s.objects[obj as usize];
    if cfg.embm() {
        obj
    } else if cfg.fixed_shininess().is_some() && !o.specular {
        // Hardware of one shininess (a ROM table, a squaring unit): an object without the
        // specular blend reads no power, so its fragments go with the built-in one (a
        // loadable table keeps each object's).
        cfg.shininess
    } else {
        o.shininess
    }
}

/// The fragments of scene `name` rendered at `size` (default: the scene's own), grouped by
/// [`group_key`] in its order: one group per power table, or under EMBM per object.
pub fn scene_groups(cfg: &PipelineConfig, name: &str, size: Option<(u32, u32)>) -> Result<Vec<SceneGroup>> {
    scene_sets_made(cfg, &format!("scene:{name}"))?;
    let s = crate::scene::Scene::load(name)?;
    s.check_config(cfg, &crate::config::origin())?;
    let (w, h) = size.unwrap_or((s.size[0], s.size[1]));
    crate::limits::check_render(crate::limits::PixelUse::SceneVectors, &s.file, w, h, s.triangles())?;
    let p = crate::raster::Prepared::new(&s, cfg, w, h)?;
    let gb = crate::raster::rasterise::rasterise(&p)?;
    let frags = crate::raster::fragment::fragments(&p, &gb);
    let mut groups: std::collections::BTreeMap<u32, (Vec<TopStim>, Vec<[u32; 2]>)> = Default::default();
    // `fragments` gives each triangle's fragments together: a setup starts each run.
    let mut prev: std::collections::BTreeMap<u32, (u32, u32)> = Default::default();
    for f in frags {
        let key = group_key(cfg, &s, f.obj);
        let tri_start = prev.insert(key, (f.obj, f.tri)) != Some((f.obj, f.tri));
        let (stims, pixels) = groups.entry(key).or_default();
        stims.push(TopStim {
            frag: f.frag,
            state: f.state,
            tri_start,
        });
        pixels.push([f.x, f.y]);
    }
    let stem = Source::Scene(name.to_string()).stem();
    let multi = groups.len() > 1;
    let mut objects: Vec<Option<crate::model::env_map::EnvMaps>> = p.objects.into_iter().map(|o| Some(o.env)).collect();
    Ok(groups
        .into_iter()
        .map(|(key, (stims, pixels))| {
            let (shininess, tag, env) = match cfg.embm() {
                true => (cfg.shininess, format!("_o{key}"), objects[key as usize].take()),
                false => (key, format!("_n{key}"), None),
            };
            SceneGroup {
                shininess,
                stem: if multi { format!("{stem}{tag}") } else { stem.clone() },
                stims,
                env,
                pixels: Some((pixels, [w, h])),
            }
        })
        .collect())
}

/// A corner stimulus: every light slot the same, grey colours given in the configuration's
/// codes, L and H clamped into their format, both blend enables on.
#[allow(clippy::too_many_arguments)]
fn corner_stim(cfg: &PipelineConfig, codes: [u32; 3], l: [i64; 3], h: [i64; 3], lc: u32, k: i64, c: u32, t: u32) -> TopStim {
    let lh = cfg.lh_fmt();
    let fit = |v: [i64; 3]| v.map(|x| x.clamp(lh.min_raw(), lh.max_raw()));
    let mut state = BumpState::default();
    for s in state.lights.iter_mut().take(cfg.lights as usize) {
        *s = LightSlot {
            l: fit(l),
            h: fit(h),
            lc: [lc; 3],
            k,
        };
    }
    if cfg.frame_transform {
        // The identity frame: a corner means in the frame's space what it means in bump space.
        let one = one(cfg);
        state.frame = [[one, 0, 0], [0, one, 0], [0, 0, one]];
    }
    let frag = FragmentIn {
        bump: bump_of(cfg, codes),
        c_src: [c; 3],
        tex: [t; 3],
        diffuse_en: true,
        specular_en: true,
    };
    // Every corner is a triangle of its own: one-fragment triangles back to back.
    TopStim {
        frag,
        state,
        tri_start: true,
    }
}

/// The bump texel a fragment of `cfg` carries for stored codes `rgb`: the codes, or in a
/// palette configuration the index of the power-up palette's entry nearest to them.
fn bump_of(cfg: &PipelineConfig, rgb: [u32; 3]) -> BumpTexel {
    if !cfg.palette {
        return BumpTexel::Rgb(rgb);
    }
    let pal = crate::rtlgen::rom::default_palette(cfg);
    let d = |e: &[u32; 3]| (0..3).map(|i| (e[i] as i64 - rgb[i] as i64).pow(2)).sum::<i64>();
    let best = (0..pal.0.len()).min_by_key(|&i| d(&pal.0[i])).expect("a palette entry");
    BumpTexel::Index(best as u8)
}

/// An 8-bit colour value scaled to a channel whose full scale is `cmax`.
fn scale8(x: u32, cmax: u32) -> u32 {
    ((x as u64 * cmax as u64 + 127) / 255).min(cmax as u64) as u32
}

/// The corner-case catalogue at `level`. Each entry says why it is there.
pub fn corners(cfg: &PipelineConfig, level: u8) -> Vec<(String, TopStim)> {
    if cfg.embm() {
        return corners_embm(cfg, level);
    }
    let mut v: Vec<(String, TopStim)> = corners_level1(cfg).into_iter().map(|(w, s)| (w.to_string(), s)).collect();
    if cfg.palette {
        // The palette's first and last entries, under a light straight above.
        let o = one(cfg);
        let m = cfg.colour_max();
        for ix in [0u8, 255] {
            let mut s = corner_stim(cfg, [0; 3], [0, 0, o], [0, 0, o], m, 1 << cfg.k_frac_bits, m / 4, m);
            s.frag.bump = BumpTexel::Index(ix);
            v.push((format!("palette index {ix}"), s));
        }
    }
    if level >= 2 {
        v.extend(corners_level2(cfg));
    }
    if cfg.skip_flat {
        // Most corners carry the flat code, which skip_flat bypasses: say so where the reason
        // would otherwise describe lighting the record does not get.
        let flat = BumpTexel::Rgb(flat_code(cfg));
        for (why, s) in &mut v {
            if s.frag.bump == flat && !why.contains("skip_flat") {
                why.push_str(" (the flat code: skip_flat bypasses the blends, C_src·T only)");
            }
        }
    }
    v
}

/// The flat normal's stored code (2^(w-1), 2^(w-1), 2^w - 1), in either normal range.
fn flat_code(cfg: &PipelineConfig) -> [u32; 3] {
    let half = 1u32 << (cfg.normal_bits - 1);
    [half, half, (1u32 << cfg.normal_bits) - 1]
}

/// EMBM's corners: each of `env_coords`' own edges (texel centres, clamps, the truncation
/// of the sub-texel fraction, the widest sums) as a fragment, under a mid-grey C_src and a
/// white texture; then the enables off, a saturating C_src and a black texture at the map's
/// centre; level 2 adds the blocks at the map's four corners.
fn corners_embm(cfg: &PipelineConfig, level: u8) -> Vec<(String, TopStim)> {
    let half = 1i64 << (cfg.normal_bits - 1);
    let nmax = (1u32 << cfg.normal_bits) - 1;
    let cmax = cfg.colour_max();
    let stim = |b: &[i64], st: &[i64], m: &[i64], c: u32, t: u32, de: bool, se: bool| {
        let mut s = corner_stim(cfg, [0; 3], [0; 3], [0; 3], 0, 0, c, t);
        s.state = BumpState {
            env: crate::model::env_map::EnvState {
                st: [st[0], st[1]],
                m: [m[0], m[1], m[2], m[3]],
            },
            ..Default::default()
        };
        s.frag.bump = bump_of(cfg, [(b[0] + half) as u32, (b[1] + half) as u32, nmax]);
        s.frag.diffuse_en = de;
        s.frag.specular_en = se;
        s
    };
    let coords = crate::units::unit("env_coords").expect("unit");
    let mut v: Vec<(String, TopStim)> = coords
        .corners(cfg)
        .into_iter()
        .map(|(why, i)| (why, stim(&i[0], &i[1], &i[2], scale8(96, cmax), cmax, true, true)))
        .collect();
    let o = one(cfg);
    let id = [o, 0, 0, o];
    for (why, c, t, de, se) in [
        (
            "both enables off: C_src through the texture alone",
            scale8(96, cmax),
            cmax,
            false,
            false,
        ),
        ("C_src at full scale: both blends saturate", cmax, cmax, true, true),
        (
            "black texture: the diffuse light vanishes, the specular stays",
            scale8(96, cmax),
            0,
            true,
            true,
        ),
    ] {
        v.push((why.to_string(), stim(&[0, 0], &[0, 0], &id, c, t, de, se)));
    }
    if level >= 2 {
        let n = cfg.env_map_side() as i64;
        let centre = |i: i64| ((2 * i + 1) * o) / n - o;
        for (x, y) in [(0, 0), (n - 1, 0), (0, n - 1), (n - 1, n - 1)] {
            v.push((
                format!("the map's corner texel ({x}, {y}) alone"),
                stim(&[0, 0], &[centre(x), centre(y)], &id, 0, cmax, true, true),
            ));
        }
    }
    v
}

/// Level 1: every unit at its edges, one vector each.
fn corners_level1(cfg: &PipelineConfig) -> Vec<(&'static str, TopStim)> {
    let o = one(cfg);
    let cmax = cfg.colour_max();
    let half = 1u32 << (cfg.normal_bits - 1);
    let nmax = (1u32 << cfg.normal_bits) - 1;
    let kone = 1i64 << cfg.k_frac_bits;
    let flat = flat_code(cfg);
    let lh = cfg.lh_fmt();
    // Colours below are written for 8-bit channels and scaled to the configured width.
    let sc = |x: u32| scale8(x, cmax);
    let base = |codes: [u32; 3], l: [i64; 3], h: [i64; 3], lc: u32, k: i64, c: u32, t: u32| {
        let (c, t, lc) = (
            if c == cmax { c } else { sc(c) },
            if t == cmax { t } else { sc(t) },
            if lc == cmax { lc } else { sc(lc) },
        );
        corner_stim(cfg, codes, l, h, lc, k, c, t)
    };
    let mut v = vec![
        // Each entry: why it is there, then the stimulus.
        (
            "flat normal, light and half vector straight up: the largest dot (B·L = 1 - 2^-(w-1) in both normal ranges: the flat code's B_z is 2^(w-1) - 1; bypassed under skip_flat)",
            base(flat, [0, 0, o], [0, 0, o], cmax, kone, 0, cmax),
        ),
        (
            "light exactly in the surface plane: B·L = 0",
            base(flat, [o, 0, 0], [o, 0, 0], cmax, kone, 10, cmax),
        ),
        (
            "light below the horizon: B·L < 0 clamps to 0 (self-shadowing)",
            base(flat, [0, 0, -o], [0, 0, -o], cmax, kone, 10, cmax),
        ),
        (
            "one L/H LSB above the horizon",
            base(flat, [o, 0, 1], [o, 0, 1], cmax, kone, 10, cmax),
        ),
        (
            "one L/H LSB below the horizon",
            base(flat, [o, 0, -1], [o, 0, -1], cmax, kone, 10, cmax),
        ),
        (
            "largest negative codes everywhere: the dot product's most positive exact sum",
            base([0, 0, 0], [lh.min_raw(); 3], [lh.min_raw(); 3], cmax, kone, 0, cmax),
        ),
        (
            "largest positive L/H against the most negative normal: the most negative sum",
            base([0, 0, 0], [lh.max_raw(); 3], [lh.max_raw(); 3], cmax, kone, 0, cmax),
        ),
        (
            "every light slot at full colour on a white source: saturation",
            base(flat, [0, 0, o], [0, 0, o], cmax, kone, cmax, cmax),
        ),
        (
            "k = 0: lights switched off by modulation",
            base(flat, [0, 0, o], [0, 0, o], cmax, 0, 77, cmax),
        ),
        (
            "black texture colour T: diffuse multiplied away, specular kept in split order",
            base(flat, [0, 0, o], [0, 0, o], cmax, kone, 100, 0),
        ),
        (
            "grazing light: x^n underflows to 0 in the power table",
            base(flat, [o, 0, (o >> 8).max(1)], [o, 0, (o >> 8).max(1)], cmax, kone, 0, cmax),
        ),
        (
            "normal nearly in the surface plane (largest gradient)",
            base([nmax, half, half + 1], [o, 0, 0], [o, 0, 0], cmax, kone, 0, cmax),
        ),
        (
            "zero colour lights: nothing to add",
            base(flat, [0, 0, o], [0, 0, o], 0, kone, 128, 200),
        ),
        (
            "unnormalised (long) L: dot above 1 clamps to 1",
            base(flat, [0, 0, lh.max_raw()], [0, 0, lh.max_raw()], cmax, kone, 0, cmax),
        ),
    ];
    let mut off = base(flat, [0, 0, o], [0, 0, o], cmax, kone, 50, cmax);
    off.frag.diffuse_en = false;
    off.frag.specular_en = false;
    v.push(("both blend enables off: colour passes through texture only", off));
    // Exact ties of the dot-product rounding (the dot_clamp unit's), on L with the highlight
    // off, so the three roundings give three different pairs of colours; only where the
    // fetched B reaches the dot product as it is (renormalising it, or placing it in a frame,
    // moves it off the tie).
    let b_as_fetched = !cfg.renormalise_bump && !cfg.frame_transform && !cfg.palette;
    for (odd, b, l) in crate::model::dot_clamp::rounding_ties(cfg)
        .into_iter()
        .flatten()
        .filter(|_| b_as_fetched)
    {
        let code = |x: i64| (x + half as i64) as u32;
        let mut tie = base([code(b[0]), code(b[1]), code(b[2])], l, [0, 0, 0], cmax, kone, 0, cmax);
        tie.frag.specular_en = false;
        v.push((
            if odd == 1 {
                "dot product B·L exactly 1/2 fd LSB: a rounding tie above an even code"
            } else {
                "dot product B·L exactly 3/2 fd LSB: a rounding tie above an odd code"
            },
            tie,
        ));
    }
    for slot in 0..cfg.lights as usize {
        let mut s = base(flat, [0, 0, o], [0, 0, o], 0, kone, 0, cmax);
        s.state.lights[slot].lc = [cmax, 0, cmax / 2];
        if cfg.white_lights {
            // Lc is not read: the other slots are switched off by k instead.
            for (j, l) in s.state.lights.iter_mut().enumerate().take(cfg.lights as usize) {
                if j != slot {
                    l.k = 0;
                }
            }
        }
        v.push(("a single active light slot (each slot in turn)", s));
    }
    v
}

/// Level 2: sweeps of one and two LSBs around every edge of level 1, grazing and
/// below-horizon angles, the largest gradients in eight directions, unnormalised vectors.
fn corners_level2(cfg: &PipelineConfig) -> Vec<(String, TopStim)> {
    let o = one(cfg);
    let cmax = cfg.colour_max();
    let half = 1u32 << (cfg.normal_bits - 1);
    let nmax = (1u32 << cfg.normal_bits) - 1;
    let kone = 1i64 << cfg.k_frac_bits;
    let lh = cfg.lh_fmt();
    let flat = flat_code(cfg);
    let sc = |x: u32| scale8(x, cmax);
    let mk = |codes: [u32; 3], l: [i64; 3], h: [i64; 3], k: i64, c: u32, t: u32| {
        let (c, t) = (
            if c == cmax || c == cmax / 2 || c == cmax / 2 + 1 {
                c
            } else {
                sc(c)
            },
            if t == cmax || t == cmax / 2 + 1 || t == cmax / 2 {
                t
            } else {
                sc(t)
            },
        );
        corner_stim(cfg, codes, l, h, cmax, k, c, t)
    };
    let mut v = Vec::new();
    // B·L = +1 exactly (B = -1 on x, L = -1 on x) and one or two L LSBs either side.
    for d in -2i64..=2 {
        v.push((
            format!("B·L = +1 {d:+} LSB of L (exact +1 needs B = -1: the positive range stops at 1 - 2^-(w-1))"),
            mk([0, half, half], [-o + d, 0, 0], [-o + d, 0, 0], kone, 0, cmax),
        ));
        v.push((
            format!("B·L = -1 {d:+} LSB of L: the most negative dot clamps to 0"),
            mk([half, half, 0], [0, 0, o + d], [0, 0, o + d], kone, 0, cmax),
        ));
        v.push((
            format!("B·L = 0 {d:+} LSB: either side of the clamp"),
            mk(flat, [o, 0, d], [o, 0, d], kone, 0, cmax),
        ));
    }
    // Elevations of L and H above and below the horizon, in degrees.
    for deg in [-45.0f64, -1.0, -0.1, 0.0, 0.05, 0.1, 0.5, 1.0, 2.0, 5.0, 30.0, 89.9] {
        let r = deg.to_radians();
        let l = [(r.cos() * o as f64).round() as i64, 0, (r.sin() * o as f64).round() as i64];
        v.push((
            format!("light and half vector at {deg}° elevation (grazing, horizon and self-shadowing)"),
            mk(flat, l, l, kone, 20, cmax),
        ));
    }
    // Largest gradients: normals nearly in the surface plane, eight directions.
    let m = nmax as i64;
    let h2 = half as i64;
    for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, 1), (1, -1), (-1, -1)] {
        let comp = |d: i64| {
            (if d > 0 {
                m
            } else if d < 0 {
                0
            } else {
                h2
            }) as u32
        };
        v.push((
            format!("largest gradient towards ({dx}, {dy}): normal almost in the plane"),
            mk(
                [comp(dx), comp(dy), half + 1],
                [dx * o / 2, dy * o / 2, o / 2],
                [0, 0, o],
                kone,
                0,
                cmax,
            ),
        ));
    }
    // Unnormalised by quantisation: components rounded up push |L| above 1.
    let c3 = ((o as f64) / 3f64.sqrt()).ceil() as i64;
    v.push((
        "L = (1,1,1)/√3 rounded up: |L| slightly above 1".into(),
        mk([nmax, nmax, nmax], [c3; 3], [c3; 3], kone, 0, cmax),
    ));
    v.push((
        "L and H at the largest raw code on every component: |L| ≈ 3.46".into(),
        mk([nmax, nmax, nmax], [lh.max_raw(); 3], [lh.max_raw(); 3], kone, 0, cmax),
    ));
    // k at 0, one LSB, one LSB below 1, 1; C_src at 0 and max; T 0 and max.
    for k in [0, 1, kone - 1, kone] {
        for (c, t) in [(0, 0), (0, cmax), (cmax, 0), (cmax, cmax), (cmax / 2, cmax / 2 + 1)] {
            v.push((
                format!("k = {k}/2^K with C_src {c}, T {t}"),
                mk(flat, [0, 0, o], [0, 0, o], k, c, t),
            ));
        }
    }
    v
}

/// How many vectors `exhaustive:unit` holds under `cfg`, or why it cannot be swept (checked
/// before anything is built or written).
pub fn exhaustive_count(cfg: &PipelineConfig, unit: &str) -> Result<u64> {
    let Some(u) = crate::units::unit(unit) else {
        let usual = format!("one of {}", crate::vectors::targets::all_targets()[1..].join(", "));
        return Err(Error::Other(format!(
            "exhaustive:{unit}: no such unit\n  fix: {}",
            crate::renamed::unit_fix(unit, usual)
        )));
    };
    let Some(count) = u.exhaustive_count(cfg) else {
        let swept: Vec<&str> = crate::units::UNITS
            .iter()
            .filter(|u| u.included(cfg) && u.exhaustive_count(cfg).is_some())
            .map(|u| u.name())
            .collect();
        let when = u
            .exhaustive_when()
            .map_or(String::new(), |w| format!("; exhaustive:{unit} needs {w}"));
        return Err(Error::Other(format!(
            "exhaustive:{unit}: {unit} has too many input combinations to sweep under this configuration\n  fix: use random:N{when}; this configuration sweeps whole: {}",
            swept.join(", ")
        )));
    };
    let max = crate::limits::MAX_EXHAUSTIVE_VECTORS;
    if count > max {
        return Err(Error::Other(format!(
            "exhaustive:{unit}: {count} vectors under this configuration, more than MAX_EXHAUSTIVE_VECTORS = {max}\n  fix: use random:N for this configuration"
        )));
    }
    Ok(count)
}

/// Unit stimuli that sweep a small unit exhaustively.
pub fn exhaustive(cfg: &PipelineConfig, unit: &str) -> Result<Vec<UnitStim>> {
    let count = exhaustive_count(cfg, unit)?;
    let u = crate::units::unit(unit).expect("checked");
    Ok((0..count)
        .map(|i| UnitStim {
            unit: u.name(),
            inputs: u.exhaustive_input(cfg, i),
        })
        .collect())
}

#[cfg(test)]
mod exhaustive_tests {
    /// A unit whose domain fits only some configurations says which, with the fix.
    #[test]
    fn a_too_large_domain_names_when_the_unit_has_one() {
        let toml = "bump_state = \"fragment\"\ninterpolate = \"h\"\nrenormalise = true\nlight_mode = \"parallel\"\n";
        let cfg = crate::PipelineConfig::from_toml("x.toml", toml).unwrap();
        let e = super::exhaustive_count(&cfg, "normalise").unwrap_err().to_string();
        assert!(e.contains("needs lh_bits <= 6") && e.contains("random:N"), "{e}");
        let narrow = crate::PipelineConfig { lh_bits: 6, ..cfg };
        assert_eq!(super::exhaustive_count(&narrow, "normalise").unwrap(), 1 << 18);
    }
}

#[cfg(test)]
mod triangle_tests {
    use super::*;

    /// The documented triangle lengths: 1 to TRIANGLE_MAX_FRAGMENTS, ONE_FRAGMENT_SHARE of one,
    /// and one-fragment triangles back to back.
    #[test]
    fn random_triangles_have_the_documented_lengths() {
        let cfg = PipelineConfig::default();
        let mut t = RandomTriangles::new(&cfg, chunk_rng(7, 0));
        let mut lens: Vec<u64> = Vec::new();
        let mut prev: Option<TopStim> = None;
        for _ in 0..200_000 {
            let s = t.next(&cfg);
            if s.tri_start {
                lens.push(0);
            } else {
                assert_eq!(
                    s.state,
                    prev.expect("a triangle before").state,
                    "a triangle's fragments share its state"
                );
            }
            *lens.last_mut().expect("the stream starts a triangle") += 1;
            prev = Some(s);
        }
        lens.pop();
        assert!(lens.iter().all(|&n| (1..=TRIANGLE_MAX_FRAGMENTS).contains(&n)));
        assert!(lens.contains(&TRIANGLE_MAX_FRAGMENTS));
        let ones = lens.iter().filter(|&&n| n == 1).count() as f64 / lens.len() as f64;
        let mean = lens.iter().sum::<u64>() as f64 / lens.len() as f64;
        // The figures the integration notes state, from the same function.
        let (want_ones, want_mean) = random_triangle_shape();
        println!(
            "one-fragment share {ones:.4} (stated {want_ones:.4}), mean {mean:.3} (stated {want_mean:.3}) over {} triangles",
            lens.len()
        );
        assert!((ones - want_ones).abs() < 0.01, "{ones} against {want_ones}");
        assert!((mean / want_mean - 1.0).abs() < 0.02, "{mean} against {want_mean}");
        assert!(lens.windows(2).any(|w| w == [1, 1]));
    }
}

#[cfg(test)]
mod state_tests {
    use super::*;
    use crate::vectors::rng::{range_of, unit_of};

    /// The state one light at a time, as gbump drew it before the lanes: a seed's records
    /// must not change between versions.
    fn one_light_at_a_time(cfg: &PipelineConfig, rng: &mut SplitMix64) -> BumpState {
        let q_vec = |v: [f64; 3]| {
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            // The library's rounding, not the lanes' own, so the two are checked apart.
            v.map(|c| (c / len * one(cfg) as f64).round() as i64)
                .map(|c| c.clamp(cfg.lh_fmt().min_raw(), cfg.lh_fmt().max_raw()))
        };
        let (cmax, kone) = (cfg.colour_max() as i64, 1i64 << cfg.k_frac_bits);
        let raw = rng.chance(0.5);
        let lh = cfg.lh_fmt();
        let mut state = BumpState::default();
        for s in state.lights.iter_mut().take(cfg.lights as usize) {
            let x = rng.next_block::<10>();
            let vec = |at: usize| {
                if raw {
                    [0, 1, 2].map(|i| range_of(x[at + i], lh.min_raw(), lh.max_raw()))
                } else {
                    let u = |i: usize| unit_of(x[at + i]);
                    q_vec([u(0) * 2.0 - 1.0, u(1) * 2.0 - 1.0, u(2) * 1.2 - 0.2])
                }
            };
            *s = LightSlot {
                l: vec(0),
                h: vec(3),
                lc: [6, 7, 8].map(|i| range_of(x[i], 0, cmax) as u32),
                k: if unit_of(x[9]) < 0.5 { kone } else { rng.range(0, kone) },
            };
        }
        state
    }

    /// The lanes' rounding is the library's, half away from zero, on every value it is
    /// given, NaN (0) and the edges of its range among them.
    #[test]
    fn round_half_away_is_round() {
        let mut rng = SplitMix64(0x0DD);
        let two52 = (1u64 << 52) as f64;
        let edges = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -2.5,
            0.49999999999999994,
            -0.49999999999999994,
            two52,
            -two52,
            two52 - 0.5,
        ];
        let drawn = (0..100_000).map(|i| (unit_of(rng.next_u64()) * 2.0 - 1.0) * (1u64 << (i % 53)) as f64);
        for x in edges.into_iter().chain(drawn) {
            assert_eq!(round_half_away(x), x.round() as i64, "{x}");
        }
        assert_eq!(round_half_away(f64::NAN), 0);
        let wide = 1i64 << 62;
        assert_eq!((round_half_away(1e300), round_half_away(-f64::INFINITY)), (wide, -wide));
    }

    #[test]
    fn lanes_draw_the_states_one_light_at_a_time_drew() {
        for (lights, lh_bits, k_frac_bits) in [(1, 16, 8), (4, 16, 8), (8, 24, 3), (3, 6, 0), (8, 4, 12)] {
            let cfg = PipelineConfig {
                lights,
                lh_bits,
                k_frac_bits,
                ..PipelineConfig::default()
            };
            let (mut a, mut b) = (SplitMix64(lights as u64), SplitMix64(lights as u64));
            for _ in 0..20_000 {
                let (x, y) = (random_state(&cfg, &mut a), one_light_at_a_time(&cfg, &mut b));
                assert_eq!(x.lights, y.lights, "{lights} lights, lh_bits {lh_bits}");
            }
            assert_eq!(a.next_u64(), b.next_u64());
        }
    }
}
