//! A run that fails or is interrupted over an earlier run's output leaves that output whole:
//! the files of one command land together or not at all (`src/commit.rs`).

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use std::time::Duration;

fn gbump() -> Command {
    let mut c = Command::new(assert_cmd::cargo::cargo_bin("gbump"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

/// Every file of `dir` (not hidden ones) with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .filter(|e| e.path().is_file())
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
        .collect()
}

/// Temporary names left in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp"))
        .collect()
}

/// `gbump rtl` that fails on one file (a folder stands at its name) keeps every other file of
/// the earlier RTL as it was, and leaves no temporary file.
#[test]
fn a_failed_rtl_run_keeps_the_earlier_rtl() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("rtl");
    assert!(gbump().args(["rtl", "--out"]).arg(&out).status().unwrap().success());
    let before = snapshot(&out);
    let blocked = before.keys().find(|n| n.starts_with("tb_top_")).unwrap().clone();
    std::fs::remove_file(out.join(&blocked)).unwrap();
    std::fs::create_dir_all(out.join(&blocked).join("inside")).unwrap();
    // The same configuration from a file: the same names, and every header (the command
    // line) would change.
    let cfg = d.path().join("default.toml");
    let text = gbump().arg("config").output().unwrap().stdout;
    std::fs::write(&cfg, text).unwrap();
    let o = gbump().args(["rtl", "--config"]).arg(&cfg).arg("--out").arg(&out).output().unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&blocked) && err.contains("fix:"), "{err}");
    let mut after = snapshot(&out);
    let mut want = before.clone();
    want.remove(&blocked);
    after.retain(|n, _| !n.starts_with('.'));
    assert_eq!(after.keys().collect::<Vec<_>>(), want.keys().collect::<Vec<_>>());
    assert!(after == want, "a file of the earlier RTL changed");
    let hidden = temporaries(&out);
    assert!(hidden.is_empty(), "{hidden:?}");
}

/// `gbump vectors` interrupted (SIGINT) at several moments over an earlier dump: afterwards
/// every manifest in the folder verifies against its files, and all of them are of one run
/// (the earlier seed everywhere, or the new one everywhere).
#[test]
fn an_interrupted_dump_leaves_one_whole_run() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("v");
    let dump = |seed: &str| {
        let mut c = gbump();
        c.args(["vectors", "--source", "random:150000", "--seed", seed, "--out"]).arg(&out);
        c
    };
    assert!(dump("1").status().unwrap().success());
    for (k, ms) in [40u64, 120, 250, 400, 700, 1100].into_iter().enumerate() {
        let seed = (k + 2).to_string();
        let mut child = dump(&seed).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(ms));
        // SAFETY: a plain kill(2) of the child this test started.
        unsafe {
            libc::kill(child.id() as libc::pid_t, libc::SIGINT);
        }
        child.wait().unwrap();
        let mut seeds = std::collections::BTreeSet::new();
        for e in std::fs::read_dir(&out).unwrap().flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "json") {
                let (m, _) = gbump::vectors::verify(&p).unwrap_or_else(|e| panic!("after SIGINT at {ms} ms: {}: {e}", p.display()));
                seeds.insert(m.seed);
            }
        }
        assert_eq!(seeds.len(), 1, "after SIGINT at {ms} ms the folder mixes runs: seeds {seeds:?}");
        let tmp = temporaries(&out);
        assert!(tmp.is_empty(), "after SIGINT at {ms} ms: {tmp:?}");
    }
}

