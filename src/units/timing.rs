//! Timing as a parameter: where each arithmetic unit may hold a register inside, and how many
//! of those cuts `pipeline_depth` puts in place. A unit's latency is one (its output
//! register) plus its cuts in place, and its Verilog emitter asks the same function, so the
//! latency the scheduler and the benches read is the register count the RTL has.
//!
//! Cuts are listed in the order depth adds them: the first one always splits the longest
//! path (two chained multipliers in a blend), later ones peel off adders and rounding.

use crate::config::PipelineConfig;

/// dot_clamp: three products, their sum, one rounding and the clamp.
pub const DOT_CLAMP: &[&str] = &["after the three products B_c V_c", "after their sum"];
/// diffuse_blend / specular_blend (parallel): f·k, then ·Lc, the sum over lights, the finish.
pub const BLEND: &[&str] = &["after f k", "after f k Lc", "after the sum over the lights"];
/// light_accumulate: f·k, then ·Lc; the running sum stays the last stage, so its feedback
/// (`acc_in`) is one cycle at any depth.
pub const ACCUMULATE: &[&str] = &["after f k", "after f k Lc"];
/// env_coords: the four products M b with st, then the texel coordinates (clamp, floor and
/// the sub-texel fraction); the weights' small products stay before the output register.
pub const ENV_COORDS: &[&str] = &["after s = st + M b", "after the texel and its fractions"];
/// texture_modulate: c·t, then the exact division by 2^w - 1 (two adds).
pub const TEXTURE: &[&str] = &["after c t"];

/// normalise: the squared length; the shift, the table and the Newton steps; the scaled
/// products x·r (their shift and rounding stay before the output register).
pub const NORMALISE: &[&str] = &[
    "after the sum of squares",
    "after the table and the Newton steps",
    "after the products x r",
];

/// normalise_cube: the face choice (magnitudes, the major axis, the minors picked); the texel
/// divisions (the map read, its signs and the axes' order stay before the output register).
pub const NORMALISE_CUBE: &[&str] = &["after the face choice", "after the texel divisions"];

/// frame_transform: per component three products, their sum, one rounding and the clamp
/// (a dot_clamp's shape, three times).
pub const FRAME_TRANSFORM: &[&str] = &["after the nine products b_i F_i", "after the three sums"];

/// quat_frame: the quaternion's ten products, then the nine entries' sums, rounding and clamp.
pub const QUAT_FRAME: &[&str] = &["after the ten products"];

/// power_unit, squaring: the chain of rounded products split into equal parts (each cut
/// registers the running power, and x while a multiply by it remains;
/// `rtlgen::power_units::squaring_cut_positions`).
pub const SQUARING: &[&str] = &["the products cut in two", "in three", "in four"];

/// How many of `cuts` are in place at the configuration's depth.
pub fn cuts_in_place(cfg: &PipelineConfig, cuts: &[&str]) -> u32 {
    (cfg.pipeline_depth.saturating_sub(1)).min(cuts.len() as u32)
}

/// Latency of a unit with `cuts`: its output register plus the cuts in place.
pub fn latency(cfg: &PipelineConfig, cuts: &[&str]) -> u32 {
    1 + cuts_in_place(cfg, cuts)
}

/// Whether cut `i` (0-based, in the list's order) is in place.
pub fn cut(cfg: &PipelineConfig, cuts: &[&str], i: usize) -> bool {
    (i as u32) < cuts_in_place(cfg, cuts)
}

/// The cuts of unit `name` (a power unit's by its kind; none for a unit whose output register
/// is its only one).
fn cuts_of(name: &str, kind: crate::config::PowerUnitKind) -> &'static [&'static str] {
    match name {
        "dot_clamp" => DOT_CLAMP,
        "diffuse_blend" | "specular_blend" => BLEND,
        "light_accumulate" => ACCUMULATE,
        "texture_modulate" => TEXTURE,
        "normalise" | "normalise_b" => NORMALISE,
        "normalise_cube" => NORMALISE_CUBE,
        "frame_transform" => FRAME_TRANSFORM,
        "quat_frame" => QUAT_FRAME,
        "env_coords" => ENV_COORDS,
        "power_unit" if kind == crate::config::PowerUnitKind::Squaring => SQUARING,
        _ => &[],
    }
}

/// The table header: a column per depth, `mine` marked as the configuration's own.
fn header(mine: Option<u32>) -> String {
    let hi = crate::limits::MAX_PIPELINE_DEPTH;
    let mut s = String::from("| unit |");
    for d in 1..=hi {
        s += &format!(" depth {d}{} |", if Some(d) == mine { " (this configuration)" } else { "" });
    }
    s += " register cuts, in the order depth adds them |\n|---|";
    for _ in 1..=hi {
        s += "---:|";
    }
    s + "---|\n"
}

/// `gbump timing --config`: the table for one configuration, each unit it includes and its
/// top at every depth (the rest of the configuration as it is), its own depth marked. The
/// README's table covers the default's units and two tops; an EMBM or Cg top's units and
/// latency are here.
pub fn config_markdown(cfg: &PipelineConfig) -> String {
    let hi = crate::limits::MAX_PIPELINE_DEPTH;
    let at = |d: u32| PipelineConfig {
        pipeline_depth: d,
        ..cfg.clone()
    };
    let mut s = format!("Config `{}`\n\n", cfg.hash()) + &header(Some(cfg.pipeline_depth));
    for u in super::included(cfg) {
        s += &format!("| `{}` |", u.name());
        for d in 1..=hi {
            s += &format!(" {} |", u.latency(&at(d)));
        }
        let cuts = cuts_of(u.name(), cfg.power_unit);
        s += &format!(" {} |\n", if cuts.is_empty() { "none".to_string() } else { cuts.join("; ") });
    }
    s += "| top |";
    for d in 1..=hi {
        s += &format!(" {} |", crate::rtlgen::top::latency(&at(d)));
    }
    s + " the scheduler's result (`rtlgen::top::latency`) |\n"
}

