//! The C library (src/capi): the checked-in header and DPI-C package are what cbindgen and
//! the generator make of the current source; the functions, called as C would call them,
//! replay `gbump vectors` bit for bit (random stream, top and unit records); errors and
//! panics come back as a status and a message, never an unwind; a C program built against
//! `include/gbump.h` and `libgbump.so` runs.

#[path = "../examples/capi_header.rs"]
#[allow(dead_code)]
mod capi_header;

use gbump::capi::ffi::*;
use gbump::vectors::layout::Record;
use gbump::vectors::{dump, DumpOptions, Source};
use gbump::PipelineConfig;
use std::ffi::{CStr, CString};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn s(p: *const std::ffi::c_char) -> String {
    assert!(!p.is_null());
    unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
}

fn c(t: &str) -> CString {
    CString::new(t).unwrap()
}

#[test]
fn header_and_dpi_package_are_current() {
    for (name, text) in capi_header::generate(&root()) {
        let have = std::fs::read_to_string(root().join("include").join(&name)).unwrap_or_default();
        assert!(
            have == text,
            "include/{name} is stale: src/capi changed since it was generated\n  fix: {}",
            capi_header::REGENERATE
        );
    }
}

/// Every set of a dump: its target and its records (hex lines).
fn dumped(cfg: &PipelineConfig, source: &str, seed: u64, dir: &Path) -> Vec<(String, Vec<String>)> {
    let o = DumpOptions {
        seed,
        ..DumpOptions::formats("test", true, false)
    };
    let targets = gbump::vectors::targets::resolve(cfg, &["all".to_string()]).unwrap();
    let sets = dump(cfg, &Source::parse(source).unwrap(), &targets, dir, &o).unwrap();
    sets.iter()
        .map(|set| {
            let hex = set.manifest.with_extension("hex");
            (
                set.target.clone(),
                std::fs::read_to_string(hex).unwrap().lines().map(str::to_string).collect(),
            )
        })
        .collect()
}

fn hex_of(words: &[u32], digits: usize) -> String {
    Record::from_words32(words).hex(digits)
}

#[test]
fn stream_and_eval_replay_vector_files() {
    // Above 2^63, where a signed 64-bit path would break.
    const SEED: u64 = 18_446_744_073_709_551_557;
    // 16 400 records cross the first 16 384-record chunk of the random stream.
    let d = tempfile::tempdir().unwrap();
    let toml = c("lights = 2\nlight_mode = \"parallel\"\nshininess = 40\n");
    let h = unsafe { gbump_config_from_toml(toml.as_ptr(), c("two.toml").as_ptr()) };
    assert!(!h.is_null(), "{}", s(gbump_last_error()));
    let cfg = PipelineConfig::from_toml("two.toml", "lights = 2\nlight_mode = \"parallel\"\nshininess = 40\n").unwrap();
    let sets = dumped(&cfg, "random:16400", SEED, d.path());
    let top = c("top");
    let n = unsafe { gbump_record_words(h, top.as_ptr()) } as usize;
    let digits = (unsafe { gbump_record_bits(h, top.as_ptr()) } as usize).div_ceil(4);
    let g = unsafe { gbump_stim_new(h, SEED) };
    let (mut stims, mut rec) = (Vec::new(), vec![0u32; n]);
    for want in &sets.iter().find(|(t, _)| t == "top").unwrap().1 {
        assert_eq!(unsafe { gbump_stim_next(g, rec.as_mut_ptr()) }, 0);
        stims.extend_from_slice(&rec);
        let mut out = vec![0u32; n];
        assert_eq!(unsafe { gbump_eval(h, top.as_ptr(), rec.as_ptr(), out.as_mut_ptr()) }, 0);
        assert_eq!(&hex_of(&out, digits), want, "record {}", unsafe { gbump_stim_index(g) } - 1);
    }
    // A batch (in place) equals the single calls.
    let mut batch = stims.clone();
    assert_eq!(
        unsafe { gbump_eval_batch(h, top.as_ptr(), batch.as_ptr(), batch.as_mut_ptr(), (stims.len() / n) as i64) },
        0
    );
    let top_lines = &sets.iter().find(|(t, _)| t == "top").unwrap().1;
    for (i, w) in batch.chunks(n).enumerate() {
        assert_eq!(&hex_of(w, digits), &top_lines[i]);
    }
    // Every unit record of the dump evaluates to itself from its stimulus columns.
    for (target, lines) in sets.iter().filter(|(t, _)| t != "top") {
        let t = c(target);
        let n = unsafe { gbump_record_words(h, t.as_ptr()) } as usize;
        let digits = (unsafe { gbump_record_bits(h, t.as_ptr()) } as usize).div_ceil(4);
        for line in lines.iter().take(500) {
            let r = Record::from_hex(line).unwrap().to_words32(n);
            let mut out = vec![0u32; n];
            assert_eq!(
                unsafe { gbump_eval(h, t.as_ptr(), r.as_ptr(), out.as_mut_ptr()) },
                0,
                "{}",
                s(gbump_last_error())
            );
            assert_eq!(&hex_of(&out, digits), line, "{target}");
        }
    }
    // The power table is the set's table file, word for word.
    let table = std::fs::read_to_string(d.path().join("random16400_top_power_table.hex")).unwrap();
    let words: Vec<i64> = table
        .lines()
        .filter(|l| !l.starts_with("//") && !l.trim().is_empty())
        .map(|l| i64::from_str_radix(l.trim(), 16).unwrap())
        .collect();
    assert_eq!(unsafe { gbump_power_words(h) } as usize, words.len());
    for (i, w) in words.iter().enumerate() {
        assert_eq!(unsafe { gbump_power_word(h, i as i32) }, *w);
    }
    unsafe {
        gbump_stim_free(g);
        gbump_config_free(h);
    }
}

