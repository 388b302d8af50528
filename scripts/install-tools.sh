#!/usr/bin/env bash
# Install the simulators, synthesis and place-and-route tools gbump drives (Debian packages)
# and the Python tools its integration kit is tested with (pinned, pip), each only when
# missing; then builds and installs gbump's own Python module (scripts/python-module.sh).
# nextpnr-ice40 needs the iCE40 chip database (fpga-icestorm-chipdb, a dependency);
# fpga-icestorm adds icepack and icetime.
set -euo pipefail
missing=()
for t in iverilog verilator yosys nextpnr-ice40; do
    command -v "$t" >/dev/null 2>&1 || missing+=("$t")
done
# FuseSoC (runs the generated .core), cocotb (examples/cocotb*), maturin (builds python/) and
# NumPy (the module's arrays), pinned, from PyPI.
PY_PKGS=(fusesoc==2.4.3 cocotb==1.9.2 maturin==1.16.0 numpy==2.3.5)
python_tools_present() {
    command -v fusesoc >/dev/null 2>&1 && command -v cocotb-config >/dev/null 2>&1 &&
        command -v maturin >/dev/null 2>&1 &&
        python3 -c 'import cocotb, fusesoc, numpy' >/dev/null 2>&1
}
if ! python_tools_present; then
    echo "installing: ${PY_PKGS[*]} (pip)" >&2
    python3 -m pip install --quiet "${PY_PKGS[@]}"
    # pyenv finds new console scripts only after a rehash.
    if command -v pyenv >/dev/null 2>&1; then pyenv rehash || true; fi
    python_tools_present || { echo "error: fusesoc, cocotb, maturin or numpy still missing after pip install ${PY_PKGS[*]}" >&2; exit 1; }
fi
"$(dirname "$0")/python-module.sh"
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
