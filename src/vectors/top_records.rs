//! Top records in bulk: the fast model's colours (`model::fast`), checked against the readable
//! per-unit model, encoded as `gbump vectors` writes them. `gbump vectors`, `gbump regress
//! --stream`, the bench and the C ABI make their top records here, so every set they produce
//! passes the same check.
//!
//! The check: every record of the first [`FULL_CHECK_RECORDS`] of a set (the whole of a set
//! up to that size), then the first [`CHECK_SAMPLE`] of every later `RANDOM_CHUNK`, so a
//! long stream pays for a 1.6 % sample rather than the readable model's whole cost.

use super::layout::{Layout, Record};
use super::sources::{chunk_rng, RandomTriangles, RANDOM_CHUNK};
use super::targets::{top_layout, TopEncoder, TopStim};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::model::{BumpState, FastModel, FragmentIn};
use crate::units::Memories;
use std::borrow::Cow;

/// Records of a set checked one by one against the readable model from its start.
pub const FULL_CHECK_RECORDS: u64 = 1 << 18;
/// Records checked at the start of every later chunk.
pub const CHECK_SAMPLE: u64 = 256;
/// Stimuli made, shaded and encoded together: small enough to stay in the cache.
pub const BATCH: usize = 256;

/// Whether record `i` of a set is checked against the readable model.
pub fn checked(i: u64) -> bool {
    i < FULL_CHECK_RECORDS || i % RANDOM_CHUNK < CHECK_SAMPLE
}

/// One configuration's top records, with its memories.
pub struct TopRecords<'a> {
    pub cfg: &'a PipelineConfig,
    pub mem: Memories<'a>,
    pub layout: Layout,
    pub fast: Cow<'a, FastModel>,
}

impl<'a> TopRecords<'a> {
    pub fn new(cfg: &'a PipelineConfig, mem: Memories<'a>) -> TopRecords<'a> {
        let fast = Cow::Owned(FastModel::of(cfg, &mem));
        TopRecords::with(cfg, mem, fast)
    }

    /// With a fast model already built (of `cfg` and `mem`: a handle keeps one).
    pub fn with(cfg: &'a PipelineConfig, mem: Memories<'a>, fast: Cow<'a, FastModel>) -> TopRecords<'a> {
        TopRecords {
            cfg,
            layout: top_layout(cfg),
            fast,
            mem,
        }
    }

    /// The colours of `stims`, records `first..` of their set, into `out`; the records
    /// [`checked`] names are compared with the readable model.
    pub fn colours(&self, first: u64, stims: &[TopStim], out: &mut [[u32; 3]]) -> Result<()> {
        self.fast.colours(stims, |s| (&s.state, &s.frag), out);
        for (k, (s, got)) in stims.iter().zip(out.iter()).enumerate() {
            self.check(first + k as u64, &s.state, &s.frag, *got)?;
        }
        Ok(())
    }

    /// Record `i`'s colour `got` against the readable model, when [`checked`] names it.
    #[inline]
    fn check(&self, i: u64, state: &BumpState, frag: &FragmentIn, got: [u32; 3]) -> Result<()> {
        if checked(i) {
            let want = self.mem.shade(self.cfg, state, frag).colour();
            if want != got {
                return Err(mismatch(self.cfg, i, frag, want, got));
            }
        }
        Ok(())
    }

    /// Append the records of `stims` (records `first..` of their set) to `bin` (binary, when
    /// given) and `hex` (text lines, when given), a run of equal states at a time.
    pub fn encode(&self, first: u64, stims: &[TopStim], mut bin: Option<&mut Vec<u8>>, mut hex: Option<&mut String>) -> Result<()> {
        let mut enc = RunEncoder::new(self);
        let mut frags = Vec::with_capacity(BATCH);
        let mut i = 0;
        while i < stims.len() {
            let s = &stims[i];
            let mut j = i + 1;
            while j < stims.len() && j - i < BATCH && !stims[j].tri_start && stims[j].state == s.state {
                j += 1;
            }
            frags.clear();
            frags.extend(stims[i..j].iter().map(|x| x.frag));
            let run = Run {
                first: first + i as u64,
                state: &s.state,
                tri_start: s.tri_start,
                frags: &frags,
            };
            enc.encode_run(&run, bin.as_deref_mut(), hex.as_deref_mut())?;
            i = j;
        }
        Ok(())
    }

    /// Chunk `c` of `random:count` with `seed`, drawn a triangle's run at a time as it is
    /// encoded (`sources::random_chunk`'s stimuli, without holding them); returns the
    /// records' count and, when `keep`, their stimuli.
    pub fn random_chunk(
        &self,
        seed: u64,
        c: u64,
        count: u64,
        bin: Option<&mut Vec<u8>>,
        hex: Option<&mut String>,
        keep: bool,
    ) -> Result<(u64, Vec<TopStim>)> {
        let m = self;
        crate::simd::at_level!(crate::simd::level(), [] [] fn(
            m: &TopRecords<'_>,
            seed: u64,
            c: u64,
            count: u64,
            bin: Option<&mut Vec<u8>>,
            hex: Option<&mut String>,
            keep: bool,
        ) -> Result<(u64, Vec<TopStim>)> {
            m.random_chunk_at(seed, c, count, bin, hex, keep)
        })
    }

    /// [`random_chunk`](Self::random_chunk)'s loop, compiled into each level's copy.
    #[inline(always)]
    fn random_chunk_at(
        &self,
        seed: u64,
        c: u64,
        count: u64,
        mut bin: Option<&mut Vec<u8>>,
        mut hex: Option<&mut String>,
        keep: bool,
    ) -> Result<(u64, Vec<TopStim>)> {
        let len = RANDOM_CHUNK.min(count - c * RANDOM_CHUNK);
        let mut tris = RandomTriangles::new(self.cfg, chunk_rng(seed, c));
        let mut enc = RunEncoder::new(self);
        let mut kept = Vec::new();
        let mut frags = Vec::with_capacity(BATCH);
        let mut done = 0;
        while done < len {
            let (state, tri_start) = tris.next_run(self.cfg, BATCH.min((len - done) as usize), &mut frags);
            let run = Run {
                first: c * RANDOM_CHUNK + done,
                state,
                tri_start,
                frags: &frags,
            };
            enc.encode_run(&run, bin.as_deref_mut(), hex.as_deref_mut())?;
            if keep {
                kept.extend(frags.iter().enumerate().map(|(k, f)| TopStim {
                    frag: *f,
                    state: *state,
                    tri_start: tri_start && k == 0,
                }));
            }
            done += frags.len() as u64;
        }
        Ok((len, kept))
    }
}

