#!/usr/bin/env bash
# Install the simulators, synthesis and place-and-route tools gbump drives (Debian packages)
# and the Python tools its integration kit is tested with (pinned, pip), each only when
# missing; then builds and installs gbump's own Python module (scripts/python-module.sh).
# nextpnr-ice40 needs the iCE40 chip database (fpga-icestorm-chipdb, a dependency);
# fpga-icestorm adds icepack and icetime.
set -euo pipefail
# Debian packages first: Verilator's C++ builds need make and g++ (the verilator package
# depends on neither), and the Python tools need python3 with pip (a bare Debian has
# neither; the rust image has python3 without pip).
apt_pkgs=()
missing=()
for t in iverilog verilator yosys nextpnr-ice40; do
    command -v "$t" >/dev/null 2>&1 || missing+=("$t")
done
if [ ${#missing[@]} -gt 0 ]; then
    apt_pkgs+=(iverilog verilator yosys nextpnr-ice40 fpga-icestorm)
fi
for t in make g++; do
    command -v "$t" >/dev/null 2>&1 || apt_pkgs+=("$t")
done
# strace: the suite kills a run at its k-th rename (tests/output_commit.rs).
command -v strace >/dev/null 2>&1 || apt_pkgs+=(strace)
if ! command -v python3 >/dev/null 2>&1; then
    apt_pkgs+=(python3 python3-pip)
elif ! python3 -m pip --version >/dev/null 2>&1; then
    apt_pkgs+=(python3-pip)
fi
if [ ${#apt_pkgs[@]} -gt 0 ]; then
    echo "installing: ${apt_pkgs[*]} (apt-get)" >&2
    SUDO=""
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null 2>&1 || { echo "error: need root or sudo to apt-get install ${apt_pkgs[*]}" >&2; exit 1; }
        SUDO="sudo"
    fi
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq "${apt_pkgs[@]}" >/dev/null
    for t in iverilog verilator yosys nextpnr-ice40 make g++ python3 strace; do
        command -v "$t" >/dev/null 2>&1 || { echo "error: $t still missing after apt-get install ${apt_pkgs[*]}" >&2; exit 1; }
    done
    python3 -m pip --version >/dev/null 2>&1 || { echo "error: python3 has no pip after apt-get install ${apt_pkgs[*]}" >&2; exit 1; }
fi
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
    "$(dirname "$0")/pip-install.sh" "${PY_PKGS[@]}"
    # pyenv finds new console scripts only after a rehash.
    if command -v pyenv >/dev/null 2>&1; then pyenv rehash || true; fi
    hash -r
    python_tools_present || { echo "error: fusesoc, cocotb, maturin or numpy still missing after pip install ${PY_PKGS[*]} (is pip's script folder on PATH?)" >&2; exit 1; }
fi
"$(dirname "$0")/python-module.sh"
