#!/usr/bin/env bash
# Install the simulators and synthesis tool gbump drives (Debian packages), if any is missing.
set -euo pipefail
missing=()
for t in iverilog verilator yosys; do
    command -v "$t" >/dev/null 2>&1 || missing+=("$t")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
echo "installing: iverilog verilator yosys (missing: ${missing[*]})" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null 2>&1 || { echo "error: need root or sudo to apt-get install iverilog verilator yosys" >&2; exit 1; }
    SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq iverilog verilator yosys >/dev/null
for t in iverilog verilator yosys; do
    command -v "$t" >/dev/null 2>&1 || { echo "error: $t still missing after apt-get install" >&2; exit 1; }
done