/// Encodes runs of one [`TopRecords`], its columns looked up and its buffers made once.
pub struct RunEncoder<'m, 'a> {
    maker: &'m TopRecords<'a>,
    enc: TopEncoder<'m>,
    colours: Vec<[u32; 3]>,
    /// The run's state columns, the rest zero.
    state: Record,
    /// The record being made: the run's state, and in the words `frag_words` names the
    /// current fragment's columns too.
    r: Record,
    frag_words: Vec<usize>,
    /// One binary record as whole words, its state already in place: a fragment rewrites
    /// only its own words, and the record goes to the output in one copy.
    bytes: Vec<u8>,
}

impl<'m, 'a> RunEncoder<'m, 'a> {
    pub fn new(maker: &'m TopRecords<'a>) -> RunEncoder<'m, 'a> {
        let enc = TopEncoder::new(maker.cfg, &maker.layout);
        let r = Record::new(&maker.layout);
        RunEncoder {
            frag_words: enc.fragment_words(),
            enc,
            colours: vec![[0; 3]; BATCH],
            state: r.clone(),
            // Whole 16-byte pieces, so a record is copied in fixed-size moves (`push_padded`).
            bytes: vec![0; (8 * r.words.len()).next_multiple_of(16)],
            r,
            maker,
        }
    }

