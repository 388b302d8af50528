#!/usr/bin/env bash
# One `gbump fit` end to end with the checks the suite leaves out: the search, the chosen
# configuration and the front synthesised by Yosys beside the area model's estimate
# (--yosys, about 30 s a configuration), the choice regressed on Icarus and Verilator, then
# its PSNR re-measured by `gbump render` alone. A few minutes on two cores (tests/fit.rs runs
# the search and regression without Yosys).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-tools.sh
cargo build --release --quiet
out=$(mktemp -d)
./target/release/gbump fit --scene cg_wall_front --budget 'psnr>=45' --yosys --out "$out" --work target/gbump-fit
./target/release/gbump render --scene cg_wall_front --config "$out/fit.toml" --out "$out/render" | grep "f64 Gouraud"
