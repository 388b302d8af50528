//! Lockstep co-simulation for real (`gbump cosim`, Verilator + libgbump through DPI-C, no
//! vector file): zero mismatches on the default and a one-light parallel configuration, and
//! failures for mutant RTLs (one operator flipped in a generated unit; the output gate removed) and for the RTL of
//! another configuration (same ports, truncating instead of rounding), or of one with other
//! ports (refused at start-up, naming the column).

#[path = "common/mutants.rs"]
mod mutants;

use assert_cmd::Command as Gbump;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `gbump ARGS` in one shared work folder (builds are cached per RTL): (success, output).
fn gbump(args: &[&str], work: &Path) -> (bool, String) {
    let out = Gbump::cargo_bin("gbump")
        .unwrap()
        .args(args)
        .args(["--work", work.to_str().unwrap()])
        .output()
        .unwrap();
    let log = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    // The README's exit statuses: 0 for a clean run, 1 for an error or a failed check, 2 for
    // a usage error (clap's message, not gbump's).
    let usage = out.status.code() == Some(2) && !log.contains("gbump: error:");
    assert!(
        matches!(out.status.code(), Some(0 | 1)) || usage,
        "exit status {:?}:\n{log}",
        out.status.code()
    );
    (out.status.success(), log)
}

fn rtl(config: Option<&str>, dir: &Path) {
    // Another configuration's files left from an earlier run would make the folder ambiguous.
    let _ = std::fs::remove_dir_all(dir);
    let mut cmd = Gbump::cargo_bin("gbump").unwrap();
    cmd.args(["rtl", "--out", dir.to_str().unwrap()]);
    if let Some(c) = config {
        cmd.args(["--config", c]);
    }
    assert!(cmd.output().unwrap().status.success());
}

/// The lockstep binary built under `builds` for the RTL folder `rtl`: the build whose source
/// is the one this gbump fills for it (a kept work folder holds builds of older sources for
/// the same folder too).
fn build_for(builds: &Path, rtl: &Path) -> PathBuf {
    let jf = gbump::cosim::interface_file(rtl).unwrap();
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&jf).unwrap()).unwrap();
    let source = format!("{}\n{}", gbump::capi::DPI_PACKAGE, gbump::cosim::tb::fill(&j, &jf, rtl).unwrap());
    std::fs::read_dir(builds)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|d| std::fs::read_to_string(d.join("tb_cosim.sv")).is_ok_and(|t| t == source))
        .map(|d| d.join("tb_cosim"))
        .unwrap_or_else(|| panic!("no build of this source under {}", builds.display()))
}

/// A work folder per test, so the two tests (and their Verilator builds) run side by side.
fn work(name: &str) -> PathBuf {
    let w = root().join("target/test-cosim").join(name);
    std::fs::create_dir_all(&w).unwrap();
    w
}

#[test]
fn cosim_matches_the_model() {
    let w = work("pass");
    let one = root().join("tests/configs/one_light_parallel.toml");
    let one = one.to_str().unwrap();
    // A seed above 2^63 reaches the model whole (the testbench reads it as hexadecimal).
    for args in [
        vec!["cosim", "--random", "3000", "--seed", "18446744073709551557"],
        vec!["cosim", "--config", one, "--random", "3000"],
    ] {
        let (ok, log) = gbump(&args, &w);
        assert!(ok && log.contains("3000 passed, 0 failed"), "gbump {}:\n{log}", args.join(" "));
        assert!(log.contains("3000 fragments"), "{log}");
    }
    let (_, log) = gbump(&["cosim", "--random", "10", "--seed", "18446744073709551557"], &w);
    assert!(log.contains("seed 18446744073709551557, 10 fragments"), "{log}");

    // The one-light RTL against the default model: refused before any fragment (latency,
    // widths).
    let (ok, log) = gbump(
        &[
            "cosim",
            "--rtl",
            w.join(format!("cosim_rtl_{}", gbump::PipelineConfig::load(Path::new(one)).unwrap().hash()))
                .to_str()
                .unwrap(),
            "--random",
            "10",
        ],
        &w,
    );
    assert!(
        !ok && log.contains("another configuration"),
        "one-light RTL against the default model:\n{log}"
    );
}