    /// Append the records of one run of a triangle's fragments: its state's columns are
    /// packed once, the fast model's per-triangle products formed once.
    #[inline(always)]
    pub fn encode_run(&mut self, run: &Run, mut bin: Option<&mut Vec<u8>>, mut hex: Option<&mut String>) -> Result<()> {
        let m = self.maker;
        self.state.words.fill(0);
        self.enc.fill_state(run.state, &mut self.state);
        // `r` and `bytes` hold the run's state; a fragment rewrites only its own words.
        self.r.words.copy_from_slice(&self.state.words);
        for (dst, w) in self.bytes.chunks_exact_mut(8).zip(&self.state.words) {
            dst.copy_from_slice(&w.to_le_bytes());
        }
        let (bytes, digits) = (m.layout.bytes(), m.layout.hex_digits());
        if let Some(bin) = bin.as_deref_mut() {
            // Room for the run's records and for the last one's whole 16-byte pieces
            // (`push_padded`), so the buffer is not grown for the padding.
            bin.reserve(bytes * run.frags.len() + 16);
        }
        // A packed layout's binary record is the state's bytes with the fragment's two
        // values ORed in: no record of words in between.
        let packed = self.enc.packed();
        let windows = packed.and_then(|p| p.windows(&self.bytes[..bytes]));
        for (b, frags) in run.frags.chunks(BATCH).enumerate() {
            let out = &mut self.colours[..frags.len()];
            m.fast.colours_run(run.state, frags, out);
            for (k, (f, c)) in frags.iter().zip(out.iter()).enumerate() {
                let i = b * BATCH + k;
                m.check(run.first + i as u64, run.state, f, *c)?;
                let tri_start = run.tri_start && i == 0;
                if let (Some(bin), Some(p)) = (bin.as_deref_mut(), packed) {
                    let (stim, colour) = self.enc.fragment_bits(f, tri_start, *c);
                    let at = bin.len();
                    push_padded(bin, &self.bytes, bytes);
                    match &windows {
                        Some(w) => w.put(&mut bin[at..], stim, colour),
                        None => p.or_into(&mut bin[at..], stim, colour),
                    }
                    if hex.is_none() {
                        continue;
                    }
                }
                for &w in &self.frag_words {
                    self.r.words[w] = self.state.words[w];
                }
                self.enc.fill_fragment(f, tri_start, *c, &mut self.r);
                if let (Some(bin), None) = (bin.as_deref_mut(), packed) {
                    for &w in &self.frag_words {
                        self.bytes[8 * w..8 * w + 8].copy_from_slice(&self.r.words[w].to_le_bytes());
                    }
                    bin.extend_from_slice(&self.bytes[..bytes]);
                }
                if let Some(hex) = hex.as_deref_mut() {
                    hex.push_str(&self.r.hex(digits));
                    hex.push('\n');
                }
            }
        }
        Ok(())
    }
}

/// Append the first `bytes` of `record` (a whole number of 16-byte pieces long) to `bin`,
/// copied a piece at a time into its spare room: `extend_from_slice` of a length known only
/// at run time was a call to `memmove` per record.
#[inline(always)]
fn push_padded(bin: &mut Vec<u8>, record: &[u8], bytes: usize) {
    let at = bin.len();
    let padded = bytes.next_multiple_of(16);
    bin.reserve(padded);
    assert!(record.len() >= padded, "a record of whole pieces");
    // SAFETY: `reserve` made room for `padded` bytes after `at`, and `record` holds as many;
    // the `padded` bytes are written before the length takes in `bytes` of them.
    unsafe {
        let (src, dst) = (record.as_ptr() as *const [u8; 16], bin.as_mut_ptr().add(at) as *mut [u8; 16]);
        for k in 0..padded / 16 {
            dst.add(k).write_unaligned(src.add(k).read_unaligned());
        }
        bin.set_len(at + bytes);
    }
}

/// Consecutive records of one triangle: record `first` of the set on, one state.
pub struct Run<'a> {
    pub first: u64,
    pub state: &'a BumpState,
    /// Whether the first record starts its triangle.
    pub tri_start: bool,
    pub frags: &'a [FragmentIn],
}

