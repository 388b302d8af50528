//! The integration kit gbump writes beside the RTL, used the way a designer would, from folders
//! other than the RTL's: the filelists with Verilator, Icarus and Yosys; the FuseSoC core on
//! Icarus and Verilator (real `fusesoc`); the SystemVerilog package with Verilator and Icarus;
//! the cocotb example on two configurations (and a mutant RTL it must reject); ROM file names.

#[path = "common/mutants.rs"]
mod mutants;

use assert_cmd::Command as Gbump;
use gbump::rtlgen::kit;
use gbump::rtlgen::units_v::module_name;
use gbump::PipelineConfig;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A tool the test needs: missing is a failure that names the fix, never a skip.
fn need(tool: &str) {
    let found = std::env::var_os("PATH").is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(tool).is_file()));
    assert!(found, "{tool} is not installed: run scripts/install-tools.sh");
}

fn gbump(args: &[&str]) {
    let out = Gbump::cargo_bin("gbump").unwrap().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "gbump {}:\n{}{}",
        args.join(" "),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Run `cmd` in `cwd`; (success, stdout + stderr).
fn run(cmd: &mut Command, cwd: &Path) -> (bool, String) {
    let out = cmd.current_dir(cwd).output().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    let log = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.success(), log)
}

fn cfg_of(config: Option<&str>) -> PipelineConfig {
    config.map_or_else(PipelineConfig::default, |p| PipelineConfig::load(&root().join(p)).unwrap())
}

/// `gbump rtl` (and the config flag) into `dir`.
fn rtl(config: Option<&str>, dir: &Path) {
    let c = config.map(|p| root().join(p).display().to_string());
    let mut a = vec!["rtl", "--out", dir.to_str().unwrap()];
    if let Some(c) = &c {
        a.extend(["--config", c]);
    }
    gbump(&a);
}

/// `gbump vectors --target top --format hex` of `source` with `shininess`; the manifest path.
fn top_vectors(config: Option<&str>, source: &str, shininess: u32, dir: &Path) -> PathBuf {
    let c = config.map(|p| root().join(p).display().to_string());
    let n = shininess.to_string();
    let mut a = vec![
        "vectors",
        "--source",
        source,
        "--target",
        "top",
        "--format",
        "hex",
        "--shininess",
        &n,
    ];
    a.extend(["--out", dir.to_str().unwrap()]);
    if let Some(c) = &c {
        a.extend(["--config", c]);
    }
    gbump(&a);
    let stem = source.replace(':', "");
    dir.join(format!("{stem}_top.json"))
}

/// The `N passed, N failed` line of a testbench log.
fn passed_failed(log: &str) -> (u64, u64) {
    let line = log
        .lines()
        .rev()
        .find(|l| l.contains(" passed, ") && l.trim_end().ends_with(" failed"))
        .unwrap_or_else(|| panic!("no `N passed, N failed` line in:\n{log}"));
    let nums: Vec<u64> = line
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    let k = nums.len();
    (nums[k - 2], nums[k - 1])
}

#[test]
fn filelists_work_from_any_folder_with_verilator_icarus_and_yosys() {
    for t in ["verilator", "iverilog", "yosys"] {
        need(t);
    }
    let cfg = PipelineConfig::default();
    let top = module_name(&cfg, "gbump_pipeline");
    let tmp = tempfile::tempdir().unwrap();
    rtl(None, &tmp.path().join("ip/rtl"));
    // Another folder, two levels away; the lists are named by relative paths from there.
    let cwd = tmp.path().join("work/a");
    std::fs::create_dir_all(&cwd).unwrap();
    let (f, fi, fy) = kit::filelist_names(&cfg);
    let rel = |n: &str| format!("../../ip/rtl/{n}");
    // Every list names every RTL source and no testbench.
    let srcs: Vec<String> = gbump::rtlgen::sources(&gbump::rtlgen::generate(&cfg, "x"));
    assert!(srcs.len() >= 9 && srcs.contains(&format!("{top}.v")));
    for n in [&f, &fi, &fy] {
        let text = std::fs::read_to_string(tmp.path().join("ip/rtl").join(n)).unwrap();
        assert!(text.contains("do not edit") && text.contains(&cfg.hash()), "{n}: header");
        for s in &srcs {
            assert!(text.contains(s.as_str()), "{n} lacks {s}");
        }
        assert!(!text.contains("tb_top_"), "{n} lists the testbench");
    }
    // Verilator resolves `-F` names against the list.
    let (ok, log) = run(
        Command::new("verilator").args([
            "--lint-only",
            "-Wall",
            &rel(&format!("{top}.vlt")),
            "-F",
            &rel(&f),
            "--top-module",
            &top,
        ]),
        &cwd,
    );
    assert!(ok, "verilator -F from another folder:\n{log}");
    // Icarus resolves `-c` names against its working folder: the plain list fails from here
    // (why Icarus has its own list) and the Icarus list works with GBUMP_RTL set.
    let (ok, _) = run(
        Command::new("iverilog").args(["-g2005", "-s", &top, "-o", "plain.vvp", "-c", &rel(&f)]),
        &cwd,
    );
    assert!(
        !ok,
        "iverilog -c resolved the plain list against the list's folder: the docs are wrong"
    );
    let (ok, log) = run(
        Command::new("iverilog").env(kit::ICARUS_DIR_VAR, "../../ip/rtl").args([
            "-g2005",
            "-Wall",
            "-s",
            &top,
            "-o",
            "top.vvp",
            "-c",
            &rel(&fi),
        ]),
        &cwd,
    );
    assert!(ok && cwd.join("top.vvp").is_file(), "iverilog -c {fi}:\n{log}");
    // Yosys reads every source through the Tcl script, run as a script or from -p.
    let (ok, log) = run(Command::new("yosys").args(["-c", &rel(&fy)]), &cwd);
    assert!(ok, "yosys -c:\n{log}");
    let script = format!("tcl {}; hierarchy -check -top {top}; proc; check -assert", rel(&fy));
    let (ok, log) = run(Command::new("yosys").args(["-p", &script]), &cwd);
    assert!(ok, "yosys -p tcl:\n{log}");
    for s in &srcs {
        assert!(log.contains(&format!("ip/rtl/{s}")), "yosys did not read {s}:\n{log}");
    }
}

