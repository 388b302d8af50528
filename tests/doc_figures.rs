//! Figures README.md and ARCHITECTURE.md state about the generated design and the tools,
//! each read from the code that sets it: a changed constant or formula fails here until the
//! text says the same.

use gbump::config::PipelineConfig;
use gbump::rtlgen::top::{latency, output_depth, top_ports};

fn flat(rel: &str) -> String {
    let text = std::fs::read_to_string(format!("{}/{rel}", env!("CARGO_MANIFEST_DIR"))).unwrap();
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn says(rel: &str, want: &str) {
    assert!(flat(rel).contains(want), "{rel} should say: {want}");
}

fn config(rel: &str) -> PipelineConfig {
    PipelineConfig::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)).unwrap()
}

fn tops() -> Vec<PipelineConfig> {
    let mut all = Vec::new();
    for base in [PipelineConfig::default(), config("tests/configs/one_light_parallel.toml")] {
        for pipeline_depth in 1..=gbump::limits::MAX_PIPELINE_DEPTH {
            all.push(PipelineConfig {
                pipeline_depth,
                ..base.clone()
            });
        }
    }
    all
}

/// Rounding the colour once at the end costs the `colour_round` unit's one cycle, at every
/// depth, serial and parallel.
#[test]
fn guard_bits_cost_one_cycle_of_latency() {
    for cfg in tops() {
        let guarded = PipelineConfig {
            colour_guard_bits: 2,
            ..cfg.clone()
        };
        assert_eq!(
            latency(&guarded),
            latency(&cfg) + 1,
            "depth {}, {:?}",
            cfg.pipeline_depth,
            cfg.light_mode
        );
    }
    says("README.md", "`colour_round` unit (one more cycle of latency)");
    says("ARCHITECTURE.md", "and one more cycle of latency");
}

/// The output buffer holds every result that can be in flight when an accept is allowed.
#[test]
fn the_output_buffer_is_the_stated_formula() {
    for cfg in tops() {
        let want = latency(&cfg).div_ceil(cfg.initiation_interval()) + 1;
        assert_eq!(output_depth(&cfg), Some(want), "depth {}, {:?}", cfg.pipeline_depth, cfg.light_mode);
    }
    says(
        "ARCHITECTURE.md",
        "buffer of `top::output_depth` = ceil(latency / interval) + 1 results",
    );
}

/// The one-light parallel configuration the README's tour refers to takes a fragment a clock.
#[test]
fn the_one_light_parallel_top_takes_a_fragment_a_clock() {
    assert_eq!(config("tests/configs/one_light_parallel.toml").initiation_interval(), 1);
    says("README.md", "(`tests/configs/one_light_parallel.toml`, one fragment per clock)");
}

/// The DPI-C package's vector width and the C library's batch threshold.
#[test]
fn the_c_librarys_widths_and_batches_are_its_constants() {
    let bits = gbump::capi::MAX_RECORD_BITS;
    says("ARCHITECTURE.md", &format!("`GBUMP_MAX_BITS` = {bits} wide"));
    says("README.md", &format!("write the whole {bits}-bit vector"));
    let batch = gbump::capi::PARALLEL_RECORDS;
    says(
        "README.md",
        &format!("Batches of {batch} records or more run on the library's thread pool"),
    );
}

/// Every regressing command's stream and mismatch limit, and the hand-written benches'
/// own defaults.
#[test]
fn the_regression_stream_and_mismatch_limit_are_the_constants() {
    use gbump::sim::regress::{MAX_ERRORS, STALL};
    says("ARCHITECTURE.md", &format!("stop after {MAX_ERRORS} mismatches"));
    says("ARCHITECTURE.md", &format!("regressions use {STALL})"));
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let harness = std::fs::read_to_string(root.join("testbench/harness_top.cpp.tpl")).unwrap();
    assert!(
        harness.contains(&format!("long max_errors = {MAX_ERRORS};")),
        "the C++ harness's default"
    );
    let cosim = std::fs::read_to_string(root.join("testbench/tb_cosim.sv.tpl")).unwrap();
    assert!(
        cosim.contains(&format!("[+max_errors=N] (default {MAX_ERRORS})")),
        "the cosim bench's default"
    );
}

/// The area model's split of its configurations into fitted and held out.
#[test]
fn the_area_models_split_is_the_commands_default() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let n = std::fs::read_dir(root.join("tests/area_model/configs"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "toml"))
        .count();
    let fitted = gbump::cli::AREA_MODEL_CALIBRATE;
    says(
        "README.md",
        &format!(
            "fitted to Yosys on the first {fitted} configurations (each unit and top), checked on the other {}",
            n - fitted
        ),
    );
}