fn mismatch(cfg: &PipelineConfig, i: u64, frag: &FragmentIn, want: [u32; 3], got: [u32; 3]) -> Error {
    Error::Other(format!(
        "record {i}: the fast model gives colour {got:?}, the readable model {want:?} (config {}, fragment {:?})\n  fix: this is a gbump bug in src/model/fast.rs; report it with this configuration",
        cfg.hash(),
        frag
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::MemoryContents;

    /// A deliberately wrong fast model (each mutant a constant the real one must get right)
    /// is caught by the check on ordinary random records.
    #[test]
    fn a_wrong_fast_model_is_caught() {
        let cfg = PipelineConfig::default();
        let contents = MemoryContents::new(&cfg, cfg.shininess);
        let mut stims = crate::vectors::sources::random_chunk(&cfg, 1, 0, 4096);
        // The corners hold the flat normals the bypass mutant needs.
        stims.extend(crate::vectors::sources::corners(&cfg, 2).into_iter().map(|c| c.1));
        let right = TopRecords::new(&cfg, contents.view());
        let mut out = vec![[0; 3]; stims.len()];
        right.colours(0, &stims, &mut out).expect("the fast model agrees");
        let mutants = [
            PipelineConfig {
                rounding: crate::fixed::Rounding::Truncate,
                ..cfg.clone()
            },
            PipelineConfig {
                blend_order: crate::config::BlendOrder::TextureLast,
                ..cfg.clone()
            },
            PipelineConfig {
                skip_flat: true,
                ..cfg.clone()
            },
            PipelineConfig { lights: 3, ..cfg.clone() },
        ];
        for m in &mutants {
            let mut wrong = TopRecords::new(&cfg, contents.view());
            wrong.fast = Cow::Owned(FastModel::new(m, &contents.table, Some(&contents.palette)));
            let e = wrong.colours(0, &stims, &mut out).expect_err("a mutant passes the check");
            assert!(e.to_string().contains("fast model"), "{e}");
            let mut bin = Vec::new();
            assert!(
                wrong.encode(0, &stims, Some(&mut bin), None).is_err(),
                "a mutant passes the encoder's check"
            );
        }
        let other_table = crate::model::PowerTable::build(&cfg, cfg.shininess + 1);
        let mut wrong = TopRecords::new(&cfg, contents.view());
        wrong.fast = Cow::Owned(FastModel::new(&cfg, &other_table, Some(&contents.palette)));
        assert!(wrong.colours(0, &stims, &mut out).is_err(), "a wrong power table passes");
    }

    /// Records made here are the bytes the readable model's encoder gives, and a random chunk
    /// drawn a batch at a time is `random_chunk`'s.
    #[test]
    fn records_are_the_readable_encoders() {
        let cfg = PipelineConfig::default();
        let contents = MemoryContents::new(&cfg, cfg.shininess);
        let t = TopRecords::new(&cfg, contents.view());
        let n = RANDOM_CHUNK + 300;
        let (mut bin, mut hex) = (Vec::new(), String::new());
        let (len, kept) = t.random_chunk(9, 1, n, Some(&mut bin), Some(&mut hex), true).unwrap();
        let stims = crate::vectors::sources::random_chunk(&cfg, 9, 1, n);
        assert_eq!((len, &kept), (300, &stims));
        let (mut want_bin, mut want_hex) = (Vec::new(), String::new());
        for s in &stims {
            let r = super::super::targets::top_record(&cfg, &t.layout, s, &super::super::targets::eval_top(&cfg, &t.mem, s));
            r.to_bytes(t.layout.bytes(), &mut want_bin);
            want_hex += &(r.hex(t.layout.hex_digits()) + "\n");
        }
        assert_eq!(bin, want_bin);
        assert_eq!(hex, want_hex);
    }

    /// The same over random valid configurations (every width, lane count and layout the
    /// fuzzer draws), where the packed fragment columns and the per-word record updates must
    /// hold for layouts other than the default's.
    #[test]
    fn records_are_the_readable_encoders_for_every_configuration() {
        let mut rng = crate::vectors::rng::SplitMix64(0xE4C0_DE);
        for i in 0..120 {
            let cfg = crate::sim::fuzz::random_config(&mut rng);
            let contents = MemoryContents::new(&cfg, cfg.shininess);
            let t = TopRecords::new(&cfg, contents.view());
            let n = 700;
            let (mut bin, mut hex) = (Vec::new(), String::new());
            t.random_chunk(i, 0, n, Some(&mut bin), Some(&mut hex), false).unwrap();
            let stims = crate::vectors::sources::random_chunk(&cfg, i, 0, n);
            let (mut want_bin, mut want_hex) = (Vec::new(), String::new());
            for s in &stims {
                let r = super::super::targets::top_record(&cfg, &t.layout, s, &super::super::targets::eval_top(&cfg, &t.mem, s));
                r.to_bytes(t.layout.bytes(), &mut want_bin);
                want_hex += &(r.hex(t.layout.hex_digits()) + "\n");
            }
            assert!(bin == want_bin, "config {} binary records differ:\n{}", cfg.hash(), cfg.to_toml());
            assert!(hex == want_hex, "config {} text records differ:\n{}", cfg.hash(), cfg.to_toml());
        }
    }

    #[test]
    fn the_check_covers_small_sets_whole_and_samples_every_chunk() {
        assert!((0..FULL_CHECK_RECORDS).all(checked));
        let c = FULL_CHECK_RECORDS.div_ceil(RANDOM_CHUNK) * RANDOM_CHUNK + 5 * RANDOM_CHUNK;
        assert!(checked(c) && checked(c + CHECK_SAMPLE - 1) && !checked(c + CHECK_SAMPLE));
    }
}