/// `fusesoc run` of the generated core from another folder: whether it exited 0, and the
/// testbench's log.
fn fusesoc_run(cwd: &Path, cores: &Path, target: &str, core: &str, plus: &[String]) -> (bool, String) {
    let mut c = Command::new("fusesoc");
    c.arg("--cores-root").arg(cores).args(["run", "--target", target, core]).args(plus);
    run(&mut c, cwd)
}

/// A `fusesoc run` that must pass; its log.
fn fusesoc(cwd: &Path, cores: &Path, target: &str, core: &str, plus: &[String]) -> String {
    let (ok, log) = fusesoc_run(cwd, cores, target, core, plus);
    assert!(ok, "fusesoc run --target {target}:\n{log}");
    log
}

#[test]
fn the_fusesoc_core_runs_the_top_testbench_on_icarus_and_verilator() {
    for t in ["fusesoc", "iverilog", "verilator"] {
        need(t);
    }
    let cfg = PipelineConfig::default();
    let tmp = tempfile::tempdir().unwrap();
    let cores = tmp.path().join("cores/gbump");
    rtl(None, &cores);
    // A shininess other than the power-up table's: the core must load it through the port.
    assert_ne!(cfg.shininess, 40);
    let man = top_vectors(None, "random:400", 40, &tmp.path().join("v"));
    let cwd = tmp.path().join("elsewhere");
    std::fs::create_dir_all(&cwd).unwrap();
    let core = format!("gbump:gbump:{}", module_name(&cfg, "gbump_pipeline"));
    let hex = "../v/random400_top.hex".to_string();
    let table = "../v/random400_top_power_table.hex".to_string();
    assert!(man.is_file());
    // The lint target: Verilator -Wall on the RTL, its waivers and the package (fails on any warning).
    fusesoc(&cwd, Path::new("../cores"), "lint", &core, &[]);
    for target in ["sim_icarus", "sim_verilator"] {
        let log = fusesoc(
            &cwd,
            Path::new("../cores"),
            target,
            &core,
            &[
                format!("--vectors={hex}"),
                "--count=400".into(),
                format!("--table={table}"),
                "--bubbles=7".into(),
            ],
        );
        assert_eq!(passed_failed(&log), (400, 0), "{target}:\n{log}");
    }
    // A file damaged the ways an edit or a copy damages one is refused by line (or by its
    // count) on both simulators, and fusesoc fails: never read as records of another width.
    let text = std::fs::read_to_string(tmp.path().join("v/random400_top.hex")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let edited = |i: usize, l: &str| {
        let mut v: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        v[i] = l.to_string();
        v.join("\n") + "\n"
    };
    let line = lines[4];
    let damaged = [
        ("grown", edited(3, &format!("12 34\n{}", lines[3])), "line 4: 5 characters"),
        ("half", edited(1, &lines[1][..lines[1].len() / 2]), "line 2: 77 characters"),
        (
            "stray",
            edited(4, &format!("{}g{}", &line[..9], &line[10..])),
            "line 5: a character that is not a hex digit",
        ),
        (
            "padded",
            edited(4, &format!(" {}", &line[1..])),
            "line 5: a character that is not a hex digit",
        ),
        ("x", edited(5, &format!("x{}", &lines[5][1..])), "line 6 holds an x, z or ? digit"),
        ("cut", lines[..300].join("\n") + "\n", "holds 300 records, where +count=400"),
        (
            "underscore",
            edited(6, &format!("{}_{}", &lines[6][..20], &lines[6][21..])),
            "line 7: a character that is not a hex digit",
        ),
    ];
    // Blank lines (a trailing one, one between records) are passed over, as $readmemh does.
    std::fs::write(
        tmp.path().join("v/blank.hex"),
        format!("{}\n\n{}\n\n", lines[..200].join("\n"), lines[200..].join("\n")),
    )
    .unwrap();
    for target in ["sim_icarus", "sim_verilator"] {
        let plus = [
            "--vectors=../v/blank.hex".to_string(),
            "--count=400".into(),
            format!("--table={table}"),
        ];
        let log = fusesoc(&cwd, Path::new("../cores"), target, &core, &plus);
        assert_eq!(passed_failed(&log), (400, 0), "{target}, blank lines:\n{log}");
    }
    for (name, body, want) in &damaged {
        std::fs::write(tmp.path().join(format!("v/{name}.hex")), body).unwrap();
        for target in ["sim_icarus", "sim_verilator"] {
            let plus = [
                format!("--vectors=../v/{name}.hex"),
                "--count=400".into(),
                format!("--table={table}"),
            ];
            let (ok, log) = fusesoc_run(&cwd, Path::new("../cores"), target, &core, &plus);
            assert!(!ok && log.contains(want), "{target}, {name} file: wanted `{want}`:\n{log}");
        }
    }
    // Without the table the pipeline runs on its power-up contents (n = 16, INIT_FILE found
    // in the simulator's folder): the n = 40 vectors must fail there, and fusesoc with them.
    for target in ["sim_icarus", "sim_verilator"] {
        let (ok, log) = fusesoc_run(&cwd, Path::new("../cores"), target, &core, &[format!("--vectors={hex}")]);
        let (_, failed) = passed_failed(&log);
        assert!(failed > 0, "{target}: n = 40 vectors passed on the n = 16 power-up table:\n{log}");
        assert!(!ok, "{target}: fusesoc exited 0 on a failing simulation:\n{log}");
    }
    // ... and the power-up table's own shininess passes with nothing loaded.
    top_vectors(None, "random:100", cfg.shininess, &tmp.path().join("v16"));
    let log = fusesoc(
        &cwd,
        Path::new("../cores"),
        "sim_icarus",
        &core,
        &["--vectors=../v16/random100_top.hex".into()],
    );
    assert_eq!(passed_failed(&log), (100, 0), "{log}");
}

/// Every memory the top reads powers up from a file the core copies into the simulator's
/// folder: EMBM's two maps (left out, every result was X) and a palette configuration's
/// palette, each run with nothing loaded; a power table nothing reads is neither copied nor
/// offered as `--table`.
#[test]
fn the_fusesoc_core_copies_every_memorys_power_up_file() {
    use gbump::rtlgen::top::{memory_init_file, power_table_read, read_memories};
    for t in ["fusesoc", "iverilog"] {
        need(t);
    }
    for config in ["tests/configs/embm.toml", "tests/configs/palette_serial.toml"] {
        let cfg = cfg_of(Some(config));
        let tmp = tempfile::tempdir().unwrap();
        let cores = tmp.path().join("cores/gbump");
        rtl(Some(config), &cores);
        let top = module_name(&cfg, "gbump_pipeline");
        let text = std::fs::read_to_string(cores.join(format!("{top}.core"))).unwrap();
        let read = read_memories(&cfg);
        assert!(read.len() >= 2, "{config}: a top with memories besides the table");
        for m in &read {
            let f = memory_init_file(&cfg, m);
            assert!(text.contains(&format!("copyto: {f}}}")), "{config}: {f} not copied:\n{text}");
            assert!(
                text.contains(&format!("  {}:\n", m.init_param)),
                "{config}: no {} parameter",
                m.init_param
            );
        }
        assert_eq!(text.contains("copyto: power_table_"), power_table_read(&cfg), "{config}:\n{text}");
        // A target's Verilog parameters are ones its toplevel declares (Verilator refuses a
        // `-G` of a parameter the design lacks): the testbench's for sim_*, the top's for default.
        let tb = std::fs::read_to_string(cores.join(kit::tb_file_name(&cfg))).unwrap();
        let rtl_top = std::fs::read_to_string(cores.join(format!("{top}.v"))).unwrap();
        let vlog = |name: &str| text.contains(&format!("  {name}:\n    datatype: str\n    paramtype: vlogparam"));
        for line in text.lines().filter(|l| l.trim_start().starts_with("parameters: [")) {
            let list = line.split('[').nth(1).unwrap().trim_end_matches(']');
            for name in list.split(", ").filter(|n| vlog(n)) {
                // The simulation targets' lists hold the plusargs too.
                let toplevel = if list.contains("vectors") { &tb } else { &rtl_top };
                assert!(
                    toplevel.contains(&format!("parameter {name} =")),
                    "{config}: {name} of `{line}` is not its toplevel's"
                );
            }
        }
        assert_eq!(text.contains("--table="), power_table_read(&cfg), "{config}:\n{text}");
        let c = root().join(config).display().to_string();
        let v = tmp.path().join("v");
        gbump(&[
            "vectors",
            "--source",
            "random:300",
            "--target",
            "top",
            "--format",
            "hex",
            "--config",
            &c,
            "--out",
            v.to_str().unwrap(),
        ]);
        let cwd = tmp.path().join("elsewhere");
        std::fs::create_dir_all(&cwd).unwrap();
        let plus = ["--vectors=../v/random300_top.hex".to_string(), "--count=300".into()];
        let log = fusesoc(&cwd, Path::new("../cores"), "sim_icarus", &format!("gbump:gbump:{top}"), &plus);
        assert_eq!(passed_failed(&log), (300, 0), "{config}:\n{log}");
        assert!(!log.contains("Unable to open"), "{config}: a power-up file is missing:\n{log}");
    }
}

/// A record's field from a `$readmemh` line (hex digits, LSB last).
fn hex_field(line: &str, lsb: u32, width: u32) -> String {
    let bits: Vec<u8> = line
        .trim()
        .chars()
        .rev()
        .flat_map(|c| {
            let v = c.to_digit(16).unwrap();
            (0..4).map(move |b| ((v >> b) & 1) as u8)
        })
        .collect();
    let mut digits = String::new();
    for d in (0..width.div_ceil(4)).rev() {
        let mut v = 0;
        for b in 0..4 {
            let i = (lsb + 4 * d + b) as usize;
            if 4 * d + b < width && i < bits.len() {
                v |= (bits[i] as u32) << b;
            }
        }
        digits.push(char::from_digit(v, 16).unwrap());
    }
    digits
}

#[test]
fn the_sv_package_compiles_and_its_record_struct_reads_a_dumped_record() {
    need("verilator");
    need("iverilog");
    for config in [None, Some("tests/configs/one_light_parallel.toml")] {
        let cfg = cfg_of(config);
        let tmp = tempfile::tempdir().unwrap();
        rtl(config, &tmp.path().join("rtl"));
        let man = top_vectors(config, "random:3", cfg.shininess, &tmp.path().join("v"));
        let hex = man.with_file_name("random3_top.hex");
        let pkg = tmp.path().join("rtl").join(kit::package_file_name(&cfg));
        let name = kit::package_name(&cfg);
        let user = tmp.path().join("user.sv");
        std::fs::write(
            &user,
            format!(
                "`timescale 1ns / 1ps\n`default_nettype none\nmodule user;\n    import {name}::*;\n    logic [TOP_RECORD_BITS-1:0] mem [0:2];\n    top_record_t r;\n    initial begin\n        $readmemh(\"{}\", mem);\n        r = mem[1];\n        $display(\"out_c=%h in_bump=%h in_h=%h in_k=%h h01=%h lc02=%h k0=%h lat=%0d ii=%0d\", r.out_c, r.in_bump, r.{p}_h, r.{p}_k, {p}_h_lane(r.{p}_h, 0, 1), {p}_lc_lane(r.{p}_lc, 0, 2), {p}_k_lane(r.{p}_k, 0), LATENCY, INITIATION_INTERVAL);\n        $display(\"reset=%0d buffer=%0d banks=%0d hold=%0d setup=%0d\", RESET_CYCLES, OUTPUT_BUFFER_RESULTS, TRIANGLE_BANKS, BANK_HOLD_CYCLES, SETUP_EDGES);\n    end\nendmodule\n`default_nettype wire\n",
                hex.display(),
                p = if cfg.per_triangle() { "tri" } else { "in" }
            ),
        )
        .unwrap();
        let (ok, log) = run(
            Command::new("verilator").args(["--lint-only", "-Wall", "-sv"]).arg(&pkg),
            tmp.path(),
        );
        assert!(ok, "verilator --lint-only -Wall -sv on the package:\n{log}");
        let (ok, log) = run(
            Command::new("verilator")
                .args(["--lint-only", "-Wall", "-Wno-UNUSEDSIGNAL", "-sv"])
                .arg(&pkg)
                .arg(&user),
            tmp.path(),
        );
        assert!(ok, "verilator, package and user:\n{log}");
        let (ok, log) = run(
            Command::new("iverilog").args(["-g2012", "-o", "u.vvp"]).arg(&pkg).arg(&user),
            tmp.path(),
        );
        assert!(ok, "iverilog -g2012:\n{log}");
        let (ok, log) = run(Command::new("vvp").args(["-n", "u.vvp"]), tmp.path());
        assert!(ok, "{log}");
        // The struct's fields are the manifest's columns.
        let line = std::fs::read_to_string(&hex)
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with("//"))
            .nth(1)
            .unwrap()
            .to_string();
        let l = gbump::vectors::targets::top_layout(&cfg);
        let col = |n: &str| l.column(n).clone();
        let st = |f: &str| gbump::vectors::targets::state_column(&cfg, f);
        let (h, lc, k) = (col(&st("h")), col(&st("lc")), col(&st("k")));
        let lw = |c: &gbump::vectors::layout::Column| c.width / c.lanes;
        let want = format!(
            "out_c={} in_bump={} in_h={} in_k={} h01={} lc02={} k0={} lat={} ii={}",
            hex_field(&line, col("out_c").lsb, col("out_c").width),
            hex_field(&line, col("in_bump").lsb, col("in_bump").width),
            hex_field(&line, h.lsb, h.width),
            hex_field(&line, k.lsb, k.width),
            hex_field(&line, h.lsb + lw(&h), lw(&h)),
            hex_field(&line, lc.lsb + 2 * lw(&lc), lw(&lc)),
            hex_field(&line, k.lsb, lw(&k)),
            gbump::rtlgen::top::latency(&cfg),
            cfg.initiation_interval()
        );
        assert!(
            log.contains(&want),
            "package fields differ from the manifest's columns:\nwant {want}\n{log}"
        );
        // The handshake's numbers are the interface JSON's (0 where it has none or null).
        let json: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(
                tmp.path()
                    .join("rtl")
                    .join(format!("{}.json", gbump::rtlgen::units_v::module_name(&cfg, "gbump_pipeline"))),
            )
            .unwrap(),
        )
        .unwrap();
        let num = |v: &serde_json::Value| v.as_u64().unwrap_or(0);
        let want = format!(
            "reset={} buffer={} banks={} hold={} setup={}",
            num(&json["reset_cycles"]),
            num(&json["output_buffer_results"]),
            num(&json["bump_state"]["banks"]),
            num(&json["bump_state"]["bank_hold_cycles"]),
            num(&json["bump_state"]["setup_edges"])
        );
        assert!(
            log.contains(&want),
            "package timing differs from the interface JSON:\nwant {want}\n{log}"
        );
        assert!(num(&json["reset_cycles"]) > 0 && num(&json["output_buffer_results"]) > 0, "{want}");
    }
}

