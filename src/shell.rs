//! Words as a POSIX shell reads them back: the commands gbump records (file headers,
//! manifests, fix hints) paste back whole.

/// `a` as a POSIX shell reads it back: as is when it holds only safe characters, else in
/// single quotes.
pub fn quoted(a: &str) -> String {
    if !a.is_empty() && a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./+,:@=%^".contains(c)) {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', "'\\''"))
    }
}

/// Words quoted for a POSIX shell, joined.
pub fn quoted_words(words: &[String]) -> String {
    words.iter().map(|w| quoted(w)).collect::<Vec<_>>().join(" ")
}
