//! Typed errors of the library. Every variant names the input it is about and, where the
//! user can act, what to do; `main` prints it and exits non-zero.

use std::path::PathBuf;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum Error {
    /// A TOML file (scene or config) that does not parse or does not validate.
    #[error("{file}:{line}:{col}: {msg}\n  fix: {fix}")]
    Input {
        file: String,
        line: usize,
        col: usize,
        msg: String,
        fix: String,
    },

    /// A named value that is out of range, NaN or otherwise unusable.
    #[error("{file}: field `{field}`: {msg}\n  fix: {fix}")]
    Field {
        file: String,
        field: String,
        msg: String,
        fix: String,
    },

    /// A scene rendered smaller than its own image size covers no pixel centre: the size asked
    /// for is what to change (at its own size or above, its camera or objects are: a `Field`
    /// error of `objects`).
    #[error("scene {scene} at {w}x{h}: no object covers a pixel centre, so no fragment reaches the pipeline\n  fix: give a larger size (the scene's own is {}x{})", .own[0], .own[1])]
    NoPixelAtSize { scene: String, w: u32, h: u32, own: [u32; 2] },

    #[error("unknown scene `{name}`\n  fix: run `gbump scenes` for the built-in names, or pass a path to a .toml scene file")]
    UnknownScene { name: String },

    #[error("{path}: {msg}")]
    Io { path: PathBuf, msg: String },

    #[error("{path}: cannot read image: {msg}\n  fix: give a readable PNG file (greyscale, RGB or RGBA; its luminance is the height, alpha is ignored)")]
    Image { path: PathBuf, msg: String },

    #[error("{0}")]
    Other(String),
}

pub type Result<T> = std::result::Result<T, Error>;

/// The name standard output has in messages.
pub const STDOUT: &str = "<standard output>";

/// Whether `e` is a write to standard output whose reader had closed it (a broken pipe).
pub fn is_closed_stdout(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        matches!(c.downcast_ref::<Error>(), Some(Error::Io { path, msg }) if path.as_os_str() == STDOUT && msg.starts_with("Broken pipe"))
    })
}

impl Error {
    /// An I/O error on `path`, with the OS message.
    pub fn io(path: impl Into<PathBuf>, e: std::io::Error) -> Error {
        let path = path.into();
        // Every I/O failure says what to do about it, whatever command met it.
        use std::io::ErrorKind as K;
        let hint = match e.kind() {
            // A relative path in a folder that was removed under the run reads as missing.
            K::NotFound if std::env::current_dir().is_err() => "\n  fix: the current folder no longer exists; cd to one that does",
            K::NotFound => "\n  fix: check the path (nothing is there)",
            K::PermissionDenied => "\n  fix: check permissions of the file or folder",
            K::IsADirectory => "\n  fix: this is a folder; give the file itself",
            K::AlreadyExists => "\n  fix: a file is in the way of a folder gbump makes here; move it, or give another path",
            K::NotADirectory => "\n  fix: a part of the path is a file, not a folder; give a path through folders",
            K::StorageFull | K::QuotaExceeded => "\n  fix: free space on that disk, or write elsewhere",
            K::FileTooLarge => "\n  fix: a file-size limit stopped the write (`ulimit -f`): raise it, or write less (fewer records)",
            K::ReadOnlyFilesystem => "\n  fix: write to a writable folder",
            K::InvalidData => "\n  fix: give a text file in UTF-8",
            K::BrokenPipe => "\n  fix: the program reading this output closed it early; let it read to the end",
            _ => "\n  fix: check the path, the disk and the permissions",
        };
        Error::Io {
            path,
            msg: format!("{e}{hint}"),
        }
    }

    pub fn field(file: &str, field: &str, msg: impl Into<String>, fix: impl Into<String>) -> Error {
        Error::Field {
            file: file.to_string(),
            field: field.to_string(),
            msg: msg.into(),
            fix: fix.into(),
        }
    }
}

