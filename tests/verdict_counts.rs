//! A simulator run is judged by what it checked, not only by its summary line: a testbench
//! (or a simulator stand-in) that reports fewer vectors than the set holds, or the right
//! count without the digest of the set's own records, fails the regression.

use std::os::unix::fs::PermissionsExt;
use std::process::Command;

#[test]
fn a_run_that_checks_fewer_records_than_its_set_fails() {
    // Icarus builds for real; its runtime only prints a clean summary.
    let (ok, text) = regress_with_vvp(&|_| "#!/bin/sh\necho '5 passed, 0 failed'\n".into());
    assert!(!ok, "a run that checked 5 of 200 records passed:\n{text}");
    assert!(text.contains("5 vectors checked, and the set holds 200"), "{text}");
}

/// Runs `gbump regress` on Icarus with `vvp` replaced by `script` (given the real vvp's path),
/// the one-light top's random set of 200 records and its corners; the combined output.
fn regress_with_vvp(script: &dyn Fn(&str) -> String) -> (bool, String) {
    let d = tempfile::tempdir().unwrap();
    let bin = d.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    let real = gbump::tool::on_path("vvp").expect("vvp (scripts/install-tools.sh)");
    let vvp = bin.join("vvp");
    std::fs::write(&vvp, script(&real.display().to_string())).unwrap();
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
        ])
        .args(["--target", "top", "--random-icarus", "200", "--work"])
        .arg(d.path().join("work"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    (o.status.success(), text)
}

/// A stand-in that prints the right count without having read the set (it takes the count
/// from `+count=`) does not pass: it printed no digest of the records it checked.
#[test]
fn a_run_that_prints_the_right_count_without_reading_the_set_fails() {
    let (ok, text) = regress_with_vvp(&|real| {
        format!("#!/bin/bash\ncase \"$1\" in -V|--version) exec '{real}' \"$@\";; esac\nfor a in \"$@\"; do case \"$a\" in +count=*) n=${{a#+count=}};; esac; done\necho \"$n passed, 0 failed\"\n")
    });
    assert!(!ok, "a stand-in that read nothing passed:\n{text}");
    assert!(
        text.contains("printed no digest of the records it checked") && text.contains("fix:"),
        "{text}"
    );
}

/// The real testbench run on another file of the same length (another seed's records, which
/// the RTL gets right as well) does not pass for the set it was meant to run: its digest is
/// not the set's.
#[test]
fn a_run_of_another_file_of_the_same_length_fails() {
    let other = tempfile::tempdir().unwrap();
    let o = Command::new(assert_cmd::cargo::cargo_bin("gbump"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "vectors",
            "--config",
            "tests/configs/one_light_parallel.toml",
            "--source",
            "random:200",
        ])
        .args(["--seed", "2", "--target", "top", "--format", "hex", "--out"])
        .arg(other.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let swap = other.path().join("random200_top.hex");
    let (ok, text) = regress_with_vvp(&|real| {
        format!(
            "#!/bin/bash\nargs=()\nfor a in \"$@\"; do case \"$a\" in +vectors=*random200_top.hex) args+=(\"+vectors={}\");; *) args+=(\"$a\");; esac; done\nexec '{real}' \"${{args[@]}}\"\n",
            swap.display()
        )
    });
    assert!(!ok, "a run of another set's records passed:\n{text}");
    assert!(
        text.contains("the testbench's digest of the records it checked is") && text.contains("it read other records"),
        "{text}"
    );
}
