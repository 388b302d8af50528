#!/usr/bin/env bash
# The whole test suite: model, golden images, CLI and bad input, generated-file currency,
# and the RTL under Icarus Verilog and Verilator (installed first when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-tools.sh
cargo test --release --all-targets
