//! `gbump regress --junit`: the XML a CI server reads lands where the path leads (through a
//! symbolic link, which stays a link), says what ran, and a path it could never be written to
//! is refused before the regression spends its time.

use std::process::Command;

#[path = "common/fake_tools.rs"]
mod fake_tools;

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

/// `gbump regress --sim icarus` of the set `json` with a JUnit report (and `path` for PATH):
/// its output, and stdout and stderr as one text.
fn regress_set(
    json: &std::path::Path,
    work: &std::path::Path,
    junit: &std::path::Path,
    path: Option<&str>,
) -> (std::process::Output, String) {
    let mut c = Command::new(assert_cmd::cargo::cargo_bin("gbump"));
    if let Some(p) = path {
        c.env("PATH", p);
    }
    let o = c
        .args(["regress", "--sim", "icarus", "--vectors"])
        .arg(json)
        .arg("--work")
        .arg(work)
        .arg("--junit")
        .arg(junit)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    (o, text)
}

/// `random:20`'s top set, text only, into `v`.
fn random20_text_set(v: &std::path::Path) {
    let o = Command::new(assert_cmd::cargo::cargo_bin("gbump"))
        .args(["vectors", "--source", "random:20", "--target", "top", "--format", "hex", "--out"])
        .arg(v)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
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

/// A regression that fails before it has runs to report (here a set it refuses) replaces an
/// earlier run's green report with its error, so CI never reads the old verdict; a --junit
/// path that holds something else (not a gbump report) is left as it is.
#[test]
fn a_failed_regression_leaves_no_earlier_green_report() {
    let d = tempfile::tempdir().unwrap();
    let junit = d.path().join("junit.xml");
    let (ok, text) = regress(d.path(), &junit);
    assert!(ok, "{text}");
    assert!(std::fs::read_to_string(&junit).unwrap().contains("failures=\"0\""));
    // A set with a character that is not a hex digit: refused before anything runs.
    let v = d.path().join("v");
    random20_text_set(&v);
    let hex = v.join("random20_top.hex");
    let text = std::fs::read_to_string(&hex).unwrap();
    std::fs::write(&hex, text.replacen(|c: char| c.is_ascii_hexdigit(), "g", 1)).unwrap();
    let failing = |junit: &std::path::Path| {
        Command::new(assert_cmd::cargo::cargo_bin("gbump"))
            .args(["regress", "--sim", "icarus", "--vectors"])
            .arg(v.join("random20_top.json"))
            .arg("--work")
            .arg(d.path().join("work2"))
            .arg("--junit")
            .arg(junit)
            .output()
            .unwrap()
    };
    let o = failing(&junit);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    let report = std::fs::read_to_string(&junit).unwrap();
    assert!(report.contains("errors=\"1\"") && report.contains("<error message="), "{report}");
    let first = err.lines().next().unwrap().trim_start_matches("gbump: error: ");
    let esc = first
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;");
    assert!(report.contains(&esc), "the report lacks the error `{first}`:\n{report}");
    // Not a report gbump wrote: kept.
    let other = d.path().join("notes.xml");
    std::fs::write(&other, "mine").unwrap();
    assert!(!failing(&other).status.success());
    assert_eq!(std::fs::read_to_string(&other).unwrap(), "mine");
}

/// A failed regression whose --junit is a named pipe ends with its error instead of waiting
/// on the pipe to see whether it holds an earlier report.
#[test]
fn a_failed_regression_with_a_pipe_for_its_report_does_not_wait() {
    let d = tempfile::tempdir().unwrap();
    let fifo = d.path().join("j.xml");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let o = assert_cmd::Command::cargo_bin("gbump")
        .unwrap()
        .args(["regress", "--sim", "icarus", "--vectors"])
        .arg(d.path().join("absent.json"))
        .arg("--work")
        .arg(d.path().join("w"))
        .arg("--junit")
        .arg(&fifo)
        .timeout(std::time::Duration::from_secs(30))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("absent.json"), "{err}");
}

/// `--junit` naming a file of a given set (its text or binary records, its power table) is
/// refused before anything runs, as naming its manifest is: the report would replace the
/// data the run reads, and the next regression would find the set broken.
#[test]
fn junit_over_a_sets_data_file_is_refused_first() {
    let d = tempfile::tempdir().unwrap();
    let v = d.path().join("v");
    let gbump = |args: &[&str]| {
        let o = Command::new(assert_cmd::cargo::cargo_bin("gbump")).args(args).output().unwrap();
        (
            o.status.success(),
            String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr),
        )
    };
    let (ok, text) = gbump(&["vectors", "--source", "random:50", "--target", "top", "--out", v.to_str().unwrap()]);
    assert!(ok, "{text}");
    let manifest = v.join("random50_top.json");
    for data in ["random50_top.hex", "random50_top.bin", "random50_top_power_table.hex"] {
        let target = v.join(data);
        let before = std::fs::read(&target).unwrap();
        let w = d.path().join("w");
        let (ok, text) = gbump(&[
            "regress",
            "--sim",
            "icarus",
            "--vectors",
            manifest.to_str().unwrap(),
            "--work",
            w.to_str().unwrap(),
            "--junit",
            target.to_str().unwrap(),
        ]);
        assert!(
            !ok && text.contains("an input of this run") && text.contains(data),
            "{data}: {text}"
        );
        assert!(!text.contains("passed"), "{data}: the regression ran before the refusal:\n{text}");
        assert_eq!(std::fs::read(&target).unwrap(), before, "{data} was changed");
    }
}

