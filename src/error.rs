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

    #[error("unknown scene `{name}`\n  fix: run `gbump scenes` for the built-in names, or pass a path to a .toml scene file")]
    UnknownScene { name: String },

    #[error("{path}: {msg}")]
    Io { path: PathBuf, msg: String },

    #[error("{path}: cannot read image: {msg}\n  fix: give a readable greyscale or RGB PNG file")]
    Image { path: PathBuf, msg: String },

    #[error("{0}")]
    Other(String),
}

pub type Result<T> = std::result::Result<T, Error>;

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

/// The `[table]` (or `[[array]]`) header the text above a line last opened, if any.
fn table_above(above: &str) -> Option<&str> {
    above.lines().rev().map(str::trim).find(|l| l.starts_with('[')).map(|l| {
        let l = l.split('#').next().unwrap_or(l).trim();
        l.trim_start_matches('[').trim_end_matches(']').trim()
    })
}

/// Turn a `toml` deserialisation error into an [`Error::Input`] that names file, line and column.
///
/// The parser's message names neither the key nor, at a missing value, anything at all
/// (`shininess =` at the end of a file gives an empty one), so the key is read off the line
/// the error points into and a missing value is said in words.
pub fn toml_error(file: &str, text: &str, e: &toml::de::Error, fix: &str) -> Error {
    let start = e.span().map_or(0, |s| s.start.min(text.len()));
    let (line, col) = line_col(text, start);
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let (before, after) = (&text[line_start..start], &text[start..line_end]);
    let key = key_before(before).map(|k| match table_above(&text[..line_start]) {
        Some(t) => format!("{t}.{k}"),
        None => k.to_string(),
    });
    let mut msg = e.message().trim().to_string();
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
    Error::Input {
        file: file.to_string(),
        line,
        col,
        msg,
        fix: fix.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn the_key_is_the_one_the_error_points_into() {
        assert_eq!(message("a =\n"), "`a` has no value after `=`");
        let m = message("[light]\nx = 1\ny =\n");
        assert!(m.starts_with("`light.y`"), "{m}");
        let m = message("light = { x = 1, y = }\n");
        assert!(m.starts_with("`y`"), "{m}");
        // No key is made up from a comment or a header.
        let m = message("# a = \n[light\n");
        assert!(!m.starts_with('`'), "{m}");
    }
}