/// Run the cocotb example (its Makefile, from `cwd`); (success, log).
fn cocotb(cwd: &Path, iface: &Path, man: &Path, table: Option<&Path>) -> (bool, String) {
    let mut c = Command::new("make");
    c.arg("-f").arg(root().join("examples/cocotb/Makefile"));
    c.arg(format!("INTERFACE={}", iface.display()))
        .arg(format!("VECTORS={}", man.display()));
    if let Some(t) = table {
        c.arg(format!("TABLE={}", t.display()));
    }
    run(c.arg("BUBBLES=0.25").arg("SEED=3"), cwd)
}

#[test]
fn the_cocotb_example_passes_on_two_configurations_and_rejects_a_mutant() {
    need("make");
    need("iverilog");
    need("cocotb-config");
    for (config, count) in [(None, 1200), (Some("tests/configs/one_light_parallel.toml"), 2500)] {
        let cfg = cfg_of(config);
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("rtl");
        rtl(config, &dir);
        let iface = dir.join(format!("{}.json", module_name(&cfg, "gbump_pipeline")));
        // Shininess 40 through the load port, from `gbump rom` (the set's own table is the same).
        let man = top_vectors(config, &format!("random:{count}"), 40, &tmp.path().join("v"));
        let c = config.map(|p| root().join(p).display().to_string());
        let rom = tmp.path().join("rom");
        let mut a = vec!["rom", "--shininess", "40", "--out", rom.to_str().unwrap()];
        if let Some(c) = &c {
            a.extend(["--config", c]);
        }
        gbump(&a);
        let table = rom.join(format!("power_table_n40_{}.hex", &cfg.hash()[..8]));
        let cwd = tmp.path().join("cocotb");
        std::fs::create_dir_all(&cwd).unwrap();
        let (ok, log) = cocotb(&cwd, &iface, &man, Some(&table));
        assert!(ok, "cocotb example, config {config:?}:\n{log}");
        assert!(
            log.contains(&format!("{count} passed, 0 failed")) && log.contains("FAIL=0"),
            "{log}"
        );
        // The power-up table is the wrong one for these vectors: caught.
        let (ok, log) = cocotb(
            &cwd,
            &iface,
            &man,
            Some(&dir.join(gbump::rtlgen::units_v::rom_file_name(&cfg, "power_table", "hex"))),
        );
        assert!(!ok && log.contains("MISMATCH"), "n = 16 table passed n = 40 vectors:\n{log}");
        if config.is_none() {
            // A wrong rounding constant in texture_modulate: caught and reported.
            let tm = dir.join(format!("{}.v", module_name(&cfg, "texture_modulate")));
            let text = std::fs::read_to_string(&tm).unwrap();
            std::fs::write(&tm, mutants::texture_rounding(&text).expect("the rounding constant")).unwrap();
            let (ok, log) = cocotb(&cwd, &iface, &man, None);
            assert!(
                !ok && log.contains("MISMATCH") && log.contains("out_c expected"),
                "the mutant passed:\n{log}"
            );
            // The right rounding, and no output gate: out_c shows its last result while
            // out_valid is low.
            std::fs::write(&tm, text).unwrap();
            let top = dir.join(format!("{}.v", module_name(&cfg, "gbump_pipeline")));
            let v = std::fs::read_to_string(&top).unwrap();
            std::fs::write(&top, mutants::output_ungated(&v).expect("the output gate")).unwrap();
            let (ok, log) = cocotb(&cwd, &iface, &man, None);
            assert!(
                !ok && log.contains("out_c is not 0 while out_valid is low"),
                "the ungated top passed:\n{log}"
            );
        }
    }
}

