#!/usr/bin/env bash
# Builds LIGGGHTS-PUBLIC 3.8.0 (Debian 12's source) with the paper's normal contact model
# (scripts/liggghts-paper/normal_model_paper.h: `model paper`, `model paper/linear`) as a serial
# binary, and installs it as .codes/liggghts-paper/bin/liggghts-paper (MILLIMPACT_CODES_DIR moves
# .codes). Prints the time it took.
#
# - Source: Debian's orig tarball liggghts_3.8.0+repack1.orig.tar.xz through `apt-get source
#   --download-only` (a deb-src entry is added when apt has none), checked against its SHA-256.
#   Debian's patch tarball (…-9.debian.tar.xz) is no longer on the mirror; it is not needed.
# - Build: `make serial` with the MPI stubs of src/STUBS, -std=gnu++98 -fpermissive, without the
#   VTK dump styles, one comparison in finish.cpp fixed for g++ 12, `make -j$JOBS` (default 2,
#   MILLIMPACT_BUILD_JOBS changes it).
# - Cache, outside the clone so that a fresh clone finds it: ${XDG_CACHE_HOME:-$HOME/.cache}/
#   millimpact/liggghts-paper (MILLIMPACT_CACHE_DIR replaces ${XDG_CACHE_HOME:-$HOME/.cache}/
#   millimpact). It keeps the tarball (download/), the build tree (build/: a change of the model
#   header recompiles only what includes it) and each built binary under the key of what it was
#   built from (<key>/liggghts-paper): a hash of the tarball's checksum, the model files and this
#   script. The install's stamp .codes/liggghts-paper/.millimpact-built holds the key too:
#   - stamp and binary match the key: nothing to do (a second run in the same clone);
#   - the cache holds the key's binary: it is installed from there (a fresh clone);
#   - else the build runs, and its binary is cached under the key, then installed.
#   Each install is smoke-run on example.in before its stamp is written; builds of one cache
#   are serialised by a lock.
# - Build dependencies (build-essential, xz-utils) are installed with apt-get when missing.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
CODES_DIR="${MILLIMPACT_CODES_DIR:-$ROOT/.codes}"
DIR="$CODES_DIR/liggghts-paper"
MODEL_DIR="$ROOT/scripts/liggghts-paper"
BIN="$DIR/bin/liggghts-paper"
STAMP="$DIR/.millimpact-built"
CACHE="${MILLIMPACT_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/millimpact}/liggghts-paper"
JOBS="${MILLIMPACT_BUILD_JOBS:-2}"

ORIG=liggghts_3.8.0+repack1.orig.tar.xz
ORIG_SHA256=c18721d9a870c5170f03b91e4f1ffe13335c66ed1f0ff2c64ebd3be91c37867a
TREE=LIGGGHTS-PUBLIC-3.8.0
MODEL_FILES=(normal_model_paper.h style_contact_model_user.whitelist)
FLAGS="-O2 -fPIC -std=gnu++98 -fpermissive"

started=$(date +%s)