/// A set whose expected values are not the model's (one expected colour bit flipped, its
/// manifest's checksum brought along, so it passes every file check) is refused before any
/// simulator runs, naming the record and the column: the RTL would otherwise be judged by
/// values the model does not give.
#[test]
fn a_set_whose_expected_values_are_not_the_models_is_refused() {
    use sha2::Digest;
    let d = tempfile::tempdir().unwrap();
    let v = d.path().join("v");
    random20_text_set(&v);
    let (hex, json) = (v.join("random20_top.hex"), v.join("random20_top.json"));
    let mut m: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let out_c = m["columns"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "out_c")
        .unwrap()
        .clone();
    let bits = m["record_bits"].as_u64().unwrap() as usize;
    let digits = bits.div_ceil(4);
    // One bit inside out_c, in the third record (lines are most significant digit first).
    let bit = out_c["lsb"].as_u64().unwrap() as usize + 9;
    let text = std::fs::read_to_string(&hex).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let data: Vec<usize> = (0..lines.len()).filter(|&i| !lines[i].starts_with("//")).collect();
    let line = &mut lines[data[2]];
    assert_eq!(line.len(), digits);
    let at = digits - 1 - bit / 4;
    let flipped = u8::from_str_radix(&line[at..at + 1], 16).unwrap() ^ (1 << (bit % 4));
    line.replace_range(at..at + 1, &format!("{flipped:x}"));
    let text = lines.join("\n") + "\n";
    std::fs::write(&hex, &text).unwrap();
    let sha: String = sha2::Sha256::digest(text.as_bytes()).iter().map(|b| format!("{b:02x}")).collect();
    m["hex"]["sha256"] = sha.into();
    m["hex"]["bytes"] = text.len().into();
    std::fs::write(&json, serde_json::to_string_pretty(&m).unwrap()).unwrap();
    let junit = d.path().join("junit.xml");
    let (o, out) = regress_set(&json, &d.path().join("work"), &junit, None);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(
        out.contains("record 2: `out_c` lane 1 is")
            && out.contains("not this gbump's model's")
            && out.contains("fix: regenerate with: gbump vectors"),
        "{out}"
    );
    assert!(!out.contains("passed"), "a simulator ran: {out}");
}

/// A regression that runs and finds mismatches reports every run, the failing one as a
/// `<failure>` with its counts, not one error in place of the table (a CI server shows
/// which set failed). The simulator is a stand-in that reports one mismatch of 20 on each
/// run (a real mismatch needs a wrong RTL: tests/rtl_sim.rs and tests/stream.rs run those).
#[test]
fn a_regression_with_mismatches_reports_each_run() {
    let d = tempfile::tempdir().unwrap();
    let path = fake_tools::icarus(
        &d.path().join("bin"),
        "if [ \"$1\" = --version ]; then echo fake vvp; exit 0; fi\necho 'MISMATCH record 2: out_c expected 0x10 got 0x11'\necho '19 passed, 1 failed'\nexit 1",
    );
    let v = d.path().join("v");
    random20_text_set(&v);
    let junit = d.path().join("junit.xml");
    let (o, out) = regress_set(&v.join("random20_top.json"), &d.path().join("work"), &junit, Some(&path));
    assert!(!o.status.success(), "{out}");
    assert!(out.contains("19 passed, 1 failed") || out.contains("1 failed"), "{out}");
    let report = std::fs::read_to_string(&junit).unwrap();
    // The set runs on the loaded table and on the power-up one: two runs, both failing.
    assert!(report.contains("tests=\"2\" failures=\"2\""), "{report}");
    assert_eq!(report.matches("<failure message=\"19 passed, 1 failed\"").count(), 2, "{report}");
    assert!(
        report.contains("name=\"icarus.random20_top\"") && report.contains("name=\"icarus.random20_top+power-up\""),
        "{report}"
    );
    assert!(!report.contains("<error"), "{report}");
}

/// A simulator whose output holds control characters (colour codes, stray bytes) and markup
/// gets a report that is still well-formed XML: every character is one XML 1.0 allows, and
/// the markup is escaped.
#[test]
fn a_report_of_control_characters_is_well_formed() {
    let d = tempfile::tempdir().unwrap();
    let path = fake_tools::icarus(
        &d.path().join("bin"),
        "if [ \"$1\" = --version ]; then echo fake vvp; exit 0; fi\nprintf 'MISMATCH \\001\\002\\033[31m red \\377 ]]> </failure> & <x>\\n0 passed, 1 failed\\n'\nexit 1",
    );
    let v = d.path().join("v");
    random20_text_set(&v);
    let junit = d.path().join("j.xml");
    let (o, text) = regress_set(&v.join("random20_top.json"), &d.path().join("work"), &junit, Some(&path));
    assert_eq!(o.status.code(), Some(1), "{text}");
    let xml = std::fs::read_to_string(&junit).unwrap();
    let bad: Vec<char> = xml
        .chars()
        .filter(|&c| c.is_control() && !matches!(c, '\n' | '\t' | '\r'))
        .collect();
    assert!(bad.is_empty(), "characters XML 1.0 does not allow: {bad:?}\n{xml}");
    assert!(
        xml.contains("\\u{1b}[31m red") && xml.contains("&lt;/failure&gt; &amp; &lt;x&gt;"),
        "{xml}"
    );
    assert_eq!(xml.matches("<failure").count(), xml.matches("</failure>").count(), "{xml}");
}
