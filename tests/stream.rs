//! Streamed regressions (`gbump regress --stream`): records made in-process and piped into the
//! Verilator C++ harness pass on the default configuration, are byte for byte the records
//! `gbump vectors` writes, give a mutant RTL the same verdict and mismatch lines as the file
//! run of the same seed with the seed and record to replay, and bad requests are refused
//! before anything is built. The work folders are those of `tests/rtl_sim.rs`, so the
//! harness builds are shared (cached by their inputs).

#[path = "common/mutants.rs"]
mod mutants;

use assert_cmd::Command;
use gbump::sim::stream::{build, first_failing_record, run_stream, streams, StreamRun, StreamSource};
use gbump::sim::{Simulator, Verilator};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn gbump(args: &[&str]) -> (bool, String) {
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .current_dir(root())
        .args(args)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
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

#[test]
fn a_streamed_random_regression_passes_on_the_default_config() {
    let (ok, log) = gbump(&[
        "regress",
        "--stream",
        "random:20000",
        "--seed",
        "3",
        "--work",
        "target/test-regress/default",
    ]);
    assert!(ok, "{log}");
    let line = log
        .lines()
        .find(|l| l.starts_with("verilator") && l.contains("stream_random20000_top"))
        .expect(&log);
    let f: Vec<&str> = line.split_whitespace().collect();
    assert_eq!((f[2], f[3]), ("20000", "0"), "{line}");
    assert!(
        log.contains("1 runs, 20000 vectors passed, 0 failed checks, 0 failing run(s)"),
        "{log}"
    );
}

/// A scene streams under the scene's own configuration, as `gbump vectors` writes it, and
/// says so: a streamed and a file regression of one source check the same RTL.
#[test]
fn a_scene_streams_under_its_own_configuration() {
    let own = gbump::scene::Scene::load("torus_caps").unwrap().derive_config().unwrap();
    assert_ne!(own.hash(), gbump::PipelineConfig::default().hash());
    let (ok, log) = gbump(&[
        "regress",
        "--stream",
        "scene:torus_caps",
        "--scene-size",
        "16x16",
        "--work",
        "target/test-regress/scene_stream",
    ]);
    assert!(ok, "{log}");
    assert!(
        log.contains(&format!("targets the scene's own configuration {}", own.hash())),
        "{log}"
    );
    assert!(log.contains(&format!("regress config {}", own.hash())), "{log}");
}

#[test]
fn a_mutant_fails_streamed_as_it_fails_from_the_file_and_names_seed_and_record() {
    // The mutant of tests/rtl_sim.rs (texture modulation's rounding constant one off), in its
    // folder: the same bytes reuse its harness build.
    let cfg = gbump::PipelineConfig::default();
    let work = std::path::absolute(root().join("target/test-stream/mutant")).unwrap();
    let rtl = gbump::sim::regress::write_rtl(&cfg, &work.join("rtl"), "mutant").unwrap();
    let tm = rtl
        .sources
        .iter()
        .find(|p| p.to_string_lossy().contains("texture_modulate"))
        .unwrap();
    let text = std::fs::read_to_string(tm).unwrap();
    std::fs::write(
        tm,
        mutants::texture_rounding(&text).expect("the constant to change is gone; pick another"),
    )
    .unwrap();
    let exe = build(&cfg, &work, &rtl).unwrap();

    let seed = 11;
    let o = gbump::vectors::DumpOptions {
        seed,
        ..gbump::vectors::DumpOptions::formats("test", false, true)
    };
    let vdir = work.join("stream_vectors");
    let set = &gbump::vectors::dump(&cfg, &gbump::vectors::Source::Random(20_000), &["top".into()], &vdir, &o).unwrap()[0];
    let (m, dir) = gbump::vectors::verify(&set.manifest).unwrap();
    let bin = dir.join(&m.bin.as_ref().unwrap().name);
    let table = dir.join(&m.power_table.name);

    // The stream's records are the file's, byte for byte.
    let s = &streams(&cfg, &StreamSource::Random(20_000), seed, None).unwrap()[0];
    let contents = gbump::units::MemoryContents::new(&cfg, cfg.shininess);
    let maker = gbump::vectors::top_records::TopRecords::new(&cfg, contents.view());
    let streamed: Vec<u8> = (0..2).flat_map(|c| s.chunk_bytes(&maker, c).unwrap()).collect();
    assert!(streamed == std::fs::read(&bin).unwrap(), "streamed records differ from the file's");

    let args: Vec<String> = [
        "--vectors",
        bin.to_str().unwrap(),
        "--table",
        table.to_str().unwrap(),
        "--max-errors",
        "5",
    ]
    .iter()
    .map(|a| a.to_string())
    .collect();
    let file = Verilator.run(&exe, &args, None, &work, "file").unwrap();
    let run = StreamRun {
        exe: &exe,
        table: &table,
        cwd: &work,
        max_errors: 5,
        bubbles: 0,
        stall: 0,
        progress: false,
    };
    let streamed = run_stream(&cfg, s, &run).unwrap();
    assert!(file.failed >= 5 && file.log.contains("stopping after 5 mismatches"), "{}", file.log);
    assert_eq!((streamed.passed, streamed.failed), (file.passed, file.failed));
    let mismatches = |log: &str| {
        log.lines()
            .filter(|l| l.starts_with("MISMATCH") || l.starts_with("  "))
            .map(String::from)
            .collect::<Vec<_>>()
    };
    assert_eq!(mismatches(&streamed.log), mismatches(&file.log));

    let k = first_failing_record(&streamed.log).expect("a failing record");
    let hint = s.replay("", Some(k));
    assert!(
        hint.contains(&format!("seed {seed}, record {k}")) && hint.contains(&format!("--source random:20000 --seed {seed}")),
        "{hint}"
    );
    assert!(hint.contains("gbump regress --sim verilator"), "{hint}");
}

/// Every refusal comes before the work folder is made (so before any build), says how to fix
/// it, and exits non-zero.
#[test]
fn bad_stream_requests_are_refused_before_anything_is_built() {
    let work = root().join("target/test-stream/refused");
    let _ = std::fs::remove_dir_all(&work);
    let w = work.to_str().unwrap();
    let max = gbump::limits::MAX_STREAM_VECTORS;
    let too_many = format!("random:{}", max + 1);
    for (args, want) in [
        (vec!["--stream", "random:0"], "MAX_STREAM_VECTORS"),
        (vec!["--stream", &too_many], "MAX_STREAM_VECTORS"),
        (vec!["--stream", "randm:5"], "not a stream source"),
        (vec!["--stream", "random:1e3"], "decimal digits alone"),
        (vec!["--stream", "random:-1"], "decimal digits alone"),
        (vec!["--stream", "random:+5"], "decimal digits alone"),
        (vec!["--stream", "random:18446744073709551616"], "exceeds MAX_STREAM_VECTORS"),
        (vec!["--stream", "exhaustive:dot_clamp"], "not a stream source"),
        (vec!["--stream", "scene:no_such_scene"], "no_such_scene"),
        (vec!["--stream", "random:5", "--sim", "icarus"], "runs on Verilator"),
        (vec!["--stream", "random:5", "--vectors", "x.json"], "cannot be used with"),
    ] {
        let mut a = vec!["regress", "--work", w];
        a.extend(args.iter().copied());
        let (ok, log) = gbump(&a);
        assert!(!ok && log.contains(want), "{a:?}:\n{log}");
        assert!(log.contains("fix:") || log.contains("Usage"), "{a:?}: no fix:\n{log}");
        assert!(!Path::new(&work).exists(), "{a:?} made the work folder");
    }
    let empty = tempfile::tempdir().unwrap();
    let out = Command::cargo_bin("gbump")
        .unwrap()
        .env("PATH", empty.path())
        .args(["regress", "--stream", "random:5", "--work", w])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("verilator is not installed"), "{err}");
    assert!(!Path::new(&work).exists());
}

/// The report's long regression at a small count: the streamed run and the file run of the
/// same records both pass every record, and the report's table holds both. It shares the
/// default configuration's harness build with the streamed test above (same folder, same
/// RTL), holding the folder's lock as `gbump regress` does.
#[test]
fn the_long_regression_runs_streamed_and_from_a_file() {
    let work = Path::new("target/test-regress/default");
    let _lock = gbump::work_lock::WorkLock::acquire(work, "tests/stream.rs long regression").unwrap();
    let cfg = gbump::config::PipelineConfig::default();
    let n = 20_000;
    let runs = gbump::measure::long_run::long_run(&cfg, "", work, n).unwrap();
    assert_eq!(runs.len(), 2);
    for r in &runs {
        assert_eq!((r.outcome.passed, r.outcome.failed), (n, 0), "{}", r.outcome.log);
    }
    assert!(runs[1].prepare > 0.0 && runs[0].prepare == 0.0);
    let md = gbump::measure::long_run::markdown(&cfg, n, &runs);
    assert!(
        md.contains(&format!("--stream random:{n}")) && md.contains("| streamed") && md.contains("| from a file"),
        "{md}"
    );
    assert!(!work.join("long_run_vectors").exists(), "the vector file is removed");
}