/// The Verilog file of generated module `module` (its name carries the configuration's
/// hash) in RTL folder `dir`.
fn module_file(dir: &Path, module: &str) -> PathBuf {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| {
            let n = p.file_name().unwrap().to_string_lossy().into_owned();
            n.starts_with(&format!("{module}_")) && n.ends_with(".v")
        })
        .unwrap_or_else(|| panic!("no {module}_*.v in {}", dir.display()))
}

#[test]
fn cosim_catches_mutants() {
    let w = work("mutants");
    // One operator flipped in the default configuration's texture modulation.
    // Fixed folders, rewritten each run: the same bytes at the same path reuse the cached build.
    let d = w.clone();
    let mutant = d.join("mutant");
    rtl(None, &mutant);
    let f = module_file(&mutant, "texture_modulate");
    let v = std::fs::read_to_string(&f).unwrap();
    let flipped = v.replacen("p1 + (p1 >>", "p1 - (p1 >>", 1);
    assert_ne!(v, flipped, "{}: the operator to flip is gone; pick another", f.display());
    std::fs::write(&f, flipped).unwrap();
    let (ok, log) = gbump(&["cosim", "--rtl", mutant.to_str().unwrap(), "--random", "2000"], &w);
    assert!(
        !ok && log.contains("MISMATCH fragment") && log.contains("replay the seed"),
        "mutant passed:\n{log}"
    );
    // The replay the message gives, followed as written, runs this folder's RTL and fails
    // too (replayed through `gbump regress`, which generates its own RTL, it would pass).
    let fix = log
        .lines()
        .find(|l| l.contains("replay the seed as vectors: "))
        .expect("the replay line");
    let (vectors, rest) = fix
        .split_once("replay the seed as vectors: ")
        .unwrap()
        .1
        .split_once(", then ")
        .unwrap();
    let simulate = rest.split(" (the --rtl").next().unwrap();
    let dir = w.join("replay");
    let _ = std::fs::remove_dir_all(&dir);
    let words = |c: &str| shell_words::split(&c.replace("DIR", dir.to_str().unwrap())).unwrap();
    let v = words(vectors);
    assert_eq!(v[0], "gbump", "{fix}");
    let o = Gbump::cargo_bin("gbump").unwrap().args(&v[1..]).output().unwrap();
    assert!(o.status.success(), "{vectors}:\n{}", String::from_utf8_lossy(&o.stderr));
    let f = words(simulate);
    assert_eq!(f[0], "fusesoc", "{fix}");
    // Every path in it is absolute here; fusesoc's build folder goes in the work folder.
    let o = Command::new("fusesoc").args(&f[1..]).current_dir(&w).output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout).to_string() + &String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && out.contains("MISMATCH"),
        "the replay passed on the mutant RTL:\n{simulate}\n{out}"
    );
    // The lockstep binary run alone, as a user's script would, exits 1 on the mismatch.
    let exe = build_for(&w.join("builds"), &std::path::absolute(&mutant).unwrap());
    let cfg_file = w.join(format!("cosim_config_{}.toml", gbump::PipelineConfig::default().hash()));
    let o = std::process::Command::new(&exe)
        .args([format!("+config={}", cfg_file.display()), "+seed=1".into(), "+count=2000".into()])
        .current_dir(&w)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{}:\n{out}", exe.display());
    assert!(out.contains(gbump::rtlgen::testbench::EXIT_MARK), "{out}");

    // Another configuration's RTL with the same ports (truncating where the model rounds) is
    // refused by its interface's hash before anything is built.
    let other = d.join("truncate");
    let cfg = d.join("truncate.toml");
    std::fs::write(&cfg, "rounding = \"truncate\"\n").unwrap();
    rtl(Some(cfg.to_str().unwrap()), &other);
    let (ok, log) = gbump(&["cosim", "--rtl", other.to_str().unwrap(), "--random", "2000"], &w);
    assert!(
        !ok && log.contains("not of the one picked") && log.contains("fix:"),
        "another configuration's RTL passed:\n{log}"
    );

    // The top with its output gate removed: out_c holds the last result while out_valid is
    // low, where the integration notes promise 0 (the other two benches catch it too).
    let ungated = d.join("ungated");
    rtl(None, &ungated);
    let top = module_file(&ungated, "gbump_pipeline");
    let text = std::fs::read_to_string(&top).unwrap();
    std::fs::write(&top, mutants::output_ungated(&text).expect("the output gate")).unwrap();
    let (ok, log) = gbump(&["cosim", "--rtl", ungated.to_str().unwrap(), "--random", "2000"], &w);
    assert!(
        !ok && log.contains("MISMATCH: out_c is not 0 while out_valid is low"),
        "the ungated top passed:\n{log}"
    );
}