/// A folder standing where a result file goes is refused the same way by every writer, the
/// streamed vector files as the files written whole: the message says to move it (it is an
/// output, so "give the file itself" would be wrong), the run fails, and no file is left.
#[test]
fn a_folder_in_a_results_place_is_refused_alike_by_every_writer() {
    for (args, blocked) in [
        (vec!["vectors", "--source", "corners", "--target", "top"], "corners_top.hex"),
        (vec!["vectors", "--source", "corners", "--target", "top"], "corners_top.json"),
        (vec!["rom", "--shininess", "8"], "power_table_n8_3dc36989.hex"),
    ] {
        let d = tempfile::tempdir().unwrap();
        let out = d.path().join("o");
        std::fs::create_dir_all(out.join(blocked)).unwrap();
        let o = gbump().args(&args).arg("--out").arg(&out).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} with a folder at {blocked}");
        assert!(
            err.contains(blocked) && err.contains("is a folder, where this run writes a file") && err.contains("move the folder away"),
            "{args:?}, {blocked}: {err}"
        );
        let left: Vec<_> = std::fs::read_dir(&out).unwrap().flatten().map(|e| e.file_name()).collect();
        assert_eq!(left, vec![std::ffi::OsString::from(blocked)], "{args:?}");
    }
}

/// A vector file that is a symbolic link is written through to its target, and the set's
/// manifest still names the file by the set's own name (the link), so the set verifies.
#[test]
fn a_vector_file_behind_a_symbolic_link_keeps_its_name_in_the_manifest() {
    let d = tempfile::tempdir().unwrap();
    let (vs, other) = (d.path().join("vs"), d.path().join("other"));
    std::fs::create_dir_all(&vs).unwrap();
    std::fs::create_dir_all(&other).unwrap();
    std::os::unix::fs::symlink("../other/elsewhere.hex", vs.join("random10_top.hex")).unwrap();
    let o = gbump()
        .args(["vectors", "--source", "random:10", "--target", "top", "--format", "hex", "--out"])
        .arg(&vs)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(vs.join("random10_top.json")).unwrap()).unwrap();
    assert_eq!(m["hex"]["name"], "random10_top.hex", "{m}");
    assert!(std::fs::symlink_metadata(vs.join("random10_top.hex"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read_to_string(other.join("elsewhere.hex")).unwrap().lines().count(), 10);
    let (man, _) = gbump::vectors::verify(&vs.join("random10_top.json")).unwrap();
    assert_eq!(man.count, 10);
}

/// A run killed (SIGKILL, no cleanup) at each rename of its commit in turn leaves the folder
/// for the next run in it to put back whole: the set there afterwards is one run's, every
/// file matching its manifest, and no backup or journal is left. strace injects the kill at
/// the k-th rename (scripts/install-tools.sh installs it).
#[test]
fn a_run_killed_between_its_renames_is_undone_by_the_next() {
    assert!(
        gbump::tool::on_path("strace").is_some(),
        "strace is missing: run scripts/install-tools.sh"
    );
    let exe = assert_cmd::cargo::cargo_bin("gbump");
    let mut killed = 0;
    for k in 1..=6 {
        let d = tempfile::tempdir().unwrap();
        let out = d.path().join("v");
        let dump = |seed: &'static str| {
            vec![
                "vectors",
                "--source",
                "random:1000",
                "--seed",
                seed,
                "--target",
                "top",
                "--format",
                "both",
                "--out",
            ]
        };
        assert!(gbump().args(dump("1")).arg(&out).status().unwrap().success());
        let inject = format!("inject=rename,renameat,renameat2:signal=SIGKILL:when={k}");
        let s = Command::new("strace")
            .args(["-f", "-o", "/dev/null", "-e", "trace=rename,renameat,renameat2", "-e", &inject])
            .arg(&exe)
            .args(dump("2"))
            .arg(&out)
            .output()
            .unwrap();
        killed += !s.status.success() as usize;
        // The next run writing into the folder: another set beside it.
        assert!(gbump()
            .args(["vectors", "--source", "random:10", "--target", "top", "--out"])
            .arg(&out)
            .status()
            .unwrap()
            .success());
        let manifest = out.join("random1000_top.json");
        let verified = gbump::vectors::verify(&manifest);
        assert!(verified.is_ok(), "kill at rename {k}: {:?}", verified.err().map(|e| e.to_string()));
        let left: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(".gbump"))
            .collect();
        assert!(left.is_empty(), "kill at rename {k}: left {left:?}");
    }
    assert!(killed >= 3, "only {killed} of the runs were killed: the renames were not reached");
}
