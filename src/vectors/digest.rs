//! The digest every gbump testbench prints beside its summary: a fold of each record it
//! checked, in order, so a pass shows that the records it compared were the set's own. A
//! count of passed vectors alone is printed as easily by a program that read nothing (a
//! wrapper, another testbench, a file of another set of the same length).
//!
//! A record's fold is the XOR of its 64-bit words, LSB first (the binary record's bytes as
//! little-endian words, zero past its last byte; the text record's value in 64-bit slices);
//! the digest starts at 0 and takes each record as `d = rotl(d, 1) ^ fold`. It is printed as
//! `digest` and 16 hex digits.

/// The line's first word.
pub const PREFIX: &str = "digest ";

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Digest(pub u64);

impl Digest {
    /// Take one record given as its 64-bit words, LSB first.
    #[inline]
    pub fn words(&mut self, words: &[u64]) {
        self.0 = self.0.rotate_left(1) ^ words.iter().fold(0, |f, w| f ^ w);
    }

    /// Take one binary record (its bytes, LSB first).
    #[inline]
    pub fn bytes(&mut self, record: &[u8]) {
        let f = record.chunks(8).fold(0u64, |f, c| {
            let mut w = [0u8; 8];
            w[..c.len()].copy_from_slice(c);
            f ^ u64::from_le_bytes(w)
        });
        self.0 = self.0.rotate_left(1) ^ f;
    }

    /// Take every record of `bin`, `record_bytes` each.
    pub fn records(&mut self, bin: &[u8], record_bytes: usize) {
        for r in bin.chunks_exact(record_bytes) {
            self.bytes(r);
        }
    }

    /// The line a testbench prints.
    pub fn line(&self) -> String {
        format!("{PREFIX}{:016x}", self.0)
    }

    /// The digest a testbench's log states (its last `digest` line), if any.
    pub fn of_log(log: &str) -> Option<Digest> {
        log.lines()
            .rev()
            .find_map(|l| l.trim().strip_prefix(PREFIX))
            .and_then(|h| u64::from_str_radix(h.trim(), 16).ok())
            .map(Digest)
    }
}

#[cfg(test)]
mod tests {
    use super::Digest;

    /// A record's bytes and its words fold alike, and the order of records counts.
    #[test]
    fn bytes_and_words_agree_and_order_counts() {
        let words = [0x0123_4567_89ab_cdefu64, 0x0000_0000_00ff_0001];
        let mut bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        bytes.truncate(11);
        let (mut a, mut b) = (Digest::default(), Digest::default());
        a.words(&words);
        b.bytes(&bytes);
        assert_eq!(a, b);
        let (mut x, mut y) = (Digest::default(), Digest::default());
        x.words(&[1]);
        x.words(&[2]);
        y.words(&[2]);
        y.words(&[1]);
        assert_ne!(x, y);
        assert_eq!(Digest::of_log(&format!("3 passed, 0 failed\n{}\n", x.line())), Some(x));
        assert_eq!(Digest::of_log("3 passed, 0 failed\n"), None);
    }
}
