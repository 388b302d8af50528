//! What a vector set tests: the top pipeline, or one unit of `units::UNITS`. Each target has
//! a layout (its ports as columns, from the same table the RTL is generated from) and a way
//! to fill a record from a stimulus evaluated by the model.

use super::layout::{Column, Layout, Record, Role};
use crate::config::PipelineConfig;
use crate::model::{BumpState, BumpTexel, FragmentIn, Shaded};
use crate::units::{Dir, Memories, UNITS};

/// A top-level stimulus: one fragment with its triangle's bump state, and whether it is the
/// first fragment of its triangle (a per-triangle top loads the state through its setup port
/// before this fragment; the model, which reads the state from every record, ignores it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TopStim {
    pub frag: FragmentIn,
    pub state: BumpState,
    pub tri_start: bool,
}

/// The vector column that marks a triangle's first fragment (per-triangle tops only; not a
/// port: the testbench drives a setup beat from the record's `tri_*` columns first).
pub const TRI_START: &str = "tri_start";

/// A unit-level stimulus: the unit's input lanes, by port, in UNITS order.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitStim {
    pub unit: &'static str,
    pub inputs: Vec<Vec<i64>>,
}

/// Layout of the top's vectors, from the top's port list: its fragment ports, then (per-triangle
/// tops) `tri_start` and the triangle-setup ports, then its result. Every record is a whole
/// fragment with its triangle's state, so any record can be evaluated on its own.
pub fn top_layout(cfg: &PipelineConfig) -> Layout {
    use crate::rtlgen::top::{port_list, PortKind};
    let mut l = Layout::default();
    for kind in [PortKind::Fragment, PortKind::Triangle, PortKind::Result] {
        if kind == PortKind::Triangle && cfg.per_triangle() {
            l.push(TRI_START, Role::Stimulus, 1, 1, "u1.0".into());
        }
        for p in port_list(cfg).into_iter().filter(|p| p.kind == kind) {
            let role = if kind == PortKind::Result { Role::Expected } else { Role::Stimulus };
            l.push(&p.name, role, p.fmt.width, p.lanes, p.fmt.name());
        }
    }
    l
}

/// The frame column of a top with `frame_transform` (a per-fragment top: it enters with the
/// fragment's state).
pub const FRAME: &str = "in_frame";

/// The name of bump-state field `f` (`l`, `h`, `lc`, `k`) on the top's ports and in its vectors.
pub fn state_column(cfg: &PipelineConfig, f: &str) -> String {
    format!("{}_{f}", if cfg.per_triangle() { "tri" } else { "in" })
}