/// A message as the terminal should show it: control characters (but the line breaks and
/// tabs the message is laid out with) and the bidirectional overrides that would reorder
/// what follows them, as `\u{...}` escapes, so a name taken from a file or an argument
/// cannot rewrite or hide the rest of the message.
pub fn shown(msg: &str) -> String {
    msg.chars()
        .map(|c| {
            let bidi = matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}' | '\u{200E}' | '\u{200F}' | '\u{061C}');
            if (c.is_control() && c != '\n' && c != '\t') || bidi {
                format!("\\u{{{:x}}}", c as u32)
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// The same text with its line breaks and tabs shown as `\n`, `\r` and `\t`, for a caller's
/// string a message quotes inside one of its lines (a name given through the C library or
/// Python, where a line break would start a line of the message, a forged `fix:` among them).
pub fn one_line(s: &str) -> String {
    s.replace('\n', "\\n").replace('\r', "\\r").replace('\t', "\\t")
}

/// Line and column (1-based) of a byte offset in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |s| s.chars().count()) + 1;
    (line, col)
}

/// The key whose value the error points into: the word before the last `=` on the line, after
/// any `{` or `,` of an inline table (`light = { x = }` names `x`). None on a comment, a
/// table header or a line without `=`.
fn key_before(before: &str) -> Option<&str> {
    let (lhs, _) = before.rsplit_once('=')?;
    let k = lhs.rsplit(['{', ',']).next()?.trim().trim_matches('"');
    let plain = |c: char| c.is_ascii_alphanumeric() || "_-.".contains(c);
    (!k.is_empty() && k.chars().all(plain) && !before.trim_start().starts_with(['#', '['])).then_some(k)
}

/// The table the text above a line last opened, as a path that names array entries by index:
/// the third `[[objects]]` is `objects[2]`, and `[objects.shape]` under it `objects[2].shape`.
/// None above every header.
fn table_above(above: &str) -> Option<String> {
    let headers: Vec<(bool, &str)> = above
        .lines()
        .map(|l| l.split('#').next().unwrap_or(l).trim())
        .filter(|l| l.starts_with('['))
        .map(|l| (l.starts_with("[["), l.trim_start_matches('[').trim_end_matches(']').trim()))
        .collect();
    let &(_, last) = headers.last()?;
    let parts: Vec<&str> = last.split('.').map(str::trim).collect();
    let mut path = String::new();
    for k in 0..parts.len() {
        let prefix = parts[..=k].join(".");
        if !path.is_empty() {
            path.push('.');
        }
        path += parts[k];
        // An array of tables: its entry is the count of its headers so far, less one.
        let entries = headers
            .iter()
            .filter(|(array, h)| *array && h.split('.').map(str::trim).collect::<Vec<_>>().join(".") == prefix)
            .count();
        if entries > 0 {
            path += &format!("[{}]", entries - 1);
        }
    }
    Some(path)
}

/// The inline tables open on a line before the error (`shape = { kind = "torus", major = `
/// is inside `shape`), outermost first. Inline tables are on one line in TOML.
fn inline_tables(before: &str) -> Vec<String> {
    let (mut open, mut key, mut seg, mut quoted) = (Vec::new(), String::new(), 0, false);
    let mut last_sig = ' ';
    for (i, c) in before.char_indices() {
        if quoted {
            quoted = c != '"';
            continue;
        }
        match c {
            '"' => quoted = true,
            '=' => key = before[seg..i].trim().trim_matches('"').to_string(),
            '{' if last_sig == '=' => open.push(std::mem::take(&mut key)),
            '}' => {
                open.pop();
            }
            _ => {}
        }
        if matches!(c, '{' | ',') {
            seg = i + c.len_utf8();
        }
        if !c.is_whitespace() {
            last_sig = c;
        }
    }
    open
}

/// The kind of gbump file `text` is by its top-level keys, when it is clearly the other kind
/// than the one being read: a scene has `objects` or `camera`; a pipeline configuration has
/// none of those and fields only a configuration has. `reading` is "scene" or
/// "configuration"; the answer is the refusal's fix, or None.
pub fn wrong_kind(text: &str, reading: &str) -> Option<String> {
    let table = text.parse::<toml::Table>().ok()?;
    let scene = table.contains_key("objects") || table.contains_key("camera");
    let config_only = [
        "light_mode",
        "normal_bits",
        "lh_bits",
        "bump_state",
        "pipeline_depth",
        "dot_frac_bits",
    ];
    let config = !scene && table.keys().any(|k| config_only.contains(&k.as_str()));
    match reading {
        "configuration" if !scene && table.get("pipeline").is_some_and(|p| p.is_table()) => Some(
            "a configuration file is flat, its fields at the top; `[pipeline]` is the table a scene file holds them in: drop the `[pipeline]` line (or pass the scene with --scene)".into(),
        ),
        "configuration" if scene => Some(
            "this is a scene file (it has `objects` or `camera`), not a pipeline configuration: pass it with --scene, which derives the configuration (`gbump config --scene FILE` prints it)".into(),
        ),
        "scene" if config => Some(
            "this is a pipeline configuration (it has fields such as `light_mode` or `normal_bits` at the top), not a scene: pass it with --config, or put its fields under `[pipeline]` in a scene".into(),
        ),
        _ => None,
    }
}

/// Turn a `toml` deserialisation error into an [`Error::Input`] that names file, line and column.
///
/// The parser's message names neither the key nor, at a missing value, anything at all
/// (`shininess =` at the end of a file gives an empty one), so the key is read off the line
/// the error points into and a missing value is said in words.
pub fn toml_error(file: &str, text: &str, e: &toml::de::Error, fix: &str) -> Error {
    let mut start = e.span().map_or(0, |s| s.start.min(text.len()));
    // A value read whole (an internally tagged table such as a shape) is pointed at from its
    // `{`: the key inside it whose value the message quotes is the place.
    if let Some(at) = e
        .span()
        .and_then(|s| quoted_value_at(&text[s.start.min(text.len())..s.end.min(text.len())], e.message()))
    {
        start += at;
    }
    let (line, col) = line_col(text, start);
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let (before, after) = (&text[line_start..start], &text[start..line_end]);
    let key = key_before(before)
        .map(|k| {
            let mut path: Vec<String> = table_above(&text[..line_start]).into_iter().collect();
            path.extend(inline_tables(before));
            path.push(k.to_string());
            path.join(".")
        })
        // An error at a table header (`[lights]` where a number goes): the header names the key.
        .or_else(|| {
            let h = after.trim();
            (before.trim().is_empty() && h.starts_with('[') && !h.starts_with("[[") && h.ends_with(']'))
                .then(|| h.trim_matches(['[', ']']).trim().trim_matches('"').to_string())
        });
    let mut msg = e.message().trim().to_string();
    // A date or time arrives as serde's map of one private key, which the message calls a
    // map: say what was written.
    if let Some(dt) = datetime_at(after).filter(|_| msg.contains("invalid type: map")) {
        msg = msg.replace("invalid type: map", &format!("invalid type: date-time `{dt}`"));
    }
    if let Some(k) = key {
        if before.trim_end().ends_with('=') && after.trim().is_empty() {
            msg = format!("`{k}` has no value after `=`");
        } else if msg.is_empty() {
            msg = format!("`{k}`: this value cannot be read");
        } else {
            msg = format!("`{k}`: {msg}");
        }
    } else if msg.is_empty() {
        msg = "the file cannot be read as TOML here".to_string();
    }
    let mut fix = fix.to_string();
    let syntax = toml::from_str::<toml::Table>(text).is_err();
    let number = ["number", "floating-point", "integer"].iter().any(|w| msg.contains(w));
    let twice = msg.contains("duplicate key") || msg.contains("duplicate table") || msg.contains("redefin");
    if twice {
        // Valid TOML piece by piece, but a key or table is given twice.
        fix = "a key or table is given twice in this file; keep one of them".to_string();
    } else if syntax && number {
        // A number TOML itself cannot hold (1e400, 2^64 and beyond).
        fix = format!("this number cannot be read: an integer must fit in 64 bits and a float in a double's range; {fix}");
    } else if syntax {
        // Not TOML at all: the caller's hint is about fields, which this is not yet about.
        fix = "this is not TOML syntax: a table header is `[name]` alone on its line, a field `name = value`, text in double quotes, a list in `[ ]`".to_string();
    } else if let Some((name, expected)) = unknown_field(&msg) {
        let known: Vec<&str> = expected.iter().copied().filter(|e| !RETIRED_NAMES.contains(e)).collect();
        fix = match nearest(name, &known) {
            Some(n) => format!("did you mean `{n}`? {fix}"),
            None if known.is_empty() => format!("this table takes no fields; {fix}"),
            None => format!("the fields here: {}; {fix}", known.join(", ")),
        };
        msg = format!("unknown field `{name}`");
    }
    Error::Input {
        file: file.to_string(),
        line,
        col,
        msg: shorten_quoted(&msg),
        fix,
    }
}

/// Longest quoted value an error message repeats whole; a longer one (a 900 kB string) keeps
/// its start and says how long it was.
pub const MAX_QUOTED_CHARS: usize = 80;

/// `msg` with every double-quoted value longer than [`MAX_QUOTED_CHARS`] cut to its start.
fn shorten_quoted(msg: &str) -> String {
    let parts: Vec<&str> = msg.split('"').collect();
    let mut out = String::with_capacity(msg.len().min(1024));
    for (i, p) in parts.iter().enumerate() {
        if i > 0 {
            out.push('"');
        }
        // Odd pieces lie between quotes (a closing quote follows them).
        let n = p.chars().count();
        if i % 2 == 1 && i + 1 < parts.len() && n > MAX_QUOTED_CHARS {
            out.extend(p.chars().take(MAX_QUOTED_CHARS / 2));
            out += &format!("… ({n} characters in all)");
        } else {
            out.push_str(p);
        }
    }
    out
}

/// The TOML date or time `text` starts with (ended by a comma, a closing bracket or a
/// comment), as written.
fn datetime_at(text: &str) -> Option<&str> {
    let end = text.find([',', '}', ']', '#']).unwrap_or(text.len());
    let value = text[..end].trim();
    value.parse::<toml::value::Datetime>().is_ok().then_some(value)
}

/// Where, in the text of an inline table `span` (`{ kind = "torus", major = "big" }`), the
/// value an "invalid type: string \"big\", expected f64" message quotes stands, when the
/// message quotes one and the table holds it once.
fn quoted_value_at(span: &str, msg: &str) -> Option<usize> {
    if !span.trim_start().starts_with('{') {
        return None;
    }
    let quoted = msg.split_once("invalid type: ")?.1.split_once(", expected")?.0;
    // `string "big"` keeps its quotes; `integer `3``, `boolean `true`` and `floating point
    // `1.5`` are between backticks.
    let value = match quoted.split_once('"') {
        Some(_) => &quoted[quoted.find('"')?..],
        None => quoted.split('`').nth(1)?,
    };
    let mut hits = span.match_indices(value).filter(|(i, _)| {
        let before = span[..*i].trim_end();
        let after = span[i + value.len()..].trim_start();
        before.ends_with('=') && (after.starts_with(',') || after.starts_with('}'))
    });
    let (at, _) = hits.next()?;
    hits.next().is_none().then_some(at)
}

/// Old field names still read (with a warning) that an unknown-field error should not
/// suggest: the configuration's `RENAMED_FIELDS`, kept here so the bottom module needs no
/// import from above it (a test checks the two lists agree).
pub const RETIRED_NAMES: [&str; 3] = ["dot_bits", "power_bits", "k_bits"];

/// (name, expected names) of serde's "unknown field `x`, expected one of `a`, `b`, `c`",
/// "expected `a` or `b`", "expected `a`" or "there are no fields" (the message may carry a
/// `key: ` prefix).
fn unknown_field(msg: &str) -> Option<(&str, Vec<&str>)> {
    let rest = &msg[msg.find("unknown field `")? + "unknown field `".len()..];
    let (name, rest) = rest.split_once('`')?;
    Some((name, expected_names(rest)))
}

/// The names a serde message lists as expected ("expected one of `a`, `b`, `c`", "expected
/// `a` or `b`", "expected `a`"; none for "there are no fields"), for an unknown field or
/// variant alike.
pub fn expected_names(msg: &str) -> Vec<&str> {
    let list = msg.split_once("expected ").map_or("", |(_, l)| l);
    let list = list.strip_prefix("one of ").unwrap_or(list);
    // Each name is between backticks; the separators (", ", " or ") are outside them.
    list.split('`').skip(1).step_by(2).filter(|x| !x.is_empty()).collect()
}

/// The candidate closest to `name` by edit distance, if it is close enough to be a typo (at
/// most a third of the name's letters wrong).
pub fn nearest<'a>(name: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let d = |a: &str, b: &str| {
        let b: Vec<char> = b.chars().collect();
        let mut row: Vec<usize> = (0..=b.len()).collect();
        for (i, ca) in a.chars().enumerate() {
            let mut prev = row[0];
            row[0] = i + 1;
            for j in 0..b.len() {
                let cur = row[j + 1];
                row[j + 1] = (prev + usize::from(ca != b[j])).min(row[j] + 1).min(cur + 1);
                prev = cur;
            }
        }
        row[b.len()]
    };
    let (best, dist) = candidates.iter().map(|c| (*c, d(name, c))).min_by_key(|x| x.1)?;
    (dist > 0 && dist * 3 <= name.chars().count().max(3)).then_some(best)
}