#[test]
fn queries_agree_with_the_interface() {
    let h = gbump_config_default();
    let cfg = PipelineConfig::default();
    unsafe {
        assert_eq!(s(gbump_config_hash(h)), cfg.hash());
        assert_eq!(s(gbump_module_name(h)), gbump::rtlgen::units_v::module_name(&cfg, "gbump_pipeline"));
        assert_eq!(gbump_latency(h) as u32, gbump::rtlgen::top::latency(&cfg));
        assert_eq!(gbump_initiation_interval(h) as u32, cfg.initiation_interval());
        assert_eq!(gbump_lights(h), 4);
        assert_eq!(gbump_abi_version(), gbump::capi::ABI_VERSION);
        assert!(s(gbump_version()).starts_with("gbump "));
        let j: serde_json::Value = serde_json::from_str(&gbump::rtlgen::interface::interface_json(&cfg, "x")).unwrap();
        let ports = j["ports"].as_array().unwrap();
        assert_eq!(gbump_port_count(h) as usize, ports.len());
        for (i, p) in ports.iter().enumerate() {
            assert_eq!(s(gbump_port_name(h, i as i32)), p["name"].as_str().unwrap());
            assert_eq!(gbump_port_width(h, i as i32) as u64, p["width"].as_u64().unwrap());
            assert_eq!(gbump_port_is_output(h, i as i32) == 1, p["dir"] == "output");
        }
        let (mut lsb, mut w, mut lanes, mut exp) = (0, 0, 0, 0);
        assert_eq!(
            gbump_column(h, c("top").as_ptr(), c("out_c").as_ptr(), &mut lsb, &mut w, &mut lanes, &mut exp),
            0
        );
        let out = gbump::vectors::targets::top_layout(&cfg).column("out_c").clone();
        assert_eq!((lsb as u32, w as u32, lanes as u32, exp), (out.lsb, out.width, out.lanes, 1));
        assert_eq!(s(gbump_column_name(h, c("top").as_ptr(), 0)), "in_bump");
        assert_eq!(
            gbump_unit_latency(h, c("dot_clamp").as_ptr()) as u32,
            gbump::units::unit("dot_clamp").unwrap().latency(&cfg)
        );
        assert_eq!(gbump_set_shininess(h, 3), 0);
        assert_eq!(gbump_shininess(h), 3);
        // The targets are the top and the configuration's units, each one gbump_eval takes.
        let targets: Vec<String> = (0..gbump_target_count(h)).map(|i| s(gbump_target_name(h, i))).collect();
        let units: Vec<&str> = gbump::units::included(&cfg).iter().map(|u| u.name()).collect();
        assert_eq!(targets[0], "top");
        assert_eq!(&targets[1..], &units[..], "the units the configuration has, in data-flow order");
        for t in &targets {
            assert!(gbump_record_words(h, c(t).as_ptr()) > 0, "{t}");
        }
        assert!(gbump_target_name(h, targets.len() as i32).is_null());
        assert!(s(gbump_last_error()).contains("gbump_target_count"));
        assert_eq!(s(gbump_config_warnings(h)), "", "the default gives no warning");
        gbump_config_free(h);
    }
}

