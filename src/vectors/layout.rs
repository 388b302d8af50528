//! The vector record layout: named columns packed LSB-first into one fixed-width record.
//! A record is one `$readmemh` line (hex, most significant digit first) or
//! `bytes()` little-endian bytes in the binary file; the manifest lists every column's
//! offset and width so any tool can slice it.

use serde::Serialize;

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    Stimulus,
    Expected,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Column {
    pub name: String,
    pub role: Role,
    pub lsb: u32,
    pub width: u32,
    /// Lanes of `width / lanes` bits each (lane 0 in the low bits).
    pub lanes: u32,
    pub format: String,
    /// Edges after its record's other inputs at which this input is sampled (a unit port's
    /// [`crate::units::Port::enters`]; 0 everywhere else).
    pub enters: u32,
}

impl Column {
    /// Whether lanes hold two's-complement values (format `sW.F`), to sign-extend on reading.
    pub fn signed(&self) -> bool {
        self.format.starts_with('s')
    }
}

#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Layout {
    pub columns: Vec<Column>,
    pub bits: u32,
}

impl Layout {
    pub fn push(&mut self, name: &str, role: Role, lane_bits: u32, lanes: u32, format: String) {
        let width = lane_bits * lanes;
        self.columns.push(Column {
            name: name.to_string(),
            role,
            lsb: self.bits,
            width,
            lanes,
            format,
            enters: 0,
        });
        self.bits += width;
    }

    pub fn bytes(&self) -> usize {
        self.bits.div_ceil(8) as usize
    }

    /// 32-bit words of a record (the C ABI's unit).
    pub fn words32(&self) -> usize {
        self.bits.div_ceil(32) as usize
    }

    pub fn hex_digits(&self) -> usize {
        self.bits.div_ceil(4) as usize
    }

    pub fn column(&self, name: &str) -> &Column {
        self.columns
            .iter()
            .find(|c| c.name == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    }
}

/// One record being packed.
#[derive(Clone, Debug)]
pub struct Record {
    pub words: Vec<u64>,
}

impl Record {
    pub fn new(layout: &Layout) -> Record {
        Record {
            words: vec![0; (layout.bits as usize).div_ceil(64).max(1)],
        }
    }

    /// Put the low `width` (≤ 64) bits of `v` at `lsb`; at most two word updates.
    #[inline(always)]
    pub fn set(&mut self, lsb: u32, width: u32, v: u64) {
        if width == 0 {
            return;
        }
        let v = if width >= 64 { v } else { v & ((1u64 << width) - 1) };
        let (w, off) = ((lsb / 64) as usize, lsb % 64);
        self.words[w] |= v << off;
        if off + width > 64 {
            self.words[w + 1] |= v >> (64 - off);
        }
    }

    #[inline]
    pub fn get(&self, lsb: u32, width: u32) -> u64 {
        if width == 0 {
            return 0;
        }
        let (w, off) = ((lsb / 64) as usize, lsb % 64);
        let mut v = self.words[w] >> off;
        if off + width > 64 {
            v |= self.words[w + 1] << (64 - off);
        }
        if width >= 64 {
            v
        } else {
            v & ((1u64 << width) - 1)
        }
    }

    /// Set lane `i` of column `c` (two's complement values are masked to the lane width).
    /// # Panics
    /// When `v` fits the lane neither as an unsigned nor as a two's-complement value: a
    /// generator bug, which must never be masked into a silently different stimulus.
    pub fn set_lane(&mut self, c: &Column, i: u32, v: i64) {
        let lw = c.width / c.lanes;
        assert!(
            lw >= 63 || (v >= -(1i64 << (lw - 1)) && v < (1i64 << lw)),
            "value {v} does not fit {}-bit lane {i} of column {}",
            lw,
            c.name
        );
        let mask = if lw >= 64 { u64::MAX } else { (1u64 << lw) - 1 };
        self.set(c.lsb + i * lw, lw, v as u64 & mask);
    }

    pub fn get_lane(&self, c: &Column, i: u32) -> u64 {
        let lw = c.width / c.lanes;
        self.get(c.lsb + i * lw, lw)
    }

    /// Lane `i` of column `c` as a value: sign-extended when the column is signed.
    pub fn lane_value(&self, c: &Column, i: u32) -> i64 {
        let lw = c.width / c.lanes;
        let v = self.get_lane(c, i);
        if c.signed() && lw < 64 {
            ((v << (64 - lw)) as i64) >> (64 - lw)
        } else {
            v as i64
        }
    }

    /// The record as 32-bit words, LSB first (the C ABI's and SystemVerilog DPI's
    /// `svBitVecVal` layout): `n` words.
    pub fn to_words32(&self, n: usize) -> Vec<u32> {
        (0..n)
            .map(|i| (self.words.get(i / 2).copied().unwrap_or(0) >> (32 * (i % 2))) as u32)
            .collect()
    }

    /// A record from 32-bit words, LSB first.
    pub fn from_words32(w: &[u32]) -> Record {
        let mut words = vec![0u64; w.len().div_ceil(2).max(1)];
        for (i, &x) in w.iter().enumerate() {
            words[i / 2] |= (x as u64) << (32 * (i % 2));
        }
        Record { words }
    }

    pub fn hex(&self, digits: usize) -> String {
        let mut s = String::with_capacity(digits);
        for d in (0..digits).rev() {
            let nib = (self.words[d / 16] >> ((d % 16) * 4)) & 0xF;
            s.push(char::from_digit(nib as u32, 16).expect("nibble"));
        }
        s
    }

    pub fn to_bytes(&self, n: usize, out: &mut Vec<u8>) {
        let full = n / 8;
        for w in &self.words[..full] {
            out.extend_from_slice(&w.to_le_bytes());
        }
        if !n.is_multiple_of(8) {
            out.extend_from_slice(&self.words[full].to_le_bytes()[..n % 8]);
        }
    }

    pub fn from_bytes(b: &[u8]) -> Record {
        let mut words = vec![0u64; b.len().div_ceil(8).max(1)];
        for (i, byte) in b.iter().enumerate() {
            words[i / 8] |= (*byte as u64) << ((i % 8) * 8);
        }
        Record { words }
    }

    pub fn from_hex(s: &str) -> Option<Record> {
        let digits: Vec<u32> = s.trim().chars().rev().map(|c| c.to_digit(16)).collect::<Option<_>>()?;
        let mut words = vec![0u64; digits.len().div_ceil(16).max(1)];
        for (d, v) in digits.iter().enumerate() {
            words[d / 16] |= (*v as u64) << ((d % 16) * 4);
        }
        Some(Record { words })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pack_round_trips() {
        let mut l = Layout::default();
        l.push("a", Role::Stimulus, 7, 3, "u".into());
        l.push("b", Role::Expected, 61, 2, "s".into());
        let mut r = Record::new(&l);
        r.set_lane(l.column("a"), 2, 0x55);
        r.set_lane(l.column("b"), 1, -3);
        assert_eq!(r.get_lane(l.column("a"), 2), 0x55);
        assert_eq!(r.get_lane(l.column("b"), 1), (1u64 << 61) - 3);
        let h = r.hex(l.hex_digits());
        assert_eq!(Record::from_hex(&h).unwrap().hex(l.hex_digits()), h);
        let mut b = Vec::new();
        r.to_bytes(l.bytes(), &mut b);
        assert_eq!(Record::from_bytes(&b).hex(l.hex_digits()), h);
    }
}