/// The pins of the bare top, which no iCE40 package bonds (hence the FPGA shell).
#[test]
fn the_tops_pin_counts_are_its_ports() {
    let pins = |c: &PipelineConfig| top_ports(c).iter().map(|p| p.2).sum::<u32>();
    let about = |n: u32| (n + 5) / 10 * 10;
    let (four, one) = (
        pins(&PipelineConfig::default()),
        pins(&config("tests/configs/one_light_parallel.toml")),
    );
    says(
        "ARCHITECTURE.md",
        &format!("about {} for the default four-light top, {} for one light", about(four), about(one)),
    );
}

/// docs/SCENES.md's count of `blend_split`'s records whose C_src, exactly 25.5 in the
/// scene's equations, came out as 26 or as 25 from the interpolation weights' rounding.
#[test]
fn scenes_md_counts_blend_splits_tied_colours() {
    let s = gbump::scene::Scene::load("blend_split").unwrap();
    let cfg = s.derive_config().unwrap();
    let groups = gbump::vectors::sources::scene_groups(&cfg, "blend_split", None).unwrap();
    // A grey C_src: a record carries the value in all three lanes.
    let count = |v: u32| groups.iter().flat_map(|g| &g.stims).filter(|t| t.frag.c_src == [v; 3]).count();
    let spaced = |n: usize| match n {
        0..=999 => n.to_string(),
        _ => format!("{} {:03}", n / 1000, n % 1000),
    };
    says(
        "docs/SCENES.md",
        &format!("`in_c_src = 26` {} times and 25 {} times", spaced(count(26)), spaced(count(25))),
    );
}

/// The normalisation cube map's stored quarter face, at every face size a configuration takes.
#[test]
fn the_cube_map_holds_a_quarter_face() {
    for k in 2..=7 {
        let face = 1u32 << k;
        assert_eq!(gbump::model::cube_normalise::words(face), (face / 2) * (face / 2), "face {face}");
    }
    says("README.md", "(`(face/2)²` words of three components, a constant table in logic)");
}

/// The normalise unit's exhaustive set: made up to the width its description states, not past.
#[test]
fn the_normalise_units_exhaustive_width_is_its_descriptions() {
    let u = gbump::units::unit("normalise").unwrap();
    let when = u.exhaustive_when().unwrap();
    let bits: u32 = when
        .strip_prefix("lh_bits <= ")
        .and_then(|r| r.split(' ').next())
        .unwrap()
        .parse()
        .unwrap();
    for (lh_bits, made) in [(bits, true), (bits + 1, false)] {
        let cfg = PipelineConfig {
            lh_bits,
            renormalise: true,
            interpolate: gbump::config::Interpolate::Hl,
            bump_state: gbump::config::BumpStateAt::Fragment,
            ..PipelineConfig::default()
        };
        assert_eq!(u.exhaustive_count(&cfg).is_some(), made, "lh_bits = {lh_bits}");
    }
    says("README.md", &format!("exhaustive for `lh_bits <= {bits}`"));
}

/// The deepest pipeline's cost over the default depth on the two tops whose Fmax chose the
/// default, as ARCHITECTURE.md weighs it.
#[test]
fn depth_four_costs_two_cycles_over_three() {
    for cfg in [
        config("tests/configs/one_light_parallel.toml"),
        config("tests/configs/paper_sample_one_light.toml"),
    ] {
        let at = |pipeline_depth| {
            latency(&PipelineConfig {
                pipeline_depth,
                ..cfg.clone()
            })
        };
        assert_eq!(at(4), at(3) + 2, "{:?}", cfg.light_mode);
    }
    says("ARCHITECTURE.md", "for two more cycles of latency and more logic cells");
}

/// ARCHITECTURE.md's counterexamples to the add-and-shift identity for a guarded colour's
/// products (why the texture stage divides through a constant reciprocal): each fails as
/// stated, while every product of two w-bit codes holds.
#[test]
fn the_add_and_shift_counterexamples_fail_as_stated() {
    use gbump::fixed::{unorm_div_round, unorm_mul};
    let three_terms = |a: u64, b: u64, w: u32| {
        let t = a * b + (1 << (w - 1));
        (t + (t >> w) + (t >> (2 * w))) >> w
    };
    for (w, g, a, b, terms) in [(8, 1, 304, 242, 2), (6, 2, 199, 41, 3), (8, 3, 1427, 229, 3)] {
        assert!(a < 1 << (w + g) && b < 1 << w, "{a}·{b} is a guarded colour times a code");
        let got = if terms == 2 { unorm_mul(a, b, w) } else { three_terms(a, b, w) };
        assert_ne!(got, unorm_div_round(a * b, w), "w = {w}, g = {g} at {a}·{b}");
        let at = format!("w = {w}, g = {g} at {a}·{b}");
        assert!(flat("ARCHITECTURE.md").contains(&at), "ARCHITECTURE.md should say: {at}");
    }
    for w in [6, 8] {
        for a in 0..1u64 << w {
            for b in 0..1u64 << w {
                assert_eq!(unorm_mul(a, b, w), unorm_div_round(a * b, w), "w = {w}: {a}·{b}");
            }
        }
    }
}