/// light_accumulate's sum wraps at the accumulator's width as the RTL's adder does (an
/// accumulator at its format's top plus a full term), and the unit's own corners evaluate.
#[test]
fn an_accumulator_wraps_as_the_rtl_does_and_its_corners_evaluate() {
    let cfg = PipelineConfig::default();
    let h = gbump::capi::GbumpConfig::new(cfg.clone()).unwrap();
    let t = h.target("light_accumulate").unwrap();
    let mut r = Record::new(&t.layout);
    let set = |r: &mut Record, name: &str, lanes: &[i64]| {
        for (i, v) in lanes.iter().enumerate() {
            r.set_lane(t.layout.column(name), i as u32, *v);
        }
    };
    let acc_max = cfg.acc_fmt().max_raw();
    set(&mut r, "acc_in", &[acc_max; 3]);
    set(&mut r, "f", &[1 << cfg.factor_frac()]);
    set(&mut r, "k", &[1 << cfg.k_frac_bits]);
    set(&mut r, "lc", &[cfg.colour_max() as i64; 3]);
    let out = h.eval(t, &r).unwrap();
    let term = (1i64 << cfg.factor_frac()) * (1 << cfg.k_frac_bits) * cfg.colour_max() as i64;
    let wrapped = (acc_max + term) & ((1i64 << cfg.acc_fmt().width) - 1);
    assert_eq!(out.lane_value(t.layout.column("acc"), 0), wrapped);
    let u = gbump::units::unit("light_accumulate").unwrap();
    for (why, lanes) in u.corners(&cfg) {
        let mut r = Record::new(&t.layout);
        for (port, v) in gbump::units::inputs(u, &cfg).iter().zip(&lanes) {
            set(&mut r, port.name, v);
        }
        h.eval(t, &r).unwrap_or_else(|e| panic!("{why}: {e}"));
    }
}

/// A configuration under an old field name is read, its warning kept in the handle: the
/// library writes nothing to its host's stderr.
#[test]
fn warnings_stay_in_the_handle() {
    unsafe {
        let h = gbump_config_from_toml(c("dot_bits = 8\n").as_ptr(), c("old.toml").as_ptr());
        assert!(!h.is_null(), "{}", s(gbump_last_error()));
        let w = s(gbump_config_warnings(h));
        assert!(w.contains("old.toml:1:1") && w.contains("dot_frac_bits"), "{w}");
        gbump_config_free(h);
    }
}

