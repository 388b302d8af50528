//! A set's expected columns against this gbump's model, before a simulator judges the RTL by
//! them. The manifest's digests prove the files are the ones it lists, not that their
//! expected values are the model's: a set edited throughout (its records and the manifest's
//! digests), or made by a gbump whose model has since changed, would have its mismatches
//! blamed on the RTL. Every record is evaluated again from its stimulus columns, with the
//! memories the set runs on (the power table of its shininess, its environment maps), and
//! must come back bit for bit.

use super::layout::{Layout, Record, Role};
use super::manifest::Manifest;
use super::targets::{top_stim, unit_stim, TopEncoder};
use crate::error::{Error, Result};
use crate::units::MemoryContents;
use rayon::prelude::*;
use std::path::Path;

/// Records evaluated together (a chunk is one task on the pool).
const CHUNK: usize = 1 << 14;

/// Check every record of the set `m` (its files in `dir`, already checked against the
/// manifest) against the model; `regen` is the command that remakes it. Returns the set's
/// [`Digest`](super::digest::Digest), which its testbench's must equal.
pub fn check_expected(m: &Manifest, dir: &Path, regen: &str) -> Result<super::digest::Digest> {
    let cfg = &m.config;
    let layout = super::targets::layout(cfg, &m.target);
    let records = read_records(m, dir, &layout)?;
    let mut mem = MemoryContents::new(cfg, m.shininess);
    if let Some(e) = &m.env_maps {
        if let Some(f) = &e.diffuse {
            mem.env.diffuse = env_map(&dir.join(&f.name), cfg)?;
        }
        if let Some(f) = &e.specular {
            mem.env.specular = env_map(&dir.join(&f.name), cfg)?;
        }
    }
    let view = mem.view();
    let unit = (m.target != "top").then(|| crate::units::unit(&m.target)).flatten();
    let top = (m.target == "top").then(|| (super::top_records::TopRecords::new(cfg, view), TopEncoder::new(cfg, &layout)));
    // The first record (in set order) the model does not give back.
    let bad =
        records
            .par_chunks(CHUNK)
            .enumerate()
            .find_map_first(|(c, chunk)| -> Option<(usize, Record, std::result::Result<Record, Error>)> {
                let first = c * CHUNK;
                if let Some((maker, enc)) = &top {
                    let stims: Vec<_> = chunk.iter().map(|r| top_stim(cfg, &layout, r)).collect();
                    let mut colours = vec![[0u32; 3]; stims.len()];
                    if let Err(e) = maker.colours(first as u64, &stims, &mut colours) {
                        return Some((first, chunk[0].clone(), Err(e)));
                    }
                    let mut want = Record::new(&layout);
                    chunk.iter().zip(&stims).zip(&colours).enumerate().find_map(|(k, ((r, s), c))| {
                        enc.fill_colour(s, *c, &mut want);
                        (want.words != r.words).then(|| (first + k, r.clone(), Ok(want.clone())))
                    })
                } else {
                    let u = unit?;
                    chunk.iter().enumerate().find_map(|(k, r)| {
                        let s = unit_stim(&layout, u.name(), r);
                        let want = super::targets::checked_unit_record(cfg, &view, &layout, &s);
                        match want {
                            Ok(w) if w.words == r.words => None,
                            w => Some((first + k, r.clone(), w)),
                        }
                    })
                }
            });
    let Some((i, got, want)) = bad else {
        let mut d = super::digest::Digest::default();
        for r in &records {
            d.words(&r.words);
        }
        return Ok(d);
    };
    let file = m
        .bin
        .as_ref()
        .or(m.hex.as_ref())
        .map_or(String::new(), |f| dir.join(&f.name).display().to_string());
    let why = match want {
        Err(e) => format!("the model refuses its stimulus ({e})"),
        Ok(want) => {
            // Lane by lane: a column may be wider than a word (a light state's).
            let diff: Vec<String> = layout
                .columns
                .iter()
                .flat_map(|c| (0..c.lanes).map(move |i| (c, i)))
                .filter(|(c, i)| got.get_lane(c, *i) != want.get_lane(c, *i))
                .map(|(c, i)| {
                    format!(
                        "`{}`{} is {:#x} in the file, {:#x} from the model{}",
                        c.name,
                        if c.lanes > 1 { format!(" lane {i}") } else { String::new() },
                        got.get_lane(c, i),
                        want.get_lane(c, i),
                        if c.role == Role::Stimulus {
                            " (a stimulus column that does not read back)"
                        } else {
                            ""
                        }
                    )
                })
                .take(4)
                .collect();
            diff.join("; ")
        }
    };
    Err(Error::Other(format!(
        "{file}: record {i}: {why}: the set's expected values are not this gbump's model's (the set was edited, or made by another gbump: its manifest says `{}`, this is `{}`), so the RTL would be judged by them\n  fix: regenerate with: {regen}",
        m.generator,
        crate::TOOL
    )))
}

/// The set's records, from its binary file where it has one, else its text file.
fn read_records(m: &Manifest, dir: &Path, layout: &Layout) -> Result<Vec<Record>> {
    if let Some(b) = &m.bin {
        let p = dir.join(&b.name);
        let bytes = std::fs::read(&p).map_err(|e| Error::io(&p, e))?;
        return Ok(bytes.chunks(layout.bytes()).map(Record::from_bytes).collect());
    }
    let h = m
        .hex
        .as_ref()
        .ok_or_else(|| Error::Other("a set with neither a .bin nor a .hex file".into()))?;
    let p = dir.join(&h.name);
    let text = std::fs::read_to_string(&p).map_err(|e| Error::io(&p, e))?;
    text.lines()
        .map(|l| Record::from_hex(l.trim()).ok_or_else(|| Error::Other(format!("{}: `{l}` is not a record", p.display()))))
        .collect()
}

/// An environment map file's texels: one {B, G, R} word a line after its `//` header, R in
/// the low `colour_bits`.
fn env_map(p: &Path, cfg: &crate::config::PipelineConfig) -> Result<Vec<[u32; 3]>> {
    let text = std::fs::read_to_string(p).map_err(|e| Error::io(p, e))?;
    let words = crate::rtlgen::rom::parse(&text, crate::rtlgen::rom::RomFormat::Hex)
        .map_err(|e| Error::Other(format!("{}: {e}: not a texel word", p.display())))?;
    crate::model::env_map::texels_of_words(cfg, &words, &p.display().to_string())
}
