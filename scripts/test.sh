#!/usr/bin/env bash
# The whole test suite: model, golden images, CLI and bad input, generated-file currency,
# and the RTL under Icarus Verilog and Verilator (installed first when missing).
# cargo-nextest, where the machine has it, schedules every test of every target on both
# cores at once (cargo test runs one target at a time, so a target with one long test
# leaves a core idle); both run the same tests.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-tools.sh
if cargo nextest --version >/dev/null 2>&1; then
    cargo nextest run --release --all-targets --no-fail-fast --failure-output final
else
    cargo test --release --all-targets --no-fail-fast
fi