/// The top's columns by name, looked up once per layout.
struct TopColumns<'a> {
    bump: &'a Column,
    c_src: &'a Column,
    tex: &'a Column,
    de: &'a Column,
    se: &'a Column,
    start: Option<&'a Column>,
    /// The light slots' columns (none under EMBM, whose slots are its texels).
    lights: Option<[&'a Column; 4]>,
    /// EMBM's `in_st` and `in_m`.
    env: Option<[&'a Column; 2]>,
    /// `in_frame` (`frame_transform`).
    frame: Option<&'a Column>,
    out: &'a Column,
}

impl<'a> TopColumns<'a> {
    fn of(cfg: &PipelineConfig, l: &'a Layout) -> TopColumns<'a> {
        let st = |f: &str| l.column(&state_column(cfg, f));
        TopColumns {
            bump: l.column("in_bump"),
            c_src: l.column("in_c_src"),
            tex: l.column("in_tex"),
            de: l.column("in_diffuse_en"),
            se: l.column("in_specular_en"),
            start: l.columns.iter().find(|c| c.name == TRI_START),
            lights: (!cfg.embm()).then(|| [st("l"), st("h"), st("lc"), st("k")]),
            env: cfg.embm().then(|| [l.column("in_st"), l.column("in_m")]),
            frame: l.columns.iter().find(|c| c.name == FRAME),
            out: l.column("out_c"),
        }
    }
}

/// Layout of `target`'s vectors: the top's, or a unit's.
pub fn layout(cfg: &PipelineConfig, target: &str) -> Layout {
    if target == "top" {
        top_layout(cfg)
    } else {
        unit_layout(cfg, target)
    }
}

/// Layout of a unit's vectors: its ports from `UNITS`, inputs then outputs.
pub fn unit_layout(cfg: &PipelineConfig, unit: &str) -> Layout {
    let u = crate::units::unit(unit).unwrap_or_else(|| panic!("unknown unit {unit}"));
    let mut l = Layout::default();
    for dir in [Dir::In, Dir::Out] {
        for p in u.ports(cfg).into_iter().filter(|p| p.dir == dir) {
            let role = if dir == Dir::In { Role::Stimulus } else { Role::Expected };
            l.push(p.name, role, p.fmt.width, p.lanes, p.fmt.name());
            l.columns.last_mut().expect("just pushed").enters = p.enters;
        }
    }
    l
}

/// Fill a top record.
pub fn top_record(cfg: &PipelineConfig, l: &Layout, s: &TopStim, out: &Shaded) -> Record {
    TopEncoder::new(cfg, l).record(s, out)
}

/// Fills the top records of one layout with its columns looked up once: looking them up by
/// name, and dividing out each lane's width, for every record cost more than the model's
/// evaluation of it.
pub struct TopEncoder<'a> {
    cfg: &'a PipelineConfig,
    layout: &'a Layout,
    bump: Lanes<'a>,
    c_src: Lanes<'a>,
    tex: Lanes<'a>,
    de: Lanes<'a>,
    se: Lanes<'a>,
    start: Option<Lanes<'a>>,
    /// L, H, Lc and k (none under EMBM).
    lights: Option<[Lanes<'a>; 4]>,
    /// EMBM's st and M.
    env: Option<[Lanes<'a>; 2]>,
    frame: Option<Lanes<'a>>,
    out: Lanes<'a>,
    /// Where the fragment's stimulus columns start, when they follow one another in
    /// [`fill_fragment`](Self::fill_fragment)'s order within 120 bits (the default layout
    /// and most others): they are then packed in one word pair instead of lane by lane.
    packed_from: Option<u32>,
    /// Where the lights' columns start, when L, H, Lc and k follow one another (every layout
    /// gbump makes): [`fill_state`](Self::fill_state) then writes their lanes as one stream
    /// of bits.
    lights_from: Option<u32>,
}

/// A column's lanes: where lane 0 starts, their width and the values that fit them.
#[derive(Clone, Copy)]
struct Lanes<'a> {
    col: &'a Column,
    lsb: u32,
    width: u32,
    lo: i64,
    hi: i64,
}

impl<'a> Lanes<'a> {
    fn of(col: &'a Column) -> Lanes<'a> {
        let width = col.width / col.lanes;
        let (lo, hi) = if width >= 63 {
            (i64::MIN, i64::MAX)
        } else {
            (-(1i64 << (width - 1)), (1i64 << width) - 1)
        };
        Lanes {
            col,
            lsb: col.lsb,
            width,
            lo,
            hi,
        }
    }

    /// `Record::set_lane`, with the same refusal of a value that does not fit (one unsigned
    /// compare inline, the message out of line: this runs for every lane of every record).
    #[inline(always)]
    fn set(&self, r: &mut Record, i: u32, v: i64) {
        self.check(i, v);
        r.set(self.lsb + i * self.width, self.width, v as u64);
    }

    /// Lanes `i..i + 3` in one or two writes (a triangle's state is a run of such triples).
    #[inline(always)]
    fn set3(&self, r: &mut Record, i: u32, v: [i64; 3]) {
        let (lsb, width) = (self.lsb + i * self.width, 3 * self.width);
        if width > 128 {
            // Wider than one u128 (lanes above 42 bits): a lane at a time.
            return (0..3).for_each(|k| self.set(r, i + k as u32, v[k]));
        }
        let mask = if self.width >= 64 { u64::MAX } else { (1u64 << self.width) - 1 };
        if width <= 64 {
            // The usual case (lanes of 21 bits or fewer) in a u64: u128 shifts by a run-time
            // width cost a branch each.
            let mut all = 0u64;
            for k in (0..3).rev() {
                self.check(i + k as u32, v[k]);
                all = (all << self.width) | (v[k] as u64 & mask);
            }
            return r.set(lsb, width, all);
        }
        let mut all = 0u128;
        for k in (0..3).rev() {
            self.check(i + k as u32, v[k]);
            all = (all << self.width) | (v[k] as u64 & mask) as u128;
        }
        r.set(lsb, width.min(64), all as u64);
        if width > 64 {
            r.set(lsb + 64, width - 64, (all >> 64) as u64);
        }
    }

    #[inline(always)]
    fn check(&self, i: u32, v: i64) {
        if v.wrapping_sub(self.lo) as u64 > self.hi.wrapping_sub(self.lo) as u64 {
            self.misfit(i, v);
        }
    }

    #[cold]
    #[inline(never)]
    fn misfit(&self, i: u32, v: i64) -> ! {
        panic!("value {v} does not fit {}-bit lane {i} of column {}", self.width, self.col.name)
    }
}

impl<'a> TopEncoder<'a> {
    pub fn new(cfg: &'a PipelineConfig, layout: &'a Layout) -> TopEncoder<'a> {
        let c = TopColumns::of(cfg, layout);
        TopEncoder {
            cfg,
            layout,
            bump: Lanes::of(c.bump),
            c_src: Lanes::of(c.c_src),
            tex: Lanes::of(c.tex),
            de: Lanes::of(c.de),
            se: Lanes::of(c.se),
            start: c.start.map(Lanes::of),
            lights: c.lights.map(|l| l.map(Lanes::of)),
            env: c.env.map(|e| e.map(Lanes::of)),
            frame: c.frame.map(Lanes::of),
            out: Lanes::of(c.out),
            packed_from: packed_from(&c),
            lights_from: c.lights.and_then(|cols| {
                let follow = cols.windows(2).all(|w| w[0].lsb + w[0].width == w[1].lsb);
                let narrow = cols.iter().all(|c| c.lanes > 0 && (1..64).contains(&(c.width / c.lanes)));
                (follow && narrow).then_some(cols[0].lsb)
            }),
        }
    }

    /// The record of stimulus `s` with the model's result `out`.
    pub fn record(&self, s: &TopStim, out: &Shaded) -> Record {
        let mut r = Record::new(self.layout);
        self.fill(s, out, &mut r);
        r
    }

    /// [`record`](Self::record) into `r`, a record of this layout, which it clears first.
    pub fn fill(&self, s: &TopStim, out: &Shaded, r: &mut Record) {
        self.fill_colour(s, out.colour(), r)
    }

    /// [`fill`](Self::fill) from the result colour alone (what the fast model gives).
    pub fn fill_colour(&self, s: &TopStim, colour: [u32; 3], r: &mut Record) {
        r.words.fill(0);
        self.fill_state_lanes(&s.state, r);
        self.fill_fragment(&s.frag, s.tri_start, colour, r);
    }

    /// The bump-state columns, into `r` (whose state columns are zero): a triangle's
    /// records share them, so a run of its fragments starts from one record holding them.
    /// The lights' lanes go as one stream of bits where their columns follow one another;
    /// [`fill_state_lanes`](Self::fill_state_lanes), which sets them lane by lane, is what
    /// the tests hold it to.
    pub fn fill_state(&self, state: &BumpState, r: &mut Record) {
        let (Some(from), Some([l, h, lc, k])) = (self.lights_from, &self.lights) else {
            return self.fill_state_lanes(state, r);
        };
        let n = self.cfg.lights as usize;
        // `top_layout`'s columns: three lanes a light for L, H and Lc, one for k.
        debug_assert!([l, h, lc].iter().all(|c| c.col.lanes as usize == 3 * n) && k.col.lanes as usize == n);
        let mut bits = BitStream::at(&mut r.words, from);
        let mut put = |c: &Lanes, i: usize, v: i64| {
            c.check(i as u32, v);
            bits.push(v as u64 & (u64::MAX >> (64 - c.width)), c.width);
        };
        for (j, s) in state.lights.iter().take(n).enumerate() {
            (0..3).for_each(|ch| put(l, 3 * j + ch, s.l[ch]));
        }
        for (j, s) in state.lights.iter().take(n).enumerate() {
            (0..3).for_each(|ch| put(h, 3 * j + ch, s.h[ch]));
        }
        for (j, s) in state.lights.iter().take(n).enumerate() {
            (0..3).for_each(|ch| put(lc, 3 * j + ch, s.lc[ch] as i64));
        }
        for (j, s) in state.lights.iter().take(n).enumerate() {
            put(k, j, s.k);
        }
        bits.flush();
        self.fill_rest_of_state(state, r);
    }

    /// [`fill_state`](Self::fill_state) a lane at a time, for any layout.
    pub fn fill_state_lanes(&self, state: &BumpState, r: &mut Record) {
        if let Some([l, h, lc, k]) = &self.lights {
            for j in 0..self.cfg.lights as usize {
                let ls = &state.lights[j];
                let lane = 3 * j as u32;
                l.set3(r, lane, ls.l);
                h.set3(r, lane, ls.h);
                lc.set3(r, lane, ls.lc.map(i64::from));
                k.set(r, j as u32, ls.k);
            }
        }
        self.fill_rest_of_state(state, r);
    }

    /// The state's columns other than the lights': EMBM's and the frame.
    fn fill_rest_of_state(&self, state: &BumpState, r: &mut Record) {
        if let Some([st, m]) = &self.env {
            for (i, v) in state.env.st.iter().enumerate() {
                st.set(r, i as u32, *v);
            }
            for (i, v) in state.env.m.iter().enumerate() {
                m.set(r, i as u32, *v);
            }
        }
        if let Some(f) = &self.frame {
            for (i, v) in state.frame.iter().enumerate() {
                f.set3(r, 3 * i as u32, *v);
            }
        }
    }

    /// The 64-bit words of a record that [`fill_fragment`](Self::fill_fragment) writes: the
    /// rest of a record is its triangle's state.
    pub fn fragment_words(&self) -> Vec<usize> {
        let mut cols = vec![self.bump, self.c_src, self.tex, self.de, self.se, self.out];
        cols.extend(self.start);
        let mut words: Vec<usize> = cols
            .iter()
            // The whole column, every lane (a `Lanes`' own width is one lane's).
            .map(|c| c.col)
            .filter(|c| c.width > 0)
            .flat_map(|c| (c.lsb / 64) as usize..=((c.lsb + c.width - 1) / 64) as usize)
            .collect();
        words.sort_unstable();
        words.dedup();
        words
    }

    /// Every other column (the fragment, `tri_start`, the result), into `r` (where they are
    /// zero).
    #[inline]
    pub fn fill_fragment(&self, frag: &FragmentIn, tri_start: bool, colour: [u32; 3], r: &mut Record) {
        let Some(p) = self.packed() else {
            return self.fill_fragment_lanes(frag, tri_start, colour, r);
        };
        let (stim, out) = self.fragment_bits(frag, tri_start, colour);
        for (lsb, width, v) in [(p.stim_lsb, p.stim_width, stim), (p.out_lsb, p.out_width, out)] {
            r.set(lsb, width.min(64), v as u64);
            if width > 64 {
                r.set(lsb + 64, width - 64, (v >> 64) as u64);
            }
        }
    }

    /// Where the fragment's columns lie when they are packed (see [`PackedFragment`]).
    pub fn packed(&self) -> Option<PackedFragment> {
        let lsb = self.packed_from?;
        Some(PackedFragment {
            stim_lsb: lsb,
            stim_width: self.bump.col.width + self.c_src.col.width + self.tex.col.width + 2 + self.start.is_some() as u32,
            out_lsb: self.out.lsb,
            out_width: self.out.col.width,
        })
    }

    /// A packed layout's fragment columns as two values: the stimulus (bump, c_src, tex and
    /// the flags, from its first column up) and the result, each refused if it does not fit
    /// its lanes.
    #[inline(always)]
    pub fn fragment_bits(&self, frag: &FragmentIn, tri_start: bool, colour: [u32; 3]) -> (u128, u128) {
        // A column's three lanes as one value (each lane is at most 21 bits wide here, so
        // the three fit a u64: u128 shifts by a run-time width cost a branch each).
        let three = |l: &Lanes, v: [u32; 3]| {
            for (i, &x) in v.iter().enumerate() {
                l.check(i as u32, x as i64);
            }
            ((v[2] as u64) << l.width | v[1] as u64) << l.width | v[0] as u64
        };
        let bump = match frag.bump {
            BumpTexel::Rgb(codes) => three(&self.bump, codes),
            BumpTexel::Index(ix) => {
                self.bump.check(0, ix as i64);
                ix as u64
            }
        };
        // `tri_start` has a column only where the layout holds one.
        let flags = frag.diffuse_en as u64 | (frag.specular_en as u64) << 1 | ((tri_start & self.start.is_some()) as u64) << 2;
        let (wb, wc, wt) = (self.bump.col.width, self.c_src.col.width, self.tex.col.width);
        let (c_src, tex) = (three(&self.c_src, frag.c_src), three(&self.tex, frag.tex));
        let stim = if wb + wc <= 64 && wt + 3 <= 64 {
            // Two u64 halves and one u128 shift (the usual widths): each u128 shift by a
            // run-time amount is a handful of instructions.
            (bump | c_src << wb) as u128 | ((tex | flags << wt) as u128) << (wb + wc)
        } else {
            bump as u128 | (c_src as u128) << wb | (tex as u128) << (wb + wc) | (flags as u128) << (wb + wc + wt)
        };
        (stim, three(&self.out, colour) as u128)
    }

    /// [`fill_fragment`](Self::fill_fragment) a lane at a time, for any layout.
    fn fill_fragment_lanes(&self, frag: &FragmentIn, tri_start: bool, colour: [u32; 3], r: &mut Record) {
        if let Some(c) = &self.start {
            c.set(r, 0, tri_start as i64);
        }
        match frag.bump {
            BumpTexel::Rgb(codes) => {
                for (i, &x) in codes.iter().enumerate() {
                    self.bump.set(r, i as u32, x as i64);
                }
            }
            BumpTexel::Index(ix) => self.bump.set(r, 0, ix as i64),
        }
        for i in 0..3 {
            self.c_src.set(r, i as u32, frag.c_src[i] as i64);
            self.tex.set(r, i as u32, frag.tex[i] as i64);
            self.out.set(r, i as u32, colour[i] as i64);
        }
        self.de.set(r, 0, frag.diffuse_en as i64);
        self.se.set(r, 0, frag.specular_en as i64);
    }
}

/// Where the fragment's stimulus columns start when they lie one after another in
/// `fill_fragment`'s order, each three-lane column and the result within one 64-bit value,
/// the stimulus columns within 120 bits.
fn packed_from(c: &TopColumns) -> Option<u32> {
    let mut cols = vec![c.bump, c.c_src, c.tex, c.de, c.se];
    cols.extend(c.start);
    let from = cols[0].lsb;
    let mut at = from;
    for (i, col) in cols.iter().enumerate() {
        // The bump column is three codes or one palette index; the flags one bit each.
        let lanes_ok = match i {
            0 => col.lanes == 3 || col.lanes == 1,
            1 | 2 => col.lanes == 3,
            _ => col.lanes == 1 && col.width == 1,
        };
        if col.lsb != at || !lanes_ok || col.width > 63 {
            return None;
        }
        at += col.width;
    }
    // Each value, shifted to its byte, in one u128.
    (c.out.lanes == 3 && c.out.width <= 63 && at - from <= 120).then_some(from)
}

/// Values of up to 63 bits written one after another into a record's words from a bit on
/// (the words there zero), a word at a time.
struct BitStream<'w> {
    words: &'w mut [u64],
    /// The word being filled, and how many of its bits are.
    at: usize,
    fill: u32,
    acc: u64,
}

impl<'w> BitStream<'w> {
    fn at(words: &'w mut [u64], lsb: u32) -> BitStream<'w> {
        BitStream {
            at: (lsb / 64) as usize,
            fill: lsb % 64,
            acc: 0,
            words,
        }
    }

    /// Append `v` (`width` < 64 bits, the rest of `v` zero).
    #[inline(always)]
    fn push(&mut self, v: u64, width: u32) {
        debug_assert!((1..64).contains(&width) && v >> width == 0, "{width}-bit value {v}");
        let f = self.fill;
        self.acc |= v << f;
        if f + width >= 64 {
            self.words[self.at] |= self.acc;
            self.at += 1;
            // The bits of `v` that did not fit (`f` is at least 1 here, as `width` < 64).
            self.acc = v >> (64 - f);
            self.fill = f + width - 64;
        } else {
            self.fill = f + width;
        }
    }

    fn flush(self) {
        if self.fill > 0 {
            self.words[self.at] |= self.acc;
        }
    }
}

/// Where a packed layout's fragment columns lie: the stimulus columns one after another from
/// `stim_lsb`, the result at `out_lsb`; each at most 120 bits, so a value shifted to its byte
/// offset fits a u128.
#[derive(Clone, Copy, Debug)]
pub struct PackedFragment {
    pub stim_lsb: u32,
    pub stim_width: u32,
    pub out_lsb: u32,
    pub out_width: u32,
}

impl PackedFragment {
    /// OR the fragment's two values (as [`TopEncoder::fragment_bits`] gives them) into
    /// `record`, one record's little-endian bytes whose fragment columns are zero.
    #[inline(always)]
    pub fn or_into(&self, record: &mut [u8], stim: u128, out: u128) {
        or_bits(record, self.stim_lsb, self.stim_width, stim);
        or_bits(record, self.out_lsb, self.out_width, out);
    }

    /// The two values' 16-byte windows in `record` (a run's record, its fragment columns
    /// zero), each holding its value whole; None when the record is shorter than a window.
    pub fn windows(&self, record: &[u8]) -> Option<Windows> {
        let bytes = record.len();
        if bytes < 16 {
            return None;
        }
        // From the value's first byte, or the record's last 16 where that runs past its end.
        let place = |lsb: u32, width: u32| {
            let at = ((lsb / 8) as usize).min(bytes - 16);
            let shift = lsb - 8 * at as u32;
            (shift + width <= 128).then_some((at, shift))
        };
        let ((stim_at, stim_shift), (out_at, out_shift)) = (place(self.stim_lsb, self.stim_width)?, place(self.out_lsb, self.out_width)?);
        let load = |at: usize| u128::from_le_bytes(record[at..at + 16].try_into().expect("16 bytes"));
        Some(Windows {
            stim_at,
            stim_shift,
            out_at,
            out_shift,
            stim_state: load(stim_at),
            out_state: load(out_at),
        })
    }
}

/// Where a packed fragment's two values are stored in a record copied from its run's state:
/// each as one 16-byte window of the state's bytes with the value ORed in, so a record is a
/// copy and two stores. ORing into the copied bytes instead read them back right after the
/// copy's wide stores, a store-forwarding stall on every record.
#[derive(Clone, Copy, Debug)]
pub struct Windows {
    stim_at: usize,
    stim_shift: u32,
    out_at: usize,
    out_shift: u32,
    /// The state's bytes in each window.
    stim_state: u128,
    out_state: u128,
}

impl Windows {
    /// Store the fragment's two values (as [`TopEncoder::fragment_bits`] gives them) into
    /// `record`, a copy of the run's state bytes.
    #[inline(always)]
    pub fn put(&self, record: &mut [u8], stim: u128, out: u128) {
        let (s, o) = (stim << self.stim_shift, out << self.out_shift);
        // Windows may overlap: each carries the other's value where it does, so the order of
        // the two stores does not matter.
        let d = self.out_at as isize - self.stim_at as isize;
        let w_stim = self.stim_state | s | moved(o, d);
        let w_out = self.out_state | o | moved(s, -d);
        record[self.stim_at..self.stim_at + 16].copy_from_slice(&w_stim.to_le_bytes());
        record[self.out_at..self.out_at + 16].copy_from_slice(&w_out.to_le_bytes());
    }
}

/// `v`'s bytes moved `by` bytes up (down where negative), those leaving 16 bytes dropped.
#[inline(always)]
fn moved(v: u128, by: isize) -> u128 {
    match by {
        16.. | ..=-16 => 0,
        0.. => v << (8 * by),
        _ => v >> (8 * -by),
    }
}

#[inline(always)]
fn or_bits(record: &mut [u8], lsb: u32, width: u32, v: u128) {
    let (at, shift) = ((lsb / 8) as usize, lsb % 8);
    let n = (shift + width).div_ceil(8) as usize;
    let b = (v << shift).to_le_bytes();
    for (d, s) in record[at..at + n].iter_mut().zip(&b[..n]) {
        *d |= *s;
    }
}

/// Read a top record's stimulus back (the inverse of [`top_record`]; the expected columns are
/// ignored), so a record from any source can be evaluated by the model.
pub fn top_stim(cfg: &PipelineConfig, l: &Layout, r: &Record) -> TopStim {
    let TopColumns {
        bump: c_bump,
        c_src,
        tex: c_tex,
        de: c_de,
        se: c_se,
        start,
        lights,
        env,
        frame: c_frame,
        ..
    } = TopColumns::of(cfg, l);
    let lane3 = |c, base: u32| [0, 1, 2].map(|i| r.lane_value(c, base + i));
    let code3 = |c| lane3(c, 0).map(|v| v as u32);
    let mut state = BumpState::default();
    if let Some([c_l, c_h, c_lc, c_k]) = lights {
        for (j, s) in state.lights.iter_mut().enumerate().take(cfg.lights as usize) {
            let b = 3 * j as u32;
            s.l = lane3(c_l, b);
            s.h = lane3(c_h, b);
            s.lc = lane3(c_lc, b).map(|v| v as u32);
            s.k = r.lane_value(c_k, j as u32);
        }
    }
    if let Some([c_st, c_m]) = env {
        state.env.st = [0, 1].map(|i| r.lane_value(c_st, i));
        state.env.m = [0, 1, 2, 3].map(|i| r.lane_value(c_m, i));
    }
    if let Some(c) = c_frame {
        state.frame = std::array::from_fn(|i| lane3(c, 3 * i as u32));
    }
    TopStim {
        frag: FragmentIn {
            bump: if cfg.palette {
                BumpTexel::Index(r.lane_value(c_bump, 0) as u8)
            } else {
                BumpTexel::Rgb(code3(c_bump))
            },
            c_src: code3(c_src),
            tex: code3(c_tex),
            diffuse_en: r.lane_value(c_de, 0) != 0,
            specular_en: r.lane_value(c_se, 0) != 0,
        },
        state,
        // A per-fragment top has no setup: every record stands alone.
        tri_start: start.is_none_or(|c| r.lane_value(c, 0) != 0),
    }
}

/// Read a unit record's stimulus back (the inverse of [`unit_record`]'s input columns).
pub fn unit_stim(l: &Layout, unit: &'static str, r: &Record) -> UnitStim {
    let inputs = l
        .columns
        .iter()
        .filter(|c| c.role == Role::Stimulus)
        .map(|c| (0..c.lanes).map(|i| r.lane_value(c, i)).collect())
        .collect();
    UnitStim { unit, inputs }
}

/// Evaluate a unit on its inputs with the unit's own model.
pub fn eval_unit(cfg: &PipelineConfig, mem: &Memories, s: &UnitStim) -> Vec<Vec<i64>> {
    crate::units::unit(s.unit)
        .unwrap_or_else(|| panic!("no unit {}", s.unit))
        .eval(cfg, mem, &s.inputs)
}

/// Fill a unit record from its stimulus and outputs.
/// The record of `s` as the unit gives it back, for a caller's record: refused where the
/// stimulus is outside the unit's domain or the result outside its ports (a record of one's
/// own, or an edited set), which `unit_record` would not hold. The C library and regress's
/// check of a set's expected values both evaluate through it.
pub fn checked_unit_record(cfg: &PipelineConfig, mem: &Memories, l: &Layout, s: &UnitStim) -> crate::error::Result<Record> {
    let u = crate::units::unit(s.unit).unwrap_or_else(|| panic!("no unit {}", s.unit));
    crate::units::check_domain(u, cfg, &s.inputs)?;
    let outs = eval_unit(cfg, mem, s);
    crate::units::check_outputs(u, cfg, &outs)?;
    Ok(unit_record(l, s, &outs))
}

pub fn unit_record(l: &Layout, s: &UnitStim, outs: &[Vec<i64>]) -> Record {
    let mut r = Record::new(l);
    let (ins, exps): (Vec<_>, Vec<_>) = l.columns.iter().partition(|c| c.role == Role::Stimulus);
    for (c, vals) in ins.iter().zip(&s.inputs).chain(exps.iter().zip(outs)) {
        for (i, v) in vals.iter().enumerate() {
            r.set_lane(c, i as u32, *v);
        }
    }
    r
}

/// The unit stimuli a top stimulus exercises, from the model's trace of it: every instance
/// of every unit the top of `cfg` holds, with the inputs it sees.
pub fn unit_stims(cfg: &PipelineConfig, s: &TopStim, t: &Shaded) -> Vec<UnitStim> {
    let n = cfg.lights as usize;
    let mut v = Vec::new();
    match s.frag.bump {
        BumpTexel::Rgb(codes) => v.push(UnitStim {
            unit: "bump_fetch",
            inputs: vec![codes.iter().map(|&x| x as i64).collect()],
        }),
        BumpTexel::Index(i) => v.push(UnitStim {
            unit: "palette_fetch",
            inputs: vec![vec![i as i64]],
        }),
    }
    if cfg.frame_build {
        v.push(UnitStim {
            unit: "frame_build",
            inputs: vec![s.state.frame[0].to_vec(), s.state.frame[2].to_vec()],
        });
    }
    if cfg.frame_quaternion {
        v.push(UnitStim {
            unit: "quat_frame",
            inputs: {
                let (q, n_i) = crate::model::quat_frame::lanes(&s.state.frame);
                vec![q.to_vec(), n_i.to_vec()]
            },
        });
    }
    if cfg.frame_transform {
        v.push(UnitStim {
            unit: "frame_transform",
            inputs: vec![t.fetched.to_vec(), t.frame.concat()],
        });
    }
    if cfg.renormalise_bump {
        v.push(UnitStim {
            unit: "normalise_b",
            inputs: vec![t.framed.to_vec()],
        });
    }
    // Each blend's k and light colours (white: every code at 1.0, and no lc input); under
    // EMBM k is one and the colours are each map's four texels.
    let (k, lc_d, lc_s) = if cfg.embm() {
        let texels = |map: usize| t.texels[map].iter().flat_map(|c| c.map(i64::from)).collect::<Vec<i64>>();
        v.extend(embm_fetch_stims(cfg, s, t));
        (vec![1i64 << cfg.k_frac_bits; n], texels(0), texels(1))
    } else {
        let lc: Vec<i64> = (0..n)
            .flat_map(|j| cfg.light_colour(s.state.lights[j].lc).map(|x| x as i64))
            .collect();
        ((0..n).map(|j| s.state.lights[j].k).collect(), lc.clone(), lc)
    };
    let white = cfg.white_lights;
    for j in (0..n).filter(|_| !cfg.embm()) {
        let ls = &s.state.lights[j];
        // The normalise instances: H's, and L's when it is interpolated too.
        let (norm_l, norm_h) = crate::model::normalise::renormalised(cfg);
        for (on, v_in) in [(cfg.diffuse && norm_l, ls.l), (cfg.specular && norm_h, ls.h)] {
            if on {
                v.push(UnitStim {
                    unit: crate::model::normalise::lh_unit(cfg),
                    inputs: vec![v_in.to_vec()],
                });
            }
        }
        if cfg.diffuse {
            v.push(UnitStim {
                unit: "dot_clamp",
                inputs: vec![t.b.to_vec(), t.l[j].to_vec()],
            });
        }
        if cfg.specular {
            v.push(UnitStim {
                unit: "dot_clamp",
                inputs: vec![t.b.to_vec(), t.h[j].to_vec()],
            });
            v.push(UnitStim {
                unit: "power_unit",
                inputs: vec![vec![t.xh[j]]],
            });
        }
    }
    let serial = cfg.light_mode == crate::config::LightMode::Serial;
    // The serial form: one accumulate per slot, then the finish; the parallel form: one blend.
    let blend_in = |c_in: [u32; 3], f: &[i64], v: &mut Vec<UnitStim>, unit: &'static str| {
        let c = c_in.iter().map(|&y| y as i64).collect::<Vec<_>>();
        let lc = if unit == "specular_blend" { &lc_s } else { &lc_d };
        if !serial {
            let mut inputs = vec![c, f[..n].to_vec(), k.clone()];
            if !white {
                inputs.push(lc.clone());
            }
            v.push(UnitStim { unit, inputs });
            return;
        }
        let mut acc = vec![0i64; 3];
        for j in 0..n {
            let lcj = lc[3 * j..3 * j + 3].to_vec();
            let mut inputs = vec![acc.clone(), vec![(j == 0) as i64], vec![f[j]], vec![k[j]]];
            if !white {
                inputs.push(lcj.clone());
            }
            acc = crate::units::accumulate(cfg, &acc, j == 0, f[j], k[j], &lcj).to_vec();
            v.push(UnitStim {
                unit: "light_accumulate",
                inputs,
            });
        }
        v.push(UnitStim {
            unit: "blend_finish",
            inputs: vec![c, acc],
        });
    };
    let order = crate::rtlgen::top::stage_order(cfg);
    // Stage colours carry the guard bits from the first stage on.
    let mut c_in = s.frag.c_src.map(|c| c << cfg.colour_guard_bits);
    for (i, unit) in order.iter().enumerate() {
        match *unit {
            "diffuse_blend" if cfg.diffuse => blend_in(c_in, &t.dfac, &mut v, "diffuse_blend"),
            "specular_blend" if cfg.specular => blend_in(c_in, &t.sfac, &mut v, "specular_blend"),
            "texture_modulate" => v.push(UnitStim {
                unit: "texture_modulate",
                inputs: vec![
                    c_in.iter().map(|&y| y as i64).collect(),
                    s.frag.tex.iter().map(|&y| y as i64).collect(),
                ],
            }),
            _ => {}
        }
        c_in = t.stages[i];
    }
    if cfg.colour_guard_bits > 0 {
        v.push(UnitStim {
            unit: "colour_round",
            inputs: vec![c_in.iter().map(|&y| y as i64).collect()],
        });
    }
    v
}

/// An EMBM top's own units among [`unit_stims`]: `env_coords` on the fetched normal's x and
/// y, then each map's `env_fetch` at the block it chose.
fn embm_fetch_stims(cfg: &PipelineConfig, s: &TopStim, t: &Shaded) -> Vec<UnitStim> {
    let mut v = vec![UnitStim {
        unit: "env_coords",
        inputs: vec![t.b[..2].to_vec(), s.state.env.st.to_vec(), s.state.env.m.to_vec()],
    }];
    for (on, unit) in [(cfg.diffuse, "env_fetch_diffuse"), (cfg.specular, "env_fetch_specular")] {
        if on {
            v.push(UnitStim {
                unit,
                inputs: vec![vec![t.env.x0], vec![t.env.y0]],
            });
        }
    }
    v
}

/// Model evaluation of a top stimulus.
pub fn eval_top(cfg: &PipelineConfig, mem: &Memories, s: &TopStim) -> Shaded {
    mem.shade(cfg, &s.state, &s.frag)
}

/// Names of every target.
pub fn all_targets() -> Vec<&'static str> {
    std::iter::once("top").chain(UNITS.iter().map(|u| u.name())).collect()
}