/// The README table: every unit's latency at every depth, where its cuts sit, and the
/// latency of the default and the one-light parallel top.
pub fn markdown() -> String {
    let hi = crate::limits::MAX_PIPELINE_DEPTH;
    let mut s = header(None);
    // Every unit under a configuration that includes it, at each depth.
    let base = |depth: u32, serial: bool, kind: crate::config::PowerUnitKind, palette: bool| PipelineConfig {
        pipeline_depth: depth,
        light_mode: if serial {
            crate::config::LightMode::Serial
        } else {
            crate::config::LightMode::Parallel
        },
        power_unit: kind,
        palette,
        ..PipelineConfig::default()
    };
    use crate::config::PowerUnitKind::{Lerp, Squaring, Table};
    let rows: [(&str, bool, crate::config::PowerUnitKind, bool, &str); 18] = [
        ("bump_fetch", true, Table, false, "none (an inversion)"),
        (
            "frame_build",
            true,
            Table,
            false,
            "two normalise units in a row (N, then B), each followed by a registered cross product: twice the normalise latency plus 2",
        ),
        ("quat_frame", true, Table, false, ""),
        ("frame_transform", true, Table, false, ""),
        ("normalise", false, Table, false, ""),
        ("normalise_cube", false, Table, false, ""),
        ("normalise_b", true, Table, false, ""),
        ("palette_fetch", true, Table, true, "none (the RAM's read register is the output)"),
        ("dot_clamp", true, Table, false, ""),
        (
            "power_unit",
            true,
            Table,
            false,
            "table: none (the RAM's read register is the output)",
        ),
        (
            "power_unit",
            true,
            Lerp,
            false,
            "lerp, segmented: the RAM's read register, then the interpolation",
        ),
        ("power_unit", true, Squaring, false, ""),
        ("diffuse_blend", false, Table, false, ""),
        ("light_accumulate", true, Table, false, ""),
        ("blend_finish", true, Table, false, "none"),
        ("texture_modulate", true, Table, false, ""),
        ("specular_blend", false, Table, false, ""),
        ("colour_round", true, Table, false, "none (present with colour_guard_bits > 0)"),
    ];
    for (name, serial, kind, palette, note) in rows {
        let u = super::unit(name).expect("unit");
        s += &format!("| `{name}` |");
        for d in 1..=hi {
            let mut cfg = base(d, serial, kind, palette);
            if name == "colour_round" {
                cfg.colour_guard_bits = 2;
            }
            if name == "normalise" || name == "normalise_cube" {
                cfg.bump_state = crate::config::BumpStateAt::Fragment;
                cfg.interpolate = crate::config::Interpolate::H;
                cfg.renormalise = true;
            }
            if name == "normalise_cube" {
                cfg.cube_map_face = 32;
            }
            cfg.renormalise_bump = name == "normalise_b";
            if name == "frame_transform" || name == "frame_build" || name == "quat_frame" {
                cfg.bump_state = crate::config::BumpStateAt::Fragment;
                cfg.frame_transform = true;
                cfg.frame_build = name == "frame_build";
                cfg.frame_quaternion = name == "quat_frame";
            }
            s += &format!(" {} |", u.latency(&cfg));
        }
        let cuts = cuts_of(name, kind);
        let text = match (cuts.is_empty(), kind) {
            (true, _) => note.to_string(),
            (false, Squaring) => format!("squaring: {}", cuts.join("; ")),
            (false, _) => cuts.join("; "),
        };
        s += &format!(" {text} |\n");
    }
    // The tops: the scheduler's latency (what every bench checks per vector).
    for (name, serial) in [("top, default (4 lights, serial)", true), ("top, 1 light, parallel", false)] {
        s += &format!("| {name} |");
        for d in 1..=hi {
            let mut cfg = base(d, serial, Table, false);
            if !serial {
                cfg.lights = 1;
            }
            s += &format!(" {} |", crate::rtlgen::top::latency(&cfg));
        }
        s += " the scheduler's result (`rtlgen::top::latency`) |\n";
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_adds_cuts_in_order_up_to_the_unit_s_last() {
        let at = |d| PipelineConfig {
            pipeline_depth: d,
            ..Default::default()
        };
        assert_eq!(latency(&at(1), BLEND), 1);
        assert_eq!(latency(&at(2), BLEND), 2);
        assert!(cut(&at(2), BLEND, 0) && !cut(&at(2), BLEND, 1));
        assert_eq!(latency(&at(4), BLEND), 4);
        assert_eq!(latency(&at(4), TEXTURE), 2);
        // The deepest unit's cuts end at the limit: one more stage would cut nothing.
        let deepest = [
            DOT_CLAMP,
            BLEND,
            ACCUMULATE,
            TEXTURE,
            NORMALISE,
            NORMALISE_CUBE,
            SQUARING,
            FRAME_TRANSFORM,
            QUAT_FRAME,
        ]
        .iter()
        .map(|c| c.len())
        .max()
        .unwrap() as u32;
        assert_eq!(deepest + 1, crate::limits::MAX_PIPELINE_DEPTH);
    }
}
