#!/usr/bin/env bash
# Creates the Python environment of the peer solver (scipy's solve_ivp) in .codes/peer/venv,
# with pinned scipy and numpy from PyPI, once. Safe to run again: it installs only what is
# missing. The folder ignores itself in git (it writes its own .gitignore).
set -euo pipefail

SCIPY=1.17.1
NUMPY=2.4.6

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
peer="$root/.codes/peer"
venv="$peer/venv"
python="${PYTHON:-python3}"

mkdir -p "$peer"
[ -f "$peer/.gitignore" ] || printf '*\n' > "$peer/.gitignore"

have() {
  [ -x "$venv/bin/python" ] &&
    "$venv/bin/python" - "$SCIPY" "$NUMPY" >/dev/null 2>&1 <<'PY'
import sys
import numpy
import scipy
sys.exit(0 if (scipy.__version__, numpy.__version__) == (sys.argv[1], sys.argv[2]) else 1)
PY
}

if ! have; then
  [ -x "$venv/bin/python" ] || "$python" -m venv "$venv"
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    "scipy==$SCIPY" "numpy==$NUMPY"
  have || { echo "setup.sh: scipy $SCIPY / numpy $NUMPY did not install in $venv" >&2; exit 1; }
fi
"$venv/bin/python" -c 'import numpy, scipy, sys; print(f"peer: Python {sys.version.split()[0]}, scipy {scipy.__version__}, numpy {numpy.__version__} in .codes/peer/venv")'