/// The `--target` arguments as target names: `all` is every target `cfg` has; a named target
/// must exist in `cfg`'s hardware and be named once, so no set is silently empty or doubled.
pub fn resolve(cfg: &PipelineConfig, args: &[String]) -> crate::error::Result<Vec<String>> {
    use crate::error::Error;
    let all = all_targets();
    let here: Vec<&str> = all.iter().copied().filter(|u| super::writer::unit_present(cfg, u)).collect();
    let mut out: Vec<String> = Vec::new();
    for t in args {
        let named: Vec<&str> = if t == "all" {
            here.clone()
        } else if !all.contains(&t.as_str()) {
            // This configuration's targets, the nearest first if the name looks like a typo.
            let mut usual = format!("one of all, {} (this configuration's targets)", here.join(", "));
            if let Some(n) = crate::error::nearest(t, &here) {
                usual = format!("did you mean `{n}`? {usual}");
            }
            return Err(Error::Other(format!(
                "--target {t}: unknown\n  fix: {}",
                crate::renamed::unit_fix(t, usual)
            )));
        } else if !super::writer::unit_present(cfg, t) {
            let u = crate::units::unit(t).expect("unit");
            return Err(Error::Other(format!("--target {t}: {}", crate::units::absence(u, cfg))));
        } else {
            vec![t.as_str()]
        };
        for n in named {
            if out.iter().any(|o| o == n) {
                return Err(Error::Other(format!(
                    "--target {t}: names `{n}` a second time\n  fix: give each target once (`all` already includes every unit and top)"
                )));
            }
            out.push(n.to_string());
        }
    }
    if out.is_empty() {
        return Err(Error::Other(
            "--target: no target\n  fix: give --target all, top or a unit name".into(),
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lights' columns written as one stream of bits are the columns set lane by lane,
    /// over random configurations (the default's among those streamed).
    #[test]
    fn a_streamed_state_is_the_lane_by_lane_one() {
        let mut rng = crate::vectors::rng::SplitMix64(0x57A7E);
        let mut streamed = 0;
        for i in 0..200 {
            let cfg = crate::sim::fuzz::random_config(&mut rng);
            let layout = top_layout(&cfg);
            let enc = TopEncoder::new(&cfg, &layout);
            streamed += enc.lights_from.is_some() as usize;
            let mut draws = crate::vectors::rng::SplitMix64(i);
            for _ in 0..20 {
                let state = crate::vectors::sources::random_state(&cfg, &mut draws);
                let (mut a, mut b) = (Record::new(&layout), Record::new(&layout));
                enc.fill_state(&state, &mut a);
                enc.fill_state_lanes(&state, &mut b);
                assert_eq!(a.words, b.words, "config {}:\n{}", cfg.hash(), cfg.to_toml());
            }
        }
        assert!(streamed > 100, "only {streamed} of 200 configurations streamed");
        let cfg = PipelineConfig::default();
        let layout = top_layout(&cfg);
        assert!(
            TopEncoder::new(&cfg, &layout).lights_from.is_some(),
            "the default layout is not streamed"
        );
    }

    /// A fragment stored through its windows is the state with both values ORed in, wherever
    /// the two values lie: apart, in overlapping windows, in one window, at the record's end.
    #[test]
    fn windows_store_what_or_into_does() {
        let mut rng = crate::vectors::rng::SplitMix64(0x71D0);
        let mut tried = [0usize; 3];
        for _ in 0..20_000 {
            let bytes = rng.range(1, 40) as usize;
            let bits = 8 * bytes as i64;
            let stim_width = rng.range(1, 120.min(bits)) as u32;
            let out_width = rng.range(1, 63.min(bits)) as u32;
            let stim_lsb = rng.range(0, bits - stim_width as i64) as u32;
            let out_lsb = rng.range(0, bits - out_width as i64) as u32;
            // The two values may not share bits.
            if stim_lsb < out_lsb + out_width && out_lsb < stim_lsb + stim_width {
                continue;
            }
            let p = PackedFragment {
                stim_lsb,
                stim_width,
                out_lsb,
                out_width,
            };
            let mut state: Vec<u8> = (0..bytes).map(|_| rng.next_u64() as u8).collect();
            for (lsb, width) in [(stim_lsb, stim_width), (out_lsb, out_width)] {
                for b in lsb..lsb + width {
                    state[(b / 8) as usize] &= !(1 << (b % 8));
                }
            }
            let mask = |w: u32| if w >= 128 { u128::MAX } else { (1u128 << w) - 1 };
            let stim = (rng.next_u64() as u128) << 64 | rng.next_u64() as u128 & mask(stim_width);
            let (stim, out) = (stim & mask(stim_width), rng.next_u64() as u128 & mask(out_width));
            let mut want = state.clone();
            p.or_into(&mut want, stim, out);
            let Some(w) = p.windows(&state) else {
                tried[0] += 1;
                assert!(bytes < 16, "no windows for a {bytes}-byte record");
                continue;
            };
            let mut got = state.clone();
            w.put(&mut got, stim, out);
            assert_eq!(got, want, "{p:?} in {bytes} bytes");
            tried[1 + (w.stim_at.abs_diff(w.out_at) < 16) as usize] += 1;
        }
        assert!(tried.iter().all(|&n| n > 100), "cases: {tried:?}");
    }

    /// A top record built lane by lane from the layout's column names with
    /// `Record::set_lane`, sharing nothing with `TopEncoder`.
    fn by_name(cfg: &PipelineConfig, l: &Layout, s: &TopStim, colour: [u32; 3]) -> Record {
        let mut r = Record::new(l);
        let mut put = |name: &str, vals: &[i64]| {
            let c = l.column(name);
            for (i, v) in vals.iter().enumerate() {
                r.set_lane(c, i as u32, *v);
            }
        };
        match s.frag.bump {
            BumpTexel::Rgb(c) => put("in_bump", &c.map(i64::from)),
            BumpTexel::Index(i) => put("in_bump", &[i64::from(i)]),
        }
        put("in_c_src", &s.frag.c_src.map(i64::from));
        put("in_tex", &s.frag.tex.map(i64::from));
        put("in_diffuse_en", &[s.frag.diffuse_en as i64]);
        put("in_specular_en", &[s.frag.specular_en as i64]);
        if cfg.per_triangle() {
            put(TRI_START, &[s.tri_start as i64]);
        }
        let n = cfg.lights as usize;
        let st = &s.state.lights[..n];
        if cfg.embm() {
            put("in_st", &s.state.env.st);
            put("in_m", &s.state.env.m);
        } else {
            put(&state_column(cfg, "l"), &st.iter().flat_map(|x| x.l).collect::<Vec<_>>());
            put(&state_column(cfg, "h"), &st.iter().flat_map(|x| x.h).collect::<Vec<_>>());
            put(
                &state_column(cfg, "lc"),
                &st.iter().flat_map(|x| x.lc.map(i64::from)).collect::<Vec<_>>(),
            );
            put(&state_column(cfg, "k"), &st.iter().map(|x| x.k).collect::<Vec<_>>());
        }
        if cfg.frame_transform {
            put(FRAME, &s.state.frame.concat());
        }
        put("out_c", &colour.map(i64::from));
        r
    }

    /// The packed fragment columns and the lane-by-lane ones give the records a by-name
    /// reference gives, over the fuzzer's random and corner configurations.
    #[test]
    fn every_layout_packs_as_the_by_name_reference() {
        let mut rng = crate::vectors::rng::SplitMix64(0xC01_5EED);
        let mut cfgs: Vec<PipelineConfig> = crate::sim::fuzz::corner_configs().into_iter().map(|c| c.1).collect();
        cfgs.extend(crate::sim::fuzz::normalise_configs());
        cfgs.extend((0..150).map(|_| crate::sim::fuzz::random_config(&mut rng)));
        let mut packed = 0;
        for (k, cfg) in cfgs.iter().enumerate() {
            let l = top_layout(cfg);
            let enc = TopEncoder::new(cfg, &l);
            packed += enc.packed_from.is_some() as usize;
            for s in crate::vectors::sources::random_chunk(cfg, k as u64, 0, 200) {
                let colour = [0, 1, 2].map(|i| (s.frag.c_src[i] ^ s.frag.tex[(i + 1) % 3]) & cfg.colour_max());
                let want = by_name(cfg, &l, &s, colour);
                let mut got = Record::new(&l);
                enc.fill_state(&s.state, &mut got);
                enc.fill_fragment(&s.frag, s.tri_start, colour, &mut got);
                assert_eq!(got.words, want.words, "packed, config {}:\n{}", cfg.hash(), cfg.to_toml());
                let mut lanes = Record::new(&l);
                enc.fill_state(&s.state, &mut lanes);
                enc.fill_fragment_lanes(&s.frag, s.tri_start, colour, &mut lanes);
                assert_eq!(lanes.words, want.words, "lane by lane, config {}", cfg.hash());
                // The words `fragment_words` names are the only ones a fragment changes.
                let mut state_only = Record::new(&l);
                enc.fill_state(&s.state, &mut state_only);
                for (w, (a, b)) in want.words.iter().zip(&state_only.words).enumerate() {
                    assert!(
                        a == b || enc.fragment_words().contains(&w),
                        "word {w} changed, config {}",
                        cfg.hash()
                    );
                }
            }
        }
        assert!(packed > cfgs.len() / 2, "{packed} of {} layouts packed", cfgs.len());
    }
}
