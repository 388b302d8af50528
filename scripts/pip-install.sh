#!/usr/bin/env bash
# `python3 -m pip install ARGS...` into the python3 on PATH, also where that is Debian's own
# interpreter: Debian marks it externally managed (PEP 668), and pip refuses every install
# into it unless told --break-system-packages. As root that installs into
# /usr/local/lib/python3*/, the folder Debian leaves to local installs (apt's own packages in
# /usr/lib/python3 stay as they are), and the console scripts (fusesoc, cocotb-config,
# maturin) into /usr/local/bin, on PATH. A virtual environment (or pyenv's interpreter) is
# not marked and gets no flag. Not root: sudo where the interpreter's site-packages is not
# the user's, else a user install (~/.local/bin must then be on PATH).
set -euo pipefail
# One interpreter for every probe and the install: `sudo python3` could find another.
py=$(python3 -c 'import sys; print(sys.executable)')
flags=()
# pip's own test: the marker beside the standard library, outside a virtual environment.
if "$py" -c 'import os, sys, sysconfig; sys.exit(not (sys.prefix == sys.base_prefix and os.path.exists(os.path.join(sysconfig.get_path("stdlib"), "EXTERNALLY-MANAGED"))))'; then
    flags+=(--break-system-packages)
fi
run=()
if [ "$(id -u)" -ne 0 ] && ! "$py" -c 'import os, sys, sysconfig; sys.exit(not os.access(sysconfig.get_path("purelib"), os.W_OK))'; then
    if command -v sudo >/dev/null 2>&1; then
        run=(sudo)
    else
        echo "note: $py's site-packages is not writable and sudo is missing: installing for this user (put ~/.local/bin on PATH)" >&2
        flags+=(--user)
    fi
fi
# pip's warning about running as root is noise here: root is how the scripts are meant to run
# (an environment variable, which a pip too old for the option ignores; set past sudo).
${run[@]+"${run[@]}"} env PIP_ROOT_USER_ACTION=ignore "$py" -m pip install --quiet ${flags[@]+"${flags[@]}"} "$@"
