//! SplitMix64: a tiny, fixed pseudo-random generator, so that a seed gives the same vectors in
//! every gbump version and on every platform (library RNG streams may change between releases).

#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

#[inline(always)]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl SplitMix64 {
    #[inline(always)]
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(GAMMA);
        mix(self.0)
    }

    /// The next `K` values, the same as `K` calls of [`next_u64`](Self::next_u64): each
    /// depends only on the state and its place, so the `K` mixes run side by side (vector
    /// operations where the caller is compiled for them).
    #[inline(always)]
    pub fn next_block<const K: usize>(&mut self) -> [u64; K] {
        let block = self.peek_block::<K>();
        self.skip(K as u64);
        block
    }

    /// The next `K` values without taking them: `take` of them are taken with
    /// [`skip`](Self::skip). Drawing ahead in a fixed-size block lets the mixes of several
    /// records run in vector registers when fewer are needed than the block holds.
    #[inline(always)]
    pub fn peek_block<const K: usize>(&self) -> [u64; K] {
        // A loop over an array, not `array::from_fn`: past a few dozen values that became a
        // call, compiled without the caller's vector instructions, a mix at a time.
        let mut block = [0u64; K];
        let mut x = self.0;
        for b in block.iter_mut() {
            x = x.wrapping_add(GAMMA);
            *b = mix(x);
        }
        block
    }

    /// Take `n` values unseen (the state `n` calls of [`next_u64`](Self::next_u64) leave).
    #[inline(always)]
    pub fn skip(&mut self, n: u64) {
        self.0 = self.0.wrapping_add(n.wrapping_mul(GAMMA));
    }

    /// Uniform in `lo..=hi`.
    #[inline(always)]
    pub fn range(&mut self, lo: i64, hi: i64) -> i64 {
        range_of(self.next_u64(), lo, hi)
    }

    /// Uniform in [0, 1).
    #[inline(always)]
    pub fn unit(&mut self) -> f64 {
        unit_of(self.next_u64())
    }

    #[inline(always)]
    pub fn chance(&mut self, p: f64) -> bool {
        unit_of(self.next_u64()) < p
    }
}

/// [`SplitMix64::range`] of the drawn value `x`.
#[inline(always)]
pub fn range_of(x: u64, lo: i64, hi: i64) -> i64 {
    let span = (hi - lo) as u64 + 1;
    // The same value as `%`; a mask where it may be (every colour and normal code span at
    // the usual widths), since a 64-bit division costs more than the rest of the draw.
    lo + if span.is_power_of_two() { x & (span - 1) } else { x % span } as i64
}

/// [`range_of`] for one range, its remainder formed by multiplications (Lemire, Kaser and
/// Kurz, "Faster remainder by direct computation", 2019: exact for every 64-bit value with a
/// 128-bit constant), where `%` by a span known only at run time is a 64-bit division.
#[derive(Clone, Copy, Debug)]
pub struct Span {
    lo: i64,
    span: u64,
    /// ceil(2^128 / span); 0 for a power-of-two span, which is a mask.
    m: u128,
}

impl Span {
    #[inline(always)]
    pub fn new(lo: i64, hi: i64) -> Span {
        let span = (hi - lo) as u64 + 1;
        let m = if span.is_power_of_two() { 0 } else { u128::MAX / span as u128 + 1 };
        Span { lo, span, m }
    }

    /// `range_of(x, lo, hi)`.
    #[inline(always)]
    pub fn of(&self, x: u64) -> i64 {
        if self.m == 0 {
            return self.lo + (x & self.span.wrapping_sub(1)) as i64;
        }
        // x mod span = floor(frac(x·m / 2^128)·span): the high 64 bits of the 192-bit
        // product of the low 128 bits of x·m and the span.
        let low = self.m.wrapping_mul(x as u128);
        let (lo_part, hi_part) = (low as u64 as u128, low >> 64);
        let d = self.span as u128;
        let top = (hi_part * d + ((lo_part * d) >> 64)) >> 64;
        self.lo + top as i64
    }
}

/// [`SplitMix64::unit`] of the drawn value `x`.
#[inline(always)]
pub fn unit_of(x: u64) -> f64 {
    // Through i64 (the 53-bit value is one either way): a signed conversion is one
    // instruction on every x86-64, and vectorises; an unsigned one is a sequence.
    ((x >> 11) as i64) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A span's remainder by multiplication is `%`'s, for every span shape and the values
    /// at the edges of the 64-bit range.
    #[test]
    fn a_span_is_range_of() {
        let mut rng = SplitMix64(0x5BA);
        let spans = [
            (0, 256),
            (0, 255),
            (-5, 5),
            (0, 1),
            (0, 0),
            (3, 3),
            (0, (1 << 40) + 7),
            (i64::MIN / 2, i64::MAX / 2 - 1),
            // 2^63, the widest span `range_of` takes, a power of two two ways.
            (i64::MIN / 2, i64::MAX / 2),
            (i64::MIN, -1),
        ];
        for (lo, hi) in spans {
            let s = Span::new(lo, hi);
            let edges = [0, 1, u64::MAX, u64::MAX - 1, 1 << 63, (1 << 63) - 1];
            for x in edges.into_iter().chain((0..20_000).map(|_| rng.next_u64())) {
                assert_eq!(s.of(x), range_of(x, lo, hi), "{x} in {lo}..={hi}");
            }
        }
    }

    /// A block is the values one call at a time gives, and leaves the same state.
    #[test]
    fn a_block_is_successive_draws() {
        for seed in [0, 1, 0x5EED, u64::MAX - 3] {
            let (mut a, mut b) = (SplitMix64(seed), SplitMix64(seed));
            let block = a.next_block::<11>();
            let one: Vec<u64> = (0..11).map(|_| b.next_u64()).collect();
            assert_eq!(block.to_vec(), one);
            assert_eq!(a.next_u64(), b.next_u64());
            // A peeked block is the same values; skipping part of it leaves the state those
            // draws would.
            let (mut c, mut d) = (SplitMix64(seed), SplitMix64(seed));
            let ahead = c.peek_block::<16>();
            c.skip(5);
            let one: Vec<u64> = (0..5).map(|_| d.next_u64()).collect();
            assert_eq!(ahead[..5], one[..]);
            assert_eq!(c.next_u64(), d.next_u64());
            assert_eq!(c.next_u64(), ahead[6]);
        }
    }
}
