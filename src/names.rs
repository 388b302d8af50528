//! Names that become part of a file or folder name (scene names, set stems, units, a sweep
//! space's stem). Every such site calls [`check`], so no name can climb out of the folder
//! the user named (`../x`), land at an absolute path, hide (`.x`) or read as a flag (`-x`).

use crate::error::{Error, Result};
use crate::limits::MAX_NAME_CHARS;

/// Whether `name` is safe inside a path: `[A-Za-z0-9_.-]`, not starting with `.` or `-`,
/// 1..=[`MAX_NAME_CHARS`] characters.
pub fn is_safe(name: &str) -> bool {
    !name.is_empty() && name.len() as u64 <= MAX_NAME_CHARS && !name.starts_with(['.', '-']) && name.chars().all(plain_char)
}

/// Whether `c` may be in a plain name: `[A-Za-z0-9_.-]`.
pub fn plain_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '-')
}

/// Refuse `name` (the value of `field` in `file`) unless [`is_safe`].
pub fn check(file: &str, field: &str, name: &str) -> Result<()> {
    if is_safe(name) {
        return Ok(());
    }
    Err(Error::field(
        file,
        field,
        format!("`{name}` cannot be part of a file name"),
        format!("use 1..={MAX_NAME_CHARS} letters, digits, `_`, `.` or `-`, not starting with `.` or `-` (no `/`, no spaces)"),
    ))
}

#[cfg(test)]
mod tests {
    use super::is_safe;

    #[test]
    fn only_plain_names_pass() {
        for ok in ["torus_caps", "a", "v1.2-b", "X9"] {
            assert!(is_safe(ok), "{ok}");
        }
        let long = "a".repeat(65);
        for bad in [
            "",
            "../escaped",
            "/tmp/x",
            ".hidden",
            "-rf",
            "a/b",
            "a b",
            "a\\b",
            "é",
            &long,
            "..",
            "a\0b",
        ] {
            assert!(!is_safe(bad), "{bad:?}");
        }
    }
}

/// A choice and its value as the caller spells them: `--shininess 40` on the command line,
/// `shininess=40` for a keyword argument.
pub fn choice(name: &str, value: impl std::fmt::Display) -> String {
    match name.ends_with('=') {
        true => format!("{name}{value}"),
        false => format!("{name} {value}"),
    }
}
