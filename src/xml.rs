//! Text for XML files (JUnit reports, SVG plots).

/// `s` as XML text or an attribute value: markup characters escaped, and control characters
/// (a simulator's colour codes, a stray byte) shown as `\u{1b}`, since XML 1.0 has no way to
/// hold them and a report with one is not well-formed (a CI server rejects the whole file).
pub fn escape(s: &str) -> String {
    crate::error::shown(s)
        // The two noncharacters XML 1.0 excludes too.
        .replace('\u{FFFE}', "\\u{fffe}")
        .replace('\u{FFFF}', "\\u{ffff}")
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    #[test]
    fn markup_and_control_characters_are_escaped() {
        assert_eq!(
            super::escape("a < b & \"c\" \u{1b}[31mred\u{1}\u{fffe}\n"),
            "a &lt; b &amp; &quot;c&quot; \\u{1b}[31mred\\u{1}\\u{fffe}\n"
        );
    }
}
