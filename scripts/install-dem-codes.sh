#!/usr/bin/env bash
# Installs the reference DEM codes, once, and prints their versions. Safe to run again: it
# installs only what is missing, and a second run takes about a second.
#
# - Debian packages: LIGGGHTS, YADE and LAMMPS 29 Sep 2021 (`liggghts`, `yade`, `lmp` on PATH).
# - PyPI, each into its own venv under .codes/ (git-ignored; MILLIMPACT_CODES_DIR moves it),
#   made with this machine's `python3 -m venv`, versions pinned:
#     .codes/lammps-2025/  LAMMPS 22 Jul 2025 - Update 4 (`lammps[mpi]`, plus `mpich`: the
#                          wheel's binary needs libmpi.so.12). Run the real binary
#                          .codes/lammps-2025/lib/python3.X/site-packages/lammps/lmp with
#                          LD_LIBRARY_PATH=.codes/lammps-2025/lib, not the Python wrapper
#                          .codes/lammps-2025/bin/lmp.
#     .codes/kratos/       Kratos Multiphysics 10.4.4 with its DEMApplication
#                          (.codes/kratos/bin/python runs a Kratos script).
#   A venv is (re)built only when its stamp file does not name exactly the pinned packages and
#   this python3's version; the stamp is written after a smoke test of the installed code.
# - Built here, by scripts/build-liggghts-paper.sh: .codes/liggghts-paper/bin/liggghts-paper,
#   LIGGGHTS 3.8.0 from Debian's source with the paper's contact model (scripts/liggghts-paper/).
#   Its build is cached outside the clone (${XDG_CACHE_HOME:-$HOME/.cache}/millimpact), so only
#   the first run on a machine compiles (about 7.5 minutes on 2 cores); a fresh clone installs
#   it from the cache in seconds.
# - Built here, by scripts/build-lammps-paper.sh: .codes/lammps-paper/lib/paperplugin.so, the
#   paper's law as a plugin of the LAMMPS 2025 venv (scripts/lammps-paper/; 3 s, cached alike).
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
CODES_DIR="${MILLIMPACT_CODES_DIR:-$ROOT/.codes}"

# --- Debian packages -------------------------------------------------------------------------
need=()
command -v liggghts >/dev/null 2>&1 || need+=(liggghts)
command -v yade >/dev/null 2>&1 || need+=(yade)
command -v lmp >/dev/null 2>&1 || need+=(lammps)

if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  echo "installing: ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi

# --- PyPI codes, one venv each ---------------------------------------------------------------
LAMMPS_2025_DIR="$CODES_DIR/lammps-2025"
LAMMPS_2025_PACKAGES=("lammps[mpi]==2025.7.22.4.0" "mpich==5.0.2")
KRATOS_DIR="$CODES_DIR/kratos"
KRATOS_PACKAGES=("KratosMultiphysics==10.4.4" "KratosDEMApplication==10.4.4" "numpy==2.4.6")
STAMP=.millimpact-installed

PY_VERSION="$(python3 -c 'import sys; print("%d.%d.%d" % sys.version_info[:3])')"
PY_MINOR="$(python3 -c 'import sys; print("python%d.%d" % sys.version_info[:2])')"

# The real LAMMPS binary inside the venv (bin/lmp is a Python wrapper that execs it).
lammps_2025_binary() {
  echo "$LAMMPS_2025_DIR/lib/$PY_MINOR/site-packages/lammps/lmp"
}

smoke_lammps_2025() {
  # The first line of `lmp -h` names the version; the GRANULAR package must be built in.
  local help
  help="$(LD_LIBRARY_PATH="$LAMMPS_2025_DIR/lib" OMP_NUM_THREADS=1 "$(lammps_2025_binary)" -h)"
  grep -q "22 Jul 2025" <<<"$help"
  grep -qw GRANULAR <<<"$help"
}

smoke_kratos() {
  OMP_NUM_THREADS=1 "$KRATOS_DIR/bin/python" -c \
    'import KratosMultiphysics, KratosMultiphysics.DEMApplication' >/dev/null
}

# install_venv DIR SMOKE_FUNCTION PACKAGE...
install_venv() {
  local dir="$1" smoke="$2"
  shift 2
  local want="python $PY_VERSION; $*"
  if [ -f "$dir/$STAMP" ] && [ "$(cat "$dir/$STAMP")" = "$want" ] && [ -x "$dir/bin/python" ]; then
    return 0
  fi
  echo "installing into $dir: $*"
  rm -rf "$dir"
  mkdir -p "$(dirname "$dir")"
  python3 -m venv "$dir"
  "$dir/bin/python" -m pip install --quiet --no-cache-dir --disable-pip-version-check "$@"
  "$smoke"
  echo "$want" >"$dir/$STAMP"
}

install_venv "$LAMMPS_2025_DIR" smoke_lammps_2025 "${LAMMPS_2025_PACKAGES[@]}"
install_venv "$KRATOS_DIR" smoke_kratos "${KRATOS_PACKAGES[@]}"

# --- LIGGGHTS with the paper's law, built from source (cached) --------------------------------
MILLIMPACT_CODES_DIR="$CODES_DIR" bash "$ROOT/scripts/build-liggghts-paper.sh"
MILLIMPACT_CODES_DIR="$CODES_DIR" bash "$ROOT/scripts/build-lammps-paper.sh"

# --- versions --------------------------------------------------------------------------------
dpkg-query -W -f='${Package} ${Version}\n' liggghts yade lammps
pypi_versions() {
  "$1/bin/python" - "${@:2}" <<'EOF'
import sys
from importlib.metadata import version
for name in sys.argv[1:]:
    print(name, version(name))
EOF
}
pypi_versions "$LAMMPS_2025_DIR" lammps mpich | sed "s|^|$LAMMPS_2025_DIR: |"
pypi_versions "$KRATOS_DIR" KratosMultiphysics KratosDEMApplication | sed "s|^|$KRATOS_DIR: |"
echo "lammps-2025 binary: $(lammps_2025_binary) (LD_LIBRARY_PATH=$LAMMPS_2025_DIR/lib)"
echo "liggghts-paper binary: $CODES_DIR/liggghts-paper/bin/liggghts-paper"
echo "lammps-paper plugin: $CODES_DIR/lammps-paper/lib/paperplugin.so (run by the lammps-2025 binary)"
