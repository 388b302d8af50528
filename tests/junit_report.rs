//! `gbump regress --junit`: the XML a CI server reads lands where the path leads (through a
//! symbolic link, which stays a link), says what ran, and a path it could never be written to
//! is refused before the regression spends its time.

use std::process::Command;

fn regress(dir: &std::path::Path, junit: &std::path::Path) -> (bool, String) {
    let o = Command::new(assert_cmd::cargo::cargo_bin("gbump"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
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
        .arg(dir.join("work"))
        .arg("--junit")
        .arg(junit)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    (o.status.success(), text)
}

#[test]
fn junit_lands_through_a_link_and_an_unwritable_path_is_refused_first() {
    let d = tempfile::tempdir().unwrap();
    let real = d.path().join("reports").join("real.xml");
    std::fs::create_dir(real.parent().unwrap()).unwrap();
    let link = d.path().join("junit.xml");
    std::os::unix::fs::symlink("reports/real.xml", &link).unwrap();
    let (ok, text) = regress(d.path(), &link);
    assert!(ok, "{text}");
    assert!(
        std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(),
        "the link was replaced by a file"
    );
    let xml = std::fs::read_to_string(&real).expect("the XML is where the link leads");
    assert!(xml.starts_with("<?xml") && xml.contains("failures=\"0\""), "{xml}");
    assert!(xml.contains("<testcase classname=\"top\""), "{xml}");

    // A folder that is a file: nothing can be written there, so nothing runs.
    let blocker = d.path().join("plain_file");
    std::fs::write(&blocker, "x").unwrap();
    let (ok, text) = regress(d.path(), &blocker.join("out.xml"));
    assert!(!ok, "{text}");
    assert!(text.contains("plain_file") && text.contains("fix:"), "{text}");
    assert!(!text.contains("passed"), "the regression ran before the refusal:\n{text}");
}
