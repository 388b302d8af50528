//! The protocol the interface file documents, checked on the real simulators: latency and
//! initiation interval per vector (a testbench told a wrong number fails), the power table's
//! power-up contents from any folder (a missing init file fails), and sets in a format a
//! simulator's bench cannot read refused before anything is built.

#[path = "common/mutants.rs"]
mod mutants;

use assert_cmd::Command;
use gbump::sim::regress::{write_rtl, Rtl};
use gbump::sim::testbench::{harness_top, tb_top};
use gbump::sim::{Icarus, Outcome, Simulator, Testbench, Verilator};
use gbump::vectors::{dump, verify, DumpOptions, Source};
use gbump::PipelineConfig;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn work(name: &str) -> PathBuf {
    let w = root().join("target/test-protocol").join(name);
    let _ = std::fs::remove_dir_all(&w);
    std::fs::create_dir_all(&w).unwrap();
    w
}

/// Corner vectors of the top (text and binary): (hex, bin) paths.
fn corner_vectors(cfg: &PipelineConfig, dir: &Path) -> (String, String) {
    top_vectors(cfg, dir, Source::Corners(2))
}

/// Vectors of the top from `src` (text and binary): (hex, bin) paths.
fn top_vectors(cfg: &PipelineConfig, dir: &Path, src: Source) -> (String, String) {
    let o = DumpOptions::formats("test", true, true);
    let sets = dump(cfg, &src, &["top".into()], dir, &o).unwrap();
    let (m, d) = verify(&sets[0].manifest).unwrap();
    let f = |e: &Option<gbump::vectors::manifest::FileEntry>| d.join(&e.as_ref().unwrap().name).display().to_string();
    (f(&m.hex), f(&m.bin))
}

fn config(path: Option<&str>) -> PipelineConfig {
    path.map_or_else(PipelineConfig::default, |p| PipelineConfig::load(&root().join(p)).unwrap())
}

fn icarus_top(w: &Path, rtl: &Rtl, tb: &str, hex: &str, extra: &[&str], cwd: &Path) -> gbump::Result<Outcome> {
    // The testbench's module (`tb_top_<hash8>`), as its text declares it.
    let module = tb
        .lines()
        .find_map(|l| l.strip_prefix("module ")?.strip_suffix(';'))
        .expect("a module line");
    let exe = Icarus.build(&w.join("build"), &Testbench::new(module, tb), rtl)?;
    let mut plus = vec![format!("+vectors={hex}"), "+max_errors=5".to_string()];
    plus.extend(extra.iter().map(|s| s.to_string()));
    Icarus.run(&exe, &plus, None, cwd, "icarus")
}

fn harness(w: &Path, cfg: &PipelineConfig, rtl: &Rtl, cpp: &str, bin: &str, extra: &[&str], cwd: &Path) -> gbump::Result<Outcome> {
    let top = gbump::rtlgen::units_v::module_name(cfg, "gbump_pipeline");
    let exe = Verilator.build_harness(&w.join("build"), &top, cpp, rtl)?;
    let mut args = vec!["--vectors".to_string(), bin.to_string(), "--max-errors".into(), "5".into()];
    args.extend(extra.iter().map(|s| s.to_string()));
    Verilator.run(&exe, &args, None, cwd, "verilator")
}

