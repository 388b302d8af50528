//! Every command a message or a document tells the user to run must exist: each
//! "`gbump SUB --flag`" quoted in src/, README.md, ARCHITECTURE.md and docs/, and each
//! `gbump` command line in them, scripts/ and examples/, is checked against clap's definition.

use clap::CommandFactory;
use std::path::Path;

fn sources(dir: &Path, out: &mut Vec<(String, String)>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push((p.display().to_string(), std::fs::read_to_string(&p).unwrap()));
        }
    }
}

/// The quoted commands in `text`: what follows "`gbump " or "\"gbump " up to the closing quote.
fn quoted_commands(text: &str) -> Vec<String> {
    let mut v = Vec::new();
    for open in ['`', '"'] {
        let pat = format!("{open}gbump ");
        for (i, _) in text.match_indices(&pat) {
            let rest = &text[i + pat.len()..];
            let end = rest.find([open, '\n']).unwrap_or(rest.len());
            v.push(rest[..end].to_string());
        }
    }
    // A command line of its own, in a fenced example or a script (where a Markdown file has
    // no fence, prose lines start with "gbump" too): up to its comment.
    let fenced = text.contains("\n```");
    let mut inside = !fenced;
    for line in text.lines() {
        if fenced && line.trim_start().starts_with("```") {
            inside = !inside;
        } else if let Some(rest) = line.trim_start().strip_prefix("gbump ").filter(|_| inside) {
            v.push(rest.split(" #").next().unwrap().to_string());
        }
    }
    v
}

/// Problems with one command line (empty when every subcommand and flag exists).
fn problems(cli: &clap::Command, line: &str) -> Vec<String> {
    let mut words = line.split_whitespace();
    let Some(sub) = words.next().filter(|s| s.chars().all(|c| c.is_ascii_lowercase() || c == '-')) else {
        return vec![];
    };
    // The top level's own flags, which clap adds itself.
    if sub.starts_with("--") {
        return match sub {
            "--version" | "--help" => vec![],
            _ => vec![format!("`gbump {line}`: gbump has no flag {sub}")],
        };
    }
    let Some(cmd) = cli.find_subcommand(sub) else {
        return vec![format!("`gbump {line}`: no subcommand `{sub}`")];
    };
    words
        .filter_map(|w| w.strip_prefix("--"))
        .map(|f| f.split(['=', '`', ')', ',']).next().unwrap())
        .filter(|f| !f.is_empty() && f.chars().all(|c| c.is_ascii_lowercase() || c == '-'))
        .filter(|f| !cmd.get_arguments().any(|a| a.get_long() == Some(f)))
        .map(|f| format!("`gbump {line}`: `{sub}` has no flag --{f}"))
        .collect()
}

#[test]
fn every_command_named_in_a_message_or_the_readme_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    sources(&root.join("src"), &mut files);
    for doc in ["README.md", "ARCHITECTURE.md", "docs/SCENES.md", "docs/REPORT.md"] {
        files.push((doc.into(), std::fs::read_to_string(root.join(doc)).unwrap()));
    }
    for dir in ["scripts", "examples"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.is_file() {
                if let Ok(text) = std::fs::read_to_string(&p) {
                    files.push((p.display().to_string(), text));
                }
            }
        }
    }
    let cli = gbump::cli::Cli::command();
    let mut checked = 0;
    let mut bad = Vec::new();
    for (name, text) in &files {
        for line in quoted_commands(text) {
            checked += 1;
            bad.extend(problems(&cli, &line).into_iter().map(|p| format!("{name}: {p}")));
        }
    }
    assert!(checked > 20, "only {checked} commands found: the scan is broken");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn the_checker_catches_a_wrong_flag() {
    let cli = gbump::cli::Cli::command();
    assert!(!problems(&cli, "config --show").is_empty());
    assert!(!problems(&cli, "nosuch --x").is_empty());
    assert!(problems(&cli, "scenes --show NAME").is_empty());
    assert!(problems(&cli, "--version").is_empty());
    assert!(!problems(&cli, "--nosuch").is_empty());
    // A command on a line of its own is found, up to its comment.
    assert_eq!(
        quoted_commands("x\n  gbump fit --budget 'max<=2'   # --nosuch\n"),
        ["fit --budget 'max<=2'  "]
    );
    assert_eq!(quoted_commands("gbump checks\n```sh\ngbump fit --x\n```\n"), ["fit --x"]);
}