#[test]
fn rom_names_carry_their_parameters_and_the_config_hash() {
    use gbump::cli::ConfigPick;
    let none = ConfigPick { config: None, scene: None };
    let a = PipelineConfig::default();
    let b = PipelineConfig {
        colour_bits: 10,
        ..Default::default()
    };
    let mut all = std::collections::BTreeSet::new();
    for (cfg, pick, n, cube) in [(&a, &none, 16, 32), (&a, &none, 40, 32), (&a, &none, 16, 16), (&b, &none, 16, 32)] {
        let h = &cfg.hash()[..8];
        for (name, _) in rom_files(cfg, pick, Some(n), cube, Path::new("x")).unwrap() {
            if name.starts_with("power_table") {
                assert!(name.starts_with(&format!("power_table_n{n}_{h}.")), "{name}");
            } else if name.starts_with("cube_map") {
                // The same for every configuration: its name carries its size and word format.
                assert!(name.starts_with(&format!("cube_map_{cube}x{cube}x6_rgb8.")), "{name}");
            } else {
                assert!(name.starts_with(&format!("bump_palette_spiral_{h}.")), "{name}");
            }
            all.insert(name);
        }
    }
    // Distinct inputs give distinct power-table and cube-map names; the palette of one config is one file.
    assert_eq!(all.iter().filter(|n| n.starts_with("power_table")).count(), 3 * 3);
    assert_eq!(all.iter().filter(|n| n.starts_with("cube_map")).count(), 2 * 3);
    // A palette from a scene carries the scene's name.
    let scene = ConfigPick {
        config: None,
        scene: Some("torus_caps".into()),
    };
    let cfg = scene.resolve().unwrap();
    let files = rom_files(&cfg, &scene, None, 8, Path::new("x")).unwrap();
    let h = &cfg.hash()[..8];
    assert!(
        files.iter().any(|f| f.0 == format!("bump_palette_torus_caps_{h}.hex")),
        "{:?}",
        files.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
}

/// `gbump rom`'s files for a configuration picked as on the command line.
fn rom_files(
    cfg: &gbump::PipelineConfig,
    pick: &gbump::cli::ConfigPick,
    n: Option<u32>,
    cube: usize,
    out: &std::path::Path,
) -> gbump::Result<Vec<(String, String)>> {
    gbump::rtlgen::rom_files::rom_files(cfg, pick.scene.as_deref(), &pick.args(), n, Some(cube), out)
}

/// Two configurations' kits, testbenches included, compile into one Icarus design: every
/// generated module, the testbench's too, carries its configuration's hash.
#[test]
fn two_configurations_kits_compile_together() {
    need("iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let configs = [None, Some("tests/configs/one_light_parallel.toml")];
    let mut sources = Vec::new();
    let mut tops = Vec::new();
    for (i, c) in configs.iter().enumerate() {
        let dir = tmp.path().join(format!("kit{i}"));
        rtl(*c, &dir);
        let cfg = cfg_of(*c);
        let tb = kit::tb_file_name(&cfg);
        let text = std::fs::read_to_string(dir.join(&tb)).unwrap();
        assert!(
            text.contains(&format!("module {};", kit::tb_module_name(&cfg))),
            "{tb} declares another module"
        );
        tops.push(kit::tb_module_name(&cfg));
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "v") {
                sources.push(p);
            }
        }
    }
    assert_ne!(tops[0], tops[1]);
    let mut cmd = Command::new("iverilog");
    cmd.args(["-g2005", "-o", "both.vvp"]);
    for t in &tops {
        cmd.args(["-s", t]);
    }
    cmd.args(&sources);
    let (ok, log) = run(&mut cmd, tmp.path());
    assert!(ok, "two kits do not compile together:\n{log}");
}

