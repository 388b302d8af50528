//! What one dump of a source may be asked for, whoever asks: `gbump vectors`, the Python
//! module's `Config.vectors`. A choice the source ignores, or that the configuration's
//! hardware cannot serve, is refused in the caller's own words for it, since a set made
//! without it (or for a shininess the top never holds) would be taken for what was asked.

use super::Source;
use crate::config::PipelineConfig;
use crate::error::{Error, Result};

/// How a caller spells its choices in a refusal.
pub struct Spelling {
    pub seed: &'static str,
    pub shininess: &'static str,
    pub size: &'static str,
    pub level: &'static str,
    /// The source as the caller gave it, e.g. `--source corners`.
    pub source: String,
    /// How to ask for a scene source, e.g. `--source scene:NAME`.
    pub scene_source: &'static str,
}

impl Spelling {
    /// `gbump vectors`'s flags.
    pub fn cli(source: &str) -> Spelling {
        Spelling {
            seed: "--seed",
            shininess: "--shininess",
            size: "--size",
            level: "--level",
            source: format!("--source {source}"),
            scene_source: "--source scene:NAME",
        }
    }

    /// A library call's keyword arguments (`seed=`, `shininess=`, `size=`).
    pub fn keywords(source: &str) -> Spelling {
        Spelling {
            seed: "seed=",
            shininess: "shininess=",
            size: "size=",
            level: "level=",
            source: format!("source \"{source}\""),
            scene_source: "source \"scene:NAME\"",
        }
    }

    /// The refusal of `choice`, which this source ignores for the reason `why`.
    pub fn ignored(&self, choice: &str, why: &str) -> Error {
        Error::Other(format!("{choice} has no effect on {}: {why}\n  fix: drop {choice}", self.source))
    }
}

/// What was chosen beside the source (only whether, for all but the shininess).
#[derive(Default)]
pub struct Asked {
    pub seed: bool,
    pub shininess: Option<u32>,
    pub size: bool,
    pub level: bool,
}

/// Refuse a choice `src` ignores (before any configuration is loaded).
pub fn refuse_ignored(src: &Source, a: &Asked, s: &Spelling) -> Result<()> {
    if a.level && !matches!(src, Source::Corners(_)) {
        return Err(s.ignored(s.level, "only the corner catalogue has levels"));
    }
    if a.seed && !matches!(src, Source::Random(_)) {
        return Err(s.ignored(s.seed, "only random sources draw from a seed"));
    }
    if a.shininess.is_some() && matches!(src, Source::Scene(_)) {
        return Err(s.ignored(
            s.shininess,
            "a scene's objects carry their own shininess, and the scene writes one set per shininess",
        ));
    }
    if a.size && !matches!(src, Source::Scene(_)) {
        return Err(Error::Other(format!(
            "{}: only scene sources render an image, not {}\n  fix: drop {}, or use {}",
            s.size, s.source, s.size, s.scene_source
        )));
    }
    Ok(())
}

/// Refuse a shininess `cfg`'s hardware cannot serve in sets of the `written` targets: EMBM
/// has no power unit, and a ROM table or a squaring unit holds the configuration's own.
pub fn refuse_unservable(cfg: &PipelineConfig, written: &[&str], a: &Asked, s: &Spelling) -> Result<()> {
    if a.shininess.is_some() && cfg.embm() {
        return Err(s.ignored(
            s.shininess,
            "EMBM has no power unit (its specular light comes from the environment map)",
        ));
    }
    if let Some(n) = a.shininess.filter(|&n| n != cfg.shininess) {
        if let Some(fixed) = written.iter().find_map(|t| cfg.fixed_shininess_of(t)) {
            // The set would fail or be refused by every regression of this configuration.
            return Err(fixed.refuse(s.shininess, n));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule refuses in the caller's spelling, and a choice the source uses passes.
    #[test]
    fn refusals_use_the_callers_words() {
        let random = Source::Random(10);
        let py = Spelling::keywords("corners");
        let e = refuse_ignored(
            &Source::Corners(1),
            &Asked {
                seed: true,
                ..Asked::default()
            },
            &py,
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("seed= has no effect on source \"corners\""), "{e}");
        assert!(refuse_ignored(
            &random,
            &Asked {
                seed: true,
                ..Asked::default()
            },
            &Spelling::cli("random:10")
        )
        .is_ok());
        // Each other rule, in the command line's words.
        let cli = Spelling::cli("random:10");
        let scene = Source::Scene("blend_split".into());
        let asked = |level, size, shininess| Asked {
            seed: false,
            level,
            size,
            shininess,
        };
        let cases = [
            (&random, asked(true, false, None), "--level has no effect on --source random:10"),
            (&random, asked(false, true, None), "--size: only scene sources render an image"),
            (&scene, asked(false, false, Some(3)), "--shininess has no effect"),
        ];
        for (src, a, want) in cases {
            let e = refuse_ignored(src, &a, &cli).unwrap_err().to_string();
            assert!(e.contains(want) && e.contains("fix:"), "{e}");
        }
        assert!(refuse_ignored(&scene, &asked(false, true, None), &cli).is_ok());
        assert!(refuse_ignored(&Source::Corners(2), &asked(true, false, None), &cli).is_ok());
        let embm = PipelineConfig {
            env_map_bits: 4,
            ..PipelineConfig::default()
        };
        let e = refuse_unservable(&embm, &["top"], &asked(false, false, Some(embm.shininess)), &cli).unwrap_err();
        assert!(e.to_string().contains("EMBM has no power unit"), "{e}");
        let rom = PipelineConfig {
            power_rom: true,
            ..PipelineConfig::default()
        };
        let other = Asked {
            shininess: Some(rom.shininess + 1),
            ..Asked::default()
        };
        let e = refuse_unservable(&rom, &["top"], &other, &py).unwrap_err();
        assert!(e.to_string().contains("shininess=") && e.to_string().contains("ROM holding"), "{e}");
        // A unit set reads no ROM (its harness loads the table), and the own shininess is served.
        assert!(refuse_unservable(&rom, &["power_unit"], &other, &py).is_ok());
        let own = Asked {
            shininess: Some(rom.shininess),
            ..Asked::default()
        };
        assert!(refuse_unservable(&rom, &["top"], &own, &py).is_ok());
    }
}
