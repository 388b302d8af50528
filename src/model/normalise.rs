//! normalise: a vector scaled back to unit length, as per-pixel engines renormalise their
//! interpolated vectors (the Cg tutorial's normalisation cube map, §8.2; Blinn's N'/|N'|,
//! paper §2), done the way hardware does it without a divider or a square root: a table of
//! reciprocal square roots, indexed by the leading bits of the squared length, refined by
//! Newton steps.
//!
//! Two units share it, each for its [`Shape`]: `normalise` for an interpolated L or H (raw
//! `s1.F` components, F = lh_bits - 2, the unit length carrying `scale` =
//! `PipelineConfig::normal_scale`: 1, or 2^(w-1)/(2^(w-1)-1) for symmetric normals), and
//! `normalise_b` for the fetched bump normal (raw `s0.F`, F = normal_bits - 1, whose unit is
//! 2^F codes, or 2^F - 1 for symmetric normals). Each computes `v · 2^F · scale / |v|`:
//!
//! 1. `s = x² + y² + z²`, exact. For L and H with symmetric normals `S = s·(h-1)²` with
//!    h = 2^(nb-1) (two shifted subtractions), so that `scale/sqrt(s) = h/sqrt(S)`; otherwise
//!    `S = s`.
//! 2. `S` is shifted left by the even amount `z` that puts its leading one in the top two
//!    bits of an `L`-bit window (`L` = 2(F+2), plus 2(nb-1) for L and H with symmetric
//!    normals): `m = (S << z) / 2^L` lies in [1/4, 1) and `1/sqrt(S) = (1/sqrt(m)) · 2^((z-L)/2)`.
//! 3. `r0 = table[top T bits of S << z]`: `round(2^Y / sqrt(mid-point of the interval))`,
//!    u2.Y. The table has `3·2^(T-2)` entries (the index's top two bits are never 00).
//! 4. Newton steps for `1/sqrt(m)`, each truncating to Y fraction bits:
//!    `q = r²`, `u = m_M · q` (m cut to M bits), `r = r · (3 - u) / 2`.
//! 5. `n = round(x · r · 2^(z/2) / 2^(Y+2))`, half up whatever the configuration's `rounding`
//!    (Newton's method approaches 1/sqrt(m) from below, so truncating would shorten every
//!    vector: a unit axis would lose an LSB), saturated to the input's format. A bump normal
//!    with symmetric normals is multiplied by 2^(nb-1) - 1 (a shift and a subtraction)
//!    before that rounding, which then drops nb - 1 more bits.
//!
//! A zero vector stays zero. How many table bits and Newton steps are used follows from F
//! ([`params`]): the table alone for short words, one step when a table of at most
//! 2^[`MAX_ONE_STEP_TABLE_BITS`] index values makes it enough, two otherwise; `normalise`'s tests hold the result within
//! [`ERROR_BOUND_LSB`] of `v·scale/|v|` for every width.

use crate::config::{NormalRange, PipelineConfig};
use crate::fixed::shift_round;

/// The unit's one rounding (see step 5 above).
pub const ROUNDING: crate::fixed::Rounding = crate::fixed::Rounding::HalfUp;

/// How far the unit's result may be from `v·scale/|v|`, in LSBs of s1.F, at every width
/// (the tests hold it; the README states it).
pub const ERROR_BOUND_LSB: f64 = 0.75;

/// What a normalise unit scales: its components' width and fraction bits (`s?.F`), and the
/// factor its unit length carries: `v · 2^F · scale / |v|`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shape {
    pub width: u32,
    pub frac: u32,
    /// S is multiplied by (2^pre - 1)^2, scaling the result by 2^pre / (2^pre - 1): L and H
    /// with symmetric normals (0: none).
    pub pre_bits: u32,
    /// The result is multiplied by (2^post - 1) / 2^post: a bump normal with symmetric
    /// normals, whose unit is 2^(nb-1) - 1 (0: none).
    pub post_bits: u32,
}