#[cfg(test)]
mod tests {
    /// A long quoted value in a message keeps its start and its length; short ones and the
    /// rest of the message stay whole.
    #[test]
    fn long_quoted_values_are_cut() {
        let long = "x".repeat(10_000);
        let m = super::shorten_quoted(&format!("invalid type: string \"{long}\", expected u32 and \"short\""));
        assert!(
            m.len() < 200 && m.contains("10000 characters in all") && m.contains("\"short\"") && m.ends_with('"'),
            "{m}"
        );
        assert_eq!(super::shorten_quoted("a \"b\" c"), "a \"b\" c");
    }

    use super::*;

    /// Every form serde gives the expected names in is read: a long list, two, one, none.
    #[test]
    fn unknown_field_reads_every_list_form() {
        let cases: [(&str, &[&str]); 4] = [
            (
                "unknown field `celss`, expected one of `cells`, `radius`, `depth`",
                &["cells", "radius", "depth"],
            ),
            (
                "bump.source: unknown field `celss`, expected `cells` or `radius`",
                &["cells", "radius"],
            ),
            ("unknown field `celss`, expected `cells`", &["cells"]),
            ("unknown field `celss`, there are no fields", &[]),
        ];
        for (msg, want) in cases {
            assert_eq!(unknown_field(msg), Some(("celss", want.to_vec())), "{msg}");
        }
    }

