#!/usr/bin/env bash
# `python3 -m pip install ARGS...` that also works where python3 is Debian's own interpreter:
# Debian marks it externally managed (PEP 668), and pip refuses every install into it unless
# told --break-system-packages. As root that installs into /usr/local/lib/python3*/, the
# folder Debian leaves to local installs (apt's own packages in /usr/lib/python3 stay as they
# are), and the console scripts (fusesoc, cocotb-config, maturin) into /usr/local/bin, on
# PATH. A virtual environment or pyenv interpreter is not marked, and gets no flag. A user
# who is not root installs with sudo when the interpreter's site-packages is not theirs.
set -euo pipefail
flags=()
if python3 -c 'import os, sys, sysconfig; sys.exit(not os.path.exists(os.path.join(sysconfig.get_path("stdlib"), "EXTERNALLY-MANAGED")))'; then
    flags+=(--break-system-packages)
fi
run=()
if [ "$(id -u)" -ne 0 ] && ! python3 -c 'import os, sys, sysconfig; sys.exit(not os.access(sysconfig.get_path("purelib"), os.W_OK))'; then
    command -v sudo >/dev/null 2>&1 || { echo "error: python3's site-packages ($(python3 -c 'import sysconfig; print(sysconfig.get_path("purelib"))')) is not writable and sudo is missing: run as root, or make a virtual environment first (python3 -m venv .venv && . .venv/bin/activate)" >&2; exit 1; }
    run=(sudo)
fi
# pip's warning about running as root is noise here: root is how the scripts are meant to run.
"${run[@]}" python3 -m pip install --quiet --root-user-action=ignore "${flags[@]}" "$@"