/// Verilator's runtime objects are compiled once into the shared cache (`GBUMP_CACHE`) and
/// taken from it by the next build; a damaged entry is compiled again, never linked.
#[test]
fn verilators_runtime_objects_come_from_the_shared_cache() {
    use gbump::sim::verilator_runtime::RUNTIME_RECORD;
    let tmp = tempfile::tempdir().unwrap();
    let cache = tmp.path().join("cache");
    let run = |work: &str| {
        let work = tmp.path().join(work);
        let out = Gbump::cargo_bin("gbump")
            .unwrap()
            .env("GBUMP_CACHE", &cache)
            .args([
                "cosim",
                "--config",
                "tests/configs/one_light_parallel.toml",
                "--random",
                "300",
                "--work",
            ])
            .arg(&work)
            .current_dir(root())
            .output()
            .unwrap();
        let log = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        assert!(out.status.success(), "{log}");
        let builds = work.join("builds");
        let b = std::fs::read_dir(&builds)
            .unwrap()
            .flatten()
            .find(|e| e.path().join(RUNTIME_RECORD).exists())
            .unwrap_or_else(|| panic!("no build with {RUNTIME_RECORD} in {}", builds.display()));
        let text = std::fs::read_to_string(b.path().join(RUNTIME_RECORD)).unwrap();
        text.lines()
            .map(|l| l.split(' ').map(str::to_string).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    };
    let first = run("w1");
    assert!(first.len() >= 2 && first.iter().any(|l| l[0] == "verilated.o"), "{first:?}");
    assert!(
        first.iter().all(|l| l[1] == "compiled"),
        "an empty cache compiles everything: {first:?}"
    );
    // Damage one entry: it is compiled again; the others are taken.
    let damaged = &first[0];
    std::fs::write(Path::new(&damaged[2]).join(&damaged[0]), b"not an object").unwrap();
    let second = run("w2");
    for l in &second {
        let want = if l[0] == damaged[0] { "compiled" } else { "cached" };
        assert_eq!(l[1], want, "{second:?}");
    }
    assert_eq!(second.len(), first.len());
    // Garbage that its entry's digest vouches for (the digest rewritten): the build does not
    // link, so every runtime object is compiled again and the entries are replaced.
    let bad = Path::new(&second[0][2]);
    let obj = bad.join(&second[0][0]);
    std::fs::write(&obj, b"garbage that is not an object file").unwrap();
    let sum = Command::new("sha256sum").arg(&obj).output().unwrap();
    let digest = String::from_utf8_lossy(&sum.stdout).split_whitespace().next().unwrap().to_string();
    std::fs::write(bad.join(".complete"), format!("{digest}  {}\n", second[0][0])).unwrap();
    let third = run("w3");
    assert!(
        third.iter().all(|l| l[1] == "compiled"),
        "a cached object that does not link is compiled again: {third:?}"
    );
    assert_ne!(
        std::fs::read(&obj).unwrap(),
        b"garbage that is not an object file",
        "the entry is replaced"
    );
}

/// An RTL folder whose interface JSON was edited is refused before anything is built, naming
/// the field: a file name that leads out of the folder (whose contents must not be read, nor
/// echoed), an empty one, a `top` that is not the configuration's module, and a latency.
#[test]
fn an_edited_interface_json_is_refused_by_field() {
    let w = work("edited_json");
    let dir = w.join("rtl");
    rtl(None, &dir);
    let jf = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|x| x == "json"))
        .unwrap();
    let original = std::fs::read_to_string(&jf).unwrap();
    let j: serde_json::Value = serde_json::from_str(&original).unwrap();
    let edits: [(&[&str], &str, &str); 4] = [
        (&["files", "filelist"], "/etc/passwd", "files.filelist"),
        (&["power_table", "init_file"], "../elsewhere.hex", "power_table.init_file"),
        (&["files", "filelist"], "", "files.filelist"),
        (&["top"], "gbump_pipeline_deadbeef", "`top`"),
    ];
    for (path, value, says) in edits {
        let mut e = j.clone();
        let mut at = &mut e;
        for k in path {
            at = at.get_mut(*k).unwrap();
        }
        *at = serde_json::Value::String(value.into());
        std::fs::write(&jf, serde_json::to_string_pretty(&e).unwrap()).unwrap();
        let (ok, log) = gbump(&["cosim", "--rtl", dir.to_str().unwrap(), "--random", "10"], &w);
        assert!(!ok && log.contains(says) && log.contains("fix:"), "{value}:\n{log}");
        assert!(!log.contains("root:"), "{value}: a file outside the folder was read:\n{log}");
    }
    // A number the testbench is made from, edited with the hash left alone: refused, naming
    // the field and both values, not simulated into mismatches blamed on the RTL.
    let mut e = j.clone();
    let latency = e["latency_cycles"].as_u64().unwrap();
    e["latency_cycles"] = serde_json::json!(latency - 1);
    std::fs::write(&jf, serde_json::to_string_pretty(&e).unwrap()).unwrap();
    let (ok, log) = gbump(&["cosim", "--rtl", dir.to_str().unwrap(), "--random", "10"], &w);
    assert!(
        !ok && log.contains(&format!("`latency_cycles` is {}", latency - 1))
            && log.contains(&format!("has {latency}"))
            && log.contains("was edited"),
        "{log}"
    );
    std::fs::write(&jf, original).unwrap();
}

