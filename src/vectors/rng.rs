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
        let s = self.0;
        self.0 = s.wrapping_add((K as u64).wrapping_mul(GAMMA));
        std::array::from_fn(|k| mix(s.wrapping_add((k as u64 + 1).wrapping_mul(GAMMA))))
    }

    /// The next `K` values without taking them: `take` of them are taken with
    /// [`skip`](Self::skip). Drawing ahead in a fixed-size block lets the mixes of several
    /// records run in vector registers when fewer are needed than the block holds.
    #[inline(always)]
    pub fn peek_block<const K: usize>(&self) -> [u64; K] {
        let s = self.0;
        std::array::from_fn(|k| mix(s.wrapping_add((k as u64 + 1).wrapping_mul(GAMMA))))
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

/// [`SplitMix64::unit`] of the drawn value `x`.
#[inline(always)]
pub fn unit_of(x: u64) -> f64 {
    (x >> 11) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

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
