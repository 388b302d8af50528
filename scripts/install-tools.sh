#!/usr/bin/env bash
# Install the simulators, synthesis and place-and-route tools gbump drives (Debian packages),
# if any is missing. nextpnr-ice40 needs the iCE40 chip database (fpga-icestorm-chipdb, a
# dependency); fpga-icestorm adds icepack and icetime.
set -euo pipefail
missing=()
for t in iverilog verilator yosys nextpnr-ice40; do
    command -v "$t" >/dev/null 2>&1 || missing+=("$t")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
echo "installing: iverilog verilator yosys nextpnr-ice40 fpga-icestorm (missing: ${missing[*]})" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null 2>&1 || { echo "error: need root or sudo to apt-get install iverilog verilator yosys nextpnr-ice40 fpga-icestorm" >&2; exit 1; }
    SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq iverilog verilator yosys nextpnr-ice40 fpga-icestorm >/dev/null
for t in iverilog verilator yosys nextpnr-ice40; do
    command -v "$t" >/dev/null 2>&1 || { echo "error: $t still missing after apt-get install" >&2; exit 1; }
done