/// Both benches, told the documented numbers, pass (with bubbles); told a latency or an
/// initiation interval one off, they fail on the first vectors with a timing mismatch.
fn timing_is_checked(cfg_path: Option<&str>, name: &str) {
    let cfg = config(cfg_path);
    let w = work(name);
    let rtl = write_rtl(&cfg, &w.join("rtl"), "test").unwrap();
    // Random triangles: fragments back to back within one (the interval binds), and
    // one-fragment triangles back to back (the bank hold binds).
    let (hex, bin) = top_vectors(&cfg, &w.join("vectors"), Source::Random(300));
    let (lat, ii) = (gbump::rtlgen::top::latency(&cfg), cfg.initiation_interval());
    // The interface file states the numbers the benches check.
    let top = gbump::rtlgen::units_v::module_name(&cfg, "gbump_pipeline");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(rtl.dir.join(format!("{top}.json"))).unwrap()).unwrap();
    assert_eq!(json["latency_cycles"], lat);
    assert_eq!(json["initiation_interval"], ii);
    let table = format!("+table={}", rtl.init_file.display());
    let tb = tb_top(&cfg, &rtl);
    let cpp = harness_top(&cfg);
    let (tb_lat, tb_ii) = (format!("localparam LAT = {lat};"), format!("localparam II = {ii};"));
    let (cpp_lat, cpp_ii) = (
        format!("static const long long LATENCY = {lat};"),
        format!("static const long long II = {ii};"),
    );
    assert!(tb.contains(&tb_lat) && tb.contains(&tb_ii) && cpp.contains(&cpp_lat) && cpp.contains(&cpp_ii));
    let ok = icarus_top(&w, &rtl, &tb, &hex, &[&table, "+bubbles=3"], &w).unwrap();
    assert!(ok.failed == 0 && ok.passed > 0, "{}", ok.log);
    let t = rtl.init_file.display().to_string();
    let ok = harness(&w, &cfg, &rtl, &cpp, &bin, &["--bubbles", "3", "--table", &t], &w).unwrap();
    assert!(ok.failed == 0 && ok.passed > 0, "{}", ok.log);
    let mut mutants = vec![(lat + 1, ii), (lat - 1, ii), (lat, ii + 1)];
    if ii > 1 {
        mutants.push((lat, ii - 1));
    }
    for (l, i) in mutants {
        let tbm = tb
            .replace(&tb_lat, &format!("localparam LAT = {l};"))
            .replace(&tb_ii, &format!("localparam II = {i};"));
        let bad = icarus_top(&w, &rtl, &tbm, &hex, &[&table], &w).unwrap();
        assert!(
            bad.failed > 0 && bad.log.contains("timing"),
            "icarus, latency {l}, II {i}:\n{}",
            bad.log
        );
    }
    // The bank hold.
    if let Some(hold) = gbump::rtlgen::top::bank_hold(&cfg) {
        assert_eq!(json["bump_state"]["bank_hold_cycles"], hold);
        let tb_hold = format!("localparam BANK_HOLD = {hold};");
        assert!(tb.contains(&tb_hold) && cpp.contains(&format!("static const long long BANK_HOLD = {hold};")));
        // A hold longer than the RTL's is caught whenever a setup is offered at the bound;
        // a shorter one only when setups really wait. The serial top's setups span n edges
        // each, so in a bench that offers one setup after another the hold never binds: its
        // value is checked by `the_bank_hold_binds_where_the_interface_says` instead.
        let base = icarus_top(&w, &rtl, &tb, &hex, &[&table], &w).unwrap();
        assert!(base.failed == 0 && base.log.contains("triangle setups"), "{}", base.log);
        let waits = !base.log.contains(" 0 edges waited");
        let mut holds = vec![hold + 1];
        if waits {
            holds.push(hold - 1);
        }
        if gbump::rtlgen::top::setup_edges(&cfg) > 1 {
            holds.clear();
        }
        for h in holds {
            let bad = icarus_top(
                &w,
                &rtl,
                &tb.replace(&tb_hold, &format!("localparam BANK_HOLD = {h};")),
                &hex,
                &[&table],
                &w,
            )
            .unwrap();
            assert!(bad.failed > 0 && bad.log.contains("bank"), "icarus, bank hold {h}:\n{}", bad.log);
        }
        if cfg.light_mode == gbump::config::LightMode::Serial {
            assert!(waits, "serial setups wait (for their slot writes):\n{}", base.log);
        }
        // The edges a setup spans (the serial top writes a light slot per edge into its bank
        // RAM): a bench told one more or one fewer fails, in both benches' checks.
        let edges = gbump::rtlgen::top::setup_edges(&cfg);
        assert_eq!(json["bump_state"]["setup_edges"], edges);
        let tb_edges = format!("localparam SETUP_EDGES = {edges};");
        let cpp_edges = format!("static const long long SETUP_EDGES = {edges};");
        assert!(tb.contains(&tb_edges) && cpp.contains(&cpp_edges));
        if edges > 1 {
            for e in [edges - 1, edges + 1] {
                let bad = icarus_top(
                    &w,
                    &rtl,
                    &tb.replace(&tb_edges, &format!("localparam SETUP_EDGES = {e};")),
                    &hex,
                    &[&table],
                    &w,
                )
                .unwrap();
                assert!(bad.failed > 0 && bad.log.contains("setup"), "icarus, setup edges {e}:\n{}", bad.log);
            }
            let bad = harness(
                &w,
                &cfg,
                &rtl,
                &cpp.replace(&cpp_edges, &format!("static const long long SETUP_EDGES = {};", edges + 1)),
                &bin,
                &["--table", &t],
                &w,
            )
            .unwrap();
            assert!(
                bad.failed > 0 && bad.log.contains("setup"),
                "harness, setup edges {}:\n{}",
                edges + 1,
                bad.log
            );
        }
    }
    // The output buffer: with out_ready stalled, in_ready must fall exactly when the untaken
    // results fill it, and results wait; a bench told another depth fails.
    if let Some(d) = gbump::rtlgen::top::output_depth(&cfg) {
        assert_eq!(json["output_buffer_results"], d);
        let tb_d = format!("localparam OUT_DEPTH = {d};");
        assert!(tb.contains(&tb_d) && cpp.contains(&format!("static const size_t OUT_DEPTH = {d};")));
        for stall in ["+stall=5", "+stall=2"] {
            let ok = icarus_top(&w, &rtl, &tb, &hex, &[&table, stall], &w).unwrap();
            assert!(ok.failed == 0 && ok.passed > 0, "{stall}:\n{}", ok.log);
        }
        let ok = harness(&w, &cfg, &rtl, &cpp, &bin, &["--stall", "5", "--table", &t], &w).unwrap();
        assert!(ok.failed == 0 && ok.passed > 0, "stalled harness:\n{}", ok.log);
        // out_ready high one edge in six: the buffer fills even behind a serial top.
        for dd in [d - 1, d + 1] {
            let bad = icarus_top(
                &w,
                &rtl,
                &tb.replace(&tb_d, &format!("localparam OUT_DEPTH = {dd};")),
                &hex,
                &[&table, "+stall=2"],
                &w,
            )
            .unwrap();
            assert!(
                bad.failed > 0 && (bad.log.contains("output buffer") || bad.log.contains("in_ready low")),
                "icarus, output depth {dd}:\n{}",
                bad.log
            );
        }
    }
    // Verilator builds are slower: one latency and one interval mutant.
    for (l, i) in [(lat + 1, ii), (lat, ii + 1)] {
        let m = cpp
            .replace(&cpp_lat, &format!("static const long long LATENCY = {l};"))
            .replace(&cpp_ii, &format!("static const long long II = {i};"));
        let bad = harness(&w, &cfg, &rtl, &m, &bin, &[], &w).unwrap();
        assert!(
            bad.failed > 0 && bad.log.contains("timing"),
            "verilator, latency {l}, II {i}:\n{}",
            bad.log
        );
    }
}

