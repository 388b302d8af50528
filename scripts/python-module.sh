#!/usr/bin/env bash
# Build the Python module `gbump` (python/, PyO3, by maturin) and install it into python3's
# site-packages when the installed extension differs from the one just built. Cheap when
# nothing changed: cargo finds everything built (the module shares target/ and the library's
# compile with `cargo build` and `cargo test`), maturin repacks the wheel, pip does not run.
# Needs maturin and numpy (scripts/install-tools.sh installs them, pinned).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v maturin >/dev/null 2>&1 || { echo "error: maturin is not installed: run scripts/install-tools.sh" >&2; exit 1; }
out=target/wheels
mkdir -p "$out"
rm -f "$out"/gbump-*.whl
# Quiet unless it fails: the log names the compiler's error.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! maturin build --release -m python/Cargo.toml -o "$out" ${CARGO_BUILD_JOBS:+-j "$CARGO_BUILD_JOBS"} >"$log" 2>&1; then
    cat "$log" >&2
    echo "error: maturin build of python/ failed (log above)" >&2
    exit 1
fi
whl=$(ls "$out"/gbump-*.whl)
built=$(python3 -c 'import hashlib, sys, zipfile; print(hashlib.sha256(zipfile.ZipFile(sys.argv[1]).read("gbump/gbump.abi3.so")).hexdigest())' "$whl")
# Where an installed copy would be, found without importing it (a stale one may not import).
dir=$(python3 -c 'import importlib.util as u, os; s = u.find_spec("gbump"); print(os.path.dirname(s.origin) if s else "")')
installed=""
if [ -n "$dir" ] && [ -f "$dir/gbump.abi3.so" ]; then
    installed=$(sha256sum "$dir/gbump.abi3.so" | cut -d' ' -f1)
fi
if [ "$built" != "$installed" ]; then
    echo "installing the Python module gbump ($whl)" >&2
    scripts/pip-install.sh --force-reinstall --no-deps "$whl"
fi
python3 -c 'import gbump' || { echo "error: the Python module gbump does not import after installing $whl" >&2; exit 1; }
