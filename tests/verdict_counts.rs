//! A simulator run is judged by what it checked, not only by its summary line: a testbench
//! (or a simulator stand-in) that reports fewer vectors than the set holds, with no
//! mismatch, fails the regression.

use std::os::unix::fs::PermissionsExt;
use std::process::Command;

#[test]
fn a_run_that_checks_fewer_records_than_its_set_fails() {
    let d = tempfile::tempdir().unwrap();
    let bin = d.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    // Icarus builds for real; its runtime only prints a clean summary.
    let vvp = bin.join("vvp");
    std::fs::write(&vvp, "#!/bin/sh\necho '5 passed, 0 failed'\n").unwrap();
    std::fs::set_permissions(&vvp, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap());
    let o = Command::new(assert_cmd::cargo::cargo_bin("gbump"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("PATH", path)
        .args([
            "regress",
            "--config",
            "tests/configs/one_light_parallel.toml",
            "--sim",
            "icarus",
            "--no-scenes",
            "--target",
            "top",
            "--random-icarus",
            "200",
            "--work",
        ])
        .arg(d.path().join("work"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a run that checked 5 of 200 records passed:\n{text}");
    assert!(text.contains("5 vectors checked, and the set holds 200"), "{text}");
}