impl Shape {
    /// An interpolated L or H: `s1.(lh-2)`, times the normals' scale.
    pub fn lh(cfg: &PipelineConfig) -> Shape {
        Shape {
            width: cfg.lh_bits,
            frac: cfg.lh_bits - 2,
            pre_bits: match cfg.normal_range {
                NormalRange::Binary => 0,
                NormalRange::Symmetric => cfg.normal_bits - 1,
            },
            post_bits: 0,
        }
    }
    /// An axis of a frame built per fragment (`frame_build`): `s1.(lh-2)` at plain unit
    /// length, the scale `in_frame` gives 1.0 whatever the normals' range.
    pub fn frame(cfg: &PipelineConfig) -> Shape {
        Shape {
            width: cfg.lh_bits,
            frac: cfg.lh_bits - 2,
            pre_bits: 0,
            post_bits: 0,
        }
    }
    /// A fetched bump normal B: `s0.(nb-1)`, whose unit is 2^(nb-1) (binary) or 2^(nb-1) - 1
    /// (symmetric) codes.
    pub fn bump(cfg: &PipelineConfig) -> Shape {
        Shape {
            width: cfg.normal_bits,
            frac: cfg.normal_bits - 1,
            pre_bits: 0,
            post_bits: match cfg.normal_range {
                NormalRange::Binary => 0,
                NormalRange::Symmetric => cfg.normal_bits - 1,
            },
        }
    }
    /// The components' format, in and out.
    pub fn fmt(&self) -> crate::fixed::Format {
        crate::fixed::Format::s(self.width, self.frac)
    }
    /// The factor the unit length carries.
    pub fn scale(&self) -> f64 {
        let up = |b: u32| {
            if b == 0 {
                1.0
            } else {
                (b as f64).exp2() / ((b as f64).exp2() - 1.0)
            }
        };
        up(self.pre_bits) / up(self.post_bits)
    }
}

/// The sizes of a normalise unit under a configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Params {
    /// Index bits T of the reciprocal-square-root table.
    pub table_bits: u32,
    /// Newton steps after the table (0 to 2).
    pub steps: u32,
    /// Fraction bits Y of the reciprocal r (u2.Y).
    pub r_frac: u32,
    /// Bits M of m that the Newton steps multiply by.
    pub m_bits: u32,
    /// Extra bits of S for symmetric normals (nb - 1, else 0).
    pub pre_bits: u32,
    /// Bits of the final (2^post - 1) multiply ([`Shape::post_bits`]).
    pub post_bits: u32,
    /// Width L of the normalised squared-length window.
    pub window: u32,
}

impl Params {
    /// Table entries: index values 2^(T-2) ..= 2^T - 1.
    pub fn entries(&self) -> u32 {
        3 << (self.table_bits - 2)
    }
    /// The first index the table holds.
    pub fn first_index(&self) -> u32 {
        1 << (self.table_bits - 2)
    }
    /// Bits of the even shift z, which reaches L - 2 (S = 1).
    pub fn shift_bits(&self) -> u32 {
        32 - (self.window - 2).leading_zeros()
    }
    /// Bits of a table word (u2.Y).
    pub fn word_bits(&self) -> u32 {
        self.r_frac + 2
    }
}

/// The widest table index of the one-step regime: a table of 3·2^(T-2) words costs less logic
/// than a second Newton step's three multipliers up to here (384 words at the default 16-bit
/// L and H), and a chain of two steps in one stage is what synthesis takes longest over.
pub const MAX_ONE_STEP_TABLE_BITS: u32 = 9;

/// The table and Newton-step sizes for `cfg`: enough for the result to be within one LSB of
/// `v·scale/|v|`. The relative error of a mid-point table is at most 2^-T (at m = 1/4), and a
/// Newton step squares it (times 3/2); the result needs about 2^-(F+2).
pub fn params(cfg: &PipelineConfig) -> Params {
    params_of(&Shape::lh(cfg))
}

/// The same for any [`Shape`]: the sizes follow from its fraction bits F alone.
pub fn params_of(shape: &Shape) -> Params {
    let f = shape.frac;
    let (table_bits, steps) = if f + 2 <= 6 {
        ((f + 2).max(4), 0)
    } else if (f + 3).div_ceil(2) <= MAX_ONE_STEP_TABLE_BITS {
        ((f + 3).div_ceil(2), 1)
    } else {
        ((f + 4).div_ceil(4).max(4), 2)
    };
    let pre_bits = shape.pre_bits;
    let r_frac = f + 4;
    Params {
        table_bits,
        steps,
        r_frac,
        m_bits: r_frac + 2,
        pre_bits,
        post_bits: shape.post_bits,
        window: 2 * (f + 2) + 2 * pre_bits,
    }
}