#[test]
fn serial_tops_are_checked_against_their_documented_latency_and_interval() {
    timing_is_checked(None, "serial4");
    timing_is_checked(Some("tests/configs/four_serial_dot10.toml"), "serial4_dot10");
}

#[test]
fn parallel_tops_are_checked_against_their_documented_latency_and_interval() {
    timing_is_checked(Some("tests/configs/one_light_parallel.toml"), "parallel1");
}

#[test]
fn the_power_up_table_loads_from_any_folder_and_a_missing_init_file_fails() {
    let cfg = PipelineConfig::default();
    let w = work("powerup");
    let rtl = write_rtl(&cfg, &w.join("rtl"), "test").unwrap();
    let (hex, bin) = corner_vectors(&cfg, &w.join("vectors"));
    // Nothing loaded through the port, started from another folder.
    let elsewhere = tempfile::tempdir().unwrap();
    let o = icarus_top(&w, &rtl, &tb_top(&cfg, &rtl), &hex, &[], elsewhere.path()).unwrap();
    assert!(o.failed == 0 && o.passed > 0, "{}", o.log);
    let o = harness(&w, &cfg, &rtl, &harness_top(&cfg), &bin, &[], elsewhere.path()).unwrap();
    assert!(o.failed == 0 && o.passed > 0, "{}", o.log);
    // An init file that does not exist: the simulator's warning fails the run.
    let lost = Rtl {
        init_file: w.join("no_such_table.hex"),
        ..rtl.clone()
    };
    let e = icarus_top(&w, &lost, &tb_top(&cfg, &lost), &hex, &[], elsewhere.path())
        .unwrap_err()
        .to_string();
    assert!(e.contains("$readmemh") && e.contains("INIT_FILE"), "{e}");
    let e = harness(&w, &cfg, &lost, &harness_top(&cfg), &bin, &[], elsewhere.path())
        .unwrap_err()
        .to_string();
    assert!(e.to_lowercase().contains("readmem") || e.contains("no_such_table"), "{e}");
}

fn gbump() -> Command {
    let mut c = Command::cargo_bin("gbump").unwrap();
    c.current_dir(root());
    c
}