/// A damaged Verilog file in a folder of the user's fails the build with the simulator's own
/// lines and a fix that names the file as not what `gbump rtl` wrote, never "a gbump bug".
#[test]
fn a_damaged_verilog_file_is_named_as_not_gbumps() {
    let w = work("damaged_v");
    let dir = w.join("rtl");
    rtl(None, &dir);
    let cfg = gbump::PipelineConfig::default();
    let name = format!("{}.v", gbump::rtlgen::units_v::module_name(&cfg, "light_accumulate"));
    let f = dir.join(&name);
    let text = std::fs::read_to_string(&f).unwrap();
    std::fs::write(&f, &text[..text.len() / 2]).unwrap();
    let (ok, log) = gbump(&["cosim", "--rtl", dir.to_str().unwrap(), "--random", "10"], &w);
    assert!(!ok, "{log}");
    assert!(
        log.contains("is not what `gbump rtl` writes") && log.contains(&name) && !log.contains("gbump bug"),
        "{log}"
    );
}

/// The DPI-C package alone is clean under `verilator --lint-only -Wall`, as a testbench that
/// imports it for a few functions is linted.
#[test]
fn the_dpi_package_lints_clean_under_wall() {
    let out = std::process::Command::new("verilator")
        .args(["--lint-only", "-Wall"])
        .arg(root().join("include/gbump_dpi_pkg.sv"))
        .output()
        .expect("verilator (scripts/install-tools.sh installs it)");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}
