#!/usr/bin/env bash
# Regenerate the checked-in RTL, ROM files, vectors and golden images of the default
# configuration. tests/generated_current.rs fails when these are stale.
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