#[test]
fn a_set_in_a_format_the_bench_cannot_read_is_refused_or_routed_before_building() {
    let w = work("formats");
    for fmt in ["hex", "bin"] {
        gbump()
            .args(["vectors", "--source", "corners", "--target", "top", "--format", fmt, "--out"])
            .arg(w.join(fmt))
            .assert()
            .success();
    }
    // Binary records on Icarus: refused up front, naming the set and both fixes.
    let o = gbump()
        .args(["regress", "--sim", "icarus", "--work"])
        .arg(w.join("work_bin"))
        .arg("--vectors")
        .arg(w.join("bin"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&o.get_output().stderr).into_owned();
    assert!(
        err.contains("only binary") && err.contains("--format") && err.contains("--sim verilator"),
        "{err}"
    );
    assert!(!w.join("work_bin/build").exists(), "something was built before the refusal");
    // Text records on Verilator: the Verilog testbench runs them.
    let o = gbump()
        .args(["regress", "--sim", "verilator", "--work"])
        .arg(w.join("work_hex"))
        .arg("--vectors")
        .arg(w.join("hex"))
        .assert()
        .success();
    let out = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    assert!(out.contains("corners_top") && out.contains(", 0 failing run(s)"), "{out}");
    // The same set from two folders: each run is named by its folder, so the summary and
    // the JUnit report tell them apart.
    let junit = w.join("both.xml");
    let o = gbump()
        .args(["regress", "--sim", "verilator", "--work"])
        .arg(w.join("work_both"))
        .arg("--vectors")
        .arg(w.join("hex"))
        .arg("--vectors")
        .arg(w.join("bin"))
        .arg("--junit")
        .arg(&junit)
        .assert()
        .success();
    let out = String::from_utf8_lossy(&o.get_output().stdout).into_owned();
    assert!(out.contains("hex/corners_top ") && out.contains("bin/corners_top "), "{out}");
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(xml.contains("hex/corners_top") && xml.contains("bin/corners_top"), "{xml}");
}

/// Corner vectors of the top for shininess `n`: (hex, that set's power table).
fn corner_vectors_for(cfg: &PipelineConfig, dir: &Path, n: u32) -> (String, String) {
    let o = DumpOptions {
        shininess: Some(n),
        ..DumpOptions::formats("test", true, false)
    };
    let sets = dump(cfg, &Source::Corners(2), &["top".into()], dir, &o).unwrap();
    let (m, d) = verify(&sets[0].manifest).unwrap();
    (
        d.join(&m.hex.as_ref().unwrap().name).display().to_string(),
        d.join(&m.power_table.name).display().to_string(),
    )
}

/// The documented reset behaviour: nothing is accepted while `rst` is high, and `rst` keeps
/// the table that was written (a set for another shininess passes after a reset that follows
/// the load, and fails without the load, so the check can tell).
fn reset_behaviour(cfg_path: Option<&str>, name: &str) {
    let cfg = config(cfg_path);
    let w = work(name);
    let rtl = write_rtl(&cfg, &w.join("rtl"), "test").unwrap();
    let n = if cfg.shininess == 2 { 3 } else { 2 };
    let (hex, table) = corner_vectors_for(&cfg, &w.join("vectors"), n);
    let tb = tb_top(&cfg, &rtl);
    let table = format!("+table={table}");
    let ok = icarus_top(&w, &rtl, &tb, &hex, &[&table, "+reset_after_load", "+valid_during_reset"], &w).unwrap();
    assert!(ok.failed == 0 && ok.passed > 0, "{}", ok.log);
    let stale = icarus_top(&w, &rtl, &tb, &hex, &[], &w).unwrap();
    assert!(
        stale.failed > 0,
        "the set does not depend on the table, so the check proves nothing"
    );
}

#[test]
fn reset_takes_no_fragment_and_keeps_the_power_table() {
    reset_behaviour(None, "reset_serial");
    reset_behaviour(Some("tests/configs/one_light_parallel.toml"), "reset_parallel");
    // A top whose first valid bit ignores rst takes the fragment offered during reset.
    let cfg = config(Some("tests/configs/one_light_parallel.toml"));
    let w = work("reset_mutant");
    let rtl = write_rtl(&cfg, &w.join("rtl"), "test").unwrap();
    let top = rtl.sources.iter().find(|p| p.to_string_lossy().contains("gbump_pipeline")).unwrap();
    let text = std::fs::read_to_string(top).unwrap();
    let good = "accept_d1 <= rst ? 1'd0 : accept;";
    assert!(text.contains(good), "the top changed: update the mutant");
    std::fs::write(top, text.replace(good, "accept_d1 <= accept;")).unwrap();
    let (hex, _) = corner_vectors_for(&cfg, &w.join("vectors"), cfg.shininess);
    let bad = icarus_top(&w, &rtl, &tb_top(&cfg, &rtl), &hex, &["+valid_during_reset"], &w).unwrap();
    assert!(bad.failed > 0, "a fragment taken during reset went unnoticed:\n{}", bad.log);
}

/// The top's module name, a `reg` (inputs: `rst` and `out_ready` 1, the rest 0) or `wire`
/// per port, and the port connections, for a hand-written bench.
fn top_ports(cfg: &PipelineConfig) -> (String, String, String) {
    let top = gbump::rtlgen::units_v::module_name(cfg, "gbump_pipeline");
    let mut decl = String::new();
    let mut conn = Vec::new();
    for p in gbump::rtlgen::top::port_list(cfg) {
        let kind = if p.dir == gbump::units::Dir::In { "reg" } else { "wire" };
        let init = match (p.dir == gbump::units::Dir::In, p.name.as_str()) {
            (true, "rst") => " = 1'b1".to_string(),
            (true, "out_ready") => " = 1'b1".to_string(),
            (true, _) => format!(" = {}'d0", p.width()),
            _ => String::new(),
        };
        decl += &format!("{kind} [{}:0] {}{init};\n", p.width() - 1, p.name);
        conn.push(format!(".{0}({0})", p.name));
    }
    (top, decl, conn.join(", "))
}

/// A hand-written Icarus bench of `cfg`'s top in work folder `name`: `bench(top, decl, conn)`
/// (from [`top_ports`]) is its source, module `module`; returns its line that starts with
/// `tag` and that line's numbers.
fn directed(cfg: &PipelineConfig, name: &str, module: &str, tag: &str, bench: impl Fn(&str, &str, &str) -> String) -> (String, Vec<i64>) {
    let w = work(name);
    let rtl = write_rtl(cfg, &w.join("rtl"), "test").unwrap();
    let (top, decl, conn) = top_ports(cfg);
    let exe = Icarus
        .build(&w.join("build"), &Testbench::new(module, &bench(&top, &decl, &conn)), &rtl)
        .unwrap();
    let (_, log, _) = Icarus.run_log(&exe, &[], None, &rtl.dir, "vvp").unwrap();
    let line = log.lines().find(|l| l.starts_with(tag)).unwrap_or_else(|| panic!("{log}"));
    let v = line.split_whitespace().filter_map(|t| t.parse().ok()).collect();
    (line.to_string(), v)
}

/// A setup offered while `rst` is high: `tri_ready` stays low through reset, and the setup
/// is taken at the span's last edge counted from the first edge with `rst` low (the
/// integration section's rule). Then a fragment is accepted and `rst` pulsed for one edge
/// before its result is due: the result is discarded (`out_valid` stays low). Last, setups
/// offered while the power table is written are taken (the notes allow a setup during a
/// table load).
fn setup_during_reset(cfg_path: Option<&str>, name: &str) {
    let cfg = config(cfg_path);
    let lat = gbump::rtlgen::top::latency(&cfg);
    let (line, v) = directed(&cfg, name, "tb_rst", "r ", |top, decl, conn| {
        format!(
            "`timescale 1ns / 1ps\nmodule tb_rst;\n{decl}integer cyc = 0, r = -1, t = -1, ready_in_reset = 0, valid_after = 0, load_setup = 0, k;\nalways #5 clk = ~clk;\nalways @(posedge clk) cyc <= cyc + 1;\n{top} dut ({conn});\ninitial begin\n  tri_valid = 1'b1;\n  repeat (4) begin @(negedge clk); ready_in_reset = ready_in_reset | tri_ready; end\n  rst = 1'b0;\n  r = cyc + 1;\n  #1;\n  while (!tri_ready) @(negedge clk);\n  t = cyc + 1;\n  @(negedge clk);\n  tri_valid = 1'b0;\n  in_valid = 1'b1;\n  while (!in_ready) @(negedge clk);\n  @(negedge clk);\n  in_valid = 1'b0;\n  rst = 1'b1;\n  @(negedge clk);\n  rst = 1'b0;\n  for (k = 0; k < {lat} + 8; k = k + 1) begin @(negedge clk); valid_after = valid_after | out_valid; end\n  power_table_we = 1'b1;\n  tri_valid = 1'b1;\n  for (k = 0; k < 16; k = k + 1) begin power_table_waddr = k; #1; if (tri_ready) load_setup = load_setup + 1; @(negedge clk); end\n  power_table_we = 1'b0;\n  tri_valid = 1'b0;\n  $display(\"r %0d t %0d ready_in_reset %0d valid_after %0d load_setup %0d\", r, t, ready_in_reset, valid_after, load_setup);\n  $finish;\nend\ninitial begin #100000 $display(\"FATAL: timeout\"); $finish; end\nendmodule\n"
        )
    });
    let edges = gbump::rtlgen::top::setup_edges(&cfg) as i64;
    assert_eq!(v[2], 0, "{line}: tri_ready rose while rst was high");
    assert_eq!(
        v[1],
        v[0] + edges - 1,
        "{line}: the setup's {edges} edges do not count from the first edge with rst low"
    );
    assert_eq!(v[3], 0, "{line}: a result in flight at a reset came out after it");
    // Setups offered for 16 edges of table writes: each taken as the span allows, so at
    // least 16 / edges of them (the banks are not the table).
    assert!(v[4] >= 16 / edges, "{line}: setups were held off while the power table was written");
}

#[test]
fn a_setup_offered_in_reset_counts_from_its_end_and_a_reset_discards_results() {
    setup_during_reset(None, "rst_setup_serial");
    setup_during_reset(Some("tests/configs/one_light_parallel.toml"), "rst_setup_parallel");
}

/// Two reset rules of the integration notes. A reset ends every bank hold: a fragment is
/// accepted, `rst` pulsed at the next edge, and the first setup after it is taken when its
/// span allows, not a bank hold after that fragment. And at the first edge at which `rst` is
/// sampled high, `out_valid` still shows a result held for `out_ready`; from the next edge on
/// it is low.
fn reset_edges(cfg_path: Option<&str>, name: &str) {
    let cfg = config(cfg_path);
    let (line, v) = directed(&cfg, name, "tb_redge", "a ", |top, decl, conn| {
        format!(
            "`timescale 1ns / 1ps\nmodule tb_redge;\n{decl}integer cyc = 0, a = -1, t = -1, at_edge = -1, after = -1;\nalways #5 clk = ~clk;\nalways @(posedge clk) cyc <= cyc + 1;\n{top} dut ({conn});\ninitial begin\n  repeat (3) @(negedge clk);\n  rst = 1'b0;\n  tri_valid = 1'b1;\n  #1;\n  while (!tri_ready) @(negedge clk);\n  @(negedge clk);\n  tri_valid = 1'b0;\n  in_valid = 1'b1;\n  #1;\n  while (!in_ready) @(negedge clk);\n  a = cyc + 1;\n  @(negedge clk);\n  in_valid = 1'b0;\n  rst = 1'b1;\n  @(negedge clk);\n  rst = 1'b0;\n  tri_valid = 1'b1;\n  #1;\n  while (!tri_ready) @(negedge clk);\n  t = cyc + 1;\n  @(negedge clk);\n  tri_valid = 1'b0;\n  out_ready = 1'b0;\n  in_valid = 1'b1;\n  #1;\n  while (!in_ready) @(negedge clk);\n  @(negedge clk);\n  in_valid = 1'b0;\n  while (!out_valid) @(negedge clk);\n  repeat (3) @(negedge clk);\n  rst = 1'b1;\n  out_ready = 1'b1;\n  at_edge = out_valid;\n  @(negedge clk);\n  after = out_valid;\n  rst = 1'b0;\n  $display(\"a %0d t %0d at_edge %0d after %0d\", a, t, at_edge, after);\n  $finish;\nend\ninitial begin #100000 $display(\"FATAL: timeout\"); $finish; end\nendmodule\n"
        )
    });
    let hold = gbump::rtlgen::top::bank_hold(&cfg).unwrap() as i64;
    let edges = gbump::rtlgen::top::setup_edges(&cfg) as i64;
    let (a, t) = (v[0], v[1]);
    // Offered from a + 2 (a + 1 is the reset edge): taken at its span's last edge.
    assert!(a + hold > a + 1 + edges, "a hold that had not ended would not bind: {line}");
    assert_eq!(t, a + 1 + edges, "{line}: the first setup after a reset waited for a bank hold");
    assert_eq!(v[2], 1, "{line}: out_valid fell before the first reset edge");
    assert_eq!(v[3], 0, "{line}: out_valid stayed high after the first reset edge");
}

/// A reset restarts the span of a setup not yet taken (the integration notes): a setup
/// offered for two edges, then one reset edge, then offered on, is taken at the first edge
/// with `rst` low + setup_edges - 1, as if first offered there.
fn reset_restarts_a_setup(cfg_path: Option<&str>, name: &str) {
    let cfg = config(cfg_path);
    let (line, v) = directed(&cfg, name, "tb_rsetup", "r ", |top, decl, conn| {
        format!(
            "`timescale 1ns / 1ps\nmodule tb_rsetup;\n{decl}integer cyc = 0, r = -1, t = -1, early = 0;\nalways #5 clk = ~clk;\nalways @(posedge clk) cyc <= cyc + 1;\n{top} dut ({conn});\ninitial begin\n  repeat (3) @(negedge clk);\n  rst = 1'b0;\n  tri_valid = 1'b1;\n  repeat (2) begin @(negedge clk); early = early | tri_ready; end\n  rst = 1'b1;\n  @(negedge clk);\n  rst = 1'b0;\n  r = cyc + 1;\n  #1;\n  while (!tri_ready) @(negedge clk);\n  t = cyc + 1;\n  @(negedge clk);\n  tri_valid = 1'b0;\n  $display(\"r %0d t %0d early %0d\", r, t, early);\n  $finish;\nend\ninitial begin #100000 $display(\"FATAL: timeout\"); $finish; end\nendmodule\n"
        )
    });
    let edges = gbump::rtlgen::top::setup_edges(&cfg) as i64;
    let (r, t, early) = (v[0], v[1], v[2]);
    if edges > 2 {
        assert_eq!(early, 0, "{line}: the setup was taken before the reset");
    }
    assert_eq!(
        t,
        r + edges - 1,
        "{line}: a setup offered before a reset counted edges from before it"
    );
}

/// Why the integration notes say to hold `in_valid` low while a setup is pending: `in_ready`
/// does not look at it, so a triangle's fragment offered beside its setup enters first, or
/// at the setup's own edge, and belongs to the previous triangle. If the top ever gated
/// `in_ready` with a pending setup, this fails and the notes' rule can go.
fn a_fragment_beside_its_setup_enters_first(cfg_path: Option<&str>, name: &str) {
    let cfg = config(cfg_path);
    let (line, v) = directed(&cfg, name, "tb_beside", "t ", |top, decl, conn| {
        format!(
            "`timescale 1ns / 1ps\nmodule tb_beside;\n{decl}integer cyc = 0, t = -1, f = -1;\nalways #5 clk = ~clk;\nalways @(posedge clk) cyc <= cyc + 1;\n{top} dut ({conn});\ninitial begin\n  repeat (3) @(negedge clk);\n  rst = 1'b0;\n  tri_valid = 1'b1;\n  #1;\n  while (!tri_ready) @(negedge clk);\n  @(negedge clk);\n  tri_valid = 1'b0;\n  in_valid = 1'b1;\n  #1;\n  while (!in_ready) @(negedge clk);\n  @(negedge clk);\n  in_valid = 1'b0;\n  repeat (40) @(negedge clk);\n  tri_valid = 1'b1;\n  in_valid = 1'b1;\n  fork\n    begin #1; while (!tri_ready) @(negedge clk); t = cyc + 1; @(negedge clk); tri_valid = 1'b0; end\n    begin #1; while (!in_ready) @(negedge clk); f = cyc + 1; @(negedge clk); in_valid = 1'b0; end\n  join\n  $display(\"t %0d f %0d\", t, f);\n  $finish;\nend\ninitial begin #100000 $display(\"FATAL: timeout\"); $finish; end\nendmodule\n"
        )
    });
    let (t, f) = (v[0], v[1]);
    assert!(t > 0 && f > 0, "{line}: the setup or the fragment was never taken");
    assert!(
        f <= t,
        "{line}: the fragment waited for its setup (in_ready now looks at tri_valid: update the integration notes)"
    );
}

#[test]
fn a_fragment_offered_beside_its_setup_enters_first() {
    a_fragment_beside_its_setup_enters_first(None, "beside_serial");
    a_fragment_beside_its_setup_enters_first(Some("tests/configs/one_light_parallel.toml"), "beside_parallel");
}

#[test]
fn a_reset_restarts_a_setup_not_yet_taken() {
    reset_restarts_a_setup(None, "rst_restart_serial");
    reset_restarts_a_setup(Some("tests/configs/three_banks_serial.toml"), "rst_restart_serial3");
}

#[test]
fn a_reset_ends_bank_holds_and_its_first_edge_still_shows_the_output() {
    reset_edges(None, "reset_edges_serial");
    reset_edges(Some("tests/configs/one_light_parallel.toml"), "reset_edges_parallel");
}

/// Setup A, then fragment A offered together with setup B (B is taken after A's fragment, so
/// that fragment keeps A's bank), then setup C, which loads A's bank again, offered from the
/// edge after B's accept. C must be taken exactly at max(A's accept + bank hold, C's first
/// offer + setup edges - 1), the interface's numbers, and with two banks the hold binds there.
fn bank_hold_binds(cfg_path: Option<&str>, name: &str) {
    let cfg = config(cfg_path);
    assert_eq!(cfg.triangle_banks, 2, "the sequence reuses A's bank with the second setup after it");
    let (line, v) = directed(&cfg, name, "tb_hold", "a ", |top, decl, conn| {
        format!(
            "`timescale 1ns / 1ps\nmodule tb_hold;\n{decl}integer cyc = 0, a = -1, b = -1, c_off = -1, c_acc = -1, idle_any = 0, idle_all = 1;\nalways #5 clk = ~clk;\nalways @(posedge clk) cyc <= cyc + 1;\n{top} dut ({conn});\ninitial begin\n  repeat (3) @(negedge clk);\n  rst = 1'b0;\n  repeat (6) begin @(negedge clk); idle_any = idle_any | tri_ready; idle_all = idle_all & tri_ready; end\n  tri_valid = 1'b1;\n  while (!tri_ready) @(negedge clk);\n  @(negedge clk);\n  in_valid = 1'b1;\n  fork\n    begin\n      while (!in_ready) @(negedge clk);\n      a = cyc + 1;\n      @(negedge clk);\n      in_valid = 1'b0;\n    end\n    begin\n      while (!tri_ready) @(negedge clk);\n      b = cyc + 1;\n      @(negedge clk);\n      c_off = cyc + 1;\n      while (!tri_ready) @(negedge clk);\n      c_acc = cyc + 1;\n      @(negedge clk);\n      tri_valid = 1'b0;\n    end\n  join\n  $display(\"a %0d b %0d c_off %0d c_acc %0d idle_any %0d idle_all %0d\", a, b, c_off, c_acc, idle_any, idle_all);\n  $finish;\nend\ninitial begin #100000 $display(\"FATAL: timeout\"); $finish; end\nendmodule\n"
        )
    });
    let (a, b, c_off, c_acc) = (v[0], v[1], v[2], v[3]);
    let hold = gbump::rtlgen::top::bank_hold(&cfg).unwrap() as i64;
    let edges = gbump::rtlgen::top::setup_edges(&cfg) as i64;
    // Idle after reset with every bank free: register banks are ready; a setup spanning
    // several edges shows tri_ready only at the edge that takes an offered setup, as the
    // integration section says.
    let (idle_any, idle_all) = (v[4], v[5]);
    if edges > 1 {
        assert_eq!(idle_any, 0, "{line}: tri_ready rose with no setup offered");
    } else {
        assert_eq!(idle_all, 1, "{line}: tri_ready fell while idle with every bank free");
    }
    assert!(b >= a, "setup B was taken before fragment A: {line}");
    assert!(
        a + hold > c_off + edges - 1,
        "the hold does not bind in this sequence: {line}, hold {hold}"
    );
    assert_eq!(
        c_acc,
        a + hold,
        "{line}: setup C must be taken {hold} edges (the bank hold) after fragment A"
    );
}

#[test]
fn the_bank_hold_binds_where_the_interface_says() {
    bank_hold_binds(None, "hold_serial");
    bank_hold_binds(Some("tests/configs/one_light_parallel.toml"), "hold_parallel");
}

/// A top that stops taking setups or fragments (its `tri_ready` or `in_ready` tied low) fails
/// every bench with a FATAL line naming the handshake, after the bound the benches wait,
/// rather than hanging the simulator: the file testbench on Icarus, the C++ harness, and the
/// DPI-C lockstep bench (`gbump cosim`). Mismatch stops are out of reach (`max_errors` far
/// above the bound), so the wait's own bound ends each run.
#[test]
fn a_top_that_stops_answering_fails_every_bench_without_hanging() {
    let cfg = config(None);
    assert!(cfg.per_triangle(), "the default top takes triangle setups");
    let w = work("stops_answering");
    let (hex, bin) = top_vectors(&cfg, &w.join("vectors"), Source::Random(50));
    let top = gbump::rtlgen::units_v::module_name(&cfg, "gbump_pipeline");
    for ready in ["tri_ready", "in_ready"] {
        let rtl = write_rtl(&cfg, &w.join(ready), "test").unwrap();
        let f = rtl.dir.join(format!("{top}.v"));
        let text = std::fs::read_to_string(&f).unwrap();
        std::fs::write(&f, mutants::ready_stuck_low(&text, ready).expect("the top assigns the port")).unwrap();
        let many = "+max_errors=1000000";
        let tb = tb_top(&cfg, &rtl);
        let module = tb.lines().find_map(|l| l.strip_prefix("module ")?.strip_suffix(';')).unwrap();
        let exe = Icarus.build(&w.join("build"), &Testbench::new(module, &tb), &rtl).unwrap();
        // The bound the README states: 4 · latency_cycles + 100 edges.
        let wait = 4 * gbump::rtlgen::top::latency(&cfg) + 100;
        let stuck = format!("FATAL: {ready} stayed low for {wait} edges before record 0");
        let log = failure(Icarus.run(&exe, &[format!("+vectors={hex}"), many.into()], None, &w, "icarus"));
        assert!(log.contains(&stuck), "icarus, {ready}:\n{log}");
        let cpp = harness_top(&cfg);
        let exe = Verilator.build_harness(&w.join("build"), &top, &cpp, &rtl).unwrap();
        let log = failure(Verilator.run(
            &exe,
            &["--vectors".into(), bin.clone(), "--max-errors".into(), "1000000".into()],
            None,
            &w,
            "verilator",
        ));
        assert!(log.contains(&stuck), "harness, {ready}:\n{log}");
        let out = gbump()
            .args([
                "cosim",
                "--rtl",
                rtl.dir.to_str().unwrap(),
                "--random",
                "50",
                "--max-errors",
                "1000000",
            ])
            .args(["--work", w.join("cosim").to_str().unwrap()])
            .timeout(std::time::Duration::from_secs(600))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(&stuck), "cosim, {ready}:\n{err}");
    }
}

/// The log of a run that must have failed: its mismatches, or the error it gave up with.
fn failure(run: gbump::Result<Outcome>) -> String {
    match run {
        Ok(o) => {
            assert!(o.failed > 0, "the run passed:\n{}", o.log);
            o.log
        }
        Err(e) => e.to_string(),
    }
}
