//! ROM/LUT contents and their init-file writers: `$readmemh` hex, Intel `.mif`, Xilinx `.coe`.
//! Contents come from the model (power table, palette) or from the Cg tutorial's
//! normalisation cube map, so the RTL's tables are the model's tables by construction.

use crate::config::PipelineConfig;
use crate::model::bump_fetch::Palette;
use crate::model::PowerTable;
use glam::DVec3;

/// A ROM: `width`-bit words.
#[derive(Clone, Debug, PartialEq)]
pub struct Rom {
    pub name: String,
    pub width: u32,
    pub words: Vec<u64>,
    /// One line per word describing its layout (for headers).
    pub layout: String,
}

/// Init-file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RomFormat {
    Hex,
    Mif,
    Coe,
}

impl RomFormat {
    pub const ALL: [RomFormat; 3] = [RomFormat::Hex, RomFormat::Mif, RomFormat::Coe];
    pub fn ext(self) -> &'static str {
        match self {
            RomFormat::Hex => "hex",
            RomFormat::Mif => "mif",
            RomFormat::Coe => "coe",
        }
    }
}

fn digits(width: u32) -> usize {
    width.div_ceil(4) as usize
}

/// Render `rom` in `fmt`, with `header` lines as comments.
pub fn write(rom: &Rom, fmt: RomFormat, header: &[String]) -> String {
    let d = digits(rom.width);
    let mut s = String::new();
    let comment = match fmt {
        RomFormat::Hex => "// ",
        RomFormat::Mif => "-- ",
        RomFormat::Coe => "; ",
    };
    for l in header.iter().chain(std::iter::once(&format!(
        "{}: {} words of {} bits; {}",
        rom.name,
        rom.words.len(),
        rom.width,
        rom.layout
    ))) {
        s += &format!("{comment}{l}\n");
    }
    match fmt {
        RomFormat::Hex => {
            for w in &rom.words {
                s += &format!("{w:0d$x}\n");
            }
        }
        RomFormat::Mif => {
            s += &format!(
                "WIDTH={};\nDEPTH={};\nADDRESS_RADIX=HEX;\nDATA_RADIX=HEX;\nCONTENT BEGIN\n",
                rom.width,
                rom.words.len()
            );
            for (a, w) in rom.words.iter().enumerate() {
                s += &format!("    {a:x} : {w:0d$x};\n");
            }
            s += "END;\n";
        }
        RomFormat::Coe => {
            s += "memory_initialization_radix=16;\nmemory_initialization_vector=\n";
            let n = rom.words.len();
            for (i, w) in rom.words.iter().enumerate() {
                s += &format!("{w:0d$x}{}\n", if i + 1 == n { ";" } else { "," });
            }
        }
    }
    s
}

/// Parse any of the three formats back to words (for the round-trip tests).
pub fn parse(text: &str, fmt: RomFormat) -> Result<Vec<u64>, String> {
    let mut out = Vec::new();
    let hex = |t: &str, line: usize| u64::from_str_radix(t.trim(), 16).map_err(|e| format!("line {line}: `{t}`: {e}"));
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        match fmt {
            RomFormat::Hex => {
                let t = raw.split("//").next().unwrap_or("").trim();
                if !t.is_empty() {
                    out.push(hex(t, line)?);
                }
            }
            RomFormat::Mif => {
                let t = raw.split("--").next().unwrap_or("").trim();
                if let Some((_, v)) = t.split_once(':') {
                    out.push(hex(v.trim_end_matches(';'), line)?);
                }
            }
            RomFormat::Coe => {
                let t = raw.trim();
                if !t.is_empty() && !t.starts_with(';') && !t.contains('=') {
                    out.push(hex(t.trim_end_matches([',', ';']), line)?);
                }
            }
        }
    }
    Ok(out)
}

/// The power table for shininess `n`.
pub fn power_rom(cfg: &PipelineConfig, n: u32) -> Rom {
    let t = PowerTable::build(cfg, n);
    Rom {
        name: format!("power_table n={n}"),
        width: cfg.power_bits + 1,
        words: t.entries.iter().map(|&e| e as u64).collect(),
        layout: match cfg.power_unit {
            crate::config::PowerUnitKind::Table => format!(
                "entry i = round((i/{})^{n} * 2^{}), u1.{}",
                cfg.power_entries - 1,
                cfg.power_bits,
                cfg.power_bits
            ),
            _ => format!(
                "{} knots for n = {n}, u1.{} (layout: model::power_unit)",
                cfg.power_design().label(),
                cfg.power_bits
            ),
        },
    }
}