/// Table word `i` (index `first_index + i`): round(2^Y / sqrt(mid-point)), u2.Y. Computed in
/// f64 from a correctly rounded square root and division, so every platform agrees.
pub fn table_word(p: &Params, i: u32) -> i64 {
    let idx = (p.first_index() + i) as f64;
    let mid = (idx + 0.5) / (p.table_bits as f64).exp2();
    ((p.r_frac as f64).exp2() / mid.sqrt() + 0.5).floor() as i64
}

/// One Newton step for 1/sqrt(m) from `r` (u2.Y, m cut to M bits), as the RTL computes it:
/// the step's `3 - m r²` and the new r.
pub fn newton_step(p: &Params, m: i128, r: i128) -> (i128, i128) {
    let y = p.r_frac;
    let q = (r * r) >> y;
    let e = (3i128 << y) - ((m * q) >> p.m_bits);
    (e, (r * e) >> (y + 1))
}

/// The unit's arithmetic up to the reciprocal, as (the even shift z, r): None for a zero
/// vector.
pub fn reciprocal(p: &Params, v: [i64; 3]) -> Option<(u32, i64)> {
    let s: i128 = v.iter().map(|&x| (x as i128) * (x as i128)).sum();
    if s == 0 {
        return None;
    }
    let big_s = if p.pre_bits == 0 {
        s
    } else {
        // s·(h-1)² = s·h² - 2·s·h + s, h = 2^(nb-1): shifts and adds.
        (s << (2 * p.pre_bits)) - (s << (p.pre_bits + 1)) + s
    };
    let len = 128 - big_s.leading_zeros();
    let shift = (p.window - len) & !1;
    let sn = big_s << shift;
    let index = (sn >> (p.window - p.table_bits)) as u32;
    let mut r = table_word(p, index - p.first_index()) as i128;
    let m = sn >> (p.window - p.m_bits);
    for _ in 0..p.steps {
        r = newton_step(p, m, r).1;
    }
    Some((shift, r as i64))
}

/// Which of a light's vectors the pipeline renormalises under `cfg`, as (L, H): H whenever
/// `renormalise` is set, L only when it is interpolated too (`interpolate = "hl"`; a
/// per-triangle L is a unit vector already). The top, the model, the per-unit stimuli and the
/// error measure all ask this.
pub fn renormalised(cfg: &PipelineConfig) -> (bool, bool) {
    (
        cfg.renormalise && cfg.interpolate == crate::config::Interpolate::Hl,
        cfg.renormalise,
    )
}

/// The unit that renormalises L and H under `cfg`: `normalise`, or `normalise_cube` when the
/// configuration reads a cube map.
pub fn lh_unit(cfg: &PipelineConfig) -> &'static str {
    if cfg.cube_map_face > 0 {
        "normalise_cube"
    } else {
        "normalise"
    }
}

/// The normalised L or H, raw `s1.F` components: the `normalise` unit's arithmetic, or the
/// `normalise_cube` unit's map when `cube_map_face` is set.
pub fn normalise(cfg: &PipelineConfig, v: [i64; 3]) -> [i64; 3] {
    if cfg.cube_map_face > 0 {
        return super::cube_normalise::cube_normalise(cfg, v);
    }
    normalise_shape(&Shape::lh(cfg), v)
}

/// The normalised bump normal (`renormalise_bump`), raw `s0.(nb-1)` components.
pub fn normalise_bump(cfg: &PipelineConfig, b: [i64; 3]) -> [i64; 3] {
    normalise_shape(&Shape::bump(cfg), b)
}

/// A vector of `shape` normalised: the unit's arithmetic.
// Never inlined: inlined into the fast model's run, its table set-up (an `exp2`) was hoisted
// above the check that skips it, and every run of every configuration paid for it.
#[inline(never)]
pub fn normalise_shape(shape: &Shape, v: [i64; 3]) -> [i64; 3] {
    let p = params_of(shape);
    let Some((shift, r)) = reciprocal(&p, v) else {
        return [0; 3];
    };
    let fmt = shape.fmt();
    v.map(|x| {
        let mut q = (x as i128) * (r as i128);
        if p.post_bits > 0 {
            // Times 2^post - 1: a shift and a subtraction.
            q = (q << p.post_bits) - q;
        }
        let n = shift_round(q << (shift / 2), p.r_frac + 2 + p.post_bits, ROUNDING);
        n.clamp(fmt.min_raw() as i128, fmt.max_raw() as i128) as i64
    })
}

