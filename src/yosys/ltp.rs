//! The reader of Yosys `ltp -noff` output: the logic depth (longest topological path, in
//! cells, flip-flops cut).

/// The length of the last "Longest topological path" line; 0 when there is none (a design
/// with no logic between its ports and registers).
pub fn depth(text: &str) -> u64 {
    text.lines()
        .rev()
        .find(|l| l.contains("Longest topological path"))
        .and_then(|l| {
            l.split("length=")
                .nth(1)?
                .trim_end_matches("):")
                .trim_end_matches(['(', ')', ':'])
                .parse()
                .ok()
        })
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    #[test]
    fn reads_the_last_longest_path() {
        let log = "Longest topological path in dot_clamp (length=7):\n  ...\nLongest topological path in top (length=23):\n";
        assert_eq!(super::depth(log), 23);
        assert_eq!(super::depth("nothing here\n"), 0);
    }
}
