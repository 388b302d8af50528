//! `gbump fit`: bad or unreachable budgets fail cleanly and write nothing. A whole search takes
//! minutes (`scripts/fit-check.sh` runs one end to end, regression included), so the suite
//! checks the search itself in `fit::search`'s unit test.

use assert_cmd::Command;

fn gbump() -> Command {
    let mut c = Command::cargo_bin("gbump").unwrap();
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn text(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

#[test]
fn bad_and_unreachable_budgets_fail_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit");
    for (budget, want) in [("max<2", "fix: use max<=LSB"), ("max<=0", "fix: loosen the budget")] {
        let o = gbump()
            .args(["fit", "--scene", "flat_artifact", "--no-regress", "--budget", budget, "--out"])
            .arg(&out)
            .assert()
            .failure();
        let t = text(o.get_output());
        assert!(t.contains(want), "{budget}: {t}");
        assert!(!out.exists(), "{budget}: output written");
    }
}