    /// The message of `toml_error` for `text` read as a table of integers and strings.
    fn message(text: &str) -> String {
        let e = toml::from_str::<toml::Table>(text).map(|_| ()).or_else(|_| {
            // Syntax is fine: fail on a type instead, as a config's fields do.
            #[derive(serde::Deserialize, Debug)]
            #[allow(dead_code)]
            struct T {
                a: Option<u32>,
                light: Option<std::collections::BTreeMap<String, u32>>,
            }
            toml::from_str::<T>(text).map(|_| ())
        });
        let e = e.expect_err(text);
        match toml_error("f.toml", text, &e, "fix") {
            Error::Input { msg, .. } => msg,
            other => panic!("{other:?}"),
        }
    }

    /// A type error inside a value read whole (an internally tagged inline table) names the
    /// key inside it, at its value's column.
    #[test]
    fn a_type_error_inside_a_tagged_inline_table_names_its_key() {
        #[derive(serde::Deserialize, Debug)]
        #[serde(tag = "kind", rename_all = "lowercase")]
        #[allow(dead_code)]
        enum Shape {
            Torus { major: f64, minor: f64 },
        }
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct Obj {
            shape: Shape,
        }
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct Scene {
            objects: Vec<Obj>,
        }
        let text = "[[objects]]\nshape = { kind = \"torus\", major = \"big\", minor = 0.4 }\n";
        let e = toml::from_str::<Scene>(text).unwrap_err();
        let msg = toml_error("s.toml", text, &e, "fix").to_string();
        assert!(msg.contains("s.toml:2:") && msg.contains("objects[0].shape.major"), "{msg}");
        let col = text.lines().nth(1).unwrap().find("\"big\"").unwrap() + 1;
        assert!(msg.contains(&format!(":2:{col}:")), "{msg}");
    }

