#!/usr/bin/env bash
# Regenerate the checked-in RTL, ROM files, vectors and golden images of the default
# configuration, and the README's generated sections and tables (interface, integration,
# timing, limits). tests/generated_current.rs and tests/readme_limits.rs fail when stale.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
g=./target/release/gbump
rm -rf rtl vectors
$g rtl --out rtl
$g rom --shininess 16 --cube-size 32 --out rtl/rom
$g vectors --source corners --out vectors
$g vectors --source random:256 --seed 1 --out vectors
GBUMP_BLESS=1 cargo test --release --quiet --test golden_images every_builtin_scene_matches_its_golden_png
# The README's generated sections: everything between a section's heading and the next one.
paste_section() { # heading, command
    local out
    out=$(mktemp)
    "${@:2}" > "$out.body"
    awk -v h="$1" -v body="$out.body" '
        $0 == h { print; print ""; while ((getline l < body) > 0) print l; print ""; skip = 1; next }
        skip && /^## / { skip = 0 }
        !skip { print }' README.md > "$out"
    mv "$out" README.md
    rm -f "$out.body"
}
paste_section "## Interface (default configuration)" $g interface
paste_section "## Integrating the RTL: protocol and records" $g integration
# Tables inside hand-written sections: the table rows only (from the line that starts with
# the table's heading row to its last row), the prose around them kept.
paste_table() { # heading row prefix, file holding the new table
    local out
    out=$(mktemp)
    awk -v head="$1" -v body="$2" '
        index($0, head) == 1 { while ((getline l < body) > 0) print l; skip = 1; next }
        skip && /^\|/ { next }
        { skip = 0; print }' README.md > "$out"
    mv "$out" README.md
}
tables=$(mktemp -d)
$g timing > "$tables/timing"
paste_table "| unit | depth 1" "$tables/timing"
# `gbump limits` prints the size limits, a blank line, then the configuration keys' ranges.
$g limits | awk -v a="$tables/limits" -v b="$tables/ranges" '/^$/ { second = 1; next } { print > (second ? b : a) }'
paste_table "| limit | value | bounds |" "$tables/limits"
paste_table "| configuration key | range |" "$tables/ranges"
rm -rf "$tables"