/// Every kept configuration's package compiles on both simulators and holds what its
/// interface JSON lists: each memory's words, address width and power-up parameter, and a
/// lane helper for each data port (the EMBM package once had helpers for ports its top does
/// not have, and compiled nowhere).
#[test]
fn every_package_compiles_and_names_its_tops_memories_and_lanes() {
    need("verilator");
    need("iverilog");
    // Every configuration the suite keeps (each family: EMBM, palettes, frames, power ROM,
    // squaring, per-fragment state, one light in parallel, ...).
    let mut configs: Vec<String> = std::fs::read_dir("tests/configs")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| p.display().to_string())
        .collect();
    configs.sort();
    assert!(configs.len() >= 20, "{configs:?}");
    for config in configs.iter().map(String::as_str) {
        let tmp = tempfile::tempdir().unwrap();
        rtl(Some(config), &tmp.path().join("rtl"));
        let cfg = cfg_of(Some(config));
        let json = tmp.path().join("rtl").join(format!("{}.json", module_name(&cfg, "gbump_pipeline")));
        let pkg = tmp.path().join("rtl").join(kit::package_file_name(&cfg));
        let (ok, log) = run(
            Command::new("verilator").args(["--lint-only", "-Wall", "-sv"]).arg(&pkg),
            tmp.path(),
        );
        assert!(ok, "{config}: verilator:\n{log}");
        // Icarus wants a top module: one that imports the package.
        let user = tmp.path().join("u.sv");
        std::fs::write(&user, format!("module u;\n    import {}::*;\nendmodule\n", kit::package_name(&cfg))).unwrap();
        let (ok, log) = run(
            Command::new("iverilog").args(["-g2012", "-o", "p.vvp"]).arg(&pkg).arg(&user),
            tmp.path(),
        );
        assert!(ok, "{config}: iverilog -g2012:\n{log}");
        let text = std::fs::read_to_string(&pkg).unwrap();
        let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        // EMBM's top and a squaring unit read no power table, though its port stays.
        let read = !cfg.embm() && cfg.power_unit != gbump::config::PowerUnitKind::Squaring;
        assert_eq!(j["power_table"]["present"], read, "{config}");
        assert_eq!(
            text.contains("INIT_FILE = ") && !text.contains("// unused"),
            read,
            "{config}: the package's INIT_FILE"
        );
        for (name, m) in j["memories"].as_object().unwrap() {
            let up = name.to_uppercase();
            for (k, v) in [("WORDS", &m["words"]), ("ADDR_BITS", &m["addr_bits"])] {
                assert!(
                    text.contains(&format!("localparam int {up}_{k} = {v};")),
                    "{config}: {up}_{k} = {v}"
                );
            }
        }
        for (param, p) in j["parameters"].as_object().unwrap() {
            assert!(
                text.contains(&format!("localparam {param} = {};", p["default"])),
                "{config}: {param}"
            );
        }
        for port in j["ports"].as_array().unwrap() {
            let f = &port["field"];
            let data = ["fragment", "triangle", "result"].contains(&port["kind"].as_str().unwrap())
                || (port["kind"] == "load" && f["lanes"].as_u64() > Some(1));
            if data && f["lane_bits"].as_u64() > Some(1) {
                let helper = format!(
                    "function automatic logic [{}:0] {}_lane(",
                    f["lane_bits"].as_u64().unwrap() - 1,
                    port["name"].as_str().unwrap()
                );
                assert!(text.contains(&helper), "{config}: no {helper}");
            }
        }
    }
}