#[test]
fn errors_come_back_as_status_and_message() {
    use std::ptr::null_mut;
    unsafe {
        // A range error names its line, as one read from a file does.
        let bad = c("\n\nlights = 9\n");
        assert!(gbump_config_from_toml(bad.as_ptr(), c("mine.toml").as_ptr()).is_null());
        let e = s(gbump_last_error());
        assert!(e.contains("mine.toml:3:1") && e.contains("lights") && e.contains("fix:"), "{e}");
        // A caller's control characters come back escaped, as the CLI shows them.
        assert!(gbump_config_from_toml(c("lights = 9\n").as_ptr(), c("a\u{1b}[31m.toml").as_ptr()).is_null());
        assert!(s(gbump_last_error()).contains("a\\u{1b}[31m.toml"), "{}", s(gbump_last_error()));
        let syntax = c("lights = = 2\n");
        assert!(gbump_config_from_toml(syntax.as_ptr(), c("syn.toml").as_ptr()).is_null());
        assert!(s(gbump_last_error()).contains("syn.toml:1:"), "{}", s(gbump_last_error()));
        assert!(gbump_config_from_file(c("/no/such/gbump.toml").as_ptr()).is_null());
        assert!(s(gbump_last_error()).contains("/no/such/gbump.toml"));
        assert!(gbump_config_from_toml(c("palette = true\n").as_ptr(), c("p.toml").as_ptr()).is_null());
        assert!(s(gbump_last_error()).contains("palette"));
        assert_eq!(gbump_latency(std::ptr::null()), -1);
        assert!(s(gbump_last_error()).contains("NULL"));
        let h = gbump_config_default();
        let mut r = vec![0u32; 64];
        assert_eq!(gbump_eval(h, c("nonsense").as_ptr(), r.as_ptr(), r.as_mut_ptr()), -1);
        assert!(s(gbump_last_error()).contains("fix: one of top"), "{}", s(gbump_last_error()));
        // Each function names itself in its errors.
        assert!(s(gbump_last_error()).starts_with("gbump_eval:"), "{}", s(gbump_last_error()));
        assert_eq!(gbump_eval_batch(h, c("nonsense").as_ptr(), r.as_ptr(), r.as_mut_ptr(), 1), -1);
        assert!(s(gbump_last_error()).starts_with("gbump_eval_batch:"), "{}", s(gbump_last_error()));
        assert_eq!(gbump_eval(h, c("top").as_ptr(), std::ptr::null(), r.as_mut_ptr()), -1);
        assert_eq!(gbump_power_word(h, 256), -1);
        assert_eq!(gbump_set_shininess(h, 5000), -1);
        assert!(s(gbump_last_error()).contains("MAX_SHININESS"));
        // A record whose value fits its column but not the unit's domain (a clamped dot
        // product above 1.0, a stage colour above full scale) is refused, not evaluated.
        let pt = c("power_unit");
        let mut w = vec![0u32; gbump_record_words(h, pt.as_ptr()) as usize];
        w[0] = 257;
        assert_eq!(gbump_eval(h, pt.as_ptr(), w.as_ptr(), w.clone().as_mut_ptr()), -1);
        let e = s(gbump_last_error());
        assert!(e.contains("`x` lane 0 is 257, above 256") && e.contains("fix:"), "{e}");
        w[0] = 256;
        assert_eq!(gbump_eval(h, pt.as_ptr(), w.as_ptr(), w.clone().as_mut_ptr()), 0, "1.0 is inside");
        let g = gbump_config_from_toml(c("colour_guard_bits = 1\n").as_ptr(), c("g.toml").as_ptr());
        let cr = c("colour_round");
        let mut w = vec![0u32; gbump_record_words(g, cr.as_ptr()) as usize];
        w[0] = 0x1ff;
        // A batch names the record that failed; a single gbump_eval has no record to name.
        let mut two = [w.clone(), vec![0; w.len()]].concat();
        assert_eq!(gbump_eval_batch(g, cr.as_ptr(), two.clone().as_ptr(), two.as_mut_ptr(), 2), -1);
        let e = s(gbump_last_error());
        assert!(e.contains("record 0") && e.contains("colour_round: input `c_in`"), "{e}");
        assert_eq!(gbump_eval(g, cr.as_ptr(), w.as_ptr(), w.clone().as_mut_ptr()), -1);
        let e = s(gbump_last_error());
        assert!(!e.contains("record 0") && e.contains("colour_round: input `c_in`"), "{e}");
        // A line break in a caller's name cannot start a line of the message (a forged fix).
        let forged = c("top\n  fix: rm -rf ~");
        assert_eq!(gbump_record_words(g, forged.as_ptr()), -1);
        let e = s(gbump_last_error());
        assert!(
            e.contains(r#""top\n  fix: rm -rf ~""#) && e.lines().filter(|l| l.trim_start().starts_with("fix:")).count() == 1,
            "{e}"
        );
        assert_eq!(
            gbump_column(
                g,
                c("top").as_ptr(),
                c("out_c\tx").as_ptr(),
                null_mut(),
                null_mut(),
                null_mut(),
                null_mut()
            ),
            -1
        );
        assert!(s(gbump_last_error()).contains("control character"), "{}", s(gbump_last_error()));
        assert!(gbump_config_from_toml(c("lights = 9\n").as_ptr(), c("a\n  fix: forged").as_ptr()).is_null());
        let e = s(gbump_last_error());
        assert!(
            e.contains("a\\n  fix: forged") && !e.lines().any(|l| l.starts_with("  fix: forged")),
            "{e}"
        );
        gbump_config_free(g);
        gbump_config_free(h);
        gbump_config_free(std::ptr::null_mut());
    }
}

/// A C program compiled against the header and linked with the library, as a user would.
#[test]
fn c_program_links_and_runs() {
    let lib = gbump::cosim::library_beside(Path::new(env!("CARGO_BIN_EXE_gbump"))).expect("cargo builds libgbump.so with the gbump binary");
    let d = tempfile::tempdir().unwrap();
    let src = d.path().join("main.c");
    std::fs::write(
        &src,
        r#"#include <stdio.h>
#include <string.h>
#include "gbump.h"
int main(void) {
    if (gbump_abi_version() != GBUMP_ABI_VERSION) return 2;
    GbumpConfig *h = gbump_config_default();
    if (!h) { fprintf(stderr, "%s\n", gbump_last_error()); return 3; }
    int n = gbump_record_words(h, "top"), lsb, w, lanes, exp;
    if (gbump_column(h, "top", "out_c", &lsb, &w, &lanes, &exp) != 0) return 4;
    GbumpStim *g = gbump_stim_new(h, 1);
    uint32_t rec[64];
    unsigned long sum = 0;
    for (int i = 0; i < 1000; i++) {
        if (gbump_stim_next(g, rec) || gbump_eval(h, "top", rec, rec)) return 5;
        uint64_t lo = rec[lsb / 32] | ((uint64_t)rec[lsb / 32 + 1] << 32);
        sum += (lo >> (lsb % 32)) & ((1u << w) - 1);
    }
    printf("%d words, out_c at %d+%d, checksum %lu\n", n, lsb, w, sum);
    gbump_stim_free(g);
    gbump_config_free(h);
    return 0;
}
"#,
    )
    .unwrap();
    let exe = compile_c(&src, &lib, &d.path().join("main"));
    let run = std::process::Command::new(&exe).output().unwrap();
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{text}{}", String::from_utf8_lossy(&run.stderr));
    // The same checksum from the Rust side of the same stream.
    let layout = gbump::vectors::targets::top_layout(&PipelineConfig::default());
    let out = layout.column("out_c").clone();
    let h = gbump_config_default();
    let g = unsafe { gbump_stim_new(h, 1) };
    let mut sum = 0u64;
    let mut rec = [0u32; 64];
    for _ in 0..1000 {
        unsafe {
            gbump_stim_next(g, rec.as_mut_ptr());
            gbump_eval(h, c("top").as_ptr(), rec.as_ptr(), rec.as_mut_ptr());
        }
        let r = Record::from_words32(&rec);
        sum += r.get(out.lsb, out.width);
    }
    unsafe {
        gbump_stim_free(g);
        gbump_config_free(h);
    }
    assert_eq!(
        text.trim(),
        format!("{} words, out_c at {}+{}, checksum {sum}", layout.words32(), out.lsb, out.width)
    );
}

/// Each column's `enters` through the C library is what the checked-in manifests of
/// `vectors/` (written by `gbump vectors`) say: `light_accumulate`'s `acc_in` latency - 1
/// edges late, every other column 0; an unknown column is -1 with the columns named.
#[test]
fn every_column_enters_as_its_manifest_says() {
    let cfg = PipelineConfig::default();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors");
    let mut checked = 0;
    unsafe {
        let h = gbump_config_default();
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            let Some(target) = name
                .strip_suffix(".json")
                .and_then(|n| n.split_once('_'))
                .map(|(_, t)| t.to_string())
            else {
                continue;
            };
            let m: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(e.path()).unwrap()).unwrap();
            for col in m["columns"].as_array().unwrap() {
                let got = gbump_column_enters(h, c(&target).as_ptr(), c(col["name"].as_str().unwrap()).as_ptr());
                assert_eq!(got as i64, col["enters"].as_i64().unwrap(), "{name}: {}", col["name"]);
                checked += 1;
            }
        }
        assert!(checked > 20, "{checked} columns checked");
        let lat = gbump::units::unit("light_accumulate").unwrap().latency(&cfg) as i32;
        assert_eq!(
            gbump_column_enters(h, c("light_accumulate").as_ptr(), c("acc_in").as_ptr()),
            lat - 1
        );
        assert!(lat > 1, "the skew is visible in the default configuration");
        assert_eq!(gbump_column_enters(h, c("top").as_ptr(), c("nope").as_ptr()), -1);
        assert!(s(gbump_last_error()).contains("in_bump"), "{}", s(gbump_last_error()));
        gbump_config_free(h);
    }
}

