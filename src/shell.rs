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

/// Where a recorded command's subcommand is in its words: the first word after the program
/// that is not a global option (`--tool-timeout S` or `--tool-timeout=S` may come first).
pub fn subcommand_at(words: &[String]) -> Option<usize> {
    let mut i = 1;
    while let Some(w) = words.get(i) {
        match w.as_str() {
            "--tool-timeout" => i += 2,
            w if w.starts_with("--tool-timeout=") => i += 1,
            _ => return Some(i),
        }
    }
    None
}

/// The value `words` give option `flag` (`--flag V` or `--flag=V`; the last, as clap takes it).
pub fn option_value<'a>(words: &'a [String], flag: &str) -> Option<&'a str> {
    let mut found = None;
    for (i, w) in words.iter().enumerate() {
        if w == flag {
            found = words.get(i + 1).map(String::as_str).or(found);
        } else if let Some(v) = w.strip_prefix(flag).and_then(|r| r.strip_prefix('=')) {
            found = Some(v);
        }
    }
    found
}
