#!/usr/bin/env bash
# The fuzz targets (fuzz/fuzz_targets/: the case reader and the four deck readers) run for a
# fixed time each, from their seeds (fuzz/corpus/<target>/): a panic, an input that runs longer
# than a few seconds, or one that takes gigabytes fails the run, and libFuzzer's reproducer is
# kept in fuzz/artifacts/<target>/ (`cargo fuzz run <target> <that file>` runs it again).
#
# - cargo-fuzz is installed once (pinned, into cargo's bin folder); the targets are built with
#   the stable toolchain (RUSTC_BOOTSTRAP=1 lets it take the sanitizer flags cargo-fuzz passes).
# - The instrumented build is kept outside the clone, so a fresh clone builds only what changed:
#   ${XDG_CACHE_HOME:-$HOME/.cache}/millimpact/fuzz-target (MILLIMPACT_CACHE_DIR replaces
#   ${XDG_CACHE_HOME:-$HOME/.cache}/millimpact, as for the LAMMPS plugin).
# - What libFuzzer finds on the way is written to a scratch corpus, never into the clone.
# - Each target runs a fixed number of inputs from a fixed seed (about a minute each here), so a
#   run is repeatable for a given build: a crash CI meets is met again by the same command on
#   the same commit. MILLIMPACT_FUZZ_RUNS multiplies the inputs (default 1), and a time cap
#   (MILLIMPACT_FUZZ_SECONDS, default 180 s per target) bounds a slow machine.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"

seconds="${MILLIMPACT_FUZZ_SECONDS:-180}"
scale="${MILLIMPACT_FUZZ_RUNS:-1}"
cargo_fuzz="$(command -v cargo-fuzz || echo "${CARGO_HOME:-$HOME/.cargo}/bin/cargo-fuzz")"
if [ ! -x "$cargo_fuzz" ]; then
    cargo install cargo-fuzz --version 0.13.2 --locked
fi
export CARGO_TARGET_DIR="${MILLIMPACT_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/millimpact}/fuzz-target"
export RUSTC_BOOTSTRAP=1
# Both readers reach the DEM codes' names only through their environment variables: a LAMMPS
# deck's reader asks its build for its conventions where a binary is found, and a fuzz run
# starts no code.
export MILLIMPACT_LAMMPS_BINARY=/nonexistent MILLIMPACT_LAMMPS_2025_BINARY=/nonexistent

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
# Inputs per target: the case reader runs about 8,000 a second here, the deck readers about 670.
for run in case_reader:500000 deck_readers:40000; do
    target="${run%%:*}"
    runs=$(( ${run##*:} * scale ))
    mkdir -p "$scratch/$target"
    echo "fuzz: $target, $runs inputs from seed 1 (at most ${seconds} s)"
    cargo fuzz run -O "$target" "$scratch/$target" "corpus/$target" -- \
        -seed=1 -runs="$runs" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
        -print_final_stats=1
done