/// The integration notes of every kept configuration state the numbers its interface JSON
/// holds (latency, interval, output buffer, bank hold, setup span), where a reader looks for
/// them: the notes are written per configuration, and a number in one branch of the text
/// could drift from the generator's.
#[test]
fn every_configurations_integration_notes_state_its_interface_numbers() {
    let mut n = 0;
    for e in std::fs::read_dir("tests/configs").unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let cfg = PipelineConfig::load(&p).unwrap();
        let doc = gbump::rtlgen::integration_doc::markdown(&cfg);
        let j: serde_json::Value = serde_json::from_str(&gbump::rtlgen::interface::interface_json(&cfg, "test")).unwrap();
        let name = p.display();
        let lat = &j["latency_cycles"];
        assert!(doc.contains(&format!("(latency {lat})")), "{name}: latency {lat}");
        // `gbump timing --config`: a row per unit the top includes, and the top's latency in
        // the column of the configuration's own depth.
        let timing = gbump::units::timing::config_markdown(&cfg);
        for u in gbump::units::included(&cfg) {
            assert!(
                timing.contains(&format!("| `{}` |", u.name())),
                "{name}: timing has no {} row",
                u.name()
            );
        }
        let header: Vec<&str> = timing.lines().find(|l| l.starts_with("| unit |")).unwrap().split('|').collect();
        let col = header.iter().position(|c| c.contains("(this configuration)")).unwrap();
        let top: Vec<&str> = timing.lines().find(|l| l.starts_with("| top |")).unwrap().split('|').collect();
        assert_eq!(
            top[col].trim(),
            lat.to_string(),
            "{name}: timing's top row against the interface's latency"
        );
        let ii = &j["initiation_interval"];
        assert!(doc.contains(&format!("Initiation interval **{ii}**")), "{name}: interval {ii}");
        if let Some(d) = j["output_buffer_results"].as_u64() {
            assert!(doc.contains(&format!("buffer of **{d}**")), "{name}: buffer {d}");
        }
        let bs = &j["bump_state"];
        if let Some(hold) = bs["bank_hold_cycles"].as_u64() {
            assert!(doc.contains(&format!("from **{hold}**")), "{name}: bank hold {hold}");
        }
        if let Some(e) = bs["setup_edges"].as_u64().filter(|e| *e > 1) {
            assert!(doc.contains(&format!("spans **{e}**")), "{name}: setup span {e}");
        }
        n += 1;
    }
    assert!(n >= 20);
}

