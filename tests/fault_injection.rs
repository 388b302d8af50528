//! Runs killed with SIGKILL at seeded random moments (the whole process group, as a CI
//! timeout does, or only gbump, as the OOM killer does): the next run in the same folders must
//! give exactly the answer of an undisturbed run and leave no temporary files behind. And two
//! runs sharing a work folder take turns instead of racing.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn gbump() -> Command {
    let mut c = Command::new(assert_cmd::cargo::cargo_bin("gbump"));
    c.current_dir(root()).stdin(Stdio::null());
    c
}

fn fresh(name: &str) -> PathBuf {
    let d = root().join("target/test-faults").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// SplitMix64: the kill moments depend on the seed alone.
fn fraction(seed: u64) -> f64 {
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    0.05 + 0.9 * (z >> 11) as f64 / (1u64 << 53) as f64
}

/// Run to the end: (success, stdout).
fn finish(args: &[String]) -> (bool, String, String) {
    let o = gbump().args(args).output().unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Start `args`, kill it after `after`; `group` kills its children too.
fn kill_after(args: &[String], after: Duration, group: bool) {
    let mut c = gbump();
    c.args(args).stdout(Stdio::null()).stderr(Stdio::null());
    if group {
        c.process_group(0);
    }
    let mut child = c.spawn().unwrap();
    let t0 = Instant::now();
    while t0.elapsed() < after {
        if child.try_wait().unwrap().is_some() {
            return;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    if group {
        let _ = Command::new("kill")
            .args(["-s", "KILL", "--", &format!("-{}", child.id())])
            .status();
    } else {
        let _ = child.kill();
    }
    let _ = child.wait();
    // Orphaned children (a compiler, a linker) may still be writing: let them run out.
    std::thread::sleep(Duration::from_millis(300));
}

/// Every file under `dir` (relative path, bytes), leaving out the lock and build caches.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().display().to_string();
                out.push((rel, std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

fn temporaries(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if name
                .rsplit_once(".tmp")
                .is_some_and(|(_, pid)| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()))
            {
                out.push(e.path().display().to_string());
            } else if e.path().is_dir() {
                stack.push(e.path());
            }
        }
    }
    out
}

/// The run table of `gbump regress` (sim, set, passed, failed), without timings.
fn regress_table(stdout: &str) -> Vec<String> {
    stdout
        .lines()
        .filter(|l| l.starts_with("icarus") || l.starts_with("verilator") || l.starts_with("regress config"))
        .map(|l| l.split_whitespace().take(4).collect::<Vec<_>>().join(" "))
        .collect()
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

#[test]
fn killed_vector_dumps_leave_nothing_wrong_behind() {
    let base = fresh("vectors");
    // One output folder for every run, so the command lines (recorded in the manifests and
    // file headers) are the same and the files must be byte for byte the same.
    let out = base.join("out");
    let mut args = strings(&["vectors", "--source", "random:200000", "--seed", "3", "--out"]);
    args.push(out.display().to_string());
    let t0 = Instant::now();
    let (ok, _, err) = finish(&args);
    assert!(ok, "{err}");
    let took = t0.elapsed();
    let want = files(&out);
    for seed in 1..=3u64 {
        // Odd seeds start from an empty folder; even ones over a complete earlier dump.
        if seed % 2 == 1 {
            std::fs::remove_dir_all(&out).unwrap();
        }
        kill_after(&args, took.mul_f64(fraction(seed)), seed != 3);
        let (ok, _, err) = finish(&args);
        assert!(ok, "seed {seed}: {err}");
        let got = files(&out);
        let names = |v: &[(String, Vec<u8>)]| v.iter().map(|f| f.0.clone()).collect::<Vec<_>>();
        assert_eq!(names(&got), names(&want), "seed {seed}: other files");
        for (g, w) in got.iter().zip(&want) {
            assert!(g.1 == w.1, "seed {seed}: {} differs from an undisturbed dump", g.0);
        }
        assert_eq!(temporaries(&out), Vec::<String>::new(), "seed {seed}");
    }
}

#[test]
fn killed_regressions_are_rerun_to_the_same_answer() {
    let base = fresh("regress");
    // Diffuse only, one light: fewer units for Verilator to build, the same kill-and-rerun path.
    let config = base.join("diffuse.toml");
    std::fs::write(&config, "lights = 1\nlight_mode = \"parallel\"\nspecular = false\n").unwrap();
    let args = |work: &Path| {
        let mut a = strings(&[
            "regress",
            "--config",
            config.to_str().unwrap(),
            "--sim",
            "verilator",
            "--random",
            "20000",
            "--random-icarus",
            "0",
            "--no-scenes",
            "--work",
        ]);
        a.push(work.display().to_string());
        a
    };
    let t0 = Instant::now();
    let (ok, out, err) = finish(&args(&base.join("clean")));
    assert!(ok, "{out}{err}");
    let took = t0.elapsed();
    let want = regress_table(&out);
    assert!(want.len() > 5, "{out}");
    for seed in 1..=2u64 {
        let work = base.join(format!("killed{seed}"));
        kill_after(&args(&work), took.mul_f64(fraction(seed + 10)), seed != 2);
        let (ok, out, err) = finish(&args(&work));
        assert!(ok, "seed {seed}: {out}{err}");
        assert_eq!(regress_table(&out), want, "seed {seed}");
        assert_eq!(temporaries(&work), Vec::<String>::new(), "seed {seed}");
    }
}

#[test]
fn a_killed_sweep_resumes_to_the_same_table() {
    let base = fresh("sweep");
    let space = base.join("space.toml");
    // Diffuse only, on a one-light scene: a smaller top for Yosys, the same resume path.
    std::fs::write(
        &space,
        "scene = \"cg_wall_front\"\n[base]\nlights = 1\nlight_mode = \"parallel\"\nspecular = false\n[grid]\nnormal_bits = [8]\n",
    )
    .unwrap();
    let args = |dir: &Path| {
        let mut a = strings(&["sweep", "--yosys", "--space"]);
        a.push(space.display().to_string());
        a.extend(["--out".into(), dir.join("out").display().to_string()]);
        a.extend(["--work".into(), dir.join("work").display().to_string()]);
        a
    };
    let t0 = Instant::now();
    let (ok, out, err) = finish(&args(&base.join("clean")));
    assert!(ok, "{out}{err}");
    let took = t0.elapsed();
    let want = std::fs::read_to_string(base.join("clean/out/space.csv")).unwrap();
    for seed in 1..=2u64 {
        let dir = base.join(format!("killed{seed}"));
        kill_after(&args(&dir), took.mul_f64(fraction(seed + 20)), true);
        let (ok, out, err) = finish(&args(&dir));
        assert!(ok, "seed {seed}: {out}{err}");
        assert_eq!(std::fs::read_to_string(dir.join("out/space.csv")).unwrap(), want, "seed {seed}");
        assert_eq!(temporaries(&dir), Vec::<String>::new(), "seed {seed}");
    }
}

#[test]
fn two_regressions_in_one_work_folder_take_turns() {
    let work = fresh("shared");
    let mut args = strings(&[
        "regress",
        "--sim",
        "verilator",
        "--random",
        "5000",
        "--random-icarus",
        "0",
        "--no-scenes",
        "--work",
    ]);
    args.push(work.display().to_string());
    let first = gbump().args(&args).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    // Wait until the first run holds the folder.
    let lock = work.join(".gbump.lock");
    let t0 = Instant::now();
    while std::fs::read_to_string(&lock).map_or(true, |s| s.is_empty()) {
        assert!(t0.elapsed() < Duration::from_secs(30), "the first run never took the lock");
        std::thread::sleep(Duration::from_millis(10));
    }
    let (ok2, out2, err2) = finish(&args);
    let o1 = first.wait_with_output().unwrap();
    let out1 = String::from_utf8_lossy(&o1.stdout).into_owned();
    assert!(o1.status.success(), "{out1}{}", String::from_utf8_lossy(&o1.stderr));
    assert!(ok2, "{out2}{err2}");
    assert!(err2.contains("waiting for") && err2.contains("gbump regress"), "{err2}");
    assert_eq!(regress_table(&out1), regress_table(&out2));
}
