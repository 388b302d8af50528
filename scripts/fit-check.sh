#!/usr/bin/env bash
# One `gbump fit` end to end: search, Yosys sizing of the winners, the chosen configuration
# regressed on Icarus and Verilator, then its PSNR re-measured by `gbump render` alone.
# Several minutes on two cores (too long for the suite; see tests/fit.rs).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-tools.sh
cargo build --release --quiet
out=$(mktemp -d)
./target/release/gbump fit --scene cg_wall_front --budget 'psnr>=45' --out "$out" --work target/gbump-fit
./target/release/gbump render --scene cg_wall_front --config "$out/fit.toml" --out "$out/render" | grep "f64 Gouraud"