/// The interface JSON's `units` are the generated modules' own ports and the vector sets'
/// columns: for every kept configuration, each unit's module declares exactly the ports the
/// JSON lists (name, direction, width at the default parameters), and its stimulus and
/// expected ports are the unit layout's columns (widths, formats, `enters`).
#[test]
fn the_interface_json_describes_each_unit_as_its_module_and_its_vectors_do() {
    let mut configs = vec![PipelineConfig::default()];
    for e in std::fs::read_dir("tests/configs").unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "toml") {
            configs.push(PipelineConfig::load(&p).unwrap());
        }
    }
    let width = |range: &str| -> u64 {
        // `[N:0]` or `[R*K-1:0]` at R = 1.
        let hi = range.trim_start_matches('[').split(':').next().unwrap();
        match hi.strip_prefix("R*") {
            Some(k) => k.trim_end_matches("-1").parse::<u64>().unwrap(),
            None => hi.parse::<u64>().unwrap() + 1,
        }
    };
    for cfg in &configs {
        let files = gbump::rtlgen::generate(cfg, "");
        let j: serde_json::Value = serde_json::from_str(&gbump::rtlgen::interface::interface_json(cfg, "")).unwrap();
        let units = j["units"].as_object().unwrap();
        assert_eq!(units.len(), gbump::units::included(cfg).len(), "{}", cfg.hash());
        for (name, u) in units {
            let module = u["module"].as_str().unwrap();
            let (_, text) = files
                .iter()
                .find(|f| f.0 == format!("{module}.v"))
                .unwrap_or_else(|| panic!("no {module}.v"));
            let at = text.find(&format!("module {module}")).unwrap();
            let header = &text[at..at + text[at..].find(");").unwrap()];
            let mut declared: Vec<(String, String, u64)> = header
                .lines()
                .map(str::trim)
                .filter(|l| l.starts_with("input") || l.starts_with("output"))
                .map(|l| {
                    let l = l.trim_end_matches(',');
                    let dir = if l.starts_with("input") { "in" } else { "out" };
                    let words: Vec<&str> = l.split_whitespace().collect();
                    let range = words.iter().find(|w| w.starts_with('['));
                    (words.last().unwrap().to_string(), dir.to_string(), range.map_or(1, |r| width(r)))
                })
                .collect();
            let mut listed: Vec<(String, String, u64)> = u["ports"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| {
                    (
                        p["name"].as_str().unwrap().into(),
                        p["dir"].as_str().unwrap().into(),
                        p["width"].as_u64().unwrap(),
                    )
                })
                .collect();
            declared.sort();
            listed.sort();
            assert_eq!(declared, listed, "{} unit {name}: the module's ports against the JSON", cfg.hash());
            assert_eq!(u["latency_cycles"], gbump::units::unit(name).unwrap().latency(cfg), "{name}");
            let layout = gbump::vectors::targets::unit_layout(cfg, name);
            let data: Vec<&serde_json::Value> = u["ports"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|p| ["stimulus", "expected"].contains(&p["role"].as_str().unwrap()))
                .collect();
            assert_eq!(data.len(), layout.columns.len(), "{} unit {name}: columns", cfg.hash());
            for (p, c) in data.iter().zip(&layout.columns) {
                assert_eq!(p["name"], c.name.as_str(), "{name}");
                assert_eq!(p["width"], c.width, "{name}.{}", c.name);
                assert_eq!(p["enters"], c.enters, "{name}.{}", c.name);
            }
        }
    }
}