    /// An escape sequence or a right-to-left override in a name cannot rewrite the message.
    #[test]
    fn control_and_bidi_characters_are_shown_escaped() {
        assert_eq!(shown("a\u{1b}[2Jb\u{202E}c\nd\te"), "a\\u{1b}[2Jb\\u{202e}c\nd\te");
    }

    #[test]
    fn a_typo_is_answered_with_the_nearest_name_and_syntax_with_syntax() {
        assert_eq!(nearest("bump_stat", &["bump_state", "lights", "light_mode"]), Some("bump_state"));
        assert_eq!(nearest("toop", &["top", "all", "power_unit"]), Some("top"));
        assert_eq!(nearest("zebra", &["top", "all"]), None);
        let e = toml::from_str::<toml::Table>("[pipeline\nlights = 2\n").unwrap_err();
        match toml_error("f.toml", "[pipeline\nlights = 2\n", &e, "about fields") {
            Error::Input { fix, .. } => assert!(fix.contains("not TOML syntax") && !fix.contains("about fields"), "{fix}"),
            other => panic!("{other:?}"),
        }
        // A key given twice is said as such, not as a syntax slip.
        for text in ["a = 1\na = 2\n", "[t]\nx = 1\n[t]\ny = 2\n"] {
            let e = toml::from_str::<toml::Table>(text).unwrap_err();
            match toml_error("f.toml", text, &e, "about fields") {
                Error::Input { fix, .. } => assert!(fix.contains("given twice"), "{text:?}: {fix}"),
                other => panic!("{other:?}"),
            }
        }
        // A number TOML cannot hold is not a syntax slip.
        let e = toml::from_str::<toml::Table>("x = 1e400\n").unwrap_err();
        match toml_error("f.toml", "x = 1e400\n", &e, "about fields") {
            Error::Input { fix, .. } => assert!(
                fix.starts_with("this number cannot be read") && fix.ends_with("about fields"),
                "{fix}"
            ),
            other => panic!("{other:?}"),
        }
        #[derive(serde::Deserialize, Debug)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)]
        struct T {
            bump_state: Option<u32>,
            #[serde(alias = "dot_bits")]
            dot_frac_bits: Option<u32>,
        }
        let text = "bump_stat = 1\n";
        let e = toml::from_str::<T>(text).unwrap_err();
        match toml_error("f.toml", text, &e, "see the fields") {
            Error::Input { msg, fix, .. } => {
                assert_eq!(msg, "unknown field `bump_stat`");
                assert!(
                    fix.starts_with("did you mean `bump_state`?") && fix.ends_with("see the fields"),
                    "{fix}"
                );
            }
            other => panic!("{other:?}"),
        }
        let e = toml::from_str::<T>("zzz = 1\n").unwrap_err();
        match toml_error("f.toml", "zzz = 1\n", &e, "x") {
            Error::Input { fix, .. } => assert!(
                fix.contains("bump_state") && !fix.contains("dot_bits"),
                "retired names are not offered: {fix}"
            ),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn the_key_is_the_one_the_error_points_into() {
        assert_eq!(message("a =\n"), "`a` has no value after `=`");
        let m = message("[light]\nx = 1\ny =\n");
        assert!(m.starts_with("`light.y`"), "{m}");
        let m = message("light = { x = 1, y = }\n");
        assert!(m.starts_with("`light.y`"), "{m}");
        // Array entries by index, inline tables by name.
        let m = message("[[objects]]\na = 1\n[[objects]]\nshape = { kind = \"torus\", major = }\n");
        assert!(m.starts_with("`objects[1].shape.major`"), "{m}");
        let m = message("[[objects]]\n[objects.bump]\nsource = { n = { r = 1 }, cells = }\n");
        assert!(m.starts_with("`objects[0].bump.source.cells`"), "{m}");
        // No key is made up from a comment or a header.
        let m = message("# a = \n[light\n");
        assert!(!m.starts_with('`'), "{m}");
    }
}
