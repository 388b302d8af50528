//! Commands that run for minutes say what they are doing. Off a terminal (as here) that is
//! one stderr line per finished step, `what: [k/N] step (seconds)`, every k in turn, so a log
//! shows progress; stdout keeps only the results.

use assert_cmd::Command;

fn run(args: &[&str]) -> (String, String) {
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .assert()
        .success();
    let out = o.get_output();
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The steps of job `what` in `stderr`, checked to count 1..=N without gaps; returns N.
fn steps(stderr: &str, what: &str) -> usize {
    let lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with(&format!("{what}: ["))).collect();
    let n = lines.len();
    assert!(n > 0, "no `{what}` progress on stderr:\n{stderr}");
    for (i, l) in lines.iter().enumerate() {
        assert!(
            l.contains(&format!("[{}/{n}]", i + 1)),
            "step {} of {n} out of order: {l}\n{stderr}",
            i + 1
        );
    }
    n
}

#[test]
fn power_space_reports_each_design() {
    let (out, err) = run(&["power-space", "--max-n", "4"]);
    let designs = out.lines().filter(|l| l.starts_with("| ") && !l.starts_with("| design")).count();
    assert_eq!(steps(&err, "power-space u1.8"), designs, "one step per design in the table");
    assert!(!out.contains("power-space u1.8: ["), "progress belongs on stderr");
}

#[test]
fn lint_reports_each_tool_run() {
    let (out, err) = run(&[
        "lint",
        "--config",
        "tests/configs/one_light_parallel.toml",
        "--work",
        "target/test-lint-progress",
    ]);
    assert!(out.contains("clean"), "{out}");
    let n = steps(&err, "lint");
    assert!(err.contains(&format!("[{n}/{n}] yosys synthesis check")), "{err}");
}