/// The same in f64, without roundings: `v · scale / |v|` in output LSBs (0 for a zero vector);
/// with `cube_map_face`, the direction through the texel's centre that the map rounds.
pub fn normalise_exact(cfg: &PipelineConfig, v: [i64; 3]) -> [f64; 3] {
    if cfg.cube_map_face > 0 {
        return super::cube_normalise::cube_normalise_exact(cfg, v);
    }
    normalise_exact_shape(&Shape::lh(cfg), v)
}

/// [`normalise_exact`] for any [`Shape`].
pub fn normalise_exact_shape(shape: &Shape, v: [i64; 3]) -> [f64; 3] {
    let s: f64 = v.iter().map(|&x| (x as f64) * (x as f64)).sum();
    if s == 0.0 {
        return [0.0; 3];
    }
    let k = shape.scale() * (shape.frac as f64).exp2() / s.sqrt();
    v.map(|x| x as f64 * k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cfg(lh: u32, range: NormalRange, nb: u32) -> PipelineConfig {
        PipelineConfig {
            lh_bits: lh,
            normal_range: range,
            normal_bits: nb,
            ..Default::default()
        }
    }

    /// SplitMix64, for reproducible draws without a dependency.
    fn next(s: &mut u64) -> u64 {
        *s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = *s;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// The worst distance from `v·scale/|v|` over `vs`, in LSBs (the exact value clamped to
    /// the format, as the unit saturates).
    fn worst(c: &PipelineConfig, vs: impl Iterator<Item = [i64; 3]>) -> (f64, [i64; 3]) {
        let f = c.lh_fmt();
        let mut w = (0f64, [0; 3]);
        for v in vs {
            let (n, e) = (normalise(c, v), normalise_exact(c, v));
            for k in 0..3 {
                let d = (n[k] as f64 - e[k].clamp(f.min_raw() as f64, f.max_raw() as f64)).abs();
                if d > w.0 {
                    w = (d, v);
                }
            }
        }
        w
    }

    /// The normal ranges the unit is checked under: binary, and symmetric at the narrowest,
    /// two middle and the widest normals (the scale is largest at the narrowest).
    const RANGES: [(NormalRange, u32); 5] = [
        (NormalRange::Binary, 8),
        (NormalRange::Symmetric, 3),
        (NormalRange::Symmetric, 4),
        (NormalRange::Symmetric, 8),
        (NormalRange::Symmetric, 16),
    ];

    /// Within ERROR_BOUND_LSB of the exact unit vector: every vector of every width up to 6
    /// bits (the table-alone regime), and for wider words the shortest vectors, the most
    /// negative components, and random vectors of every length the format holds.
    #[test]
    fn within_the_bound_of_the_exact_unit_vector_at_every_width() {
        let (lo, hi) = crate::config::limit("lh_bits");
        for lh in lo..=hi {
            for (range, nb) in RANGES {
                let c = cfg(lh, range, nb);
                let f = c.lh_fmt();
                let (min, top) = (f.min_raw(), f.max_raw());
                let (w, at) = if lh <= 6 {
                    let span = (top - min + 1) as u64;
                    worst(
                        &c,
                        (0..span.pow(3)).map(|i| [i % span, i / span % span, i / span / span].map(|x| min + x as i64)),
                    )
                } else {
                    let mut seed = lh as u64 * 1000 + nb as u64;
                    let edges = [
                        [min, 0, 0],
                        [min, min, min],
                        [min, top, 0],
                        [top, top, top],
                        [1, 0, 0],
                        [1, 1, 1],
                        [-1, 1, -1],
                    ];
                    let random = (0..20_000u64).map(move |i| {
                        let bits = 1 + (i % (lh as u64 - 1)) as u32;
                        let lim = 1i64 << bits;
                        [0, 1, 2].map(|_| ((next(&mut seed) % (2 * lim as u64 + 1)) as i64 - lim).clamp(min, top))
                    });
                    worst(&c, edges.into_iter().chain(random))
                };
                assert!(
                    w <= ERROR_BOUND_LSB,
                    "lh {lh} {range:?} nb {nb}: {w} LSB at {at:?}, {:?}",
                    params(&c)
                );
            }
        }
    }

    /// A fetched bump normal (`renormalise_bump`) within the same bound of `b · unit / |b|`:
    /// every vector up to 6-bit normals, edges and random vectors above, both ranges.
    #[test]
    fn bump_normals_are_within_the_bound_at_every_width() {
        let (lo, hi) = crate::config::limit("normal_bits");
        for nb in lo..=hi {
            for range in [NormalRange::Binary, NormalRange::Symmetric] {
                let c = cfg(16, range, nb);
                let shape = Shape::bump(&c);
                let f = shape.fmt();
                let (min, top) = (f.min_raw(), f.max_raw());
                let all: Box<dyn Iterator<Item = [i64; 3]>> = if nb <= 6 {
                    let span = (top - min + 1) as u64;
                    Box::new((0..span.pow(3)).map(move |i| [i % span, i / span % span, i / span / span].map(|x| min + x as i64)))
                } else {
                    let mut seed = nb as u64 * 77;
                    let edges = [[min, 0, 0], [min, min, min], [top, top, top], [1, 0, 0], [-1, 1, -1], [0, 0, top]];
                    Box::new(edges.into_iter().chain((0..20_000u64).map(move |i| {
                        let bits = 1 + (i % (nb as u64 - 1)) as u32;
                        let lim = 1i64 << bits;
                        [0, 1, 2].map(|_| ((next(&mut seed) % (2 * lim as u64 + 1)) as i64 - lim).clamp(min, top))
                    })))
                };
                let mut w = (0f64, [0; 3]);
                for v in all {
                    let (n, e) = (normalise_shape(&shape, v), normalise_exact_shape(&shape, v));
                    for k in 0..3 {
                        let d = (n[k] as f64 - e[k].clamp(min as f64, top as f64)).abs();
                        if d > w.0 {
                            w = (d, v);
                        }
                    }
                }
                assert!(w.0 <= ERROR_BOUND_LSB, "nb {nb} {range:?}: {} LSB at {:?}", w.0, w.1);
            }
        }
        // The flat normal stays the flat normal, so the flat bypass sees the same codes.
        for range in [NormalRange::Binary, NormalRange::Symmetric] {
            let c = cfg(16, range, 8);
            assert_eq!(normalise_bump(&c, c.flat_normal()), c.flat_normal());
        }
    }

    /// The README states the bound and the table sizes this module uses.
    #[test]
    fn the_readme_states_the_bound_and_the_sizes() {
        let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
        let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(flat.contains(&format!("within {ERROR_BOUND_LSB} LSB of `v·scale/|v|`")));
        // The last width of each regime, and the largest table of the one-step regime.
        let regime = |lh: u32| params(&cfg(lh, NormalRange::Binary, 8));
        assert!(regime(6).steps == 0 && regime(7).steps == 1 && regime(17).steps == 1 && regime(18).steps == 2);
        assert!(flat.contains("the table alone up to `lh_bits = 6`, one step with a table of at most 384 words up to 17, two steps above"));
        assert_eq!((4..=17).map(regime).filter(|p| p.steps == 1).map(|p| p.entries()).max(), Some(384));
    }

    #[test]
    fn axes_stay_unit_vectors_and_zero_stays_zero() {
        let c = PipelineConfig::default();
        let one = 1i64 << (c.lh_bits - 2);
        assert_eq!(normalise(&c, [0, 0, 0]), [0, 0, 0]);
        for len in [1, 3, one / 2, one, one + 7, 2 * one - 1] {
            assert_eq!(normalise(&c, [0, 0, len]), [0, 0, one], "length {len}");
            assert_eq!(normalise(&c, [-len, 0, 0]), [-one, 0, 0], "length {len}");
        }
    }

    #[test]
    fn the_table_index_covers_its_words() {
        for lh in 4..=24 {
            let p = params(&cfg(lh, NormalRange::Binary, 8));
            assert!((4..=MAX_ONE_STEP_TABLE_BITS).contains(&p.table_bits), "{p:?}");
            // The largest word fits u2.Y.
            assert!(table_word(&p, 0) < 1 << p.word_bits());
        }
    }
}