# --- cache -----------------------------------------------------------------------------------
key="$(
  {
    echo "$ORIG_SHA256"
    for f in "${MODEL_FILES[@]}"; do sha256sum <"$MODEL_DIR/$f"; done
    sha256sum <"$0"
  } | sha256sum | cut -d' ' -f1
)"
if [ -x "$BIN" ] && [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$key" ]; then
  echo "liggghts-paper is up to date: $BIN"
  exit 0
fi
CACHED="$CACHE/$key/liggghts-paper"

# smoke BINARY: run example.in with it; it must print the realised COR.
smoke() {
  local dir
  dir="$(mktemp -d)"
  if ! (cd "$dir" && "$1" -in "$MODEL_DIR/example.in" -log none -echo none >run.log 2>&1) \
    || ! grep -q "^COR " "$dir/run.log"; then
    tail -n 20 "$dir/run.log" >&2
    rm -rf "$dir"
    echo "error: the smoke run of scripts/liggghts-paper/example.in with $1 failed" >&2
    return 1
  fi
  grep "^COR " "$dir/run.log" | sed 's/^/smoke run (example.in): /'
  rm -rf "$dir"
}

# install_cached: install the key's cached binary, smoke-run it, stamp the install.
install_cached() {
  install -D -m 755 "$CACHED" "$BIN"
  smoke "$BIN"
  echo "$key" >"$STAMP"
}

mkdir -p "$CACHE"
exec 9>"$CACHE/.lock"
flock 9
if [ -x "$CACHED" ]; then
  install_cached
  echo "liggghts-paper installed from the cache ($CACHED) in $(($(date +%s) - started)) s: $BIN"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
apt_install() {
  local need=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
  done
  [ ${#need[@]} -eq 0 ] && return 0
  echo "installing: ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
}

# --- build dependencies ----------------------------------------------------------------------
apt_install build-essential xz-utils

# --- source tarball --------------------------------------------------------------------------
DOWNLOAD="$CACHE/download"
mkdir -p "$DOWNLOAD"
tarball_ok() {
  [ -f "$DOWNLOAD/$ORIG" ] && echo "$ORIG_SHA256  $DOWNLOAD/$ORIG" | sha256sum --check --status
}
if ! tarball_ok; then
  # apt must know the source package: refresh its lists, and add a deb-src entry for this
  # release's main archive if that is not enough.
  if ! apt-get source --print-uris liggghts >/dev/null 2>&1; then
    $SUDO apt-get update -qq
  fi
  if ! apt-get source --print-uris liggghts >/dev/null 2>&1; then
    . /etc/os-release
    src_list=/etc/apt/sources.list.d/millimpact-deb-src.sources
    echo "adding $src_list (deb-src for $VERSION_CODENAME)"
    $SUDO tee "$src_list" >/dev/null <<EOF
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: $VERSION_CODENAME
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
    $SUDO apt-get update -qq
  fi
  rm -f "$DOWNLOAD/$ORIG"
  # The Debian patch tarball is gone from the mirror (404), so apt-get fails after fetching the
  # orig tarball; the checksum below decides.
  (cd "$DOWNLOAD" && apt-get source --download-only liggghts >/dev/null 2>&1) || true
  if ! tarball_ok; then
    echo "error: could not fetch $ORIG (SHA-256 $ORIG_SHA256) with apt-get source" >&2
    exit 1
  fi
fi

# --- source tree -----------------------------------------------------------------------------
BUILD="$CACHE/build"
SRC="$BUILD/$TREE/src"
if [ "$(cat "$BUILD/.source-sha256" 2>/dev/null)" != "$ORIG_SHA256" ] || [ ! -d "$SRC" ]; then
  echo "unpacking $ORIG"
  rm -rf "$BUILD"
  mkdir -p "$BUILD"
  tar -xJf "$DOWNLOAD/$ORIG" -C "$BUILD"
  # The VTK dump styles need VTK headers; this build has none.
  rm -f "$SRC"/*_vtk.cpp "$SRC"/*_vtk.h "$SRC"/*_vtm.cpp "$SRC"/*_vtm.h
  # g++ 12 refuses an ordered comparison of a pointer with 0, even with -fpermissive.
  sed -i 's/if (neighbor->lists\[m\]->numneigh > 0) {/if (neighbor->lists[m]->numneigh != NULL) {/' "$SRC/finish.cpp"
  grep -q 'numneigh != NULL' "$SRC/finish.cpp" || { echo "error: finish.cpp patch did not apply" >&2; exit 1; }
  echo "$ORIG_SHA256" >"$BUILD/.source-sha256"
fi

# The model: copied only when changed, so make sees a new time stamp only then. The whitelist
# lists the contact-model combinations compiled with it (LIGGGHTS's Make.sh merges it into
# style_contact_model.h; Make.sh picks up the NORMAL_MODEL lines of the header by itself).
for f in "${MODEL_FILES[@]}"; do
  cmp -s "$MODEL_DIR/$f" "$SRC/$f" || cp "$MODEL_DIR/$f" "$SRC/$f"
done

# --- build -----------------------------------------------------------------------------------
if [ ! -f "$SRC/STUBS/libmpi_stubs.a" ]; then
  make -C "$SRC/STUBS" >"$BUILD/stubs.log" 2>&1 || { cat "$BUILD/stubs.log" >&2; exit 1; }
fi
echo "building LIGGGHTS with the paper's model (make -j$JOBS serial; log: $BUILD/make.log)"
if ! make -C "$SRC" -j"$JOBS" serial CCFLAGS="$FLAGS" LINKFLAGS="-O2 -fPIC" >"$BUILD/make.log" 2>&1; then
  tail -n 40 "$BUILD/make.log" >&2
  echo "error: the LIGGGHTS build failed (full log: $BUILD/make.log)" >&2
  exit 1
fi
smoke "$SRC/lmp_serial"
install -D -m 755 "$SRC/lmp_serial" "$CACHED"
install_cached

echo "liggghts-paper built in $(($(date +%s) - started)) s (cached as $CACHED): $BIN"