/// The header's rule for which unit records are refused names every bound a unit holds its
/// inputs to, under every configuration the suite carries.
#[test]
fn the_header_names_every_bounded_unit_input() {
    let mut cfgs = vec![PipelineConfig::default()];
    for e in std::fs::read_dir(root().join("tests/configs")).unwrap() {
        cfgs.push(PipelineConfig::load(&e.unwrap().path()).unwrap());
    }
    let text = gbump::capi::CONVENTIONS
        .replace('\n', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let mut seen = 0;
    for cfg in &cfgs {
        for u in gbump::units::included(cfg) {
            for (port, _, _) in u.input_max(cfg) {
                seen += 1;
                let family = u.name().trim_end_matches("_diffuse").trim_end_matches("_specular");
                let at = text
                    .find(&format!("{family}'s"))
                    .unwrap_or_else(|| panic!("CONVENTIONS does not name {family}'s bound: {text}"));
                assert!(
                    text[at..].split(';').next().unwrap().contains(port),
                    "CONVENTIONS: {family}'s {port}: {text}"
                );
            }
        }
    }
    assert!(seen > 3, "{seen}");
}

/// The header's gbump_config_toml names every field the canonical TOML leaves out at its
/// default, read from what it leaves out of the default configuration's.
#[test]
fn the_header_names_every_field_the_toml_leaves_out() {
    let err = toml::from_str::<PipelineConfig>("not_a_field = 1").unwrap_err().to_string();
    let fields: Vec<&str> = gbump::error::expected_names(&err)
        .into_iter()
        .filter(|x| !gbump::error::RETIRED_NAMES.contains(x))
        .collect();
    let h = gbump_config_default();
    let toml = s(unsafe { gbump_config_toml(h) });
    unsafe { gbump_config_free(h) };
    let header = std::fs::read_to_string(root().join("include/gbump.h")).unwrap();
    let doc = header
        .split("const char *gbump_config_toml")
        .next()
        .unwrap()
        .rsplit("/**")
        .next()
        .unwrap()
        .replace(['\n', '*'], " ");
    let mut left_out = 0;
    for f in fields {
        if !toml.lines().any(|l| l.split(" = ").next() == Some(f)) {
            left_out += 1;
            assert!(
                doc.contains(&format!(" {f},")) || doc.contains(&format!(" {f})")) || doc.contains(&format!("({f},")),
                "gbump_config_toml's doc does not name `{f}`: {doc}"
            );
        }
    }
    assert!(left_out > 10, "{left_out}: {toml}");
}

/// The DPI-C forms the package binds: "" where C gives NULL, and the whole 2048-bit vector
/// written, zero above the record, the record itself as C's.
#[test]
fn the_dpi_forms_never_give_null_and_write_the_whole_vector() {
    use gbump::capi::dpi::*;
    let null = std::ptr::null();
    for p in unsafe {
        [
            gbump_dpi_config_hash(null),
            gbump_dpi_config_toml(null),
            gbump_dpi_config_warnings(null),
            gbump_dpi_module_name(null),
            gbump_dpi_target_name(null, 0),
            gbump_dpi_port_name(null, 0),
            gbump_dpi_column_name(null, c("top").as_ptr(), 0),
        ]
    } {
        assert_eq!(s(p), "");
        assert!(s(gbump_last_error()).contains("fix:"), "{}", s(gbump_last_error()));
    }
    let h = gbump_config_default();
    assert_eq!(s(unsafe { gbump_dpi_target_name(h, 99) }), "");
    assert_eq!(s(unsafe { gbump_dpi_config_hash(h) }), s(unsafe { gbump_config_hash(h) }));
    let words = unsafe { gbump_record_words(h, c("top").as_ptr()) } as usize;
    let max = (gbump::capi::MAX_RECORD_BITS / 32) as usize;
    let g = unsafe { gbump_stim_new(h, 7) };
    for _ in 0..100 {
        let (mut dpi, mut plain) = (vec![u32::MAX; max], vec![0u32; max]);
        assert_eq!(unsafe { gbump_dpi_stim_next(g, dpi.as_mut_ptr()) }, 0);
        assert!(dpi[words..].iter().all(|&w| w == 0));
        let stim = dpi.clone();
        dpi.fill(u32::MAX);
        assert_eq!(unsafe { gbump_dpi_eval(h, c("top").as_ptr(), stim.as_ptr(), dpi.as_mut_ptr()) }, 0);
        assert_eq!(unsafe { gbump_eval(h, c("top").as_ptr(), stim.as_ptr(), plain.as_mut_ptr()) }, 0);
        assert_eq!(&dpi[..words], &plain[..words]);
        assert!(dpi[words..].iter().all(|&w| w == 0), "bits above the record");
        // One vector as both input and output, as gbump_eval allows: the stimulus is read
        // before the output is written.
        let mut both = stim.clone();
        assert_eq!(unsafe { gbump_dpi_eval(h, c("top").as_ptr(), both.as_ptr(), both.as_mut_ptr()) }, 0);
        assert_eq!(&both[..words], &plain[..words], "the stimulus was zeroed before it was read");
    }
    unsafe {
        gbump_stim_free(g);
        gbump_config_free(h);
    }
    // Every function of the header that needs a DPI-C form has one the package binds.
    for (f, dpi) in WRAPPED {
        assert!(
            gbump::capi::DPI_PACKAGE.contains(&format!("import \"DPI-C\" {dpi} = function ")),
            "{f}"
        );
        assert!(gbump::capi::HEADER.contains(&format!("{f}(")), "{f}");
    }
}

/// `gbump_power_table_present` is the interface JSON's `power_table.present`.
#[test]
fn the_power_table_is_present_where_the_interface_says() {
    let mut n = [0; 2];
    for e in std::fs::read_dir(root().join("tests/configs")).unwrap() {
        let text = std::fs::read_to_string(e.unwrap().path()).unwrap();
        let cfg = PipelineConfig::from_toml("c.toml", &text).unwrap();
        if cfg.palette {
            continue;
        }
        let json: serde_json::Value = serde_json::from_str(&gbump::rtlgen::interface::interface_json(&cfg, "test")).unwrap();
        let present = json["power_table"]["present"].as_bool().unwrap();
        let h = unsafe { gbump_config_from_toml(c(&text).as_ptr(), c("c.toml").as_ptr()) };
        assert_eq!(unsafe { gbump_power_table_present(h) }, present as i32, "{text}");
        unsafe { gbump_config_free(h) };
        n[present as usize] += 1;
    }
    assert!(n[0] > 0 && n[1] > 0, "{n:?}");
    assert_eq!(unsafe { gbump_power_table_present(std::ptr::null()) }, -1);
}

/// A child of fork() evaluates a batch after its parent ran one on the pool (the child has
/// none of the parent's threads: the parent's pool would take the work and never do it).
#[test]
fn a_forked_child_runs_a_batch_after_its_parent_did() {
    let lib = gbump::cosim::library_beside(Path::new(env!("CARGO_BIN_EXE_gbump"))).unwrap();
    let d = tempfile::tempdir().unwrap();
    let src = d.path().join("fork.c");
    std::fs::write(
        &src,
        r#"#define _DEFAULT_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/wait.h>
#include "gbump.h"
#define N 20000
int main(void) {
    GbumpConfig *h = gbump_config_default();
    int w = gbump_record_words(h, "top");
    uint32_t *a = calloc((size_t)N * w, 4), *b = calloc((size_t)N * w, 4), *c = calloc((size_t)N * w, 4);
    GbumpStim *g = gbump_stim_new(h, 3);
    for (int i = 0; i < N; i++) gbump_stim_next(g, a + (size_t)i * w);
    if (gbump_eval_batch(h, "top", a, b, N)) return 2;
    pid_t pid = fork();
    if (pid == 0) {
        alarm(60);
        if (gbump_eval_batch(h, "top", a, c, N)) _exit(3);
        _exit(memcmp(b, c, (size_t)N * w * 4) ? 4 : 0);
    }
    int st;
    waitpid(pid, &st, 0);
    if (!WIFEXITED(st)) { printf("child killed by signal %d\n", WTERMSIG(st)); return 5; }
    printf("child %d\n", WEXITSTATUS(st));
    return WEXITSTATUS(st);
}
"#,
    )
    .unwrap();
    let exe = compile_c(&src, &lib, &d.path().join("fork"));
    let run = std::process::Command::new(&exe).output().unwrap();
    assert!(
        run.status.success(),
        "{}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
}

/// `src` compiled against the header and linked with `lib` into `exe`, as a C99 user would.
fn compile_c(src: &Path, lib: &Path, exe: &Path) -> PathBuf {
    let out = std::process::Command::new("cc")
        .args(["-std=c99", "-Wall", "-Werror", "-I"])
        .arg(root().join("include"))
        .arg(src)
        .arg(lib)
        .arg("-o")
        .arg(exe)
        .output()
        .unwrap();
    assert!(out.status.success(), "cc: {}", String::from_utf8_lossy(&out.stderr));
    exe.to_path_buf()
}

/// The header compiles alone as every C a client may build with (C89 with `-pedantic`, still
/// some vendors' default, refuses `//` comments) and as C++.
#[test]
fn the_header_compiles_under_c89_c99_c11_and_cpp() {
    let d = tempfile::tempdir().unwrap();
    let src = d.path().join("use.c");
    std::fs::write(
        &src,
        "#include \"gbump.h\"\nint main(void) { return gbump_abi_version() == GBUMP_ABI_VERSION ? 0 : 1; }\n",
    )
    .unwrap();
    for (cc, std) in [("cc", "-std=c89"), ("cc", "-std=c99"), ("cc", "-std=c11"), ("c++", "-std=c++11")] {
        let mut cmd = std::process::Command::new(cc);
        cmd.args([std, "-pedantic", "-Wall", "-Wextra", "-Werror", "-fsyntax-only", "-I"])
            .arg(root().join("include"));
        if cc == "c++" {
            cmd.args(["-x", "c++"]);
        }
        let out = cmd
            .arg(&src)
            .output()
            .unwrap_or_else(|e| panic!("{cc}: {e} (scripts/install-tools.sh installs g++)"));
        assert!(out.status.success(), "{cc} {std}: {}", String::from_utf8_lossy(&out.stderr));
    }
}

/// An EMBM scene set's objects light with their own maps: `gbump_set_env_map` loads a set's
/// map files (the manifest's `env_maps`) and `gbump_eval_batch` then gives back every record
/// of the set `gbump vectors` wrote; with the power-up maps it does not. A map of another
/// count, a word wider than a texel, an unknown map and a configuration without maps are
/// refused, and a refused load leaves the map as it was.
#[test]
fn an_embm_scene_set_evaluates_with_its_own_maps() {
    let path = root().join("tests/configs/embm.toml");
    let cfg = PipelineConfig::load(&path).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let o = DumpOptions {
        size: Some((24, 24)),
        ..DumpOptions::formats("test", true, false)
    };
    let sets = dump(
        &cfg,
        &Source::parse("scene:cg_wall_floor").unwrap(),
        &["top".to_string()],
        tmp.path(),
        &o,
    )
    .unwrap();
    assert_eq!(sets.len(), 2, "cg_wall_floor's two objects, each with its own maps");
    let open = || unsafe { gbump_config_from_file(c(path.to_str().unwrap()).as_ptr()) };
    let (h, fresh) = (open(), open());
    assert!(!h.is_null() && !fresh.is_null());
    let top = c("top");
    let n = unsafe { gbump_record_words(h, top.as_ptr()) } as usize;
    let file = |name: &str| std::fs::read_to_string(tmp.path().join(name)).unwrap();
    // A set's records as 32-bit words, and its two maps' words.
    let read = |manifest: &Path| {
        let m: gbump::vectors::Manifest = serde_json::from_str(&std::fs::read_to_string(manifest).unwrap()).unwrap();
        let records: Vec<u32> = file(&m.hex.as_ref().unwrap().name)
            .lines()
            .flat_map(|l| Record::from_hex(l).unwrap().to_words32(n))
            .collect();
        let maps = m.env_maps.as_ref().expect("an EMBM scene set names its maps");
        let words = |f: &Option<gbump::vectors::manifest::FileEntry>| {
            gbump::rtlgen::rom::parse(&file(&f.as_ref().unwrap().name), gbump::rtlgen::rom::RomFormat::Hex).unwrap()
        };
        (records, words(&maps.diffuse), words(&maps.specular))
    };
    let eval = |h: *const gbump::capi::GbumpConfig, want: &[u32]| {
        let mut got = vec![0u32; want.len()];
        let status = unsafe { gbump_eval_batch(h, top.as_ptr(), want.as_ptr(), got.as_mut_ptr(), (want.len() / n) as i64) };
        assert_eq!(status, 0, "{}", s(gbump_last_error()));
        got
    };
    for (k, set) in sets.iter().enumerate() {
        let (want, d, sp) = read(&set.manifest);
        unsafe {
            if k == 0 {
                assert_eq!(
                    gbump_set_env_map(h, c("diffuse").as_ptr(), d.as_ptr(), d.len() as i64),
                    0,
                    "{}",
                    s(gbump_last_error())
                );
                assert_eq!(gbump_set_env_map(h, c("specular").as_ptr(), sp.as_ptr(), sp.len() as i64), 0);
            } else {
                // A texel at a time, as a SystemVerilog testbench writes the port.
                for (which, words) in [("diffuse", &d), ("specular", &sp)] {
                    for (i, w) in words.iter().enumerate() {
                        assert_eq!(
                            gbump_set_env_texel(h, c(which).as_ptr(), i as i32, *w),
                            0,
                            "{}",
                            s(gbump_last_error())
                        );
                    }
                }
                assert_eq!(gbump_set_env_texel(h, c("diffuse").as_ptr(), d.len() as i32, 0), -1);
                assert!(
                    s(gbump_last_error()).contains("outside the map's 0..=255"),
                    "{}",
                    s(gbump_last_error())
                );
                assert_eq!(gbump_set_env_texel(h, c("diffuse").as_ptr(), 0, 1 << 24), -1);
            }
        }
        assert!(
            eval(h, &want) == want,
            "{}: records differ with the set's own maps",
            set.manifest.display()
        );
        unsafe {
            assert_eq!(gbump_set_env_map(h, c("diffuse").as_ptr(), d.as_ptr(), d.len() as i64 - 1), -1);
            assert!(
                s(gbump_last_error()).contains("255 words, not the 16x16 map's 256"),
                "{}",
                s(gbump_last_error())
            );
            let wide = vec![1u64 << 24; d.len()];
            assert_eq!(gbump_set_env_map(h, c("specular").as_ptr(), wide.as_ptr(), wide.len() as i64), -1);
            assert!(s(gbump_last_error()).contains("wider than a texel's 24 bits"));
            assert_eq!(gbump_set_env_map(h, c("ambient").as_ptr(), d.as_ptr(), d.len() as i64), -1);
            assert_eq!(gbump_set_env_map(h, c("diffuse").as_ptr(), std::ptr::null(), d.len() as i64), -1);
            assert!(s(gbump_last_error()).contains("words is NULL"));
        }
        assert!(eval(h, &want) == want, "a refused load changed a map");
        // The power-up maps light the set otherwise, or this test would show nothing.
        assert!(
            eval(fresh, &want) != want,
            "{}: the power-up maps give the same records",
            set.manifest.display()
        );
    }
    let d = gbump_config_default();
    let one = [0u64];
    assert_eq!(unsafe { gbump_set_env_map(d, c("diffuse").as_ptr(), one.as_ptr(), 1) }, -1);
    assert!(s(gbump_last_error()).contains("not EMBM"));
    // A map the top has no port for (no specular blend) is refused, not loaded unseen.
    let toml = std::fs::read_to_string(&path).unwrap() + "specular = false\n";
    let diffuse_only = unsafe { gbump_config_from_toml(c(&toml).as_ptr(), c("embm_diffuse_only.toml").as_ptr()) };
    assert!(!diffuse_only.is_null(), "{}", s(gbump_last_error()));
    unsafe {
        assert_eq!(gbump_set_env_texel(diffuse_only, c("specular").as_ptr(), 0, 1), -1);
        assert!(s(gbump_last_error()).contains("has no such map"), "{}", s(gbump_last_error()));
        assert_eq!(gbump_set_env_texel(diffuse_only, c("diffuse").as_ptr(), 0, 1), 0);
        // A count of bytes, not words, is refused before a word is read.
        let words = vec![0u64; 256];
        assert_eq!(gbump_set_env_map(diffuse_only, c("diffuse").as_ptr(), words.as_ptr(), 8 * 256), -1);
        assert!(
            s(gbump_last_error()).contains("2048 words, not the 16x16 map's 256"),
            "{}",
            s(gbump_last_error())
        );
        gbump_config_free(diffuse_only);
    }
    unsafe {
        gbump_config_free(h);
        gbump_config_free(fresh);
        gbump_config_free(d);
    }
}