/// Every file the README's commands name with `--config` or `--space` exists in the
/// repository, apart from the placeholder `my.toml` the reader writes.
#[test]
fn files_the_readme_names_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let mut missing = Vec::new();
    let mut seen = 0;
    for flag in ["--config ", "--space "] {
        for (i, _) in readme.match_indices(flag) {
            let rest = &readme[i + flag.len()..];
            let word: String = rest.chars().take_while(|c| !c.is_whitespace() && !"`)|,".contains(*c)).collect();
            if !word.ends_with(".toml") || word == "my.toml" || word.contains("FILE") {
                continue;
            }
            seen += 1;
            if !root.join(&word).exists() {
                missing.push(word);
            }
        }
    }
    assert!(seen > 0, "the README names no configuration file");
    assert!(missing.is_empty(), "the README names files that do not exist: {missing:?}");
}

/// Every configuration the repository carries loads as a user's would: a rule added to the
/// loader (a refused inert field, say) must not leave a checked-in file the README or a test
/// names behind it.
#[test]
fn every_checked_in_configuration_loads() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut loaded = 0;
    let mut bad = Vec::new();
    for dir in ["tests/configs", "tests/area_model/configs"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "toml") {
                loaded += 1;
                if let Err(e) = gbump::config::PipelineConfig::load(&p) {
                    bad.push(e.to_string());
                }
            }
        }
    }
    assert!(loaded > 40, "{loaded} configurations found");
    assert!(bad.is_empty(), "checked-in configurations refused:\n{}", bad.join("\n"));
}

/// A unit the configuration lacks, asked for as an exhaustive sweep: the fix names every
/// setting the sweep needs, and a configuration with exactly those sweeps it.
#[test]
fn following_the_exhaustive_sweeps_fix_is_enough() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        assert_cmd::Command::cargo_bin("gbump")
            .unwrap()
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap()
    };
    let o = run(&["vectors", "--source", "exhaustive:normalise", "--target", "normalise", "--out", "v"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    let fix = err.split("fix:").nth(1).unwrap_or_else(|| panic!("{err}"));
    let settings = fix.split("set ").nth(1).unwrap_or_else(|| panic!("{err}"));
    let mut toml = String::new();
    for part in settings.split(" and ") {
        let part = part.trim_start_matches("for the sweep ");
        let part = part.split(" in the configuration").next().unwrap().trim();
        let part = part.split(" (").next().unwrap();
        if let Some((k, v)) = part.split_once(" <= ") {
            toml += &format!("{k} = {v}\n");
        } else if let Some((k, v)) = part.split_once(" = ") {
            toml += &format!("{k} = {v}\n");
        }
    }
    assert!(toml.contains("lh_bits = 6"), "the fix leaves out the sweep's width: {err}");
    std::fs::write(dir.path().join("c.toml"), &toml).unwrap();
    let o = run(&[
        "vectors",
        "--source",
        "exhaustive:normalise",
        "--target",
        "normalise",
        "--config",
        "c.toml",
        "--out",
        "v",
    ]);
    assert!(o.status.success(), "{toml}\n{}", String::from_utf8_lossy(&o.stderr));
}

/// Every field a configuration file takes is in `gbump config`'s output (set, or as a `#`
/// comment with its default), as the messages that send users there promise; the fields are
/// the ones serde lists for an unknown name, so a new field cannot be left out.
#[test]
fn gbump_config_prints_every_field() {
    let err = toml::from_str::<gbump::PipelineConfig>("not_a_field = 1").unwrap_err().to_string();
    let fields: Vec<&str> = gbump::error::expected_names(&err)
        .into_iter()
        .filter(|x| !gbump::error::RETIRED_NAMES.contains(x))
        .collect();
    assert!(fields.len() > 30, "{fields:?}");
    let out = assert_cmd::Command::cargo_bin("gbump").unwrap().arg("config").output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for f in fields {
        let listed = text
            .lines()
            .any(|l| l.trim_start_matches("# ").split_once(" = ").is_some_and(|(k, _)| k == f));
        assert!(listed, "`gbump config` does not print `{f}`:\n{text}");
    }
}

/// The README names every kind of bump source a scene takes (the kinds serde lists for an
/// unknown one), each as `kind`.
#[test]
fn the_readme_names_every_bump_source() {
    let err = toml::from_str::<gbump::bumpmap::height::HeightSource>("kind = \"not_a_kind\"")
        .unwrap_err()
        .to_string();
    let kinds = gbump::error::expected_names(&err);
    assert!(kinds.len() >= 5 && kinds.contains(&"png"), "{kinds:?}");
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    for k in kinds {
        assert!(readme.contains(&format!("`{k}`")), "the README does not name bump source `{k}`");
    }
}
