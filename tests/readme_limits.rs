//! README's "Limits" table must be what `gbump limits` prints from `src/limits.rs` today.

#[test]
fn readme_limits_table_is_current() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let table = gbump::limits::markdown();
    assert!(
        readme.contains("## Limits\n") && readme.contains(&table),
        "README's Limits table is stale: run scripts/regen.sh (it pastes `gbump limits`)"
    );
    // The configuration keys' ranges, which `gbump limits` prints after it.
    assert!(
        readme.contains(&gbump::config::limits_markdown()),
        "README's table of configuration ranges is stale: run scripts/regen.sh (it pastes `gbump limits`)"
    );
}

#[test]
fn every_limit_constant_is_in_the_table() {
    let src = include_str!("../src/limits.rs");
    let consts: Vec<&str> = src
        .lines()
        .filter_map(|l| l.strip_prefix("pub const ")?.split(':').next())
        .filter(|n| *n != "ALL")
        .collect();
    assert!(consts.len() > 10);
    for c in consts {
        assert!(gbump::limits::ALL.iter().any(|(n, ..)| *n == c), "{c} is missing from limits::ALL");
    }
}

/// The range the README gives for `colour_guard_bits` is the configuration's limit.
#[test]
fn readme_guard_bit_range_is_the_limit() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let (lo, hi) = gbump::config::limit("colour_guard_bits");
    assert!(
        readme.contains(&format!("`colour_guard_bits = g` ({lo}..={hi}, default 0)")),
        "README states another range for colour_guard_bits than {lo}..={hi}"
    );
    assert_eq!(gbump::PipelineConfig::default().colour_guard_bits, 0);
}