/// A generic 256-normal palette: a Fibonacci spiral over the upper hemisphere, entry 0 the
/// unperturbed normal. Used as reset contents; scenes load their own palettes.
pub fn default_palette(cfg: &PipelineConfig) -> Palette {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let entries = (0..256)
        .map(|i| {
            let z = 1.0 - i as f64 / 256.0;
            let r = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            crate::bumpmap::storage::encode_normal(cfg, DVec3::new(r * phi.cos(), r * phi.sin(), z))
        })
        .collect();
    Palette(entries)
}

/// Palette as a ROM: {z, y, x} packed, x in the low bits (the `b` lane order).
pub fn palette_rom(cfg: &PipelineConfig, p: &Palette) -> Rom {
    let nb = cfg.normal_bits;
    Rom {
        name: "bump_palette".into(),
        width: 3 * nb,
        words: p
            .0
            .iter()
            .map(|e| e[0] as u64 | (e[1] as u64) << nb | (e[2] as u64) << (2 * nb))
            .collect(),
        layout: format!("{{z, y, x}}, {nb}-bit offset-binary components, x in bits [{}:0]", nb - 1),
    }
}

/// Direction through texel (s, t) of cube face `face` (OpenGL order +X −X +Y −Y +Z −Z).
pub fn cube_dir(face: usize, s: usize, t: usize, size: usize) -> DVec3 {
    let sc = 2.0 * (s as f64 + 0.5) / size as f64 - 1.0;
    let tc = 2.0 * (t as f64 + 0.5) / size as f64 - 1.0;
    match face {
        0 => DVec3::new(1.0, -tc, -sc),
        1 => DVec3::new(-1.0, -tc, sc),
        2 => DVec3::new(sc, 1.0, tc),
        3 => DVec3::new(sc, -1.0, -tc),
        4 => DVec3::new(sc, -tc, 1.0),
        _ => DVec3::new(-sc, -tc, -1.0),
    }
}

/// The Cg tutorial's normalisation cube map (§8.1.3): each texel holds its own direction,
/// normalised and range-compressed to RGB8 ((n + 1)/2 · 255, rounded).
pub fn cube_map_rom(size: usize) -> Rom {
    let mut words = Vec::with_capacity(6 * size * size);
    for face in 0..6 {
        for t in 0..size {
            for s in 0..size {
                let n = cube_dir(face, s, t, size).normalize();
                let c = [n.x, n.y, n.z].map(|x| (((x + 1.0) * 0.5) * 255.0).round() as u64);
                words.push(c[0] | c[1] << 8 | c[2] << 16);
            }
        }
    }
    Rom {
        name: format!("normalisation_cube_map {size}x{size}x6"),
        width: 24,
        words,
        layout: format!(
            "address = face*{} + t*{size} + s, faces +X -X +Y -Y +Z -Z; {{B, G, R}} = range-compressed (z, y, x)",
            size * size
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_round_trip() {
        let cfg = PipelineConfig::default();
        for rom in [power_rom(&cfg, 16), palette_rom(&cfg, &default_palette(&cfg)), cube_map_rom(4)] {
            for f in RomFormat::ALL {
                let text = write(&rom, f, &["hdr".into()]);
                assert_eq!(parse(&text, f).unwrap(), rom.words, "{} {:?}", rom.name, f);
            }
        }
    }

    #[test]
    fn cube_map_matches_cg_example() {
        // Cg §8.1.3: (3, 1.5, 0.9) pierces +X and reads back about (0.93, 0.72, 0.63).
        let rom = cube_map_rom(32);
        let d = DVec3::new(3.0, 1.5, 0.9);
        let (sc, tc) = (-d.z / d.x, -d.y / d.x);
        let s = (((sc + 1.0) / 2.0) * 32.0) as usize;
        let t = (((tc + 1.0) / 2.0) * 32.0) as usize;
        let w = rom.words[t * 32 + s];
        let rgb = [w & 255, (w >> 8) & 255, w >> 16].map(|c| c as f64 / 255.0);
        assert!(
            (rgb[0] - 0.93).abs() < 0.02 && (rgb[1] - 0.72).abs() < 0.03 && (rgb[2] - 0.63).abs() < 0.03,
            "{rgb:?}"
        );
    }
}
